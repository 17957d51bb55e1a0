"""The bounds of validation.impact.face_bounds: the barrier COR line and the simulated Rules COR test.

Oracles: Chou & Yang's two measured points (0.85 at 20 m/s, 0.78 at 45 m/s); on a rigid face the pair's e of the
model is its restitution input, e_ball + the driver preset's gain 0.083 (the rigid-face form of round 1); the face at
the COR limit was sized (docs/models.md, a model output of benchmarks/measure_face_flex.py) so that the tour ball's
own e 0.787 reads 0.830.
"""

import types
import warnings

import numpy as np
import pytest

from validation.impact import face_bounds as fb


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def test_the_barrier_line_passes_through_the_measured_points():
    assert fb.barrier_cor(20.0) == pytest.approx(0.85)
    assert fb.barrier_cor(45.0) == pytest.approx(0.78)
    # the slope 0.07 / 25 = 0.0028 per m/s, lit33's "e = 0.906 - 0.0028 v"
    assert fb.barrier_cor(0.0) == pytest.approx(0.85 + 20 * 0.0028)
    assert fb.penner(20.0) == pytest.approx(0.802)


def _table(speed, spin_loft_deg):
    n = np.size(speed)
    return types.SimpleNamespace(delivery={"club_speed": np.asarray(speed, float),
                                           "spin_loft": np.radians(np.full(n, spin_loft_deg)),
                                           "dynamic_loft": np.full(n, np.nan), "attack_angle": np.full(n, np.nan)})


def test_e_ball_bounds_are_the_barrier_cor_at_the_rows_normal_speeds():
    # normal speed V cos(60 deg) = V / 2: rows at 40 and 90 m/s strike at 20 and 45 m/s normal
    table = _table(np.r_[np.full(50, 40.0), np.full(50, 90.0)], 60.0)
    low, high, start, _ = fb.e_ball_bounds(table)
    assert (low, high) == (pytest.approx(0.78), pytest.approx(0.85))
    assert low <= start <= high


def test_head_cor_on_a_rigid_face_is_the_ball_e_plus_the_gain():
    for e in (0.70, 0.787):
        assert fb.head_cor(e, {"inelastic": "hysteretic"}) == pytest.approx(e + 0.083, abs=1e-3)


def test_the_face_at_the_cor_limit_reads_the_limit_with_the_ball_it_was_sized_with():
    assert fb.head_cor(0.787) == pytest.approx(0.830, abs=1e-3)
    # a livelier ball gives a livelier pair: round 2's bound 0.747 sits well under the limit
    assert fb.head_cor(0.747) < fb.head_cor(0.787) - 0.02
    assert fb.e_ball_at_limit() == pytest.approx(0.787, abs=2e-3)


def test_no_admissible_e_ball_when_the_head_cor_cap_is_below_the_barrier_range():
    from validation.impact import rate_laws as rl

    table = _table(np.r_[np.full(20, 50.0), np.full(20, 70.0)], 60.0)  # 25 and 35 m/s normal: e 0.836 and 0.808
    bounds, text = fb._bounds(rl, table, cap=0.787)
    assert bounds is None and "empty" in text
    bounds, _ = fb._bounds(rl, table, cap=0.82)
    assert bounds["e_ball"][:2] == (pytest.approx(0.808), pytest.approx(0.82))
