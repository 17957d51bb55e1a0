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
