"""Launch-monitor sessions read as exported: vendor layouts as data, one normalised table out.

A session file is a table a launch monitor's software wrote (TrackMan, Garmin Golf, Foresight FSX, Rapsodo,
FlightScope, Square Golf), JSON shot records (GSPro Open Connect messages, Uneekor's report; read as rows by
:mod:`impactlab.data.sessions.json_records`) or a table in impactlab's own vocabulary (``Club Speed [mph]``,
``ball_speed (m/s)``). Each vendor's
layout is a YAML column map in ``impactlab/data/sessions/vendors/`` (:func:`vendor_maps`): the header names that recognise
it, where its units are (a units row under the header, inside the header names, or implied by the layout), its
column names in the vocabulary of :data:`FIELDS`, per-column signs, no-data sentinels, estimated-value flags,
clamped values, placeholders (values that stand for "not measured"), rows that are no shot, values a layout
requires, the point of the club head its club data describe, and for an export in another language the layout it
translates (``base``, ``headers``). A map key ``Name [unit]``
matches the column ``Name`` only when the header gives it a unit (FlightScope's ``Club`` is the club's name,
``Club (mph)`` its speed).

The reader (:func:`read_session`) never guesses: the separator comes from a ``sep=`` line or the header; decimal
commas are recognised per file (a quoted ``"-0,9"`` is -0.9) and a file that mixes decimal marks is refused; a
number without a unit is refused; two columns that give one quantity (``Ball Speed [mph]`` and ``Ball Speed
[m/s]``) are refused, naming both; a cell that is not a number is refused with its file:line:column. Values are
flagged, not dropped: no-data sentinels become missing, estimated and clamped values are kept in the session but
left out of fits and comparisons unless asked (:meth:`Session.shot_table`), and the rows a model cannot use are
skipped with their reason while the rest of the session is used.

All values are SI (angles in rad, spins in rad/s) with the signs of :mod:`impactlab.vocabulary`: horizontal
angles, spin axis, side spin and offline distance positive to the right of the target line.
"""

from __future__ import annotations

from pathlib import Path

import attrs
import numpy as np

from impactlab.scene.plausibility import wrong_sign
from impactlab.errors import StudyError
from impactlab.scene.catalogue import club_key
from impactlab.data.sessions.shot_table import DEFAULT_SIGMA, DELIVERY_FIELDS, MEASURED_FIELDS, ShotTable, _resolve_spin_loft
from impactlab.data.sessions.layouts import (DESCRIPTIONS, FIELDS, GENERIC, TEXT_FIELDS, VendorMap,
                                            _column_plan, _header_index, _norm, _recognise, split_header)
from impactlab.data.sessions.json_records import json_rows, looks_like_json
from impactlab.data.sessions.air import _air_from_text, _check_air
from impactlab.data.sessions.values import (_UNITS_CELL, _check_spin_signs, _club_names, _decimal_mark, _derive,
                                           _flag_all_zero, _flag_estimated, _flag_excluded, _flag_no_data,
                                           _flag_without, _legacy_text, _merge_repeated, _progress, _read_bytes,
                                           _read_flags, _row_key, _rows_of, _to_numbers, _units_difference)
# the report and the normalised table of a session, importable from here (the CLI and users import them so)
from impactlab.data.sessions.report import describe as describe, write_normalised as write_normalised

#: the delivery the impact models need in every row
NEEDED_DELIVERY = ("club_speed", "attack_angle", "dynamic_loft")
#: the launch the impact models predict (what a row is compared on)
PREDICTED = ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis")


# -- the session -----------------------------------------------------------------------------------------------
@attrs.frozen
class Session:
    """A launch-monitor session read as exported, normalised to :data:`FIELDS` (SI) with what was done to it.

    Attributes
    ----------
    file : str
    vendor : VendorMap
    values : dict of ndarray
        Field -> per-row SI values (NaN: not in the file or no data).
    text : dict of tuple of str
        ``label``, ``club`` and ``handedness`` per row ('' where not given); a YAML table whose rows name their
        sources also ``source`` (every row's, the table's name where a row names none).
    lines : ndarray of int
        The file line of each row.
    flags : dict of ndarray of bool
        ``(field, kind)`` -> per-row mask; kind ``estimated``, ``clamped`` or ``no data`` (a sentinel).
    used : list of (header, field, unit, sign)
        Each column used, the field it gives, the unit it was read in and the sign applied.
    unused : list of str
        Columns not used.
    skipped : list of (line, reason)
        Rows that are no shot at all (summary rows).
    notes : list of str
        What the reader inferred (separator, decimal mark, units row, derived values).
    """

    file: str
    vendor: VendorMap
    values: dict = attrs.field(eq=False)
    text: dict = attrs.field(eq=False)
    lines: np.ndarray = attrs.field(eq=False)
    flags: dict = attrs.field(eq=False)
    used: list = attrs.field(eq=False)
    unused: list = attrs.field(eq=False)
    skipped: list = attrs.field(eq=False)
    notes: list = attrs.field(eq=False)

    @property
    def size(self) -> int:
        """Number of shots read."""
        return len(self.lines)

    def flagged(self, field: str) -> np.ndarray:
        """Rows whose ``field`` is flagged (estimated or clamped; no-data values are already missing)."""
        mask = np.zeros(self.size, bool)
        for (name, kind), rows in self.flags.items():
            if name == field and kind in ("estimated", "clamped", "inconsistent"):
                mask |= rows
        return mask

    def usable(self, include_flagged: bool = False) -> tuple[np.ndarray, list]:
        """Rows the impact models can use, and ``(line, reason)`` of every row they cannot.

        A row needs a club the catalogue knows, the club speed, attack angle and dynamic loft, and at least one
        measured launch quantity that is not flagged (unless ``include_flagged``).
        """
        keep = np.ones(self.size, bool)
        reasons: list[list[str]] = [[] for _ in range(self.size)]
        keys = {name: club_key(name) if name else None for name in set(self.text["club"])}  # once per name
        clubs = [keys[name] for name in self.text["club"]]
        for index, (name, key) in enumerate(zip(self.text["club"], clubs)):
            if not name:
                reasons[index].append("no club named")
            elif key is None:
                reasons[index].append(f"club {name!r} is not in the club catalogue")
        for index in np.flatnonzero(self.flags.get(("row", "excluded"), np.zeros(self.size, bool))).tolist():
            reasons[index].append("marked not to use in the file" + (
                f" ({self.vendor.excluded['column']} = {', '.join(map(str, self.vendor.excluded['values']))})"
                if self.vendor.excluded else ""))
        for field in NEEDED_DELIVERY:
            given = np.isfinite(self.values[field])
            if field == "dynamic_loft" and "spin_loft" in self.values:  # the spin loft gives the dynamic loft
                given |= np.isfinite(self.values["spin_loft"])
            for index in np.flatnonzero(~given).tolist():
                reasons[index].append(f"no {DESCRIPTIONS[field]}")
        measured, given = np.zeros(self.size, bool), np.zeros(self.size, bool)
        for field in PREDICTED:
            ok = np.isfinite(self.values[field])
            given |= ok
            if not include_flagged:
                ok &= ~self.flagged(field)
            measured |= ok
        for index in np.flatnonzero(~measured).tolist():
            reasons[index].append("no measured launch quantity" + (" that is not flagged" if given[index] else ""))
        out = []
        for index, why in enumerate(reasons):
            if why:
                keep[index] = False
                out.append((int(self.lines[index]), "; ".join(why)))
        return keep, out

    def shot_table(self, include_flagged: bool = False, every_row: bool = False):
        """The :class:`~impactlab.data.sessions.shots.ShotTable` of the rows the impact models can use.

        The one assembly of a shot table: launch-monitor exports and impactlab's YAML tables
        (:func:`impactlab.data.sessions.shots.read_yaml`) both come here as a session. Flagged values (estimated, clamped)
        are left out of the comparison unless ``include_flagged``; a row without face angle or club path keeps its
        ball speed, launch angle and spin but not its launch direction and spin axis (a square face would be a
        guess). A row the models cannot use (:meth:`usable`) is skipped with its reason, or, with ``every_row`` (a
        table written by hand, where such a row is the author's slip), refused. Raises StudyError, listing every
        problem at its file:line: no usable row, a spin loft or face to path that disagrees with the row's angles,
        a magnitude below zero, an uncertainty that is not positive.
        """
        keep, skipped = self.usable(include_flagged)
        problems = []
        if every_row:
            problems = [f"{self.file}:{line}: a row the impact models cannot use: {why}" for line, why in skipped]
            keep, skipped = np.ones(self.size, bool), []
        elif not keep.any():
            reasons = "; ".join(f"{self.file}:{line}: {why}" for line, why in skipped[:10])
            more = f" (and {len(skipped) - 10} more)" if len(skipped) > 10 else ""
            raise StudyError(f"{self.file}: no row the impact models can use ({self.size} shot(s) read): "
                             f"{reasons}{more}")
        index = np.flatnonzero(keep)
        # a field no layout of this vendor maps (the 3-D spin loft) is absent: NaN, as an empty cell
        delivery = {key: (self.values[key][index].copy() if key in self.values else np.full(index.size, np.nan))
                    for key in DELIVERY_FIELDS}
        problems += _resolve_spin_loft(delivery, self.lines[index], self.file)
        square = ~(np.isfinite(delivery["face_angle"]) & np.isfinite(delivery["path"]))
        strike_known = np.isfinite(delivery["strike_toe"]) & np.isfinite(delivery["strike_high"])
        for key in ("path", "face_angle", "strike_toe", "strike_high"):
            delivery[key] = np.nan_to_num(delivery[key])
        measured = {}
        for key in MEASURED_FIELDS:
            values = self.values[key][index].copy()
            if not include_flagged:
                values[self.flagged(key)[index]] = np.nan
            if key in ("horizontal_launch_angle", "spin_axis"):
                values[square] = np.nan
            measured[key] = values
        # a magnitude below zero is no measurement (a ball speed of -70 mph): refused, naming each row
        problems += [problem for row in range(index.size)
                     for problem in wrong_sign(measured, row, f"{self.file}:{self.lines[index[row]]}")]
        sigma = {}
        for key in MEASURED_FIELDS:
            given = self.values[f"{key}_sigma"][index]
            bad = np.isfinite(given) & ~(given > 0)
            if bad.any():
                lines = ", ".join(f"{self.file}:{self.lines[index[i]]}" for i in np.flatnonzero(bad)[:10])
                problems.append(f"{lines}: {key}_sigma: expected a positive uncertainty, got "
                                f"{given[np.flatnonzero(bad)[0]]:g}")
            sigma[key] = np.where(np.isfinite(given), given, DEFAULT_SIGMA[key])
        if problems:
            raise StudyError("; ".join(problems))
        labels = tuple(self.text["label"][i] or f"line {self.lines[i]}" for i in index)
        # every kept row's club is in the catalogue (usable() refuses the others)
        keys = {name: known for name in {self.text["club"][i] for i in index} if (known := club_key(name)) is not None}
        source = f"read from {self.file} ({self.vendor.name})"
        if self.vendor.club_reference_point != "unknown":
            source += f"; club data at the head's {self.vendor.club_reference_point.replace('_', ' ')}"
        elif self.vendor is not GENERIC:
            source += "; the point of the head its club data describe is not stated"
        return ShotTable(name=Path(self.file).stem, source=source,
                         labels=labels, clubs=tuple(keys[self.text["club"][i]] for i in index),
                         handedness=tuple(self.text["handedness"][i] or "right" for i in index),
                         delivery=delivery, measured=measured, sigma=sigma, loft_at=self.vendor.loft_at,
                         skipped=tuple(skipped), strike_known=strike_known,
                         row_sources=tuple(self.text["source"][i] for i in index) if "source" in self.text else ())


def read_session(path, vendor: str | None = None) -> Session:
    """Read a launch-monitor export (or an impactlab shot-table CSV) as exported; see the module docstring.

    Parameters
    ----------
    path : str or Path
        The file.
    vendor : str, optional
        A vendor id of :func:`vendor_maps` (default: recognised from the header).
    """
    path = Path(path)
    try:
        text, encoding = _read_bytes(path), ""
    except StudyError as exc:  # not UTF-8: read in a legacy encoding only where a layout says its exports use one
        text, encoding = _legacy_text(path, exc, lambda rows: _recognise(
            [cell.strip() for cell in rows[_header_index(rows, vendor)]], vendor, str(path)))
    session = read_session_text(text, str(path), vendor)
    if encoding:
        session.notes.insert(0, f"read as {encoding} text (not UTF-8), the encoding of {session.vendor.name} files")
    return session


def read_session_text(text: str, file: str = "<csv>", vendor: str | None = None) -> Session:
    """A :class:`Session` from the text of an export (see :func:`read_session`)."""
    rows, lines, notes = json_rows(text, file) if looks_like_json(text) else _rows_of(text, file)
    start = _header_index(rows, vendor)
    if not rows or not any(cell.strip() for cell in rows[start]):
        raise StudyError(f"{file}: empty file; expected a header row of columns")
    header = [cell.strip() for cell in rows[start]]
    while header and not header[-1]:  # a trailing separator (Foresight, TrackMan's empty last column)
        header.pop()
    layout = _recognise(header, vendor, file)
    header_line = lines[start]
    preamble = [line for line, cells in zip(lines[:start], rows[:start]) if any(c.strip() for c in cells)]
    if preamble:
        notes.append(f"line(s) {', '.join(map(str, preamble))} before the header are a title, not shots")
    body, body_lines = rows[start + 1:], lines[start + 1:]
    units_row = None
    if body and any(cell.strip() for cell in body[0]) and (layout.units_row_plain or all(
            _UNITS_CELL.match(cell) or not cell.strip() for cell in body[0])):  # SkyTrak: MPH, DEG without brackets
        units_row = [cell.strip() if layout.units_row_plain else cell.strip()[1:-1].strip() for cell in body[0]]
        body_units, units_line = body[0], body_lines[0]
        notes.append(f"units row at line {body_lines[0]}")
        body, body_lines = body[1:], body_lines[1:]
    keep = [i for i, cells in enumerate(body) if any(cell.strip() for cell in cells)]
    body = [body[i] for i in keep]
    body_lines = [body_lines[i] for i in keep]

    # columns: which field, which unit, which sign
    plan, unused, repeated = _column_plan(header, layout, units_row, file, header_line)
    problems: list[str] = []
    by_field = {field: column for column, _, field, *_ in plan}
    in_row = set() if units_row is None else {column for column, cell in enumerate(units_row) if cell}
    implied = [f"{cell} [{unit}]" for column, cell, field, unit, _, factor in plan
               if layout.units == "implied" and factor is not None and unit and split_header(cell)[1] is None
               and column not in in_row]
    named = [cell for cell in header if cell]
    if layout is GENERIC and len(unused) * 2 > len(named):  # most columns unknown: a vendor export not recognised?
        notes.append(f"no vendor layout recognises this header ({len(unused)} of {len(named)} columns unknown): read "
                     f"in impactlab's own layout, whose signs are the vocabulary's (side spin, spin axis and "
                     f"directions positive to the right); if a launch monitor wrote it, name it with --vendor")
    if implied:
        notes.append(f"units not in the file for {', '.join(implied)}: taken from the {layout.name} layout "
                     f"({layout.source})")

    # summary rows (and heartbeats), values a layout requires, ragged rows
    skipped = []
    width = len(header)
    names = [_norm(split_header(c)[0]) for c in header]
    summary = [(names.index(_norm(rule["column"])), {_norm(v) for v in rule["values"]}, rule.get("why"))
               for rule in layout.summary_rows or [] if _norm(rule["column"]) in names]
    required = layout.required or {"column": None, "values": []}
    required_column = names.index(_norm(required["column"])) if required["column"] and \
        _norm(required["column"]) in names else None
    required_values = {_norm(str(value)) for value in required["values"]}
    refused = []
    shots, shot_lines = [], []
    header_key = _row_key(header)
    units_key = None if units_row is None else _row_key(body_units)
    after_header = False
    trailer, trailer_values = None, {_norm(v) for v in (layout.trailer or {}).get("values", ())}
    trailer_column = names.index(_norm(layout.trailer["column"])) if layout.trailer and \
        _norm(layout.trailer["column"]) in names else None
    block_club, shot_clubs = "", []
    seen: dict[tuple, int] = {}
    repeats: list[str] = []
    for cells, line in zip(body, body_lines):
        while len(cells) > width and not cells[-1].strip():
            cells = cells[:-1]
        # the header again: a new block of the export (Rapsodo writes it above every club's shots) or a second
        # session appended to the first; its units row must be the first block's, else the units would be mixed
        if _row_key(cells) == header_key:
            skipped.append((line, "the header again (a new block of the export), not a shot"))
            after_header = True
            continue
        if after_header and units_row is not None and (_row_key(cells) == units_key or all(
                _UNITS_CELL.match(c) or not c.strip() for c in cells)):
            if _row_key(cells) != units_key:
                problems.append(f"{file}:{line}: a units row that differs from the one at line {units_line} "
                                f"({_units_difference(header, body_units, cells)}): the file joins blocks in "
                                f"different units; export or read them separately")
            else:
                skipped.append((line, "the units row again, under the repeated header"))
            after_header = False
            continue
        after_header = False
        if layout is not GENERIC and set(layout.recognise) <= {_norm(split_header(c)[0]) for c in cells}:
            problems.append(f"{file}:{line}: a second header, with other columns than line {header_line}'s: the "
                            f"file joins two exports (or app versions) of different columns; read them separately")
            continue
        if trailer is not None or (trailer_column is not None and trailer_column < len(cells)
                                   and _norm(cells[trailer_column]) in trailer_values):
            trailer = trailer or line  # notes after the shots: this row and every row below it
            skipped.append((line, f"{(layout.trailer or {}).get('why', 'not a shot')} (from line {trailer})"))
            continue
        if layout.club_rows and cells and cells[0].strip() and not cells[0].strip().isdigit() and not any(
                c.strip() for c in cells[1:]):  # a shot number alone is a shot with nothing measured
            block_club = cells[0].strip()  # SkyTrak: a row holding only a club's name heads that club's shots
            skipped.append((line, f"names the club of the shots below it ({block_club!r})"))
            continue
        summary_row = next(((column, why) for column, values, why in summary
                            if column < len(cells) and _norm(cells[column]) in values), None)
        if summary_row is not None:
            column, why = summary_row
            skipped.append((line, f"{why} ({header[column]} = {cells[column].strip()!r})" if why else
                            f"a summary row ({cells[column].strip()!r}), not a shot"))
            continue
        if required_column is not None and required_column < len(cells) and \
                _norm(cells[required_column]) not in required_values:  # 'yards' is Yards: case is not the unit
            refused.append((line, cells[required_column].strip()))
            continue
        if len(cells) != width:
            problems.append(f"{file}:{line}: expected {width} columns, got {len(cells)}")
            continue
        # a vendor's row (a time, a shot number, values to 16 digits) or a labelled one, repeated: one shot twice;
        # impactlab's own table has no time: identical rounded rows there may be two shots, kept and said
        if (key := tuple(cell.strip() for cell in cells)) in seen and (layout is not GENERIC or (
                "label" in by_field and cells[by_field["label"]].strip())):
            skipped.append((line, f"repeats line {seen[key]} cell for cell (the same shot twice: a session exported "
                                  f"or appended twice, a message sent again)"))
            continue
        if key in seen:
            repeats.append(f"line {line} repeats line {seen[key]}")
        seen.setdefault(key, line)
        shots.append(cells)
        shot_lines.append(line)
        shot_clubs.append(block_club)
    if repeats:
        notes.append(f"{', '.join(repeats[:10])}{' ...' if len(repeats) > 10 else ''} cell for cell: kept as shots "
                     f"(this table has no time or label to tell a copied row from a shot of the same numbers; delete "
                     f"copies)")
    if refused and required_column is not None:
        shown = ", ".join(f"{file}:{line} ({value!r})" for line, value in refused[:10])
        raise StudyError(f"{file}: {header[required_column]}: expected "
                         f"{' or '.join(repr(str(v)) for v in required['values'])}, got {shown}"
                         f"{' and more' if len(refused) > 10 else ''}: {required.get('why', '')}".rstrip(": "))
    size = len(shots)
    if size == 0 and problems:
        raise StudyError(f"{file}: {len(problems)} bad row(s): " + "; ".join(problems[:20]))
    if size == 0:
        raise StudyError(f"{file}: no shots below the header (line {header_line})")
    lines_array = np.array(shot_lines, dtype=np.int64)

    columns = _merge_repeated(list(zip(*shots)) if shots else [], repeated, layout, header, notes)
    values = {field: np.full(size, np.nan) for field in FIELDS}
    text_values = {field: ("",) * size for field in TEXT_FIELDS}
    flags = {}
    used = []
    decimal = _decimal_mark([columns[c] for c, _, field, *_ in plan if field in FIELDS], file)
    if decimal == ",":
        notes.append("decimal commas (every number in the file is written with one)")
    bar = _progress(size * max(len(plan), 1), "reading")
    for column, cell, field, unit, sign, factor in plan:
        raw = columns[column]
        bar.update(size)
        if field in TEXT_FIELDS:
            text_values[field] = tuple(value.strip() for value in raw)
            used.append((cell, field, "", 1.0))
            continue
        numbers, missing_mask, bad = _to_numbers(raw, layout, decimal)
        for index in bad[:20]:
            problems.append(f"{file}:{shot_lines[index]}:{column + 1} ({cell}): expected a number, got "
                            f"{raw[index].strip()!r}")
        if len(bad) > 20:
            problems.append(f"{file}: and {len(bad) - 20} more bad cells in column {cell!r}")
        if layout.sentinel_at_least is not None:
            sentinel = np.abs(numbers) >= layout.sentinel_at_least
            if sentinel.any():
                flags[(field, "no data")] = sentinel
                numbers = np.where(sentinel, np.nan, numbers)
        if field in layout.zero_is_no_data and (placeholder := numbers == 0.0).any():
            flags[(field, "no data")] = flags.get((field, "no data"), np.zeros(size, bool)) | placeholder
            numbers = np.where(placeholder, np.nan, numbers)
        assert factor is not None, "every numeric column of the plan has its unit's scale and offset"
        scale, offset = factor
        values[field] = sign * scale * numbers + offset
        used.append((cell, field, unit or "", sign))
    bar.close()
    if problems:
        shown = "; ".join(problems[:40]) + (f" (and {len(problems) - 40} more)" if len(problems) > 40 else "")
        raise StudyError(f"{file}: {len(problems)} bad cell(s) or row(s): {shown}")

    _flag_estimated(layout, header, columns, values, flags, used, unused, notes)
    _flag_excluded(layout, header, columns, flags, used, unused)
    _flag_no_data(layout, header, columns, values, flags, used, unused)
    _air_from_text(layout, header, columns, values, used, unused, notes, file, shot_lines)
    if layout is GENERIC and "flags" in [_norm(cell) for cell in header]:
        _read_flags(header, columns, flags, used, unused, file, shot_lines)
    stops = [(field, limit, False) for field, limit in layout.clamped.items()]
    for field, limit, floor in stops + [(field, limit, True) for field, limit in layout.floored.items()]:
        with np.errstate(invalid="ignore"):
            clamped = values[field] <= limit + 1e-5 * abs(limit) if floor else \
                np.abs(values[field]) >= limit * (1 - 1e-5)
        if clamped.any():
            flags[(field, "clamped")] = flags.get((field, "clamped"), np.zeros_like(clamped)) | clamped
    _flag_all_zero(layout, values, flags, notes)
    _flag_without(layout, values, flags, notes)
    _derive(values, used, notes, flags)
    _check_spin_signs(layout, values, used, notes, flags)
    _check_air(values, notes, flags)
    if layout.club_rows:
        text_values["club"] = tuple(shot_clubs)
    text_values["club"] = _club_names(layout, text_values["club"], notes)
    handedness = text_values["handedness"]
    bad_hand = sorted({h for h in handedness if h and h.lower() not in ("right", "left", "r", "l", "rh", "lh")})
    if bad_hand:
        raise StudyError(f"{file}: handedness: expected right or left, got {', '.join(map(repr, bad_hand))}")
    text_values["handedness"] = tuple({"r": "right", "rh": "right", "l": "left", "lh": "left"}.get(h.lower(),
                                                                                                  h.lower())
                                      for h in handedness)
    return Session(file=file, vendor=layout, values=values, text=text_values, lines=lines_array, flags=flags,
                   used=used, unused=unused, skipped=skipped, notes=notes)
