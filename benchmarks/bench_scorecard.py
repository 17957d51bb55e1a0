"""The shared TrackMan session at scale (issue 32, Performance): reading it, the scorecard of every model and both
baselines, and ``fit`` with 5-fold cross-validation of rigid_coulomb and maw on 8,000 rows, in one run.

Goals on 2 cores: reading < 5 s of CPU; scorecard < 60 s; rigid_coulomb fit + 5 folds < 60 s; maw < 10 min. Each
step prints its CPU time (what it costs with a core to itself) and its wall time (what it took on this machine,
whose load average is printed: the machine is shared), and the peak memory of the process.

    .venv/bin/python benchmarks/bench_scorecard.py [FILE] [--maw-rows N]

FILE: the shared export (default: the copy shipped as the dataset ``trackman_driver_sessions``, as published); rows a
model cannot take are skipped by the reader. ``--maw-rows`` fits maw on fewer rows and
extrapolates to 8,000 (cost linear in rows: every fold evaluation predicts every row once), saying so.
"""

from __future__ import annotations

import argparse
import os
import resource
import time
import warnings

from impactlab.data.fit.calibration import DEFAULT_PARAMETERS, calibrate, cross_validate
from impactlab.data.sessions.reader import read_session
from impactlab.data.shot_report import SHOT_MODELS
from impactlab.data.validation.scorecard import format_scorecard, scorecard
from impactlab.data.validation.splits import folds
from impactlab.model.registry import get_model

#: the shared export as published, shipped with impactlab (impactlab.data.sessions.reader.DATASETS)
SHARED = "trackman_driver_sessions"
GOALS = {"read": 5.0, "scorecard": 60.0, "rigid_coulomb": 60.0, "maw": 600.0}


class Clock:
    """CPU (this process) and wall time of a block."""

    def __enter__(self):
        self.cpu, self.wall = time.process_time(), time.perf_counter()
        return self

    def __exit__(self, *exc):
        self.cpu = time.process_time() - self.cpu
        self.wall = time.perf_counter() - self.wall


def line(what: str, clock: Clock, goal: float, extra: str = "") -> str:
    verdict = "met" if clock.cpu < goal else f"MISSED by {clock.cpu / goal:.1f}x"
    return (f"{what:<44} CPU {clock.cpu:7.1f} s, wall {clock.wall:7.1f} s (goal < {goal:g} s of CPU: {verdict})"
            f"{extra}")


def fit_with_folds(name: str, table, k: int = 5) -> tuple[Clock, str]:
    model = get_model(name)()
    names = [p for p in DEFAULT_PARAMETERS if p != "tangential_loss" or "tangential_loss" in model.optional_inputs]
    with Clock() as clock:
        full = calibrate(model, table, names)
        by, parts = folds(table, k)
        held = cross_validate(model, table, names, folds=parts, start=dict(zip(full.parameters, full.values)))
    summary = ", ".join(f"{key} {value:.2f}" for key, value in held["summary"].items())
    return clock, f"{full.describe()}\n    {k}-fold by {by}, RMS on the rows not fitted: {summary}"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("file", nargs="?", default=str(SHARED))
    parser.add_argument("--rows", type=int, default=8000, help="rows of the fits (default 8,000)")
    parser.add_argument("--maw-rows", type=int, default=None, help="fit maw on this many rows and extrapolate")
    args = parser.parse_args()
    warnings.simplefilter("ignore")  # a session's unusual values are counted by the reader, not timed here
    print(f"{args.file}; {os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f} at the start")

    with Clock() as clock:
        session = read_session(args.file)
        table = session.shot_table()
    print(line(f"read {session.size} rows ({table.size} usable)", clock, GOALS["read"]))

    for name in SHOT_MODELS:  # numba compiles once per process: not the scorecard's cost
        get_model(name)()
    with Clock() as clock:
        card = scorecard(table, SHOT_MODELS)
    print(line("scorecard: 5 models + 2 baselines", clock, GOALS["scorecard"]))
    print(format_scorecard(card, breakdowns=False))

    rows = table.subset(range(min(args.rows, table.size)))
    clock, text = fit_with_folds("rigid_coulomb", rows)
    print(line(f"fit rigid_coulomb, {rows.size} rows + 5 folds", clock, GOALS["rigid_coulomb"]))
    print(f"    {text}")

    maw_rows = rows if args.maw_rows is None else table.subset(range(min(args.maw_rows, table.size)))
    clock, text = fit_with_folds("maw", maw_rows)
    if maw_rows.size == rows.size:
        print(line(f"fit maw, {rows.size} rows + 5 folds", clock, GOALS["maw"]))
    else:
        scale = rows.size / maw_rows.size
        estimate = Clock()
        estimate.cpu, estimate.wall = clock.cpu * scale, clock.wall * scale
        print(line(f"fit maw, {maw_rows.size} rows + 5 folds (measured)", clock, GOALS["maw"] / scale))
        print(line(f"fit maw, {rows.size} rows + 5 folds (EXTRAPOLATED x{scale:.1f})", estimate, GOALS["maw"]))
    print(f"    {text}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"peak memory {peak:.0f} MB; load average {os.getloadavg()[0]:.1f} at the end")


if __name__ == "__main__":
    main()
