"""The ball-flight model against TrackMan's published tour carries (impactlab/data/validation/trackman_carry*.yaml).

:func:`carry_table` reads the measured rows (launch in, max height, land angle and carry out, per club) with their
citation; :func:`validate_carry` flies each row's launch with a model of :data:`impactlab.physics.aerodynamics.MODELS`
and gives model beside measurement; :func:`session_carry` does the same for the shots of a launch-monitor export that
carry the vendor's carry. ``python -m impactlab.data.carry [MODEL ...]`` prints the tables of docs/flight.md.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from importlib import resources

import attrs
import numpy as np
import yaml

from impactlab.data.sessions.reader import read_session
from impactlab.data.sessions.flight import fly_session
from impactlab.errors import StudyError
from impactlab.physics import flight
from impactlab.physics.aerodynamics import DEFAULT_MODEL, MODELS, retired_reason
from impactlab.units import MPH, YARD

#: the measured carry tables shipped (TrackMan PGA classic, PGA 2023 season, LPGA 2023 season)
TABLES = ("trackman_carry", "trackman_carry_pga_2023", "trackman_carry_lpga_2023")
RPM = np.pi / 30.0  #: rad/s per rpm


@attrs.frozen
class CarryTable:
    """Measured launch and flight per club (SI): what the flight model is validated on.

    Attributes
    ----------
    clubs : tuple of str
    ball_speed, launch_angle, spin_rate : ndarray
        The launch: m/s, rad, rad/s.
    max_height, land_angle, carry : ndarray
        The measured flight: m, rad, m (NaN where the table has no such column or cell).
    source, confirmed : str
        Citation, and which cells were checked as text.
    flight_time : ndarray or None
        Measured flight (hang) time, s, where the table has one (NaN cells where not published).
    air : dict
        The air the table was measured in as :func:`impactlab.physics.flight.fly` keywords (``temperature`` K,
        ``relative_humidity``, ``altitude`` m), where the table states or implies it; empty: not published.
    """

    clubs: tuple
    ball_speed: np.ndarray = attrs.field(eq=False)
    launch_angle: np.ndarray = attrs.field(eq=False)
    spin_rate: np.ndarray = attrs.field(eq=False)
    max_height: np.ndarray = attrs.field(eq=False)
    land_angle: np.ndarray = attrs.field(eq=False)
    carry: np.ndarray = attrs.field(eq=False)
    source: str = ""
    confirmed: str = ""
    flight_time: np.ndarray | None = attrs.field(eq=False, default=None)
    air: dict = attrs.field(eq=False, factory=dict)


#: columns every measured table has, and their units as written in the YAML
REQUIRED_UNITS = {"ball_speed": "mph", "launch_angle": "deg", "spin_rate": "rpm", "carry": "yd"}
#: columns a table may have (NaN where it has not)
OPTIONAL_UNITS = {"max_height": "yd", "land_angle": "deg", "flight_time": "s"}
#: the keys of a table's ``air`` block and the factor to the fly() keyword's SI unit
AIR_KEYS = {"temperature_degC": ("temperature", 1.0, 273.15), "relative_humidity": ("relative_humidity", 1.0, 0.0),
            "altitude_m": ("altitude", 1.0, 0.0)}
#: the range each ``air`` value must lie in, as written (a humidity of 50 is a percentage, not a fraction)
AIR_RANGES = {"temperature_degC": (-40.0, 50.0), "relative_humidity": (0.0, 1.0), "altitude_m": (-500.0, 5000.0)}


@functools.cache
def carry_table(name: str = "trackman_carry") -> CarryTable:
    """The measured table ``name`` shipped in impactlab/data/validation (units converted to SI).

    The file's ``units`` must name every column of :data:`REQUIRED_UNITS` and may name those of
    :data:`OPTIONAL_UNITS`, each in the unit given there; its optional ``air`` block (:data:`AIR_KEYS`) becomes
    :attr:`CarryTable.air`.
    """
    document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath(f"{name}.yaml").read_text())
    # a malformed table is one ValueError naming the file and what is wrong (never a column taken in a unit it is
    # not in, a required cell read as NaN or an air key dropped: each would be a wrong carry, not a refusal)
    where = f"impactlab/data/validation/{name}.yaml"
    if document.get("kind") != "measurement":
        raise ValueError(f"{where}: kind: expected 'measurement', got {document.get('kind')!r}")
    units = document.get("units") or {}
    known = {**REQUIRED_UNITS, **OPTIONAL_UNITS}
    wrong = {key: unit for key, unit in units.items() if known.get(key) != unit}
    missing = sorted(set(REQUIRED_UNITS) - set(units))
    if wrong or missing:
        raise ValueError(f"{where}: units: expected {REQUIRED_UNITS} and any of {OPTIONAL_UNITS}; "
                         + "; ".join(([f"missing {missing}"] if missing else [])
                                     + [f"{key}: {unit!r} not accepted" for key, unit in wrong.items()]))
    rows = document["rows"]
    for index, row in enumerate(rows):
        empty = [key for key in ("club", *REQUIRED_UNITS) if row.get(key) is None]
        if empty:
            raise ValueError(f"{where}: row {index + 1} ({row.get('club', '?')}): no {', '.join(empty)} (every row "
                             f"needs the club, {', '.join(REQUIRED_UNITS)})")
    unknown = sorted(set(document.get("air") or {}) - set(AIR_KEYS))
    if unknown:
        raise ValueError(f"{where}: air: unknown {unknown}; expected keys among {sorted(AIR_KEYS)}")
    for key, value in (document.get("air") or {}).items():
        low, high = AIR_RANGES[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not low <= value <= high:
            raise ValueError(f"{where}: air: {key}: expected a number from {low:g} to {high:g}, got {value!r}")

    def column(key, factor):
        if key not in units:
            return np.full(len(rows), np.nan)
        return np.array([np.nan if row.get(key) is None else row[key] for row in rows], dtype=float) * factor

    air = {AIR_KEYS[key][0]: float(value) * AIR_KEYS[key][1] + AIR_KEYS[key][2]
           for key, value in (document.get("air") or {}).items()}
    return CarryTable(tuple(row["club"] for row in rows), column("ball_speed", MPH),
                      column("launch_angle", np.pi / 180), column("spin_rate", RPM), column("max_height", YARD),
                      column("land_angle", np.pi / 180), column("carry", YARD), document["source"].strip(),
                      document.get("confirmed", "").strip(),
                      column("flight_time", 1.0) if "flight_time" in units else None, air)


def validate_carry(model: str | Callable = DEFAULT_MODEL, table: CarryTable | None = None, **options) -> dict:
    """Fly every row of ``table`` with ``model``; model and measurement side by side (SI) and the carry errors.

    Parameters
    ----------
    model : str or callable
        A key of :data:`impactlab.physics.aerodynamics.MODELS`, or a function ``(S, Re) -> (CD, CL)``.
    table : CarryTable, optional
        Default :func:`carry_table`.
    **options
        Passed to :func:`impactlab.physics.flight.fly` (air, spin decay...); default the table's :attr:`~CarryTable.air`
        where it states one, else the standard air (15 degC, 101 325 Pa, 50 %), since TrackMan's tables are not
        normalised to any.

    Returns
    -------
    dict
        ``carry``, ``apex_height`` [m], ``landing_angle`` [rad], ``flight_time`` [s] of the model; ``carry_error``
        (relative, model over measurement minus 1); ``rms_carry_error`` (relative); ``table``.
    """
    table = table or carry_table()
    result = flight.fly(table.ball_speed, table.launch_angle, table.spin_rate, model=model, **{**table.air, **options})
    error = result["carry_distance"] / table.carry - 1.0
    return {"carry": result["carry_distance"], "apex_height": result["apex_height"],
            "landing_angle": result["landing_angle"], "flight_time": result["flight_time"], "carry_error": error,
            "rms_carry_error": float(np.sqrt(np.mean(np.square(error)))), "table": table}


def session_carry(path, model: str = DEFAULT_MODEL, conditions=None, include_flagged: bool = True,
                  session_air: bool = False) -> dict:
    """Fly the launch of every shot of a launch-monitor export that has the vendor's carry; model beside vendor.

    The table of docs/flight.md ("Launch-monitor exports"): :func:`impactlab.data.sessions.flight.fly_session` (the
    one code path of ``impactlab fly SESSION``), kept to the shots with a carry, by default with the monitor's
    flagged launches too and in the standard air (the vendors' own models are compared on one air).

    Parameters
    ----------
    path : path-like
        An export :func:`impactlab.data.sessions.reader.read_session` reads.
    model : str
        A key of :data:`impactlab.physics.aerodynamics.MODELS`.
    conditions : mapping, optional
        The air, as :func:`impactlab.fly` takes it (each value with its unit); None: the standard air.
    include_flagged, session_air : bool
        As :func:`~impactlab.data.sessions.flight.fly_session`: fly launches the monitor flags (estimated spins);
        fly each shot in the air its export states.

    Returns
    -------
    dict
        ``vendor`` (name), ``club``, ``ball_speed`` [m/s], ``launch_angle`` [rad], ``spin_rate`` [rad/s], ``spin_axis``
        [rad] (0 where the export has none), ``vendor_carry`` and ``carry`` [m], ``carry_error`` (model over vendor
        minus 1), for the shots flown that have a carry.

    Raises
    ------
    StudyError
        A shot with a ball speed or spin below zero, or a carry that is not positive (each at its file:line).
    """
    session = read_session(path)
    v = session.values
    # a carry that is not positive beside a launch is a placeholder or a column error: refused at its line rather
    # than divided by (a row without a launch, one the monitor did not read, is no shot to compare: not flown)
    launched = np.all([np.isfinite(v[name]) for name in ("ball_speed", "vertical_launch_angle", "spin_rate")], axis=0)
    problems = [f"{session.file}:{line}: carry_distance: expected a carry > 0, got {carry:.6g} m"
                for line, carry, launch in zip(session.lines, v["carry_distance"], launched)
                if launch and np.isfinite(carry) and not carry > 0.0]
    # a comparison table of the docs, not a user's session: a bad row (a spin below zero...) refuses it, named
    problems = [f"{session.file}:{line}: {why}" for line, why in session.bad_rows()] + problems
    try:
        flown = fly_session(session, model=model, conditions=conditions, include_flagged=include_flagged,
                            session_air=session_air)
    except StudyError as exc:  # the launches' problems (a negative speed or spin) beside the carries'
        raise StudyError("; ".join([str(exc), *problems])) from None
    if problems:
        raise StudyError("; ".join(problems))
    if "monitor_carry_distance" not in flown:
        raise StudyError(f"{session.file}: no shot flown has the monitor's carry to compare with")
    keep = np.isfinite(flown["monitor_carry_distance"].values)
    picked = flown.isel(shot=np.flatnonzero(keep))
    vendor_carry = picked["monitor_carry_distance"].values
    return {"vendor": session.vendor.name, "club": [str(club) for club in picked.club.values],
            "ball_speed": picked.ball_speed.values, "launch_angle": np.radians(picked.vertical_launch_angle.values),
            "spin_rate": picked.spin_rate.values * np.pi / 30.0,
            "spin_axis": np.nan_to_num(np.radians(picked.spin_axis.values)), "vendor_carry": vendor_carry,
            "carry": picked.carry_distance.values, "carry_error": picked.carry_distance.values / vendor_carry - 1.0}


def format_validation(model: str = DEFAULT_MODEL, table: str = "trackman_carry", **options) -> str:
    """The validation of ``model`` on the shipped table ``table`` as Markdown (yards, degrees), with its RMS error."""
    check = validate_carry(model, carry_table(table), **options)
    rows = check["table"]
    lines = [f"{model}: RMS carry error {100 * check['rms_carry_error']:.1f} %, mean "
             f"{100 * float(np.nanmean(check['carry_error'])):+.1f} %", "",
             "| club | carry TM yd | model yd | error | height TM yd | model yd | land TM deg | model deg |",
             "|---|---|---|---|---|---|---|---|"]
    for index, club in enumerate(rows.clubs):
        lines.append(
            f"| {club} | {rows.carry[index] / YARD:.0f} | {check['carry'][index] / YARD:.1f} | "
            f"{100 * check['carry_error'][index]:+.1f} % | {rows.max_height[index] / YARD:.0f} | "
            f"{check['apex_height'][index] / YARD:.1f} | {np.degrees(rows.land_angle[index]):.0f} | "
            f"{np.degrees(check['landing_angle'][index]):.1f} |")
    return "\n".join(lines)


def format_summary(models) -> str:
    """One Markdown row per model: RMS (mean) carry error on each of :data:`TABLES`, and the mean height and land-angle
    differences over all their rows (model minus measurement)."""
    lines = ["| model | " + " | ".join(f"{name} RMS (mean) carry" for name in TABLES) + " | height (mean) | land "
             "angle (mean) |", "|---" * (len(TABLES) + 3) + "|"]
    for model in models:
        checks = [validate_carry(model, carry_table(name)) for name in TABLES]
        cells = [f"{100 * c['rms_carry_error']:.1f} % ({100 * float(np.nanmean(c['carry_error'])):+.1f} %)"
                 for c in checks]
        height = np.concatenate([c["apex_height"] - c["table"].max_height for c in checks]) / YARD
        land = np.degrees(np.concatenate([c["landing_angle"] - c["table"].land_angle for c in checks]))
        lines.append(f"| `{model}` | " + " | ".join(cells) + f" | {np.nanmean(height):+.1f} yd | "
                     f"{np.nanmean(land):+.1f} deg |")
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m impactlab.data.carry [MODEL ...]``: the summary and every table's validation (default every
    model but ``vacuum``). An unknown model is one message and exit code 2 (argparse), never a traceback."""
    import argparse

    names = [key for key in MODELS if key != "vacuum"]
    parser = argparse.ArgumentParser(prog="python -m impactlab.data.carry",
                                     description="Fly TrackMan's tour tables with aerodynamic models (docs/flight.md).")
    parser.add_argument("models", nargs="*", metavar="MODEL", help=f"models to fly (default all: {', '.join(names)})")
    models = parser.parse_args(argv).models or names
    retired = [reason for reason in map(retired_reason, models) if reason]
    if retired:
        parser.error("; ".join(retired))
    unknown = [name for name in models if name not in MODELS]
    if unknown:
        parser.error(f"unknown model {', '.join(unknown)}; choose from {', '.join(sorted(MODELS))}")
    print(format_summary(models), end="\n\n")
    for table_name in TABLES:
        print(f"## {table_name}", end="\n\n")
        for name in models:
            print(format_validation(name, table_name), end="\n\n")
    return 0


if __name__ == "__main__":  # pragma: no cover - prints the tables of docs/flight.md
    raise SystemExit(main())
