"""The scene blocks of a study (ball, face, club, strike, contact, impact, delivery) read into value objects.

Split from :mod:`impactlab.study`, which reads the rest (sweeps, models, outputs, plots) and
re-exports these builders. Every error is a FieldError naming the field path.
"""

from __future__ import annotations

from collections.abc import Mapping

import attrs

from .clubs import INERTIA_COMPONENTS, ClubHead, Strike, club_preset
from .errors import FieldError
from .materials import MATERIAL_PRESETS, RESTITUTION_LAWS, Ball, Face, Material, RestitutionLaw, ball_preset, \
    face_preset
from .scene import HANDEDNESS, Contact, Delivery, Impact, Scene
from .units import to_si

CLUB_KEYS = ("preset", "mass", "inertia", "center_of_mass", "loft", "lie", "bulge_radius", "roll_radius", "material",
             "rigid", "youngs_modulus", "poisson_ratio", "restitution_gain")
INERTIA_KEYS = ("toe", "up", "target", "toe_up", "toe_target", "up_target", "principal", "axes")
CENTER_KEYS = ("toe", "high", "depth")
STRIKE_KEYS = ("toe", "high")
DELIVERY_KEYS = ("club_speed", "path", "face_angle", "attack_angle", "dynamic_loft", "handedness")
BALL_KEYS = ("preset", "radius", "mass", "inertia_factor", "youngs_modulus", "poisson_ratio", "friction", "restitution",
             "tangential_loss")
FACE_KEYS = ("preset", "rigid", "youngs_modulus", "poisson_ratio", "mass")
CONTACT_KEYS = ("friction", "restitution")
IMPACT_KEYS = ("speed", "angle", "spin")


class _SI(float):
    """A value already converted to SI (sweeps substitute these into the document)."""


def _require_mapping(value, path: str, keys: tuple[str, ...], what: str) -> dict:
    if value is None:
        return {}
    if not isinstance(value, Mapping):
        raise FieldError(path, f"a mapping ({what}) with keys from: {', '.join(keys)}", value)
    for key in value:
        if key not in keys:
            raise FieldError(f"{path}.{key}" if path else str(key), f"a key of {path or 'the study'}", str(key),
                             choices=keys)
    return dict(value)


def _quantity(block: dict, key: str, dimension: str, path: str):
    value = block.get(key)
    if value is None:
        return None
    if isinstance(value, _SI):
        return float(value)
    return to_si(value, dimension, f"{path}.{key}")


def _construct(cls, where: str, **kwargs):
    try:
        return cls(**kwargs)
    except FieldError as exc:
        raise exc.at(prefix=where) from None


def _material(block: dict, path: str, base: Material | None) -> Material | None:
    modulus = _quantity(block, "youngs_modulus", "pressure", path)
    ratio = _quantity(block, "poisson_ratio", "dimensionless", path)
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


def _preset(block: dict, path: str, lookup, default):
    """The preset the block names (its errors at ``path.preset``), or ``default`` where it names none."""
    if "preset" not in block:
        return default
    try:
        return lookup(block["preset"])
    except FieldError as exc:
        raise exc.at(prefix=path) from None


def build_ball(value, path: str = "ball") -> Ball:
    block = _require_mapping(value, path, BALL_KEYS, "the ball")
    base = _preset(block, path, ball_preset, None)
    fields = {}
    for key in ("radius", "mass"):
        fields[key] = _quantity(block, key, "length" if key == "radius" else "mass", path)
        if fields[key] is None:
            if base is None:
                raise FieldError(f"{path}.{key}", f"the ball {key} (or a preset)", "nothing")
            fields[key] = getattr(base, key)
    inertia = _quantity(block, "inertia_factor", "dimensionless", path)
    fields["inertia_factor"] = inertia if inertia is not None else (base.inertia_factor if base else 0.4)
    material = _material(block, path, base.material if base else None)
    friction = _quantity(block, "friction", "dimensionless", path)
    fields["friction"] = friction if friction is not None else (base.friction if base else None)
    loss = _quantity(block, "tangential_loss", "dimensionless", path)
    fields["tangential_loss"] = loss if loss is not None else (base.tangential_loss if base else 0.0)
    fields["restitution"] = (_restitution_law(block["restitution"], f"{path}.restitution") if "restitution" in block
                             else (base.restitution if base else None))
    return _construct(Ball, path, material=material, name=base.name if base else "",
                      source=base.source if base else "", **fields)


RESTITUTION_KEYS = ("law", "value", "reference_speed", "slope", "exponent", "speeds", "values")


def _restitution_law(value, path: str) -> RestitutionLaw:
    """A restitution law from a number (constant) or a mapping {law, value, reference_speed, slope, ...}."""
    if not isinstance(value, Mapping):
        return _construct(RestitutionLaw, path, kind="constant", value=to_si(value, "dimensionless", path),
                          source="given in the study")
    block = _require_mapping(value, path, RESTITUTION_KEYS, "a restitution law")
    kind = block.get("law", "constant")
    if kind not in RESTITUTION_LAWS:
        raise FieldError(f"{path}.law", "a restitution law", kind, choices=RESTITUTION_LAWS)
    fields = {"kind": kind, "source": "given in the study"}
    for key, dimension in (("value", "dimensionless"), ("reference_speed", "speed"), ("exponent", "dimensionless")):
        if key in block:
            fields[key] = _quantity(block, key, dimension, path)
    if "slope" in block:  # de/dv: a number in s/m, or a string with units of inverse speed
        slope = block["slope"]
        fields["slope"] = _inverse_speed(slope, f"{path}.slope")
    for key, dimension in (("speeds", "speed"), ("values", "dimensionless")):
        if key in block:
            items = block[key]
            if not isinstance(items, list):
                raise FieldError(f"{path}.{key}", "a list", items)
            fields[key] = tuple(to_si(item, dimension, f"{path}.{key}[{i}]") for i, item in enumerate(items))
    return _construct(RestitutionLaw, path, **fields)


def _inverse_speed(value, path: str) -> float:
    """A slope de/dv: a bare number in s/m or a quantity with units of inverse speed (e.g. "-0.002 s/m")."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return float(value)
    try:
        from .units import registry

        quantity = registry().Quantity(str(value))
        return float(quantity.to("s/m").magnitude)
    except Exception:  # noqa: BLE001 - pint raises many kinds; the message says what was expected
        raise FieldError(path, "a slope de/dv in s/m (a number, or e.g. '-0.002 s/m')", value) from None


def build_face(value, path: str = "face") -> Face:
    block = _require_mapping(value, path, FACE_KEYS, "the face")
    base = _preset(block, path, face_preset, Face())
    rigid = block.get("rigid", base.rigid)
    if not isinstance(rigid, bool):
        raise FieldError(f"{path}.rigid", "true or false", rigid)
    material = _material(block, path, None if rigid else base.material)
    if rigid and material is not None:
        raise FieldError(f"{path}.rigid", "either rigid: true or youngs_modulus + poisson_ratio, not both",
                         "both")
    mass = _quantity(block, "mass", "mass", path)
    return _construct(Face, path, material=material, rigid=rigid, mass=base.mass if mass is None else mass,
                      name=base.name, source=base.source)


def _inertia(value, path: str, base) -> tuple | None:
    """A head inertia tensor (toe, up, target axes) from a mapping of components or of principal moments and axes."""
    if value is None:
        return base
    if isinstance(value, list):
        try:
            rows = [[to_si(item, "inertia", f"{path}[{i}][{j}]") for j, item in enumerate(row)]
                    for i, row in enumerate(value)]
        except TypeError:
            raise FieldError(path, "a 3x3 list of lists (the tensor in toe, up, target axes)", value) from None
        return tuple(tuple(row) for row in rows)
    block = _require_mapping(value, path, INERTIA_KEYS, "the head's inertia about its centre of mass")
    if "principal" in block or "axes" in block:
        extra = [key for key in block if key not in ("principal", "axes")]
        if extra:
            raise FieldError(f"{path}.{extra[0]}", "either principal + axes or tensor components, not both", extra[0])
        moments, axes = block.get("principal"), block.get("axes")
        if not isinstance(moments, list) or len(moments) != 3:
            raise FieldError(f"{path}.principal", "three principal moments", moments)
        values = [to_si(item, "inertia", f"{path}.principal[{i}]") for i, item in enumerate(moments)]
        if (not isinstance(axes, list) or len(axes) != 3
                or not all(isinstance(row, list) and len(row) == 3 for row in axes)):
            raise FieldError(f"{path}.axes", "three unit axes [toe, up, target], one per principal moment", axes)
        try:
            return ClubHead.from_principal(values, axes, mass=1.0, center_of_mass=(0.0, 0.0, 1.0)).inertia
        except FieldError as exc:
            raise exc.at(prefix=path) from None
        except (TypeError, ValueError):
            raise FieldError(f"{path}.axes", "numbers", axes) from None
    components = dict(zip(INERTIA_COMPONENTS, (0.0,) * 6))
    if base is not None:
        components.update(ClubHead(mass=1.0, inertia=base, center_of_mass=(0.0, 0.0, 1.0)).inertia_components())
    for key in ("toe", "up", "target"):
        if key not in block and base is None:
            raise FieldError(f"{path}.{key}", f"the moment of inertia about the {key} axis", "nothing")
    for key in INERTIA_COMPONENTS:
        if key in block:
            components[key] = _quantity(block, key, "inertia", path)
    c = components
    return ((c["toe"], c["toe_up"], c["toe_target"]), (c["toe_up"], c["up"], c["up_target"]),
            (c["toe_target"], c["up_target"], c["target"]))


def build_club(value, path: str = "club") -> ClubHead:
    """A club head from a study block: a preset, its keys overridden, or every key given."""
    block = _require_mapping(value, path, CLUB_KEYS, "the club head")
    base = _preset(block, path, club_preset, None)
    fields = {}
    for key, dimension in (("mass", "mass"), ("loft", "angle"), ("lie", "angle"), ("bulge_radius", "length"),
                           ("roll_radius", "length"), ("restitution_gain", "dimensionless")):
        given = _quantity(block, key, dimension, path)
        if given is None and base is not None:
            given = getattr(base, key)
        if given is not None:
            fields[key] = given
    if "mass" not in fields:
        raise FieldError(f"{path}.mass", "the head mass (or a preset)", "nothing")
    fields["inertia"] = _inertia(block.get("inertia"), f"{path}.inertia", base.inertia if base else None)
    if fields["inertia"] is None:
        raise FieldError(f"{path}.inertia", "the head's inertia (toe, up, target moments) or a preset", "nothing")
    center = block.get("center_of_mass")
    if center is None:
        if base is None:
            raise FieldError(f"{path}.center_of_mass", "the centre of mass {toe, high, depth} or a preset", "nothing")
        fields["center_of_mass"] = base.center_of_mass
    else:
        center = _require_mapping(center, f"{path}.center_of_mass", CENTER_KEYS, "the centre of mass")
        defaults = dict(zip(CENTER_KEYS, base.center_of_mass)) if base else {"toe": 0.0, "high": 0.0}
        values = []
        for key in CENTER_KEYS:
            given = _quantity(center, key, "length", f"{path}.center_of_mass")
            if given is None and key not in defaults:
                raise FieldError(f"{path}.center_of_mass.{key}", "the centre of mass's depth behind the face",
                                 "nothing")
            values.append(defaults[key] if given is None else given)
        fields["center_of_mass"] = tuple(values)
    material = base.material if base else None
    if "material" in block:
        name = block["material"]
        if name not in MATERIAL_PRESETS:
            raise FieldError(f"{path}.material", "a material preset", name, choices=MATERIAL_PRESETS)
        material = MATERIAL_PRESETS[name]
    rigid = block.get("rigid", False)
    if not isinstance(rigid, bool):
        raise FieldError(f"{path}.rigid", "true or false", rigid)
    material = None if rigid else _material(block, path, material)
    if rigid and ("youngs_modulus" in block or "material" in block):
        raise FieldError(f"{path}.rigid", "either rigid: true or a face material, not both", "both")
    return _construct(ClubHead, path, material=material, name=base.name if base else "",
                      source=base.source if base else "", **fields)


def build_strike(value, path: str = "strike") -> Strike:
    block = _require_mapping(value, path, STRIKE_KEYS, "the impact point on the face")
    fields = {key: _quantity(block, key, "length", path) for key in STRIKE_KEYS}
    return _construct(Strike, path, **{key: v for key, v in fields.items() if v is not None})


def build_contact(value, path: str = "contact") -> Contact:
    block = _require_mapping(value, path, CONTACT_KEYS, "the contact")
    return _construct(Contact, path, friction=_quantity(block, "friction", "dimensionless", path),
                      restitution=_quantity(block, "restitution", "dimensionless", path))


def build_impact(value, path: str = "impact") -> Impact:
    block = _require_mapping(value, path, IMPACT_KEYS, "the impact conditions")
    fields = {}
    for key, dimension in (("speed", "speed"), ("angle", "angle")):
        fields[key] = _quantity(block, key, dimension, path)
        if fields[key] is None:
            raise FieldError(f"{path}.{key}", f"the impact {key}", "nothing")
    spin = _quantity(block, "spin", "angular_speed", path)
    return _construct(Impact, path, spin=0.0 if spin is None else spin, **fields)


def build_delivery(value, path: str = "delivery") -> Delivery:
    block = _require_mapping(value, path, DELIVERY_KEYS, "the golf delivery")
    speed = _quantity(block, "club_speed", "speed", path)
    if speed is None:
        raise FieldError(f"{path}.club_speed", "the club speed", "nothing")
    angles = {key: _quantity(block, key, "angle", path) for key in DELIVERY_KEYS[1:5]}
    angles = {key: value for key, value in angles.items() if value is not None}
    handedness = block.get("handedness", "right")
    if handedness not in HANDEDNESS:
        raise FieldError(f"{path}.handedness", "the golfer's handedness", handedness, choices=HANDEDNESS)
    return _construct(Delivery, path, club_speed=speed, handedness=handedness, **angles)


def build_scene(document: Mapping) -> Scene:
    """The scene a study document describes (without its sweep)."""
    if "ball" not in document:
        raise FieldError("ball", "a ball: {preset: NAME} or radius, mass, ...", "nothing")
    ball, face, contact = (build_ball(document["ball"]), build_face(document.get("face")),
                           build_contact(document.get("contact")))
    club, strike = None, Strike()
    if "club" in document:
        if "face" in document:
            raise FieldError("face", "either a face or a club (whose face it is), not both", "both")
        club = build_club(document["club"])
        face = Scene.face_of(club)
    if "strike" in document:
        if club is None:
            raise FieldError("strike", "a club block to strike (a fixed or point-mass face has no off-centre)",
                             "no club")
        strike = build_strike(document["strike"])
    if "delivery" in document:
        impact = _require_mapping(document.get("impact"), "impact", IMPACT_KEYS, "the impact conditions")
        for key in ("speed", "angle"):
            if key in impact:
                raise FieldError(f"impact.{key}", "either a delivery or impact speed and angle, not both",
                                 impact[key])
        spin = _quantity(impact, "spin", "angular_speed", "impact")
        return Scene.from_delivery(ball, face, contact, build_delivery(document["delivery"]),
                                   0.0 if spin is None else spin, club, strike)
    if "impact" not in document:
        raise FieldError("impact", "impact conditions (speed and angle) or a delivery block", "nothing")
    return Scene(ball, face, contact, build_impact(document["impact"]), club=club, strike=strike)
