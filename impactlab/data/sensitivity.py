"""Sensitivity and model-form studies: how much each input and each modelling choice moves each output.

A study with a ``sensitivity:`` block runs, for every case of its sweep (e.g. three golf deliveries):

- **parameter uncertainty**: the inputs named under ``parameters`` are drawn from uniform ranges
  (absolute ``low``/``high``, or ``spread`` around each case's own value) by SALib's samplers, every
  model of ``models`` runs on the sample, and SALib's estimators give the indices: Sobol first-order
  ``S1`` and total ``ST`` (Saltelli's scheme; ``method: sobol``) or Morris's ``mu_star`` and ``sigma``
  (``method: morris``), with bootstrap confidence intervals. ``spread`` is the output's 5-95 % range
  over the sample, in the output's units;
- **model-form spread**: every model entry of the study runs at the nominal inputs; for each group of
  ``choices`` (e.g. the inelastic law: ``maw`` against ``maw`` with ``inelastic: hysteretic``) the range
  max - min over its entries is ``model_form_range``;
- **numerical error**: each model with a ``tolerance`` option runs the nominal inputs again at a tenth of
  its tolerance; the difference is ``numerical_error`` (0 for closed forms). Where the model says the
  tolerance was not met (``tolerance_not_met``, e.g. ``maw``'s hysteretic cases re-solved by annular
  strips at their ring cap) the refinement cannot measure the error and it is NaN.

The sampling and the indices are SALib's (Herman & Usher, J. Open Source Softw. 2 (2017) 97; Iwanaga,
Usher & Herman, Socio-Environ. Syst. Model. 4 (2022) 18155): Saltelli, Comput. Phys. Commun. 145 (2002)
280; Saltelli et al., Comput. Phys. Commun. 181 (2010) 259; Morris, Technometrics 33 (1991) 161;
Campolongo, Cariboni & Saltelli, Environ. Model. Softw. 22 (2007) 1509.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import platform
import warnings
from collections.abc import Mapping

import attrs
import numpy as np
import xarray as xr

from impactlab._version import __version__
from impactlab.io.results import RESULT_FORMAT
from impactlab.errors import FieldError
from impactlab.units import to_si
from impactlab.vocabulary import INPUT_BY_PATH, INPUTS, OUTPUTS, is_scalar

METHODS = ("sobol", "morris")
#: the percentiles whose distance is the parameter spread
SPREAD_PERCENTILES = (5.0, 95.0)


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


def parse_sensitivity(block, model_ids: list[str], scene_inputs: Mapping[str, float], swept: set[str],
                      where: str = "sensitivity") -> SensitivitySpec:
    """Validate a study's ``sensitivity:`` block; every error names the field, what it takes and what it got."""
    from impactlab.study.schema import ParameterRangeBlock, SensitivityBlock, keys_of, structure

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


def problem(spec: SensitivitySpec) -> dict:
    """SALib's problem: every parameter on [0, 1], mapped to its range per case (the indices do not change)."""
    return {"num_vars": len(spec.parameters), "names": [p.path for p in spec.parameters],
            "bounds": [[0.0, 1.0]] * len(spec.parameters)}


def unit_sample(spec: SensitivitySpec) -> np.ndarray:
    """The sample on [0, 1]^D from SALib: Saltelli's scheme (N (D + 2) rows) or Morris trajectories (N (D + 1))."""
    if spec.method == "sobol":
        from SALib.sample import sobol

        return sobol.sample(problem(spec), spec.samples, calc_second_order=False, seed=spec.seed)
    from SALib.sample import morris

    return morris.sample(problem(spec), spec.samples, num_levels=spec.levels, seed=spec.seed)


def indices(spec: SensitivitySpec, unit: np.ndarray, values: np.ndarray) -> dict[str, np.ndarray]:
    """SALib's indices of one output over the sample: arrays of one value per parameter.

    An output that does not vary over the sample (std below 1e-12 of its magnitude or 1e-9 in its units: the
    beta of a ball that leaves rolling in a rigid model, round-off only) has no indices: NaN.
    """
    size = len(spec.parameters)
    names = ("S1", "S1_conf", "ST", "ST_conf") if spec.method == "sobol" else ("mu_star", "mu_star_conf", "sigma")
    scale = max(float(np.nanmax(np.abs(values))), 1e-300) if np.any(np.isfinite(values)) else 1.0
    if not np.all(np.isfinite(values)) or np.std(values) <= max(1e-12 * scale, 1e-9):
        return {name: np.full(size, np.nan) for name in names}
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        if spec.method == "sobol":
            from SALib.analyze import sobol

            result = sobol.analyze(problem(spec), values, calc_second_order=False, num_resamples=200,
                                   conf_level=0.95, print_to_console=False, seed=spec.seed)
        else:
            from SALib.analyze import morris

            result = morris.analyze(problem(spec), unit, values, num_resamples=200, conf_level=0.95,
                                    print_to_console=False, num_levels=spec.levels, seed=spec.seed)
    return {name: np.asarray(result[name], dtype=float) for name in names}


def _sampled_inputs(study, spec: SensitivitySpec, base: dict[str, np.ndarray], unit: np.ndarray):
    """Inputs for every (case, sample): the case's inputs with the sampled parameters set (SI, flat, case-major)."""
    from impactlab.scene.core import ball_restitution, complete_inputs

    n_cases, n_samples = study.n_cases, unit.shape[0]
    inputs = {name: np.repeat(np.asarray(values, dtype=float), n_samples) for name, values in base.items()}
    for column, parameter in enumerate(spec.parameters):
        nominal = np.asarray(base[parameter.input], dtype=float)
        low, high = parameter.bounds(nominal)
        spec_in = INPUTS[parameter.input]
        for label, bound in (("low", low), ("high", high)):
            bad = spec_in.out_of_range(bound)
            if np.any(bad):
                case = int(np.argmax(bad))
                shown = float(bound[case]) * spec_in.display_factor
                raise FieldError(f"sensitivity.parameters.{parameter.path}.spread",
                                 f"a spread that keeps each case's range valid ({spec_in.range_text()})",
                                 f"{label} end {shown:g} {spec_in.display_unit or spec_in.unit} in case {case}")
        inputs[parameter.input] = (np.repeat(low, n_samples)
                                   + np.tile(unit[:, column], n_cases) * np.repeat(high - low, n_samples))
    complete_inputs(inputs)
    sampled = {p.input for p in spec.parameters}
    if study.scene.contact.restitution is None and study.scene.ball.restitution is not None \
            and "restitution" not in sampled:
        inputs["restitution"] = ball_restitution(study.scene.ball, inputs)
    if np.any(inputs["angle"] >= np.pi / 2):
        raise FieldError("sensitivity.parameters", "ranges whose every delivery meets the ball (spin loft < 90 deg)",
                         f"spin loft {np.degrees(np.max(inputs['angle'])):.1f} deg")
    return inputs


def _run(model, inputs, outputs) -> tuple[np.ndarray, np.ndarray]:
    """(outputs in the vocabulary's units, shape (n, n_outputs); validity flags)."""
    result = model.compute_arrays(inputs, list(outputs) + ["validity"])
    values = np.stack([result.in_units(name) for name in outputs], axis=-1)
    return values, np.nan_to_num(result["validity"]).astype(np.int64)


def run_sensitivity(study, progress=None) -> xr.Dataset:
    """Run a study's sensitivity block: indices, parameter spread, model-form range and numerical error.

    Returns
    -------
    xarray.Dataset
        Dimensions ``model``, the study's sweep dimensions, ``parameter``, ``output``, ``choice`` and
        ``sample``; every variable in the units of its output (``output_units``), with provenance.
    """
    from impactlab.run.runner import case_inputs

    say = progress or (lambda text: None)
    spec = study.sensitivity
    outputs = list(study.outputs)
    for name in outputs:
        if not is_scalar(name) or OUTPUTS[name].diagnostic:
            raise FieldError("outputs", "scalar outputs for a sensitivity study", name)
    base = case_inputs(study)
    entries = {entry.id: entry for entry in study.models}
    ids = list(entries)
    n_cases, n_out, n_par = study.n_cases, len(outputs), len(spec.parameters)
    unit = unit_sample(spec)
    n_samples = unit.shape[0]
    try:  # the sampled ranges are checked before anything runs
        inputs = _sampled_inputs(study, spec, base, unit)
    except FieldError as exc:
        raise exc.at(file=study.file) from None
    # model form and numerical error, at the nominal inputs, every model
    nominal = np.full((len(ids), n_cases, n_out), np.nan)
    numerical = np.zeros_like(nominal)
    validity = np.zeros((len(ids), n_cases), dtype=np.int64)
    for m, entry_id in enumerate(ids):
        model = entries[entry_id].model
        nominal[m], flags = _run(model, base, outputs)
        validity[m] = flags
        if model.has_tolerance:  # declared (rule 8 of ImpactModel): its tolerance sets the numerical error
            finer = type(model)(attrs.evolve(model.options, tolerance=model.options.tolerance / 10.0))
            fine, _ = _run(finer, base, outputs)
            numerical[m] = np.abs(fine - nominal[m])
            numerical[m][(flags & 4) != 0] = np.nan
        say(f"{entry_id}: nominal cases done")
    choices = list(spec.choices) + [("all models", tuple(ids))]
    form = np.stack([np.nanmax(nominal[[ids.index(i) for i in group]], axis=0)
                     - np.nanmin(nominal[[ids.index(i) for i in group]], axis=0) for _, group in choices])
    form[form <= 1e-9] = 0.0  # models that agree to round-off (in the outputs' units)
    # parameter uncertainty, the models of the block
    index_names = ("S1", "S1_conf", "ST", "ST_conf") if spec.method == "sobol" else ("mu_star", "mu_star_conf",
                                                                                         "sigma")
    found = {name: np.full((len(ids), n_cases, n_par, n_out), np.nan) for name in index_names}
    sampled = np.full((len(ids), n_cases, n_samples, n_out), np.nan)
    spread = np.full((len(ids), n_cases, n_out), np.nan)
    deviation = np.full_like(spread, np.nan)
    for entry_id in spec.models:
        m = ids.index(entry_id)
        values, _ = _run(entries[entry_id].model, inputs, outputs)
        sampled[m] = values.reshape(n_cases, n_samples, n_out)
        for c in range(n_cases):
            for o in range(n_out):
                column = sampled[m, c, :, o]
                low, high = np.nanpercentile(column, SPREAD_PERCENTILES)
                spread[m, c, o], deviation[m, c, o] = high - low, np.nanstd(column)
                if deviation[m, c, o] <= 1e-9:  # round-off of an output that does not move (rigid beta = 0)
                    spread[m, c, o] = deviation[m, c, o] = 0.0
                for name, value in indices(spec, unit, column).items():
                    found[name][m, c, :, o] = value
        say(f"{entry_id}: {n_cases * n_samples} sampled impacts done")
    dataset = _dataset(study, spec, ids, outputs, choices, unit, nominal, numerical, form, found, sampled, spread,
                       deviation)
    from impactlab.model.diagnostics import flag_attributes

    dims = ("model",) + tuple(axis.dim for axis in study.sweep)
    dataset["validity"] = (dims, validity.reshape((len(ids),) + tuple(study.shape)),
                           {"units": "1", "long_name": "validity flags of the nominal runs (docs/accuracy.md)",
                            **flag_attributes()})
    return dataset


_LONG_NAMES = {
    "S1": "Sobol first-order index (share of the output's variance from this input alone)",
    "S1_conf": "95 % bootstrap half-width of S1",
    "ST": "Sobol total index (share of the variance that involves this input)",
    "ST_conf": "95 % bootstrap half-width of ST",
    "mu_star": "Morris mean absolute elementary effect, over the input's whole range [output units]",
    "mu_star_conf": "95 % bootstrap half-width of mu_star [output units]",
    "sigma": "Morris standard deviation of the elementary effects (interactions, non-linearity) [output units]",
}


def _dataset(study, spec, ids, outputs, choices, unit, nominal, numerical, form, found, sampled, spread,
             deviation) -> xr.Dataset:
    dims = [axis.dim for axis in study.sweep]
    shape = study.shape

    def variable(array, lead, tail, attrs_):
        values = array.reshape(array.shape[:len(lead)] + tuple(shape) + array.shape[len(lead) + 1:])
        return (tuple(lead) + tuple(dims) + tuple(tail), values, attrs_)

    data = {
        "nominal": variable(nominal, ["model"], ["output"], {"long_name": "output at the nominal inputs"}),
        "numerical_error": variable(numerical, ["model"], ["output"], {
            "long_name": "numerical error at the nominal inputs: |result at the model's tolerance - result at a "
                         "tenth of it| (0: closed form; NaN: tolerance not met, not measurable this way)"}),
        "model_form_range": variable(form, ["choice"], ["output"], {
            "long_name": "range (max - min) of the output over the model entries of each modelling choice, "
                         "nominal inputs"}),
        "spread": variable(spread, ["model"], ["output"], {
            "long_name": f"parameter spread: {SPREAD_PERCENTILES[0]:g}-{SPREAD_PERCENTILES[1]:g} percentile range "
                         "of the output over the sampled inputs"}),
        "std": variable(deviation, ["model"], ["output"], {"long_name": "standard deviation of the output over "
                                                                        "the sampled inputs"}),
        "sampled": variable(sampled, ["model"], ["sample", "output"], {"long_name": "output at each sample"}),
    }
    for name, array in found.items():
        data[name] = variable(array, ["model"], ["parameter", "output"], {"long_name": _LONG_NAMES[name]})
    coords = {"model": ids, "output": outputs, "output_units": ("output", [OUTPUTS[name].units for name in outputs]),
              "parameter": [p.path for p in spec.parameters],
              "parameter_range": ("parameter", [p.describe() for p in spec.parameters]),
              "choice": [name for name, _ in choices],
              "choice_models": ("choice", [", ".join(group) for _, group in choices]),
              "sample_unit": (("sample", "parameter"), unit,
                              {"long_name": "sample on [0, 1] per parameter (0: low end, 1: high end of its "
                                            "range in each case)"})}
    dataset = xr.Dataset(data, coords=coords)
    for axis in study.sweep:
        if axis.grouped:
            dataset = dataset.assign_coords({axis.dim: list(axis.labels) if axis.labels else list(range(axis.size))})
        for field in axis.fields:
            input_spec = INPUTS[field.input]
            values = [float(f"{value * input_spec.display_factor:.12g}") for value in field.values]
            dataset = dataset.assign_coords({field.coord: (axis.dim, values)})
            dataset[field.coord].attrs = {"units": input_spec.display_unit or input_spec.unit,
                                          "long_name": input_spec.description, "study_path": field.path}
    models = [{"id": entry.id, "name": entry.name, "options": entry.model.options_dict(),
               "references": list(entry.model.references)} for entry in study.models]
    dataset.attrs = {
        "title": f"impactlab sensitivity study {study.name}",
        "study_type": "sensitivity",
        "study_name": study.name,
        "study_description": study.description,
        "study_file": study.file or "",
        "study_source": study.source,
        "sensitivity": json.dumps(spec.as_dict()),
        "sampler": ("SALib.sample.sobol (Saltelli, no second order)" if spec.method == "sobol"
                    else f"SALib.sample.morris ({spec.levels} levels)"),
        "analyser": "SALib.analyze.sobol" if spec.method == "sobol" else "SALib.analyze.morris",
        "salib_version": _salib_version(),
        "models": json.dumps(models),
        "impactlab_version": __version__, "impactlab_format": RESULT_FORMAT,
        "python_version": platform.python_version(),
        "numpy_version": np.__version__,
        "xarray_version": xr.__version__,
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "method": __doc__.strip().split("\n\n")[1].replace("\n", " "),
    }
    return dataset


def _salib_version() -> str:
    from importlib.metadata import version

    return version("SALib")


def _case_labels(dataset: xr.Dataset) -> list[tuple[dict, str]]:
    dims = [dim for dim in dataset["nominal"].dims if dim not in ("model", "output")]
    if not dims:
        return [({}, "")]
    grids = np.meshgrid(*[np.arange(dataset.sizes[d]) for d in dims], indexing="ij")
    labels = []
    for flat in range(grids[0].size):
        where = {d: int(g.reshape(-1)[flat]) for d, g in zip(dims, grids)}
        text = ", ".join(str(dataset[d].values[i]) for d, i in where.items())
        labels.append((where, text))
    return labels


def plot_sensitivity(dataset: xr.Dataset, path) -> list:
    """Two figures: the three error sources side by side per output and case, and the indices of each model.

    ``path`` names the first PNG; the second gets ``_indices`` added to its stem.
    """
    from pathlib import Path

    import matplotlib.ticker
    # a bare Figure, no pyplot: drawing never changes the caller's backend or open figures
    from matplotlib.figure import Figure

    path = Path(path)
    outputs = list(dataset.output.values)
    cases = _case_labels(dataset)
    analysed = [m for m in dataset.model.values if np.any(np.isfinite(dataset["spread"].sel(model=m).values))]
    figure = Figure(figsize=(max(4.6 * len(cases), 9.0), 2.9 * len(outputs)))
    axes = figure.subplots(len(outputs), len(cases), squeeze=False)
    colours = {"numerical": "tab:grey", "parameter": "tab:blue", "form": "tab:red"}
    for row, output in enumerate(outputs):
        unit = str(dataset.output_units.sel(output=output).values)
        for column, (where, label) in enumerate(cases):
            axis = axes[row, column]
            bars = []
            error = dataset["numerical_error"].isel(where).sel(output=output)
            for model in dataset.model.values:
                value = float(error.sel(model=model))
                bars.append((f"numerical: {model}", value, "numerical"))
            for model in analysed:
                bars.append((f"parameters: {model}", float(dataset["spread"].isel(where).sel(model=model,
                                                                                          output=output)), "parameter"))
            for choice in dataset.choice.values:
                bars.append((f"model form: {choice}", float(dataset["model_form_range"].isel(where).sel(
                    choice=choice, output=output)), "form"))
            positives = [value for _, value, _ in bars if np.isfinite(value) and value > 0]
            floor = (min(positives) if positives else 1.0) / 30.0
            for position, (_, value, kind) in enumerate(bars):
                shown = value if np.isfinite(value) and value > 0 else floor
                axis.barh(position, shown, color=colours[kind], alpha=1.0 if np.isfinite(value) and value > 0
                          else 0.25)
                if not (np.isfinite(value) and value > 0):
                    words = {"numerical": " exact (closed form)", "parameter": " 0 (does not move)",
                             "form": " 0 (the models agree)"}[kind] if value == 0 \
                        else " not measured (tolerance not met)"
                    axis.text(shown, position, words, va="center", fontsize=6)
            axis.set_yticks(range(len(bars)))
            axis.set_yticklabels([text for text, _, _ in bars] if column == 0 else [], fontsize=6)
            axis.invert_yaxis()
            axis.set_xscale("log")
            axis.grid(True, axis="x", which="major", alpha=0.3)
            axis.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
            axis.tick_params(axis="x", labelsize=7)
            axis.set_xlabel(f"{output} [{unit}]", fontsize=8)
            if row == 0:
                axis.set_title(label, fontsize=9)
    from matplotlib.patches import Patch

    figure.legend(handles=[Patch(color=colours["numerical"], label="numerical error (|tolerance - tolerance/10|)"),
                           Patch(color=colours["parameter"], label="parameter uncertainty (5-95 % range over the "
                                                                    "sampled inputs)"),
                           Patch(color=colours["form"], label="model form (max - min over the choice's models)")],
                  loc="lower center", ncol=3 if len(cases) > 2 else 1, fontsize=8, frameon=False)
    figure.suptitle(f"{dataset.attrs.get('study_name', '')}: numerical error, parameter uncertainty and model form "
                    "(log scale)", fontsize=10)
    figure.tight_layout(rect=(0, 0.03 if len(cases) > 2 else 0.08, 1, 0.97))
    figure.savefig(path, dpi=110)
    pictures = [path]

    total = "ST" if "ST" in dataset else "mu_star"
    parameters = list(dataset.parameter.values)
    figure = Figure(figsize=(4.2 * len(cases), 0.5 + 0.45 * len(parameters) * len(analysed) + 0.6 * len(analysed)))
    axes = figure.subplots(len(analysed), len(cases), squeeze=False)
    for row, model in enumerate(analysed):
        for column, (where, label) in enumerate(cases):
            axis = axes[row, column]
            values = dataset[total].isel(where).sel(model=model).transpose("parameter", "output").values
            with warnings.catch_warnings(), np.errstate(all="ignore"):  # an output that does not move: all NaN
                warnings.simplefilter("ignore")
                shown = values if total == "ST" else values / np.nanmax(np.abs(values), axis=0, keepdims=True)
            image = axis.imshow(np.nan_to_num(shown, nan=0.0), vmin=0, vmax=1, cmap="Blues", aspect="auto")
            for i in range(len(parameters)):
                for j in range(len(outputs)):
                    value = values[i, j]
                    axis.text(j, i, "n/a" if not np.isfinite(value) else f"{value:.2f}" if total == "ST"
                              else f"{value:.3g}", ha="center", va="center", fontsize=7,
                              color="white" if np.isfinite(shown[i, j]) and shown[i, j] > 0.6 else "black")
            axis.set_xticks(range(len(outputs)))
            labels = [f"{name} [{unit}]" for name, unit in zip(outputs, dataset.output_units.values)]
            axis.set_xticklabels(labels if row == len(analysed) - 1 else [], rotation=30, ha="right", fontsize=7)
            axis.set_yticks(range(len(parameters)))
            axis.set_yticklabels(parameters if column == 0 else [], fontsize=7)
            axis.set_title(f"{model}, {label}" if label else str(model), fontsize=8)
    figure.colorbar(image, ax=axes, shrink=0.6, label="Sobol total index ST [1]" if total == "ST"
                    else "Morris mu* / largest mu* of the output [1]")
    figure.suptitle(f"{dataset.attrs.get('study_name', '')}: "
                    + ("Sobol total indices (share of each output's variance involving each input)" if total == "ST"
                       else "Morris mu* (output units; shading relative per output)")
                    + "; n/a: the output does not move over the sample", fontsize=10)
    second = path.with_name(f"{path.stem}_indices.png")
    figure.savefig(second, dpi=110, bbox_inches="tight")
    pictures.append(second)
    return pictures
