"""Tangential compliance with Coulomb microslip by the method of dimensionality reduction (MDR).

The 3-D contact of a sphere is mapped exactly (Popov & Hess) onto a row of
independent springs along x with the profile g(x) = x^2/R: normal spring
displacement w = delta - x^2/R, tangential springs that take the rigid
tangential displacement of the contact while they stick and are capped at
|G* u| <= mu E* w. Springs enter contact with u = 0 and are reset on leaving.

Scaling (elastic normal problem, see :mod:`.hertz`): with tau = t V_z/delta_max,
xi = x/a_max, the approach h(tau) and the tangential displacement in units of
mu E* delta_max / G*, the whole impact depends on one parameter and one input
(Maw, Barber & Fawcett 1976):

    chi  = (kappa / 2) m*/m_t,          kappa = G*/E*  (= k_t/k_n)
    psi1 = kappa V_x / (mu V_z)         (normalised incidence)

and the slip obeys X'' = -(15/4) chi * integral_0^1 u(xi) dxi with X'(0) = psi1.
Gross slip throughout gives psi2 = psi1 - 4 chi exactly.

Numerics: springs at the mid-points of n equal cells of [0, 1]; the time grid
is a uniform grid merged with the exact instants at which each spring enters
and leaves contact (in closed form for the elastic law), so contact changes
fall on steps. A damped normal law (:class:`.hertz.DampedNormal`) scales the
springs' normal force, hence their Coulomb caps, by its load factor.
Between nodes, velocity Verlet; each step adds the slip increment to every
spring and returns it to its Coulomb cap (a return map, exact for a
monotonic slip within a step).

References
----------
V. L. Popov and M. Hess, *Method of Dimensionality Reduction in Contact
Mechanics and Friction*, Springer (2015), ch. 3 and 5.
N. Maw, J. R. Barber and J. N. Fawcett, "The oblique impact of elastic
spheres", Wear 38 (1976) 101-114.
"""

from __future__ import annotations

import attrs
import numpy as np

from . import _kernels
from .hertz import ELASTIC, cached_grid

#: dX''/dtau = -TANGENTIAL_GAIN * chi * integral u dxi
TANGENTIAL_GAIN = 15.0 / 4.0


@attrs.frozen
class TangentialSolution:
    """Result of :func:`solve_scaled`.

    Attributes
    ----------
    slip_change : ndarray (cases,)
        psi2 - psi1, the change of the normalised slip velocity.
    tau : ndarray (nodes,) or None
        Scaled time nodes (histories only).
    force : ndarray (cases, nodes) or None
        Scaled tangential force F_t / (mu F_max), positive along the incoming slip
        of the springs (opposing the slip on the ball).
    stick_radius : ndarray (cases, nodes) or None
        Radius of the stuck central region over a_max: the springs from the
        centre outwards that are below their Coulomb cap (0 in gross slip; the
        contact radius when the whole contact sticks).
    steps : int
        Number of time steps taken.
    dissipation : ndarray (cases,)
        Work of the tangential force on the contact over the impact (trapezoid
        rule), scaled so that (psi1^2 - psi2^2)/2 = TANGENTIAL_GAIN * chi *
        dissipation in exact arithmetic: the springs store nothing once contact
        ends, so all of it was dissipated by friction. The residual measures the
        time integration's error in the energy balance.
    """

    slip_change: np.ndarray
    tau: np.ndarray | None
    force: np.ndarray | None
    stick_radius: np.ndarray | None
    steps: int
    dissipation: np.ndarray | None = None

    def energy_residual(self, chi, psi1):
        """Scaled energy-balance residual: tangential kinetic energy lost minus friction work."""
        psi2 = psi1 + self.slip_change
        return 0.5 * (psi1**2 - psi2**2) - TANGENTIAL_GAIN * chi * self.dissipation


def event_grid(levels, steps: int, normal) -> np.ndarray:
    """A uniform grid over the contact merged with the instants h rises through and falls through each level."""
    rise, fall = normal.crossing_times(levels)
    tau = np.unique(np.concatenate([np.linspace(0.0, normal.tau_end, steps + 1), rise, fall]))
    return tau[(tau >= 0.0) & (tau <= normal.tau_end)]


def _spring_grid(normal, springs: int, steps: int):
    """Spring offsets xi^2, time nodes, h and load factor at the nodes, springs inside at each node."""
    xi = (np.arange(springs) + 0.5) / springs
    tau = event_grid(xi**2, steps, normal)
    h_nodes = normal.approach(tau)
    inside = np.searchsorted(xi**2, h_nodes, side="left").astype(np.int64)  # springs with xi^2 < h
    return xi**2, tau, h_nodes, normal.load_factor(tau), inside


def solve_scaled(chi, psi1, *, springs: int = 200, steps: int = 400, record: bool = False,
                 normal=None, _force_numpy: bool = False) -> TangentialSolution:
    """Solve the scaled tangential impact for each (chi, psi1) pair, vectorised over cases.

    Parameters
    ----------
    chi : array_like (cases,)
        MBF parameter (kappa/2) m*/m_t > 0.
    psi1 : array_like (cases,)
        Normalised incidence kappa V_x / (mu V_z) >= 0.
    springs : int
        Springs on the half-contact 0 <= xi <= 1.
    steps : int
        Uniform steps over the contact (spring entry and exit instants are added).
    record : bool
        Keep the scaled force and stick-radius histories.
    normal : ElasticNormal or DampedNormal, optional
        The scaled normal history h(tau) and its load factor (default: elastic Hertz).
    """
    normal = normal or ELASTIC
    chi = np.atleast_1d(np.asarray(chi, dtype=float))
    psi1 = np.atleast_1d(np.asarray(psi1, dtype=float))
    weight = 1.0 / springs
    gain = TANGENTIAL_GAIN * chi * weight
    cap_offset, tau, h_nodes, load_nodes, inside = cached_grid(normal, ("mdr", springs, steps),
                                                               lambda: _spring_grid(normal, springs, steps))
    if _kernels.HAVE_NUMBA and not _force_numpy:
        history = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
        stick = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
        velocity_change, dissipation = _kernels.mdr_cases(chi, psi1, cap_offset, tau, h_nodes, load_nodes, inside,
                                                          weight, TANGENTIAL_GAIN, record, history, stick)
        return TangentialSolution(velocity_change, tau if record else None, 1.5 * history if record else None,
                                  stick if record else None, tau.size - 1, dissipation)

    u = np.zeros((chi.size, springs))
    velocity_change = np.zeros(chi.size)  # X' - psi1, kept apart so a huge psi1 loses no digits
    dissipation = np.zeros(chi.size)
    acceleration = np.zeros(chi.size)
    history = np.zeros((chi.size, tau.size)) if record else None
    stick = np.zeros((chi.size, tau.size)) if record else None
    for k in range(1, tau.size):
        dt = tau[k] - tau[k - 1]
        half = velocity_change + 0.5 * dt * acceleration
        u += (dt * (psi1 + half))[:, None]
        cap = np.maximum(h_nodes[k] - cap_offset, 0.0) * load_nodes[k]
        np.clip(u, -cap, cap, out=u)
        previous_total = -acceleration / gain if k > 1 else np.zeros(chi.size)
        total = u.sum(axis=1)
        # work of the tangential force on the contact (trapezoid); all of it is dissipated once contact ends
        dissipation += 0.5 * weight * (previous_total + total) * dt * (psi1 + half)
        acceleration = -gain * total
        velocity_change = half + 0.5 * dt * acceleration
        if record:
            history[:, k] = total * weight
            stick[:, k] = _stick_radius(u, cap, h_nodes[k], springs)
    force = None
    if record:
        # F_t = mu * 2 E* a_max delta_max * integral u  and  F_max = (4/3) E* a_max delta_max
        force = 1.5 * history
    return TangentialSolution(velocity_change, tau if record else None, force, stick, tau.size - 1, dissipation)


#: uniform time steps per spring: the cheapest split between time and spring error (measured)
STEPS_PER_SPRING = 6
#: measured constant of the error model in :func:`resolution` (largest over chi 0.3-15, psi1 1e-3-6 chi)
ERROR_CONSTANT = 1.2
#: below this normalised incidence the rule stops refining (a loft of a few hundredths of a degree)
SMALLEST_SCALE = 1e-3
#: finest resolution the rule may choose; a tolerance needing more is flagged tolerance_not_met
MAX_SPRINGS = 8192


def resolution(tolerance: float, chi, psi1) -> tuple[np.ndarray, np.ndarray]:
    """Springs for each case so that |dJ_t| <= tolerance * min(mu J_n, m_t |V_x|), and whether capped.

    The bound is relative to the smaller of the tangential impulse's two scales, the Coulomb bound
    mu J_n and the impulse m_t |V_x| that stops the slip, so beta (= J_t/(m_t V_x) - 1), the spin and
    the launch angle are all accurate to about the tolerance. In the scaled variables the error of
    psi2 must stay below tol * min(4 chi, psi1). Measured (docs/accuracy.md):

        |d psi2| <= 1.2 max(1, chi/4)^1.15 min(4 chi, psi1) / (springs^2 sqrt(min(4 chi, psi1)))

    the quadrature and time errors together at STEPS_PER_SPRING steps per spring; the slip annuli of
    a mostly stuck contact (small psi1) are thin, hence the extra factor. Springs are rounded up on a
    ladder of quarter-octaves so that cases with nearby (chi, psi1) share one batched solve.
    """
    chi = np.asarray(chi, dtype=float)
    scale = np.maximum(np.minimum(np.asarray(psi1, dtype=float), 4.0 * chi), SMALLEST_SCALE)
    wanted = np.sqrt(ERROR_CONSTANT * np.maximum(1.0, chi / 4.0) ** 1.15 / (tolerance * np.sqrt(scale)))
    wanted = np.maximum(12.0, wanted)
    springs = np.ceil(12.0 * 2.0 ** (np.ceil(4.0 * np.log2(wanted / 12.0) - 1e-9) / 4.0)).astype(np.int64)
    return np.minimum(springs, MAX_SPRINGS), springs > MAX_SPRINGS


def _stick_radius(u, cap, h, springs):
    """Scaled radius of the stuck central region: cells from the centre whose spring is below its cap."""
    slipping = (np.abs(u) >= cap * (1.0 - 1e-12)) & (cap > 0.0)
    first_slip = np.where(slipping.any(axis=1), slipping.argmax(axis=1), springs)
    return np.minimum(first_slip / springs, np.sqrt(max(h, 0.0)))
