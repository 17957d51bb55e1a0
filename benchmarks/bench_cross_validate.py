"""Leave-one-source-out cross-validation against one fit, and ``impactlab fit --cross-validate`` on 100 shots.

The 100-shot table exists only here: the four cited TrackMan tour rows (trackman_tour.yaml), 25 copies of each
with stated Gaussian noise (seeded): delivery club speed 1 mph, attack angle and dynamic loft 0.5 deg; measured
ball speed 1 mph, launch 0.5 deg, spin 150 rpm (the table's stated sigma). It is a load for timing, not data.
Targets (issue 21): cross-validation at most 10x one fit; the command under 10 s.

    .venv/bin/python benchmarks/bench_cross_validate.py [--models hertz_mindlin rigid_coulomb]
"""

from __future__ import annotations

import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import yaml

from impactlab.data.fit.calibration import DEFAULT_PARAMETERS, calibrate, cross_validate
from impactlab.data.sessions.shots import read_shots
from impactlab.model.registry import get_model

NOISE = {"club_speed": 1.0, "attack_angle": 0.5, "dynamic_loft": 0.5, "ball_speed": 1.0,
         "vertical_launch_angle": 0.5, "spin_rate": 150.0}


def hundred_shots(path: Path, seed: int = 1) -> Path:
    source = Path(__file__).resolve().parents[1] / "impactlab/data/validation/trackman_tour.yaml"
    document = yaml.safe_load(source.read_text())
    rng = np.random.default_rng(seed)
    rows = []
    for row in document["rows"]:
        for copy in range(25):
            new = dict(row, label=f"{row['label']} #{copy + 1}")
            for key, sigma in NOISE.items():
                new[key] = round(float(row[key] + rng.normal(0.0, sigma)), 3)
            rows.append(new)
    document.update(name="trackman_tour_x100", rows=rows, budgets={},
                    source="benchmark load: trackman_tour.yaml's rows with seeded noise (not data)")
    path.write_text(yaml.safe_dump(document, sort_keys=False))
    return path


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--models", nargs="+", default=["hertz_mindlin", "rigid_coulomb"])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        path = hundred_shots(Path(folder) / "x100.yaml")
        table = read_shots(path)
        print(f"{table.size} shots, sources: {sorted(set(table.sources))}")
        for name in args.models:
            model = get_model(name)()
            names = [p for p in DEFAULT_PARAMETERS
                     if p != "tangential_loss" or "tangential_loss" in model.optional_inputs]
            calibrate(model, table.subset([0, 1]), names)  # compile / warm caches
            t0 = time.perf_counter()
            full = calibrate(model, table, names)
            one = time.perf_counter() - t0
            t0 = time.perf_counter()
            cross_validate(model, table, names, by="source", start=dict(zip(full.parameters, full.values)))
            warm = time.perf_counter() - t0
            t0 = time.perf_counter()
            cross_validate(model, table, names, by="source")
            cold = time.perf_counter() - t0
            print(f"{name:<14} one fit {one:6.2f} s; leave-one-source-out warm {warm:6.2f} s ({warm / one:4.1f}x one "
                  f"fit, target <= 10x), cold {cold:6.2f} s ({cold / one:4.1f}x)")
        command = [sys.executable, "-m", "impactlab", "fit", str(path), "--cross-validate"]
        for name in args.models:
            command += ["--model", name]
        # wall time is what the user waits; the child's CPU time (user + system) is what the command costs
        # when it has a core to itself (this machine is shared: the two part when other jobs load it)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run(command, check=True, capture_output=True)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        print(f"impactlab fit x100.yaml --cross-validate --model {' --model '.join(args.models)}: "
              f"{wall:.2f} s wall, {cpu:.2f} s CPU (target < 10 s; load average {os.getloadavg()[0]:.1f} "
              f"on {os.cpu_count()} cores)")


if __name__ == "__main__":
    main()
