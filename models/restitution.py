"""Coefficient-of-restitution model: normal e and contact-point tangential beta, capped by Coulomb friction."""

from __future__ import annotations

import attrs

from impactlab._validate import in_range, to_float
from impactlab.model import ImpactModel
from impactlab.physics.rigid import restitution_impulses

from ._common import (CLOSED_FORM_DIAGNOSTICS, IMPULSES, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL, RIGID_NOT_PROVIDED,
                      STRONGE, closed_form_diagnostics)


@attrs.frozen
class RestitutionOptions:
    """Options of ``restitution``.

    Parameters
    ----------
    tangential_restitution : float
        Contact-point tangential restitution beta, -1 <= beta <= 1 (-1:
        frictionless, 0: leaves rolling, > 0: the ball grips and the contact
        point reverses). Default 0.
    """

    tangential_restitution: float = attrs.field(
        default=0.0, converter=to_float,
        validator=in_range(-1.0, 1.0, "a tangential restitution with -1 <= beta <= 1"))


class RestitutionModel(ImpactModel):
    """Impact described by two coefficients of restitution, with a Coulomb cap.

    J_n = (1 + e) m* V_z and J_t = (1 + beta) m_t V_x, where beta is the
    option ``tangential_restitution``; if the scene gives a friction
    coefficient, J_t is capped at mu J_n (the ball then slides and leaves
    with a lower beta than asked). With beta = 0 the model equals the rolling
    branch of ``rigid_coulomb``; measured golf impacts grip, beta > 0
    (Cross & Dewhurst 2018 report about 0.1-0.2 for golf).

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
    optional_inputs = RIGID_BODY_OPTIONAL | {"friction"}
    provides = IMPULSES | CLOSED_FORM_DIAGNOSTICS
    not_provided = RIGID_NOT_PROVIDED
    Options = RestitutionOptions

    def _compute(self, inputs, outputs):
        jn, jt, _ = restitution_impulses(tangential_restitution=self.options.tangential_restitution, **inputs)
        return {"normal_impulse": jn, "tangential_impulse": jt, **closed_form_diagnostics(jn.size)}
