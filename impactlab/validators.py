"""attrs validators and converters whose failures say what was expected and what was given.

Public: plugin authors use them for their ``Options`` classes, as the built-in
models do (docs/writing-a-model.md). Every validator raises
:class:`impactlab.errors.FieldError` naming the field, the expectation and the
value, which the study loader turns into ``file:line: path: expected ..., got
...``.

Examples
--------
>>> import attrs
>>> from impactlab.validators import in_range, to_float
>>> @attrs.frozen
... class Options:
...     beta: float = attrs.field(default=0.0, converter=to_float,
...                               validator=in_range(-1.0, 1.0, "-1 <= beta <= 1"))
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from impactlab.errors import FieldError


#: an attrs validator: called with the instance, the attribute and the value; raises to refuse the value
Validator = Callable[[Any, Any, Any], None]


def check(predicate: Callable[[Any], bool], expected: str, optional: bool = False) -> Validator:
    """An attrs validator: ``predicate(value)`` must hold, else FieldError(name, expected, value)."""

    def validator(instance: Any, attribute: Any, value: Any) -> None:
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


def positive(expected: str = "a positive, finite number", optional: bool = False) -> Validator:
    """An attrs validator: a number with 0 < value < inf (``None`` too when ``optional``)."""
    return check(lambda v: _is_number(v) and 0 < v < math.inf, expected, optional)


def positive_or_inf(expected: str = "a positive number (or inf)", optional: bool = False) -> Validator:
    """An attrs validator: a number with value > 0, ``inf`` allowed (a flat face's radius, a fixed face's mass)."""
    return check(lambda v: _is_number(v) and v > 0, expected, optional)


def inside(values: Any, low: float, high: float, low_open: bool = False, high_open: bool = False) -> Any:
    """Whether ``values`` (a number or an array, elementwise) lie in [low, high], ends excluded when open.

    The one range test: option validators (:func:`in_range`) and the input arrays handed to a model
    (:meth:`impactlab.vocabulary.InputSpec.out_of_range`) both use it. NaN is never inside.
    """
    above = values > low if low_open else values >= low
    below = values < high if high_open else values <= high
    return above & below


def in_range(low: float, high: float, expected: str, low_open: bool = False, high_open: bool = False,
             optional: bool = False) -> Validator:
    """An attrs validator: a number in [low, high], either end excluded when ``low_open``/``high_open``.

    ``expected`` is the message's expectation, in the user's words (e.g. "a friction coefficient >= 0").
    """

    def predicate(v: Any) -> bool:
        return _is_number(v) and bool(inside(v, low, high, low_open, high_open))

    return check(predicate, expected, optional)


def finite(expected: str = "a finite number", optional: bool = False) -> Validator:
    """An attrs validator: a finite number (not NaN, not inf)."""
    return check(lambda v: _is_number(v) and math.isfinite(v), expected, optional)


def to_float(value: Any) -> Any:
    """attrs converter: ints become floats, other values pass through (validators judge them)."""
    if isinstance(value, int) and not isinstance(value, bool):
        return float(value)
    return value


def number_or_array(value: Any) -> Any:
    """attrs converter for a field that takes one number or one per element: a list, tuple or array of numbers
    becomes a read-only float array (a 0-d array a float), an int a float; other values pass through (validators
    judge them)."""
    if isinstance(value, (list, tuple, np.ndarray)):
        try:
            array = np.array(value, dtype=float)
        except (TypeError, ValueError):
            return value
        if np.asarray(value).dtype.kind not in "iuf":  # bools, strings, objects: not numbers
            return value
        if not array.ndim:
            return float(array)
        array.setflags(write=False)
        return array
    return to_float(value)


def in_range_each(low: float, high: float, expected: str, low_open: bool = False, high_open: bool = False,
                  optional: bool = False) -> Validator:
    """An attrs validator as :func:`in_range` for a number, and for an array of numbers every element.

    A refused element is named by its index and value (``FieldError("temperature[3]", expected, 400.0)``); an
    empty array is refused. With ``optional``, None and NaN elements (a value not given for that element) pass.
    """
    scalar = in_range(low, high, expected, low_open, high_open, optional)

    def validator(instance: Any, attribute: Any, value: Any) -> None:
        if not isinstance(value, np.ndarray):
            scalar(instance, attribute, value)
            return
        if not value.size:
            raise FieldError(attribute.name, f"{expected}: one value, or one per element", "an empty array")
        refused = ~inside(value, low, high, low_open, high_open)
        if optional:
            refused &= ~np.isnan(value)
        if np.any(refused):
            index = np.unravel_index(int(np.flatnonzero(refused)[0]), value.shape)
            raise FieldError(f"{attribute.name}[{', '.join(str(int(i)) for i in index)}]", expected,
                             float(value[index]))

    return validator


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["Validator", "check", "positive", "positive_or_inf", "inside", "in_range", "finite", "to_float",
           "number_or_array", "in_range_each"]
