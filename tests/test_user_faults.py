"""Faults a user causes on the command line and in ``impactlab.fly``, injected one at a time (review trust7).

Each test asserts the exit status, the one message, no traceback, and that no file was written or damaged; the
oracle for a refused value is written out here (its range and why), not taken from the code.
"""

import errno
import hashlib
from pathlib import Path

import pytest

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
    study = tmp_path / "study.yaml"
    study.write_text(STUDY)
    session = tmp_path / "session.csv"
    session.write_bytes((VENDORS / "trackman_tps_drivers.csv").read_bytes())
    result = tmp_path / "result.h5"
    result.write_bytes(result_file.read_bytes())
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
    old = tmp_path / "old.png"
    old.write_bytes(b"an old result named .png")
    code, err = cli(capsys, "run", study, "-o", old, "--plot", old)
    assert code == 2 and "is the file read" in err
    assert old.read_bytes() == b"an old result named .png"


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
