"""Hertz normal contact of a sphere on a half-space, and its elastic impact.

The elastic Hertz impact has a universal shape: with the maximum approach
delta_max and T = delta_max / V_z, the approach is delta(t) = delta_max h(t/T)
where h'' = -(5/4) h^(3/2), h(0) = 0, h'(0) = 1. Energy conservation gives
h'^2 = 1 - h^(5/2), so the time to reach h is an incomplete beta function and
its inverse gives h(tau) exactly (no time stepping).

References
----------
K. L. Johnson, *Contact Mechanics*, Cambridge University Press (1985), §4.2, §11.4.
"""

from __future__ import annotations

import numpy as np
from scipy import special

_A, _B = 0.4, 0.5
#: scaled time at maximum compression, tau_m = (2/5) B(2/5, 1/2)
TAU_MAX_COMPRESSION = 0.4 * special.beta(_A, _B)
#: scaled contact duration, tau_c = 2 tau_m = 2.9432...
TAU_CONTACT = 2.0 * TAU_MAX_COMPRESSION


def effective_modulus(e1, nu1, e2, nu2):
    """Hertz contact modulus E*, 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 [Pa] (E2 = inf: rigid face)."""
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


def tangential_modulus(e1, nu1, e2, nu2):
    """MDR tangential modulus G*, 1/G* = (2 - nu1)/(4 G1) + (2 - nu2)/(4 G2) [Pa].

    The Mindlin incremental tangential stiffness of a circular contact of
    radius a is 2 a G* (= 8 a G*_J with G*_J = G*/4).
    """
    g1 = e1 / (2.0 * (1.0 + nu1))
    g2 = e2 / (2.0 * (1.0 + nu2))
    return 1.0 / ((2.0 - nu1) / (4.0 * g1) + (2.0 - nu2) / (4.0 * g2))


def max_approach(effective_mass, radius, modulus, normal_speed):
    """delta_max = (15 m* V^2 / (16 E* sqrt(R)))^(2/5) [m]."""
    return (15.0 * effective_mass * normal_speed**2 / (16.0 * modulus * np.sqrt(radius))) ** 0.4


def contact_time(effective_mass, radius, modulus, normal_speed):
    """Elastic Hertz contact duration t_c = tau_c delta_max / V = 2.8682 (m*^2/(R E*^2 V))^(1/5) [s]."""
    return TAU_CONTACT * max_approach(effective_mass, radius, modulus, normal_speed) / normal_speed


def peak_force(effective_mass, radius, modulus, normal_speed):
    """F_max = (4/3) E* sqrt(R) delta_max^(3/2) [N]."""
    return 4.0 / 3.0 * modulus * np.sqrt(radius) * max_approach(effective_mass, radius, modulus, normal_speed) ** 1.5


def scaled_approach(tau):
    """h(tau) = delta/delta_max of the elastic Hertz impact; 0 outside [0, tau_c]."""
    tau = np.asarray(tau, dtype=float)
    rising = np.clip(np.minimum(tau, TAU_CONTACT - tau), 0.0, TAU_MAX_COMPRESSION)
    # time_to_reach inverted: tau/tau_m = I(h^(5/2); 2/5, 1/2)
    return special.betaincinv(_A, _B, rising / TAU_MAX_COMPRESSION) ** 0.4


def time_to_reach(h):
    """Scaled time at which the approach first reaches h delta_max (0 <= h <= 1)."""
    h = np.asarray(h, dtype=float)
    return TAU_MAX_COMPRESSION * special.betainc(_A, _B, np.clip(h, 0.0, 1.0) ** 2.5)
