"""Benchmark: a launch-monitor session whose every shot states its own air, flown one call per air against one call
with per-shot air arrays (``impactlab fly SESSION``, :func:`impactlab.data.sessions.flight.fly_session`).

Run:  python benchmarks/bench_session_air.py [--shots 400] [--repeat 2]

Writes a Garmin export of SHOTS copies of the first shot of tests/data/vendors/garmin_r50.csv, each with its own
``Temperature`` (50.00, 50.05, ... degF) and an empty ``Air Density`` cell (so the reader has no density to check
the air against), reads it once, and times in one process (best of REPEAT):

1. per air: the shots grouped by their air and one :func:`impactlab.fly` call per distinct air (what
   ``fly_session`` did before it took per-shot air arrays: here SHOTS calls);
2. one call: :func:`impactlab.fly` once, the air of every shot as arrays (:class:`impactlab.scene.air.Conditions`);
3. fly_session: the whole ``impactlab fly`` computation on the session read (one call inside).

It checks that 1 and 2 give the same carries (to the bit) and prints the times and the ratio 1 / 2.

Measured 2026-11-24 on this 2-core machine shared with other jobs (load ~1.7): ``impactlab fly`` on the 400-shot
file, the whole command (imports, reading, printing), 11.4 s with the code of eab783a (one call per air) against
1.3 s after (one call), runs interleaved, identical output; this script: per air 10.3 s, one call 0.037 s,
fly_session 0.039 s (ratio 281).
"""

import argparse
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

FIXTURE = Path(__file__).parent.parent / "tests" / "data" / "vendors" / "garmin_r50.csv"


def session_text(shots: int) -> str:
    """The fixture's header and units rows, then its first shot ``shots`` times, each at its own temperature."""
    lines = FIXTURE.read_text().splitlines()
    header = lines[0].split(",")
    out = lines[:2]
    for index in range(shots):
        cells = lines[2].split(",")
        cells[header.index("Temperature")] = f"{50 + index * 0.05:.2f}"
        cells[header.index("Air Density")] = ""
        out.append(",".join(cells))
    return "\n".join(out) + "\n"


def best(function, repeat: int) -> tuple[float, object]:
    times, result = [], None
    for _ in range(repeat):
        start = time.perf_counter()
        result = function()
        times.append(time.perf_counter() - start)
    return min(times), result


def main():
    import impactlab
    from impactlab.data.sessions.reader import read_session
    from impactlab.data.sessions.flight import fly_session
    from impactlab.scene.air import Conditions

    parser = argparse.ArgumentParser()
    parser.add_argument("--shots", type=int, default=400)
    parser.add_argument("--repeat", type=int, default=2)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "garmin_many_airs.csv"
        path.write_text(session_text(args.shots))
        start = time.perf_counter()
        session = read_session(path)
        read = time.perf_counter() - start
    v = session.values
    launch = [v["ball_speed"], v["vertical_launch_angle"], v["spin_rate"], np.nan_to_num(v["spin_axis"]),
              np.nan_to_num(v["horizontal_launch_angle"])]
    airs = [Conditions(temperature=float(v["air_temperature"][row]), pressure=float(v["air_pressure"][row]),
                       relative_humidity=float(v["relative_humidity"][row])) for row in range(session.size)]

    def per_air():
        groups: dict[Conditions, list[int]] = {}
        for index, air in enumerate(airs):
            groups.setdefault(air, []).append(index)
        carry = np.full(session.size, np.nan)
        for air, members in groups.items():
            carry[members] = impactlab.fly(*(values[members] for values in launch), air).carry_distance.values
        return carry, len(groups)

    def one_call():
        air = Conditions(temperature=v["air_temperature"], pressure=v["air_pressure"],
                         relative_humidity=v["relative_humidity"])
        return impactlab.fly(*launch, air).carry_distance.values

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        grouped, (grouped_carry, calls) = best(per_air, args.repeat)
        single, single_carry = best(one_call, args.repeat)
        session_time, _ = best(lambda: fly_session(session), args.repeat)
    same = bool(np.array_equal(grouped_carry, single_carry))
    print(f"{args.shots} shots, {calls} distinct airs; read_session {read:.3f} s")
    print(f"per air ({calls} impactlab.fly calls): {grouped:.3f} s")
    print(f"one call (per-shot air arrays):      {single:.3f} s")
    print(f"fly_session (one call inside):       {session_time:.3f} s")
    print(f"ratio per air / one call: {grouped / single:.1f}; carries identical: {same}")


if __name__ == "__main__":
    main()
