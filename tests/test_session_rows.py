"""A session's bad rows are skipped with their reason, never sinking the file (issue 32, item 1; issue 35, items 4, 5
and 7): no-value markers of every layout read as missing, the row rules in every command, consistency checks an
export allows, encodings named as they are. Oracles: values typed here and the layouts' own YAML, not the reader."""

from __future__ import annotations

import math

import numpy as np
import pytest

from impactlab.cli import main
from impactlab.data.sessions.layouts import FIELDS, GENERIC, vendor_maps
from impactlab.data.sessions.reader import read_session, read_session_text
from impactlab.errors import FieldError, StudyError

MPH, DEG, RPM, YD = 0.44704, math.pi / 180, math.pi / 30, 0.9144
#: a plausible driver shot per field [SI] (its smash factor 1.45 = ball / club speed), and a unit per dimension
TYPICAL = {"club_speed": 46.0, "ball_speed": 66.7, "smash_factor": 1.45, "spin_rate": 280.0, "back_spin": 275.0,
           "side_spin": 20.0, "spin_axis": 0.07, "total_distance": 240.0, "carry_distance": 225.0, "flight_time": 6.5,
           "tracked_time": 6.4, "apex_height": 30.0, "landing_angle": 0.7, "dynamic_loft": 0.22,
           "vertical_launch_angle": 0.2, "landing_ball_speed": 30.0, "relative_humidity": 0.5,
           "air_temperature": 293.0, "air_pressure": 101000.0, "air_density": 1.2, "altitude": 100.0}
UNITS = {"speed": "mph", "angle": "deg", "angular_speed": "rpm", "length": "yd", "time": "s", "dimensionless": "",
         "temperature": "degC", "pressure": "kPa", "density": "kg/m^3"}


def _layout_table(layout) -> tuple[str, list[str], str]:
    """A CSV head (header, and units row where the layout has one) of ``layout``'s own numeric columns (its
    recognising names included), a row of one plausible driver shot in those units, and the ball speed's column
    (or the first numeric one)."""
    from impactlab.data.sessions.layouts import _unit_factor

    names, fields = [], []
    for name in dict.fromkeys([*layout.recognise, *layout.columns]):  # one column per field, recognising first
        rule = layout.rule(name)
        field = rule.field if rule is not None and rule.field in FIELDS and " [" not in name else None
        if name in layout.recognise or (field is not None and field not in fields):
            names.append(name)
            fields.append(field)
    unit = {name: (layout.implied_units.get(name) or UNITS[FIELDS[field]]) if field else ""
            for name, field in zip(names, fields)}
    row = []
    for name, field in zip(names, fields):
        if field is None:  # a text column: a name, a club, a hand
            rule = layout.rule(name)
            row.append({"club": "Driver", "handedness": "R"}.get(rule.field if rule else "", "1"))
            continue
        scale, offset = _unit_factor(unit[name], FIELDS[field], name)
        row.append(f"{(TYPICAL.get(field, 0.05) - offset) / scale:.6g}")
    in_header = {name for name in names if unit[name] and (layout.units == "header" or (
        layout.units == "implied" and name not in layout.implied_units))}
    header = [f"{name} [{unit[name]}]" if name in in_header else name for name in names]
    if layout.required:  # a value each row must hold (GSPro's Units: Yards)
        header.append(layout.required["column"])
        row.append(str(layout.required["values"][0]))
        fields.append(None)
        names.append(layout.required["column"])
    lines = [",".join(header)]
    if layout.units == "row":
        lines.append(",".join((unit[name] if layout.units_row_plain else f"[{unit[name]}]") if field and unit[name]
                              else "" for name, field in zip(names, fields)))
    target = next(name for name, field in zip(header, fields) if field == "ball_speed") if "ball_speed" in fields \
        else next(name for name, field in zip(header, fields) if field)
    return "\n".join(lines), row, target


def _sentinels(layout) -> list[str]:
    """Every no-value marker the layout declares, as a cell would hold it."""
    cells = [text for text in layout.missing if text]
    cells += [f"{rule['value']:.10g}" for rule in layout.sentinels]
    cells += [f"{rule['value'] * 10:.6g}" for rule in layout.sentinels if rule["scaled"]]  # TrackMan's -2.14748e+10
    if layout.sentinel_at_least is not None:
        cells.append(f"{layout.sentinel_at_least:.10g}")
    return cells


@pytest.mark.parametrize("vendor", sorted(vendor_maps()))
def test_every_no_value_marker_of_every_layout_is_read_as_missing_and_flagged(vendor):
    layout = vendor_maps()[vendor]
    head, row, target = _layout_table(layout)
    column = head.splitlines()[0].split(",").index(target)
    for marker in _sentinels(layout) + [""]:  # the empty cell: missing in every layout, flagged in none
        hit = list(row)
        hit[column] = f'"{marker}"' if "," in marker else marker
        session = read_session_text("\n".join([head, ",".join(row), ",".join(hit)]) + "\n", f"{vendor}.csv", vendor)
        field = layout.rule(target).field if layout.rule(target) else "ball_speed"
        assert np.isfinite(session.values[field][0]), (vendor, marker)
        assert np.isnan(session.values[field][1]), (vendor, marker)
        if marker:
            assert session.flags[(field, "no data")].tolist() == [False, True], (vendor, marker)
        assert session.bad_rows() == []  # a marker is a missing value, not a bad row


def test_the_older_trackman_layout_declares_its_minus_two_to_the_31_as_data():
    layout = vendor_maps()["trackman_tps_legacy"]
    assert [rule["value"] for rule in layout.sentinels] == [-2.0 ** 31] and layout.sentinels[0]["scaled"]
    assert set(layout.missing) >= {"", "-", "NaN", "N/A"}


HEADER = ("Club,Club Speed [mph],Attack Angle [deg],Dyn. Loft [deg],Club Path [deg],Face Angle [deg],"
          "Ball Speed [mph],Launch Angle [deg],Spin Rate [rpm],Impact Height [mm]\n")
GOOD = "Driver,110,2,12,0,0,160,12,2500,3\n"


def test_each_row_rule_skips_its_row_with_a_reason_and_the_others_are_used():
    rows = {
        3: "Driver,110,2,12,0,0,inf,12,2500,3\n",  # not finite
        4: "Driver,110,2,12,0,0,1000000,12,2500,3\n",  # 1e6 mph: no instrument reads it
        5: "Driver,110,2,12,0,0,160,12,2500,31\n",  # 31 mm up a driver's 60 mm face: off it
        6: "Driver,110,2,12,0,0,190,12,2500,3\n",  # smash 1.73: no driver gives it
        7: "Driver,110,2,12,0,0,-160,12,2500,3\n",  # a magnitude below zero
        8: "Driver,110,2,12,0,0,160,95,2500,3\n",  # a launch at 95 deg
        9: "Driver,110,45,12,0,0,160,12,2500,3\n",  # an attack angle beyond +-30 deg
    }
    session = read_session_text(HEADER + GOOD + "".join(rows.values()), "r.csv")
    table = session.shot_table()
    assert table.labels == ("line 2",)
    reasons = dict(table.skipped)
    assert reasons[3] == "Ball Speed [mph]: not a finite number"
    assert reasons[4].startswith("Ball Speed [mph] beyond any golf shot (above 300 mph); a smash factor no driver")
    assert reasons[5] == "strike off the driver's face (Impact Height [mm] beyond 30 mm of its centre)"
    assert reasons[6].startswith("a smash factor no driver gives (above 1.530")
    assert reasons[7] == "Ball Speed [mph] below 0 (a magnitude)"
    assert reasons[8] == "Launch Angle [deg] beyond any golf shot (-90 to 90 deg)"
    assert reasons[9] == "Attack Angle [deg] beyond any golf shot (-30 to 30 deg)"
    assert [line for line, _ in session.bad_rows()] == list(rows)
    with pytest.raises(StudyError, match=r"--strict: 7 bad row\(s\): r.csv:3: Ball Speed \[mph\]: not a finite"):
        session.refuse_bad_rows()


def test_the_smash_limit_is_the_rules_cor_at_the_heads_mass_with_the_stated_allowance():
    from impactlab.data.sessions.rows import smash_limit
    from impactlab.scene.catalogue import club_preset

    mass = club_preset("driver").mass
    assert mass == pytest.approx(0.204)
    assert smash_limit("driver") == pytest.approx(1.838 * 0.204 / (0.204 + 0.04593) * 1.02)


def test_a_strike_off_the_face_is_skipped_in_a_session_and_still_refused_in_a_study():
    from impactlab.study.core import load_study

    session = read_session_text(HEADER + GOOD + GOOD.replace(",3\n", ",31\n"), "s.csv")
    assert [line for line, _ in session.shot_table().skipped] == [3]
    study = {"name": "off", "ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
             "contact": {"friction": 0.4, "restitution": 0.8},
             "delivery": {"club_speed": "110 mph", "path": "0 deg", "face_angle": "0 deg", "attack_angle": "2 deg",
                          "dynamic_loft": "12 deg"}, "strike": {"toe": "0 mm", "high": "31 mm"},
             "models": ["rigid_coulomb"]}
    with pytest.raises((FieldError, StudyError), match="strike on the club's face between -30 and 30 mm"):
        load_study(study)


@pytest.mark.parametrize("command", ["validate", "fit"])
def test_inf_and_a_million_mph_are_skipped_with_their_reason_in_validate_and_fit(tmp_path, capsys, command):
    path = tmp_path / "m.csv"
    path.write_text(HEADER + GOOD + "Driver,105,1,13,0,0,152,13,2700,0\n" + GOOD.replace("160", "inf")
                    + GOOD.replace("160", "1e6"))
    argv = (["validate", "--dataset", str(path)] if command == "validate" else ["fit", str(path)]) + [
        "--model", "rigid_coulomb"]
    if command == "fit":
        argv += ["--parameter", "friction"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "2 of 4 row(s) not used" in out
    assert "Ball Speed [mph]: not a finite number: 1 row(s) (first line 4)" in out
    assert "Ball Speed [mph] beyond any golf shot (above 300 mph): 1 row(s) (first line 5)" in out
    assert main([*argv, "--strict"]) == 2


def test_swapped_speed_headers_are_said_once_with_their_rows_and_not_flown(capsys, tmp_path):
    header = "Club,Club Speed [mph],Ball Speed [mph],Smash Factor,Launch Angle [deg],Spin Rate [rpm]\n"
    rows = "Driver,150,103,1.45,12,2500\nDriver,148,101,1.46,11,2600\nDriver,100,150,1.50,12,2500\n"
    session = read_session_text(header + rows, "swap.csv")
    said = [note for note in session.notes if note.startswith("Smash Factor disagrees")]
    assert len(said) == 1 and "2 row(s) (line(s) 2, 3;" in said[0] and "look swapped" in said[0]
    assert session.flags[("ball_speed", "inconsistent")].tolist() == [True, True, False]
    path = tmp_path / "swap.csv"
    path.write_text(header + rows)
    assert main(["fly", str(path), "--show-rows"]) == 0
    out = capsys.readouterr().out
    assert "ball speed inconsistent by the monitor (--include-flagged flies it): 2 row(s) (line(s) 2, 3)" in out


def test_a_total_spin_that_disagrees_with_its_back_and_side_spin_is_said_and_not_flown():
    header = ("Club,Club head Speed (mph),Ball Speed (mph),Launch Angle (deg),Azimuth (deg),Back Spin (rpm),"
              "Side Spin (rpm),Total Spin (rpm),Carry (yds),Face to Target (deg)\n")
    rows = "Driver,105,150,12,1,2500,300,2518,250,0\nDriver,105,150,12,1,6804,95,3000,250,0\n"
    session = read_session_text(header + rows, "fsx.csv")
    assert session.vendor.id == "foresight_fsx"
    note = next(note for note in session.notes if note.startswith("spin rate differs from hypot"))
    assert "1 row(s) (line(s) 3;" in note and "3000 rpm stated, back 6804 and side 95 rpm give 6805" in note
    assert session.flags[("spin_rate", "inconsistent")].tolist() == [False, True]


def test_a_speed_unit_too_small_for_the_monitors_carry_is_said():
    # km/h on values in mph: 150 "km/h" is 41.7 m/s, and 250 yd of carry is beyond v^2/g = 177 m even in a vacuum
    header = "Club,Ball Speed,Launch Angle,Spin Rate,Carry\n,[km/h],[deg],[rpm],[yds]\n"
    rows = "Driver,150,12,2500,250\nDriver,145,12,2600,240\nDriver,160,11,2400,265\n"
    session = read_session_text(header + rows, "kmh.csv")
    note = next(note for note in session.notes if note.startswith("Ball Speed [km/h]"))
    assert "in 3 of 3 row(s)" in note and "mph read as km/h?" in note
    assert session.flags[("ball_speed", "inconsistent")].all()
    right = read_session_text(header.replace("km/h", "mph") + rows, "mph.csv")
    assert ("ball_speed", "inconsistent") not in right.flags


@pytest.mark.parametrize("codec, bom, named", [
    ("utf-16-le", b"", "UTF-16 (little-endian, no byte-order mark)"),
    ("utf-16-be", b"", "UTF-16 (big-endian, no byte-order mark)"),
    ("utf-32-le", b"\xff\xfe\x00\x00", ""),  # its mark names it: read, nothing to say
    ("utf-32-le", b"", "UTF-32 (little-endian, no byte-order mark)"),
    ("utf-32-be", b"", "UTF-32 (big-endian, no byte-order mark)"),
])
def test_wide_encodings_are_read_and_named_as_they_are(tmp_path, codec, bom, named):
    path = tmp_path / "wide.csv"
    path.write_bytes(bom + (HEADER + GOOD).encode(codec))
    session = read_session(path)
    assert session.size == 1 and session.values["ball_speed"][0] == pytest.approx(160 * MPH)
    said = [note for note in session.notes if note.startswith("read as")]
    assert said == ([f"read as {named} text"] if named else [])


def test_the_monitors_flight_is_measured_or_modelled_by_its_tracked_time_and_fly_compares_only_measured(capsys,
                                                                                                       tmp_path):
    head = ("Club,Club Speed,Attack Angle,Dyn. Loft,Face To Path,Ball Speed,Smash Factor,Launch Angle,Spin Rate,"
            "Last data Point - Time,Carry Flat - Length,Carry Flat - Time\n,[mph],[deg],[deg],[deg],[mph],[],[deg],"
            "[rpm],[s],[yds],[s]\n")
    rows = ("Driver,110,2,12,0,160,1.4545,12,2500,6.0,250,6.2\n"  # tracked 97 %: measured
            "Driver,110,2,12,0,160,1.4545,12,2500,0.3,200,6.2\n"  # 5 %: TrackMan's model
            "Driver,110,2,12,0,160,1.4545,12,2500,0,0,0\n")  # no flight at all: 0 is no value
    session = read_session_text(head + rows, "tm.csv")
    assert session.vendor.id == "trackman_tps_legacy"
    assert session.flags[("carry_distance", "modelled")].tolist() == [False, True, False]
    assert np.isnan(session.values["carry_distance"][2]) and np.isnan(session.values["flight_time"][2])
    path = tmp_path / "tm.csv"
    path.write_text(head + rows)
    assert main(["fly", str(path)]) == 0
    out = capsys.readouterr().out
    assert "model against the monitor's carry, 1 shot(s)" in out and "(1 of 2 with a carry;" in out
    table = [line for line in out.splitlines() if line.startswith("| 3 ") or line.startswith("| 4 ")]
    assert table[0].endswith("| measured |") and table[1].endswith("| model |")


def test_the_generic_layout_is_not_a_vendors_and_reads_no_vendor_marker():
    assert GENERIC.sentinels == () and GENERIC.sentinel_at_least is None
