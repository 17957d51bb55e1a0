"""Launch-monitor exports as their users export them, beyond the first layouts of tests/test_vendors.py: a header
repeated above every block (Rapsodo), a second session appended, placeholders written where a monitor read no club
(Garmin R10 and R50), spin-rate types a layout does not know, and the Garmin Golf app's exports in German, Spanish,
Dutch and Thai. Fixtures and their sources: tests/data/vendors/README.md. The oracles are numbers typed from the
fixtures and units converted by their definitions (1 km/h = 1/3.6 m/s, 1 yd = 0.9144 m), not values the reader
computed."""

import math
from pathlib import Path

import numpy as np
import pytest

from impactlab.cli import main
from impactlab.data.sessions.reader import read_session, read_session_text
from impactlab.errors import StudyError
from impactlab.scene.catalogue import club_key

DATA = Path(__file__).parent / "data" / "vendors"
YD = 0.9144  # m
FT = 0.3048  # m
MPH = 0.44704  # m/s
KMH = 1 / 3.6  # m/s
RPM = 2 * math.pi / 60  # rad/s
DEG = math.pi / 180


def test_rapsodo_blocks_repeat_their_header_and_every_block_is_read():
    # real rows (DocNR/raid.golf rapsodo_mlm2pro_mixed_club_sample.csv) in the per-club block layout: the header
    # again above the 5i, each block closed by Average and Std. Dev.; before, the second header was read as a shot
    # and the file refused at its cells ('expected a number, got 'Carry Distance'')
    session = read_session(DATA / "rapsodo_mlm2pro_blocks.csv")
    assert session.vendor.id == "rapsodo_mlm2pro"
    assert session.lines.tolist() == [4, 5, 10, 11]
    assert list(session.text["club"]) == ["7i", "7i", "5i", "5i"]
    v = session.values
    assert v["carry_distance"].tolist() == pytest.approx([142.2 * YD, 146.8 * YD, 157.8 * YD, 157.0 * YD])
    assert v["apex_height"][2] == pytest.approx(67.9 * FT)
    assert v["offline_distance"][2] == pytest.approx(-10.3 * YD)  # negative = left, as exported
    assert v["spin_axis"][3] == pytest.approx(6.8 * DEG)
    reasons = dict(session.skipped)
    assert reasons[9] == "the header again (a new block of the export), not a shot"
    assert {6, 7, 12, 13} <= set(reasons) and "Average" in reasons[12]


GARMIN_HEADER = ("Date,Player,Club Type,Club Speed,Ball Speed,Launch Angle,Backspin,Sidespin,Spin Rate,"
                 "Spin Rate Type,Spin Axis,Carry Distance,Carry Deviation Distance")
GARMIN_UNITS = ",,,[mph],[mph],[deg],[rpm],[rpm],[rpm],,[deg],[yds],[yds]"
GARMIN_ROW = "6/6/26 08:40:02,P,7 Iron,59.7,77.4,15.8,3545.8,-702.5,3614.7,Measured,11.2,85.3,7.4"


GARMIN_ROW_2 = "6/7/26 09:10:00,P,7 Iron,60.1,78.0,16.0,3500.0,-700.0,3569.3,Measured,11.3,86.0,7.5"


def test_a_second_session_appended_reads_if_its_units_agree_and_is_refused_if_not():
    same = "\n".join([GARMIN_HEADER, GARMIN_UNITS, GARMIN_ROW, GARMIN_HEADER, GARMIN_UNITS, GARMIN_ROW_2,
                      GARMIN_ROW]) + "\n"
    session = read_session_text(same, "two.csv")
    assert session.size == 2 and session.lines.tolist() == [3, 6]
    reasons = dict(session.skipped)
    assert reasons[4] == "the header again (a new block of the export), not a shot"
    assert reasons[5] == "the units row again, under the repeated header"
    assert reasons[7].startswith("repeats line 3 cell for cell (the same shot twice")  # one session appended twice
    assert session.values["ball_speed"].tolist() == pytest.approx([77.4 * MPH, 78.0 * MPH])
    metric = "\n".join([GARMIN_HEADER, GARMIN_UNITS, GARMIN_ROW, GARMIN_HEADER,
                        GARMIN_UNITS.replace("[mph],[mph]", "[km/h],[km/h]"), GARMIN_ROW]) + "\n"
    with pytest.raises(StudyError, match=r"two.csv:5: a units row that differs from the one at line 2 "
                                         r"\('Club Speed' \[km/h\], was \[mph\]\)"):
        read_session_text(metric, "two.csv")


def test_garmin_r50_club_face_and_smash_factor_written_without_club_data_are_no_data():
    # the R50 export's pattern (luis-godinez/golf-analytics CSVs/25:04:01.csv; the fixture's numbers are ours): no
    # club speed, attack angle, path or face to path, yet Club Face 0.0 and Smash Factor = -(ball speed in m/s)
    session = read_session(DATA / "garmin_r50.csv")
    assert session.vendor.id == "garmin_golf"
    v = session.values
    assert v["ball_speed"].tolist() == pytest.approx([95.0 * KMH, 153.0 * KMH])  # [km/h]
    assert v["apex_height"].tolist() == pytest.approx([21.0, 29.5])  # [m]
    assert v["carry_distance"].tolist() == pytest.approx([58.0 * YD, 135.0 * YD])  # [Yards]
    assert v["side_spin"].tolist() == pytest.approx([-150.0 * RPM, 400.0 * RPM])  # Sidespin positive left: turned
    assert v["spin_axis"].tolist() == pytest.approx([-4.763642 * DEG, 8.130102 * DEG])
    for field in ("face_angle", "smash_factor"):
        assert np.isnan(v[field]).all(), field  # not a square face, not a smash of -26.4
        assert session.flags[(field, "no data")].tolist() == [True, True], field
    assert any("face_angle exactly 0 with no path" in note for note in session.notes)
    assert any("smash_factor a value with no club_speed" in note for note in session.notes)
    # the R10 fixture's row without club data writes Face to Path 0.0 (jgamblin/golf 2026-04-19 11:48:31 does)
    r10 = read_session(DATA / "garmin_r10.csv")
    assert np.isnan(r10.values["face_to_path"][3]) and r10.flags[("face_to_path", "no data")].tolist() == \
        [False, False, False, True]
    assert r10.values["face_to_path"][0] == pytest.approx(11.013476371765137 * DEG)  # a measured one is kept


def test_a_spin_rate_type_the_layout_does_not_know_is_flagged_not_read_as_measured():
    # TrackMan writes Measured or Estimated (the export of record); a word it does not know, here 'Calculated' in
    # the 7:07:22 PM row, cannot be told from an estimate: flagged and said (before: read as measured)
    text = (DATA / "trackman_tps_drivers.csv").read_text(encoding="utf-8-sig")
    lines = text.split("\n")
    lines[4] = lines[4].replace('"Measured"', '"Calculated"')
    session = read_session_text("\n".join(lines), "tps.csv")
    assert session.flags[("spin_rate", "estimated")].tolist() == [False, True, False, False, False, False, False]
    assert any("Spin Rate Type: 1 row(s) hold 'calculated'" in note for note in session.notes)
    assert not any("Spin Rate Type" in note for note in read_session(DATA / "trackman_tps_drivers.csv").notes)


def test_garmin_german_export_headers_spin_type_and_club_names():
    # the real row of thraizz/r10progress csvLocalization.ts (14.02.24 13:33:18, Eisen 9, 'Berechnet') and a row of
    # ours ('Gemessen', 'Holz 3'), under the German header; units row ours (km/h and m, as the row's numbers are)
    session = read_session(DATA / "garmin_golf_de.csv")
    assert session.vendor.id == "garmin_golf_de"
    v = session.values
    assert v["club_speed"][0] == pytest.approx(113.42900776786246 * KMH)
    assert v["ball_speed"][0] == pytest.approx(128.24671443709485 * KMH)
    assert v["carry_distance"][0] == pytest.approx(88.6080322265625)  # [m]
    assert v["offline_distance"][0] == pytest.approx(1.655823826789856)
    # Sidespin -644.06 rpm is positive curving left in Garmin's export: +644.06 in the vocabulary, with Drehachse +7.54
    assert v["side_spin"][0] == pytest.approx(644.055908203125 * RPM)
    assert v["spin_axis"][0] == pytest.approx(7.544279098510742 * DEG)
    # the row's own identities: face to path = face - path, spin = hypot(back, side), axis = atan(side/back)
    assert v["face_angle"][0] - v["path"][0] == pytest.approx(2.9994254112243652 * DEG, abs=1e-6)
    assert v["spin_rate"][0] == pytest.approx(math.hypot(4863.04638671875, 644.055908203125) * RPM, rel=1e-6)
    assert session.flags[("spin_rate", "estimated")].tolist() == [True, False]  # Berechnet / Gemessen
    assert list(session.text["club"]) == ["Iron 9", "Wood 3"]
    assert [club_key(name) for name in session.text["club"]] == ["9_iron", "3_wood"]


def test_garmin_thai_export_units_in_thai_and_an_unknown_spin_type():
    session = read_session(DATA / "garmin_golf_th.csv")
    assert session.vendor.id == "garmin_golf_th"
    v = session.values
    assert v["apex_height"].tolist() == pytest.approx([25.0, 28.0])  # [ม.]: metres
    assert v["carry_distance"][0] == pytest.approx(230.0 * YD) and np.isnan(v["carry_distance"][1])  # [หลา]: yards
    assert v["ball_speed"][0] == pytest.approx(135.0 * MPH)
    assert v["side_spin"][0] == pytest.approx(300.0 * RPM) and v["spin_axis"][0] == pytest.approx(6.843 * DEG)
    assert session.flags[("spin_rate", "estimated")].tolist() == [True, True]  # 'วัด': not a word the layout knows
    assert any("hold 'วัด'" in note for note in session.notes)
    assert [club_key(name) for name in session.text["club"]] == ["driver", "7_iron"]


@pytest.mark.parametrize("vendor, header", [
    # the Dutch header line of thraizz/r10progress src/types/GolfSwingData.ts, verbatim
    ("garmin_golf_nl", "Datum,Speler,Clubnaam,Type club,Clubsnelh.,Aanvalshoek,Clubtraject,Slagvlak van de club,"
                       "Slagvlak t.o.v. traject,Balsnelheid,Smashfactor,Slaghoek,Slagrichting,Backspin,Sidespin,"
                       "Spinsnelheid,Type draaisnelheid,Spinas,Apexhoogte,Carry-afstand,Carry-afwijkingshoek,"
                       "Carry-afwijkingsafstand,Totale afstand"),
    # the Spanish names of the same file (type GolfSwingDataES), in the English export's order
    ("garmin_golf_es", "Fecha,Jugador,Nombre,Tipo de palo,Vel. palo,Ángulo de ataque,Línea cabeza del palo,"
                       "Cara del palo,Cara a línea,Velocidad de la pelota,Calidad del impacto,Ángulo de lanzamiento,"
                       "Dirección de lanzamiento,Retroceso,Efecto lateral,Velocidad de rotación,"
                       "Tipo de velocidad de rotación,Eje de rotación,Altura máxima,Dist.vuelo,"
                       "Ángulo de desviación de vuelo,Distancia de desviación de vuelo,Distancia total"),
])
def test_garmin_dutch_and_spanish_headers_map_onto_the_english_columns(vendor, header):
    units = ",,,,[km/h],[deg],[deg],[deg],[deg],[km/h],,[deg],[deg],[rpm],[rpm],[rpm],,[deg],[m],[m],[deg],[m],[m]"
    row = ("1.6.24 10:00:00,P,,7,120.0,-3.0,-2.0,1.0,3.0,160.0,1.33,17.0,0.5,5000.0,-400.0,5016.0,X,4.57,25.0,130.0,"
           "2.0,4.5,140.0")
    session = read_session_text("\n".join([header, units, row]) + "\n", "x.csv")
    assert session.vendor.id == vendor
    v = session.values
    expected = {"club_speed": 120.0 * KMH, "attack_angle": -3.0 * DEG, "path": -2.0 * DEG, "face_angle": 1.0 * DEG,
                "face_to_path": 3.0 * DEG, "ball_speed": 160.0 * KMH, "smash_factor": 1.33,
                "vertical_launch_angle": 17.0 * DEG, "horizontal_launch_angle": 0.5 * DEG, "back_spin": 5000.0 * RPM,
                "side_spin": 400.0 * RPM, "spin_rate": 5016.0 * RPM, "spin_axis": 4.57 * DEG, "apex_height": 25.0,
                "carry_distance": 130.0, "offline_distance": 4.5, "total_distance": 140.0}
    for field, value in expected.items():
        assert v[field][0] == pytest.approx(value), field
    assert session.flags[("spin_rate", "estimated")].tolist() == [True]  # 'X': this layout knows no spin-type word


def test_a_translated_layout_names_its_base_translates_real_columns_and_restates_worded_rules():
    from impactlab.data.sessions.layouts import _with_base

    base = {"id": "b", "name": "b", "source": "", "recognise": ["Club"], "units": "row",
            "columns": {"Club": "club", "Speed": "ball_speed"},
            "estimated": {"column": "Type", "values": ["Estimated"], "fields": ["ball_speed"]}}
    layout = {"id": "t", "base": "b", "name": "t", "source": "", "recognise": ["Schläger"],
              "headers": {"Schläger": "Club", "Tempo": "Speed"},
              "estimated": {"column": "Typ", "values": ["Berechnet"], "fields": ["ball_speed"]}}
    merged = _with_base(layout, {"b": base}, "t.yaml")
    assert merged["columns"]["Tempo"] == "ball_speed" and merged["recognise"] == ["Schläger"]
    with pytest.raises(StudyError, match=r"t.yaml: base: expected the id of a shipped layout"):
        _with_base({**layout, "base": "nope"}, {"b": base}, "t.yaml")
    with pytest.raises(StudyError, match=r"t.yaml: headers.Tempo: 'Sped' is no column of the b layout"):
        _with_base({**layout, "headers": {"Tempo": "Sped"}}, {"b": base}, "t.yaml")
    without = {key: value for key, value in layout.items() if key != "estimated"}
    with pytest.raises(StudyError, match=r"t.yaml: estimated: the b layout's rule names its column"):
        _with_base(without, {"b": base}, "t.yaml")


def test_shots_reads_the_german_export_and_fly_flies_the_r50_rows(capsys):
    assert main(["shots", str(DATA / "garmin_golf_de.csv")]) == 0
    report = capsys.readouterr().out
    assert "(garmin_golf_de)" in report and "'Eisen 9' as 'Iron 9'" in report
    assert "'Drehratentyp' -> estimated flag: Berechnet marks" in report
    assert main(["fly", str(DATA / "garmin_r50.csv")]) == 0
    flown = capsys.readouterr().out
    assert "2 shot(s) flown" in flown and "| 58.0 |" in flown  # the monitor's carry [Yards] beside the model's


def test_a_header_no_layout_knows_is_read_in_impactlabs_layout_and_said():
    # the German export with one of the columns its layout recognises it by spelled otherwise (an app version no
    # layout knows): only Backspin, Sidespin and Smash Factor are names impactlab knows, and Sidespin would be read
    # positive right (Garmin writes it positive left): the report says so. (Forcing --vendor impactlab onto the
    # recognised file is refused instead: test_vendors.test_a_vendor_forced_onto_another_vendors_export_is_refused)
    text = (DATA / "garmin_golf_de.csv").read_text(encoding="utf-8").replace("Schlägerart", "Schlaegerart", 1)
    session = read_session_text(text, "garmin_de_variant.csv")
    assert session.vendor.id == "impactlab"
    assert any("no vendor layout recognises this header (28 of 31 columns unknown)" in note for note in session.notes)
    assert not any("no vendor layout" in note for note in read_session(DATA / "garmin_golf_de.csv").notes)


def test_skytrak_club_blocks_a_plain_units_row_and_two_columns_named_side():
    # the legacy ShotsHistory layout (brandon-rice/golf_swing_stats's parser and fixtures; numbers ours)
    session = read_session(DATA / "skytrak.csv")
    assert session.vendor.id == "skytrak"
    assert session.lines.tolist() == [7, 8, 12] and list(session.text["club"]) == ["PW", "PW", "7I"]
    assert [club_key(name) for name in session.text["club"]] == ["pitching_wedge", "pitching_wedge", "7_iron"]
    assert list(session.text["handedness"]) == ["right"] * 3
    v = session.values
    # the two SIDE columns, told apart by their units (RPM, DEG)
    assert v["side_spin"].tolist() == pytest.approx([-400 * RPM, 470 * RPM, -200 * RPM])
    assert v["horizontal_launch_angle"].tolist() == pytest.approx([4.0 * DEG, -3.0 * DEG, 2.0 * DEG])
    assert v["ball_speed"][0] == pytest.approx(96.0 * MPH) and v["apex_height"][0] == pytest.approx(20.0 * YD)
    assert v["flight_time"][0] == pytest.approx(5.0) and v["smash_factor"][0] == pytest.approx(1.30)
    assert v["spin_rate"][0] == pytest.approx(math.hypot(6000, 400) * RPM)  # no spin column: from BACK and SIDE
    assert v["spin_axis"][0] == pytest.approx(-math.atan(400 / 6000))
    reasons = dict(session.skipped)
    assert reasons[6] == "names the club of the shots below it ('PW')" and "average" in reasons[9]
    assert reasons[16].startswith("the session's notes") and 17 in reasons  # NOTES and the free text under it


def test_skytrak_newer_export_quoted_ragged_rows_and_face_to_path():
    text = ('"PRACTICE GREENS: 08/23/2026 \u2022 04:30 PM"\n"PLAYER: "\n\n'
            '"SHOT","HAND","SHOT SCORE","BALL SPEED","LAUNCH","BACK","SIDE","SIDE","OFFLINE","CARRY","ROLL","TOTAL",'
            '"FLIGHT","DSCNT","HEIGHT","CLUB SPEED","SMASH","PATH","FTP","FTT"\n'
            '"#","L/R","SCORE","MPH","DEG","RPM","RPM","DEG","YD","YD","YD","YD","SEC","DEG","YD","MPH","FACTOR",'
            '"DEG","DEG","DEG"\n\n"9 IRON"\n'
            '"1","R","100","104","18.5","5400","640","7.5","28","148","0","148","5","44","24","76","1.37","5.0",'
            '"3.0","8.0"\n'
            '"AVG","","100","104","18.5","5400","640","7.5","28","148","0","148","5","44","24","76","1.37","5.0",'
            '"3.0","8.0"\n')
    session = read_session_text(text, "activity.csv")
    assert session.vendor.id == "skytrak" and session.size == 1 and list(session.text["club"]) == ["9 IRON"]
    v = session.values
    assert v["face_to_path"][0] == pytest.approx(3.0 * DEG) and v["face_angle"][0] == pytest.approx(8.0 * DEG)
    assert v["path"][0] == pytest.approx(5.0 * DEG) and v["offline_distance"][0] == pytest.approx(28 * YD)
    assert club_key(session.text["club"][0]) == "9_iron"


def test_garmin_r10_launch_angle_floor_is_flagged_and_a_value_above_it_is_not():
    # jgamblin/golf 2026-05-22 (verbatim rows): 08:42:42 launches at 0.4999999701976776 deg, float32 just below 0.5
    # (a 5 Iron at 89.6 mph carrying 7.9 yd), 08:52:35 at 0.5413 deg
    session = read_session(DATA / "garmin_r10_0522.csv")
    v = session.values
    assert v["vertical_launch_angle"].tolist() == pytest.approx(
        [3.3272037506103516 * DEG, 0.4999999701976776 * DEG, 8.20970630645752 * DEG, 0.5413448810577393 * DEG])
    assert session.flags[("vertical_launch_angle", "clamped")].tolist() == [False, True, False, False]
    assert session.flags[("spin_axis", "clamped")].tolist() == [False, False, True, False]  # 30.0
    # 2.4063345335889608e-05 rpm (a number in exponent notation) is read, positive curving left: turned
    assert v["side_spin"][0] == pytest.approx(-2.4063345335889608e-05 * RPM)
    assert session.flagged("vertical_launch_angle").tolist() == [False, True, False, False]


def test_flightscope_simulator_windows_1252_repeated_columns_and_right_left_suffixes(tmp_path):
    # the layout of GekoZRH/FlightScopeDataAnalysis's docs and tests (numbers ours): Windows-1252 text ('Jürg' is
    # byte 0xfc), units in square brackets, 'Total [m]' and 'Club Speed [mph]' written twice, '3.2 L' and '1.2 R'
    session = read_session(DATA / "flightscope_simulator.csv")
    assert session.vendor.id == "flightscope_simulator"
    assert session.notes[0].startswith("read as windows-1252 text (not UTF-8)")
    v = session.values
    assert v["total_distance"][:2].tolist() == pytest.approx([158.34, 230.1])  # the first, more precise column
    assert v["club_speed"][:2].tolist() == pytest.approx([87.0 * MPH, 103.5 * MPH])  # the second where it is empty
    assert v["offline_distance"][0] == pytest.approx(-3.2) and v["spin_axis"][0] == pytest.approx(-4.5 * DEG)
    assert v["horizontal_launch_angle"][:2].tolist() == pytest.approx([1.2 * DEG, -0.5 * DEG])
    assert v["face_angle"][0] - v["path"][0] == pytest.approx(v["face_to_path"][0])  # FTT - Club Path = FTP
    assert v["face_to_path"][0] == pytest.approx(-1.5 * DEG) and v["flight_time"][0] == pytest.approx(6.6)
    keep, skipped = session.usable()
    assert keep.tolist() == [True, True, False] and "'7 Iron 245' is not in the club catalogue" in skipped[0][1]
    # a file in Windows-1252 that no layout with that encoding claims is refused as before, at its byte
    other = tmp_path / "r50.csv"
    other.write_bytes((DATA / "garmin_r50.csv").read_text().replace("Player", "Jürg").encode("windows-1252"))
    with pytest.raises(StudyError, match=r"r50.csv:1: is not UTF-8 text \(byte 0xfc\)"):
        read_session(other)


def test_flightscope_fsgolf_real_mevo_export_gives_club_data_and_flags_its_smash_rows():
    # the whole real file (russosanti/golf-metrics, a Mevo+ range session of 36 8-irons, MIT): before it was found the
    # layout came from parsers only and mapped no dynamic loft, so every row of this file was refused for the models
    session = read_session(DATA / "flightscope_fsgolf_mevo.csv")
    assert session.vendor.id == "flightscope_fsgolf" and session.size == 36
    assert [line for line, _ in session.skipped] == [38, 39]  # the Avg and Dev rows, with their reason
    v = session.values
    # shot 1, typed from the file: AOA -6.5, Dynamic Loft 28.3, Spin Loft 34.9, Club Path 1.3 L, FTP 2.3 L, FTT 3.6 L,
    # Spin Axis 4.3 L, Launch V 18.3, DescentV 40.4, Spin 6820 rpm, Ball 105.1 mph, Club 84.8 mph
    assert v["attack_angle"][0] == pytest.approx(-6.5 * DEG) and v["dynamic_loft"][0] == pytest.approx(28.3 * DEG)
    assert v["spin_loft"][0] == pytest.approx(34.9 * DEG) and v["landing_angle"][0] == pytest.approx(40.4 * DEG)
    assert v["path"][0] == pytest.approx(-1.3 * DEG) and v["face_to_path"][0] == pytest.approx(-2.3 * DEG)
    assert v["face_angle"][0] == pytest.approx(-3.6 * DEG) and v["spin_axis"][0] == pytest.approx(-4.3 * DEG)
    assert v["spin_rate"][0] == pytest.approx(6820 * RPM) and v["vertical_launch_angle"][0] == pytest.approx(18.3 * DEG)
    assert v["ball_speed"][0] == pytest.approx(105.1 * MPH) and v["club_speed"][0] == pytest.approx(84.8 * MPH)
    # shot 5 curves right (Fade, Curve Dist +8.1, Lateral 12.1 R): its axis is positive
    assert v["spin_axis"][4] == pytest.approx(5.6 * DEG) and v["offline_distance"][4] == pytest.approx(12.1 * YD)
    # the 3-D spin loft: shot 31, face 17.9 deg closed to the path, spin loft 51.6 where loft - attack is 48.8
    assert v["spin_loft"][30] - (v["dynamic_loft"][30] - v["attack_angle"][30]) == pytest.approx(2.8 * DEG)
    # seven rows whose Smash is not Ball / Club within 2 % (shot 12: 1.29 stated, 106.4 / 84.6 = 1.258): their speeds
    # are flagged and the rows left out of the models, each with its line; the other 29 are used
    flagged = session.flagged("club_speed")
    assert session.lines[flagged].tolist() == [13, 15, 16, 17, 18, 26, 36]
    keep, skipped = session.usable()
    assert int(keep.sum()) == 29
    assert all("smash factor" in why for _, why in skipped)
    # impact location (inches, sign not stated, stops at +-1.38 and -1.18 in) and the air (unit in each value) unread
    assert np.isnan(v["strike_high"]).all() and "Vertical Impact (in)" in session.unused
    # the parsers' metric layout has Spin Loft but no Club Path or FTP: no dynamic loft is made of it on a face
    # assumed square, so its rows serve ball data only
    metric = read_session(DATA / "flightscope_fsgolf_metric.csv")
    keep, skipped = metric.usable()
    assert not keep.any() and all(why == "no dynamic loft" for _, why in skipped)


def test_two_app_versions_joined_in_one_file_are_refused_at_the_second_header():
    # the 42-column export of 2026-04-19 and the 32-column one of 2026-05-23 (jgamblin/golf, the fixtures' real
    # lines) pasted into one file: the second header has other columns, so its rows cannot be read by the first's
    first = (DATA / "garmin_r10.csv").read_text().splitlines()[:3]
    second = (DATA / "garmin_r10_b.csv").read_text().splitlines()[:3]
    with pytest.raises(StudyError, match=r"joined.csv:4: a second header, with other columns than line 1's"):
        read_session_text("\n".join(first + second) + "\n", "joined.csv")


@pytest.mark.parametrize("name, vendor", [
    ("garmin_golf_de.csv", "garmin_golf_de"), ("garmin_golf_th.csv", "garmin_golf_th"),
    ("garmin_r50.csv", "garmin_golf"), ("garmin_r10_0522.csv", "garmin_golf"), ("skytrak.csv", "skytrak"),
    ("rapsodo_mlm2pro_blocks.csv", "rapsodo_mlm2pro"), ("flightscope_simulator.csv", "flightscope_simulator"),
])
def test_each_new_fixture_reads_back_from_its_normalised_table(name, vendor, tmp_path, capsys):
    out = tmp_path / "normal.csv"
    assert main(["shots", str(DATA / name), "--csv", str(out)]) == 0
    assert f"({vendor})" in capsys.readouterr().out.splitlines()[0]
    session, again = read_session(DATA / name), read_session(out)
    assert list(again.text["club"]) == list(session.text["club"])
    for field in ("ball_speed", "spin_rate", "spin_axis", "side_spin", "horizontal_launch_angle", "face_angle",
                  "carry_distance", "apex_height", "smash_factor"):
        np.testing.assert_allclose(again.values[field], session.values[field], rtol=1e-9, equal_nan=True)
    assert {key: rows.tolist() for key, rows in again.flags.items()} == \
        {key: rows.tolist() for key, rows in session.flags.items()}


@pytest.mark.parametrize("name", ["garmin_golf_de", "garmin_golf_th"])
def test_translated_garmin_exports_state_their_air_as_the_english_one(name):
    """Temperatur / อุณหภูมิ [deg C], Luftdruck / ความกดอากาศ [kPa], Relative Luftfeuchtigkeit / ความชื้นสัมพัทธ์ [%]
    and Luftdichte / ความหนาแน่นของอากาศ [g/L] are the English export's air columns: read per shot (the first row's
    cells found here by their units-row units) and checked against each other."""
    import csv

    with open(DATA / f"{name}.csv", encoding="utf-8", newline="") as stream:
        rows = list(csv.reader(stream))
    header, units, first = rows[0], rows[1], rows[2]
    column = {unit: index for index, unit in enumerate(units) if unit in ("[g/L]", "[deg C]", "[kPa]", "[%]")}
    session = read_session(DATA / f"{name}.csv")
    v = session.values
    assert v["air_temperature"][0] == pytest.approx(float(first[column["[deg C]"]]) + 273.15)
    assert v["air_pressure"][0] == pytest.approx(float(first[column["[kPa]"]]) * 1e3)
    assert v["relative_humidity"][0] == pytest.approx(float(first[column["[%]"]]) / 100)
    assert v["air_density"][0] == pytest.approx(float(first[column["[g/L]"]]))
    assert any(note.startswith("air density: as its temperature") for note in session.notes), header


@pytest.mark.parametrize("content, says", [
    (b"PK\x03\x04\x14\x00\x06\x00" + b"\x00" * 22 + b"[Content_Types].xml" + b"\x00" * 40 + b"xl/workbook.xml",
     "is an Excel workbook (.xlsx), not a text export; save the sheet as CSV"),
    (bytes.fromhex("d0cf11e0a1b11ae1") + b"\x00" * 504, "is an Excel 97-2003 workbook (.xls)"),
    (b"PK\x03\x04" + b"\x00" * 26 + b"mimetypeapplication/vnd.oasis.opendocument.spreadsheet",
     "is an OpenDocument spreadsheet (.ods)"),
])
def test_a_workbook_given_as_a_session_is_named_and_the_way_out_said(tmp_path, capsys, content, says):
    """A TrackMan or FlightScope session saved as a workbook (the file's magic bytes, written here) was called 'a
    binary file'; it is named, and the user is told to save or export CSV. One line, exit 2."""
    path = tmp_path / "session.xlsx"
    path.write_bytes(content)
    assert main(["shots", str(path)]) == 2
    err = capsys.readouterr().err
    assert says in err and len(err.strip().splitlines()) == 1 and "Traceback" not in err
