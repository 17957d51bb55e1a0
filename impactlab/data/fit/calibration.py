"""Calibrate a model's ball and contact parameters to launch-monitor shots, and cross-validate the calibration.

Weighted least squares (``scipy.optimize.least_squares``, bounded trust region)
of the model's predicted ball speed, launch angle, launch direction, spin rate
and spin axis against every measured value of a
:class:`~impactlab.data.sessions.shots.ShotTable`, each residual divided by its measurement
uncertainty. Several parameters at once (:data:`PARAMETERS`): friction, the
cover's tangential loss, a linear restitution law of the normal speed (e at
40 m/s and its slope), the restitution gain of a thin wood face, and a mean
strike offset up the face. The optimiser, the covariance (not rescaled: the
residuals are in units of their sigma), and the rules for "identified", "at its
bound" and "beyond a physical limit" (a driver's COR above the USGA/R&A limit of
0.830) are those of :mod:`impactlab.data.fit.least_squares`, shared with
:mod:`impactlab.data.fit.fitting`. Rows the model cannot predict (a non-finite
prediction of a measured value) are left out and named.

Cross-validation: fit on all rows but some, predict those; by default one row
is left out at a time. The errors on the rows not fitted are the honest
measure of what a calibration buys.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np

from impactlab.data.fit import least_squares
from impactlab.errors import FieldError
from impactlab.model.base import ImpactModel
from impactlab.scene.materials import Ball, RestitutionLaw
from impactlab.data.sessions.shots import (
    ERROR_KEYS, MEASURED_FIELDS, ShotTable, errors_by_source, predict, shot_errors, summary, table_inputs,
)
from impactlab.physics.contact import approach_state
from impactlab.study.scene_blocks import build_ball

#: parameter -> (bounds, start, what it is). A ball's restitution is bounded not to rise with the impact speed (its
#: viscoelastic losses grow with the strain rate). The face gain's bound is wide on purpose: a fit that puts a
#: driver's e above the USGA's COR limit of 0.830 is reported as such (docs/validation.md), not clipped out of sight.
PARAMETERS = {
    "friction": ((0.05, 1.0), 0.4, "Coulomb friction of ball and face"),
    "tangential_loss": ((0.0, 1.5), 0.2, "loss factor of the cover in shear (compliant models)"),
    "restitution": ((0.5, 0.95), 0.78, "normal restitution of the ball on a rigid steel face at 40 m/s"),
    "restitution_slope": ((-0.01, 0.0), -0.001, "de/dv of the ball's restitution law [s/m]"),
    "face_restitution_gain": ((0.0, 0.15), 0.03, "rise of e on a thin wood face (rows whose club face is bulged)"),
    "strike_high": ((-0.015, 0.015), 0.0, "mean strike offset up the face [m]"),
    "rolling_hysteresis": ((0.0, 1.0), 0.1, "loss fraction alpha of the cover's rolling resistance, d = (3/16) alpha a "
                           "(a model option; impactlab.physics.ball_laws)"),
}
#: parameters that are a model's options, not its inputs: the model is rebuilt with the value
MODEL_OPTIONS = ("rolling_hysteresis",)
#: normal speed at which the fitted restitution law's ``restitution`` applies [m/s]
REFERENCE_SPEED = 40.0
DEFAULT_PARAMETERS = ("friction", "tangential_loss", "restitution", "face_restitution_gain")
#: ball speed of the USGA/R&A pendulum test of a driver's coefficient of restitution [m/s] (160 ft/s)
COR_TEST_SPEED = 48.77
#: the USGA/R&A limit of a driver's coefficient of restitution (a rule, not a measurement): Equipment Rules
#: (2023), Part 2, 5a, measured by the USGA's "Procedure for Measuring the Velocity Ratio of a Club Head for
#: Conformance to Rule 4-1e" at 48.77 m/s
DRIVER_COR_LIMIT = 0.830


@attrs.frozen
class Calibration:
    """Fitted parameters of one model on one shot table, with their uncertainty and the errors before and after.

    ``values`` and ``uncertainties`` are SI (one standard deviation, not a variance; ``inf`` where not
    identified); ``identified``, ``at_bound`` and ``near_bound`` per parameter and ``beyond_limit`` (one sentence
    per physical limit the fit exceeds) follow the rules of :mod:`impactlab.data.fit.least_squares`;
    ``unused_rows`` names the rows left out (the model could not predict them). ``rms_before`` and ``rms_after``
    are the RMS of the sigma-weighted residuals; ``errors_before`` and ``errors_after`` the RMS errors per
    measured quantity (:func:`impactlab.data.sessions.shots.summary`).
    """

    model: str
    table: str
    parameters: tuple[str, ...]
    values: tuple[float, ...]
    uncertainties: tuple[float, ...]
    correlation: tuple[tuple[float, ...], ...]
    identified: tuple[bool, ...]
    singular_values: tuple[float, ...]
    rms_before: float
    rms_after: float
    errors_before: dict = attrs.field(eq=False)
    errors_after: dict = attrs.field(eq=False)
    at_bound: tuple[bool, ...] = ()
    near_bound: tuple[bool, ...] = ()
    beyond_limit: tuple[str, ...] = ()
    unused_rows: tuple[str, ...] = ()

    def as_dict(self) -> dict:
        """The calibration as plain data (JSON-ready; ``impactlab fit --json``)."""
        return attrs.asdict(self)

    def describe(self) -> str:
        """One line: each parameter with its one-sigma uncertainty, or 'not identified by these data', its
        bound and any physical limit it exceeds said."""
        lines = [f"{name} = {least_squares.state(*state)}"
                 for name, *state in zip(self.parameters, self.values, self.uncertainties, self.identified,
                                         self.at_bound or (False,) * len(self.parameters),
                                         self.near_bound or (False,) * len(self.parameters))]
        lines += [f"BEYOND A PHYSICAL LIMIT: {message}" for message in self.beyond_limit]
        return "; ".join(lines)


def apply(inputs: dict, names: Sequence[str], values: Sequence[float], ball: Ball | None = None) -> dict:
    """The model inputs with the calibration parameters ``names`` set to ``values`` (SI arrays).

    ``ball`` (a :class:`~impactlab.scene.materials.Ball`) supplies the restitution law where the parameters do not
    replace it. A fitted strike offset moves the strike: where the inputs count the loft at the contact point
    (input ``loft_at_contact``, a table's ``loft_at: contact``) the contact point keeps the measured loft and the
    head turns instead; at the face centre the contact point's loft changes with the roll.
    """
    out = {key: np.array(value, dtype=float) for key, value in inputs.items()}
    given = dict(zip(names, values))
    n = out["speed"].size
    for name in ("friction", "tangential_loss"):
        if name in given:
            out[name] = np.full(n, given[name])
    if "strike_high" in given:
        out["strike_high"] = out["strike_high"] + given["strike_high"]
    if "face_restitution_gain" in given:
        wood = np.isfinite(out["face_bulge_radius"])
        out["club_restitution_gain"] = np.where(wood, given["face_restitution_gain"], 0.0)
    law = None
    if "restitution" in given or "restitution_slope" in given:
        law = RestitutionLaw("linear", given.get("restitution", PARAMETERS["restitution"][1]), REFERENCE_SPEED,
                             slope=given.get("restitution_slope", 0.0))
    elif ball is not None and ball.restitution is not None and {"strike_high", "face_restitution_gain"} & set(given):
        law = ball.restitution
    if law is not None:
        gain = out.get("club_restitution_gain", 0.0)
        out["restitution"] = np.clip(law(approach_state(out)["normal_speed"]) + gain, 0.0, 1.0)
    return out


def _residuals(predicted: dict, table: ShotTable) -> np.ndarray:
    parts = []
    for key in MEASURED_FIELDS:
        measured = table.measured[key]
        keep = np.isfinite(measured)
        difference = predicted[key][keep] - measured[keep]
        if key in ("horizontal_launch_angle", "spin_axis"):
            difference = (difference + math.pi) % (2 * math.pi) - math.pi
        parts.append(difference / table.sigma[key][keep])
    return np.concatenate(parts)


def _table_ball(table: ShotTable, ball_block: dict | None):
    return build_ball(ball_block or table.ball or {"preset": "urethane_tour"})


def rows_of(inputs: dict, rows) -> dict:
    """The model inputs (:func:`impactlab.data.sessions.shots.table_inputs`) of some rows (an index or a mask):
    every per-row array sliced, the rest as it is. The inputs of a row depend on that row alone, so a fold's
    inputs are sliced from the whole table's instead of rebuilt from its scenes."""
    size = len(inputs["speed"])
    return {key: (value[rows] if isinstance(value, np.ndarray) and value.ndim and len(value) == size else value)
            for key, value in inputs.items()}


def calibrate(model: ImpactModel, table: ShotTable, parameters: Sequence[str] = DEFAULT_PARAMETERS,
              ball: dict | None = None,
              start: dict | None = None, inputs: dict | None = None) -> Calibration:
    """Fit ``parameters`` of ``model`` (an ImpactModel instance) to every measured value of ``table``.

    Parameters
    ----------
    model : ImpactModel
    table : ShotTable
    parameters : sequence of str
        Names from :data:`PARAMETERS`.
    ball : dict, optional
        A study ``ball:`` block (default: the table's, else the ``urethane_tour`` preset).
    start : dict, optional
        Start values by parameter name (default: :data:`PARAMETERS`).
    inputs : dict, optional
        The table's model inputs, when the caller has them (:func:`impactlab.data.sessions.shots.table_inputs`
        of ``table`` with ``ball``): a cross-validation builds them once for every fold.
    """
    names = tuple(parameters)
    for name in names:
        if name not in PARAMETERS:
            raise FieldError("--parameter", "a parameter the calibration can fit", name, choices=PARAMETERS)
    if len(set(names)) != len(names):
        raise FieldError("--parameter", "distinct parameters", list(names))
    if "tangential_loss" in names and "tangential_loss" not in model.optional_inputs | model.requires:
        raise FieldError("--parameter", f"a parameter model {model.name!r} uses (it has no tangential loss)",
                         "tangential_loss", choices=[n for n in PARAMETERS if n != "tangential_loss"])
    for name in MODEL_OPTIONS:
        if name in names and name not in model.options_dict():
            raise FieldError("--parameter", f"a parameter model {model.name!r} has (it has no {name} option)", name,
                             choices=[n for n in PARAMETERS if n not in MODEL_OPTIONS])
    if "face_restitution_gain" in names and float(model.options_dict().get("face_frequency", 0.0) or 0.0) > 0.0:
        # the flexing face (models._common.face_inputs) replaces the gain, which then only marks the faces that
        # flex: the fit would be flat in it, its COR check would add it, and at its bound 0 it switches the face off
        raise FieldError("--parameter", f"parameters without face_restitution_gain: model {model.name!r} has the "
                         f"flexing face (face_frequency), which replaces the gain (the gain only marks which faces "
                         f"flex, and a fit reaching 0 would switch the face off)", "face_restitution_gain",
                         choices=[n for n in PARAMETERS if n != "face_restitution_gain"])
    measured_values = sum(int(np.isfinite(table.measured[key]).sum()) for key in MEASURED_FIELDS)
    if measured_values < len(names):
        raise FieldError("--parameter", f"at most as many parameters as measured values ({measured_values})",
                         list(names))
    ball_object = _table_ball(table, ball)
    low = np.array([PARAMETERS[name][0][0] for name in names])
    high = np.array([PARAMETERS[name][0][1] for name in names])
    x0 = np.clip(np.array([(start or {}).get(name, PARAMETERS[name][1]) for name in names], dtype=float), low, high)
    inputs = table_inputs(table, ball) if inputs is None else inputs
    first = predict(model_with(model, names, x0), apply(inputs, names, x0, ball_object))
    usable = least_squares.usable_rows(np.stack([first[key] for key in MEASURED_FIELDS], axis=1),
                                       np.stack([table.measured[key] for key in MEASURED_FIELDS], axis=1))
    unused = tuple(label for label, ok in zip(table.labels, usable) if not ok)
    if not usable.any():
        raise FieldError("shot table", "rows the model can predict", f"none of {table.size} ({model.name!r})")
    if unused:
        table = table.subset(usable)
        inputs = rows_of(inputs, usable)

    def predicted(x):
        return predict(model_with(model, names, x), apply(inputs, names, x, ball_object))

    before = predicted(x0)
    solution = least_squares.solve(lambda x: _residuals(predicted(x), table), x0, low, high, weighted=True,
                                   names=names, limits=_limits(ball_object))
    correlation = solution.correlation
    return Calibration(
        model=model.name, table=table.name, parameters=names, values=tuple(float(v) for v in solution.values),
        uncertainties=tuple(float(s) for s in solution.uncertainties),
        correlation=tuple(tuple(float(c) for c in row) for row in correlation),
        identified=tuple(bool(v) for v in solution.identified),
        singular_values=tuple(float(s) for s in solution.singular_values),
        rms_before=float(np.sqrt(np.mean(solution.start_residuals**2))),
        rms_after=float(np.sqrt(np.mean(solution.residuals**2))),
        errors_before=summary(shot_errors(before, table)),
        errors_after=summary(shot_errors(predicted(solution.values), table)),
        at_bound=tuple(bool(v) for v in solution.at_bound), near_bound=tuple(bool(v) for v in solution.near_bound),
        beyond_limit=solution.beyond_limit, unused_rows=unused)


def _limits(ball) -> tuple:
    """The physical limits a calibration is checked against: a driver's COR (ball law at the USGA test speed
    plus the wood face's gain) at most :data:`DRIVER_COR_LIMIT`."""

    def driver_cor(fitted: dict):
        if "face_restitution_gain" not in fitted:
            return None
        if "restitution" in fitted:
            ball_e = fitted["restitution"] + fitted.get("restitution_slope", 0.0) * (COR_TEST_SPEED - REFERENCE_SPEED)
        elif ball is not None and ball.restitution is not None:
            ball_e = float(ball.restitution(COR_TEST_SPEED))
        else:
            return None
        return ball_e + fitted["face_restitution_gain"]

    return (least_squares.PhysicalLimit(f"a driver's COR at {COR_TEST_SPEED} m/s (ball law + face gain)",
                                        driver_cor, DRIVER_COR_LIMIT, "USGA/R&A Equipment Rules, Part 2, 5a"),)


def predict_with(model: ImpactModel, table: ShotTable, calibration: Calibration, ball: dict | None = None,
                 inputs: dict | None = None) -> dict:
    """The model's predictions of ``table``'s rows with the fitted values of ``calibration`` (SI arrays);
    ``inputs``: the table's model inputs when the caller has them."""
    inputs = table_inputs(table, ball) if inputs is None else inputs
    return predict(model_with(model, calibration.parameters, calibration.values),
                   apply(inputs, calibration.parameters, calibration.values, _table_ball(table, ball)))


def model_with(model: ImpactModel, names: Sequence[str], values: Sequence[float]) -> ImpactModel:
    """``model`` with the calibration's model options (:data:`MODEL_OPTIONS`) among ``names`` set to ``values``
    (the model itself when there are none)."""
    given = {name: float(value) for name, value in zip(names, values) if name in MODEL_OPTIONS}
    if not given:
        return model
    return type(model)(**{**model.options_dict(), **given})


def source_folds(table: ShotTable) -> list[list[int]]:
    """One fold per source of the table's rows (:attr:`ShotTable.sources`): the rows of that source."""
    sources = list(table.sources)
    return [[i for i, s in enumerate(sources) if s == source] for source in dict.fromkeys(sources)]


def cross_validate(model: ImpactModel, table: ShotTable, parameters: Sequence[str] = DEFAULT_PARAMETERS,
                   ball: dict | None = None, folds: Sequence[Any] | None = None, by: str = "row",
                   start: dict | None = None) -> dict:
    """Fit on all rows but some, predict those: leave one row out at a time (``by="row"``) or one source
    (``by="source"``: every row of one source held out, the fit made on the other sources only).

    Each fold's fit starts from ``start`` (a warm start: the full fit's values, so that a fold costs a few
    iterations from near its optimum, not a fit from the defaults); the optimum is the same as from a cold start
    within the optimiser's tolerance (tests/test_validation_sources.py).

    Returns
    -------
    dict
        ``errors``: per-row errors on the rows left out (keys of :data:`ERROR_KEYS`, NaN where not measured);
        ``summary``: their RMS; ``by_source``: the RMS per held-out source; ``fits``: the fitted values of each
        fold; ``calibrations``: each fold's :class:`Calibration` (at-bound and beyond-limit flags); ``folds``:
        the held-out rows; ``labels``: the rows.
    """
    if folds is None:
        if by not in ("row", "source"):
            raise FieldError("--by", "row or source", by)
        folds = source_folds(table) if by == "source" else [[i] for i in range(table.size)]
    held = {key: np.full(table.size, np.nan) for key in ERROR_KEYS}
    fits, calibrations = [], []
    inputs = table_inputs(table, ball)  # once: each fold's are sliced from them (rows_of)
    for rows in folds:
        rows = np.asarray(rows)
        train = np.setdiff1d(np.arange(table.size), rows)
        if train.size == 0:
            raise FieldError("folds", "folds that leave rows to fit on (a table of one source cannot be "
                             "cross-validated by source)", rows.tolist())
        result = calibrate(model, table.subset(train), parameters, ball, start=start, inputs=rows_of(inputs, train))
        fits.append(dict(zip(result.parameters, result.values)))
        calibrations.append(result)
        test = table.subset(rows)
        for key, values in shot_errors(predict_with(model, test, result, ball, rows_of(inputs, rows)), test).items():
            held[key][rows] = values
    return {"errors": held, "summary": summary(held), "by_source": errors_by_source(held, table), "fits": fits,
            "calibrations": calibrations, "folds": [list(map(int, f)) for f in folds], "labels": table.labels}


def leave_one_row_out(model: ImpactModel, table: ShotTable, calibration: Calibration,
                      ball: dict | None = None) -> dict:
    """Leave-one-row-out cross-validation in closed form from the full fit: one Gauss-Newton step per row.

    With ``r_i`` (the row's sigma-weighted residuals, up to five) and ``J_i`` (their derivatives in the fitted
    parameters, forward differences of :data:`impactlab.data.fit.least_squares.DIFF_STEP` of each range) at the
    full optimum ``x``, ``A = sum_j J_j^T J_j`` and ``g = sum_j J_j^T r_j`` (zero at an interior optimum), the fit
    without row ``i`` is one Gauss-Newton step away,

        x_(-i) = x - (A - J_i^T J_i)^-1 (g - J_i^T r_i),

    clipped into the bounds, and row ``i`` is predicted there to first order, ``p_i + dp_i/dx (x_(-i) - x)``. For
    a model linear in its parameters this is the exact leave-one-out (the hat-matrix identity
    ``e_(-i) = (I - H_ii)^-1 e_i`` of least squares [1]_); for the impact models it is exact to the second order
    of the change one row makes (tests/test_scorecard.py checks it against explicit refits). Its cost is that of
    ``p + 1`` predictions, not ``N`` fits. Parameters the full fit did not identify or left at a bound stay where
    they are.

    Returns
    -------
    dict
        As :func:`cross_validate`: ``errors`` per row (keys of :data:`ERROR_KEYS`), ``summary``, ``by_source``,
        ``fits`` (each row's parameter values), ``labels``; and ``method``.

    References
    ----------
    .. [1] Cook, R. D. & Weisberg, S. (1982). *Residuals and Influence in Regression*, Chapman & Hall, section
       2.2 (deleted residuals from the hat matrix); the one-step approximation for nonlinear least squares:
       Pregibon, D. (1981), Ann. Statist. 9:705 (one-step influence).
    """
    names = tuple(calibration.parameters)
    x = np.array(calibration.values, dtype=float)
    low = np.array([PARAMETERS[name][0][0] for name in names])
    high = np.array([PARAMETERS[name][0][1] for name in names])
    span = high - low
    free = (np.array(calibration.identified, bool)
            & ~np.array(calibration.at_bound or (False,) * len(names), bool))
    if calibration.unused_rows:
        keep = np.array([label not in set(calibration.unused_rows) for label in table.labels])
        table = table.subset(keep)
    ball_object = _table_ball(table, ball)
    inputs = table_inputs(table, ball)

    def predicted(values):
        return predict(model_with(model, names, values), apply(inputs, names, values, ball_object))

    def stacked(prediction):
        return np.stack([prediction[key] for key in MEASURED_FIELDS], axis=1)  # rows x 5

    base = stacked(predicted(x))
    measured = np.stack([table.measured[key] for key in MEASURED_FIELDS], axis=1)
    sigma = np.stack([table.sigma[key] for key in MEASURED_FIELDS], axis=1)
    given = np.isfinite(measured)
    difference = np.where(given, base - np.nan_to_num(measured), 0.0)
    angles = [i for i, key in enumerate(MEASURED_FIELDS) if key in ("horizontal_launch_angle", "spin_axis")]
    difference[:, angles] = (difference[:, angles] + math.pi) % (2 * math.pi) - math.pi
    residual = difference / sigma  # rows x 5, 0 where not measured
    derivative = np.zeros((*base.shape, len(names)))  # d prediction / d parameter: rows x 5 x p
    for p in np.flatnonzero(free):
        step = least_squares.DIFF_STEP * span[p] * (1.0 if x[p] + least_squares.DIFF_STEP * span[p] <= high[p]
                                                    else -1.0)
        moved = x.copy()
        moved[p] += step
        derivative[:, :, p] = (stacked(predicted(moved)) - base) / step
    jacobian = np.where(given[:, :, None], derivative / sigma[:, :, None], 0.0)[:, :, free]  # rows x 5 x q
    row_normal = np.einsum("rkp,rkq->rpq", jacobian, jacobian)
    row_gradient = np.einsum("rkp,rk->rp", jacobian, residual)
    without = row_normal.sum(axis=0)[None] - row_normal
    gradient = row_gradient.sum(axis=0)[None] - row_gradient
    change = np.zeros((table.size, len(names)))
    if free.any():
        change[:, free] = -np.einsum("rpq,rq->rp", np.linalg.pinv(without), gradient)
    change = np.clip(x[None] + change, low, high) - x[None]
    held_out = base + np.einsum("rkp,rp->rk", derivative, change)
    prediction = {key: held_out[:, i] for i, key in enumerate(MEASURED_FIELDS)}
    errors = shot_errors(prediction, table)
    return {"errors": errors, "summary": summary(errors), "by_source": errors_by_source(errors, table),
            "fits": [dict(zip(names, (float(v) for v in x + c))) for c in change], "labels": table.labels,
            "method": "closed form: one Gauss-Newton step per row from the full fit"}
