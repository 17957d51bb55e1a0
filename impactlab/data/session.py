"""Launch-monitor sessions read as exported: vendor layouts as data, one normalised table out.

A session file is a table a launch monitor's software wrote (TrackMan, Garmin Golf, Foresight FSX, Rapsodo,
FlightScope) or a table in impactlab's own vocabulary (``Club Speed [mph]``, ``ball_speed (m/s)``). Each vendor's
layout is a YAML column map in ``impactlab/data/vendors/`` (:func:`vendor_maps`): the header names that recognise
it, where its units are (a units row under the header, inside the header names, or implied by the layout), its
column names in the vocabulary of :data:`FIELDS`, per-column signs, no-data sentinels, estimated-value flags,
clamped values, summary rows, and the point of the club head its club data describe. A map key ``Name [unit]``
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

import csv
import functools
import io
import math
import re
import stat
import sys
from importlib import resources
from pathlib import Path

import attrs
import numpy as np

from impactlab.errors import FieldError, StudyError
from impactlab.data.shot_table import (DEFAULT_SIGMA, DELIVERY_FIELDS, MEASURED_FIELDS, ShotTable, _field_of,
                                       _resolve_spin_loft)

#: the session vocabulary: field -> physical dimension (impactlab.units.DIMENSIONS); names follow
#: impactlab.vocabulary (inputs: club_speed is the delivery's speed; outputs: ball_speed, back_spin...) and the ball
#: flight's outputs (carry_distance, apex_height, landing_angle, offline_distance, flight_time)
FIELDS = {
    "club_speed": "speed", "attack_angle": "angle", "path": "angle", "face_angle": "angle",
    "dynamic_loft": "angle", "face_to_path": "angle", "spin_loft": "angle", "strike_toe": "length",
    "strike_high": "length", "ball_speed": "speed", "vertical_launch_angle": "angle",
    "horizontal_launch_angle": "angle",
    "spin_rate": "angular_speed", "spin_axis": "angle", "back_spin": "angular_speed", "side_spin": "angular_speed",
    "smash_factor": "dimensionless",
    "carry_distance": "length", "total_distance": "length", "apex_height": "length", "offline_distance": "length",
    "landing_angle": "angle", "flight_time": "time",
}
TEXT_FIELDS = ("label", "club", "handedness")
#: per-row one-sigma uncertainties of the predicted quantities (impactlab's own layout: ``ball_speed_sigma [mph]``)
SIGMA_FIELDS = {f"{key}_sigma": FIELDS[key] for key in
                ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis")}
FIELDS.update(SIGMA_FIELDS)
#: what each field is, for reports
DESCRIPTIONS = {
    "club_speed": "club speed", "attack_angle": "attack angle", "path": "club path", "face_angle": "face angle",
    "dynamic_loft": "dynamic loft", "face_to_path": "face to path (checked against face angle - path)",
    "spin_loft": "spin loft (3-D; gives the dynamic loft a row leaves out, checked against it when both are given)",
    "strike_toe": "impact point towards the toe", "strike_high": "impact point up the face",
    "ball_speed": "ball speed", "vertical_launch_angle": "launch angle", "horizontal_launch_angle": "launch direction",
    "spin_rate": "spin rate", "spin_axis": "spin axis", "back_spin": "back spin", "side_spin": "side spin",
    "smash_factor": "smash factor", "carry_distance": "carry", "total_distance": "total distance",
    "apex_height": "apex height", "offline_distance": "offline distance", "landing_angle": "landing angle",
    "flight_time": "flight time", **{key: f"uncertainty of the {key[:-6].replace('_', ' ')}" for key in SIGMA_FIELDS},
    "label": "shot label", "club": "club name", "handedness": "handedness",
}
#: units written by the normalised table (--csv): the vocabulary's display units
DISPLAY_UNITS = {"speed": "m/s", "angle": "deg", "angular_speed": "rpm", "length": "m", "time": "s",
                 "dimensionless": "1"}
#: vendor spellings of units -> pint spellings
UNIT_SPELLINGS = {
    "yds": "yd", "yards": "yd", "yard": "yd", "meters": "m", "metres": "m", "meter": "m", "metre": "m",
    "°": "deg", "*": "deg", "degrees": "deg", "degree": "deg", "sec": "s", "inches": "in", "inch": "in",
    "feet": "ft", "kph": "km/h", "km/t": "km/h", "kmh": "km/h", "mi/h": "mph", "": "",
}
#: the delivery the impact models need in every row
NEEDED_DELIVERY = ("club_speed", "attack_angle", "dynamic_loft")
#: the launch the impact models predict (what a row is compared on)
PREDICTED = ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis")
#: which measurements each prediction needs, for the report
NEEDS = {
    "impact models (ball speed, launch angle, spin)": "club, club speed, attack angle and dynamic loft",
    "launch direction and spin axis": "also face angle and club path",
    "ball flight (carry, apex, landing)": "ball speed, launch angle and spin rate (spin axis for offline)",
}
#: the largest file read as a session [bytes]
MAX_SESSION_BYTES = 512 * 2**20
#: rows above which a progress bar is drawn (on a terminal)
PROGRESS_ROWS = 20_000


# -- vendor maps -----------------------------------------------------------------------------------------------
@attrs.frozen
class ColumnRule:
    """How one vendor column becomes a field: the field and the sign that turns it into the vocabulary's."""

    field: str
    sign: float = 1.0


@attrs.frozen
class VendorMap:
    """A vendor's export layout (one YAML file of ``impactlab/data/vendors``); see the module docstring."""

    id: str
    name: str
    source: str
    recognise: tuple[str, ...]
    units: str
    columns: dict = attrs.field(eq=False)
    implied_units: dict = attrs.field(factory=dict, eq=False)
    loft_at: str = "contact"
    #: the point of the head whose motion the club data give: geometric_centre (TrackMan: ~ the centre of mass),
    #: face_centre (optical monitors) or unknown
    club_reference_point: str = attrs.field(default="unknown", validator=attrs.validators.in_(
        ("geometric_centre", "face_centre", "unknown")))
    club_reference: str = ""
    signs: str = ""
    missing: tuple[str, ...] = ("",)
    sentinel_at_least: float | None = None
    estimated: dict | None = attrs.field(default=None, eq=False)
    clamped: dict = attrs.field(factory=dict, eq=False)
    summary_rows: dict | None = attrs.field(default=None, eq=False)
    left_right_suffix: bool = False
    #: True: the file's spin-axis sign is checked against its side spin (whose sign the layout states) and turned
    #: when every row disagrees (Garmin Golf app versions write the axis with either sign)
    spin_axis_follows_side_spin: bool = False
    #: {column, values}: rows the user marked not to use (TrackMan's Use In Stat = FALSE)
    excluded: dict | None = attrs.field(default=None, eq=False)

    def rule(self, header: str) -> ColumnRule | None:
        """The rule of a header cell (matched case- and space-insensitively; ``Name [unit]`` keys need a unit)."""
        name, unit = split_header(header)
        full = _norm(header)
        if full in self.columns:
            return self.columns[full]
        if unit is not None and f"{_norm(name)} [unit]" in self.columns:
            return self.columns[f"{_norm(name)} [unit]"]
        return self.columns.get(_norm(name))


def _norm(text: str) -> str:
    return re.sub(r"\s+", " ", str(text).strip().lower())


def _vendor_from_document(document: dict, where: str) -> VendorMap:
    keys = {"id", "name", "source", "recognise", "units", "columns", "implied_units", "loft_at", "club_reference",
            "club_reference_point",
            "signs", "missing", "sentinel_at_least", "estimated", "clamped", "summary_rows", "left_right_suffix",
            "excluded", "spin_axis_follows_side_spin"}
    unknown = set(document) - keys
    if unknown:
        raise StudyError(f"{where}: unknown keys {sorted(unknown)} (a vendor map takes {sorted(keys)})")
    columns = {}
    for header, rule in (document.get("columns") or {}).items():
        rule = {"field": rule} if isinstance(rule, str) or rule is None else dict(rule)
        field = rule.get("field")
        if field is not None and field not in FIELDS and field not in TEXT_FIELDS:
            raise StudyError(f"{where}: columns.{header}: {field!r} is not a session field "
                             f"({', '.join((*FIELDS, *TEXT_FIELDS))})")
        columns[_norm(header)] = None if field is None else ColumnRule(field, float(rule.get("sign", 1)))
    if document.get("units") not in ("row", "header", "implied"):
        raise StudyError(f"{where}: units: expected row, header or implied")
    clamped = {}
    from impactlab.units import to_si

    for field, limit in (document.get("clamped") or {}).items():
        clamped[field] = to_si(str(limit), FIELDS[field], f"{where}: clamped.{field}")
    return VendorMap(
        id=document["id"], name=document["name"], source=document["source"],
        recognise=tuple(_norm(name) for name in document["recognise"]), units=document["units"], columns=columns,
        implied_units={_norm(k): str(v) for k, v in (document.get("implied_units") or {}).items()},
        loft_at=document.get("loft_at", "contact"),
        club_reference_point=document.get("club_reference_point", "unknown"),
        club_reference=" ".join(str(document.get("club_reference", "")).split()),
        signs=" ".join(str(document.get("signs", "")).split()), missing=tuple(document.get("missing", [""])),
        sentinel_at_least=document.get("sentinel_at_least"), estimated=document.get("estimated"), clamped=clamped,
        summary_rows=document.get("summary_rows"), left_right_suffix=bool(document.get("left_right_suffix", False)),
        excluded=document.get("excluded"),
        spin_axis_follows_side_spin=bool(document.get("spin_axis_follows_side_spin", False)))


@functools.cache
def vendor_maps() -> dict[str, VendorMap]:
    """Every vendor layout shipped with impactlab, by id."""
    import yaml

    maps = {}
    for entry in sorted(resources.files("impactlab.data.vendors").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".yaml"):
            vendor = _vendor_from_document(yaml.safe_load(entry.read_text(encoding="utf-8")),
                                           f"impactlab/data/vendors/{entry.name}")
            maps[vendor.id] = vendor
    return maps


#: impactlab's own layout: vocabulary names and the usual launch-monitor names, units in the header or a units row
GENERIC = VendorMap(id="impactlab", name="impactlab shot table (vocabulary or usual launch-monitor names)",
                    source="", recognise=(), units="header", columns={}, missing=("",),
                    club_reference="as the table states (impactlab counts the delivery at the face centre after "
                                   "turning a contact-point loft back to it; docs/vendors.md)")


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
        ``label``, ``club`` and ``handedness`` per row ('' where not given).
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
        from impactlab.scene.clubs import club_key

        keep = np.ones(self.size, bool)
        reasons = [[] for _ in range(self.size)]
        keys = {name: club_key(name) if name else None for name in set(self.text["club"])}  # once per name
        clubs = [keys[name] for name in self.text["club"]]
        for index, (name, key) in enumerate(zip(self.text["club"], clubs)):
            if not name:
                reasons[index].append("no club named")
            elif key is None:
                reasons[index].append(f"club {name!r} is not in the club catalogue")
        for index in np.flatnonzero(self.flags.get(("row", "excluded"), np.zeros(self.size, bool))):
            reasons[index].append("marked not to use in the file" + (
                f" ({self.vendor.excluded['column']} = {', '.join(map(str, self.vendor.excluded['values']))})"
                if self.vendor.excluded else ""))
        for field in NEEDED_DELIVERY:
            given = np.isfinite(self.values[field])
            if field == "dynamic_loft" and "spin_loft" in self.values:  # the spin loft gives the dynamic loft
                given |= np.isfinite(self.values["spin_loft"])
            for index in np.flatnonzero(~given):
                reasons[index].append(f"no {DESCRIPTIONS[field]}")
        measured = np.zeros(self.size, bool)
        for field in PREDICTED:
            ok = np.isfinite(self.values[field])
            if not include_flagged:
                ok &= ~self.flagged(field)
            measured |= ok
        for index in np.flatnonzero(~measured):
            reasons[index].append("no measured launch quantity that is not flagged")
        out = []
        for index, why in enumerate(reasons):
            if why:
                keep[index] = False
                out.append((int(self.lines[index]), "; ".join(why)))
        return keep, out

    def shot_table(self, include_flagged: bool = False):
        """The :class:`~impactlab.data.shots.ShotTable` of the rows the impact models can use.

        Flagged values (estimated, clamped) are left out of the comparison unless ``include_flagged``; a row
        without face angle or club path keeps its ball speed, launch angle and spin but not its launch direction
        and spin axis (a square face would be a guess). Raises StudyError when no row is usable, with the reasons.
        """
        from impactlab.scene.clubs import club_key

        keep, skipped = self.usable(include_flagged)
        if not keep.any():
            reasons = "; ".join(f"{self.file}:{line}: {why}" for line, why in skipped[:10])
            more = f" (and {len(skipped) - 10} more)" if len(skipped) > 10 else ""
            raise StudyError(f"{self.file}: no row the impact models can use ({self.size} shot(s) read): "
                             f"{reasons}{more}")
        index = np.flatnonzero(keep)
        # a field no layout of this vendor maps (the 3-D spin loft) is absent: NaN, as an empty cell
        delivery = {key: (self.values[key][index].copy() if key in self.values else np.full(index.size, np.nan))
                    for key in DELIVERY_FIELDS}
        problems = _resolve_spin_loft(delivery, [{"_line": self.lines[i]} for i in index], self.file)
        if problems:
            raise StudyError("; ".join(problems))
        square = ~(np.isfinite(delivery["face_angle"]) & np.isfinite(delivery["path"]))
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
        sigma = {}
        for key in MEASURED_FIELDS:
            given = self.values[f"{key}_sigma"][index]
            bad = np.isfinite(given) & ~(given > 0)
            if bad.any():
                lines = ", ".join(f"{self.file}:{self.lines[index[i]]}" for i in np.flatnonzero(bad)[:10])
                raise StudyError(f"{lines}: {key}_sigma: expected a positive uncertainty, got "
                                 f"{given[np.flatnonzero(bad)[0]]:g}")
            sigma[key] = np.where(np.isfinite(given), given, DEFAULT_SIGMA[key])
        labels = tuple(self.text["label"][i] or f"line {self.lines[i]}" for i in index)
        keys = {name: club_key(name) for name in {self.text["club"][i] for i in index}}
        source = f"read from {self.file} ({self.vendor.name})"
        if self.vendor.club_reference_point != "unknown":
            source += f"; club data at the head's {self.vendor.club_reference_point.replace('_', ' ')}"
        elif self.vendor is not GENERIC:
            source += "; the point of the head its club data describe is not stated"
        return ShotTable(name=Path(self.file).stem, source=source,
                         labels=labels, clubs=tuple(keys[self.text["club"][i]] for i in index),
                         handedness=tuple(self.text["handedness"][i] or "right" for i in index),
                         delivery=delivery, measured=measured, sigma=sigma, loft_at=self.vendor.loft_at,
                         skipped=tuple(skipped))


# -- reading ---------------------------------------------------------------------------------------------------
def split_header(header: str) -> tuple[str, str | None]:
    """(name, unit) of a header cell: ``Club Speed [mph]``, ``Ball Speed (m/s)``, ``AOA (°)`` (unit None: none)."""
    match = re.match(r"^\s*(.*?)\s*(?:[\[(]\s*([^\[\]()]*?)\s*[\])])?\s*$", str(header))
    return match.group(1), match.group(2)


def _unit_factor(unit: str, dimension: str, where: str) -> float:
    """SI value of one ``unit`` of ``dimension`` (vendor spellings accepted); FieldError when it is not one."""
    from impactlab.units import to_si

    spelled = UNIT_SPELLINGS.get(unit.strip().lower(), unit.strip())
    if dimension == "dimensionless":
        if spelled in ("", "1", "-"):
            return 1.0
        raise FieldError(where, "a number without unit", unit)
    return to_si(f"1 {spelled}", dimension, where)


def _read_bytes(path: Path) -> str:
    try:
        info = path.stat()
    except FileNotFoundError:
        raise StudyError(f"{path}: no such shot table (a launch-monitor export, .csv or .yaml)") from None
    except OSError as exc:
        raise StudyError(f"{path}: cannot read this shot table: {exc.strerror}") from None
    if stat.S_ISDIR(info.st_mode):
        raise StudyError(f"{path}: is a folder, not a shot table")
    if info.st_size > MAX_SESSION_BYTES:
        raise StudyError(f"{path}: {info.st_size:,} bytes is too large for a shot table (at most "
                         f"{MAX_SESSION_BYTES:,})")
    data = path.read_bytes()
    if data.startswith((b"\xff\xfe", b"\xfe\xff")):
        try:
            return data.decode("utf-16")
        except UnicodeDecodeError:
            raise StudyError(f"{path}: is not UTF-16 text after its UTF-16 byte-order mark") from None
    if b"\0" in data:
        raise StudyError(f"{path}: is a binary file (it holds NUL bytes), not a shot table")
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        raise StudyError(f"{path}:{line}: is not UTF-8 text (byte 0x{data[exc.start]:02x}); save the shot table "
                         "as UTF-8") from None


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
    return read_session_text(_read_bytes(path), str(path), vendor)


def _rows_of(text: str, file: str) -> tuple[list[list[str]], list[int], list[str]]:
    """Rows (cells) with their file lines, after the ``sep=`` line; the separator said in notes."""
    notes = []
    text = text.lstrip("\ufeff")
    first_end = text.find("\n")
    first = text if first_end < 0 else text[:first_end]
    delimiter = None
    line_offset = 0
    match = re.match(r'^\s*"?sep=(.)"?\s*$', first.rstrip("\r"))
    if match:
        delimiter = match.group(1)
        notes.append(f"separator {delimiter!r} (from the file's 'sep=' line)")
        text = "" if first_end < 0 else text[first_end + 1:]
        line_offset = 1
    sample = [line for line in text[:20000].splitlines() if line.strip()][:6]
    if delimiter is None:
        # the separator that splits the header (the widest of the first lines: a title line may come first)
        # into the most columns, then the one whose other lines agree with that width
        scores = {}
        for candidate in (",", ";", "\t"):
            widths = [len(next(csv.reader([line], delimiter=candidate))) for line in sample] or [1]
            widest = max(widths)
            scores[candidate] = (widest, sum(width == widest for width in widths), candidate == ",")
        delimiter = max(scores, key=scores.get)
        if scores[delimiter][0] <= 1:
            delimiter = ","
        if delimiter != ",":
            notes.append(f"separator {delimiter!r} (the header splits into {scores[delimiter][0]} columns with it)")
    reader = csv.reader(io.StringIO(text, newline=""), delimiter=delimiter, skipinitialspace=True)
    rows, lines = [], []
    try:
        for cells in reader:
            rows.append(cells)
            lines.append(reader.line_num + line_offset)
    except csv.Error as exc:
        raise StudyError(f"{file}:{reader.line_num + line_offset}: not readable as a table: {exc}") from None
    return rows, lines, notes


def _recognise(header: list[str], forced: str | None, file: str) -> VendorMap:
    maps = vendor_maps()
    if forced is not None:
        if forced == GENERIC.id:
            return GENERIC
        if forced not in maps:
            raise FieldError("--vendor", "a vendor layout", forced, choices=[GENERIC.id, *maps])
        return maps[forced]
    names = {_norm(split_header(cell)[0]) for cell in header}
    found = [vendor for vendor in maps.values() if set(vendor.recognise) <= names]
    if not found:
        return GENERIC
    found.sort(key=lambda vendor: -len(vendor.recognise))
    return found[0]


def _header_index(rows: list[list[str]], forced: str | None) -> int:
    """The row holding the header: the first that a vendor map recognises, else the first non-empty row."""
    maps = vendor_maps() if forced in (None,) else ({forced: vendor_maps()[forced]} if forced in vendor_maps()
                                                     else {})
    first = None
    for index, cells in enumerate(rows[:12]):
        if not any(cell.strip() for cell in cells):
            continue
        if first is None:
            first = index
        names = {_norm(split_header(cell)[0]) for cell in cells}
        if any(set(vendor.recognise) <= names for vendor in maps.values()):
            return index
    return 0 if first is None else first


_UNITS_CELL = re.compile(r"^\s*\[[^\]]*\]\s*$")
_NUMBER_POINT = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
_NUMBER_COMMA = re.compile(r"^[+-]?\d+,\d+$")


def _progress(total: int, label: str):
    """A tqdm bar on a terminal for large sessions; a do-nothing stand-in otherwise."""
    if total < PROGRESS_ROWS or not sys.stderr.isatty():
        class _Quiet:
            def update(self, n):
                pass

            def close(self):
                pass
        return _Quiet()
    from tqdm import tqdm

    return tqdm(total=total, desc=label, unit="row", file=sys.stderr, leave=False)


def read_session_text(text: str, file: str = "<csv>", vendor: str | None = None) -> Session:
    """A :class:`Session` from the text of an export (see :func:`read_session`)."""
    rows, lines, notes = _rows_of(text, file)
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
    if body and any(cell.strip() for cell in body[0]) and all(
            _UNITS_CELL.match(cell) or not cell.strip() for cell in body[0]):
        units_row = [cell.strip()[1:-1].strip() if cell.strip() else "" for cell in body[0]]
        notes.append(f"units row at line {body_lines[0]}")
        body, body_lines = body[1:], body_lines[1:]
    keep = [i for i, cells in enumerate(body) if any(cell.strip() for cell in cells)]
    body = [body[i] for i in keep]
    body_lines = [body_lines[i] for i in keep]

    # columns: which field, which unit, which sign
    problems = []
    plan, unused, by_field = [], [], {}
    for column, cell in enumerate(header):
        if not cell:
            continue
        if layout is GENERIC:
            field, unit = _generic_field(cell)
            rule = None if field is None else ColumnRule(field)
        else:
            rule = layout.rule(cell)
            unit = split_header(cell)[1]
        if rule is None:
            unused.append(cell)
            continue
        field = rule.field
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
                problems.append(f"{where}: expected a unit for the {DESCRIPTIONS[field]} (in the header, "
                                f"'{split_header(cell)[0]} [unit]', or a units row under it); a number without "
                                f"its unit is not read (115 could be mph or m/s)")
                continue
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
    if layout.units == "implied" and any(unit and split_header(cell)[1] is None
                                         for _, cell, field, unit, _, factor in plan if factor is not None):
        notes.append(f"units not in the file: taken from the {layout.name} layout ({layout.source})")

    # summary rows and ragged rows
    skipped = []
    width = len(header)
    summary_column = None
    if layout.summary_rows:
        names = [_norm(split_header(c)[0]) for c in header]
        if _norm(layout.summary_rows["column"]) in names:
            summary_column = names.index(_norm(layout.summary_rows["column"]))
    summary_values = {_norm(v) for v in (layout.summary_rows or {}).get("values", [])}
    shots, shot_lines = [], []
    for cells, line in zip(body, body_lines):
        while len(cells) > width and not cells[-1].strip():
            cells = cells[:-1]
        if summary_column is not None and summary_column < len(cells) and _norm(cells[summary_column]) in \
                summary_values:
            skipped.append((line, f"a summary row ({cells[summary_column].strip()!r}), not a shot"))
            continue
        if len(cells) != width:
            problems.append(f"{file}:{line}: expected {width} columns, got {len(cells)}")
            continue
        shots.append(cells)
        shot_lines.append(line)
    size = len(shots)
    if size == 0 and problems:
        raise StudyError(f"{file}: {len(problems)} bad row(s): " + "; ".join(problems[:20]))
    if size == 0:
        raise StudyError(f"{file}: no shots below the header (line {header_line})")
    lines_array = np.array(shot_lines, dtype=np.int64)

    columns = list(zip(*shots)) if shots else []
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
        values[field] = sign * factor * numbers
        used.append((cell, field, unit or "", sign))
    bar.close()
    if problems:
        shown = "; ".join(problems[:40]) + (f" (and {len(problems) - 40} more)" if len(problems) > 40 else "")
        raise StudyError(f"{file}: {len(problems)} bad cell(s) or row(s): {shown}")

    _flag_estimated(layout, header, columns, values, flags, used, unused)
    _flag_excluded(layout, header, columns, flags, used, unused)
    if layout is GENERIC and "flags" in [_norm(cell) for cell in header]:
        _read_flags(header, columns, flags, used, unused, file, shot_lines)
    for field, limit in layout.clamped.items():
        clamped = np.abs(values[field]) >= limit * (1 - 1e-5)
        if clamped.any():
            flags[(field, "clamped")] = clamped
    _derive(values, used, notes, flags)
    _check_spin_signs(layout, values, used, notes, flags)
    handedness = text_values["handedness"]
    bad_hand = sorted({h for h in handedness if h and h.lower() not in ("right", "left", "r", "l", "rh", "lh")})
    if bad_hand:
        raise StudyError(f"{file}: handedness: expected right or left, got {', '.join(map(repr, bad_hand))}")
    text_values["handedness"] = tuple({"r": "right", "rh": "right", "l": "left", "lh": "left"}.get(h.lower(),
                                                                                                  h.lower())
                                      for h in handedness)
    return Session(file=file, vendor=layout, values=values, text=text_values, lines=lines_array, flags=flags,
                   used=used, unused=unused, skipped=skipped, notes=notes)


def _generic_field(header: str) -> tuple[str | None, str | None]:
    """(field, unit) of a column of impactlab's own layout (vocabulary names and the usual aliases)."""
    field, unit = _field_of(header)
    if field is None:
        name, unit = split_header(header)
        key = _norm(name).replace(" ", "_")
        key = {"carry": "carry_distance", "total": "total_distance", "apex": "apex_height",
               "backspin": "back_spin", "sidespin": "side_spin", "back_spin": "back_spin",
               "offline": "offline_distance", "smash": "smash_factor", "face_to_path": "face_to_path",
               "club_path": "path", "club_face": "face_angle"}.get(key, key)
        if key in FIELDS or key in TEXT_FIELDS:
            return key, unit
        return None, unit
    return field, unit


def _decimal_mark(columns: list, file: str) -> str:
    """'.' or ',' for the numbers of the file; StudyError when both occur (never read one as the other)."""
    import pandas as pd

    comma_example = point_example = None
    for raw in columns:
        cells = pd.Series(raw, dtype=object).astype(str).str.strip().str.rstrip("LRlr ").str.strip()
        commas = cells[cells.str.match(_NUMBER_COMMA.pattern)]
        points = cells[cells.str.contains(".", regex=False) & cells.str.match(_NUMBER_POINT.pattern)]
        if comma_example is None and len(commas):
            comma_example = commas.iloc[0]
        if point_example is None and len(points):
            point_example = points.iloc[0]
        if comma_example and point_example:
            raise StudyError(f"{file}: numbers are written with both decimal marks ({point_example!r} and "
                             f"{comma_example!r}); the file cannot be read without guessing which is meant")
    return "," if comma_example else "."


def _to_numbers(raw, layout: VendorMap, decimal: str):
    """(values, missing mask, indices of bad cells) of one column's text cells, vectorised."""
    import pandas as pd

    series = pd.Series(raw, dtype=object).astype(str).str.strip()
    missing = series.isin(list(layout.missing)) | series.str.upper().isin(["NAN", "N/A", "NA"])
    cleaned = series
    if layout.left_right_suffix:
        side = cleaned.str.extract(r"^(.*?)\s*([LRlr])$")
        has = side[1].notna()
        cleaned = cleaned.where(~has, side[0])
        signs = np.where(has & side[1].str.upper().eq("L"), -1.0, 1.0)
    else:
        signs = 1.0
    if decimal == ",":
        cleaned = cleaned.str.replace(",", ".", regex=False)
    numbers = pd.to_numeric(cleaned.where(~missing, "nan"), errors="coerce").to_numpy(dtype=float)
    bad = np.flatnonzero(np.isnan(numbers) & ~missing.to_numpy())
    return numbers * signs, missing.to_numpy(), bad.tolist()


def _flag_estimated(layout, header, columns, values, flags, used, unused) -> None:
    rule = layout.estimated
    if not rule:
        return
    names = [_norm(split_header(c)[0]) for c in header]
    if _norm(rule["column"]) not in names:
        return
    column = names.index(_norm(rule["column"]))
    cells = columns[column]
    if header[column] in unused:
        unused.remove(header[column])
        used.append((header[column], "estimated flag: " + " or ".join(map(str, rule["values"])) + " marks "
                     + ", ".join(rule["fields"]) + " as estimated", "", 1.0))
    marks = {_norm(v) for v in rule["values"]}
    estimated = np.array([_norm(cell) in marks for cell in cells])
    if estimated.any():
        for field in rule["fields"]:
            present = estimated & np.isfinite(values[field])
            if present.any():
                flags[(field, "estimated")] = present


def _flag_excluded(layout, header, columns, flags, used, unused) -> None:
    rule = layout.excluded
    if not rule:
        return
    names = [_norm(split_header(c)[0]) for c in header]
    if _norm(rule["column"]) not in names:
        return
    column = names.index(_norm(rule["column"]))
    if header[column] in unused:
        unused.remove(header[column])
        used.append((header[column], "rows marked not to use: " + " or ".join(map(str, rule["values"])), "", 1.0))
    marks = {_norm(v) for v in rule["values"]}
    excluded = np.array([_norm(cell) in marks for cell in columns[column]])
    if excluded.any():
        flags[("row", "excluded")] = excluded


def _read_flags(header, columns, flags, used, unused, file, lines) -> None:
    """The ``flags`` column of impactlab's normalised table (``spin_rate:estimated;spin_axis:clamped``)."""
    column = [_norm(cell) for cell in header].index("flags")
    unused.remove(header[column])
    used.append((header[column], "flags (field:estimated, field:clamped, field:no data)", "", 1.0))
    for index, cell in enumerate(columns[column]):
        for item in filter(None, (part.strip() for part in cell.split(";"))):
            field, _, kind = item.partition(":")
            if (field, kind) != ("row", "excluded") and (field not in FIELDS
                                                          or kind not in ("estimated", "clamped", "no data",
                                                                          "inconsistent")):
                raise StudyError(f"{file}:{lines[index]}: flags: expected field:estimated, field:clamped or "
                                 f"field:no data with a field of the vocabulary, got {item!r}")
            flags.setdefault((field, kind), np.zeros(len(lines), bool))[index] = True


def _derive(values: dict, used: list, notes: list, flags: dict) -> None:
    """Fill what follows from other columns: spin rate and axis from back and side spin, the face angle from
    face-to-path and path; say each, and check face to path where both sides are given."""
    back, side = values["back_spin"], values["side_spin"]
    given = {field for _, field, _, _ in used}
    if "spin_rate" not in given and np.isfinite(back).any():
        values["spin_rate"] = np.hypot(back, side)
        notes.append("spin rate = hypot(back spin, side spin) (no spin-rate column)")
        _inherit(flags, "spin_rate", ("back_spin", "side_spin"))
    if "spin_axis" not in given and np.isfinite(back).any() and np.isfinite(side).any():
        values["spin_axis"] = np.arctan2(side, back)
        notes.append("spin axis = atan(side spin / back spin) (no spin-axis column; both positive curving right)")
        _inherit(flags, "spin_axis", ("back_spin", "side_spin"))
    if "face_angle" not in given and "face_to_path" in given and "path" in given:
        values["face_angle"] = values["path"] + values["face_to_path"]
        notes.append("face angle = club path + face to path (no face-angle column)")
        _inherit(flags, "face_angle", ("path", "face_to_path"))
    elif {"face_angle", "face_to_path", "path"} <= given:
        with np.errstate(invalid="ignore"):
            off = np.abs(values["face_angle"] - values["path"] - values["face_to_path"]) > math.radians(0.05)
        if off.any():
            notes.append(f"face to path differs from face angle - club path by more than 0.05 deg in {int(off.sum())}"
                         f" row(s) (kept as measured; face angle and path are used)")


def _check_spin_signs(layout, values, used, notes, flags) -> None:
    """Side spin and spin axis describe one tilt: in the vocabulary both are positive curving right. Where a file
    gives both, rows whose signs disagree (both clearly non-zero: 50 rpm, 0.5 deg) are a convention the layout does
    not describe: a layout whose axis follows its side spin has its axis turned when every such row disagrees;
    otherwise the disagreeing rows' spin axis and side spin are flagged ``inconsistent`` (left out like estimated
    values) and the report says how many."""
    given = {field for _, field, _, _ in used}
    if not {"spin_axis", "side_spin"} <= given:
        return
    side, axis = values["side_spin"], values["spin_axis"]
    with np.errstate(invalid="ignore"):
        clear = (np.abs(side) > 50 * 2 * math.pi / 60) & (np.abs(axis) > math.radians(0.5))
        disagree = clear & (np.sign(side) != np.sign(axis))
    if not disagree.any():
        return
    if layout.spin_axis_follows_side_spin and disagree.sum() == clear.sum():
        values["spin_axis"] = -axis
        notes.append(f"spin axis: its sign disagrees with the side spin's in all {int(clear.sum())} row(s) with "
                     f"clear spin, so this export counts the axis positive curving left; turned to the vocabulary's "
                     f"(positive curving right, agreeing with the side spin)")
        return
    for field in ("spin_axis", "side_spin"):
        flags[(field, "inconsistent")] = disagree
    notes.append(f"side spin and spin axis disagree in sign in {int(disagree.sum())} of {int(clear.sum())} row(s) "
                 f"with clear spin: those rows' spin axis and side spin are flagged inconsistent and left out")


def _inherit(flags: dict, field: str, sources) -> None:
    for (name, kind), rows in list(flags.items()):
        if name in sources and kind in ("estimated", "clamped"):
            flags[(field, kind)] = flags.get((field, kind), np.zeros_like(rows)) | rows


# -- output ----------------------------------------------------------------------------------------------------
def write_normalised(session: Session, path) -> Path:
    """Write the session in the vocabulary (display units in the header, flags in a ``flags`` column) as CSV."""
    from impactlab.io.safe_output import write_atomically
    from impactlab.units import _factor

    present = [field for field in FIELDS if np.isfinite(session.values[field]).any()]
    texts = [field for field in TEXT_FIELDS if any(session.text[field])]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    units = {field: DISPLAY_UNITS[FIELDS[field]] for field in present}
    writer.writerow(["line", *texts, *(f"{field} [{units[field]}]" for field in present), "flags"])
    scale = {}
    for field in present:
        dimension = FIELDS[field]
        from impactlab.units import DIMENSIONS

        scale[field] = 1.0 if dimension == "dimensionless" else 1.0 / _factor(units[field], DIMENSIONS[dimension][0])
    flag_text = [[] for _ in range(session.size)]
    for (field, kind), rows in session.flags.items():
        for index in np.flatnonzero(rows):
            flag_text[index].append(f"{field}:{kind}")
    for index in range(session.size):
        cells = [str(session.lines[index]), *(session.text[field][index] for field in texts)]
        for field in present:
            value = session.values[field][index]
            cells.append("" if not math.isfinite(value) else f"{value * scale[field]:.10g}")
        cells.append(";".join(sorted(flag_text[index])))
        writer.writerow(cells)
    return write_atomically(path, buffer.getvalue().encode())


def describe(session: Session, include_flagged: bool = False) -> str:
    """The report of ``impactlab shots``: vendor, shots and clubs, columns used and not, rows skipped, flags."""
    from collections import Counter

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
            what = {"excluded": "marked not to use in the file", "no data": "no-data sentinel, read as missing",
                    "inconsistent": "whose sign disagrees with the other spin column's",
                    "estimated": "estimated by the monitor, not measured",
                    "clamped": "at the monitor's limit (clamped)"}[kind]
            out.append(f"    {field}: {int(rows.sum())} row(s) {what}")
        if not include_flagged:
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
    measured_spin = ball & ~session.flagged("spin_rate")
    out.append(f"  ball data (ball speed, launch angle, spin): {int(ball.sum())} row(s), {int(measured_spin.sum())} "
               f"with a spin that is not flagged")
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
