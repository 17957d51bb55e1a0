"""Quantities written by users, turned into SI floats.

A quantity in a study is either a plain number, read in the field's *plain
unit* (SI, except angles in degrees and spin in rpm, as the study format
promises), or a string with a unit that pint understands (``"80 mph"``,
``"21.335 mm"``, ``"136 MPa"``). Inside impactlab everything is SI with angles
in radians and spin in rad/s.
"""

from __future__ import annotations

import functools
import math
from numbers import Real
from typing import TYPE_CHECKING, Any

from impactlab.errors import FieldError

if TYPE_CHECKING:  # pint itself is imported on first use (it is slow to load)
    import pint

#: Physical dimension name -> (SI unit as pint understands it, plain unit of
#: bare numbers, words for messages).
DIMENSIONS: dict[str, tuple[str, str, str]] = {
    "length": ("m", "m", "a length"),
    "mass": ("kg", "kg", "a mass"),
    "pressure": ("Pa", "Pa", "a modulus (pressure)"),
    "speed": ("m/s", "m/s", "a speed"),
    "angle": ("rad", "deg", "an angle"),
    "angular_speed": ("rad/s", "rpm", "a spin rate"),
    "time": ("s", "s", "a time"),
    "inertia": ("kg*m**2", "kg*m**2", "a moment of inertia"),
    "dimensionless": ("dimensionless", "dimensionless", "a number"),
}


@functools.cache
def registry() -> pint.UnitRegistry:
    """The shared pint unit registry (created on first use: pint is slow to load)."""
    import pint

    # "15 degC" is a temperature, not 15 times an offset unit (which pint refuses as ambiguous)
    return pint.UnitRegistry(autoconvert_offset_to_baseunit=True)


def to_si(value: object, dimension: str, path: str = "") -> float:
    """Convert a user quantity to an SI float.

    Parameters
    ----------
    value : float or str
        A bare number (read in the plain unit of ``dimension``) or a string
        such as ``"80 mph"``.
    dimension : str
        A key of :data:`DIMENSIONS`.
    path : str
        Field path for error messages.

    Raises
    ------
    FieldError
        When the value is not a number or quantity of that dimension.
    """
    si_unit, plain_unit, words = DIMENSIONS[dimension]
    expected = f"{words} (a number in {plain_unit} or a string with a unit)" if dimension != "dimensionless" \
        else "a number"
    if isinstance(value, bool) or value is None:
        raise FieldError(path, expected, value)
    if isinstance(value, Real):
        return float(value) * _factor(plain_unit, si_unit)
    if not isinstance(value, str):
        raise FieldError(path, expected, value)
    converted = _string_to_si(value.strip(), dimension)
    if isinstance(converted, str):  # why the text is not a quantity of this dimension
        raise FieldError(path, f"{expected}{converted}", value)
    return converted


@functools.lru_cache(maxsize=64)
def _factor(unit: str, si_unit: str) -> float:
    """SI per ``unit`` (a bare number in a study is read in its field's plain unit)."""
    return 1.0 if unit == si_unit else float(registry().Quantity(1.0, unit).to(si_unit).magnitude)


@functools.lru_cache(maxsize=4096)
def _string_to_si(text: str, dimension: str) -> float | str:
    """The SI value of a quantity written as text, or the reason (a suffix of the message) it is not one.

    Memoised: pint parses a quantity in about 0.3 ms, and a study names the same few ("80 mph", "20 deg")
    in its base scene and again in every scene its sweep checks; the answer depends on the text alone.
    """
    si_unit, plain_unit, _ = DIMENSIONS[dimension]
    ureg = registry()
    try:
        quantity: Any = ureg.Quantity(text)
    except Exception:  # noqa: BLE001 - pint raises many kinds for text it cannot read; the message says what to write
        return ""
    if not isinstance(quantity, ureg.Quantity):  # a bare number written as a string
        return float(quantity) * _factor(plain_unit, si_unit)
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


#: air temperature (the ball flight's conditions): K; "15 degC" and "59 degF" are read as temperatures
DIMENSIONS["temperature"] = ("K", "K", "a temperature")
