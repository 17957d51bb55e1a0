"""Compiled inner loops (numba), with the numpy implementations as the reference and the fallback.

The kernels run one case at a time, which lets them skip the springs outside
the contact and keep a case's springs in cache; the numpy versions in
:mod:`.mdr` run all cases at once. Both do the same arithmetic in the same
order per spring, so results agree to round-off (tests/test_kernels.py).
Set IMPACTLAB_KERNELS=numpy to force the numpy path.
"""

from __future__ import annotations

import os

import numpy as np

try:  # numba is a dependency, but impactlab stays usable (slower) where it cannot be installed
    import numba

    HAVE_NUMBA = os.environ.get("IMPACTLAB_KERNELS", "numba") != "numpy"
except ImportError:  # pragma: no cover - depends on the platform
    numba = None
    HAVE_NUMBA = False


def _mdr_cases(chi, psi1, xi2, tau, h_nodes, load_nodes, inside, weight, gain_factor, record, history, stick):
    """MDR time loop for each case; see mdr.solve_scaled for the method. Returns (slip change, dissipation)."""
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


if HAVE_NUMBA:
    mdr_cases = numba.njit(cache=True, nogil=True)(_mdr_cases)
else:  # pragma: no cover
    mdr_cases = None
