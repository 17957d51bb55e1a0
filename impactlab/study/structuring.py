"""Structuring a study block: a :class:`cattrs.Converter` turns a YAML mapping into a block of
:mod:`impactlab.study.schema`.

Every quantity goes through :func:`impactlab.units.to_si` with its field's dimension, unknown keys are refused
(``forbid_extra_keys``) and every field is checked (``detailed_validation``). A failure comes back as one
:class:`~impactlab.errors.FieldError` at the dotted path of the offending key, with the messages the study
format has always given, so that :func:`impactlab.load_study` maps it to its file and line.

What it costs, measured against the hand-written parser it replaced (2 shared cores, best of many repeats,
text quantities memoised by ``to_si`` in both): building a scene from its blocks takes about 10 us more (85
instead of 77 us for a scene; a block takes 5-15 us to structure), and a whole ``load_study`` about 0.1 ms
more (0.7 instead of 0.6 ms for the 540-case benchmark's study, 0.3 % of its ``run_study``; 10^5 swept
values still load in about 40 ms). Once per process, importing cattrs and defining the blocks takes 20-40 ms
and generating their structuring functions about 14 ms, at the first study loaded. In exchange, a block's
keys, kinds and units are declared once, in one place, and an unknown key is refused at any depth.
"""

from __future__ import annotations

import functools
import types
from collections.abc import Mapping
from typing import Any, Union, get_args, get_origin

import attrs
from cattrs import Converter
from cattrs.errors import AttributeValidationNote, BaseValidationError, ForbiddenExtraKeysError, \
    IterableValidationNote
from cattrs.gen import make_dict_structure_fn

from impactlab.errors import FieldError
from impactlab.study.schema import (_DIMENSIONS, SI, Count, Flag, InertiaBlock, InertiaSpec,
                                    Name, Restitution, RestitutionBlock, SurfaceBlock, SurfaceSpec, keys_of)
from impactlab.study.yaml_lines import format_path, parse_path
from impactlab.units import to_si


def _quantity_hook(dimension: str):
    def structure(value, _):
        if isinstance(value, SI):
            return float(value)
        return to_si(value, dimension)
    return structure


def _flag(value, _) -> bool:
    if not isinstance(value, bool):
        raise FieldError("", "true or false", value)
    return value


def _count(value, _) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < 1:
        raise FieldError("", "a whole number of values >= 1", value)
    return value


def _located(function, value, index: int):
    """``function(value)`` with a FieldError's path put under ``[index]``."""
    try:
        return function(value)
    except FieldError as exc:
        raise FieldError(format_path((index,) + parse_path(exc.path)), exc.expected, exc.given, exc.choices) from None


def _list_hook(type_, converter: Converter):
    """Lists only: a string or mapping is not a list of values (plain cattrs would iterate over it)."""
    item_type = type_.__args__[0]
    item = converter.get_structure_hook(item_type)

    def structure(value, _):
        if not isinstance(value, list):
            raise TypeError("not a list")  # worded by the field's ``expected``
        return [_located(lambda v: item(v, item_type), v, index) for index, v in enumerate(value)]
    return structure


def _restitution(value, _):
    """A ball's restitution: a law written as a mapping, or a number (a constant law, as most studies write it)."""
    if isinstance(value, Mapping):
        return _hook(RestitutionBlock)(value, RestitutionBlock)
    return to_si(value, "dimensionless")


def _surface_spec(value, _):
    """A face's surface: a preset's name (looked up by the builder), or a SurfaceBlock of a preset and/or fields."""
    if isinstance(value, str):
        return value
    return _hook(SurfaceBlock)(value, SurfaceBlock)


def _inertia_spec(value, _):
    """A head's inertia: the tensor as a 3x3 list (each entry located as ``[i][j]``), or an InertiaBlock."""
    if not isinstance(value, list):
        return _hook(InertiaBlock)(value, InertiaBlock)
    if not all(isinstance(row, list) for row in value):
        raise FieldError("", "a 3x3 list of lists (the tensor in toe, up, target axes)", value)
    moment = _quantity_hook("inertia")
    return tuple(_located(lambda row: tuple(_located(lambda v: moment(v, None), v, j) for j, v in enumerate(row)),
                          row, i) for i, row in enumerate(value))


def _is_optional(type_) -> bool:
    return get_origin(type_) in (Union, types.UnionType) and len(get_args(type_)) == 2 and type(None) in get_args(type_)


def _optional_hook(type_, converter: Converter):
    """``X | None`` with X's hook bound once (cattrs looks it up again at every value: 15 % of a block's time)."""
    inner_type = next(arg for arg in get_args(type_) if arg is not type(None))
    inner = converter.get_structure_hook(inner_type)
    return lambda value, _: None if value is None else inner(value, inner_type)


def _is_block(type_) -> bool:
    """A block: a frozen attrs class that says what it is (``_what``) for the messages."""
    return isinstance(type_, type) and attrs.has(type_) and hasattr(type_, "_what")


def _block_hook(cls, converter: Converter):
    generated = make_dict_structure_fn(cls, converter, _cattrs_forbid_extra_keys=True,
                                       _cattrs_detailed_validation=True)
    expected = f"a mapping ({cls._what}) with keys from: {', '.join(keys_of(cls))}"

    def structure(value, _):
        if not isinstance(value, Mapping):
            raise FieldError("", expected, value)
        return generated(value, cls)
    return structure


@functools.cache
def _base_converter() -> Converter:
    """What every document of impactlab structures the same way: blocks (unknown keys refused, every field checked,
    a mapping required) and optional values. Each document's converter is a :meth:`~cattrs.Converter.copy` of it
    with the hooks of its own kinds of value; the factories take the converter they run in (cattrs >= 24.1), so a
    copy's blocks find the copy's hooks."""
    converter = Converter()
    converter.register_structure_hook_factory(_is_block, _block_hook)
    converter.register_structure_hook_factory(_is_optional, _optional_hook)
    return converter


def document_converter() -> Converter:
    """A new converter for one kind of document: blocks and optional values structured as in a study.

    Register the hooks of the document's own value types on it (later registrations win over these). Errors it
    raises are turned into one :class:`~impactlab.errors.FieldError` by :func:`field_error`.

    Returns
    -------
    cattrs.Converter
        A copy of the shared converter (changing it leaves the shared one and every other copy as they are).
    """
    return _base_converter().copy()


@functools.cache
def _converter() -> Converter:
    """The converter of study blocks, made once (it generates one structuring function per block)."""
    converter = document_converter()
    for type_, dimension in _DIMENSIONS.items():
        converter.register_structure_hook(type_, _quantity_hook(dimension))
    hooks: tuple[tuple[Any, Any], ...] = ((Flag, _flag), (Count, _count),
                                          (Name, lambda v, _: v), (Restitution, _restitution),
                                          (InertiaSpec, _inertia_spec), (SurfaceSpec, _surface_spec))
    for type_, hook in hooks:
        converter.register_structure_hook(type_, hook)
    converter.register_structure_hook_factory(lambda t: getattr(t, "__origin__", None) is list, _list_hook)
    return converter


@functools.cache
def _hook(cls):
    """The structuring function of a block (generated on first use)."""
    return _converter().get_structure_hook(cls)


def lookup(document: Any, path: tuple) -> Any:
    """The node at ``path`` in a document, or None where there is none."""
    node = document
    for part in path:
        if isinstance(node, (str, bytes)):  # text has no nodes: its [0] is a letter, not what the user wrote there
            return None
        try:
            node = node[part]
        except (KeyError, IndexError, TypeError):
            return None
    return node


def structure(value: Any, cls: Any, path: str) -> Any:
    """Structure one study block, or raise the FieldError a user should see.

    Parameters
    ----------
    value : Mapping or None
        The block as written (None or absent: every key left out).
    cls : type
        One of the block classes of this module.
    path : str
        Where the block sits in the study (``"club"``, ``"sweep.impact.angle"``; ``""`` for the study itself).

    Returns
    -------
    object
        An instance of ``cls``: quantities in SI, every other key as written.

    Raises
    ------
    FieldError
        At the dotted path of the first bad key (unknown keys first, then the keys in the block's order).
    """
    if value is None:
        value = {}
    try:
        return _hook(cls)(value, cls)
    except (BaseValidationError, FieldError, ForbiddenExtraKeysError) as exc:
        raise field_error(exc, value, path, (), cls, None) from None


def _step(exc) -> tuple:
    """The path step a cattrs note puts on an error: an attribute name or a list index."""
    for note in getattr(exc, "__notes__", ()):
        if isinstance(note, AttributeValidationNote):
            return (note.name,)
        if isinstance(note, IterableValidationNote):
            return (note.index,)
    return ()


def field_error(exc, value, where: str, steps: tuple, cls, name: str | None) -> FieldError:
    """The FieldError of the first failure in a cattrs error tree, at ``where`` + ``steps``.

    Parameters
    ----------
    exc : Exception
        What a converter of :func:`document_converter` raised (a cattrs validation error, a FieldError, a
        ForbiddenExtraKeysError).
    value : object
        The document (or block) that was structured.
    where : str
        The dotted path of ``value`` in its document (``""``: the document itself).
    steps : tuple
        Path steps below ``where`` already walked.
    cls : type
        The block class being structured.
    name : str or None
        The field being structured, whose ``expected`` metadata words a failure of cattrs itself.

    Returns
    -------
    FieldError
        At the dotted path of the first bad key (unknown keys first).
    """
    if isinstance(exc, BaseValidationError):
        # unknown keys first, as before cattrs: a misspelt key also leaves its field missing
        first = min(exc.exceptions, key=lambda e: not isinstance(e, ForbiddenExtraKeysError))
        step = _step(first)
        return field_error(first, value, where, steps + step, exc.cl,
                            step[0] if step and isinstance(step[0], str) else name)
    parts = parse_path(where) + steps
    path = format_path(parts)
    if isinstance(exc, ForbiddenExtraKeysError):
        node = lookup(value, steps)
        key = next(str(key) for key in node if key in exc.extra_fields)
        whose = getattr(exc.cl, "_key_of", path or "the study")
        return FieldError(f"{path}.{key}" if path else key, f"a key of {whose}", key, choices=keys_of(exc.cl))
    if isinstance(exc, FieldError):
        return FieldError(format_path(parts + parse_path(exc.path)), exc.expected, exc.given, exc.choices)
    # a failure of cattrs itself (a list that is not one, a required key left out): worded by the field
    field = attrs.fields_dict(cls).get(name) if name else None
    expected = (field.metadata.get("expected") if field is not None else None) or f"a valid value ({exc})"
    return FieldError(path, expected, "nothing" if isinstance(exc, KeyError) else lookup(value, steps))
