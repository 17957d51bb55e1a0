"""The framework's work around the physics on a golf study: run_study on 10^4 off-centre driver strikes.

A golf study is where the contact state (frame, approach speeds and the 3x3 mobility of every case) matters:
the ball's restitution law needs the approach speeds of every case before the first chunk, the models need
the full state per chunk, and the plan's sentence on the solver paths counts the cases on one line. Each is
built once (issue 20): the restitution from the approach speeds alone, the mobility once per chunk, the path
count from the chunks' own states. Measured on 2 shared cores (2026-11-23, load ~9), best of 5, two runs
each, before / after: 410, 425 ms / 322, 322 ms.

Run: ``python benchmarks/bench_golf_run.py``.
"""

import time
import warnings

import impactlab

STUDY = {"name": "golf-run", "ball": {"preset": "tour_urethane"}, "club": {"preset": "driver"},
         "delivery": {"club_speed": "100 mph", "attack_angle": "-1 deg", "dynamic_loft": "13 deg"},
         "sweep": {"strike.toe": {"start": "-20 mm", "stop": "20 mm", "num": 100},
                   "strike.high": {"start": "-10 mm", "stop": "10 mm", "num": 100}},
         "models": ["rigid_coulomb", "restitution"], "outputs": ["ball_speed", "spin_rate", "spin_axis"]}


def main() -> None:
    warnings.simplefilter("ignore")  # the validity warnings of golf cases, once per repeat
    impactlab.run_study(STUDY, executor="serial")  # compile and warm up
    times = []
    for _ in range(5):
        start = time.perf_counter()
        impactlab.run_study(STUDY, executor="serial")
        times.append(time.perf_counter() - start)
    print(f"golf 10^4 cases, rigid_coulomb + restitution, serial run_study: best {min(times) * 1e3:.0f} ms")


if __name__ == "__main__":
    main()
