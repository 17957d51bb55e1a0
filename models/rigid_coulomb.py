"""Rigid-body impact with Coulomb friction: the ball slides throughout or leaves rolling."""

from __future__ import annotations

import attrs

import numpy as np

from impactlab.model import ImpactModel
from impactlab.physics.rigid import STRONGE_STEPS, coulomb_impulses_1d, stronge_impulses

from ._common import (CLOSED_FORM_DIAGNOSTICS, IMPULSES_3D, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL,
                      RIGID_NOT_PROVIDED, STRONGE, closed_form_diagnostics, impulse_outputs)


@attrs.frozen
class RigidCoulombOptions:
    """Options of ``rigid_coulomb`` (friction and restitution come from the scene's contact).

    Parameters
    ----------
    steps : int
        Steps over the normal impulse of the 3-D integration (scenes whose slip may turn); exact where the
        slip keeps its direction, first order in 1/steps where it turns. Default 2000.
    """

    steps: int = attrs.field(default=STRONGE_STEPS, validator=attrs.validators.and_(
        attrs.validators.instance_of(int), attrs.validators.ge(10), attrs.validators.le(10**6)))


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
    provides = IMPULSES_3D | CLOSED_FORM_DIAGNOSTICS
    not_provided = RIGID_NOT_PROVIDED
    Options = RigidCoulombOptions

    def _compute(self, inputs, outputs):
        state = inputs.contact_state()
        n = state["normal_speed"].size
        friction = np.broadcast_to(inputs["friction"], (n,))
        restitution = np.broadcast_to(inputs["restitution"], (n,))
        impulse = np.zeros((n, 3))
        diagnostics = closed_form_diagnostics(n)
        line = state["one_dimensional"]
        if np.any(line):
            w = state["mobility"][line]
            jn, jt, _ = coulomb_impulses_1d(state["normal_speed"][line], state["slip_speed"][line],
                                            1.0 / w[:, 2, 2], 1.0 / w[:, 0, 0], friction[line], restitution[line])
            impulse[line, 0], impulse[line, 2] = -jt, jn
        if not np.all(line):
            solved, flags = stronge_impulses(state["initial_velocity"][~line], state["mobility"][~line],
                                             friction[~line], restitution[~line], self.options.steps)
            impulse[~line] = solved
            diagnostics["steps"][~line] = self.options.steps
            diagnostics["validity"][~line] = np.where(flags & 1, 4.0, 0.0)
        return {**impulse_outputs(impulse), **diagnostics}
