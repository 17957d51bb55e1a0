"""Ball flight in a user's terms: the air a shot flies through, and :func:`impactlab.fly`.

:func:`fly` takes a launch as a launch monitor gives it (ball speed, vertical and horizontal launch angle, spin rate
and spin axis) in SI numbers, strings with units or pint quantities, scalars or arrays, flies it with
:func:`impactlab.physics.flight.fly` and returns an :class:`xarray.Dataset` of the carry, apex, landing angle,
offline distance and flight time in the units of :data:`impactlab.vocabulary.OUTPUTS`. A study asks for the same
outputs after any impact model (:mod:`impactlab.model.derive`); its ``conditions`` block is a :class:`Conditions`
(:mod:`impactlab.scene.air`), which here may also give each shot its own air (arrays broadcasting with the launch).

Signs (docs/conventions.md): ``spin_axis``, ``launch_direction`` and ``offline_distance`` are positive to the right
of the target line; a positive spin axis curves the ball right. The model, its coefficients and its validation
against TrackMan's tour averages are in docs/flight.md.
"""

from __future__ import annotations

import functools
import math
import warnings
from collections.abc import Mapping

import numpy as np

from impactlab.errors import FieldError, PlausibilityWarning
from impactlab.physics import aerodynamics
from impactlab.physics import flight as physics
from impactlab.scene.air import (CONDITION_KEYS, PRESSURE_RANGE, STANDARD_RELATIVE_HUMIDITY, STANDARD_TEMPERATURE,
                                 TEMPERATURE_RANGE, Conditions, air_arrays, air_description, flight_air)
from impactlab.scene.plausibility import GOLF_LIMITS
from impactlab.units import DIMENSIONS, MPH, to_si
from impactlab.vocabulary import OUTPUTS

def is_number_text(text: str) -> bool:
    """True when ``text`` is a number alone (``"167"``, ``"1e3"``): a value whose unit would have to be guessed."""
    try:
        float(text)
    except ValueError:
        return False
    return True


def quantity_array(value, dimension: str, path: str) -> np.ndarray:
    """``value`` as an SI float array: numbers (SI) as they are, strings with units and pint quantities converted.

    Parameters
    ----------
    value : float, array_like, str, sequence of str or of pint.Quantity, or pint.Quantity
        Numbers are SI (angles in rad, spin in rad/s); a string must carry its unit (``"167 mph"``): a number
        written as text is refused, its unit is not guessed.
    dimension : str
        A key of :data:`impactlab.units.DIMENSIONS`.
    path : str
        The argument's name, for messages.

    Raises
    ------
    FieldError
        A value of the wrong dimension, a string without a unit, or something that is not a quantity.
    """
    if isinstance(value, bool) or value is None:
        raise FieldError(path, f"{_words(dimension)}", value)
    if hasattr(value, "magnitude") and hasattr(value, "units") and hasattr(value, "to"):  # a pint quantity
        magnitude = np.asarray(value.magnitude, dtype=float)
        unit = f"{value.units:~}" or "dimensionless"
        if dimension == "temperature":  # offset units: convert the values, not a factor
            try:
                return np.asarray(value.to("K").magnitude, dtype=float)
            except Exception:  # noqa: BLE001 - pint's DimensionalityError
                raise FieldError(path, _words(dimension), f"{value}") from None
        factor = to_si(f"1 {unit}", dimension, path) if unit != "dimensionless" else to_si(1.0, dimension, path)
        return magnitude * factor
    if isinstance(value, str):
        if is_number_text(value):
            example = "50 %" if dimension == "dimensionless" else f"{value} {_EXAMPLE[dimension]}"
            raise FieldError(path, f"{_words(dimension)}; a number as text has no unit (write e.g. "
                                   f"'{example}', or a number in SI)", value)
        return np.asarray(_text_to_si(value, dimension, path), dtype=float)
    if isinstance(value, (list, tuple)) and value and any(isinstance(item, str) or hasattr(item, "magnitude")
                                                          for item in value):  # strings or pint quantities, each
        return np.array([float(quantity_array(item, dimension, f"{path}[{index}]"))
                         for index, item in enumerate(value)])
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise FieldError(path, _words(dimension), value) from None
    if isinstance(value, (list, tuple, np.ndarray)) and array.size:
        # True read as 1.0 (spin_axis=[True, False] is 1 rad, 57 deg): refused as a lone True is
        flags = np.asarray(value).dtype.kind == "b" or (not isinstance(value, np.ndarray) and any(
            isinstance(item, (bool, np.bool_)) for item in np.asarray(value, dtype=object).ravel()))
        if flags:
            raise FieldError(path, f"{_words(dimension)} (not True/False)", value)
    return array


@functools.lru_cache(maxsize=512)
def _text_to_si(text: str, dimension: str, path: str) -> float:
    """:func:`impactlab.units.to_si` of a text with its unit, remembered: pint parses ``"167 mph"`` in about 1 ms, the
    flight of the shot it launches takes 0.2 ms. A refusal is raised each time (lru_cache keeps no exception)."""
    return to_si(text, dimension, path)


def _fingerprint(model: str) -> str:
    """:func:`impactlab.physics.aerodynamics.model_fingerprint`, remembered per model, per its function and per the
    constants a refit changes (its 775 coefficient evaluations cost half a shot's flight): a changed constant gives
    the new fingerprint at once."""
    constants = (tuple(aerodynamics.MEASURED_FIT.items()), tuple(aerodynamics.MEASURED_FIT_OFFSETS.items()),
                 aerodynamics.INDUCED_DRAG_FACTOR, aerodynamics.LYU_LIFT_PEAK)
    return _remembered_fingerprint(model, aerodynamics.MODELS[model][0], constants)


@functools.lru_cache(maxsize=64)
def _remembered_fingerprint(model: str, function, constants: tuple) -> str:
    return aerodynamics.model_fingerprint(model)


def _first(name: str, array: np.ndarray, bad: np.ndarray) -> tuple[str, float]:
    """The first refused value of ``array`` and its path (``ball_speed[2000]``): a message names that one value,
    not every value of a long array."""
    if not array.ndim:
        return name, float(array)
    index = np.unravel_index(int(np.flatnonzero(bad)[0]), array.shape)
    return f"{name}[{', '.join(str(int(i)) for i in index)}]", float(array[index])


def _in_unit(array: np.ndarray, unit: str) -> str:
    """Values for a message, with the unit they are in (an SI value shown without its unit reads as the user's)."""
    return ", ".join(f"{value:.6g} {unit}" for value in np.ravel(array))


_EXAMPLE = {"speed": "mph", "angle": "deg", "angular_speed": "rpm", "temperature": "degC", "pressure": "hPa",
            "length": "m", "mass": "g", "dimensionless": "%"}


def _words(dimension: str) -> str:
    si_unit = DIMENSIONS[dimension][0]
    if dimension == "dimensionless":
        return "a number (or a string with a unit such as '50 %')"
    return f"{DIMENSIONS[dimension][2]}: a number in {si_unit} or a string with a unit (e.g. '{_EXAMPLE[dimension]}')"


_LAUNCH_DIMENSIONS = {"ball_speed": "speed", "launch_angle": "angle", "spin_rate": "angular_speed",
                      "spin_axis": "angle", "launch_direction": "angle"}
#: display unit, factor from SI, the SI value beyond which a launch is unusual (flown, and warned about), and why
UNUSUAL_LAUNCH = {
    # the fastest measured club speeds are about 150 mph (scene.plausibility, long drive) and a smash factor
    # above 1.5 is beyond the Rules' COR limit: about 225 mph of ball speed
    "ball_speed": ("mph", 1.0 / MPH, 100.0, "the fastest measured ball speeds are about 225 mph: 150 mph "
                   "of long-drive club speed at a smash factor of 1.5"),
    "spin_rate": ("rpm", 30.0 / math.pi, 12000.0 * math.pi / 30.0, "golf balls leave a club with at most about "
                  "12,000 rpm"),
}
#: the SI value beyond which no golf shot has a launch value (refused; a session's row is not flown), and why
IMPOSSIBLE_LAUNCH = {
    # the club speed no human swing reaches, 200 mph (scene.plausibility), at the largest smash factor the Rules'
    # COR limit allows, (1 + 0.83) / (1 + 45.93 g / 200 g) = 1.49 (a 200 g head): 298 mph
    "ball_speed": (300.0 * MPH, "a ball speed up to 300 mph (200 mph of club speed, which no swing reaches, at "
                   "the largest smash factor the Rules' COR limit allows, 1.49)"),
    # the incoming spin a golf scene refuses (scene.plausibility: balls leave a club with at most about 12,000 rpm)
    "spin_rate": (20000.0 * math.pi / 30.0, "a spin rate up to 20,000 rpm (golf balls leave a club with at most "
                  "about 12,000 rpm)"),
}


def _bare(value) -> bool:
    """Whether a launch value was given as plain numbers (SI), not text with units or a pint quantity."""
    if isinstance(value, str) or (hasattr(value, "magnitude") and hasattr(value, "units")):
        return False
    return not (isinstance(value, (list, tuple)) and any(isinstance(item, str) for item in value))


def _si_note(given, value: float, unit: str) -> str:
    """For a value given as a plain number: that numbers are SI, and how to write the value meant."""
    if not _bare(given):
        return ""
    return f" (a number is SI: {value:.6g} {unit}; with a unit, e.g. '{value:.6g} {_EXAMPLE[_unit_dimension(unit)]}')"


def _unit_dimension(unit: str) -> str:
    return {"rad": "angle", "m/s": "speed", "rad/s": "angular_speed"}[unit]


def _warn_unusual(values: dict, given: dict) -> None:
    """A launch beyond what golf shots measure is flown, and said once (a PlausibilityWarning): a ball speed of
    167 or a spin of 2686 given as plain numbers are SI (m/s, rad/s), not mph and rpm."""
    for name, (unit, factor, limit, why) in UNUSUAL_LAUNCH.items():
        unusual = values[name] > limit
        if np.any(unusual):
            where, value = _first(name, values[name], unusual)
            si_unit = DIMENSIONS[_LAUNCH_DIMENSIONS[name]][0]
            note = f" (a number is SI: {value:.6g} {si_unit})" if _bare(given[name]) else ""
            warnings.warn(f"{where}: {value * factor:.6g} {unit}{note} is unusual for golf ({why}); flown as given",
                          PlausibilityWarning, stacklevel=4)


def conditions_from(conditions) -> Conditions:
    """A :class:`Conditions` from None (the standard air), a Conditions, or a mapping of :data:`CONDITION_KEYS`.

    Each value of the mapping is read as :func:`quantity_array` reads it (SI numbers, strings with units, pint
    quantities), one value or an array of them (one per shot); a value refused is shown in SI with its unit, and
    as given where it was text (``conditions.temperature[2]: ... got 473.15 K (given as '200 degC')``).
    """
    if conditions is None:
        return Conditions()
    if isinstance(conditions, Conditions):
        return conditions
    if not isinstance(conditions, Mapping):
        raise FieldError("conditions", "a mapping with keys from: " + ", ".join(CONDITION_KEYS), conditions)
    values: dict = {}
    for key, value in conditions.items():
        if key not in CONDITION_KEYS:
            raise FieldError(f"conditions.{key}", "a key of the air conditions", str(key), choices=CONDITION_KEYS)
        if value is None:
            continue
        array = quantity_array(value, CONDITION_KEYS[key], f"conditions.{key}")
        values[key] = array if array.ndim else float(array)
    try:
        return Conditions(**values)
    except FieldError as exc:
        key, _, index = (exc.path or "").partition("[")
        if key in values and not isinstance(exc.given, str):
            # the value refused is in SI: shown with its unit and as given (a bare 473.15 for '200 degC' reads as
            # the user's number)
            dimension = CONDITION_KEYS[key]
            refused = exc.given if index and isinstance(exc.given, float) else values[key]
            shown = f"{refused:.6g}" + ("" if dimension == "dimensionless" else f" {DIMENSIONS[dimension][0]}")
            given = conditions[key]
            if index and isinstance(given, (list, tuple)) and "," not in index:
                given = given[int(index.rstrip("]"))]
            if isinstance(given, str):
                shown += f" (given as {given!r})"
            exc = FieldError(exc.path, exc.expected, shown, exc.choices, file=exc.file, line=exc.line)
        raise exc.at(prefix="conditions") from None


def fly(ball_speed, launch_angle, spin_rate, spin_axis=0.0, launch_direction=0.0, conditions=None, *,
        ball_mass=aerodynamics.BALL_MASS, ball_radius=aerodynamics.BALL_RADIUS, model=aerodynamics.DEFAULT_MODEL,
        trajectories=False):
    """Fly golf shots from their launch to where they come back to tee height; one Dataset of the results.

    Parameters
    ----------
    ball_speed : float, array_like, str or pint.Quantity
        Ball speed at launch: a number in m/s, or with a unit (``"167 mph"``).
    launch_angle : float, array_like, str or pint.Quantity
        Vertical launch angle above the horizontal: a number in rad, or with a unit (``"10.9 deg"``).
    spin_rate : float, array_like, str or pint.Quantity
        Spin rate (total spin, >= 0): a number in rad/s, or with a unit (``"2686 rpm"``).
    spin_axis : float, array_like, str or pint.Quantity
        Tilt of the spin axis, rad or with a unit; positive tilted right, the ball curves right (TrackMan's sign).
    launch_direction : float, array_like, str or pint.Quantity
        Horizontal launch angle, rad or with a unit; positive right of the target line.
    conditions : None, mapping or Conditions
        The air: ``temperature`` (K, or ``"25 degC"``), ``pressure`` (Pa or ``"1013 hPa"``; absent: the ISA
        pressure at ``altitude``), ``relative_humidity`` (fraction, or ``"50 %"``), ``altitude`` (m, or
        ``"5280 ft"``), ``headwind`` and ``crosswind`` (m/s or ``"10 mph"``; headwind against the shot,
        crosswind towards the right). None: 15 degC, 101 325 Pa, 50 %, still air. Each value is one air for
        every shot, or an array of values (a list of strings with units or of pint quantities, a pint array, SI
        numbers) giving each shot its own: the air arrays broadcast with the launch's (an array of the launch's
        shape pairs shot ``i`` with air ``i``). In an array, NaN for ``pressure`` (``altitude``) marks a shot
        without one: its pressure is the ISA pressure at its altitude (at sea level without one); a shot may have
        a pressure or an altitude, not both.
    ball_mass, ball_radius : float, str or pint.Quantity
        Default the R&A/USGA limits, 45.93 g and 21.335 mm.
    model : str
        Aerodynamic model, a key of :data:`impactlab.physics.aerodynamics.MODELS` (default
        ``"measured_fit"``, impactlab's fit to measured lift and drag).
    trajectories : bool
        Also return the sampled paths ``x``, ``y`` (right positive), ``z`` [m] over ``t`` [s], on dims
        (``shot``, ``t``); each shot's path stops at its landing point (later samples repeat it).

    Returns
    -------
    xarray.Dataset
        ``carry_distance``, ``offline_distance``, ``apex_height`` [m], ``landing_angle`` [degree] and
        ``flight_time`` [s], shaped like the broadcast inputs (dims ``shot_0``, ``shot_1``...; no dims for
        scalars), with ``units`` and ``long_name`` from :data:`impactlab.vocabulary.OUTPUTS`; the aerodynamic
        model and its references in ``attrs``. The air: one air for every shot is said by the attributes
        ``air_temperature_K``, ``air_pressure_Pa``, ``air_relative_humidity`` and ``air_density_kg_m3``; an air
        that varies from shot to shot (any of temperature, pressure or humidity) by the coordinates
        ``air_temperature`` [K], ``air_pressure`` [Pa] (the station pressure flown, from the altitude where that
        was given), ``relative_humidity`` [1] and ``air_density`` [kg/m^3] on the shot dims, and then no
        ``air_*`` attribute. The wind likewise: attributes ``headwind_m_s`` and ``crosswind_m_s``, or coordinates
        ``headwind`` and ``crosswind`` [m/s]. NaN for a shot still in the air after 15 s (the
        integration's limit; e.g. 300 mph at 89 deg). A shot launched below the horizontal is at the ground going
        down: carry, apex and flight time 0, its landing angle the launch's.

    Raises
    ------
    FieldError
        Air values (or an element of them) out of the ranges of :class:`Conditions`, named by their index
        (``conditions.temperature[3]``) and shown in SI with their unit; air arrays that do not broadcast with each
        other or with the launch (the message lists the shapes). A value of the wrong dimension or out of range
        (speed <= 0 or above 300 mph, spin < 0 or above 20,000 rpm,
        a launch angle or launch direction at or beyond +-90 deg, a spin axis beyond +-90 deg: no golf shot has
        them; :data:`IMPOSSIBLE_LAUNCH`), a string without a unit. A value refused that was given as a plain number
        is said to be SI (``spin_axis=3`` is 3 rad = 172 deg).

    Warns
    -----
    PlausibilityWarning
        A ball speed above 100 m/s (about 225 mph) or a spin above 12,000 rpm: beyond measured golf shots, flown
        as given (often a plain number meant in mph or rpm, read as SI).

    Notes
    -----
    Point-mass flight with drag, Magnus lift and spin decay (:func:`impactlab.physics.flight.fly`); the default
    coefficients (``measured_fit``) are impactlab's fit to 277 measured lift and drag rows (wind tunnel, indoor
    range, free flight; impactlab/data/validation/aero_coefficients.yaml), not tuned to any launch-monitor table.
    Against TrackMan's three tour tables, never fitted, they carry within 2.4-2.9 % RMS, every club within 5.4 %
    (docs/flight.md); ``model="smits_smith_1994"`` gives the published wind-tunnel model (4.9-8.4 %).

    References
    ----------
    B. Lyu, J. Kensrud, L. Smith, "The reverse Magnus effect in golf balls", Sports Engineering 23 (2020) 3;
    A. J. Smits and D. R. Smith, "A new aerodynamic model of a golf ball in flight", Science and Golf II (1994)
    340-347; the other sources of the fit in docs/flight.md.

    Examples
    --------
    >>> import impactlab
    >>> shot = impactlab.fly(ball_speed="167 mph", launch_angle="10.9 deg", spin_rate="2686 rpm")
    >>> round(float(shot.carry_distance) / 0.9144)  # yards
    275
    >>> airs = impactlab.fly("167 mph", "10.9 deg", "2686 rpm", conditions={"temperature": ["5 degC", "35 degC"]})
    >>> [round(float(carry) / 0.9144) for carry in airs.carry_distance]  # warm air is thinner: longer
    [272, 279]
    """
    given = {"ball_speed": ball_speed, "launch_angle": launch_angle, "spin_rate": spin_rate, "spin_axis": spin_axis,
             "launch_direction": launch_direction}
    values = _launch_values(given)
    mass, radius = _ball_values(ball_mass, ball_radius)
    if model not in aerodynamics.MODELS:
        retired = aerodynamics.retired_reason(model)
        raise FieldError("model", "an aerodynamic model" + (f" ({retired})" if retired else ""), str(model),
                         choices=aerodynamics.MODELS)
    air = _air_for(values, conditions)
    arguments = flight_air(air)
    result = physics.fly(values["ball_speed"], values["launch_angle"], values["spin_rate"], values["spin_axis"],
                         values["launch_direction"], ball_mass=mass, ball_radius=radius, model=model,
                         return_trajectories=trajectories, **arguments)
    return _dataset(result, model, air, arguments, mass, radius, trajectories)


def _launch_values(given):
    """The launch of :func:`fly` as SI arrays, each value checked: finite, broadcasting together, inside what golf
    shots have (refused beyond :data:`IMPOSSIBLE_LAUNCH`, warned about beyond :data:`UNUSUAL_LAUNCH`)."""
    values = {name: quantity_array(value, _LAUNCH_DIMENSIONS[name], name) for name, value in given.items()}
    for name, array in values.items():
        if not np.all(np.isfinite(array)):
            where, value = _first(name, array, ~np.isfinite(array))
            raise FieldError(where, "finite values", float(value))
    try:
        np.broadcast_shapes(*(array.shape for array in values.values()))
    except ValueError:
        raise FieldError("launch", "values of one shape, or single values, that broadcast together (one per shot)",
                         ", ".join(f"{name} {array.shape}" for name, array in values.items())) from None
    if np.any(values["ball_speed"] <= 0.0):
        where, value = _first("ball_speed", values["ball_speed"], values["ball_speed"] <= 0.0)
        raise FieldError(where, "a positive ball speed", _in_unit(value, "m/s"))
    if np.any(values["spin_rate"] < 0.0):
        where, value = _first("spin_rate", values["spin_rate"], values["spin_rate"] < 0.0)
        raise FieldError(where, "a spin rate >= 0 (the direction of the spin is the spin axis)",
                         _in_unit(value * 30.0 / math.pi, "rpm"))
    _refuse_angles(values, given)
    for name, (limit, words) in IMPOSSIBLE_LAUNCH.items():
        refused = values[name] > limit
        if np.any(refused):
            where, value = _first(name, values[name], refused)
            unit, factor = UNUSUAL_LAUNCH[name][:2]
            si_unit = DIMENSIONS[_LAUNCH_DIMENSIONS[name]][0]
            note = f" (a number is SI: {value:.6g} {si_unit})" if _bare(given[name]) else ""
            raise FieldError(where, words, f"{value * factor:.6g} {unit}{note}")
    _warn_unusual(values, given)
    return values


def _refuse_angles(values, given):
    """FieldError for a launch angle, spin axis or launch direction no golf shot has (in degrees, said SI where it
    was a plain number)."""
    for name, words, refused in (
            ("launch_angle", "a launch angle between -90 and 90 deg", np.abs(values["launch_angle"]) >= math.pi / 2),
            # beyond +-90 deg the axis tilts past the vertical: the ball turns over (topspin), which the spin rate
            # and the lift of a backspinning ball do not describe
            ("spin_axis", "a spin axis between -90 and 90 deg (beyond, the ball has topspin)",
             np.abs(values["spin_axis"]) > math.pi / 2),
            # at +-90 deg the ball leaves square to the target line, beyond it backwards: no golf shot
            ("launch_direction", "a launch direction between -90 and 90 deg of the target line",
             np.abs(values["launch_direction"]) >= math.pi / 2)):
        if np.any(refused):
            where, value = _first(name, values[name], refused)
            raise FieldError(where, words, _in_unit(np.degrees(value), "deg") + _si_note(given[name], value, "rad"))


def _ball_values(ball_mass, ball_radius):
    """The ball's mass and radius in SI, positive and inside the golf scene's ball limits (scene.plausibility)."""
    mass = quantity_array(ball_mass, "mass", "ball_mass")
    radius = quantity_array(ball_radius, "length", "ball_radius")
    if np.any(mass <= 0.0) or np.any(radius <= 0.0):
        raise FieldError("ball_mass" if np.any(mass <= 0.0) else "ball_radius", "a positive value",
                         (mass if np.any(mass <= 0.0) else radius).tolist())
    # the golf scene's ball limits (scene.plausibility): ball_radius=21.335 (mm meant, m read) flew a 43 m ball
    for name, array, given_value, unit, factor, si_unit in (("ball_radius", radius, ball_radius, "mm", 1e3, "m"),
                                                            ("ball_mass", mass, ball_mass, "g", 1e3, "kg")):
        limit = GOLF_LIMITS[name.replace("_", ".")]
        low, high = (bound / factor for bound in limit.impossible)
        refused = (array < low) | (array > high)
        if np.any(refused):
            where, value = _first(name, array, refused)
            note = f" (a number is SI: {value:.6g} {si_unit})" if _bare(given_value) else ""
            raise FieldError(where, f"{limit.words} between {limit.impossible[0]:g} and {limit.impossible[1]:g} "
                             f"{unit} ({limit.why})", f"{value * factor:.6g} {unit}{note}")
    return mass, radius


def _air_for(values, conditions):
    """The air of :func:`fly` as a :class:`Conditions`, its arrays broadcasting with the launch's (else one
    FieldError listing the shapes)."""
    air = conditions_from(conditions)
    launch_shape = np.broadcast_shapes(*(array.shape for array in values.values()))
    try:
        np.broadcast_shapes(launch_shape, air.shape)
    except ValueError:
        shapes = [f"{name} {array.shape}" for name, array in values.items() if array.ndim] + [
            f"conditions.{key} {np.shape(value)}" for key, value in zip(CONDITION_KEYS, (
                air.temperature, air.pressure, air.relative_humidity, air.altitude, air.headwind, air.crosswind))
            if np.ndim(value)]
        raise FieldError("conditions", "air values that broadcast with the launch: one value for every shot, or one "
                         "per shot (an array of the launch's shape)", ", ".join(shapes)) from None
    return air


def _dataset(result, model, air, arguments, mass, radius, trajectories):
    """:func:`fly`'s Dataset from the physics' dict: the outputs in the units of :data:`OUTPUTS`, the air and the
    ball said, the model named with its references and fingerprint."""
    import xarray as xr

    shape = np.shape(result["carry_distance"])
    dims = tuple(f"shot_{index}" for index in range(len(shape)))
    data = {}
    for name in ("carry_distance", "offline_distance", "apex_height", "landing_angle", "flight_time"):
        spec = OUTPUTS[name]
        # Variables built here, not (dims, values, attrs) tuples: xarray's conversion of those costs about 1 ms
        data[name] = xr.Variable(dims, np.asarray(result[name]) * spec.factor,
                                 {"units": spec.units, "long_name": spec.long_name})
    coords = {}
    if trajectories:
        coords["t"] = ("t", result["t"], {"units": "s", "long_name": "time since launch"})
        for axis, words in (("x", "along the target line"), ("y", "right of the target line"), ("z", "height")):
            data[f"trajectory_{axis}"] = xr.Variable(("shot", "t"), result[axis],
                                                     {"units": "m", "long_name": f"ball position, {words}"})
    air_attributes, air_coords = air_description(air, arguments, shape, dims)
    coords.update(air_coords)
    attributes = {
        "aerodynamic_model": model,
        "aerodynamic_references": aerodynamics.MODEL_REFERENCES[model],
        **air_attributes,
        "ball_mass_kg": float(mass) if mass.ndim == 0 else str(mass.tolist()),
        "ball_radius_m": float(radius) if radius.ndim == 0 else str(radius.tolist()),
        # the coefficients' fingerprint: a refit keeps the model's name (aerodynamics.model_fingerprint)
        "aerodynamic_fingerprint": _fingerprint(model),
    }
    return xr.Dataset(data, coords=coords, attrs=attributes)


__all__ = ["Conditions", "fly", "is_number_text",
           "air_arrays", "quantity_array", "conditions_from", "CONDITION_KEYS", "UNUSUAL_LAUNCH",
           "IMPOSSIBLE_LAUNCH",
           # the air's constants, defined in impactlab.scene.air, kept importable from here
           "PRESSURE_RANGE", "STANDARD_RELATIVE_HUMIDITY", "STANDARD_TEMPERATURE", "TEMPERATURE_RANGE"]
