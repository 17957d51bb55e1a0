"""The air a launch-monitor export states for its shots: its temperature, pressure, humidity and density in columns
(Garmin), or in words in a text column (TrackMan's Condition), read into the session's air fields and checked
against each other; :func:`impactlab.data.sessions.flight.fly_session` flies each shot in it.
"""

from __future__ import annotations

import re

import numpy as np

from impactlab.data.sessions.layouts import FIELDS, _norm, _unit_factor, split_header
from impactlab.errors import FieldError, StudyError
from impactlab.physics.atmosphere import air_density


#: how far a stated air density may lie from the density of the stated temperature, pressure and humidity (Garmin's
#: own agrees with impactlab.physics.atmosphere.air_density to 0.01 % on the real exports; a temperature read in the
#: wrong unit moves it by 5 % or more: 1 degF against 1 degC at 15 degC is 1.9 %, 60 degF read as degC 15 %)
AIR_DENSITY_TOLERANCE = 0.01
#: each air field's SI value in the words people read it in (reports and messages)
AIR_IN_WORDS = {"air_temperature": lambda x: f"{x - 273.15:.1f} degC ({x:.2f} K)",
                "air_pressure": lambda x: f"{x / 100:.1f} hPa", "altitude": lambda x: f"{x:.0f} m",
                "relative_humidity": lambda x: f"{100 * x:.0f} %"}


def _check_air(values: dict, notes: list, flags: dict) -> None:
    """Rows stating their air density beside its temperature, pressure and humidity: where the density is not the
    one those give (:data:`AIR_DENSITY_TOLERANCE`), a unit or a column is wrong; the four are flagged
    ``inconsistent`` (that air is not flown) and the report gives the first row's two densities."""
    fields = ("air_temperature", "air_pressure", "relative_humidity", "air_density")
    stated = values["air_density"]
    complete = np.all([np.isfinite(values[field]) for field in fields], axis=0)
    if not complete.any():
        return
    with np.errstate(invalid="ignore", divide="ignore"):
        computed = air_density(values["air_temperature"], values["air_pressure"], values["relative_humidity"])
        off = complete & ~(np.abs(stated / computed - 1.0) <= AIR_DENSITY_TOLERANCE)
    if not off.any():
        notes.append(f"air density: as its temperature, pressure and humidity give it, within "
                     f"{100 * AIR_DENSITY_TOLERANCE:g} %, in all {int(complete.sum())} row(s) stating the four")
        return
    for field in fields:
        flags[(field, "inconsistent")] = off
    first = int(np.flatnonzero(off)[0])
    notes.append(f"air density differs from the density of its temperature, pressure and humidity by more than "
                 f"{100 * AIR_DENSITY_TOLERANCE:g} % in {int(off.sum())} of {int(complete.sum())} row(s) (first: "
                 f"{stated[first]:.4f} kg/m^3 stated, {computed[first]:.4f} computed from " + ", ".join(
                     AIR_IN_WORDS[field](values[field][first]) for field in fields[:3])
                 + "): a unit or a column is wrong; that air is flagged inconsistent and not flown")


def _air_from_text(layout, header, columns, values, used, unused, notes, file: str, lines) -> None:
    """The air a layout's text column states in words (``layout.air_text``: TrackMan's Condition, "Data are
    normalized to no wind conditions at 0 ft altitude, 76.99999999999994 ℉ with a Premium ball"): each named group
    of its pattern, a number with its unit, read into its field (the unit spelled as the layout's units are; a
    capture whose unit is not one of its field is refused at the cell, never guessed)."""
    rule = layout.air_text
    if not rule:
        return
    names = [_norm(split_header(cell)[0]) for cell in header]
    if _norm(rule["column"]) not in names:
        return
    column = names.index(_norm(rule["column"]))
    pattern = re.compile(rule["pattern"])
    cells = columns[column]
    found: dict[str, np.ndarray] = {field: np.full(len(cells), np.nan) for field in pattern.groupindex}
    for row, cell in enumerate(cells):
        match = pattern.search(str(cell))
        if match is None:
            continue
        for field, text in match.groupdict().items():
            if text is None:
                continue
            quantity = _NUMBER_AND_UNIT.match(text)
            where = f"{file}:{lines[row]}:{column + 1} ({header[column]})"
            if quantity is None:
                raise StudyError(f"{where}: {field}: expected a number and its unit, got {text!r}")
            try:
                scale, offset = _unit_factor(quantity.group(2), FIELDS[field], f"{where}: {field}")
            except FieldError as exc:  # a unit that is not one of the field's: refused at the cell, never guessed
                raise StudyError(str(exc)) from None
            found[field][row] = float(quantity.group(1)) * scale + offset
    stated = {field: array for field, array in found.items() if np.isfinite(array).any()}
    if not stated:
        return
    for field, array in stated.items():
        values[field] = np.where(np.isfinite(array), array, values[field])
    if header[column] in unused:
        unused.remove(header[column])
    used.append((header[column], "air stated in words: " + ", ".join(stated), "", 1.0))
    rows = int(np.any([np.isfinite(array) for array in stated.values()], axis=0).sum())
    notes.append(f"{header[column]}: the air stated in words in {rows} row(s) (" + ", ".join(
        _air_words(field, array) for field, array in stated.items()) + ")")


#: a number and the unit written after it, with or without a space ("0 ft", "76.99999999999994 ℉", "25℃")
_NUMBER_AND_UNIT = re.compile(r"^\s*([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(.*?)\s*$")


def _air_words(field: str, array: np.ndarray) -> str:
    finite = array[np.isfinite(array)]
    low, high = finite.min(), finite.max()
    form = AIR_IN_WORDS[field]
    return f"{field.replace('_', ' ')} {form(low)}" + ("" if low == high else f" to {form(high)}")
