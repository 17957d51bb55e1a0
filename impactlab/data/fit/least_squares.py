"""The one bounded least-squares core behind ``impactlab fit``: datasets (:mod:`~impactlab.data.fit.fitting`) and shot
tables (:mod:`~impactlab.data.fit.calibration`).

Problem
-------
Minimise ``sum(r_i(x)**2)`` over parameters ``x`` with ``lower <= x <= upper``, where ``r`` are residuals
``(predicted - measured) / sigma`` (``scipy.optimize.least_squares``, trust-region reflective, finite-difference
Jacobian with a step of 1 % of each parameter's range: well above the models' discretisation error of about 1e-4).

Covariance
----------
``C = (J^T J)^+`` at the optimum over the identified parameters, with ``J`` the Jacobian of the residuals.
When the residuals are divided by the measurements' stated one-sigma uncertainties (``weighted=True``) ``C`` is
the covariance of the parameters as it stands. When the data state no uncertainty (``weighted=False``, unit
weights) it is rescaled by the reduced chi-square ``s^2 = SSR / (n - p)`` (the residual variance: ``n`` residuals,
``p`` identified parameters; left unscaled when ``n <= p``, where the fit is exact and no variance can be
estimated) [1]_. Reported uncertainties are standard deviations, ``sqrt(diag(C))``, never variances.

Rules, the same for every fit
-----------------------------
identified
    The parameter's column of ``J``, scaled by its allowed range (the change in the residuals across the whole
    range), is above ``IDENTIFIED_COLUMN`` = 1e-8 of the largest scaled column (the data depend on it at all),
    **and** its one-sigma uncertainty is below ``IDENTIFIED_SIGMA`` = 0.5 of its range (the data pin it inside
    the range: a parameter correlated with another so strongly that only their combination is determined fails
    this). A parameter not identified has an infinite uncertainty and is left where the optimiser put it.
at its bound
    The optimum lies within ``AT_BOUND`` = 1e-3 of the parameter's range from a bound: the data want a value the
    bounds do not allow, and the quoted uncertainty (of a curvature at the bound) does not describe where the
    data would put it.
near its bound
    Not at it, but the bound lies within one standard deviation of the value: the interval quoted crosses the
    bound.
beyond a physical limit
    A limit stated by a rule or by physics (:class:`PhysicalLimit`, e.g. the USGA/R&A limit of a driver's
    coefficient of restitution, 0.830) that a combination of the fitted values exceeds. Bounds are left wide
    on purpose where such a fit says something (the model needs more than physics allows), so it is reported,
    not clipped out of sight.

References
----------
.. [1] Press, W. H., Teukolsky, S. A., Vetterling, W. T. & Flannery, B. P. (2007). *Numerical Recipes*, 3rd ed.,
   section 15.4.2 and 15.5 (covariance of a least-squares fit; scaling by the residual variance when the
   measurement errors are unknown).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import attrs
import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import least_squares

#: a scaled Jacobian column below this fraction of the largest one: the data do not depend on the parameter
IDENTIFIED_COLUMN = 1e-8
#: a one-sigma uncertainty above this fraction of the allowed range: the data do not pin the parameter
IDENTIFIED_SIGMA = 0.5
#: an optimum within this fraction of the allowed range from a bound sits at that bound
AT_BOUND = 1e-3
#: finite-difference step of the Jacobian, as a fraction of each parameter's range
DIFF_STEP = 0.01


@attrs.frozen
class PhysicalLimit:
    """A limit a combination of fitted values may not exceed in reality (a rule or physics).

    Parameters
    ----------
    name : str
        What is limited, in words (``"driver COR at 48.8 m/s"``).
    value : callable
        ``value(fitted)`` -> the limited quantity, ``fitted`` a mapping parameter name -> fitted value (SI);
        None when the limit does not apply to this fit (a parameter it needs was not fitted).
    maximum : float
        The largest value allowed.
    source : str
        Where the limit comes from (rule, edition, clause).
    """

    name: str
    value: Callable
    maximum: float
    source: str

    def check(self, fitted: dict) -> str | None:
        """A sentence when ``fitted`` exceeds the limit, else None."""
        value = self.value(fitted)
        if value is None or not value > self.maximum:
            return None
        return f"{self.name} = {value:.3f} beyond the limit {self.maximum:g} ({self.source})"


@attrs.frozen
class Solution:
    """The optimum of a bounded least-squares problem and what the data say about each parameter.

    ``values``, ``uncertainties`` (one standard deviation; ``inf`` where not identified) and the per-parameter
    flags are in the order of the parameters; ``covariance`` over every parameter (rows and columns of
    parameters not identified are NaN); ``residuals`` and ``start_residuals`` the (weighted) residuals at the
    optimum and at the start; ``singular_values`` those of the range-scaled Jacobian (its conditioning);
    ``beyond_limit`` one sentence per physical limit exceeded.
    """

    values: np.ndarray = attrs.field(eq=False)
    uncertainties: np.ndarray = attrs.field(eq=False)
    covariance: np.ndarray = attrs.field(eq=False)
    identified: np.ndarray = attrs.field(eq=False)
    at_bound: np.ndarray = attrs.field(eq=False)
    near_bound: np.ndarray = attrs.field(eq=False)
    residuals: np.ndarray = attrs.field(eq=False)
    start_residuals: np.ndarray = attrs.field(eq=False)
    singular_values: np.ndarray = attrs.field(eq=False)
    scaled: bool
    beyond_limit: tuple[str, ...] = ()

    @property
    def correlation(self) -> np.ndarray:
        """The correlation matrix of the parameters (NaN where not identified)."""
        sigma = np.sqrt(np.abs(np.diag(self.covariance)))
        with np.errstate(invalid="ignore", divide="ignore"):
            return self.covariance / np.outer(sigma, sigma)


def analyse(jacobian: np.ndarray, residuals: np.ndarray, values: np.ndarray, lower: np.ndarray,
            upper: np.ndarray, weighted: bool) -> dict:
    """Covariance, uncertainties and the identified / at-bound / near-bound flags at an optimum.

    Parameters
    ----------
    jacobian : ndarray, shape (n, p)
        d residual / d parameter at the optimum.
    residuals : ndarray, shape (n,)
        The residuals at the optimum (divided by their sigma when ``weighted``).
    values, lower, upper : ndarray, shape (p,)
        The optimum and the bounds (finite).
    weighted : bool
        True when the residuals are in units of the measurements' stated one-sigma uncertainty (the covariance is
        then not rescaled); False for unit weights (rescaled by the reduced chi-square).

    Returns
    -------
    dict
        ``covariance`` (p, p), ``uncertainties`` (p,: standard deviations, inf where not identified),
        ``identified``, ``at_bound``, ``near_bound`` (p,: bool), ``singular_values``, ``scaled`` (whether the
        covariance was rescaled).
    """
    jacobian = np.asarray(jacobian, dtype=float)
    n, p = jacobian.shape
    span = upper - lower
    scaled_jacobian = jacobian * span
    column = np.linalg.norm(scaled_jacobian, axis=0)
    depends = column > IDENTIFIED_COLUMN * max(float(column.max(initial=0.0)), 1e-300)
    covariance = np.full((p, p), np.nan)
    sigma = np.full(p, np.inf)
    rescaled = False
    if depends.any():
        block = jacobian[:, depends]
        inner = np.linalg.pinv(block.T @ block)
        if not weighted and n > depends.sum():
            inner = inner * (float(residuals @ residuals) / (n - depends.sum()))
            rescaled = True
        covariance[np.ix_(depends, depends)] = inner
        sigma[depends] = np.sqrt(np.maximum(np.diag(inner), 0.0))
    identified = depends & (sigma < IDENTIFIED_SIGMA * span)
    uncertainties = np.where(identified, sigma, np.inf)
    distance = np.minimum(values - lower, upper - values)
    at_bound = distance <= AT_BOUND * span
    near_bound = ~at_bound & identified & (distance <= uncertainties)
    return {"covariance": covariance, "uncertainties": uncertainties, "identified": identified,
            "at_bound": at_bound, "near_bound": near_bound, "scaled": rescaled,
            "singular_values": np.linalg.svd(scaled_jacobian, compute_uv=False)}


def solve(residuals: Callable[[np.ndarray], np.ndarray], start: ArrayLike, lower: ArrayLike,
          upper: ArrayLike, *, weighted: bool, names: Sequence[str] = (),
          limits: Sequence[PhysicalLimit] = ()) -> Solution:
    """Minimise the sum of squares of ``residuals(x)`` within the bounds and say what the data tell of each x.

    Parameters
    ----------
    residuals : callable
        ``residuals(x)`` -> ndarray of (predicted - measured) / sigma, every entry finite.
    start, lower, upper : sequence of float
        Start values (clipped into the bounds) and finite bounds, one per parameter [the parameters' units].
    weighted : bool
        Whether the residuals are divided by stated measurement uncertainties (see the module's *Covariance*).
    names : sequence of str
        The parameters' names, for ``limits`` (their ``value`` sees ``{name: value}``).
    limits : sequence of PhysicalLimit
        Physical limits to check the optimum against.

    Returns
    -------
    Solution
    """
    low = np.asarray(lower, dtype=float)
    high = np.asarray(upper, dtype=float)
    if not (np.all(np.isfinite(low)) and np.all(np.isfinite(high)) and np.all(high > low)):
        raise ValueError("least-squares bounds must be finite with upper > lower")
    span = high - low
    x0 = np.clip(np.asarray(start, dtype=float), low, high)
    start_residuals = np.asarray(residuals(x0), dtype=float)
    # absolute finite-difference step DIFF_STEP * span (scipy's diff_step is relative to max(1, |x|) ... |x|)
    step = DIFF_STEP * span / np.maximum(np.abs(x0), 1e-3)
    solution = least_squares(residuals, x0, bounds=(low, high), x_scale=span, diff_step=step, method="trf")
    found = analyse(solution.jac, solution.fun, solution.x, low, high, weighted)
    fitted = dict(zip(names, (float(v) for v in solution.x)))
    beyond = tuple(message for limit in limits if (message := limit.check(fitted)) is not None)
    return Solution(values=solution.x, uncertainties=found["uncertainties"], covariance=found["covariance"],
                    identified=found["identified"], at_bound=found["at_bound"], near_bound=found["near_bound"],
                    residuals=np.asarray(solution.fun, dtype=float), start_residuals=start_residuals,
                    singular_values=found["singular_values"], scaled=found["scaled"], beyond_limit=beyond)


def state(value: float, sigma: float, identified: bool, at_bound: bool, near_bound: bool,
          spec: str = ".4g", sigma_spec: str = ".2g") -> str:
    """One parameter's fitted value in words: ``0.3 +- 0.01``, or with its bound or 'not identified' said.

    ``spec`` and ``sigma_spec`` are the format specifications of the value and of its standard deviation."""
    if not identified:
        text = f"{value:{spec}} (not identified by these data)"
    else:
        text = f"{value:{spec}} +- {sigma:{sigma_spec}}"
    if at_bound:
        text += " AT ITS BOUND (the data want a value the bounds do not allow; the +- does not apply)"
    elif near_bound:
        text += " (near its bound: within one sigma of it)"
    return text


def usable_rows(predicted: np.ndarray, measured: np.ndarray) -> np.ndarray:
    """Mask of the rows a fit can use: the prediction is finite wherever the row was measured.

    ``predicted`` and ``measured`` have the rows along their first axis (NaN in ``measured``: not measured).
    A row the model cannot predict (a NaN or infinite prediction of a measured value) is left out of a fit and
    named, never turned into a silent NaN residual.
    """
    predicted = np.asarray(predicted, dtype=float)
    measured = np.asarray(measured, dtype=float)
    bad = np.isfinite(measured) & ~np.isfinite(predicted)
    return ~bad.reshape(len(bad), -1).any(axis=1)


__all__ = ["AT_BOUND", "IDENTIFIED_COLUMN", "IDENTIFIED_SIGMA", "PhysicalLimit", "Solution", "analyse", "solve",
           "state", "usable_rows"]
