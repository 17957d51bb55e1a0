"""Compiled MDR time loop (:func:`impactlab.physics.mdr.solve_scaled`'s kernel), numpy reference beside it."""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


def _mdr_cases(chi, psi1, xi2, tau, h_nodes, load_nodes, inside, weight, gain_factor, record, history, stick,
               detect, kernel, check_every, excess, interior):
    """MDR time loop for each case; see mdr.solve_scaled for the method. Returns (slip change, dissipation).

    With ``detect``, ``interior[case]`` is set when, at one of the steps checked (every ``check_every``), the
    3-D traction the springs represent exceeds the 3-D Coulomb limit by more than ``excess`` somewhere (see
    mdr.coulomb_excess); ``kernel`` is mdr.transform_kernel(springs).
    """
    cases = chi.size
    springs = xi2.size
    nodes = tau.size
    velocity_change_out = np.zeros(cases)
    dissipation_out = np.zeros(cases)
    u = np.zeros(springs)
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
                # the 3-D traction and pressure the springs in contact represent (inverse MDR transform, at the
                # cell mid-points, the two edge cells left out); a traction beyond the Coulomb limit flags the case
                m = 0
                while m < reach and (h - xi2[m]) * load > 0.0:
                    m += 1
                for i in range(m - 2):
                    traction = 0.0
                    pressure = 0.0
                    for j in range(i, m):
                        next_u = u[j + 1] if j + 1 < m else 0.0
                        next_cap = (h - xi2[j + 1]) * load if j + 1 < m else 0.0
                        traction += (u[j] - next_u) * kernel[i, j]
                        pressure += ((h - xi2[j]) * load - next_cap) * kernel[i, j]
                    if abs(traction) > pressure * (1.0 + excess):
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
