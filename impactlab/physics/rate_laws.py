"""Ball laws with a speed, time or pressure scale of their own (issue 33), as plain array functions of SI values.

Every other ball law of the package is scale-free: a Hertz-Mindlin-Coulomb impact with a constant restitution has no
speed in it (Maw, Barber & Fawcett 1981: one dimensionless parameter and the normalised incidence), so at a fixed
delivery its spin grows exactly as the club speed. The three laws below each carry a physical scale; each is off at
its vanishing setting (the plain model exactly) and each is measured alone (validation/impact/rate_laws.py).

(a) Viscoelastic normal contact: a standard linear solid under Hertz's contact
------------------------------------------------------------------------------
Relaxation modulus E(t) = E_inf + E_1 exp(-t / tau) (a spring E_inf beside a Maxwell arm E_1, tau), instantaneous
modulus E_0 = E_inf + E_1 and relaxed fraction g = E_1 / E_0. While the contact grows, Lee & Radok's hereditary
integral is exact for a viscoelastic sphere: the elastic Hertz force with the modulus replaced by the relaxation
operator,

    F(t) = (4/3) sqrt(R) int_0^t E(t - s) d(delta^(3/2))/ds ds = (4/3) sqrt(R) E_0 [(1 - g) delta^(3/2) + g z],
    dz/dt = d(delta^(3/2))/dt - z / tau,

and the same form is kept while it shrinks (Ting 1966 gives the exact unloading; the force is set to zero once it
would pull: no adhesion). Scaled by the elastic impact of the instantaneous modulus (delta_0, T_0 = delta_0 / V), the
motion m* delta'' = -F depends on g and theta = tau / T_0 alone; theta ~ tau V^(1/5), so the restitution e(g, theta)
changes with the impact speed, only as V^(1/5) of theta. Limits (closed forms, tested): tau -> 0, the Maxwell arm
relaxes at once: an elastic Hertz impact of E_inf (e = 1, t_c of E_inf); tau -> infinity, it never relaxes: elastic
of E_0 (e = 1, t_c of E_0). Between them the arm dissipates: e < 1, least near theta ~ 1.

In the models the law gives the SHAPE of the restitution against the normal speed: e(v) = e_input e_sls(v) /
e_sls(v_ref), so the restitution input keeps its meaning (the pair's e at the reference normal speed, a head COR
bounded by the Rules) and relaxation_time 0 is the plain model exactly.

(b) Tangential laws with a scale
--------------------------------
- Friction falling with the contact pressure, mu = mu_0 (p_mean / p_ref)^(-n), p_mean = F_max / (pi a_max^2) of the
  elastic Hertz impact, p_ref = 10 MPa: the adhesive (constant-shear-strength) regime of elastomer friction gives
  n = 1 (friction force = tau A), Hertzian multi-asperity contact about 1/3; elastomers on rough surfaces fall with
  load as a power law (Popov et al. 2018, measurement). n = 0: Coulomb, the plain model.
- Friction rising with the sliding speed, mu = mu_0 (u / u_ref)^m, u the impact's slip speed and u_ref = 10 m/s
  (about a driver's, 50 m/s x sin 12 deg). Arakawa measured golf balls' oblique impacts (angular velocity, contact
  force and area; 2014: F = mu N + mu eta dA/dt) and described them in 2017 by a friction stress proportional to the
  sliding speed, F = lambda A u; read as a coefficient, mu = lambda u / p_mean, that is m = 1 together with the
  pressure law above at n = 1. Here m is a parameter of its own, fitted (validation/impact/slip_friction.py). With
  Mindlin's tangential compliance a driver's spin falls as mu rises beyond about 0.1 (the contact grips earlier and its
  spring gives spin back before separation: Maw, Barber & Fawcett 1981), so a friction that grows with the impact's
  speed makes the spin grow more slowly than the speed. m = 0: Coulomb, the plain model. One mu per impact, at its
  own slip scale (as the pressure law; not through the slip's history, as Arakawa's instantaneous u would be): the
  models read the larger of the initial slip and the slip a frictionless impact would leave (the gear effect's slip
  on an off-centre strike with none to begin with). No cap: validated on drivers (u about 6-14 m/s) only; at a
  wedge's 20-30 m/s mu is 2-3 mu_0.
- Tangential compliance with viscous loss of a physical time: a dashpot beside each tangential spring with a fixed
  relaxation time tau_t [s] (Kelvin-Voigt), whose loss factor at the contact's pulse frequency omega = pi / t_c is
  eta = omega tau_t = pi tau_t / t_c: as the contact shortens at higher speed, the cover's shear spring returns
  less of what it stored. tau_t = 0: elastic springs, the plain model. (The compliant models' ``tangential_loss``
  input is that eta held constant, scale-free.)

(c) The normal force's line of action moved by the ball's deformation
---------------------------------------------------------------------
A rigid-body driver model fitted to measured club and ball motion needed the normal force's line about 0.5 mm off
the ball's centre (McNally, McPhee & Henrikson 2020, Proceedings 49:47; a fitted model parameter, not a
measurement); Cross (2002, measurement on bouncing balls) saw the normal force act off-centre. A deformed ball's
offset can only exist while it is deformed: here d = lambda delta(t), proportional to the compression, acting as
the rolling couple of :mod:`.ball_laws` (a couple up to d F_n opposing the relative rolling of ball and face: it only
dissipates). Its impulse-weighted mean over an elastic Hertz history is lambda delta_max int h^(5/2) / int h^(3/2)
(:func:`compression_ratio`). Since delta_max ~ V^(4/5), the spin it removes grows as V^(4/5) relative to the
spin friction gives: the lever-arm law has a speed scale, through the ball's stiffness. lambda = 0: no offset.

References
----------
E. H. Lee and J. R. M. Radok, The contact problem for viscoelastic bodies, J. Appl. Mech. 27 (1960) 438-444.
T. C. T. Ting, The contact stresses between a rigid indenter and a viscoelastic half-space, J. Appl. Mech. 33
(1966) 845-854.
P. C. Chou and L. J. Yang, Contact forces, coefficient of restitution and spin rate of golf ball impact, in Science
and Golf II (1994) 297 (measured e = 0.85 at 20 m/s and 0.78 at 45 m/s; quoted second-hand, issue 33's lit33).
A. R. Penner, The physics of golf: the optimum loft of a driver, Am. J. Phys. 69 (2001) 563 (e = 0.86 - 0.0029
v_n [m/s], a fit to measurements, a model line).
W. McNally, J. McPhee, E. Henrikson, The golf shot simulator, Proceedings 49 (2020) 47 (a 0.5 mm offset, fitted).
R. Cross, Grip-slip behavior of a bouncing ball, Am. J. Phys. 70 (2002) 1093.
V. L. Popov et al., Friction coefficient of elastomers on rough surfaces ..., Tribol. Int. 120 (2018) 376.
"""

from __future__ import annotations

import functools

import numpy as np

from . import hertz

#: the Rules' limit of a club head's COR: 0.822 + 0.008 tolerance (USGA/R&A, since 2004)
HEAD_COR_LIMIT = 0.830
#: the pressure at which a pressure-dependent friction coefficient equals its input mu_0 [Pa]
REFERENCE_PRESSURE = 10e6
#: the slip-speed friction law's reference slip speed [m/s] (module docstring, (b)): mu = mu_0 there
REFERENCE_SLIP_SPEED = 10.0
#: default reference normal speed of the viscoelastic restitution's shape [m/s] (a driver's normal speed)
REFERENCE_SPEED = 40.0
#: steps of the scaled SLS impact (velocity Verlet; error below 1e-5 in e, tests/test_rate_laws.py)
SLS_STEPS = 3000
#: the scaled relaxation times of the tabulated laws (log-spaced); beyond them the closed-form limits
THETA_GRID = np.geomspace(1e-3, 1e3, 121)


def check_head_cor(restitution, limit: float = HEAD_COR_LIMIT) -> None:
    """Refuse a club-ball restitution beyond the Rules' head COR limit (ValueError): a fit reaching the data only
    with such a head is unphysical and is never reported as a result.

    Parameters
    ----------
    restitution : array_like
        The club-ball pair's e at the driver (the head's COR as the pendulum/cannon test measures it) [1].
    limit : float
        0.830 (USGA/R&A: 0.822 plus the test's tolerance 0.008).
    """
    e = np.asarray(restitution, float)
    if np.any(e > limit + 1e-9):
        raise ValueError(f"head COR {float(np.max(e)):.4f} beyond the Rules' limit {limit:.3f}: an unphysical "
                         f"club, refused (fit within the bound, or say the data cannot be reached inside it)")


def sls_scaled(fraction, theta, steps: int = SLS_STEPS):
    """Restitution and scaled contact duration of the Hertz standard-linear-solid impact (module docstring, (a)).

    Integrates h'' = -(5/4) [(1 - g) h^(3/2) + g z], z' = (h^(3/2))' - z / theta, h(0) = 0, h'(0) = 1, z(0) = 0
    (time scaled by T_0 = delta_0 / V, the approach by delta_0, both of the elastic impact of the instantaneous
    modulus) by velocity Verlet, z advanced exactly for h^(3/2) linear over a step (stable for any theta), until h
    returns to 0 or the force would pull.

    Parameters
    ----------
    fraction : array_like
        Relaxed fraction g = E_1 / E_0 of the instantaneous modulus, 0 <= g < 1 [1].
    theta : array_like
        Relaxation time over T_0 [1] (0: relaxed at once; inf: never relaxes).
    steps : int
        Steps over the longest possible contact (that of the relaxed modulus).

    Returns
    -------
    restitution, duration : ndarray
        e = exit speed over approach speed [1]; contact duration over T_0 [1].
    """
    g, theta = np.broadcast_arrays(np.asarray(fraction, float), np.asarray(theta, float))
    g, theta = g.ravel().copy(), theta.ravel().copy()
    if np.any((g < 0.0) | (g >= 1.0)):
        raise ValueError("relaxed fraction g must lie in [0, 1)")
    relaxed = 1.0 - g
    # the longest contact is the relaxed modulus's elastic one, tau_c (1 - g)^(-2/5); 5 % margin
    dt = 1.05 * hertz.TAU_CONTACT * relaxed.min() ** -0.4 / steps
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        decay = np.where(theta > 0.0, np.exp(-dt / np.where(theta > 0.0, theta, 1.0)), 0.0)
        # z gains dp theta / dt (1 - exp(-dt / theta)) of an increment dp spread over the step: 0 when theta = 0,
        # dp when theta = inf
        gain = np.where(np.isinf(theta), 1.0, np.where(theta > 0.0, theta / dt * (1.0 - decay), 0.0))
    decay = np.where(np.isinf(theta), 1.0, decay)
    h, v, z, p = np.zeros_like(g), np.ones_like(g), np.zeros_like(g), np.zeros_like(g)
    a = np.zeros_like(g)
    active = np.ones(g.size, dtype=bool)
    exit_speed, duration = np.zeros_like(g), np.zeros_like(g)
    time = 0.0
    for _ in range(2 * steps):
        h_new = h + v * dt + 0.5 * a * dt * dt
        p_new = np.maximum(h_new, 0.0) ** 1.5
        z_new = z * decay + (p_new - p) * gain
        force = relaxed * p_new + g * z_new
        a_new = -1.25 * np.maximum(force, 0.0)
        v_new = v + 0.5 * (a + a_new) * dt
        ended = active & (v_new < 0.0) & ((h_new <= 0.0) | (force <= 0.0))
        if np.any(ended):
            # the end inside the step: linear in h (touching down) or in the force (letting go)
            old_force = relaxed * p + g * z
            by_h = np.where(h - h_new != 0.0, h / np.where(h - h_new != 0.0, h - h_new, 1.0), 1.0)
            by_f = np.where(old_force - force != 0.0, old_force / np.where(old_force - force != 0.0,
                                                                          old_force - force, 1.0), 1.0)
            frac = np.clip(np.where(h_new <= 0.0, by_h, by_f), 0.0, 1.0)
            exit_speed[ended] = -(v + frac * (v_new - v))[ended]
            duration[ended] = time + (frac * dt)[ended]
            active &= ~ended
            if not np.any(active):
                break
        h, v, z, p, a = h_new, v_new, z_new, p_new, a_new
        time += dt
    exit_speed[active], duration[active] = -v[active], time
    return exit_speed, duration


@functools.lru_cache(maxsize=32)
def sls_table(fraction: float) -> tuple[np.ndarray, np.ndarray]:
    """(restitution, scaled duration) of one relaxed fraction g on :data:`THETA_GRID`, computed once per g."""
    e, tau = sls_scaled(np.full(THETA_GRID.size, float(fraction)), THETA_GRID)
    e.setflags(write=False)
    tau.setflags(write=False)
    return e, tau


@functools.lru_cache(maxsize=32)
def _sls_interpolants(fraction: float):
    """Monotone cubic interpolants in log theta of :func:`sls_table` (e, scaled duration), built once per g: building
    them took a fifth of a rigid batch's time when done on every call."""
    from scipy.interpolate import PchipInterpolator

    e_table, tau_table = sls_table(fraction)
    return PchipInterpolator(np.log(THETA_GRID), e_table), PchipInterpolator(np.log(THETA_GRID), tau_table)


def sls_restitution(fraction, relaxation_time, normal_speed, effective_mass, radius, modulus, direct: bool = False):
    """Restitution and contact time of a Hertz standard-linear-solid impact at each case (module docstring, (a)).

    Parameters
    ----------
    fraction : float
        Relaxed fraction g = E_1 / E_0 [1], 0 <= g < 1 (one value for the batch: its table is computed once).
    relaxation_time : array_like
        tau of the Maxwell arm [s] (0: relaxed at once; inf: never relaxes).
    normal_speed, effective_mass, radius, modulus : array_like
        V_n [m/s], m* [kg], relative radius R [m], instantaneous contact modulus E_0* [Pa].

    Returns
    -------
    restitution : ndarray
        e [1] (1 in both limits).
    contact_time : ndarray
        t_c [s] (in the limits Hertz's of E_inf = (1 - g) E_0 and of E_0).

    Notes
    -----
    ``direct``: integrated case by case (:func:`sls_scaled`), else interpolated (monotone cubic in log theta) on
    :func:`sls_table`, agreeing within 2e-4 (tests/test_rate_laws.py); outside the table's range the closed-form
    limit of that side (theta = tau V / delta_0 below 1e-3 or above 1e3, where e differs from 1 by less than
    3e-3 and 1e-3 for g <= 0.9).
    """
    g = float(fraction)
    speed = np.asarray(normal_speed, float)
    approach = hertz.max_approach(effective_mass, radius, modulus, speed)
    t0 = approach / speed
    theta = np.asarray(relaxation_time, float) / t0
    theta, t0 = np.broadcast_arrays(theta, t0)
    if direct:  # integrated case by case (a fit over few cases); the models take the table, so that a case's
        # result never depends on the batch around it
        e, tau = sls_scaled(np.full(theta.size, g), theta.ravel())
        return e.reshape(theta.shape), tau.reshape(theta.shape) * t0
    e_of, tau_of = _sls_interpolants(g)
    x = np.log(np.clip(theta, THETA_GRID[0], THETA_GRID[-1]))
    e, tau = e_of(x), tau_of(x)
    fast, slow = theta < THETA_GRID[0], theta > THETA_GRID[-1]
    e = np.where(fast | slow, 1.0, e)
    tau = np.where(fast, hertz.TAU_CONTACT * (1.0 - g) ** -0.4, np.where(slow, hertz.TAU_CONTACT, tau))
    return e, tau * t0


def restitution_shape(restitution, fraction, relaxation_time, normal_speed, effective_mass, radius, modulus,
                      reference_speed=REFERENCE_SPEED):
    """The restitution input carried to each case's normal speed by the SLS law: e v-dependent [1].

    e(v) = e_input e_sls(v) / e_sls(v_ref) (module docstring, (a)), clipped to [0.05, 1]. relaxation_time 0 or
    fraction 0 returns ``restitution`` unchanged.
    """
    e_in = np.asarray(restitution, float)
    if float(fraction) == 0.0 or np.all(np.asarray(relaxation_time) == 0.0):
        return np.broadcast_to(e_in, np.broadcast(e_in, normal_speed).shape).copy()
    at_speed, _ = sls_restitution(fraction, relaxation_time, normal_speed, effective_mass, radius, modulus)
    at_reference, _ = sls_restitution(fraction, relaxation_time, np.full_like(np.asarray(normal_speed, float),
                                                                              reference_speed),
                                      effective_mass, radius, modulus)
    return np.clip(e_in * at_speed / at_reference, 0.05, 1.0)


def mean_pressure(effective_mass, radius, modulus, normal_speed):
    """Mean contact pressure at the elastic Hertz impact's maximum compression, F_max / (pi R delta_max) [Pa]."""
    approach = hertz.max_approach(effective_mass, radius, modulus, normal_speed)
    return hertz.peak_force(effective_mass, radius, modulus, normal_speed) / (np.pi * radius * approach)


def pressure_friction(friction, exponent, pressure, reference=REFERENCE_PRESSURE):
    """mu = mu_0 (p / p_ref)^(-n) [1] (module docstring, (b)); n = 0 returns mu_0."""
    mu = np.asarray(friction, float)
    n = float(exponent)
    if n == 0.0:
        return np.broadcast_to(mu, np.broadcast(mu, pressure).shape).copy()
    return mu * (np.asarray(pressure, float) / reference) ** (-n)


def slip_friction(friction, exponent, slip_speed, reference=REFERENCE_SLIP_SPEED):
    """Friction rising with the sliding speed, mu = mu_0 (|u| / u_ref)^m [1] (module docstring, (b)).

    Parameters
    ----------
    friction : array_like
        mu_0, the friction coefficient at the reference slip speed [1].
    exponent : float
        m [1]; 0 returns mu_0 (Coulomb); 1 with the pressure law at n = 1 is a friction stress proportional to the
        sliding speed (Arakawa 2017).
    slip_speed : array_like
        The impact's slip speed u [m/s] (its sign, the slip's direction, is ignored; the models pass
        ``impactlab_models.shared.characteristic_slip``).
    reference : float
        u_ref [m/s], 10 m/s by default.

    Returns
    -------
    ndarray
        mu per case [1].

    References
    ----------
    K. Arakawa, Effect of time derivative of contact area on dynamic friction, Appl. Phys. Lett. 104 (2014) 241603
    (measured golf-ball oblique impacts; F = mu N + mu eta dA/dt).
    K. Arakawa, An analytical model of dynamic sliding friction during impact, Sci. Rep. 7 (2017), published
    5 January 2017 (F = lambda A u, compared with the measured angular velocities; abstract read).
    """
    mu = np.asarray(friction, float)
    m = float(exponent)
    if m == 0.0:
        return np.broadcast_to(mu, np.broadcast(mu, slip_speed).shape).copy()
    factor = (np.abs(np.asarray(slip_speed, float)) / reference) ** m
    finite = np.isfinite(mu)
    # no cap stays no cap: inf x 0 at zero slip would be NaN
    return np.where(finite, np.where(finite, mu, 0.0) * factor, mu)


def tangential_loss_of_time(relaxation_time, contact_time):
    """Loss factor eta = pi tau_t / t_c of a tangential dashpot of relaxation time tau_t [s] at the contact's pulse
    frequency pi / t_c [1] (module docstring, (b)); the compliant kernel's ``tangential_loss``."""
    return np.pi * np.asarray(relaxation_time, float) / np.asarray(contact_time, float)


@functools.lru_cache(maxsize=1)
def compression_ratio() -> float:
    """int delta F dt / (delta_max int F dt) of the elastic Hertz impact: int h^(5/2) / int h^(3/2) (0.807)."""
    tau = np.linspace(0.0, hertz.TAU_CONTACT, 20001)
    h = np.clip(hertz.scaled_approach(tau), 0.0, None)
    return float(np.trapezoid(h**2.5, tau) / np.trapezoid(h**1.5, tau))


def compression_arm(lever, effective_mass, radius, modulus, normal_speed):
    """Impulse-weighted mean offset of the normal force's line, lambda delta_max int h^(5/2) / int h^(3/2) [m].

    Parameters
    ----------
    lever : float or array_like
        lambda = d / delta [1] (0: no offset).
    effective_mass, radius, modulus, normal_speed : array_like
        m* [kg], relative radius R [m], E* [Pa], V_n [m/s] of the elastic Hertz impact.
    """
    approach = hertz.max_approach(effective_mass, radius, modulus, normal_speed)
    return np.asarray(lever, float) * compression_ratio() * approach


def arm_factor_of_lever(lever, radius, approach):
    """The compliant kernel's arm factor d / a (per case) whose impulse-weighted offset equals the lever law's.

    The kernel's couple arm is factor x a(t); with a = sqrt(R delta) the lever's mean offset lambda delta_max r_d
    (:func:`compression_ratio`) is matched by factor = lambda r_d delta_max / (r_a a_max), r_a = 0.896 the mean
    radius ratio (:func:`impactlab.physics.ball_laws.mean_radius_ratio`): the mean and its speed scaling (~ V^(2/5)
    of the factor) are kept, the shape in time is that of a.
    """
    from .ball_laws import mean_radius_ratio

    reach = np.sqrt(np.asarray(radius, float) * approach)
    return np.asarray(lever, float) * compression_ratio() * approach / (mean_radius_ratio() * reach)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["HEAD_COR_LIMIT", "REFERENCE_PRESSURE", "REFERENCE_SLIP_SPEED", "REFERENCE_SPEED", "SLS_STEPS",
           "THETA_GRID", "check_head_cor", "sls_scaled", "sls_table", "sls_restitution", "restitution_shape",
           "mean_pressure", "pressure_friction", "slip_friction", "tangential_loss_of_time", "compression_ratio",
           "compression_arm", "arm_factor_of_lever"]
