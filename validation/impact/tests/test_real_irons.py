"""validation.impact.real_irons: the iron session as the protocol reads it, and its own-floor baselines.

Oracles: the fixture's rows typed from the file (36 shots, 7 with a Smash 2-5 % off Ball / Club, Avg and Dev rows),
and leave-one-out written out by hand on a three-row table (a row's own value never enters its prediction).
"""

import types

import numpy as np
import pytest

from validation.impact import real_irons


def test_the_session_keeps_29_of_36_shots_and_says_why_for_the_others():
    table, report = real_irons.session_table()
    assert table.size == 29
    assert report[0] == "shots read: 36; used: 29"
    assert sum("smash factor" in line for line in report) == 7
    assert sum("summary row" in line for line in report) == 2
    # shot 1 (line 2), typed from the file: 84.8 mph, AOA -6.5, dynamic loft 28.3 deg, 6820 rpm
    assert table.delivery["club_speed"][0] == pytest.approx(84.8 * 0.44704)
    assert np.degrees(table.delivery["dynamic_loft"][0]) == pytest.approx(28.3)
    assert table.measured["spin_rate"][0] * 60 / (2 * np.pi) == pytest.approx(6820)


def test_leave_one_out_baselines_never_use_the_row_they_predict():
    spin = np.array([1.0, 2.0, 9.0])
    table = types.SimpleNamespace(measured={"spin_rate": spin},
                                  delivery={"club_speed": np.ones(3), "spin_loft": np.full(3, np.pi / 2),
                                            "dynamic_loft": np.full(3, np.nan), "attack_angle": np.zeros(3)})
    # medians of the other two rows: (2 + 9) / 2, (1 + 9) / 2, (1 + 2) / 2
    assert real_irons.leave_one_out_constant(table).tolist() == pytest.approx([5.5, 5.0, 1.5])
    # with V sin(spin loft) = 1 on every row, the regression's k is the same median of the others
    assert real_irons.leave_one_out_regression(table).tolist() == pytest.approx([5.5, 5.0, 1.5])
