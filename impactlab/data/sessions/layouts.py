"""Launch-monitor layouts as data: the session vocabulary, each vendor's column map, and how a header is read.

:data:`FIELDS` is what a session can hold (field -> physical dimension); :func:`vendor_maps` reads the YAML column maps
of ``impactlab/data/sessions/vendors/`` (the module docstring of :mod:`impactlab.data.sessions.reader` says what a map
holds) and :data:`GENERIC` is impactlab's own layout. :func:`split_header`, :func:`_unit_factor` and :func:`_recognise`
turn a header row into fields, units and the layout that wrote it.
"""

from __future__ import annotations

import functools
import re
from importlib import resources

import attrs
from cattrs.gen import make_dict_structure_fn

from impactlab.errors import FieldError, StudyError
from impactlab.study.structuring import document_converter
from impactlab.units import DIMENSIONS, ZERO_DEPENDS_ON_UNIT, to_si, unit_affine
from impactlab.data.sessions.shot_table import DELIVERY_FIELDS, MEASURED_FIELDS

#: the session vocabulary: field -> physical dimension (impactlab.units.DIMENSIONS); names follow
#: impactlab.vocabulary (inputs: club_speed is the delivery's speed; outputs: ball_speed, back_spin...) and the ball
#: flight's outputs (carry_distance, apex_height, landing_angle, offline_distance, flight_time)
FIELDS = {
    **DELIVERY_FIELDS, **MEASURED_FIELDS,  # a shot table's fields, with their dimensions as the shot table has them
    "back_spin": "angular_speed", "side_spin": "angular_speed", "smash_factor": "dimensionless",
    "carry_distance": "length", "total_distance": "length", "apex_height": "length", "offline_distance": "length",
    "landing_angle": "angle", "flight_time": "time",
    # the monitor's flight beyond the carry, and how much of it was tracked (TrackMan's older layout: Carry Flat - Ball
    # Speed, Side Total, Last data Point - Time)
    "landing_ball_speed": "speed", "total_offline_distance": "length", "tracked_time": "time",
    # the air the monitor states for a shot (Garmin: Temperature [deg F], Air Pressure [kPa], Relative Humidity [%],
    # Air Density [g/L]); `impactlab fly SESSION` flies each shot in it
    "air_temperature": "temperature", "air_pressure": "pressure", "relative_humidity": "dimensionless",
    "air_density": "density", "altitude": "length",
}
#: text columns a layout may map; ``ball_setting`` is the ball the monitor was set to (TrackMan's Ball column),
#: not the models' ball: it groups the scorecard's rows, it changes no prediction
TEXT_FIELDS = ("label", "club", "handedness", "ball_setting")
#: per-row one-sigma uncertainties of the predicted quantities (impactlab's own layout: ``ball_speed_sigma [mph]``)
SIGMA_FIELDS = {f"{key}_sigma": dimension for key, dimension in MEASURED_FIELDS.items()}
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
    "flight_time": "flight time", "landing_ball_speed": "ball speed at landing",
    "total_offline_distance": "offline distance after the roll", "tracked_time": "time the monitor tracked the ball",
    "air_temperature": "air temperature", "air_pressure": "air pressure",
    "relative_humidity": "relative humidity (a fraction; '[%]' in a units row)",
    "air_density": "air density (checked against the temperature, pressure and humidity)",
    "altitude": "altitude of the air (the ISA pressure there, where no pressure is given)",
    **{key: f"uncertainty of the {key[:-6].replace('_', ' ')}" for key in SIGMA_FIELDS},
    "label": "shot label", "club": "club name", "handedness": "handedness",
    "ball_setting": "the ball the monitor was set to (text: groups the scorecard's rows, not the models' ball)",
}
#: units written by the normalised table (--csv): the vocabulary's display units
DISPLAY_UNITS = {"speed": "m/s", "angle": "deg", "angular_speed": "rpm", "length": "m", "time": "s",
                 "dimensionless": "1", "temperature": "degC", "pressure": "kPa", "density": "kg/m^3"}
#: vendor spellings of units -> pint spellings
UNIT_SPELLINGS = {
    "yds": "yd", "yards": "yd", "yard": "yd", "meters": "m", "metres": "m", "meter": "m", "metre": "m",
    "°": "deg", "*": "deg", "degrees": "deg", "degree": "deg", "sec": "s", "inches": "in", "inch": "in",
    "feet": "ft", "kph": "km/h", "km/t": "km/h", "kmh": "km/h", "mi/h": "mph", "": "",
    # temperatures: Garmin writes "[deg F]" ("[deg C]" in metric sessions); a bare "F" or "C" is not read as one
    # (pint reads F as the farad, C as the coulomb: refused as not a temperature, never guessed)
    "deg f": "degF", "deg c": "degC", "°f": "degF", "°c": "degC", "℉": "degF", "℃": "degC",
    "g/l": "g/L",
}


# -- vendor maps -----------------------------------------------------------------------------------------------
@attrs.frozen
class ColumnRule:
    """How one vendor column becomes a field: the field and the sign that turns it into the vocabulary's."""

    field: str
    sign: float = 1.0


@attrs.frozen
class VendorMap:
    """A vendor's export layout (one YAML file of ``impactlab/data/sessions/vendors``); see the module docstring."""

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
    #: [{value, scaled, why}]: numbers that mean "no value" (TrackMan's -2^31); ``scaled``: also the value times a
    #: power of ten (the instrument's integer written in another unit); read as missing, flagged ``no data``
    sentinels: tuple = ()
    #: columns whose presence says the header is another layout's (the older TrackMan layout is the newer one's
    #: columns without ``Spin Rate Type``)
    unless: tuple[str, ...] = ()
    #: {time, of, at_least, fields, why}: a flight tracked for less than ``at_least`` of its hang time (the field
    #: ``time`` over the field ``of``) is the monitor's model output: its ``fields`` are flagged ``modelled``
    tracked: dict | None = attrs.field(default=None, eq=False)
    estimated: dict | None = attrs.field(default=None, eq=False)
    clamped: dict = attrs.field(factory=dict, eq=False)
    #: field -> SI floor: values at or below it are the monitor's floor, flagged ``clamped`` (the R10 writes a launch
    #: angle of 0.4999999702 deg, float32 just below 0.5, for a ball it saw launch lower)
    floored: dict = attrs.field(factory=dict, eq=False)
    #: [{column, values, why}]: rows that are no shot (summary rows, heartbeats), skipped with ``why``
    summary_rows: list | None = attrs.field(default=None, eq=False)
    left_right_suffix: bool = False
    #: directions written with a leading L/R (Square Golf: ``L34.8`` is -34.8, ``R8.5`` is +8.5)
    left_right_prefix: bool = False
    #: fields that together mark "no club data" when every one of them reads exactly 0 in a row (Square Golf writes
    #: ``L0.0,L0.0,0.0,0.0`` for path, face, attack angle and dynamic loft when its camera saw no club): read as
    #: missing and flagged ``no data``
    no_data_when_all_zero: tuple[str, ...] = ()
    #: fields whose exact 0 is a placeholder, not a measurement (GSPro Open Connect clients send 0.0 for what their
    #: monitor did not measure: a 0 rpm TotalSpin beside real back and side spin, a 0 deg loft): missing, flagged
    zero_is_no_data: tuple[str, ...] = ()
    #: {column, values, fields}: rows whose column holds one of the values carry no data in those fields (GSPro's
    #: ContainsClubData = false): missing, flagged ``no data``
    no_data: dict | None = attrs.field(default=None, eq=False)
    #: {column, values, why}: every row's column must hold one of the values (an empty cell counts as ""); a file
    #: with another value is refused, naming its lines and ``why`` (GSPro's Units: only Yards is documented)
    required: dict | None = attrs.field(default=None, eq=False)
    #: True: the file's spin-axis sign is checked against its side spin (whose sign the layout states) and turned
    #: when every row disagrees (Garmin Golf app versions write the axis with either sign)
    spin_axis_follows_side_spin: bool = False
    #: {column, pattern}: the air stated in words in a text column (TrackMan's Condition: "Data are normalized to no
    #: wind conditions at 0 ft altitude, 77 degF ..."): the pattern's named groups are session fields, each
    #: captured as a number with its unit
    air_text: dict | None = attrs.field(default=None, eq=False)
    #: {column, values}: rows the user marked not to use (TrackMan's Use In Stat = FALSE)
    excluded: dict | None = attrs.field(default=None, eq=False)
    #: [{field, without, only_zero, why}]: a value written where a field it is made from is missing is a placeholder
    #: (Garmin writes Club Face 0.0 or Face to Path 0.0 with no club path, and a Smash Factor of -26.25 with no club
    #: speed): read as missing, flagged ``no data``; ``only_zero: true`` limits the rule to exact zeros
    no_data_without: tuple = ()
    #: the layout's own unit spellings in its units row (a Thai export's ``[ม.]`` is metres): spelling -> unit
    unit_spellings: dict = attrs.field(factory=dict, eq=False)
    #: words of the layout's club names -> the catalogue's (German ``Eisen 7`` -> ``Iron 7``), whole words only
    club_words: dict = attrs.field(factory=dict, eq=False)
    #: the text encoding of the vendor's files when they are not UTF-8 (FlightScope's simulator: windows-1252); a
    #: file in another encoding than UTF-8 is read only where the layout that recognises its header says so
    encoding: str = attrs.field(default="utf-8", validator=attrs.validators.in_(("utf-8", "windows-1252")))
    #: a column written twice under one header is merged (the first's value, the second's where it is empty)
    merge_repeated_columns: bool = False
    #: the row under the header holds the units without brackets (SkyTrak: ``#,L/R,SCORE,MPH,DEG,RPM``)
    units_row_plain: bool = False
    #: a row holding only its first cell names the club of the shots below it (SkyTrak's club blocks)
    club_rows: bool = False
    #: {column, values, why}: the row whose column holds one of the values, and every row below it, are no shots
    #: (SkyTrak's NOTES and the free text under it)
    trailer: dict | None = attrs.field(default=None, eq=False)

    def rule(self, header: str, row_unit: str | None = None) -> ColumnRule | None:
        """The rule of a header cell (matched case- and space-insensitively; ``Name [unit]`` keys need a unit).

        ``row_unit``, the column's unit in a units row, tells apart columns of one name (SkyTrak's two ``SIDE``:
        ``SIDE [RPM]`` the side spin, ``SIDE [DEG]`` the launch direction)."""
        name, unit = split_header(header)
        if row_unit and f"{_norm(name)} [{_norm(row_unit)}]" in self.columns:
            return self.columns[f"{_norm(name)} [{_norm(row_unit)}]"]
        full = _norm(header)
        if full in self.columns:
            return self.columns[full]
        if unit is not None and f"{_norm(name)} [unit]" in self.columns:
            return self.columns[f"{_norm(name)} [unit]"]
        return self.columns.get(_norm(name))


def _norm(text: str) -> str:
    return re.sub(r"\s+", " ", str(text).strip().lower())


#: the keys a layout may write: the fields of VendorMap (one list; the converter refuses any other)
_LAYOUT_KEYS = frozenset(field.name for field in attrs.fields(VendorMap))


@functools.cache
def _layout_converter():
    """The project's converter (:func:`impactlab.study.structuring.document_converter`) with VendorMap structured
    from a layout's checked values, unknown keys refused."""
    converter = document_converter()
    converter.register_structure_hook(VendorMap, make_dict_structure_fn(VendorMap, converter,
                                                                        _cattrs_forbid_extra_keys=True))
    return converter


def _vendor_from_document(document: dict, where: str) -> VendorMap:
    unknown = set(document) - _LAYOUT_KEYS
    if unknown:
        raise StudyError(f"{where}: unknown keys {sorted(unknown)} (a vendor map takes {sorted(_LAYOUT_KEYS)})")
    values = _layout_fields(document, where)
    values.update(_layout_rules(document, where))
    return _layout_converter().structure(values, VendorMap)


def _layout_fields(document: dict, where: str) -> dict:
    """A layout's columns and the rules naming fields, checked (StudyError at ``where``) and normalised."""
    columns = {}
    for header, rule in (document.get("columns") or {}).items():
        rule = {"field": rule} if isinstance(rule, str) or rule is None else dict(rule)
        field = rule.get("field")
        if field is not None and field not in FIELDS and field not in TEXT_FIELDS:
            raise StudyError(f"{where}: columns.{header}: {field!r} is not a session field "
                             f"({', '.join((*FIELDS, *TEXT_FIELDS))})")
        columns[_norm(header)] = None if field is None else ColumnRule(field, float(rule.get("sign", 1)))
    all_zero = tuple(document.get("no_data_when_all_zero") or ())
    zero = tuple(document.get("zero_is_no_data") or ())
    for key, fields in (("no_data_when_all_zero", all_zero), ("zero_is_no_data", zero),
                        ("no_data.fields", tuple((document.get("no_data") or {}).get("fields", ()))),
                        ("estimated.fields", tuple((document.get("estimated") or {}).get("fields", ())))):
        for field in fields:
            if field not in FIELDS:
                raise StudyError(f"{where}: {key}: {field!r} is not a numeric session field")
    without = _without(document.get("no_data_without"), where)
    summary = document.get("summary_rows")
    summary = [] if summary is None else (summary if isinstance(summary, list) else [summary])
    estimated = document.get("estimated")
    if estimated is not None and set(estimated) - {"column", "values", "measured", "fields"}:
        raise StudyError(f"{where}: estimated: {estimated!r}: expected {{column, values, measured, fields}}")
    for rule in (*summary, document.get("no_data"), document.get("required"), estimated, document.get("trailer")):
        if rule is not None and not ({"column", "values"} <= set(rule)):
            raise StudyError(f"{where}: {rule!r}: a row rule needs a column and its values")
    return {"columns": columns, "no_data_when_all_zero": all_zero, "zero_is_no_data": zero,
            "no_data_without": tuple(without), "summary_rows": summary or None, "estimated": estimated}


def _layout_rules(document: dict, where: str) -> dict:
    """A layout's other keys, checked (StudyError at ``where``) and normalised; limits in SI."""
    if document.get("left_right_suffix") and document.get("left_right_prefix"):
        raise StudyError(f"{where}: left_right_suffix and left_right_prefix: a layout writes L/R one way")
    if document.get("units") not in ("row", "header", "implied"):
        raise StudyError(f"{where}: units: expected row, header or implied")
    clamped = {}
    for field, limit in (document.get("clamped") or {}).items():
        clamped[field] = to_si(str(limit), FIELDS[field], f"{where}: clamped.{field}")
    floored = {field: to_si(str(limit), FIELDS[field], f"{where}: floored.{field}")
               for field, limit in (document.get("floored") or {}).items()}
    air_text = document.get("air_text")
    if air_text is not None:
        if set(air_text) != {"column", "pattern"}:
            raise StudyError(f"{where}: air_text: {air_text!r}: expected {{column, pattern}}")
        try:
            groups = re.compile(air_text["pattern"]).groupindex
        except re.error as exc:
            raise StudyError(f"{where}: air_text.pattern: {exc}") from None
        if not groups or set(groups) - {"air_temperature", "air_pressure", "relative_humidity", "altitude"}:
            raise StudyError(f"{where}: air_text.pattern: its named groups must be air fields (air_temperature, "
                             f"air_pressure, relative_humidity, altitude), got {sorted(groups)}")
    flag = {key: bool(document.get(key, False)) for key in (
        "left_right_suffix", "left_right_prefix", "units_row_plain", "club_rows", "merge_repeated_columns",
        "spin_axis_follows_side_spin")}
    return {**flag,
            "id": document["id"], "name": document["name"], "source": document["source"],
            "recognise": tuple(_norm(name) for name in document["recognise"]), "units": document["units"],
            "implied_units": {_norm(k): str(v) for k, v in (document.get("implied_units") or {}).items()},
            "loft_at": document.get("loft_at", "contact"),
            "club_reference_point": document.get("club_reference_point", "unknown"),
            "club_reference": " ".join(str(document.get("club_reference", "")).split()),
            "signs": " ".join(str(document.get("signs", "")).split()), "missing": tuple(document.get("missing", [""])),
            "sentinel_at_least": document.get("sentinel_at_least"), "clamped": clamped, "floored": floored,
            "no_data": document.get("no_data"), "required": document.get("required"),
            "excluded": document.get("excluded"),
            "unit_spellings": {_norm(k): str(v) for k, v in (document.get("unit_spellings") or {}).items()},
            "club_words": {_norm(k): str(v) for k, v in (document.get("club_words") or {}).items()},
            "trailer": document.get("trailer"), "encoding": document.get("encoding", "utf-8"), "air_text": air_text,
            "sentinels": _sentinels(document.get("sentinels"), where),
            "tracked": _tracked(document.get("tracked"), where),
            "unless": tuple(_norm(name) for name in document.get("unless") or ())}


def _without(rules, where: str) -> list:
    """A layout's ``no_data_without`` rules, checked."""
    without = []
    for rule in rules or ():
        if not isinstance(rule, dict) or not {"field", "without"} <= set(rule) or \
                set(rule) - {"field", "without", "only_zero", "why"}:
            raise StudyError(f"{where}: no_data_without: {rule!r}: expected {{field, without, only_zero, why}}")
        for field in (rule["field"], *rule["without"]):
            if field not in FIELDS:
                raise StudyError(f"{where}: no_data_without: {field!r} is not a numeric session field")
        without.append({"field": rule["field"], "without": tuple(rule["without"]),
                        "only_zero": bool(rule.get("only_zero", False)), "why": str(rule.get("why", ""))})
    return without


def _sentinels(rules, where: str) -> tuple:
    """A layout's numeric no-value markers, checked: ``[{value, scaled, why}]``."""
    for rule in rules or ():
        if not isinstance(rule, dict) or "value" not in rule or set(rule) - {"value", "scaled", "why"} or \
                isinstance(rule["value"], bool) or not isinstance(rule["value"], (int, float)):
            raise StudyError(f"{where}: sentinels: {rule!r}: expected {{value (a number), scaled, why}}")
    return tuple({"value": float(rule["value"]), "scaled": bool(rule.get("scaled", False)),
                  "why": str(rule.get("why", "a no-value marker"))} for rule in rules or ())


def _tracked(rule, where: str) -> dict | None:
    """A layout's rule of what its monitor tracked (``tracked``), checked."""
    if rule is None:
        return None
    if not isinstance(rule, dict) or set(rule) != {"time", "of", "at_least", "fields", "why"}:
        raise StudyError(f"{where}: tracked: {rule!r}: expected {{time, of, at_least, fields, why}}")
    for field in (rule["time"], rule["of"], *rule["fields"]):
        if field not in FIELDS:
            raise StudyError(f"{where}: tracked: {field!r} is not a numeric session field")
    if not 0 < float(rule["at_least"]) <= 1:
        raise StudyError(f"{where}: tracked.at_least: expected a fraction of the hang time in (0, 1]")
    return {**rule, "at_least": float(rule["at_least"]), "fields": tuple(rule["fields"])}


#: rules of a layout that name a column and the words written in it: a translated layout restates them
_WORDED_RULES = ("estimated", "excluded", "no_data", "required", "summary_rows", "trailer")


def _with_base(document: dict, documents: dict, where: str) -> dict:
    """A translated layout (``base: garmin_golf`` and ``headers: {Datum: Date, ...}``): the base layout's document
    with the translated header names added to its columns (each with the rule of the base's column it translates,
    signs included) and the layout's own keys over the base's. Rules that name a column and its words
    (:data:`_WORDED_RULES`) must be restated in the layout's words; implied units follow the translated names."""
    if "base" not in document:
        if "headers" in document:
            raise StudyError(f"{where}: headers: translates a base layout's headers; name the layout in 'base'")
        return document
    base = documents.get(document["base"])
    if base is None or "base" in base:
        raise StudyError(f"{where}: base: expected the id of a shipped layout that has no base itself, got "
                         f"{document['base']!r}")
    headers = document.get("headers") or {}
    if not headers:
        raise StudyError(f"{where}: headers: a layout with a base gives its header names (name: base layout's name)")
    base_columns = {_norm(k): v for k, v in (base.get("columns") or {}).items()}
    merged = {key: value for key, value in base.items() if key not in _WORDED_RULES}
    merged.update({key: value for key, value in document.items() if key not in ("base", "headers")})
    columns = dict(base.get("columns") or {})
    english = {}
    for local, name in headers.items():
        if _norm(name) not in base_columns:
            raise StudyError(f"{where}: headers.{local}: {name!r} is no column of the {document['base']} layout")
        columns[local] = base_columns[_norm(name)]
        english[_norm(name)] = local
    merged["columns"] = {**columns, **(document.get("columns") or {})}
    missing = [key for key in _WORDED_RULES if base.get(key) and key not in document]
    if missing:
        raise StudyError(f"{where}: {', '.join(missing)}: the {document['base']} layout's rule names its column and "
                         f"values in its own words; restate it in this layout's")
    merged["implied_units"] = {english.get(_norm(k), k): v for k, v in (base.get("implied_units") or {}).items()}
    merged["implied_units"].update(document.get("implied_units") or {})
    return merged


#: first words of layout ids that name no monitor: impactlab's own tables, and GSPro's relay, which carries any monitor
NO_MAKER = ("impactlab", "gspro")


def maker_of(layout_id: str) -> str:
    """The monitor's maker a layout names: the first word of its id (``trackman_tps_legacy``: trackman); '' for
    :data:`NO_MAKER`."""
    first = layout_id.split("_")[0]
    return "" if first in NO_MAKER else first


@functools.cache
def vendor_maps() -> dict[str, VendorMap]:
    """Every vendor layout shipped with impactlab, by id (a translated layout built on its base, :func:`_with_base`)."""
    import yaml

    documents = {}
    for entry in sorted(resources.files("impactlab.data.sessions.vendors").iterdir(), key=lambda e: e.name):
        if entry.name.endswith(".yaml"):
            where = f"impactlab/data/sessions/vendors/{entry.name}"
            documents[where] = yaml.safe_load(entry.read_text(encoding="utf-8"))
    by_id = {document.get("id"): document for document in documents.values() if isinstance(document, dict)}
    maps = {}
    for where, document in documents.items():
        vendor = _vendor_from_document(_with_base(document, by_id, where), where)
        maps[vendor.id] = vendor
    return maps


#: impactlab's own layout: vocabulary names and the usual launch-monitor names, units in the header or a units row
GENERIC = VendorMap(id="impactlab", name="impactlab shot table (vocabulary or usual launch-monitor names)",
                    source="", recognise=(), units="header", columns={}, missing=("",),
                    club_reference="as the table states (impactlab counts the delivery at the face centre after "
                                   "turning a contact-point loft back to it; docs/vendors.md)")


def split_header(header: str) -> tuple[str, str | None]:
    """(name, unit) of a header cell: ``Club Speed [mph]``, ``Ball Speed (m/s)``, ``AOA (°)`` (unit None: none)."""
    match = re.match(r"^\s*(.*?)\s*(?:[\[(]\s*([^\[\]()]*?)\s*[\])])?\s*$", str(header))
    if match is None:  # a cell holding a line break (a quoted CSV cell may): refused, never a traceback
        raise StudyError(f"header {header!r}: expected a column name on one line")
    return match.group(1), match.group(2)


def _unit_factor(unit: str, dimension: str, where: str) -> tuple[float, float]:
    """(scale, offset) of ``unit`` of ``dimension``: SI value = scale x + offset (vendor spellings accepted; the
    offset is 0 but for temperatures: 0 degF is 255.37 K); FieldError when it is not a unit of ``dimension``."""
    spelled = UNIT_SPELLINGS.get(unit.strip().lower(), unit.strip())
    if dimension == "dimensionless":
        if spelled in ("", "1", "-"):
            return 1.0, 0.0
        if spelled == "%":  # a relative humidity's [%]: the vocabulary's fractions
            return 0.01, 0.0
        raise FieldError(where, "a number without unit (or a percentage, [%])", unit)
    scale = to_si(f"1 {spelled}", dimension, where)  # refuses a unit that is not one of this dimension
    if dimension in ZERO_DEPENDS_ON_UNIT:
        return unit_affine(spelled, DIMENSIONS[dimension][0])
    return scale, 0.0


def _recognise(header: list[str], forced: str | None, file: str) -> VendorMap:
    maps = vendor_maps()
    names = {_norm(split_header(cell)[0]) for cell in header}
    found = [vendor for vendor in maps.values() if set(vendor.recognise) <= names and not set(vendor.unless) & names]
    found.sort(key=lambda vendor: -len(vendor.recognise))
    if forced is not None:
        if forced != GENERIC.id and forced not in maps:
            raise FieldError("--vendor", "a vendor layout", forced, choices=[GENERIC.id, *maps])
        chosen = GENERIC if forced == GENERIC.id else maps[forced]
        if found and chosen not in found:
            # another vendor's columns, read with this layout's signs, units and flags, would be wrong silently
            # (a Garmin file read as TrackMan's: its Sidespin's sign, its +-30 deg spin-axis clamp unflagged)
            raise StudyError(f"{file}: --vendor {forced}: the header is that of the {found[0].name} "
                             f"({found[0].id}; columns {', '.join(repr(name) for name in found[0].recognise)}), not "
                             f"of the {chosen.name}; read with the {forced} layout, its signs and flags would be "
                             f"wrong. Leave --vendor out, or give --vendor {found[0].id}")
        return chosen
    return found[0] if found else GENERIC


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
