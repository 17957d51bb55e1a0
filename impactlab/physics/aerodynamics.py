"""A golf ball in the air: its Reynolds number and spin ratio, the published drag and lift models, and the spin
decay (plain numpy, SI units; every function broadcasts its inputs).

Used by the trajectory integrator :func:`impactlab.physics.flight.fly`; docs/flight.md has the models, their
validation and what failed.

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
.. [Ly20] B. Lyu, J. Kensrud, L. Smith, "The reverse Magnus effect in golf
   balls", Sports Engineering 23:3 (2020), doi:10.1007/s12283-020-0318-1
   (CC BY): lift and drag of a Pro V1, a Chrome Soft and a B330-RX across
   their drag crisis (free flight, light gates).
.. [Na04] T. Naruo, T. Mizota, H. Shimozono, "Aerodynamic force measurement of
   highly spinning golf ball in uniform flow and trajectory experiment", Trans.
   JSME B 70(697):2371-2377 (2004), doi:10.1299/kikaib.70.2371: CD and CL of a
   commercial ball (Bridgestone Skyway SD432) at S 0.03-1.13, wind tunnel.
.. [BH76] P. W. Bearman and J. K. Harvey, "Golf ball aerodynamics",
   Aeronautical Quarterly 27:112-122 (1976): wind tunnel, spinning model,
   S up to 1.0.
.. [Na08] A. M. Nathan, "The spin decay of a baseball" (2008),
   baseball.physics.illinois.edu/spindown-rev1.pdf -- restates the Smits &
   Smith and Tavares et al. golf spin-decay fits, SRD = -lambda S.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "BALL_MASS",
    "BALL_RADIUS",
    "DEFAULT_MODEL",
    "MODELS",
    "MEASUREMENT_FITS",
    "MEASURED_FIT",
    "MEASURED_FIT_OFFSETS",
    "RETIRED_MODELS",
    "MODEL_REFERENCES",
    "PUBLISHED_MODELS",
    "aero_coefficients",
    "model_fingerprint",
    "model_function",
    "retired_reason",
    "reynolds_number",
    "spin_decay_rate",
    "spin_ratio",
]

BALL_MASS = 0.04593  #: maximum legal ball mass (R&A/USGA Equipment Rules), kg
BALL_RADIUS = 0.021335  #: minimum legal ball radius (42.67 mm diameter), m
_RHO_REF = 1.225  # kg/m^3, ISA sea level; reference density of the spin-decay fit


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


def _select(condition, if_true, if_false):
    """``np.where`` for the coefficient formulas: the compiled flight kernel (:mod:`impactlab.physics.kernels.flight`)
    gives this name a scalar branch, so each formula below is written once and flies both in numpy and compiled."""
    return np.where(condition, if_true, if_false)


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
    cd = _select(re < 7.5e4, cd_low, cd_high)
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


#: ``measured_fit`` constants: least squares on the measurements of impactlab/data/validation/aero_coefficients.yaml
#: only (:func:`validation.flight.aero_fit.fit`; tests/test_flight.py refits and compares). Supercritical lift
#: a S / (1 + b S); supercritical drag c0 + c_re Re/1e5 + k CL_sc^2 (c0 of the modern balls); drag crisis
#: d / (1 + exp((Re - Re_d exp(-m S)) / w_d)), reached at a lower Re the more the ball spins; lift in the crisis times
#: 1 - beta exp(-ln(Re/Re_l)^2 / (2 sigma^2)) exp(-S/s_l).
MEASURED_FIT = {"a": 2.05615, "b": 3.56629, "c0": 0.191258, "c_re": -0.00257435, "k": 1.35502,
                "re_l": 57644.7, "sigma": 0.14871, "beta": 2.09728, "s_l": 0.263919,
                "re_d": 73423.2, "w_d": 3718.75, "d": 0.282182, "m": 1.27341}
#: the supercritical drag offset c0 the same fit gives each measured ball group (the model takes ``modern``)
MEASURED_FIT_OFFSETS = {"modern": 0.191258, "usga_1998": 0.21136, "bh_1976": 0.234607, "naruo_2004": 0.222771,
                        "acushnet_invention": 0.191965, "acushnet_prior_art": 0.199902}


def _crisis_step(s, re):
    # the drag crisis' logistic step 1 / (1 + exp((Re - Re_d exp(-m S)) / w_d)) of measured_fit, no overflow
    return _crisis_formula(s, re, MEASURED_FIT["re_d"], MEASURED_FIT["w_d"], MEASURED_FIT["m"])


def _crisis_formula(s, re, re_d, w_d, m):
    midpoint = re_d * np.exp(-m * s)
    return 0.5 * (1.0 - np.tanh(0.5 * (re - midpoint) / w_d))


def _measured_fit_constants(c0=None):
    """The constants of :data:`MEASURED_FIT` in the order of :func:`_measured_fit_formula`'s arguments (``c0``
    replaced when given): read at each call, so the numpy and the compiled flight fly today's constants."""
    c = dict(MEASURED_FIT) if c0 is None else {**MEASURED_FIT, "c0": c0}
    return (c["a"], c["b"], c["c0"], c["c_re"], c["k"], c["re_l"], c["sigma"], c["beta"], c["s_l"], c["re_d"],
            c["w_d"], c["d"], c["m"])


def _measured_fit_formula(s, re, a, b, c0, c_re, k, re_l, sigma, beta, s_l, re_d, w_d, d, m):
    # measured_fit's formula (aero_coefficients), its constants as arguments: numpy arrays here, scalars compiled
    lift_sc = a * s / (1.0 + b * s)
    cd = c0 + c_re * re / 1.0e5 + k * lift_sc**2 + d * _crisis_formula(s, re, re_d, w_d, m)
    loss = beta * np.exp(-0.5 * (np.log(np.maximum(re, 1.0) / re_l) / sigma) ** 2 - s / s_l)
    return cd, lift_sc * (1.0 - loss)


def _cd_cl_measured_fit(s, re, c0=None):
    # Fitted by impactlab (validation.flight.aero_fit) to measured CD and CL of golf balls: Lyu, Kensrud & Smith 2020
    # and Lyu et al. 2018 (modern balls, free flight), Naruo, Mizota & Shimozono 2004 (wind tunnel, S to 1.13),
    # Acushnet's US 6,729,976 and the USGA's US 6,186,002 (indoor test ranges), Bridgestone's patent tables, Bearman &
    # Harvey 1976 (wind tunnel). Never fitted to TrackMan's tables.
    return _measured_fit_formula(s, re, *_measured_fit_constants(c0))


def _cd_cl_measured_fit_usga_ball(s, re):
    # NOT a validated choice: measured_fit with the drag level the fit gives the 1998 USGA ITR ball instead of the
    # modern balls'. Shipped as the sensitivity of the carry to the ball's drag level (docs/flight.md).
    return _cd_cl_measured_fit(s, re, c0=MEASURED_FIT_OFFSETS["usga_1998"])


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
    "measured_fit": (_cd_cl_measured_fit, 2.0e-5),
    "measured_fit_usga_ball": (_cd_cl_measured_fit_usga_ball, 2.0e-5),
    "vacuum": (_cd_cl_vacuum, 0.0),
}
#: the models whose coefficients are published as they are (the others combine published pieces; docs/flight.md)
PUBLISHED_MODELS = ("smits_smith_1994", "lyu_2018", "usga_patent_2001")
#: the models impactlab fitted itself to published measurements of CD and CL (never to the carry tables)
MEASUREMENT_FITS = ("measured_fit",)
#: the default: the one model fitted to every measured CD and CL row shipped, with the drag crisis, its advance with
#: spin and the lift's saturation those rows show; on TrackMan's three tour tables (never fitted) it carries within
#: 2.4-2.9 % RMS, where Smits & Smith (1994), extrapolated beyond its stated range, gives 4.9-8.4 % (docs/flight.md)
DEFAULT_MODEL = "measured_fit"
#: models no longer shipped -> why, and what to use (said when one is asked for)
RETIRED_MODELS = {
    "measured_fit_late_crisis": "retired on 2026-11-24: it moved measured_fit's drag crisis to the non-spinning "
                                "balls' position; measured_fit now has that position without spin and the measured "
                                "advance of the crisis with spin (docs/flight.md); use 'measured_fit'",
}
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
    "measured_fit": "fitted by impactlab to measured golf-ball CD and CL (Lyu, Kensrud & Smith 2020; Lyu et al. 2018; "
                    "Naruo, Mizota & Shimozono 2004; USGA ITR example table of US 6,186,002; Acushnet US 6,729,976; "
                    "Bridgestone US 7,238,121; Bearman & Harvey 1976), "
                    "impactlab/data/validation/aero_coefficients.yaml; spin decay lambda = 2e-5 (Smits & Smith 1994)",
    "measured_fit_usga_ball": "measured_fit with the drag level of the 1998 USGA ITR ball (c0 0.2114 for 0.1913): "
                              "a sensitivity to the ball's drag level, not a validated model",
    "vacuum": "no air (a test limit)",
}


def retired_reason(model) -> str:
    """``"'<name>' was retired on ...; use ..."`` for a retired model's name (:data:`RETIRED_MODELS`), else ``""``:
    the one wording every entry point refusing a model by name gives."""
    return f"{model!r} was {RETIRED_MODELS[model]}" if isinstance(model, str) and model in RETIRED_MODELS else ""


def model_function(model):
    """The function ``(S, Re) -> (CD, CL)`` of the model named ``model`` (a key of :data:`MODELS`).

    Raises
    ------
    ValueError
        A name not in :data:`MODELS`; a retired one (:data:`RETIRED_MODELS`) is named with why and what to use.
    """
    if not isinstance(model, str) or model not in MODELS:
        retired = retired_reason(model)
        raise ValueError(f"unknown model {model!r}{f' ({retired})' if retired else ''}; choose from {sorted(MODELS)}")
    return MODELS[model][0]


def model_fingerprint(model) -> str:
    """A short fingerprint of the coefficients the model named ``model`` gives today: the SHA-256 of its CD and CL,
    rounded to 1e-9, on a fixed grid of S 0-1.2 and Re 3e4-3e5 (12 hex digits).

    A result records it beside ``aerodynamic_model``, so a figure that flies the stored launches again can tell when
    the model's constants changed since (a refit keeps the name): the paths would not match the stored carries.
    """
    import hashlib

    s, re = np.meshgrid(np.linspace(0.0, 1.2, 25), np.geomspace(3.0e4, 3.0e5, 31))
    cd, cl = model_function(model)(s, re)
    values = np.round(np.concatenate([np.ravel(cd), np.ravel(cl)]), 9) + 0.0  # + 0.0: no negative zeros
    return hashlib.sha256(values.tobytes()).hexdigest()[:12]


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

        ``"smits_smith_1994"`` -- [SS94]_, fitted by the authors to
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

        ``"measured_fit"`` (default) -- fitted by impactlab to measured CD and CL only
        (impactlab/data/validation/aero_coefficients.yaml: [Ly20]_, [Ly18]_,
        [Na04]_, [US01]_'s ITR table, Acushnet's and Bridgestone's patent
        tables, [BH76]_), never to a carry table; constants :data:`MEASURED_FIT`::

            CL_sc = a S / (1 + b S)                        (saturates at a/b = 0.58)
            CD    = c0 + c_re Re/1e5 + k CL_sc^2 + d / (1 + exp((Re - Re_d exp(-m S))/w_d))
            CL    = CL_sc (1 - beta exp(-ln(Re/Re_l)^2 / (2 sigma^2)) exp(-S/s_l))

        The drag crisis is reached at a lower Re the more the ball spins
        (m = 1.27: midpoint Re 73 400 without spin, 57 000 at S 0.2); the last
        factor is the lift lost in the crisis (reverse Magnus below Re ~6.5e4
        at S < 0.2, [Ly20]_); c0 is the modern balls' drag.

        ``"measured_fit_usga_ball"`` -- the same with the drag level the fit
        gives the 1998 USGA ITR ball (c0 = 0.2114); a sensitivity to the
        ball's drag level, not a validated model.

        ``"vacuum"`` -- zero drag and lift (for tests).

    Returns
    -------
    cd, cl : ndarray
        Drag and lift coefficients referred to ``q = rho v^2 / 2`` and the
        frontal area ``pi R^2``.

    Raises
    ------
    ValueError
        A model not in :data:`MODELS`; a retired one (:data:`RETIRED_MODELS`)
        is named with why and what to use.

    Notes
    -----
    All three published models are curve fits to measurements; outside their
    fitted ranges (irons and wedges reach S = 0.3-1.2 late in flight) they are
    extrapolations.  See docs/flight.md for the validation of each.
    """
    fn = model_function(model)
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
