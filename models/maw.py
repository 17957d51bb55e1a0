"""Hertz impact with tangential compliance and Coulomb microslip (Maw, Barber & Fawcett), MDR engine."""

from __future__ import annotations

import functools

import attrs
import numpy as np

from impactlab._validate import check
from impactlab.diagnostics import LARGE_CONTACT_RATIO
from impactlab.model import ImpactModel
from impactlab.physics import annuli, hertz, mdr
from impactlab.physics.mechanics import approach_velocities, effective_mass, tangential_mass

from ._common import IMPULSES, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL

METHODS = ("mdr", "annuli")
INELASTIC = ("adjusted_speed", "hysteretic")
#: cases solved together; bounds the memory of the spring arrays
BLOCK = 2048


def _int_at_least(low: int):
    return check(lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= low, f"an integer >= {low}")


def _optional_int(low: int):
    return check(lambda v: v is None or (isinstance(v, int) and not isinstance(v, bool) and v >= low),
                 f"an integer >= {low} (or leave it out and set tolerance)")


#: default tolerance of each method on |J_t| / (mu J_n)
DEFAULT_TOLERANCE = {"mdr": 1e-5, "annuli": 1e-3}


@attrs.frozen
class MawOptions:
    """Options of ``maw``.

    Parameters
    ----------
    method : str
        ``"mdr"`` (default, fast): method of dimensionality reduction, a row of
        independent springs that reproduces the axisymmetric Mindlin contact
        exactly (Popov & Hess 2015). ``"annuli"`` (faithful to the paper): the
        annular-strip solution of Maw, Barber & Fawcett, a mixed boundary-value
        problem over all rings at every step.
    tolerance : float, optional
        Target error of the tangential impulse relative to its Coulomb bound,
        |dJ_t| / (mu J_n) (launch angle, spin and beta follow from J_t). The
        method picks its resolution from it and from the physics (the
        tangential oscillation quickens as chi grows). Default 1e-5 for MDR,
        1e-3 for annuli (see docs/accuracy.md for the measured error).
    springs, rings, steps : int, optional
        Expert resolution that overrides ``tolerance``: MDR springs across the
        half-width of the largest contact, annuli, and uniform time steps over
        the contact (spring or ring entry and exit instants are added to them).
    history_points : int
        Samples of the force histories on the shared time axis (when asked).
    inelastic : str
        How a restitution e < 1 enters. ``"adjusted_speed"`` (default, the
        paper's approach): the elastic problem is solved at the normal speed
        (1 + e) V_z / 2, so the normal impulse is (1 + e) m* V_z.
        ``"hysteretic"``: Hertz contact with Hunt-Crossley damping chosen to
        rebound at e, solved at the real approach speed; the Coulomb limit
        follows the damped normal force.
    """

    method: str = attrs.field(default="mdr", validator=check(lambda v: v in METHODS,
                                                             f"one of {', '.join(METHODS)}"))
    tolerance: float = attrs.field(validator=check(
        lambda v: isinstance(v, (int, float)) and not isinstance(v, bool) and 1e-9 <= v <= 0.1,
        "a tolerance between 1e-9 and 0.1"))
    springs: int | None = attrs.field(default=None, validator=_optional_int(8))
    rings: int | None = attrs.field(default=None, validator=_optional_int(4))
    steps: int | None = attrs.field(default=None, validator=_optional_int(16))
    history_points: int = attrs.field(default=256, validator=_int_at_least(2))
    inelastic: str = attrs.field(default="adjusted_speed", validator=check(
        lambda v: v in INELASTIC, f"one of {', '.join(INELASTIC)}"))

    @tolerance.default
    def _default_tolerance(self):
        return DEFAULT_TOLERANCE.get(self.method, 1e-5)

    def resolution(self, chi: float) -> tuple[int, int, bool]:
        """(springs or rings, uniform steps, tolerance not met) for a case with this chi."""
        tolerance = self.tolerance
        if self.method == "annuli":
            if self.rings is not None:
                return self.rings, self.resolution_steps(self.rings), False
            rings, _, capped = annuli.resolution(tolerance)
            return rings, self.resolution_steps(rings), capped
        if self.springs is not None:
            return self.springs, self.resolution_steps(self.springs), False
        springs, _ = mdr.resolution(tolerance, chi)
        return springs, self.resolution_steps(springs), False

    def resolution_steps(self, count: int) -> int:
        """Uniform time steps that go with ``count`` springs or rings (unless given)."""
        if self.steps is not None:
            return self.steps
        return max(200, 10 * count) if self.method == "annuli" else mdr.STEPS_PER_SPRING * count


class MawModel(ImpactModel):
    """Elastic sphere striking a face: Hertz normal contact, Mindlin tangential compliance, Coulomb microslip.

    The normal contact is Hertz's (contact modulus E*, effective mass m*);
    the tangential traction builds up in the stuck centre of the contact and
    slips at its edge, where it may not exceed mu times the local pressure,
    and the whole contact may slip. The tangential problem is solved with the
    method of dimensionality reduction (springs on the equivalent profile
    x^2/R), which is exact for the axisymmetric Mindlin contact with any
    loading history, in the universal variables of Maw, Barber & Fawcett:
    chi = (kappa/2) m*/m_t and psi1 = kappa V_x/(mu V_z), kappa = G*/E*.

    Normal restitution: with e < 1 in the scene, option ``inelastic`` picks
    either the approach of Henrikson et al. (2020), the elastic problem at the
    normal speed (1 + e) V_z / 2 so that the normal impulse is (1 + e) m* V_z,
    or a hysteretic (Hunt-Crossley) normal law that rebounds at e.

    Inputs: ball and face materials (a rigid face has 1/E_face = 0), ball
    mass, radius, inertia factor; impact speed and angle; friction; optional
    spin, restitution and club mass. Outputs: impulses, contact time and,
    on request, the normal and tangential force histories [N] on a shared
    time axis.

    References
    ----------
    N. Maw, J. R. Barber, J. N. Fawcett, The oblique impact of elastic spheres, Wear 38 (1976) 101-114.
    N. Maw, J. R. Barber, J. N. Fawcett, The role of elastic tangential compliance in oblique impact,
    J. Lubr. Technol. 103 (1981) 74-80.
    V. L. Popov, M. Hess, Method of Dimensionality Reduction in Contact Mechanics and Friction, Springer (2015).
    E. Henrikson, P. Wood, C. Broadie, T. Nuttall, Proceedings 49 (2020) 27.
    K. H. Hunt, F. R. E. Crossley, J. Appl. Mech. 42 (1975) 440-445.
    """

    name = "maw"
    label = "Hertz + tangential compliance + Coulomb microslip (Maw)"
    references = (
        "N. Maw, J. R. Barber, J. N. Fawcett, The oblique impact of elastic spheres, Wear 38 (1976) 101-114",
        "N. Maw, J. R. Barber, J. N. Fawcett, The role of elastic tangential compliance in oblique impact, "
        "J. Lubr. Technol. 103 (1981) 74-80",
        "V. L. Popov, M. Hess, Method of Dimensionality Reduction in Contact Mechanics and Friction, Springer (2015)",
        "E. Henrikson, P. Wood, C. Broadie, T. Nuttall, The role of friction and tangential compliance on the "
        "resultant launch angle of a golf ball, Proceedings 49 (2020) 27",
    )
    requires = RIGID_BODY_INPUTS | {"friction", "ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                                    "face_poisson_ratio"}
    optional_inputs = RIGID_BODY_OPTIONAL | {"restitution"}
    provides = IMPULSES | {"contact_time", "normal_force", "tangential_force", "stick_radius", "contact_radius_ratio",
                           "steps", "energy_error", "validity"}
    Options = MawOptions

    def reference_options(self, tolerance):
        # both methods solve the same problem; MDR converges fastest, so it sets the reference for both
        return attrs.evolve(self.options, method="mdr", tolerance=tolerance, springs=None, rings=None, steps=None)

    def can_reach(self, tolerance):
        return not attrs.evolve(self.options, tolerance=tolerance).resolution(1.0)[2]

    def _compute(self, inputs, outputs):
        p = inputs
        radius, ball_mass, friction = p["ball_radius"], p["ball_mass"], p["friction"]
        moduli = (p["ball_youngs_modulus"], p["ball_poisson_ratio"], p["face_youngs_modulus"], p["face_poisson_ratio"])
        modulus = hertz.effective_modulus(*moduli)
        kappa = hertz.tangential_modulus(*moduli) / modulus
        m_normal = effective_mass(ball_mass, p["club_mass"])
        m_tangential = tangential_mass(ball_mass, p["ball_inertia_factor"], p["club_mass"])
        normal_speed, slip = approach_velocities(p["speed"], p["angle"], p["spin"], radius)
        restitution = p.get("restitution", np.ones_like(normal_speed))
        if self.options.inelastic == "adjusted_speed":
            # Henrikson et al.: the elastic problem at an adjusted speed carries the inelastic normal impulse
            scale_speed = 0.5 * (1.0 + restitution) * normal_speed
            law_of_case = np.zeros(slip.size, dtype=int)
            laws = [hertz.ElasticNormal()]
        else:
            scale_speed = normal_speed
            levels, law_of_case = np.unique(restitution, return_inverse=True)
            laws = [self._damped_law(level) for level in levels]

        histories = {"normal_force", "tangential_force", "stick_radius"} & outputs
        record = bool(histories - {"normal_force"})
        sliding = (friction > 0.0) & (slip != 0.0)
        chi = 0.5 * kappa * m_normal / m_tangential
        psi1 = kappa * np.abs(slip) / np.where(sliding, friction * scale_speed, 1.0)
        slip_change, residual, steps = np.zeros_like(slip), np.zeros_like(slip), np.zeros_like(slip)
        # each case's resolution depends on its own chi only, so a case's result never depends on its batch
        resolution = np.zeros(slip.size, dtype=int)
        capped = np.zeros(slip.size, dtype=bool)
        for value in np.unique(chi[sliding]):
            members = chi == value
            count, _, too_fine = self.options.resolution(float(value))
            resolution[members], capped[members] = count, too_fine
        solution_of_case = [None] * slip.size  # (solution, row) of each solved case, for its histories
        for index, law in enumerate(laws):
            for count in np.unique(resolution[sliding & (law_of_case == index)]):
                members = sliding & (law_of_case == index) & (resolution == count)
                steps_wanted = self.options.resolution_steps(int(count))
                solved = self._solve(chi[members], psi1[members], record, law, int(count), steps_wanted)
                slip_change[members] = solved.slip_change
                residual[members] = solved.energy_residual(chi[members], psi1[members])
                steps[members] = solved.steps
                for row, case in enumerate(np.nonzero(members)[0]):
                    solution_of_case[case] = (solved, row)
        # back from the scaled slip velocity (units mu V / kappa) to m/s, and the energy residual to joules
        velocity_unit = friction * scale_speed / kappa
        slip_change *= velocity_unit
        initial_energy = 0.5 * ball_mass * p["speed"] ** 2 + 0.5 * p["ball_inertia_factor"] * ball_mass * (
            radius * p["spin"]) ** 2
        approach_scale = hertz.max_approach(m_normal, radius, modulus, scale_speed)
        duration = np.array([laws[index].tau_end for index in law_of_case]) * approach_scale / scale_speed
        contact_ratio = np.sqrt(approach_scale / radius)
        face_compliance = (1.0 - p["face_poisson_ratio"] ** 2) / p["face_youngs_modulus"]
        ball_compliance = (1.0 - p["ball_poisson_ratio"] ** 2) / p["ball_youngs_modulus"]
        validity = (np.where(contact_ratio > LARGE_CONTACT_RATIO, 1, 0) | np.where(face_compliance > ball_compliance, 2, 0)
                    | np.where(sliding & capped, 4, 0))
        result = {
            "normal_impulse": (1.0 + restitution) * m_normal * normal_speed,
            # the contact point's slip falls by |slip_change|; the impulse on the ball opposes the slip
            "tangential_impulse": -np.sign(slip) * m_tangential * slip_change,
            "contact_time": duration,
            "contact_radius_ratio": contact_ratio,
            "steps": steps,
            "energy_error": m_tangential * velocity_unit**2 * residual / initial_energy,
            "validity": validity.astype(float),
        }
        if histories:
            peak = hertz.peak_force(m_normal, radius, modulus, scale_speed)
            scales = {"normal_force": peak, "tangential_force": peak * friction * np.sign(slip),
                      "stick_radius": np.sqrt(radius * approach_scale)}
            result.update(self._histories(histories, duration, approach_scale / scale_speed, scales, laws,
                                          law_of_case, solution_of_case))
        return {name: result[name] for name in outputs | ({"time"} if histories else set())}

    @staticmethod
    @functools.lru_cache(maxsize=64)
    def _damped_law(restitution: float):
        return hertz.DampedNormal(hertz.damping_for_restitution(float(restitution)))

    def _solve(self, chi, psi1, record, normal, resolution, steps):
        if self.options.method == "annuli":
            def solve(chi_part, psi_part):
                return annuli.solve_scaled(chi_part, psi_part, rings=resolution, steps=steps, record=record,
                                           normal=normal)
        else:
            def solve(chi_part, psi_part):
                return mdr.solve_scaled(chi_part, psi_part, springs=resolution, steps=steps, record=record,
                                        normal=normal)
        parts = [solve(chi[i:i + BLOCK], psi1[i:i + BLOCK]) for i in range(0, chi.size, BLOCK)]
        joined = {name: np.concatenate([getattr(part, name) for part in parts]) if record else None
                  for name in ("force", "stick_radius")}
        return mdr.TangentialSolution(np.concatenate([part.slip_change for part in parts]), parts[0].tau,
                                      joined["force"], joined["stick_radius"], parts[0].steps,
                                      np.concatenate([part.dissipation for part in parts]))

    def _histories(self, wanted, duration, time_scale, scales, laws, law_of_case, solution_of_case):
        """Histories on one time axis from 0 to the longest contact; NaN after a case's contact ends."""
        time = np.linspace(0.0, float(duration.max()), self.options.history_points)
        out = {"time": time}
        shapes = {name: np.full((duration.size, time.size), np.nan) for name in wanted}
        for case in range(duration.size):
            law = laws[law_of_case[case]]
            tau = time / time_scale[case]
            inside = tau <= law.tau_end * (1 + 1e-12)
            h = law.approach(tau)
            solved, row = solution_of_case[case] or (None, None)
            for name in wanted:
                if name == "normal_force":
                    shape = h**1.5 * law.load_factor(tau)
                elif row is not None:
                    history = solved.force if name == "tangential_force" else solved.stick_radius
                    shape = np.interp(tau, solved.tau, history[row])
                elif name == "stick_radius":  # no tangential load anywhere: the whole contact sticks
                    shape = np.sqrt(h)
                else:
                    shape = np.zeros_like(tau)
                shapes[name][case] = np.where(inside, shape, np.nan)
        for name in wanted:
            out[name] = scales[name][:, None] * shapes[name]
        return out
