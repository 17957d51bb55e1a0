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
springs' normal force, hence their Coulomb caps, by its load factor; the
springs then stop being exact where their 3-D traction exceeds mu p(r), which
is checked (:func:`coulomb_excess`, ``TangentialSolution.breaks_3d_limit``).
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

from . import kernels as _kernels
from .hertz import ELASTIC, NormalLaw, cached_grid

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
    #: (cases,) bool: at a step checked, the 3-D traction the springs represent exceeded the 3-D Coulomb limit
    #: (damped normal laws only, see coulomb_excess; None: not checked)
    breaks_3d_limit: np.ndarray | None = None
    #: (cases,) bool: the resolution the tolerance asks for exceeds what the method allows (None: not set here)
    capped: np.ndarray | None = None
    #: (cases,): a rolling couple's angular impulse, integral c d tau, and its work on the rolling, integral c w d tau
    #: [F_max delta_max] (scaled as in impactlab.physics.compliant3d; None: no couple; dem.solve_scaled)
    moment: np.ndarray | None = None
    rolling_work: np.ndarray | None = None

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


#: bytes kept of the compiled limit check's arrays: the inverse-transform kernels (they depend on the springs alone, so
#: one copy serves every normal law) and each law's 3-D pressures at the steps checked. Kept apart from
#: hertz.cached_grid's budget so that they never push a law's own grids out: held there, with one kernel per law, a
#: batch of 20 restitutions (20 laws) at the default tolerance rebuilt every grid at every call and ran 3x slower than
#: with no cache. Beyond these budgets an array is built for its call only (never slower than that).
KERNEL_BYTES = 16 * 2**20
CHECK_BYTES = 32 * 2**20
_KERNELS: dict = {}
_CHECKS: dict = {}


def _kept(store: dict, budget: int, key: tuple, owner, build) -> tuple:
    """The arrays ``build()`` returns, read-only, kept in ``store`` under ``key`` while ``budget`` bytes allow (oldest
    dropped first); ``owner`` is held with them so that an id in the key cannot be reused while kept."""
    hit = store.get(key)
    if hit is not None and hit[0] is owner:
        return hit[1]
    arrays = build()
    for array in arrays:
        array.setflags(write=False)
    size = sum(array.nbytes for array in arrays)
    if size <= budget:
        total = size + sum(entry[2] for entry in store.values())
        while store and total > budget:
            total -= store.pop(next(iter(store)))[2]
        store[key] = (owner, arrays, size)
    return arrays


def solve_scaled(chi, psi1, *, springs: int = 200, steps: int = 400, record: bool = False,
                 normal: NormalLaw | None = None, observe=None, _force_numpy: bool = False) -> TangentialSolution:
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
    normal : NormalLaw, optional
        The scaled normal history h(tau) and its load factor (default: elastic Hertz).
    observe : callable, optional
        Called after every step as ``observe(tau, u, cap)`` with the springs' scaled forces u (cases,
        springs) and their Coulomb caps (springs,); runs the numpy path (for diagnostics such as
        :func:`traction_3d`).
    """
    normal = normal or ELASTIC
    chi = np.atleast_1d(np.asarray(chi, dtype=float))
    psi1 = np.atleast_1d(np.asarray(psi1, dtype=float))
    weight = 1.0 / springs
    gain = TANGENTIAL_GAIN * chi * weight
    cap_offset, tau, h_nodes, load_nodes, inside = cached_grid(normal, ("mdr", springs, steps),
                                                               lambda: _spring_grid(normal, springs, steps))
    # a load factor that varies (a damped law) can make the springs' 3-D traction exceed mu p(r): MDR's limit
    detect = bool(np.ptp(load_nodes) > 0.0)
    interior = np.zeros(chi.size, dtype=bool)
    check_every = max(1, (tau.size - 1) // CHECKS)
    if _kernels.HAVE_NUMBA and not _force_numpy and observe is None:
        history = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
        stick = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
        if detect:  # the 3-D pressure at the steps checked depends on the grid alone, the transform on the springs
            kernel, = _kept(_KERNELS, KERNEL_BYTES, (springs,), None, lambda: (transform_kernel(springs),))
            pressure, jumps, in_contact = _kept(_CHECKS, CHECK_BYTES, (id(normal), springs, steps), normal, lambda: (
                _kernels.mdr_pressures(cap_offset, h_nodes, load_nodes, inside, kernel, check_every)))
        else:
            kernel, pressure, jumps, in_contact = np.zeros((1, 1)), np.zeros((1, 1)), np.zeros((1, 1)), np.zeros(
                1, dtype=np.int64)
        velocity_change, dissipation = _kernels.mdr_cases(chi, psi1, cap_offset, tau, h_nodes, load_nodes, inside,
                                                          weight, TANGENTIAL_GAIN, record, history, stick, detect,
                                                          kernel, check_every, EXCESS, interior, pressure, jumps,
                                                          in_contact)
        return TangentialSolution(velocity_change, tau if record else None, 1.5 * history if record else None,
                                  stick if record else None, tau.size - 1, dissipation,
                                  interior if detect else None)

    u = np.zeros((chi.size, springs))
    velocity_change = np.zeros(chi.size)  # X' - psi1, kept apart so a huge psi1 loses no digits
    dissipation = np.zeros(chi.size)
    acceleration = np.zeros(chi.size)
    history = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))  # written only when recording
    stick = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
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
        if observe is not None:
            observe(tau[k], u, cap)
        if detect and k % check_every == 0:
            interior |= coulomb_excess(u, cap) > EXCESS
    force = None
    if record:
        # F_t = mu * 2 E* a_max delta_max * integral u  and  F_max = (4/3) E* a_max delta_max
        force = 1.5 * history
    return TangentialSolution(velocity_change, tau if record else None, force, stick if record else None,
                              tau.size - 1, dissipation, interior if detect else None)


#: uniform time steps per spring: the cheapest split between time and spring error over the golf range (measured;
#: at low psi1 more steps per spring would pay, see docs/accuracy.md, but the steps follow the springs alone)
STEPS_PER_SPRING = 6
#: measured constant of the spring (quadrature) term of the error model in :func:`resolution`
ERROR_CONSTANT = 1.0
#: measured constant of the time-step term of the error model, which dominates at low psi1 (a nearly stuck contact)
TIME_ERROR_CONSTANT = 0.15
#: the rule until 2026-11 (this constant, the spring term alone) stays a floor: no case gets fewer springs than
#: it gave, so results that met a tighter check than the tolerance (gross slip against the rigid closed forms to
#: 1e-6, tests/test_benchmarks.py) still do
PREVIOUS_CONSTANT = 1.2
#: below this normalised incidence the rule stops refining (a loft of a few hundredths of a degree)
SMALLEST_SCALE = 1e-3
#: finest resolution the rule may choose; a tolerance needing more is flagged tolerance_not_met
MAX_SPRINGS = 8192


def resolution(tolerance: float, chi, psi1) -> tuple[np.ndarray, np.ndarray]:
    """Springs for each case so that |dJ_t| <= tolerance * min(mu J_n, m_t |V_x|), and whether capped.

    The bound is relative to the smaller of the tangential impulse's two scales, the Coulomb bound
    mu J_n and the impulse m_t |V_x| that stops the slip, so beta (= J_t/(m_t V_x) - 1), the spin and
    the launch angle are all accurate to about the tolerance. In the scaled variables the error of
    psi2 must stay below tol * min(4 chi, psi1). Measured (docs/accuracy.md, benchmarks/resolution_rule.py),
    with s = min(4 chi, psi1) and g = max(1, chi/4):

        |d psi2| / s <= (1.0 g^1.15 / sqrt(s) + 0.15 g^0.5 / s) / springs^2

    at STEPS_PER_SPRING steps per spring. The first term is the springs' (quadrature) error: the slip
    annuli of a mostly stuck contact are thin, hence its growth at small psi1. The second is the time
    steps' error (it falls as steps^-2 at fixed springs), which does not shrink with the slip and so
    dominates below psi1 of about 0.02 for a light-core ball (chi near 5). The springs are at least those
    of the previous rule, 1.2 g^1.15 / sqrt(s) alone (PREVIOUS_CONSTANT), which sets them above s of
    about 0.56 g^-1.3. Springs are rounded up on a ladder of quarter-octaves so that cases with nearby (chi, psi1)
    share one batched solve.
    """
    chi = np.asarray(chi, dtype=float)
    scale = np.maximum(np.minimum(np.asarray(psi1, dtype=float), 4.0 * chi), SMALLEST_SCALE)
    heavy = np.maximum(1.0, chi / 4.0)
    springs_term = heavy ** 1.15 / np.sqrt(scale)
    error = np.maximum(ERROR_CONSTANT * springs_term + TIME_ERROR_CONSTANT * np.sqrt(heavy) / scale,
                       PREVIOUS_CONSTANT * springs_term)
    wanted = np.maximum(12.0, np.sqrt(error / tolerance))
    springs = np.ceil(12.0 * 2.0 ** (np.ceil(4.0 * np.log2(wanted / 12.0) - 1e-9) / 4.0)).astype(np.int64)
    return np.minimum(springs, MAX_SPRINGS), springs > MAX_SPRINGS


#: steps at which a damped law's MDR state is checked against the 3-D Coulomb limit (about; see solve_scaled)
CHECKS = 64
#: relative excess of the 3-D traction over mu p(r) that flags a case (elastic laws give 0 to round-off)
EXCESS = 1e-3


def transform_kernel(cells: int) -> np.ndarray:
    """K[i, j] = 1/(pi sqrt(x_j^2 - r_i^2)) for the outer cell edges x_j > mid-points r_i, in cell widths."""
    edges = np.arange(1, cells + 1, dtype=float)
    mids = np.arange(cells, dtype=float) + 0.5
    return np.where(edges[None, :] > mids[:, None],
                    1.0 / (np.pi * np.sqrt(np.maximum(edges[None, :] ** 2 - mids[:, None] ** 2, 1e-300))), 0.0)


def traction_3d(line_load) -> np.ndarray:
    """The 3-D axisymmetric distribution at the cell mid-points that a row of MDR springs represents.

    The inverse MDR transform (Popov & Hess 2015, ch. 3), p(r) = -(1/pi) int_r^a q'(x) / sqrt(x^2 - r^2) dx,
    for a line load q piecewise constant on equal cells from the centre (q = 0 beyond the last cell given):
    it maps the springs' normal forces to the contact pressure and their tangential forces to the
    tangential traction.

    Parameters
    ----------
    line_load : ndarray (..., m)
        Forces of the springs of the first m cells (those in contact), any units.

    Returns
    -------
    ndarray (..., m)
        The 3-D distribution at the m cell mid-points, with lengths counted in cell widths (times the number
        of cells n per unit radius: per unit of the radius). The cell edges sample the integrable
        1/sqrt(x - r) singularity, so the error falls as n^-1/2 (3 % at 400 cells); a ratio of two transforms
        on the same cells (a traction over a pressure) is exact where both are proportional.
    """
    q = np.asarray(line_load, dtype=float)
    jumps = -np.diff(np.concatenate([q, np.zeros(q.shape[:-1] + (1,))], axis=-1), axis=-1)
    return jumps @ transform_kernel(q.shape[-1]).T


def coulomb_excess(u, cap) -> np.ndarray:
    """Largest max(|tau(r)| / (mu p(r))) - 1 over the contact of the 3-D state that MDR springs represent.

    ``u`` (cases, springs) are the springs' tangential forces, ``cap`` (springs,) their Coulomb caps, both in
    the scaled units of :func:`solve_scaled`. The two cells at the contact's edge, where both transforms vanish,
    are left out. With an elastic (Hertz) pressure the MDR state satisfies the 3-D limit exactly (0 to
    round-off); a damped law's does not everywhere (docs/models.md).
    """
    u = np.atleast_2d(u)
    m = int(np.count_nonzero(cap > 0.0))
    if m < 3:
        return np.zeros(u.shape[0])
    traction = traction_3d(u[:, :m])[:, : m - 2]
    pressure = traction_3d(cap[:m])[: m - 2]
    return np.max(np.abs(traction) / pressure[None, :], axis=1) - 1.0


def slip_inside_stick(u, cap) -> np.ndarray:
    """Whether a spring slips (at its cap) inside a spring that sticks, per case: a slip zone that is not an
    annulus at the contact's edge."""
    u = np.atleast_2d(u)
    inside = cap > 0.0
    slipping = (np.abs(u) >= cap * (1.0 - 1e-12)) & inside
    stuck = ~slipping & inside
    outermost_stuck = np.where(stuck.any(axis=1), stuck.shape[1] - 1 - np.argmax(stuck[:, ::-1], axis=1), -1)
    index = np.arange(u.shape[1])
    return np.any(slipping & (index[None, :] < outermost_stuck[:, None]), axis=1)


def _stick_radius(u, cap, h, springs):
    """Scaled radius of the stuck central region: cells from the centre whose spring is below its cap."""
    slipping = (np.abs(u) >= cap * (1.0 - 1e-12)) & (cap > 0.0)
    first_slip = np.where(slipping.any(axis=1), slipping.argmax(axis=1), springs)
    return np.minimum(first_slip / springs, np.sqrt(max(h, 0.0)))


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["TANGENTIAL_GAIN", "TangentialSolution", "event_grid", "KERNEL_BYTES", "CHECK_BYTES", "solve_scaled",
           "STEPS_PER_SPRING", "ERROR_CONSTANT", "TIME_ERROR_CONSTANT", "PREVIOUS_CONSTANT", "SMALLEST_SCALE",
           "MAX_SPRINGS", "resolution", "CHECKS", "EXCESS", "transform_kernel", "traction_3d", "coulomb_excess",
           "slip_inside_stick"]
