"""Baselines a model must beat, fitted on a training part of a session only (:mod:`.scorecard`).

Two kinds, both predicting each shot's launch from its measured delivery alone (no ball or club physics):

physics-shaped regressions (:class:`PhysicsRegression`), least squares without intercept on the training rows
    ball speed = s V_club (s: the smash factor); launch angle = a dynamic loft + b attack angle;
    launch direction = p face angle + q club path; spin rate = k V_club sin(spin loft);
    spin axis = c face to path.
    One or two coefficients each: what a fitter would draw through a session by hand. Spin loft is the 3-D angle
    between the face normal and the club's velocity (:func:`impactlab.physics.delivery.spin_loft`).
a flexible data-driven model (:func:`flexible_baseline`)
    scikit-learn's ``HistGradientBoostingRegressor`` per output on the delivery (club speed, attack angle, club
    path, face angle, dynamic loft, strike toe and height; missing strikes handled natively). scikit-learn is
    an optional dependency (``pip install 'impactlab[baselines]'``); without it the scorecard says so.

Neither ever sees a held-out row: :meth:`PhysicsRegression.fitted` and :func:`flexible_baseline` take the training
table only (tests/test_scorecard.py plants an absurd held-out row and checks the coefficients do not move).
"""

from __future__ import annotations

import math

import attrs
import numpy as np

from impactlab.data.sessions.shots import MEASURED_FIELDS, ShotTable
from impactlab.physics.delivery import spin_loft
from impactlab.units import MPH, RAD_TO_DEG, RADS_TO_RPM

#: the baselines' names in a scorecard
REGRESSION = "regression"
FLEXIBLE = "gradient_boosting"
#: the delivery inputs of the flexible baseline
FEATURES = ("club_speed", "attack_angle", "path", "face_angle", "dynamic_loft", "strike_toe", "strike_high")
#: fewest training rows of an output for a baseline of it
MIN_TRAINING = 5


def _handed(table: ShotTable) -> np.ndarray:
    return np.array([-1.0 if h == "left" else 1.0 for h in table.handedness])


def regressors(table: ShotTable) -> dict[str, np.ndarray]:
    """Each output's regressor columns (rows x coefficients) from the delivery (SI)."""
    d = table.delivery
    with np.errstate(invalid="ignore"):
        loft = spin_loft(d["path"], d["face_angle"], d["attack_angle"], d["dynamic_loft"], _handed(table))
    return {"ball_speed": d["club_speed"][:, None],
            "vertical_launch_angle": np.stack([d["dynamic_loft"], d["attack_angle"]], axis=1),
            "horizontal_launch_angle": np.stack([d["face_angle"], d["path"]], axis=1),
            "spin_rate": (d["club_speed"] * np.sin(loft))[:, None],
            "spin_axis": (d["face_angle"] - d["path"])[:, None]}


@attrs.frozen
class PhysicsRegression:
    """The one- and two-coefficient physics-shaped regressions (module docstring), coefficients SI."""

    coefficients: dict = attrs.field(eq=False)
    rows: dict = attrs.field(eq=False)

    @classmethod
    def fitted(cls, train: ShotTable) -> PhysicsRegression:
        """Least squares (no intercept) of every output on the rows of ``train`` that measure it."""
        columns = regressors(train)
        coefficients, rows = {}, {}
        for field, x in columns.items():
            y = train.measured[field]
            keep = np.isfinite(y) & np.isfinite(x).all(axis=1)
            rows[field] = int(keep.sum())
            if rows[field] < max(MIN_TRAINING, x.shape[1]):
                coefficients[field] = np.full(x.shape[1], np.nan)
                continue
            coefficients[field] = np.linalg.lstsq(x[keep], y[keep], rcond=None)[0]
        return cls(coefficients, rows)

    def predict(self, table: ShotTable) -> dict:
        """The outputs of every row of ``table`` (SI arrays; NaN where a regressor is missing)."""
        columns = regressors(table)
        return {field: columns[field] @ self.coefficients[field] for field in MEASURED_FIELDS}

    def describe(self) -> str:
        """The fitted coefficients in a fitter's units."""
        c = self.coefficients
        spin = c["spin_rate"][0] * RADS_TO_RPM * MPH  # rpm per (mph x sin)
        return (f"ball speed = {c['ball_speed'][0]:.3f} x club speed; launch = {c['vertical_launch_angle'][0]:.3f} "
                f"dynamic loft {c['vertical_launch_angle'][1]:+.3f} attack angle; direction = "
                f"{c['horizontal_launch_angle'][0]:.3f} face {c['horizontal_launch_angle'][1]:+.3f} path; spin = "
                f"{spin:.1f} rpm x club speed [mph] x sin(spin loft); spin axis = {c['spin_axis'][0]:.3f} x face to "
                f"path")


def features(table: ShotTable) -> np.ndarray:
    """The flexible baseline's inputs (rows x :data:`FEATURES`), in mph and degrees (trees do not care; a reader
    of a dump does)."""
    d = table.delivery
    scale = {"club_speed": 1.0 / MPH, "strike_toe": 1e3, "strike_high": 1e3}
    return np.stack([d[name] * scale.get(name, RAD_TO_DEG) for name in FEATURES], axis=1)


@attrs.frozen
class FlexibleBaseline:
    """One fitted scikit-learn regressor per output (None where too few training rows measure it)."""

    regressors: dict = attrs.field(eq=False)

    def predict(self, table: ShotTable) -> dict:
        """The outputs of every row of ``table`` (SI arrays)."""
        from threadpoolctl import threadpool_limits

        x = features(table)
        out = {}
        with threadpool_limits(limits=1):
            for field in MEASURED_FIELDS:
                model = self.regressors.get(field)
                out[field] = model.predict(x) if model is not None and len(x) else np.full(len(x), math.nan)
        return out


def flexible_baseline(train: ShotTable, seed: int = 0) -> FlexibleBaseline | str:
    """Gradient boosting per output fitted on ``train`` (the delivery -> each measured output), or a sentence
    saying why there is none (scikit-learn not installed)."""
    try:
        from sklearn.ensemble import HistGradientBoostingRegressor
    except ImportError:
        return ("the flexible baseline (scikit-learn's gradient boosting) is missing: scikit-learn is not installed "
                "(pip install 'impactlab[baselines]')")
    from threadpoolctl import threadpool_limits  # a dependency of scikit-learn

    x = features(train)
    fitted: dict = {}
    # one OpenMP thread: on a shared machine the threads of a small fit wait for each other (5 s instead of 0.1 s)
    with threadpool_limits(limits=1):
        for field in MEASURED_FIELDS:
            y = train.measured[field]
            keep = np.isfinite(y)
            if keep.sum() < MIN_TRAINING:
                fitted[field] = None
                continue
            # defaults but a fixed seed: the same session gives the same scorecard
            fitted[field] = HistGradientBoostingRegressor(random_state=seed).fit(x[keep], y[keep])
    return FlexibleBaseline(fitted)
