"""The ball's flight parameters fitted to measured flights that are not TrackMan's tour tables; the tables held out.

``measured_fit`` (:mod:`impactlab.physics.aerodynamics`) takes every coefficient from measured CD and CL of golf balls
(:mod:`validation.flight.aero_fit`), but one number decides its carries more than any other: the ball's supercritical
drag level ``c0``, which the measured balls spread over 0.207-0.274 (the modern balls', the 1998 USGA ball's and the
1976 ball's offsets, :data:`impactlab.physics.aerodynamics.MEASURED_FIT_OFFSETS`). This module settles ``c0`` on
measured flights (launch, and the carry a radar tracked to the ground), bounded to that measured range, and then flies
TrackMan's three per-club tour tables (:data:`impactlab.data.carry.TABLES`) with it, as held out:

- :data:`SOURCES`: the measured flights fitted (impactlab/data/validation, ``kind: measurement``), each flown in the
  air its file states (:attr:`impactlab.data.carry.CarryTable.air`);
- :func:`fit`: least squares (scipy.optimize) of the relative carry errors over ``c0``, and optionally a lift scale
  (every CL times a factor bounded to the spread of the measured CL rows at the drivers' spin ratios, S <= 0.2), and
  optionally the apex heights as a second observable;
- :func:`leave_one_out`: the fit repeated without each group of rows (each source, or each row label such as a
  season), with the held-out group's carry error;
- :func:`held_out`: the tour tables flown with the fitted parameters in the standard air (as
  :func:`impactlab.data.carry.validate_carry` flies them), carry RMS with and without the driver rows, heights and
  land angles per club.

``python -m validation.flight.flight_fit`` prints the tables of docs/flight.md ("Settling the drag level on measured
flights"); :data:`FITTED` holds the fitted constants (validation/flight/tests/test_flight_fit.py refits them from the
YAML).

References
----------
PGA TOUR radar statistics (TrackMan, Par 4 and 5 tee shots), season averages as tabulated in jhoblitt/tmelevation,
docs/research/land-angle-spike/provenance.md @ 98f8a49 (impactlab/data/validation/pgatour_radar_driver.yaml).
"""

from __future__ import annotations

import functools
from importlib import resources

import numpy as np
import yaml

from validation.flight import aero_fit
from impactlab.data.carry import TABLES, YARD, carry_table, validate_carry
from impactlab.physics.aerodynamics import MEASURED_FIT, MEASURED_FIT_OFFSETS, aero_coefficients

#: the measured flights the parameters are fitted to (never a tour table of :data:`impactlab.data.carry.TABLES`)
SOURCES = ("pgatour_radar_driver",)
#: bounds of ``c0``: the smallest and largest supercritical drag offset of the measured ball groups
C0_BOUNDS = (min(MEASURED_FIT_OFFSETS.values()), max(MEASURED_FIT_OFFSETS.values()))
#: spin ratios of the drivers' flights (launch S 0.07-0.1, rising to about 0.2 at the apex): where the lift scale's
#: bounds are read from the measured CL rows
DRIVER_S = 0.2
#: weight of an apex-height residual (relative) against a carry residual (relative) when both are fitted: the apex is
#: measured less directly (averages of other shot subsets, a 1-yard resolution on a 30-yard apex)
APEX_WEIGHT = 0.3
#: the fitted constants (:func:`fit` on :data:`SOURCES`, carry only, ``c0`` only; tests refit and compare)
FITTED = {"c0": 0.195184}


def coefficients(c0: float = MEASURED_FIT["c0"], lift_scale: float = 1.0):
    """``measured_fit`` with the drag level ``c0`` and every CL times ``lift_scale``, as a function ``(S, Re) -> (CD,
    CL)`` that :func:`impactlab.physics.flight.fly` takes for ``model`` (the induced drag keeps the unscaled lift,
    as fitted to the measured CD rows)."""

    def cd_cl(s, re):
        cd, cl = aero_coefficients(s, re, "measured_fit")
        return cd + (c0 - MEASURED_FIT["c0"]), cl * lift_scale

    return cd_cl


@functools.cache
def lift_scale_bounds(percentiles: tuple = (10.0, 90.0)) -> tuple:
    """The spread of the measured CL rows about ``measured_fit``'s supercritical lift at S <= :data:`DRIVER_S`:
    the ``percentiles`` of measured over fitted CL (the rows of :func:`validation.flight.aero_fit.measurements` above
    each ball's drag crisis)."""
    m = aero_fit.measurements()
    rows = m["supercritical"] & np.isfinite(m["cl"]) & (m["s"] <= DRIVER_S) & (m["s"] > 0)
    ratio = m["cl"][rows] / aero_fit.lift_supercritical(m["s"][rows], MEASURED_FIT["a"], MEASURED_FIT["b"])
    low, high = np.percentile(ratio, percentiles)
    return float(low), float(high)


@functools.cache
def labels(name: str) -> tuple:
    """Each row's label in the measured table ``name``: its ``season`` where the file has one, else its club."""
    document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath(f"{name}.yaml").read_text())
    return tuple(str(row.get("season", row["club"])) for row in document["rows"])


def _flights(params: dict, sources, tables=None, **options) -> list:
    """Fly every source's rows with ``params`` (``c0``, ``lift_scale``); one :func:`validate_carry` result each
    (``tables``: name -> :class:`~impactlab.data.carry.CarryTable` used instead of the shipped file)."""
    model = coefficients(params.get("c0", MEASURED_FIT["c0"]), params.get("lift_scale", 1.0))
    return [validate_carry(model, (tables or {}).get(name) or carry_table(name), **options) for name in sources]


def _residuals(params: dict, sources, keep, observables, tables, options) -> np.ndarray:
    checks = _flights(params, sources, tables, **options)
    parts = [np.concatenate([c["carry_error"] for c in checks])[keep]]
    if "max_height" in observables:
        apex = np.concatenate([c["apex_height"] / c["table"].max_height - 1.0 for c in checks])[keep]
        parts.append(APEX_WEIGHT * apex[np.isfinite(apex)])
    return np.concatenate(parts)


def fit(sources=SOURCES, exclude=(), parameters=("c0",), observables=("carry",), tables=None, **options) -> dict:
    """Least squares of the relative errors of the measured flights ``sources`` over ``parameters``.

    Parameters
    ----------
    sources : sequence of str
        Measured tables (impactlab/data/validation); each is flown in the air it states.
    exclude : collection of str
        Row groups left out of the fit: a source's name (all its rows) or a row label (:func:`labels`).
    parameters : tuple
        ``("c0",)`` or ``("c0", "lift_scale")``; ``c0`` is bounded by :data:`C0_BOUNDS`, ``lift_scale`` by
        :func:`lift_scale_bounds`.
    observables : tuple
        ``("carry",)`` or ``("carry", "max_height")`` (apex heights weighted by :data:`APEX_WEIGHT`).
    tables : dict, optional
        Source name -> :class:`~impactlab.data.carry.CarryTable` to fit instead of the shipped file (same rows).
    **options
        Passed to :func:`impactlab.data.carry.validate_carry` over each source's own air (a sensitivity, e.g.
        ``temperature=288.15``).

    Returns
    -------
    dict
        The fitted ``c0`` and ``lift_scale`` (1 unless fitted); ``rows`` fitted; ``rms_carry_error`` over the fitted
        rows (relative); ``at_bound`` (a parameter ended on its bound).

    Raises
    ------
    ValueError
        An unknown parameter or observable, or no row left to fit.
    """
    from scipy.optimize import least_squares  # scipy-heavy: only when fitting

    if not set(parameters) <= {"c0", "lift_scale"} or "c0" not in parameters:
        raise ValueError(f"parameters: expected ('c0',) or ('c0', 'lift_scale'), got {parameters!r}")
    if not set(observables) <= {"carry", "max_height"} or "carry" not in observables:
        raise ValueError(f"observables: expected ('carry',) or ('carry', 'max_height'), got {observables!r}")
    keep = np.array([name not in exclude and label not in exclude for name in sources for label in labels(name)])
    if not keep.any():
        raise ValueError(f"no row left to fit: {list(sources)} without {sorted(exclude)}")
    bounds = {"c0": C0_BOUNDS, "lift_scale": lift_scale_bounds()}
    start = {"c0": MEASURED_FIT["c0"] + 0.005, "lift_scale": 1.0}
    low = [bounds[p][0] for p in parameters]
    high = [bounds[p][1] for p in parameters]
    solution = least_squares(
        lambda x: _residuals(dict(zip(parameters, x)), sources, keep, observables, tables, options),
        [start[p] for p in parameters], bounds=(low, high), x_scale=[0.01 if p == "c0" else 0.1 for p in parameters],
        diff_step=1e-4, xtol=1e-8)
    params = {"c0": MEASURED_FIT["c0"], "lift_scale": 1.0, **dict(zip(parameters, map(float, solution.x)))}
    errors = np.concatenate([c["carry_error"] for c in _flights(params, sources, tables, **options)])[keep]
    at_bound = any(np.isclose(value, b, rtol=0, atol=1e-6) for p, value in zip(parameters, solution.x)
                   for b in bounds[p])
    return {**params, "rows": int(keep.sum()), "rms_carry_error": float(np.sqrt(np.mean(errors**2))),
            "at_bound": bool(at_bound)}


def leave_one_out(sources=SOURCES, by: str = "label", **options) -> list:
    """Refit without each group of rows and fly the group held out.

    Parameters
    ----------
    sources : sequence of str
        As for :func:`fit`.
    by : {"label", "source"}
        Leave out one row label at a time (e.g. one season of a source) or one source at a time.
    **options
        ``parameters`` and ``observables`` of :func:`fit`; the rest is passed to
        :func:`impactlab.data.carry.validate_carry` (fit and held-out flights alike).

    Returns
    -------
    list of dict
        Per group: ``group``, the parameters fitted without it, and ``carry_error`` (relative, one per held-out row)
        and ``rms_carry_error`` of the held-out rows.
    """
    if by not in ("label", "source"):
        raise ValueError(f"by: expected 'label' or 'source', got {by!r}")
    groups = list(sources) if by == "source" else [label for name in sources for label in labels(name)]
    if len(groups) < 2:
        raise ValueError(f"leave-one-out needs two groups or more, got {groups}")
    shape = {key: options.pop(key) for key in ("parameters", "observables") if key in options}
    out = []
    for group in groups:
        params = fit(sources, exclude=(group,), **shape, **options)
        errors = np.concatenate([c["carry_error"] for c in _flights(params, sources, **options)])
        held = np.array([group in (name, label) for name in sources for label in labels(name)])
        out.append({"group": group, "c0": params["c0"], "lift_scale": params["lift_scale"],
                    "carry_error": errors[held], "rms_carry_error": float(np.sqrt(np.mean(errors[held] ** 2)))})
    return out


def held_out(c0: float, lift_scale: float = 1.0, tables=TABLES, **options) -> dict:
    """TrackMan's tour tables flown with the fitted ``c0`` (and ``lift_scale``): nothing of them was fitted.

    Parameters
    ----------
    c0, lift_scale : float
        As returned by :func:`fit`.
    tables : sequence of str
        Default the three tour tables :data:`impactlab.data.carry.TABLES`.
    **options
        Passed to :func:`impactlab.data.carry.validate_carry` (default the standard air, 15 degC).

    Returns
    -------
    dict
        Per table name: the :func:`impactlab.data.carry.validate_carry` result plus ``rms_without_driver`` (the rows
        other than the driver, which share no shot with the radar seasons; relative), ``height_error`` [m] and
        ``land_error`` [rad] (model minus table).
    """
    model = coefficients(c0, lift_scale)
    out = {}
    for name in tables:
        check = validate_carry(model, carry_table(name), **options)
        other = np.array([club != "Driver" for club in check["table"].clubs])
        out[name] = {**check, "rms_without_driver": float(np.sqrt(np.mean(check["carry_error"][other] ** 2))),
                     "height_error": check["apex_height"] - check["table"].max_height,
                     "land_error": check["landing_angle"] - check["table"].land_angle}
    return out


def format_report(sources=SOURCES) -> str:
    """The fit, its leave-one-out and the held-out tour tables as Markdown (yards, degrees)."""
    lines = []
    main = fit(sources)
    rows = validate_carry(coefficients(main["c0"]), carry_table(sources[0]))
    base = validate_carry("measured_fit", carry_table(sources[0]))
    lines += [f"fit on {', '.join(sources)}: c0 = {main['c0']:.4f} (bounds {C0_BOUNDS[0]:.4f}-{C0_BOUNDS[1]:.4f}), "
              f"{main['rows']} rows, carry RMS {100 * main['rms_carry_error']:.2f} %", "",
              "| row | carry yd | measured_fit | fitted c0 | apex yd | fitted c0 | hang s | fitted c0 |",
              "|---|---|---|---|---|---|---|---|"]
    table = rows["table"]
    hang = table.flight_time if table.flight_time is not None else np.full(len(table.clubs), np.nan)
    for i, label in enumerate(labels(sources[0])):
        # a season whose hang time the source does not give (2018-19) shows "-", as the docs' table does
        hang_cells = (f"{hang[i]:.2f} | {rows['flight_time'][i] - hang[i]:+.2f}" if np.isfinite(hang[i])
                      else "- | -")
        lines.append(f"| {label} | {table.carry[i] / YARD:.1f} | {100 * base['carry_error'][i]:+.1f} % | "
                     f"{100 * rows['carry_error'][i]:+.1f} % | {table.max_height[i] / YARD:.1f} | "
                     f"{(rows['apex_height'][i] - table.max_height[i]) / YARD:+.1f} | {hang_cells} |")
    lines += ["", "| left out | c0 fitted without it | held-out carry error |", "|---|---|---|"]
    for fold in leave_one_out(sources):
        lines.append(f"| {fold['group']} | {fold['c0']:.4f} | "
                     + ", ".join(f"{100 * e:+.1f} %" for e in fold["carry_error"]) + " |")
    variants = [("measured_fit (c0 of the modern balls)", MEASURED_FIT["c0"], 1.0),
                ("fitted c0 (held out)", main["c0"], 1.0)]
    both = fit(sources, parameters=("c0", "lift_scale"), observables=("carry", "max_height"))
    variants.append((f"c0 and lift scale fitted to carry and apex ({both['c0']:.4f}, {both['lift_scale']:.3f})",
                     both["c0"], both["lift_scale"]))
    lines += ["", "| parameters | " + " | ".join(f"{t} RMS (without driver)" for t in TABLES)
              + " | height (mean) | land angle (mean) |", "|---" * (len(TABLES) + 3) + "|"]
    fitted = held_out(main["c0"])  # the fitted drag level's held-out tables: a row below and the per-club tables
    for title, c0, scale in variants:
        checks = fitted if (c0, scale) == (main["c0"], 1.0) else held_out(c0, scale)
        cells = [f"{100 * c['rms_carry_error']:.1f} % ({100 * c['rms_without_driver']:.1f} %)" for c in checks.values()]
        height = np.concatenate([c["height_error"] for c in checks.values()]) / YARD
        land = np.degrees(np.concatenate([c["land_error"] for c in checks.values()]))
        lines.append(f"| {title} | " + " | ".join(cells) + f" | {np.mean(height):+.1f} yd | {np.mean(land):+.1f} deg |")
    cold = fit(sources, temperature=288.15)
    lines += ["", "| sensitivity (air) | " + " | ".join(TABLES) + " |", "|---" * (len(TABLES) + 1) + "|"]
    for title, c0, options in ((f"tables at 25 degC too (c0 {main['c0']:.4f})", main["c0"], {"temperature": 298.15}),
                               (f"seasons fitted at 15 degC (c0 {cold['c0']:.4f})", cold["c0"], {})):
        lines.append(f"| {title} | " + " | ".join(f"{100 * c['rms_carry_error']:.2f} %"
                                                   for c in held_out(c0, **options).values()) + " |")
    for name, check in fitted.items():
        lines += ["", f"held out, {name}: RMS {100 * check['rms_carry_error']:.1f} %", "",
                  "| club | carry TM yd | error | height TM yd | error yd | land TM deg | error deg |",
                  "|---|---|---|---|---|---|---|"]
        for i, club in enumerate(check["table"].clubs):
            lines.append(f"| {club} | {check['table'].carry[i] / YARD:.0f} | {100 * check['carry_error'][i]:+.1f} % | "
                         f"{check['table'].max_height[i] / YARD:.0f} | {check['height_error'][i] / YARD:+.1f} | "
                         f"{np.degrees(check['table'].land_angle[i]):.0f} | "
                         f"{np.degrees(check['land_error'][i]):+.1f} |")
    return "\n".join(lines)


def report_command(module: str, description: str, report, argv=None) -> int:
    """``python -m impactlab.data.<module>``: print ``report()`` (the module's tables of docs/flight.md). The
    command takes no argument: one given is one message and exit code 2 (argparse), not ignored."""
    import argparse

    argparse.ArgumentParser(prog=f"python -m impactlab.data.{module}", description=description).parse_args(argv)
    print(report())
    return 0


def main(argv=None) -> int:
    """``python -m validation.flight.flight_fit``: the tables of docs/flight.md (:func:`report_command`)."""
    return report_command("flight_fit", "Fit the ball's drag level on measured radar flights and fly TrackMan's "
                                        "tour tables held out (docs/flight.md).", format_report, argv)


if __name__ == "__main__":  # pragma: no cover - prints the tables of docs/flight.md
    raise SystemExit(main())
