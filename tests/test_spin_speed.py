"""Spin against club speed at a fixed delivery (docs/validation.md, "Driver spin against club speed: what controlled
data say"; benchmarks/measure_spin_speed.py).

Oracles, written apart from the code: dimensional analysis of the impact (a Hertz-Mindlin or linear-spring contact
with Coulomb friction and a constant coefficient of restitution has no speed scale, so every impulse, hence the spin,
is proportional to the approach speed at a fixed geometry: Maw, Barber & Fawcett, Wear 38 (1976) 101, whose outcome
depends on the incidence angle and the material ratios only); Hertz's contact radius a ~ v^(2/5) (Johnson, Contact
Mechanics, 1985, ch. 11), which makes the rolling couple d J_n, d = (3/16) alpha a, grow as v^(7/5); and a linear
restitution law evaluated by hand at the normal approach speed v cos(spin loft) of a centred, square strike.
"""

import numpy as np
import pytest

from impactlab.data.shot_report import shot_table
from impactlab.data.sessions.shots import predict, table_inputs
from impactlab.model.registry import get_model
from impactlab.scene.catalogue import CLUB_PRESETS
from impactlab.scene.core import Contact, Delivery, Scene, Strike, complete_inputs
from impactlab.scene.materials import BALL_PRESETS

MPH = 0.44704
SPEEDS = np.array([70.0, 95.0, 130.0]) * MPH


def driver_cases(toe=0.0, high=0.0):
    """The PGA driver row's attack angle and dynamic loft at three club speeds, constant e and friction."""
    club = CLUB_PRESETS["driver"]
    scenes = [Scene.from_delivery(BALL_PRESETS["urethane_tour"], Scene.face_of(club), Contact(0.4, 0.8),
                                  Delivery(v, attack_angle=np.radians(-0.9), dynamic_loft=np.radians(12.8)), 0.0,
                                  club, Strike(toe, high)) for v in SPEEDS]
    keys = set.intersection(*(set(scene.inputs()) for scene in scenes))
    return complete_inputs({key: np.array([scene.inputs()[key] for scene in scenes]) for key in sorted(keys)})


@pytest.mark.parametrize("name", ["rigid_coulomb", "restitution", "hertz_mindlin", "maw", "dem_linear"])
@pytest.mark.parametrize("strike", [(0.0, 0.0), (0.012, -0.006)])
def test_spin_is_proportional_to_club_speed_without_a_speed_dependent_law(name, strike):
    spin = np.asarray(predict(get_model(name)(), driver_cases(*strike))["spin_rate"])
    per_speed = spin / SPEEDS
    assert np.all(spin > 0.0)
    np.testing.assert_allclose(per_speed, per_speed[0], rtol=1e-6)


def test_the_rolling_couple_grows_as_the_speed_to_the_seven_fifths():
    inputs = driver_cases()
    free = np.asarray(predict(get_model("rigid_coulomb")(), inputs)["spin_rate"])
    rolling = np.asarray(predict(get_model("rigid_coulomb")(rolling_hysteresis=0.3), inputs)["spin_rate"])
    deficit = (free - rolling) / SPEEDS**1.4
    assert np.all(free - rolling > 0.0)
    np.testing.assert_allclose(deficit, deficit[0], rtol=1e-3)
    # so the spin's exponent between 96 and 115 mph stays far above the tours' apparent 0.19
    exponent = np.log(rolling[2] / rolling[1]) / np.log(SPEEDS[2] / SPEEDS[1])
    assert 0.7 < exponent < 1.0


def test_a_falling_restitution_law_is_read_at_each_rows_normal_speed():
    table = shot_table("trackman_tour")
    slope = -0.004  # s/m
    ball = {"preset": "urethane_tour", "restitution": {"law": "linear", "value": 0.787,
                                                         "reference_speed": "40 m/s", "slope": f"{slope} s/m"}}
    inputs = table_inputs(table, ball)
    e_ball = inputs["restitution"] - inputs.get("club_restitution_gain", 0.0)
    d = table.delivery
    normal = d["club_speed"] * np.cos(d["dynamic_loft"] - d["attack_angle"])  # centred, square: by hand
    np.testing.assert_allclose(e_ball, 0.787 + slope * (normal - 40.0), atol=1e-9)
    # the PGA driver (about 50 m/s along the normal) is struck harder than the LPGA driver (about 41 m/s)
    pga, lpga = table.labels.index("PGA driver"), table.labels.index("LPGA driver")
    assert e_ball[pga] < e_ball[lpga] < 0.787
