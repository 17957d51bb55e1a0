"""Hertz normal contact of a sphere on a half-space, and its elastic impact.

The elastic Hertz impact has a universal shape: with the maximum approach
delta_max and T = delta_max / V_z, the approach is delta(t) = delta_max h(t/T)
where h'' = -(5/4) h^(3/2), h(0) = 0, h'(0) = 1. Energy conservation gives
h'^2 = 1 - h^(5/2), so the time to reach h is an incomplete beta function and
its inverse gives h(tau) exactly (no time stepping).

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press (1985), §4.2, §11.4.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike
from scipy import special

from impactlab.physics import Values

_A, _B = 0.4, 0.5
#: scaled time at maximum compression, tau_m = (2/5) B(2/5, 1/2)
TAU_MAX_COMPRESSION = 0.4 * special.beta(_A, _B)
#: scaled contact duration, tau_c = 2 tau_m = 2.9432...
TAU_CONTACT = 2.0 * TAU_MAX_COMPRESSION


def effective_modulus(e1: Values, nu1: Values, e2: Values, nu2: Values) -> Values:
    """Hertz contact modulus E*, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [Pa] (E2 = inf: rigid face)."""
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


def tangential_modulus(e1: Values, nu1: Values, e2: Values, nu2: Values) -> Values:
    """MDR tangential modulus G*, 1/G* = (2 - nu1)/(4 G1) + (2 - nu2)/(4 G2) [Pa].

    The Mindlin incremental tangential stiffness of a circular contact of
    radius a is 2 a G* (= 8 a G*_J with G*_J = G*/4).
    """
    g1 = e1 / (2.0 * (1.0 + nu1))
    g2 = e2 / (2.0 * (1.0 + nu2))
    return 1.0 / ((2.0 - nu1) / (4.0 * g1) + (2.0 - nu2) / (4.0 * g2))


def max_approach(effective_mass: Values, radius: Values, modulus: Values, normal_speed: Values) -> Values:
    """delta_max = (15 m* V^2 / (16 E* sqrt(R)))^(2/5) [m]."""
    return (15.0 * effective_mass * normal_speed**2 / (16.0 * modulus * np.sqrt(radius))) ** 0.4


def contact_time(effective_mass: Values, radius: Values, modulus: Values, normal_speed: Values) -> Values:
    """Elastic Hertz contact duration t_c = tau_c delta_max / V = 2.8682 (m*^2/(R E*^2 V))^(1/5) [s]."""
    return TAU_CONTACT * max_approach(effective_mass, radius, modulus, normal_speed) / normal_speed


def peak_force(effective_mass: Values, radius: Values, modulus: Values, normal_speed: Values) -> Values:
    """F_max = (4/3) E* sqrt(R) delta_max^(3/2) [N]."""
    return 4.0 / 3.0 * modulus * np.sqrt(radius) * max_approach(effective_mass, radius, modulus, normal_speed) ** 1.5


def scaled_approach(tau: ArrayLike) -> np.ndarray:
    """h(tau) = delta/delta_max of the elastic Hertz impact; 0 outside [0, tau_c]."""
    tau = np.asarray(tau, dtype=float)
    rising = np.clip(np.minimum(tau, TAU_CONTACT - tau), 0.0, TAU_MAX_COMPRESSION)
    # time_to_reach inverted: tau/tau_m = I(h^(5/2); 2/5, 1/2)
    return special.betaincinv(_A, _B, rising / TAU_MAX_COMPRESSION) ** 0.4


def time_to_reach(h: ArrayLike) -> np.ndarray:
    """Scaled time at which the approach first reaches h delta_max (0 <= h <= 1)."""
    h = np.asarray(h, dtype=float)
    return TAU_MAX_COMPRESSION * special.betainc(_A, _B, np.clip(h, 0.0, 1.0) ** 2.5)


@runtime_checkable
class NormalLaw(Protocol):
    """A normal law in scaled time, one for a whole batch: what the tangential kernels and the histories use.

    Time tau is scaled by T = delta_max / V_z and the approach h by delta_max of the elastic impact at the same
    approach speed, so that one law serves every case. :class:`ElasticNormal` (:data:`ELASTIC`) and
    :class:`DampedNormal` implement it; :class:`CaseNormals` (one damped law per case) carries only
    ``restitution``, ``damping`` and ``tau_end`` as arrays, which is all the 3-D kernel reads.

    Attributes
    ----------
    damping : float
        Hunt-Crossley damping c (0: elastic).
    restitution : float
        Exit speed over approach speed.
    tau_end : float
        Scaled time at which contact ends.
    """

    __slots__ = ()

    damping: float
    restitution: float
    tau_end: float

    def approach(self, tau: ArrayLike) -> np.ndarray:
        """h(tau) = delta / delta_max, 0 outside the contact."""

    def load_factor(self, tau: ArrayLike) -> np.ndarray:
        """Normal force over the elastic force k delta^(3/2) at the same approach (1 for the elastic law)."""

    def crossing_times(self, level: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Scaled times at which h rises through and falls back through ``level`` (arrays)."""


class ElasticNormal(NormalLaw):
    """The elastic Hertz impact in scaled time: h(tau), load factor 1, closed-form crossing times."""

    damping = 0.0
    restitution = 1.0
    tau_end = TAU_CONTACT

    def approach(self, tau: ArrayLike) -> np.ndarray:
        return scaled_approach(tau)

    def load_factor(self, tau: ArrayLike) -> np.ndarray:
        return np.ones_like(np.asarray(tau, dtype=float))

    def crossing_times(self, level: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Scaled times at which h rises through and falls back through ``level`` (arrays)."""
        rise = time_to_reach(level)
        return rise, TAU_CONTACT - rise


#: the elastic law (stateless): one instance, so that grids derived from it are cached once for all
ELASTIC = ElasticNormal()

_GRIDS: dict = {}
#: memory the cache may hold; the oldest grids go first
_GRIDS_BYTES = 64 * 2**20


def cached_grid(normal: NormalLaw, key: tuple, build: Callable[[], tuple]) -> tuple:
    """Arrays derived from a normal law (its time grid and samples), built once per law and key.

    The normal solution is shared by every case of a batch and every batch with the same law and
    resolution; sampling it (an inverse incomplete beta function per node) would otherwise dominate
    small batches. The arrays are returned read-only.
    """
    full_key = (id(normal), *key)
    hit = _GRIDS.get(full_key)
    if hit is not None and hit[0] is normal:
        return hit[1]
    arrays = build()
    size = 0
    for array in arrays:
        if isinstance(array, np.ndarray):
            array.setflags(write=False)
            size += array.nbytes
    _GRIDS[full_key] = (normal, arrays, size)  # holding the law keeps its id from being reused while cached
    total = sum(entry[2] for entry in _GRIDS.values())
    for oldest in list(_GRIDS):
        if total <= _GRIDS_BYTES or oldest == full_key:
            break
        total -= _GRIDS.pop(oldest)[2]
    return arrays


class DampedNormal(NormalLaw):
    """Hertz contact with Hunt-Crossley damping, F = k delta^(3/2) (1 + c d(delta)/dt / V_z), scaled.

    h'' = -(5/4) h^(3/2) (1 + c h') with h(0) = 0, h'(0) = 1 (scaled by the
    elastic delta_max and T = delta_max/V_z of the same approach speed). The
    force never pulls: contact ends when h returns to 0 or the force falls to
    zero first. The exit speed -h'(tau_end) is the coefficient of restitution,
    a function of c alone, so the law is chosen per requested e.

    References
    ----------
    K. H. Hunt and F. R. E. Crossley, Coefficient of restitution interpreted as
    damping in vibroimpact, J. Appl. Mech. 42 (1975) 440-445.
    """

    def __init__(self, damping: float):
        # scipy's solvers are imported where they are used (all of this module's): scipy.optimize alone takes
        # about 0.2 s to import, and a study of closed-form models never needs them
        from scipy.integrate import solve_ivp

        self.damping = float(damping)
        c = self.damping

        def rhs(_, y):
            h, v = y
            return [v, -1.25 * max(h, 0.0) ** 1.5 * (1.0 + c * v)]

        def unloaded(_, y):  # the force vanishes on the way out: 1 + c h' = 0, or h = 0
            h, v = y
            return min(h, 1.0 + c * v) if v < 0 else 1.0

        event: Any = unloaded  # solve_ivp reads its flags from attributes of the event function
        event.terminal, event.direction = True, -1
        solution = solve_ivp(rhs, (0.0, 4.0 * TAU_CONTACT), [0.0, 1.0], method="DOP853", rtol=1e-11, atol=1e-13,
                             dense_output=True, events=unloaded, first_step=1e-6)
        self._solution = solution.sol
        self.tau_end = float(solution.t_events[0][0]) if len(solution.t_events[0]) else float(solution.t[-1])
        h_end, v_end = solution.sol(self.tau_end)
        self.restitution = float(-v_end)
        self._peak_time = float(_argmax_time(solution.sol, self.tau_end))

    def approach(self, tau: ArrayLike) -> np.ndarray:
        tau = np.clip(np.asarray(tau, dtype=float), 0.0, self.tau_end)
        return np.maximum(self._solution(tau)[0], 0.0)

    def load_factor(self, tau: ArrayLike) -> np.ndarray:
        tau = np.clip(np.asarray(tau, dtype=float), 0.0, self.tau_end)
        return np.maximum(1.0 + self.damping * self._solution(tau)[1], 0.0)

    def crossing_times(self, level: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        from scipy.optimize import brentq

        level = np.asarray(level, dtype=float)
        peak = float(self.approach(self._peak_time))
        rise, fall = np.empty_like(level), np.empty_like(level)
        h_end = float(self.approach(self.tau_end))
        for index, target in enumerate(level):
            if target >= peak:
                rise[index] = fall[index] = self._peak_time
                continue
            rise[index] = brentq(lambda t: self.approach(t) - target, 0.0, self._peak_time, xtol=1e-13)
            fall[index] = self.tau_end if target <= h_end else brentq(
                lambda t: self.approach(t) - target, self._peak_time, self.tau_end, xtol=1e-13)
        return rise, fall


def _argmax_time(sol, tau_end):
    from scipy.optimize import brentq

    return brentq(lambda t: sol(t)[1], 1e-9, tau_end, xtol=1e-14)


@functools.cache
def _restitution_table() -> tuple[np.ndarray, np.ndarray]:
    """(damping, restitution) of exactly solved laws on a coarse grid: brackets for the root of one law."""
    dampings = np.concatenate([[0.0], np.geomspace(1e-3, 200.0, 60)])
    return dampings, np.array([DampedNormal(c).restitution for c in dampings])


def damping_for_restitution(restitution: float) -> float:
    """The Hunt-Crossley damping c (scaled) whose impact rebounds with ``restitution`` (0.05 <= e <= 1)."""
    from scipy.optimize import brentq

    if restitution >= 1.0:
        return 0.0
    dampings, restitutions = _restitution_table()
    if restitution < restitutions[-1]:
        raise ValueError(f"restitution {restitution} is below what the damped Hertz law reaches "
                         f"({restitutions[-1]:.3f})")
    index = int(np.searchsorted(-restitutions, -restitution))
    low, high = dampings[max(index - 1, 0)], dampings[min(index, dampings.size - 1)]
    return float(brentq(lambda c: DampedNormal(c).restitution - restitution, low, high, xtol=1e-10))


def _damped_exit(damping: float, steps: int = 20000) -> tuple[float, float]:
    """Exit speed (the restitution) and scaled duration of h'' = -(5/4) h^1.5 (1 + c h'), h(0) = 0, h'(0) = 1 (RK4).

    The contact ends when h returns to 0 or the force vanishes on the way out (1 + c h' = 0).
    """
    dt = 2.0 * TAU_CONTACT / steps

    def acceleration(h, v):
        return -1.25 * max(h, 0.0) ** 1.5 * max(1.0 + damping * v, 0.0)

    h, v, tau = 0.0, 1.0, 0.0
    for _ in range(4 * steps):
        k1h, k1v = v, acceleration(h, v)
        k2h, k2v = v + 0.5 * dt * k1v, acceleration(h + 0.5 * dt * k1h, v + 0.5 * dt * k1v)
        k3h, k3v = v + 0.5 * dt * k2v, acceleration(h + 0.5 * dt * k2h, v + 0.5 * dt * k2v)
        k4h, k4v = v + dt * k3v, acceleration(h + dt * k3h, v + dt * k3v)
        h_new = h + dt * (k1h + 2 * k2h + 2 * k3h + k4h) / 6
        v_new = v + dt * (k1v + 2 * k2v + 2 * k3v + k4v) / 6
        if v_new < 0.0 and (h_new <= 0.0 or 1.0 + damping * v_new <= 0.0):
            # the end inside this step: linear interpolation of the crossing
            if h_new <= 0.0:
                fraction = h / (h - h_new) if h != h_new else 1.0
            else:
                fraction = (1.0 + damping * v) / (damping * (v - v_new)) if v != v_new else 1.0
            fraction = min(max(fraction, 0.0), 1.0)
            return float(-(v + fraction * (v_new - v))), tau + fraction * dt
        h, v, tau = h_new, v_new, tau + dt
    return float(-v), tau


@functools.cache
def damping_table() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(restitution, damping, scaled duration) on a dense grid of the Hunt-Crossley damping, built once per process.

    Building it integrates 161 damped Hertz impacts of 4000 steps each in Python: 9.9-11 s measured on the project's
    shared 2-core machine (``python -c "from impactlab.physics import hertz; hertz.damping_for_restitutions([0.8])"``,
    issue 34), not the ~1 s once stated; every later call takes about a millisecond.

    A law per case (a speed-dependent restitution makes every case's e distinct) cannot afford the per-law
    solve of :class:`DampedNormal`; the table, inverted by monotone interpolation, gives c and the duration.
    """
    dampings = np.concatenate([[0.0], np.geomspace(1e-3, 200.0, 160)])
    exits = np.array([_damped_exit(c, steps=4000) for c in dampings])
    return exits[:, 0], dampings, exits[:, 1]


def damping_for_restitutions(restitution) -> tuple[np.ndarray, np.ndarray]:
    """Hunt-Crossley damping c and scaled contact duration for each restitution (vectorised, table + PCHIP).

    The first call in a process builds :func:`damping_table` (about 10 s); later calls take about a millisecond.
    """
    from scipy.interpolate import PchipInterpolator

    restitutions, dampings, durations = damping_table()
    order = np.argsort(restitutions)
    e = np.clip(np.asarray(restitution, dtype=float), restitutions.min(), 1.0)
    # interpolate log(1 + c), smooth in e; the table is monotone (more damping, less rebound)
    c = np.expm1(PchipInterpolator(restitutions[order], np.log1p(dampings[order]))(e))
    tau = PchipInterpolator(restitutions[order], durations[order])(e)
    return np.where(e >= 1.0, 0.0, c), tau


class CaseNormals:
    """Hunt-Crossley laws, one per case (arrays of damping and scaled duration), for the 3-D kernel.

    Used when the cases' restitutions are too many to solve a :class:`DampedNormal` for each (a restitution law
    of the impact speed makes every case's e distinct).
    """

    def __init__(self, restitution):
        self.restitution = np.asarray(restitution, dtype=float)
        self.damping, self.tau_end = damping_for_restitutions(self.restitution)

    def subset(self, rows) -> CaseNormals:
        """The laws of the cases ``rows`` (an index or mask), for a batch split by solver path."""
        part = object.__new__(CaseNormals)
        part.restitution, part.damping, part.tau_end = self.restitution[rows], self.damping[rows], self.tau_end[rows]
        return part


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["TAU_MAX_COMPRESSION", "TAU_CONTACT", "effective_modulus", "tangential_modulus", "max_approach",
           "contact_time", "peak_force", "scaled_approach", "time_to_reach", "NormalLaw", "ElasticNormal", "ELASTIC",
           "cached_grid", "DampedNormal", "damping_for_restitution", "damping_table", "damping_for_restitutions",
           "CaseNormals"]
