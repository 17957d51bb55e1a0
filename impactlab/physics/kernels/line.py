"""The compliant contact of :mod:`.contact3d` on one line: its kernel's arithmetic for a case that stays on a line.

A centred strike on a fixed face or a point-mass head has a mobility diagonal in the contact frame (a = W_tt/W_nn
diagonal, b = W_tn/W_nn = 0): the slip stays along s, the friction force along s, the springs and the core's modes
move along s only, and a rolling couple (when it stays planar: no normal or in-plane coupling, rolling about the
lateral axis alone) turns about l only. :func:`_contact3d_cases` then carries zeros in half of its 2-vectors. This
kernel runs the same steps on the non-zero halves (scalars): the same normal problem (Hunt-Crossley load, the face's
mode), the same tangential laws (MDR springs on their caps, one DEM spring), the same core modes, couple, impulses,
work and histories, in the same order, so that its results equal the 3-D kernel's to round-off (tests/test_kernels.py
checks 1e-12). It exists because the cases on the line that leave the scaled 1-D solvers (a flexing face, a core with
a rolling couple, a lossy cover, a per-case normal law) spent 2-3x more per step in the 2-vector arithmetic.

The caller (:func:`impactlab.physics.compliant3d.solve_once`) gives it the cases that are exactly on the line; the
arguments are :func:`impactlab.physics.kernels.contact3d._contact3d_cases`'s, plus ``rows``, the cases to solve.
"""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


def _line_cases(ratio_tt, coupling, kappa, friction, psi, damping, dtau, max_steps, law, stiffness_factor,
                store_force, rescale, tangential_damping, relaxation, xi2, weight, record, history_normal,
                history_tangential, history_stick, out, couple_n, couple_t, couple_rr, rolling0, arm,
                mode_gain, mode_frequency, mode_damping, mode_arm, face_gain, face_frequency, face_damping, rows):
    """:func:`impactlab.physics.kernels.contact3d._contact3d_cases` for the cases ``rows``, each on one line.

    On the line: a_sl = a_ls = 0, b = 0, no lateral slip; with a couple (arm > 0), B_n = 0, B_ss = B_ll = 0,
    D_sl = D_ls = 0 and no rolling about s before impact (the caller checks). Only the components along s of the
    slip, the friction force, the springs and the modes, and the couple and rolling rate about l, are carried.
    """
    springs = xi2.size
    u = np.zeros(springs)
    modes = mode_gain.shape[1]
    ym = np.zeros(modes)
    am = np.zeros(modes)
    hm = np.zeros(modes)
    coef = np.zeros((modes, 5))  # per mode: (5/4) kappa g, Omega^2, d, (5/4)(kappa/mu) g a_max/R, its damping's weight
    for case in rows:
        mu = friction[case]
        k = kappa[case]
        c = damping[case]
        lag = relaxation[case]
        a00 = ratio_tt[case, 0, 0]
        p0 = psi[case, 0]
        dt = dtau[case]
        for i in range(springs):
            u[i] = 0.0
        spring0 = 0.0
        h = 0.0
        hh = 1.0
        s0 = p0
        ah = 0.0
        as0 = 0.0
        imp_n = 0.0
        imp_0 = 0.0
        cum_n = 0.0
        cum_0 = 0.0
        prev_n = 0.0
        prev_0 = 0.0
        work = 0.0
        tau = 0.0
        chi_along = 0.5 * k * a00
        steps = 0
        rho = arm[case] if mu > 0.0 else 0.0
        ct01 = couple_t[case, 0, 1]
        r11 = couple_rr[case, 1, 1]
        w1 = rolling0[case, 1]
        aw1 = 0.0
        c1 = 0.0
        prev_c1 = 0.0
        mom1 = 0.0
        live = modes > 0 and mu > 0.0
        core_scale = 0.4 * mu * mu / (k * k) if live else 0.0
        q_arm = mu * mode_arm[case] / k if live else 0.0
        core_taken = 0.0
        mode_rr = 0.0
        for j in range(modes):
            hm[j] = 0.0
            ym[j] = 0.0
            am[j] = 0.0
            mode_rr += mode_gain[case, j] * mode_arm[case] * mode_arm[case]
            if live:
                coef[j, 0] = 1.25 * k * mode_gain[case, j]
                coef[j, 1] = mode_frequency[case, j] * mode_frequency[case, j]
                coef[j, 2] = mode_damping[case, j]
                coef[j, 3] = (1.25 * k / mu) * mode_gain[case, j] * mode_arm[case]
                coef[j, 4] = 2.0 * core_scale * mode_damping[case, j] / mode_gain[case, j] if mode_gain[case, j] > 0.0 \
                    else 0.0
        damped_core = live and mode_damping[case].max() > 0.0
        gf = face_gain[case]
        flex = gf > 0.0
        face_push = 1.25 * gf
        face_w2 = face_frequency[case] * face_frequency[case]
        face_d = face_damping[case]
        face_loss = 0.8 * face_d / gf if flex else 0.0
        fy = 0.0
        fz = 0.0
        fa = 0.0
        rigid = 0.0
        face_taken = 0.0
        last_touch = 0.0
        root_old = 0.0
        for step in range(1, max_steps + 1):
            h_half = hh + 0.5 * dt * ah
            vr0 = s0 + 0.5 * dt * as0
            v0 = vr0
            wc1 = 0.0
            if live:
                for j in range(modes):
                    hm[j] += (0.5 if step == 1 else 1.0) * dt * am[j]
                    ym[j] += dt * hm[j]
                    v0 += hm[j]
                if rho > 0.0:
                    for j in range(modes):
                        wc1 -= hm[j]
                    wc1 *= q_arm
            h_old = h
            if flex:
                fz += (0.5 if step == 1 else 1.0) * dt * fa
                fy += dt * fz
                rigid += dt * h_half
                h = rigid - fy
            else:
                h = h + dt * h_half
            if flex:
                load = 1.0 + c * (h_half + 0.5 * dt * ah - fz - 0.5 * dt * fa) if c > 0.0 else 1.0
            else:
                load = 1.0 + c * (h_half + 0.5 * dt * ah) if c > 0.0 else 1.0
            if load < 0.0:
                load = 0.0
            hp = h if h > 0.0 else 0.0
            root = np.sqrt(hp)
            normal = hp * root * load
            d0 = dt * v0
            ratio = dt / lag if lag > 0.0 else 1e300
            f0 = 0.0
            stuck_to = 0.0
            if law == 0:
                reach_h = h if h > h_old else h_old
                both_h = h if h < h_old else h_old
                first_slip = springs
                i = 0
                while i < springs and xi2[i] < both_h:
                    cap = (hp - xi2[i]) * load
                    x0 = u[i] + d0 + lag * v0
                    if abs(x0) > cap:  # on the cap (the 3-D kernel's radial return on one line)
                        x0 = cap if x0 > 0.0 else -cap
                        u[i] = (u[i] + ratio * x0) / (1.0 + ratio)
                        if record and first_slip == springs:
                            first_slip = i
                    else:
                        u[i] = x0 - lag * v0
                    f0 += x0
                    i += 1
                while i < springs and xi2[i] < reach_h:
                    cap = (hp - xi2[i]) * load
                    if cap <= 0.0:
                        u[i] = 0.0
                        i += 1
                        continue
                    inside = (h - xi2[i]) / (h - h_old) if xi2[i] > h_old else 1.0
                    x0 = u[i] + inside * d0 + lag * v0
                    if abs(x0) > cap:
                        x0 = cap if x0 > 0.0 else -cap
                        u[i] = (u[i] + ratio * x0) / (1.0 + ratio)
                        if record and first_slip == springs:
                            first_slip = i
                    else:
                        u[i] = x0 - lag * v0
                    f0 += x0
                    i += 1
                f0 *= 1.5 * weight
                radius = first_slip / springs
                stuck_to = radius if radius < root else root
            else:
                if law == 1:
                    stiff = 1.5 * stiffness_factor
                    stiff_mean = stiff
                else:
                    stiff = 1.5 * stiffness_factor * root
                    stiff_mean = 0.5 * (stiff + 1.5 * stiffness_factor * root_old)
                shrink = 1.0
                if rescale and h < h_old and h_old > 0.0:
                    shrink = np.sqrt(np.sqrt(hp / h_old))
                spring0 *= shrink
                if store_force:
                    spring0 += stiff_mean * d0
                else:
                    spring0 += d0
                spring0 *= shrink
                e0 = spring0 if store_force else stiff * spring0
                visc = stiff * lag
                if tangential_damping > 0.0 and chi_along > 0.0:
                    visc += 2.0 * tangential_damping * np.sqrt(stiff / (2.5 * chi_along))
                f0 = e0 + visc * v0
                if abs(f0) > normal:
                    f0 = normal if f0 > 0.0 else -normal
                    r0 = f0 - visc * v0
                    if store_force:
                        spring0 = r0
                    else:
                        spring0 = r0 / stiff if stiff > 0.0 else 0.0
                else:
                    stuck_to = root
            root_old = root
            if mu == 0.0:
                f0 = 0.0
            c1 = 0.0
            g1 = 0.0
            if rho > 0.0:
                wm1 = w1 + 0.5 * dt * aw1
                g1 = -mu * ct01 * f0
                if live:
                    q1 = -((wm1 + wc1) / (0.625 * dt) + g1)
                    for j in range(modes):
                        free0 = -coef[j, 0] * f0 - coef[j, 1] * ym[j] - coef[j, 2] * hm[j]
                        q1 += 0.8 * q_arm * free0
                    c1 = q1 / (r11 + mode_rr)
                else:
                    q1 = -(wm1 / (0.625 * dt) + g1)
                    c1 = q1 / r11
                limit = rho * root * normal
                if abs(c1) > limit:
                    c1 = limit if c1 > 0.0 else -limit
            ah = -1.25 * normal
            if flex:
                fa = face_push * normal - face_w2 * fy - face_d * fz
                if face_d > 0.0:
                    face_taken += dt * face_loss * fz * fz
                if normal > 0.0:
                    last_touch = tau + dt
            if mu > 0.0:
                as0 = -1.25 * k * a00 * f0 + (1.25 * k / mu) * ct01 * c1
            if live:
                for j in range(modes):
                    am[j] = -coef[j, 0] * f0 - coef[j, 3] * c1 - coef[j, 1] * ym[j] - coef[j, 2] * hm[j]
                if damped_core:
                    for j in range(modes):
                        core_taken += dt * coef[j, 4] * hm[j] * hm[j]
            if rho > 0.0:
                aw1 = 1.25 * (g1 + r11 * c1)
                w1 = wm1 + 0.5 * dt * aw1
                if live:
                    work += dt * 0.5 * (prev_c1 + c1) * (wm1 + wc1)
                else:
                    work += dt * 0.5 * (prev_c1 + c1) * wm1
                mom1 += 0.5 * dt * (prev_c1 + c1)
                prev_c1 = c1
            h_new = h_half + 0.5 * dt * ah
            n0 = vr0 + 0.5 * dt * as0
            work += dt * (-0.5 * (prev_n + normal) * h_half - (mu * mu / k) * 0.5 * (prev_0 + f0) * v0)
            old_n = imp_n
            old_0 = imp_0
            imp_n += 0.5 * dt * (prev_n + normal)
            imp_0 += 0.5 * dt * (prev_0 + f0)
            cum_n += 0.5 * dt * (old_n + imp_n)
            cum_0 += 0.5 * dt * (old_0 + imp_0)
            prev_n = normal
            prev_0 = f0
            hh = h_new
            s0 = n0
            tau += dt
            steps = step
            if record:
                history_normal[case, step] = normal
                history_tangential[case, step] = f0
                history_stick[case, step] = stuck_to
            if flex and (h > 0.0 or hh >= 0.0 or rigid + np.sqrt(fy * fy + fz * fz / face_w2) > 0.0):
                continue
            if h <= 0.0 and hh < 0.0:
                break
            if load == 0.0 and hh < 0.0:
                break
        out[case, 0] = imp_n
        out[case, 1] = imp_0
        out[case, 2] = 0.0
        out[case, 3] = last_touch if flex else tau
        out[case, 4] = cum_n
        out[case, 5] = cum_0
        out[case, 6] = 0.0
        out[case, 8] = steps
        out[case, 9] = 0.0
        out[case, 10] = mom1
        for j in range(modes if live else 0):
            if mode_gain[case, j] > 0.0:
                zm = hm[j] + 0.5 * dt * am[j]
                core_taken += core_scale * (zm * zm + mode_frequency[case, j] ** 2 * ym[j] * ym[j]) / mode_gain[case, j]
        out[case, 7] = work - core_taken if live else work
        out[case, 11] = core_taken
        if flex:
            fz += 0.5 * dt * fa
            out[case, 12] = face_taken + 0.4 * (fz * fz + face_w2 * fy * fy) / gf


line_cases = _compiled(_line_cases, fastmath={"reassoc", "nsz", "arcp", "contract"})
