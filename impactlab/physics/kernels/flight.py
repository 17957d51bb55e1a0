"""Compiled ball flight (:func:`impactlab.physics.flight.fly`'s kernel): a batch of shots, each in its own air,
integrated one shot at a time by an embedded Runge-Kutta 5(4) pair (Dormand & Prince) whose step is chosen for a
local error bound, with the landing and the apex located on the integrator's own partial steps.

The drag and lift coefficients are the formulas of :mod:`impactlab.physics.aerodynamics` compiled as they are
(numba's ``register_jitable``: the same Python function flies on numpy arrays there and on scalars here), not a
table: no interpolation error to bound, and a model's constants (``MEASURED_FIT``) are passed at each call, so a refit
flies at once. numba's on-disk cache does not follow an edit of aerodynamics.py's formulas: :func:`kernel_model`
compares the compiled coefficients with the numpy ones once per model and process, and answers None (the caller then
flies the numpy integrator, with a warning) where they differ.

References
----------
J. R. Dormand and P. J. Prince, "A family of embedded Runge-Kutta formulae", J. Comput. Appl. Math. 6 (1980) 19-26;
E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., Springer (1993),
section II.4 (step-size control) and II.6 (dense output, Hermite interpolation).
"""

from __future__ import annotations

import warnings

import numpy as np
from numba.extending import overload, register_jitable

from impactlab.physics import aerodynamics as _aero

from ._numba import compiled as _compiled


@overload(_aero._select)
def _select_scalar(condition, if_true, if_false):  # pragma: no cover - numba compiles it
    # aerodynamics._select is np.where on arrays; on the kernel's scalars, a branch (np.where would allocate)
    return lambda condition, if_true, if_false: if_true if condition else if_false


for _function in (_aero._cd_cl_smits_smith, _aero._cd_cl_lyu, _aero._cd_cl_usga, _aero._cd_cl_smits_smith_capped,
                  _aero._cd_cl_lyu_induced, _aero._crisis_formula, _aero._measured_fit_formula):
    register_jitable(_function)

#: the models the kernel flies: the function of :data:`impactlab.physics.aerodynamics.MODELS` -> its number here
_MODEL_NUMBERS = {_aero._cd_cl_vacuum: 0, _aero._cd_cl_smits_smith: 1, _aero._cd_cl_lyu: 2, _aero._cd_cl_usga: 3,
                  _aero._cd_cl_smits_smith_capped: 4, _aero._cd_cl_lyu_induced: 5, _aero._cd_cl_measured_fit: 6,
                  _aero._cd_cl_measured_fit_usga_ball: 6}


def _model_constants(function):
    """The constants the kernel passes a model's formula (measured_fit's, read now), else an empty array."""
    if function is _aero._cd_cl_measured_fit:
        return np.array(_aero._measured_fit_constants())
    if function is _aero._cd_cl_measured_fit_usga_ball:
        return np.array(_aero._measured_fit_constants(_aero.MEASURED_FIT_OFFSETS["usga_1998"]))
    return np.zeros(13)


@register_jitable
def _coefficients(model, c, s, re):
    """CD, CL of model number ``model`` (constants ``c``) at spin ratio ``s`` and Reynolds number ``re``."""
    if model == 1:
        return _aero._cd_cl_smits_smith(s, re)
    if model == 2:
        return _aero._cd_cl_lyu(s, re)
    if model == 3:
        return _aero._cd_cl_usga(s, re)
    if model == 4:
        return _aero._cd_cl_smits_smith_capped(s, re)
    if model == 5:
        return _aero._cd_cl_lyu_induced(s, re)
    if model == 6:
        return _aero._measured_fit_formula(s, re, c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8], c[9],
                                           c[10], c[11], c[12])
    return 0.0, 0.0  # vacuum


def _coefficient_grid(model, c, s, re, cd, cl):
    """The compiled coefficients on the points (s[i], re[i]), written to cd, cl (the check against numpy)."""
    for i in range(s.size):
        cd[i], cl[i] = _coefficients(model, c, s[i], re[i])


@register_jitable
def _derivative(y, out, air, model, c, gravity):
    """d/dt of the state y = (x, y, z, vx, vy, vz, omega) (internal frame, y LEFT) into ``out``.

    ``air`` holds the shot's wind (3), spin axis (3), rho 2R / mu, R, rho A / (2 m) and the spin decay
    lam rho / 1.225: the arithmetic of :func:`impactlab.physics.flight_numpy._derivs`, one shot at a time.
    """
    rx = y[3] - air[0]
    ry = y[4] - air[1]
    rz = y[5] - air[2]
    speed = max(np.sqrt(rx * rx + ry * ry + rz * rz), 1e-9)
    inv = 1.0 / speed
    # omega_hat x v_hat; its norm is the sine of the angle between the axis and the air-relative velocity
    cx = (air[4] * rz - air[5] * ry) * inv
    cy = (air[5] * rx - air[3] * rz) * inv
    cz = (air[3] * ry - air[4] * rx) * inv
    sin_axis = np.sqrt(cx * cx + cy * cy + cz * cz)
    radius = air[7]
    cd, cl = _coefficients(model, c, radius * y[6] * sin_axis * inv, air[6] * speed)
    drag = air[8] * cd * speed
    lift = air[8] * cl * speed * speed / max(sin_axis, 1e-12)
    out[0] = y[3]
    out[1] = y[4]
    out[2] = y[5]
    out[3] = -drag * rx + lift * cx
    out[4] = -drag * ry + lift * cy
    out[5] = -drag * rz + lift * cz - gravity
    out[6] = -air[9] * speed * y[6] / radius


# Dormand-Prince 5(4): nodes, the stages' weights, the 5th-order weights and the error weights (5th minus 4th)
_A = np.array([[0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
               [1 / 5, 0.0, 0.0, 0.0, 0.0, 0.0],
               [3 / 40, 9 / 40, 0.0, 0.0, 0.0, 0.0],
               [44 / 45, -56 / 15, 32 / 9, 0.0, 0.0, 0.0],
               [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0, 0.0],
               [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0.0]])
_B = np.array([35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84, 0.0])
_E = np.array([71 / 57600, 0.0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])


@register_jitable
def _step(y, h, stages, out, work, air, model, c, gravity):
    """One Dormand-Prince step of length h from y (``stages[0]`` = f(y) given) to ``out`` (5th order); fills
    stages 1-5, not the 7th (f(out), which the caller evaluates when it keeps the step)."""
    for i in range(1, 6):
        for j in range(7):
            acc = y[j]
            for m in range(i):
                acc += h * _A[i, m] * stages[m, j]
            work[j] = acc
        _derivative(work, stages[i], air, model, c, gravity)
    for j in range(7):
        acc = y[j]
        for m in range(6):
            acc += h * _B[m] * stages[m, j]
        out[j] = acc


@register_jitable
def _error(y, out, h, stages, rtol):
    """The step's error estimate over its tolerance (1: at the bound); stage 6 = f(out). The horizontal position
    and velocity are measured by their length, so the steps (and the carry) do not change when the launch direction
    turns the shot about the vertical; an absolute scale of 1 (m, m/s, rad/s): the error of a flight's metres, not
    of its launch's digits."""
    e = np.empty(7)
    for j in range(7):
        acc = 0.0
        for m in range(7):
            acc += _E[m] * stages[m, j]
        e[j] = h * acc
    worst = 0.0
    for j in (0, 3):  # the horizontal position, then velocity
        size = max(np.sqrt(y[j] ** 2 + y[j + 1] ** 2), np.sqrt(out[j] ** 2 + out[j + 1] ** 2))
        worst = max(worst, np.sqrt(e[j] ** 2 + e[j + 1] ** 2) / (rtol * (1.0 + size)))
    for j in (2, 5, 6):  # height, vertical velocity, spin
        worst = max(worst, abs(e[j]) / (rtol * (1.0 + max(abs(y[j]), abs(out[j])))))
    return worst


# the Dormand-Prince continuous extension (Hairer, Norsett & Wanner II.6; as in scipy's RK45): the state at
# t0 + theta h is y0 + h sum_i k_i sum_j _P[i, j] theta^(j + 1), of order 4 (exact for a path polynomial of degree 4)
_P = np.array([[1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432],
               [0.0, 0.0, 0.0, 0.0],
               [0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799],
               [0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072],
               [0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632],
               [0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844],
               [0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423]])


@register_jitable
def _dense(y, stages, h, theta, out):
    """The state at t0 + theta h of the step [t0, t0 + h] from y (stages k1-k7 of the step) into ``out``."""
    powers = (theta, theta * theta, theta**3, theta**4)
    for j in range(7):
        acc = 0.0
        for i in range(7):
            acc += stages[i, j] * (_P[i, 0] * powers[0] + _P[i, 1] * powers[1] + _P[i, 2] * powers[2]
                                   + _P[i, 3] * powers[3])
        out[j] = y[j] + h * acc


@register_jitable
def _dense_slope(stages, h, theta, index):
    """d/dt of component ``index`` of the continuous extension at t0 + theta h."""
    acc = 0.0
    for i in range(7):
        acc += stages[i, index] * (_P[i, 0] + 2.0 * _P[i, 1] * theta + 3.0 * _P[i, 2] * theta**2
                                   + 4.0 * _P[i, 3] * theta**3)
    return acc


@register_jitable
def _root(y, stages, h, index, out):
    """The fraction theta of the step at which component ``index`` of the state crosses zero going down (positive,
    or zero at the launch, at 0; not positive at 1), by Newton's method on the continuous extension kept in the
    bracket by bisection; the state there in ``out``. Newton from the step's end approaches the last root from
    the right, so the launch's own zero (a flight shorter than one step) is not taken for the landing."""
    lo = 0.0
    hi = 1.0
    theta = 1.0
    for _ in range(100):
        _dense(y, stages, h, theta, out)
        value = out[index]
        if value > 0.0:
            lo = theta
        else:
            hi = theta
        if value == 0.0 or hi - lo <= 1e-15:
            break
        slope = h * _dense_slope(stages, h, theta, index)
        nxt = theta - value / slope if slope != 0.0 else 0.5 * (lo + hi)
        if not lo < nxt < hi:
            nxt = 0.5 * (lo + hi)
        if abs(nxt - theta) <= 1e-15:
            theta = nxt
            _dense(y, stages, h, theta, out)
            break
        theta = nxt
    return theta


@register_jitable
def _sample(y, stages, t0, h, land_time, land, samples, every, shot, out, scratch):
    """The path at the times k * every inside the step [t0, t0 + h] (its continuous extension) before
    ``land_time``, the landing state ``land`` from it on (to the last sample where the shot lands in this step)."""
    first = max(int(np.floor(t0 / every)) + 1, 1)
    last = samples - 1 if land_time <= t0 + h else min(int(np.floor((t0 + h) / every)), samples - 1)
    for k in range(first, last + 1):
        t = k * every
        if t >= land_time:
            for j in range(6):
                out[shot, j, k] = land[j]
            continue
        _dense(y, stages, h, (t - t0) / h, scratch)
        for j in range(6):
            out[shot, j, k] = scratch[j]


#: the most steps (taken or refused) of one shot: a golf shot takes 20-60; beyond this the step is following a
#: singular path (the ball stopped in the air) and the shot is not landed (NaN), never an endless loop
_MAX_STEPS = 20000


def _flight_cases(state0, air, model, c, gravity, rtol, max_step, t_max, every, results, paths):
    """Fly each shot (row of ``state0``, its air a row of ``air``) to where z comes back to 0.

    results[i] = landing x, y, z, vx, vy, vz, omega, time, apex height (NaN where the shot is still in the air at
    t_max, or where the steps fall below 1 ns or number more than ``_MAX_STEPS``: a ball stopped in the air, whose
    lift turns at once). With ``every`` > 0 the paths (x, y, z, vx, vy, vz) are sampled every ``every`` s into
    ``paths`` (shots, 6, samples), each from its landing on at its landing state.
    """
    stages = np.empty((7, 7))
    y = np.empty(7)
    y1 = np.empty(7)
    scratch = np.empty(7)
    work = np.empty(7)
    samples = paths.shape[2]
    for shot in range(state0.shape[0]):
        a = air[shot]
        for j in range(7):
            y[j] = state0[shot, j]
        for j in range(9):
            results[shot, j] = np.nan
        if every > 0.0:
            for j in range(6):
                paths[shot, j, 0] = y[j]
        if y[5] < 0.0:  # launched below the horizontal from the ground: it meets the ground at once
            for j in range(7):
                results[shot, j] = y[j]
            results[shot, 7] = 0.0
            results[shot, 8] = 0.0
            if every > 0.0:
                _sample(y, stages, 0.0, every, 0.0, y, samples, every, shot, paths, scratch)
            continue
        apex = 0.0
        _derivative(y, stages[0], a, model, c, gravity)
        t = 0.0
        h = min(0.01, max_step)
        for _ in range(_MAX_STEPS):
            if t >= t_max:
                break
            h = min(h, t_max - t)
            _step(y, h, stages, y1, work, a, model, c, gravity)
            _derivative(y1, stages[6], a, model, c, gravity)
            err = _error(y, y1, h, stages, rtol)
            if not err <= 1.0:  # rejected (or NaN): shrink (5th root of the error ratio, Hairer II.4), retry
                h *= max(0.2, 0.9 * err ** -0.2) if err == err else 0.2
                if h < 1e-9:  # a path the step cannot follow (a ball stopped in the air: its lift turns at once)
                    break  # not landed: NaN, as a flight still in the air at t_max
                continue
            if y[5] > 0.0 and y1[5] <= 0.0:  # the apex inside this step: vz = 0
                _root(y, stages, h, 5, scratch)
                apex = max(apex, scratch[2], y[2], y1[2])
            if y1[2] <= 0.0 and y1[5] < 0.0:  # landed inside this step: z = 0 going down
                theta = _root(y, stages, h, 2, scratch)
                for j in range(7):
                    results[shot, j] = scratch[j]
                results[shot, 7] = t + theta * h
                results[shot, 8] = apex
                if every > 0.0:
                    _sample(y, stages, t, h, t + theta * h, results[shot], samples, every, shot, paths, work)
                break
            if every > 0.0:
                _sample(y, stages, t, h, np.inf, y1, samples, every, shot, paths, scratch)
            t += h
            for j in range(7):
                y[j] = y1[j]
                stages[0, j] = stages[6, j]  # first same as last
            h = min(h * min(5.0, 0.9 * max(err, 1e-10) ** -0.2), max_step)


_flight_cases_kernel = _compiled(_flight_cases)
_coefficient_grid_kernel = _compiled(_coefficient_grid)
_checked: dict = {}


def kernel_model(model):
    """``(number, constants)`` with which the kernel flies the registered model named ``model``, or None where it
    cannot (a callable, a model it does not know, compiled coefficients that differ from numpy's: a stale cache)."""
    if not isinstance(model, str) or model not in _aero.MODELS:
        return None
    function = _aero.MODELS[model][0]
    number = _MODEL_NUMBERS.get(function)
    if number is None:
        return None
    constants = _model_constants(function)
    key = (model, function, constants.tobytes())
    if key not in _checked:
        s, re = (grid.ravel() for grid in np.meshgrid(np.linspace(0.0, 1.5, 16), np.geomspace(2.0e4, 4.0e5, 24)))
        cd, cl = np.empty(s.size), np.empty(s.size)
        _coefficient_grid_kernel(number, constants, s, re, cd, cl)
        want = np.broadcast_arrays(*function(s, re), s)[:2]
        _checked[key] = bool(np.allclose(cd, want[0], rtol=1e-12, atol=1e-14)
                             and np.allclose(cl, want[1], rtol=1e-12, atol=1e-14))
        if not _checked[key]:
            warnings.warn(f"the compiled coefficients of {model!r} differ from impactlab.physics.aerodynamics' (a "
                          f"numba cache older than an edit of its formulas?): flying it with the numpy integrator; "
                          f"delete impactlab/physics/kernels/__pycache__ to recompile", RuntimeWarning, stacklevel=3)
    return (number, constants) if _checked[key] else None


def flight_cases(state0, air, model, constants, gravity, rtol, max_step, t_max, every, samples):
    """Fly shots with the compiled kernel: ``(results (n, 9), paths (n, 6, samples))``; see :func:`_flight_cases`."""
    n = state0.shape[0]
    results = np.empty((n, 9))
    paths = np.full((n, 6, samples if every > 0.0 else 1), np.nan)
    _flight_cases_kernel(np.ascontiguousarray(state0), np.ascontiguousarray(air), model, constants, float(gravity),
                         float(rtol), float(max_step), float(t_max), float(every), results, paths)
    return results, paths
