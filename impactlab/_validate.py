"""attrs validators whose failures say what was expected and what was given."""

from __future__ import annotations

import math
from collections.abc import Callable

from .errors import FieldError


def check(predicate: Callable[[float], bool], expected: str, optional: bool = False):
    """An attrs validator: ``predicate(value)`` must hold, else FieldError(name, expected, value)."""

    def validator(instance, attribute, value):
        if value is None and optional:
            return
        try:
            ok = predicate(value)
        except TypeError:
            ok = False
        if not ok:
            raise FieldError(attribute.name, expected, value)

    return validator


def _is_number(value) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and not math.isnan(value)


def positive(expected: str = "a positive, finite number", optional: bool = False):
    return check(lambda v: _is_number(v) and 0 < v < math.inf, expected, optional)


def positive_or_inf(expected: str = "a positive number (or inf)", optional: bool = False):
    return check(lambda v: _is_number(v) and v > 0, expected, optional)


def in_range(low: float, high: float, expected: str, low_open=False, high_open=False, optional=False):
    def predicate(v):
        if not _is_number(v):
            return False
        above = v > low if low_open else v >= low
        below = v < high if high_open else v <= high
        return above and below

    return check(predicate, expected, optional)


def finite(expected: str = "a finite number", optional: bool = False):
    return check(lambda v: _is_number(v) and math.isfinite(v), expected, optional)


def to_float(value):
    """attrs converter: ints become floats, other values pass through (validators judge them)."""
    if isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    return value
