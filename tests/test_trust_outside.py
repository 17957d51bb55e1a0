"""Trust in what comes from outside (issue 35): files, simulator replies and stored results.

Each test injects one fault a hostile or broken source can carry and checks what the user sees through
``impactlab.cli.main``: one message, exit status 2 (the user's input) or 3 (the environment: a server), no
traceback, no internal error, and no raw control character on the terminal. The GSPro Connect stand-in is a
local TCP server on a thread; its timing is driven by events and by what it reads, never by sleeps.
"""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from test_gspro import FakeGSPro  # the one fake GSPro Connect of the suite

from impactlab._version import __version__
from impactlab.cli import main
from impactlab.foreign import MAX_NESTING, check_json_nesting, json_depth_exceeded, shown, terminal_safe
from impactlab.io.results import write_results

#: the control characters a hostile text carries: clear screen and home, a colour, a bell, CR LF, a BiDi override
HOSTILE = "\x1b[2J\x1b[H\x1b[31mred\x07\r\nimpactlab: error: forged line\u202e"
WAIT = 30.0  # seconds a socket waits for anything: generous, only a hang reaches it


def raw_controls(text: str) -> list[str]:
    """Control characters other than line breaks and tabs in what reached the terminal."""
    return [char for char in text if (ord(char) < 32 and char not in "\n\t") or 0x7F <= ord(char) < 0xA0
            or char in "\u202e\u202d\u2066\u2067\u2068\u2069"]


def assert_clean(captured, status, expected_status):
    text = captured.out + captured.err
    assert status == expected_status, text
    assert "Traceback" not in text and "internal error" not in text, text
    assert raw_controls(text) == [], text
    # no line of the output is one a foreign text forged
    assert not any(line.startswith("impactlab: error: forged") for line in text.splitlines()), text


# ---- 2. the one escaping function ------------------------------------------------------------------------------

def test_shown_escapes_every_control_character_and_keeps_printable_text():
    assert shown("Golf Club 7i, 10.5° – ok") == "Golf Club 7i, 10.5° – ok"
    assert shown(HOSTILE) == ("\\x1b[2J\\x1b[H\\x1b[31mred\\x07\\r\\nimpactlab: error: forged line\\u202e")
    assert shown("\x9b2J\x00\x7f") == "\\x9b2J\\x00\\x7f"  # C1 CSI, NUL and DEL too
    # whole messages keep their line breaks and tabs, nothing else
    assert terminal_safe("a\tb\nc\x1b[0m\r") == "a\tb\nc\\x1b[0m\\r"
    assert raw_controls(shown("".join(map(chr, range(0x00, 0xA0))))) == []


# ---- 1. one bound on nesting, checked before a parser recurses ---------------------------------------------------

def test_the_depth_scan_counts_brackets_outside_strings_only():
    assert json_depth_exceeded("[" * 101 + "]" * 101) == 1
    assert json_depth_exceeded("[" * 100 + "]" * 100) == 0
    # brackets inside strings, escaped quotes included, are text
    assert json_depth_exceeded('{"a": "' + "[" * 500 + '\\"' + "{" * 500 + '"}') == 0
    assert json_depth_exceeded('{"a":\n\n' + "[" * 200 + "]" * 200 + "}") == 3  # the line where it exceeds


def test_a_json_shot_file_nested_100000_deep_is_refused_by_fly(tmp_path, capsys):
    path = tmp_path / "deep.json"
    path.write_text('{"BallData": ' + "[" * 100_000 + "]" * 100_000 + "}")
    status = main(["fly", str(path)])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert f"nests more than {MAX_NESTING} levels deep" in captured.err


@pytest.mark.slow  # validate imports scipy.optimize first
def test_a_deep_json_dataset_is_refused_by_validate_not_crashed(tmp_path, capsys):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000 + "]" * 100_000)
    status = main(["validate", "--dataset", str(path)])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert f"nests more than {MAX_NESTING} levels deep" in captured.err


def test_the_yaml_and_json_readers_say_the_same_words(tmp_path, capsys):
    (tmp_path / "deep.yaml").write_text("[" * 5_000 + "]" * 5_000)
    assert main(["run", str(tmp_path / "deep.yaml"), "-q"]) == 2
    yaml_words = capsys.readouterr().err.split(": ", 3)[-1]
    with pytest.raises(Exception) as caught:
        check_json_nesting("[" * 5_000, "x.json")
    assert str(caught.value).split(": ", 2)[-1] == yaml_words.strip().replace("YAML", "JSON")


# ---- a local GSPro Connect ---------------------------------------------------------------------------------------

OK = b'{"Code":200,"Message":"Shot received successfully"}'
PLAYER = b'{"Code":201,"Message":"GSPro Player Information","Player":{"Handed":"RH","Club":"DR"}}'


# ---- stored results: a delivery result written by hand ----------------------------------------------------------

def hand_result(path, changes=None, scene_changes=None, attrs_changes=None):
    """A golf result of two cases of one model, as impactlab writes it, with ``changes`` applied (variable ->
    values, or (values, attrs)); the base scene's air and the carry's aerodynamic attributes may be changed too."""
    from impactlab.physics.aerodynamics import model_fingerprint

    back = np.array([3725.0, 3729.0])
    side = np.array([-829.0, 414.8])
    values = {"ball_speed": (np.array([55.36, 55.46]), "m/s"),
              "vertical_launch_angle": (np.array([10.55, 10.56]), "degree"),
              "horizontal_launch_angle": (np.array([-2.21, 2.605]), "degree"),
              "spin_rate": (np.hypot(back, side), "rpm"),
              "spin_axis": (np.degrees(np.arctan2(side, back)), "degree"),
              "back_spin": (back, "rpm"), "side_spin": (side, "rpm"),
              "carry_distance": (np.array([164.1, 166.0]), "m")}
    data = {}
    for name, (column, unit) in values.items():
        attrs = {"units": unit}
        if name == "carry_distance":
            attrs.update(aerodynamic_model="measured_fit", aerodynamic_fingerprint=model_fingerprint("measured_fit"))
        data[name] = [np.asarray(column, float), attrs]
    for name, change in (changes or {}).items():
        if isinstance(change, tuple):
            data[name][0] = np.asarray(change[0], float)
            data[name][1].update(change[1])
        else:
            data[name][0] = np.asarray(change, float)
    scene = {"speed": 40.2336, "attack_angle": math.radians(-4), "dynamic_loft": math.radians(14),
             "path": math.radians(1), "face_angle": 0.0, "handedness": 1.0, "ball_mass": 0.04593,
             "ball_radius": 0.021335, **(scene_changes or {})}
    dataset = xr.Dataset({name: (("model", "face_angle"), column[None, :], attrs)
                          for name, (column, attrs) in data.items()},
                         coords={"model": ["rigid_coulomb"],
                                 "face_angle": ("face_angle", [-3.0, 3.0],
                                                {"units": "deg", "study_path": "delivery.face_angle"})},
                         attrs={"impactlab_version": __version__, "impactlab_format": 1, "study_name": "hand",
                                "base_scene_si": json.dumps(scene), "models": json.dumps(
                                    [{"id": "rigid_coulomb", "name": "rigid_coulomb", "options": {}}]),
                                **(attrs_changes or {})})
    write_results(dataset, path)
    return path


@pytest.fixture
def result_file(tmp_path):
    return hand_result(tmp_path / "hand.h5")


@pytest.mark.slow  # draws the figure and flies the paths (the first flight compiles the integrator)
def test_the_hand_result_is_sound_and_exports(result_file, tmp_path, capsys):
    # the oracle of the tests below: unaltered, both paths take the file
    assert main(["export", str(result_file), "-o", str(tmp_path / "shots.json")]) == 0
    shots = json.loads((tmp_path / "shots.json").read_text())
    assert [shot["BallData"]["Speed"] for shot in shots] == [round(55.36 / 0.44704, 2), round(55.46 / 0.44704, 2)]
    assert main(["plot", str(result_file), "--trajectories", "-o", str(tmp_path / "t.png")]) == 0
    assert_clean(capsys.readouterr(), 0, 0)


# ---- 1 and 2 through the GSPro link: a deep reply, escape sequences in a Message ----------------------------------

def test_a_gspro_reply_nested_30000_deep_is_refused_not_crashed(result_file, capsys):
    deep = b'{"Code":200,"Message":"ok","Player":' + b"[" * 30_000 + b"]" * 30_000 + b"}"
    assert len(deep) < 64 * 1024  # under the reply size limit: the depth bound is what refuses it
    with FakeGSPro(lambda i: deep) as server:
        status = main(["export", str(result_file), "--gspro", server.address, "--timeout", "5"])
    captured = capsys.readouterr()
    assert_clean(captured, status, 3)
    assert f"nests more than {MAX_NESTING} levels deep" in captured.err


def test_a_servers_escape_sequences_never_reach_the_terminal(result_file, capsys):
    hostile = json.dumps({"Code": 501, "Message": HOSTILE}).encode()
    with FakeGSPro(lambda i: hostile) as server:
        status = main(["export", str(result_file), "--gspro", server.address, "--timeout", "5"])
    captured = capsys.readouterr()
    assert_clean(captured, status, 3)
    # said, escaped: the user sees what the server sent
    assert "\\x1b[2J" in captured.err and "\\x07" in captured.err and "\\r\\n" in captured.err
    assert len(captured.err.strip().splitlines()) == 1


def test_a_notices_player_names_are_escaped_too(result_file, capsys):
    notice = json.dumps({"Code": 201, "Message": "Player", "Player": {"Club": HOSTILE}}).encode()
    with FakeGSPro(lambda i: notice + OK) as server:
        status = main(["export", str(result_file), "--gspro", server.address, "--timeout", "5"])
    assert_clean(capsys.readouterr(), status, 0)


# ---- 4. replies paired with their shots; notices counted -----------------------------------------------------------

def _send(result_file, server, lines, settle=WAIT):
    from impactlab.io.gspro_connect import send_shots
    from impactlab.io.interchange import gspro_shots
    from impactlab.io.results import open_results

    host, port = server.address.split(":")
    return send_shots(gspro_shots(open_results(result_file)), host, int(port), timeout=WAIT, progress=lines.append,
                      settle=settle)


def test_a_stray_200_on_connect_is_set_aside_and_said(result_file):
    lines = []
    # the server closes after its second answer, so the client's wait for a late reply ends without a clock
    with FakeGSPro(lambda i: OK, greeting=b'{"Code":200}', close_after=2) as server:
        replies = _send(result_file, server, lines)
    assert len(server.messages) == 2 and len(replies) == 2
    # whether the stray came before shot 1 went out or was read as its answer (then shot 1's own 200 is the one
    # left over), one reply more than shots came, and it is set aside and said, never counted as an answer
    assert len(replies.set_aside) == 1
    assert sum("answers no shot sent, so it is set aside" in line for line in lines) == 1


def test_the_closing_line_says_replies_that_answered_no_shot(result_file, capsys):
    with FakeGSPro(lambda i: OK + b'{"Code":200}') as server:
        status = main(["export", str(result_file), "--gspro", server.address, "--timeout", "5"])
    captured = capsys.readouterr()
    assert_clean(captured, status, 0)
    assert "every one accepted" not in captured.err
    assert "2 more reply(ies) answered no shot (set aside, said above)" in captured.err


def test_a_second_200_after_each_shot_is_never_the_next_shots_answer(result_file):
    lines = []
    with FakeGSPro(lambda i: OK + b'{"Code":200}', close_after=2) as server:
        replies = _send(result_file, server, lines)
    # each shot is sent after its own answer came (the server saw both), the extra 200s set aside, one per shot
    assert len(server.messages) == 2 and len(replies) == 2
    assert len(replies.set_aside) == 2
    assert "before shot 2 of 2" in replies.set_aside[0] and "after the last shot" in replies.set_aside[1]
    assert sum("set aside" in line for line in lines) == 2


def test_a_flood_of_notices_is_counted_not_printed_line_by_line(result_file, capsys):
    flood = PLAYER * 5_000
    with FakeGSPro(lambda i: flood + OK) as server:
        status = main(["export", str(result_file), "--gspro", server.address, "--timeout", "5"])
    captured = capsys.readouterr()
    assert_clean(captured, status, 0)
    assert len(server.messages) == 2
    lines = captured.err.strip().splitlines()
    assert len(lines) <= 4, lines
    assert "10,000 notice(s) of its own" in captured.err and "10,000 x Code 201" in captured.err


# ---- 3. stored results are inputs: plot --trajectories and export check what they read ---------------------------

ALTERED = {
    "ball speed of 7e5 m/s": ({"ball_speed": [7e5, 55.46]}, {},
                              "ball_speed at model rigid_coulomb, face_angle -3.0: 1.56586e+06 mph; expected a "
                              "positive ball speed up to 300 mph"),
    "95 deg launch": ({"vertical_launch_angle": [95.0, 10.56]}, {}, "vertical_launch_angle at model rigid_coulomb, "
                                                                    "face_angle -3.0: 95 degree"),
    "rad on values in degrees": ({"vertical_launch_angle": ([10.55, 10.56], {"units": "rad"})}, {},
                                 "604.47 degree (10.55 rad as its units attribute states)"),
    "rad on a spin axis in degrees": ({"spin_axis": ([-1.5, 0.5], {"units": "rad"})}, {},
                                      "spin_axis at model rigid_coulomb, face_angle -3.0: -85.9437 deg, where its "
                                      "back and side spin tilt the axis -12.5"),
    "a units attribute of another quantity": ({"ball_speed": ([55.36, 55.46], {"units": "kg"})}, {},
                                              "ball_speed.units: expected a speed"),
    "air temperature 5000 K": ({}, {"air_temperature": 5000.0}, "the stored air, temperature: expected an air "
                                                                "temperature between -90 and 60 degC"),
    "a retired aerodynamic model": ({"carry_distance": ([164.1, 166.0], {"aerodynamic_model":
                                                                          "measured_fit_late_crisis"})}, {},
                                    "'measured_fit_late_crisis' was retired on 2026-11-24"),
    "an unknown aerodynamic model": ({"carry_distance": ([164.1, 166.0], {"aerodynamic_model": "x\x1b[2J"})}, {},
                                     "is not an aerodynamic model of this impactlab"),
}


@pytest.mark.parametrize("command", ["plot", "export"])
@pytest.mark.parametrize("case", list(ALTERED))
def test_an_altered_result_is_refused_with_the_reason(tmp_path, capsys, command, case):
    changes, scene, words = ALTERED[case]
    path = hand_result(tmp_path / "altered.h5", changes, scene)
    argv = (["plot", str(path), "--trajectories", "-o", str(tmp_path / "t.png")] if command == "plot" else
            ["export", str(path), "-o", str(tmp_path / "shots.json")])
    status = main(argv)
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert words in captured.err, captured.err
    assert not (tmp_path / "t.png").exists() and not (tmp_path / "shots.json").exists()


def test_a_refitted_models_fingerprint_is_said(tmp_path, capsys):
    path = hand_result(tmp_path / "old.h5", {"carry_distance": ([164.1, 166.0],
                                                                {"aerodynamic_fingerprint": "000000000000"})})
    status = main(["export", str(path), "-o", str(tmp_path / "shots.json")])
    captured = capsys.readouterr()
    assert_clean(captured, status, 0)
    assert "fingerprint 000000000000" in captured.err and "refitted" in captured.err


def test_a_figure_that_would_be_empty_is_said_not_drawn(tmp_path, capsys):
    path = hand_result(tmp_path / "nan.h5", {"spin_axis": [np.nan, np.nan]})
    status = main(["plot", str(path), "--trajectories", "-o", str(tmp_path / "t.png")])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert "spin_axis NaN in every case" in captured.err and "would be empty" in captured.err
    assert not (tmp_path / "t.png").exists()


# ---- 2. foreign text from files: a column header, a club name, a file name ---------------------------------------

def hostile_export(folder):
    """A shot table whose file name, a column header and a club name carry escape sequences and a bell."""
    path = folder / "ev\x1b[2Jil\x07.csv"
    path.write_text("Club,Ball Speed,Launch Angle,Spin Rate,Spin Axis,\x1b[2JEvil\x07 \u202eheader\n"
                    ",[mph],[deg],[rpm],[deg],[]\n"
                    "Driver\x1b[31m\x07,160,12,2600,1,1\nDriver,161,12,2700,1,1\n")
    return path


@pytest.mark.parametrize("command", ["shots", "fly"])
def test_escape_sequences_in_a_files_names_never_reach_the_terminal(tmp_path, capsys, command):
    status = main([command, str(hostile_export(tmp_path))])
    captured = capsys.readouterr()
    assert_clean(captured, status, 0)
    text = captured.out + captured.err
    assert "ev\\x1b[2Jil\\x07.csv" in text  # the file name, escaped: the user still sees what it is
    assert "Driver\\x1b[31m\\x07" in text  # the club name
    if command == "shots":
        assert "\\x1b[2JEvil\\x07 \\u202eheader" in text  # the unused column's header


def test_a_refusal_quoting_a_files_text_is_escaped(tmp_path, capsys):
    path = tmp_path / "bad\x1b[2J.yaml"
    path.write_text("name: t\x07\nball: {preset: \"urethane\x1b[31m\"}\n")
    status = main(["run", str(path), "--plan"])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert "bad\\x1b[2J.yaml" in captured.err


# ---- 5. options that change nothing are said; spec sheets within golf's ranges; examples in the usual unit ---------

SHEET = ("name: my driver\nnames: [My Driver]\nloft: 10.5 deg\nlie: 58 deg\nmass: 203 g\n"
         "moi: {up: 5200 g cm^2, toe: 2900 g cm^2, target: 4000 g cm^2}\ncg: {toe: 0 mm, high: 2 mm, depth: 38 mm}\n")
TABLE = ("Club,Club Speed [mph],Attack Angle [deg],Dyn. Loft [deg],Ball Speed [mph]\n"
         "Driver,110,2,13,163\n8 Iron,80,-4,30,105\n")


@pytest.mark.parametrize("command", ["shots", "validate", "fit"])
def test_a_club_sheet_matching_no_row_is_refused_by_name(tmp_path, capsys, command):
    sheet, table = tmp_path / "mine.yaml", tmp_path / "s.csv"
    sheet.write_text(SHEET)
    table.write_text(TABLE)
    argv = {"shots": ["shots", str(table)], "validate": ["validate", "--dataset", str(table), "--model",
                                                         "rigid_coulomb"],
            "fit": ["fit", str(table), "--model", "rigid_coulomb"]}[command]
    status = main([*argv, "--club", str(sheet)])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert (f"--club {sheet} (it answers to 'My Driver'): matches no row of" in captured.err
            and "would change nothing" in captured.err)
    assert re.search(r"its rows name '8[ _]iron', 'driver'", captured.err, flags=re.IGNORECASE)
    # the same sheet naming the table's club is taken (the check does not refuse a sheet that is used)
    sheet.write_text(SHEET.replace("[My Driver]", "[My Driver, Driver]"))
    if command == "shots":
        assert main([*argv, "--club", str(sheet)]) == 0
        capsys.readouterr()


@pytest.mark.parametrize("old, new, words", [
    # kg m^2 written where g cm^2 was meant: 10^7 times a driver's moment
    ("g cm^2", "kg m^2", "club.moi.toe: expected a moment of inertia between 50.75 and 64318.5 g cm^2 for this 203 "
                         "g head"),
    ("g cm^2", "mg mm^2", "club.moi.toe: expected a moment of inertia between"),
    ("mass: 203 g", "mass: 203 kg", "club.mass: expected a club-head mass between 50 and 1000 g"),
    ("depth: 38 mm", "depth: 38 cm", "club.cg.depth: expected a centre of mass inside the head"),
])
def test_a_spec_sheets_values_beyond_any_golf_head_are_refused_with_the_range(tmp_path, capsys, old, new, words):
    sheet, table = tmp_path / "mine.yaml", tmp_path / "s.csv"
    sheet.write_text(SHEET.replace(old, new).replace("[My Driver]", "[Driver]"))
    table.write_text(TABLE)
    status = main(["shots", str(table), "--club", str(sheet)])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert words in captured.err and f"{sheet}:" in captured.err


def test_the_moment_range_is_the_heads_mass_at_5_to_178_mm():
    from impactlab.scene.catalogue import CLUB_PRESETS
    from impactlab.study.club_specs import check_golf_ranges

    # hand-computed: 0.203 kg x (0.005 m)^2 = 5.075e-6 kg m^2 = 50.75 g cm^2; x (0.178 m)^2 = 6.432e-3 = 64318 g cm^2
    assert 0.203 * 0.005 ** 2 * 1e7 == pytest.approx(50.75)
    for head in CLUB_PRESETS.values():  # every catalogue club is a golf head and passes
        check_golf_ranges(head)


@pytest.mark.parametrize("argv, words", [
    (["fly", "--ball-speed", "160 mph", "--launch-angle", "12 deg", "--spin-rate", "2500 rpm", "--pressure", "1013"],
     "e.g. '1013 hPa'"),
])
def test_a_bare_air_pressures_example_is_in_hpa(capsys, argv, words):
    assert main(argv) == 2
    assert words in capsys.readouterr().err


def test_a_studys_bare_air_pressure_is_shown_in_hpa_and_a_modulus_in_mpa(tmp_path, capsys):
    study = tmp_path / "p.yaml"
    study.write_text("name: t\nball: {preset: urethane_tour}\nclub: {preset: driver}\ncontact: {friction: 0.4}\n"
                     "delivery: {club_speed: 100 mph, path: 0 deg, face_angle: 0 deg, attack_angle: 0 deg, "
                     "dynamic_loft: 12 deg}\nconditions: {pressure: 1013}\nmodels: [rigid_coulomb]\n"
                     "outputs: [ball_speed, carry_distance]\n")
    assert main(["run", str(study), "--plan"]) == 2
    err = capsys.readouterr().err
    assert "conditions.pressure: expected an air pressure with its unit, e.g. 1013 hPa or 101300 Pa" in err
    assert "MPa" not in err
    study.write_text(study.read_text().replace("conditions: {pressure: 1013}", "conditions: {altitude: 1500}"))
    assert main(["run", str(study), "--plan"]) == 2
    assert "conditions.altitude: expected an altitude with its unit, e.g. 1500 m" in capsys.readouterr().err


# ---- 4. never replace a file the user did not name as output of this kind; one size limit -------------------------

RAW_EXPORT = ("Club,Ball Speed,Launch Angle,Spin Rate,Spin Axis\n,[mph],[deg],[rpm],[deg]\n"
              "Driver,160,12,2600,1\nDriver,150,13,2800,-2\n")


@pytest.mark.parametrize("command", ["shots", "fly", "validate"])
def test_csv_aimed_at_a_raw_export_is_refused_unless_forced(tmp_path, capsys, command):
    session, other = tmp_path / "today.csv", tmp_path / "yesterday.csv"
    session.write_text(RAW_EXPORT)
    other.write_text(RAW_EXPORT.replace("160", "161"))  # the user's other raw export, the only copy
    table = tmp_path / "t.csv"
    table.write_text(TABLE)
    argv = {"shots": ["shots", str(session)], "fly": ["fly", str(session)],
            "validate": ["validate", "--dataset", str(table), "--model", "rigid_coulomb"]}[command]
    status = main([*argv, "--csv", str(other)])
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert "exists and is not a table impactlab wrote" in captured.err and "--force" in captured.err
    assert other.read_text() == RAW_EXPORT.replace("160", "161")  # untouched
    # a new file, then impactlab's own previous output, are written without --force; --force replaces the export
    fresh = tmp_path / "out.csv"
    assert main([*argv, "--csv", str(fresh)]) == 0
    assert main([*argv, "--csv", str(fresh)]) == 0
    assert main([*argv, "--csv", str(other), "--force"]) == 0
    assert other.read_text() == fresh.read_text()
    capsys.readouterr()


def test_impactlabs_own_tables_carry_the_marker_and_exports_do_not(tmp_path):
    from impactlab.io.safe_output import written_by_impactlab

    path = tmp_path / "x.csv"
    for header, own in (("line,label,club,ball_speed [m/s],flags", True),
                        ("table,shot,club,handedness,model,ball_speed measured [m/s]", True),
                        ("line,club,carry_distance [m],flagged", True), ("shot,carry_distance [m]", True),
                        ("Club,Ball Speed,Launch Angle", False),  # a vendor's export
                        ("club,ball_speed [mph]", False),  # a hand-written table in the vocabulary's names
                        ("line,label,Ball Speed [mph],flags", False)):
        path.write_text(header + "\n")
        assert written_by_impactlab(path) is own, header


def test_every_session_text_column_marks_impactlabs_own_table(tmp_path, capsys):
    # a text column added to the sessions (ball_setting, from TrackMan's Ball) once made 'shots --csv' refuse to
    # replace its own table from a TrackMan export: each text field must be a marker cell
    from impactlab.cli import main
    from impactlab.data.sessions.layouts import TEXT_FIELDS
    from impactlab.io.safe_output import written_by_impactlab

    path = tmp_path / "x.csv"
    path.write_text("line," + ",".join(TEXT_FIELDS) + ",ball_speed [m/s],flags\n")
    assert written_by_impactlab(path)
    out = tmp_path / "out.csv"
    export = Path(__file__).parent / "data" / "vendors" / "trackman_tps.csv"
    for _ in range(2):  # the second run replaces the table the first wrote
        assert main(["shots", str(export), "--csv", str(out)]) == 0
    assert "ball_setting" in out.read_text().splitlines()[0]
    capsys.readouterr()


def test_an_input_beyond_the_one_size_limit_is_refused_before_it_is_read(tmp_path, capsys):
    from impactlab.foreign import MAX_INPUT_BYTES

    path = tmp_path / "huge.csv"
    with open(path, "wb") as stream:  # a sparse file: its size is what is checked, before a byte is read
        stream.write(b"Club,Ball Speed\n")
        stream.truncate(MAX_INPUT_BYTES + 1)
    for argv in (["shots", str(path)], ["fly", str(path)], ["run", str(path.with_suffix(".yaml"))]):
        if argv[0] == "run":
            path.rename(path.with_suffix(".yaml"))
        status = main(argv)
        captured = capsys.readouterr()
        assert_clean(captured, status, 2)
        assert f"{MAX_INPUT_BYTES + 1:,} bytes (64 MiB) is too large" in captured.err
        assert "at most 67,108,864 bytes, 64 MiB" in captured.err


def test_a_file_of_repeated_rows_never_prints_a_line_per_row(tmp_path, capsys, monkeypatch):
    from impactlab.cli import fly_command

    monkeypatch.setattr(fly_command, "MAX_PRINTED_ROWS", 10)
    path = tmp_path / "copies.csv"
    path.write_text("Club,Ball Speed,Launch Angle,Spin Rate,Spin Axis\n,[mph],[deg],[rpm],[deg]\n"
                    + "Driver,160,12,2600,1\n" * 60)
    assert main(["fly", str(path)]) == 0
    out = capsys.readouterr().out
    rows = [line for line in out.splitlines() if re.match(r"^\| \d+ \| Driver", line)]
    assert len(rows) == 10 and "50 shot(s) not shown (--csv FILE writes every one)" in out
    assert "59 of 60 shot(s) repeat an earlier shot's launch exactly" in out


def test_a_result_attribute_nested_deep_is_refused_as_altered(tmp_path, capsys):
    path = hand_result(tmp_path / "deep.h5", attrs_changes={"plots": "[" * 50_000 + "]" * 50_000})
    for argv in (["show", str(path)], ["export", str(path), "-o", str(tmp_path / "s.json")]):
        status = main(argv)
        captured = capsys.readouterr()
        assert_clean(captured, status, 2)
        assert "its 'plots' attribute is not the JSON list" in captured.err
        assert f"nesting more than {MAX_NESTING} levels deep" in captured.err


def test_a_study_name_with_control_characters_names_no_file(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "n.yaml").write_text(
        'name: "t\\nimpactlab: error: forged\\e[2J"\nball: {preset: urethane_tour}\nface: {rigid: true}\n'
        "contact: {friction: 0.4, restitution: 0.8}\nimpact: {speed: 80 mph, angle: 15 deg}\n"
        "models: [rigid_coulomb]\noutputs: [ball_speed]\n")
    status = main(["run", "n.yaml", "-q"])
    assert_clean(capsys.readouterr(), status, 2)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["n.yaml"]


def test_show_prints_a_results_names_escaped(tmp_path, capsys):
    path = hand_result(tmp_path / "names.h5", attrs_changes={"models": json.dumps(
        [{"id": "rigid_coulomb", "name": "rigid\r\nimpactlab: error: forged\x1b[2J", "options": {}}])})
    status = main(["show", str(path)])
    captured = capsys.readouterr()
    assert_clean(captured, status, 0)
    assert "rigid\\r\\nimpactlab: error: forged\\x1b[2J" in captured.out


@pytest.mark.parametrize("reader", ["club spec", "shot table YAML", "study JSON"])
def test_every_structured_reader_bounds_its_nesting(tmp_path, capsys, reader):
    deep = "[" * 20_000 + "]" * 20_000
    table = tmp_path / "t.csv"
    table.write_text(TABLE)
    if reader == "club spec":
        (tmp_path / "c.yaml").write_text(f"name: x\nloft: {deep}\n")
        argv = ["shots", str(table), "--club", str(tmp_path / "c.yaml")]
    elif reader == "shot table YAML":
        (tmp_path / "rows.yaml").write_text(f"rows: {deep}\n")
        argv = ["validate", "--dataset", str(tmp_path / "rows.yaml")]
    else:  # JSON is YAML: a study written as JSON goes through the YAML reader's bound
        (tmp_path / "s.json").write_text('{"name": ' + deep + "}")
        argv = ["run", str(tmp_path / "s.json"), "--plan"]
    status = main(argv)
    captured = capsys.readouterr()
    assert_clean(captured, status, 2)
    assert f"nests more than {MAX_NESTING} levels deep" in captured.err


def test_argparses_own_messages_show_arguments_escaped(capsys):
    # a file name from a shell glob lands in argparse's 'unrecognized arguments' as given
    with pytest.raises(SystemExit) as stopped:
        main(["shots", "a.csv", "b\x1b[2J\r\nimpactlab: error: forged.csv"])
    captured = capsys.readouterr()
    assert stopped.value.code == 2
    assert raw_controls(captured.err) == [] and "b\\x1b[2J\\r\\nimpactlab: error: forged.csv" in captured.err


def test_the_terminal_guard_escapes_what_a_command_prints_and_keeps_a_progress_bars_return():
    import io

    from impactlab.foreign import TerminalGuard

    out, err = io.StringIO(), io.StringIO()
    TerminalGuard(out).write("a\x1b[2J\tb\r\n")
    TerminalGuard(err, keep_cr=True).write("50%|####\r")
    assert out.getvalue() == "a\\x1b[2J\tb\\r\n" and err.getvalue() == "50%|####\r"
