"""Air for a golf ball's flight: saturation vapour pressure, ISA pressure with altitude, moist-air density and
viscosity (plain numpy, SI units: K, Pa, kg/m^3, Pa s; every function broadcasts its inputs).

Used by the trajectory integrator :func:`impactlab.physics.flight.fly`; docs/flight.md has the model.

References
----------
.. [Bu81] A. L. Buck, "New equations for computing vapor pressure and
   enhancement factor", J. Appl. Meteor. 20, 1527-1532 (1981).
.. [ISA] ISO 2533:1975 Standard Atmosphere (troposphere, 0-11 km).
"""

from __future__ import annotations

import numpy as np

__all__ = ["G0", "air_density", "air_viscosity", "pressure_at_altitude", "saturation_vapour_pressure"]

G0 = 9.80665  #: standard gravity, m/s^2 (ISO 2533)
_R_UNIVERSAL = 8.314462618  # J/(mol K)
_M_DRY = 0.0289644  # kg/mol, dry air
_M_VAP = 0.018015  # kg/mol, water
_R_DRY = _R_UNIVERSAL / _M_DRY  # 287.05 J/(kg K)
_R_VAP = _R_UNIVERSAL / _M_VAP  # 461.5 J/(kg K)


def saturation_vapour_pressure(temperature):
    """Saturation vapour pressure of water over liquid water.

    Parameters
    ----------
    temperature : array_like
        Air temperature, K.

    Returns
    -------
    ndarray
        Saturation vapour pressure, Pa.

    Notes
    -----
    Buck (1981) equation [Bu81]_ ("e_w4" of Buck's paper, as revised 1996):
    ``e_s = 611.21 exp((18.678 - T/234.5) (T / (257.14 + T)))`` with ``T`` in
    degC.  Accurate to about 0.05 % between -40 and +50 degC.
    """
    t_c = np.asarray(temperature, dtype=float) - 273.15
    return 611.21 * np.exp((18.678 - t_c / 234.5) * (t_c / (257.14 + t_c)))


def pressure_at_altitude(altitude, sea_level_pressure=101325.0):
    """Static pressure of the ISA standard atmosphere at a geopotential height.

    Parameters
    ----------
    altitude : array_like
        Height above mean sea level, m (valid 0-11 000 m, the troposphere).
    sea_level_pressure : array_like, optional
        Pressure at sea level, Pa.  Default 101 325 Pa.

    Returns
    -------
    ndarray
        Pressure, Pa.

    Notes
    -----
    Barometric formula for a constant lapse rate [ISA]_:
    ``p = p0 (1 - L h / T0) ** (g0 M / (R L))`` with ``T0 = 288.15 K``,
    ``L = 0.0065 K/m``, ``M = 0.0289644 kg/mol``.
    Examples: 1 609 m (Denver) -> 83.4 kPa; 2 240 m (Mexico City) -> 77.1 kPa.
    """
    h = np.asarray(altitude, dtype=float)
    t0, lapse = 288.15, 0.0065
    expo = G0 * _M_DRY / (_R_UNIVERSAL * lapse)
    return np.asarray(sea_level_pressure, dtype=float) * (1.0 - lapse * h / t0) ** expo


def air_density(temperature=288.15, pressure=101325.0, relative_humidity=0.0):
    """Density of moist air from temperature, pressure and relative humidity.

    Parameters
    ----------
    temperature : array_like
        Air temperature, K.
    pressure : array_like
        Total (station) air pressure, Pa.
    relative_humidity : array_like
        Relative humidity as a fraction, 0 to 1.

    Returns
    -------
    ndarray
        Air density, kg/m^3.

    Notes
    -----
    Ideal-gas mixture of dry air and water vapour (Dalton's law):
    ``rho = (p - e) / (R_d T) + e / (R_v T)``, ``e = RH * e_s(T)`` with the
    Buck saturation pressure [Bu81]_.  At 288.15 K, 101 325 Pa, RH 0 this is
    1.2250 kg/m^3 (ISA).  Humid air is *lighter* than dry air.
    """
    t = np.asarray(temperature, dtype=float)
    p = np.asarray(pressure, dtype=float)
    rh = np.asarray(relative_humidity, dtype=float)
    e = rh * saturation_vapour_pressure(t)
    return (p - e) / (_R_DRY * t) + e / (_R_VAP * t)


def air_viscosity(temperature):
    """Dynamic viscosity of air (Sutherland's law).

    Parameters
    ----------
    temperature : array_like
        Temperature, K.

    Returns
    -------
    ndarray
        Dynamic viscosity, Pa s (1.789e-5 at 288.15 K).

    Notes
    -----
    ``mu = 1.458e-6 T^1.5 / (T + 110.4)`` (the ISO 2533 form).
    """
    t = np.asarray(temperature, dtype=float)
    return 1.458e-6 * t**1.5 / (t + 110.4)
