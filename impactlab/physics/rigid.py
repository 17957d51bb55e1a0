"""Rigid-body impulse laws: Coulomb friction (Stronge) and restitution coefficients (Cross & Dewhurst).

References
----------
W. J. Stronge, *Impact Mechanics* (2000), ch. 5.
R. Cross and P. Dewhurst, "Launch speed, angle and spin in golf",
Eur. J. Phys. 39 (2018) 065003.
"""

from __future__ import annotations

import numpy as np

from .mechanics import approach_velocities, effective_mass, tangential_mass


def coulomb_impulses(*, ball_mass, ball_radius, ball_inertia_factor, speed, angle, spin, friction, restitution,
                     club_mass=np.inf):
    """Normal and tangential impulse of a rigid ball on a rigid face with Coulomb friction [N s].

    J_n = (1 + e) m* V_z. The ball slides throughout, J_t = mu J_n, if the
    slip |V_x| >= mu J_n / m_t; otherwise slip stops during contact and the
    ball leaves rolling, J_t = m_t V_x (tangential restitution beta = 0).

    Returns
    -------
    normal_impulse, tangential_impulse : ndarray
    sliding : ndarray of bool
        True where the ball slid throughout.
    """
    vz, vx = approach_velocities(speed, angle, spin, ball_radius)
    jn = (1.0 + restitution) * effective_mass(ball_mass, club_mass) * vz
    mt = tangential_mass(ball_mass, ball_inertia_factor, club_mass)
    stop_slip = mt * np.abs(vx)
    cap = friction * jn
    sliding = stop_slip >= cap
    jt = np.sign(vx) * np.where(sliding, cap, stop_slip)
    return jn, jt, sliding


def restitution_impulses(*, ball_mass, ball_radius, ball_inertia_factor, speed, angle, spin, restitution,
                         tangential_restitution, friction=np.inf, club_mass=np.inf):
    """Impulses from a normal (e) and a contact-point tangential (beta) coefficient of restitution [N s].

    J_n = (1 + e) m* V_z and J_t = (1 + beta) m_t V_x, capped at mu J_n
    (the ball then slides and beta is lower than asked).

    Returns
    -------
    normal_impulse, tangential_impulse : ndarray
    capped : ndarray of bool
        True where the Coulomb cap limited J_t.
    """
    vz, vx = approach_velocities(speed, angle, spin, ball_radius)
    jn = (1.0 + restitution) * effective_mass(ball_mass, club_mass) * vz
    wanted = (1.0 + tangential_restitution) * tangential_mass(ball_mass, ball_inertia_factor, club_mass) * np.abs(vx)
    cap = friction * jn
    capped = wanted > cap
    jt = np.sign(vx) * np.minimum(wanted, cap)
    return jn, jt, capped
