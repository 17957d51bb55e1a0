"""Hertz impact with tangential compliance and Coulomb microslip (Maw, Barber & Fawcett), MDR engine."""

from __future__ import annotations

import attrs
import numpy as np

from impactlab._validate import check
from impactlab.model import ImpactModel
from impactlab.physics import annuli, hertz, mdr
from impactlab.physics.mechanics import approach_velocities, effective_mass, tangential_mass

from ._common import IMPULSES, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL

METHODS = ("mdr", "annuli")
#: cases solved together; bounds the memory of the spring arrays
BLOCK = 2048


def _int_at_least(low: int):
    return check(lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= low, f"an integer >= {low}")


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
    springs : int
        MDR springs across the half-width of the largest contact; error falls
        as 1/springs^2 (about 3e-5 in psi2 at the default 200).
    rings : int
        Annuli of the annular-strip method; error falls roughly as
        1/rings^1.4 (about 4e-3 in psi2 at the default 40, 1.4e-3 at 80).
    steps : int
        Uniform time steps over the contact; each spring's entry and exit
        instants are added to them, so contact changes fall on steps.
    history_points : int
        Samples of the force histories on the shared time axis (when asked).
    """

    method: str = attrs.field(default="mdr", validator=check(lambda v: v in METHODS,
                                                             f"one of {', '.join(METHODS)}"))
    springs: int = attrs.field(default=200, validator=_int_at_least(8))
    rings: int = attrs.field(default=40, validator=_int_at_least(4))
    steps: int = attrs.field(default=400, validator=_int_at_least(16))
    history_points: int = attrs.field(default=256, validator=_int_at_least(2))


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

    Normal restitution: the model is elastic. When the scene gives e < 1 it
    follows Henrikson et al. (2020): it solves the elastic problem at the
    normal speed (1 + e) V_z / 2, so that the normal impulse is (1 + e) m* V_z,
    with the real tangential slip speed.

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
    provides = IMPULSES | {"contact_time", "normal_force", "tangential_force", "stick_radius"}
    Options = MawOptions

    def _compute(self, inputs, outputs):
        p = inputs
        radius, ball_mass = p["ball_radius"], p["ball_mass"]
        modulus = hertz.effective_modulus(p["ball_youngs_modulus"], p["ball_poisson_ratio"],
                                          p["face_youngs_modulus"], p["face_poisson_ratio"])
        kappa = hertz.tangential_modulus(p["ball_youngs_modulus"], p["ball_poisson_ratio"],
                                         p["face_youngs_modulus"], p["face_poisson_ratio"]) / modulus
        m_normal = effective_mass(ball_mass, p["club_mass"])
        m_tangential = tangential_mass(ball_mass, p["ball_inertia_factor"], p["club_mass"])
        normal_speed, slip = approach_velocities(p["speed"], p["angle"], p["spin"], radius)
        restitution = p.get("restitution", np.ones_like(normal_speed))
        # Henrikson et al.: the elastic problem at an adjusted speed carries the inelastic normal impulse.
        elastic_speed = 0.5 * (1.0 + restitution) * normal_speed
        friction = p["friction"]

        histories = {"normal_force", "tangential_force", "stick_radius"} & outputs
        sliding = (friction > 0.0) & (slip != 0.0)
        slip_change = np.zeros_like(slip)
        scaled_history, tau = {}, None
        if np.any(sliding):
            chi = 0.5 * kappa * m_normal / m_tangential
            psi1 = kappa * np.abs(slip) / np.where(sliding, friction * elastic_speed, 1.0)
            scaled = self._solve(chi[sliding], psi1[sliding], record=bool(histories - {"normal_force"}))
            slip_change[sliding] = scaled.slip_change * friction[sliding] * elastic_speed[sliding] / kappa[sliding]
            if scaled.force is not None:
                tau = scaled.tau
                for name, values in (("tangential_force", scaled.force), ("stick_radius", scaled.stick_radius)):
                    scaled_history[name] = np.zeros((slip.size, tau.size))
                    scaled_history[name][sliding] = values
        result = {
            "normal_impulse": 2.0 * m_normal * elastic_speed,
            # the contact point's slip falls by |slip_change|; the impulse on the ball opposes the slip
            "tangential_impulse": -np.sign(slip) * m_tangential * slip_change,
            "contact_time": hertz.contact_time(m_normal, radius, modulus, elastic_speed),
        }
        if histories:
            scales = {"normal_force": hertz.peak_force(m_normal, radius, modulus, elastic_speed),
                      "tangential_force": hertz.peak_force(m_normal, radius, modulus, elastic_speed)
                      * friction * np.sign(slip),
                      "stick_radius": np.sqrt(radius * hertz.max_approach(m_normal, radius, modulus, elastic_speed))}
            result.update(self._histories(histories, result["contact_time"], scales, tau, scaled_history))
        return {name: result[name] for name in outputs | ({"time"} if histories else set())}

    def _solve(self, chi, psi1, record):
        options = self.options
        if options.method == "annuli":
            def solve(chi_part, psi_part):
                return annuli.solve_scaled(chi_part, psi_part, rings=options.rings, steps=options.steps, record=record)
        else:
            def solve(chi_part, psi_part):
                return mdr.solve_scaled(chi_part, psi_part, springs=options.springs, steps=options.steps,
                                        record=record)
        parts = [solve(chi[i:i + BLOCK], psi1[i:i + BLOCK]) for i in range(0, chi.size, BLOCK)]
        joined = {name: np.concatenate([getattr(part, name) for part in parts]) if record else None
                  for name in ("force", "stick_radius")}
        return mdr.TangentialSolution(np.concatenate([part.slip_change for part in parts]), parts[0].tau,
                                      joined["force"], joined["stick_radius"], parts[0].steps)

    def _histories(self, wanted, duration, scales, tau, scaled_history):
        """Histories on one time axis from 0 to the longest contact; NaN after a case's contact ends."""
        time = np.linspace(0.0, float(duration.max()), self.options.history_points)
        scaled_time = time[None, :] / (duration[:, None] / hertz.TAU_CONTACT)
        inside = scaled_time <= hertz.TAU_CONTACT * (1 + 1e-12)
        out = {"time": time}
        for name in wanted:
            if name == "normal_force":
                shape = hertz.scaled_approach(scaled_time) ** 1.5
            elif name in scaled_history:
                shape = np.vstack([np.interp(scaled_time[case], tau, scaled_history[name][case])
                                   for case in range(scaled_time.shape[0])])
            elif name == "stick_radius":  # no tangential load anywhere: the whole contact sticks
                shape = np.sqrt(hertz.scaled_approach(scaled_time))
            else:
                shape = np.zeros_like(scaled_time)
            out[name] = np.where(inside, scales[name][:, None] * shape, np.nan)
        return out
