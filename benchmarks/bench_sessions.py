"""Benchmark: a large launch-monitor session read, checked and turned into model inputs (issue 23, item 3).

Run:  python benchmarks/bench_sessions.py [--rows 100000]
      python benchmarks/bench_sessions.py --dataset   (the shipped trackman_driver_sessions, issue 32)

Writes a TrackMan TPS export of ROWS shots (the layout of tests/data/vendors/trackman_tps.csv: BOM, sep= line,
units row, every value quoted, CRLF; clubs cycled through the catalogue's names; every 50th spin estimated, every
97th row without a dynamic loft) to a temporary folder and times, in one process:
1. read_session (parse, units, flags), 2. describe (the `impactlab shots` report), 3. shot_table (rows usable by
the impact models, with the reasons for the others), 4. write_normalised (--csv), 5. table_inputs (the
models' SI input arrays, one scene per row). The target is "well under a minute" for 1-3.

``--dataset`` reads the shipped dataset trackman_driver_sessions (10,169 TrackMan driver shots as published) and
prints the CPU time of read_session and of the row rules (goal: reading < 5 s of CPU, issue 32) and the peak of
Python's allocations while reading a quarter, a half and all of its rows (tracemalloc: numpy's arrays included),
whose ratios say whether memory grows linearly in rows.
"""

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

HEADER = (Path(__file__).parent.parent / "tests" / "data" / "vendors" / "trackman_tps.csv").read_bytes() \
    .decode("utf-8-sig").split("\r\n")[:3]
CLUBS = ("Driver", "3 Wood", "4 Hybrid", "5 Iron", "6 Iron", "7 Iron", "8 Iron", "9 Iron", "Pitching Wedge",
         "Gap Wedge", "Sand Wedge")


def session_text(rows: int, seed: int = 1) -> str:
    rng = np.random.default_rng(seed)
    names = HEADER[1].split(",")
    col = {name: i for i, name in enumerate(names)}
    lines = list(HEADER)
    speed = rng.uniform(70, 115, rows)
    attack = rng.uniform(-5, 3, rows)
    loft = rng.uniform(12, 45, rows)
    face = rng.normal(0, 2, rows)
    path = rng.normal(0, 3, rows)
    ball = speed * rng.uniform(1.2, 1.48, rows)
    launch = loft * 0.8
    spin = rng.uniform(2000, 9000, rows)
    axis = rng.normal(0, 5, rows)
    for i in range(rows):
        cells = [""] * len(names)
        values = {"Date": f"5/6/2026 {i}", "Club": CLUBS[i % len(CLUBS)], "Club Speed": speed[i],
                  "Attack Angle": attack[i], "Club Path": path[i], "Dyn. Loft": "" if i % 97 == 0 else loft[i],
                  "Face Angle": face[i], "Face To Path": face[i] - path[i], "Ball Speed": ball[i],
                  "Launch Angle": launch[i], "Launch Direction": face[i] * 0.8, "Spin Rate": spin[i],
                  "Spin Rate Type": "Estimated" if i % 50 == 0 else "Measured", "Spin Axis": axis[i],
                  "Use In Stat": "TRUE"}
        for name, value in values.items():
            cells[col[name]] = f'"{value}"' if value != "" else ""
        lines.append(",".join(cells))
    return "\ufeff" + "\r\n".join(lines) + "\r\n"


def dataset_line() -> None:
    """CPU time and peak memory of reading the shipped 10,169-shot TrackMan dataset, in one run."""
    import gzip
    import tracemalloc

    from impactlab.data.sessions import dataset_path, read_session, read_session_text

    read_session("trackman_driver_sessions")  # imports and caches (pandas, the layouts) out of the timing
    start = time.process_time()
    session = read_session("trackman_driver_sessions")
    read = time.process_time() - start
    start = time.process_time()
    keep, skipped = session.usable()
    rules = time.process_time() - start
    print(f"trackman_driver_sessions: {session.size} shots read (of 10169 rows) in {read:.2f} s of CPU (goal < 5 s); "
          f"row rules and usable rows {rules:.2f} s of CPU ({int(keep.sum())} usable, {len(skipped)} skipped)")
    lines = gzip.decompress(dataset_path("trackman_driver_sessions").read_bytes()).decode().splitlines(keepends=True)
    peaks = []
    for fraction in (4, 2, 1):
        rows = (len(lines) - 2) // fraction
        text = "".join(lines[:2 + rows])
        tracemalloc.start()
        read_session_text(text, "part.csv")
        peaks.append((rows, tracemalloc.get_traced_memory()[1] / 2**20))
        tracemalloc.stop()
    print("peak memory of reading (tracemalloc): " + ", ".join(f"{rows} rows {peak:.1f} MiB" for rows, peak in peaks)
          + f"; ratio all / half {peaks[2][1] / peaks[1][1]:.2f}, half / quarter {peaks[1][1] / peaks[0][1]:.2f} "
            "(2.00: linear in rows)")


def main():
    from impactlab.data.sessions.reader import describe, read_session, write_normalised
    from impactlab.data.sessions.shots import table_inputs

    parser = argparse.ArgumentParser()
    parser.add_argument("--rows", type=int, default=100_000)
    parser.add_argument("--dataset", action="store_true", help="time the shipped trackman_driver_sessions instead")
    args = parser.parse_args()
    if args.dataset:
        dataset_line()
        return
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "big.csv"
        path.write_text(session_text(args.rows), encoding="utf-8", newline="")
        print(f"{args.rows} rows, {path.stat().st_size / 2**20:.1f} MiB")
        start = time.perf_counter()
        session = read_session(path)
        t1 = time.perf_counter()
        report = describe(session)
        t2 = time.perf_counter()
        table = session.shot_table()
        t3 = time.perf_counter()
        write_normalised(session, Path(folder) / "normal.csv")
        t4 = time.perf_counter()
        table_inputs(table)
        t5 = time.perf_counter()
    print(f"read_session  {t1 - start:7.2f} s")
    print(f"describe      {t2 - t1:7.2f} s  ({len(report.splitlines())} report lines)")
    print(f"shot_table    {t3 - t2:7.2f} s  ({table.size} usable, {len(table.skipped)} skipped)")
    print(f"read + check  {t3 - start:7.2f} s  (target: well under 60 s)")
    print(f"write --csv   {t4 - t3:7.2f} s")
    print(f"table_inputs  {t5 - t4:7.2f} s  (one scene per row)")


if __name__ == "__main__":
    main()
