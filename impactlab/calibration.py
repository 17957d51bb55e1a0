"""Calibrate a model's ball and contact parameters to launch-monitor shots, and cross-validate the calibration.

Weighted least squares (scipy.optimize.least_squares, bounded trust region) of
the model's predicted ball speed, launch angle, launch direction, spin rate and
spin axis against every measured value of a :class:`~impactlab.shots.ShotTable`,
each residual divided by its measurement uncertainty. Several parameters at
once: friction, the cover's tangential loss, a linear restitution law (e at a
normal speed of 40 m/s and its slope) and a mean strike offset up the face.
The covariance is (J^T J)^-1 at the optimum (the residuals are in units of
their sigma, so it is not rescaled), with its correlation matrix; a parameter
whose one-sigma uncertainty exceeds half its allowed range, or whose column of
J vanishes, is reported as not identified by the data.

Cross-validation: leave one row out, fit on the others, predict it; the errors
on the rows not fitted are the honest measure of what a calibration buys.
"""

from __future__ import annotations

import math

import attrs
import numpy as np
from scipy.optimize import least_squares

from .errors import FieldError
from .materials import RestitutionLaw
from .shots import MEASURED_FIELDS, ShotTable, predict, shot_errors, summary, table_inputs

#: parameter -> (bounds, start, what it is)
PARAMETERS = {
    "friction": ((0.05, 1.0), 0.4, "Coulomb friction of ball and face"),
    "tangential_loss": ((0.0, 1.5), 0.2, "loss factor of the cover in shear (compliant models)"),
    "restitution": ((0.5, 0.95), 0.8, "normal restitution at a normal speed of 40 m/s"),
    "restitution_slope": ((-0.01, 0.004), -0.002, "de/dv of the restitution law [s/m]"),
    "strike_high": ((-0.015, 0.015), 0.0, "mean strike offset up the face [m]"),
}
REFERENCE_SPEED = 40.0
DEFAULT_PARAMETERS = ("friction", "tangential_loss", "restitution", "restitution_slope")


@attrs.frozen
class Calibration:
    model: str
    table: str
    parameters: tuple[str, ...]
    values: tuple[float, ...]
    uncertainties: tuple[float, ...]
    correlation: tuple[tuple[float, ...], ...]
    identified: tuple[bool, ...]
    singular_values: tuple[float, ...]
    rms_before: float  # RMS of the weighted residuals at the start values
    rms_after: float
    errors_before: dict = attrs.field(eq=False)  # summary(shot_errors) before and after
    errors_after: dict = attrs.field(eq=False)

    def as_dict(self) -> dict:
        return attrs.asdict(self)

    def describe(self) -> str:
        lines = []
        for name, value, sigma, ok in zip(self.parameters, self.values, self.uncertainties, self.identified):
            state = f"{value:.4g} +- {sigma:.2g}" if ok else f"{value:.4g} (not identified by these data)"
            lines.append(f"{name} = {state}")
        return "; ".join(lines)


def apply(inputs: dict, names, values) -> dict:
    """The inputs with the parameters ``names`` set to ``values`` (SI)."""
    from .physics.contact import contact_state

    out = {key: np.array(value, dtype=float) for key, value in inputs.items()}
    given = dict(zip(names, values))
    n = out["speed"].size
    if "friction" in given:
        out["friction"] = np.full(n, given["friction"])
    if "tangential_loss" in given:
        out["tangential_loss"] = np.full(n, given["tangential_loss"])
    if "strike_high" in given:
        out["strike_high"] = out.get("strike_high", np.zeros(n)) + given["strike_high"]
    if "restitution" in given or "restitution_slope" in given:
        law = RestitutionLaw("linear", given.get("restitution", 0.8), REFERENCE_SPEED,
                             slope=given.get("restitution_slope", 0.0))
        out["restitution"] = law(contact_state(out)["normal_speed"])
    return out


def _residuals(model, inputs, table: ShotTable, names, values) -> np.ndarray:
    predicted = predict(model, apply(inputs, names, values))
    parts = []
    for key in MEASURED_FIELDS:
        measured = table.measured[key]
        keep = np.isfinite(measured)
        difference = predicted[key][keep] - measured[keep]
        if key in ("horizontal_launch_angle", "spin_axis"):
            difference = (difference + math.pi) % (2 * math.pi) - math.pi
        parts.append(difference / table.sigma[key][keep])
    return np.concatenate(parts)


def calibrate(model, table: ShotTable, parameters=DEFAULT_PARAMETERS, ball: dict | None = None,
              start: dict | None = None) -> Calibration:
    """Fit ``parameters`` of ``model`` (an ImpactModel instance) to every measured value of ``table``."""
    names = tuple(parameters)
    for name in names:
        if name not in PARAMETERS:
            raise FieldError("--parameter", "a parameter the calibration can fit", name, choices=PARAMETERS)
    if "tangential_loss" in names and "tangential_loss" not in model.optional_inputs | model.requires:
        raise FieldError("--parameter", f"a parameter model {model.name!r} uses (it has no tangential loss)",
                         "tangential_loss", choices=[n for n in PARAMETERS if n != "tangential_loss"])
    inputs = table_inputs(table, ball)
    low = np.array([PARAMETERS[name][0][0] for name in names])
    high = np.array([PARAMETERS[name][0][1] for name in names])
    x0 = np.array([(start or {}).get(name, PARAMETERS[name][1]) for name in names], dtype=float)
    x0 = np.clip(x0, low, high)

    def residuals(x):
        return _residuals(model, inputs, table, names, x)

    before = residuals(x0)
    # finite-difference steps of 1 % of each range: well above the models' discretisation error (1e-4)
    solution = least_squares(residuals, x0, bounds=(low, high), x_scale=high - low,
                             diff_step=0.01 * (high - low) / np.maximum(np.abs(x0), 1e-3), method="trf")
    jacobian = solution.jac
    scaled = jacobian * (high - low)
    singular = np.linalg.svd(scaled, compute_uv=False)
    try:
        covariance = np.linalg.pinv(jacobian.T @ jacobian)
    except np.linalg.LinAlgError:  # pragma: no cover - pinv does not raise for finite input
        covariance = np.full((len(names), len(names)), np.inf)
    sigma = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    column = np.linalg.norm(jacobian, axis=0)
    identified = (column > 1e-9 * max(column.max(), 1e-300)) & (sigma < 0.5 * (high - low))
    with np.errstate(invalid="ignore", divide="ignore"):
        correlation = covariance / np.outer(sigma, sigma)
    after_inputs = apply(inputs, names, solution.x)
    return Calibration(
        model=model.name, table=table.name, parameters=names, values=tuple(float(v) for v in solution.x),
        uncertainties=tuple(float(s) if ok else math.inf for s, ok in zip(sigma, identified)),
        correlation=tuple(tuple(float(c) for c in row) for row in correlation),
        identified=tuple(bool(v) for v in identified), singular_values=tuple(float(s) for s in singular),
        rms_before=float(np.sqrt(np.mean(before**2))), rms_after=float(np.sqrt(np.mean(solution.fun**2))),
        errors_before=summary(shot_errors(predict(model, apply(inputs, names, x0)), table)),
        errors_after=summary(shot_errors(predict(model, after_inputs), table)))


def cross_validate(model, table: ShotTable, parameters=DEFAULT_PARAMETERS, ball: dict | None = None,
                   folds=None) -> dict:
    """Fit on all rows but some, predict those; by default leave one row out at a time.

    Returns per-row errors on the rows left out (``shot_errors`` keys), their RMS (``summary``), and the fitted
    values of each fold.
    """
    folds = folds or [[i] for i in range(table.size)]
    held = {key: np.full(table.size, np.nan) for key in ("ball_speed [%]", "launch angle [deg]",
                                                         "launch direction [deg]", "spin [%]", "spin axis [deg]")}
    fits = []
    for rows in folds:
        train = np.setdiff1d(np.arange(table.size), rows)
        if train.size == 0:
            raise FieldError("folds", "folds that leave rows to fit on", rows)
        result = calibrate(model, table.subset(train), parameters, ball)
        fits.append(dict(zip(result.parameters, result.values)))
        test = table.subset(np.asarray(rows))
        predicted = predict(model, apply(table_inputs(test, ball), result.parameters, result.values))
        for key, values in shot_errors(predicted, test).items():
            held[key][np.asarray(rows)] = values
    return {"errors": held, "summary": summary(held), "fits": fits, "labels": table.labels}
