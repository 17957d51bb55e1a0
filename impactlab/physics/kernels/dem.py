"""Compiled one-spring DEM time loop (:mod:`impactlab.physics.dem`'s kernel)."""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


def _dem_cases(chi, psi1, tau, cap, stiffness, mean_stiffness, shrink, store_force, damping, gain, record, force,
               stuck, root, couple_slip, couple_roll, rotation, rolling0, arm, mode_force, mode_frequency2,
               mode_damping):
    """One-spring DEM time loop per case; see dem.solve_scaled and dem._numpy_cases (the reference).

    With ``arm[case]`` > 0 a rolling-resistance couple on the line (dem.solve_scaled, ``rolling``): per step the
    couple that stops the rolling by the step's end, put on its limit arm sqrt(h) f_n, the arithmetic of
    :func:`impactlab.physics.kernels.contact3d._contact3d_cases` on one line. Returns (slip change, work of the
    spring's force on the slip, angular impulse of the couple, its work on the rolling).

    The core's modes on the line (``mode_force`` of shape (n, 0): none; dem.solve_scaled, ``core``): each adds its
    rate Z to the slip, Y' = Z, Z' = -mode_force f - mode_frequency2 Y - mode_damping Z, by the same velocity
    Verlet; the energy they took (held at the end, (Z^2 + Omega^2 Y^2) / (2 mode_force), and damped) is added to
    the work, so that the work is what the rigid bodies' slip lost. Not combined with a couple.
    """
    cases = chi.size
    nodes = tau.size
    modes = mode_force.shape[1]
    zm = np.zeros(modes)
    ym = np.zeros(modes)
    am = np.zeros(modes)
    hm = np.zeros(modes)
    change_out = np.zeros(cases)
    work_out = np.zeros(cases)
    moment_out = np.zeros(cases)
    rolling_work_out = np.zeros(cases)
    for case in range(cases):
        spring = 0.0
        change = 0.0
        acceleration = 0.0
        work = 0.0
        previous = 0.0
        p1 = psi1[case]
        rho = arm[case]
        slip_gain = couple_slip[case]
        roll_gain = couple_roll[case]
        r = rotation[case]
        w = rolling0[case]
        aw = 0.0
        couple = 0.0
        previous_couple = 0.0
        moment = 0.0
        rolling_work = 0.0
        core_taken = 0.0
        damped_core = False
        for j in range(modes):
            hm[j] = 0.0
            ym[j] = 0.0
            am[j] = 0.0
            damped_core = damped_core or mode_damping[case, j] > 0.0
        for k in range(1, nodes):
            dt = tau[k] - tau[k - 1]
            half = change + 0.5 * dt * acceleration
            velocity = p1 + half
            for j in range(modes):  # the core's modes (leapfrog): half-step rates, new angles, rates in the slip
                hm[j] += (0.5 if k == 1 else 1.0) * dt * am[j]
                ym[j] += dt * hm[j]
                velocity += hm[j]
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
            for j in range(modes):
                am[j] = -mode_force[case, j] * total - mode_frequency2[case, j] * ym[j] - mode_damping[case, j] * hm[j]
                if damped_core and mode_force[case, j] > 0.0:  # (gain 0: a padding mode, inert)
                    core_taken += dt * mode_damping[case, j] * hm[j] * hm[j] / mode_force[case, j]
            if rho > 0.0:
                # rolling rate at the half step; the couple that stops it by the step's end, put on its limit
                middle = w + 0.5 * dt * aw
                drive = -roll_gain * total
                couple = -(middle / (0.625 * dt) + drive) / r
                limit = rho * root[k] * cap[k]
                if abs(couple) > limit:
                    couple = limit if couple > 0.0 else -limit
                acceleration += slip_gain * couple
                aw = 1.25 * (drive + r * couple)
                w = middle + 0.5 * dt * aw
                rolling_work += dt * 0.5 * (previous_couple + couple) * middle
                moment += 0.5 * dt * (previous_couple + couple)
                previous_couple = couple
            change = half + 0.5 * dt * acceleration
            if record:
                force[case, k] = total
                stuck[case, k] = 0.0 if over else 1.0
        for j in range(modes):  # the rates at the last step's end
            zm[j] = hm[j] + 0.5 * (tau[nodes - 1] - tau[nodes - 2]) * am[j]
            if mode_force[case, j] > 0.0:
                core_taken += (zm[j] * zm[j] + mode_frequency2[case, j] * ym[j] * ym[j]) / (2.0 * mode_force[case, j])
        change_out[case] = change
        work_out[case] = work + core_taken if modes > 0 else work
        moment_out[case] = moment
        rolling_work_out[case] = rolling_work
    return change_out, work_out, moment_out, rolling_work_out


dem_cases = _compiled(_dem_cases)
