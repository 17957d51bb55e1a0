"""Compiled compliant 3-D contact, normal and tangential coupled (:mod:`impactlab.physics.compliant3d`'s kernel)."""

from __future__ import annotations

import numpy as np

from ._numba import HAVE_NUMBA, numba
from ._numba import compiled as _compiled


def _mdr_spring(u, i, move0, move1, cap, lag, v0, v1, ratio):
    """One MDR spring's update over a step: the trial extension, the radial return to the Coulomb circle.

    ``u[i]`` (the spring's stored extension, a 2-vector) is moved by the step's slip ``move`` (the part of it
    after the spring entered the contact) and its dashpot's ``lag * v``; beyond the circle of radius ``cap``
    the pair is brought back to it and the spring relaxes towards it (backward Euler of k u + c u' = cap, with
    ``ratio`` = dt / relaxation); inside, the spring takes the whole extension. Returns the spring-dashpot's
    force components (x0, x1) and whether it slips. Written once for both loops of :func:`_contact3d_cases`;
    compiled inline into it, so the kernel keeps its speed and its fastmath flags.
    """
    x0 = u[i, 0] + move0 + lag * v0
    x1 = u[i, 1] + move1 + lag * v1
    squared = x0 * x0 + x1 * x1
    if squared > cap * cap:  # back to the Coulomb circle (the square root only when needed)
        shrink_to = cap / np.sqrt(squared)
        x0 *= shrink_to
        x1 *= shrink_to
        # sliding: the spring-dashpot carries the cap and relaxes towards it; without a dashpot it sits on the
        # circle
        u[i, 0] = (u[i, 0] + ratio * x0) / (1.0 + ratio)
        u[i, 1] = (u[i, 1] + ratio * x1) / (1.0 + ratio)
        return x0, x1, True
    u[i, 0] = x0 - lag * v0
    u[i, 1] = x1 - lag * v1
    return x0, x1, False


if HAVE_NUMBA:  # inlined into the kernel's IR (the kernel looks its globals up when it compiles)
    _mdr_spring = numba.njit(inline="always")(_mdr_spring)


def _contact3d_cases(ratio_tt, coupling, kappa, friction, psi, damping, dtau, max_steps, law, stiffness_factor,
                     store_force, rescale, tangential_damping, relaxation, xi2, weight, record, history_normal,
                     history_tangential, history_stick, out, couple_n, couple_t, couple_rr, rolling0, arm,
                     mode_gain, mode_frequency, mode_damping, mode_arm, face_gain, face_frequency, face_damping,
                     rows):
    """Compliant 3-D contact of the cases ``rows``, in MBF's scaled variables, normal and tangential coupled.

    Scaled state: approach h and its rate H = h' (1 at first touch), slip S (2-vector, units mu V_z/kappa),
    and the tangential springs: MDR springs u_i (2-vectors on the Coulomb circle |u_i| <= (h - xi_i^2) L)
    for law 0, one DEM spring for law 1 (linear) and 2 (Mindlin). With f = F_t/(mu F_max) along the slip
    (f = 1.5 sum u_i w for MDR) and the mobility ratios a = W_tt/W_nn, b = W_tn/W_nn:

        h'' = -(5/4) (h^1.5 L - mu b.f),      S' = -(5/4) kappa a f + (5/4) (kappa/mu) b h^1.5 L,

    L = max(1 + c H, 0) the Hunt-Crossley load factor (c = 0: elastic). ``relaxation`` (per case, scaled time)
    puts a dashpot beside every tangential spring (Kelvin-Voigt: force = k (u + relaxation u')) in series with the
    Coulomb slider: stuck, the pair extends with the slip; sliding, it carries the cap and its spring relaxes
    towards it (for the MDR springs; the DEM springs keep their codes' reset to the cap less the dashpot's part).
    Velocity Verlet on a uniform grid;
    the springs take the step's slip and return to their circle (a radial return map). Stops when the bodies
    separate. Impulses are the trapezoid sums of the forces, the ones velocity Verlet applies, so momentum is
    kept exactly; with mu = 0 the tangential problem is skipped (no force, no scale). ``out`` columns:
    integral f_n, integral f_0, integral f_1 (d tau), tau_end, the time integrals of those running impulses,
    the work of the contact forces on the relative motion [F_max delta_max], steps, and the couple's angular
    impulse along (s, l) [integral c d tau].

    Rolling resistance (``arm`` > 0, :mod:`impactlab.physics.ball_laws`): a couple C on the ball, scaled
    c = C / (F_max a_max), of size at most arm h^0.5 f_n (d = arm a_max h^0.5), opposing the scaled relative
    rolling rate w = Omega a_max / V_z (start ``rolling0``); with couple_n = m* a_max B_n, couple_t = m* a_max B_t
    and couple_rr = m* a_max^2 D (:func:`impactlab.physics.contact.couple_mobility`):

        h'' += -(5/4) couple_n.c,   S' += (5/4)(kappa/mu) couple_t c,
        w' = (5/4) (couple_n f_n - mu couple_t^T f + couple_rr c).

    Each step the couple that stops the rolling by the step's end is taken if it lies within its limit, else
    that couple put on the limit (the rolling analogue of Coulomb's law); the couple acts only with friction.

    The core turning behind the shell (:mod:`impactlab.physics.core_torsion`; ``mode_gain`` of shape (n, 0): none):
    mode k of the core adds Z_k (2-vector, the slip's units) to the slip and q (Z_k1, -Z_k0) to the rolling rate
    (q = mu mode_arm / kappa, mode_arm = a_max / R), with g_k = m* R^2 / I_k, Omega_k = omega_k delta_max / V_z and
    d_k = eta Omega_k:

        Y_k' = Z_k,   Z_k' = -(5/4) kappa g_k f + (5/4)(kappa/mu) g_k mode_arm (-c_1, c_0) - Omega_k^2 Y_k - d_k Z_k,

    integrated by the same velocity Verlet. The modes' own energy (2/5)(mu/kappa)^2 (Z^2 + Omega^2 Y^2) / g_k at
    the end and what their damping took are taken out of ``work`` (the rigid bodies' balance) and given in
    ``out[:, 11]``; the couple that stops the rolling counts the modes' part of it.

    The face flexing behind the contact (:mod:`impactlab.physics.face_flex`; ``face_gain`` 0: a rigid face): one
    modal oscillator of the face along the normal, displacement y (into the head, units delta_max) with
    g = m*/m_f, Omega = omega_f delta_max / V_z and d = eta Omega; the rigid bodies' approach r keeps the equation
    of h above, and the ball's compression is h = r - y:

        y'' = (5/4) g h^1.5 L - Omega^2 y - d y'

    (leapfrog, as the core's modes; the Hunt-Crossley rate is the compression's, r' - y'). ``work`` stays the
    forces' work on the rigid bodies' approach; what the face holds at the end and what its loss took,
    (2/5)(y'^2 + Omega^2 y^2) / g and (2/5) d / g int y'^2, is ``out[:, 12]``. The contact ends when the bodies
    separate and the face's swing (amplitude sqrt(y^2 + (y'/Omega)^2)) can no longer reach the ball; the contact
    time is the last instant with a force.
    """
    springs = xi2.size
    u = np.zeros((springs, 2))
    modes = mode_gain.shape[1]
    zm = np.zeros((modes, 2))
    ym = np.zeros((modes, 2))
    am = np.zeros((modes, 2))
    hm = np.zeros((modes, 2))
    coef = np.zeros((modes, 5))  # per mode: (5/4) kappa g, Omega^2, d, (5/4)(kappa/mu) g a_max/R, its damping's weight
    for case in rows:
        mu = friction[case]
        k = kappa[case]
        c = damping[case]
        lag = relaxation[case]
        a00 = ratio_tt[case, 0, 0]
        a01 = ratio_tt[case, 0, 1]
        a10 = ratio_tt[case, 1, 0]
        a11 = ratio_tt[case, 1, 1]
        b0 = coupling[case, 0]
        b1 = coupling[case, 1]
        p0 = psi[case, 0]
        p1 = psi[case, 1]
        dt = dtau[case]
        for i in range(springs):
            u[i, 0] = 0.0
            u[i, 1] = 0.0
        spring0 = 0.0
        spring1 = 0.0
        h = 0.0
        hh = 1.0
        s0 = p0
        s1 = p1
        ah = 0.0
        as0 = 0.0
        as1 = 0.0
        imp_n = 0.0
        imp_0 = 0.0
        imp_1 = 0.0
        cum_n = 0.0
        cum_0 = 0.0
        cum_1 = 0.0
        prev_n = 0.0
        prev_0 = 0.0
        prev_1 = 0.0
        work = 0.0
        tau = 0.0
        chi_along = 0.5 * k * a00
        steps = 0
        rho = arm[case] if mu > 0.0 else 0.0
        cn0 = couple_n[case, 0]
        cn1 = couple_n[case, 1]
        ct00 = couple_t[case, 0, 0]
        ct01 = couple_t[case, 0, 1]
        ct10 = couple_t[case, 1, 0]
        ct11 = couple_t[case, 1, 1]
        r00 = couple_rr[case, 0, 0]
        r01 = couple_rr[case, 0, 1]
        r10 = couple_rr[case, 1, 0]
        r11 = couple_rr[case, 1, 1]
        det = r00 * r11 - r01 * r10
        w0 = rolling0[case, 0]
        w1 = rolling0[case, 1]
        aw0 = 0.0
        aw1 = 0.0
        c0 = 0.0
        c1 = 0.0
        prev_c0 = 0.0
        prev_c1 = 0.0
        mom0 = 0.0
        mom1 = 0.0
        live = modes > 0 and mu > 0.0
        core_scale = 0.4 * mu * mu / (k * k) if live else 0.0
        q_arm = mu * mode_arm[case] / k if live else 0.0
        core_taken = 0.0
        mode_rr = 0.0
        for j in range(modes):
            zm[j, 0] = 0.0
            zm[j, 1] = 0.0
            hm[j, 0] = 0.0
            hm[j, 1] = 0.0
            ym[j, 0] = 0.0
            ym[j, 1] = 0.0
            am[j, 0] = 0.0
            am[j, 1] = 0.0
            mode_rr += mode_gain[case, j] * mode_arm[case] * mode_arm[case]
            if live:
                coef[j, 0] = 1.25 * k * mode_gain[case, j]
                coef[j, 1] = mode_frequency[case, j] * mode_frequency[case, j]
                coef[j, 2] = mode_damping[case, j]
                coef[j, 3] = (1.25 * k / mu) * mode_gain[case, j] * mode_arm[case]
                # (gain 0: a mode that pads a case with fewer modes than its batch; inert, it takes nothing)
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
        for step in range(1, max_steps + 1):
            h_half = hh + 0.5 * dt * ah
            vr0 = s0 + 0.5 * dt * as0
            vr1 = s1 + 0.5 * dt * as1
            v0 = vr0
            v1 = vr1
            # the core's modes: half-step rates, new angles; their rates join the slip and the rolling rate
            wc0 = 0.0
            wc1 = 0.0
            if live:  # (leapfrog: the half-step rate moves by a whole step of the last acceleration)
                for j in range(modes):
                    hm[j, 0] += (0.5 if step == 1 else 1.0) * dt * am[j, 0]
                    hm[j, 1] += (0.5 if step == 1 else 1.0) * dt * am[j, 1]
                    ym[j, 0] += dt * hm[j, 0]
                    ym[j, 1] += dt * hm[j, 1]
                    v0 += hm[j, 0]
                    v1 += hm[j, 1]
                if rho > 0.0:
                    for j in range(modes):
                        wc0 += hm[j, 1]
                        wc1 -= hm[j, 0]
                    wc0 *= q_arm
                    wc1 *= q_arm
            h_old = h
            if flex:  # the face's mode (leapfrog); the ball's compression is the bodies' approach less the face's
                fz += (0.5 if step == 1 else 1.0) * dt * fa
                fy += dt * fz
                rigid += dt * h_half
                h = rigid - fy
            else:
                h = h + dt * h_half
            # the damped law's force at the step's end needs the rate there: predicted with the last acceleration
            if flex:
                load = 1.0 + c * (h_half + 0.5 * dt * ah - fz - 0.5 * dt * fa) if c > 0.0 else 1.0
            else:
                load = 1.0 + c * (h_half + 0.5 * dt * ah) if c > 0.0 else 1.0
            if load < 0.0:
                load = 0.0
            hp = h if h > 0.0 else 0.0
            root = np.sqrt(hp)  # a / a_max; h^1.5 as h sqrt(h): pow is a library call, sqrt an instruction
            normal = hp * root * load
            d0 = dt * v0
            d1 = dt * v1
            ratio = dt / lag if lag > 0.0 else 1e300  # step over the dashpot's relaxation time
            f0 = 0.0
            f1 = 0.0
            stuck_to = 0.0
            if law == 0:
                reach_h = h if h > h_old else h_old
                both_h = h if h < h_old else h_old
                first_slip = springs
                i = 0
                # springs inside the contact for the whole step: the common case, kept free of the edge logic
                while i < springs and xi2[i] < both_h:
                    cap = (hp - xi2[i]) * load
                    x0, x1, slips = _mdr_spring(u, i, d0, d1, cap, lag, v0, v1, ratio)
                    if slips and record and first_slip == springs:
                        first_slip = i
                    f0 += x0
                    f1 += x1
                    i += 1
                # springs entering or leaving during the step
                while i < springs and xi2[i] < reach_h:
                    cap = (hp - xi2[i]) * load
                    if cap <= 0.0:
                        u[i, 0] = 0.0
                        u[i, 1] = 0.0
                        i += 1
                        continue
                    # a spring that enters during the step slips with the contact only for the part after entry
                    inside = (h - xi2[i]) / (h - h_old) if xi2[i] > h_old else 1.0
                    x0, x1, slips = _mdr_spring(u, i, inside * d0, inside * d1, cap, lag, v0, v1, ratio)
                    if slips and record and first_slip == springs:
                        first_slip = i
                    f0 += x0
                    f1 += x1
                    i += 1
                f0 *= 1.5 * weight
                f1 *= 1.5 * weight
                radius = first_slip / springs
                stuck_to = radius if radius < root else root
            else:
                if law == 1:
                    stiff = 1.5 * stiffness_factor
                    stiff_mean = stiff
                else:
                    stiff = 1.5 * stiffness_factor * root
                    stiff_mean = 0.5 * (stiff + 1.5 * stiffness_factor * np.sqrt(h_old if h_old > 0.0 else 0.0))
                shrink = 1.0
                if rescale and h < h_old and h_old > 0.0:
                    shrink = np.sqrt(np.sqrt(hp / h_old))
                spring0 *= shrink
                spring1 *= shrink
                if store_force:
                    spring0 += stiff_mean * d0
                    spring1 += stiff_mean * d1
                else:
                    spring0 += d0
                    spring1 += d1
                spring0 *= shrink
                spring1 *= shrink
                e0 = spring0 if store_force else stiff * spring0
                e1 = spring1 if store_force else stiff * spring1
                visc = stiff * lag
                if tangential_damping > 0.0 and chi_along > 0.0:
                    visc += 2.0 * tangential_damping * np.sqrt(stiff / (2.5 * chi_along))
                f0 = e0 + visc * v0
                f1 = e1 + visc * v1
                size = np.sqrt(f0 * f0 + f1 * f1)
                if size > normal:
                    scale = normal / size if size > 0.0 else 0.0
                    f0 *= scale
                    f1 *= scale
                    r0 = f0 - visc * v0
                    r1 = f1 - visc * v1
                    if store_force:
                        spring0 = r0
                        spring1 = r1
                    else:
                        spring0 = r0 / stiff if stiff > 0.0 else 0.0
                        spring1 = r1 / stiff if stiff > 0.0 else 0.0
                else:
                    stuck_to = root
            if mu == 0.0:
                f0 = 0.0
                f1 = 0.0
            c0 = 0.0
            c1 = 0.0
            g0 = 0.0
            g1 = 0.0
            if rho > 0.0:
                # rolling rate at the half step; the couple that stops it by the step's end, put on its limit
                wm0 = w0 + 0.5 * dt * aw0
                wm1 = w1 + 0.5 * dt * aw1
                g0 = cn0 * normal - mu * (ct00 * f0 + ct10 * f1)
                g1 = cn1 * normal - mu * (ct01 * f0 + ct11 * f1)
                if live:  # the modes' rolling rate by the step's end without the couple, and their give to it
                    q0 = -((wm0 + wc0) / (0.625 * dt) + g0)
                    q1 = -((wm1 + wc1) / (0.625 * dt) + g1)
                    for j in range(modes):
                        free0 = -coef[j, 0] * f0 - coef[j, 1] * ym[j, 0] - coef[j, 2] * hm[j, 0]
                        free1 = -coef[j, 0] * f1 - coef[j, 1] * ym[j, 1] - coef[j, 2] * hm[j, 1]
                        q0 -= 0.8 * q_arm * free1
                        q1 += 0.8 * q_arm * free0
                    e00 = r00 + mode_rr
                    e11 = r11 + mode_rr
                    det_all = e00 * e11 - r01 * r10
                    c0 = (e11 * q0 - r01 * q1) / det_all
                    c1 = (-r10 * q0 + e00 * q1) / det_all
                else:
                    q0 = -(wm0 / (0.625 * dt) + g0)
                    q1 = -(wm1 / (0.625 * dt) + g1)
                    c0 = (r11 * q0 - r01 * q1) / det
                    c1 = (-r10 * q0 + r00 * q1) / det
                limit = rho * root * normal
                size = np.sqrt(c0 * c0 + c1 * c1)
                if size > limit:
                    c0 *= limit / size
                    c1 *= limit / size
            ah = -1.25 * (normal - mu * (b0 * f0 + b1 * f1) + cn0 * c0 + cn1 * c1)
            if flex:
                fa = face_push * normal - face_w2 * fy - face_d * fz
                if face_d > 0.0:
                    face_taken += dt * face_loss * fz * fz
                if normal > 0.0:
                    last_touch = tau + dt
            if mu > 0.0:
                as0 = -1.25 * k * (a00 * f0 + a01 * f1) + (1.25 * k / mu) * (b0 * normal + ct00 * c0 + ct01 * c1)
                as1 = -1.25 * k * (a10 * f0 + a11 * f1) + (1.25 * k / mu) * (b1 * normal + ct10 * c0 + ct11 * c1)
            if live:
                for j in range(modes):
                    am[j, 0] = -coef[j, 0] * f0 - coef[j, 3] * c1 - coef[j, 1] * ym[j, 0] - coef[j, 2] * hm[j, 0]
                    am[j, 1] = -coef[j, 0] * f1 + coef[j, 3] * c0 - coef[j, 1] * ym[j, 1] - coef[j, 2] * hm[j, 1]
                if damped_core:
                    for j in range(modes):
                        core_taken += dt * coef[j, 4] * (hm[j, 0] * hm[j, 0] + hm[j, 1] * hm[j, 1])
            if rho > 0.0:
                aw0 = 1.25 * (g0 + r00 * c0 + r01 * c1)
                aw1 = 1.25 * (g1 + r10 * c0 + r11 * c1)
                w0 = wm0 + 0.5 * dt * aw0
                w1 = wm1 + 0.5 * dt * aw1
                # the couple's work on the half-step rolling rate, as the forces' work below [F_max delta_max]
                if live:  # the rolling rate includes the core's modes
                    work += dt * 0.5 * ((prev_c0 + c0) * (wm0 + wc0) + (prev_c1 + c1) * (wm1 + wc1))
                else:
                    work += dt * 0.5 * ((prev_c0 + c0) * wm0 + (prev_c1 + c1) * wm1)
                mom0 += 0.5 * dt * (prev_c0 + c0)
                mom1 += 0.5 * dt * (prev_c1 + c1)
                prev_c0 = c0
                prev_c1 = c1
            h_new = h_half + 0.5 * dt * ah
            n0 = vr0 + 0.5 * dt * as0
            n1 = vr1 + 0.5 * dt * as1
            work += dt * (-0.5 * (prev_n + normal) * h_half
                          - (mu * mu / k) * 0.5 * ((prev_0 + f0) * v0 + (prev_1 + f1) * v1))
            old_n = imp_n
            old_0 = imp_0
            old_1 = imp_1
            imp_n += 0.5 * dt * (prev_n + normal)
            imp_0 += 0.5 * dt * (prev_0 + f0)
            imp_1 += 0.5 * dt * (prev_1 + f1)
            cum_n += 0.5 * dt * (old_n + imp_n)
            cum_0 += 0.5 * dt * (old_0 + imp_0)
            cum_1 += 0.5 * dt * (old_1 + imp_1)
            prev_n = normal
            prev_0 = f0
            prev_1 = f1
            # work of the contact forces on the relative motion, in units of F_max delta_max
            hh = h_new
            s0 = n0
            s1 = n1
            tau += dt
            steps = step
            if record:
                history_normal[case, step] = normal
                history_tangential[case, step] = f0
                history_stick[case, step] = stuck_to
            if flex and (h > 0.0 or hh >= 0.0 or rigid + np.sqrt(fy * fy + fz * fz / face_w2) > 0.0):
                continue  # the face's swing may still reach the ball
            if h <= 0.0 and hh < 0.0:
                break
            if load == 0.0 and hh < 0.0:  # a damped contact that stopped pushing: the bodies separate
                break
        out[case, 0] = imp_n
        out[case, 1] = imp_0
        out[case, 2] = imp_1
        out[case, 3] = last_touch if flex else tau
        out[case, 4] = cum_n
        out[case, 5] = cum_0
        out[case, 6] = cum_1
        out[case, 8] = steps
        out[case, 9] = mom0
        out[case, 10] = mom1
        for j in range(modes if live else 0):  # what the core's modes hold at separation (rates at the step's end)
            zm[j, 0] = hm[j, 0] + 0.5 * dt * am[j, 0]
            zm[j, 1] = hm[j, 1] + 0.5 * dt * am[j, 1]
            if mode_gain[case, j] > 0.0:
                core_taken += core_scale * (zm[j, 0] ** 2 + zm[j, 1] ** 2 + mode_frequency[case, j] ** 2 * (
                    ym[j, 0] ** 2 + ym[j, 1] ** 2)) / mode_gain[case, j]
        out[case, 7] = work - core_taken if live else work
        out[case, 11] = core_taken
        if flex:  # what the face holds at the end (its rate at the step's end), with what its loss took
            fz += 0.5 * dt * fa
            out[case, 12] = face_taken + 0.4 * (fz * fz + face_w2 * fy * fy) / gf


contact3d_cases = _compiled(_contact3d_cases, fastmath={"reassoc", "nsz", "arcp", "contract"})
