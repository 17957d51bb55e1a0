"""validation.impact.goal_limits: the rigid-body closed forms, the exponent window and the file's neighbourhoods.

Oracles: the package's rigid_coulomb model on a sphere striking a free, translating face (an independent code path:
its impulses, whatever frame it reports speeds in, are the closed forms' m v), hand values of the textbook limits
(a head-on impact of a ball on an immovable face leaves at (1 + e) V; the rolling friction of a fixed face is
K tan(a) / ((1 + K)(1 + e))), and synthetic rows built to sit at the window's edges.
"""

import math
import types

import numpy as np
import pytest

from impactlab.data.validation.benchmarks import Sphere, plate_inputs
from impactlab.model.registry import get_model
from validation.impact import goal_limits as gl

BALL_MASS, RADIUS, HEAD = 0.04593, 0.021335, 0.204
GOLF = Sphere("golf-sized", RADIUS, BALL_MASS / (4.0 / 3.0 * math.pi * RADIUS**3), 6.0e7, 0.45, "test")


def _rigid(angle, friction, restitution=0.83, head=HEAD, speed=50.0):
    inputs = plate_inputs(GOLF, speed=speed, angle=angle, friction=friction, restitution=restitution,
                          face_mass=head)
    ds = get_model("rigid_coulomb")().compute(inputs, ["normal_impulse", "tangential_impulse"])
    return np.asarray(ds.normal_impulse.values, float), np.asarray(ds.tangential_impulse.values, float)


def test_the_speed_ratio_is_the_rigid_models_impulse_over_m_v_when_the_ball_rolls():
    angles = np.radians([0.0, 8.0, 13.7, 25.0, 38.0])
    normal, tangential = _rigid(angles, friction=5.0)  # ample friction: the ball leaves rolling
    expected = gl.free_head_speed_ratio(angles, 0.83, BALL_MASS, HEAD)
    np.testing.assert_allclose(np.hypot(normal, tangential) / (BALL_MASS * 50.0), expected, rtol=1e-9)


def test_the_speed_ratio_at_its_textbook_limits():
    # head-on, immovable face: (1 + e); head-on, free head: (1 + e) / (1 + m / M); and it grows with the head mass
    assert gl.free_head_speed_ratio(0.0, 0.83, BALL_MASS, 1e12) == pytest.approx(1.83, rel=1e-9)
    assert gl.free_head_speed_ratio(0.0, 0.83, BALL_MASS, HEAD) == pytest.approx(1.83 / (1 + BALL_MASS / HEAD))
    lofted = gl.free_head_speed_ratio(math.radians(13.7), 0.83, BALL_MASS, np.array([0.19, 0.204, 0.23]))
    assert np.all(np.diff(lofted) > 0)
    assert lofted[1] < 1.83 / (1 + BALL_MASS / HEAD)  # loft only takes speed away


def test_head_mass_for_inverts_the_speed_ratio_and_says_when_no_mass_is_enough():
    loft = math.radians(13.7)
    for mass in (0.15, 0.204, 0.3):
        ratio = float(gl.free_head_speed_ratio(loft, 0.83, BALL_MASS, mass))
        assert gl.head_mass_for(ratio, loft, 0.83, BALL_MASS) == pytest.approx(mass, rel=1e-8)
    assert gl.head_mass_for(1.9, loft, 0.83, BALL_MASS) == math.inf  # beyond (1 + e) at any mass


def test_the_rolling_friction_separates_sliding_from_rolling_in_the_rigid_model():
    angle, e = math.radians(38.0), 0.787
    mu_c = float(gl.rolling_friction(angle, e, BALL_MASS, 0.303))
    normal, rolling = _rigid(angle, friction=4 * mu_c, restitution=e, head=0.303)
    _, half = _rigid(angle, friction=0.5 * mu_c, restitution=e, head=0.303)
    _, above = _rigid(angle, friction=1.001 * mu_c, restitution=e, head=0.303)
    _, below = _rigid(angle, friction=0.999 * mu_c, restitution=e, head=0.303)
    assert rolling[0] == pytest.approx(mu_c * normal[0], rel=1e-9)  # the rolling impulse is mu_c J_n
    assert half[0] == pytest.approx(0.5 * rolling[0], rel=1e-9)  # sliding: proportional to mu
    assert above[0] == pytest.approx(rolling[0], rel=1e-9)
    assert below[0] == pytest.approx(0.999 * rolling[0], rel=1e-9)


def test_the_rolling_friction_of_a_fixed_face_is_the_textbook_value():
    angle, e, k = math.radians(30.0), 0.8, 0.4
    assert gl.rolling_friction(angle, e, BALL_MASS, 1e15, k) == pytest.approx(
        k * math.tan(angle) / ((1 + k) * (1 + e)), rel=1e-9)


def test_the_exponent_window_puts_two_rows_at_plus_and_minus_the_tolerance_at_its_edges():
    speed_ratio, loft_ratio, spin_ratio, c = 1.2, 1.08, 1.02, 0.6
    k_min, k_max = gl.exponent_window(speed_ratio, loft_ratio, spin_ratio, c)
    assert k_min < k_max
    for k, sign in ((k_max, 1), (k_min, -1)):
        predicted = speed_ratio**k * loft_ratio**c  # the law's ratio of the two rows
        # with the level chosen between them, the first row lies +t and the second -t (or the reverse)
        first, second = 1 + sign * 0.07, 1 - sign * 0.07
        assert predicted / spin_ratio == pytest.approx(first / second, rel=1e-12)
    inside = 0.5 * (k_min + k_max)
    ratio = speed_ratio**inside * loft_ratio**c / spin_ratio
    assert 0.93 / 1.07 < ratio < 1.07 / 0.93


def test_neighbours_take_the_rows_within_each_half_width():
    mph = 0.44704
    speed = np.array([115, 119.5, 110.5, 115, 115, 115]) * mph  # row 1 and 2: 4.5 mph off
    loft = np.radians([12.8, 12.8, 12.8, 14.5, 12.8, 12.8])  # row 3: spin loft 1.7 deg off
    attack = np.radians([-0.9, -0.9, -0.9, -0.9, 2.5, -3.8])  # row 4: attack 3.4 deg off; row 5: 2.9
    table = types.SimpleNamespace(delivery={"club_speed": speed, "dynamic_loft": loft + attack,
                                            "attack_angle": attack, "spin_loft": np.full(6, np.nan)})
    mask = gl.neighbours(table, {"club_speed": 115.0, "spin_loft": 12.8, "attack_angle": -0.9})
    assert mask.tolist() == [True, False, False, False, False, True]


def test_the_tracked_fraction_is_each_lines_last_tracked_time_over_its_hang_time(tmp_path):
    path = tmp_path / "data.csv"
    path.write_text("Club,Last data Point - Time,Carry Flat - Time\n,[s],[s]\n"
                    "Driver,6.0,6.0\nDriver,0.3,6.0\nDriver,,5.0\nDriver,-,5.0\n", encoding="utf-8")  # lines 3-6
    table = types.SimpleNamespace(labels=("data.csv line 4", "data.csv line 3", "data.csv line 5", "data.csv line 6",
                                          "data.csv line 9"))
    fraction = gl.tracked_fraction(table, path)
    assert fraction[:2] == pytest.approx([0.05, 1.0])
    assert np.all(np.isnan(fraction[2:]))  # a blank cell, a dash, a line the file does not hold


def test_the_allowed_restitution_rises_only_below_the_cor_tests_speed():
    slope = (0.78 - 0.85) / (45.0 - 20.0)  # Chou & Yang: e falls with speed
    e = gl.allowed_restitution(np.array([30.0, 48.8, 60.0]), 0.83, slope)
    assert e[0] == pytest.approx(0.83 + 0.0028 * 18.8)  # slower than the test: more lively
    assert e[1] == e[2] == pytest.approx(0.83)  # at and above the test's speed: the limit itself


def test_head_mass_for_passes_the_balls_inertia_factor_on():
    loft, k = math.radians(30.0), 0.3  # a large loft, where the tangential share matters
    ratio = float(gl.free_head_speed_ratio(loft, 0.8, BALL_MASS, 0.25, k))
    assert gl.head_mass_for(ratio, loft, 0.8, BALL_MASS, k) == pytest.approx(0.25, rel=1e-8)


def test_the_spin_loft_of_a_delivery_is_its_dynamic_loft_less_its_attack():
    assert gl.spin_loft_of({"dynamic_loft": math.radians(34.0), "attack_angle": math.radians(-4.0)}) == \
        pytest.approx(math.radians(38.0))


def test_the_oracle_error_ignores_the_level_and_keeps_the_shape():
    measured = np.array([100.0, 200.0, 300.0, 400.0, 500.0])
    shaped = measured * np.array([1.1, 0.9, 1.0, 1.2, 0.8])  # errors of +-10 and +-20 % around the right level
    assert gl.oracle_error(shaped, measured) == pytest.approx(gl.oracle_error(3.0 * shaped, measured))
    assert gl.oracle_error(measured * 0.5, measured) == pytest.approx(0.0, abs=1e-12)  # a pure level error vanishes
    assert gl.median_error(measured * 0.5, measured) == pytest.approx(50.0)


def test_session_blocks_start_at_each_jump_of_more_than_the_gap():
    assert gl.session_blocks([3, 4, 50, 151, 152, 400]).tolist() == [0, 0, 0, 1, 1, 2]  # 50 -> 151: 101 lines


def test_the_block_bootstrap_resamples_whole_blocks():
    values = np.array([1.0, 1.0, 1.0, 5.0, 5.0, 5.0])
    # two blocks of equal values: every resample is 0, 1 or 2 copies of each block, its median 1, 3 or 5
    median, low, high = gl.median_interval(values, blocks=[0, 0, 0, 1, 1, 1], draws=400)
    assert median == 3.0 and low == 1.0 and high == 5.0
    median, low, high = gl.median_interval(values, blocks=[0] * 6, draws=50)  # one block: no spread at all
    assert low == high == median == 3.0
    _, low, high = gl.median_interval(np.arange(1000.0), draws=400)  # independent rows: a narrow 95 % interval
    assert 440 < low < 499.5 < high < 560


def test_neighbours_include_the_edges_of_each_half_width():
    mph = 0.44704
    speed = np.array([119.0, 111.0]) * mph  # exactly 4 mph off either way
    attack = np.radians([2.1, -3.9])  # exactly 3 deg off
    loft = np.radians([14.3, 11.3])  # spin loft exactly 1.5 deg off
    table = types.SimpleNamespace(delivery={"club_speed": speed, "dynamic_loft": loft + attack,
                                            "attack_angle": attack, "spin_loft": np.full(2, np.nan)})
    mask = gl.neighbours(table, {"club_speed": 115.0, "spin_loft": 12.8, "attack_angle": -0.9})
    assert mask.tolist() == [True, True]


def test_the_balls_cor_slope_is_chou_and_yangs_fall_with_speed():
    assert gl.ball_cor_slope() == pytest.approx((0.78 - 0.85) / 25.0)


def test_the_instantaneous_slip_law_matches_a_step_by_step_integration():
    # an oracle written independently: march the normal impulse in small steps, friction mu_0 u / u_ref each step,
    # the slip reduced by dJ_t / m_t (a sphere on a translating face), against the closed form's exponential
    angle, e, head, speed, k = math.radians(38.0), 0.787, 0.303, 29.0, 0.4
    m_n = 1.0 / (1.0 / BALL_MASS + 1.0 / head)
    m_t = 1.0 / (1.0 / BALL_MASS + 1.0 / head + 1.0 / (k * BALL_MASS))
    total = (1.0 + e) * m_n * speed * math.cos(angle)
    for mu in (0.02, 0.1, 0.35):
        slip, tangential, steps = speed * math.sin(angle), 0.0, 200_000
        for _ in range(steps):
            d = mu * slip / 10.0 * total / steps
            tangential += d
            slip -= d / m_t
        rolling = m_t * speed * math.sin(angle)
        assert gl.instantaneous_slip_fraction(mu, angle, e, BALL_MASS, head, speed, k) == pytest.approx(
            tangential / rolling, rel=1e-4)
    assert gl.instantaneous_slip_fraction(50.0, angle, e, BALL_MASS, head, speed) == pytest.approx(1.0)  # rolls
