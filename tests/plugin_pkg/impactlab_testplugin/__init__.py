"""A plugin package written from docs/writing-a-model.md alone, for tests/test_plugin_package.py.

It declares, through its entry points only (entry_points.txt beside it), one of each extension point: a model
with an option (``grip``), a scene field (``tack``, a study's ``plugin:`` block) and a derived output
(``impulse_ratio``). Nothing in impactlab is edited for it.
"""

import attrs
import numpy as np

from impactlab.model import ImpactModel
from impactlab.validators import in_range, to_float


@attrs.frozen
class GripOptions:
    """Options of ``sticky_plugin``.

    Parameters
    ----------
    grip : float
        Tangential restitution beta of the contact point, 0 <= beta <= 1 (0: the ball leaves rolling).
    """

    grip: float = attrs.field(default=0.0, converter=to_float, validator=in_range(0.0, 1.0, "a grip 0 <= beta <= 1"))


class StickyPlugin(ImpactModel):
    """Normal restitution e and a tangential restitution beta = grip + tack, capped by Coulomb friction.

    J_n = (1 + e) V_n / W_nn, J_t = min(mu J_n, (1 + beta) V_s / W_ss) with the contact's mobility W; on one line
    only (no sideways impulse). It reads the geometry through ``inputs.contact_state()`` (takes_contact_state).

    References
    ----------
    R. Cross and P. Dewhurst, Eur. J. Phys. 39 (2018) 065003.
    """

    name = "sticky_plugin"
    label = "restitution e and a plugin's grip"
    references = ("R. Cross and P. Dewhurst, Eur. J. Phys. 39 (2018) 065003",)
    requires = frozenset({"ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle", "friction",
                          "restitution"})
    optional_inputs = frozenset({"spin", "club_mass", "tack"})
    provides = frozenset({"normal_impulse", "tangential_impulse"})
    takes_contact_state = True
    Options = GripOptions

    def _compute(self, inputs, outputs):
        state = inputs.contact_state()
        mobility = state["mobility"]
        jn = (1.0 + inputs["restitution"]) * state["normal_speed"] / mobility[:, 2, 2]
        beta = self.options.grip + inputs.get("tack", 0.0)
        jt = np.minimum(inputs["friction"] * jn, (1.0 + beta) * state["slip_speed"] / mobility[:, 0, 0])
        return {"normal_impulse": jn, "tangential_impulse": jt}


def impulse_ratio(normal_impulse, tangential_impulse):
    """J_t / J_n: the friction coefficient the impact used (mu where the ball slid throughout)."""
    return tangential_impulse / normal_impulse


#: entry point impactlab.outputs: impulse_ratio (plain data: no impactlab import is needed to declare it)
IMPULSE_RATIO = {"units": "1", "long_name": "tangential over normal impulse (the friction the impact used)",
                 "needs": ("normal_impulse", "tangential_impulse"), "function": impulse_ratio}

#: entry point impactlab.inputs: tack, a study's plugin.tack
TACK = {"unit": "1", "dimension": "dimensionless", "description": "extra grip of a tacky cover (adds to beta)",
        "low": 0.0, "high": 0.5}
