"""Rigid-body impact with Coulomb friction: the ball slides throughout or leaves rolling."""

from __future__ import annotations

import attrs

import numpy as np

from impactlab.errors import ModelInputError
from impactlab.model import ImpactModel
from impactlab.physics import ball_laws, hertz, rolling_line
from impactlab.physics.contact import couple_mobility
from impactlab.physics.rigid import STRONGE_STEPS, coulomb_impulses_1d, stronge_impulses

from .shared import (CLOSED_FORM_DIAGNOSTICS, IMPULSES_3D, MATERIAL_OPTIONAL, RIGID_BODY_INPUTS,
                      RIGID_BODY_OPTIONAL, RIGID_NOT_PROVIDED, ROLLING_HYSTERESIS, ROLLING_OUTPUTS, STRONGE,
                      FRICTION_INPUTS, FRICTION_LAW, closed_form_diagnostics, impulse_outputs, law_friction,
                      rolling_on)


@attrs.frozen
class RigidCoulombOptions:
    """Options of ``rigid_coulomb`` (friction and restitution come from the scene's contact).

    Parameters
    ----------
    steps : int
        Steps over the normal impulse of the 3-D integration (scenes whose slip may turn); exact where the
        slip keeps its direction, first order in 1/steps where it turns. Default 2000.
    rolling_hysteresis : float or str
        Rolling resistance of the viscoelastic cover (:mod:`impactlab.physics.ball_laws`): the normal force
        acts d = (3/16) alpha a ahead of the contact centre (Greenwood & Tabor; Johnson 1985, ch. 8), a
        couple d F_n opposing the relative rolling of ball and face; this rigid model uses the impulse-weighted
        mean offset of the Hertz history (0.896 a_max), so it reads the ball's and face's elastic constants.
        alpha, the fraction of a loading-unloading cycle's energy the cover loses, is a number in [0, 1] or
        ``"restitution"`` for 1 - e_ball^2 (the normal impact is that cycle: no free parameter; e_ball = e -
        club_restitution_gain, the ball's own e against a rigid face, without a wood face's spring-like gain).
        Default 0: no couple, the model unchanged.
    friction_law : str
        ``"coulomb"`` (default): the ``friction`` input; ``"adhesion"``: the coefficient of the ball-face pair's
        friction law (:mod:`impactlab.physics.friction_laws`; shared.FRICTION_LAW_DOC).
    """

    steps: int = attrs.field(default=STRONGE_STEPS, validator=attrs.validators.and_(
        attrs.validators.instance_of(int), attrs.validators.ge(10), attrs.validators.le(10**6)))
    rolling_hysteresis: float | str = attrs.field(default=0.0, validator=ROLLING_HYSTERESIS)
    friction_law: str = attrs.field(default="coulomb", validator=FRICTION_LAW)


class RigidCoulombModel(ImpactModel):
    """Rigid ball on a rigid face, normal restitution e and Coulomb friction mu.

    The normal impulse is J_n = (1 + e) m* V_z with 1/m* = 1/m + 1/M. If the
    contact-point slip V_x is large enough to survive the impact,
    |V_x| >= mu J_n / m_t with 1/m_t = (1 + 1/K^2)/m + 1/M, the ball slides
    throughout and J_t = mu J_n; otherwise the slip stops and the ball leaves
    rolling, J_t = m_t V_x (tangential restitution beta = 0; a solid sphere on
    a fixed face keeps 5/7 of its tangential speed). There is no tangential
    compliance, so beta is never positive.

    Inputs: ball mass, radius and inertia factor; impact speed, angle and
    (optional) spin; contact friction and restitution; club mass (optional,
    default infinite). Outputs: the impulses, from which the framework derives
    launch and spin.

    References
    ----------
    W. J. Stronge, *Impact Mechanics* (2000), ch. 5.
    R. M. Brach, *Mechanical Impact Dynamics* (1991).
    """

    name = "rigid_coulomb"
    label = "rigid body, Coulomb friction"
    references = (STRONGE, "R. M. Brach, Mechanical Impact Dynamics, Wiley (1991)")
    requires = RIGID_BODY_INPUTS | {"friction", "restitution"}
    optional_inputs = RIGID_BODY_OPTIONAL | MATERIAL_OPTIONAL | FRICTION_INPUTS | {"club_restitution_gain"}
    provides = IMPULSES_3D | CLOSED_FORM_DIAGNOSTICS | ROLLING_OUTPUTS
    not_provided = RIGID_NOT_PROVIDED
    Options = RigidCoulombOptions

    def _compute(self, inputs, outputs):
        state = inputs.contact_state()
        n = state["normal_speed"].size
        restitution = np.broadcast_to(inputs["restitution"], (n,))
        friction = law_friction(self.options, inputs, state, restitution)
        impulse = np.zeros((n, 3))
        diagnostics = closed_form_diagnostics(n)
        zero = np.zeros(n)
        rolling = {"rolling_moment": zero.copy(), "rolling_moment_slip": zero.copy()}
        todo = np.ones(n, dtype=bool)
        # a subclass's Options may leave the law out (getattr): then the model is today's
        hysteresis = getattr(self.options, "rolling_hysteresis", 0.0)
        if rolling_on(hysteresis):
            # cases with a positive offset take the integrator with the couple; the others (alpha = 0, no
            # friction to roll the ball) stay exactly today's model
            todo = self._rolling(inputs, state, friction, restitution, impulse, diagnostics, rolling)
        line = state["one_dimensional"] & todo
        if np.any(line):
            w = state["mobility"][line]
            jn, jt, _ = coulomb_impulses_1d(state["normal_speed"][line], state["slip_speed"][line],
                                            1.0 / w[:, 2, 2], 1.0 / w[:, 0, 0], friction[line], restitution[line])
            impulse[line, 0], impulse[line, 2] = -jt, jn
        coupled = todo & ~line
        if np.any(coupled):
            solved, flags = stronge_impulses(state["initial_velocity"][coupled], state["mobility"][coupled],
                                             friction[coupled], restitution[coupled], self.options.steps)
            impulse[coupled] = solved
            diagnostics["steps"][coupled] = self.options.steps
            diagnostics["validity"][coupled] = np.where(flags & 1, 4.0, 0.0)
        return {**impulse_outputs(impulse), **diagnostics, **rolling}

    def _rolling(self, inputs, state, friction, restitution, impulse, diagnostics, rolling):
        """Cases with a rolling offset d > 0 and friction: in closed form on one line, else the integrator (ball_laws).

        Fills their rows of ``impulse``, ``diagnostics`` and ``rolling``; returns the cases left to solve.
        """
        missing = sorted(MATERIAL_OPTIONAL - set(inputs))
        if missing:
            raise ModelInputError(
                f"rigid_coulomb with rolling_hysteresis needs the Hertz contact radius, hence the ball's and face's "
                f"elastic constants; missing: {', '.join(missing)} (give ball and face materials)")
        moduli = [inputs[name] for name in ("ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                                            "face_poisson_ratio")]
        modulus = hertz.effective_modulus(*moduli)
        mobility = state["mobility"]
        alpha = ball_laws.hysteresis_fraction(self.options.rolling_hysteresis, restitution,
                                              inputs.get("club_restitution_gain", 0.0))
        arm = ball_laws.mean_rolling_arm(alpha, state["contact_radius"], 1.0 / mobility[:, 2, 2], modulus,
                                         state["normal_speed"])
        # a couple needs friction to roll the ball, or a ball already rolling relative to the face
        coupling, rotation, rates = couple_mobility(state, inputs["ball_mass"], inputs["ball_radius"],
                                                    inputs["ball_inertia_factor"])
        rows = (arm > 0.0) & ((friction > 0.0) | np.any(rates != 0.0, axis=-1))
        # cases on one line take the exact event-driven solution (impactlab.physics.rolling_line), the others the
        # integrator over the normal impulse
        line = rows & rolling_line.on_line(state["initial_velocity"], mobility, coupling, rotation, rates)
        for cases, solve, steps in ((line, rolling_line.rolling_line_impulses, 0),
                                    (rows & ~line, ball_laws.rolling_impulses, 3 * ball_laws.ROLLING_STEPS)):
            if not np.any(cases):
                continue
            solved, moment, flags = solve(state["initial_velocity"][cases], mobility[cases], coupling[cases],
                                          rotation[cases], rates[cases], friction[cases], restitution[cases],
                                          arm[cases])
            impulse[cases] = solved
            diagnostics["steps"][cases] = steps
            diagnostics["validity"][cases] = np.where(flags & 1, 8.0, 0.0)
            rolling["rolling_moment"][cases], rolling["rolling_moment_slip"][cases] = moment[:, 1], moment[:, 0]
        return ~rows
