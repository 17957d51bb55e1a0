"""The annular-strip solution of Maw, Barber & Fawcett: the contact's tangential traction, ring by ring.

The potential contact circle (radius a_max) is divided by n equally spaced
circles gamma_j = j/n (in units of a_max). The tangential traction is a sum
of elementary flat-punch distributions, one per circle,

    q_j(r) = lambda_j / sqrt(c_j^2 - r^2)   (r < c_j),

each of which displaces the surface uniformly inside its circle, by
pi lambda_j / G* (G* the MDR tangential modulus; Johnson 1985, section 7.2),
and, in the axisymmetric approximation, by (2/pi) arcsin(c_j/r) of that
outside it. At the ring mid-points rho_i = (i - 1/2)/n each step is a mixed
boundary-value problem for all rings at once:

- a ring outside the contact carries no traction;
- a ring that sticks moves with the rigid tangential displacement of the
  contact (its elastic displacement is the rigid one less the slip it has
  accumulated);
- a ring that slips carries the limiting traction mu p(r) against its slip.

Which rings stick is found by iteration (a stuck ring that would need more
than mu p slips; a slipping ring whose slip would reverse sticks again) until
the set no longer changes. New contact is laid down free of traction: a ring
entering contact starts stuck at the displacement it had just before.

Scaled like :mod:`.mdr` (tau = t V_z/delta_max, displacements in units of
mu E* delta_max / G*, Lambda_j = pi lambda_j / (mu E* delta_max)): the stuck
ring displacement is sum_j A_ij Lambda_j, the load on annulus i is
(1/2) sum_j C_ij Lambda_j against its limit integral sqrt(h - r^2) r dr, and the tangential force
enters the slip equation as X'' = -(15/4) chi sum_j Lambda_j gamma_j.

References
----------
N. Maw, J. R. Barber and J. N. Fawcett, Wear 38 (1976) 101-114; J. Lubr.
Technol. 103 (1981) 74-80. K. L. Johnson, *Contact Mechanics* (1985), §7.2.
"""

from __future__ import annotations

import numpy as np

from . import kernels as _kernels
from .hertz import ELASTIC, NormalLaw, cached_grid
from .mdr import TANGENTIAL_GAIN, TangentialSolution, event_grid

OUT, STICK, SLIP = 0, 1, 2


def influence_matrices(rings: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Ring radii rho, circle radii gamma, and the displacement A_ij and load C_ij coefficients.

    A_ij: displacement at the mid-radius of annulus i due to distribution j.
    C_ij: tangential load that distribution j puts on annulus i
    (gamma_{i-1} < r < gamma_i), the integral of r / sqrt(gamma_j^2 - r^2)
    over it; the Coulomb limit is imposed annulus by annulus on these loads,
    which makes the gross-slip force mu F_n exact whatever n.
    """
    rho = (np.arange(rings) + 0.5) / rings
    gamma = np.arange(1, rings + 1) / rings
    inner = gamma - 1.0 / rings
    inside = gamma[None, :] > rho[:, None]  # annulus i lies inside circle j
    load = np.where(inside, np.sqrt(np.maximum(gamma[None, :] ** 2 - inner[:, None] ** 2, 0.0))
                    - np.sqrt(np.maximum(gamma[None, :] ** 2 - gamma[:, None] ** 2, 0.0)), 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        displacement = np.where(inside, 1.0, 2.0 / np.pi * np.arcsin(np.minimum(gamma[None, :] / rho[:, None], 1.0)))
    return rho, gamma, displacement, load


def _pressure_loads(h: float, gamma: np.ndarray, rings: int) -> np.ndarray:
    """Integral of sqrt(h - r^2) r dr over each annulus (the Hertz load on it, scaled)."""
    radius = np.sqrt(max(h, 0.0))
    inner = np.minimum(gamma - 1.0 / rings, radius)
    outer = np.minimum(gamma, radius)
    return (np.maximum(h - inner**2, 0.0) ** 1.5 - np.maximum(h - outer**2, 0.0) ** 1.5) / 3.0


def _caps(h_nodes, load_nodes, inside, gamma, rings):
    """Coulomb limit of every annulus at every node, the sliver beyond the last mid-radius merged inwards."""
    caps = np.zeros((h_nodes.size, rings))
    for k, h in enumerate(h_nodes):
        cap = _pressure_loads(h, gamma, rings) * load_nodes[k]
        last = int(inside[k]) - 1
        if 0 <= last < rings - 1:
            # the sliver of contact beyond the last mid-radius is carried by the last annulus in contact
            cap[last] += cap[last + 1]
        caps[k] = cap
    return caps


def _ring_grid(normal, rings: int, steps: int):
    """Everything of a solve that depends on the normal law and the resolution only (cached per pair)."""
    rho, gamma, displacement, load = influence_matrices(rings)
    tau = event_grid(rho**2, steps, normal)
    h_nodes, load_nodes = normal.approach(tau), normal.load_factor(tau)
    inside = np.searchsorted(rho**2, h_nodes, side="left").astype(np.int64)  # annuli with rho^2 < h
    caps = _caps(h_nodes, load_nodes, inside, gamma, rings)
    return rho, gamma, displacement, load, tau, h_nodes, load_nodes, caps, inside


def solve_scaled(chi, psi1, *, rings: int = 40, steps: int = 400, record: bool = False,
                 max_iterations: int | None = None, normal: NormalLaw | None = None,
                 dense: bool = False) -> TangentialSolution:
    """Solve the scaled tangential impact by the annular-strip method, vectorised over cases.

    Parameters and result as :func:`impactlab.physics.mdr.solve_scaled`, with
    ``rings`` annuli instead of springs. ``steps`` counts the stick/slip
    iterations too (``TangentialSolution.steps`` is the number of time steps).

    ``dense=True`` runs the plain version: every case's full system solved
    afresh at every step and iteration (numpy, batched over cases). The
    default uses the compiled kernel, which factorises each case's system only
    when its stick/slip set changes and solves only the annuli in contact.

    Raises
    ------
    RuntimeError
        If the stick/slip set of some ring does not settle within
        ``max_iterations`` (default 2 * rings) at some step.
    """
    chi = np.atleast_1d(np.asarray(chi, dtype=float))
    psi1 = np.atleast_1d(np.asarray(psi1, dtype=float))
    cases = chi.size
    normal = normal or ELASTIC
    rho, gamma, displacement, load, tau, h_nodes, load_nodes, caps, inside = cached_grid(
        normal, ("annuli", rings, steps), lambda: _ring_grid(normal, rings, steps))
    max_iterations = max_iterations or 2 * rings
    if _kernels.HAVE_NUMBA and not dense:
        history = np.zeros((cases, tau.size)) if record else np.zeros((1, 1))
        stick = np.zeros((cases, tau.size)) if record else np.zeros((1, 1))
        velocity_change, dissipation, failures = _kernels.annuli_cases(
            chi, psi1, tau, inside, caps, displacement, load, gamma, TANGENTIAL_GAIN, max_iterations, record,
            history, stick, h_nodes)
        if failures:
            raise RuntimeError(f"annular-strip stick/slip set did not settle in {max_iterations} iterations "
                               f"at {failures} step(s)")
        return TangentialSolution(velocity_change, tau if record else None, history if record else None,
                                  stick if record else None, tau.size - 1, dissipation)

    mode = np.zeros((cases, rings), dtype=np.int8)  # all rings outside the contact at first touch
    direction = np.zeros((cases, rings))  # sign of the limiting traction of slipping rings
    offset = np.zeros((cases, rings))  # accumulated slip: a stuck ring sits at X - offset
    strength = np.zeros((cases, rings))  # Lambda_j
    position = np.zeros(cases)
    velocity_change = np.zeros(cases)
    dissipation = np.zeros(cases)
    acceleration = np.zeros(cases)
    force = np.zeros((cases, tau.size)) if record else np.zeros((1, 1))  # written only when recording
    stick = np.zeros((cases, tau.size)) if record else np.zeros((1, 1))

    for k in range(1, tau.size):
        dt = tau[k] - tau[k - 1]
        half = velocity_change + 0.5 * dt * acceleration
        previous_position = position
        position = position + dt * (psi1 + half)
        in_contact = np.arange(rings) < inside[k]
        cap = caps[k]

        # rings entering contact stick where they are; rings leaving carry no traction
        entering = (mode == OUT) & in_contact[None, :]
        if entering.any():
            before = strength @ displacement.T
            offset = np.where(entering, previous_position[:, None] - before, offset)
            mode = np.where(entering, STICK, mode)
        mode = np.where(in_contact[None, :], mode, OUT)

        for _ in range(max_iterations):
            matrix = np.where((mode == STICK)[:, :, None], displacement[None], load[None])
            rhs = np.where(mode == STICK, position[:, None] - offset,
                           np.where(mode == SLIP, 2.0 * direction * cap, 0.0))
            strength = np.linalg.solve(matrix, rhs[:, :, None])[:, :, 0]
            q = 0.5 * strength @ load.T  # load on each annulus, against its Coulomb limit mu * cap
            u = strength @ displacement.T
            overloaded = (mode == STICK) & (np.abs(q) > cap * (1 + 1e-10) + 1e-14)
            reversing = (mode == SLIP) & (direction * (position[:, None] - u - offset) < -1e-12)
            if not (overloaded.any() or reversing.any()):
                break
            direction = np.where(overloaded, np.sign(q), direction)
            mode = np.where(overloaded, SLIP, np.where(reversing, STICK, mode))
        else:
            raise RuntimeError(f"annular-strip stick/slip set did not settle in {max_iterations} iterations "
                               f"at tau = {tau[k]:.4g}")
        offset = np.where(mode == SLIP, position[:, None] - u, offset)

        previous_total = -acceleration / (TANGENTIAL_GAIN * chi)
        total = strength @ gamma
        # work of the tangential force on the contact (trapezoid), all dissipated once contact ends
        dissipation += 0.5 * (previous_total + total) * (position - previous_position)
        acceleration = -TANGENTIAL_GAIN * chi * total
        velocity_change = half + 0.5 * dt * acceleration
        if record:
            force[:, k] = 1.5 * total  # F_t / (mu F_max), as in mdr
            slipping = (mode == SLIP)
            first_slip = np.where(slipping.any(axis=1), slipping.argmax(axis=1), rings)
            stick[:, k] = np.where(first_slip >= inside[k], np.sqrt(h_nodes[k]), first_slip / rings)
    return TangentialSolution(velocity_change, tau if record else None, force if record else None,
                              stick if record else None, tau.size - 1, dissipation)


def resolution(tolerance: float) -> tuple[int, bool]:
    """Annuli for a target error of |J_t| / (mu J_n); True when capped at MAX_RINGS.

    Measured against MDR: the error falls as ~0.15 / rings^1.4 (docs/accuracy.md). Unlike MDR's
    rule, this one bounds the error against the Coulomb bound only (beta at low loft is looser).
    """
    wanted = int(np.ceil((0.15 / tolerance) ** (1.0 / 1.4)))
    return min(max(wanted, 8), MAX_RINGS), wanted > MAX_RINGS


#: uniform time steps per annulus (at least ANNULI_MIN_STEPS)
STEPS_PER_ANNULUS = 10
ANNULI_MIN_STEPS = 200


#: beyond this a dense solve per step and iteration gets slow; a tighter tolerance is flagged as not met
MAX_RINGS = 160


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["influence_matrices", "solve_scaled", "resolution", "STEPS_PER_ANNULUS", "ANNULI_MIN_STEPS", "MAX_RINGS"]
