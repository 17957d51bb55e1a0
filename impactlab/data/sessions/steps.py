"""The steps of reading an export's text (:func:`impactlab.data.sessions.reader.read_session_text`), one function each:
the header and its layout, the units row, the rows (shots, summary rows, repeated headers, ragged rows), the
numbers of each column (sentinels read as missing, unreadable cells kept as the row's problem), the flags the layout
implies, and the air. Each step fills a :class:`_Reading`; the reader strings them together.
"""

from __future__ import annotations

import attrs
import numpy as np

from impactlab.errors import StudyError
from impactlab.data.sessions.layouts import (FIELDS, GENERIC, TEXT_FIELDS, VendorMap, _header_index,
                                            _norm, _recognise, split_header)
from impactlab.data.sessions.json_records import json_rows, looks_like_json
from impactlab.data.sessions.values import (_UNITS_CELL, _decimal_mark, _merge_repeated, _progress, _row_key,
                                           _rows_of, _to_numbers, _units_difference)

#: a scaled sentinel matches its value times 10^k to this relative precision (exports round to 6 digits:
#: -2.14748e+10 is -2^31 x 10 to 2e-6)
SENTINEL_PRECISION = 5e-6


@attrs.define
class _Reading:
    """What the steps have read so far (one export)."""

    file: str
    layout: VendorMap
    header: list
    header_line: int
    notes: list
    body: list = attrs.field(factory=list)
    body_lines: list = attrs.field(factory=list)
    units_row: list | None = None
    body_units: list | None = None
    units_line: int = 0
    problems: list = attrs.field(factory=list)
    skipped: list = attrs.field(factory=list)
    shots: list = attrs.field(factory=list)
    shot_lines: list = attrs.field(factory=list)
    shot_clubs: list = attrs.field(factory=list)
    #: (field, kind) -> {row index: the cell's text}: cells no number could be read from (the row is skipped)
    unreadable: dict = attrs.field(factory=dict)


def read_header(text: str, file: str, vendor: str | None) -> _Reading:
    """Step 1: the rows of the text, the header row and the layout that recognises it."""
    rows, lines, notes = json_rows(text, file) if looks_like_json(text) else _rows_of(text, file)
    start = _header_index(rows, vendor)
    if not rows or not any(cell.strip() for cell in rows[start]):
        raise StudyError(f"{file}: empty file; expected a header row of columns")
    header = [cell.strip() for cell in rows[start]]
    while header and not header[-1]:  # a trailing separator (Foresight, TrackMan's empty last column)
        header.pop()
    layout = _recognise(header, vendor, file)
    preamble = [line for line, cells in zip(lines[:start], rows[:start]) if any(c.strip() for c in cells)]
    if preamble:
        notes.append(f"line(s) {', '.join(map(str, preamble))} before the header are a title, not shots")
    return _Reading(file=file, layout=layout, header=header, header_line=lines[start], notes=notes,
                    body=rows[start + 1:], body_lines=lines[start + 1:])


def read_units(reading: _Reading) -> None:
    """Step 2: the units row under the header (bracketed cells, or a layout's plain units), and empty rows out."""
    body, body_lines, layout = reading.body, reading.body_lines, reading.layout
    if body and any(cell.strip() for cell in body[0]) and (layout.units_row_plain or all(
            _UNITS_CELL.match(cell) or not cell.strip() for cell in body[0])):  # SkyTrak: MPH, DEG without brackets
        reading.units_row = [cell.strip() if layout.units_row_plain else cell.strip()[1:-1].strip()
                             for cell in body[0]]
        reading.body_units, reading.units_line = body[0], body_lines[0]
        reading.notes.append(f"units row at line {body_lines[0]}")
        body, body_lines = body[1:], body_lines[1:]
    keep = [i for i, cells in enumerate(body) if any(cell.strip() for cell in cells)]
    reading.body = [body[i] for i in keep]
    reading.body_lines = [body_lines[i] for i in keep]


def _rule_column(names: list, rule: dict | None) -> int | None:
    return names.index(_norm(rule["column"])) if rule and _norm(rule["column"]) in names else None


def read_rows(reading: _Reading, by_field: dict) -> None:
    """Step 3: the shots among the rows below the header. Summary rows, repeated headers and units rows, a trailer,
    club-name rows and repeated shots are skipped with their reason; a row of another width than the header is
    skipped too (a bad row never sinks the file); a second header of other columns, units rows that differ, and a
    value a layout requires that a row lacks refuse the file (they are no row's fault)."""
    layout, header = reading.layout, reading.header
    names = [_norm(split_header(c)[0]) for c in header]
    summary = [(names.index(_norm(rule["column"])), {_norm(v) for v in rule["values"]}, rule.get("why"))
               for rule in layout.summary_rows or [] if _norm(rule["column"]) in names]
    required = layout.required or {"column": None, "values": []}
    required_column = _rule_column(names, layout.required)
    required_values = {_norm(str(value)) for value in required["values"]}
    trailer_values = {_norm(v) for v in (layout.trailer or {}).get("values", ())}
    trailer_column = _rule_column(names, layout.trailer)
    walk = _Walk(header_key=_row_key(header),
                 units_key=None if reading.units_row is None else _row_key(reading.body_units))
    refused = []
    for cells, line in zip(reading.body, reading.body_lines):
        while len(cells) > len(header) and not cells[-1].strip():
            cells = cells[:-1]
        if _block_row(reading, walk, cells, line):
            continue
        if walk.trailer is not None or (trailer_column is not None and trailer_column < len(cells)
                                        and _norm(cells[trailer_column]) in trailer_values):
            walk.trailer = walk.trailer or line  # notes after the shots: this row and every row below it
            reading.skipped.append((line, f"{(layout.trailer or {}).get('why', 'not a shot')} (from line "
                                          f"{walk.trailer})"))
            continue
        if layout.club_rows and cells and cells[0].strip() and not cells[0].strip().isdigit() and not any(
                c.strip() for c in cells[1:]):  # a shot number alone is a shot with nothing measured
            walk.block_club = cells[0].strip()  # SkyTrak: a row holding only a club's name heads that club's shots
            reading.skipped.append((line, f"names the club of the shots below it ({walk.block_club!r})"))
            continue
        summary_row = next(((column, why) for column, values, why in summary
                            if column < len(cells) and _norm(cells[column]) in values), None)
        if summary_row is not None:
            column, why = summary_row
            reading.skipped.append((line, f"{why} ({header[column]} = {cells[column].strip()!r})" if why else
                                    f"a summary row ({cells[column].strip()!r}), not a shot"))
            continue
        if required_column is not None and required_column < len(cells) and \
                _norm(cells[required_column]) not in required_values:  # 'yards' is Yards: case is not the unit
            refused.append((line, cells[required_column].strip()))
            continue
        if len(cells) != len(header):  # a row cut short or run on: its cells cannot be told apart
            reading.skipped.append((line, f"a row of {len(cells)} cells under a header of {len(header)} columns "
                                          f"(cut short or run on), not read"))
            continue
        _keep_shot(reading, walk, cells, line, by_field)
    if walk.repeats:
        reading.notes.append(f"{', '.join(walk.repeats[:10])}{' ...' if len(walk.repeats) > 10 else ''} cell for "
                             f"cell: kept as shots (this table has no time or label to tell a copied row from a shot "
                             f"of the same numbers; delete copies)")
    if refused and required_column is not None:
        shown = ", ".join(f"{reading.file}:{line} ({value!r})" for line, value in refused[:10])
        raise StudyError(f"{reading.file}: {header[required_column]}: expected "
                         f"{' or '.join(repr(str(v)) for v in required['values'])}, got {shown}"
                         f"{' and more' if len(refused) > 10 else ''}: {required.get('why', '')}".rstrip(": "))
    if not reading.shots and reading.problems:
        raise StudyError(f"{reading.file}: {len(reading.problems)} bad row(s): " + "; ".join(reading.problems[:20]))
    if not reading.shots:
        raise StudyError(f"{reading.file}: no shots below the header (line {reading.header_line})")


@attrs.define
class _Walk:
    """The state of the walk through the rows: the last header seen, the club block, the shots seen."""

    header_key: tuple
    units_key: tuple | None
    after_header: bool = False
    trailer: int | None = None
    block_club: str = ""
    seen: dict = attrs.field(factory=dict)
    repeats: list = attrs.field(factory=list)


def _block_row(reading: _Reading, walk: _Walk, cells: list, line: int) -> bool:
    """Whether ``cells`` is the header again, its units row again, or a second header of other columns (a new block
    of the export or a second export appended): skipped or refused here; True when the row is consumed."""
    if _row_key(cells) == walk.header_key:  # Rapsodo writes the header above every club's shots
        reading.skipped.append((line, "the header again (a new block of the export), not a shot"))
        walk.after_header = True
        return True
    if walk.after_header and reading.units_row is not None and (_row_key(cells) == walk.units_key or all(
            _UNITS_CELL.match(c) or not c.strip() for c in cells)):
        if _row_key(cells) != walk.units_key:  # blocks in different units would be read in the first's
            differs = _units_difference(reading.header, reading.body_units, cells)
            reading.problems.append(f"{reading.file}:{line}: a units row that differs from the one at line "
                                    f"{reading.units_line} ({differs}): the file joins blocks in different units; "
                                    f"export or read them separately")
        else:
            reading.skipped.append((line, "the units row again, under the repeated header"))
        walk.after_header = False
        return True
    walk.after_header = False
    layout = reading.layout
    if layout is not GENERIC and set(layout.recognise) <= {_norm(split_header(c)[0]) for c in cells}:
        reading.problems.append(f"{reading.file}:{line}: a second header, with other columns than line "
                                f"{reading.header_line}'s: the file joins two exports (or app versions) of different "
                                f"columns; read them separately")
        return True
    return False


def _keep_shot(reading: _Reading, walk: _Walk, cells: list, line: int, by_field: dict) -> None:
    """Keep a shot, unless it repeats an earlier row cell for cell: a vendor's row (a time, a shot number, values to
    16 digits) or a labelled one repeated is one shot twice; impactlab's own table has no time, so identical rounded
    rows there may be two shots, kept and said."""
    key = tuple(cell.strip() for cell in cells)
    if key in walk.seen and (reading.layout is not GENERIC or (
            "label" in by_field and cells[by_field["label"]].strip())):
        reading.skipped.append((line, f"repeats line {walk.seen[key]} cell for cell (the same shot twice: a session "
                                      f"exported or appended twice, a message sent again)"))
        return
    if key in walk.seen:
        walk.repeats.append(f"line {line} repeats line {walk.seen[key]}")
    walk.seen.setdefault(key, line)
    reading.shots.append(cells)
    reading.shot_lines.append(line)
    reading.shot_clubs.append(walk.block_club)


def sentinel_mask(numbers: np.ndarray, layout: VendorMap) -> tuple[np.ndarray, str]:
    """Cells holding one of the layout's numeric no-value markers (as written, before any unit), and why."""
    marked = np.zeros(numbers.shape, bool)
    why = []
    with np.errstate(invalid="ignore", divide="ignore"):
        if layout.sentinel_at_least is not None:
            beyond = np.abs(numbers) >= layout.sentinel_at_least
            if beyond.any():
                why.append(f"a no-value marker (at least {layout.sentinel_at_least:g} in magnitude)")
            marked |= beyond
        for rule in layout.sentinels:
            ratio = numbers / rule["value"]
            if rule["scaled"]:  # the marker times 10^k: a ratio that is a power of ten
                exponent = np.round(np.log10(np.where(ratio > 0, ratio, np.nan)))
                hit = np.abs(ratio / 10.0 ** exponent - 1.0) <= SENTINEL_PRECISION
            else:
                hit = np.abs(ratio - 1.0) <= SENTINEL_PRECISION
            hit &= np.isfinite(numbers)
            if hit.any():
                why.append(rule["why"])
            marked |= hit
    return marked, "; ".join(why)


def read_columns(reading: _Reading, plan: list, repeated: list):
    """Step 4: each planned column's cells as numbers (SI, the layout's sign), its text fields as text. A no-value
    marker (text or number) is missing and flagged ``no data``; a cell no number can be read from is kept as its
    row's problem (the row is skipped with it), unless no cell of its column can be read: then the header does
    not describe the rows, and the file is refused at the first cell."""
    layout, file, size = reading.layout, reading.file, len(reading.shots)
    columns = _merge_repeated(list(zip(*reading.shots)), repeated, layout, reading.header, reading.notes)
    values = {field: np.full(size, np.nan) for field in FIELDS}
    text_values = {field: ("",) * size for field in TEXT_FIELDS}
    flags: dict = {}
    used: list = []
    decimal = _decimal_mark([columns[c] for c, _, field, *_ in plan if field in FIELDS], file)
    if decimal == ",":
        reading.notes.append("decimal commas (every number in the file is written with one)")
    bar = _progress(size * max(len(plan), 1), "reading")
    for column, cell, field, unit, sign, factor in plan:
        raw = columns[column]
        bar.update(size)
        if field in TEXT_FIELDS:
            text_values[field] = tuple(value.strip() for value in raw)
            used.append((cell, field, "", 1.0))
            continue
        numbers, missing_mask, bad = _to_numbers(raw, layout, decimal)
        if bad and len(bad) == int((~missing_mask).sum()):
            reading.problems.append(f"{file}:{reading.shot_lines[bad[0]]}:{column + 1} ({cell}): expected a number, "
                                    f"got {raw[bad[0]].strip()!r} (no cell of the column is a number: the header does "
                                    f"not describe the rows)")
        elif bad:
            reading.unreadable[(field, cell)] = {index: raw[index].strip() for index in bad}
        marked, why = sentinel_mask(numbers, layout)
        written = missing_mask & np.array([bool(value.strip()) for value in raw])  # '-', 'N/A': a marker, said
        if written.any():
            marked |= written
            shown = sorted({raw[index].strip() for index in np.flatnonzero(written)[:50].tolist()})
            why = "; ".join(filter(None, [why, f"a no-value word ({', '.join(map(repr, shown))})"]))
        if field in layout.zero_is_no_data:
            marked |= numbers == 0.0
        if marked.any():
            flags[(field, "no data")] = flags.get((field, "no data"), np.zeros(size, bool)) | marked
            numbers = np.where(marked, np.nan, numbers)
            if why:
                reading.notes.append(f"{cell}: {int(marked.sum())} row(s) hold {why}: read as missing")
        assert factor is not None, "every numeric column of the plan has its unit's scale and offset"
        scale, offset = factor
        values[field] = sign * scale * numbers + offset
        used.append((cell, field, unit or "", sign))
    bar.close()
    if reading.problems:
        listed = "; ".join(reading.problems[:40]) + (f" (and {len(reading.problems) - 40} more)"
                                                     if len(reading.problems) > 40 else "")
        raise StudyError(f"{file}: {len(reading.problems)} bad cell(s) or row(s): {listed}")
    return columns, values, text_values, flags, used


def flag_tracked(layout: VendorMap, values: dict, flags: dict, notes: list) -> None:
    """The flights a monitor tracked for less than ``layout.tracked['at_least']`` of their hang time: their flight
    values are the monitor's model output, flagged ``modelled`` (kept, and left out of comparisons)."""
    rule = layout.tracked
    if not rule:
        return
    tracked, hang = values[rule["time"]], values[rule["of"]]
    with np.errstate(invalid="ignore", divide="ignore"):
        fraction = tracked / hang
    known = np.isfinite(fraction)
    modelled = known & (fraction < rule["at_least"])
    for field in rule["fields"]:
        present = modelled & np.isfinite(values[field])
        if present.any():
            flags[(field, "modelled")] = present
    notes.append(f"flight tracked for at least {100 * rule['at_least']:g} % of its hang time in "
                 f"{int((known & ~modelled).sum())} row(s) (measured), for less in {int(modelled.sum())} (the "
                 f"monitor's model output, flagged modelled), not known in {int((~known).sum())}")


def clamp_flags(layout: VendorMap, values: dict, flags: dict) -> None:
    """Values at the monitor's stops (``clamped``: at or beyond the limit; ``floored``: at or below it)."""
    stops = [(field, limit, False) for field, limit in layout.clamped.items()]
    for field, limit, floor in stops + [(field, limit, True) for field, limit in layout.floored.items()]:
        with np.errstate(invalid="ignore"):
            clamped = values[field] <= limit + 1e-5 * abs(limit) if floor else \
                np.abs(values[field]) >= limit * (1 - 1e-5)
        if clamped.any():
            flags[(field, "clamped")] = flags.get((field, "clamped"), np.zeros_like(clamped)) | clamped


def handedness_of(values: tuple, file: str) -> tuple:
    """Handedness per row as ``right`` or ``left`` (R, RH, L, LH accepted; anything else refused)."""
    bad = sorted({h for h in values if h and h.lower() not in ("right", "left", "r", "l", "rh", "lh")})
    if bad:
        raise StudyError(f"{file}: handedness: expected right or left, got {', '.join(map(repr, bad))}")
    return tuple({"r": "right", "rh": "right", "l": "left", "lh": "left"}.get(h.lower(), h.lower()) for h in values)

