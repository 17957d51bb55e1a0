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

from impactlab.errors import FieldError, StudyError
from impactlab.study.limits import check_cases
from impactlab.model.base import ImpactModel
from impactlab.model.registry import available, get_model
from impactlab.scene.core import Scene
# the scene blocks live in study_scene; their builders stay importable from here
from impactlab.study.scene_blocks import (build_ball, build_club, build_contact, build_delivery, build_face,  # noqa: F401
                          build_impact, build_scene, build_strike)
from impactlab.study.schema import (SI, PlotBlock, RangeBlock, StudyBlock, keys_of, lookup, rate_with_unit,
                                    structure)
from impactlab.units import to_si
from impactlab.vocabulary import (DEFAULT_OUTPUTS, DIAGNOSTIC_OUTPUTS, INPUT_BY_PATH, INPUTS, MODEL_DIM, OUTPUTS,
                                  SCALAR_OUTPUTS, check_output_names)
from impactlab.study.yaml_lines import line_of, load_yaml, parse_path, read_text_file

TOP_LEVEL_KEYS = keys_of(StudyBlock)
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


@attrs.frozen
class ModelEntry:
    """A model to run in a study: its coordinate in the results, and the configured model."""

    id: str
    model: ImpactModel = attrs.field(eq=False)

    @property
    def name(self) -> str:
        """The registry name of the entry's model (its ``id`` may differ)."""
        return self.model.name


PLOT_KEYS = keys_of(PlotBlock)
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
    #: a zoomed view: [low, high] of the horizontal axis, in its display units (where the interesting region is small)
    xlim: tuple[float, float] | None = None
    #: names of shipped measured datasets (impactlab.data.validation) drawn beside the curves, with their error bars
    measured: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """The figure's specification as plain data (stored with the results, read back by ``impactlab plot``)."""
        return {"name": self.name, "y": list(self.y), "x": self.x, "select": dict(self.select), "title": self.title,
                "kind": self.kind, "xlim": list(self.xlim) if self.xlim else None, "measured": list(self.measured)}


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
    #: a sensitivity and model-form study (impactlab.data.sensitivity.SensitivitySpec), or None for a plain sweep
    sensitivity: Any = None

    @property
    def all_outputs(self) -> tuple[str, ...]:
        """The outputs asked for, then the stability report every result carries."""
        return self.outputs + tuple(name for name in DIAGNOSTIC_OUTPUTS if name not in self.outputs)

    @property
    def shape(self) -> tuple[int, ...]:
        """Sizes of the sweep dimensions, in order."""
        return tuple(axis.size for axis in self.sweep)

    @property
    def n_cases(self) -> int:
        """Number of cases: the product of the sweep sizes (1 without a sweep)."""
        return int(np.prod(self.shape, dtype=np.int64)) if self.sweep else 1



def load_study(source: Any, *, file: str | None = None) -> Study:
    """Read a study from a path, YAML text or a mapping.

    Parameters
    ----------
    source : str, os.PathLike or Mapping
        A path to a YAML file (``str`` ending in .yaml/.yml or a PathLike),
        YAML text, or the mapping itself. In a mapping, a ``models`` entry may
        also be a model class or a configured model instance (alone, or as the
        ``name`` of an entry with an ``id``).
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
        document = copy.deepcopy(dict(source), _models_as_given(source))
        text = yaml.safe_dump(_plain(document), sort_keys=False)
        file = file or "<mapping>"
    else:
        if isinstance(source, os.PathLike) or (isinstance(source, str) and _names_a_file(source)):
            path = Path(source)
            text = read_text_file(path)
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
        written = lookup(document, path)
        about_a_key = bool(path) and exc.given == path[-1]
        if (not about_a_key and isinstance(written, (str, int, float)) and not isinstance(written, bool)
                and written != exc.given):
            # show what the user wrote, not the SI number it became
            exc = FieldError(exc.path, exc.expected, written, exc.choices)
        raise exc.at(file=file, line=line_of(lines, path)) from None


def _models_as_given(source: Mapping) -> dict:
    """A deepcopy memo that keeps the model instances of a Python study: configured objects, used as they are."""
    entries = source.get("models")
    given = [entry.get("name") if isinstance(entry, Mapping) else entry
             for entry in (entries if isinstance(entries, list) else [])]
    return {id(model): model for model in given if isinstance(model, ImpactModel)}


def _names_a_file(text: str) -> bool:
    """Whether a one-line string is a path (ends in .yaml/.yml in any case, or names something that exists)."""
    if "\n" in text:
        return False
    if text.strip().lower().endswith((".yaml", ".yml")):
        return True
    try:
        return Path(text).exists() and ":" not in text  # 'name: x' is YAML text even if such a file existed
    except (OSError, ValueError):
        return False


def _document_path(text: str) -> tuple:
    """Field path of an error -> path in the document ('sweep.impact.angle[2]' keeps 'impact.angle' whole)."""
    path = parse_path(text)
    if len(path) >= 3 and path[0] == "sweep" and isinstance(path[1], str) and isinstance(path[2], str):
        path = ("sweep", f"{path[1]}.{path[2]}") + path[3:]
    return path


def _plain(value):
    """A Python study as plain data for its YAML text (the provenance a result file keeps)."""
    if isinstance(value, ImpactModel):  # a configured model: its name and every option
        return {"name": value.name, **value.options_dict()}
    if isinstance(value, type) and issubclass(value, ImpactModel):
        return value.name
    if isinstance(value, Mapping):
        if isinstance(value.get("name"), ImpactModel):  # {name: MawModel(...), id: ...}
            return {**_plain(value["name"]), **{str(key): _plain(item) for key, item in value.items() if key != "name"}}
        return {str(key): _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(item) for item in value]
    if isinstance(value, (np.floating, np.integer)):
        return value.item()
    return value


def _sweep_values(path: str, spec, dimension: str) -> list[float]:
    where = f"sweep.{path}"
    if isinstance(spec, Mapping):
        block = structure(spec, RangeBlock, where)
        num = block.num
        check_cases(num, f"{where}.num")  # before the values are generated
        convert = ((lambda value, _, at: rate_with_unit(value, at)) if path.startswith("delivery.head_rotation.")
                   else to_si)
        start = convert(block.start, dimension, f"{where}.start")
        stop = convert(block.stop, dimension, f"{where}.stop")
        if num > 1 and start == stop:
            raise FieldError(f"{where}", "a range whose start and stop differ (num values would all be equal)",
                             f"start = stop with num: {num}")
        return list(np.linspace(start, stop, num))
    if isinstance(spec, (list, tuple)):
        if not spec:
            raise FieldError(where, "a non-empty list of values", spec)
        check_cases(len(spec), where)
        if path.startswith("delivery.head_rotation."):  # a turning rate carries its unit (deg/s or rpm?)
            return [rate_with_unit(item, f"{where}[{index}]") for index, item in enumerate(spec)]
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
        section, *inner, key = path.split(".")  # a nested field: delivery.head_rotation.up
        block = dict(trial.get(section) or {})
        trial[section] = block
        for part in inner:
            block[part] = dict(block.get(part) or {})
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
                      "face_poisson_ratio", "club_restitution_gain")


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


def _preset_fields(document: Mapping, key: str, names, where: str) -> tuple[list[tuple[str, str, list[float]]], list]:
    """The inputs of each preset in ``names`` of block ``club`` or ``ball`` (the study's other keys of that block
    applied), as sweep fields, and the scene of each preset (whose ball carries its restitution law)."""
    block, mark = PRESET_SWEEPS[key]
    if not isinstance(names, list) or not names or not all(isinstance(name, str) for name in names) \
            or len(set(names)) != len(names):
        raise FieldError(where, f"a list of distinct {block} preset names", names)
    if block not in document:
        raise FieldError(where, f"a {block} block in the study to sweep the preset of", f"no {block}")
    wanted = CLUB_PRESET_INPUTS if block == "club" else _ball_preset_inputs(document)
    values, scenes = {name: [] for name in wanted}, []
    for index, preset in enumerate(names):
        trial = dict(document, **{block: dict(document.get(block) or {}, preset=preset)})
        try:
            scene = build_scene(trial)
        except FieldError as exc:
            raise FieldError(f"{where}[{index}]", f"{exc.expected} (for {exc.path})", exc.given, exc.choices) from None
        inputs = scene.inputs()
        missing = [name for name in wanted if name not in inputs]
        if missing:
            raise FieldError(f"{where}[{index}]", f"a {block} preset that gives {INPUTS[missing[0]].path} like the "
                             "others swept beside it", preset)
        for name in wanted:
            values[name].append(inputs[name])
        scenes.append(scene)
    return [(f"{mark}{INPUTS[name].path}", name, values[name]) for name in wanted], scenes


def _build_sweep(document: Mapping) -> tuple[SweepAxis, ...]:
    sweep = document.get("sweep") or {}
    if not isinstance(sweep, Mapping):
        raise FieldError("sweep", "a mapping from dotted field paths (or dimension names) to values", sweep)
    raw_axes = []  # (dim or None, labels, [(path, input, values)], balls or None)
    for key, spec in sweep.items():
        key = str(key)
        if key in PRESET_SWEEPS:  # a dimension "club" or "ball" labelled by preset, setting every input of it
            fields, scenes = _preset_fields(document, key, spec, f"sweep.{key}")
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
            more, scenes = _preset_fields(document, preset_key, spec[preset_key], f"sweep.{key}.{preset_key}")
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


def _build_models(value) -> tuple[ModelEntry, ...]:
    if not isinstance(value, list) or not value:
        raise FieldError("models", "a non-empty list of models ({name: NAME, option: value})", value,
                         choices=available())
    entries, seen = [], {}
    for index, item in enumerate(value):
        where = f"models[{index}]"
        if isinstance(item, str) or _is_model(item):
            item = {"name": item}
        if not isinstance(item, Mapping) or "name" not in item:
            raise FieldError(where, "{name: MODEL, option: value, ...}", item, choices=available())
        options = {key: val for key, val in item.items() if key not in ("name", "id")}
        model = _configured_model(item["name"], options, where)
        entry_id = item.get("id", model.name)
        if not isinstance(entry_id, str) or not entry_id:
            raise FieldError(f"{where}.id", "a non-empty name for this entry in the results", entry_id)
        if entry_id in seen:
            raise FieldError(f"{where}.id" if "id" in item else f"{where}.name",
                             f"a name not used by models[{seen[entry_id]}]; give repeated models an id", entry_id)
        seen[entry_id] = index
        entries.append(ModelEntry(entry_id, model))
    return tuple(entries)


def _is_model(value) -> bool:
    """Whether ``value`` is a model class or a configured model (a Python study may name a model by either)."""
    return isinstance(value, ImpactModel) or (isinstance(value, type) and issubclass(value, ImpactModel))


def _configured_model(name, options: Mapping, where: str) -> ImpactModel:
    """The model an entry names, configured with its options: a registered name, a model class or an instance."""
    if isinstance(name, ImpactModel):  # configured already, as a backend instance is
        if options:
            key = str(next(iter(options)))
            raise FieldError(f"{where}.{key}", "options of a model class or name (an instance has its own)", key)
        return name
    if not _is_model(name):
        models = available()
        if not isinstance(name, str) or name not in models:
            raise FieldError(f"{where}.name", "a registered model", str(name), choices=models)
        name = get_model(name)
    try:
        return name(**options)
    except FieldError as exc:
        raise exc.at(prefix=where) from None


def _build_outputs(value) -> tuple[str, ...]:
    if value is None:
        return DEFAULT_OUTPUTS
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not value:
        raise FieldError("outputs", "a non-empty list of output names", value, choices=OUTPUTS)
    return tuple(dict.fromkeys(check_output_names(value)))


def _build_study(document, text: str, file: str | None) -> Study:
    if not isinstance(document, Mapping):
        raise FieldError("", "a study mapping with keys name, ball, face, contact, impact, sweep, models, outputs",
                         type(document).__name__)
    structure(document, StudyBlock, "")
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
    check_cases(int(np.prod([axis.size for axis in sweep], dtype=object)) if sweep else 1, f"study {name!r} sweep")
    outputs = _build_outputs(document.get("outputs"))
    models = _build_models(document["models"])
    sensitivity = None
    if "sensitivity" in document:
        from impactlab.data.sensitivity import parse_sensitivity

        sensitivity = parse_sensitivity(document["sensitivity"], [entry.id for entry in models], scene.inputs(),
                                        {field.input for axis in sweep for field in axis.fields})
    return Study(name=name, description=description, scene=scene, sweep=sweep, models=models, outputs=outputs,
                 source=text, file=file,
                 plots=_build_plots(document.get("plots"), sweep, outputs, [entry.id for entry in models]),
                 sensitivity=sensitivity)


def _build_plots(value, sweep, outputs, model_ids=()) -> tuple[PlotSpec, ...]:
    if value is None:
        return ()
    if not isinstance(value, list):
        raise FieldError("plots", "a list of figures ({name, y, x, select, title, kind})", value)
    dims = [axis.dim for axis in sweep]
    plots = []
    for index, item in enumerate(value):
        where = f"plots[{index}]"
        block = structure(item, PlotBlock, where)
        name = f"plot{index}" if block.name is None else block.name
        if not isinstance(name, str) or not name.replace("-", "_").isidentifier():
            raise FieldError(f"{where}.name", "a short file-name-safe name", name)
        wanted = block.y
        wanted = [wanted] if isinstance(wanted, str) else wanted
        if not isinstance(wanted, list) or not wanted:
            raise FieldError(f"{where}.y", "an output name or a list of them", wanted, choices=outputs)
        for position, output in enumerate(wanted):
            if output not in outputs:
                raise FieldError(f"{where}.y[{position}]", "an output the study computes", output, choices=outputs)
        kind = block.kind or "lines"
        if kind not in PLOT_KINDS:
            raise FieldError(f"{where}.kind", "a kind of figure", kind, choices=PLOT_KINDS)
        x = block.x
        scalar_outputs = [name for name in outputs if name in SCALAR_OUTPUTS]
        if x is not None and x not in dims + scalar_outputs:
            raise FieldError(f"{where}.x", "a sweep dimension or a scalar output of the study", x,
                             choices=dims + scalar_outputs)
        select = block.select or {}
        if not isinstance(select, Mapping):
            raise FieldError(f"{where}.select", "a mapping from dimension to value", select)
        for key in select:
            if key not in dims + [MODEL_DIM]:
                raise FieldError(f"{where}.select.{key}", "a sweep dimension or model", key,
                                 choices=dims + [MODEL_DIM])
            if key == MODEL_DIM and model_ids and select[key] not in model_ids:  # else it fails after the run
                raise FieldError(f"{where}.select.{key}", "a model of the study", str(select[key]), choices=model_ids)
        title = block.title or ""
        xlim = block.xlim
        if xlim is not None and not (isinstance(xlim, list) and len(xlim) == 2 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in xlim) and xlim[0] < xlim[1]):
            raise FieldError(f"{where}.xlim", "[low, high] of the horizontal axis, low < high", xlim)
        measured = block.measured or []
        measured = [measured] if isinstance(measured, str) else measured
        if not isinstance(measured, list):
            raise FieldError(f"{where}.measured", "a shipped measured dataset or a list of them", measured)
        from impactlab.data.validation import DATASETS

        for position, data in enumerate(measured):
            if not isinstance(data, str) or data not in DATASETS or DATASETS[data].quantity not in wanted:
                raise FieldError(f"{where}.measured[{position}]", "a shipped measured dataset of an output drawn",
                                 data, choices=[k for k, v in DATASETS.items() if v.quantity in wanted])
        plots.append(PlotSpec(name, tuple(wanted), x, tuple(select.items()), str(title), kind,
                              tuple(float(v) for v in xlim) if xlim else None, tuple(measured)))
    names = [plot.name for plot in plots]
    if len(set(names)) != len(names):
        raise FieldError("plots", "figures with distinct names", names)
    return tuple(plots)


__all__ = ["Study", "SweepAxis", "SweepField", "ModelEntry", "load_study", "build_scene"]
