"""Declarations shared by the built-in models."""

import numpy as np

RIGID_BODY_INPUTS = frozenset({"ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle"})
RIGID_BODY_OPTIONAL = frozenset({"spin", "club_mass"})
IMPULSES = frozenset({"normal_impulse", "tangential_impulse"})

RIGID_NOT_PROVIDED = {
    "contact_time": "a rigid-body impulse model has no contact duration",
    "normal_force": "a rigid-body impulse model gives impulses, not force histories",
    "tangential_force": "a rigid-body impulse model gives impulses, not force histories",
}

STRONGE = "W. J. Stronge, Impact Mechanics, Cambridge University Press (2000), ch. 5"

#: the stability report of a closed-form model: no steps, no energy residual, no flags
CLOSED_FORM_DIAGNOSTICS = frozenset({"steps", "energy_error", "validity"})


def closed_form_diagnostics(size: int) -> dict:
    return {name: np.zeros(size) for name in CLOSED_FORM_DIAGNOSTICS}
