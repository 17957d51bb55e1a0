"""Sweeps: a study's ``sweep:`` block read into axes of SI values, each value checked to make a valid scene.

A sweep axis is one swept field, or several fields swept together (optionally labelled, e.g. the clubs of a
bag, or ``club.preset`` setting every input of a club head at once). The study's cases are the Cartesian
product of its axes (:func:`impactlab.study.arrays.case_inputs` builds their arrays).
"""

from __future__ import annotations

from collections.abc import Mapping

import attrs
import numpy as np

from impactlab.errors import FieldError
from impactlab.study.limits import check_cases
from impactlab.study.scene_blocks import build_scene
from impactlab.study.schema import SI, RangeBlock, keys_of
from impactlab.study.structuring import structure
from impactlab.units import DIMENSIONS, EXAMPLE_UNITS, to_si
from impactlab.vocabulary import INPUT_BY_PATH, INPUTS, MODEL_DIM

SWEEP_RANGE_KEYS = keys_of(RangeBlock)


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
    #: a ``ball.preset`` sweep's balls, one per value: their restitution laws apply case by case
    balls: tuple | None = attrs.field(default=None, eq=False, repr=False)

    @property
    def size(self) -> int:
        """Number of values along this dimension."""
        return len(self.fields[0].values)

    @property
    def grouped(self) -> bool:
        """Whether several fields change together (or labels name the values): a dimension of its own name."""
        return len(self.fields) > 1 or self.labels is not None
def _sweep_values(path: str, spec, dimension: str) -> list[float]:
    where = f"sweep.{path}"
    if isinstance(spec, Mapping):
        block = structure(spec, RangeBlock, where)
        num = block.num
        check_cases(num, f"{where}.num")  # before the values are generated
        start = to_si(block.start, dimension, f"{where}.start")
        stop = to_si(block.stop, dimension, f"{where}.stop")
        if num > 1 and start == stop:
            raise FieldError(f"{where}", "a range whose start and stop differ (num values would all be equal)",
                             f"start = stop with num: {num}")
        if num == 1 and start != stop:  # linspace gives start alone: the stop written would be dropped silently
            raise FieldError(f"{where}.num", "2 or more values from start to stop (num: 1 keeps start and drops stop; "
                             "one value is a list of one, [start])", f"num: 1 from {block.start} to {block.stop}")
        return list(np.linspace(start, stop, num))
    if isinstance(spec, (list, tuple)):
        if not spec:
            raise FieldError(where, "a non-empty list of values", spec)
        check_cases(len(spec), where)
        return [to_si(item, dimension, f"{where}[{index}]") for index, item in enumerate(spec)]
    raise FieldError(where, "a list of values or {start, stop, num}", spec)


def _refuse_repeats(where: str, rows: list, written: list) -> None:
    """Two equal values of a dimension would make two cases with one coordinate value, silently."""
    first: dict = {}
    for index, row in enumerate(rows):
        if row in first:
            shown = written[index] if isinstance(written, list) and index < len(written) else row
            raise FieldError(f"{where}[{index}]", f"distinct values (this one repeats [{first[row]}])", shown)
        first[row] = index


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
            candidates = set(range(size))
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
                raise FieldError(f"{where}[{index}]", f"{exc.expected} (for {exc.path})",
                                 _with_unit(exc.path, exc.given), exc.choices) from None
        raise  # pragma: no cover - a value that failed above fails again here


def _with_unit(path: str | None, given):
    """A swept value refused, as the user reads it: a range's values are made in SI (1.5746 for 90.2 deg), and an
    SI number shown bare reads as the user's number in the user's unit."""
    name = INPUT_BY_PATH.get(path or "")
    dimension = INPUTS[name].dimension if name else None
    if isinstance(given, bool) or not isinstance(given, (float, int)) or dimension in (None, "dimensionless"):
        return given
    si_unit = DIMENSIONS[dimension][0]
    if dimension == "temperature":
        return f"{given - 273.15:.6g} degC ({given:.6g} K)"
    unit, size = EXAMPLE_UNITS[dimension]
    return f"{given / size:.6g} {unit}" + ("" if unit == si_unit else f" ({given:.6g} {si_unit})")


def _build_swept_scene(document: Mapping, fields: list[tuple[str, list[float]]], index: int) -> None:
    trial = dict(document)
    for path, values in fields:
        section, *inner, key = path.split(".")  # a nested field: delivery.head_rotation.up
        block = dict(trial.get(section) or {})
        trial[section] = block
        for part in inner:
            given = block.get(part)  # a surface named by its preset: that preset, the swept field over it
            block[part] = {"preset": given} if isinstance(given, str) else dict(given or {})
            block = block[part]
        block[key] = SI(values[index])
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
                      "face_poisson_ratio", "club_restitution_gain",
                      # the face's surface (friction_law: adhesion): a wedge swept beside a driver keeps its grooves
                      "face_roughness_slope", "face_roughness", "face_groove_land", "face_water_film",
                      "face_effusivity")


#: study path of a field set by a club preset sweep: "club.preset:" + the field's own path
PRESET_MARK = "club.preset:"
BALL_PRESET_MARK = "ball.preset:"
#: the sweep keys that set a whole block from a preset: the block, the mark of its fields
PRESET_SWEEPS = {"club.preset": ("club", PRESET_MARK), "ball.preset": ("ball", BALL_PRESET_MARK)}


def _ball_preset_inputs(document: Mapping) -> tuple[str, ...]:
    """Inputs a ball preset sets: the ball's own, and the pair's friction where the study's contact leaves it out."""
    own = tuple(name for name, spec in INPUTS.items() if spec.path.startswith("ball."))
    contact = document.get("contact") or {}
    return own + (() if isinstance(contact, Mapping) and contact.get("friction") is not None else ("friction",))


#: a ball's cover as the friction law sees it: inputs only some ball presets give
COVER_INPUTS = ("ball_shear_strength", "ball_cover_modulus", "ball_cover_melt_rise", "ball_cover_effusivity")


def friction_law_entry(models):
    """The first of a study's configured model entries whose friction law is not Coulomb's, or None.

    Such a law reads the ball's cover and the face's surface, which Coulomb friction never does; the sweep and the
    study's face check both ask this one question of the built entries.
    """
    return next((entry for entry in models if getattr(entry.model.options, "friction_law", "coulomb") != "coulomb"),
                None)


def _preset_fields(document: Mapping, key: str, names, where: str,
                   reads_cover: bool) -> tuple[list[tuple[str, str, list[float]]], list]:
    """The inputs of each preset in ``names`` of block ``club`` or ``ball`` (the study's other keys of that block
    applied), as sweep fields, and the scene of each preset (whose ball carries its restitution law);
    ``reads_cover``: whether a model's friction law reads the ball's cover."""
    block, mark = PRESET_SWEEPS[key]
    if not isinstance(names, list) or not names or not all(isinstance(name, str) for name in names) \
            or len(set(names)) != len(names):
        raise FieldError(where, f"a list of distinct {block} preset names", names)
    if block not in document:
        raise FieldError(where, f"a {block} block in the study to sweep the preset of", f"no {block}")
    wanted = CLUB_PRESET_INPUTS if block == "club" else _ball_preset_inputs(document)
    values: dict[str, list] = {name: [] for name in wanted}
    scenes = []
    for index, preset in enumerate(names):
        trial = dict(document, **{block: dict(document.get(block) or {}, preset=preset)})
        try:
            scene = build_scene(trial)
        except FieldError as exc:
            raise FieldError(f"{where}[{index}]", f"{exc.expected} (for {exc.path})", exc.given, exc.choices) from None
        inputs = scene.inputs()
        missing = [name for name in wanted if name not in inputs]
        if missing and block == "ball" and set(missing) <= set(COVER_INPUTS) and not reads_cover:
            # a ball without the friction law's cover data (surlyn_distance) beside one with it: nothing reads them
            # unless a model's friction_law does, so they are left out of the sweep rather than refused
            wanted = tuple(name for name in wanted if name not in COVER_INPUTS)
            values = {name: values[name] for name in wanted}
            missing = []
        if missing:
            law = (" (friction_law: adhesion reads the ball's cover: urethane_tour and two_piece_ionomer carry it)"
                   if set(missing) <= set(COVER_INPUTS) else "")
            raise FieldError(f"{where}[{index}]", f"a {block} preset that gives {INPUTS[missing[0]].path} like the "
                             f"others swept beside it{law}", preset)
        for name in wanted:
            values[name].append(inputs[name])
        scenes.append(scene)
    return [(f"{mark}{INPUTS[name].path}", name, values[name]) for name in wanted], scenes


def build_sweep(document: Mapping, models=()) -> tuple[SweepAxis, ...]:
    """The axes of a study's ``sweep:`` block (SI values), every value checked to make a valid scene; ``models``:
    the study's configured model entries (a ball preset sweep needs the cover's inputs only if one reads them)."""
    reads_cover = friction_law_entry(models) is not None
    sweep = document.get("sweep") or {}
    if not isinstance(sweep, Mapping):
        raise FieldError("sweep", "a mapping from dotted field paths (or dimension names) to values", sweep)
    raw_axes: list[tuple] = []  # (dim or None, labels, [(path, input, values)], balls or None)
    for key, spec in sweep.items():
        key = str(key)
        if key in PRESET_SWEEPS:  # a dimension "club" or "ball" labelled by preset, setting every input of it
            fields, scenes = _preset_fields(document, key, spec, f"sweep.{key}", reads_cover)
            raw_axes.append((PRESET_SWEEPS[key][0], tuple(spec), fields,
                             tuple(scene.ball for scene in scenes) if key == "ball.preset" else None))
            continue
        if "." in key or not isinstance(spec, Mapping) or set(spec) <= set(SWEEP_RANGE_KEYS):
            name, values = _sweep_field_values(key, spec, f"sweep.{key}")
            _refuse_repeats(f"sweep.{key}", values, spec)
            _check_sweep_values(document, f"sweep.{key}", [(key, values)])
            raw_axes.append((None, None, [(key, name, values)], None))
            continue
        # a named dimension along which several fields change together
        if not key.isidentifier() or key in (MODEL_DIM, "time"):
            raise FieldError(f"sweep.{key}", "a dimension name (letters, digits, _; not model or time)", key)
        labels = spec.get("labels")
        fields = [(path, *_sweep_field_values(path, values, f"sweep.{key}.{path}"))
                  for path, values in spec.items() if path != "labels" and path not in PRESET_SWEEPS]
        balls = None
        for preset_key in (name for name in PRESET_SWEEPS if name in spec):
            more, scenes = _preset_fields(document, preset_key, spec[preset_key], f"sweep.{key}.{preset_key}",
                                          reads_cover)
            fields += more
            labels = labels if labels is not None else spec[preset_key]
            if preset_key == "ball.preset":
                balls = tuple(scene.ball for scene in scenes)
        if not fields:
            raise FieldError(f"sweep.{key}", "at least one dotted field path with its values", "none")
        sizes = {len(values) for _, _, values in fields} | ({len(labels)} if isinstance(labels, list) else set())
        if labels is not None and (not isinstance(labels, list) or not all(isinstance(x, str) for x in labels)
                                   or len(set(labels)) != len(labels)):
            raise FieldError(f"sweep.{key}.labels", "a list of distinct names, one per value", labels)
        if len(sizes) != 1:
            raise FieldError(f"sweep.{key}", "lists of one length for every field (and labels)", sorted(sizes))
        if labels is None:  # fields changing together may repeat a value, but not a whole row
            _refuse_repeats(f"sweep.{key}", list(zip(*[values for _, _, values in fields])), [])
        _check_sweep_values(document, f"sweep.{key}", [(path, values) for path, _, values in fields
                                                         if not path.startswith(_MARKS)])
        raw_axes.append((key, tuple(labels) if labels else None, fields, balls))

    paths = [path for _, _, fields, _ in raw_axes for path, _, _ in fields]
    repeated = sorted({path for path in paths if paths.count(path) > 1})
    swept_inputs = [(name, path) for _, _, fields, _ in raw_axes for path, name, _ in fields]
    names = [name for name, _ in swept_inputs]
    twice = [path for name, path in swept_inputs if names.count(name) > 1 and not path.startswith(_MARKS)]
    if twice and not repeated:
        raise FieldError(f"sweep.{twice[0]}", "each field swept at most once (a swept preset sets it)",
                         "swept twice")
    if repeated:
        raise FieldError(f"sweep.{repeated[0]}", "each field swept at most once", "swept twice")
    short = [path.split(".")[-1] for path in paths if not path.startswith(_MARKS)]
    taken = {dim for dim, _, _, _ in raw_axes if dim}

    def name_of(path, name):
        if path.startswith(_MARKS):  # set by a preset: named by its input, which never clashes
            return name
        last = path.split(".")[-1]
        clash = short.count(last) > 1 or last in (MODEL_DIM, "time") or last in taken
        return path.replace(".", "_") if clash else last

    axes = []
    for dim, labels, fields, balls in raw_axes:
        sweep_fields = tuple(SweepField(path, name, tuple(float(v) for v in values), name_of(path, name))
                             for path, name, values in fields)
        axes.append(SweepAxis(dim or sweep_fields[0].coord, sweep_fields, labels, balls))
    return tuple(axes)


_MARKS = (PRESET_MARK, BALL_PRESET_MARK)
