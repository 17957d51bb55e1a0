"""Coefficient-of-restitution model: normal e and contact-point tangential beta, capped by Coulomb friction."""

from __future__ import annotations

import attrs

from impactlab.validators import in_range, to_float
import numpy as np

from impactlab.model import ImpactModel
from impactlab.physics.rigid import restitution_impulses

from .shared import (CLOSED_FORM_DIAGNOSTICS, FRICTION_INPUTS, FRICTION_LAW, IMPULSES_3D, MATERIAL_OPTIONAL,
                      PLAIN_BALL, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL, RIGID_NOT_PROVIDED, STRONGE,
                      closed_form_diagnostics, impulse_outputs, law_friction, pressure_exponent_field,
                      slip_exponent_field, rate_law_state,
                      reference_speed_field, relaxation_time_field, relaxed_fraction_field)


@attrs.frozen
class RestitutionOptions:
    """Options of ``restitution``.

    Parameters
    ----------
    tangential_restitution : float
        Contact-point tangential restitution beta, -1 <= beta <= 1 (-1:
        frictionless, 0: leaves rolling, > 0: the ball grips and the contact
        point reverses). Default 0.
    friction_law : str
        The Coulomb cap's coefficient: ``"coulomb"`` (default), the ``friction`` input (none given: no cap);
        ``"adhesion"``: :mod:`impactlab.physics.friction_laws` (shared.FRICTION_LAW_DOC).
    relaxation_time, relaxed_fraction, relaxation_reference_speed, friction_pressure_exponent, friction_slip_exponent
        The SLS normal law and the pressure- and slip-speed-dependent friction cap of :mod:`impactlab.physics.rate_laws`
        (shared.RATE_LAWS_DOC), each off by default; they read the ball's and face's elastic constants. (The
        lever has no place here: this model has no rolling couple, beta sets the tangential exit.)
    """

    tangential_restitution: float = attrs.field(
        default=0.0, converter=to_float,
        validator=in_range(-1.0, 1.0, "a tangential restitution with -1 <= beta <= 1"))
    friction_law: str = attrs.field(default="coulomb", validator=FRICTION_LAW)
    relaxation_time: float = relaxation_time_field("relaxation_time", 0.01)
    relaxed_fraction: float = relaxed_fraction_field()
    relaxation_reference_speed: float = reference_speed_field()
    friction_pressure_exponent: float = pressure_exponent_field()
    friction_slip_exponent: float = slip_exponent_field()


class RestitutionModel(ImpactModel):
    """Impact described by two coefficients of restitution, with a Coulomb cap.

    J_n = (1 + e) m* V_z and J_t = (1 + beta) m_t V_x, where beta is the
    option ``tangential_restitution``; if the scene gives a friction
    coefficient, J_t is capped at mu J_n (the ball then slides and leaves
    with a lower beta than asked). With beta = 0 the model equals the rolling
    branch of ``rigid_coulomb``; measured golf impacts grip, beta > 0
    (Cross & Dewhurst 2018 report about 0.1-0.2 for golf).

    In 3-D (a free head struck off its centre-of-mass line, a curved face)
    the coefficients act on the relative velocity of the contact point with
    the full mobility matrix W: W J = v1 - v0 with v1 = (-beta V_s, 0, e V_n)
    in the contact frame (slip reversed and scaled by beta, no lateral slip,
    normal velocity reversed and scaled by e); a tangential impulse outside
    the Coulomb cone is put on the cone in its direction, with the normal
    impulse that keeps e. Kinematic coefficients with a coupled W can ask for
    an impulse that creates kinetic energy (0.2 J at e = 1 on a driver struck
    30 mm off centre); such an impulse is capped: scaled down along its own
    direction to the largest that creates none
    (:func:`impactlab.physics.rigid.energy_cap`; the 1-D cases never need it).
    The cap is reported as validity flag 32 (``energy_capped``).

    References
    ----------
    R. Cross and P. Dewhurst, Eur. J. Phys. 39 (2018) 065003.
    R. Cross, Am. J. Phys. 70 (2002) 1093-1102.
    """

    name = "restitution"
    label = "restitution coefficients e and beta"
    references = ("R. Cross and P. Dewhurst, Launch speed, angle and spin in golf, Eur. J. Phys. 39 (2018) 065003",
                  "R. Cross, Grip-slip behavior of a bouncing ball, Am. J. Phys. 70 (2002) 1093", STRONGE)
    requires = RIGID_BODY_INPUTS | {"restitution"}
    optional_inputs = RIGID_BODY_OPTIONAL | {"friction", "club_restitution_gain"} | MATERIAL_OPTIONAL | FRICTION_INPUTS
    provides = IMPULSES_3D | CLOSED_FORM_DIAGNOSTICS
    not_provided = RIGID_NOT_PROVIDED
    Options = RestitutionOptions
    ball_law_options = {name: PLAIN_BALL[name] for name in ("friction_law", "relaxation_time",
                                                            "friction_pressure_exponent", "friction_slip_exponent")}

    def _compute(self, inputs, outputs):
        state = inputs.contact_state()
        cap = (inputs.get("friction", np.inf) if self.options.friction_law == "coulomb"
               else law_friction(self.options, inputs, state, inputs["restitution"]))
        # the laws with a scale (rate_laws; RATE_LAWS_DOC): each off returns its input (today's model exactly)
        restitution, cap, _ = rate_law_state(self.options, inputs, state, inputs["restitution"], cap)
        impulse, _, energy_capped = restitution_impulses(
            state["initial_velocity"], state["mobility"], restitution, self.options.tangential_restitution, cap)
        diagnostics = closed_form_diagnostics(impulse.shape[0])
        diagnostics["validity"] = np.where(energy_capped, 32.0, 0.0)
        return {**impulse_outputs(impulse), **diagnostics}
