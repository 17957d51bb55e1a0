"""Outputs the framework derives from a model's impulses (rule 6 of the model contract).

Two families: the face-frame and ground-frame results of any impact
(:func:`impactlab.physics.mechanics.after_impact`), and, when the scene is a
golf delivery, the 3-D launch (:func:`impactlab.physics.delivery.launch`).
"""

from __future__ import annotations

from .physics.delivery import DELIVERY_INPUTS, launch
from .physics.mechanics import AFTER_IMPACT_INPUTS, AFTER_IMPACT_OPTIONAL, after_impact

IMPULSES = frozenset({"normal_impulse", "tangential_impulse"})
FROM_IMPULSES = frozenset({
    "launch_angle", "launch_ratio", "rebound_angle", "total_angle", "ball_speed", "spin_rate", "normal_velocity",
    "tangential_velocity", "tangential_restitution", "energy_loss",
})
FROM_DELIVERY = frozenset({
    "spin_loft", "vertical_launch_angle", "horizontal_launch_angle", "vertical_launch_ratio",
    "horizontal_launch_ratio", "spin_axis",
})
#: inputs each family needs (the optional ones default: no spin, a fixed face)
NEEDS = {
    "impulses": frozenset(AFTER_IMPACT_INPUTS) - {"spin"},
    "delivery": frozenset(DELIVERY_INPUTS),
}
NO_DELIVERY = "needs a golf delivery (a delivery block: path, face angle, attack angle, dynamic loft)"


def derivable(name: str, provides, given_inputs=None) -> tuple[bool, str | None]:
    """Whether ``name`` can be derived for a model that provides ``provides``; if not, why (None: not derivable)."""
    if not IMPULSES <= set(provides) or name not in FROM_IMPULSES | FROM_DELIVERY:
        return False, None
    if name in FROM_DELIVERY and given_inputs is not None and not NEEDS["delivery"] <= set(given_inputs):
        return False, NO_DELIVERY
    return True, None


def derive(names, raw, inputs) -> dict:
    """Compute the derived outputs ``names`` from the impulses in ``raw`` and the case ``inputs`` (SI)."""
    names = set(names)
    out = {}
    if not names:
        return out
    basics = after_impact(raw["normal_impulse"], raw["tangential_impulse"],
                          **{name: inputs[name] for name in AFTER_IMPACT_INPUTS + AFTER_IMPACT_OPTIONAL})
    out.update({name: basics[name] for name in names & FROM_IMPULSES})
    if names & FROM_DELIVERY:
        golf = launch(raw["normal_impulse"], raw["tangential_impulse"], basics["spin_rate"],
                      ball_mass=inputs["ball_mass"], **{name: inputs[name] for name in DELIVERY_INPUTS})
        out.update({name: golf[name] for name in names & FROM_DELIVERY})
    return out
