"""Compiled one-spring DEM time loop (:mod:`impactlab.physics.dem`'s kernel)."""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


def _dem_cases(chi, psi1, tau, cap, stiffness, mean_stiffness, shrink, store_force, damping, gain, record, force,
               stuck):
    """One-spring DEM time loop per case; see dem.solve_scaled and dem._numpy_cases (the reference)."""
    cases = chi.size
    nodes = tau.size
    change_out = np.zeros(cases)
    work_out = np.zeros(cases)
    for case in range(cases):
        spring = 0.0
        change = 0.0
        acceleration = 0.0
        work = 0.0
        previous = 0.0
        p1 = psi1[case]
        for k in range(1, nodes):
            dt = tau[k] - tau[k - 1]
            half = change + 0.5 * dt * acceleration
            velocity = p1 + half
            stiff = stiffness[k]
            spring *= shrink[k]
            spring += (mean_stiffness[k] if store_force else 1.0) * dt * velocity
            spring *= shrink[k]
            elastic = spring if store_force else stiff * spring
            viscous = 2.0 * damping * np.sqrt(stiff / (gain * chi[case])) * velocity if damping > 0.0 else 0.0
            total = elastic + viscous
            over = abs(total) > cap[k]
            if over:
                total = cap[k] if total > 0.0 else -cap[k]
                if store_force:
                    spring = total - viscous
                else:
                    spring = (total - viscous) / stiff if stiff > 0.0 else 0.0
            work += 0.5 * (previous + total) * dt * velocity
            previous = total
            acceleration = -gain * chi[case] * total
            change = half + 0.5 * dt * acceleration
            if record:
                force[case, k] = total
                stuck[case, k] = 0.0 if over else 1.0
        change_out[case] = change
        work_out[case] = work
    return change_out, work_out


dem_cases = _compiled(_dem_cases)
