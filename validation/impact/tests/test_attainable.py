"""validation.impact.attainable: the in-band folds, the power law and the repeatability pairs.

Oracles: synthetic tables whose spin is an exact power law (the fit must return its exponents and predict it
exactly), folds checked by counting, and pairs built by hand.
"""

import types

import numpy as np
import pytest

from validation.impact import attainable as at


def test_contiguous_folds_partition_the_rows_in_order():
    seen = []
    for train, test in at.contiguous_folds(23, 5):
        assert np.all(np.diff(test) == 1)  # one contiguous block
        assert set(train) | set(test) == set(range(23)) and not set(train) & set(test)
        seen.extend(test.tolist())
    assert seen == list(range(23))


def _table(speed, loft, spin, strike=None):
    n = len(speed)
    strike = np.full((n, 2), np.nan) if strike is None else np.asarray(strike, float)
    table = types.SimpleNamespace(
        delivery={"club_speed": np.asarray(speed, float), "spin_loft": np.asarray(loft, float),
                  "dynamic_loft": np.full(n, np.nan), "attack_angle": np.full(n, np.nan),
                  "strike_toe": strike[:, 0], "strike_high": strike[:, 1]},
        measured={"spin_rate": np.asarray(spin, float)}, size=n)
    table.subset = lambda rows: _table(np.asarray(speed)[rows], np.asarray(loft)[rows], np.asarray(spin)[rows],
                                       strike[rows])
    return table


def test_the_power_law_recovers_its_exponents_and_predicts_exactly():
    rng = np.random.default_rng(0)
    speed = rng.uniform(30.0, 55.0, 200)
    loft = np.radians(rng.uniform(8.0, 20.0, 200))
    spin = 12.0 * speed**0.6 * np.sin(loft) ** 0.8
    table = _table(speed, loft, spin)
    predicted, b, c = at.power_law(table.subset(np.arange(150)), table.subset(np.arange(150, 200)))
    assert (b, c) == (pytest.approx(0.6), pytest.approx(0.8))
    assert predicted == pytest.approx(spin[150:], rel=1e-9)


def test_repeatability_counts_only_near_identical_consecutive_deliveries():
    speed = [40.0, 40.2, 46.0, 46.1, 46.2]  # pairs (0,1), (2,3), (3,4) are within 2 %; (1,2) is not
    loft = np.radians([12.0, 12.5, 12.0, 14.0, 14.2])  # (2,3) differs by 2 deg: out
    spin = [300.0, 330.0, 300.0, 310.0, 341.0]
    strike = [[0, 0], [0, 0.001], [0, 0], [0, 0], [0.0, 0.02]]  # (3,4) struck 20 mm apart: out
    pair, count = at.repeatability(_table(speed, loft, spin, strike), np.ones(5, bool))
    assert count == 1
    assert pair == pytest.approx(10.0)  # 330 / 300
