"""The measured-data documents as the user writes them, structured by cattrs like the blocks of a study.

Two documents: a YAML shot table (:func:`impactlab.data.sessions.shots.read_yaml`) and a measured-data file
(:func:`impactlab.data.validation.load_measured`). Each has a frozen attrs class per block whose fields are the
keys a user may write, typed by what they hold; :func:`structure_document` turns the parsed YAML into it with
unknown keys refused and every value of the wrong shape (a list where a mapping belongs, a mapping where a
number belongs...) one :class:`~impactlab.errors.FieldError` at the key's ``file:line``, with the pattern and the
error wording of :mod:`impactlab.study.structuring`. The blocks check shapes; what the values mean (a field name, a
unit, a club preset) is checked by the readers, which report every bad cell at once.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Mapping
from typing import Any, NewType, get_args, get_origin

import attrs
from cattrs import Converter
from cattrs.errors import BaseValidationError, ForbiddenExtraKeysError

from impactlab.errors import FieldError
from impactlab.study.structuring import document_converter, field_error
from impactlab.study.yaml_lines import format_path, line_of, parse_path

#: a piece of text: a string (a number written where text belongs is taken as its text, as YAML reads ``7``)
Text = NewType("Text", str)
#: a value with its unit as the user wrote it (``"1 mph"``, ``0.5``): checked and converted by the reader
Scalar = NewType("Scalar", object)
#: a finite number
Finite = NewType("Finite", float)
#: a positive, finite number
Positive = NewType("Positive", float)
#: a mapping kept as written (a study ``ball:`` block: structured later by the study's own schema)
Block = NewType("Block", dict)
#: one row of a shot table: a mapping of column to cell, the cells checked by the reader
Row = NewType("Row", object)


def _field(expected: str, default: Any = None):
    return attrs.field(default=default, metadata={"expected": expected})


@attrs.frozen
class ShotTableBlock:
    """A YAML shot table (:func:`impactlab.data.sessions.shots.read_yaml`)."""

    _what = "a shot table"
    _key_of = "a shot table"
    rows: list[Row] = _field("a list of rows, each a mapping of fields", None)
    name: Text | None = _field("the table's name (text)")
    source: Text | None = _field("where the numbers come from (text)")
    ball: Block | None = _field("a ball block (a mapping, as in a study: preset, mass...)")
    units: dict[str, Text] | None = _field("a mapping of field to its unit (e.g. club_speed: mph)")
    sigma: dict[str, Scalar] | None = _field("a mapping of measured field to its one-sigma uncertainty with unit")
    loft_at: Text | None = _field("contact or centre")
    instrument: Text | None = _field("the maker of the monitor that measured the rows (trackman, flightscope...)")
    budgets: dict[str, dict[str, Positive]] | None = _field(
        "a mapping of model id to a mapping of error to its largest allowed RMS")


@attrs.frozen
class PointBlock:
    """One measured point of a measured-data file."""

    _what = "a measured point"
    _key_of = "a point"
    label: Text = _field("the point's label in the study's sweep (required)")
    value: Finite = _field("the measured value, a finite number (required)")
    sigma: Positive | None = _field("a positive number (or leave it out)")


@attrs.frozen
class MeasuredDataBlock:
    """A measured-data file (:func:`impactlab.data.validation.load_measured`)."""

    _what = "a measured-data file"
    _key_of = "a measured-data file"
    source: Text = _field("where the data come from (required)")
    quantity: Text = _field("a scalar output of impactlab (required)")
    study: Text = _field("the study that reproduces the data, a file name (required)")
    dimension: Text = _field("the study's labelled sweep the points lie along (required)")
    points: list[PointBlock] = _field("a list of {label, value, sigma} (required)")
    name: Text | None = _field("the data's name (text)")
    budgets: dict[str, Positive] | None = _field("a mapping from model id to a positive RMS error")
    note: Text | None = _field("a note (text)")


BLOCKS = (ShotTableBlock, PointBlock, MeasuredDataBlock)


def _text(value, _) -> str:
    if isinstance(value, (Mapping, list, bool)) or value is None:
        raise FieldError("", "text", value)
    return str(value)


def _scalar(value, _):
    if isinstance(value, (Mapping, list, bool)) or value is None:
        raise FieldError("", "a value with its unit (e.g. '1 mph' or '0.5 deg')", value)
    return value


def _number(positive: bool):
    def structure(value, _) -> float:
        ok = isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
        if not ok or (positive and not value > 0):
            raise FieldError("", "a positive number" if positive else "a finite number", value)
        return float(value)
    return structure


def _block(value, _) -> dict:
    if not isinstance(value, Mapping):
        raise FieldError("", "a mapping", value)
    return dict(value)


def _mapping_hook(type_, converter: Converter):
    """``dict[str, X]``: a mapping only (a list is said, not iterated), each value located under its key."""
    value_type = get_args(type_)[1]
    inner = converter.get_structure_hook(value_type)

    def structure(value, _):
        if not isinstance(value, Mapping):
            raise FieldError("", "a mapping", value)
        out = {}
        for key, item in value.items():
            try:
                out[str(key)] = inner(item, value_type)
            except FieldError as exc:
                if any(mark in str(key) for mark in ".[]"):  # not a path step ('ball_speed [%]'): said in words
                    raise FieldError(exc.path, f"{exc.expected} for {str(key)!r}", exc.given, exc.choices) from None
                raise FieldError(format_path((str(key),) + parse_path(exc.path)), exc.expected, exc.given,
                                 exc.choices) from None
        return out
    return structure


def _list_hook(type_, converter: Converter):
    """Lists only (a string or mapping is not a list of values), each item's error located under ``[index]``."""
    item_type = get_args(type_)[0]
    item = converter.get_structure_hook(item_type)

    def structure(value, _):
        if not isinstance(value, list):
            raise FieldError("", "a list", value)
        out = []
        for index, entry in enumerate(value):
            try:
                out.append(item(entry, item_type))
            except (BaseValidationError, FieldError, ForbiddenExtraKeysError) as exc:
                error = field_error(exc, entry, "", (), item_type, None)
                raise FieldError(format_path((index,) + parse_path(error.path)), error.expected, error.given,
                                 error.choices) from None
        return out
    return structure


@functools.cache
def _converter() -> Converter:
    """The study's converter (:func:`~impactlab.study.structuring.document_converter`: blocks and optional values)
    with the kinds of value of measured data, and lists and mappings located item by item."""
    converter = document_converter()
    for type_, hook in ((Text, _text), (Scalar, _scalar), (Finite, _number(False)), (Positive, _number(True)),
                        (Block, _block), (Row, lambda value, _: value)):
        converter.register_structure_hook(type_, hook)
    converter.register_structure_hook_factory(lambda t: get_origin(t) is list, _list_hook)
    converter.register_structure_hook_factory(lambda t: get_origin(t) is dict, _mapping_hook)
    return converter


def structure_document(document, cls, file: str, lines) -> Any:
    """Structure a parsed YAML document into ``cls``, or raise the FieldError at its ``file:line``.

    Parameters
    ----------
    document : object
        What the YAML parser returned.
    cls : type
        :class:`ShotTableBlock` or :class:`MeasuredDataBlock`.
    file : str
        The file's name, for the message.
    lines : object
        The line index of :func:`impactlab.study.yaml_lines.load_yaml`.

    Raises
    ------
    FieldError
        At the dotted path and line of the first bad key (unknown keys first).
    """
    try:
        return _converter().get_structure_hook(cls)(document, cls)
    except (BaseValidationError, FieldError, ForbiddenExtraKeysError) as exc:
        error = field_error(exc, document, "", (), cls, None)
    path = parse_path(error.path) if error.path else ()
    line = line_of(lines, path) if path else None
    raise FieldError(error.path, error.expected, error.given, error.choices, file=file, line=line)


__all__ = ["MeasuredDataBlock", "PointBlock", "ShotTableBlock", "structure_document"]
