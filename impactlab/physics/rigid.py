"""Rigid-body impulse laws on the contact of :mod:`.contact`: Coulomb friction (Stronge) and restitution coefficients.

Both work on the relative contact velocity v0 (contact frame s, l, n) and the
mobility matrix W of the pair, so a fixed face, a point-mass club and a free
3-D head are one code path. When W is diagonal in the contact frame (a centred
strike on the centre-of-mass line of a flat face, a point-mass or fixed club)
the slip stays on its line and both laws have closed forms, which the 1-D
cases take; otherwise :func:`stronge_impulses` integrates over the normal
impulse.

References
----------
W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 5.
R. Cross and P. Dewhurst, "Launch speed, angle and spin in golf",
Eur. J. Phys. 39 (2018) 065003.
"""

from __future__ import annotations

import numpy as np

from . import kernels as _kernels

#: default steps over the normal impulse of the 3-D Coulomb integration
STRONGE_STEPS = 2000


def coulomb_impulses_1d(normal_speed, slip, m_normal, m_tangential, friction, restitution):
    """Closed form on one line: J_n = (1 + e) m* V_z; J_t = mu J_n if the ball slides throughout, else m_t V_x.

    The ball slides throughout if |V_x| >= mu J_n / m_t; otherwise its slip stops and it leaves rolling
    (tangential restitution 0). Returns (J_n, J_t opposing the slip, sliding).
    """
    jn = (1.0 + restitution) * m_normal * normal_speed
    stop_slip = m_tangential * np.abs(slip)
    cap = friction * jn
    sliding = stop_slip >= cap
    return jn, np.sign(slip) * np.where(sliding, cap, stop_slip), sliding


def stronge_impulses(initial, mobility, friction, restitution, steps: int = STRONGE_STEPS):
    """3-D rigid impact with Coulomb friction and Stronge's energetic restitution, per case.

    Parameters
    ----------
    initial : ndarray (n, 3)
        Relative contact velocity before impact in the contact frame (s, l, n) [m/s] (v_n < 0: approaching).
    mobility : ndarray (n, 3, 3)
        W in the same frame [1/kg].
    friction, restitution : ndarray (n,)
        mu and the energetic coefficient e: the normal force's work while the bodies separate is e^2 times
        (minus) its work while they approach. With W diagonal it equals Newton's kinematic e.
    steps : int
        Steps over the normal impulse (1 + e) V_n / W_nn; exact where the slip keeps its direction.

    Returns
    -------
    impulse : ndarray (n, 3)
        The impulse on the ball in (s, l, n) [N s].
    flags : ndarray (n,) of int
        Bit 1: the step limit was reached before the impact ended.
    """
    n = initial.shape[0]
    impulse, flags = np.zeros((n, 3)), np.zeros(n, dtype=np.int64)
    kernel = _kernels.stronge_cases if _kernels.HAVE_NUMBA else _kernels._stronge_cases
    kernel(np.ascontiguousarray(initial, dtype=float), np.ascontiguousarray(mobility, dtype=float),
           np.broadcast_to(np.asarray(friction, float), (n,)).copy(),
           np.broadcast_to(np.asarray(restitution, float), (n,)).copy(), int(steps), impulse, flags)
    return impulse, flags


def restitution_impulses(initial, mobility, restitution, tangential_restitution, friction=np.inf):
    """Impulse that gives normal restitution e and contact-point tangential restitution beta, capped by Coulomb.

    Solves W J = v1 - v0 for v1 = (-beta v_s, 0, e V_n): the contact leaves with its normal velocity reversed
    and scaled by e, its slip reversed and scaled by beta and no lateral slip. If the tangential impulse
    |J_t| > mu J_n, the impulse is put on the friction cone in the same tangential direction, J = J_n (n + mu d),
    with J_n chosen so that the normal restitution still holds. On one line this is J_n = (1 + e) m* V_z,
    J_t = min((1 + beta) m_t |V_x|, mu J_n).

    Returns (impulse (n, 3) in (s, l, n), capped (n,) bool).
    """
    n = initial.shape[0]
    e = np.broadcast_to(np.asarray(restitution, float), (n,))
    beta = np.broadcast_to(np.asarray(tangential_restitution, float), (n,))
    mu = np.broadcast_to(np.asarray(friction, float), (n,))
    target = np.stack([-beta * initial[:, 0], np.zeros(n), -e * initial[:, 2]], -1)
    impulse = np.linalg.solve(mobility, (target - initial)[:, :, None])[:, :, 0]
    tangential = np.hypot(impulse[:, 0], impulse[:, 1])
    capped = tangential > mu * impulse[:, 2]
    if np.any(capped):
        direction = impulse[capped, :2] / tangential[capped, None]
        w = mobility[capped]
        normal_rate = w[:, 2, 2] + mu[capped] * np.einsum("ni,ni->n", w[:, 2, :2], direction)
        jn = (1.0 + e[capped]) * (-initial[capped, 2]) / normal_rate
        impulse[capped] = np.concatenate([mu[capped, None] * jn[:, None] * direction, jn[:, None]], -1)
    return impulse, capped
