"""The blocks of a study file as the user writes them: one frozen attrs class per block.

Each block of a study (``ball``, ``face``, ``club``, ``strike``...) has a frozen attrs class here whose fields
are the keys a user may write, typed by what they hold: a ``Length``, an ``Angle``, a ``Flag``...
:func:`impactlab.study.structuring.structure` turns a YAML mapping into such a block (every quantity through
:func:`impactlab.units.to_si` with its field's dimension, unknown keys refused, every field checked), and
a failure comes back as one :class:`~impactlab.errors.FieldError` at the dotted path of the offending key.

The blocks carry no physics: ``impactlab.study.scene_blocks`` resolves presets, overrides and mutual exclusions
from them into ``Ball``, ``ClubHead``, ``Scene``...
"""

from __future__ import annotations

from typing import Any, NewType

import attrs


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
#: an air temperature (the ball flight's conditions): '25 degC', '298 K'
Temperature = NewType("Temperature", float)
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
#: a face's surface for the friction law: a name of ``materials.FACE_SURFACES`` or a :class:`SurfaceBlock`
SurfaceSpec = NewType("SurfaceSpec", object)
#: a thermal effusivity sqrt(k rho c) with its unit ('8030 J/(m**2*K*s**0.5)')
Effusivity = NewType("Effusivity", float)
_DIMENSIONS = {Length: "length", Mass: "mass", Pressure: "pressure", Speed: "speed", Angle: "angle",
               Spin: "angular_speed", Inertia: "inertia", Number: "dimensionless", Temperature: "temperature",
               InverseSpeed: "inverse_speed", Effusivity: "effusivity"}


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
    shear_strength: Pressure | None = None
    cover_modulus: Pressure | None = None


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
class SurfaceBlock:
    """``club.surface`` (or ``face.surface``) as a mapping: a surface preset and/or its fields (docs/models.md)."""

    _what = "the face's surface"
    preset: Name | None = None
    roughness_slope: Number | None = None
    roughness: Length | None = None
    groove_land: Length | None = None
    water_film: Length | None = None
    effusivity: Effusivity | None = None


@attrs.frozen
class FaceBlock:
    """The ``face`` block: a preset, ``rigid``, a material and an optional head mass."""

    _what = "the face"
    preset: Name | None = None
    rigid: Flag | None = None
    youngs_modulus: Pressure | None = None
    poisson_ratio: Number | None = None
    mass: Mass | None = None
    surface: SurfaceSpec | None = None


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
    surface: SurfaceSpec | None = None


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
    toe: Spin | None = None
    up: Spin | None = None
    target: Spin | None = None


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
    pressure: Pressure | None = None
    relative_humidity: Number | None = None
    altitude: Length | None = None
    headwind: Speed | None = None
    crosswind: Speed | None = None


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
    #: scene fields plugins declare (entry-point group impactlab.inputs): {NAME: value with its unit}
    plugin: Any = None


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


BLOCKS = (StudyBlock, BallBlock, RestitutionBlock, SurfaceBlock, FaceBlock, InertiaBlock, CenterBlock, ClubBlock,
          StrikeBlock, ContactBlock, ImpactBlock, DeliveryBlock, ConditionsBlock, RangeBlock, PlotBlock,
          SensitivityBlock, ParameterRangeBlock)


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


__all__ = ["keys_of", "SI", "BallBlock", "RestitutionBlock", "SurfaceBlock", "FaceBlock", "InertiaBlock",
           "CenterBlock", "ClubBlock", "StrikeBlock", "ContactBlock", "ImpactBlock", "DeliveryBlock", "ConditionsBlock",
           "RangeBlock",
           "StudyBlock", "PlotBlock", "SensitivityBlock", "ParameterRangeBlock",
           "Length", "Mass", "Pressure", "Speed", "Angle", "Spin", "Inertia", "Number",
           "InverseSpeed", "Flag", "Count", "Name"]
