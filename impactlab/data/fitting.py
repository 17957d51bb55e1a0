"""Estimate a model's free parameters from measured launch data, with uncertainty (``impactlab fit``).

Weighted least squares (scipy.optimize.least_squares, trust region with
bounds) of the model's prediction against a :class:`~impactlab.data.validation.MeasuredData`
set: residuals (predicted - measured)/sigma, sigma the source's stated
uncertainty, or 1 when it gives none. The parameter covariance is
(J^T J)^-1 at the optimum, scaled by the residual variance SSR/(n - p) when
the source gives no uncertainty (and n > p). A parameter the data do not
constrain (its column of J vanishes) is reported as not identified.
"""

from __future__ import annotations

from collections.abc import Sequence

import attrs
import numpy as np
from scipy.optimize import least_squares

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

    Uncertainties are one standard deviation (inf where the data do not identify the parameter);
    ``residuals`` are predicted minus measured at the optimum, ``rms`` their root mean square and
    ``start_rms`` the same before fitting."""
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

    def as_dict(self) -> dict:
        """The fit as plain data (JSON-ready)."""
        return attrs.asdict(self)


def describe(result: FitResult) -> str:
    """One line per parameter, in words."""
    lines = []
    for name, value, sigma, identified, bound in zip(result.parameters, result.values, result.uncertainties,
                                                     result.identified, result.at_bound):
        if not identified:
            lines.append(f"{name} = not identified (the data do not depend on it; left at {value:.3g})")
        elif bound:
            lines.append(f"{name} = {value:.3f} (at its bound: the model cannot reach the data)")
        else:
            lines.append(f"{name} = {value:.3f} +- {sigma:.3f}")
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
    order = point_order(data, study)
    sigma = np.asarray(data.sigma, dtype=float) if data.sigma is not None else np.ones(len(data.values))
    measured = data.measured

    def predict(vector):
        inputs = dict(base)
        model_options = dict(options)
        for name, value in zip(parameters, vector):
            if PARAMETERS[name][0] == "input":
                inputs[name] = np.full_like(base[name], value)
            else:
                model_options[name] = float(value)
        model = type(entry.model)(**model_options)
        return model.compute_arrays(inputs, [data.quantity]).in_units(data.quantity)[order]

    def residuals(vector):
        return (predict(vector) - measured) / sigma

    start = np.array([options.get(name, PARAMETERS[name][2]) if PARAMETERS[name][0] == "option"
                      else float(np.mean(base[name])) for name in parameters])
    lower = np.array([PARAMETERS[name][1][0] for name in parameters])
    upper = np.array([PARAMETERS[name][1][1] for name in parameters])
    start = np.clip(start, lower + 1e-6, upper - 1e-6)
    # relative finite-difference steps of 1e-2 keep the models' discretisation (a resolution that can change
    # with the parameter, errors ~ tolerance = 1e-4) a few percent of each difference
    solution = least_squares(residuals, start, bounds=(lower, upper), diff_step=1e-2, x_scale="jac")
    jacobian = solution.jac
    n, p = len(measured), len(parameters)
    identified = np.linalg.norm(jacobian, axis=0) > 1e-6 * max(1.0, float(np.linalg.norm(jacobian)))
    uncertainties = np.full(p, np.inf)
    if identified.any():
        block = jacobian[:, identified]
        covariance = np.linalg.pinv(block.T @ block)
        if data.sigma is None and n > identified.sum():
            covariance *= 2.0 * solution.cost / (n - identified.sum())
        uncertainties[identified] = np.sqrt(np.diag(covariance))
    final = solution.fun * sigma  # predicted - measured at the optimum
    at_bound = np.isclose(solution.x, lower, rtol=0, atol=1e-4) | np.isclose(solution.x, upper, rtol=0, atol=1e-4)
    return FitResult(model_id, data.name, parameters, tuple(float(v) for v in solution.x),
                     tuple(float(u) for u in uncertainties), tuple(bool(i) for i in identified),
                     tuple(bool(b) for b in at_bound),
                     tuple(float(r) for r in final), float(np.sqrt(np.mean(final**2))),
                     float(np.sqrt(np.mean((predict(start) - measured) ** 2))))
