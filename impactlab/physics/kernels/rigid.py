"""Compiled 3-D rigid impact with Coulomb friction, Stronge's integration (:mod:`impactlab.physics.rigid`'s kernel)."""

from __future__ import annotations

import numpy as np

from ._numba import compiled as _compiled


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
