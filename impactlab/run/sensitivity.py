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
import platform
import warnings
from collections.abc import Callable
from importlib.metadata import version

import attrs
import numpy as np
import xarray as xr

from impactlab._version import __version__
from impactlab.io.results import RESULT_FORMAT
from impactlab.errors import FieldError
from impactlab.model.diagnostics import flag_attributes
from impactlab.scene.core import ball_restitution, complete_inputs
from impactlab.study.arrays import case_inputs
from impactlab.study.core import Study
from impactlab.study.sensitivity import SensitivitySpec
from impactlab.vocabulary import INPUTS, OUTPUTS, is_scalar

#: the percentiles whose distance is the parameter spread
SPREAD_PERCENTILES = (5.0, 95.0)


def problem(spec: SensitivitySpec) -> dict:
    """SALib's problem: every parameter on [0, 1], mapped to its range per case (the indices do not change)."""
    return {"num_vars": len(spec.parameters), "names": [p.path for p in spec.parameters],
            "bounds": [[0.0, 1.0]] * len(spec.parameters)}


def unit_sample(spec: SensitivitySpec) -> np.ndarray:
    """The sample on [0, 1]^D from SALib: Saltelli's scheme (N (D + 2) rows) or Morris trajectories (N (D + 1))."""
    # SALib is imported where it is used: it is heavy (scipy, pandas) and only sensitivity studies need it
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


def run_sensitivity(study: Study, progress: Callable[[str], None] | None = None) -> xr.Dataset:
    """Run a study's sensitivity block: indices, parameter spread, model-form range and numerical error.

    Returns
    -------
    xarray.Dataset
        Dimensions ``model``, the study's sweep dimensions, ``parameter``, ``output``, ``choice`` and
        ``sample``; every variable in the units of its output (``output_units``), with provenance.
    """
    say = progress or (lambda text: None)
    spec = study.sensitivity
    if spec is None:
        raise ValueError(f"study {study.name!r} has no sensitivity block to run")
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
    return version("SALib")
