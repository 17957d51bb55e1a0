"""A launch-monitor session flown: each shot's measured launch through the air, beside what the monitor reported.

``impactlab fly SESSION`` (and :func:`fly_session`) takes an export as :func:`impactlab.data.sessions.reader.read_session`
reads it, flies every shot that has a ball speed, a launch angle and a spin rate with
:func:`impactlab.scene.flight.fly`, and puts the monitor's own carry, offline, apex, landing angle and flight time
beside each prediction where the export has them. Nothing is guessed for a shot:

- a shot without ball speed, launch angle or spin is not flown, and the result says why (``skipped``);
- a shot whose spin (or ball speed, or launch) the monitor marks estimated, clamped or inconsistent is not flown
  unless asked (``include_flagged``): an estimated spin is the monitor's model, not a measurement; a spin rate the
  export lacks but the reader derives from measured back and side spin (flagged ``no data`` there) is flown;
- a shot launched below the horizontal (a topped ball) is not flown: from the ground it meets the ground at once,
  and a carry of 0 beside the monitor's would only say so; nor a shot whose back spin is below 0 (topspin: the
  spin rate and spin axis the export gives would fly it as backspin), nor one whose launch angle, launch direction
  or spin axis is 90 deg or more from the target's (beyond +-90 deg for the axis): no golf shot has them;
- a shot without a spin axis is flown as pure backspin and without a launch direction as straight, and its offline
  distance is then not given (NaN): the carry barely depends on them (cos of the tilt in the lift), the offline
  entirely.

The air: a shot whose export states its air (Garmin's Temperature, Air Pressure and Relative Humidity, checked
against its Air Density by the reader; TrackMan's Condition in words) is flown in that air, unless ``conditions``
give the air itself (a temperature, pressure, altitude or humidity: they then set the air of every shot, and the
result says the session's own was not used) or ``session_air`` is False; a wind alone (``headwind``,
``crosswind``) blows through each shot's own air. A shot without its air (or with air the reader flags
inconsistent) flies in the standard air, and the result counts them.

The monitor's carry is what the export says. Whether it is measured depends on the unit: radar units outdoors
track much of the flight; camera units and indoor sessions fly the launch with their own model, and some exports
state that their rows are normalised to a standard air (docs/vendors.md, docs/flight.md).
"""

from __future__ import annotations

import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from impactlab.data.sessions.reader import Session
from impactlab.data.sessions.air import AIR_IN_WORDS
from impactlab.errors import FieldError, PlausibilityWarning, StudyError
from impactlab.physics.aerodynamics import DEFAULT_MODEL
from impactlab.scene import flight
from impactlab.scene.plausibility import wrong_sign

#: the launch a shot needs to be flown
LAUNCH = ("ball_speed", "vertical_launch_angle", "spin_rate")
#: what the flight predicts, and the session field the monitor reports it in (the same names)
PREDICTED = ("carry_distance", "offline_distance", "apex_height", "landing_angle", "flight_time")
#: the prefix of the monitor's own value of a predicted quantity in the result
MONITOR = "monitor_"
#: the air a shot states (session fields), as :class:`impactlab.scene.flight.Conditions` takes it: a temperature
#: and a pressure or an altitude (the ISA pressure there) state an air; a humidity not stated is the standard 50 %
SESSION_AIR = {"air_temperature": "temperature", "air_pressure": "pressure", "altitude": "altitude",
               "relative_humidity": "relative_humidity"}


def fly_session(session: Session, *, model: str = DEFAULT_MODEL, conditions: Mapping | None = None,
                include_flagged: bool = False, session_air: bool = True) -> xr.Dataset:
    """Fly every shot of ``session`` that has a launch; the monitor's values beside the predictions.

    Parameters
    ----------
    session : Session
        A session as :func:`impactlab.data.sessions.reader.read_session` returns it (SI values).
    model : str
        Aerodynamic model, a key of :data:`impactlab.physics.aerodynamics.MODELS`.
    conditions : mapping, optional
        The air, as :func:`impactlab.fly` takes it (``temperature``, ``pressure`` or ``altitude``,
        ``relative_humidity``, ``headwind``, ``crosswind``, each with its unit), for every shot; None (or empty):
        each shot in the air its export states, else 15 degC, 101 325 Pa, 50 %, still; a wind alone is added to
        each shot's own air. A comparison with a monitor that normalises its rows should give that monitor's
        standard air.
    include_flagged : bool
        Also fly shots whose launch values the monitor marks estimated, clamped or inconsistent.
    session_air : bool
        Fly a shot in the air its export states (when ``conditions`` are not given); False: the standard air.

    Returns
    -------
    xarray.Dataset
        On dim ``shot`` (the shots flown, in file order), coordinates ``line`` (the file line) and ``club``;
        the launch flown (``ball_speed`` [m/s], ``vertical_launch_angle`` [degree], ``spin_rate`` [rpm],
        ``spin_axis`` [degree], NaN where the export has none); the predictions of :data:`PREDICTED` in the units
        of :data:`impactlab.vocabulary.OUTPUTS` (``offline_distance`` NaN where the spin axis or launch direction
        is missing); ``monitor_<name>`` for each predicted quantity the export has (NaN in the rows without
        it); ``flagged`` (bool: a launch value flown though the monitor flags it); ``air_density`` [kg/m^3], the
        air each shot was flown in. Attributes: ``file``, ``vendor``, ``aerodynamic_model``, ``skipped`` (one
        "line N: reason" per shot not flown, ``; ``-joined), ``air_source`` (whose air, in words); where every shot
        flew in one air, its ``air_*`` attributes as :func:`impactlab.fly` gives them.

    Raises
    ------
    StudyError
        A shot with a negative ball speed or spin (a sign or column error, never a shot to fly), or air the
        flight cannot take (e.g. a temperature above 77 degC), at its file:line; or a session with no shot to fly,
        saying why each was left out.
    """
    v = session.values
    fly_rows, flagged, skipped = _rows_to_fly(session, include_flagged)
    rows = np.flatnonzero(fly_rows)
    if rows.size == 0:
        raise StudyError(f"{session.file}: no shot to fly (each needs a ball speed, a launch angle and a spin "
                         f"rate): " + "; ".join(skipped or ["the file has no shots"]))
    problems = [problem for row in rows.tolist() for problem in wrong_sign(
        {"ball_speed": v["ball_speed"], "spin_rate": v["spin_rate"]}, row, f"{session.file}:{session.lines[row]}")]
    if problems:
        raise StudyError("; ".join(problems))
    axis, direction = v["spin_axis"][rows], v["horizontal_launch_angle"][rows]
    for name, (unit, factor, limit, because) in flight.UNUSUAL_LAUNCH.items():
        for row in rows[v[name][rows] > limit].tolist():  # said at the file's line, not at an index of the flight
            warnings.warn(f"{session.file}:{session.lines[row]}: {name.replace('_', ' ')} {v[name][row] * factor:.6g} "
                          f"{unit} is unusual for golf ({because}); flown as given", PlausibilityWarning, stacklevel=2)
    air, air_source = _airs(session, rows, conditions, session_air)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        flown, air_density = _fly_in(air, v, rows, model)
    return _flight_dataset(session, rows, flagged, skipped, flown, air_density, axis, direction, model,
                           air_source)


def _rows_to_fly(session, include_flagged: bool) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """The rows that can be flown, the rows whose launch the monitor flags, and why each other row is not flown."""
    v = session.values
    with np.errstate(invalid="ignore"):
        downward = v["vertical_launch_angle"] < 0.0
        topspin = v["back_spin"] < 0.0
        # angles no golf shot has (a column in other units or conventions): an axis tilted past the vertical is
        # topspin, a launch at or beyond 90 deg goes straight up or backwards; flown, each would be a number
        impossible = {name: np.abs(v[name]) >= limit for name, limit in (
            ("vertical_launch_angle", np.pi / 2), ("spin_axis", np.nextafter(np.pi / 2, 4.0)),
            ("horizontal_launch_angle", np.pi / 2))}
        beyond = {name: v[name] > limit for name, (limit, _) in flight.IMPOSSIBLE_LAUNCH.items()}
    present = (np.all([np.isfinite(v[name]) for name in LAUNCH], axis=0) & ~(v["ball_speed"] == 0.0) & ~downward
               & ~topspin & ~np.any(list(impossible.values()), axis=0) & ~np.any(list(beyond.values()), axis=0))
    flagged = np.zeros(session.size, dtype=bool)
    why: dict[int, list[str]] = {}
    for (field, kind), rows in session.flags.items():
        # a 'no data' flag marks a value the export lacks: it is NaN (missing, said below) unless the reader derived
        # it from measured values (a spin rate from back and side spin), which is no estimate
        if field in LAUNCH + ("spin_axis",) and kind != "no data":
            flagged |= rows
            for row in np.flatnonzero(rows).tolist():
                why.setdefault(row, []).append(f"{field} {kind}")
    fly_rows = present & (include_flagged | ~flagged)
    skipped = [f"line {session.lines[row]}: {_reason(v, row, downward, topspin, impossible, beyond, why)}"
               for row in np.flatnonzero(~fly_rows).tolist()]
    return fly_rows, flagged, skipped


def _reason(v: dict, row: int, downward, topspin, impossible: dict, beyond: dict, why: dict) -> str:
    """Why a row is not flown, in words."""
    missing = [name for name in LAUNCH if not np.isfinite(v[name][row])] + (
        ["ball speed above 0 (the row's is 0: no shot)"] if v["ball_speed"][row] == 0.0 else [])
    if missing:
        reason = "no " + ", no ".join(missing)
    elif downward[row]:
        reason = (f"launch angle {np.degrees(v['vertical_launch_angle'][row]):.1f} deg, below the horizontal: the "
                  "ball meets the ground at once, there is no carry to predict")
    elif topspin[row]:
        reason = (f"back spin {v['back_spin'][row] * 30.0 / np.pi:.0f} rpm, below 0 (topspin), which a spin rate "
                  "and a tilt of the axis do not carry: flown, it would be backspin")
    elif any(refused[row] for refused in impossible.values()):
        name = next(name for name, refused in impossible.items() if refused[row])
        reason = (f"{name.replace('_', ' ')} {np.degrees(v[name][row]):.1f} deg, beyond +-90 deg: no golf shot "
                  "(a column in other units or another convention?)")
    elif any(refused[row] for refused in beyond.values()):
        name = next(name for name, refused in beyond.items() if refused[row])
        unit, factor = flight.UNUSUAL_LAUNCH[name][:2]
        reason = (f"{name.replace('_', ' ')} {v[name][row] * factor:.6g} {unit}, beyond "
                  f"{flight.IMPOSSIBLE_LAUNCH[name][1].split(' (')[0].split(' up to ')[1]}: no golf shot (a column "
                  "in other units?)")
    else:
        reason = (f"launch values flagged by the monitor ({', '.join(why[row])}; --include-flagged flies "
                  "them)")
    return reason


def _flight_dataset(session, rows, flagged, skipped, flown, air_density, axis, direction, model: str,
                    air_source: str) -> xr.Dataset:
    """The flown shots beside what the monitor reported, one ``shot`` per row flown."""
    v = session.values
    data = {
        "ball_speed": ("shot", v["ball_speed"][rows], {"units": "m/s", "long_name": "ball speed flown"}),
        "vertical_launch_angle": ("shot", np.degrees(v["vertical_launch_angle"][rows]),
                                  {"units": "degree", "long_name": "launch angle flown"}),
        "spin_rate": ("shot", v["spin_rate"][rows] * 30.0 / np.pi, {"units": "rpm", "long_name": "spin rate flown"}),
        "spin_axis": ("shot", np.degrees(axis), {"units": "degree", "long_name": "spin axis flown (NaN: not in the "
                                                 "export, flown as 0)"}),
        "flagged": ("shot", flagged[rows], {"long_name": "a launch value the monitor flags (estimated or clamped)"}),
        "air_density": ("shot", air_density, {"units": "kg/m^3", "long_name": "density of the air flown in"}),
    }
    for name in PREDICTED:
        values = np.array(flown[name].values, dtype=float)
        if name == "offline_distance":
            values[~(np.isfinite(axis) & np.isfinite(direction))] = np.nan
        data[name] = ("shot", values, dict(flown[name].attrs))
        if np.isfinite(v[name][rows]).any():
            reported = v[name][rows] if name != "landing_angle" else np.degrees(v[name][rows])
            data[MONITOR + name] = ("shot", reported, {"units": flown[name].attrs["units"],
                                                       "long_name": f"{name.replace('_', ' ')} the monitor reports"})
    coords = {"line": ("shot", np.asarray(session.lines)[rows]),
              "club": ("shot", [session.text["club"][row] for row in rows.tolist()])}
    attributes = {"file": str(session.file), "vendor": session.vendor.name, "aerodynamic_model": model,
                  "skipped": "; ".join(skipped), "air_source": air_source}
    attributes.update({key: value for key, value in flown.attrs.items() if key not in attributes})
    return xr.Dataset(data, coords=coords, attrs=attributes)


def _airs(session: Session, rows: np.ndarray, conditions: Mapping | None, session_air: bool):
    """(the air of the rows flown: a Conditions of one value per shot, the ``conditions`` mapping for all, or None
    for the standard air; whose air, in words)."""
    v = session.values
    with_pressure = np.isfinite(v["air_pressure"])
    states = np.isfinite(v["air_temperature"]) & (with_pressure | np.isfinite(v["altitude"]))
    doubtful = np.zeros_like(states)
    for (field, _), marked in session.flags.items():  # any flag on the air: estimated, inconsistent
        if field in SESSION_AIR or field == "air_density":
            doubtful |= marked & states
    usable = states & ~doubtful
    stated, rejected = int(usable[rows].sum()), int(doubtful[rows].sum())
    caveat = (f"; the air of {rejected} shot(s) is flagged inconsistent by the reader (`impactlab shots` says why) "
              "and not used" if rejected else "")
    # wind options blow through each shot's own air; any other air option replaces the export's air
    wind = {key: value for key, value in (conditions or {}).items() if key in ("headwind", "crosswind")}
    replaces = len(wind) < len(conditions or {})
    if replaces or not session_air or not stated:
        if conditions:
            words = "the options" + (f" (the export's own air, stated for {stated} shot(s) flown, not used)"
                                     if stated else "")
        elif stated:
            words = f"the standard air (the export's own air, stated for {stated} shot(s) flown, not used)"
        else:
            words = "the standard air" + ("" if rejected else " (the export states no air)")
        return conditions if conditions else None, words + caveat
    blowing = flight.conditions_from(wind) if wind else flight.Conditions()
    # one air per shot flown, as arrays: a row without its air (or with air flagged) takes the standard air; a
    # pressure, when stated, sets the air, an altitude only where no pressure is (NaN: not given for that shot)
    own = usable[rows]
    pressure = np.where(own & with_pressure[rows], v["air_pressure"][rows], np.nan)
    altitude = np.where(own & ~with_pressure[rows], v["altitude"][rows], np.nan)
    given: dict[str, Any] = {
        "temperature": np.where(own, v["air_temperature"][rows], flight.STANDARD_TEMPERATURE),
        "pressure": pressure if np.isfinite(pressure).any() else None,
        "altitude": altitude if np.isfinite(altitude).any() else None,
        "relative_humidity": np.where(own & np.isfinite(v["relative_humidity"][rows]), v["relative_humidity"][rows],
                                      flight.STANDARD_RELATIVE_HUMIDITY),
        "headwind": blowing.headwind, "crosswind": blowing.crosswind}
    try:
        air = flight.Conditions(**given)
    except FieldError as exc:  # the row's value in the words people use for it, not its SI float
        key, _, index = exc.path.partition("[")
        field = next((field for field, name in SESSION_AIR.items() if name == key), None)
        row = rows[int(index.rstrip("]"))] if index else rows[0]
        raise FieldError(f"air.{key}", exc.expected, AIR_IN_WORDS[field](exc.given)
                         if field and isinstance(exc.given, float) else exc.given, file=str(session.file),
                         line=session.lines[row]) from None
    standard = rows.size - stated
    stated_fields = [words for field, words in (("air_pressure", "pressure"), ("altitude", "altitude"),
                                                ("relative_humidity", "humidity"))
                     if np.isfinite(v[field][rows][usable[rows]]).any()]
    no_humidity = int((usable[rows] & ~np.isfinite(v["relative_humidity"][rows])).sum())
    return air, (f"the export's own, per shot (each row's temperature, {' and '.join(stated_fields)})"
                  + (f"; humidity not stated for {no_humidity} shot(s): 50 % taken" if no_humidity else "")
                  + (f"; {standard} shot(s) in the standard air" if standard else "")
                  + ("; the options' wind in every shot's air" if wind else "") + caveat)


def _fly_in(air, v: dict, rows: np.ndarray, model: str):
    """Fly ``rows`` of ``v`` in one call, each shot in its air (``air``: None, a mapping or a Conditions, one value
    for every shot or one per shot); (the flight, with its air_* attributes only where every shot flew in one air,
    and each shot's air density [kg/m^3])."""
    axis, direction = v["spin_axis"][rows], v["horizontal_launch_angle"][rows]
    flown = flight.fly(v["ball_speed"][rows], v["vertical_launch_angle"][rows], v["spin_rate"][rows],
                       np.nan_to_num(axis), np.nan_to_num(direction), air, model=model)
    if "air_density" in flown.coords:  # the air varies from shot to shot
        density = np.asarray(flown["air_density"].values, dtype=float)
    else:
        density = np.full(rows.size, flown.attrs["air_density_kg_m3"])
    return flown, density
