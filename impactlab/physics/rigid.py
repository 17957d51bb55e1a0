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

    Returns (impulse (n, 3) in (s, l, n), capped on the friction cone (n,) bool, scaled by :func:`energy_cap`
    (n,) bool).
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
    capped_impulse = energy_cap(initial, mobility, impulse)
    return capped_impulse, capped, np.any(capped_impulse != impulse, axis=-1)


def energy_cap(initial, mobility, impulse):
    """The impulse scaled down along its own direction where it would create kinetic energy (a documented cap).

    The kinetic energy of ball and head changes by dT = J . v0 + J . W J / 2 (the work of the impulse on the mean
    relative contact velocity; Stronge 2000, ch. 5). Newton's kinematic coefficients (v1 = (-beta v_s, 0, -e v_n))
    fix the velocity after impact, not the work: where W couples the normal and tangential directions (a free
    head struck off its centre-of-mass line, a curved face) they can ask for dT > 0, e.g. 0.2 J at e = 1 on a
    driver struck 30 mm off centre. There the impulse is replaced by lambda J with
    lambda = -2 J . v0 / (J . W J) in (0, 1), the largest multiple of J that creates no energy (dT = 0: an
    elastic impact along the asked direction). If J . v0 >= 0 (no positive multiple of J does work against the
    approach) the impulse is the frictionless elastic one, (0, 0, -2 v_n / W_nn). Elsewhere J is unchanged, so
    every 1-D case (W diagonal: dT <= 0 for 0 <= e, beta <= 1) is exactly the kinematic model.

    Parameters
    ----------
    initial : ndarray (n, 3)
        Relative contact velocity before impact in (s, l, n) [m/s].
    mobility : ndarray (n, 3, 3)
        W in the same frame [1/kg].
    impulse : ndarray (n, 3)
        The impulse on the ball [N s].

    Returns
    -------
    ndarray (n, 3)
        The impulse, capped where it would create energy [N s].

    References
    ----------
    W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 5 (energy inconsistency of
    Newton's kinematic restitution with coupled mobilities).
    """
    work = np.einsum("ni,ni->n", impulse, initial)
    quadratic = np.einsum("ni,nij,nj->n", impulse, mobility, impulse)
    rises = work + 0.5 * quadratic > 0.0
    if not np.any(rises):
        return impulse
    impulse = impulse.copy()
    scalable = rises & (work < 0.0)
    scale = -2.0 * work[scalable] / quadratic[scalable]
    impulse[scalable] *= scale[:, None]
    elastic = rises & ~scalable
    if np.any(elastic):
        impulse[elastic] = 0.0
        impulse[elastic, 2] = -2.0 * initial[elastic, 2] / mobility[elastic, 2, 2]
    return impulse


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["STRONGE_STEPS", "coulomb_impulses_1d", "stronge_impulses", "restitution_impulses", "energy_cap"]
