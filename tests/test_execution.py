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
    assert {k: v for k, v in a.attrs.items() if k != "created"} == {k: v for k, v in b.attrs.items() if k != "created"}


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
