"""validation.impact.ball_groups: each row's ball setting read from its own file line.

Oracle: a file written here, whose Ball column differs line by line; a table's rows are labelled by their line.
"""

import types

from validation.impact.ball_groups import ball_settings

HEADER = "Club,Ball,Club Speed\n,,[mph]\n"
ROWS = ["Driver,Premium,100", "Driver,Limited Distance Soft,95", "Driver,Medium,105"]  # lines 3, 4, 5


def test_each_row_takes_the_ball_setting_of_its_own_line(tmp_path):
    path = tmp_path / "data.csv"
    path.write_text(HEADER + "\n".join(ROWS) + "\n", encoding="utf-8")
    # rows in another order than the file's, and a line the file does not hold
    table = types.SimpleNamespace(labels=("data.csv line 5", "data.csv line 3", "data.csv line 4", "data.csv line 9"))
    assert ball_settings(table, path).tolist() == ["Medium", "Premium", "Limited Distance Soft", ""]


def test_the_wedge_test_gives_each_ball_its_own_fitted_values():
    # the same values for both balls: no difference (their presets' other data do not move a rolling ball's spin);
    # the ionomer alone at mu_0 = 0.05 slides on the wedge and spins far less, the urethane ball unchanged
    from validation.impact.ball_groups import forms, wedge_ratio

    form = forms()[1]
    values = {"e_ball": 0.78, "friction": 0.32}
    same, spin = wedge_ratio(form, values, values)
    assert abs(same) < 1e-3
    lower, spin_low = wedge_ratio(form, values, {**values, "friction": 0.05})
    assert spin_low["urethane"] == spin["urethane"]
    assert spin_low["ionomer"] < 0.6 * spin["ionomer"] and lower > 0.5
