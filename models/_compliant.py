"""Shared machinery of the models on a Hertz normal contact with a tangential law in MBF's scaled variables."""

from __future__ import annotations

import functools
from types import SimpleNamespace
from typing import Protocol, runtime_checkable

import numpy as np

from impactlab.validators import check
from impactlab.errors import ModelContractError
from impactlab.model import LARGE_CONTACT_RATIO, ImpactModel
from impactlab.physics import compliant3d, coupling, hertz, mdr

from impactlab.physics import ball_laws
from impactlab.physics.contact import couple_mobility
from impactlab.physics.rolling_line import planar_couple

from ._common import (FRICTION_INPUTS, IMPULSES_3D, PLAIN_BALL, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL,
                      ROLLING_OUTPUTS, core_inputs, face_inputs, face_restitution, law_friction, rate_law_state,
                      rolling_on)
from impactlab.physics import rate_laws

#: distinct restitutions above which the hysteretic law is tabulated per case and solved by the 3-D kernel
MAX_DAMPED_LAWS = 8
#: how a restitution e < 1 enters the compliant models (option ``inelastic``)
INELASTIC = ("adjusted_speed", "hysteretic")


def int_at_least(low: int):
    return check(lambda v: isinstance(v, int) and not isinstance(v, bool) and v >= low, f"an integer >= {low}")


def optional_int(low: int):
    return check(lambda v: v is None or (isinstance(v, int) and not isinstance(v, bool) and v >= low),
                 f"an integer >= {low} (or leave it out and set tolerance)")


@runtime_checkable
class CompliantOptions(Protocol):
    """What the options of a :class:`HertzTangentialModel` provide: how finely to solve, and how.

    ``maw``'s and the DEM models' Options subclass it; a new compliant model's Options must provide the same
    (checked when the model is made).

    Attributes
    ----------
    tolerance : float
        Target error of the tangential impulse (the model declares ``has_tolerance``).
    history_points : int
        Samples of the force histories on the shared time axis.
    inelastic : str
        How a restitution e < 1 enters, one of :data:`INELASTIC`.
    """

    __slots__ = ()

    tolerance: float
    history_points: int
    inelastic: str

    def resolution(self, chi: float, psi1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(springs or rings, tolerance not met) of the 1-D solver for each case with this chi and these psi1."""

    def resolution_steps(self, count: int) -> int:
        """Uniform time steps of the 1-D solver that go with ``count`` springs or rings."""

    def resolution_3d(self) -> tuple[int, int, bool]:
        """(springs, steps, tolerance not met) of the 3-D kernel."""

    def expert_resolution(self) -> tuple[int, int] | None:
        """(springs, steps) set by hand (overriding the tolerance), or None (:meth:`ImpactModel.expert_resolution`)."""


class HertzTangentialModel(ImpactModel):
    """Base of the compliant models: Hertz normal contact, a tangential law solved in scaled variables.

    The normal problem is Hertz's, shared by every tangential law; restitution
    enters by option ``inelastic`` (adjusted speed or a hysteretic law). The
    tangential problem is posed in the variables of Maw, Barber & Fawcett,
    chi = (kappa/2) m*/m_t and psi1 = kappa V_x/(mu V_z), and solved by the
    subclass's :meth:`_solve`, which returns a :class:`~impactlab.physics.mdr.TangentialSolution`.
    Its options are :class:`CompliantOptions`.
    """

    requires = RIGID_BODY_INPUTS | {"friction", "ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                                    "face_poisson_ratio"}
    optional_inputs = RIGID_BODY_OPTIONAL | FRICTION_INPUTS | {"restitution", "tangential_loss",
                                                              "club_restitution_gain"}
    provides = IMPULSES_3D | {"contact_time", "normal_force", "tangential_force", "stick_radius",
                              "contact_radius_ratio", "coupling_estimate", "steps", "energy_error", "validity",
                              "face_rotation"} | ROLLING_OUTPUTS
    #: whether the 3-D law's parameters depend on kappa (grouping of cases); DEM laws with a fixed ratio do
    _3d_depends_on_kappa = False
    has_tolerance = True
    #: every ball and face law of BallLawOptions (the reference-value checks hold with all of them off)
    ball_law_options = PLAIN_BALL

    def __init__(self, options=None, **option_values):
        super().__init__(options, **option_values)
        if not isinstance(self.options, CompliantOptions):
            raise ModelContractError(f"options of {self.name!r} ({type(self.options).__name__}) must provide what "
                                     "CompliantOptions declares (models/_compliant.py)")

    def history_length(self) -> int:
        return self.options.history_points

    def expert_resolution(self):
        return self.options.expert_resolution()

    def _compute(self, inputs, outputs):
        # the steps, each its own method: the contact and its laws, the plan of each case (1-D line or 3-D
        # kernel), the 1-D solves, the scalar results and their validity, the 3-D solves, the histories
        c = self._contact(inputs)
        self._normal_laws(c)
        histories = {"normal_force", "tangential_force", "stick_radius"} & outputs
        record = bool(histories - {"normal_force"})
        self._plan(c, inputs, outputs)
        self._solve_line(c, record)
        result = self._scalar_results(c, inputs)
        if np.any(c.three_d):
            self._solve_3d(c.three_d, c.state, c.friction, c.laws, c.law_of_case, c.resolution, c.scale_speed,
                           c.kappa, c.modulus, bool(histories), result, c.solution_of_case, c.initial_energy, c.loss,
                           c.rolling, c.core, None if c.face is None else c.face[0])
            self._correct_3d_limit(c, result)
        if c.couple is not None:
            # the friction's work on the slip [J] (the 1-D solvers' dissipation, TangentialSolution)
            friction_work = -c.m_tangential * c.velocity_unit**2 * mdr.TANGENTIAL_GAIN * c.chi * c.dissipation
            self._planar_results(result, c.rolling, c.planar, c.slip, c.moment, c.rolling_work, friction_work,
                                 (c.m_normal, c.m_tangential), c.radius, c.modulus, c.approach_scale, c.scale_speed,
                                 c.initial_energy)
        result["validity"] = (result["validity"].astype(int) | np.where(c.limit_broken, 64, 0)).astype(float)
        if histories:
            peak = hertz.peak_force(c.m_normal, c.radius, c.modulus, c.scale_speed)
            scales = {"normal_force": peak, "tangential_force": peak * c.friction * np.sign(c.slip),
                      "stick_radius": np.sqrt(c.radius * c.approach_scale)}
            result.update(self._histories(histories, result["contact_time"], c.approach_scale / c.scale_speed,
                                          scales, c.laws, c.law_of_case, c.solution_of_case))
        return {name: result[name] for name in outputs | ({"time"} if histories else set())}

    def _contact(self, p) -> SimpleNamespace:
        """Step 1: the contact of each case (moduli, masses, speeds, friction, the flexing face)."""
        c = SimpleNamespace()
        c.ball_mass = p["ball_mass"]
        c.moduli = (p["ball_youngs_modulus"], p["ball_poisson_ratio"], p["face_youngs_modulus"],
                    p["face_poisson_ratio"])
        c.modulus = hertz.effective_modulus(*c.moduli)
        kappa = hertz.tangential_modulus(*c.moduli) / c.modulus
        c.state = p.contact_state()
        c.kappa = self._construction_kappa(kappa, c.moduli, c.modulus, c.state)
        mobility = c.state["mobility"]
        # the contact's own masses: m* = 1/W_nn, m_t = 1/W_ss (a point mass or fixed face: the 1-D formulas)
        c.m_normal, c.m_tangential = 1.0 / mobility[:, 2, 2], 1.0 / mobility[:, 0, 0]
        c.normal_speed, c.slip, c.radius = c.state["normal_speed"], c.state["slip_speed"], c.state["contact_radius"]
        c.restitution = p.get("restitution", np.ones_like(c.normal_speed))
        # the friction law's coefficient per case (option friction_law; "coulomb": the friction input)
        c.friction = law_friction(self.options, p, c.state, c.restitution)
        # the laws with a scale (rate_laws; RATE_LAWS_DOC): each off returns its input (today's model exactly)
        c.restitution, c.friction, c.lever_arm = rate_law_state(self.options, p, c.state, c.restitution, c.friction)
        # the face flexing behind the contact (options face_frequency & co.; impactlab.physics.face_flex): on a
        # spring-like face the normal law takes the ball's own e, the face's mode giving what the gain stood for
        c.face = face_inputs(self.options, p, c.normal_speed.size)
        c.normal_restitution = face_restitution(c.face, p, c.restitution)
        return c

    def _normal_laws(self, c) -> None:
        """Step 2: the normal law of each case and the speed its scaled problem runs at."""
        if self.options.inelastic == "adjusted_speed":
            # Henrikson et al.: the elastic problem at an adjusted speed carries the inelastic normal impulse
            c.scale_speed = 0.5 * (1.0 + c.normal_restitution) * c.normal_speed
            c.law_of_case = np.zeros(c.slip.size, dtype=int)
            c.laws = [hertz.ELASTIC]
        else:
            c.scale_speed = c.normal_speed
            levels, c.law_of_case = np.unique(c.normal_restitution, return_inverse=True)
            per_case = levels.size > MAX_DAMPED_LAWS
            if per_case:  # a law per case (a restitution law of the speed): tabulated laws, the 3-D kernel
                c.laws, c.law_of_case = [hertz.CaseNormals(c.normal_restitution)], np.zeros(c.slip.size, dtype=int)
            else:
                c.laws = [self._damped_law(level) for level in levels]

    def _plan(self, c, p, outputs) -> None:
        """Step 3: the plan of each case: the scaled 1-D solver where the mobility is diagonal in the contact frame
        (the slip stays on one line, the normal problem is uncoupled) or there is no friction to couple them; the
        3-D solver elsewhere, and wherever the head's rotation during contact is asked for."""
        slip, friction = c.slip, c.friction
        c.sliding = (friction > 0.0) & (slip != 0.0)
        c.loss = np.broadcast_to(p.get("tangential_loss", 0.0), slip.shape)
        relaxation = float(getattr(self.options, "tangential_relaxation_time", 0.0) or 0.0)
        if relaxation:  # a dashpot of a physical time: its loss factor at the contact's frequency, pi tau_t / t_c
            c.loss = c.loss + rate_laws.tangential_loss_of_time(relaxation, hertz.contact_time(
                c.m_normal, c.radius, c.modulus, c.scale_speed))
        # the 1-D solvers have elastic tangential springs: a lossy cover takes the 3-D kernel (which reduces to
        # the 1-D problem on one line)
        three_d = (~c.state["one_dimensional"] | (c.loss > 0.0)) & (friction > 0.0)
        # the core turning behind the shell (option core_radius; impactlab.physics.core_torsion): its modes ride on
        # the 3-D kernel's slip and rolling rate
        c.core = core = core_inputs(self.options, p, friction)
        if core is not None and not self._planar_core:
            three_d |= friction > 0.0
        elif core is not None and not isinstance(c.laws[0], hertz.CaseNormals):
            # the 1-D solver's uniform steps carry the modes by leapfrog, which diverges for Omega_k dt > 2: a case
            # whose stiffest mode needs more takes the 3-D kernel, which raises its steps per case (core_steps)
            fastest = core[1].max(axis=1) * hertz.max_approach(c.m_normal, c.radius, c.modulus, c.scale_speed) \
                / c.scale_speed
            tau_end = np.array([law.tau_end for law in c.laws])[c.law_of_case]
            three_d |= (fastest * tau_end > compliant3d.CORE_STEP * self.options.resolution_steps(1)) & (friction > 0.0)
        # rolling resistance (ball_laws): a couple on the contact. A model whose 1-D solver carries it
        # (_planar_rolling) keeps the cases where it stays on the line there (couple and rolling about the lateral
        # axis alone, no normal coupling: :func:`planar_couple`); the others take the 3-D kernel
        hysteresis = getattr(self.options, "rolling_hysteresis", 0.0)
        c.rolling, planar = None, np.zeros(slip.size, dtype=bool)
        if rolling_on(hysteresis) or c.lever_arm is not None:
            arm_factor = np.zeros(slip.size)
            if rolling_on(hysteresis):
                arm_factor = ball_laws.SPHERE_FACTOR * ball_laws.hysteresis_fraction(
                    hysteresis, c.restitution, p.get("club_restitution_gain", 0.0))
            if c.lever_arm is not None:  # the deformed ball's lever as an arm factor d / a of the same mean offset
                arm_factor = arm_factor + rate_laws.arm_factor_of_lever(
                    self.options.compression_lever, c.radius, hertz.max_approach(c.m_normal, c.radius, c.modulus,
                                                                                 c.scale_speed))
            rolls = (arm_factor > 0.0) & (friction > 0.0)
            c.rolling = self._rolling_inputs(p, c.state, arm_factor)
            if self._planar_rolling and c.rolling is not None and core is None:  # (the 1-D solver takes either)
                planar = rolls & ~three_d & (slip != 0.0) & planar_couple(*c.rolling[:3])
            three_d |= rolls & ~planar
        if isinstance(c.laws[0], hertz.CaseNormals):  # the scaled 1-D solver needs one law per batch
            three_d = np.ones(slip.size, dtype=bool)
        if c.face is not None:  # a flexing face changes the normal problem: the 3-D kernel integrates it per case
            three_d |= c.face[1]
        turning_head = c.state["head_inverse_inertia"] is not None
        if "face_rotation" in outputs and turning_head:
            three_d = np.ones(slip.size, dtype=bool)
        planar &= ~three_d
        self._check_dimensions(three_d)
        c.three_d, c.planar = three_d, planar

    def _solve_line(self, c, record: bool) -> None:
        """Step 4: the cases of the line, by the scaled 1-D solver, batched by law and resolution."""
        slip, line, sliding = c.slip, ~c.three_d, c.sliding
        c.chi = chi = 0.5 * c.kappa * c.m_normal / c.m_tangential
        c.psi1 = psi1 = c.kappa * np.abs(slip) / np.where(sliding, c.friction * c.scale_speed, 1.0)
        c.slip_change, c.residual, c.steps = np.zeros_like(slip), np.zeros_like(slip), np.zeros_like(slip)
        # each case's resolution depends on its own chi and psi1 only: its result never depends on its batch
        c.resolution = resolution = np.zeros(slip.size, dtype=int)
        c.capped = capped = np.zeros(slip.size, dtype=bool)
        for value in np.unique(chi[sliding & line]):
            members = sliding & line & (chi == value)
            resolution[members], capped[members] = self.options.resolution(float(value), psi1[members])
        springs_3d, steps_3d, capped_3d = self.options.resolution_3d()
        resolution[c.three_d], capped[c.three_d] = springs_3d, capped_3d
        c.solution_of_case = [None] * slip.size  # (solution, row) of each solved case, for its histories
        c.limit_broken = np.zeros(slip.size, dtype=bool)  # MDR broke the 3-D Coulomb limit (a damped law)
        c.approach_scale = hertz.max_approach(c.m_normal, c.radius, c.modulus, c.scale_speed)
        c.couple = self._planar_couple(c.rolling, c.planar, slip, c.friction, c.kappa, c.m_normal, c.radius,
                                       c.approach_scale, c.scale_speed) if np.any(c.planar) else None
        # the core's modes on the line, scaled as dem.solve_scaled's ``core``
        core, time_scale = c.core, c.approach_scale / c.scale_speed
        core_line = None if core is None or not self._planar_core else (
            1.25 * c.kappa[:, None] * (c.m_normal * core[3] ** 2)[:, None] * core[0],
            (core[1] * time_scale[:, None]) ** 2, core[2] * time_scale[:, None])
        c.moment, c.rolling_work, c.dissipation = np.zeros_like(slip), np.zeros_like(slip), np.zeros_like(slip)
        for index, law in enumerate(c.laws):
            for count in np.unique(resolution[line & sliding & (c.law_of_case == index)]):
                members = line & sliding & (c.law_of_case == index) & (resolution == count)
                self._solve_members(c, members, law, int(count), record, core_line)

    def _solve_members(self, c, members, law, count: int, record: bool, core_line) -> None:
        """One batch of the line: one law, one resolution."""
        couple, chi, psi1 = c.couple, c.chi, c.psi1
        steps_wanted = self.options.resolution_steps(count)
        extra = {} if couple is None else {"rolling": [part[members] for part in couple]}
        if core_line is not None:
            extra["core"] = [part[members] for part in core_line]
        solved = self._solve(chi[members], psi1[members], record, law, count, steps_wanted,
                             kappa=c.kappa[members], **extra)
        c.slip_change[members] = solved.slip_change
        if couple is not None:  # the slip change of the friction alone, and the couple's own results
            c.moment[members], c.rolling_work[members] = solved.moment, solved.rolling_work
            c.dissipation[members] = solved.dissipation
            c.slip_change[members] -= couple[0][members] * solved.moment
        if solved.capped is not None:  # a part re-solved by a method whose resolution ran out
            c.capped[members] |= solved.capped
        if getattr(solved, "breaks_3d_limit", None) is not None:
            c.limit_broken[members] |= solved.breaks_3d_limit
        c.residual[members] = solved.energy_residual(chi[members], psi1[members])
        c.steps[members] = solved.steps
        for row, case in enumerate(np.nonzero(members)[0]):
            c.solution_of_case[case] = (solved, row)

    def _scalar_results(self, c, p) -> dict:
        """Step 5: the impulses, contact time, coupling estimate and validity flags of every case (the 3-D cases'
        impulses are overwritten by their solver)."""
        slip, sliding, m_normal, m_tangential = c.slip, c.sliding, c.m_normal, c.m_tangential
        # back from the scaled slip velocity (units mu V / kappa) to m/s, and the energy residual to joules
        c.velocity_unit = c.friction * c.scale_speed / c.kappa
        c.slip_change *= c.velocity_unit
        ball_mass = c.ball_mass
        c.initial_energy = 0.5 * ball_mass * p["speed"] ** 2 + 0.5 * p["ball_inertia_factor"] * ball_mass * (
            p["ball_radius"] * p.get("spin", 0.0)) ** 2
        duration = np.array([c.laws[index].tau_end for index in c.law_of_case]) * c.approach_scale / c.scale_speed \
            if not isinstance(c.laws[0], hertz.CaseNormals) else c.laws[0].tau_end * c.approach_scale / c.scale_speed
        contact_ratio = np.sqrt(c.approach_scale / c.radius)
        face_compliance = (1.0 - p["face_poisson_ratio"] ** 2) / p["face_youngs_modulus"]
        ball_compliance = (1.0 - p["ball_poisson_ratio"] ** 2) / p["ball_youngs_modulus"]
        # the neglected normal-tangential coupling (Dundurs' beta; impactlab.physics.coupling): its estimated
        # change of J_t against what the tolerance allows, tol * min(mu J_n, m_t |V_x|)
        beta_d = coupling.dundurs_beta(*c.moduli)
        coupled = coupling.coupling_estimate(beta_d, c.kappa, c.friction)
        coulomb = c.friction * (1.0 + c.restitution) * m_normal * c.normal_speed
        allowed = self.options.tolerance * np.minimum(coulomb, m_tangential * np.abs(slip))
        validity = (np.where(contact_ratio > LARGE_CONTACT_RATIO, 1, 0)
                    | np.where(face_compliance > ball_compliance, 2, 0)
                    | np.where((sliding | c.three_d) & c.capped, 4, 0)
                    | np.where(sliding & (coupled * coulomb > allowed), 16, 0))
        return {
            "normal_impulse": (1.0 + c.restitution) * m_normal * c.normal_speed,
            # the contact point's slip falls by |slip_change|; the impulse on the ball opposes the slip
            "tangential_impulse": -np.sign(slip) * m_tangential * c.slip_change,
            "lateral_impulse": np.zeros_like(slip),
            "face_rotation": np.zeros_like(slip),
            "rolling_moment": np.zeros_like(slip),
            "rolling_moment_slip": np.zeros_like(slip),
            "contact_time": duration,
            "contact_radius_ratio": contact_ratio,
            "coupling_estimate": np.where(sliding, coupled, 0.0),
            "steps": c.steps,
            "energy_error": m_tangential * c.velocity_unit**2 * c.residual / c.initial_energy,
            "validity": validity.astype(float),
        }

    def _correct_3d_limit(self, c, result: dict) -> None:
        """Step 6: the 3-D kernel's MDR springs face the same 3-D Coulomb limit as the 1-D solver's: check it
        through the decoupled equivalent of each case (same chi and psi1) and carry the 1-D path's correction, so
        that the answer is one continuous function of the strike position (issue 21, item 5); with a core, that of
        its rigid ball (the core's effect on the correction neglected, as the coupling's: exact in the stiff
        limit)."""
        if type(self)._limit_correction is HertzTangentialModel._limit_correction:
            # this model's 1-D solver corrects nothing (the spring models): skip it, and above all the damped law
            # each distinct restitution would otherwise solve for it (0.07 s a level: a restitution law of the speed
            # made a 400-shot batch 150 times slower, for a correction of zero)
            return
        damped = [index for index, law in enumerate(c.laws) if not isinstance(law, hertz.ElasticNormal)]
        if not damped:
            return
        correct = c.three_d & c.sliding & (c.loss == 0.0)  # a flexing face's too: its rigid face's (exact when stiff)
        if isinstance(c.laws[0], hertz.CaseNormals):
            levels, level_of_case = np.unique(c.normal_restitution, return_inverse=True)
            groups = [(self._damped_law(float(level)), correct & (level_of_case == k))
                      for k, level in enumerate(levels)]
        else:
            groups = [(c.laws[index], correct & (c.law_of_case == index)) for index in damped]
        for law, members in groups:
            if not np.any(members):
                continue
            change, broken = self._limit_correction(c.chi[members], c.psi1[members], law)
            result["tangential_impulse"][members] += -np.sign(c.slip[members]) * c.m_tangential[members] \
                * change * c.velocity_unit[members]
            c.limit_broken[members] |= broken

    def _check_dimensions(self, three_d) -> None:
        """Refuse 3-D cases if the configured method solves only 1-D ones (a model may override)."""

    def _law_3d(self, kappa: float) -> dict:
        """Keyword arguments of :func:`impactlab.physics.compliant3d.solve` for this model's tangential law."""
        raise NotImplementedError

    def _construction_kappa(self, kappa, moduli, modulus, state):
        """kappa of a ball with a cover (options ``cover_thickness``, ``cover_modulus``; ball_laws.layered_kappa)."""
        thickness = getattr(self.options, "cover_thickness", 0.0)
        if not thickness:
            return kappa
        ball_modulus, ball_poisson = moduli[0], moduli[1]
        cover = getattr(self.options, "cover_modulus", None) or ball_modulus
        mobility = state["mobility"]
        # the contact radius at which the layer is taken: the Hertz impulse-weighted mean, 0.896 a_max
        approach = hertz.max_approach(1.0 / mobility[:, 2, 2], state["contact_radius"], modulus,
                                      state["normal_speed"])
        radius = ball_laws.mean_radius_ratio() * np.sqrt(state["contact_radius"] * approach)
        shear = 1.0 / (2.0 * (1.0 + ball_poisson))
        return ball_laws.layered_kappa(kappa, kappa * modulus, ball_modulus * shear, radius, thickness,
                                       cover * shear)

    #: whether :meth:`_solve` takes ``rolling`` (a couple on the line; see dem.solve_scaled)
    _planar_rolling = False
    #: whether :meth:`_solve` takes ``core`` (the core's modes on the line; see dem.solve_scaled)
    _planar_core = False

    @staticmethod
    def _planar_couple(rolling, planar, slip, friction, kappa, m_normal, radius, approach, speed):
        """The scaled couple of the 1-D solver (dem.solve_scaled's ``rolling``) per case; arm 0 off ``planar``.

        The scales of the 3-D kernel (compliant3d.solve_once): couple C / (F_max a_max), rolling rate
        Omega a_max / V_z, with b = m* a_max B_sl and r = m* a_max^2 D_ll; on the line the 1-D solver counts the
        slip positive (psi1 = kappa |V_s| / (mu V_z)), so the rolling rate is counted with the slip's sign.
        """
        coupling, rotation, rate, factor = rolling
        reach = np.sqrt(radius * approach)
        with np.errstate(divide="ignore", invalid="ignore"):
            b = coupling[:, 0, 1] * m_normal * reach
            r = np.where(planar, rotation[:, 1, 1] * m_normal * reach**2, 1.0)
            slip_gain = np.where(planar, 1.25 * kappa * b / friction, 0.0)
        start = np.where(planar, np.sign(slip) * rate[:, 1] * reach / speed, 0.0)
        return slip_gain, np.where(planar, friction * b, 0.0), r, start, np.where(planar, factor, 0.0)

    @staticmethod
    def _planar_results(result, rolling, planar, slip, moment, rolling_work, friction_work, masses, radius,
                        modulus, approach, speed, initial_energy):
        """The couple's angular impulse and the energy residual of the cases solved with a couple on the line.

        Residual as the 1-D solvers count it (energy lost minus work dissipated, over the initial kinetic energy),
        on the tangential and rolling coordinates, which the normal problem does not couple to on the line: the
        kinetic energy change J_s (v_s + dv_s / 2) + C (Omega + dOmega / 2) of the generalised mobility
        (:func:`impactlab.physics.contact.couple_mobility`) against the work of the friction and the couple.
        """
        coupling, rotation, rate, _ = rolling
        m_normal, m_tangential = masses
        peak = hertz.peak_force(m_normal, radius, modulus, speed)
        reach, unit = np.sqrt(radius * approach), peak * approach  # a_max [m], F_max delta_max [J]
        couple = np.sign(slip) * moment * peak * reach * approach / speed  # on the ball, along l [N m s]
        jt = -result["tangential_impulse"]  # on the ball, along s [N s]
        b, d = coupling[:, 0, 1], rotation[:, 1, 1]
        gained = jt * (slip + 0.5 * (jt / m_tangential + b * couple)) + couple * (rate[:, 1] + 0.5 * (b * jt
                                                                                                   + d * couple))
        work = friction_work + unit * rolling_work
        result["rolling_moment"] = np.where(planar, couple, result["rolling_moment"])
        result["energy_error"] = np.where(planar, (work - gained) / initial_energy, result["energy_error"])

    @staticmethod
    def _rolling_inputs(inputs, state, arm_factor):
        """(B, D, rolling rate, arm factor) of every case for the 3-D kernel's couple, or None without one."""
        if not np.any(arm_factor > 0.0):
            return None
        coupling, rotation, rate = couple_mobility(state, inputs["ball_mass"], inputs["ball_radius"],
                                                   inputs["ball_inertia_factor"])
        return coupling, rotation, rate, arm_factor

    def _solve_3d(self, members, state, friction, laws, law_of_case, resolution, scale_speed, kappa, modulus, record,
                  result, solution_of_case, initial_energy, loss, rolling=None, core=None, face=None):
        """The 3-D cases, grouped by normal law, resolution and (for laws that depend on it) kappa."""
        groups = np.unique(np.stack([law_of_case, resolution, kappa if self._3d_depends_on_kappa
                                     else np.zeros_like(kappa)], -1)[members], axis=0)
        for law_index, count, kappa_value in groups:
            rows = members & (law_of_case == law_index) & (resolution == count)
            if self._3d_depends_on_kappa:
                rows &= kappa == kappa_value
            springs, steps = int(count), self.options.resolution_3d()[1]
            normal = laws[int(law_index)]
            if isinstance(normal, hertz.CaseNormals):
                normal = normal.subset(rows)
            solved = compliant3d.solve(state["mobility"][rows], scale_speed[rows], state["slip_speed"][rows],
                                       friction=friction[rows], kappa=kappa[rows], modulus=modulus[rows],
                                       radius=state["contact_radius"][rows], normal=normal,
                                       springs=springs, steps=steps, record=record, tangential_loss=loss[rows],
                                       rolling=None if rolling is None else tuple(part[rows] for part in rolling),
                                       core=None if core is None else tuple(part[rows] for part in core),
                                       face=None if face is None else tuple(part[rows] for part in face),
                                       **self._law_3d(kappa_value))
            impulse = solved.impulse
            result["normal_impulse"][rows] = impulse[:, 2]
            result["tangential_impulse"][rows] = -impulse[:, 0]
            result["lateral_impulse"][rows] = impulse[:, 1]
            result["contact_time"][rows] = solved.contact_time
            result["steps"][rows] = solved.steps
            result["validity"][rows] = (result["validity"][rows].astype(int) | np.where(solved.unfinished, 8, 0))
            # energy balance of the solved (scaled-speed) problem: kinetic energy change = work of the forces
            initial = np.stack([state["slip_speed"][rows], np.zeros(impulse.shape[0]), -scale_speed[rows]], -1)
            mean = initial + 0.5 * np.einsum("nij,nj->ni", state["mobility"][rows], impulse)
            kinetic = np.sum(impulse * mean, -1)
            if rolling is not None:  # the couple's work on the mean relative rolling rate
                coupling, rotation, rate, _ = (part[rows] for part in rolling)
                moment = solved.moment
                result["rolling_moment"][rows], result["rolling_moment_slip"][rows] = moment[:, 1], moment[:, 0]
                rate_after = rate + np.einsum("nji,nj->ni", coupling, impulse) + np.einsum("nij,nj->ni", rotation,
                                                                                            moment)
                mean = mean + 0.5 * np.einsum("nij,nj->ni", coupling, moment)
                kinetic = np.sum(impulse * mean, -1) + np.sum(moment * 0.5 * (rate + rate_after), -1)
            result["energy_error"][rows] = (kinetic - solved.work) / initial_energy[rows]
            if state["head_inverse_inertia"] is not None:
                moment = np.einsum("nij,nj->ni", state["frame"][rows], solved.impulse_time)
                turn = np.einsum("nij,nj->ni", state["head_inverse_inertia"][rows],
                                 np.cross(state["lever"][rows], moment))
                result["face_rotation"][rows] = np.linalg.norm(turn, axis=-1)
            for row, case in enumerate(np.nonzero(rows)[0]):
                solution_of_case[case] = ("3d", solved, row)

    @staticmethod
    @functools.lru_cache(maxsize=64)
    def _damped_law(restitution: float):
        return hertz.DampedNormal(hertz.damping_for_restitution(float(restitution)))

    def _limit_correction(self, chi, psi1, normal) -> tuple[np.ndarray, np.ndarray]:
        """(change of the scaled slip change, 3-D limit broken) that the 1-D solver applies to MDR under ``normal``.

        A model whose 1-D solver corrects MDR where a damped law breaks the 3-D Coulomb limit returns that
        correction for the decoupled equivalents (chi, psi1) of 3-D cases; the default: none.
        """
        return np.zeros_like(chi), np.zeros(chi.size, dtype=bool)

    def _solve(self, chi, psi1, record, normal, resolution, steps, kappa):
        """Solve the scaled tangential problem of the cases (chi, psi1) under ``normal``; kappa = k_t/k_n."""
        raise NotImplementedError

    def _histories(self, wanted, duration, time_scale, scales, laws, law_of_case, solution_of_case):
        """Histories on one time axis from 0 to the longest contact; NaN after a case's contact ends."""
        time = np.linspace(0.0, float(duration.max()), self.options.history_points)
        out = {"time": time}
        shapes = {name: np.full((duration.size, time.size), np.nan) for name in wanted}
        for case in range(duration.size):
            solved, row = (solution_of_case[case] or (None, None))[:2]
            if solved == "3d":  # its own time grid, in SI: interpolate onto the shared axis
                _, solved3, row = solution_of_case[case]
                for name in wanted:
                    own = getattr(solved3, name)[row]
                    valid = ~np.isnan(own)
                    scale = scales[name][case] if scales[name][case] != 0.0 else 1.0
                    shapes[name][case] = np.where(time <= solved3.time[row][valid][-1] * (1 + 1e-12), np.interp(
                        time, solved3.time[row][valid], own[valid]), np.nan) / scale
                continue
            law = laws[law_of_case[case]]
            tau = time / time_scale[case]
            inside = tau <= law.tau_end * (1 + 1e-12)
            h = law.approach(tau)
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
