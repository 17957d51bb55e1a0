"""The air a golf shot flies through: :class:`Conditions`, one value for every shot or one per shot (SI values).

A :class:`Conditions` holds the temperature, station pressure or altitude, relative humidity and wind of a flight,
each a number (the same for every shot) or an array (one value per shot, broadcasting with the launch arrays of
:func:`impactlab.fly`). It is validated on construction, element by element: a refusal names the element and its
value (``temperature[3]``). :func:`flight_air` turns it into the keyword arguments of
:func:`impactlab.physics.flight.fly`, and :func:`air_description` into the attributes (one air for every shot) or
per-shot coordinates (an air that varies) of a flight's Dataset. A study's ``conditions:`` block is a Conditions
of numbers (:mod:`impactlab.study.scene_blocks`).

References
----------
ISO 2533:1975 Standard Atmosphere (the ISA pressure at an altitude, :func:`impactlab.physics.atmosphere.
pressure_at_altitude`); WMO Weather and Climate Extremes Archive (the ranges of temperature and pressure taken).
"""

from __future__ import annotations

from collections.abc import Mapping

import attrs
import numpy as np

from impactlab.errors import FieldError
from impactlab.physics import atmosphere
from impactlab.validators import in_range_each, number_or_array

#: the air when a study or a call gives none: 15 degC, ISA sea-level pressure, 50 % relative humidity, still
STANDARD_TEMPERATURE = 288.15
STANDARD_RELATIVE_HUMIDITY = 0.5
#: the air temperatures [K] a flight takes: -90 to 60 degC, around the extremes measured on Earth (WMO's Weather and
#: Climate Extremes Archive: -89.2 degC at Vostok, 21 July 1983; 56.7 degC at Death Valley, 10 July 1913, measured). A
#: value beyond is a unit mistake (77 degF written as degC) more likely than an air any golf shot flies through
TEMPERATURE_RANGE = (183.15, 333.15)
#: the station pressures [Pa] a flight takes: from the ISA pressure at 11 000 m, the top of the altitudes taken
#: (22 632 Pa, ISO 2533), to 110 kPa, above the highest sea-level pressure recorded (1083.8 hPa, Agata, Siberia,
#: 31 December 1968, WMO archive, measured) and the ISA pressure 500 m below sea level (107.5 kPa). Below, a pressure
#: in Pa given for hPa (1013 Pa) would fly an almost airless ball without a word
PRESSURE_RANGE = (2.0e4, 1.1e5)
#: keys of a conditions mapping (fly's ``conditions=``, a study's ``conditions:`` block), with their dimensions
CONDITION_KEYS = {"temperature": "temperature", "pressure": "pressure", "relative_humidity": "dimensionless",
                  "altitude": "length", "headwind": "speed", "crosswind": "speed"}


def _same(a, b) -> bool:
    """Equality of two field values, numbers or arrays (an array compares equal to an equal array)."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return bool(np.array_equal(a, b))
    return bool(a == b)


def _field(default, validator):
    return attrs.field(default=default, converter=number_or_array, validator=validator,
                       eq=attrs.cmp_using(eq=_same))


@attrs.frozen(unsafe_hash=False)
class Conditions:
    """The air a golf shot flies through (a study's ``conditions`` block), SI values, one air or one per shot.

    Each field is a number (the same for every shot) or an array of numbers (one per shot: the arrays broadcast
    with each other and, in :func:`impactlab.fly`, with the launch). Arrays are stored as read-only float arrays.
    Every element is checked; a refusal names the first element out of range and its value (``temperature[3]``).

    Parameters
    ----------
    temperature : float or array_like
        Air temperature [K], 183.15-333.15 K (-90 to 60 degC); default 288.15 K (15 degC). Not lapsed with
        altitude.
    pressure : float, array_like or None
        Station pressure [Pa], 20-110 kPa; None: the ISA pressure at ``altitude`` (sea level without one). In an
        array, NaN marks a shot without a pressure (the ISA pressure at its altitude). Give either a pressure or an
        altitude for a shot, not both.
    relative_humidity : float or array_like
        Fraction 0-1; default 0.5.
    altitude : float, array_like or None
        Height of the tee above sea level [m], -500 to 11 000 m, used for the ISA pressure of a shot without a
        pressure. In an array, NaN marks a shot without an altitude.
    headwind : float or array_like
        Wind against the shot along the target line [m/s], -50 to 50 (negative: a tailwind); uniform with height.
    crosswind : float or array_like
        Wind across the target line [m/s], -50 to 50, positive blowing towards the right (a left-to-right wind).

    Raises
    ------
    FieldError
        A value (or an element) out of range, a pressure and an altitude for the same shot, or arrays that do not
        broadcast together.
    """

    temperature: float | np.ndarray = _field(STANDARD_TEMPERATURE, in_range_each(
        *TEMPERATURE_RANGE, "an air temperature between -90 and 60 degC (183.15 and 333.15 K, around the coldest "
        "and hottest air measured on Earth: -89.2 and 56.7 degC; a degF value written as degC lands above)"))
    pressure: float | np.ndarray | None = _field(None, in_range_each(
        *PRESSURE_RANGE, "a station pressure between 200 and 1100 hPa (the ISA pressure at 11 000 m is 226 hPa, the "
        "highest sea-level pressure recorded 1084 hPa; hPa written as Pa lands below)", optional=True))
    relative_humidity: float | np.ndarray = _field(STANDARD_RELATIVE_HUMIDITY, in_range_each(
        0.0, 1.0, "a relative humidity between 0 and 1 (a fraction, or e.g. '50 %')"))
    altitude: float | np.ndarray | None = _field(None, in_range_each(
        -500.0, 11000.0, "an altitude between -500 and 11 000 m (the ISA troposphere)", optional=True))
    headwind: float | np.ndarray = _field(0.0, in_range_each(-50.0, 50.0, "a wind speed between -50 and 50 m/s"))
    crosswind: float | np.ndarray = _field(0.0, in_range_each(-50.0, 50.0, "a wind speed between -50 and 50 m/s"))

    def __attrs_post_init__(self):
        shapes = {name: np.shape(value) for name, value in attrs.asdict(self, recurse=False).items()
                  if isinstance(value, np.ndarray)}
        try:
            shape = np.broadcast_shapes(*shapes.values())
        except ValueError:
            raise FieldError(list(shapes)[-1], "values of one shape, or single values, that broadcast together "
                             "(one per shot)", ", ".join(f"{name} {shape}" for name, shape in shapes.items())) from None
        if self.pressure is None or self.altitude is None:
            return
        pressure, altitude = (np.broadcast_to(value, shape) for value in (self.pressure, self.altitude))
        both = np.isfinite(pressure) & np.isfinite(altitude)  # NaN in an array: not given for that shot
        if np.any(both):
            index = np.unravel_index(int(np.flatnonzero(both)[0]), shape)
            where = f"[{', '.join(str(int(i)) for i in index)}]" if shape else ""
            raise FieldError(f"altitude{where}", "either a pressure or an altitude (which sets the ISA pressure), "
                             "not both", f"pressure {float(pressure[index]):g} Pa and altitude "
                             f"{float(altitude[index]):g} m")

    def __hash__(self):
        return hash(tuple(value.tobytes() if isinstance(value, np.ndarray) else value
                          for value in attrs.astuple(self, recurse=False)))

    @property
    def shape(self) -> tuple[int, ...]:
        """The broadcast shape of the fields: () for one air for every shot."""
        return np.broadcast_shapes(*(np.shape(value) for value in attrs.astuple(self, recurse=False)
                                     if isinstance(value, np.ndarray)))


def air_arrays(inputs: Mapping) -> dict:
    """The keyword arguments of :func:`impactlab.physics.flight.fly` for the air in ``inputs`` (SI arrays).

    ``inputs`` maps the input names of :data:`impactlab.vocabulary.INPUTS` (``air_temperature`` [K],
    ``air_pressure`` [Pa], ``relative_humidity`` [1], ``altitude`` [m], ``headwind`` and ``crosswind`` [m/s]) to
    values; absent ones take the standard air.
    """
    temperature = inputs.get("air_temperature", STANDARD_TEMPERATURE)
    pressure = inputs.get("air_pressure")
    if pressure is None:
        pressure = atmosphere.pressure_at_altitude(inputs.get("altitude", 0.0))
    headwind = np.asarray(inputs.get("headwind", 0.0), dtype=float)
    crosswind = np.asarray(inputs.get("crosswind", 0.0), dtype=float)
    headwind, crosswind = np.broadcast_arrays(headwind, crosswind)
    wind = np.stack([-headwind, crosswind, np.zeros_like(headwind)], axis=-1)
    return {"temperature": temperature, "pressure": pressure,
            "relative_humidity": inputs.get("relative_humidity", STANDARD_RELATIVE_HUMIDITY), "wind": wind}


def station_pressure(air: Conditions):
    """The station pressure [Pa] of each shot of ``air``: its pressure, else the ISA pressure at its altitude, else
    at sea level (101 325 Pa). A float or 0-d array for one air, an array where the pressure or altitude is one."""
    if isinstance(air.pressure, float):
        return air.pressure
    altitude = 0.0 if air.altitude is None else air.altitude
    if isinstance(altitude, np.ndarray):
        altitude = np.where(np.isnan(altitude), 0.0, altitude)
    isa = atmosphere.pressure_at_altitude(altitude)
    if air.pressure is None:
        return isa
    return np.where(np.isnan(air.pressure), isa, air.pressure)


def flight_air(air: Conditions) -> dict:
    """The keyword arguments of :func:`impactlab.physics.flight.fly` for ``air``: ``temperature`` [K],
    ``pressure`` [Pa], ``relative_humidity`` [1] and ``wind`` [m/s, public frame], shape (3,) for one wind or
    (..., 3) for one per shot."""
    inputs = {"air_temperature": air.temperature, "air_pressure": station_pressure(air),
              "relative_humidity": air.relative_humidity, "headwind": air.headwind, "crosswind": air.crosswind}
    arguments = air_arrays(inputs)
    if arguments["wind"].ndim == 1:
        arguments["wind"] = arguments["wind"].reshape(3)
    return arguments


def _one(value) -> float | None:
    """The value every element of ``value`` has, or None where they differ."""
    array = np.asarray(value, dtype=float)
    first = float(array.flat[0])
    return first if np.all(array == first) else None


def air_description(air: Conditions, arguments: Mapping, shape: tuple[int, ...], dims: tuple[str, ...]):
    """The air of a flight for its Dataset: (attributes, coordinates).

    The air (temperature, pressure, humidity and the density they give) the same for every shot is said by the
    attributes ``air_temperature_K``, ``air_pressure_Pa``, ``air_relative_humidity`` and ``air_density_kg_m3``;
    an air that varies from shot to shot by the coordinates ``air_temperature`` [K], ``air_pressure`` [Pa],
    ``relative_humidity`` [1] and ``air_density`` [kg/m^3] on ``dims`` (shaped ``shape``), and no ``air_*``
    attribute. The wind likewise: attributes ``headwind_m_s`` and ``crosswind_m_s``, or coordinates ``headwind``
    and ``crosswind`` [m/s].
    """
    temperature, pressure = arguments["temperature"], arguments["pressure"]
    humidity = arguments["relative_humidity"]
    attributes: dict = {}
    coords: dict = {}
    one = [_one(value) for value in (temperature, pressure, humidity)]
    if all(value is not None for value in one):
        attributes.update({
            "air_temperature_K": air.temperature if isinstance(air.temperature, float) else one[0],
            "air_pressure_Pa": one[1],
            "air_relative_humidity": (air.relative_humidity if isinstance(air.relative_humidity, float)
                                      else one[2]),
            "air_density_kg_m3": float(atmosphere.air_density(one[0], one[1], one[2]))})
    else:
        density = atmosphere.air_density(temperature, pressure, humidity)
        for name, value, unit, words in (
                ("air_temperature", temperature, "K", "air temperature"),
                ("air_pressure", pressure, "Pa", "station air pressure"),
                ("relative_humidity", humidity, "1", "relative humidity of the air, a fraction 0-1"),
                ("air_density", density, "kg/m^3", "density of the air flown in")):
            coords[name] = (dims, np.broadcast_to(np.asarray(value, dtype=float), shape).copy(),
                            {"units": unit, "long_name": words})
    wind = [_one(value) for value in (air.headwind, air.crosswind)]
    if all(value is not None for value in wind):
        attributes.update({"headwind_m_s": air.headwind if isinstance(air.headwind, float) else wind[0],
                           "crosswind_m_s": air.crosswind if isinstance(air.crosswind, float) else wind[1]})
    else:
        for name, value, words in (("headwind", air.headwind, "wind against the shot (negative: a tailwind)"),
                                   ("crosswind", air.crosswind, "wind across the target line, towards the right")):
            coords[name] = (dims, np.broadcast_to(np.asarray(value, dtype=float), shape).copy(),
                            {"units": "m/s", "long_name": words})
    return attributes, coords


__all__ = ["Conditions", "CONDITION_KEYS", "PRESSURE_RANGE", "STANDARD_RELATIVE_HUMIDITY", "STANDARD_TEMPERATURE",
           "TEMPERATURE_RANGE", "air_arrays", "air_description", "flight_air", "station_pressure"]
