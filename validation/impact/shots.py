"""The shared TrackMan driver file, filtered for the impact laws' validation (issue 33), and its speed bands.

The file (``/work/shared/data/trackman-driver-sessions/data.csv``, a public TrackMan Performance Studio export,
README beside it) is read twice: with the csv module, to apply this study's own row filter and count each reason,
and with the package's reader (:func:`impactlab.data.sessions.shots.read_shots`), whose rows carry the delivery in SI
and are labelled by their line in the file. A row is kept when both keep it.

The filter (issue 33): a row lacking club speed, dynamic loft, attack angle, ball speed, launch angle or spin, or
holding TrackMan's -2.147e10 sentinel (a value it could not measure) in any column, or whose smash factor (ball
speed over club speed) lies outside 1.0-1.6, is dropped; so is a row whose impact location lies off the face
(|offset| or |height| beyond 30 mm: the ball would have missed the driver's face, the scene refuses it).
"""

from __future__ import annotations

import csv
import os
from collections import Counter
from pathlib import Path

import numpy as np

from impactlab.data.sessions.shots import read_shots

DATA = Path(os.environ.get("IMPACTLAB_TRACKMAN_FILE", "/work/shared/data/trackman-driver-sessions/data.csv"))
REQUIRED = ("Club Speed", "Dyn. Loft", "Attack Angle", "Ball Speed", "Launch Angle", "Spin Rate")
SENTINEL = -2.0e10  # TrackMan writes -2.147e10 for a value it could not measure
MPH = 0.44704
#: the speed bands of the extrapolation protocol [mph of club speed]
SLOW, FAST = 95.0, 100.0
FACE_LIMIT = 30.0  # mm


def _number(text: str) -> float | None:
    try:
        value = float(text)
    except (TypeError, ValueError):
        return None
    return value if np.isfinite(value) else None


def filtered_lines(path: Path = DATA) -> tuple[set[int], Counter, int]:
    """(1-based line numbers of the rows kept, reasons for the rows dropped, rows read)."""
    kept, reasons = set(), Counter()
    with open(path, newline="", encoding="utf-8") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        next(reader)  # the units row
        column = {name: header.index(name) for name in header}
        total = 0
        for line, row in enumerate(reader, start=3):
            total += 1
            values = {name: _number(row[column[name]]) if column[name] < len(row) else None for name in header}
            if any(v is not None and v < SENTINEL for v in values.values()):
                reasons["sentinel -2.147e10 in a column"] += 1
                continue
            missing = [name for name in REQUIRED if values[name] is None]
            if missing:
                reasons["lacks " + ", ".join(missing) if len(missing) < 3 else "lacks 3 or more of the six"] += 1
                continue
            smash = values["Ball Speed"] / values["Club Speed"] if values["Club Speed"] else 0.0
            if not 1.0 <= smash <= 1.6:
                reasons["smash factor outside 1.0-1.6"] += 1
                continue
            off = [values[name] for name in ("Impact Offset", "Impact Height") if values[name] is not None]
            if any(abs(v) > FACE_LIMIT for v in off):
                reasons["impact location off the face (> 30 mm)"] += 1
                continue
            kept.add(line)
    return kept, reasons, total


def load(path: Path = DATA):
    """(table of the kept rows, report lines): the file's rows both this filter and the package reader keep."""
    kept, reasons, total = filtered_lines(path)
    table = read_shots(path)
    lines = np.array([int(label.split()[-1]) for label in table.labels])
    mine = np.array([line in kept for line in lines])
    table = table.subset(np.flatnonzero(mine))
    report = [f"rows read: {total}", *(f"dropped, {why}: {count}" for why, count in sorted(reasons.items())),
              f"kept by this filter: {len(kept)}",
              f"kept by the package reader too (its own skips: {len(kept - set(lines.tolist()))} more): {table.size}"]
    return table, report


def file_columns(table, names, convert=str, path: Path | None = None) -> dict:
    """The file's columns ``names`` for each row of ``table`` (rows labelled by their file line), through
    ``convert``, the file read once; a line the file does not hold, or a cell ``convert`` refuses, gives
    ``convert``'s empty value ('' for str, NaN for float)."""
    empty = "" if convert is str else np.nan
    with open(path or DATA, newline="", encoding="utf-8") as handle:
        rows = list(csv.reader(handle))
    lines = [int(label.split()[-1]) for label in table.labels]
    out = {}
    for name in names:
        column = rows[0].index(name)
        cells = {line: row[column] for line, row in enumerate(rows[2:], start=3) if column < len(row)}

        def value(line: int):
            try:
                return convert(cells[line])
            except (KeyError, ValueError):
                return empty

        out[name] = np.array([value(line) for line in lines])
    return out


def file_column(table, name: str, convert=str, path: Path | None = None) -> np.ndarray:
    """The file's column ``name`` for each row of ``table``: :func:`file_columns` of one name."""
    return file_columns(table, (name,), convert, path)[name]


def bands(table):
    """Boolean masks (slow: club speed < 95 mph, fast: > 100 mph)."""
    speed = np.asarray(table.delivery["club_speed"]) / MPH
    return speed < SLOW, speed > FAST
