"""What the framework costs around the physics, measured in one run (issue: the framework gets out of the way).

Prints, each as a ratio of times measured here and now:
- ``run_study`` end to end (load, plan, compute, assemble) against the models' hooks alone on a 540-case
  Fig.-6-sized sweep (target: within 1.2x);
- one case through ``ImpactModel.compute`` (and ``compute_arrays``) against its hook (target: within 3x);
- loading a study with 10^5 swept values (target: under a second).

- with ``--large``: a 10^6-case study end to end (serial and on every core) against its hooks (minutes).

Run: ``python benchmarks/bench_framework.py [--large]``. Times are the best of several repeats (the machine is shared).
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

import impactlab
from impactlab.model.case_inputs import CaseInputs
from impactlab.model.derive import derive
from impactlab.study.arrays import case_inputs
from impactlab.study.core import load_study

STUDY = """
name: bench-540
ball: {preset: urethane_tour}
face: {preset: steel}
contact: {friction: 0.4, restitution: 0.8}
impact: {speed: 80 mph, angle: 20 deg}
sweep:
  impact.angle: {start: 1 deg, stop: 60 deg, num: 60}
  contact.friction: [0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5]
models: [maw, rigid_coulomb, restitution]
outputs: [launch_angle, spin_rate, tangential_restitution]
"""


def best(function, repeats: int = 7) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def best_pair(first, second, repeats: int = 25) -> tuple[float, float]:
    """Best times of two functions timed in turn, so that a load on the shared machine meets both alike."""
    times = ([], [])
    for _ in range(repeats):
        for function, kept in zip((first, second), times):
            start = time.perf_counter()
            function()
            kept.append(time.perf_counter() - start)
    return min(times[0]), min(times[1])


def hooks(study, with_derivation: bool = False, chunk: int | None = None) -> None:
    """The models' own work: each hook asked for what the study's plan asks of it (impulses and the stability
    report the model computes itself). The batch is fresh, so the contact state is built here, once per chunk,
    as in a serial run (where the models share it): it is physics, counted on this side.

    ``with_derivation``: also the physics of rule 6, the launch conditions from each model's impulses
    (:func:`impactlab.model.derive.derive`, plain array functions of impactlab.physics.contact). ``chunk``: cases
    per batch, as the serial executor splits a large study (default: all at once).
    """
    inputs = case_inputs(study)
    batch = CaseInputs(inputs, copy=False)  # the study's own arrays, as the serial executor takes them
    plans = [entry.model.plan(study.all_outputs, inputs) for entry in study.models]
    size = chunk or study.n_cases
    for first in range(0, study.n_cases, size):
        part = batch.slice(first, min(first + size, study.n_cases))
        for entry, plan in zip(study.models, plans):
            model = entry.model
            raw = model._compute(part.only(model.requires | model.optional_inputs), plan.from_model)
            if with_derivation:
                derive(plan.derived, raw, part)


def main() -> None:
    import warnings

    from impactlab.model.diagnostics import ValidityWarning

    warnings.simplefilter("ignore", ValidityWarning)  # the golf cases' large-contact flags, once per repeat
    study = load_study(STUDY)
    impactlab.run_study(study)  # warm-up: compiled kernels, caches
    end_to_end, kernel = best_pair(lambda: impactlab.run_study(STUDY), lambda: hooks(study))
    again, physics = best_pair(lambda: impactlab.run_study(STUDY), lambda: hooks(study, with_derivation=True))
    print(f"540-case sweep, 3 models: run_study {end_to_end * 1e3:.1f} ms, hooks {kernel * 1e3:.1f} ms, "
          f"ratio {end_to_end / kernel:.2f} (target 1.2); against hooks and the derivation's physics "
          f"{physics * 1e3:.1f} ms: {again / physics:.2f}")

    one = {name: np.array([value[0]]) for name, value in case_inputs(study).items()}
    for entry in study.models[:1]:
        model = entry.model
        given = {name: one[name] for name in model.requires | model.optional_inputs if name in one}
        outputs = ["launch_angle", "spin_rate", "tangential_restitution"]
        # a fresh batch each call: the contact state the hook computes is physics, counted on its side
        physics = best(lambda: model._compute(CaseInputs(given), frozenset({"normal_impulse", "tangential_impulse"})),
                       50)
        arrays = best(lambda: model.compute_arrays(one, outputs), 50)
        dataset = best(lambda: model.compute(one, outputs), 50)
        print(f"one case, {model.name}: hook {physics * 1e6:.0f} us, compute_arrays {arrays * 1e6:.0f} us "
              f"({arrays / physics:.1f}x), compute {dataset * 1e6:.0f} us ({dataset / physics:.1f}x) (target 3x)")

    big = STUDY.replace("  contact.friction: [0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5]\n", "").replace(
        "num: 60", "num: 100000")
    load = best(lambda: load_study(big), 3)
    print(f"load a study with 10^5 swept values: {load * 1e3:.0f} ms (target under 1000 ms)")
    if "--large" in sys.argv:
        large()


LARGE = STUDY.replace("num: 60", "num: 1000").replace(
    "contact.friction: [0.1, 0.15, 0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5]",
    "contact.friction: {start: 0.05, stop: 0.6, num: 1000}").replace("[maw, rigid_coulomb, restitution]",
                                                                    "[maw, rigid_coulomb]")


def large(chunk: int = 8192) -> None:
    """10^6 cases, two models: run_study in this process (serial) against the hooks run chunk by chunk as the
    serial executor runs them, timed hooks-run-run-hooks (best of two each: a minute apiece on 2 cores, and
    the machine is shared), then run_study on every core once."""
    study = load_study(LARGE)

    kernel = lambda: hooks(study, chunk=chunk)

    def timed(function):
        start = time.perf_counter()
        function()
        return time.perf_counter() - start

    serial_run = lambda: impactlab.run_study(LARGE, executor="serial")
    first_hooks, first_run, second_run, second_hooks = (timed(f) for f in (kernel, serial_run, serial_run, kernel))
    hooks_time, serial = min(first_hooks, second_hooks), min(first_run, second_run)
    parallel = timed(lambda: impactlab.run_study(LARGE, executor="processes"))
    print(f"10^6 cases, maw and rigid_coulomb: hooks {hooks_time:.1f} s (one process; {first_hooks:.1f}, "
          f"{second_hooks:.1f}), run_study serial {serial:.1f} s ({first_run:.1f}, {second_run:.1f}): ratio "
          f"{serial / hooks_time:.2f}; run_study on {os.cpu_count()} processes {parallel:.1f} s "
          f"({hooks_time / parallel:.2f}x faster than the hooks in one process)")


if __name__ == "__main__":
    main()
