"""Compiled MDR time loop (:func:`impactlab.physics.mdr.solve_scaled`'s kernel), numpy reference beside it."""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


def _mdr_pressures(xi2, h_nodes, load_nodes, inside, kernel, check_every):
    """The 3-D pressure (inverse MDR transform of the springs' caps) at every step checked, and the springs in contact.

    It depends on the grid alone, not on the case: computed once per grid (mdr.solve_scaled caches it), so that a
    case's check in :func:`_mdr_cases` costs one triangular product, its traction. Row c is step (c + 1) check_every;
    the two cells at the contact's edge are left out (0). Also the jumps of the caps from cell to cell (> 0), whose
    transform the pressure is.
    """
    springs = xi2.size
    checks = (h_nodes.size - 1) // check_every
    pressure = np.zeros((max(checks, 1), springs))
    pressure_jump = np.zeros((max(checks, 1), springs))
    in_contact = np.zeros(max(checks, 1), dtype=np.int64)
    for c in range(checks):
        k = (c + 1) * check_every
        h = h_nodes[k]
        load = load_nodes[k]
        reach = max(inside[k], inside[k - 1])
        m = 0
        while m < reach and (h - xi2[m]) * load > 0.0:
            m += 1
        in_contact[c] = m
        for j in range(m):
            pressure_jump[c, j] = (h - xi2[j]) * load - ((h - xi2[j + 1]) * load if j + 1 < m else 0.0)
        for i in range(m - 2):
            total = 0.0
            for j in range(i, m):
                next_cap = (h - xi2[j + 1]) * load if j + 1 < m else 0.0
                total += ((h - xi2[j]) * load - next_cap) * kernel[i, j]
            pressure[c, i] = total
    return pressure, pressure_jump, in_contact


def _mdr_cases(chi, psi1, xi2, tau, h_nodes, load_nodes, inside, weight, gain_factor, record, history, stick,
               detect, kernel, check_every, excess, interior, pressure, pressure_jump, in_contact):
    """MDR time loop for each case; see mdr.solve_scaled for the method. Returns (slip change, dissipation).

    With ``detect``, ``interior[case]`` is set when, at one of the steps checked (every ``check_every``), the
    3-D traction the springs represent exceeds the 3-D Coulomb limit by more than ``excess`` somewhere (see
    mdr.coulomb_excess); ``kernel`` is mdr.transform_kernel(springs), ``pressure``, ``pressure_jump`` and
    ``in_contact`` those of :func:`_mdr_pressures` on the same grid.
    """
    cases = chi.size
    springs = xi2.size
    nodes = tau.size
    velocity_change_out = np.zeros(cases)
    dissipation_out = np.zeros(cases)
    u = np.zeros(springs)
    jump = np.zeros(springs)
    for case in range(cases):
        for i in range(springs):
            u[i] = 0.0
        gain = gain_factor * chi[case] * weight
        velocity_change = 0.0
        acceleration = 0.0
        dissipation = 0.0
        previous_total = 0.0
        p1 = psi1[case]
        for k in range(1, nodes):
            dt = tau[k] - tau[k - 1]
            half = velocity_change + 0.5 * dt * acceleration
            dx = dt * (p1 + half)
            h = h_nodes[k]
            load = load_nodes[k]
            reach = max(inside[k], inside[k - 1])  # springs beyond both contacts are, and stay, at zero
            total = 0.0
            first_slip = springs
            if not record:
                # the fast path, no stick radius to track: branch-free, so that the loop vectorises (the
                # kernel is compiled with reassociation; the sum differs from numpy's by round-off only)
                for i in range(reach):
                    limit = max((h - xi2[i]) * load, 0.0)
                    value = max(min(u[i] + dx, limit), -limit)
                    u[i] = value
                    total += value
            else:
                for i in range(reach):
                    cap = (h - xi2[i]) * load
                    if cap < 0.0:
                        cap = 0.0
                    value = u[i] + dx
                    if value > cap:
                        value = cap
                        if first_slip == springs and cap > 0.0:
                            first_slip = i
                    elif value < -cap:
                        value = -cap
                        if first_slip == springs and cap > 0.0:
                            first_slip = i
                    u[i] = value
                    total += value
            if detect and not interior[case] and k % check_every == 0:
                # the 3-D traction the springs in contact represent (inverse MDR transform, at the cell mid-points,
                # the two edge cells left out) against the step's 3-D pressure: beyond the Coulomb limit flags the case
                c = k // check_every - 1
                m = in_contact[c]
                # the transform's weights are positive: where no jump of the springs' forces beyond the cell exceeds
                # the caps' (1 + excess), neither can the traction exceed the pressure (1 + excess). Only the cells
                # inside the outermost such jump are summed
                last = -1
                for j in range(m):
                    jump[j] = u[j] - (u[j + 1] if j + 1 < m else 0.0)
                    if abs(jump[j]) > pressure_jump[c, j] * (1.0 + excess):
                        last = j
                for i in range(min(last + 1, m - 2)):
                    traction = 0.0
                    for j in range(i, m):
                        traction += jump[j] * kernel[i, j]
                    if abs(traction) > pressure[c, i] * (1.0 + excess):
                        interior[case] = True
                        break
            dissipation += 0.5 * weight * (previous_total + total) * dx
            previous_total = total
            acceleration = -gain * total
            velocity_change = half + 0.5 * dt * acceleration
            if record:
                history[case, k] = total * weight
                radius = first_slip / springs
                root = np.sqrt(h) if h > 0.0 else 0.0
                stick[case, k] = radius if radius < root else root
        velocity_change_out[case] = velocity_change
        dissipation_out[case] = dissipation
    return velocity_change_out, dissipation_out


# one function with its own flags: a fastmath helper linked into a plain kernel compiles differently when
# fresh and when loaded from numba's cache, which would make results depend on the process (executors)
mdr_cases = _compiled(_mdr_cases, fastmath={"reassoc", "nsz"})
mdr_pressures = _compiled(_mdr_pressures, fastmath={"reassoc", "nsz"})
