"""Rigid-body bookkeeping of a ball struck by a face: masses, slip, and what follows from the impulses.

Frame (the face frame): ``x`` in the face along the incoming slip of the
contact point, ``z`` along the face normal away from the face. The club moves
along the path p = cos(alpha) z - sin(alpha) x relative to the ball, which
starts at rest (it may spin). Impulses are those on the ball: ``J_n`` along
+z, ``J_t`` along -x (positive when it opposes the incoming slip).

References
----------
W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 5.
"""

from __future__ import annotations

import numpy as np


def effective_mass(ball_mass, club_mass):
    """Normal effective mass m* = 1 / (1/m + 1/M) [kg] (M = inf: m* = m)."""
    return 1.0 / (1.0 / ball_mass + 1.0 / club_mass)


def tangential_mass(ball_mass, inertia_factor, club_mass):
    """Effective mass of the contact point in tangential slip, 1/m_t = (1 + 1/K^2)/m + 1/M [kg]."""
    return 1.0 / ((1.0 + 1.0 / inertia_factor) / ball_mass + 1.0 / club_mass)


def approach_velocities(speed, angle, spin, radius):
    """Normal approach speed V_z = V cos(alpha) and contact-point slip V_x = V sin(alpha) - R omega0 [m/s]."""
    return speed * np.cos(angle), speed * np.sin(angle) - radius * spin


def after_impact(normal_impulse, tangential_impulse, *, ball_mass, ball_radius, ball_inertia_factor, speed, angle,
                 spin, club_mass=np.inf):
    """Everything the impulses imply about the ball after impact (SI units, angles in rad).

    Parameters
    ----------
    normal_impulse, tangential_impulse : array_like
        J_n and J_t on the ball [N s].
    ball_mass, ball_radius, ball_inertia_factor : array_like
        m [kg], R [m], K^2 [1].
    speed, angle, spin : array_like
        V [m/s], alpha [rad], incoming spin omega0 [rad/s], counted like the output spin (positive: the
        backspin a lofted face gives, topspin about the flight of a ball arriving at a plate; docs/conventions.md).
    club_mass : array_like
        M [kg]; inf for a fixed face.

    Returns
    -------
    dict
        ``normal_velocity``, ``tangential_velocity`` (ball centre relative to
        the face after impact), ``spin_rate`` [rad/s], ``tangential_restitution``
        (NaN where there was no incoming slip), ``launch_angle`` [rad],
        ``launch_ratio`` (NaN at alpha = 0), ``rebound_angle`` [rad], ``total_angle``
        (incidence plus rebound angle, the plate experiment's measure) [rad],
        ``ball_speed`` [m/s] (ground frame) and ``energy_loss`` [J].
    """
    jn = np.asarray(normal_impulse, dtype=float)
    jt = np.asarray(tangential_impulse, dtype=float)
    m, radius, k2, club = ball_mass, ball_radius, ball_inertia_factor, club_mass
    inertia = k2 * m * radius**2
    vz, vx = approach_velocities(speed, angle, spin, radius)
    sin_a, cos_a = np.sin(angle), np.cos(angle)

    normal_velocity = jn / effective_mass(m, club) - vz
    tangential_velocity = speed * sin_a - jt * (1.0 / m + 1.0 / club)
    spin_after = spin + jt * radius / inertia
    slip_after = tangential_velocity - radius * spin_after
    with np.errstate(divide="ignore", invalid="ignore"):
        beta = np.where(vx != 0.0, -slip_after / np.where(vx != 0.0, vx, 1.0), np.nan)
        launch_angle = angle - np.arctan2(jt, jn)
        launch_ratio = np.where(angle != 0.0, launch_angle / np.where(angle != 0.0, angle, 1.0), np.nan)
    rebound_angle = np.arctan2(tangential_velocity, normal_velocity)
    ball_speed = np.hypot(jn, jt) / m

    # Club: before V p, after V p - J/M. Ball: before at rest with spin omega0.
    work_on_club = speed * (jt * sin_a + jn * cos_a) - np.where(np.isinf(club), 0.0, (jn**2 + jt**2) / (2 * club))
    energy_loss = (work_on_club + 0.5 * inertia * spin**2
                   - 0.5 * m * ball_speed**2 - 0.5 * inertia * spin_after**2)
    return {
        "normal_velocity": normal_velocity,
        "tangential_velocity": tangential_velocity,
        "spin_rate": spin_after,
        "tangential_restitution": beta,
        "launch_angle": launch_angle,
        "launch_ratio": launch_ratio,
        "rebound_angle": rebound_angle,
        "total_angle": angle + rebound_angle,
        "ball_speed": ball_speed,
        "energy_loss": energy_loss,
    }


#: what after_impact needs besides the impulses (model input names)
AFTER_IMPACT_INPUTS = ("ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle", "spin")
