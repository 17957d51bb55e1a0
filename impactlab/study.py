"""Study definitions: YAML (or a mapping) read into validated, frozen objects.

A study names a base scene (ball, face, contact, impact), sweeps over some of
its fields, the models to compare with their options, and the outputs wanted.
Every error names the file, the line and the path of the offending field,
what was expected, what was given and, where there are choices, the choices.

See docs/user-guide.md for the format.
"""

from __future__ import annotations

import copy
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import attrs
import numpy as np
import yaml

from .clubs import INERTIA_COMPONENTS, ClubHead, Strike, club_preset
from .errors import FieldError, StudyError
from .materials import MATERIAL_PRESETS, RESTITUTION_LAWS, Ball, Face, Material, RestitutionLaw, ball_preset, \
    face_preset
from .model import ImpactModel
from .registry import available, get_model
from .scene import HANDEDNESS, Contact, Delivery, Impact, Scene
from .units import to_si
from .vocabulary import DEFAULT_OUTPUTS, DIAGNOSTIC_OUTPUTS, INPUT_BY_PATH, INPUTS, MODEL_DIM, OUTPUTS, SCALAR
from .yaml_lines import line_of, load_yaml, parse_path

TOP_LEVEL_KEYS = ("name", "description", "ball", "face", "club", "strike", "contact", "impact", "delivery", "sweep",
                  "models", "outputs", "plots", "sensitivity")
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
SWEEP_RANGE_KEYS = ("start", "stop", "num")


@attrs.frozen
class SweepField:
    """A field set by a sweep: its study path, the model input it sets, its SI values, and its coordinate name."""

    path: str
    input: str
    values: tuple[float, ...]
    coord: str


@attrs.frozen
class SweepAxis:
    """One dimension of a study: one swept field, or several fields swept together (with optional labels)."""

    dim: str
    fields: tuple[SweepField, ...]
    labels: tuple[str, ...] | None = None

    @property
    def size(self) -> int:
        return len(self.fields[0].values)

    @property
    def grouped(self) -> bool:
        return len(self.fields) > 1 or self.labels is not None


@attrs.frozen
class ModelEntry:
    """A model to run in a study: its coordinate in the results, and the configured model."""

    id: str
    model: ImpactModel = attrs.field(eq=False)

    @property
    def name(self) -> str:
        return self.model.name


PLOT_KEYS = ("name", "y", "x", "select", "title", "kind")
PLOT_KINDS = ("lines", "history")


@attrs.frozen
class PlotSpec:
    """A figure a study declares: ``y`` against sweep dimension ``x`` (or time), lines per model and per other value."""

    name: str
    y: tuple[str, ...]
    x: str | None = None
    select: tuple[tuple[str, Any], ...] = ()
    title: str = ""
    kind: str = "lines"

    def as_dict(self) -> dict:
        return {"name": self.name, "y": list(self.y), "x": self.x, "select": dict(self.select), "title": self.title,
                "kind": self.kind}


@attrs.frozen
class Study:
    """A validated study.

    Attributes
    ----------
    name, description : str
    scene : Scene
        The base scene; sweeps replace some of its values.
    sweep : tuple of SweepAxis
        In the order given; the results' dimensions follow it.
    models : tuple of ModelEntry
    outputs : tuple of str
    source : str
        The study text (YAML), kept as provenance.
    file : str or None
    """

    name: str
    description: str
    scene: Scene
    sweep: tuple[SweepAxis, ...]
    models: tuple[ModelEntry, ...]
    outputs: tuple[str, ...]
    source: str = attrs.field(repr=False)
    file: str | None = None
    plots: tuple[PlotSpec, ...] = ()
    #: a sensitivity and model-form study (impactlab.sensitivity.SensitivitySpec), or None for a plain sweep
    sensitivity: Any = None

    @property
    def all_outputs(self) -> tuple[str, ...]:
        """The outputs asked for, then the stability report every result carries."""
        return self.outputs + tuple(name for name in DIAGNOSTIC_OUTPUTS if name not in self.outputs)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(axis.size for axis in self.sweep)

    @property
    def n_cases(self) -> int:
        return int(np.prod(self.shape, dtype=np.int64)) if self.sweep else 1


class _SI(float):
    """A value already converted to SI (sweeps substitute these into the document)."""


def load_study(source: Any, *, file: str | None = None) -> Study:
    """Read a study from a path, YAML text or a mapping.

    Parameters
    ----------
    source : str, os.PathLike or Mapping
        A path to a YAML file (``str`` ending in .yaml/.yml or a PathLike),
        YAML text, or the mapping itself.
    file : str, optional
        Name used in error messages when ``source`` is text or a mapping.

    Raises
    ------
    FieldError, StudyError
        With file, line and field path.
    """
    if isinstance(source, Study):
        return source
    lines: dict = {}
    if isinstance(source, Mapping):
        document = copy.deepcopy(dict(source))
        text = yaml.safe_dump(_plain(document), sort_keys=False)
        file = file or "<mapping>"
    else:
        if isinstance(source, os.PathLike) or (isinstance(source, str) and "\n" not in source
                                                and source.strip().endswith((".yaml", ".yml"))):
            path = Path(source)
            if not path.is_file():
                raise StudyError(f"{path}: no such study file")
            text = path.read_text(encoding="utf-8")
            file = file or str(path)
        elif isinstance(source, str):
            text = source
            file = file or "<text>"
        else:
            raise StudyError(f"a study is a path, YAML text or a mapping, got {type(source).__name__}")
        document, lines = load_yaml(text, file)
    try:
        return _build_study(document, text, file)
    except FieldError as exc:
        path = _document_path(exc.path)
        written = _lookup(document, path)
        about_a_key = bool(path) and exc.given == path[-1]
        if (not about_a_key and isinstance(written, (str, int, float)) and not isinstance(written, bool)
                and written != exc.given):
            # show what the user wrote, not the SI number it became
            exc = FieldError(exc.path, exc.expected, written, exc.choices)
        raise exc.at(file=file, line=line_of(lines, path)) from None


def _document_path(text: str) -> tuple:
    """Field path of an error -> path in the document ('sweep.impact.angle[2]' keeps 'impact.angle' whole)."""
    path = parse_path(text)
    if len(path) >= 3 and path[0] == "sweep" and isinstance(path[1], str) and isinstance(path[2], str):
        path = ("sweep", f"{path[1]}.{path[2]}") + path[3:]
    return path


def _lookup(document, path: tuple):
    node = document
    for part in path:
        try:
            node = node[part]
        except (KeyError, IndexError, TypeError):
            return None
    return node


def _plain(value):
    if isinstance(value, Mapping):
        return {str(key): _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


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


def build_ball(value, path: str = "ball") -> Ball:
    block = _require_mapping(value, path, BALL_KEYS, "the ball")
    base = None
    if "preset" in block:
        try:
            base = ball_preset(block["preset"])
        except FieldError as exc:
            raise exc.at(prefix=path) from None
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
    base = Face()
    if "preset" in block:
        try:
            base = face_preset(block["preset"])
        except FieldError as exc:
            raise exc.at(prefix=path) from None
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
    base = None
    if "preset" in block:
        try:
            base = club_preset(block["preset"])
        except FieldError as exc:
            raise exc.at(prefix=path) from None
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


def _sweep_values(path: str, spec, dimension: str) -> list[float]:
    where = f"sweep.{path}"
    if isinstance(spec, Mapping):
        for key in spec:
            if key not in SWEEP_RANGE_KEYS:
                raise FieldError(f"{where}.{key}", "a key of a sweep range", str(key), choices=SWEEP_RANGE_KEYS)
        missing = [key for key in SWEEP_RANGE_KEYS if key not in spec]
        if missing:
            raise FieldError(f"{where}.{missing[0]}", "start, stop and num of the range", "nothing")
        num = spec["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise FieldError(f"{where}.num", "a whole number of values >= 1", num)
        start = to_si(spec["start"], dimension, f"{where}.start")
        stop = to_si(spec["stop"], dimension, f"{where}.stop")
        return list(np.linspace(start, stop, num))
    if isinstance(spec, (list, tuple)):
        if not spec:
            raise FieldError(where, "a non-empty list of values", spec)
        return [to_si(item, dimension, f"{where}[{index}]") for index, item in enumerate(spec)]
    raise FieldError(where, "a list of values or {start, stop, num}", spec)


def _check_sweep_values(document: Mapping, where: str, fields: list[tuple[str, list[float]]]) -> None:
    """Every swept value (all fields of one index together) must make a valid scene, with the base's messages.

    Each field's validity is an interval with the other fields held (every validator of the vocabulary is a
    range check), so a scene is built only at the first index and at each field's smallest and largest value:
    O(1) scenes instead of one per value (10^5 swept values load in well under a second). Where one of those
    fails, or a value is not finite, every index is tried in order, so the message names the first bad index.
    """
    size = len(fields[0][1])
    candidates = {0}
    for _, values in fields:
        array = np.asarray(values, dtype=float)
        if not np.all(np.isfinite(array)):
            candidates = range(size)
            break
        candidates |= {int(np.argmin(array)), int(np.argmax(array))}
    try:
        for index in sorted(candidates):
            _build_swept_scene(document, fields, index)
    except FieldError:
        for index in range(size):
            try:
                _build_swept_scene(document, fields, index)
            except FieldError as exc:
                raise FieldError(f"{where}[{index}]", f"{exc.expected} (for {exc.path})", exc.given,
                                 exc.choices) from None
        raise  # pragma: no cover - a value that failed above fails again here


def _build_swept_scene(document: Mapping, fields: list[tuple[str, list[float]]], index: int) -> None:
    trial = dict(document)
    for path, values in fields:
        section, key = path.split(".")
        trial[section] = dict(trial.get(section) or {}, **{key: _SI(values[index])})
    build_scene(trial)


def _sweep_field_values(path: str, spec, where: str) -> tuple[str, list[float]]:
    if path not in INPUT_BY_PATH:
        raise FieldError(where, "a dotted path of a swept field", str(path), choices=INPUT_BY_PATH)
    name = INPUT_BY_PATH[path]
    return name, _sweep_values(path, spec, INPUTS[name].dimension)


#: inputs a club preset sets (a sweep over ``club.preset`` sets them all together)
CLUB_PRESET_INPUTS = ("club_mass", "club_inertia_toe", "club_inertia_up", "club_inertia_target", "club_inertia_toe_up",
                      "club_inertia_toe_target", "club_inertia_up_target", "club_cg_toe", "club_cg_high",
                      "club_cg_depth", "club_loft", "face_bulge_radius", "face_roll_radius", "face_youngs_modulus",
                      "face_poisson_ratio", "club_restitution_gain")


#: study path of a field set by a club preset sweep: "club.preset:" + the field's own path
PRESET_MARK = "club.preset:"


def _club_preset_fields(document: Mapping, names, where: str) -> list[tuple[str, str, list[float]]]:
    """The club inputs of each preset in ``names`` (with the study's other club keys applied), as sweep fields."""
    if not isinstance(names, list) or not names or not all(isinstance(name, str) for name in names) \
            or len(set(names)) != len(names):
        raise FieldError(where, "a list of distinct club preset names", names)
    if "club" not in document:
        raise FieldError(where, "a club block in the study to sweep the preset of", "no club")
    values = {name: [] for name in CLUB_PRESET_INPUTS}
    for index, preset in enumerate(names):
        trial = dict(document, club=dict(document.get("club") or {}, preset=preset))
        try:
            inputs = build_scene(trial).inputs()
        except FieldError as exc:
            raise FieldError(f"{where}[{index}]", f"{exc.expected} (for {exc.path})", exc.given, exc.choices) from None
        for name in CLUB_PRESET_INPUTS:
            values[name].append(inputs[name])
    return [(f"{PRESET_MARK}{INPUTS[name].path}", name, values[name]) for name in CLUB_PRESET_INPUTS]


def _build_sweep(document: Mapping) -> tuple[SweepAxis, ...]:
    sweep = document.get("sweep") or {}
    if not isinstance(sweep, Mapping):
        raise FieldError("sweep", "a mapping from dotted field paths (or dimension names) to values", sweep)
    raw_axes = []  # (dim or None, labels, [(path, input, values)])
    for key, spec in sweep.items():
        key = str(key)
        if key == "club.preset":  # a dimension "club" labelled by preset, setting every input of the head
            raw_axes.append(("club", tuple(spec) if isinstance(spec, list) else None,
                             _club_preset_fields(document, spec, f"sweep.{key}")))
            continue
        if "." in key or not isinstance(spec, Mapping) or set(spec) <= set(SWEEP_RANGE_KEYS):
            name, values = _sweep_field_values(key, spec, f"sweep.{key}")
            _check_sweep_values(document, f"sweep.{key}", [(key, values)])
            raw_axes.append((None, None, [(key, name, values)]))
            continue
        # a named dimension along which several fields change together
        if not key.isidentifier() or key in (MODEL_DIM, "time"):
            raise FieldError(f"sweep.{key}", "a dimension name (letters, digits, _; not model or time)", key)
        labels = spec.get("labels")
        fields = [(path, *_sweep_field_values(path, values, f"sweep.{key}.{path}"))
                  for path, values in spec.items() if path not in ("labels", "club.preset")]
        if "club.preset" in spec:
            fields += _club_preset_fields(document, spec["club.preset"], f"sweep.{key}.club.preset")
            labels = labels if labels is not None else spec["club.preset"]
        if not fields:
            raise FieldError(f"sweep.{key}", "at least one dotted field path with its values", "none")
        sizes = {len(values) for _, _, values in fields} | ({len(labels)} if isinstance(labels, list) else set())
        if labels is not None and (not isinstance(labels, list) or not all(isinstance(x, str) for x in labels)
                                   or len(set(labels)) != len(labels)):
            raise FieldError(f"sweep.{key}.labels", "a list of distinct names, one per value", labels)
        if len(sizes) != 1:
            raise FieldError(f"sweep.{key}", "lists of one length for every field (and labels)", sorted(sizes))
        _check_sweep_values(document, f"sweep.{key}", [(path, values) for path, _, values in fields
                                                         if not path.startswith(PRESET_MARK)])
        raw_axes.append((key, tuple(labels) if labels else None, fields))

    paths = [path for _, _, fields in raw_axes for path, _, _ in fields]
    repeated = sorted({path for path in paths if paths.count(path) > 1})
    swept_inputs = [(name, path) for _, _, fields in raw_axes for path, name, _ in fields]
    names = [name for name, _ in swept_inputs]
    twice = [path for name, path in swept_inputs if names.count(name) > 1 and not path.startswith(PRESET_MARK)]
    if twice and not repeated:
        raise FieldError(f"sweep.{twice[0]}", "each field swept at most once (a swept club preset sets it)",
                         "swept twice")
    if repeated:
        raise FieldError(f"sweep.{repeated[0]}", "each field swept at most once", "swept twice")
    short = [path.split(".")[-1] for path in paths if not path.startswith(PRESET_MARK)]
    taken = {dim for dim, _, _ in raw_axes if dim}

    def name_of(path):
        if path.startswith(PRESET_MARK):  # set by a club preset: named by its input, which never clashes
            own = path[len(PRESET_MARK):]
            return next(name for name in CLUB_PRESET_INPUTS if INPUTS[name].path == own)
        last = path.split(".")[-1]
        clash = short.count(last) > 1 or last in (MODEL_DIM, "time") or last in taken
        return path.replace(".", "_") if clash else last

    axes = []
    for dim, labels, fields in raw_axes:
        sweep_fields = tuple(SweepField(path, name, tuple(float(v) for v in values), name_of(path))
                             for path, name, values in fields)
        axes.append(SweepAxis(dim or sweep_fields[0].coord, sweep_fields, labels))
    return tuple(axes)


def _build_models(value) -> tuple[ModelEntry, ...]:
    if not isinstance(value, list) or not value:
        raise FieldError("models", "a non-empty list of models ({name: NAME, option: value})", value,
                         choices=available())
    entries, seen = [], {}
    for index, item in enumerate(value):
        where = f"models[{index}]"
        if isinstance(item, str):
            item = {"name": item}
        if not isinstance(item, Mapping) or "name" not in item:
            raise FieldError(where, "{name: MODEL, option: value, ...}", item, choices=available())
        options = {key: val for key, val in item.items() if key not in ("name", "id")}
        name = item["name"]
        models = available()
        if name not in models:
            raise FieldError(f"{where}.name", "a registered model", str(name), choices=models)
        try:
            model = get_model(name)(**options)
        except FieldError as exc:
            raise exc.at(prefix=where) from None
        entry_id = item.get("id", name)
        if not isinstance(entry_id, str) or not entry_id:
            raise FieldError(f"{where}.id", "a non-empty name for this entry in the results", entry_id)
        if entry_id in seen:
            raise FieldError(f"{where}.id" if "id" in item else f"{where}.name",
                             f"a name not used by models[{seen[entry_id]}]; give repeated models an id", entry_id)
        seen[entry_id] = index
        entries.append(ModelEntry(entry_id, model))
    return tuple(entries)


def _build_outputs(value) -> tuple[str, ...]:
    if value is None:
        return DEFAULT_OUTPUTS
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not value:
        raise FieldError("outputs", "a non-empty list of output names", value, choices=OUTPUTS)
    for index, name in enumerate(value):
        if name not in OUTPUTS:
            raise FieldError(f"outputs[{index}]", "an output name", str(name), choices=OUTPUTS)
    return tuple(dict.fromkeys(value))


def _build_study(document, text: str, file: str | None) -> Study:
    if not isinstance(document, Mapping):
        raise FieldError("", "a study mapping with keys name, ball, face, contact, impact, sweep, models, outputs",
                         type(document).__name__)
    _require_mapping(document, "", TOP_LEVEL_KEYS, "the study")
    default_name = Path(file).stem if file and not file.startswith("<") else "study"
    name = document.get("name", default_name)
    if not isinstance(name, str) or not name:
        raise FieldError("name", "a non-empty study name", name)
    description = document.get("description", "")
    if not isinstance(description, str):
        raise FieldError("description", "text", description)
    if "models" not in document:
        raise FieldError("models", "a list of models to run", "nothing", choices=available())
    scene = build_scene(document)  # the base scene first: its errors are its own, not a sweep's
    sweep = _build_sweep(document)
    outputs = _build_outputs(document.get("outputs"))
    models = _build_models(document["models"])
    sensitivity = None
    if "sensitivity" in document:
        from .sensitivity import parse_sensitivity

        sensitivity = parse_sensitivity(document["sensitivity"], [entry.id for entry in models], scene.inputs(),
                                        {field.input for axis in sweep for field in axis.fields})
    return Study(name=name, description=description, scene=scene, sweep=sweep,
                 models=models, outputs=outputs, source=text, file=file,
                 plots=_build_plots(document.get("plots"), sweep, outputs), sensitivity=sensitivity)


def _build_plots(value, sweep, outputs) -> tuple[PlotSpec, ...]:
    if value is None:
        return ()
    if not isinstance(value, list):
        raise FieldError("plots", "a list of figures ({name, y, x, select, title, kind})", value)
    dims = [axis.dim for axis in sweep]
    plots = []
    for index, item in enumerate(value):
        where = f"plots[{index}]"
        block = _require_mapping(item, where, PLOT_KEYS, "a figure")
        name = block.get("name", f"plot{index}")
        if not isinstance(name, str) or not name.replace("-", "_").isidentifier():
            raise FieldError(f"{where}.name", "a short file-name-safe name", name)
        wanted = block.get("y")
        wanted = [wanted] if isinstance(wanted, str) else wanted
        if not isinstance(wanted, list) or not wanted:
            raise FieldError(f"{where}.y", "an output name or a list of them", wanted, choices=outputs)
        for position, output in enumerate(wanted):
            if output not in outputs:
                raise FieldError(f"{where}.y[{position}]", "an output the study computes", output, choices=outputs)
        kind = block.get("kind", "lines")
        if kind not in PLOT_KINDS:
            raise FieldError(f"{where}.kind", "a kind of figure", kind, choices=PLOT_KINDS)
        x = block.get("x")
        scalar_outputs = [name for name in outputs if OUTPUTS[name].kind == SCALAR]
        if x is not None and x not in dims + scalar_outputs:
            raise FieldError(f"{where}.x", "a sweep dimension or a scalar output of the study", x,
                             choices=dims + scalar_outputs)
        select = block.get("select") or {}
        if not isinstance(select, Mapping):
            raise FieldError(f"{where}.select", "a mapping from dimension to value", select)
        for key in select:
            if key not in dims + [MODEL_DIM]:
                raise FieldError(f"{where}.select.{key}", "a sweep dimension or model", key,
                                 choices=dims + [MODEL_DIM])
        title = block.get("title", "")
        plots.append(PlotSpec(name, tuple(wanted), x, tuple(select.items()), str(title), kind))
    names = [plot.name for plot in plots]
    if len(set(names)) != len(names):
        raise FieldError("plots", "figures with distinct names", names)
    return tuple(plots)


__all__ = ["Study", "SweepAxis", "SweepField", "ModelEntry", "load_study", "build_scene"]
