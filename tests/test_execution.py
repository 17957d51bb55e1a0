"""Executors give identical results; chunks join exactly; a killed run resumes to the same result."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import impactlab

STUDY = {"name": "exec", "ball": {"preset": "urethane_tour"}, "face": {"preset": "steel"},
         "contact": {"friction": 0.4, "restitution": 0.8}, "impact": {"speed": "40 m/s", "angle": "20 deg"},
         "sweep": {"impact.angle": {"start": "2 deg", "stop": "60 deg", "num": 30}, "contact.friction": [0.1, 0.3, 0.5],
                   "ball.inertia_factor": [0.1, 0.4]},
         "models": ["maw", {"name": "maw", "id": "hyst", "inelastic": "hysteretic"}, "rigid_coulomb"],
         "outputs": ["launch_ratio", "spin_rate", "tangential_restitution"]}


def same(a, b):
    xr.testing.assert_identical(a.drop_attrs(), b.drop_attrs())
    stamped = ("created", "history")  # the time of the run, and the CF history line that carries it
    assert {k: v for k, v in a.attrs.items() if k not in stamped} == {k: v for k, v in b.attrs.items()
                                                                       if k not in stamped}


@pytest.fixture(scope="module")
def serial():
    return impactlab.run_study(STUDY, executor="serial", chunk_size=10_000)


@pytest.mark.slow
def test_small_chunks_join_to_the_same_result(serial):
    same(impactlab.run_study(STUDY, executor="serial", chunk_size=7), serial)


@pytest.mark.slow
def test_processes_give_identical_results(serial):
    same(impactlab.run_study(STUDY, executor="processes", workers=2, chunk_size=40), serial)


@pytest.mark.slow
def test_dask_local_cluster_gives_identical_results(serial):
    pytest.importorskip("dask.distributed")
    same(impactlab.run_study(STUDY, executor="dask", workers=2, chunk_size=50), serial)


@pytest.mark.slow
def test_saved_chunks_are_reused(tmp_path, serial, monkeypatch):
    folder = tmp_path / "progress"
    impactlab.run_study(STUDY, executor="serial", chunk_size=20, progress_folder=folder)
    saved = sorted(p.name for p in folder.glob("*.npz"))
    assert len(saved) == 3 * 9  # 3 models x 180 cases / 20
    from impactlab.run import execution

    def refuse(*args, **kwargs):
        raise AssertionError("a saved chunk was computed again")

    monkeypatch.setattr(execution, "compute_chunk", refuse)
    same(impactlab.run_study(STUDY, executor="serial", chunk_size=20, progress_folder=folder), serial)


@pytest.mark.slow
def test_progress_of_another_study_is_discarded(tmp_path):
    folder = tmp_path / "progress"
    impactlab.run_study(STUDY, executor="serial", chunk_size=60, progress_folder=folder)
    other = dict(STUDY, contact={"friction": 0.2, "restitution": 0.8})
    messages = []
    result = impactlab.run_study(other, executor="serial", chunk_size=60, progress_folder=folder,
                                 progress=messages.append)
    assert any("different study" in text for text in messages)
    same(result, impactlab.run_study(other, executor="serial"))


BIG = """name: resumable
ball: {preset: urethane_tour}
face: {preset: steel}
contact: {friction: 0.4, restitution: 0.8}
impact: {speed: 40 m/s, angle: 20 deg}
sweep:
  impact.angle: {start: 1 deg, stop: 60 deg, num: 200}
  contact.friction: {start: 0.1, stop: 0.5, num: 20}
models: [{name: maw, tolerance: 2.0e-5}]
outputs: [launch_ratio, spin_rate]
"""


@pytest.mark.slow
def test_a_killed_run_resumes_to_the_identical_result(tmp_path):
    study = tmp_path / "big.yaml"
    study.write_text(BIG)
    out = tmp_path / "big.h5"
    progress = Path(f"{out}.progress")
    command = [sys.executable, "-m", "impactlab", "run", str(study), "-o", str(out), "--executor", "serial",
               "--chunk-size", "100", "-q"]
    process = subprocess.Popen(command, stderr=subprocess.PIPE)
    deadline = time.time() + 120
    while time.time() < deadline and len(list(progress.glob("*.npz"))) < 3:
        time.sleep(0.05)
    os.kill(process.pid, signal.SIGKILL)
    process.wait()
    done_before = len(list(progress.glob("*.npz")))
    assert 3 <= done_before < 40, "the run should have been killed half way"
    assert not out.exists()
    resumed = subprocess.run(command, capture_output=True, text=True)
    assert resumed.returncode == 0, resumed.stderr
    assert not progress.exists()  # cleaned up once the result is written
    fresh = tmp_path / "fresh.h5"
    subprocess.run([sys.executable, "-m", "impactlab", "run", str(study), "-o", str(fresh), "--executor", "serial",
                    "-q"], check=True)
    same(impactlab.open_results(out), impactlab.open_results(fresh))
    assert np.all(np.isfinite(impactlab.open_results(out).launch_ratio.values))


GOLF = {"name": "once", "ball": {"preset": "tour_urethane"}, "club": {"preset": "driver"},
        "delivery": {"club_speed": "100 mph", "attack_angle": "-1 deg", "dynamic_loft": "13 deg"},
        "sweep": {"strike.toe": ["-10 mm", "0 mm", "10 mm"], "delivery.club_speed": ["90 mph", "110 mph"]},
        "models": ["rigid_coulomb", "restitution", "maw"], "outputs": ["ball_speed", "spin_rate", "spin_axis"]}


@pytest.mark.slow
def test_a_run_checks_limits_plans_models_and_builds_the_contact_state_once(tmp_path, monkeypatch):
    """Limits once per study, each model planned once per study, the 3x3 mobility once per chunk (serial: shared
    by the models), and the ball's restitution from the approach speeds alone; results bit-identical to each
    model computed on its own (planned by itself, its own contact state)."""
    import yaml

    from impactlab.cli import main
    from impactlab.model import case_inputs as batch_module
    from impactlab.model.base import ImpactModel
    from impactlab.physics import contact
    from impactlab.run import rules_test
    from impactlab.run import runner as runner_module
    from impactlab.run.runner import case_input_names, case_inputs
    from impactlab.study import limits

    study = impactlab.load_study(GOLF)
    inputs = case_inputs(study)
    assert case_input_names(study) == set(inputs) and "restitution" in inputs  # the ball's law applies
    alone = {entry.id: entry.model.compute(inputs, GOLF["outputs"]) for entry in study.models}

    counts = {"check": 0, "plan": 0, "mobility": 0}
    real_check, real_plan, real_state = limits.check, ImpactModel.plan, contact.contact_state

    def check(*args, **kwargs):
        counts["check"] += 1
        return real_check(*args, **kwargs)

    # the Rules' COR test each model runs once on the study's driver (impactlab.run.rules_test) is a computation of
    # its own, outside the run's chunks: its plans and contact states are counted apart
    inside_cor_test: list[int] = []
    real_cor = rules_test.simulated_cor

    def cor(*args, **kwargs):
        inside_cor_test.append(1)
        try:
            return real_cor(*args, **kwargs)
        finally:
            inside_cor_test.pop()

    def plan(self, *args, **kwargs):
        key = "cor_test_plan" if inside_cor_test else "plan"
        counts[key] = counts.get(key, 0) + 1
        return real_plan(self, *args, **kwargs)

    def state(inputs, mobility=True):
        key = "cor_test_mobility" if inside_cor_test else "mobility"
        counts[key] = counts.get(key, 0) + bool(mobility)
        return real_state(inputs, mobility)

    monkeypatch.setattr(limits, "check", check)
    monkeypatch.setattr(runner_module, "check", check)  # the runner's own name for it (imported at its top)
    monkeypatch.setattr(ImpactModel, "plan", plan)
    monkeypatch.setattr(rules_test, "simulated_cor", cor)
    monkeypatch.setattr(contact, "contact_state", state)
    monkeypatch.setattr(batch_module, "contact_state", state)
    path = tmp_path / "once.yaml"
    path.write_text(yaml.safe_dump(GOLF, sort_keys=False))
    out = tmp_path / "once.h5"
    assert main(["run", str(path), "-o", str(out), "-q", "--executor", "serial", "--chunk-size", "4"]) == 0
    # 6 cases in chunks of 4: two chunks; and one COR test per model
    assert counts == {"check": 1, "plan": 3, "mobility": 2, "cor_test_plan": 3, "cor_test_mobility": 3}
    result = impactlab.open_results(out)
    for entry in study.models:
        for name in GOLF["outputs"]:
            np.testing.assert_array_equal(result[name].sel(model=entry.id).values.reshape(-1),
                                          alone[entry.id][name].values)


@pytest.mark.parametrize("tty", [True, False])
def test_the_progress_bar_redraws_on_a_terminal_and_writes_tenths_to_a_log(monkeypatch, tty):
    import io

    from impactlab.run.execution import Progress

    class Stream(io.StringIO):
        def isatty(self):
            return tty

    stream = Stream()
    monkeypatch.setattr("sys.stderr", stream)
    progress = Progress(1000, enabled=True)
    for _ in range(100):
        progress.advance(10)
    progress.close()
    text = stream.getvalue()
    assert "1000/1000" in text and "cases" in text
    if tty:
        assert "\r" in text  # redrawn in place
    else:  # a log: whole lines, no carriage return
        assert "\r" not in text and len(text.splitlines()) == 11  # the first chunk, then every tenth
    quiet = Stream()
    monkeypatch.setattr("sys.stderr", quiet)
    silent = Progress(1000, enabled=False)
    silent.advance(1000)
    silent.close()
    assert quiet.getvalue() == ""
