"""Golf ball flight: a
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

The air (:mod:`impactlab.physics.atmosphere`) and the aerodynamic models and spin decay
(:mod:`impactlab.physics.aerodynamics`), with their references, are in their own modules.
"""

from __future__ import annotations

import numpy as np

from impactlab.physics.aerodynamics import _RHO_REF, BALL_MASS, BALL_RADIUS, DEFAULT_MODEL, MODELS, model_function
from impactlab.physics.atmosphere import G0, air_density, air_viscosity, pressure_at_altitude
from impactlab.physics.flight_numpy import integrate_numpy

__all__ = ["fly", "TOLERANCE", "SAMPLE_INTERVAL"]

#: the compiled integrator's local error tolerance (relative, with an absolute floor of 1 m, 1 m/s, 1 rad/s): the
#: steps it chooses keep the carry within 1 mm of a converged integration (docs/flight.md; measured at most 0.2 um
#: on the smooth models and 0.2 mm on lyu_2018, whose drag jumps at Re 7.5e4: tests/test_flight_kernel.py)
TOLERANCE = 1.0e-8
#: the interval of the sampled paths (``return_trajectories``) and the numpy integrator's fixed step, s
SAMPLE_INTERVAL = 0.02

def _checked_coefficients(function):
    """A caller's ``(S, Re) -> (CD, CL)`` with its answer checked at every call: two finite arrays of the shape
    of S (or scalars) with CD >= 0; anything else is one ValueError naming the function, never a carry of NaN or
    of a ball that drag pushes forward."""
    name = getattr(function, "__name__", repr(function))

    def coefficients(s, re):
        answer = function(s, re)
        try:
            if isinstance(answer, np.ndarray) and answer.shape != (2,) + np.shape(s):
                raise ValueError
            cd, cl = answer
            cd = np.broadcast_to(np.asarray(cd, dtype=float), np.shape(s))
            cl = np.broadcast_to(np.asarray(cl, dtype=float), np.shape(s))
        except (TypeError, ValueError):
            parts = [np.shape(part) for part in answer] if isinstance(answer, (tuple, list)) else np.shape(answer)
            raise ValueError(f"model: the function {name} must return (CD, CL), two arrays of the shape of S "
                             f"{np.shape(s)} or two numbers; it returned a {type(answer).__name__} of shape "
                             f"{parts}") from None
        bad = ~(np.isfinite(cd) & np.isfinite(cl) & (cd >= 0.0))
        if np.any(bad):
            i = int(np.flatnonzero(bad.ravel())[0])
            raise ValueError(f"model: the function {name} returned CD {float(cd.ravel()[i]):.4g}, CL "
                             f"{float(cl.ravel()[i]):.4g} at "
                             f"S {np.ravel(s)[i]:.4g}, Re {np.ravel(re)[i]:.4g}; expected finite values with "
                             f"CD >= 0")
        return cd, cl

    return coefficients


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
    dt=None,
    t_max=15.0,
    return_trajectories=False,
    tolerance=TOLERANCE,
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
    model : str or callable, optional
        Aerodynamic model, a key of :data:`MODELS`.  Default
        ``"measured_fit"`` (:data:`impactlab.physics.aerodynamics.DEFAULT_MODEL`).
        Or a function ``(S, Re) -> (CD, CL)`` of arrays (dimensionless), flown
        with the spin decay of the registered models (``lam`` 2.0e-5, or
        ``spin_decay``) by the numpy integrator; used to fit a coefficient to
        measured flights (:mod:`validation.flight.flight_fit`). Its answer must
        be two finite arrays of the shape of S (or two numbers) with CD >= 0,
        else ValueError.
    spin_decay : float or None, optional
        Spin-decay constant ``lam`` of :func:`spin_decay_rate`; ``None`` uses
        the model's (2.0e-5, Smits & Smith); 0 disables spin decay.
    gravity : float, optional
        m/s^2.
    dt : float or None, optional
        None (default): the compiled integrator chooses its steps for
        ``tolerance`` and the paths are sampled every 0.02 s
        (:data:`SAMPLE_INTERVAL`). A number: no step longer than ``dt`` (s) and
        the paths sampled every ``dt``. The numpy integrator (a callable
        ``model``, or numba off) takes fixed RK4 steps of ``dt`` (0.02 s
        without one).
    t_max : float, optional
        Flights still airborne at ``t_max`` are reported as NaN, as are those
        whose path the compiled integrator's steps cannot follow (a ball that
        stops in the air, where the lift turns at once).
    return_trajectories : bool, optional
        Also return the sampled trajectories (public frame).
    tolerance : float, optional
        The compiled integrator's local error tolerance per step (relative,
        with an absolute floor of 1 in m, m/s and rad/s). The default
        (:data:`TOLERANCE`) keeps the carry within 1 mm of a converged
        integration over the launches of golf (docs/flight.md).

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
        ``dt`` (0.02 s without one); the sample in which a shot lands is its
        exact landing state and later samples repeat it.  Shots are flattened
        in C order of the broadcast shape.

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

    Integration (docs/flight.md): a registered model is flown by the compiled
    kernel (:mod:`impactlab.physics.kernels.flight`), one shot at a time, with
    the Dormand-Prince 5(4) pair and its step chosen for ``tolerance``; the
    landing (z = 0 going down) and the apex (vz = 0) are roots of the
    integrator's own partial steps, found by Newton's method. A callable model
    (or ``IMPACTLAB_KERNELS=numpy``) is flown by the numpy integrator: classical
    RK4 with fixed step ``dt`` on all shots at once, the landing on the cubic
    Hermite interpolant refined by partial RK4 steps. The two agree within
    1e-5 m in carry (tests/test_flight.py).

    Examples
    --------
    >>> import numpy as np
    >>> r = fly(74.7, np.radians(10.9), 2686 * np.pi / 30)
    >>> float(r["carry_distance"]) > 200
    True
    """
    coefficients, lam = _aerodynamics(model, spin_decay)
    shape, shots = _shots(ball_speed, launch_angle, spin_rate, spin_axis, launch_direction, temperature, pressure,
                          relative_humidity, altitude, wind, ball_mass, ball_radius)
    state, params = _launch(shots, lam, gravity)
    every = SAMPLE_INTERVAL if dt is None else float(dt)
    kernel = _kernel_model(model)
    if kernel is not None:
        results, paths = _integrate_kernel(state, params, kernel, every if return_trajectories else 0.0,
                                           np.inf if dt is None else float(dt), t_max, tolerance)
    else:
        params["coef"] = coefficients
        results, paths = integrate_numpy(state, params, every, t_max, return_trajectories)
    return _outputs(results, paths, shape, every, return_trajectories)


def _aerodynamics(model, spin_decay):
    """The coefficient function ``(S, Re) -> (CD, CL)`` of ``model`` (a caller's checked at each call) and the spin
    decay constant lam (the model's, or ``spin_decay``)."""
    if callable(model):
        coefficients, lam_default = _checked_coefficients(model), 2.0e-5
    else:  # model_function refuses a name it does not ship (a retired one with why)
        coefficients, lam_default = model_function(model), MODELS[model][1]
    return coefficients, lam_default if spin_decay is None else float(spin_decay)


def _shots(ball_speed, launch_angle, spin_rate, spin_axis, launch_direction, temperature, pressure,
           relative_humidity, altitude, wind, ball_mass, ball_radius):
    """The launches and their air broadcast together: the broadcast shape and a dict of flat arrays (``wind``
    (n, 3) in the internal frame, y LEFT). ValueError for a wind without 3 components, a speed <= 0 or a spin < 0."""
    wind = np.asarray(wind, dtype=float)
    if wind.shape[-1] != 3:
        raise ValueError("wind must have a last axis of length 3")
    if pressure is None:
        pressure = pressure_at_altitude(altitude)
    names = ("v0", "th", "w0", "alpha", "psi", "temp", "pres", "rh", "mass", "rad")
    b = np.broadcast_arrays(
        *[np.asarray(a, dtype=float) for a in (
            ball_speed, launch_angle, spin_rate, spin_axis, launch_direction,
            temperature, pressure, relative_humidity, ball_mass, ball_radius,
        )],
        wind[..., 0],
    )
    shape = b[0].shape
    shots = {name: array.ravel() for name, array in zip(names, b[:10])}
    n = shots["v0"].size
    shots["wind"] = np.broadcast_to(wind, shape + (3,)).reshape(n, 3).copy()
    shots["wind"][:, 1] *= -1.0  # public y-right -> internal y-left
    if np.any(shots["v0"] <= 0) or np.any(shots["w0"] < 0):
        raise ValueError("ball_speed must be > 0 and spin_rate >= 0")
    return shape, shots


def _launch(shots, lam, gravity):
    """The launch state (7, n) (x y z vx vy vz omega, internal frame) and each shot's air and spin axis."""
    rho = air_density(shots["temp"], shots["pres"], shots["rh"])
    mu = air_viscosity(shots["temp"])
    rad, n = shots["rad"], shots["v0"].size
    area = np.pi * rad**2

    # Launch velocity (internal frame, azimuth phi positive to the LEFT).
    th, phi, alpha = shots["th"], -shots["psi"], shots["alpha"]
    ct, st, cp, sp = np.cos(th), np.sin(th), np.cos(phi), np.sin(phi)
    vhat = np.stack([ct * cp, ct * sp, st], axis=1)
    # Backspin axis: horizontal, pointing to the right of the velocity.
    rhat = np.stack([sp, -cp, np.zeros(n)], axis=1)
    uhat = np.cross(rhat, vhat)  # "up" perpendicular to v
    axis = np.cos(alpha)[:, None] * rhat - np.sin(alpha)[:, None] * uhat

    params = {
        "wind": np.ascontiguousarray(shots["wind"].T),
        "axis": np.ascontiguousarray(axis.T),
        "re_per_speed": rho * 2.0 * rad / mu,
        "radius": rad,
        "k": rho * area / (2.0 * shots["mass"]),
        "lam": lam * rho / _RHO_REF,
        "g": float(gravity),
    }
    state = np.zeros((7, n))
    state[3:6] = (shots["v0"][:, None] * vhat).T
    state[6] = shots["w0"]
    return state, params


def _kernel_model(model):
    """The compiled kernel's ``(number, constants)`` for ``model``, or None: numba off, or a model it cannot fly."""
    if callable(model):
        return None
    from impactlab.physics import kernels  # numba is imported on the first flight, not with impactlab

    if not kernels.HAVE_NUMBA:
        return None
    from impactlab.physics.kernels import flight as kernel

    return kernel.kernel_model(model)


def _integrate_kernel(state, p, kernel, every, max_step, t_max, tolerance):
    """Fly every shot with the compiled kernel: results (n, 9) (landing x y z vx vy vz omega, time, apex; internal
    frame) and paths (n, 6, samples) every ``every`` s (none for 0)."""
    from impactlab.physics.kernels import flight as compiled

    air = np.column_stack([p["wind"].T, p["axis"].T, p["re_per_speed"], p["radius"], p["k"], p["lam"]])
    samples = int(np.ceil(t_max / every)) + 1 if every > 0.0 else 1
    number, constants = kernel
    return compiled.flight_cases(state.T, air, number, constants, p["g"], tolerance, max_step, t_max, every,
                                 samples)


def _outputs(results, paths, shape, every, return_trajectories):
    """The public dict of :func:`fly` from the integrators' results (internal frame, y LEFT)."""
    carry_x, carry_y, t_land, apex = results[:, 0], results[:, 1], results[:, 7], results[:, 8]
    v_land, w_land = results[:, 3:6].T, results[:, 6]
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
        if np.all(np.isfinite(t_land)) and t_land.size:  # to the sample the last shot lands at
            used = int(np.max(np.ceil(t_land / every))) + 1
            paths = paths[:, :, : max(min(used, paths.shape[2]), 2)]
        out["t"] = np.arange(paths.shape[2]) * every
        for c, name in enumerate(("x", "y", "z", "vx", "vy", "vz")):
            out[name] = -paths[:, c] if name in ("y", "vy") else paths[:, c]
    return out
