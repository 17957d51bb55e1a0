"""The blocks of a study file as the user writes them, structured by cattrs.

Each block of a study (``ball``, ``face``, ``club``, ``strike``...) has a frozen attrs class here whose fields
are the keys a user may write, typed by what they hold: a ``Length``, an ``Angle``, a ``Flag``...
A :class:`cattrs.Converter` turns a YAML mapping into such a block: every quantity through
:func:`impactlab.units.to_si` with its field's dimension, unknown keys refused (``forbid_extra_keys``), every
field checked (``detailed_validation``). A failure comes back as one :class:`~impactlab.errors.FieldError`
at the dotted path of the offending key, with the messages the study format has always given, so that
:func:`impactlab.load_study` maps it to its file and line.

The blocks carry no physics: ``impactlab.study.scene_blocks`` resolves presets, overrides and mutual exclusions
from them into ``Ball``, ``ClubHead``, ``Scene``...

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
from typing import Any, NewType, Union, get_args, get_origin

import attrs
from cattrs import Converter
from cattrs.errors import AttributeValidationNote, BaseValidationError, ForbiddenExtraKeysError, \
    IterableValidationNote
from cattrs.gen import make_dict_structure_fn

from impactlab.errors import FieldError
from impactlab.units import to_si
from impactlab.study.yaml_lines import format_path, parse_path

# Field types: a user quantity converted to an SI float with the dimension the name says
Length = NewType("Length", float)
Mass = NewType("Mass", float)
Pressure = NewType("Pressure", float)
Speed = NewType("Speed", float)
Angle = NewType("Angle", float)
Spin = NewType("Spin", float)
Inertia = NewType("Inertia", float)
Number = NewType("Number", float)
#: a restitution slope de/dv: a quantity of inverse speed ('-0.002 s/m')
InverseSpeed = NewType("InverseSpeed", float)
#: quantities whose unit must be written (a bare number is refused): the air conditions
Temperature = NewType("Temperature", float)
UnitPressure = NewType("UnitPressure", float)
UnitLength = NewType("UnitLength", float)
UnitSpeed = NewType("UnitSpeed", float)
#: true or false, nothing else ("yes" and 1 are refused, where plain ``bool`` would accept them)
Flag = NewType("Flag", bool)
#: a whole number >= 1 (the length of a sweep range)
Count = NewType("Count", int)
#: a name looked up in a table by the builder, which lists the table's keys as the choices
Name = NewType("Name", str)
#: a ball's restitution: a number (a constant law) or a :class:`RestitutionBlock`
Restitution = NewType("Restitution", object)
#: a head's inertia: a :class:`InertiaBlock` or a 3x3 list of lists
InertiaSpec = NewType("InertiaSpec", object)
#: an angular velocity that must carry its unit (0 excepted): a head's turning rate is quoted in deg/s by launch
#: monitors (closure rate) and spin in rpm by impactlab, so a bare number would be a guess between them
Rate = NewType("Rate", float)
RATE_EXPECTED = ("an angular velocity with its unit, e.g. '2000 deg/s' or '35 rad/s' (a bare number is ambiguous: "
                 "closure rates are quoted in deg/s, spin in rpm)")


def rate_with_unit(value, where: str = "") -> float:
    """An angular velocity [rad/s] from a quantity with its unit; a bare number other than 0 is refused."""
    if isinstance(value, SI):
        return float(value)
    bare = isinstance(value, (int, float)) and not isinstance(value, bool)
    if isinstance(value, str):
        try:
            float(value)
            bare = True
        except ValueError:
            pass
    if bare:
        if float(value) == 0.0:
            return 0.0
        raise FieldError(where, RATE_EXPECTED, value)
    return to_si(value, "angular_speed", where)

_DIMENSIONS = {Length: "length", Mass: "mass", Pressure: "pressure", Speed: "speed", Angle: "angle",
               Spin: "angular_speed", Inertia: "inertia", Number: "dimensionless"}
_WITH_UNIT = {Temperature: "temperature", UnitPressure: "pressure", UnitLength: "length", UnitSpeed: "speed"}


class SI(float):
    """A value already converted to SI (sweeps substitute these into the document), passed through unconverted."""


def _field(expected: str | None = None, default: Any = None):
    """A block key, absent by default; ``expected`` words a value of the wrong kind (else the type does)."""
    return attrs.field(default=default, metadata={"expected": expected} if expected else {})


@attrs.frozen
class BallBlock:
    """The ``ball`` block: a preset and/or the ball's own keys (docs/user-guide.md, Fields)."""

    _what = "the ball"
    preset: Name | None = None
    radius: Length | None = None
    mass: Mass | None = None
    inertia_factor: Number | None = None
    youngs_modulus: Pressure | None = None
    poisson_ratio: Number | None = None
    friction: Number | None = None
    restitution: Restitution | None = None
    tangential_loss: Number | None = None


@attrs.frozen
class RestitutionBlock:
    """A restitution law written as a mapping (``ball.restitution``); a bare number is a constant law."""

    _what = "a restitution law"
    law: Name = Name("constant")
    value: Number | None = None
    reference_speed: Speed | None = None
    slope: InverseSpeed | None = None
    exponent: Number | None = None
    speeds: list[Speed] | None = _field("a list of speeds")
    values: list[Number] | None = _field("a list of numbers")


@attrs.frozen
class FaceBlock:
    """The ``face`` block: a preset, ``rigid``, a material and an optional head mass."""

    _what = "the face"
    preset: Name | None = None
    rigid: Flag | None = None
    youngs_modulus: Pressure | None = None
    poisson_ratio: Number | None = None
    mass: Mass | None = None


@attrs.frozen
class InertiaBlock:
    """``club.inertia`` as a mapping: tensor components (toe, up, target axes) or principal moments + axes."""

    _what = "the head's inertia about its centre of mass"
    toe: Inertia | None = None
    up: Inertia | None = None
    target: Inertia | None = None
    toe_up: Inertia | None = None
    toe_target: Inertia | None = None
    up_target: Inertia | None = None
    principal: list[Inertia] | None = _field("three principal moments")
    axes: Any = None  # numbers, checked with the moments (ClubHead.from_principal)


@attrs.frozen
class CenterBlock:
    """``club.center_of_mass``: from the face centre, towards the toe, up the face and behind it."""

    _what = "the centre of mass"
    toe: Length | None = None
    high: Length | None = None
    depth: Length | None = None


@attrs.frozen
class ClubBlock:
    """The ``club`` block: a preset and/or the head's own keys (docs/clubs.md)."""

    _what = "the club head"
    preset: Name | None = None
    mass: Mass | None = None
    inertia: InertiaSpec | None = None
    center_of_mass: CenterBlock | None = None
    loft: Angle | None = None
    lie: Angle | None = None
    bulge_radius: Length | None = None
    roll_radius: Length | None = None
    material: Name | None = None
    rigid: Flag | None = None
    youngs_modulus: Pressure | None = None
    poisson_ratio: Number | None = None
    restitution_gain: Number | None = None
    face_width: Length | None = None
    face_height: Length | None = None


@attrs.frozen
class StrikeBlock:
    """The ``strike`` block: the impact point from the face centre, towards the toe and up the face."""

    _what = "the impact point on the face"
    toe: Length | None = None
    high: Length | None = None


@attrs.frozen
class ContactBlock:
    """The ``contact`` block: the pair's friction and restitution."""

    _what = "the contact"
    friction: Number | None = None
    restitution: Number | None = None


@attrs.frozen
class ImpactBlock:
    """The ``impact`` block: speed and angle of the face relative to the ball, and the incoming spin."""

    _what = "the impact conditions"
    speed: Speed | None = None
    angle: Angle | None = None
    spin: Spin | None = None


@attrs.frozen
class HeadRotationBlock:
    """``delivery.head_rotation``: the head's angular velocity at first contact about its toe, up and target axes."""

    _what = "the head's angular velocity"
    toe: Rate | None = None
    up: Rate | None = None
    target: Rate | None = None


@attrs.frozen
class DeliveryBlock:
    """The ``delivery`` block: a golf delivery in the golfer's terms."""

    _what = "the golf delivery"
    club_speed: Speed | None = None
    path: Angle | None = None
    face_angle: Angle | None = None
    attack_angle: Angle | None = None
    dynamic_loft: Angle | None = None
    handedness: Name = Name("right")
    loft_at: Name = Name("contact")
    club_reference: Name = Name("centre_of_mass")
    spin_loft: Angle | None = None
    face_to_path: Angle | None = None
    head_rotation: HeadRotationBlock | None = None


@attrs.frozen
class ConditionsBlock:
    """The ``conditions`` block: the air a golf shot flies through (the ball-flight outputs only).

    Every value carries its unit (``"25 degC"``, ``"1013 hPa"``, ``"1600 m"``, ``"5 mph"``); a relative humidity is
    a fraction 0-1 or a percentage (``"60 %"``).
    """

    _what = "the air conditions"
    temperature: Temperature | None = None
    pressure: UnitPressure | None = None
    relative_humidity: Number | None = None
    altitude: UnitLength | None = None
    headwind: UnitSpeed | None = None
    crosswind: UnitSpeed | None = None


@attrs.frozen
class RangeBlock:
    """A sweep range; ``start`` and ``stop`` are converted by the sweep, which knows the swept field's dimension."""

    _what = "a sweep range"
    _key_of = "a sweep range"  # its path names the swept field, not the range
    start: Any = _field("start, stop and num of the range", attrs.NOTHING)
    stop: Any = _field("start, stop and num of the range", attrs.NOTHING)
    num: Count = _field("start, stop and num of the range", attrs.NOTHING)


@attrs.frozen
class StudyBlock:
    """The top-level keys of a study; each block is structured on its own, in the order its errors matter."""

    _what = "the study"
    name: Any = None
    description: Any = None
    ball: Any = None
    face: Any = None
    club: Any = None
    strike: Any = None
    contact: Any = None
    impact: Any = None
    delivery: Any = None
    conditions: Any = None
    sweep: Any = None
    models: Any = None
    outputs: Any = None
    plots: Any = None
    sensitivity: Any = None


@attrs.frozen
class PlotBlock:
    """A figure; its names are checked against the study's outputs and dimensions by the study."""

    _what = "a figure"
    name: Any = None
    y: Any = None
    x: Any = None
    select: Any = None
    title: Any = None
    kind: Any = None
    xlim: Any = None
    measured: Any = None


@attrs.frozen
class SensitivityBlock:
    """The ``sensitivity`` block; its values are checked by :func:`impactlab.study.sensitivity.parse_sensitivity`,
    which knows the study's models and scene."""

    _what = "the sensitivity block"
    _key_of = "the sensitivity block"
    method: Any = None
    samples: Any = None
    seed: Any = None
    parameters: Any = None
    choices: Any = None
    models: Any = None
    levels: Any = None


@attrs.frozen
class ParameterRangeBlock:
    """One parameter of a sensitivity study: ``{low, high}`` or ``{spread}`` (+- around each case's value),
    converted by the sensitivity parser with the parameter's dimension."""

    _what = "a parameter range: {low, high} or {spread} (+- around each case's value)"
    _key_of = "a parameter range"
    low: Any = None
    high: Any = None
    spread: Any = None


BLOCKS = (StudyBlock, BallBlock, RestitutionBlock, FaceBlock, InertiaBlock, CenterBlock, ClubBlock, StrikeBlock,
          ContactBlock, ImpactBlock, DeliveryBlock, ConditionsBlock, RangeBlock, PlotBlock, SensitivityBlock,
          ParameterRangeBlock)


def keys_of(cls: type) -> tuple[str, ...]:
    """The keys a block accepts, in the order the study format lists them.

    Parameters
    ----------
    cls : type
        A block class of this module.

    Returns
    -------
    tuple of str
    """
    return tuple(field.name for field in attrs.fields(cls))


def _quantity_hook(dimension: str):
    def structure(value, _):
        if isinstance(value, SI):
            return float(value)
        return to_si(value, dimension)
    return structure


def _unit_required_hook(dimension: str):
    """A quantity whose unit must be written: a bare number is refused, its unit never guessed."""
    def structure(value, _):
        if isinstance(value, SI):
            return float(value)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            example = {"temperature": "15 degC", "pressure": "1013 hPa", "length": "1600 m", "speed": "5 mph"}
            raise FieldError("", f"{DIMENSIONS_WORDS[dimension]} with its unit, e.g. '{example[dimension]}' (a bare "
                                 "number's unit is never guessed)", value)
        return to_si(value, dimension)
    return structure


DIMENSIONS_WORDS = {"temperature": "a temperature", "pressure": "a pressure", "length": "a length",
                    "speed": "a speed"}


def _inverse_speed(value, _) -> float:
    if isinstance(value, SI):
        return float(value)
    return to_si(value, "inverse_speed")


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
def _converter() -> Converter:
    """The converter of study blocks, made once (it generates one structuring function per block)."""
    converter = Converter()
    for type_, dimension in _DIMENSIONS.items():
        converter.register_structure_hook(type_, _quantity_hook(dimension))
    for type_, dimension in _WITH_UNIT.items():
        converter.register_structure_hook(type_, _unit_required_hook(dimension))
    hooks: tuple[tuple[Any, Any], ...] = ((InverseSpeed, _inverse_speed), (Flag, _flag), (Count, _count),
                                          (Name, lambda v, _: v), (Restitution, _restitution),
                                          (InertiaSpec, _inertia_spec), (Rate, lambda v, _: rate_with_unit(v)))
    for type_, hook in hooks:
        converter.register_structure_hook(type_, hook)
    converter.register_structure_hook_factory(lambda t: getattr(t, "__origin__", None) is list,
                                              lambda t: _list_hook(t, converter))
    converter.register_structure_hook_factory(lambda t: t in BLOCKS, lambda t: _block_hook(t, converter))
    converter.register_structure_hook_factory(_is_optional, lambda t: _optional_hook(t, converter))
    return converter


@functools.cache
def _hook(cls):
    """The structuring function of a block (generated on first use)."""
    return _converter().get_structure_hook(cls)


def lookup(document: Any, path: tuple) -> Any:
    """The node at ``path`` in a document, or None where there is none."""
    node = document
    for part in path:
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
        raise _field_error(exc, value, path, (), cls, None) from None


def _step(exc) -> tuple:
    """The path step a cattrs note puts on an error: an attribute name or a list index."""
    for note in getattr(exc, "__notes__", ()):
        if isinstance(note, AttributeValidationNote):
            return (note.name,)
        if isinstance(note, IterableValidationNote):
            return (note.index,)
    return ()


def _field_error(exc, value, where: str, steps: tuple, cls, name: str | None) -> FieldError:
    """The FieldError of the first failure in a cattrs error tree, at ``where`` + ``steps``."""
    if isinstance(exc, BaseValidationError):
        # unknown keys first, as before cattrs: a misspelt key also leaves its field missing
        first = min(exc.exceptions, key=lambda e: not isinstance(e, ForbiddenExtraKeysError))
        step = _step(first)
        return _field_error(first, value, where, steps + step, exc.cl,
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


__all__ = ["structure", "keys_of", "lookup", "SI", "BallBlock", "RestitutionBlock", "FaceBlock", "InertiaBlock",
           "CenterBlock", "ClubBlock", "StrikeBlock", "ContactBlock", "ImpactBlock", "DeliveryBlock", "ConditionsBlock",
           "RangeBlock",
           "StudyBlock", "PlotBlock", "SensitivityBlock", "ParameterRangeBlock",
           "Length", "Mass", "Pressure", "Speed", "Angle", "Spin", "Inertia", "Number",
           "InverseSpeed", "Flag", "Count", "Name"]
