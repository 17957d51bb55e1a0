"""Shared machinery of the models on a Hertz normal contact with a tangential law in MBF's scaled variables."""

from __future__ import annotations

import functools

import numpy as np

from impactlab._validate import check
from impactlab.diagnostics import LARGE_CONTACT_RATIO
from impactlab.model import ImpactModel
from impactlab.physics import hertz
from impactlab.physics.mechanics import approach_velocities, effective_mass, tangential_mass

from ._common import IMPULSES, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL

#: how a restitution e < 1 enters the compliant models (option ``inelastic``)
INELASTIC = ("adjusted_speed", "hysteretic")


def int_at_least(low: int):
    return check(lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= low, f"an integer >= {low}")


def optional_int(low: int):
    return check(lambda v: v is None or (isinstance(v, int) and not isinstance(v, bool) and v >= low),
                 f"an integer >= {low} (or leave it out and set tolerance)")


class HertzTangentialModel(ImpactModel):
    """Base of the compliant models: Hertz normal contact, a tangential law solved in scaled variables.

    The normal problem is Hertz's, shared by every tangential law; restitution
    enters by option ``inelastic`` (adjusted speed or a hysteretic law). The
    tangential problem is posed in the variables of Maw, Barber & Fawcett,
    chi = (kappa/2) m*/m_t and psi1 = kappa V_x/(mu V_z), and solved by the
    subclass's :meth:`_solve`, which returns a :class:`~impactlab.physics.mdr.TangentialSolution`.
    Its options must provide ``resolution(chi, psi1)`` (resolution and "tolerance not met" per
    case), ``resolution_steps(count)``, ``history_points`` and ``inelastic``.
    """

    requires = RIGID_BODY_INPUTS | {"friction", "ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                                    "face_poisson_ratio"}
    optional_inputs = RIGID_BODY_OPTIONAL | {"restitution"}
    provides = IMPULSES | {"contact_time", "normal_force", "tangential_force", "stick_radius", "contact_radius_ratio",
                           "steps", "energy_error", "validity"}

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
            laws = [hertz.ELASTIC]
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
        # each case's resolution depends on its own chi and psi1 only: its result never depends on its batch
        resolution = np.zeros(slip.size, dtype=int)
        capped = np.zeros(slip.size, dtype=bool)
        for value in np.unique(chi[sliding]):
            members = sliding & (chi == value)
            resolution[members], capped[members] = self.options.resolution(float(value), psi1[members])
        solution_of_case = [None] * slip.size  # (solution, row) of each solved case, for its histories
        for index, law in enumerate(laws):
            for count in np.unique(resolution[sliding & (law_of_case == index)]):
                members = sliding & (law_of_case == index) & (resolution == count)
                steps_wanted = self.options.resolution_steps(int(count))
                solved = self._solve(chi[members], psi1[members], record, law, int(count), steps_wanted,
                                     kappa=kappa[members])
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
        validity = (np.where(contact_ratio > LARGE_CONTACT_RATIO, 1, 0)
                    | np.where(face_compliance > ball_compliance, 2, 0)
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

    def _solve(self, chi, psi1, record, normal, resolution, steps, kappa):
        """Solve the scaled tangential problem of the cases (chi, psi1) under ``normal``; kappa = k_t/k_n."""
        raise NotImplementedError

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
