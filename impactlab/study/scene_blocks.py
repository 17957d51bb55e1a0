"""The scene blocks of a study (ball, face, club, strike, contact, impact, delivery) read into value objects.

Split from :mod:`impactlab.study.core`, which reads the rest (sweeps, models, outputs, plots) and
re-exports these builders. Each block is first structured by :mod:`impactlab.study.schema` (keys, kinds and
units of its values); the builders here add what a schema cannot say: presets and their overrides, keys
required together or excluding each other, choices from a table. Every error is a FieldError naming the
field path.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator, Mapping
from contextvars import ContextVar
from typing import Any

import attrs

from impactlab.scene.catalogue import club_preset
from impactlab.scene.clubs import INERTIA_COMPONENTS, ClubHead, Strike
from impactlab.errors import FieldError
from impactlab.scene.materials import (
    MATERIAL_PRESETS, RESTITUTION_LAWS, SURFACE_FIELDS, Ball, Face, Material, RestitutionLaw, ball_preset,
    face_preset, face_surface,
)
from impactlab.physics.contact import CLUB_REFERENCES
from impactlab.scene.core import HANDEDNESS, LOFT_AT, Contact, Delivery, Impact, Scene
from impactlab.scene.flight import Conditions
from impactlab.study.schema import (BallBlock, CenterBlock, ClubBlock, ConditionsBlock, ContactBlock, DeliveryBlock,
                                    FaceBlock, ImpactBlock, RestitutionBlock, StrikeBlock, SurfaceBlock)
from impactlab.study.structuring import structure


def _construct(cls, where: str, **kwargs):
    try:
        return cls(**kwargs)
    except FieldError as exc:
        raise exc.at(prefix=where) from None


def _material(block, path: str, base: Material | None) -> Material | None:
    """The material of a block's youngs_modulus + poisson_ratio (both, or one over ``base``), else ``base``."""
    modulus, ratio = block.youngs_modulus, block.poisson_ratio
    if modulus is None and ratio is None:
        return base
    if base is not None:
        modulus = base.youngs_modulus if modulus is None else modulus
        ratio = base.poisson_ratio if ratio is None else ratio
    if modulus is None:
        raise FieldError(f"{path}.youngs_modulus", "a Young's modulus together with poisson_ratio", "nothing")
    if ratio is None:
        raise FieldError(f"{path}.poisson_ratio", "a Poisson ratio together with youngs_modulus", "nothing")
    material = _construct(Material, path, youngs_modulus=modulus, poisson_ratio=ratio)
    return attrs.evolve(material, name=base.name if base else "", source=base.source if base else "")


def _preset(block, path: str, lookup, default):
    """The preset the block names (its errors at ``path.preset``), or ``default`` where it names none."""
    if block.preset is None:
        return default
    try:
        return lookup(block.preset)
    except FieldError as exc:
        raise exc.at(prefix=path) from None


def _given(block, base, keys: tuple[str, ...], defaults: Mapping) -> dict:
    """Each key as the block gives it, else as ``base`` (a preset) has it, else its default (left out if none)."""
    fields = {}
    for key in keys:
        value = getattr(block, key)
        if value is None:
            value = getattr(base, key) if base is not None else defaults.get(key)
        if value is not None:
            fields[key] = value
    return fields


def build_ball(value: Any, path: str = "ball") -> Ball:
    """A ball from a study block: a preset, its keys overridden, or every key given."""
    block = structure(value, BallBlock, path)
    base = _preset(block, path, ball_preset, None)
    fields = _given(block, base, ("radius", "mass", "inertia_factor", "friction", "tangential_loss", "shear_strength",
                                  "cover_modulus"), {"inertia_factor": 0.4, "tangential_loss": 0.0})
    for key in ("cover_melt_rise", "cover_effusivity"):  # the friction law's cover data no study key sets
        if base is not None and getattr(base, key) is not None:
            fields[key] = getattr(base, key)
    for key in ("radius", "mass"):
        if key not in fields:
            raise FieldError(f"{path}.{key}", f"the ball {key} (or a preset)", "nothing")
    material = _material(block, path, base.material if base else None)
    restitution = (_restitution_law(block.restitution, f"{path}.restitution") if block.restitution is not None
                   else (base.restitution if base else None))
    return _construct(Ball, path, material=material, restitution=restitution, name=base.name if base else "",
                      source=base.source if base else "", **fields)


def _restitution_law(law, path: str) -> RestitutionLaw:
    """A restitution law from a number (constant) or a structured {law, value, reference_speed, slope, ...}."""
    if not isinstance(law, RestitutionBlock):
        return _construct(RestitutionLaw, path, kind="constant", value=law, source="given in the study")
    if law.law not in RESTITUTION_LAWS:
        raise FieldError(f"{path}.law", "a restitution law", law.law, choices=RESTITUTION_LAWS)
    fields = {key: getattr(law, key) for key in ("value", "reference_speed", "slope", "exponent")
              if getattr(law, key) is not None}
    fields.update({key: tuple(getattr(law, key)) for key in ("speeds", "values") if getattr(law, key) is not None})
    return _construct(RestitutionLaw, path, kind=law.law, source="given in the study", **fields)


def _surface(spec, path: str, base):
    """The face's surface a block gives: a preset's name, or a SurfaceBlock of a preset and/or fields over ``base``
    (the club preset's surface); ``base`` where the block gives none."""
    if spec is None:
        return base
    if isinstance(spec, str):
        return face_surface(spec, {}, base, path, preset_path=path)
    assert isinstance(spec, SurfaceBlock), "the schema structures a surface into a name or a SurfaceBlock"
    fields = {key: getattr(spec, key) for key in SURFACE_FIELDS if getattr(spec, key) is not None}
    return face_surface(spec.preset, fields, base, path)


def build_face(value: Any, path: str = "face") -> Face:
    """A face from a study block: a preset, rigid, or a material, with an optional head mass."""
    block = structure(value, FaceBlock, path)
    base = _preset(block, path, face_preset, Face())
    rigid = base.rigid if block.rigid is None else block.rigid
    material = _material(block, path, None if rigid else base.material)
    if rigid and material is not None:
        raise FieldError(f"{path}.rigid", "either rigid: true or youngs_modulus + poisson_ratio, not both",
                         "both")
    return _construct(Face, path, material=material, rigid=rigid, mass=base.mass if block.mass is None else block.mass,
                      name=base.name, source=base.source,
                      surface=_surface(block.surface, f"{path}.surface", base.surface))


def _inertia(value, path: str, base) -> tuple | None:
    """A head inertia tensor (toe, up, target axes) from a 3x3 list or a block of components or principal moments."""
    if value is None or isinstance(value, tuple):  # left out, or the tensor as a 3x3 list
        return value if value is not None else base
    given = [key for key in INERTIA_COMPONENTS if getattr(value, key) is not None]
    if value.principal is not None or value.axes is not None:
        if given:
            raise FieldError(f"{path}.{given[0]}", "either principal + axes or tensor components, not both", given[0])
        moments, axes = value.principal, value.axes
        if moments is None or len(moments) != 3:
            raise FieldError(f"{path}.principal", "three principal moments", moments)
        if (not isinstance(axes, list) or len(axes) != 3
                or not all(isinstance(row, list) and len(row) == 3 for row in axes)):
            raise FieldError(f"{path}.axes", "three unit axes [toe, up, target], one per principal moment", axes)
        try:
            return ClubHead.from_principal(moments, axes, mass=1.0, center_of_mass=(0.0, 0.0, 1.0)).inertia
        except FieldError as exc:
            raise exc.at(prefix=path) from None
        except (TypeError, ValueError):
            raise FieldError(f"{path}.axes", "numbers", axes) from None
    components = dict(zip(INERTIA_COMPONENTS, (0.0,) * 6))
    if base is not None:
        components.update(ClubHead(mass=1.0, inertia=base, center_of_mass=(0.0, 0.0, 1.0)).inertia_components())
    for key in ("toe", "up", "target"):
        if key not in given and base is None:
            raise FieldError(f"{path}.{key}", f"the moment of inertia about the {key} axis", "nothing")
    components.update({key: getattr(value, key) for key in given})
    c = components
    return ((c["toe"], c["toe_up"], c["toe_target"]), (c["toe_up"], c["up"], c["up_target"]),
            (c["toe_target"], c["up_target"], c["target"]))


def _center_of_mass(center: CenterBlock | None, path: str, base) -> tuple:
    """The centre of mass {toe, high, depth}: each key as given, else the preset's (toe and high default to 0)."""
    if center is None:
        if base is None:
            raise FieldError(path, "the centre of mass {toe, high, depth} or a preset", "nothing")
        return base.center_of_mass
    defaults = dict(zip(("toe", "high", "depth"), base.center_of_mass)) if base else {"toe": 0.0, "high": 0.0}
    fields = _given(center, None, ("toe", "high", "depth"), defaults)
    if "depth" not in fields:
        raise FieldError(f"{path}.depth", "the centre of mass's depth behind the face", "nothing")
    return fields["toe"], fields["high"], fields["depth"]


def build_club(value: Any, path: str = "club") -> ClubHead:
    """A club head from a study block: a preset, its keys overridden, or every key given."""
    block = structure(value, ClubBlock, path)
    base = _preset(block, path, club_preset, None)
    fields = _given(block, base, ("mass", "loft", "lie", "bulge_radius", "roll_radius", "restitution_gain",
                                       "face_width", "face_height"), {})
    if "mass" not in fields:
        raise FieldError(f"{path}.mass", "the head mass (or a preset)", "nothing")
    fields["inertia"] = _inertia(block.inertia, f"{path}.inertia", base.inertia if base else None)
    if fields["inertia"] is None:
        raise FieldError(f"{path}.inertia", "the head's inertia (toe, up, target moments) or a preset", "nothing")
    fields["center_of_mass"] = _center_of_mass(block.center_of_mass, f"{path}.center_of_mass", base)
    material = base.material if base else None
    if block.material is not None:
        if not isinstance(block.material, str) or block.material not in MATERIAL_PRESETS:
            raise FieldError(f"{path}.material", "a material preset", block.material, choices=MATERIAL_PRESETS)
        material = MATERIAL_PRESETS[block.material]
    material = None if block.rigid else _material(block, path, material)
    if block.rigid and (block.youngs_modulus is not None or block.material is not None):
        raise FieldError(f"{path}.rigid", "either rigid: true or a face material, not both", "both")
    return _construct(ClubHead, path, material=material, name=base.name if base else "",
                      source=base.source if base else "",
                      surface=_surface(block.surface, f"{path}.surface", base.surface if base else None), **fields)


def build_strike(value: Any, path: str = "strike") -> Strike:
    """Where on the club face the ball lands: toe and high from the face centre (0 where left out)."""
    block = structure(value, StrikeBlock, path)
    return _construct(Strike, path, **_given(block, None, ("toe", "high"), {}))


def build_contact(value: Any, path: str = "contact") -> Contact:
    """The pair's friction and restitution, each None where left out (the ball's then apply)."""
    block = structure(value, ContactBlock, path)
    return _construct(Contact, path, friction=block.friction, restitution=block.restitution)


def build_impact(value: Any, path: str = "impact") -> Impact:
    """Speed and angle of the face relative to the ball (both required), and the incoming spin."""
    block = structure(value, ImpactBlock, path)
    for key in ("speed", "angle"):
        if getattr(block, key) is None:
            raise FieldError(f"{path}.{key}", f"the impact {key}", "nothing")
    return _construct(Impact, path, speed=block.speed, angle=block.angle, spin=block.spin or 0.0)


def build_delivery(value: Any, path: str = "delivery") -> Delivery:
    """A golf delivery: club speed (required), path, face, attack and loft angles (or the spin loft, with the
    face to path), handedness, where the loft is the face's, the head's reference point and its rotation."""
    block = structure(value, DeliveryBlock, path)
    if block.club_speed is None:
        raise FieldError(f"{path}.club_speed", "the club speed", "nothing")
    for key, choices in (("handedness", HANDEDNESS), ("loft_at", LOFT_AT), ("club_reference", CLUB_REFERENCES)):
        if getattr(block, key) not in choices:
            raise FieldError(f"{path}.{key}", f"one of {', '.join(choices)}", getattr(block, key), choices=choices)
    rotation = block.head_rotation
    words = dict(handedness=block.handedness, loft_at=block.loft_at, club_reference=block.club_reference,
                 head_rotation=tuple(0.0 if rotation is None or getattr(rotation, axis) is None
                                     else getattr(rotation, axis) for axis in ("toe", "up", "target")))
    if block.spin_loft is None:
        if block.face_to_path is not None:
            if block.face_angle is not None:
                raise FieldError(f"{path}.face_to_path", "either face_angle or face_to_path (face angle - path)",
                                 "both")
            block = attrs.evolve(block, face_angle=(block.path or 0.0) + block.face_to_path)
        angles = _given(block, None, ("path", "face_angle", "attack_angle", "dynamic_loft"), {})
        return _construct(Delivery, path, club_speed=block.club_speed, **angles, **words)
    angles = _given(block, None, ("path", "face_angle", "attack_angle", "dynamic_loft", "face_to_path"), {})
    try:
        return Delivery.from_spin_loft(block.club_speed, block.spin_loft, **angles, **words)
    except FieldError as exc:
        raise exc.at(prefix=path) from None


def build_conditions(value):
    """The air of a ``conditions`` block (units required), or None when the study has none (the standard air)."""
    if value is None:
        return None
    block = structure(value, ConditionsBlock, "conditions")
    given = {key: getattr(block, key) for key in attrs.fields_dict(ConditionsBlock) if getattr(block, key) is not None}
    return _construct(Conditions, "conditions", **given)


def build_scene(document: Mapping) -> Scene:
    """The scene a study document describes (without its sweep)."""
    scene = _build_scene(document)
    if "conditions" in document:
        scene = attrs.evolve(scene, conditions=_built(build_conditions, document["conditions"]))
    return scene


def _build_scene(document: Mapping) -> Scene:
    if "ball" not in document:
        raise FieldError("ball", "a ball: {preset: NAME} or radius, mass, ...", "nothing")
    ball, face, contact = (_built(build_ball, document["ball"]), _built(build_face, document.get("face")),
                           _built(build_contact, document.get("contact")))
    club, strike = None, Strike()
    if "club" in document:
        if "face" in document:
            raise FieldError("face", "either a face or a club (whose face it is), not both", "both")
        club = _built(build_club, document["club"])
        face = Scene.face_of(club)
    if "strike" in document:
        if club is None:
            raise FieldError("strike", "a club block to strike (a fixed or point-mass face has no off-centre)",
                             "no club")
        strike = _built(build_strike, document["strike"])
    if "delivery" in document:
        impact = structure(document.get("impact"), ImpactBlock, "impact")
        for key in ("speed", "angle"):
            if getattr(impact, key) is not None:
                raise FieldError(f"impact.{key}", "either a delivery or impact speed and angle, not both",
                                 document["impact"][key])
        return Scene.from_delivery(ball, face, contact, _built(build_delivery, document["delivery"]),
                                   impact.spin or 0.0, club, strike)
    if "impact" not in document:
        raise FieldError("impact", "impact conditions (speed and angle) or a delivery block", "nothing")
    return Scene(ball, face, contact, _built(build_impact, document["impact"]), club=club, strike=strike)


#: the blocks built inside :func:`reusing_blocks`: (builder, id(block)) -> (the block, what it made)
_BUILT: ContextVar[dict[tuple[Any, int], tuple[Any, Any]] | None] = ContextVar("impactlab_built_blocks", default=None)


@contextlib.contextmanager
def reusing_blocks() -> Iterator[None]:
    """Inside, a study block (the very object) is read into its value object once, then reused.

    A study's sweep checks its values on trial scenes that share every block but the swept one with the base scene,
    as the same objects: each shared block is then structured and validated once, not once per trial scene (a
    ball, face and contact are ~14 of a scene's ~23 us). The swept block is a new object, read with every check;
    so is each trial scene, with the checks across its blocks. The blocks must not change inside.
    """
    token = _BUILT.set({})
    try:
        yield
    finally:
        _BUILT.reset(token)


def _built(builder, value):
    """``builder(value)``, or inside :func:`reusing_blocks` what it made of this very object (a failure is not kept:
    it fails again)."""
    memo = _BUILT.get()
    if memo is None:
        return builder(value)
    key = (builder, id(value))  # per builder: an absent face and an absent contact are both None
    kept = memo.get(key)
    if kept is not None and kept[0] is value:  # the object is held in the memo, so its id is not reused
        return kept[1]
    made = builder(value)
    memo[key] = (value, made)
    return made
