"""The row filter of the rate-law validation: each dropped row counted under its reason, the others kept."""

from validation.impact.shots import filtered_lines

HEADER = ("Club,Ball,Club Speed,Attack Angle,Dyn. Loft,Ball Speed,Smash Factor,Launch Angle,Spin Rate,Impact Offset,"
          "Impact Height\n,,[mph],[deg],[deg],[mph],[],[deg],[rpm],[mm],[mm]\n")
ROWS = [
    "Driver,Premium,100,1,12,148,1.48,12,2600,,",          # line 3: kept
    "Driver,Premium,100,1,12,148,1.48,12,,,",              # 4: lacks spin
    "Driver,Premium,100,1,12,148,1.48,12,-2147483648000,,",  # 5: the sentinel (-2.147e12 < -2e10)
    "Driver,Premium,100,1,12,180,1.80,12,2600,,",          # 6: smash factor 1.8
    "Driver,Premium,100,1,12,148,1.48,12,2600,35,0",       # 7: struck off the face
    "Driver,Premium,90,-2,14,130,1.44,13,2900,-5,3",       # 8: kept
]


def test_each_dropped_row_has_its_reason(tmp_path):
    path = tmp_path / "data.csv"
    path.write_text(HEADER + "\n".join(ROWS) + "\n", encoding="utf-8")
    kept, reasons, total = filtered_lines(path)
    assert total == 6
    assert kept == {3, 8}
    assert reasons == {"lacks Spin Rate": 1, "sentinel -2.147e10 in a column": 1, "smash factor outside 1.0-1.6": 1,
                       "impact location off the face (> 30 mm)": 1}
