"""Launch-monitor shot tables: measured deliveries and launches in, model predictions and their errors out.

A shot table holds one row per shot (or per averaged delivery): the delivery a
launch monitor measures (club speed, attack angle, club path, face angle,
dynamic loft, and the strike location when known), the club head (a preset
name), and what it measured of the ball (ball speed, vertical launch angle,
launch direction, spin rate, spin axis). Files are CSV (units in the header:
``Club Speed [mph]`` or ``club_speed (mph)``) or YAML (``units:`` for bare
numbers, ``rows:``); column names are matched case-insensitively against the
vocabulary and the usual launch-monitor names (``Dyn. Loft``, ``Launch
Direction``...). Every bad cell is reported with its line and column, and
nothing is dropped silently: a table with a bad row is refused whole, with all
its bad rows listed.
"""

from __future__ import annotations

import math
import re
import warnings
import os
from pathlib import Path
from typing import Any

import attrs
import numpy as np

from impactlab.errors import FieldError, PlausibilityWarning, StudyError
from impactlab.units import to_si
from impactlab.model.base import ImpactModel
from impactlab.scene.clubs import Strike
from impactlab.scene.catalogue import CLUB_PRESETS, club_key, club_preset
from impactlab.scene.core import Contact, Delivery, Scene, ball_restitution, complete_inputs
from impactlab.study.scene_blocks import build_ball
from impactlab.study.yaml_lines import line_of, load_yaml, read_text_file
from impactlab.data.documents import ShotTableBlock, structure_document
from impactlab.data.sessions.layouts import maker_of, vendor_maps
from impactlab.data.sessions.reader import DATASETS, GENERIC, Session, read_session, read_session_text
from impactlab.data.sessions.json_records import JSON_SESSIONS
from impactlab.data.sessions.layouts import FIELDS
# the shared definitions live in shot_table (session builds tables too); re-exported: users import them from here
from impactlab.data.sessions.shot_table import (ALIASES as ALIASES, DELIVERY_FIELDS, ERROR_KEYS, MEASURED_FIELDS,
                                               TEXT_FIELDS, ShotTable, _field_of)

def _convert(value, field: str, unit: str | None, where: str) -> float:
    base = field[:-6] if field.endswith("_sigma") else field
    dimension = DELIVERY_FIELDS.get(base) or MEASURED_FIELDS[base]
    if isinstance(value, str):
        value = value.strip()
        if value == "":
            return math.nan
        if unit and not re.search(r"[a-zA-Z%]", value):
            value = f"{value} {unit}"
        elif not unit:
            try:
                value = float(value)
            except ValueError:
                pass
    elif unit is not None and value is not None and not isinstance(value, bool):
        value = f"{value} {unit}"
    if value is None:
        return math.nan
    try:
        return to_si(value, dimension, where)  # which bare numbers are refused (all but 0) is to_si's to say
    except FieldError:
        if isinstance(value, (int, float)) and not isinstance(value, bool):  # worded for a shot table
            raise FieldError(where, "a value with its unit (in the column header, the units: block or the value)",
                             value) from None
        raise


def _session_of_rows(rows: list[dict], file: str, name: str, units: dict, loft_at: str,
                     sigma_defaults: dict) -> Session:
    """A YAML table's parsed rows (SI values, text, ``_line``) as a :class:`~impactlab.data.sessions.reader.Session`, so
    that :meth:`~impactlab.data.sessions.reader.Session.shot_table` is the one assembly of every shot table.

    What the YAML format says and an export does not is settled here: a row's uncertainty defaults to the table's
    ``sigma:`` block; a row that gives neither club path nor face angle (nor face to path) is square, as the table's
    author wrote it (a launch monitor's missing face angle is no measurement and stays missing); a row without a
    label is ``row N``; where any row names its ``source``, every other row's is the table's ``name``.
    """
    values = {field: np.array([row.get(field, math.nan) for row in rows], float) for field in FIELDS}
    for key, default in sigma_defaults.items():
        values[f"{key}_sigma"] = np.where(np.isnan(values[f"{key}_sigma"]), default, values[f"{key}_sigma"])
    values["path"] = np.nan_to_num(values["path"])
    values["face_angle"] = np.where(np.isnan(values["face_angle"]) & np.isnan(values["face_to_path"]), 0.0,
                                    values["face_angle"])
    text = {"label": tuple(str(row.get("label", f"row {i + 1}")) for i, row in enumerate(rows)),
            "club": tuple(str(row.get("club", "")) for row in rows),
            "handedness": tuple(str(row.get("handedness", "right")) for row in rows)}
    if any("source" in row for row in rows):
        text["source"] = tuple(str(row.get("source", name)) for row in rows)
    given = [field for field in FIELDS if any(field in row for row in rows)]
    return Session(file=file, vendor=attrs.evolve(GENERIC, id="impactlab_yaml", name="impactlab YAML shot table",
                                                  loft_at=loft_at),
                   values=values, text=text, lines=np.array([row["_line"] for row in rows], dtype=np.int64),
                   flags={}, used=[(field, field, units.get(field, "the unit written with each value"), 1.0)
                                   for field in given],
                   unused=[], skipped=[], notes=[])


def _check_text(row: dict, where: str, problems: list) -> None:
    if "club" in row:
        key = club_key(row["club"])
        if key is None:
            problems.append(f"{where}: club: expected a club of the catalogue ({', '.join(CLUB_PRESETS)}) or a "
                            f"launch monitor's name of one ('7 Iron', '1w', 'PW', '56°'), got {row['club']!r}")
        else:
            row["club"] = key
    if row.get("handedness", "right") not in ("right", "left"):
        problems.append(f"{where}: handedness: expected right or left, got {row['handedness']!r}")


def read_csv(text: str, file: str = "<csv>", name: str | None = None, source: str = "",
             include_flagged: bool = False) -> ShotTable:
    """A shot table from CSV text: a launch-monitor export as exported, or impactlab's own layout (a header row of
    fields with units, one shot per line); see :mod:`impactlab.data.sessions.reader`. Rows the impact models cannot use
    are skipped with their reason (``ShotTable.skipped``); a cell that cannot be read refuses the file."""
    session = read_session_text(text, file)
    table = session.shot_table(include_flagged)
    if name or source:
        table = attrs.evolve(table, name=name or table.name, source=source or table.source)
    if session.vendor is GENERIC and session.unused:
        warnings.warn(f"{file}: columns not used (not a delivery or launch quantity): {', '.join(session.unused)}",
                      stacklevel=2)
    return table


def read_yaml(text: str, file: str = "<yaml>") -> ShotTable:
    """A shot table from YAML: ``name``, ``source``, optional ``ball``, ``units``, ``sigma``, and ``rows``."""
    document, lines = load_yaml(text, file)
    if not isinstance(document, dict) or "rows" not in document:
        raise StudyError(f"{file}: expected a mapping with name, source, units, sigma and rows")
    # the shape of every block (a mapping where one belongs, text, positive budgets; unknown keys refused) at
    # its file:line; what the values mean is checked below, every bad one reported at once
    keys = [field.name for field in attrs.fields(ShotTableBlock)]  # unknown keys: reported with every other
    block = structure_document({key: value for key, value in document.items() if key in keys}, ShotTableBlock,
                               file, lines)
    units = block.units or {}
    problems = [f"{file}:{line_of(lines, (key,))}: {key}: expected a key of a shot table ({', '.join(keys)})"
                for key in document if key not in keys]
    problems += [f"{file}:{line_of(lines, ('units', key))}: units.{key}: expected a delivery or measured field "
                 f"({', '.join((*DELIVERY_FIELDS, *MEASURED_FIELDS))})"
                 for key in units if key not in DELIVERY_FIELDS and key not in MEASURED_FIELDS]
    instrument = (block.instrument or "").strip().lower()
    makers = instrument_makers()
    if instrument and instrument not in makers:
        problems.append(f"{file}:{line_of(lines, ('instrument',))}: instrument: expected the maker of the monitor, "
                        f"one of {', '.join(makers)}, got {block.instrument!r}")
    loft_at = block.loft_at or "contact"
    if loft_at not in ("contact", "centre"):
        problems.append(f"{file}:{line_of(lines, ('loft_at',))}: loft_at: expected contact (the launch monitor's "
                        f"loft at the impact point) or centre (at the face centre), got {loft_at!r}")
    sigma_defaults = {}
    for key, value in (block.sigma or {}).items():
        if key not in MEASURED_FIELDS:
            problems.append(f"{file}:{line_of(lines, ('sigma', key))}: sigma.{key}: expected one of "
                            f"{', '.join(MEASURED_FIELDS)}")
            continue
        try:
            sigma_defaults[key] = _convert(value, key, None, f"{file}: sigma.{key}")
        except FieldError as exc:
            problems.append(str(exc))
            continue
        if not sigma_defaults[key] > 0:  # the default of every row: said once, at the block's line
            problems.append(f"{file}:{line_of(lines, ('sigma', key))}: sigma.{key}: expected a positive "
                            f"uncertainty, got {sigma_defaults[key]:g} (SI)")
    budgets = block.budgets or {}
    for model, entry in budgets.items():
        if not set(entry) <= set(ERROR_KEYS):
            problems.append(f"{file}:{line_of(lines, ('budgets', model))}: budgets.{model}: expected a mapping of "
                            f"error ({', '.join(repr(k) for k in ERROR_KEYS)}) to a positive RMS")
    rows = []
    for index, item in enumerate(block.rows or []):
        line = line_of(lines, ("rows", index))
        where = f"{file}:{line}"
        if not isinstance(item, dict):
            problems.append(f"{where}: rows[{index}]: expected a mapping of fields")
            continue
        row: dict[str, Any] = {"_line": line}
        for key, value in item.items():
            field, _ = _field_of(str(key))
            if field is None:
                problems.append(f"{file}:{line_of(lines, ('rows', index, key))}: rows[{index}].{key}: expected a "
                                f"field of {', '.join((*DELIVERY_FIELDS, *MEASURED_FIELDS, *TEXT_FIELDS))}")
                continue
            if field in TEXT_FIELDS:
                row[field] = str(value)
                continue
            try:
                row[field] = _convert(value, field, units.get(field), f"{file}:{line_of(lines, ('rows', index, key))}"
                                      f": rows[{index}].{key}")
            except FieldError as exc:
                problems.append(str(exc))
        _check_text(row, where, problems)
        rows.append(row)
    if problems:
        raise StudyError(f"{file}: {len(problems)} problem(s): " + "; ".join(problems))
    if not rows:
        raise StudyError(f"{file}: the shot table has no rows")
    name = block.name if block.name is not None else Path(file).stem
    # a table written by hand is refused whole for a row the models cannot use (an export skips that row)
    table = _session_of_rows(rows, file, name, units, loft_at, sigma_defaults).shot_table(every_row=True)
    return attrs.evolve(table, name=name, source=block.source or "", ball=dict(block.ball or {}), budgets=budgets,
                        instrument=instrument)


def instrument_makers() -> list[str]:
    """The monitor makers a shot table may name (``instrument:``): those the shipped layouts name (layouts.maker_of)."""
    return sorted({maker_of(key) for key in vendor_maps()} - {""})


def read_shots(path: str | os.PathLike[str], include_flagged: bool = False) -> ShotTable:
    """A shot table from a .csv file (a launch-monitor export as exported, or impactlab's layout) or a .yaml/.yml
    file; ``include_flagged`` keeps estimated and clamped values in the comparison."""
    if str(path) in DATASETS and not Path(path).exists():  # a session dataset shipped with impactlab, by name
        return read_session(str(path)).shot_table(include_flagged)
    path = Path(path)
    if not path.exists():
        raise StudyError(f"{path}: no such shot table (a .csv, .yaml or JSON session file)")
    if path.suffix.lower() in (".csv", ".gz", *JSON_SESSIONS):
        return read_session(path).shot_table(include_flagged)
    text = read_text_file(path, "shot table")  # folders, devices, binary and UTF-16 files said as such
    if path.suffix.lower() in (".yaml", ".yml"):
        return read_yaml(text, str(path))
    raise StudyError(f"{path}: expected a .csv, .yaml or JSON (.json, .jsonl, .session) shot table")


# -- predictions -----------------------------------------------------------------------------------------------
def table_inputs(table: ShotTable, ball_block: dict | None = None, contact: dict | None = None,
                 club_reference: str = "centre_of_mass") -> dict:
    """Model inputs (SI arrays) of every row: its club preset, its delivery and strike, and the ball.

    ``ball_block`` is a study ``ball:`` mapping (default: the table's, else ``{preset: urethane_tour}``);
    ``contact`` overrides the ball's friction and restitution (``{friction, restitution}``); ``club_reference`` is
    the point of the head whose velocity the rows' club speed, path and attack angle are
    (:class:`impactlab.scene.core.Delivery`; TrackMan: the head's geometric centre, near its centre of mass).
    """
    ball = build_ball(ball_block or table.ball or {"preset": "urethane_tour"})
    contact_law = Contact(**(contact or {}))
    # the ball's restitution law is evaluated once for all rows below (at the centred delivery), not per scene
    scene_ball = attrs.evolve(ball, restitution=None) if contact_law.restitution is None else ball
    scenes = []
    with warnings.catch_warnings():
        if table.unusual is not None:  # a session's unusual values are counted per column by its reader, not
            warnings.simplefilter("ignore", PlausibilityWarning)  # warned row by row
        for index in range(table.size):
            scenes.append(_scene(table, index, scene_ball, contact_law, club_reference))
    per_scene = [scene.inputs() for scene in scenes]  # once each: inputs() evaluates the ball's law
    keys = set.intersection(*(set(values) for values in per_scene))
    inputs = complete_inputs({key: np.array([values[key] for values in per_scene]) for key in sorted(keys)})
    if contact_law.restitution is None and ball.restitution is not None:
        inputs["restitution"] = ball_restitution(ball, inputs)  # at the normal speed of the contact
    return inputs


def _scene(table: ShotTable, index: int, scene_ball, contact_law, club_reference: str) -> Scene:
    """The scene of one row: its club preset, delivery and strike."""
    club = club_preset(table.clubs[index])
    d = {key: float(value[index]) for key, value in table.delivery.items()}
    delivery = Delivery(d["club_speed"], path=d["path"], face_angle=d["face_angle"],
                        attack_angle=d["attack_angle"], dynamic_loft=d["dynamic_loft"],
                        handedness=table.handedness[index], loft_at=table.loft_at,
                        club_reference=club_reference)
    return Scene.from_delivery(scene_ball, Scene.face_of(club), contact_law, delivery, 0.0, club,
                               Strike(d["strike_toe"], d["strike_high"]))


def predict(model: ImpactModel, inputs: dict) -> dict:
    """The measured quantities as the model predicts them (SI arrays)."""
    result = model.compute_arrays(inputs, list(MEASURED_FIELDS))
    return {name: result[name] for name in MEASURED_FIELDS}


def shot_errors(predicted: dict, table: ShotTable) -> dict:
    """Per row: ball speed [%], launch angle [deg], launch direction [deg], spin [%], spin axis [deg] (NaN: not
    measured)."""
    m = table.measured
    with np.errstate(invalid="ignore", divide="ignore"):
        return {
            "ball_speed [%]": 100.0 * (predicted["ball_speed"] / m["ball_speed"] - 1.0),
            "launch angle [deg]": np.degrees(predicted["vertical_launch_angle"] - m["vertical_launch_angle"]),
            "launch direction [deg]": np.degrees(predicted["horizontal_launch_angle"]
                                                 - m["horizontal_launch_angle"]),
            "spin [%]": 100.0 * (predicted["spin_rate"] / m["spin_rate"] - 1.0),
            "spin axis [deg]": np.degrees(predicted["spin_axis"] - m["spin_axis"]),
        }


def summary(errors: dict) -> dict:
    """RMS of each error over the rows where it was measured (NaN: nowhere)."""
    out = {}
    for key, values in errors.items():
        finite = values[np.isfinite(values)]
        out[key] = float(np.sqrt(np.mean(finite**2))) if finite.size else math.nan
    return out


def errors_by_source(errors: dict, table: ShotTable) -> dict:
    """RMS of each error (:func:`shot_errors`) over the rows of each source: source -> :func:`summary`, the sources
    in the order they first appear."""
    sources = np.asarray(table.sources)
    out = {}
    for source in dict.fromkeys(table.sources):
        rows = sources == source
        out[source] = summary({key: np.asarray(values)[rows] for key, values in errors.items()})
    return out
