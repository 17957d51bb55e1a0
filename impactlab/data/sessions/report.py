"""The report of ``impactlab shots`` and the normalised table it writes (``--csv``) of a session
(:class:`impactlab.data.sessions.reader.Session`)."""

from __future__ import annotations

import csv
import io
import math
from collections import Counter
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from impactlab.io.safe_output import write_atomically
from impactlab.units import DIMENSIONS, unit_affine
from impactlab.data.sessions.layouts import DISPLAY_UNITS, FIELDS, TEXT_FIELDS
from impactlab.scene.plausibility import MAGNITUDES, wrong_sign

if TYPE_CHECKING:  # annotations only: impactlab.data.sessions.reader imports this module to re-export its functions
    from impactlab.data.sessions.reader import Session

#: which measurements each prediction needs, for the report
NEEDS = {
    "impact models (ball speed, launch angle, spin)": "club, club speed, attack angle and dynamic loft",
    "launch direction and spin axis": "also face angle and club path",
    "ball flight (carry, apex, landing)": "ball speed, launch angle and spin rate (spin axis for offline)",
}


def write_normalised(session: Session, path) -> Path:
    """Write the session in the vocabulary (display units in the header, flags in a ``flags`` column) as CSV."""
    present = [field for field in FIELDS if np.isfinite(session.values[field]).any()]
    texts = [field for field in TEXT_FIELDS if any(session.text[field])]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    units = {field: DISPLAY_UNITS[FIELDS[field]] for field in present}
    writer.writerow(["line", *texts, *(f"{field} [{units[field]}]" for field in present), "flags"])
    scale = {}
    for field in present:
        dimension = FIELDS[field]
        si_unit = DIMENSIONS[dimension][0]
        # a display unit with an offset (degC): x = (SI - offset) / scale
        scale[field] = (1.0, 0.0) if dimension == "dimensionless" else unit_affine(units[field], si_unit)
    flag_text: list[list[str]] = [[] for _ in range(session.size)]
    for (field, kind), rows in session.flags.items():
        for index in np.flatnonzero(rows).tolist():
            flag_text[index].append(f"{field}:{kind}")
    for index in range(session.size):
        cells = [str(session.lines[index]), *(session.text[field][index] for field in texts)]
        for field in present:
            value = session.values[field][index]
            size, zero = scale[field]
            cells.append("" if not math.isfinite(value) else f"{(value - zero) / size:.10g}")
        cells.append(";".join(sorted(flag_text[index])))
        writer.writerow(cells)
    return write_atomically(path, buffer.getvalue().encode())


def describe(session: Session, include_flagged: bool = False) -> str:
    """The report of ``impactlab shots``: vendor, shots and clubs, columns used and not, rows skipped, flags."""
    out = [f"{session.file}: {session.vendor.name}" + (f" ({session.vendor.id})" if session.vendor.id !=
                                                         "impactlab" else "")]
    if session.vendor.source:
        out.append(f"  layout: {session.vendor.source}")
    clubs = Counter(name or "(none)" for name in session.text["club"])
    out.append(f"  {session.size} shot(s); clubs: " + ", ".join(f"{name} x{count}" for name, count in
                                                                 clubs.most_common()))
    for note in session.notes:
        out.append(f"  read: {note}")
    out.append("  columns used:")
    for header, field, unit, sign in session.used:
        extra = f" [{unit}]" if unit else ""
        turned = " (sign turned to the vocabulary's)" if sign < 0 else ""
        out.append(f"    {header!r}{extra} -> {field}{turned}")
    if session.unused:
        shown = ", ".join(repr(h) for h in session.unused[:30])
        more = f" and {len(session.unused) - 30} more" if len(session.unused) > 30 else ""
        out.append(f"  columns not used ({len(session.unused)}): {shown}{more}")
    if session.flags:
        out.append("  values flagged:")
        for (field, kind), rows in sorted(session.flags.items()):
            what = {"excluded": "marked not to use in the file",
                    "no data": "no-data marker (a sentinel, placeholder or flag), read as missing",
                    "inconsistent": "whose sign disagrees with the other spin column's",
                    "estimated": "estimated by the monitor, not measured",
                    "clamped": "at the monitor's limit (clamped)"}[kind]
            out.append(f"    {field}: {int(rows.sum())} row(s) {what}")
        if not include_flagged and any(kind in ("estimated", "clamped", "inconsistent")
                                       for _, kind in session.flags):
            out.append("    (estimated and clamped values are left out of fits and comparisons; "
                       "--include-flagged uses them)")
    for line, why in session.skipped:
        out.append(f"  line {line} skipped: {why}")
    keep, skipped = session.usable(include_flagged)
    out.append(f"  impact models: {int(keep.sum())} of {session.size} row(s) usable")
    reasons = Counter(why for _, why in skipped)
    for why, count in reasons.most_common(8):
        lines = [str(line) for line, w in skipped if w == why]
        shown = ", ".join(lines[:6]) + (f" ... ({count} rows)" if count > 6 else "")
        out.append(f"    skipped, {why}: line(s) {shown}")
    if len(reasons) > 8:
        out.append(f"    ... and {len(reasons) - 8} other reasons")
    ball = np.isfinite(session.values["ball_speed"]) & np.isfinite(session.values["vertical_launch_angle"]) & \
        np.isfinite(session.values["spin_rate"])
    # a ball speed or spin below zero is no measurement (the shot table refuses it): not ball data, said why
    signs = {key: session.values[key] for key in MAGNITUDES}
    wrong = [(row, problems) for row in range(session.size)
             if (problems := wrong_sign(signs, row, f"line {session.lines[row]}"))]
    for row, _ in wrong:
        ball[row] = False
    measured_spin = ball & ~session.flagged("spin_rate")
    out.append(f"  ball data (ball speed, launch angle, spin): {int(ball.sum())} row(s), {int(measured_spin.sum())} "
               f"with a spin that is not flagged")
    for _, problems in wrong[:10]:
        out.append(f"    not ball data, {'; '.join(problems)}")
    if wrong:
        out.append(f"    ({len(wrong)} row(s) with a magnitude below zero: the shot table of validate and fit refuses "
                   f"the file until they are fixed or removed)")
    square = keep & ~(np.isfinite(session.values["face_angle"]) & np.isfinite(session.values["path"]))
    if square.any():
        out.append(f"  {int(square.sum())} usable row(s) without face angle or club path: compared on ball speed, "
                   "launch angle and spin only")
    out.append("  which predictions need what:")
    for what, need in NEEDS.items():
        out.append(f"    {what}: {need}")
    out.append(f"  club data reference point ({session.vendor.club_reference_point.replace('_', ' ')}): "
               f"{session.vendor.club_reference}")
    if session.vendor.signs:
        out.append(f"  signs: {session.vendor.signs}")
    return "\n".join(out)
