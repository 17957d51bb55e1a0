"""How a header row becomes columns: for each cell the field it gives, its unit (in the header, a units row or
implied by the layout), its sign and its scale to SI (:func:`_column_plan`), for a vendor layout or for
impactlab's own (:func:`_generic_field`)."""

from __future__ import annotations

from impactlab.errors import FieldError, StudyError
from impactlab.data.sessions.layouts import (DESCRIPTIONS, FIELDS, GENERIC, TEXT_FIELDS, ColumnRule, VendorMap, _norm,
                                            _unit_factor, split_header)
from impactlab.data.sessions.shot_table import _field_of


def _generic_field(header: str) -> tuple[str | None, str | None]:
    """(field, unit) of a column of impactlab's own layout (vocabulary names and the usual aliases)."""
    field, unit = _field_of(header)
    if field is None:
        name, unit = split_header(header)
        key = _norm(name).replace(" ", "_")
        key = {"carry": "carry_distance", "total": "total_distance", "apex": "apex_height",
               "backspin": "back_spin", "sidespin": "side_spin", "back_spin": "back_spin",
               "offline": "offline_distance", "smash": "smash_factor", "face_to_path": "face_to_path",
               "club_path": "path", "club_face": "face_angle",
               # impactlab.fly's and `impactlab fly`'s names of the launch (one vocabulary in and out)
               "launch_angle": "vertical_launch_angle", "launch_direction": "horizontal_launch_angle"}.get(key, key)
        if key in FIELDS or key in TEXT_FIELDS:
            return key, unit
        return None, unit
    return field, unit


def _column_plan(header: list[str], layout: VendorMap, units_row: list[str] | None, file: str,
                 header_line: int) -> tuple[list, list, list]:
    """(plan, unused, repeated) of a header: for each column read, (column, cell, field, unit, sign, (scale,
    offset) or None for a text field); the header cells no rule reads; the (first, repeat) columns of a field a
    layout writes twice. Every problem (two columns for one field, two units for one column, a quantity without its
    unit, a unit of the wrong kind) is collected and refused at once, with the file, line and column."""
    problems = []
    plan, unused, repeated = [], [], []
    by_field: dict[str, int] = {}
    for column, cell in enumerate(header):
        if not cell:
            continue
        if layout is GENERIC:
            field, unit = _generic_field(cell)
            rule = None if field is None else ColumnRule(field)
        else:
            rule = layout.rule(cell, units_row[column] if units_row and column < len(units_row) else None)
            unit = split_header(cell)[1]
        if rule is None:
            unused.append(cell)
            continue
        field = rule.field
        if field in by_field and layout.merge_repeated_columns and _norm(cell) == _norm(header[by_field[field]]):
            repeated.append((by_field[field], column))  # FlightScope writes some columns twice: merged, said
            continue
        if field in by_field:
            problems.append(f"{file}:{header_line}: columns {header[by_field[field]]!r} and {cell!r} both give "
                            f"the {DESCRIPTIONS[field]} ({field}); keep one")
            continue
        by_field[field] = column
        if field in FIELDS:
            if units_row is not None and column < len(units_row) and units_row[column]:
                if unit is not None and _norm(unit) != _norm(units_row[column]):
                    problems.append(f"{file}:{header_line}: column {cell!r} states two units ({unit!r} in its "
                                    f"name, {units_row[column]!r} in the units row)")
                unit = units_row[column]
            if unit is None and layout.units == "implied":
                unit = layout.implied_units.get(_norm(split_header(cell)[0]))
            where = f"{file}:{header_line}:{column + 1} ({cell})"
            if unit is None and FIELDS[field] != "dimensionless":
                problems.append(f"{where}: expected a unit for the {DESCRIPTIONS[field]}: in brackets, in the "
                                f"header ('{split_header(cell)[0]} [mph]'-style: '{split_header(cell)[0]} [unit]') or "
                                f"in a units row right under it ('[mph]', '[deg]', '[rpm]': every unit in brackets, "
                                f"else the row is read as a shot); a number without its unit is not read (115 could "
                                f"be mph or m/s)")
                continue
            unit = layout.unit_spellings.get(_norm(unit), unit) if unit else unit  # the layout's own spellings
            try:
                factor = _unit_factor(unit or "", FIELDS[field], where)
            except FieldError as exc:
                problems.append(str(exc))
                continue
        else:
            factor = None
        plan.append((column, cell, field, unit, rule.sign, factor))
    if problems:
        raise StudyError(f"{file}: " + "; ".join(problems))
    return plan, unused, repeated
