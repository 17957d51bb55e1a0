"""Review of the session readers merged in session 7: cases their own tests let through (each test here fails on
the defect or mutation it names)."""

from __future__ import annotations

import numpy as np
import pytest

from impactlab.data.sessions.reader import read_session_text
from impactlab.data.sessions.flight import fly_session
from impactlab.errors import StudyError

MPH = 0.44704
DEG = np.pi / 180.0


def test_identical_rounded_rows_of_a_table_without_time_or_label_are_two_shots():
    # a robot or a test plan at one setting, written to whole mph, degrees and rpm: two shots of the same numbers
    # are two shots; nothing in impactlab's own layout tells a copied row from a repeat (no time, no shot number).
    # Skipping the second (the duplicate rule of e246a7e) dropped a real shot from every fit and mean, said only
    # in `impactlab shots`' list of skipped rows
    text = ("club,ball_speed [mph],launch_angle [deg],spin_rate [rpm],carry [yd]\n"
            "7 Iron,120,18,7000,165\n7 Iron,120,18,7000,165\n7 Iron,121,18,7000,166\n")
    session = read_session_text(text, "robot.csv")
    assert session.size == 3 and session.lines.tolist() == [2, 3, 4]
    assert session.values["ball_speed"].tolist() == pytest.approx([120 * MPH, 120 * MPH, 121 * MPH])
    assert session.skipped == []
    assert any(note.startswith("line 3 repeats line 2 cell for cell: kept") for note in session.notes)


def test_a_repeated_row_with_its_label_repeated_is_still_one_shot_twice():
    # a label (a time, a shot id) that repeats with every value: the same shot written twice
    text = ("label,ball_speed [mph],launch_angle [deg],spin_rate [rpm]\n"
            "09:00:01,120,18,7000\n09:00:01,120,18,7000\n09:00:40,120,18,7000\n")
    session = read_session_text(text, "timed.csv")
    assert session.size == 2 and session.lines.tolist() == [2, 4]
    assert dict(session.skipped)[3].startswith("repeats line 2 cell for cell")


def test_a_stated_pressure_sets_the_air_over_a_stated_altitude():
    # a row stating both: the station pressure is the air's (measured there); an altitude gives only the ISA
    # pressure of a standard day. Oracle: dry air at 900 hPa and 15 degC, p / (R_d T) = 90000 / (287.05 x 288.15)
    # = 1.088 kg/m^3 (50 % humidity, not stated, lowers it by ~0.5 %); at 0 m (ISA 1013.25 hPa) it would be ~1.22
    text = ("ball_speed [mph],launch_angle [deg],spin_rate [rpm],air_temperature [degC],air_pressure [hPa],"
            "altitude [m]\n150,12,2600,15,900,0\n150,12,2600,15,900,\n")
    flown = fly_session(read_session_text(text, "air.csv"))
    density = flown["air_density"].values
    assert density[0] == density[1]
    assert density[0] == pytest.approx(90000 / (287.05 * 288.15), rel=0.01)


GARMIN = ("Date,Club Type,Club Speed,Club Path,Club Face,Ball Speed,Launch Angle,Backspin,Sidespin,Spin Rate,"
          "Spin Rate Type,Spin Axis,Carry Deviation Distance\n"
          ",,[mph],[deg],[deg],[mph],[deg],[rpm],[rpm],[rpm],,[deg],[yds]\n")


def test_a_garmin_club_face_other_than_zero_without_a_club_path_is_read():
    # only an exact 0.0 beside no club path is Garmin's placeholder (only_zero: true); a face of 2.5 deg is a value
    text = GARMIN + ("6/6/26 08:40:02,Driver,,,2.5,150,12,2600,-300,2617,Measured,6.6,5\n"
                     "6/6/26 08:41:02,Driver,,,0.0,150,12,2600,-300,2617,Measured,6.6,5\n")
    session = read_session_text(text, "garmin.csv")
    face = session.values["face_angle"]
    assert face[0] == pytest.approx(2.5 * DEG) and np.isnan(face[1])
    assert session.flags[("face_angle", "no data")].tolist() == [False, True]


CLOUD = ("sessionId,Session,Time,Club,Shot,Ball (m/s),Club (m/s),Smash,Carry (m),Total (m),Spin (rpm),Sidespin (rpm),"
         "Spin estimated,Height (m),Time (s),AOA (*),Spin Loft (*),Spin Axis (*),Lateral (m),Curve (m),Shape,"
         "Launch H(*),Launch V (*),Mode,Descent V (*),FTT (*)\n"
         "5534658,2022-10-25 18:45:08,2022-10-25T18:48:08Z,7 Iron,1,52.298,39.118,1.3369,150.883,152.181,5451,-192,1,"
         "29.078,6.1968,-8.659,39.7718,-2.0184,-0.3521,-1.3597,straight,0.364,18.744,ShortIndoor,45.0,1.0\n")


def test_a_flightscope_cloud_export_with_descent_and_ftt_columns_is_read_as_the_cloud_layout():
    # the cloud's export holds the columns its user picks; with Descent V and FTT it also held every column the
    # simulator layout recognised (Club, Launch V, Launch H, Descent V, FTT: five against the cloud's four), was read
    # as a simulator file and refused ("columns 'Club' and 'Club (m/s)' both give the club name; keep one")
    session = read_session_text(CLOUD, "cloud.csv")
    assert session.vendor.id == "flightscope_cloud"
    assert session.values["ball_speed"][0] == pytest.approx(52.298)
    assert session.flags[("spin_rate", "estimated")].tolist() == [True]


def _german(rows: list[dict]) -> str:
    """The German Garmin fixture's header and units row, and its one real row changed cell by cell per dict."""
    import csv
    import io
    from pathlib import Path

    header, units, real = list(csv.reader(io.StringIO(
        (Path(__file__).parent / "data" / "vendors" / "garmin_golf_de.csv").read_text(encoding="utf-8"))))[:3]
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerows([header, units])
    for number, changes in enumerate(rows):
        row = dict(zip(header, real), Datum=f"14.02.24 13:{number:02d}:18")
        row.update(changes)
        writer.writerow([row[name] for name in header])
    return out.getvalue()


def test_a_translated_garmin_layout_keeps_the_base_layouts_stops_placeholders_and_floor():
    # the German export is the English one in other words (base: garmin_golf): its 30 deg spin-axis stop, its
    # Club Face 0.0 written without a club path, its float32 launch floor just below 0.5 deg are the same monitor's;
    # dropping them from the translated layout passed every test of session 7
    text = _german([{}, {"Drehachse": "30.0", "Sidespin": "-2000.0"},
                    {"Schwungbahn": "", "Schlagflächenstellung": "", "Schlagfläche": "0.0"},
                    {"Abflugwinkel": "0.4999999701976776"}])
    session = read_session_text(text, "de.csv")
    assert session.vendor.id == "garmin_golf_de" and session.size == 4
    assert session.flags[("spin_axis", "clamped")].tolist() == [False, True, False, False]
    assert session.flags[("face_angle", "no data")].tolist() == [False, False, True, False]
    assert np.isnan(session.values["face_angle"][2]) and session.values["face_angle"][0] == pytest.approx(
        -1.0483050346374512 * DEG)
    assert session.flags[("vertical_launch_angle", "clamped")].tolist() == [False, False, False, True]


def test_a_translated_garmin_layout_turns_a_spin_axis_written_against_its_side_spin():
    # the real German row: Sidespin -644.06 rpm (Garmin: positive curving left, so +644 to the right) with Drehachse
    # +7.544 deg; an app version writing the axis the other way (-7.544 in every row) is turned, as in English
    text = _german([{"Drehachse": "-7.544279098510742"},
                    {"Drehachse": "-5.0", "Sidespin": "-430.0"}])
    session = read_session_text(text, "de.csv")
    assert session.values["side_spin"][0] == pytest.approx(644.055908203125 * np.pi / 30)
    assert session.values["spin_axis"].tolist() == pytest.approx([7.544279098510742 * DEG, 5.0 * DEG])


def test_a_translated_column_keeps_the_sign_of_the_column_it_translates():
    # Spanish 'Efecto lateral' is Garmin's Sidespin, positive curving LEFT: read with its sign turned (as in English)
    text = ("Fecha,Tipo de palo,Velocidad de la pelota,Ángulo de lanzamiento,Retroceso,Efecto lateral,"
            "Tipo de velocidad de rotación,Distancia de desviación de vuelo\n"
            ",,[mph],[deg],[rpm],[rpm],,[yds]\n"
            "6/6/26 08:40:02,Driver,150,12,2600,-300,Medido,5\n")
    session = read_session_text(text, "es.csv")
    assert session.vendor.id == "garmin_golf_es"
    assert session.values["side_spin"][0] == pytest.approx(300 * np.pi / 30)


def test_a_skytrak_shot_row_with_only_its_number_does_not_rename_the_club_of_the_shots_below():
    # a row holding only its first cell heads a club's block ('PW', '7I', '9 IRON'); a shot numbered 2 with nothing
    # measured ('2,,,,') named the PW shot below it club '2'
    from pathlib import Path

    text = (Path(__file__).parent / "data" / "vendors" / "skytrak.csv").read_text(encoding="utf-8").replace(
        "2,R,80,98.0,", "2" + "," * 18 + "\n3,R,80,98.0,")
    session = read_session_text(text, "skytrak.csv")
    clubs = dict(zip(session.lines.tolist(), session.text["club"]))
    assert clubs[8] == "PW" and clubs[9] == "PW" and clubs[13] == "7I"
    assert np.isnan(session.values["ball_speed"][session.lines.tolist().index(8)])


def test_session_carry_ignores_a_placeholder_carry_on_a_row_without_a_launch(tmp_path):
    # a row the monitor did not read (no ball speed, launch or spin) with Carry Distance 0.0: no shot to compare,
    # as fly SESSION leaves it out; session_carry (4c548ac) refused the whole export at that row's carry
    import csv
    import io
    from pathlib import Path

    from impactlab.data.carry import session_carry

    rows = list(csv.reader(io.StringIO((Path(__file__).parent / "data" / "vendors" / "garmin_r10.csv").read_text(
        encoding="utf-8"))))
    header = rows[0]
    unread = dict(zip(header, rows[2]), Date="6/6/26 23:59:59")
    for name in ("Ball Speed", "Launch Angle", "Spin Rate", "Backspin", "Sidespin", "Spin Axis", "Club Speed",
                 "Smash Factor"):
        unread[name] = ""
    unread["Carry Distance"] = "0.0"
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows([*rows, [unread[name] for name in header]])
    path = tmp_path / "r10.csv"
    path.write_text(out.getvalue(), encoding="utf-8")
    with_row = session_carry(path)
    without = session_carry(Path(__file__).parent / "data" / "vendors" / "garmin_r10.csv")
    assert with_row["carry"].tolist() == without["carry"].tolist()
    # a carry of 0 beside a launch that is flown is still refused, at its line
    flown_zero = dict(zip(header, rows[2]), Date="6/6/26 23:59:58")
    flown_zero["Carry Distance"] = "0.0"
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows([*rows, [flown_zero[name] for name in header]])
    path.write_text(out.getvalue(), encoding="utf-8")
    with pytest.raises(StudyError, match=rf"r10.csv:{len(rows) + 1}: carry_distance: expected a carry > 0, got 0 m"):
        session_carry(path)
