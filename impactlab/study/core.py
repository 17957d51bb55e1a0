"""Study definitions: YAML (or a mapping) read into validated, frozen objects.

A study names a base scene (ball, face, contact, impact), sweeps over some of
its fields, the models to compare with their options, and the outputs wanted.
Every error names the file, the line and the path of the offending field,
what was expected, what was given and, where there are choices, the choices.

See docs/user-guide.md for the format.
"""

from __future__ import annotations

import copy
import math
import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import attrs
import numpy as np
import yaml

from impactlab.errors import FieldError, StudyError
from impactlab.study.limits import check_cases
from impactlab.units import to_si
from impactlab.model.base import ImpactModel
from impactlab.model.registry import available, get_model
from impactlab.scene.core import Scene
from impactlab.scene.materials import FACE_SURFACES
# the scene blocks live in study_scene; their builders stay importable from here
from impactlab.study.scene_blocks import (build_ball, build_club, build_contact, build_delivery, build_face,  # noqa: F401
                          build_impact, build_scene, build_strike, reusing_blocks)
from impactlab.study.datasets import DATASETS
from impactlab.study.extensions import (SHOT_FILE_SUFFIXES, OptionAxis, build_option_sweep, build_plugin_inputs,
                                        select_value, shot_file, without_option_sweeps)
from impactlab.study.schema import PlotBlock, StudyBlock, keys_of
from impactlab.study.structuring import lookup, structure
from impactlab.study.sensitivity import SensitivitySpec, parse_sensitivity
from impactlab.study.sweeps import PRESET_MARK, SweepAxis, SweepField, build_sweep, friction_law_entry
from impactlab.vocabulary import (DEFAULT_OUTPUTS, DIAGNOSTIC_OUTPUTS, MODEL_DIM, OUTPUTS, is_scalar,
                                  check_output_names)
from impactlab.study.yaml_lines import line_of, load_yaml, parse_path, read_text_file

TOP_LEVEL_KEYS = keys_of(StudyBlock)


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
    #: names of shipped measured datasets (impactlab.study.datasets) drawn beside the curves, with their error bars
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
    #: a sensitivity and model-form study (run by impactlab.run.sensitivity), or None for a plain sweep
    sensitivity: SensitivitySpec | None = None
    #: values of the scene fields plugins declare (the ``plugin:`` block), name -> SI value
    plugin_inputs: tuple[tuple[str, float], ...] = ()
    #: model options swept (``sweep: {model_option.ENTRY.OPTION: [...]}``), dimensions after the sweep's own
    option_sweep: tuple[OptionAxis, ...] = ()

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
        # Python's product of the sizes (np.prod costs 2.4 us, and a run asks ~20 times); a loaded study's count is
        # below the case limit (impactlab.study.limits), far from any integer's range
        return math.prod(self.shape)



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
        at = _document_path(exc.path)
        written = lookup(document, at)
        about_a_key = bool(at) and exc.given == at[-1]
        if (not about_a_key and isinstance(written, (str, int, float)) and not isinstance(written, bool)
                and written != exc.given):
            # show what the user wrote, not the SI number it became
            exc = FieldError(exc.path, exc.expected, written, exc.choices)
        raise exc.at(file=file, line=line_of(lines, at)) from None


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


def _build_models(value) -> tuple[ModelEntry, ...]:
    if not isinstance(value, list) or not value:
        raise FieldError("models", "a non-empty list of models ({name: NAME, option: value})", value,
                         choices=available())
    entries: list[ModelEntry] = []
    seen: dict[str, int] = {}  # entry id -> its index
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
    fields = attrs.fields_dict(name.Options) if attrs.has(name.Options) else {}
    for key, value in options.items():  # a dimensional option (its field's metadata) takes a unit in a study
        dimension = fields[key].metadata.get("dimension") if key in fields else None
        if dimension is not None and isinstance(value, (int, float, str)) and not isinstance(value, bool):
            try:
                to_si(value, dimension, f"{where}.{key}")  # a bare number refused (0 excepted), never read as SI
            except FieldError as exc:
                raise FieldError(exc.path, fields[key].metadata.get("expected", exc.expected), exc.given) from None
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
        # in the user's words, not Python's (NoneType, list)
        found = ("an empty document (nothing but comments or blank lines)" if document is None
                 else f"a {'list' if isinstance(document, list) else 'single value'} ({str(document)[:60]!s})")
        raise FieldError("", "a study mapping with keys name, ball, face, contact, impact, sweep, models, outputs",
                         found)
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
    document, option_keys = without_option_sweeps(document)
    with reusing_blocks():  # the sweep's trial scenes share all but the swept block with the base scene
        scene = build_scene(document)  # the base scene first: its errors are its own, not a sweep's
        models = _build_models(document["models"])
        sweep = build_sweep(document, models)
    plugin_inputs = build_plugin_inputs(document.get("plugin"))
    option_sweep = build_option_sweep(option_keys, models, [axis.dim for axis in sweep])
    check_cases(int(np.prod([axis.size for axis in sweep] + [axis.size for axis in option_sweep], dtype=object))
                if sweep or option_sweep else 1, f"study {name!r} sweep")
    outputs = _build_outputs(document.get("outputs"))
    _check_face_surface(scene, sweep, models, "club" if "club" in document else "face")
    sensitivity = None
    if "sensitivity" in document:
        sensitivity = parse_sensitivity(document["sensitivity"], [entry.id for entry in models], scene.inputs(),
                                        {field.input for axis in sweep for field in axis.fields})
    _check_face_marker(document, scene, sweep, models, sensitivity)
    if sensitivity is not None and option_sweep:
        raise FieldError(f"sweep.model_option.{option_sweep[0].entry}.{option_sweep[0].option}",
                         "no model option swept in a sensitivity study (give each value its own study)", "a sweep")
    return Study(name=name, description=description, scene=scene, sweep=sweep, models=models, outputs=outputs,
                 source=text, file=file,
                 plots=_build_plots(document.get("plots"), sweep, outputs, [entry.id for entry in models],
                                    option_sweep, file),
                 sensitivity=sensitivity, plugin_inputs=plugin_inputs, option_sweep=option_sweep)


def _check_face_surface(scene, sweep, models, block: str) -> None:
    """A friction law reads the face's surface: a face without one is refused here, at the study's line, rather
    than taken as smooth and dry (a club preset's sweep gives each club its own, which every preset has)."""
    law = friction_law_entry(models)
    swept = any(field.input == "face_roughness_slope" for axis in sweep for field in axis.fields)
    if law is None or swept or getattr(scene.face, "surface", None) is not None:
        return
    club = scene.club.name if scene.club is not None and scene.club.name else f"the study's {block}"
    raise FieldError(f"{block}.surface", f"the face's surface for friction_law: {law.model.options.friction_law} "
                     f"(model {law.id}): a preset ({', '.join(FACE_SURFACES)}) or its fields roughness_slope, "
                     f"roughness, groove_land, effusivity (water_film for a wet face), each with its unit; a face is "
                     f"never taken as smooth and dry", f"none ({club} has no surface)", choices=FACE_SURFACES)


def _check_face_marker(document, scene, sweep, models, sensitivity) -> None:
    """The flexing face (model option ``face_frequency``; models._common.face_inputs) acts on the faces whose
    club_restitution_gain is > 0: a sweep of the gain from 0 to above it switches the face law on between two of
    its values, a step in every result of that model that is no physics of the gain. Refused at the sweep's line
    rather than drawn as a jump (a club preset sweep, irons beside woods, keeps each club's own face); likewise a
    sensitivity range of the gain that reaches 0 from above."""
    flexing = [entry.id for entry in models if float(getattr(entry.model.options, "face_frequency", 0.0) or 0.0) > 0]
    if not flexing:
        return
    gains = np.concatenate([np.ravel(scene.inputs().get("club_restitution_gain", 0.0))] + [
        np.asarray(field.values, float) for axis in sweep for field in axis.fields
        if field.input == "club_restitution_gain"])
    ranged = sensitivity is not None and any(p.input == "club_restitution_gain" for p in sensitivity.parameters)
    if not np.any(gains > 0.0) and not ranged:  # the option would change nothing: said, not run as a rigid face
        index = next(index for index, entry in enumerate(models) if entry.id == flexing[0])
        club = scene.club.name if scene.club is not None and scene.club.name else "the study's club or face"
        raise FieldError(f"models[{index}].face_frequency", f"a study with a spring-like face to flex: the face law "
                         f"acts on clubs with restitution_gain > 0 (the catalogue's driver, woods and hybrids), and no "
                         f"case of this study has one ({club}: 0), so it would change nothing; give the club's "
                         f"restitution_gain (the presets' fitted 0.083) or a wood's preset, or leave face_frequency "
                         f"out", flexing[0])
    swept = document.get("sweep") or {}
    for axis in sweep:
        for field in axis.fields:
            values = np.asarray(field.values, float)
            if field.input != "club_restitution_gain" or field.path.startswith(PRESET_MARK) or not (
                    np.any(values == 0.0) and np.any(values > 0.0)):
                continue
            where = f"sweep.{field.path}" if field.path in swept else f"sweep.{axis.dim}.{field.path}"
            raise FieldError(where, f"restitution gains all above 0 or all 0 with the flexing face of model "
                             f"{flexing[0]} (face_frequency): a gain > 0 marks a spring-like face, which then flexes "
                             f"and takes the ball's own e, so a sweep through 0 switches the face law on and off "
                             f"(a jump, not the gain's effect); sweep it without 0, or compare the model with and "
                             f"without face_frequency", ", ".join(f"{value:g}" for value in values))
    for parameter in () if sensitivity is None else sensitivity.parameters:
        if parameter.input != "club_restitution_gain":
            continue
        nominal = np.unique(np.concatenate([np.ravel(scene.inputs().get("club_restitution_gain", 0.0))] + [
            np.asarray(field.values, float) for axis in sweep for field in axis.fields
            if field.input == "club_restitution_gain"]))
        low, high = parameter.bounds(nominal)
        if np.any((low <= 0.0) & (high > 0.0)):
            raise FieldError(f"sensitivity.parameters.{parameter.path}", f"a range of the restitution gain above 0 "
                             f"with the flexing face of model {flexing[0]} (face_frequency): a gain > 0 marks a "
                             f"spring-like face, so a range reaching 0 switches the face law on and off inside it",
                             parameter.describe())


def _build_plots(value, sweep, outputs, model_ids=(), option_sweep=(), file=None) -> tuple[PlotSpec, ...]:
    if value is None:
        return ()
    if not isinstance(value, list):
        raise FieldError("plots", "a list of figures ({name, y, x, select, title, kind})", value)
    dims = [axis.dim for axis in sweep] + [axis.dim for axis in option_sweep]
    plots = []
    for index, item in enumerate(value):
        where = f"plots[{index}]"
        block = structure(item, PlotBlock, where)
        name = f"plot{index}" if block.name is None else block.name
        if not isinstance(name, str) or not name.replace("-", "_").isidentifier():
            raise FieldError(f"{where}.name", "a short file-name-safe name", name)
        wanted = block.y
        one = isinstance(wanted, str)
        wanted = [wanted] if one else wanted
        if not isinstance(wanted, list) or not wanted:
            raise FieldError(f"{where}.y", "an output name or a list of them", wanted, choices=outputs)
        for position, output in enumerate(wanted):
            if output not in outputs:  # y: NAME is named y, not y[0] (its first letter, read back from the file)
                raise FieldError(f"{where}.y" if one else f"{where}.y[{position}]", "an output the study computes",
                                 output, choices=outputs)
        kind = block.kind or "lines"
        if kind not in PLOT_KINDS:
            raise FieldError(f"{where}.kind", "a kind of figure", kind, choices=PLOT_KINDS)
        x = block.x
        scalar_outputs = [name for name in outputs if is_scalar(name)]
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
        for key, chosen in select.items():
            option_axis = next((axis for axis in option_sweep if axis.dim == key), None)
            if option_axis is not None and chosen not in option_axis.values:
                raise FieldError(f"{where}.select.{key}", f"a swept value of option {option_axis.option!r}",
                                 str(chosen), choices=[str(v) for v in option_axis.values])
        select = {key: select_value(next((axis for axis in sweep if axis.dim == key), None), value,
                                     f"{where}.select.{key}") for key, value in select.items()}
        title = block.title or ""
        xlim = block.xlim
        if xlim is not None and not (isinstance(xlim, list) and len(xlim) == 2 and all(
                isinstance(v, (int, float)) and not isinstance(v, bool) for v in xlim) and xlim[0] < xlim[1]):
            raise FieldError(f"{where}.xlim", "[low, high] of the horizontal axis, low < high", xlim)
        measured = block.measured or []
        measured = [measured] if isinstance(measured, str) else list(measured) if isinstance(measured, list) \
            else measured
        if not isinstance(measured, list):
            raise FieldError(f"{where}.measured", "a shipped measured dataset or a list of them", measured)
        for position, data in enumerate(measured):
            if isinstance(data, str) and data in DATASETS and DATASETS[data].quantity in wanted:
                continue
            if isinstance(data, str) and (data.lower().endswith(SHOT_FILE_SUFFIXES) or os.sep in data
                                          or "/" in data):
                measured[position] = shot_file(data, f"{where}.measured[{position}]", file)
                continue
            raise FieldError(f"{where}.measured[{position}]", "a shipped measured dataset of an output drawn, or "
                             "the path of a shot file (.csv, .yaml: a launch-monitor export or a shot table)",
                             data, choices=[k for k, v in DATASETS.items() if v.quantity in wanted])
        plots.append(PlotSpec(name, tuple(wanted), x, tuple(select.items()), str(title), kind,
                              (float(xlim[0]), float(xlim[1])) if xlim else None, tuple(measured)))
    names = [plot.name for plot in plots]
    if len(set(names)) != len(names):
        raise FieldError("plots", "figures with distinct names", names)
    return tuple(plots)


__all__ = ["Study", "SweepAxis", "SweepField", "ModelEntry", "OptionAxis", "load_study", "build_scene"]
