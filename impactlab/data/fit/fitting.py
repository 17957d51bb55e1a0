"""Estimate a model's free parameters from measured launch data, with uncertainty (``impactlab fit``).

Weighted least squares (scipy.optimize.least_squares, trust region with
bounds) of the model's prediction against a :class:`~impactlab.data.validation.MeasuredData`
set: residuals (predicted - measured)/sigma, sigma the source's stated
uncertainty, or 1 when it gives none. The optimiser, the covariance (rescaled
by the reduced chi-square SSR/(n - p) when the source gives no uncertainty)
and the rules for "identified" and "at its bound" are those of
:mod:`impactlab.data.fit.least_squares`, shared with the shot-table calibration.
Points the model cannot predict (a non-finite prediction) are left out and
named.
"""

from __future__ import annotations

from collections.abc import Sequence

import attrs
import numpy as np

from impactlab.data.fit import least_squares
from impactlab.errors import FieldError
from impactlab.study.arrays import case_inputs
from impactlab.data.validation import MeasuredData, load_dataset_study, point_order

#: fittable parameter -> (where it lives, bounds, start); "input" parameters replace a scene input for every
#: case, "option" parameters a model option
PARAMETERS: dict[str, tuple[str, tuple[float, float], float]] = {
    "friction": ("input", (0.02, 1.5), 0.4),
    "tangential_restitution": ("option", (-1.0, 1.0), 0.1),
}
#: what each model fits by default
DEFAULT_PARAMETERS: dict[str, tuple[str, ...]] = {"restitution": ("friction", "tangential_restitution")}


@attrs.frozen
class FitResult:
    """A least-squares fit of one model's parameters to a measured dataset.

    Uncertainties are one standard deviation, not variances (inf where the data do not identify the
    parameter); ``identified``, ``at_bound`` and ``near_bound`` follow :mod:`impactlab.data.fit.least_squares`;
    ``residuals`` are predicted minus measured at the optimum over the points used, ``rms`` their root mean
    square and ``start_rms`` the same before fitting; ``unused_points`` names the measured points left out
    (the model could not predict them)."""
    model: str
    dataset: str
    parameters: tuple[str, ...]
    values: tuple[float, ...]
    uncertainties: tuple[float, ...]  # one standard deviation; inf when not identified
    identified: tuple[bool, ...]
    at_bound: tuple[bool, ...]  # the optimum sits on the parameter's bound: the data want more than it allows
    residuals: tuple[float, ...]  # predicted - measured at the optimum
    rms: float
    start_rms: float
    near_bound: tuple[bool, ...] = ()  # the bound lies within one standard deviation
    unused_points: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """The fit as plain data (JSON-ready)."""
        return attrs.asdict(self)


def describe(result: FitResult) -> str:
    """One line: each parameter with its one-sigma uncertainty, its bound or 'not identified' said
    (:func:`impactlab.data.fit.least_squares.state`), and the points left out."""
    near = result.near_bound or (False,) * len(result.parameters)
    lines = [f"{name} = {least_squares.state(value, sigma, known, at, close, spec='.3f', sigma_spec='.3f')}"
             for name, value, sigma, known, at, close in zip(result.parameters, result.values, result.uncertainties,
                                                             result.identified, result.at_bound, near)]
    if result.unused_points:
        lines.append(f"points not used (the model cannot predict them): {', '.join(result.unused_points)}")
    return "; ".join(lines)


def fit(data: MeasuredData, model_id: str, parameters: Sequence[str] | None = None) -> FitResult:
    """Fit ``parameters`` of the study model ``model_id`` to ``data``."""
    study = load_dataset_study(data)
    entries = {entry.id: entry for entry in study.models}
    if model_id not in entries:
        raise FieldError("--model", "a model of the dataset's study", model_id, choices=sorted(entries))
    entry = entries[model_id]
    parameters = tuple(parameters or DEFAULT_PARAMETERS.get(entry.name, ("friction",)))
    options = entry.model.options_dict()
    for name in parameters:
        if name not in PARAMETERS:
            raise FieldError("--parameter", "a fittable parameter", name, choices=sorted(PARAMETERS))
        if PARAMETERS[name][0] == "option" and name not in options:
            raise FieldError("--parameter", f"a parameter of model {entry.name!r}", name,
                             choices=[p for p in PARAMETERS if PARAMETERS[p][0] == "input" or p in options])
    base = case_inputs(study)
    order = np.asarray(point_order(data, study))
    sigma = np.asarray(data.sigma, dtype=float) if data.sigma is not None else np.ones(len(data.values))
    measured = np.asarray(data.measured, dtype=float)

    def predict(vector):
        inputs = dict(base)
        model_options = dict(options)
        for name, value in zip(parameters, vector):
            if PARAMETERS[name][0] == "input":
                inputs[name] = np.full_like(base[name], value)
            else:
                model_options[name] = float(value)
        model = type(entry.model)(**model_options)
        return np.asarray(model.compute_arrays(inputs, [data.quantity]).in_units(data.quantity))[order]

    start = np.array([options.get(name, PARAMETERS[name][2]) if PARAMETERS[name][0] == "option"
                      else float(np.mean(base[name])) for name in parameters])
    lower = np.array([PARAMETERS[name][1][0] for name in parameters])
    upper = np.array([PARAMETERS[name][1][1] for name in parameters])
    start = np.clip(start, lower + 1e-6, upper - 1e-6)
    usable = least_squares.usable_rows(predict(start), measured)
    if not usable.any():
        raise FieldError("--model", f"a model that can predict {data.name}'s points", model_id)
    unused = tuple(str(label) for label, ok in zip(data.labels, usable) if not ok)

    def residuals(vector):
        return ((predict(vector) - measured) / sigma)[usable]

    solution = least_squares.solve(residuals, start, lower, upper, weighted=data.sigma is not None,
                                   names=parameters)
    final = solution.residuals * sigma[usable]  # predicted - measured at the optimum
    first = solution.start_residuals * sigma[usable]
    return FitResult(model_id, data.name, parameters, tuple(float(v) for v in solution.values),
                     tuple(float(u) for u in solution.uncertainties), tuple(bool(i) for i in solution.identified),
                     tuple(bool(b) for b in solution.at_bound),
                     tuple(float(r) for r in final), float(np.sqrt(np.mean(final**2))),
                     float(np.sqrt(np.mean(first**2))), tuple(bool(b) for b in solution.near_bound), unused)
