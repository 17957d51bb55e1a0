"""Quantities written by users, turned into SI floats.

No unit is ever guessed. A dimensional quantity in a study (a YAML file or a mapping given in Python) is a
string with a unit that pint understands (``"80 mph"``, ``"21.335 mm"``, ``"136 MPa"``, ``"20 deg"``) or a
pint quantity; a bare number there is refused with the field, the quantity and an example
(``club.mass: expected a mass with its unit, e.g. 200 g or 0.2 kg ..., got 200``), as shot tables refuse one:
``115`` could be mph or m/s, ``200`` g or kg, ``20`` degrees or radians. A bare ``0`` is read: zero is the same
in every unit of a length, a speed, an angle or a spin (0 mph = 0 m/s), so no unit is guessed, except where units
have offsets (:data:`ZERO_DEPENDS_ON_UNIT`: 0 degC is 273.15 K). Dimensionless quantities (friction,
restitution, inertia factor, Poisson ratio) stay bare numbers.

Python value objects (``Ball(mass=...)``, ``Delivery(club_speed=...)``) take a bare number as SI (angles in
radians, spin in rad/s), or a string with a unit, or a pint quantity: :func:`converter` makes their attrs
converters. Inside impactlab everything is SI with angles in radians and spin in rad/s.
"""

from __future__ import annotations

import enum
import re
import functools
import math
from numbers import Real
from typing import TYPE_CHECKING, Any

from impactlab.errors import FieldError

if TYPE_CHECKING:  # pint itself is imported on first use (it is slow to load)
    import pint

#: Physical dimension name -> (SI unit as pint understands it, the unit results and messages speak, words for
#: messages).
DIMENSIONS: dict[str, tuple[str, str, str]] = {
    "length": ("m", "m", "a length"),
    "mass": ("kg", "kg", "a mass"),
    "pressure": ("Pa", "Pa", "a modulus (pressure)"),
    "speed": ("m/s", "m/s", "a speed"),
    "angle": ("rad", "deg", "an angle"),
    "angular_speed": ("rad/s", "rpm", "a spin rate"),
    "time": ("s", "s", "a time"),
    "inertia": ("kg*m**2", "kg*m**2", "a moment of inertia"),
    "inverse_speed": ("s/m", "s/m", "a slope per speed"),
    # the air of the ball flight's conditions: "15 degC" and "59 degF" are read as temperatures (registry below)
    "temperature": ("K", "K", "a temperature"),
    # the air's density a launch monitor states beside its temperature, pressure and humidity (Garmin: g/L)
    "density": ("kg/m**3", "kg/m^3", "a density"),
    "dimensionless": ("dimensionless", "dimensionless", "a number"),
    # sqrt(k rho c) of a face's or a cover's material (the friction law's flash temperature)
    "effusivity": ("J/(m**2*K*s**0.5)", "J m-2 K-1 s-1/2", "a thermal effusivity sqrt(k rho c)"),
}

#: Per dimension, the unit people write it in and that unit's size in SI: the example a refused bare number is
#: shown with (``200`` as a mass: "200 g or 0.2 kg").
EXAMPLE_UNITS: dict[str, tuple[str, float]] = {
    "length": ("mm", 1e-3), "mass": ("g", 1e-3), "pressure": ("MPa", 1e6), "speed": ("mph", 0.44704),
    "angle": ("deg", math.pi / 180.0), "angular_speed": ("rpm", math.pi / 30.0), "time": ("ms", 1e-3),
    "inertia": ("g*cm**2", 1e-7), "inverse_speed": ("s/m", 1.0), "effusivity": ("J/(m**2*K*s**0.5)", 1.0),
    "density": ("kg/m**3", 1.0),
    "temperature": ("degC", 1.0),  # an offset unit: _example adds its zero, 273.15 K, instead of multiplying
}


#: Dimensions whose zero depends on the unit (pint's offset units: 0 degC = 273.15 K, 0 degF = 255.37 K): a bare 0
#: is refused for these as any bare number is; for every other dimension zero is zero in every unit and is read.
ZERO_DEPENDS_ON_UNIT = frozenset({"temperature"})
#: Why a bare number of a dimension is ambiguous beyond its scale, said after the example of its unit
UNIT_NOTES = {
    "angular_speed": "spin is quoted in rpm, a club head's turning (closure rate) in deg/s",
    "temperature": "not even 0: 0 degC is 273.15 K and 0 degF 255.37 K",
}


@functools.lru_cache(maxsize=64)
def unit_factor(unit: str, si_unit: str) -> float:
    """SI per ``unit``: how many ``si_unit`` one ``unit`` is (``unit_factor("mph", "m/s")`` = 0.44704)."""
    return 1.0 if unit == si_unit else float(registry().Quantity(1.0, unit).to(si_unit).magnitude)


@functools.lru_cache(maxsize=64)
def unit_affine(unit: str, si_unit: str) -> tuple[float, float]:
    """(scale, offset) with SI value = scale x + offset for x in ``unit``: ``unit_affine("degF", "K")`` =
    (5/9, 255.372...); for every unit without an offset the scale is :func:`unit_factor` and the offset 0.

    A column of a launch-monitor export in ``[deg F]`` needs the offset, which a factor cannot carry (0 degF is
    255.37 K, not 0 K): pint converts the two points 0 and 1 of the unit, so its own definition of the offset
    is used (pint's ``autoconvert_offset_to_baseunit``, :func:`registry`).
    """
    if unit == si_unit:
        return 1.0, 0.0
    zero = float(registry().Quantity(0.0, unit).to(si_unit).magnitude)
    one = float(registry().Quantity(1.0, unit).to(si_unit).magnitude)
    return one - zero, zero


#: fields whose usual unit is not their dimension's (by the last part of the field path): an air pressure is quoted in
#: hPa, a modulus in MPa ('1013 MPa' was the example for a bare air pressure of 1013); an altitude in m, not mm
FIELD_EXAMPLES: dict[str, tuple[str, float, str]] = {
    "pressure": ("hPa", 100.0, "an air pressure"),
    "air_pressure": ("hPa", 100.0, "an air pressure"),
    "altitude": ("m", 1.0, "an altitude"),
}


def _field_key(path: str | None) -> str:
    """The last part of a field path without its index: ``conditions.pressure[2]`` -> ``pressure``."""
    return (path or "").rsplit(".", 1)[-1].split("[", 1)[0].lstrip("-").replace("-", "_")


def _example(value: float, dimension: str, path: str | None = None) -> str:
    """``200`` as a mass -> "200 g or 0.2 kg": the number in the usual unit of the field (``path``) or of its
    dimension, and what that is in SI."""
    unit, size = EXAMPLE_UNITS[dimension]
    if _field_key(path) in FIELD_EXAMPLES and dimension == _FIELD_DIMENSIONS[_field_key(path)]:
        unit, size, _ = FIELD_EXAMPLES[_field_key(path)]
    si_unit = DIMENSIONS[dimension][0]
    if dimension == "temperature":  # 0 degC is 273.15 K by definition (SI Brochure, 9th ed., 2.3.1)
        return f"{value:g} {unit} or {value + 273.15:.6g} {si_unit}"
    if unit == si_unit:
        return f"{value:g} {unit}"
    if size < 1.0 and 0.0 < abs(value) < 1.0 and dimension != "angle":  # 0.021335 as a radius: metres, likely
        return f"{value:g} {si_unit} or {value / size:.6g} {unit}"
    return f"{value:g} {unit} or {value * size:.6g} {si_unit}"


_FIELD_DIMENSIONS = {"pressure": "pressure", "air_pressure": "pressure", "altitude": "length"}


class UnitMissing(str):
    """:func:`unit_missing`'s text, which knows how to word itself again once the field's path is known: a value is
    converted before the study loader attaches the path (``conditions.pressure``) that chooses the example's unit
    (:class:`impactlab.errors.FieldError` calls :meth:`for_path`)."""

    value: float
    dimension: str

    def for_path(self, path: str | None) -> str:
        """The same expectation worded for the field ``path`` (its usual unit in the example)."""
        return unit_missing(self.value, self.dimension, path)


def unit_missing(value: float, dimension: str, path: str | None = None) -> str:
    """The expectation a bare number for a dimensional quantity is refused with (its unit is not guessed); the
    example is in the usual unit of the field ``path`` names (:data:`FIELD_EXAMPLES`), else of its dimension."""
    words = DIMENSIONS[dimension][2]
    key = _field_key(path)
    if key in FIELD_EXAMPLES and dimension == _FIELD_DIMENSIONS[key]:
        words = FIELD_EXAMPLES[key][2]
    note = f"; {UNIT_NOTES[dimension]}" if dimension in UNIT_NOTES else ""
    value = float(value) if math.isfinite(float(value)) else 1.0  # 'e.g. nan mph' shows nothing worth writing
    text = UnitMissing(f"{words} with its unit, e.g. {_example(value, dimension, path)} (a bare number's unit is "
                       f"never guessed{note})")
    text.value, text.dimension = value, dimension
    return text


@functools.cache
def registry() -> pint.UnitRegistry:
    """The shared pint unit registry (created on first use: pint is slow to load)."""
    import pint

    # "15 degC" is a temperature, not 15 times an offset unit (which pint refuses as ambiguous)
    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def to_si(value: object, dimension: str, path: str = "", bare: str | None = None) -> float:
    """Convert a user quantity to an SI float; a bare number of a dimensional quantity is refused (0 excepted).

    Parameters
    ----------
    value : float, str or pint.Quantity
        A string with a unit such as ``"80 mph"``, or a pint quantity; for a dimensionless quantity (friction,
        restitution...) a plain number.
    dimension : str
        A key of :data:`DIMENSIONS`.
    path : str
        Field path for error messages.
    bare : {None, "si"}
        What a bare number of a dimensional quantity is: None (a study, a shot table): refused, its unit is not
        guessed, except an exact 0 (number or text) where zero is the same in every unit (every dimension but
        those of :data:`ZERO_DEPENDS_ON_UNIT`); ``"si"`` (a Python value object's argument): SI, angles in
        radians, spin in rad/s.

    Returns
    -------
    float
        The value in SI (angles in rad, spin in rad/s).

    Raises
    ------
    FieldError
        When the value is not a quantity of that dimension, or a bare number whose unit would be guessed.
    """
    si_unit, _, words = DIMENSIONS[dimension]
    expected = f"{words} (a string with a unit, e.g. {_example(1.0, dimension)})" \
        if dimension != "dimensionless" else "a number"
    if isinstance(value, bool) or value is None:
        raise FieldError(path, expected, value)
    if isinstance(value, Real):
        if dimension == "dimensionless" or bare == "si":
            return float(value)
        return _bare_zero(value, dimension, path)
    if _is_pint(value):
        return _quantity_to_si(value, dimension, path, expected)
    if not isinstance(value, str):
        raise FieldError(path, expected, value)
    converted = _string_to_si(value.strip(), dimension)
    if converted is _Bare.BARE:  # a bare number written as text: its unit would be guessed as well (in Python too)
        return _bare_zero(value, dimension, path)
    if isinstance(converted, str):  # why the text is not a quantity of this dimension
        raise FieldError(path, f"{expected}{converted}", value)
    return converted


def _bare_zero(value, dimension: str, path: str) -> float:
    """0.0 for a bare exact zero of a dimension whose zero is the same in every unit; FieldError for any other bare
    number of a dimensional quantity (its unit would be guessed)."""
    number = float(value)
    if number == 0.0 and dimension not in ZERO_DEPENDS_ON_UNIT:
        return 0.0
    raise FieldError(path, unit_missing(number, dimension, path), value)


def _is_pint(value) -> bool:
    return hasattr(value, "magnitude") and hasattr(value, "units") and hasattr(value, "to")


def _quantity_to_si(value, dimension: str, path: str, expected: str) -> float:
    """A pint quantity (of any registry) in SI, judged like its text (angles must carry an angle unit)."""
    try:
        text = f"{float(value.magnitude)!r} {value.units}"
    except (TypeError, ValueError):
        raise FieldError(path, f"{expected}; one value, not an array", str(value)) from None
    converted = _string_to_si(text, dimension)
    if converted is _Bare.BARE:
        return float(value.magnitude) if dimension == "dimensionless" else to_si(float(value.magnitude), dimension,
                                                                                  path)
    if isinstance(converted, str):
        raise FieldError(path, f"{expected}{converted}", str(value))
    return converted


def _convert(value: Any, dimension: str) -> Any:
    """The value objects' converters (``si_length``...): a bare number is SI, text with a unit or a pint quantity is
    converted, anything else (None, a bool, a list) is passed on for the validators to refuse."""
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, int):
        return float(value)
    if isinstance(value, str) or _is_pint(value):
        return to_si(value, dimension, bare="si")
    return value


# The converters of the value objects' fields, one named function per dimension: attrs' mypy plugin reads a named
# converter's signature, so ``Ball(mass="45.93 g")`` type-checks, where a converter made by a call is opaque to it.
def si_length(value: Any) -> Any:
    """attrs converter: a length as an SI float [m] (a bare number is SI; text with a unit or pint converted)."""
    return _convert(value, "length")


def si_angle(value: Any) -> Any:
    """attrs converter: an angle as an SI float [rad] (a bare number is SI; text with a unit or pint converted)."""
    return _convert(value, "angle")


def si_mass(value: Any) -> Any:
    """attrs converter: a mass as an SI float [kg] (a bare number is SI; text with a unit or pint converted)."""
    return _convert(value, "mass")


def si_speed(value: Any) -> Any:
    """attrs converter: a speed as an SI float [m/s] (a bare number is SI; text with a unit or pint converted)."""
    return _convert(value, "speed")


def si_angular_speed(value: Any) -> Any:
    """attrs converter: an angular speed as an SI float [rad/s] (a bare number is SI; text with a unit or pint
    converted)."""
    return _convert(value, "angular_speed")


def si_pressure(value: Any) -> Any:
    """attrs converter: a pressure (a modulus) as an SI float [Pa] (a bare number is SI; text with a unit or pint
    converted)."""
    return _convert(value, "pressure")


def si_inverse_speed(value: Any) -> Any:
    """attrs converter: an inverse speed as an SI float [s/m] (a bare number is SI; text with a unit or pint
    converted)."""
    return _convert(value, "inverse_speed")


class _Bare(enum.Enum):
    """What :func:`_string_to_si` answers for text that is a bare number (its one member, ``BARE``)."""

    BARE = "bare"


@functools.lru_cache(maxsize=4096)
def _string_to_si(text: str, dimension: str) -> float | str | _Bare:
    """The SI value of a quantity written as text, or the reason (a suffix of the message) it is not one.

    Memoised: pint parses a quantity in about 0.3 ms, and a study names the same few ("80 mph", "20 deg")
    in its base scene and again in every scene its sweep checks; the answer depends on the text alone.
    """
    si_unit = DIMENSIONS[dimension][0]
    ureg = registry()
    for symbol, reason in AMBIGUOUS_SYMBOLS.items():
        if re.search(rf"(?<![A-Za-z_]){symbol}(?![A-Za-z_])", text):
            return f"; {reason}"
    try:
        quantity: Any = ureg.Quantity(text)
    except Exception:  # noqa: BLE001 - pint raises many kinds for text it cannot read; the message says what to write
        return ""
    if not isinstance(quantity, ureg.Quantity) or quantity.unitless:
        try:
            number = float(text)
        except ValueError:  # a unit pint counts as none ("50 %"): judged below like any other
            number = None
        if number is not None:  # a bare number written as a string
            return number if dimension == "dimensionless" else _Bare.BARE
    # pint counts radians as dimensionless, so "50 %" would pass as 0.5 rad, "30 deg" as a friction of
    # 0.52, and "50 Hz" as 50 rad/s: whether an angle unit is written decides instead
    angular = _has_angle(quantity)
    if dimension == "angle" and not angular:
        return f"; {quantity.units:~} is not an angle unit (deg, rad)"
    if dimension == "dimensionless" and angular:
        return "; an angle unit does not belong here"
    if dimension == "angular_speed" and not angular:
        # a frequency without an angle counts turns: 50 Hz is 50 rev/s = 3000 rpm (ISO 80000-3)
        quantity = quantity * ureg.Quantity(1, "revolution")
    try:
        return float(quantity.to(si_unit).magnitude)
    except Exception:  # noqa: BLE001 - pint's DimensionalityError and friends
        return f"; units of {quantity.units:~} do not convert to {si_unit}"


#: unit symbols pint reads one way and people write meaning another: refused, never read as either
AMBIGUOUS_SYMBOLS = {
    # pint's gr is the grain (64.79891 mg, exact: the international yard and pound agreement, 1959); gr is the
    # gram's abbreviation in French, Spanish, Italian, Greek...: a 200 gr head would be 13 g
    "gr": "gr is a grain (64.8 mg) to the unit parser and a gram to many people: write g (grams) or grain",
}


def _has_angle(quantity) -> bool:
    """Whether a quantity's units include an angle (deg, rad, rpm, revolution...), which pint treats as 1."""
    return "radian" in str(quantity.to_root_units().units)


#: Conversion factors from SI to the units results are stored in. The one place they are written: not asked
#: of pint at import, whose registry takes seconds to build and which every ``import impactlab`` would pay;
#: tests/test_contract.py checks each against pint's definitions.
RAD_TO_DEG = 180.0 / math.pi
RADS_TO_RPM = 60.0 / (2.0 * math.pi)
#: metres per second in a mile per hour (exact: the international mile)
MPH = 0.44704
#: metres in a yard, a foot and an inch (exact: the international yard of 1959)
YARD = 0.9144
FOOT = 0.3048
INCH = 0.0254



#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["DIMENSIONS", "EXAMPLE_UNITS", "ZERO_DEPENDS_ON_UNIT", "UNIT_NOTES", "unit_factor", "unit_affine",
           "unit_missing", "registry", "to_si", "si_length", "si_angle", "si_mass", "si_speed", "si_angular_speed",
           "si_pressure", "si_inverse_speed", "AMBIGUOUS_SYMBOLS", "RAD_TO_DEG", "RADS_TO_RPM", "MPH", "YARD", "FOOT",
           "INCH"]
