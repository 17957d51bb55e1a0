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

import csv
import io
import math
import re
from pathlib import Path

import attrs
import numpy as np

from impactlab.errors import FieldError, StudyError
from impactlab.scene.plausibility import wrong_sign
from impactlab.units import to_si

#: field -> physical dimension (a value always comes with its unit: a bare mph/m/s mix-up is the classic misreading)
DELIVERY_FIELDS = {
    "club_speed": "speed", "attack_angle": "angle", "path": "angle", "face_angle": "angle", "dynamic_loft": "angle",
    "strike_toe": "length", "strike_high": "length",
}
MEASURED_FIELDS = {
    "ball_speed": "speed", "vertical_launch_angle": "angle", "horizontal_launch_angle": "angle",
    "spin_rate": "angular_speed", "spin_axis": "angle",
}
TEXT_FIELDS = ("label", "club", "handedness")
#: top-level keys of a YAML shot table
TABLE_KEYS = ("name", "source", "ball", "units", "sigma", "loft_at", "budgets", "rows")
#: usual launch-monitor column names -> field (lower case, single spaces)
ALIASES = {
    "club speed": "club_speed", "clubspeed": "club_speed", "club head speed": "club_speed",
    "attack angle": "attack_angle", "aoa": "attack_angle", "angle of attack": "attack_angle",
    "club path": "path", "face angle": "face_angle", "dynamic loft": "dynamic_loft", "dyn. loft": "dynamic_loft",
    "dyn loft": "dynamic_loft", "impact offset": "strike_toe", "impact height": "strike_high",
    "ball speed": "ball_speed", "launch angle": "vertical_launch_angle", "launch direction": "horizontal_launch_angle",
    "spin rate": "spin_rate", "total spin": "spin_rate", "spin axis": "spin_axis", "shot": "label", "name": "label",
}
#: the errors of a prediction against a shot table, in the data's own units
ERROR_KEYS = ("ball_speed [%]", "launch angle [deg]", "launch direction [deg]", "spin [%]", "spin axis [deg]")
#: default one-sigma uncertainty of a shot (SI), used where a table gives none: this project's assumption of how well
#: one launch-monitor shot or average represents its delivery, not a manufacturer's figure
DEFAULT_SIGMA = {"ball_speed": 0.5, "vertical_launch_angle": math.radians(0.3),
                 "horizontal_launch_angle": math.radians(0.3), "spin_rate": 200.0 * 2 * math.pi / 60,
                 "spin_axis": math.radians(1.0)}


@attrs.frozen
class ShotTable:
    """Rows of measured shots, SI values (NaN: not measured), with the table's provenance.

    Attributes
    ----------
    name, source : str
        What the table is, and where each number comes from (measurement or model output).
    labels, clubs, handedness : tuple of str
    delivery : dict of ndarray
        ``DELIVERY_FIELDS`` per row [SI].
    measured, sigma : dict of ndarray
        ``MEASURED_FIELDS`` per row and their one-sigma uncertainties [SI].
    ball : dict
        The ball block the table names (a study ``ball:`` mapping), or empty.
    loft_at : str
        Where the table's dynamic loft and face angle were measured: ``contact`` (default; what a launch
        monitor reports: TrackMan defines dynamic loft as the loft "at the center-point of contact between the
        club and ball") or ``centre`` (the face centre, as impactlab's delivery counts them). On a bulged and
        rolled face a strike off the centre meets a face turned by atan(offset/radius), so a ``contact`` table's
        deliveries are turned back to the face centre before the models see them (:func:`centre_delivery`).
    """

    name: str
    source: str
    labels: tuple[str, ...]
    clubs: tuple[str, ...]
    handedness: tuple[str, ...]
    delivery: dict = attrs.field(eq=False)
    measured: dict = attrs.field(eq=False)
    sigma: dict = attrs.field(eq=False)
    ball: dict = attrs.field(factory=dict, eq=False)
    loft_at: str = attrs.field(default="contact", validator=attrs.validators.in_(("contact", "centre")))
    #: model id -> {error key of :data:`ERROR_KEYS` -> largest allowed RMS}: regression budgets, not the data's
    #: uncertainty (tests/test_shots.py holds them and checks they only tighten)
    budgets: dict = attrs.field(factory=dict, eq=False)

    @property
    def size(self) -> int:
        """Number of shots (rows)."""
        return len(self.labels)

    def subset(self, rows) -> ShotTable:
        """The table of rows ``rows`` (an index or mask): a fold of a cross-validation."""
        rows = np.asarray(rows)
        index = np.arange(self.size)[rows]
        return attrs.evolve(self, labels=tuple(self.labels[i] for i in index),
                            clubs=tuple(self.clubs[i] for i in index),
                            handedness=tuple(self.handedness[i] for i in index),
                            delivery={k: v[index] for k, v in self.delivery.items()},
                            measured={k: v[index] for k, v in self.measured.items()},
                            sigma={k: v[index] for k, v in self.sigma.items()})


def _field_of(header: str) -> tuple[str | None, str | None]:
    """(field, unit) of a column header like 'Club Speed [mph]', 'spin_rate (rpm)' or 'ball_speed_sigma [mph]'."""
    match = re.match(r"^\s*(.*?)\s*(?:[\[(]\s*(.*?)\s*[\])])?\s*$", header)
    name, unit = match.group(1), match.group(2)
    key = re.sub(r"\s+", " ", name.strip().lower())
    sigma = key.endswith("_sigma") or key.endswith(" sigma")
    if sigma:
        key = key[:-6].strip(" _")
    key = ALIASES.get(key, key.replace(" ", "_"))
    known = key in DELIVERY_FIELDS or key in MEASURED_FIELDS or key in TEXT_FIELDS
    if not known or (sigma and key not in MEASURED_FIELDS):
        return None, unit
    return (f"{key}_sigma" if sigma else key), unit


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
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        raise FieldError(where, "a value with its unit (in the column header, the units: block or the value)", value)
    if value is None:
        return math.nan
    return to_si(value, dimension, where)


def _assemble(rows: list[dict], name: str, source: str, file: str, ball: dict, sigma_defaults: dict,
              loft_at: str = "contact", budgets: dict | None = None) -> ShotTable:
    if not rows:
        raise StudyError(f"{file}: the shot table has no rows")
    delivery = {key: np.array([row.get(key, math.nan) for row in rows], float) for key in DELIVERY_FIELDS}
    measured = {key: np.array([row.get(key, math.nan) for row in rows], float) for key in MEASURED_FIELDS}
    sigma = {key: np.array([row.get(f"{key}_sigma", math.nan) for row in rows], float) for key in MEASURED_FIELDS}
    for key in MEASURED_FIELDS:
        sigma[key] = np.where(np.isnan(sigma[key]), sigma_defaults.get(key, DEFAULT_SIGMA[key]), sigma[key])
    for key in ("path", "face_angle", "strike_toe", "strike_high"):
        delivery[key] = np.nan_to_num(delivery[key])  # square face and path, centred strike unless given
    problems = []
    for index, row in enumerate(rows):
        where = f"{file}:{row.get('_line', '?')}"
        for key in ("club_speed", "attack_angle", "dynamic_loft"):
            if not np.isfinite(delivery[key][index]):
                problems.append(f"{where}: {key}: expected the delivery's {key.replace('_', ' ')}, got nothing")
        if "club" not in row:
            problems.append(f"{where}: club: expected a club preset name, got nothing")
        for key in MEASURED_FIELDS:
            if not sigma[key][index] > 0:
                problems.append(f"{where}: {key}_sigma: expected a positive uncertainty, got {sigma[key][index]:g}")
        problems.extend(wrong_sign(measured, index, where))  # a negative ball speed or total spin
        if all(np.isnan(measured[key][index]) for key in MEASURED_FIELDS):
            problems.append(f"{where}: expected at least one measured quantity ({', '.join(MEASURED_FIELDS)})")
    if problems:
        raise StudyError("; ".join(problems))
    return ShotTable(name=name, source=source, labels=tuple(str(row.get("label", f"row {i + 1}"))
                                                             for i, row in enumerate(rows)),
                     clubs=tuple(str(row.get("club")) for row in rows),
                     handedness=tuple(str(row.get("handedness", "right")) for row in rows),
                     delivery=delivery, measured=measured, sigma=sigma, ball=ball, loft_at=loft_at,
                     budgets=budgets or {})


def _check_text(row: dict, where: str, problems: list) -> None:
    from impactlab.scene.clubs import CLUB_PRESETS

    if "club" in row and row["club"] not in CLUB_PRESETS:
        problems.append(f"{where}: club: expected a club preset ({', '.join(CLUB_PRESETS)}), got {row['club']!r}")
    if row.get("handedness", "right") not in ("right", "left"):
        problems.append(f"{where}: handedness: expected right or left, got {row['handedness']!r}")


def read_csv(text: str, file: str = "<csv>", name: str | None = None, source: str = "") -> ShotTable:
    """A shot table from CSV text: a header row of fields with units, one shot per line."""
    reader = csv.reader(io.StringIO(text))
    try:
        header = next(reader)
    except StopIteration:
        raise StudyError(f"{file}: empty file; expected a header row of columns with units") from None
    columns = [_field_of(cell) for cell in header]
    unknown = [header[i] for i, (field, _) in enumerate(columns) if field is None and header[i].strip()]
    rows, problems = [], []
    for line_number, cells in enumerate(reader, start=2):
        if not any(cell.strip() for cell in cells):
            continue
        if len(cells) != len(header):
            problems.append(f"{file}:{line_number}: expected {len(header)} columns, got {len(cells)}")
            continue
        row = {"_line": line_number}
        for column, (cell, (field, unit)) in enumerate(zip(cells, columns), start=1):
            if field is None:
                continue
            where = f"{file}:{line_number}:{column} ({header[column - 1].strip()})"
            if field in TEXT_FIELDS:
                if cell.strip():
                    row[field] = cell.strip()
                continue
            try:
                value = _convert(cell, field, unit, where)
            except FieldError as exc:
                problems.append(str(exc))
                continue
            if not np.isnan(value):
                row[field] = value
        _check_text(row, f"{file}:{line_number}", problems)
        rows.append(row)
    if problems:
        raise StudyError(f"{file}: {len(problems)} bad cell(s): " + "; ".join(problems))
    table = _assemble(rows, name or Path(file).stem, source or f"read from {file}", file, {}, {})
    if unknown:
        import warnings

        warnings.warn(f"{file}: columns not used (not a delivery or launch quantity): {', '.join(unknown)}",
                      stacklevel=2)
    return table


def read_yaml(text: str, file: str = "<yaml>") -> ShotTable:
    """A shot table from YAML: ``name``, ``source``, optional ``ball``, ``units``, ``sigma``, and ``rows``."""
    from impactlab.study.yaml_lines import line_of, load_yaml

    document, lines = load_yaml(text, file)
    if not isinstance(document, dict) or "rows" not in document:
        raise StudyError(f"{file}: expected a mapping with name, source, units, sigma and rows")
    units = document.get("units") or {}
    problems = [f"{file}:{line_of(lines, (key,))}: {key}: expected a key of a shot table ({', '.join(TABLE_KEYS)})"
                for key in document if key not in TABLE_KEYS]
    problems += [f"{file}:{line_of(lines, ('units', key))}: units.{key}: expected a delivery or measured field "
                 f"({', '.join((*DELIVERY_FIELDS, *MEASURED_FIELDS))})"
                 for key in units if key not in DELIVERY_FIELDS and key not in MEASURED_FIELDS]
    loft_at = document.get("loft_at", "contact")
    if loft_at not in ("contact", "centre"):
        problems.append(f"{file}:{line_of(lines, ('loft_at',))}: loft_at: expected contact (the launch monitor's "
                        f"loft at the impact point) or centre (at the face centre), got {loft_at!r}")
    sigma_defaults = {}
    for key, value in (document.get("sigma") or {}).items():
        if key not in MEASURED_FIELDS:
            problems.append(f"{file}:{line_of(lines, ('sigma', key))}: sigma.{key}: expected one of "
                            f"{', '.join(MEASURED_FIELDS)}")
            continue
        try:
            sigma_defaults[key] = _convert(value, key, None, f"{file}: sigma.{key}")
        except FieldError as exc:
            problems.append(str(exc))
    budgets = document.get("budgets") or {}
    for model, entry in budgets.items():
        if not isinstance(entry, dict) or not set(entry) <= set(ERROR_KEYS) \
                or not all(isinstance(v, (int, float)) and v > 0 for v in entry.values()):
            problems.append(f"{file}:{line_of(lines, ('budgets', model))}: budgets.{model}: expected a mapping of "
                            f"error ({', '.join(repr(k) for k in ERROR_KEYS)}) to a positive RMS")
    rows = []
    for index, item in enumerate(document["rows"] or []):
        line = line_of(lines, ("rows", index))
        where = f"{file}:{line}"
        if not isinstance(item, dict):
            problems.append(f"{where}: rows[{index}]: expected a mapping of fields")
            continue
        row = {"_line": line}
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
    return _assemble(rows, str(document.get("name", Path(file).stem)), str(document.get("source", "")), file,
                     dict(document.get("ball") or {}), sigma_defaults, loft_at, budgets)


def read_shots(path) -> ShotTable:
    """A shot table from a .csv or .yaml/.yml file."""
    from impactlab.study.yaml_lines import read_text_file

    path = Path(path)
    if not path.exists():
        raise StudyError(f"{path}: no such shot table (a .csv or .yaml file)")
    text = read_text_file(path, "shot table")  # folders, devices, binary and UTF-16 files said as such
    if path.suffix.lower() == ".csv":
        return read_csv(text, str(path))
    if path.suffix.lower() in (".yaml", ".yml"):
        return read_yaml(text, str(path))
    raise StudyError(f"{path}: expected a .csv or .yaml shot table")


# -- predictions -----------------------------------------------------------------------------------------------
def table_inputs(table: ShotTable, ball_block: dict | None = None, contact: dict | None = None) -> dict:
    """Model inputs (SI arrays) of every row: its club preset, its delivery and strike, and the ball.

    ``ball_block`` is a study ``ball:`` mapping (default: the table's, else ``{preset: tour_urethane}``);
    ``contact`` overrides the ball's friction and restitution (``{friction, restitution}``).
    """
    from impactlab.scene.clubs import Strike, club_preset
    from impactlab.scene.core import Contact, Delivery, Scene, ball_restitution, complete_inputs
    from impactlab.study.core import build_ball

    ball = build_ball(ball_block or table.ball or {"preset": "tour_urethane"})
    contact = Contact(**(contact or {}))
    scenes = []
    for index in range(table.size):
        club = club_preset(table.clubs[index])
        d = {key: float(value[index]) for key, value in table.delivery.items()}
        delivery = Delivery(d["club_speed"], path=d["path"], face_angle=d["face_angle"],
                            attack_angle=d["attack_angle"], dynamic_loft=d["dynamic_loft"],
                            handedness=table.handedness[index])
        scenes.append(Scene.from_delivery(ball, Scene.face_of(club), contact, delivery, 0.0, club,
                                          Strike(d["strike_toe"], d["strike_high"])))
    per_scene = [scene.inputs() for scene in scenes]  # once each: inputs() evaluates the ball's law
    keys = set.intersection(*(set(values) for values in per_scene))
    inputs = {key: np.array([values[key] for values in per_scene]) for key in sorted(keys)}
    if table.loft_at == "contact":
        inputs = centre_delivery(inputs, inputs)
    inputs = complete_inputs(inputs)
    if contact.restitution is None and ball.restitution is not None:
        inputs["restitution"] = ball_restitution(ball, inputs)  # at the normal speed of the centred delivery
    return inputs


def centre_delivery(inputs: dict, measured: dict) -> dict:
    """The inputs with the face-centre dynamic loft and face angle whose face at the strike point has the
    ``measured`` (contact-point) loft and face angle, and with the ball's restitution law re-evaluated there.

    The face at a strike ``high`` up a face of roll radius R_r is lofted by atan(high/R_r) more than at its
    centre; a strike ``toe`` towards the toe of a face of bulge radius R_b is open by atan(toe/R_b) more
    (impactlab.physics.contact tilts the normal the same way). ``measured`` holds the launch monitor's
    ``dynamic_loft`` and ``face_angle``; ``inputs`` the strike and face radii [SI].
    """
    out = dict(inputs)
    out["dynamic_loft"] = measured["dynamic_loft"] - np.arctan(inputs["strike_high"] / inputs["face_roll_radius"])
    out["face_angle"] = measured["face_angle"] - np.arctan(inputs["strike_toe"] / inputs["face_bulge_radius"])
    return out


def predict(model, inputs: dict) -> dict:
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
