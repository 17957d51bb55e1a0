"""Faults a user causes on the command line and in ``impactlab.fly``, injected one at a time (review trust7).

Each test asserts the exit status, the one message, no traceback, and that no file was written or damaged; the
oracle for a refused value is written out here (its range and why), not taken from the code.
"""

import errno
import hashlib
import json
from pathlib import Path

import numpy as np
import pytest

import impactlab
import impactlab.errors
import impactlab.run.faults
import impactlab.units
from impactlab.cli import main

ROOT = Path(__file__).resolve().parents[1]
VENDORS = ROOT / "tests" / "data" / "vendors"
STUDY = (ROOT / "studies" / "compare_models.yaml").read_text().replace("num: 60", "num: 3")


def cli(capsys, *args):
    """Run the command line in this process: (exit status, stderr); never a traceback."""
    code = main([str(arg) for arg in args])
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code, err


def digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@pytest.fixture(scope="module")
def result_file(tmp_path_factory):
    """A small result of a golf delivery study (export and plot read it)."""
    folder = tmp_path_factory.mktemp("result")
    study = folder / "golf.yaml"
    study.write_text(
        "name: golf\nball: {preset: urethane_tour}\nface: {preset: steel, mass: 200 g}\n"
        "contact: {friction: 0.4, restitution: 0.78}\n"
        "delivery: {club_speed: 90 mph, attack_angle: -4 deg, dynamic_loft: 24 deg, path: 1 deg, face_angle: 0 deg}\n"
        "sweep: {delivery.face_angle: [-3 deg, 3 deg]}\nmodels: [rigid_coulomb]\n"
        "outputs: [ball_speed, vertical_launch_angle, horizontal_launch_angle, spin_rate, spin_axis]\n")
    assert main(["run", str(study), "-o", str(folder / "golf.h5"), "-q"]) == 0
    return folder / "golf.h5"


# -- an output never replaces a file the command reads ---------------------------------------------------------
def _users_files(folder, result_file, export: str):
    """A user's study, session export (a copy of the fixture ``export``) and result file in ``folder``."""
    study = folder / "study.yaml"
    study.write_text(STUDY)
    session = folder / "session.csv"
    session.write_bytes((VENDORS / export).read_bytes())
    result = folder / "result.h5"
    result.write_bytes(result_file.read_bytes())
    return study, session, result


@pytest.mark.parametrize("command", [
    ["run", "{study}", "-o", "{study}"],
    ["run", "{study}", "-o", "./{study_name}"],
    ["convergence", "{study}", "-o", "{study}", "--repeats", "1"],
    ["validate", "--dataset", "{session}", "--csv", "{session}", "--model", "rigid_coulomb"],
    ["fit", "{session}", "--json", "{session}", "--model", "rigid_coulomb"],
    ["export", "{result}", "-o", "{result}"],
    ["paper", "{result_folder}", "-o", "{result}"],
    ["validate", "--dataset", "{session}", "--csv", "{club}", "--club", "{club}", "--model", "rigid_coulomb"],
])
def test_an_output_naming_a_file_the_command_reads_is_refused_and_the_file_kept(
        tmp_path, capsys, monkeypatch, result_file, command):
    """Before: each of these replaced the user's study, session or result by the output, exit 0 (the only copy
    of a session or of an hour's result lost to a typo); `fly` and `shots` were the only commands that checked."""
    monkeypatch.chdir(tmp_path)
    study, session, result = _users_files(tmp_path, result_file, "trackman_tps_drivers.csv")
    club = tmp_path / "driver.yaml"
    club.write_text("name: my driver\nnames: [Driver]\nbase: driver\n")
    kept = {path: digest(path) for path in (study, session, result, club)}
    before = set(tmp_path.iterdir())
    args = [part.format(study=study, study_name=study.name, session=session, result=result, club=club,
                        result_folder=tmp_path) for part in command]
    code, err = cli(capsys, *args)
    assert code == 2
    assert "is the file read" in err and "writing there would replace it: give another name" in err
    assert len(err.strip().splitlines()) == 1
    assert {path: digest(path) for path in kept} == kept
    assert set(tmp_path.iterdir()) == before  # nothing written beside them either


def test_a_picture_naming_the_result_or_the_study_is_refused_before_the_run(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("impactlab.cli.study_commands.run_study",
                        lambda *a, **k: pytest.fail("computed before refusing"))
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    old = tmp_path / "old.h5"
    old.write_bytes(b"an old result")
    code, err = cli(capsys, "run", study, "-o", old, "--plot", old)
    assert code == 2 and "is the file read" in err
    assert old.read_bytes() == b"an old result"


# -- a picture is a picture ----------------------------------------------------------------------------------
@pytest.mark.parametrize("command", [
    ["plot", "{result}", "-o", "{tmp}/figure.h5"],
    ["plot", "{result}", "-o", "{tmp}/figure"],
    ["run", "{study}", "-o", "{tmp}/r.h5", "--plot", "{tmp}/r.yaml"],
    ["validate", "--dataset", "{session}", "--plot", "{tmp}/shots.csv", "--model", "rigid_coulomb"],
])
def test_a_picture_name_without_a_picture_suffix_is_bad_input_before_any_work(tmp_path, capsys, result_file,
                                                                               command):
    """Before: `plot -o figure.h5` and `run --plot r.yaml` ran, then ended in 'internal error: ValueError: Format
    'h5' is not supported' (exit 1, as a bug); `validate --plot shots.csv` wrote a PNG named .csv."""
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    args = [part.format(result=result_file, tmp=tmp_path, study=study, session=VENDORS / "trackman_tps.csv")
            for part in command]
    before = set(tmp_path.iterdir())
    code, err = cli(capsys, *args)
    assert code == 2 and "expected a file name ending in .png" in err and "internal error" not in err
    assert set(tmp_path.iterdir()) == before


def test_a_picture_is_written_atomically_a_full_disk_keeps_the_old_one(tmp_path, capsys, result_file,
                                                                       monkeypatch):
    """Before: figures were saved by matplotlib straight into the target, so a full disk (or an interrupt)
    mid-write left a truncated picture where the old one was."""
    picture = tmp_path / "ratio.png"
    picture.write_bytes(b"the old picture")

    def full_disk(*args):
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr("impactlab.io.safe_output.os.fsync", full_disk)
    code, err = cli(capsys, "plot", result_file, "-v", "ball_speed", "-o", picture)
    assert code == 3 and "the disk is full" in err
    assert picture.read_bytes() == b"the old picture"
    assert [path.name for path in tmp_path.iterdir()] == ["ratio.png"]  # no temporary left
    monkeypatch.undo()
    code, err = cli(capsys, "plot", result_file, "-v", "ball_speed", "-o", tmp_path / "ratio.svg")
    assert code == 0 and (tmp_path / "ratio.svg").read_text().lstrip().startswith("<?xml")


# -- impactlab.fly: a value no golf shot has, and a plain number read as SI ---------------------------------------
LAUNCH = {"ball_speed": "167 mph", "launch_angle": "10.9 deg", "spin_rate": "2686 rpm"}


@pytest.mark.parametrize("changes, path, says", [
    # 3 rad = 171.9 deg: the README's spin_axis="3 deg" written as a plain 3 flew a ball with topspin to 73 m, silently
    ({"spin_axis": 3}, "spin_axis", "got 171.887 deg (a number is SI: 3 rad; with a unit, e.g. '3 deg')"),
    ({"spin_axis": ["3 deg", "95 deg"]}, "spin_axis[1]", "got 95 deg"),
    ({"spin_axis": "-90.5 deg"}, "spin_axis", "got -90.5 deg"),
    # a launch 172 deg off the target line was carried 232 m with an offline of 33 m
    ({"launch_direction": 3.0}, "launch_direction", "got 171.887 deg (a number is SI: 3 rad"),
    ({"launch_direction": "90 deg"}, "launch_direction", "got 90 deg"),
    ({"launch_angle": 15}, "launch_angle", "got 859.437 deg (a number is SI: 15 rad; with a unit, e.g. '15 deg')"),
])
def test_a_launch_angle_no_golf_shot_has_is_refused_and_a_plain_number_is_said_to_be_si(changes, path, says):
    with pytest.raises(impactlab.FieldError) as caught:
        impactlab.fly(**{**LAUNCH, **changes})
    assert caught.value.path == path and says in str(caught.value)


def test_the_limits_of_the_angles_are_flown():
    """+-90 deg of spin axis is pure side spin, a real (if wild) shot; 89 deg of launch direction is a shank."""
    shots = impactlab.fly(**{**LAUNCH, "spin_axis": ["90 deg", "-90 deg"], "launch_direction": "89 deg"})
    assert np.all(np.isfinite(shots.carry_distance.values))
    # pure side spin lifts nothing: in a vacuum of lift the ball curves as far right as left
    offline = shots.offline_distance.values
    assert offline[0] > offline[1]


@pytest.mark.parametrize("changes, words", [
    ({"ball_speed": 110}, "ball_speed: 246.063 mph (a number is SI: 110 m/s) is unusual for golf"),
    ({"spin_rate": 1300}, "spin_rate: 12414.1 rpm (a number is SI: 1300 rad/s) is unusual for golf"),
    ({"ball_speed": "250 mph"}, "ball_speed: 250 mph is unusual for golf"),
])
def test_a_launch_beyond_measured_golf_shots_is_flown_and_said(changes, words):
    """Beyond the fastest ball speeds measured, about 225 mph (150 mph of club speed, the fastest measured, at a
    smash factor of 1.5), or spins above about 12 000 rpm: flown, and a PlausibilityWarning says so."""
    with pytest.warns(impactlab.errors.PlausibilityWarning) as caught:
        shots = impactlab.fly(**{**LAUNCH, **changes})
    assert any(words in str(warning.message) for warning in caught)
    assert np.isfinite(float(shots.carry_distance))


@pytest.mark.parametrize("changes, path, says", [
    # 167 meant as mph and 2686 meant as rpm, given as plain numbers (SI), flew silently at 373 mph and 25 650 rpm
    ({"ball_speed": 167}, "ball_speed", "expected a ball speed up to 300 mph (200 mph of club speed, which no swing "
                                        "reaches, at the largest smash factor the Rules' COR limit allows, 1.49), got "
                                        "373.568 mph (a number is SI: 167 m/s)"),
    ({"spin_rate": 2686}, "spin_rate", "expected a spin rate up to 20,000 rpm (golf balls leave a club with at most "
                                       "about 12,000 rpm), got 25649.4 rpm (a number is SI: 2686 rad/s)"),
    ({"ball_speed": ["150 mph", "1000 mph"]}, "ball_speed[1]", "got 1000 mph"),
])
def test_a_launch_speed_or_spin_no_golf_shot_has_is_refused(changes, path, says):
    """The limits are the project's own: 200 mph of club speed, refused in a golf scene, times the largest smash
    factor the COR limit 0.83 allows with a 200 g head, (1 + 0.83) / (1 + 45.93 / 200) = 1.488 (298 mph); spin
    beyond 20,000 rpm, refused as a golf scene's incoming spin."""
    assert (1 + 0.83) / (1 + 45.93 / 200) * 200 == pytest.approx(297.6, abs=0.1)
    with pytest.raises(impactlab.FieldError) as caught:
        impactlab.fly(**{**LAUNCH, **changes})
    assert caught.value.path == path and says in str(caught.value)


def test_a_launch_golf_shots_have_is_flown_without_a_word(recwarn):
    impactlab.fly(ball_speed=["100 mph", "220 mph"], launch_angle="12 deg", spin_rate=["11900 rpm", "2000 rpm"])
    assert not [w for w in recwarn if issubclass(w.category, impactlab.errors.PlausibilityWarning)]


@pytest.mark.parametrize("option, given, says", [
    ("--spin-axis", "95 deg", "--spin-axis: expected a spin axis between -90 and 90 deg (beyond, the ball has "
                              "topspin), got 95 deg"),
    ("--launch-direction", "180 deg", "--launch-direction: expected a launch direction between -90 and 90 deg"),
    # 1013 Pa for 1013 hPa flew an almost airless ball 231 yd (276 yd in air) without a word
    ("--pressure", "1013 Pa", "got 1013 Pa (given as '1013 Pa')"),
    ("--pressure", "1013 mmHg", "got 135056 Pa"),  # 1013 x 133.322 Pa
    # 77 degF written as degC flew in 77 degC air; 70 degC flew too
    ("--temperature", "70 degC", "got 343.15 K (given as '70 degC')"),
    ("--temperature", "-95 degC", "got 178.15 K"),
])
def test_fly_refuses_what_no_shot_or_air_has_in_one_line(capsys, option, given, says):
    code, err = cli(capsys, "fly", "--ball-speed", "167 mph", "--launch-angle", "10.9 deg", "--spin-rate", "2686 rpm",
                    option, given)
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1
    assert "a number is SI" not in err  # the user typed a unit: no word about plain numbers


@pytest.mark.parametrize("air", [{"pressure": "226 hPa"}, {"pressure": "1099 hPa"}, {"temperature": "59 degC"},
                                 {"temperature": "-89 degC"}, {"altitude": "10999 m"}])
def test_the_air_at_the_edges_of_its_ranges_is_flown(air):
    assert np.isfinite(float(impactlab.fly(**LAUNCH, conditions=air).carry_distance))


def test_fly_warns_by_the_option_the_user_typed(capsys):
    code, err = cli(capsys, "fly", "--ball-speed", "250 mph", "--launch-angle", "10.9 deg", "--spin-rate", "2686 rpm")
    assert code == 0
    assert "impactlab: warning: --ball-speed: 250 mph is unusual for golf" in err and "a number is SI" not in err


def test_a_session_row_with_an_impossible_angle_is_not_flown_and_says_its_line(tmp_path, capsys):
    """A spin axis of 95 deg (a session whose back spin is not given, so the topspin check could not see it) was
    flown to -43.5 % of the monitor's carry and counted in the session's mean and RMS; a launch direction of
    120 deg was flown to a carry. A launch angle in the wrong unit ([rad] for degrees) was refused as
    '--launch-angle[0]', an option the user never typed, without the file's line."""
    table = tmp_path / "shots.csv"
    table.write_text("club,Ball Speed [mph],Launch Angle [deg],Spin Rate [rpm],Carry [yd],Spin Axis [deg],"
                     "Launch Direction [deg]\n"
                     "Driver,167,10.9,2686,250,95,0\n"
                     "Driver,167,10.9,2686,250,3,120\n"
                     "Driver,167,10.9,2686,270,3,1\n")
    out = tmp_path / "flown.csv"
    code, err = cli(capsys, "fly", table, "--csv", out)
    assert code == 0
    rows = out.read_text().splitlines()
    assert len(rows) == 2 and rows[1].startswith("4,")  # only line 4 flown
    radians = tmp_path / "rad.csv"
    radians.write_text("club,Ball Speed [mph],Launch Angle [rad],Spin Rate [rpm],Carry [yd]\n"
                       "Driver,167,10.9,2686,250\n")
    code, err = cli(capsys, "fly", radians)
    assert code == 2 and "--launch-angle" not in err and len(err.strip().splitlines()) == 1
    assert f"{radians}:2: Launch Angle [rad] beyond any golf shot (-90 to 90 deg)" in err
    code, err = cli(capsys, "fly", radians, "--strict")  # --strict names the value, in degrees
    assert code == 2 and "Launch Angle [rad] beyond any golf shot (-90 to 90 deg): 624.5" in err


def test_a_session_says_each_unusual_value_at_its_line(tmp_path, capsys):
    table = tmp_path / "shots.csv"
    table.write_text("club,Ball Speed [mph],Launch Angle [deg],Spin Rate [rpm]\nDriver,167,10.9,2686\n"
                     "Driver,240,10.9,2686\nDriver,1e308,10.9,2686\nDriver,167,10.9,1e30\n")
    code = main(["fly", str(table)])
    printed, err = capsys.readouterr()
    assert code == 0 and "Traceback" not in err
    # unusual values are counted per column and reason, one line each, with the line (issue 32), not warned per row
    assert "unusual, used as given: Ball Speed [mph]: unusual for golf (above 223.694 mph): 1 row(s) (first line 3)" \
        in printed and "warning" not in err
    # before: flown (a spin of 1e30 rpm to a carry of 155 yd, counted in the session's mean and RMS)
    assert "Ball Speed [mph] beyond any golf shot (above 300 mph): 1 row(s) (first line 4)" in printed
    assert "Spin Rate [rpm] beyond any golf shot (above 20000 rpm): 1 row(s) (first line 5)" in printed
    assert "model against the monitor" not in printed and "| 5 |" not in printed and "| 4 |" not in printed


def test_a_studys_air_is_held_to_the_same_ranges_at_its_line(tmp_path, capsys):
    study = tmp_path / "air.yaml"
    study.write_text("name: air\nball: {preset: urethane_tour}\nclub: {preset: driver}\ncontact: {friction: 0.4}\n"
                     "delivery: {club_speed: 100 mph, path: 0 deg, face_angle: 0 deg, attack_angle: 0 deg, "
                     "dynamic_loft: 12 deg}\nconditions: {pressure: 1013 hPa}\n"
                     "sweep: {conditions.temperature: [0 degC, 30 degC, 80 degC]}\nmodels: [rigid_coulomb]\n"
                     "outputs: [carry_distance]\n")
    code, err = cli(capsys, "run", study, "-o", tmp_path / "air.h5")
    assert code == 2 and f"{study}:7: sweep.conditions.temperature[2]: expected an air temperature between -90 and " \
                          "60 degC" in err and err.rstrip().endswith("got 80 degC")
    assert not (tmp_path / "air.h5").exists()


# -- a unit symbol read one way and meant another -----------------------------------------------------------------
@pytest.mark.parametrize("text", ["200 gr", "45.93 gr", "4000 gr*cm**2"])
def test_gr_is_refused_never_read_as_grains(text):
    """pint reads gr as the grain (64.79891 mg); gr is the gram's abbreviation in French, Spanish, Italian...: a
    club head of '200 gr' was read as 12.96 g, a ball of '45.93 gr' as 2.98 g, without a word."""
    with pytest.raises(impactlab.FieldError, match="gr is a grain .* write g .grams. or grain"):
        impactlab.units.to_si(text, "mass", "club.mass")
    assert impactlab.units.to_si("200 grain", "mass") == pytest.approx(200 * 64.79891e-6)  # spelt out: read
    assert impactlab.units.to_si("200 g", "mass") == pytest.approx(0.2)


def test_a_study_with_a_mass_in_gr_is_refused_at_its_line(tmp_path, capsys):
    study = tmp_path / "gr.yaml"
    study.write_text(STUDY.replace("mass: 45.93 g,", "mass: 45.93 gr,", 1))
    assert "45.93 gr" in study.read_text()
    code, err = cli(capsys, "run", study, "-o", tmp_path / "gr.h5")
    assert code == 2 and "ball.mass: expected a mass" in err and "gr is a grain" in err
    assert not (tmp_path / "gr.h5").exists()


# -- permissions: reading is not writing ------------------------------------------------------------------------
def test_a_file_the_user_may_not_read_is_said_so_not_to_choose_a_writable_folder(tmp_path, capsys, monkeypatch):
    """Before: `impactlab shots session.csv` on a file without read permission said 'permission denied: choose a
    folder you can write to' (exit 3), the advice for an output. (Root reads any file, so the permission is
    injected: the reader is refused, and os.access answers as for a file mode 000.)"""
    session = tmp_path / "session.csv"
    session.write_bytes((VENDORS / "trackman_tps.csv").read_bytes())

    def refuse(*args, **kwargs):
        raise PermissionError(errno.EACCES, "Permission denied", str(session))

    real_access = impactlab.run.faults.os.access
    monkeypatch.setattr("impactlab.run.faults.os.access",
                        lambda path, mode: False if str(path) == str(session) else real_access(path, mode))
    monkeypatch.setattr("impactlab.data.sessions.reader.read_session", refuse)
    monkeypatch.setattr("impactlab.cli.data_commands.read_session", refuse)
    code, err = cli(capsys, "shots", session)
    assert code == 3
    assert err.strip() == f"impactlab: error: {session}: permission denied: you may not read it; check its " \
                          "permissions (ls -l) or copy it somewhere you can"


def test_a_folder_the_user_may_not_enter_is_named(tmp_path, monkeypatch):
    from impactlab.run.faults import describe_os_error

    folder = tmp_path / "private"
    folder.mkdir()
    real_access = impactlab.run.faults.os.access
    monkeypatch.setattr("impactlab.run.faults.os.access",
                        lambda path, mode: False if str(path) == str(folder) else real_access(path, mode))
    text = describe_os_error(PermissionError(errno.EACCES, "Permission denied", str(folder / "x.h5")))
    assert text == f"{folder / 'x.h5'}: permission denied: you may not enter the folder {folder}; check its " \
                   "permissions (ls -ld)"
    # an output folder the user may enter but not write keeps the advice for outputs
    text = describe_os_error(PermissionError(errno.EACCES, "Permission denied", str(tmp_path / "new.h5")))
    assert text.endswith("permission denied: choose a folder you can write to")


# -- messages in the user's units and words -----------------------------------------------------------------------
def test_a_swept_range_value_refused_is_shown_in_the_users_unit(tmp_path, capsys):
    """A range's values are made in SI: 'got 1.5746419675196301' for the 57th of 1..95 deg read as 1.57 deg."""
    study = tmp_path / "s.yaml"
    study.write_text(STUDY.replace("{start: 1 deg, stop: 60 deg, num: 3}", "{start: 1 deg, stop: 95 deg, num: 3}"))
    assert "stop: 95 deg" in study.read_text()
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5")
    # the third value is 95 deg = 1.65806 rad
    assert code == 2 and err.rstrip().endswith("sweep.impact.angle[2]: expected an angle between -90 and 90 deg "
                                               "(for impact.angle), got 95 deg (1.65806 rad)")


@pytest.mark.parametrize("text, says", [
    ("", "got an empty document (nothing but comments or blank lines)"),
    ("# only a comment\n", "got an empty document"),
    ("- a\n- b\n", "got a list (['a', 'b'])"),
])
def test_a_file_that_holds_no_study_says_what_it_holds_in_words(tmp_path, capsys, text, says):
    """Before: 'got NoneType' for an empty file, 'got list': Python's type names."""
    study = tmp_path / "s.yaml"
    study.write_text(text)
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5")
    assert code == 2 and says in err and "NoneType" not in err


def test_a_bare_nan_shows_an_example_worth_writing(tmp_path, capsys):
    study = tmp_path / "s.yaml"
    study.write_text(STUDY.replace("speed: 80 mph", "speed: .nan"))
    assert "speed: .nan" in study.read_text()
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5")
    assert code == 2 and "e.g. 1 mph or 0.44704 m/s" in err and "e.g. nan" not in err


@pytest.mark.parametrize("option, given, example", [
    ("--humidity", "0.6", "'60 %'"), ("--humidity", "60", "'60 %'"), ("--temperature", "25", "'25 degC'"),
    ("--pressure", "1013", "'1013 hPa'"), ("--spin-axis", "3", "'3 deg'"),
])
def test_fly_refuses_a_number_alone_without_offering_si(capsys, option, given, example):
    """Before: '--humidity: ... a number as text has no unit (write e.g. '50 %', or a number in SI), got 0.6', and
    --temperature 'a number in K': on the command line every value is text and a number alone is never read."""
    code, err = cli(capsys, "fly", "--ball-speed", "167 mph", "--launch-angle", "10.9 deg", "--spin-rate", "2686 rpm",
                    option, given)
    assert code == 2 and f"{option}: expected" in err and f"e.g. {example}" in err
    assert "in SI" not in err and "a number in" not in err and len(err.strip().splitlines()) == 1


# -- two options that contradict each other: one was dropped without a word ---------------------------------------
@pytest.mark.parametrize("command, says", [
    # the result went to -o, --outdir was created empty and ignored
    (["run", "{study}", "-o", "{tmp}/x.h5", "--outdir", "{tmp}/out"], "-o names the result file, --outdir the folder"),
    # the scheduler overrode the explicit serial executor
    (["run", "{study}", "-o", "{tmp}/x.h5", "--executor", "serial", "--scheduler", "127.0.0.1:1"],
     "--scheduler runs the cases on a dask cluster, --executor serial here: give one"),
    (["run", "{study}", "-o", "{tmp}/x.h5", "--executor", "serial", "--workers", "4"],
     "--workers counts worker processes, and --executor serial runs in this one"),
    # a plain fit was made, the cross-validation asked for silently not
    (["fit", "wood2018", "--cross-validate"], "--cross-validate: for shot tables, and wood2018 is a validation "
                                               "dataset of published values (impactlab validate lists them); leave "
                                               "it out"),
    (["fit", "{session}", "--by", "row", "--model", "rigid_coulomb"],
     "--by row says what the cross-validation leaves out; add --cross-validate"),
    # exit 0 and no picture: the figure draws shot tables only
    (["validate", "--dataset", "wood2018", "--plot", "{tmp}/p.png"], "--plot: no shot table was validated"),
])
def test_contradicting_options_are_refused_not_one_dropped(tmp_path, capsys, monkeypatch, command, says):
    monkeypatch.setattr("impactlab.cli.study_commands.run_study",
                        lambda *a, **k: pytest.fail("computed before refusing"))
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    args = [part.format(study=study, tmp=tmp_path, session=VENDORS / "trackman_tps_drivers.csv") for part in command]
    code, err = cli(capsys, *args)
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1
    assert sorted(path.name for path in tmp_path.iterdir()) == ["study.yaml"]


def test_a_range_of_one_value_between_two_ends_is_refused(tmp_path, capsys):
    """{start: 1 deg, stop: 60 deg, num: 1} ran one case at 1 deg: the stop written was dropped without a word."""
    study = tmp_path / "s.yaml"
    study.write_text(STUDY.replace("{start: 1 deg, stop: 60 deg, num: 3}", "{start: 1 deg, stop: 60 deg, num: 1}"))
    assert "num: 1}" in study.read_text()
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5")
    assert code == 2 and "sweep.impact.angle.num: expected 2 or more values from start to stop (num: 1 keeps " \
                          "start and drops stop" in err
    assert not (tmp_path / "s.h5").exists()
    study.write_text(STUDY.replace("{start: 1 deg, stop: 60 deg, num: 3}", "{start: 1 deg, stop: 1 deg, num: 1}"))
    assert cli(capsys, "run", study, "-o", tmp_path / "s.h5", "-q")[0] == 0  # one value, said once: read


# -- an interrupt says what it kept ---------------------------------------------------------------------------
@pytest.mark.parametrize("finished", [False, True])
def test_an_interrupt_says_whether_chunks_were_kept(tmp_path, capsys, monkeypatch, finished):
    """Before: Ctrl-C before the first chunk finished said 'finished chunks are kept in R.h5.progress: run the
    same command again', of a folder the run had just removed (it keeps only real progress)."""
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    output = tmp_path / "r.h5"

    def interrupted(*args, **kwargs):
        folder = kwargs["progress_folder"]
        if finished:  # a chunk saved before the interrupt, as the runner saves it
            folder.mkdir()
            (folder / "m0-c0-3.npz").write_bytes(b"a chunk")
        raise KeyboardInterrupt

    monkeypatch.setattr("impactlab.cli.study_commands.run_study", interrupted)
    code, err = cli(capsys, "run", study, "-o", output, "-q")
    assert code == 130 and not output.exists()
    if finished:
        assert f"interrupted; finished chunks are kept in {output}.progress: run the same command again" in err
    else:
        assert "interrupted; no chunk had finished and no result file was written or changed" in err
        assert "kept in" not in err


def test_validate_refuses_a_model_it_would_ignore(capsys):
    """`validate --dataset wood2018 --model nonsense` printed every model and exited 0: --model chooses the models
    compared on shot tables, and a dataset's table shows its study's; an unknown name was never checked."""
    code, err = cli(capsys, "validate", "--dataset", "wood2018", "--model", "nonsense")
    assert code == 2 and "--model: expected a registered model, got nonsense. Choices: dem_linear" in err
    code, err = cli(capsys, "validate", "--dataset", "wood2018", "--model", "maw")
    assert code == 2 and "--model maw: chooses the models compared on shot tables, and none was validated" in err


@pytest.mark.parametrize("timeout", ["1e12", "3601"])
def test_a_timeout_too_long_for_a_socket_is_bad_input_not_an_internal_error(result_file, capsys, timeout):
    """--timeout 1e12 passed the check (> 0, finite), then the socket's timeout overflowed the platform's time_t:
    'internal error: OverflowError', exit 1, and a socket left open."""
    with pytest.raises(SystemExit) as stopped:
        main(["export", str(result_file), "--gspro", "127.0.0.1:1", "--timeout", timeout])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "--timeout: expected a number of seconds > 0 and at most 3600" in err
    assert "internal error" not in err


# -- what a study asks for and will not get -------------------------------------------------------------------
def test_an_output_no_model_can_give_and_air_nothing_reads_are_said_before_the_run(tmp_path, capsys):
    """A study of a ball fired at a plate that asks for carry_distance ran and exited 0 with the carry NaN for
    every model (only --plan and the file's attribute said why); a conditions block without a flight output was
    read and never used. Both still run (the file says the same), and each is said once, before the run."""
    study = tmp_path / "s.yaml"
    study.write_text(STUDY.replace("outputs: [", "conditions: {temperature: 30 degC}\noutputs: [carry_distance, ", 1))
    assert "outputs: [carry_distance, " in study.read_text()
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5", "-q")
    assert code == 0
    assert f"impactlab: warning: {study}: carry_distance will be NaN for every model (needs a golf delivery" in err
    assert "conditions (the air) are read only by the flight outputs" not in err  # carry_distance reads them
    study.write_text(STUDY.replace("outputs: [", "conditions: {temperature: 30 degC}\noutputs: [", 1))
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5", "-q")
    assert code == 0 and f"impactlab: warning: {study}: its conditions (the air) are read only by the flight " \
                          "outputs" in err
    study.write_text(STUDY)
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5", "-q")
    assert code == 0 and "warning" not in err


def test_a_magnitude_below_zero_is_shown_in_the_files_unit(tmp_path, capsys):
    """Before: 'got -67.056 (SI)' for a row's -150 mph, read as -67 in the file's mph."""
    table = tmp_path / "shots.csv"
    table.write_text("club,Ball Speed [mph],Launch Angle [deg],Spin Rate [rpm]\nDriver,-150,12,2500\n")
    code, err = cli(capsys, "fly", table)
    assert code == 2 and f"{table}:2: Ball Speed [mph] below 0 (a magnitude)" in err
    code, err = cli(capsys, "fly", table, "--strict")  # the value, in the file's unit
    assert code == 2 and err.rstrip().endswith(f"{table}:2: Ball Speed [mph] below 0 (a magnitude): -150")


def test_validates_table_header_keeps_its_columns_apart(capsys):
    """'launch angle [deg]launch direction [deg]': a 22-character name filled its 22-character column."""
    assert main(["validate", "--dataset", str(VENDORS / "trackman_tps.csv"), "--model", "rigid_coulomb"]) == 0
    header = next(line for line in capsys.readouterr().out.splitlines() if "RMS error" in line)
    assert "]l" not in header and "] " in header
    assert header.split("RMS error")[1].split() == ["ball_speed", "[%]", "launch", "angle", "[deg]", "launch",
                                                     "direction", "[deg]", "spin", "[%]", "spin", "axis", "[deg]"]


# -- a club spec sheet (--club) ---------------------------------------------------------------------------------
SHEET = ("name: my driver\nnames: [Driver, 1w]\nloft: 10.5 deg\nlie: 58 deg\nmass: 203 g\n"
         "moi: {up: 5200 g cm^2, toe: 2900 g cm^2, target: 4000 g cm^2}\ncg: {toe: 0 mm, high: 2 mm, depth: 38 mm}\n"
         "bulge: 305 mm\nroll: 254 mm\nface: titanium\n")


@pytest.mark.parametrize("old, new, says", [
    # before: 'loft: expected a static loft between 0 and 90 deg, got 1.6580627893946132' (radians), no line
    ("loft: 10.5 deg", "loft: 95 deg", "{sheet}:3: club.loft: expected a static loft between 0 and 90 deg, got 95 deg"),
    # before: 'mass: ... got -0.203', no line
    ("mass: 203 g", "mass: -203 g", "{sheet}:5: club.mass: expected a positive, finite head mass in kg, got -203 g"),
    # before: 'got None'
    (SHEET, "", "{sheet}: club: expected a mapping of club spec keys"),
])
def test_a_club_sheets_refused_value_is_named_at_its_line_as_written(tmp_path, capsys, old, new, says):
    sheet = tmp_path / "driver.yaml"
    sheet.write_text(SHEET.replace(old, new))
    code, err = cli(capsys, "validate", "--dataset", VENDORS / "trackman_tps_drivers.csv", "--club", sheet,
                    "--model", "rigid_coulomb")
    assert code == 2 and says.format(sheet=sheet) in err and "None" not in err


@pytest.mark.parametrize("ball, says", [
    ("radius: 2 m", "ball.radius: expected a golf ball's radius between 10 and 45 mm"),
    ("mass: 45.93 kg", "ball.mass: expected a golf ball's mass between 10 and 100 g"),
])
def test_a_golf_scene_refuses_a_ball_no_club_strikes(tmp_path, capsys, ball, says):
    """A 2 m ball struck by a driver ran and exited 0 (a golf scene judged the club and the delivery, not the
    ball). The Rules' ball is at least 42.67 mm across and at most 45.93 g (R&A/USGA Equipment Rules, Part 3)."""
    study = tmp_path / "g.yaml"
    study.write_text(f"name: g\nball: {{preset: urethane_tour, {ball}}}\nclub: {{preset: driver}}\n"
                     "contact: {friction: 0.4}\ndelivery: {club_speed: 100 mph, path: 0 deg, face_angle: 0 deg, "
                     "attack_angle: 0 deg, dynamic_loft: 12 deg}\nmodels: [rigid_coulomb]\noutputs: [ball_speed]\n")
    code, err = cli(capsys, "run", study, "-o", tmp_path / "g.h5")
    assert code == 2 and f"{study}:2: {says}" in err
    assert not (tmp_path / "g.h5").exists()


@pytest.mark.parametrize("changes, path, says", [
    # 21.335 meant as mm is 21.335 m: a 43 m ball, flown to NaN without a word
    ({"ball_radius": 21.335}, "ball_radius", "got 21335 mm (a number is SI: 21.335 m)"),
    ({"ball_mass": 45.93}, "ball_mass", "got 45930 g (a number is SI: 45.93 kg)"),
    ({"ball_radius": "2 m"}, "ball_radius", "got 2000 mm"),
])
def test_fly_refuses_a_ball_no_club_strikes(changes, path, says):
    with pytest.raises(impactlab.FieldError) as caught:
        impactlab.fly(**LAUNCH, **changes)
    assert caught.value.path == path
    assert "between 10 and 45 mm" in str(caught.value) or "between 10 and 100 g" in str(caught.value)
    assert says in str(caught.value)
    assert np.isfinite(float(impactlab.fly(**LAUNCH, ball_radius="21.335 mm", ball_mass="45.93 g").carry_distance))


# -- the command line's own parsing errors -------------------------------------------------------------------------
@pytest.mark.parametrize("args, says", [
    (["fly", "--model", "measured_fitt"], "impactlab: error: fly: argument --model: invalid choice: 'measured_fitt' "
                                          "(choose from"),
    (["run", "--executor", "seriall", "x.yaml"], "(did you mean 'serial'?); see `impactlab run --help`"),
    (["frobnicate"], "impactlab: error: argument command: invalid choice: 'frobnicate'"),
    (["run"], "impactlab: error: run: the following arguments are required: study; see `impactlab run --help`"),
])
def test_a_command_line_argparse_refuses_is_one_line_like_every_other_error(capsys, args, says):
    """Before: argparse's usage block (14 lines for fly, its model choices twice) then 'impactlab fly: error: ...',
    where every other failure is one 'impactlab: error: ...' line; and no closest choice for a typo."""
    with pytest.raises(SystemExit) as stopped:
        main(args)
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and says in err and len(err.strip().splitlines()) == 1
    assert err.startswith("impactlab: error: ") and "usage:" not in err
    if args[:2] == ["fly", "--model"]:
        assert "(did you mean 'measured_fit'?)" in err


def test_a_foreign_hdf5_file_is_refused_by_its_attributes_before_its_data_are_read(tmp_path, capsys, monkeypatch):
    """Before: every dataset of another program's HDF5 file was loaded into memory, then refused (a big file
    first filled the memory), with h5netcdf's 'phony_dims' warning printed on the way."""
    import h5py
    import xarray as xr

    foreign = tmp_path / "other.h5"
    with h5py.File(foreign, "w") as handle:
        handle["samples"] = np.arange(16.0)
    monkeypatch.setattr(xr.Dataset, "load", lambda self, **kw: pytest.fail("data read before the refusal"))
    code, err = cli(capsys, "export", foreign, "-o", tmp_path / "shots.json")
    assert code == 2 and err.strip() == (f"impactlab: error: {foreign}: not an impactlab result (an HDF5/netCDF file "
                                         "without the impactlab_version attribute every impactlab result carries); "
                                         "give a file written by impactlab run")


@pytest.mark.parametrize("tolerances, says", [
    # before: 'tolerance: expected a tolerance between 1e-9 and 0.1, got 0.16666666666666666' (5 / 30, never typed)
    (["5"], "argument --tolerances: expected a tolerance between 1.2e-07 and 0.1"),
    (["1e-8"], "the reference runs at a 120th of the finest), got 1e-8"),  # its reference 8.3e-11 < 1e-9
    # before: run, with two ladder points at one coordinate
    (["1e-3", "1e-3"], "--tolerances: each value once (a ladder point per tolerance), got 0.001 twice"),
])
def test_convergence_refuses_a_ladder_it_cannot_run_by_the_values_typed(tmp_path, capsys, tolerances, says):
    study = tmp_path / "s.yaml"
    study.write_text(STUDY)
    try:
        code = main(["convergence", str(study), "-o", str(tmp_path / "w.h5"), "--repeats", "1", "--tolerances",
                     *tolerances])
    except SystemExit as stopped:
        code = stopped.code
    err = capsys.readouterr().err
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "w.h5").exists()


def test_a_declared_plot_of_one_output_the_study_lacks_names_that_output(tmp_path, capsys):
    """Before: 'plots[0].y[0]: expected an output the study computes, got c' for y: contact_time (the first
    letter: the value at y[0], read back from the file, of a string)."""
    study = tmp_path / "s.yaml"
    study.write_text(STUDY + "plots:\n  - {name: f, y: contact_time, x: angle}\n")
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5")
    assert code == 2 and "plots[0].y: expected an output the study computes, got contact_time. Choices:" in err


# -- encodings --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("encoding", ["utf-16-le", "utf-16-be"])
def test_utf16_without_its_mark_is_named_not_called_binary(tmp_path, capsys, encoding):
    """Windows tools save UTF-16 without a byte-order mark: a study so saved was 'a binary file (it holds NUL
    bytes)', and `validate --dataset` on a measured-data YAML so saved printed PyYAML's two-line 'unacceptable
    character #x0000'. Each is now 'is UTF-16 text without a byte-order mark; save ... as UTF-8'."""
    study = tmp_path / "s.yaml"
    study.write_bytes(STUDY.encode(encoding))
    code, err = cli(capsys, "run", study, "-o", tmp_path / "s.h5")
    assert code == 2 and err.strip() == f"impactlab: error: {study}: is UTF-16 text without a byte-order mark; " \
                                        "save the study file as UTF-8"
    measured = tmp_path / "measured.yaml"
    measured.write_bytes("name: mine\nquantity: launch_ratio\n".encode(encoding))
    code, err = cli(capsys, "validate", "--dataset", measured)
    assert code == 2 and "is UTF-16 text without a byte-order mark" in err and len(err.strip().splitlines()) == 1


def test_a_binary_file_with_many_zeros_is_still_binary(tmp_path, capsys, result_file):
    """An HDF5 result given as a study has zeros in every other byte of its header: it is not UTF-16 text."""
    code, err = cli(capsys, "run", result_file, "--plan")
    assert code == 2 and "is a binary file (it holds NUL bytes), not a YAML study file" in err


def test_a_control_character_in_yaml_is_one_line(tmp_path, capsys):
    study = tmp_path / "s.yaml"
    study.write_text('name: x\nkey: "a\x01b"\n')
    code, err = cli(capsys, "run", study)
    assert code == 2 and "not valid YAML: unacceptable character #x0001" in err and len(err.strip().splitlines()) == 1


# -- an output's suffix says what is written -----------------------------------------------------------------------
@pytest.mark.parametrize("command, says", [
    # an HDF5 result into the user's session export (not an input of this command): replaced, exit 0
    (["run", "{study}", "-o", "{session}"], "(result file): expected a file name ending in .h5 or .hdf5"),
    (["export", "{result}", "-o", "{session}"], "(shot file): expected a file name ending in .json"),
    (["fly", "--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--csv", "{result}"],
     "(--csv file): expected a file name ending in .csv or .txt"),
    (["fit", "wood2018", "--json", "{session}"], "(--json file): expected a file name ending in .json"),
    (["paper", "{tmp}", "-o", "{session}"], "(report): expected a file name ending in .md"),
])
def test_an_output_whose_suffix_names_another_kind_of_file_is_refused(tmp_path, capsys, result_file, command, says):
    study, session, result = _users_files(tmp_path, result_file, "trackman_tps.csv")
    kept = {path: digest(path) for path in (study, session, result)}
    args = [part.format(study=study, session=session, result=result, tmp=tmp_path) for part in command]
    code, err = cli(capsys, *args)
    assert code == 2 and says in err and len(err.strip().splitlines()) == 1
    assert {path: digest(path) for path in kept} == kept


def test_a_negative_value_written_without_a_space_is_explained(capsys):
    """'--spin-axis -3deg' reads as an option named -3deg: argparse said only 'expected at least one argument'."""
    with pytest.raises(SystemExit) as stopped:
        main(["fly", "--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--spin-axis",
              "-3deg"])
    err = capsys.readouterr().err
    assert stopped.value.code == 2 and "a value starting with '-' reads as an option: join it with '=', " \
                                      "--spin-axis=-VALUE, or write a space before its unit" in err
    assert main(["fly", "--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm",
                 "--spin-axis=-3deg"]) == 0


def test_export_reads_each_ball_output_in_its_own_units(result_file, tmp_path, capsys):
    """A result edited with xarray (ball speed converted to mph, spin to deg/s, their units attributes with them)
    was read as m/s and rpm: 100 mph went to GSPro as 224 mph, without a word. Carry and the club data already
    read their units; the ball now does too (a unit of the wrong kind is refused)."""
    from impactlab.io.results import write_results

    original = impactlab.open_results(result_file)
    edited = original.copy()
    edited["ball_speed"] = original.ball_speed / 0.44704
    edited["ball_speed"].attrs = dict(original.ball_speed.attrs, units="mph")
    edited["spin_rate"] = original.spin_rate * 6.0  # 1 rpm = 6 deg/s
    edited["spin_rate"].attrs = dict(original.spin_rate.attrs, units="deg/s")
    write_results(edited, tmp_path / "edited.h5")
    shots = {}
    for name, path in (("original", result_file), ("edited", tmp_path / "edited.h5")):
        assert main(["export", str(path), "-o", str(tmp_path / f"{name}.json")]) == 0
        shots[name] = json.loads((tmp_path / f"{name}.json").read_text())
    assert [shot["BallData"] for shot in shots["edited"]] == [shot["BallData"] for shot in shots["original"]]
    speed = float(original.ball_speed.values.ravel()[0]) / 0.44704
    assert shots["edited"][0]["BallData"]["Speed"] == pytest.approx(speed, abs=0.01)
    edited["vertical_launch_angle"].attrs["units"] = "mph"
    write_results(edited, tmp_path / "wrong.h5")
    code, err = cli(capsys, "export", tmp_path / "wrong.h5", "-o", tmp_path / "u.json")
    assert code == 2 and "vertical_launch_angle.units: expected an angle" in err and "mph is not an angle unit" in err
    assert not (tmp_path / "u.json").exists()
