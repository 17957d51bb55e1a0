"""Rigid impact with Coulomb friction and a rolling-resistance couple (impactlab.physics.ball_laws), compiled."""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


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
        # warm start: each step's split between friction and couple starts from the previous step's (the energy
        # minimised per step is strictly convex, so the sweeps reach the same split from any start; successive
        # steps differ little, so from the last one they stop after one or two sweeps instead of up to six)
        x0 = 0.0
        x1 = 0.0
        c0 = 0.0
        c1 = 0.0
        for _ in range(4 * steps):
            base_t0 = v0 + w[0, 2] * dp
            base_t1 = v1 + w[1, 2] * dp
            base_r0 = o0 + b[2, 0] * dp
            base_r1 = o1 + b[2, 1] * dp
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
                if _sweep > 0 and abs(x0 - last0) + abs(x1 - last1) <= 1e-10 * (mu * dp + 1e-300):
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
