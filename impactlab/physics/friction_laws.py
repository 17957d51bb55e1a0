"""Friction laws of the ball-face pair: the Coulomb coefficient an impact sees, from what friction depends on.

Every model of impactlab takes one Coulomb coefficient mu per case (the ``friction`` input, the paper's measured
sled value). The law here replaces it by the coefficient that follows from the pair's physics over the case's
own Hertz contact history, so that the same ball on the same face grips differently at a driver's load and a
wedge's, on a wet face or a dry one, and with a soft cover or a hard one. Option ``friction_law`` of each model
selects it; ``"coulomb"`` (the default) keeps the input coefficient, today's model exactly.

The law (``"adhesion"``) is Bowden & Tabor's two-term friction, an adhesion term on the real contact area and a
ploughing (deformation) term, each written for an elastomer cover on a rough, possibly wet face:

* Adhesion: the interface carries a shear strength tau over the real area of contact A_r, a force tau A_r.
  On a rough face with r.m.s. slope s the cover touches only the asperities' tops; Persson's contact theory
  (Persson 2001; small-slope, elastic) gives the real area fraction under a local pressure p as
  erf(sqrt(2) p / (E_c* s)), with E_c* = E_c / (1 - nu^2) the cover's modulus: the asperities indent the cover,
  micrometres deep, not the core. Over the Hertz pressure of the contact, p(r) = p_0 sqrt(1 - r^2 / a^2),

      A_r = pi a^2 Phi(k),  k = sqrt(2) p_0 / (E_c* s),
      Phi(k) = erf(k) (1 - 1 / (2 k^2)) + exp(-k^2) / (k sqrt(pi))   (the area integral, done here by parts),

  Phi -> 1 on a smooth face (s -> 0: the real area is the Hertz area, and mu = tau / p_mean falls with load as
  N^(-1/3), Schallamach 1952) and Phi -> 4 k / (3 sqrt(pi)) at light load on a rough one (mu = sqrt(8/pi) tau /
  (E_c* s), independent of load: the cover's modulus sets the friction). The law's adhesion coefficient is the
  ratio of the adhesion's impulse to the normal impulse over the elastic Hertz history,

      mu_a = int tau A_r dt / int F dt,

  the coefficient that gives the same tangential impulse where the ball slides throughout (exact there, and
  sliding is where mu matters).
* Ploughing: the face's asperities, of slope s, deform the viscoelastic cover as they slide through it; Greenwood
  & Tabor's hysteresis friction of a hard asperity on a lossy solid is mu_p = (3/16) alpha a/R (Greenwood & Tabor
  1958; the same estimate as the rolling law, :mod:`impactlab.physics.ball_laws`), with a/R the asperity's contact
  slope, taken as s, and alpha = 1 - e_ball^2 the cover's loss fraction (no free parameter).
* Water: a film of thickness h_0 on the face must be squeezed out before the asperities touch the cover. Reynolds'
  squeeze film under the contact's mean pressure p_m thins as d(h^-2)/dt = 2 p_m k_d / eta, with k_d = 2 / (3 a^2)
  for the disc of the contact draining at its edge and 1 / (4 b^2) for the strips between grooves of half-land b
  draining into them (the faster of the two; Hamrock et al. 2004, ch. 16). Adhesion acts once the film is thinner
  than the face's r.m.s. roughness R_q (the asperities pierce it); ploughing acts throughout (Greenwood & Tabor
  1958: deformation friction survives lubrication). eta = 1.0 mPa s (water at 20 degC).
* Sliding speed: frictional heat raises the interface's temperature (Blok's and Jaeger's flash temperature): a
  heat flux q = mu p_m v for a time t into the two bodies raises their common surface by
  dT = 2 q sqrt(t) / (sqrt(pi) (e_c + e_f)), e = sqrt(k rho c) the thermal effusivities of cover and face. A
  thermoplastic's shear strength falls as its surface nears melting (Bowden & Tabor 1964, ch. 9; Lancaster 1971);
  taking it linear, tau (1 - dT / dT_s) with dT_s the rise to the cover's melting point, the adhesion coefficient
  that heats itself is mu_a / (1 + K mu_a / dT_s) with K = 2 p_m v sqrt(t_c) / (sqrt(pi) (e_c + e_f)), p_m the
  impulse-weighted mean pressure, v = |V_slip| / 2 the mean slip of a contact whose slip falls to zero and t_c
  the contact time. dT_s = inf (no melting cover given) switches it off.

The coefficient only ever replaces mu by a non-negative number, and each model's friction does no positive work
for any mu >= 0 (Coulomb's cone): the law dissipates, never creates energy.

References
----------
F. P. Bowden, D. Tabor, *The Friction and Lubrication of Solids*, Part I (1950) and Part II (1964), Oxford.
B. N. J. Persson, Theory of rubber friction and contact mechanics, J. Chem. Phys. 115 (2001) 3840-3861; the real
area of contact, eq. (40) and its small-load limit A/A_0 = sqrt(8/pi) p/(E* s) (cf. Hyun et al. 2004).
A. Schallamach, The load dependence of rubber friction, Proc. Phys. Soc. B 65 (1952) 657-661.
J. A. Greenwood, D. Tabor, The friction of hard sliders on lubricated rubber: the importance of deformation losses,
Proc. Phys. Soc. 71 (1958) 989-1001.
H. Blok, Theoretical study of temperature rise at surfaces of actual contact under oiliness lubricating conditions,
Proc. Inst. Mech. Eng. (1937); J. C. Jaeger, Moving sources of heat and the temperature at sliding contacts,
J. Proc. R. Soc. N.S.W. 76 (1942) 203-224.
J. K. Lancaster, Estimation of the limiting PV relationships for thermoplastic bearing materials, Tribology 4 (1971)
82-86.
B. J. Hamrock, S. R. Schmid, B. O. Jacobson, *Fundamentals of Fluid Film Lubrication*, 2nd ed., Dekker (2004),
ch. 16 (squeeze films: parallel circular disc and infinitely long plates).
"""

from __future__ import annotations

import functools

import numpy as np
from scipy import special

from . import hertz

#: friction laws a model's ``friction_law`` option may name
FRICTION_LAWS = ("coulomb", "adhesion")
#: viscosity of water at 20 degC [Pa s] (handbook value)
WATER_VISCOSITY = 1.0e-3
#: points of the scaled Hertz history the law integrates over
HISTORY_POINTS = 400
#: the inputs the adhesion law reads (all optional inputs of the models; their defaults below)
LAW_INPUTS = ("ball_shear_strength", "ball_cover_modulus", "ball_cover_melt_rise", "ball_cover_effusivity",
              "face_roughness_slope", "face_roughness", "face_groove_land", "face_water_film", "face_effusivity")
#: what a missing cover input means: the cover does not melt. The face's surface has no default: a face is never
#: assumed smooth and dry (the models refuse a case without one, models/_common.law_friction)
SURFACE_DEFAULTS = {"ball_cover_melt_rise": np.inf}


def area_fraction(k):
    """Phi(k): the real contact area of a Hertz pressure on a rough face over the Hertz area pi a^2 [1].

    Phi(k) = int_0^1 2 w erf(k w) dw = erf(k) (1 - 1/(2 k^2)) + exp(-k^2) / (k sqrt(pi)), k = sqrt(2) p_0 /
    (E_c* s) (module docstring; Persson 2001). Phi(inf) = 1 (a smooth face: the whole Hertz area), Phi(k) ->
    4 k / (3 sqrt(pi)) as k -> 0. Below k = 0.05, where the closed form cancels, the series of erf integrated term
    by term: 4 k / (3 sqrt(pi)) (1 - k^2/5 + 3 k^4/70 - k^6/126).
    """
    k = np.asarray(k, float)
    small = k < 0.05
    safe = np.where(small, 1.0, k)
    closed = special.erf(safe) * (1.0 - 0.5 / safe**2) + np.exp(-safe**2) / (safe * np.sqrt(np.pi))
    k2 = np.where(small, k, 0.0) ** 2
    series = 4.0 * np.where(small, k, 0.0) / (3.0 * np.sqrt(np.pi)) * (
        1.0 - k2 / 5.0 + 3.0 * k2**2 / 70.0 - k2**3 / 126.0)
    return np.where(np.isinf(k), 1.0, np.where(small, series, closed))


@functools.lru_cache(maxsize=1)
def _history():
    """Midpoints tau and weights of the elastic Hertz history h(tau) over the contact (scaled time)."""
    edges = np.linspace(0.0, hertz.TAU_CONTACT, HISTORY_POINTS + 1)
    tau = 0.5 * (edges[1:] + edges[:-1])
    h = hertz.scaled_approach(tau)
    return tau, h, np.diff(edges)


def hertz_means(effective_mass, radius, modulus, normal_speed):
    """Scales of the elastic Hertz impact: (a_max [m], p_0 max [Pa], impulse-weighted mean pressure [Pa], t_c [s]).

    p_0 = 2 E* a / (pi R) is the central pressure; the mean pressure F / (pi a^2) = (2/3) p_0, weighted by the
    normal force over the history: int F p_m dt / int F dt.
    """
    approach = hertz.max_approach(effective_mass, radius, modulus, normal_speed)
    a_max = np.sqrt(radius * approach)
    p0 = 2.0 * modulus * a_max / (np.pi * radius)
    _, h, weight = _history()
    weighted = np.sum(h**2 * weight) / np.sum(h**1.5 * weight)  # int h^(3/2) h^(1/2) / int h^(3/2)
    return a_max, p0, (2.0 / 3.0) * p0 * weighted, hertz.TAU_CONTACT * approach / normal_speed


def adhesion_friction(shear_strength, cover_modulus, cover_poisson, roughness_slope, effective_mass, radius,
                      modulus, normal_speed, roughness=0.0, groove_land=np.inf, water_film=0.0):
    """Adhesion coefficient mu_a = int tau A_r dt / int F dt over the elastic Hertz history, with a water film [1].

    Parameters
    ----------
    shear_strength : array_like
        Interfacial shear strength tau of cover and face [Pa].
    cover_modulus, cover_poisson : array_like
        The cover's Young's modulus E_c [Pa] and Poisson's ratio [1] (E_c* = E_c / (1 - nu^2), rigid face).
    roughness_slope : array_like
        r.m.s. slope s of the face [1]; 0 for a smooth face (real area = Hertz area).
    effective_mass, radius, modulus, normal_speed : array_like
        m* [kg], the relative radius R [m], E* of ball and face [Pa] and the normal approach speed [m/s].
    roughness : array_like
        r.m.s. roughness R_q of the face [m]: a water film thinner than it no longer stops adhesion.
    groove_land : array_like
        Half the land between grooves b [m] (the drainage length into them); inf: no grooves.
    water_film : array_like
        Water film on the face before impact h_0 [m]; 0: dry (adhesion throughout).

    Returns
    -------
    mu_a : ndarray
        The adhesion coefficient [1].
    wet_fraction : ndarray
        The fraction of the normal impulse during which the film still separates cover and face [1].
    """
    shape = np.broadcast(shear_strength, cover_modulus, roughness_slope, normal_speed, water_film, roughness,
                         groove_land).shape

    def column(value):
        return np.broadcast_to(np.asarray(value, float), shape).copy()

    a_max, p0, _, _ = hertz_means(effective_mass, radius, modulus, normal_speed)
    a_max, p0 = column(a_max), column(p0)
    stiffness = column(cover_modulus) / (1.0 - column(cover_poisson) ** 2)
    slope, film = column(roughness_slope), column(water_film)
    with np.errstate(divide="ignore"):
        load = np.where(slope > 0.0, np.sqrt(2.0) * p0 / (stiffness * slope), np.inf)  # k at the peak, h = 1
    _, h, weight = _history()
    force_integral = np.sum(h**1.5 * weight)
    area = dry_area_integral(load)  # int A_r dt / (pi a_max^2 T), dry
    wet = np.zeros(shape)
    rows = film > 0.0
    if np.any(rows):  # the squeeze film: adhesion from the instant it clears, for the wet cases only
        col = (lambda value: column(value)[rows][:, None])
        first = _clearing_index(h, weight, a_max[rows][:, None], p0[rows][:, None], film[rows][:, None],
                                col(roughness), col(groove_land), col(normal_speed), col(radius))
        force_before, area_before, area_total = _cumulative_tables(load[rows], first)
        area[rows] = area_total - area_before
        wet[rows] = force_before / force_integral
    # pi a_max^2 / F_max = 1 / p_mean,max = (3/2) / p0
    mu = column(shear_strength) * 1.5 / p0 * area / force_integral
    return mu, wet


#: log-spaced peak loads k of the tabulated dry area integral; below the first: the series, above the last: Phi = 1
_TABLE_RANGE, _TABLE_POINTS = (1e-3, 1e4), 3000


@functools.lru_cache(maxsize=1)
def _area_table():
    """(log k, log int h Phi(k sqrt h) dtau) on the history's midpoints, and the moments int h^(n/2) dtau."""
    _, h, weight = _history()
    loads = np.geomspace(*_TABLE_RANGE, _TABLE_POINTS)
    values = np.array([np.sum(h * area_fraction(k * np.sqrt(h)) * weight) for k in loads])
    moments = {n: float(np.sum(h ** (n / 2.0) * weight)) for n in (2, 3, 5, 7)}
    return np.log(loads), np.log(values), moments


def dry_area_integral(load):
    """int h Phi(k sqrt(h)) dtau over the Hertz history (the dry real area's time integral, scaled) [1].

    ``load`` is k at the peak, sqrt(2) p_0,max / (E_c* s). Tabulated once on 3000 log-spaced loads (1e-3 to 1e4;
    linear in the logarithms, relative error below 3e-6); below, the series of :func:`area_fraction` integrated
    term by term over the history (exact to k^8); above, Phi = 1 (the Hertz area, error below 1e-8).
    """
    log_k, log_value, moments = _area_table()
    k = np.asarray(load, float)
    low, high = k < _TABLE_RANGE[0], k > _TABLE_RANGE[1]
    inner = np.exp(np.interp(np.log(np.clip(k, *_TABLE_RANGE)), log_k, log_value))
    small = np.where(low, k, 0.0)
    series = 4.0 * small / (3.0 * np.sqrt(np.pi)) * (moments[3] - small**2 / 5.0 * moments[5]
                                                     + 3.0 * small**4 / 70.0 * moments[7])
    return np.where(low, series, np.where(high, moments[2], inner))


def _clearing_index(h, weight, a_max, p0, film, roughness, land, normal_speed, radius):
    """Index of the first history point at which the squeezed water film is thinner than the roughness (adhesion
    acts from there on: the film only thins), or the number of points if it never is. Columns (n, 1) in SI."""
    # scaled time -> seconds: t = tau delta_max / V, delta_max = a_max^2 / R
    seconds = weight * a_max**2 / radius / normal_speed
    root = np.sqrt(h)
    # d(h^-2)/dt = 2 p_m k_d / eta, p_m = (2/3) p0 sqrt(h), k_d the faster of disc (2 / (3 a^2)) and strips (1/(4 b^2))
    drain = np.maximum(2.0 / (3.0 * a_max**2) / root, root / (4.0 * land**2))
    growth = np.cumsum((4.0 / 3.0) * p0 / WATER_VISCOSITY * drain * seconds, -1)
    with np.errstate(divide="ignore", over="ignore"):
        needed = np.where(roughness > 0.0, roughness**-2.0, np.inf) - film**-2.0  # growth at which h = R_q
    cleared = growth >= needed
    return np.where(np.any(cleared, -1), np.argmax(cleared, -1), h.size)


#: log-spaced peak loads k of the cumulative tables of the wet cases
_CUMULATIVE_POINTS = 600


@functools.lru_cache(maxsize=1)
def _cumulative():
    """(log k, area (K, N + 1), force (N + 1)): int_0^tau_i of h Phi(k sqrt h) and of h^(3/2) over the history."""
    _, h, weight = _history()
    loads = np.geomspace(*_TABLE_RANGE, _CUMULATIVE_POINTS)
    area = np.concatenate([np.zeros((loads.size, 1)), np.cumsum(
        h * area_fraction(loads[:, None] * np.sqrt(h)) * weight, -1)], -1)
    force = np.concatenate([[0.0], np.cumsum(h**1.5 * weight)])
    return np.log(loads), area, force


def _cumulative_tables(load, first):
    """Per case: int_0^tau_first h^(3/2) dtau, int_0^tau_first h Phi(k sqrt h) dtau and the latter over the whole
    contact (the force and the dry real area before the film clears, and the area's total). Linear in log k
    between table rows; proportional to k below the table (Phi linear in k), the last row above it (Phi = 1)."""
    log_k, area, force = _cumulative()
    k = np.asarray(load, float)
    position = np.interp(np.log(np.clip(k, *_TABLE_RANGE)), log_k, np.arange(log_k.size))
    low = np.minimum(np.floor(position).astype(int), log_k.size - 2)
    fraction = position - low

    def at(index):
        value = (1.0 - fraction) * area[low, index] + fraction * area[low + 1, index]
        return np.where(k < _TABLE_RANGE[0], area[0, index] * k / _TABLE_RANGE[0], value)

    return force[first], at(first), at(np.full_like(first, force.size - 1))


def ploughing_friction(roughness_slope, restitution):
    """mu_p = (3/16) alpha s: Greenwood & Tabor's hysteresis friction of asperities of slope s, alpha = 1 - e^2 [1]."""
    alpha = np.clip(1.0 - np.asarray(restitution, float) ** 2, 0.0, 1.0)
    return (3.0 / 16.0) * alpha * np.asarray(roughness_slope, float)


def thermal_factor(mu_adhesion, mean_pressure, slip_speed, contact_time, melt_rise, cover_effusivity,
                   face_effusivity):
    """The adhesion coefficient softened by its own flash temperature, mu_a / (1 + K mu_a / dT_s) [1].

    K = 2 p_m v sqrt(t_c) / (sqrt(pi) (e_c + e_f)) [K] with v = |V_slip| / 2 (module docstring); dT_s = inf: mu_a.

    Parameters
    ----------
    mu_adhesion : array_like
        The cold adhesion coefficient [1].
    mean_pressure : array_like
        Impulse-weighted mean contact pressure [Pa].
    slip_speed : array_like
        Contact-point slip speed at first contact [m/s].
    contact_time : array_like
        [s].
    melt_rise : array_like
        Rise of the interface's temperature at which the cover's shear strength vanishes [K]; inf: none.
    cover_effusivity, face_effusivity : array_like
        sqrt(k rho c) of cover and face [J m^-2 K^-1 s^-1/2].
    """
    mu = np.asarray(mu_adhesion, float)
    rise = np.asarray(melt_rise, float)
    heating = 2.0 * np.asarray(mean_pressure, float) * 0.5 * np.abs(slip_speed) * np.sqrt(contact_time) / (
        np.sqrt(np.pi) * (np.asarray(cover_effusivity, float) + np.asarray(face_effusivity, float)))
    with np.errstate(divide="ignore", invalid="ignore"):
        soften = np.where(np.isinf(rise), 0.0, heating * mu / rise)
    return mu / (1.0 + soften)


def flash_temperature(mu, mean_pressure, slip_speed, contact_time, cover_effusivity, face_effusivity):
    """Rise of the interface's temperature over the contact, 2 mu p_m v sqrt(t_c) / (sqrt(pi) (e_c + e_f)) [K]."""
    return 2.0 * np.asarray(mu, float) * mean_pressure * 0.5 * np.abs(slip_speed) * np.sqrt(contact_time) / (
        np.sqrt(np.pi) * (np.asarray(cover_effusivity, float) + np.asarray(face_effusivity, float)))


def effective_friction(law, inputs, state, restitution=None):
    """The Coulomb coefficient each case's impact sees under ``law`` (``"coulomb"``: the ``friction`` input).

    Parameters
    ----------
    law : str
        One of :data:`FRICTION_LAWS`.
    inputs : mapping
        The case inputs (SI arrays): ``friction`` for ``"coulomb"``; for ``"adhesion"`` the ball's and face's
        elastic constants, ``ball_shear_strength``, ``ball_cover_modulus`` and the surface inputs of
        :data:`LAW_INPUTS` (the face's surface inputs required; a missing melt rise: :data:`SURFACE_DEFAULTS`).
    state : mapping
        The contact state (:func:`impactlab.physics.contact.contact_state`): mobility, normal and slip speed,
        relative radius.
    restitution : array_like, optional
        e of each case; the ball's own e = e - ``club_restitution_gain`` (a wood face's spring-like gain is not
        the cover's) sets the ploughing's loss fraction 1 - e^2. Default 1 (no loss).

    Returns
    -------
    ndarray
        mu per case [1], >= 0. The cover's Poisson ratio is taken as the ball's.
    """
    if law == "coulomb":
        return np.asarray(inputs["friction"], float)
    n = state["normal_speed"].size

    def value(name):
        if name not in inputs and name not in SURFACE_DEFAULTS:
            raise KeyError(f"friction law input {name!r} not given (a face is never assumed smooth and dry)")
        return np.broadcast_to(np.asarray(inputs[name] if name in inputs else SURFACE_DEFAULTS[name], float), (n,))

    modulus = hertz.effective_modulus(inputs["ball_youngs_modulus"], inputs["ball_poisson_ratio"],
                                      inputs["face_youngs_modulus"], inputs["face_poisson_ratio"])
    mass = 1.0 / state["mobility"][:, 2, 2]
    radius, speed = state["contact_radius"], state["normal_speed"]
    slope = value("face_roughness_slope")
    mu_a, _ = adhesion_friction(inputs["ball_shear_strength"], inputs["ball_cover_modulus"],
                                inputs["ball_poisson_ratio"], slope, mass, radius, modulus, speed,
                                value("face_roughness"), value("face_groove_land"), value("face_water_film"))
    rise = value("ball_cover_melt_rise")
    if np.any(np.isfinite(rise)):
        _, _, mean_pressure, duration = hertz_means(mass, radius, modulus, speed)
        mu_a = thermal_factor(mu_a, mean_pressure, state["slip_speed"], duration, rise,
                              value("ball_cover_effusivity"), value("face_effusivity"))
    e = np.ones(n) if restitution is None else np.broadcast_to(np.asarray(restitution, float), (n,))
    gain = np.broadcast_to(np.asarray(inputs.get("club_restitution_gain", 0.0), float), (n,))
    return mu_a + ploughing_friction(slope, e - gain)


def shear_strength_from_sled(friction, cover_modulus, cover_poisson, roughness_slope, restitution):
    """The interfacial shear strength tau [Pa] that a light-load sled friction mu_s on a rough face implies.

    At a sled's load the real contact is in Persson's light-load regime (k << 1 in :func:`area_fraction`), where
    the law gives mu_s = sqrt(8/pi) tau / (E_c* s) + (3/16) (1 - e^2) s, independent of the load; solved for tau:
    tau = (mu_s - mu_p) E_c* s / sqrt(8/pi). This is how the ball presets take tau from Henrikson et al.'s sled
    measurement on a grooved, blasted plate (a fit on that source, not on impact data).

    Parameters
    ----------
    friction : float
        Sled (light-load) friction coefficient on the face [1].
    cover_modulus, cover_poisson : float
        E_c [Pa] and nu [1] of the cover.
    roughness_slope : float
        r.m.s. slope s of the sled's plate [1], > 0.
    restitution : float
        The ball's restitution e (the ploughing's loss fraction 1 - e^2) [1].
    """
    stiffness = cover_modulus / (1.0 - cover_poisson**2)
    ploughing = float(ploughing_friction(roughness_slope, restitution))
    return max(friction - ploughing, 0.0) * stiffness * roughness_slope / np.sqrt(8.0 / np.pi)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["FRICTION_LAWS", "WATER_VISCOSITY", "HISTORY_POINTS", "LAW_INPUTS", "SURFACE_DEFAULTS", "area_fraction",
           "hertz_means", "adhesion_friction", "dry_area_integral", "ploughing_friction", "thermal_factor",
           "flash_temperature", "effective_friction", "shear_strength_from_sled"]
