"""A plain first-order MDR stepper, kept only as the yardstick for benchmarks (not used by impactlab).

Symplectic Euler in the scaled variables for both the normal and the
tangential motion, uniform springs, uniform steps, contact ending when the
approach first turns negative: what a straightforward implementation of the
physics brief's section 3.2 looks like, vectorised over cases with numpy.
"""

import numpy as np

GAIN = 15.0 / 4.0


def first_order_mdr(chi, psi1, springs, steps):
    """psi2 - psi1 for each case (elastic impact, scaled as in impactlab.physics.mdr)."""
    chi, psi1 = np.asarray(chi, float), np.asarray(psi1, float)
    xi2 = ((np.arange(springs) + 0.5) / springs) ** 2
    dt = 3.2 / steps  # a little beyond the contact time, which the stepper has to find
    h = np.zeros(chi.size)
    v = np.ones(chi.size)
    change = np.zeros(chi.size)
    u = np.zeros((chi.size, springs))
    active = np.ones(chi.size, dtype=bool)
    for _ in range(steps):
        v = np.where(active, v - 1.25 * np.maximum(h, 0.0) ** 1.5 * dt, v)
        h = np.where(active, h + v * dt, h)
        active &= h > 0.0
        u += np.where(active, (psi1 + change) * dt, 0.0)[:, None]
        cap = np.maximum(h[:, None] - xi2[None, :], 0.0)
        np.clip(u, -cap, cap, out=u)
        change = np.where(active, change - GAIN * chi * u.sum(axis=1) / springs * dt, change)
        if not active.any():
            break
    return change
