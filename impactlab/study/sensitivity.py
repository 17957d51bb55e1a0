"""The ``sensitivity:`` block of a study: the uncertain inputs, their ranges, the modelling choices, the sampler.

The block is read here, with the rest of the study (every error names the field, what it takes and what it
got); :mod:`impactlab.run.sensitivity` runs it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import attrs
import numpy as np

from impactlab.errors import FieldError
from impactlab.study.schema import ParameterRangeBlock, SensitivityBlock, keys_of
from impactlab.study.structuring import structure
from impactlab.units import to_si
from impactlab.vocabulary import INPUT_BY_PATH, INPUTS

METHODS = ("sobol", "morris")


@attrs.frozen
class Parameter:
    """An uncertain input: study path, input name, and its range (absolute, or +- ``spread`` around each case)."""

    path: str
    input: str
    low: float | None = None
    high: float | None = None
    spread: float | None = None

    def bounds(self, nominal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(low, high) per case [SI]."""
        if self.spread is not None:
            return nominal - self.spread, nominal + self.spread
        return np.full(nominal.shape, self.low), np.full(nominal.shape, self.high)

    def describe(self) -> str:
        """The parameter and its range in display units, in words."""
        spec = INPUTS[self.input]
        factor, unit = spec.display_factor, spec.display_unit or spec.unit
        unit = "" if unit == "1" else f" {unit}"
        if self.spread is not None:
            return f"+-{self.spread * factor:g}{unit}"
        assert self.low is not None and self.high is not None, "a parameter has a spread or low and high"
        return f"{self.low * factor:g} to {self.high * factor:g}{unit}"


@attrs.frozen
class SensitivitySpec:
    """A validated ``sensitivity:`` block."""

    method: str
    samples: int
    seed: int
    parameters: tuple[Parameter, ...]
    choices: tuple[tuple[str, tuple[str, ...]], ...]
    models: tuple[str, ...]
    levels: int = 4

    def as_dict(self) -> dict:
        """The specification as plain data (stored with the results as provenance)."""
        return {"method": self.method, "samples": self.samples, "seed": self.seed, "levels": self.levels,
                "parameters": {p.path: p.describe() for p in self.parameters},
                "choices": {name: list(ids) for name, ids in self.choices}, "models": list(self.models)}


def _whole(value, path: str, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise FieldError(path, f"a whole number >= {low}", value)
    return value


def parse_sensitivity(block: Any, model_ids: list[str], scene_inputs: Mapping[str, float], swept: set[str],
                      where: str = "sensitivity") -> SensitivitySpec:
    """Validate a study's ``sensitivity:`` block; every error names the field, what it takes and what it got."""
    if not isinstance(block, Mapping):
        raise FieldError(where, f"a mapping with keys from: {', '.join(keys_of(SensitivityBlock))}", block)
    given = structure(block, SensitivityBlock, where)  # unknown keys refused, as in every block
    method = "sobol" if given.method is None else given.method
    if method not in METHODS:
        raise FieldError(f"{where}.method", "a sensitivity method", method, choices=METHODS)
    samples = _whole(64 if given.samples is None else given.samples, f"{where}.samples", 2)
    if method == "sobol" and samples & (samples - 1):
        raise FieldError(f"{where}.samples", "a power of 2 (Sobol sequences lose their balance otherwise)", samples)
    seed = _whole(1 if given.seed is None else given.seed, f"{where}.seed", 0)
    levels = _whole(4 if given.levels is None else given.levels, f"{where}.levels", 2)
    if levels % 2:
        raise FieldError(f"{where}.levels", "an even number of Morris grid levels", levels)
    raw = given.parameters
    if not isinstance(raw, Mapping) or not raw:
        raise FieldError(f"{where}.parameters", "a mapping from study paths to {low, high} or {spread}", raw,
                         choices=INPUT_BY_PATH)
    parameters = []
    for path, spec in raw.items():
        at = f"{where}.parameters.{path}"
        if path not in INPUT_BY_PATH:
            raise FieldError(at, "a dotted path of an input field", str(path), choices=INPUT_BY_PATH)
        name = INPUT_BY_PATH[path]
        if name not in scene_inputs:
            raise FieldError(at, "a field the study's scene gives (add it to the scene first)", str(path))
        if not isinstance(spec, Mapping):
            raise FieldError(at, "{low: VALUE, high: VALUE} or {spread: VALUE} (+- around each case)", spec)
        structure(spec, ParameterRangeBlock, at)  # its keys; the values take the parameter's dimension below
        spec = {key: value for key, value in spec.items() if value is not None}  # a key without a value: left out
        if name in swept and "spread" not in spec:
            raise FieldError(at, "a spread around each case's value (the sweep sets this field; an absolute range "
                                 "would override the sweep)", dict(spec))
        dimension = INPUTS[name].dimension
        input_spec = INPUTS[name]
        if "spread" in spec:
            if set(spec) != {"spread"}:
                raise FieldError(at, "either spread or low and high, not both", sorted(spec))
            spread = to_si(spec["spread"], dimension, f"{at}.spread")
            if not spread > 0 or not math.isfinite(spread):
                raise FieldError(f"{at}.spread", "a positive, finite spread", spec["spread"])
            parameters.append(Parameter(path, name, spread=spread))
            continue
        if set(spec) != {"low", "high"}:
            raise FieldError(at, "both low and high (or a spread)", sorted(spec))
        low, high = (to_si(spec[key], dimension, f"{at}.{key}") for key in ("low", "high"))
        for key, value in (("low", low), ("high", high)):
            if input_spec.out_of_range(np.array([value]))[0]:
                raise FieldError(f"{at}.{key}", input_spec.range_text(), spec[key])
        if not low < high:
            raise FieldError(at, "low below high", f"low {spec['low']}, high {spec['high']}")
        parameters.append(Parameter(path, name, low=low, high=high))
    if len({p.input for p in parameters}) != len(parameters):
        raise FieldError(f"{where}.parameters", "each input once", [p.path for p in parameters])
    choices = []
    if given.choices is not None and not isinstance(given.choices, Mapping):
        raise FieldError(f"{where}.choices", "a mapping from a choice's name to model ids of the study",
                         given.choices, choices=model_ids)
    for name, ids in (given.choices or {}).items():
        at = f"{where}.choices.{name}"
        if not isinstance(ids, list) or len(ids) < 2 or len(set(ids)) != len(ids):
            raise FieldError(at, "a list of at least two distinct model ids of the study", ids, choices=model_ids)
        for index, entry in enumerate(ids):
            if entry not in model_ids:
                raise FieldError(f"{at}[{index}]", "a model id of the study", entry, choices=model_ids)
        choices.append((str(name), tuple(ids)))
    models = model_ids if given.models is None else given.models
    if not isinstance(models, list) or not models:
        raise FieldError(f"{where}.models", "a list of model ids of the study", models, choices=model_ids)
    for index, entry in enumerate(models):
        if entry not in model_ids:
            raise FieldError(f"{where}.models[{index}]", "a model id of the study", entry, choices=model_ids)
    return SensitivitySpec(method, samples, seed, tuple(parameters), tuple(choices), tuple(models), levels)
