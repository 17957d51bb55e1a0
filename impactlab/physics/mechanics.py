"""Rigid-body bookkeeping of a ball struck by a face: effective masses and the incoming slip (1-D helpers).

Frame (the face frame): ``x`` in the face along the incoming slip of the
contact point, ``z`` along the face normal away from the face. The club moves
along the path p = cos(alpha) z - sin(alpha) x relative to the ball, which
starts at rest (it may spin). Impulses are those on the ball: ``J_n`` along
+z, ``J_t`` along -x (positive when it opposes the incoming slip).

References
----------
W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 5.

What the impulses imply about the ball and the head after impact, in 3-D (a contact normal, a free head,
a slip that may turn), is :func:`impactlab.physics.contact.after_impact`.
"""

from __future__ import annotations

import numpy as np

from impactlab.physics import Values


def effective_mass(ball_mass: Values, club_mass: Values) -> Values:
    """Normal effective mass m* = 1 / (1/m + 1/M) [kg] (M = inf: m* = m)."""
    return 1.0 / (1.0 / ball_mass + 1.0 / club_mass)


def tangential_mass(ball_mass: Values, inertia_factor: Values, club_mass: Values) -> Values:
    """Effective mass of the contact point in tangential slip, 1/m_t = (1 + 1/K^2)/m + 1/M [kg]."""
    return 1.0 / ((1.0 + 1.0 / inertia_factor) / ball_mass + 1.0 / club_mass)


def approach_velocities(speed: Values, angle: Values, spin: Values, radius: Values) -> tuple[Values, Values]:
    """Normal approach speed V_z = V cos(alpha) and contact-point slip V_x = V sin(alpha) - R omega0 [m/s]."""
    return speed * np.cos(angle), speed * np.sin(angle) - radius * spin


#: what :func:`impactlab.physics.contact.after_impact` needs besides the impulses (model input names)
AFTER_IMPACT_INPUTS = ("ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle", "spin")


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["effective_mass", "tangential_mass", "approach_velocities", "AFTER_IMPACT_INPUTS"]
