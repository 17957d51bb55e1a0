"""The driver's carry against air density: the PGA TOUR radar's measured dose-response against every flight model.

Drag and lift both scale with the air density, so how much a driver's carry gains in thinner air depends on how large
both are against gravity: a measured density derivative of carry separates the drag level from the lift level, which
the radar seasons' carry alone cannot (:mod:`validation.flight.flight_fit`). The measurement
(impactlab/data/validation/pgatour_radar_altitude.yaml, :func:`evidence`) is the source's fit of 40 near-sea-level
events' player-matched carry differences on air density, raw and with the launch differences removed: the truth for
a fixed launch lies between the two (:func:`bracket`), plus three altitude venues.

- :func:`density_response`: a model's carry at the seasons' mean driver launch (:func:`season_launch`), flown in the
  seasons' air (25 degC, 50 %) with the density lowered or raised by the pressure alone; the slope in yards per 0.01
  of density ratio and relative (per cent of carry per per cent of density), the altitude venues' gains, and with
  ``freeze_re`` the coefficients held at the seasons' Reynolds numbers (the density's effect without the model's Re
  dependence: a diagnostic, not a model);
- :func:`fit`: ``c0``, a lift scale (bounded as :mod:`validation.flight.flight_fit` bounds them) and optionally the drag
  crisis position (bounded as :mod:`validation.flight.flight_candidates`), least squares on the seasons' carry, apex and
  hang time plus the density slope's distance outside the measured bracket; :func:`held_out` flies the tour tables.

``python -m validation.flight.flight_altitude`` prints the tables of docs/flight.md ("Carry against air density").

References
----------
jhoblitt/tmelevation, docs/research/land-angle-spike/altitude-evidence.md section 2 and altitude-evidence.md.notes.md
@ a541508 (PGA TOUR radar statistics, pgatour.com stats 02401-02409 and 101; analysis by that source).
"""

from __future__ import annotations

import functools
from importlib import resources

import numpy as np
import yaml

from validation.flight import flight_candidates, flight_fit
from impactlab.data.carry import TABLES, YARD, carry_table, validate_carry
from impactlab.physics import flight
from impactlab.physics.aerodynamics import MEASURED_FIT, MODELS, model_function
from impactlab.physics.atmosphere import air_density, air_viscosity
#: the reference of the source's density ratios: dry air at 25 degC and 101 325 Pa [kg/m^3]
RHO_25 = float(air_density(298.15, 101325.0, 0.0))
#: the seasons' air as impactlab flies them (pgatour_radar_driver.yaml): 25 degC, 50 % humidity
TEMPERATURE, HUMIDITY = 298.15, 0.5
#: density ratios the slope is taken between (a central difference of +-0.05 about the seasons' 0.992; the 40 events
#: span 0.906-1.062)
STEP = 0.05
#: weights of the fit's residuals against a relative carry residual: apex (as flight_fit), hang time (0.1 s resolution
#: on 6.3 s), and the density slope's relative distance outside the bracket
WEIGHTS = {"max_height": flight_fit.APEX_WEIGHT, "flight_time": 0.5, "density": 0.2}
#: what :func:`fit` fits: the seasons' carry, apex and hang time, and the density slope
OBSERVABLES = ("carry", "max_height", "flight_time", "density")
#: parameters :func:`fit` may fit, and their bounds (flight_fit's c0 and lift scale, flight_candidates' crisis shift)
#: :func:`fit` with its defaults (c0 and lift scale on the seasons' carry, apex, hang time and the density slope);
#: tests check the fit's cost is least there and fly the tables with it
FITTED = {"c0": 0.204771, "lift_scale": 1.07611}
BOUNDS = {"c0": flight_fit.C0_BOUNDS, "lift_scale": flight_fit.lift_scale_bounds(),
          "crisis_shift": flight_candidates.PARAMETERS["crisis_shift"][0],
          "lift_loss_shift": flight_candidates.PARAMETERS["lift_loss_shift"][0]}
#: the parameters :func:`fit` holds and :func:`fit_grid` scans (carry is a step function of them)
GRID = ("crisis_shift", "lift_loss_shift")
#: relative cost difference below which :func:`fit_grid` calls two grid points equal (the drivers never reach a crisis
#: moved from Re_d x 1 to x 0.9: the costs differ by 1e-5 relative)
TIE = 1e-4


@functools.cache
def evidence() -> dict:
    """The measurement file pgatour_radar_altitude.yaml as a dict (as typed from the source)."""
    path = resources.files("impactlab.data.validation").joinpath("pgatour_radar_altitude.yaml")
    return yaml.safe_load(path.read_text())


def season_launch() -> tuple:
    """The radar seasons' mean driver launch (ball speed [m/s], launch angle [rad], spin [rad/s]): the plain mean of
    the five seasons of pgatour_radar_driver.yaml."""
    table = carry_table(flight_fit.SOURCES[0])
    return float(np.mean(table.ball_speed)), float(np.mean(table.launch_angle)), float(np.mean(table.spin_rate))


def bracket() -> dict:
    """The measured slope of carry on density: yards per 0.01 of density ratio (raw, launch-adjusted), and relative
    (per cent of carry per per cent of density at the seasons' mean density, on the 2022-23 season's carry, the
    events' season): ``{"yd": (low, high), "relative": (low, high)}``, low = launch-adjusted, high = raw."""
    dose = evidence()["dose_response"]
    slopes = (-dose["launch_adjusted"]["slope"] / 100.0, -dose["raw"]["slope"] / 100.0)
    carry = carry_table(flight_fit.SOURCES[0]).carry[-1] / YARD  # the 2022-23 season
    rho = evidence()["season_density_ratio"]
    return {"yd": slopes, "relative": tuple(100.0 * s * rho / carry for s in slopes)}


def pressure_for(ratio: float) -> float:
    """Station pressure [Pa] that gives air of density ``ratio`` * :data:`RHO_25` at the seasons' temperature and
    humidity (the moist-air density is linear in the pressure at fixed temperature and humidity)."""
    # rho(p) = a p + b (the vapour pressure is fixed by temperature and humidity): a and b from two pressures
    one = float(air_density(TEMPERATURE, 101325.0, HUMIDITY))
    a = (float(air_density(TEMPERATURE, 2 * 101325.0, HUMIDITY)) - one) / 101325.0
    b = one - a * 101325.0
    return (ratio * RHO_25 - b) / a


def temperature_for(ratio: float) -> float:
    """Air temperature [K] that gives air of density ``ratio`` * :data:`RHO_25` at 101 325 Pa and the seasons'
    humidity (fixed-point iteration on the ideal-gas law; the vapour pressure changes with the temperature)."""
    temperature = TEMPERATURE
    for _ in range(50):
        temperature *= float(air_density(temperature, 101325.0, HUMIDITY)) / (ratio * RHO_25)
    return temperature


def _reynolds_frozen(model, factor, which):
    base = model_function(model) if isinstance(model, str) else model

    def cd_cl(s, re):
        frozen, flown = base(s, re / factor), base(s, re)
        cd = frozen[0] if which in (True, "drag") else flown[0]
        return cd, (frozen[1] if which in (True, "lift") else flown[1])

    return cd_cl


def density_response(model="measured_fit", launch=None, freeze_re=False, ratios=None, spin_decay=None,
                     by: str = "pressure") -> dict:
    """A model's driver carry against air density at the seasons' mean launch.

    Parameters
    ----------
    model : str or callable
        A key of :data:`impactlab.physics.aerodynamics.MODELS` or a function ``(S, Re) -> (CD, CL)``.
    launch : tuple, optional
        (ball speed [m/s], launch angle [rad], spin [rad/s]); default :func:`season_launch`.
    freeze_re : bool or {"drag", "lift"}
        Evaluate the coefficients (or only CD, or only CL) at the Reynolds number the same speed has in the seasons'
        air (the density's effect alone, without the model's Re dependence): a diagnostic.
    ratios : sequence of float, optional
        Density ratios (of :data:`RHO_25`) to fly besides the slope's; default the altitude venues'.
    spin_decay : float, optional
        Passed to :func:`impactlab.physics.flight.fly`.
    by : {"pressure", "temperature"}
        Change the density by the pressure at 25 degC (altitude; default) or by the temperature at 101 325 Pa (the
        40 near-sea-level events differ mostly in temperature; the air's viscosity, hence Re, changes too).

    Returns
    -------
    dict
        ``carry`` [yd], ``apex`` [yd] and ``hang`` [s] at the seasons' density; ``slope_yd`` (carry gained per 0.01
        drop of density ratio, yd); ``relative`` (per cent of carry per per cent of density); ``gains`` (relative
        carry gain at each of ``ratios`` against the seasons' density) and ``apex_gains`` likewise.
    """
    if freeze_re not in (False, True, "drag", "lift"):
        raise ValueError(f"freeze_re: expected False, True, 'drag' or 'lift', got {freeze_re!r}")
    if by not in ("pressure", "temperature"):
        raise ValueError(f"by: expected 'pressure' or 'temperature', got {by!r}")
    speed, angle, spin = launch or season_launch()
    season = evidence()["season_density_ratio"]
    venues = list(ratios) if ratios is not None else [e["density_ratio"] for e in evidence()["events"]]
    every = np.array([season, season - STEP, season + STEP, *venues])
    out = []
    for ratio in every:  # one flight per density (the Re-frozen model differs per density)
        air = ({"temperature": TEMPERATURE, "pressure": pressure_for(ratio)} if by == "pressure" else
               {"temperature": temperature_for(ratio), "pressure": 101325.0})
        # Re = rho v d / mu(T): frozen at the seasons' air, the factor is the density's and the viscosity's
        factor = (ratio / season) * float(air_viscosity(TEMPERATURE) / air_viscosity(air["temperature"]))
        flown = _reynolds_frozen(model, factor, freeze_re) if freeze_re else model
        result = flight.fly(speed, angle, spin, model=flown, relative_humidity=HUMIDITY, spin_decay=spin_decay, **air)
        out.append((float(result["carry_distance"]) / YARD, float(result["apex_height"]) / YARD,
                    float(result["flight_time"])))
    carry, apex, hang = np.array(out).T
    slope = (carry[1] - carry[2]) / (2 * STEP * 100.0)
    return {"carry": carry[0], "apex": apex[0], "hang": hang[0], "slope_yd": float(slope),
            "relative": float(100.0 * slope * season / carry[0]), "ratios": venues,
            "gains": carry[3:] / carry[0] - 1.0, "apex_gains": apex[3:] / apex[0] - 1.0}


def coefficients(c0: float = MEASURED_FIT["c0"], lift_scale: float = 1.0, crisis_shift: float = 1.0,
                 lift_loss_shift: float = 1.0):
    """``measured_fit`` with drag level ``c0``, every CL times ``lift_scale`` (the induced drag unscaled, as
    :func:`validation.flight.flight_fit.coefficients`), the drag crisis at Re_d times ``crisis_shift`` and the lift lost
    at low Re centred at Re_l times ``lift_loss_shift`` (:func:`validation.flight.flight_candidates.coefficients`)."""
    base = flight_candidates.coefficients(c0=c0, crisis_shift=crisis_shift, lift_loss_shift=lift_loss_shift)

    def cd_cl(s, re):
        cd, cl = base(s, re)
        return cd, cl * lift_scale

    return cd_cl


def _residuals(params: dict, observables=OBSERVABLES) -> np.ndarray:
    check = validate_carry(coefficients(**params), carry_table(flight_fit.SOURCES[0]))
    table = check["table"]
    parts = [check["carry_error"]]
    if "max_height" in observables:
        parts.append(WEIGHTS["max_height"] * (check["apex_height"] / table.max_height - 1.0))
    if "flight_time" in observables:
        hang = check["flight_time"] / table.flight_time - 1.0
        parts.append(WEIGHTS["flight_time"] * hang[np.isfinite(hang)])
    if "density" in observables:
        low, high = bracket()["relative"]
        relative = density_response(coefficients(**params), ratios=())["relative"]
        parts.append([WEIGHTS["density"] * (relative - np.clip(relative, low, high)) / low])
    return np.concatenate([np.atleast_1d(p) for p in parts])


def fit(parameters=("c0", "lift_scale"), observables=OBSERVABLES, **held) -> dict:
    """Least squares over ``parameters`` (within :data:`BOUNDS`) of the seasons' carry and, as ``observables`` says,
    apex and hang time (weighted by :data:`WEIGHTS`) and the density slope's relative distance outside
    :func:`bracket`.

    Parameters
    ----------
    parameters : tuple
        Among ``"c0"`` and ``"lift_scale"`` (``c0`` required).
    observables : tuple
        ``"carry"`` and any of ``"max_height"``, ``"flight_time"``, ``"density"`` (default all).
    **held
        ``crisis_shift`` and ``lift_loss_shift`` held during the fit (default 1; :func:`fit_grid` scans them).

    Returns
    -------
    dict
        ``c0``, ``lift_scale``, ``crisis_shift``, ``lift_loss_shift``, ``at_bound`` (names of fitted parameters on
        a bound) and ``cost`` (half the sum of squared residuals).

    Raises
    ------
    ValueError
        Parameters or observables it cannot fit, or a held shift unknown or outside its bounds.
    """
    from scipy.optimize import least_squares  # scipy-heavy: only when fitting

    if not set(parameters) <= {"c0", "lift_scale"} or "c0" not in parameters:
        raise ValueError(f"parameters: expected 'c0' and optionally 'lift_scale', got {list(parameters)}")
    if not set(observables) <= set(OBSERVABLES) or "carry" not in observables:
        raise ValueError(f"observables: expected 'carry' and any of {OBSERVABLES[1:]}, got {list(observables)}")
    for name, value in held.items():
        if name not in GRID or not BOUNDS[name][0] <= value <= BOUNDS[name][1]:
            raise ValueError(f"{name}: expected one of {GRID} within {BOUNDS.get(name, '?')} (the measured crisis "
                             f"positions), got {value}")
    fixed = {"c0": MEASURED_FIT["c0"], "lift_scale": 1.0, "crisis_shift": 1.0, "lift_loss_shift": 1.0, **held}
    solution = least_squares(
        lambda x: _residuals({**fixed, **dict(zip(parameters, x))}, observables),
        [{"c0": 0.215, "lift_scale": 1.0}[p] for p in parameters],
        bounds=([BOUNDS[p][0] for p in parameters], [BOUNDS[p][1] for p in parameters]),
        x_scale=[0.01 if p == "c0" else 0.1 for p in parameters], diff_step=1e-4, xtol=1e-8)
    params = {**fixed, **dict(zip(parameters, map(float, solution.x)))}
    at_bound = [p for p in parameters if np.isclose(params[p], BOUNDS[p], rtol=0, atol=1e-4 * np.ptp(BOUNDS[p])).any()]
    return {**params, "at_bound": at_bound, "cost": float(solution.cost)}


def fit_grid(name: str = "crisis_shift", shifts=None, **options) -> dict:
    """:func:`fit` at each value of ``shifts`` of the :data:`GRID` parameter ``name`` (a step in carry: a grid, not
    least squares; default: its bounds' two ends and 1); the one of least cost (costs within :data:`TIE` relative:
    the one nearest measured_fit's 1, since the flights fitted cannot tell them apart), with ``name`` in
    ``at_bound`` when it is an end of :data:`BOUNDS` and ``scan``, each value tried with its cost."""
    if shifts is None:
        shifts = (BOUNDS[name][0], 1.0, BOUNDS[name][1])
    tried = [fit(**{name: shift}, **options) for shift in shifts]
    least = min(r["cost"] for r in tried)
    best = dict(min((r for r in tried if r["cost"] <= least * (1 + TIE)), key=lambda r: abs(r[name] - 1.0)))
    best["scan"] = [(r[name], r["cost"]) for r in tried]
    if np.isclose(best[name], BOUNDS[name]).any():
        best["at_bound"] = [*best["at_bound"], name]
    return best


def held_out(params: dict, tables=TABLES) -> dict:
    """The seasons and the tour tables flown with ``params`` (:func:`coefficients`): per name the carry RMS with and
    without the driver row (relative), the mean land-angle [deg], height [yd] and hang-time [s] differences (model
    minus measurement, NaN where not measured)."""
    model = coefficients(**{k: params[k] for k in ("c0", "lift_scale", *GRID) if k in params})
    out = {}
    for name in (flight_fit.SOURCES[0], *tables):
        check = validate_carry(model, carry_table(name))
        table = check["table"]
        other = np.array([club != "Driver" for club in table.clubs])
        hang = table.flight_time if table.flight_time is not None else np.full(len(table.clubs), np.nan)

        def mean(x):
            return float(np.nanmean(x)) if np.isfinite(x).any() else float("nan")

        out[name] = {"rms": check["rms_carry_error"],
                     "rms_without_driver": float(np.sqrt(np.mean(check["carry_error"][other] ** 2)))
                     if other.any() else float("nan"),
                     "land": mean(np.degrees(check["landing_angle"] - table.land_angle)),
                     "height": mean((check["apex_height"] - table.max_height) / YARD),
                     "hang": mean(check["flight_time"] - hang)}
    return out


def _variants() -> list:
    """(title, model) of every registered flight model but the vacuum, and each flight_candidates parameter at the
    ends of its measured bounds (the others at measured_fit's values)."""
    out: list = [(name, name) for name in MODELS if name != "vacuum"]
    for name, ((low, high), _, _) in flight_candidates.PARAMETERS.items():
        for value in (low, high):
            if name == "spin_decay":
                out.append((f"measured_fit, spin_decay {value:.3g}", ("measured_fit", value)))
            else:
                out.append((f"measured_fit, {name} {value:.4g}", flight_candidates.coefficients(**{name: value})))
    return out


def format_report() -> str:
    """The measured bracket, every model's density response, and the fits with and without the density slope,
    as Markdown."""
    low, high = bracket()["relative"]
    events = evidence()["events"]
    lines = [f"measured: {bracket()['yd'][0]:.2f}-{bracket()['yd'][1]:.2f} yd per 0.01 of density ratio, "
             f"{low:.3f}-{high:.3f} % carry per % density (launch-adjusted - raw)", "",
             "| model | carry yd | yd per 0.01 | % per % | Re frozen: all, drag, lift | "
             + " | ".join(f"{e['event'].split()[-1]} {e['venue'].split()[0]} "
                          f"({e['adjusted_percent']:+.1f}..{e['carry_percent']:+.1f} %)" for e in events) + " |",
             "|---" * (5 + len(events)) + "|"]
    for title, model in _variants():
        decay = None
        if isinstance(model, tuple):
            model, decay = model
        r = density_response(model, spin_decay=decay)
        frozen = [density_response(model, spin_decay=decay, freeze_re=which, ratios=())["relative"]
                  for which in (True, "drag", "lift")]
        lines.append(f"| {title} | {r['carry']:.1f} | {r['slope_yd']:.2f} | {r['relative']:.3f} | "
                     + ", ".join(f"{f:.3f}" for f in frozen) + " | "
                     + " | ".join(f"{100 * g:+.1f}" for g in r["gains"]) + " |")
    seasons = OBSERVABLES[:3]
    every = "seasons' carry, apex, hang + density slope"
    fits = [("seasons' carry, apex, hang; c0", fit(("c0",), seasons)),
            ("seasons' carry, apex, hang; c0, lift scale", fit(observables=seasons)),
            ("seasons' carry + density slope; c0, lift scale", fit(observables=("carry", "density"))),
            ("seasons' carry, hang + density slope; c0, lift scale",
             fit(observables=("carry", "flight_time", "density"))),
            ("seasons' carry, apex + density slope; c0, lift scale",
             fit(observables=("carry", "max_height", "density"))),
            (f"{every}; c0, lift scale", fit()),
            (f"{every}; c0, lift scale, crisis position", fit_grid("crisis_shift")),
            (f"{every}; c0, lift scale, lift-loss position", fit_grid("lift_loss_shift"))]
    lines += ["", "| fitted on | c0 | lift scale | crisis, lift-loss shift | % per % (Re frozen: all, drag, lift) | "
              "seasons RMS, apex, hang | "
              + " | ".join(f"{t} RMS (without driver)" for t in TABLES) + " | land, height (mean) |",
              "|---" * (6 + len(TABLES) + 1) + "|"]
    for title, params in fits:
        model = coefficients(*(params[k] for k in ("c0", "lift_scale", *GRID)))
        r = density_response(model, ratios=())["relative"]
        held_re = ", ".join(f"{density_response(model, ratios=(), freeze_re=which)['relative']:.3f}"
                           for which in (True, "drag", "lift"))
        scores = held_out(params)
        radar = scores[flight_fit.SOURCES[0]]
        bound = params["at_bound"]
        cells = {k: f"{params[k]:.4g}" + (" (bound)" if k in bound else "") for k in ("c0", "lift_scale", *GRID)}
        lines.append(f"| {title} | {cells['c0']} | {cells['lift_scale']} | "
                     f"{cells['crisis_shift']}, {cells['lift_loss_shift']} | "
                     f"{r:.3f} ({held_re}) | {100 * radar['rms']:.2f} %, {radar['height']:+.1f} yd, "
                     f"{radar['hang']:+.2f} s | "
                     + " | ".join(f"{100 * scores[t]['rms']:.2f} % ({100 * scores[t]['rms_without_driver']:.2f} %)"
                                  for t in TABLES)
                     + f" | {np.mean([scores[t]['land'] for t in TABLES]):+.1f} deg, "
                       f"{np.mean([scores[t]['height'] for t in TABLES]):+.1f} yd |")
    for title, params in fits[-2:]:
        lines += ["", f"{title}: cost per grid value " + ", ".join(f"{v:g}: {c:.6f}" for v, c in params["scan"])]
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m validation.flight.flight_altitude``: the tables of docs/flight.md
    (:func:`validation.flight.flight_fit.report_command`)."""
    return flight_fit.report_command("flight_altitude", "Every flight model's driver carry against air density "
                                     "beside the PGA TOUR radar's measured dose-response, and fits with it "
                                     "(docs/flight.md).", format_report, argv)


if __name__ == "__main__":  # pragma: no cover - prints the tables of docs/flight.md
    raise SystemExit(main())
