"""Declarations shared by the built-in models."""

RIGID_BODY_INPUTS = frozenset({"ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle"})
RIGID_BODY_OPTIONAL = frozenset({"spin", "club_mass"})
IMPULSES = frozenset({"normal_impulse", "tangential_impulse"})

RIGID_NOT_PROVIDED = {
    "contact_time": "a rigid-body impulse model has no contact duration",
    "normal_force": "a rigid-body impulse model gives impulses, not force histories",
    "tangential_force": "a rigid-body impulse model gives impulses, not force histories",
}

STRONGE = "W. J. Stronge, Impact Mechanics, Cambridge University Press (2000), ch. 5"
