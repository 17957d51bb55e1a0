"""Golf ball flight: air properties, published aerodynamic models and a
vectorised 3-D trajectory integrator.

Everything here is plain numpy array code in SI units (m, s, kg, K, Pa, rad,
rad/s).  Every public function broadcasts its inputs, so a whole launch-monitor
session (or a Monte-Carlo cloud of 10^4 shots) is flown in one call.  The
user-facing wrapper (units, an :class:`xarray.Dataset`) is :func:`impactlab.fly`
(:mod:`impactlab.scene.flight`); docs/flight.md has the model, its validation
and what failed.

The signs are those of docs/conventions.md for golf outputs: ``spin_axis``,
``launch_direction`` (the study output ``horizontal_launch_angle``) and
``offline_distance`` are positive to the RIGHT of the target line, and a
positive spin axis curves the ball right.

Coordinate conventions
----------------------
Public (launch-monitor) frame, used for every input and output of :func:`fly`:

* ``x`` -- horizontal, along the target line, positive toward the target;
* ``y`` -- horizontal, positive to the RIGHT of the target line as seen by a
  golfer standing behind the ball (TrackMan/FlightScope "offline");
* ``z`` -- up.

This frame is left-handed.  Internally the integrator works in the
right-handed frame (x toward target, y to the LEFT, z up) so that the Magnus
force is the ordinary ``omega x v``; the sign of ``y`` is flipped on the way in
(wind, launch direction, spin axis) and on the way out (offline distance,
trajectories).

Angles:

* ``launch_angle`` -- vertical launch angle above horizontal (rad).
* ``launch_direction`` -- horizontal launch angle, positive = to the RIGHT of
  the target line (rad).
* ``spin_axis`` -- tilt of the spin axis (rad) about the launch velocity.
  ``0`` is pure backspin.  Positive = axis tilted right (for a right-handed
  golfer, a fade/slice axis): the lift vector leans right and the ball curves
  right.  This is the TrackMan sign convention.

References
----------
.. [SS94] A. J. Smits and D. R. Smith, "A new aerodynamic model of a golf ball
   in flight", in *Science and Golf II* (Proc. 1994 World Scientific Congress
   of Golf), A. J. Cochran and M. R. Farrally (eds.), E & FN Spon, London,
   1994, pp. 340-347.  Model constants as reproduced in R. D. Mehta's review
   text (e.g. Mehta & Pallis 2001) and in A. R. Penner, "The physics of golf:
   the optimum loft of a driver", Am. J. Phys. 69, 563 (2001), eq. (16).
.. [Ly18] Z. Lyu, J. Kensrud, L. Smith, T. Tosaya, "Aerodynamics of golf balls
   in still air", Proceedings 2(6), 238 (2018), doi:10.3390/proceedings2060238
   (CC BY 4.0).
.. [US01] B. B. Lieberman, A. J. Smits, S. J. Quintavalla, F. W. Thomas,
   D. Winfield (USGA), "Method for determining coefficients of lift and drag
   of a golf ball", US Patent 6,186,002 B1 (2001); regression "model 3" and
   its example coefficients.
.. [Na08] A. M. Nathan, "The spin decay of a baseball" (2008),
   baseball.physics.illinois.edu/spindown-rev1.pdf -- restates the Smits &
   Smith and Tavares et al. golf spin-decay fits, SRD = -lambda S.
.. [Bu81] A. L. Buck, "New equations for computing vapor pressure and
   enhancement factor", J. Appl. Meteor. 20, 1527-1532 (1981).
.. [ISA] ISO 2533:1975 Standard Atmosphere (troposphere, 0-11 km).
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "BALL_MASS",
    "BALL_RADIUS",
    "G0",
    "MODELS",
    "MODEL_REFERENCES",
    "PUBLISHED_MODELS",
    "aero_coefficients",
    "air_density",
    "air_viscosity",
    "fly",
    "pressure_at_altitude",
    "reynolds_number",
    "saturation_vapour_pressure",
    "spin_decay_rate",
    "spin_ratio",
]

# --------------------------------------------------------------------------
# Constants
# --------------------------------------------------------------------------
G0 = 9.80665  #: standard gravity, m/s^2
BALL_MASS = 0.04593  #: maximum legal ball mass (R&A/USGA Equipment Rules), kg
BALL_RADIUS = 0.021335  #: minimum legal ball radius (42.67 mm diameter), m

_R_UNIVERSAL = 8.314462618  # J/(mol K)
_M_DRY = 0.0289644  # kg/mol, dry air
_M_VAP = 0.018015  # kg/mol, water
_R_DRY = _R_UNIVERSAL / _M_DRY  # 287.05 J/(kg K)
_R_VAP = _R_UNIVERSAL / _M_VAP  # 461.5 J/(kg K)
_RHO_REF = 1.225  # kg/m^3, ISA sea level; reference density of the spin-decay fit


# --------------------------------------------------------------------------
# Air
# --------------------------------------------------------------------------
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


def reynolds_number(speed, density, viscosity, radius=BALL_RADIUS):
    """Ball Reynolds number based on diameter, ``Re = rho v (2R) / mu``.

    Parameters
    ----------
    speed : array_like
        Air-relative ball speed, m/s.
    density : array_like
        Air density, kg/m^3.
    viscosity : array_like
        Dynamic viscosity, Pa s.
    radius : array_like, optional
        Ball radius, m.

    Returns
    -------
    ndarray
        Reynolds number (dimensionless).
    """
    return np.asarray(density) * np.asarray(speed) * 2.0 * np.asarray(radius) / np.asarray(viscosity)


def spin_ratio(spin, speed, radius=BALL_RADIUS):
    """Spin ratio (spin parameter) ``S = R omega / v``.

    Parameters
    ----------
    spin : array_like
        Spin rate, rad/s.
    speed : array_like
        Air-relative speed, m/s (must be > 0).
    radius : array_like, optional
        Ball radius, m.

    Returns
    -------
    ndarray
        Spin ratio (dimensionless).
    """
    return np.asarray(radius) * np.asarray(spin) / np.asarray(speed)


# --------------------------------------------------------------------------
# Published aerodynamic models
# --------------------------------------------------------------------------
def _cd_cl_smits_smith(s, re):
    # [SS94]: wind-tunnel measurements on spinning balls (4e4 < Re < 2.5e5,
    # 0.04 < S < 1.4); closed-form model proposed for driver shots,
    # 7e4 < Re < 2.1e5, 0.08 < S < 0.2.  Constants as published:
    # CD1 = 0.24, CD2 = 0.18, CD3 = 0.06, A1 = 9e4, A2 = 2e5, CL1 = 0.54.
    cd = 0.24 + 0.18 * s + 0.06 * np.sin(np.pi * (re - 9.0e4) / 2.0e5)
    cl = 0.54 * s**0.4
    return cd, cl


def _cd_cl_lyu(s, re):
    # [Ly18]: free-flight (light-gate) measurements in still air; quadratic
    # fits published in their Figs. 3b (drag, Kirkland 2017 ball, spinning
    # 1500-2500 rpm) and 4b (lift, 13 balls, S ~ 0.04-0.32, 32-91 m/s).
    # Drag branch switch at Re = 7.5e4 (overlap of the two published fit
    # ranges; the two curves cross near there).
    cd_low = 1.29e-10 * re**2 - 2.59e-5 * re + 1.50
    cd_high = 1.91e-11 * re**2 - 5.40e-6 * re + 0.56
    cd = np.where(re < 7.5e4, cd_low, cd_high)
    # Lift fit peaks at S = 0.306 (CL = 0.305); beyond the fitted range we hold
    # the peak value rather than let the parabola go negative (extrapolation).
    s_c = np.minimum(s, 1.99 / (2 * 3.25))
    cl = -3.25 * s_c**2 + 1.99 * s_c
    return cd, cl


def _cd_cl_usga(s, re):
    # [US01]: USGA Indoor Test Range measurements of one test ball
    # (0.044 < S < 0.22, 0.81e5 < Re < 2.0e5) and the patent's example
    # regression "model 3" (Re in units of 1e5):
    #   CD = A + B S^2 + C Re + D S,  (0.2028, 2.8466, 0.0165, -0.2159)
    #   CL = A + B S + C / Re^2 + D S^2, (0.0860, 0.6463, -0.0122, 1.4789)
    r5 = re / 1.0e5
    cd = 0.2028 + 2.8466 * s**2 + 0.0165 * r5 - 0.2159 * s
    cl = 0.0860 + 0.6463 * s - 0.0122 / r5**2 + 1.4789 * s**2
    return cd, cl


#: Lyu et al. 2018's published lift fit peaks at S = 1.99/6.5 = 0.306 with CL = 0.305, the largest lift it measured
#: on modern balls (13-ball average at S ~0.32: 0.315)
LYU_LIFT_PEAK = 1.99**2 / (4 * 3.25)
#: USGA ITR example data of US 6,186,002 (seven condition means, Re/1e5, S, CD, CL; measurements of one
#: late-1990s test ball), to which the induced-drag factor of ``lyu_2018_induced_drag`` is fitted
USGA_ITR_EXAMPLE = ((0.81, 0.097, 0.223, 0.146), (0.81, 0.218, 0.305, 0.278), (1.23, 0.153, 0.256, 0.214),
                    (1.25, 0.088, 0.226, 0.146), (1.61, 0.090, 0.234, 0.151), (2.0, 0.092, 0.241, 0.153),
                    (1.98, 0.044, 0.231, 0.115))


def _induced_drag_factor():
    """k of CD = a + b Re/1e5 + k CL^2, least squares on :data:`USGA_ITR_EXAMPLE` (1.437)."""
    data = np.asarray(USGA_ITR_EXAMPLE)
    design = np.column_stack([np.ones(len(data)), data[:, 0], data[:, 3] ** 2])
    return float(np.linalg.lstsq(design, data[:, 2], rcond=None)[0][2])


INDUCED_DRAG_FACTOR = _induced_drag_factor()


def _cd_cl_smits_smith_capped(s, re):
    # NOT a published model: Smits & Smith (1994) with its lift held at the largest lift measured on modern
    # balls (Lyu et al. 2018's fit peak, 0.305). Tried because the Smits & Smith lift law is stated valid only
    # for S < 0.2 and irons fly at S 0.3-1.2; the cap was chosen after seeing the TrackMan misfit (docs/flight.md).
    cd, cl = _cd_cl_smits_smith(s, re)
    return cd, np.minimum(cl, LYU_LIFT_PEAK)


def _cd_cl_lyu_induced(s, re):
    # NOT a published model: Lyu et al. 2018's drag and lift fits plus an induced drag k CL^2, k fitted on the USGA
    # ITR example data (a source other than TrackMan): Lyu's drag fit has no spin term.
    cd, cl = _cd_cl_lyu(s, re)
    return cd + INDUCED_DRAG_FACTOR * cl**2, cl


def _cd_cl_vacuum(s, re):
    z = np.zeros(np.broadcast(s, re).shape)
    return z, z


#: Registry of published aerodynamic models: name -> (cd_cl(S, Re), spin-decay lambda).
MODELS = {
    "smits_smith_1994": (_cd_cl_smits_smith, 2.0e-5),
    "lyu_2018": (_cd_cl_lyu, 2.0e-5),
    "usga_patent_2001": (_cd_cl_usga, 2.0e-5),
    "smits_smith_lift_capped": (_cd_cl_smits_smith_capped, 2.0e-5),
    "lyu_2018_induced_drag": (_cd_cl_lyu_induced, 2.0e-5),
    "vacuum": (_cd_cl_vacuum, 0.0),
}
#: the models whose coefficients are published as they are (the others combine published pieces; docs/flight.md)
PUBLISHED_MODELS = ("smits_smith_1994", "lyu_2018", "usga_patent_2001")
DEFAULT_MODEL = "smits_smith_1994"
#: citation of each model's coefficients, and whether they are fits to measurements
MODEL_REFERENCES = {
    "smits_smith_1994": "A. J. Smits and D. R. Smith, 'A new aerodynamic model of a golf ball in flight', Science and "
                        "Golf II (1994) 340-347 (fits to wind-tunnel measurements); spin decay lambda = 2e-5 (same)",
    "lyu_2018": "Z. Lyu, J. Kensrud, L. Smith, T. Tosaya, 'Aerodynamics of golf balls in still air', Proceedings "
                "2(6), 238 (2018), doi:10.3390/proceedings2060238 (fits to free-flight measurements)",
    "usga_patent_2001": "US Patent 6,186,002 B1 (USGA, 2001), regression 'model 3' of Indoor Test Range "
                        "measurements",
    "smits_smith_lift_capped": "composite, not a published model: Smits & Smith (1994) with the lift held at 0.305, "
                               "the peak of Lyu et al. (2018)'s measured lift fit",
    "lyu_2018_induced_drag": "composite, not a published model: Lyu et al. (2018) fits plus induced drag 1.44 CL^2 "
                             "fitted on the USGA ITR example data of US 6,186,002 B1",
    "vacuum": "no air (a test limit)",
}


def aero_coefficients(s, re, model=DEFAULT_MODEL):
    """Drag and lift coefficients of a spinning golf ball.

    Parameters
    ----------
    s : array_like
        Spin ratio ``S = R omega / v`` (dimensionless, >= 0).
    re : array_like
        Reynolds number ``rho v 2R / mu`` (dimensionless).
    model : str, optional
        One of :data:`MODELS`:

        ``"smits_smith_1994"`` (default) -- [SS94]_, fitted by the authors to
        their wind-tunnel measurements::

            CD = 0.24 + 0.18 S + 0.06 sin(pi (Re - 90 000) / 200 000)
            CL = 0.54 S**0.4

        stated valid for 7e4 < Re < 2.1e5, 0.08 < S < 0.2 (driver shots);
        the underlying measurements cover 4e4 < Re < 2.5e5, 0.04 < S < 1.4.

        ``"lyu_2018"`` -- [Ly18]_, quadratic fits to free-flight light-gate
        measurements in still air::

            CD = 1.29e-10 Re^2 - 2.59e-5 Re + 1.50   (Re < 7.5e4)
            CD = 1.91e-11 Re^2 - 5.40e-6 Re + 0.56   (Re >= 7.5e4)
            CL = -3.25 S^2 + 1.99 S                  (held at its peak 0.305 for S > 0.306)

        ``"usga_patent_2001"`` -- [US01]_ "model 3" regression of USGA
        Indoor-Test-Range measurements (Re in 1e5)::

            CD = 0.2028 + 2.8466 S^2 + 0.0165 Re - 0.2159 S
            CL = 0.0860 + 0.6463 S - 0.0122 / Re^2 + 1.4789 S^2

        ``"smits_smith_lift_capped"`` -- NOT a published model: Smits & Smith
        with ``CL = min(0.54 S**0.4, 0.305)``, the cap being the peak of the
        Lyu et al. (2018) lift fit (the largest lift measured on modern balls).

        ``"lyu_2018_induced_drag"`` -- NOT a published model: Lyu et al.
        (2018) plus an induced drag ``k CL**2`` with ``k = 1.437`` fitted on
        the USGA ITR example data of [US01]_.

        ``"vacuum"`` -- zero drag and lift (for tests).

    Returns
    -------
    cd, cl : ndarray
        Drag and lift coefficients referred to ``q = rho v^2 / 2`` and the
        frontal area ``pi R^2``.

    Notes
    -----
    All three published models are curve fits to measurements; outside their
    fitted ranges (irons and wedges reach S = 0.3-1.2 late in flight) they are
    extrapolations.  See docs/flight.md for the validation of each.
    """
    fn, _ = MODELS[model]
    s = np.asarray(s, dtype=float)
    re = np.asarray(re, dtype=float)
    return fn(s, re)


def spin_decay_rate(spin, speed, density=_RHO_REF, radius=BALL_RADIUS, lam=2.0e-5):
    """Rate of change of spin from the aerodynamic torque.

    Parameters
    ----------
    spin : array_like
        Spin rate, rad/s.
    speed : array_like
        Air-relative speed, m/s.
    density : array_like, optional
        Air density, kg/m^3.  The published constant was measured near
        sea-level density; it is scaled by ``density / 1.225``.
    radius : array_like, optional
        Ball radius, m.
    lam : float, optional
        Dimensionless decay constant.  2.0e-5 (Smits & Smith 1994, wind
        tunnel); 2.5e-5 would be Tavares, Shannon & Melvin (1999, radar).

    Returns
    -------
    ndarray
        ``d omega / dt``, rad/s^2 (negative).

    Notes
    -----
    Smits & Smith found the normalised spin-decay rate
    ``SRD = (d omega/dt) R^2 / v^2`` linear in S and independent of Re:
    ``SRD = -lam S`` [SS94]_, [Na08]_, i.e.
    ``d omega / dt = -lam v omega / R`` (Penner 2001 eq. 16).  For a torque
    ``-R rho A C_M v^2`` with ``C_M`` proportional to S, ``lam`` is
    proportional to air density, hence the density scaling (an assumption of
    this module; it changes a 10 000 ft carry by about 1 yd).
    At 70 m/s this is about 6.6 %/s, at 40 m/s 3.7 %/s -- consistent with
    TrackMan's quoted "typically 4 % per second".
    """
    return (
        -lam
        * (np.asarray(density) / _RHO_REF)
        * np.asarray(speed)
        * np.asarray(spin)
        / np.asarray(radius)
    )


# --------------------------------------------------------------------------
# Trajectory integration
# --------------------------------------------------------------------------
def _derivs(state, p):
    """Time derivative of the state, shape (7, N): x y z vx vy vz omega (y LEFT)."""
    vx, vy, vz, omega = state[3], state[4], state[5], state[6]
    wind, axis = p["wind"], p["axis"]
    rx, ry, rz = vx - wind[0], vy - wind[1], vz - wind[2]
    speed = np.sqrt(rx * rx + ry * ry + rz * rz)
    speed = np.maximum(speed, 1e-9)
    inv = 1.0 / speed
    # omega_hat x v_hat; its norm is sin(angle between axis and relative
    # velocity): only the perpendicular spin component makes lift.
    ax, ay, az = axis[0], axis[1], axis[2]
    cx = (ay * rz - az * ry) * inv
    cy = (az * rx - ax * rz) * inv
    cz = (ax * ry - ay * rx) * inv
    sin_ax = np.sqrt(cx * cx + cy * cy + cz * cz)
    rad = p["radius"]
    s = rad * omega * sin_ax * inv
    re = p["re_per_speed"] * speed
    cd, cl = p["coef"](s, re)
    k = p["k"]  # rho A / (2 m)
    fd = k * cd * speed
    fl = k * cl * speed * speed / np.maximum(sin_ax, 1e-12)
    out = np.empty_like(state)
    out[0] = vx
    out[1] = vy
    out[2] = vz
    out[3] = -fd * rx + fl * cx
    out[4] = -fd * ry + fl * cy
    out[5] = -fd * rz + fl * cz - p["g"]
    out[6] = -p["lam"] * speed * omega / rad
    return out


def _rk4(state, dt, p, k1=None):
    if k1 is None:
        k1 = _derivs(state, p)
    k2 = _derivs(state + 0.5 * dt * k1, p)
    k3 = _derivs(state + 0.5 * dt * k2, p)
    k4 = _derivs(state + dt * k3, p)
    return state + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def _subset(p, idx):
    q = dict(p)
    for key in ("wind", "axis"):
        q[key] = p[key][:, idx]
    for key in ("re_per_speed", "radius", "k", "lam"):
        q[key] = p[key][idx]
    return q


def _hermite_root(z0, z1, dz0, dz1, h):
    """Fraction s in [0, 1] where the cubic Hermite through (z0,dz0),(z1,dz1) is 0."""
    s = z0 / np.where(z0 - z1 == 0, 1e-300, z0 - z1)  # linear guess
    s = np.clip(s, 0.0, 1.0)
    for _ in range(6):  # Newton on the cubic
        h00 = 2 * s**3 - 3 * s**2 + 1
        h10 = s**3 - 2 * s**2 + s
        h01 = -2 * s**3 + 3 * s**2
        h11 = s**3 - s**2
        f = h00 * z0 + h10 * h * dz0 + h01 * z1 + h11 * h * dz1
        d00 = 6 * s**2 - 6 * s
        d10 = 3 * s**2 - 4 * s + 1
        d01 = -6 * s**2 + 6 * s
        d11 = 3 * s**2 - 2 * s
        df = d00 * z0 + d10 * h * dz0 + d01 * z1 + d11 * h * dz1
        s = np.clip(s - f / np.where(df == 0, -1e-300, df), 0.0, 1.0)
    return s


def fly(
    ball_speed,
    launch_angle,
    spin_rate,
    spin_axis=0.0,
    launch_direction=0.0,
    *,
    temperature=288.15,
    pressure=None,
    relative_humidity=0.5,
    altitude=0.0,
    wind=(0.0, 0.0, 0.0),
    ball_mass=BALL_MASS,
    ball_radius=BALL_RADIUS,
    model=DEFAULT_MODEL,
    spin_decay=None,
    gravity=G0,
    dt=0.02,
    t_max=15.0,
    return_trajectories=False,
):
    """Fly golf shots from launch to landing (carry), all shots at once.

    Parameters
    ----------
    ball_speed : array_like
        Ball speed at launch, m/s.
    launch_angle : array_like
        Vertical launch angle above horizontal, rad.
    spin_rate : array_like
        Total spin rate at launch, rad/s (>= 0).  ``rpm * pi / 30``.
    spin_axis : array_like, optional
        Spin-axis tilt, rad.  0 = pure backspin; positive = tilted right,
        lift leans right, ball curves right (fade/slice for a right-hander).
    launch_direction : array_like, optional
        Horizontal launch direction, rad; positive = right of the target line.
    temperature : array_like, optional
        Air temperature, K.  Default 288.15 K (15 degC).  Not lapsed with
        altitude.
    pressure : array_like or None, optional
        Station air pressure, Pa.  ``None`` (default) = ISA pressure at
        ``altitude`` (:func:`pressure_at_altitude`).  If given, ``altitude``
        is not used.
    relative_humidity : array_like, optional
        Relative humidity, fraction 0-1.  Default 0.5.
    altitude : array_like, optional
        Height of the tee above sea level, m (used only when ``pressure`` is
        None).
    wind : array_like, shape (3,) or (..., 3), optional
        Wind velocity (m/s) in the public frame: (toward target, toward the
        right, up).  ``(-5, 0, 0)`` is a 5 m/s headwind.  Uniform with height.
    ball_mass, ball_radius : array_like, optional
        kg and m.  Defaults are the R&A/USGA limits (45.93 g, 42.67 mm).
    model : str, optional
        Aerodynamic model, a key of :data:`MODELS`.  Default
        ``"smits_smith_1994"``.
    spin_decay : float or None, optional
        Spin-decay constant ``lam`` of :func:`spin_decay_rate`; ``None`` uses
        the model's (2.0e-5, Smits & Smith); 0 disables spin decay.
    gravity : float, optional
        m/s^2.
    dt : float, optional
        RK4 step, s.  The landing and apex are located inside the step
        (cubic Hermite + a partial RK4 step); at the default 0.02 s the
        carry of a driver differs from a 0.001 s run by < 1e-6 m.
    t_max : float, optional
        Flights still airborne at ``t_max`` are reported as NaN.
    return_trajectories : bool, optional
        Also return the sampled trajectories (public frame).

    Returns
    -------
    dict of ndarray
        Shaped like the broadcast inputs:

        ``carry_distance`` (m) -- horizontal distance from tee to the landing
        point (where the ball comes back to tee height), along the ground,
        ``sqrt(x^2 + y^2)``.
        ``carry_x`` (m) -- landing point along the target line.
        ``offline_distance`` (m) -- landing point, positive right of the
        target line.
        ``apex_height`` (m) -- maximum height above the tee.
        ``landing_angle`` (rad) -- descent angle below horizontal at landing
        (ground-relative velocity).
        ``flight_time`` (s).
        ``landing_speed`` (m/s) and ``landing_spin`` (rad/s).

        With ``return_trajectories=True`` also ``t`` (n_steps,) and ``x``,
        ``y`` (positive right), ``z``, ``vx``, ``vy``, ``vz`` (ground-relative
        velocity, public frame) of shape (n_shots, n_steps), sampled every
        ``dt``; the sample in which a shot lands is replaced by its exact
        landing state and later samples repeat it.  Shots are flattened in C
        order of the broadcast shape.

    Notes
    -----
    Point-mass equations of motion (right-handed internal frame, y left)::

        m dv/dt = -m g z_hat - q A CD v_r_hat + q A CL (w_hat x v_r_hat)/|w_hat x v_r_hat|
        q = rho |v_r|^2 / 2,  v_r = v - wind,  A = pi R^2
        d omega/dt = -lam (rho/1.225) |v_r| omega / R

    with ``S = R omega |w_hat x v_r_hat| / |v_r|`` (only the spin component
    perpendicular to the air-relative velocity makes lift) and
    ``Re = rho |v_r| 2R / mu(T)``.  The spin axis ``w_hat`` is fixed in space
    (gyroscopic stability), set at launch perpendicular to the launch
    velocity and rotated by ``spin_axis`` about it.

    Integration: classical RK4 with fixed step ``dt`` on all shots at once;
    shots that have landed are dropped from the working set.  For each shot
    the zero crossing of z inside the last step is found on the cubic Hermite
    interpolant and a partial RK4 step is taken to it (twice, Newton-refined),
    giving the landing state to RK4 accuracy.  The apex uses the Hermite
    interpolant of z.

    Examples
    --------
    >>> import numpy as np
    >>> r = fly(74.7, np.radians(10.9), 2686 * np.pi / 30)
    >>> float(r["carry_distance"]) > 200
    True
    """
    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; choose from {sorted(MODELS)}")
    coef_fn, lam_default = MODELS[model]
    lam = lam_default if spin_decay is None else float(spin_decay)

    wind = np.asarray(wind, dtype=float)
    if wind.shape[-1] != 3:
        raise ValueError("wind must have a last axis of length 3")
    if pressure is None:
        pressure = pressure_at_altitude(altitude)
    b = np.broadcast_arrays(
        *[np.asarray(a, dtype=float) for a in (
            ball_speed, launch_angle, spin_rate, spin_axis, launch_direction,
            temperature, pressure, relative_humidity, ball_mass, ball_radius,
        )],
        wind[..., 0],
    )
    shape = b[0].shape
    v0, th, w0, alpha, psi, temp, pres, rh, mass, rad = (a.ravel() for a in b[:10])
    n = v0.size
    wind_b = np.broadcast_to(wind, shape + (3,)).reshape(n, 3).copy()
    wind_b[:, 1] *= -1.0  # public y-right -> internal y-left
    if np.any(v0 <= 0) or np.any(w0 < 0):
        raise ValueError("ball_speed must be > 0 and spin_rate >= 0")

    rho = air_density(temp, pres, rh)
    mu = air_viscosity(temp)
    area = np.pi * rad**2

    # Launch velocity (internal frame, azimuth phi positive to the LEFT).
    phi = -psi
    ct, st, cp, sp = np.cos(th), np.sin(th), np.cos(phi), np.sin(phi)
    vhat = np.stack([ct * cp, ct * sp, st], axis=1)
    # Backspin axis: horizontal, pointing to the right of the velocity.
    rhat = np.stack([sp, -cp, np.zeros(n)], axis=1)
    uhat = np.cross(rhat, vhat)  # "up" perpendicular to v
    axis = np.cos(alpha)[:, None] * rhat - np.sin(alpha)[:, None] * uhat

    params = {
        "wind": np.ascontiguousarray(wind_b.T),
        "axis": np.ascontiguousarray(axis.T),
        "re_per_speed": rho * 2.0 * rad / mu,
        "radius": rad,
        "k": rho * area / (2.0 * mass),
        "lam": lam * rho / _RHO_REF,
        "g": float(gravity),
        "coef": coef_fn,
    }

    state = np.zeros((7, n))
    state[3:6] = (v0[:, None] * vhat).T
    state[6] = w0

    carry_x = np.full(n, np.nan)
    carry_y = np.full(n, np.nan)
    t_land = np.full(n, np.nan)
    v_land = np.full((3, n), np.nan)
    w_land = np.full(n, np.nan)
    apex = np.where(state[5] <= 0, 0.0, np.nan)  # launched flat/down: apex at tee

    active = np.arange(n)
    t = 0.0
    n_steps = int(np.ceil(t_max / dt))
    if return_trajectories:
        traj = np.full((6, n, n_steps + 1), np.nan)
        traj[:, :, 0] = state[0:6]
    p = params
    s0 = state
    last_step = 0
    for step in range(n_steps):
        if active.size == 0:
            break
        last_step = step
        k1 = _derivs(s0, p)
        s1 = _rk4(s0, dt, p, k1)
        t += dt

        # Apex: vz changes sign within the step.
        up = (s0[5] > 0) & (s1[5] <= 0)
        if np.any(up):
            iu = np.nonzero(up)[0]
            pu = _subset(p, iu)
            d1 = _derivs(s1[:, iu], pu)
            z0, z1 = s0[2, iu], s1[2, iu]
            vz0, vz1 = s0[5, iu], s1[5, iu]
            # root of vz on its Hermite interpolant, then z there.
            sf = _hermite_root(vz0, vz1, k1[5, iu], d1[5], dt)
            h00 = 2 * sf**3 - 3 * sf**2 + 1
            h10 = sf**3 - 2 * sf**2 + sf
            h01 = -2 * sf**3 + 3 * sf**2
            h11 = sf**3 - sf**2
            zap = h00 * z0 + h10 * dt * vz0 + h01 * z1 + h11 * dt * vz1
            apex[active[iu]] = np.maximum(zap, np.maximum(z0, z1))

        # Landing: z crosses 0 going down (after leaving the tee).
        down = (s1[2] <= 0.0) & (s1[5] < 0.0)
        if np.any(down):
            idx = np.nonzero(down)[0]
            pi_ = _subset(p, idx)
            sd = s0[:, idx]
            sf = _hermite_root(sd[2], s1[2, idx], sd[5], s1[5, idx], dt)
            tau = sf * dt
            sl = _rk4(sd, tau, pi_)
            for _ in range(2):  # Newton refine on the exact RK4 sub-step
                tau = tau - sl[2] / np.where(sl[5] == 0, -1e-12, sl[5])
                tau = np.clip(tau, 0.0, dt)
                sl = _rk4(sd, tau, pi_)
            g_idx = active[idx]
            carry_x[g_idx] = sl[0]
            carry_y[g_idx] = sl[1]
            t_land[g_idx] = t - dt + tau
            v_land[:, g_idx] = sl[3:6]
            w_land[g_idx] = sl[6]
            if return_trajectories:
                s1[:, idx] = sl
        if return_trajectories:
            traj[:, active, step + 1] = s1[0:6]
        if np.any(down):
            keep = ~down
            active = active[keep]
            s0 = s1[:, keep]
            p = _subset(p, keep)  # boolean mask works as an index too
        else:
            s0 = s1

    # Shots that land while still rising (not physical for golf, but possible
    # for wind-blown lobs) would have no apex; use the launch height (0).
    apex = np.where(np.isnan(apex), 0.0, apex)
    apex = np.where(np.isnan(t_land), np.nan, apex)

    vh = np.hypot(v_land[0], v_land[1])
    out = {
        "carry_distance": np.hypot(carry_x, carry_y).reshape(shape),
        "carry_x": carry_x.reshape(shape),
        "offline_distance": (0.0 - carry_y).reshape(shape),
        "apex_height": apex.reshape(shape),
        "landing_angle": np.arctan2(-v_land[2], vh).reshape(shape),
        "flight_time": t_land.reshape(shape),
        "landing_speed": np.sqrt(np.sum(v_land**2, axis=0)).reshape(shape),
        "landing_spin": w_land.reshape(shape),
    }
    if return_trajectories:
        traj = traj[:, :, : last_step + 2]
        # freeze landed shots at their landing point
        fills = (carry_x, carry_y, np.zeros(n), v_land[0], v_land[1], v_land[2])
        for c, fill in enumerate(fills):
            comp = traj[c]
            bad = np.isnan(comp) & ~np.isnan(carry_x)[:, None]
            comp[bad] = np.broadcast_to(fill[:, None], comp.shape)[bad]
        out["t"] = np.arange(traj.shape[2]) * dt
        out["x"] = traj[0]
        out["y"] = -traj[1]
        out["z"] = traj[2]
        out["vx"] = traj[3]
        out["vy"] = -traj[4]
        out["vz"] = traj[5]
    return out
