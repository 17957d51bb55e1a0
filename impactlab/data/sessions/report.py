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
from impactlab.data.sessions.summary import show_rows_setting, skip_lines

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
    texts = [field for field in TEXT_FIELDS if any(session.text.get(field, ()))]
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
                    "inconsistent": "that disagree with another column of the row (the notes say which)",
                    "estimated": "estimated by the monitor, not measured",
                    "clamped": "at the monitor's limit (clamped)",
                    "modelled": "the monitor's model output (its flight not tracked long enough), not measured",
                    "unreadable": "a cell that is not a number (the row is skipped)"}[kind]
            out.append(f"    {field}: {int(rows.sum())} row(s) {what}")
        if not include_flagged and any(kind in ("estimated", "clamped", "inconsistent", "modelled")
                                       for _, kind in session.flags):
            out.append("    (estimated and clamped values are left out of fits and comparisons; "
                       "--include-flagged uses them)")
    show_rows = show_rows_setting()
    if session.skipped:  # rows that are no shot at all (summary rows, repeated headers and shots, ragged rows)
        out += skip_lines(session.skipped, session.size + len(session.skipped), (), show_rows, used="read as shots")
    keep, skipped = session.usable(include_flagged)
    out.append(f"  impact models: {int(keep.sum())} of {session.size} row(s) usable")
    out += skip_lines(skipped, session.size, (), show_rows, indent="    ")
    verdict = session.verdict()
    out += skip_lines([], session.size, [(reason, [int(line) for line in session.lines[mask]])
                                         for reason, mask in verdict.unusual], show_rows)
    if show_rows:
        for reason, mask, value in verdict.reasons:
            out += [f"    line {session.lines[row]}: {reason}" + (f": {value[row]:.6g}" if np.isfinite(value[row])
                                                                   else "") for row in np.flatnonzero(mask)]
    ball = np.isfinite(session.values["ball_speed"]) & np.isfinite(session.values["vertical_launch_angle"]) & \
        np.isfinite(session.values["spin_rate"]) & ~verdict.bad
    measured_spin = ball & ~session.flagged("spin_rate")
    out.append(f"  ball data (ball speed, launch angle, spin): {int(ball.sum())} row(s), {int(measured_spin.sum())} "
               f"with a spin that is not flagged (rows that break the row rules are not ball data)")
    flown = np.isfinite(session.values["carry_distance"])
    if flown.any():
        modelled = session.flags.get(("carry_distance", "modelled"), np.zeros(session.size, bool))
        out.append(f"  the monitor's flight (carry): {int(flown.sum())} row(s)" + (
            f", {int((flown & ~modelled).sum())} measured (tracked), {int((flown & modelled).sum())} the monitor's "
            f"model output" if session.vendor.tracked else ", whether measured or modelled not stated by the export"))
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
