"""The command line: runs, lists, shows, plots; bad input exits 2 with one message and no traceback."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from impactlab.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "studies" / "compare_models.yaml"


def run_cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "impactlab", *map(str, args)], capture_output=True, text=True,
                          cwd=cwd, env={**os.environ, "MPLBACKEND": "Agg"})


def small_study(tmp_path, **replace):
    text = EXAMPLE.read_text().replace("num: 60", "num: 4")
    for old, new in replace.items():
        text = text.replace(old, new)
    path = tmp_path / "study.yaml"
    path.write_text(text)
    return path


@pytest.mark.slow
def test_run_show_and_plot(tmp_path, capsys, drawn_figures):
    study = small_study(tmp_path)
    out, png = tmp_path / "r.h5", tmp_path / "r.png"
    assert main(["run", str(study), "-o", str(out), "--plot", str(png), "-q"]) == 0
    assert out.is_file()
    figure = next(f for f in drawn_figures if f["path"] == png)
    assert not figure["problems"] and figure["ink"] > 0.02
    # one panel per output, labelled in words and units; a line per model and friction, none of them empty
    labels = [panel["ylabel"].replace("\n", " ") for panel in figure["panels"]]
    assert any(label.startswith("launch ratio") and label.endswith("[1]") for label in labels)
    assert all(np.isfinite(ys).any() for panel in figure["panels"] for _, ys in panel["lines"].values())
    assert "mph" in figure["title"]  # the conditions are in the title
    assert main(["show", str(out)]) == 0
    shown = capsys.readouterr().out
    assert "compare-models" in shown and "launch_ratio" in shown and "maw, rigid_coulomb, restitution" in shown
    assert main(["plot", str(out), "-o", str(tmp_path / "again.png"), "-v", "launch_ratio"]) == 0


def test_plan_is_printed_without_running(tmp_path, capsys):
    assert main(["run", str(small_study(tmp_path)), "--plan", "-o", str(tmp_path / "never.h5")]) == 0
    text = capsys.readouterr().out
    assert "12 case(s) x 3 model(s)" in text and "derives" in text
    assert not (tmp_path / "never.h5").exists()


def test_models_lists_needs_and_provides(capsys):
    assert main(["models"]) == 0
    text = capsys.readouterr().out
    for name in ("maw", "rigid_coulomb", "restitution"):
        assert f"{name}:" in text
    assert "requires:" in text and "ball.youngs_modulus" in text


@pytest.mark.parametrize("replace, fragment", [
    ({"poisson_ratio: 0.45": "poisson_ratio: 0.7"}, "ball.poisson_ratio: expected a Poisson ratio"),
    ({"- name: maw": "- name: mow"}, "models[0].name: expected a registered model, got mow"),
    ({"radius: 21.335 mm": "radius: -1 mm"}, "ball.radius: expected a positive"),
])
def test_bad_input_exits_2_with_one_message_and_leaves_results_alone(tmp_path, replace, fragment, capsys):
    # in-process: main() returns the exit code and an uncaught exception would fail the test (no traceback
    # can slip through); the subprocess adds nothing but a second of imports (one test below keeps it)
    study = small_study(tmp_path, **replace)
    existing = tmp_path / "keep.h5"
    existing.write_bytes(b"previous results")
    assert main(["run", str(study), "-o", str(existing)]) == 2
    error = capsys.readouterr().err
    assert fragment in error
    assert len(error.strip().splitlines()) == 1
    assert existing.read_bytes() == b"previous results"


def test_missing_file_and_unwritable_output(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.yaml")]) == 2
    assert "no such study file" in capsys.readouterr().err
    assert main(["run", str(small_study(tmp_path)), "-o", str(tmp_path / "no" / "such" / "dir.h5")]) == 2
    assert "does not exist" in capsys.readouterr().err


@pytest.mark.slow
def test_the_installed_entry_point_reports_bad_input_without_a_traceback(tmp_path):
    # the one check that needs a real process: python -m impactlab, its exit status and its stderr
    result = run_cli("run", tmp_path / "nope.yaml")
    assert result.returncode == 2 and "no such study file" in result.stderr and "Traceback" not in result.stderr


@pytest.mark.slow
def test_plot_redraws_the_figures_a_study_declares(tmp_path, drawn_figures):
    study = ROOT / "studies" / "paper" / "fig7_tangential_force.yaml"
    out = tmp_path / "fig7.h5"
    assert main(["run", str(study), "-o", str(out), "-q"]) == 0
    assert main(["plot", str(out)]) == 0
    drawn = sorted(path.name for path in tmp_path.glob("*.png"))
    assert drawn == ["fig7_fig7.png", "fig7_fig7_annuli.png", "fig7_stick_radius.png"]
    assert all(not figure["problems"] and figure["ink"] > 0.02 for figure in drawn_figures)
    stick = next(f for f in drawn_figures if f["path"].name == "fig7_stick_radius.png")["panels"][0]
    assert "[mm]" in stick["ylabel"]  # a contact radius in millimetres, not metres
    # the stuck radius never exceeds the Hertz contact radius sqrt(R delta_max), about 10 mm at 80 mph
    assert max(np.nanmax(ys) for _, ys in stick["lines"].values()) < 11.0


@pytest.mark.slow
def test_validity_notes_are_one_line_per_run_and_listed_in_full_on_request(tmp_path):
    # a golf-like study raises the same two known notes every run: one line with their count, not both in full
    study = small_study(tmp_path, **{"youngs_modulus: 136 MPa": "youngs_modulus: 5 MPa"})
    out = tmp_path / "soft.h5"
    result = run_cli("run", study, "-o", out)
    assert result.returncode == 0
    lines = [line for line in result.stderr.splitlines() if line.startswith("impactlab:")]
    assert lines == [f"impactlab: 2 validity note(s) on {out} (cases outside a model's assumptions); "
                     f"`impactlab show {out}` lists them, or run with --notes"]
    full = [
        "maw: in 12 of 12 case(s) the contact radius exceeds 0.3 R, where Hertz's paraboloid misses the sphere's "
        "surface by more than 2 % at the contact edge (golf impacts reach 0.38-0.56 R: 4-9 %)",
        "maw: in 12 of 12 case(s) the normal-tangential coupling the model neglects (ball and face differ in "
        "Dundurs' beta) is estimated to change the tangential impulse by more than the tolerance asked for "
        "(output coupling_estimate; docs/models.md)"]
    noted = run_cli("run", study, "-o", tmp_path / "again.h5", "--notes")
    assert [line for line in noted.stderr.splitlines() if line.startswith("impactlab:")] == \
        [f"impactlab: note: {text}" for text in full]
    shown = run_cli("show", out)
    assert shown.returncode == 0 and all(f"  {text}" in shown.stdout.splitlines() for text in full)
