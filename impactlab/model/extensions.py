"""Inputs and outputs a plugin declares through its entry points, never by editing impactlab.

Two entry-point groups besides the models' (``impactlab.models``, :mod:`impactlab.model.registry`):

* ``impactlab.inputs``: a scene field (:class:`PluginInput`), set in a study's ``plugin:`` block and swept as
  ``plugin.NAME``; a model reads it like any input it declares.
* ``impactlab.outputs``: an output derived from a model's arrays (:class:`DerivedOutput`), usable in ``outputs:``,
  figures and result files like any other.

:func:`load_plugins` adds them to :data:`impactlab.vocabulary.INPUTS`, ``INPUT_BY_PATH`` and ``OUTPUTS`` once,
when ``impactlab`` has been imported (its ``__init__`` calls it), so that a plugin's module may import impactlab
itself. A declaration that does not load, takes a built-in name or needs what is no scalar output is skipped with a
:class:`~impactlab.errors.PluginWarning` naming it; it never takes the vocabulary down.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable
from importlib import metadata
from typing import Any

import attrs

from impactlab.errors import PluginWarning
from impactlab.units import DIMENSIONS
from impactlab.vocabulary import INPUT_BY_PATH, INPUTS, OUTPUTS, SCALAR, InputSpec, OutputSpec, refresh_output_names

#: entry-point group of scene fields a plugin adds (a study's ``plugin:`` block, sweepable like any field)
INPUT_ENTRY_POINT_GROUP = "impactlab.inputs"
#: entry-point group of outputs a plugin derives from a model's arrays (usable in ``outputs:`` and figures)
OUTPUT_ENTRY_POINT_GROUP = "impactlab.outputs"


@attrs.frozen
class PluginInput:
    """A scene field a plugin declares (entry-point group ``impactlab.inputs``; the entry point's name is the
    input's name). A study sets it in its ``plugin:`` block (``plugin: {NAME: 0.2}``) and sweeps it as
    ``plugin.NAME``; a model reads it like any input it declares in ``requires`` or ``optional_inputs``. A study
    that does not give it leaves it absent (no default is guessed).

    Attributes
    ----------
    unit : str
        The SI unit the model receives (``"1"`` for a number).
    dimension : str
        A key of :data:`impactlab.units.DIMENSIONS` (``"dimensionless"``, ``"length"``, ...): a study writes the
        value with a unit of that dimension.
    description : str
        What it is, for messages and the result file.
    low, high : float
        Allowed SI range (inclusive).
    """

    unit: str
    dimension: str
    description: str
    low: float = -math.inf
    high: float = math.inf


@attrs.frozen
class DerivedOutput:
    """An output a plugin derives from a model's arrays (entry-point group ``impactlab.outputs``; the entry point's
    name is the output's name).

    Attributes
    ----------
    units : str
        Units of the stored values (after ``factor``).
    long_name : str
        What it is (figure axes, the result file).
    needs : tuple of str
        Scalar outputs of the vocabulary it is computed from; the planner asks the model (or the framework's
        derivation) for them, and the output is NaN with the reason where a model cannot give one.
    function : callable
        ``function(**arrays) -> array``: each need by name as a 1-D SI array (one value per case), the result
        in SI, one value per case.
    factor : float
        SI result -> ``units`` (e.g. 1000 for mm from m). Default 1.
    """

    units: str
    long_name: str
    needs: tuple[str, ...]
    function: Callable[..., Any]
    factor: float = 1.0


def _plugin_entries(group: str) -> list:
    """The entry points of ``group``, sorted by name."""
    return sorted(metadata.entry_points(group=group), key=lambda entry: (entry.name, entry.value))


def _plugin_declarations(group: str, kind: type) -> dict[str, Any]:
    """Name -> declaration of each loadable plugin entry of ``group``; a broken one is skipped with a PluginWarning
    naming it."""
    found: dict[str, Any] = {}
    for entry in _plugin_entries(group):
        where = f"{group} plugin '{entry.name} = {entry.value}'"
        try:
            declared = entry.load()
            if isinstance(declared, dict):
                declared = kind(**declared)
            if not isinstance(declared, kind):
                raise TypeError(f"it is a {type(declared).__name__}, not a {kind.__name__} (or its fields as a dict)")
            if not entry.name.isidentifier():
                raise ValueError("its name is not a Python identifier")
        except Exception as exc:  # a plugin's error of any kind: skipped, the rest of the vocabulary loads
            warnings.warn(f"{where} is skipped: {type(exc).__name__}: {exc}", PluginWarning, stacklevel=3)
            continue
        found[entry.name] = declared
    return found


def _register_inputs() -> None:
    for name, declared in _plugin_declarations(INPUT_ENTRY_POINT_GROUP, PluginInput).items():
        if name in INPUTS or declared.dimension not in DIMENSIONS:
            warnings.warn(f"{INPUT_ENTRY_POINT_GROUP} plugin {name!r} is skipped: "
                          + (f"the name is taken by impactlab's input {INPUTS[name].path}" if name in INPUTS
                             else f"dimension {declared.dimension!r} is not one of {', '.join(DIMENSIONS)}"),
                          PluginWarning, stacklevel=2)
            continue
        INPUTS[name] = InputSpec(f"plugin.{name}", declared.unit, declared.dimension, declared.description,
                                 lambda scene: None, low=declared.low, high=declared.high)
        INPUT_BY_PATH[f"plugin.{name}"] = name


def _register_outputs() -> None:
    builtin = {name for name, spec in OUTPUTS.items() if spec.kind == SCALAR and spec.function is None}
    for name, declared in _plugin_declarations(OUTPUT_ENTRY_POINT_GROUP, DerivedOutput).items():
        needs = tuple(declared.needs)
        problem = (f"the name is taken by impactlab's output {name!r}" if name in OUTPUTS
                   else f"needs {', '.join(sorted(set(needs) - builtin))}, not scalar outputs of impactlab"
                   if not needs or not set(needs) <= builtin
                   else "its function is not callable" if not callable(declared.function) else "")
        if problem:
            warnings.warn(f"{OUTPUT_ENTRY_POINT_GROUP} plugin {name!r} is skipped: {problem}", PluginWarning,
                          stacklevel=2)
            continue
        OUTPUTS[name] = OutputSpec(declared.units, declared.long_name, factor=float(declared.factor), needs=needs,
                                   function=declared.function)


_LOADED: list[bool] = []


def load_plugins() -> None:
    """Add the inputs and outputs plugins declare to the vocabulary, once (see the module docstring).

    The dictionaries change in place; the tuples of names derived from them (``SCALAR_OUTPUTS``,
    ``PLUGIN_OUTPUTS``) are made again in :mod:`impactlab.vocabulary`, so read them as ``vocabulary.NAME`` or use
    :func:`impactlab.vocabulary.is_scalar`.
    """
    if _LOADED:
        return
    _LOADED.append(True)
    _register_inputs()
    _register_outputs()
    refresh_output_names()


__all__ = ["DerivedOutput", "PluginInput", "load_plugins", "INPUT_ENTRY_POINT_GROUP", "OUTPUT_ENTRY_POINT_GROUP"]
