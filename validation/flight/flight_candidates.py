"""Which physical change of the flight model moves its carry against the tour tables, and which way.

With the drag level settled on measured radar flights (:mod:`validation.flight.flight_fit`), TrackMan's tour tables are
2.1-2.7 % RMS held out, with a misfit that follows the launch spin ratio: the 3-woods to 3-irons 1-4 % long and landing
4-7 deg too shallow, the short irons 1-6 % short. This module tries one physical change at a time, each a parameter of
``measured_fit`` bounded to a published measured range (:data:`PARAMETERS`):

- the spin decay constant (Smits & Smith 1994's 2e-5; radar and TrackMan's quoted rates);
- a drag term linear in the spin ratio beyond the induced drag (Smits & Smith's 0.18 S; the measured CD rows);
- the lift's saturation at the high spin ratios of the descent (the measured CL rows);
- the drag's Reynolds-number slope (the measured CD rows);
- the position and width of the drag crisis, the lift lost in it, and how fast spin advances it (the fit's own
  uncertainties on the measured rows of Lyu et al. 2018 and 2020), and the crisis without that advance.

Each candidate (:data:`CANDIDATES`) is fitted twice, never on the table it is scored on (:func:`evaluate`): on the
PGA TOUR radar seasons alone (the honest number: no tour table in the fit), and leave-one-table-out on the seasons plus
the other two tables (optimistic: the tables share an instrument and partly players). Carry RMS per held-out table,
land angles and heights against the tables, hang times and apexes against the seasons show whether a candidate fixes
the carry by breaking the flight's shape. :func:`crisis_scan` shows what the seasons and the tables say about the crisis
position. ``python -m validation.flight.flight_candidates`` prints the tables of docs/flight.md ("Which change moves
the spin-ratio residual"), about five minutes.

References
----------
Lyu, Kensrud, Smith & Tosaya, Proceedings 2(6):238 (2018), Fig. 3a: non-spinning CD of 13 production balls, mean 0.302
at Re 7.5e4 and 0.215 at 1e5 (free flight; "differences between ball models relatively large (> 0.1) at Re < 1e5").
Lyu, Kensrud & Smith, Sports Eng. 23:3 (2020), Figs. 1, 3: "turbulent boundary layer: Re > 7.5e4, S = 0"; three
balls at 2250 rpm with CD 0.25-0.27 at Re 7.5e4 (S 0.18).
Smits & Smith (1994), Science and Golf II 340-347: spin decay (d omega/dt) R^2 / v^2 = -2e-5 S (wind tunnel).
Tavares, Shannon & Melvin (1999), Science and Golf III, as restated by A. M. Nathan, "The effect of spin-down on the
flight of a baseball" (2008): 2.5e-5 (radar). TrackMan newsletter (October 2010), quoted by D. Tutelman, "Spin decay
for a ball in flight" (tutelman.com, 2016): "typically 4 % for each second"; Tutelman's TrajectoWare model: 3.3 %/s.
"""

from __future__ import annotations

import functools

import numpy as np

from validation.flight import aero_fit, flight_fit
from impactlab.data.carry import TABLES, YARD, carry_table, validate_carry
from impactlab.physics.aerodynamics import MEASURED_FIT

#: the measured flights every candidate is fitted to (no tour table)
RADAR = flight_fit.SOURCES[0]
#: parameter -> ((low, high), measured_fit's value, where the bounds come from); every bound is a measured range
PARAMETERS = {
    "c0": (flight_fit.C0_BOUNDS, MEASURED_FIT["c0"],
           "supercritical drag offsets of the measured ball groups (modern, 1998 USGA, 1976)"),
    "spin_decay": ((1.53e-5, 2.5e-5), 2.0e-5,
                   "lambda of d omega/dt = -lambda v omega / R: 2.5e-5 Tavares et al. 1999 (radar; 4.7 %/s over a "
                   "PGA TOUR drive); 1.53e-5 the slowest rate reported, 75 rpm/s on average through a "
                   "TrackMan-measured Pro V1x drive (Acushnet US 7,591,742 B2 as reported by jhoblitt/tmelevation, "
                   "not read here), taken at 3000 rpm, the top of the 2500-3000 rpm such a drive has (1.76e-5 at "
                   "2500): 2.8 %/s over the tour drive; 2e-5 gives 3.7 %/s (TrackMan: 'typically 4 %', Tutelman's "
                   "model 3.3 %/s)"),
    "drag_spin_slope": ((0.0, 0.229), 0.0,
                        "c1 of an added drag c1 S: the measured CD rows give c1 = 0.118 +- 0.055 beside the induced "
                        "drag (0 to + 2 sigma: the slope is not negative in any source)"),
    "lift_saturation": ((3.17, 3.96), MEASURED_FIT["b"],
                        "b of CL = a S / (1 + b S): the measured CL rows' fit 3.57 +- 2 sigma (0.39)"),
    "drag_re_slope": ((-0.0117, 0.0066), MEASURED_FIT["c_re"],
                      "c_re of the supercritical drag: the measured CD rows' fit -0.0026 +- 2 sigma (0.0092)"),
    "crisis_shift": ((0.908, 1.092), 1.0,
                     "drag-crisis midpoint Re_d times this: the fit's Re_d 73 400 +- 2 sigma (3 400), the position "
                     "measured without spin (Lyu 2018 Fig. 3a mean CD 0.302 at 7.5e4)"),
    "crisis_width": ((MEASURED_FIT["w_d"], 1.0e4), MEASURED_FIT["w_d"],
                     "logistic width of the drag step: up to the 13-ball mean's span (CD 0.477, 0.302, 0.215 at "
                     "Re 5e4, 7.5e4, 1e5, Lyu 2018 Fig. 3a)"),
    "lift_loss_shift": ((0.984, 1.016), 1.0, "centre Re_l of the lift lost in the crisis times this: the fit's Re_l "
                        "57 600 +- 2 sigma (450)"),
    "crisis_spin_advance": ((0.87, 1.68), MEASURED_FIT["m"],
                            "m of the drag-crisis midpoint Re_d exp(-m S): the fit's 1.27 +- 2 sigma (0.41); 0 is a "
                            "crisis that stays where it is without spin (its own refit, "
                            "validation.flight.aero_fit.fit_without_spin_advance)"),
}
#: parameters that are scales or positions: a value <= 0 describes no ball (an inverted or infinitely sharp step)
POSITIVE = ("crisis_shift", "crisis_width", "lift_loss_shift", "lift_saturation")
#: parameters whose effect on carry is a step (the crisis): fitted on a grid of this many points, the rest by least
#: squares at each grid point
GRID = ("crisis_shift", "lift_loss_shift")
GRID_POINTS = 13
#: name -> (parameters fitted, parameters held at a value, what it tests)
CANDIDATES = {
    "drag level only": (("c0",), {}, "flight_fit's fit: the reference"),
    "spin decay": (("c0", "spin_decay"), {}, "candidate 1: spin decay within the measured rates"),
    "spin decay at 2.5e-5": (("c0",), {"spin_decay": 2.5e-5}, "candidate 1: the fastest measured decay"),
    "drag linear in S": (("c0", "drag_spin_slope"), {}, "candidate 2: CD + c1 S"),
    "lift saturation": (("c0", "lift_saturation"), {}, "candidate 2: lift at the descent's high S"),
    "drag Re slope": (("c0", "drag_re_slope"), {}, "candidate 3: Reynolds-number dependence"),
    "crisis width": (("c0", "crisis_width"), {}, "candidate 3: a gradual drag crisis"),
    "crisis position (drag and lift loss)": (("c0", "lift_loss_shift"), {"crisis_shift": None},
                                             "candidate 3: the whole crisis moved"),
    "crisis position (drag)": (("c0", "crisis_shift"), {}, "candidate 3: the drag step moved"),
    "crisis advance with spin": (("c0", "crisis_spin_advance"), {}, "candidate 4: how fast spin advances the crisis"),
    "no crisis advance (m = 0)": (("c0",), {"crisis_spin_advance": 0.0},
                                  "what the measured advance does: the crisis refitted without it"),
}


def defaults() -> dict:
    """Every parameter at ``measured_fit``'s value."""
    return {name: value for name, (_, value, _) in PARAMETERS.items()}


def coefficients(**params):
    """``measured_fit`` with any of :data:`PARAMETERS` changed, as a function ``(S, Re) -> (CD, CL)`` for
    :func:`impactlab.physics.flight.fly` (``spin_decay`` is not an aerodynamic coefficient: :func:`flights` passes it
    to ``fly``). With no argument it is ``measured_fit`` exactly.

    Raises
    ------
    ValueError
        A parameter that is not one of :data:`PARAMETERS`, or a value no ball can have (not finite; a crisis
        position, width or lift saturation that is not positive, a negative spin decay). Values outside the measured
        bounds but physical are allowed (:func:`crisis_scan` goes beyond them).
    """
    unknown = sorted(set(params) - set(PARAMETERS))
    if unknown:
        raise ValueError(f"unknown parameter {unknown}; choose from {sorted(PARAMETERS)}")
    impossible = sorted(name for name, value in params.items() if not np.isfinite(value) or (
        name in POSITIVE and value <= 0.0) or (name == "spin_decay" and value < 0.0))
    if impossible:
        raise ValueError(f"impossible value of {impossible}: {[params[name] for name in impossible]} (crisis "
                         f"positions, widths and the lift saturation are > 0, the spin decay >= 0)")
    p = {**defaults(), **params}
    m = MEASURED_FIT
    # the drag step: measured_fit's, or without the spin advance the refit that holds m = 0 (its Re_d, w_d, d)
    re_d, width, height = m["re_d"], p["crisis_width"], m["d"]
    if p["crisis_spin_advance"] == 0.0:
        _, _, _, _, re_d, refit_width, height = aero_fit.fit_without_spin_advance()["crisis"]
        # the refit's width unless a crisis width other than measured_fit's is asked for
        width = refit_width if width == PARAMETERS["crisis_width"][1] else width

    def cd_cl(s, re):
        lift_sc = m["a"] * s / (1.0 + p["lift_saturation"] * s)
        midpoint = re_d * p["crisis_shift"] * np.exp(-p["crisis_spin_advance"] * s)
        step = 0.5 * (1.0 - np.tanh(0.5 * (re - midpoint) / width))
        cd = (p["c0"] + p["drag_re_slope"] * re / 1.0e5 + m["k"] * lift_sc**2 + p["drag_spin_slope"] * s
              + height * step)
        ratio = np.log(np.maximum(re, 1.0) / (m["re_l"] * p["lift_loss_shift"])) / m["sigma"]
        loss = m["beta"] * np.exp(-0.5 * ratio**2 - s / m["s_l"])
        return cd, lift_sc * (1.0 - loss)

    return cd_cl


def flights(params: dict, name: str, **options) -> dict:
    """The measured table ``name`` flown with ``params`` (:func:`impactlab.data.carry.validate_carry` in the table's
    own air)."""
    known = {key: value for key, value in params.items() if key in PARAMETERS}  # checked there, spin decay too
    decay = params.get("spin_decay", PARAMETERS["spin_decay"][1])
    return validate_carry(coefficients(**known), carry_table(name), spin_decay=decay, **options)


def _tied(params: dict, fixed: dict) -> dict:
    # a fixed value None ties the parameter to the grid parameter fitted (the whole crisis moved as one)
    return {key: (params.get("lift_loss_shift", 1.0) if value is None else value) for key, value in fixed.items()}


def fit(sources, parameters, fixed=None) -> dict:
    """Least squares of the relative carry errors of ``sources`` over ``parameters`` within :data:`PARAMETERS`'
    bounds, the others at ``fixed`` or ``measured_fit``'s values; a :data:`GRID` parameter on a grid.

    Returns
    -------
    dict
        Every parameter's value, plus ``rms`` (the fitted rows' carry RMS, relative) and ``at_bound`` (the names of
        fitted parameters that ended on a bound).
    """
    from scipy.optimize import least_squares  # scipy-heavy: only when fitting

    unknown = sorted(set(parameters) - set(PARAMETERS))
    if unknown or "c0" not in parameters or len([p for p in parameters if p in GRID]) > 1:
        raise ValueError(f"parameters: expected 'c0' and any of {sorted(set(PARAMETERS) - {'c0'})} (one of {GRID} at "
                         f"most), got {list(parameters)}")
    fixed = dict(fixed or {})
    grid = [p for p in parameters if p in GRID]
    smooth = [p for p in parameters if p not in GRID]
    points: list = list(np.linspace(*PARAMETERS[grid[0]][0], GRID_POINTS)) if grid else [None]

    def residuals(x, extra):
        params = {**defaults(), **extra, **dict(zip(smooth, x))}
        params.update(_tied(params, fixed))
        return np.concatenate([flights(params, name)["carry_error"] for name in sources])

    start = [float(np.clip(PARAMETERS[p][1] + (0.005 if p == "c0" else 0.0), *PARAMETERS[p][0])) for p in smooth]
    bounds = ([PARAMETERS[p][0][0] for p in smooth], [PARAMETERS[p][0][1] for p in smooth])
    scale = [(PARAMETERS[p][0][1] - PARAMETERS[p][0][0]) / 10 for p in smooth]
    tried = []
    for value in points:
        extra = {grid[0]: value} if grid else {}
        solution = least_squares(residuals, start, bounds=bounds, x_scale=scale, diff_step=1e-3, xtol=1e-8,
                                 args=(extra,))
        tried.append((float(np.sum(solution.fun**2)), {**extra, **dict(zip(smooth, map(float, solution.x)))},
                      solution.fun))
    _, best, errors = min(tried, key=lambda item: item[0])
    params = {**defaults(), **best}
    params.update(_tied(params, fixed))
    at_bound = [p for p in parameters
                if np.isclose(params[p], PARAMETERS[p][0], rtol=0, atol=1e-3 * np.ptp(PARAMETERS[p][0])).any()]
    return {**params, "rms": float(np.sqrt(np.mean(errors**2))), "at_bound": at_bound}


def score(params: dict) -> dict:
    """The seasons and every tour table flown with ``params``: per name, carry RMS (relative) and the mean
    differences model minus measurement of land angle [deg], height [yd] and hang time [s] (NaN where not
    measured)."""
    out = {}
    for name in (RADAR, *TABLES):
        check = flights(params, name)
        table = check["table"]
        hang = table.flight_time if table.flight_time is not None else np.full(len(table.clubs), np.nan)

        def mean(x):
            return float(np.mean(x[np.isfinite(x)])) if np.isfinite(x).any() else float("nan")

        out[name] = {"rms": check["rms_carry_error"], "carry_error": check["carry_error"],
                     "land": mean(np.degrees(check["landing_angle"] - table.land_angle)),
                     "height": mean((check["apex_height"] - table.max_height) / YARD),
                     "hang": mean(check["flight_time"] - hang)}
    return out


@functools.cache
def evaluate(name: str) -> dict:
    """Candidate ``name`` of :data:`CANDIDATES` fitted on the radar seasons alone and leave-one-table-out.

    Returns
    -------
    dict
        ``radar``: the parameters fitted on the seasons and their :func:`score`; ``folds``: per held-out table, the
        parameters fitted on the seasons and the other two tables, the held-out table's RMS and the seasons' score.
    """
    parameters, fixed, _ = CANDIDATES[name]
    radar = fit((RADAR,), parameters, fixed)
    folds = {}
    for held in TABLES:
        params = fit((RADAR, *(t for t in TABLES if t != held)), parameters, fixed)
        folds[held] = {"params": params, "score": score(params)}
    return {"radar": {"params": radar, "score": score(radar)}, "folds": folds}


def crisis_scan(shifts=(1.0, 1.05, 1.1, 1.15, 1.2, 1.25, 1.3)) -> list:
    """The drag-crisis position against the seasons and the tables: per shift (Re_d times it, beyond the bound
    too), c0 fitted on the seasons alone, then every :func:`score`."""
    out = []
    for shift in shifts:
        params = fit((RADAR,), ("c0",), {"crisis_shift": shift})
        out.append({"crisis_shift": shift, "c0": params["c0"], "score": score(params)})
    return out


def _params_text(params: dict, names) -> str:
    return ", ".join(f"{name} {params[name]:.4g}" + (" (bound)" if name in params.get("at_bound", ()) else "")
                     for name in names)


def format_report() -> str:
    """Every candidate's held-out numbers and the crisis scan as Markdown."""
    short = {"trackman_carry": "classic", "trackman_carry_pga_2023": "PGA 2023",
             "trackman_carry_lpga_2023": "LPGA 2023"}
    lines = ["| candidate | fitted on the radar seasons | classic | PGA 2023 | LPGA 2023 | land, height (mean) | "
             "seasons: hang, apex | leave one table out: held-out RMS | seasons RMS then |", "|---" * 9 + "|"]
    for name in CANDIDATES:
        result = evaluate(name)
        radar, folds = result["radar"], result["folds"]
        parameters = CANDIDATES[name][0]
        land = np.mean([radar["score"][t]["land"] for t in TABLES])
        height = np.mean([radar["score"][t]["height"] for t in TABLES])
        held = " / ".join(f"{100 * folds[t]['score'][t]['rms']:.2f}" for t in TABLES)
        seasons = " / ".join(f"{100 * folds[t]['score'][RADAR]['rms']:.1f}" for t in TABLES)
        lines.append(f"| {name} | {_params_text(radar['params'], parameters)} | "
                     + " | ".join(f"{100 * radar['score'][t]['rms']:.2f} %" for t in TABLES)
                     + f" | {land:+.1f} deg, {height:+.1f} yd | {radar['score'][RADAR]['hang']:+.2f} s, "
                       f"{radar['score'][RADAR]['height']:+.1f} yd | {held} % | {seasons} % |")
    lines += ["", "| left out | " + " | ".join(CANDIDATES) + " |", "|---" * (len(CANDIDATES) + 1) + "|"]
    for table in TABLES:
        lines.append(f"| {short[table]} | " + " | ".join(
            _params_text(evaluate(name)["folds"][table]["params"], CANDIDATES[name][0]) for name in CANDIDATES) + " |")
    lines += ["", "| crisis shift | Re_d | c0 (seasons) | seasons RMS | classic | PGA 2023 | LPGA 2023 | land (mean) |",
              "|---" * 8 + "|"]
    for row in crisis_scan():
        s = row["score"]
        lines.append(f"| {row['crisis_shift']:.2f} | {MEASURED_FIT['re_d'] * row['crisis_shift']:.0f} | "
                     f"{row['c0']:.4f} | {100 * s[RADAR]['rms']:.2f} % | "
                     + " | ".join(f"{100 * s[t]['rms']:.2f} %" for t in TABLES)
                     + f" | {np.mean([s[t]['land'] for t in TABLES]):+.1f} deg |")
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m validation.flight.flight_candidates``: the tables of docs/flight.md
    (:func:`validation.flight.flight_fit.report_command`)."""
    return flight_fit.report_command("flight_candidates", "Fit each candidate change of the flight model on "
                                     "measured flights and fly TrackMan's tour tables held out (docs/flight.md).",
                                     format_report, argv)


if __name__ == "__main__":  # pragma: no cover - prints the tables of docs/flight.md
    raise SystemExit(main())
