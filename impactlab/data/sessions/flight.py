"""A launch-monitor session flown: each shot's measured launch through the air, beside what the monitor reported.

``impactlab fly SESSION`` (and :func:`fly_session`) takes an export as
:func:`impactlab.data.sessions.reader.read_session` reads it, flies every shot that has a ball speed, a launch angle and
a spin rate with :func:`impactlab.scene.flight.fly`, and puts the monitor's own carry, offline, apex, landing angle and
flight time beside each prediction where the export has them. Nothing is guessed for a shot:

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

import json
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np
import xarray as xr

from impactlab.data.sessions.layouts import DESCRIPTIONS
from impactlab.data.sessions.reader import Session
from impactlab.data.sessions.air import AIR_IN_WORDS
from impactlab.data.sessions.summary import reason_counts
from impactlab.errors import FieldError, PlausibilityWarning, StudyError
from impactlab.physics.aerodynamics import DEFAULT_MODEL
from impactlab.scene import flight

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
        it); ``monitor_measured`` (bool, where the layout says which flights its monitor tracked: TrackMan's
        tracked time against the hang time); ``flagged`` (bool: a launch value flown though the monitor flags it);
        ``air_density`` [kg/m^3], the air each shot was flown in. Attributes: ``file``, ``vendor``,
        ``aerodynamic_model``, ``skipped`` (one "line N: reasons" per shot not flown, ``; ``-joined),
        ``skipped_rows`` and ``unusual_rows`` (JSON: [line, reasons] pairs; [reason, lines] of the unusual values
        flown), ``air_source`` (whose air, in words); where every shot flew in one air, its ``air_*`` attributes as
        :func:`impactlab.fly` gives them.

    Raises
    ------
    StudyError
        Air the flight cannot take (e.g. a temperature above 77 degC), at its file:line; or a session with no shot
        to fly, saying why the rows were left out (counted by reason). A row that breaks the row rules (a negative
        ball speed, a value beyond any shot) is not flown, with its reason in ``skipped``.
    """
    v = session.values
    fly_rows, flagged, skipped = flight_rows(session, include_flagged)
    rows = np.flatnonzero(fly_rows)
    if rows.size == 0:
        raise StudyError(f"{session.file}: no shot to fly (each needs a ball speed, a launch angle and a spin "
                         f"rate): " + (reason_counts(skipped, file=str(session.file)) or "the file has no shots"))
    axis = v["spin_axis"][rows]
    air, air_source = _airs(session, rows, conditions, session_air)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", PlausibilityWarning)
        flown, air_density = _fly_in(air, v, rows, model)
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
    _predictions_and_monitor(session, rows, flown, data)
    coords = {"line": ("shot", np.asarray(session.lines)[rows]),
              "club": ("shot", [session.text["club"][row] for row in rows.tolist()])}
    unusual = [(reason, [int(line) for line in session.lines[mask & fly_rows]])
               for reason, mask in session.verdict().unusual if (mask & fly_rows).any()]
    attributes = {"file": str(session.file), "vendor": session.vendor.name, "aerodynamic_model": model,
                  "skipped": "; ".join(f"line {line}: {reason}" for line, reason in skipped),
                  "skipped_rows": json.dumps(skipped), "unusual_rows": json.dumps(unusual),
                  "air_source": air_source}
    attributes.update({key: value for key, value in flown.attrs.items() if key not in attributes})
    return xr.Dataset(data, coords=coords, attrs=attributes)


def _predictions_and_monitor(session: Session, rows: np.ndarray, flown: xr.Dataset, data: dict) -> None:
    """Add to ``data`` the predictions of :data:`PREDICTED`, the monitor's own value of each (``monitor_<name>``)
    and, where the layout says which flights its monitor tracked, ``monitor_measured`` per shot."""
    v = session.values
    axis, direction = v["spin_axis"][rows], v["horizontal_launch_angle"][rows]
    for name in PREDICTED:
        values = np.array(flown[name].values, dtype=float)
        if name == "offline_distance":
            values[~(np.isfinite(axis) & np.isfinite(direction))] = np.nan
        data[name] = ("shot", values, dict(flown[name].attrs))
        if np.isfinite(v[name][rows]).any():
            reported = v[name][rows] if name != "landing_angle" else np.degrees(v[name][rows])
            data[MONITOR + name] = ("shot", reported, {"units": flown[name].attrs["units"],
                                                       "long_name": f"{name.replace('_', ' ')} the monitor reports"})
    if session.vendor.tracked and MONITOR + "carry_distance" in data:
        # per value: whether the monitor measured the flight (tracked it long enough) or flew it with its own model
        data[MONITOR + "measured"] = ("shot", session.carry_measured()[rows], {
            "long_name": "the monitor's carry is measured (its flight tracked for at least "
                         f"{100 * session.vendor.tracked['at_least']:g} % of the hang time), not its model output"})


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


def flight_rows(session: Session, include_flagged: bool = False) -> tuple[np.ndarray, np.ndarray, list]:
    """(rows to fly, rows whose launch the monitor flags, ``(line, reason)`` of each row not flown): the row rules
    of every command (:meth:`Session.verdict`) and what a flight needs (see the module docstring). Reasons carry no
    values (``impactlab shots --show-rows`` gives them), so rows are counted by reason."""
    v = session.values
    reasons: list[list[str]] = [[] for _ in range(session.size)]
    no_data = {field for (field, kind) in session.flags if kind == "no data"}
    for name in LAUNCH:
        marker = session.flags.get((name, "no data"), np.zeros(session.size, bool)) if name in no_data else None
        for row in np.flatnonzero(~np.isfinite(v[name])).tolist():
            reasons[row].append(f"no {DESCRIPTIONS[name]}" + (" (a no-value marker in the file)"
                                                                  if marker is not None and marker[row] else ""))
    with np.errstate(invalid="ignore"):
        rules = [(v["ball_speed"] == 0.0, "ball speed 0 (no shot)"),
                 (v["vertical_launch_angle"] < 0.0, "launched below the horizontal (it meets the ground at once: no "
                                                    "carry to predict)"),
                 (v["back_spin"] < 0.0, "back spin below 0 (topspin, which a spin rate and axis do not carry)")]
    for mask, reason in rules + [(mask, reason) for reason, mask, _ in session.verdict().reasons]:
        for row in np.flatnonzero(mask).tolist():
            reasons[row].append(reason)
    flagged = np.zeros(session.size, dtype=bool)
    for (field, kind), marked in session.flags.items():
        # a 'no data' flag marks a value the export lacks: it is NaN (missing, said above) unless the reader derived
        # it from measured values (a spin rate from back and side spin), which is no estimate
        if field in LAUNCH + ("spin_axis",) and kind not in ("no data", "unreadable"):
            flagged |= marked
            if not include_flagged:
                for row in np.flatnonzero(marked).tolist():
                    reasons[row].append(f"{field.replace('_', ' ')} {kind} by the monitor (--include-flagged flies "
                                        f"it)")
    fly = np.array([not why for why in reasons], dtype=bool)
    skipped = [(int(session.lines[row]), "; ".join(why)) for row, why in enumerate(reasons) if why]
    return fly, flagged, skipped
