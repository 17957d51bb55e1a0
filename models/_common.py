"""Declarations shared by the built-in models."""

import numpy as np

from impactlab.physics.contact import GEOMETRY_INPUTS
from impactlab.physics.delivery import DELIVERY_INPUTS

RIGID_BODY_INPUTS = frozenset({"ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle"})
#: the club head's body and face, the strike point and the delivery's orientation make the 3-D contact
RIGID_BODY_OPTIONAL = frozenset({"spin", "club_mass"} | set(GEOMETRY_INPUTS) | set(DELIVERY_INPUTS))
IMPULSES = frozenset({"normal_impulse", "tangential_impulse"})
#: the impulse components of a model that solves the 3-D contact
IMPULSES_3D = IMPULSES | {"lateral_impulse"}

RIGID_NOT_PROVIDED = {
    "contact_time": "a rigid-body impulse model has no contact duration",
    "normal_force": "a rigid-body impulse model gives impulses, not force histories",
    "tangential_force": "a rigid-body impulse model gives impulses, not force histories",
    "face_rotation": "a rigid-body impulse model has no contact duration in which the head could turn",
}

STRONGE = "W. J. Stronge, Impact Mechanics, Cambridge University Press (2000), ch. 5"

#: the stability report of a closed-form model: no steps, no energy residual, no flags
CLOSED_FORM_DIAGNOSTICS = frozenset({"steps", "energy_error", "validity"})


def closed_form_diagnostics(size: int) -> dict:
    return {name: np.zeros(size) for name in CLOSED_FORM_DIAGNOSTICS}


def impulse_outputs(impulse) -> dict:
    """The models' impulse outputs from a contact-frame impulse (s, l, n) on the ball (tangential: opposing slip)."""
    return {"normal_impulse": impulse[:, 2], "tangential_impulse": -impulse[:, 0], "lateral_impulse": impulse[:, 1]}
