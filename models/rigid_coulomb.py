"""Rigid-body impact with Coulomb friction: the ball slides throughout or leaves rolling."""

from __future__ import annotations

import attrs

from impactlab.model import ImpactModel
from impactlab.physics.rigid import coulomb_impulses

from ._common import (CLOSED_FORM_DIAGNOSTICS, IMPULSES, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL, RIGID_NOT_PROVIDED,
                      STRONGE, closed_form_diagnostics)


@attrs.frozen
class RigidCoulombOptions:
    """``rigid_coulomb`` takes no options: friction and restitution come from the scene's contact."""


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
    optional_inputs = RIGID_BODY_OPTIONAL
    provides = IMPULSES | CLOSED_FORM_DIAGNOSTICS
    not_provided = RIGID_NOT_PROVIDED
    Options = RigidCoulombOptions

    def _compute(self, inputs, outputs):
        jn, jt, _ = coulomb_impulses(**inputs)
        return {"normal_impulse": jn, "tangential_impulse": jt, **closed_form_diagnostics(jn.size)}
