"""What a study takes besides its scene: swept model options, plugins' scene fields, figure selections and shot files.

Kept apart from :mod:`impactlab.study.core`, which calls each while it builds a study: ``model_option.ENTRY.OPTION``
sweeps (:class:`OptionAxis`, run by :mod:`impactlab.run.options`), the ``plugin:`` block of the scene fields plugins
declare (:mod:`impactlab.model.extensions`), a figure's ``select`` values with their units, and a figure's
``measured:`` shot files.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING

import attrs
import numpy as np

from impactlab.errors import FieldError
from impactlab.study.sweeps import SweepAxis
from impactlab.units import to_si
from impactlab.vocabulary import INPUTS, MODEL_DIM

if TYPE_CHECKING:  # study.core imports this module
    from impactlab.study.core import ModelEntry


@attrs.frozen
class OptionAxis:
    """A model option swept like a field: ``sweep: {model_option.ENTRY.OPTION: [v1, v2, ...]}``.

    One dimension ``dim`` of the results; the entry ``entry`` runs once per value with its options but this one
    as written, every other model is the same along it.
    """

    dim: str
    entry: str
    option: str
    values: tuple = ()
    #: the configured model of each value
    models: tuple = attrs.field(default=(), eq=False, repr=False)

    @property
    def size(self) -> int:
        """Number of values along this dimension."""
        return len(self.values)




#: a swept model option: ``model_option.ENTRY.OPTION`` (ENTRY a model's id in the study)
OPTION_MARK = "model_option."


def without_option_sweeps(document: Mapping) -> tuple[Mapping, list]:
    """The document without its ``model_option.*`` sweep keys (the scene's sweep knows nothing of models), and
    those keys with their values."""
    sweep = document.get("sweep")
    if not isinstance(sweep, Mapping) or not any(str(key).startswith(OPTION_MARK) for key in sweep):
        return document, []
    keys = [(str(key), value) for key, value in sweep.items() if str(key).startswith(OPTION_MARK)]
    rest = {key: value for key, value in sweep.items() if not str(key).startswith(OPTION_MARK)}
    return {**document, "sweep": rest}, keys


def build_option_sweep(keys: list, models: tuple[ModelEntry, ...], taken: list[str]) -> tuple[OptionAxis, ...]:
    """The swept model options, each value made into the entry's model (its options' own validation, at the path)."""
    axes: list[OptionAxis] = []
    ids = [entry.id for entry in models]
    for key, values in keys:
        where = f"sweep.{key}"
        parts = key[len(OPTION_MARK):].split(".")
        if len(parts) != 2 or not all(parts):
            raise FieldError(where, "model_option.ENTRY.OPTION (ENTRY a model id of the study)", key)
        entry_id, option = parts
        entry = next((entry for entry in models if entry.id == entry_id), None)
        if entry is None:
            raise FieldError(where, "a model id of the study after model_option.", entry_id, choices=ids)
        options = entry.model.options
        known = [field.name for field in attrs.fields(type(options))] if attrs.has(type(options)) else []
        if option not in known:
            raise FieldError(where, f"an option of model {entry.model.name!r}", option,
                             choices=known or ["(this model takes no options)"])
        if not isinstance(values, list) or not values:
            raise FieldError(where, "a non-empty list of the option's values", values)
        configured = []
        for index, value in enumerate(values):
            dimension = attrs.fields_dict(type(options))[option].metadata.get("dimension")
            if dimension is not None:
                to_si(value, dimension, f"{where}[{index}]")  # a bare number refused (0 excepted), as in models:
            try:
                configured.append(type(entry.model)(attrs.evolve(options, **{option: value})))
            except FieldError as exc:
                raise FieldError(f"{where}[{index}]", exc.expected, value, exc.choices) from None
            except (TypeError, ValueError) as exc:
                raise FieldError(f"{where}[{index}]", f"a valid value of option {option!r} of model "
                                 f"{entry.model.name!r} ({exc})", value) from None
        if len({json.dumps(model.options_dict(), sort_keys=True) for model in configured}) != len(configured):
            raise FieldError(where, "distinct values (two would make one model twice)", values)
        names = taken + [axis.dim for axis in axes]
        dim = option if option not in names + [MODEL_DIM, "time"] else f"{entry_id}_{option}"
        if dim in names:
            raise FieldError(where, "an option swept once per model", key)
        axes.append(OptionAxis(dim, entry_id, option, tuple(values), tuple(configured)))
    return tuple(axes)


def build_plugin_inputs(block) -> tuple[tuple[str, float], ...]:
    """The ``plugin:`` block: values of the scene fields plugins declare (impactlab.vocabulary.PluginInput), SI."""
    if block is None:
        return ()
    plugin = {name: spec for name, spec in INPUTS.items() if spec.path.startswith("plugin.")}
    if not isinstance(block, Mapping):
        raise FieldError("plugin", "a mapping of the scene fields plugins declare to their values", block,
                         choices=plugin)
    values = []
    for key, value in block.items():
        if key not in plugin:
            raise FieldError(f"plugin.{key}", "a scene field a plugin declares (entry-point group "
                             "impactlab.inputs)", str(key), choices=plugin or ["(no plugin declares one)"])
        spec = plugin[key]
        number = to_si(value, spec.dimension, f"plugin.{key}")
        if spec.out_of_range(np.asarray([number]))[0]:
            raise FieldError(f"plugin.{key}", spec.range_text(), value)
        values.append((str(key), number))
    return tuple(values)




#: the suffixes of a user's shot file a figure's ``measured:`` may name (impactlab.data.sessions reads them)
SHOT_FILE_SUFFIXES = (".csv", ".yaml", ".yml", ".session", ".txt")


def shot_file(given: str, where: str, study_file: str | None = None) -> str:
    """A user's shot file named in a figure's ``measured:``: it must exist (a relative path is the study file's
    folder's). What it measures is checked by :func:`impactlab.plot.figures.check_shot_files` before a run draws
    it (the readers of :mod:`impactlab.data.sessions` sit above the study layer).

    Returns
    -------
    str
        The file's absolute path (what the result stores, so ``impactlab plot`` redraws it from anywhere).
    """
    path = Path(given).expanduser()
    if not path.is_absolute() and study_file and not study_file.startswith("<"):
        path = Path(study_file).parent / path
    if not path.is_file():
        raise FieldError(where, "a shot file that exists (a relative path is the study file's folder's)", given)
    return str(path.resolve())


def select_value(axis: SweepAxis | None, value, where: str):
    """A plot's ``select`` value as the dataset's coordinate holds it, checked against the dimension's values.

    A quantity with a unit (``0 mm``, ``10 deg``) is converted to the coordinate's unit (mm, deg: the input's
    display unit); a bare number is the coordinate's value in that unit, as the result file shows it; a labelled
    dimension takes a label. Refused at load, naming the values there are, rather than after the whole run.
    """
    if axis is None:  # the model dimension: checked by the caller
        return value
    if isinstance(value, (list, tuple)):  # several values: a figure of those lines only
        if not value:
            raise FieldError(where, f"a value of {axis.dim!r} or a non-empty list of them", value)
        return [select_value(axis, item, f"{where}[{index}]") for index, item in enumerate(value)]
    if axis.grouped:
        labels = list(axis.labels) if axis.labels else list(range(axis.size))
        if value not in labels:
            raise FieldError(where, f"a value of dimension {axis.dim!r}", value, choices=[str(v) for v in labels])
        return value
    field = axis.fields[0]
    spec = INPUTS[field.input]
    coords = [float(f"{v * spec.display_factor:.12g}") for v in field.values]
    unit = spec.display_unit or spec.unit
    if isinstance(value, str) or hasattr(value, "units"):
        number = float(f"{to_si(value, spec.dimension, where) * spec.display_factor:.12g}")
    elif isinstance(value, (int, float)) and not isinstance(value, bool):
        number = float(value)
    else:
        raise FieldError(where, f"a value of {axis.dim!r} with its unit (the coordinate is in {unit})", value)
    matches = [c for c in coords if math.isclose(c, number, rel_tol=1e-9, abs_tol=1e-9 * max(map(abs, coords)))]
    if not matches:
        raise FieldError(where, f"one of the swept values of {axis.dim!r} (in {unit})", value,
                         choices=[f"{c:g} {unit}".strip() for c in coords])
    return matches[0]
