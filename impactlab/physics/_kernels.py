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


def _compiled(function, fastmath=False):
    """The numba-compiled kernel (cached on disk), or None where numba is off."""
    return numba.njit(cache=True, nogil=True, fastmath=fastmath)(function) if HAVE_NUMBA else None


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


def _lu_factor(matrix, size, pivots):
    """In-place LU factorisation with partial pivoting of matrix[:size, :size]."""
    for k in range(size):
        best, row = abs(matrix[k, k]), k
        for i in range(k + 1, size):
            if abs(matrix[i, k]) > best:
                best, row = abs(matrix[i, k]), i
        pivots[k] = row
        if row != k:
            for j in range(size):
                matrix[k, j], matrix[row, j] = matrix[row, j], matrix[k, j]
        diagonal = matrix[k, k]
        for i in range(k + 1, size):
            factor = matrix[i, k] / diagonal
            matrix[i, k] = factor
            if factor != 0.0:
                for j in range(k + 1, size):
                    matrix[i, j] -= factor * matrix[k, j]


def _lu_solve(matrix, size, pivots, vector):
    for k in range(size):
        row = pivots[k]
        if row != k:
            vector[k], vector[row] = vector[row], vector[k]
    for i in range(size):
        for j in range(i):
            vector[i] -= matrix[i, j] * vector[j]
    for i in range(size - 1, -1, -1):
        for j in range(i + 1, size):
            vector[i] -= matrix[i, j] * vector[j]
        vector[i] /= matrix[i, i]


def _annuli_cases(chi, psi1, tau, inside, caps, displacement, load, gamma, gain_factor, max_iterations, record,
                  history, stick, h_nodes):
    """Annular-strip time loop per case, factorising the mixed system only when the stick/slip set changes.

    The system's rows depend on which annuli stick, slip or are out of contact, not on time, so one LU
    factorisation serves every step until an annulus enters, leaves, sticks or slips. Annuli outside the
    contact force their distributions to zero (the load matrix is upper triangular), so only the
    inside x inside block is solved. Returns (slip change, dissipation, failures).
    """
    cases = chi.size
    rings = gamma.size
    nodes = tau.size
    velocity_out = np.zeros(cases)
    dissipation_out = np.zeros(cases)
    failures = 0
    lu = np.zeros((rings, rings))
    pivots = np.zeros(rings, dtype=np.int64)
    rhs = np.zeros(rings)
    for case in range(cases):
        mode = np.zeros(rings, dtype=np.int64)  # 0 out, 1 stick, 2 slip
        direction = np.zeros(rings)
        offset = np.zeros(rings)
        strength = np.zeros(rings)
        u = np.zeros(rings)
        q = np.zeros(rings)
        position = 0.0
        velocity_change = 0.0
        acceleration = 0.0
        dissipation = 0.0
        previous_total = 0.0
        gain = gain_factor * chi[case]
        p1 = psi1[case]
        factored = -1  # size of the factorised block, -1: none valid
        for k in range(1, nodes):
            dt = tau[k] - tau[k - 1]
            half = velocity_change + 0.5 * dt * acceleration
            previous_position = position
            position = position + dt * (p1 + half)
            size = inside[k]
            for i in range(rings):
                if i < size and mode[i] == 0:  # entering: stuck where it already was
                    displaced = 0.0
                    for j in range(rings):
                        displaced += displacement[i, j] * strength[j]
                    offset[i] = previous_position - displaced
                    mode[i] = 1
                    factored = -1
                elif i >= size and mode[i] != 0:
                    mode[i] = 0
                    factored = -1
            if size != factored and factored != -1:
                factored = -1
            settled = False
            for _ in range(max_iterations):
                if factored == -1:
                    for i in range(size):
                        for j in range(size):
                            lu[i, j] = displacement[i, j] if mode[i] == 1 else load[i, j]
                    _lu_factor(lu, size, pivots)
                    factored = size
                for i in range(size):
                    rhs[i] = position - offset[i] if mode[i] == 1 else 2.0 * direction[i] * caps[k, i]
                _lu_solve(lu, size, pivots, rhs)
                for j in range(rings):
                    strength[j] = rhs[j] if j < size else 0.0
                changed = False
                for i in range(size):
                    # a stuck annulus's displacement and a slipping one's load are what was imposed:
                    # only the other quantity needs the sum (and the load matrix is upper triangular)
                    if mode[i] == 1:
                        load_i = 0.0
                        for j in range(i, size):
                            load_i += load[i, j] * strength[j]
                        q[i] = 0.5 * load_i
                        u[i] = position - offset[i]
                        if abs(q[i]) > caps[k, i] * (1 + 1e-10) + 1e-14:
                            mode[i] = 2
                            direction[i] = 1.0 if q[i] > 0 else -1.0
                            changed = True
                    else:
                        moved = 0.0
                        for j in range(size):
                            moved += displacement[i, j] * strength[j]
                        u[i] = moved
                        q[i] = direction[i] * caps[k, i]
                        if direction[i] * (position - u[i] - offset[i]) < -1e-12:
                            mode[i] = 1
                            changed = True
                if not changed:
                    settled = True
                    break
                factored = -1
            if not settled:
                failures += 1
            for i in range(size):
                if mode[i] == 2:
                    offset[i] = position - u[i]
            total = 0.0
            for j in range(size):
                total += strength[j] * gamma[j]
            dissipation += 0.5 * (previous_total + total) * (position - previous_position)
            previous_total = total
            acceleration = -gain * total
            velocity_change = half + 0.5 * dt * acceleration
            if record:
                history[case, k] = 1.5 * total
                first_slip = rings
                for i in range(size):
                    if mode[i] == 2:
                        first_slip = i
                        break
                root = np.sqrt(h_nodes[k]) if h_nodes[k] > 0.0 else 0.0
                stick[case, k] = root if first_slip >= size else first_slip / rings
        velocity_out[case] = velocity_change
        dissipation_out[case] = dissipation
    return velocity_out, dissipation_out, failures


if HAVE_NUMBA:
    # the helpers are looked up as globals when the kernel compiles: compile them first
    _lu_factor = _compiled(_lu_factor)
    _lu_solve = _compiled(_lu_solve)
annuli_cases = _compiled(_annuli_cases)


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


def _stronge_cases(initial, mobility, friction, restitution, steps, impulse_out, flags_out):
    """3-D rigid-body impact with Coulomb friction, integrated over the normal impulse (Stronge, ch. 5).

    Per case: the relative contact velocity v (s, l, n) changes as dv = W dJ with dJ = (f, 1) dp over the
    normal impulse p, f the friction's tangential impulse per unit p: -mu v_t/|v_t| while sliding,
    -W_tt^-1 W_tn while that stays in the friction cone (stick), else sliding on the cone in the direction
    the slip starts in. Within a step the slip direction is frozen, so v is linear in p: compression's end,
    the energetic restitution's end (normal work in restitution = e^2 times that in compression) and the
    instant the slip stops fall on exact roots inside the step. Flags: bit 1 - the step limit was hit.
    """
    cases = initial.shape[0]
    for case in range(cases):
        w = mobility[case]
        mu = friction[case]
        e2 = restitution[case] ** 2
        v0 = initial[case, 0]
        v1 = initial[case, 1]
        vn = initial[case, 2]
        scale = (1.0 + restitution[case]) * (-vn) / w[2, 2]
        dp = scale / steps
        speed_scale = abs(vn) + np.sqrt(v0 * v0 + v1 * v1)
        j0 = 0.0
        j1 = 0.0
        jn = 0.0
        compression = 0.0
        recovered = 0.0
        compressing = vn < 0.0
        done = vn >= 0.0  # not approaching: no impact
        flags = 0
        for _ in range(50 * steps):
            if done:
                break
            slip = np.sqrt(v0 * v0 + v1 * v1)
            if slip > 1e-13 * speed_scale:
                f0 = -mu * v0 / slip
                f1 = -mu * v1 / slip
                sliding = True
            else:
                # stick if the cone holds the impulse ratio that keeps v_t = 0
                det = w[0, 0] * w[1, 1] - w[0, 1] * w[1, 0]
                x0 = -(w[1, 1] * w[0, 2] - w[0, 1] * w[1, 2]) / det
                x1 = -(-w[1, 0] * w[0, 2] + w[0, 0] * w[1, 2]) / det
                if x0 * x0 + x1 * x1 <= mu * mu * (1.0 + 1e-12):
                    f0 = x0
                    f1 = x1
                    sliding = False
                else:
                    # the slip restarts along s with W_tn - mu W_tt s parallel to s (fixed point)
                    s0 = w[0, 2]
                    s1 = w[1, 2]
                    norm = np.sqrt(s0 * s0 + s1 * s1)
                    s0 = s0 / norm if norm > 0.0 else 1.0
                    s1 = s1 / norm if norm > 0.0 else 0.0
                    for _it in range(60):
                        a0 = w[0, 2] - mu * (w[0, 0] * s0 + w[0, 1] * s1)
                        a1 = w[1, 2] - mu * (w[1, 0] * s0 + w[1, 1] * s1)
                        norm = np.sqrt(a0 * a0 + a1 * a1)
                        if norm == 0.0:
                            break
                        s0 = a0 / norm
                        s1 = a1 / norm
                    f0 = -mu * s0
                    f1 = -mu * s1
                    sliding = True
            r0 = w[0, 0] * f0 + w[0, 1] * f1 + w[0, 2]
            r1 = w[1, 0] * f0 + w[1, 1] * f1 + w[1, 2]
            rn = w[2, 0] * f0 + w[2, 1] * f1 + w[2, 2]
            q = dp
            event = 0  # 1: the slip stops, 2: compression ends, 3: the impact ends
            if sliding and slip > 1e-13 * speed_scale:
                along = r0 * v0 + r1 * v1
                if along < 0.0:
                    q_min = -along / (r0 * r0 + r1 * r1)  # where |v_t + r_t q| is smallest
                    if q_min <= q:
                        q = q_min
                        event = 1
            if compressing:
                if rn > 0.0 and -vn / rn <= q:
                    q = -vn / rn
                    event = 2
            else:
                remaining = e2 * compression - recovered
                if vn * q + 0.5 * rn * q * q >= remaining:
                    # vn q + rn q^2 / 2 = remaining: the smallest non-negative root
                    disc = vn * vn + 2.0 * rn * remaining
                    root = (2.0 * remaining / (vn + np.sqrt(disc))) if vn + np.sqrt(max(disc, 0.0)) > 0.0 else 0.0
                    if root <= q:
                        q = root
                        event = 3
            if compressing:
                compression -= vn * q + 0.5 * rn * q * q
            else:
                recovered += vn * q + 0.5 * rn * q * q
            j0 += f0 * q
            j1 += f1 * q
            jn += q
            v0 += r0 * q
            v1 += r1 * q
            vn += rn * q
            if event == 1:
                v0 = 0.0
                v1 = 0.0
            elif event == 2:
                vn = 0.0
                compressing = False
                if e2 == 0.0:
                    done = True
            elif event == 3:
                done = True
        if not done:
            flags |= 1
        impulse_out[case, 0] = j0
        impulse_out[case, 1] = j1
        impulse_out[case, 2] = jn
        flags_out[case] = flags


stronge_cases = _compiled(_stronge_cases)


def _contact3d_cases(ratio_tt, coupling, kappa, friction, psi, damping, dtau, max_steps, law, stiffness_factor,
                     store_force, rescale, tangential_damping, relaxation, xi2, weight, record, history_normal,
                     history_tangential, history_stick, out, couple_n, couple_t, couple_rr, rolling0, arm):
    """Compliant 3-D contact per case, in MBF's scaled variables with the normal and tangential directions coupled.

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
    """
    cases = psi.shape[0]
    springs = xi2.size
    u = np.zeros((springs, 2))
    for case in range(cases):
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
        for step in range(1, max_steps + 1):
            h_half = hh + 0.5 * dt * ah
            v0 = s0 + 0.5 * dt * as0
            v1 = s1 + 0.5 * dt * as1
            h_old = h
            h = h + dt * h_half
            # the damped law's force at the step's end needs the rate there: predicted with the last acceleration
            load = 1.0 + c * (h_half + 0.5 * dt * ah) if c > 0.0 else 1.0
            if load < 0.0:
                load = 0.0
            hp = h if h > 0.0 else 0.0
            normal = hp ** 1.5 * load
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
                    x0 = u[i, 0] + d0 + lag * v0
                    x1 = u[i, 1] + d1 + lag * v1
                    squared = x0 * x0 + x1 * x1
                    if squared > cap * cap:  # back to the Coulomb circle (the square root only when needed)
                        shrink_to = cap / np.sqrt(squared)
                        x0 *= shrink_to
                        x1 *= shrink_to
                        if record and first_slip == springs:
                            first_slip = i
                        # sliding: the spring-dashpot carries the cap and relaxes towards it (backward Euler of
                        # k u + c u' = cap); without a dashpot it sits on the circle
                        u[i, 0] = (u[i, 0] + ratio * x0) / (1.0 + ratio)
                        u[i, 1] = (u[i, 1] + ratio * x1) / (1.0 + ratio)
                    else:
                        u[i, 0] = x0 - lag * v0
                        u[i, 1] = x1 - lag * v1
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
                    x0 = u[i, 0] + inside * d0 + lag * v0
                    x1 = u[i, 1] + inside * d1 + lag * v1
                    squared = x0 * x0 + x1 * x1
                    if squared > cap * cap:
                        shrink_to = cap / np.sqrt(squared)
                        x0 *= shrink_to
                        x1 *= shrink_to
                        if record and first_slip == springs:
                            first_slip = i
                        u[i, 0] = (u[i, 0] + ratio * x0) / (1.0 + ratio)
                        u[i, 1] = (u[i, 1] + ratio * x1) / (1.0 + ratio)
                    else:
                        u[i, 0] = x0 - lag * v0
                        u[i, 1] = x1 - lag * v1
                    f0 += x0
                    f1 += x1
                    i += 1
                f0 *= 1.5 * weight
                f1 *= 1.5 * weight
                radius = first_slip / springs
                root = np.sqrt(hp)
                stuck_to = radius if radius < root else root
            else:
                if law == 1:
                    stiff = 1.5 * stiffness_factor
                    stiff_mean = stiff
                else:
                    stiff = 1.5 * stiffness_factor * np.sqrt(hp)
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
                    stuck_to = np.sqrt(hp)
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
                q0 = -(wm0 / (0.625 * dt) + g0)
                q1 = -(wm1 / (0.625 * dt) + g1)
                c0 = (r11 * q0 - r01 * q1) / det
                c1 = (-r10 * q0 + r00 * q1) / det
                limit = rho * np.sqrt(hp) * normal
                size = np.sqrt(c0 * c0 + c1 * c1)
                if size > limit:
                    c0 *= limit / size
                    c1 *= limit / size
            ah = -1.25 * (normal - mu * (b0 * f0 + b1 * f1) + cn0 * c0 + cn1 * c1)
            if mu > 0.0:
                as0 = -1.25 * k * (a00 * f0 + a01 * f1) + (1.25 * k / mu) * (b0 * normal + ct00 * c0 + ct01 * c1)
                as1 = -1.25 * k * (a10 * f0 + a11 * f1) + (1.25 * k / mu) * (b1 * normal + ct10 * c0 + ct11 * c1)
            if rho > 0.0:
                aw0 = 1.25 * (g0 + r00 * c0 + r01 * c1)
                aw1 = 1.25 * (g1 + r10 * c0 + r11 * c1)
                w0 = wm0 + 0.5 * dt * aw0
                w1 = wm1 + 0.5 * dt * aw1
                # the couple's work on the half-step rolling rate, as the forces' work below [F_max delta_max]
                work += dt * 0.5 * ((prev_c0 + c0) * wm0 + (prev_c1 + c1) * wm1)
                mom0 += 0.5 * dt * (prev_c0 + c0)
                mom1 += 0.5 * dt * (prev_c1 + c1)
                prev_c0 = c0
                prev_c1 = c1
            h_new = h_half + 0.5 * dt * ah
            n0 = v0 + 0.5 * dt * as0
            n1 = v1 + 0.5 * dt * as1
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
            if h <= 0.0 and hh < 0.0:
                break
            if load == 0.0 and hh < 0.0:  # a damped contact that stopped pushing: the bodies separate
                break
        out[case, 0] = imp_n
        out[case, 1] = imp_0
        out[case, 2] = imp_1
        out[case, 3] = tau
        out[case, 4] = cum_n
        out[case, 5] = cum_0
        out[case, 6] = cum_1
        out[case, 7] = work
        out[case, 8] = steps
        out[case, 9] = mom0
        out[case, 10] = mom1


contact3d_cases = _compiled(_contact3d_cases, fastmath={"reassoc", "nsz", "arcp", "contract"})


def _rolling_cases(initial, mobility, coupling, rotation, rolling, friction, restitution, arm, steps, sweeps,
                   impulse_out, moment_out, flags_out):
    """Rigid impact with Coulomb friction and a rolling-resistance couple over the normal impulse, per case.

    The arithmetic of :func:`impactlab.physics.ball_laws.rolling_impulses` (its numpy reference), one case at a
    time: generalised velocity (v_s, v_l, v_n, Omega_s, Omega_l), per step dP the tangential impulse in the disc
    mu dP and the couple in the disc d dP that minimise the energy after the step (projected block Gauss-Seidel,
    ``sweeps`` sweeps), the last step cut where Stronge's energetic restitution ends. Flags: bit 1 - step limit.
    """
    cases = initial.shape[0]
    for case in range(cases):
        w = mobility[case]
        b = coupling[case]
        r = rotation[case]
        mu = friction[case]
        e = restitution[case]
        d = arm[case]
        v0 = initial[case, 0]
        v1 = initial[case, 1]
        vn = initial[case, 2]
        o0 = rolling[case, 0]
        o1 = rolling[case, 1]
        dp = (1.0 + e) * (-vn) / w[2, 2] / steps
        det_w = w[0, 0] * w[1, 1] - w[0, 1] * w[1, 0]
        det_r = r[0, 0] * r[1, 1] - r[0, 1] * r[1, 0]
        j0 = 0.0
        j1 = 0.0
        jn = 0.0
        m0 = 0.0
        m1 = 0.0
        compression = 0.0
        restoring = 0.0
        separating = False
        done = False
        for _ in range(4 * steps):
            base_t0 = v0 + w[0, 2] * dp
            base_t1 = v1 + w[1, 2] * dp
            base_r0 = o0 + b[2, 0] * dp
            base_r1 = o1 + b[2, 1] * dp
            x0 = 0.0
            x1 = 0.0
            c0 = 0.0
            c1 = 0.0
            for _sweep in range(sweeps):
                last0 = x0
                last1 = x1
                q0 = -(base_t0 + b[0, 0] * c0 + b[0, 1] * c1)
                q1 = -(base_t1 + b[1, 0] * c0 + b[1, 1] * c1)
                x0 = (w[1, 1] * q0 - w[0, 1] * q1) / det_w
                x1 = (-w[1, 0] * q0 + w[0, 0] * q1) / det_w
                size = np.sqrt(x0 * x0 + x1 * x1)
                limit = mu * dp
                if size > limit:
                    x0 *= limit / size
                    x1 *= limit / size
                q0 = -(base_r0 + b[0, 0] * x0 + b[1, 0] * x1)
                q1 = -(base_r1 + b[0, 1] * x0 + b[1, 1] * x1)
                c0 = (r[1, 1] * q0 - r[0, 1] * q1) / det_r
                c1 = (-r[1, 0] * q0 + r[0, 0] * q1) / det_r
                size = np.sqrt(c0 * c0 + c1 * c1)
                limit = d * dp
                if size > limit:
                    scale = limit / size if size > 0.0 else 0.0
                    c0 *= scale
                    c1 *= scale
                if _sweep > 0 and abs(x0 - last0) + abs(x1 - last1) <= 1e-13 * (mu * dp + 1e-300):
                    break  # the split between friction and couple no longer changes
            new_n = vn + w[2, 0] * x0 + w[2, 1] * x1 + w[2, 2] * dp + b[2, 0] * c0 + b[2, 1] * c1
            fraction = 1.0
            if separating:
                remaining = -(e * e) * compression - restoring
                full = 0.5 * (vn + new_n) * dp
                if full >= remaining:
                    target = remaining / dp if remaining > 0.0 else 0.0
                    dv = new_n - vn
                    if abs(dv) > 1e-300:
                        fraction = (-vn + np.sqrt(max(vn * vn + 2.0 * dv * target, 0.0))) / dv
                    elif vn > 0.0:
                        fraction = target / vn
                    fraction = min(max(fraction, 0.0), 1.0)
                    done = True
            x0 *= fraction
            x1 *= fraction
            pn = dp * fraction
            c0 *= fraction
            c1 *= fraction
            old_n = vn
            nv0 = v0 + w[0, 0] * x0 + w[0, 1] * x1 + w[0, 2] * pn + b[0, 0] * c0 + b[0, 1] * c1
            nv1 = v1 + w[1, 0] * x0 + w[1, 1] * x1 + w[1, 2] * pn + b[1, 0] * c0 + b[1, 1] * c1
            vn = vn + w[2, 0] * x0 + w[2, 1] * x1 + w[2, 2] * pn + b[2, 0] * c0 + b[2, 1] * c1
            v0 = nv0
            v1 = nv1
            no0 = o0 + b[0, 0] * x0 + b[1, 0] * x1 + b[2, 0] * pn + r[0, 0] * c0 + r[0, 1] * c1
            o1 = o1 + b[0, 1] * x0 + b[1, 1] * x1 + b[2, 1] * pn + r[1, 0] * c0 + r[1, 1] * c1
            o0 = no0
            j0 += x0
            j1 += x1
            jn += pn
            m0 += c0
            m1 += c1
            work = 0.5 * (old_n + vn) * pn
            if separating:
                restoring += work
            else:
                compression += work
            if vn >= 0.0:
                separating = True
            if done:
                break
        impulse_out[case, 0] = j0
        impulse_out[case, 1] = j1
        impulse_out[case, 2] = jn
        moment_out[case, 0] = m0
        moment_out[case, 1] = m1
        flags_out[case] = 0 if done else 1


rolling_cases = _compiled(_rolling_cases)
