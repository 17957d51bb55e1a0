"""``measured_fit`` cross-validated by source: each publication of the measured CD and CL left out in turn.

:mod:`validation.flight.aero_fit` fits ``measured_fit`` to every measured row at once. Here each source (a publication,
:data:`SOURCES`) is left out of that fit in turn (:func:`leave_one_out`), and

(a) the left-out source's own CD and CL rows are compared with the refit (how well the other sources predict it) and
    with the full fit (:func:`source_residuals`);
(b) TrackMan's three tour tables (:data:`impactlab.data.carry.TABLES`, never fitted) are flown with the refit, with the
    refit's modern drag level ``c0`` and with ``c0`` refitted on the PGA TOUR radar seasons as
    :mod:`validation.flight.flight_fit` does (:func:`radar_c0`).

:func:`sensitivities` does the same for structural choices: the 1976 ball's own induced-drag factor k, Naruo et al.'s
rows entered at each Re they were measured at (instead of 1e5), the non-spinning drag the spin advance rests on
moved by a ball-to-ball difference, the spin advance of the crisis held at the largest S
measured (:data:`ADVANCE_CAPS`), and no advance. ``python -m validation.flight.aero_sources`` prints the tables
(about 30 s).

References
----------
Naruo, Mizota & Shimozono (2004), Trans. JSME B 70(697):2371-2377, doi:10.1299/kikaib.70.2371: Re 7.09e4, 8.51e4,
9.93e4, 1.13e5, 1.25e5 (open-jet tunnel, 25-44 m/s), ball spun up to 167 rev/s, d 42.7 mm (as read by
jhoblitt/tmelevation, docs/research/land-angle-spike/literature.md.notes.md, N3a-b; not re-read here).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from validation.flight import aero_fit, flight_fit
from impactlab.data.carry import TABLES, carry_table, validate_carry

#: publication -> the blocks of impactlab/data/validation/aero_coefficients.yaml it measured
SOURCES = {
    "lyu_2020": ("lyu_2020_fig3_b330rx", "lyu_2020_fig3_chromesoft", "lyu_2020_fig3_prov1", "lyu_2020_fig4_re50k",
                 "lyu_2020_fig4_re60k", "lyu_2020_fig4_re70k", "lyu_2020_fig4_re75k", "lyu_2020_fig5_b330rx",
                 "lyu_2020_fig5_chromesoft", "lyu_2020_fig5_prov1"),
    "lyu_2018": ("lyu_2018_fig3a", "lyu_2018_fig4a"),
    "naruo_2004": ("naruo_2004",),
    "acushnet_us6729976": ("acushnet_us6729976_table3", "acushnet_us6729976_table4"),
    "usga_us6186002": ("usga_itr_example",),
    "bridgestone_patents": ("bridgestone_patents",),
    "bearman_harvey_1976": ("bearman_harvey_1976",),
}
#: Naruo et al. 2004's five Reynolds numbers (their CD and CL "fall on almost one curve" across them)
NARUO_RE = (70900.0, 85100.0, 99300.0, 113000.0, 125000.0)
#: Naruo et al.'s largest spin, rev/s, and ball diameter, m (N3a of the tmelevation notes)
NARUO_SPIN, NARUO_DIAMETER = 167.0, 0.0427
#: Re per m/s of Naruo's tunnel: 7.09e4 at its lowest speed, 25 m/s (1.25e5 at 44 m/s gives 2841)
NARUO_RE_PER_SPEED = 70900.0 / 25.0
#: a spin ratio within 2 % of the largest is counted reachable (the lowest speed, 25 m/s, is stated to two figures)
NARUO_REACH_TOLERANCE = 1.02


def _crisis_rows_top(column: str) -> float:
    """The largest S of the modern balls' rows below their crisis end that measure ``column`` (stage 3's rows)."""
    m = aero_fit.measurements()
    modern = m["group"] == aero_fit.GROUPS.index(aero_fit.MODEL_GROUP)
    return float(np.max(m["s"][modern & ~m["supercritical"] & np.isfinite(m[column])]))


#: the spin ratios where the crisis advance is held: the largest S of the drag rows that place the crisis of a
#: spinning ball (Lyu et al. 2020 Fig. 3 at Re 5e4, 0.276), and of the lift-crisis rows (Lyu 2020 Fig. 4, 0.361)
ADVANCE_CAPS = (_crisis_rows_top("cd"), _crisis_rows_top("cl"))


def naruo_reach(re) -> np.ndarray:
    """The largest spin ratio Naruo et al. could set at Reynolds number ``re``: ``pi d N_max / U`` with
    ``U = Re / (Re per m/s)`` (0.896 at 7.09e4, 0.508 at 1.25e5)."""
    return np.pi * NARUO_DIAMETER * NARUO_SPIN / (np.asarray(re, dtype=float) / NARUO_RE_PER_SPEED)


def blocks_of(source: str) -> tuple:
    """The blocks of publication ``source``; ValueError naming the sources for an unknown one."""
    if source not in SOURCES:
        raise ValueError(f"unknown source {source!r}; the sources are {list(SOURCES)}")
    return SOURCES[source]


def coefficients(result: dict, c0: float | None = None, advance_cap: float | None = None):
    """A fit of :func:`validation.flight.aero_fit.fit` as a function ``(S, Re) -> (CD, CL)`` for
    :func:`impactlab.physics.flight.fly`: ``measured_fit``'s formulas at the fit's constants.

    Parameters
    ----------
    result : dict
        :func:`validation.flight.aero_fit.fit`'s output.
    c0 : float, optional
        Supercritical drag level; default the fit's modern balls' offset.
    advance_cap : float, optional
        The crisis midpoint ``Re_d exp(-m min(S, cap))``: the advance with spin held beyond ``cap`` (default none).
    """
    a, b = result["lift"]
    re_l, sigma, beta, s_l, re_d, w_d, d, *advance = result["crisis"]
    m = advance[0] if advance else 0.0
    offset = result["offsets"][aero_fit.MODEL_GROUP] if c0 is None else c0

    def cd_cl(s, re):
        s, re = np.asarray(s, dtype=float), np.asarray(re, dtype=float)
        held = s if advance_cap is None else np.minimum(s, advance_cap)
        extra, _ = aero_fit.crisis_terms(held, re, re_l, sigma, beta, s_l, re_d, w_d, d, m)
        _, factor = aero_fit.crisis_terms(s, np.maximum(re, 1.0), re_l, sigma, beta, s_l, re_d, w_d, d, m)
        lift = aero_fit.lift_supercritical(s, a, b)
        return offset + result["c_re"] * re / 1e5 + result["k"] * lift**2 + extra, lift * factor

    return cd_cl


def source_residuals(result: dict, blocks, own_offset: bool = False) -> dict:
    """RMS of CD and CL of the rows of ``blocks`` about the fit ``result``, in the form the fit gives each row: the
    modern balls' rows with the crisis terms (:func:`coefficients`; a row without Re, Lyu 2018 Fig. 4a, above 9e4,
    taken at 1e6), the other balls' rows above their own crisis with the supercritical drag and lift (stages 1-2 of
    :func:`validation.flight.aero_fit.fit`; their rows in the crisis are not fitted and not counted).

    ``own_offset`` takes each row's own ball-group offset for the drag (NaN where the fit has none) instead of the
    model's drag level: how well the fit describes the rows, not how well it predicts them.
    """
    m = aero_fit.measurements()
    modern = m["group"] == aero_fit.GROUPS.index(aero_fit.MODEL_GROUP)
    rows = np.isin(m["block"], list(blocks)) & (modern | m["supercritical"])
    s, re = m["s"][rows], np.where(np.isnan(m["re"][rows]), 1e6, m["re"][rows])
    lift = aero_fit.lift_supercritical(s, *result["lift"])
    offset = result["offsets"][aero_fit.MODEL_GROUP]
    cd, cl = offset + result["c_re"] * re / 1e5 + result["k"] * lift**2, lift
    full_cd, full_cl = coefficients(result)(s, re)
    cd, cl = np.where(modern[rows], full_cd, cd), np.where(modern[rows], full_cl, cl)
    if own_offset:
        cd = cd + np.array([result["offsets"][name] for name in aero_fit.GROUPS])[m["group"][rows]] - offset
    out = {}
    for name, model, measured in (("cd", cd, m["cd"][rows]), ("cl", cl, m["cl"][rows])):
        have = np.isfinite(measured)
        out[name] = float(np.sqrt(np.mean((model[have] - measured[have]) ** 2))) if have.any() else np.nan
        out[f"n_{name}"] = int(have.sum())
    return out


def unfitted_high_spin(result: dict, advance_cap: float | None = None) -> float:
    """CD RMS at Bearman & Harvey's rows that no fit uses (below their ball's crisis end, Re 3.78e4) at S >= 0.28,
    the spin ratios of the irons' descents: the modern model with the 1976 ball's drag offset (the full fit's where
    ``result`` has none). A check of the crisis' advance beyond the S it was fitted at (< 0.28)."""
    m, offset = aero_fit.measurements(), result["offsets"]["bh_1976"]
    rows = (m["block"] == "bearman_harvey_1976") & ~m["supercritical"] & (m["s"] >= 0.28) & np.isfinite(m["cd"])
    offset = aero_fit.fit()["offsets"]["bh_1976"] if not np.isfinite(offset) else offset
    cd, _ = coefficients(result, offset, advance_cap)(m["s"][rows], m["re"][rows])
    return float(np.sqrt(np.mean((cd - m["cd"][rows]) ** 2)))


def tour_rms(cd_cl) -> dict:
    """Carry RMS (relative) of each of TrackMan's tour tables flown with ``cd_cl`` (the standard air, as
    :func:`impactlab.data.carry.validate_carry` flies them)."""
    return {name: float(np.sqrt(np.mean(validate_carry(cd_cl, carry_table(name))["carry_error"] ** 2)))
            for name in TABLES}


def radar_c0(result: dict, advance_cap: float | None = None) -> float:
    """``c0`` least-squares fitted to the carries of :data:`validation.flight.flight_fit.SOURCES` (PGA TOUR radar
    seasons, each in its own air) with the rest of ``result`` held, as :func:`validation.flight.flight_fit.fit` does
    for ``measured_fit``; bounded by the smallest and largest drag offset of the fit's ball groups."""
    from scipy.optimize import least_squares  # scipy-heavy: only when fitting

    offsets = [value for value in result["offsets"].values() if np.isfinite(value)]
    low, high = min(offsets), max(offsets)
    tables = [carry_table(name) for name in flight_fit.SOURCES]

    def residuals(x):
        model = coefficients(result, float(x[0]), advance_cap)
        return np.concatenate([validate_carry(model, table)["carry_error"] for table in tables])

    start = min(max(result["offsets"][aero_fit.MODEL_GROUP] + 0.005, low), high)
    solution = least_squares(residuals, [start], bounds=([low], [high]), x_scale=[0.01], diff_step=1e-4, xtol=1e-8)
    return float(solution.x[0])


def evaluate(result: dict, advance_cap: float | None = None) -> dict:
    """A fit's constants, its tour tables with its own ``c0`` and with :func:`radar_c0`."""
    c0 = radar_c0(result, advance_cap)
    return {"fit": result, "tour": tour_rms(coefficients(result, advance_cap=advance_cap)), "radar_c0": c0,
            "tour_radar": tour_rms(coefficients(result, c0, advance_cap)),
            "high_spin": unfitted_high_spin(result, advance_cap)}


def leave_one_out(sources=tuple(SOURCES)) -> list:
    """Refit ``measured_fit`` without each source; per source the :func:`evaluate` of the refit plus the source's
    residuals (:func:`source_residuals`) under the refit (``refit``), the full fit (``full``) and the full fit with
    its own group offsets (``full_own``)."""
    full = aero_fit.fit()
    out = []
    for source in sources:
        blocks = blocks_of(source)
        refit = aero_fit.fit(exclude=blocks)
        out.append({"source": source, **evaluate(refit), "refit": source_residuals(refit, blocks),
                    "full": source_residuals(full, blocks), "full_own": source_residuals(full, blocks, True)})
    return out


def naruo_at(re) -> dict:
    """:func:`validation.flight.aero_fit.measurements` with Naruo et al.'s rows at Reynolds number ``re`` (a number,
    or one per row)."""
    m = dict(aero_fit.measurements())
    rows = m["block"] == "naruo_2004"
    m["re"], m["supercritical"] = m["re"].copy(), m["supercritical"].copy()
    m["re"][rows] = re
    m["supercritical"][rows] = m["re"][rows] >= m["supercritical_re"]["naruo_2004"]
    return m


def naruo_reachable() -> np.ndarray:
    """Each Naruo row's Re: the mean of the five Re whose speed allowed its S (:func:`naruo_reach`); the lowest Re
    for S beyond every one (S 1.0 and 1.13: the tunnel's 25 m/s and 167 rev/s reach 0.896)."""
    s = aero_fit.measurements()["s"][aero_fit.measurements()["block"] == "naruo_2004"]
    reach = naruo_reach(NARUO_RE)
    return np.array([np.mean([r for r, top in zip(NARUO_RE, reach) if NARUO_REACH_TOLERANCE * top >= x]
                             or [NARUO_RE[0]]) for x in s])


def naruo_within_reach() -> dict:
    """:func:`validation.flight.aero_fit.measurements` without Naruo et al.'s rows beyond the largest S their tunnel
    could set at any of their Re (S 1.0 and 1.13 beyond 0.896, :data:`NARUO_REACH_TOLERANCE`: the paper's polynomial
    evaluated there)."""
    m = aero_fit.measurements()
    keep = ~((m["block"] == "naruo_2004") & (m["s"] > NARUO_REACH_TOLERANCE * naruo_reach(NARUO_RE[0])))
    return {key: (value[keep] if isinstance(value, np.ndarray) else value) for key, value in m.items()}


def still_at_75k(shift: float = 0.0, in_crisis: bool = False) -> dict:
    """:func:`validation.flight.aero_fit.measurements` with the non-spinning 13-ball mean CD at Re 7.5e4 (Lyu et al.
    2018 Fig. 3a, 0.302) moved by ``shift`` (the spin advance rests on it against three other balls spinning, and
    the balls' drag is "relatively large (> 0.1)" apart below Re 1e5), or counted in the crisis (``in_crisis``: out
    of stage 2's supercritical rows; the fit's own crisis puts 40 % of the drag step there)."""
    m = aero_fit.measurements()
    row = (m["block"] == "lyu_2018_fig3a") & (m["re"] == 75000.0)
    return {**m, "cd": np.where(row, m["cd"] + shift, m["cd"]), "supercritical": m["supercritical"] & ~(
        row & in_crisis)}


def sensitivities() -> list:
    """(title, :func:`evaluate`) of the full fit and of each structural variant (module docstring)."""
    variants: list[tuple[str, dict[str, Any], float | None]] = [
        ("full fit (measured_fit)", {}, None), ("k of the 1976 ball its own", {"own_k": ("bh_1976",)}, None)]
    variants += [(f"Naruo rows at Re {re:.3g}", {"data": naruo_at(re)}, None) for re in NARUO_RE]
    variants += [("Naruo rows at the Re that reach their S", {"data": naruo_at(naruo_reachable())}, None),
                 ("Naruo rows within the tunnel's reach (S <= 0.9)", {"data": naruo_within_reach()}, None)]
    variants += [(f"13-ball mean CD at Re 7.5e4 {shift:+.2f}", {"data": still_at_75k(shift)}, None)
                 for shift in (-0.05, 0.05)] + [("13-ball mean at Re 7.5e4 in the crisis", {
                     "data": still_at_75k(in_crisis=True)}, None)]
    variants += [(f"advance held beyond S {cap:.3f}", {}, cap) for cap in ADVANCE_CAPS]
    variants += [("no advance (m = 0)", {"spin_advance": False}, None)]
    return [(title, evaluate(aero_fit.fit(**options), cap)) for title, options, cap in variants]


def _percent(values: dict) -> str:
    return " / ".join(f"{100 * v:.2f}" for v in values.values())

def _constants(result: dict) -> str:
    crisis = result["crisis"]
    m = f"{crisis[7]:.2f}" if len(crisis) > 7 else "0"
    a, b = result["lift"]
    bound = aero_fit.crisis_at_bounds(crisis)
    return (f"{result['offsets'][aero_fit.MODEL_GROUP]:.4f} | {result['k']:.3f} | {a / b:.3f} | {crisis[4]:.0f} | {m}"
            + (f" ({', '.join(bound)} on a bound)" if bound else ""))


def format_report(sources=tuple(SOURCES), structural: bool = True) -> str:
    """The leave-one-source-out and the sensitivities as Markdown tables (carry RMS in %)."""
    head = "c0 | k | a/b | Re_d | m | tour carry RMS % (c0 of the fit) | radar c0 | tour carry RMS % (radar c0)"
    lines = [f"| left out | rows CD / CL | CD RMS: full fit own offset / full fit c0 / refit c0 | CL RMS: full / refit"
             f" | {head} |", "|---" * (4 + head.count("|") + 1) + "|"]
    for fold in leave_one_out(sources):
        full, own, refit = fold["full"], fold["full_own"], fold["refit"]
        lines.append(f"| {fold['source']} | {refit['n_cd']} / {refit['n_cl']} | {own['cd']:.4f} / {full['cd']:.4f} / "
                     f"{refit['cd']:.4f} | {full['cl']:.4f} / {refit['cl']:.4f} | {_constants(fold['fit'])} | "
                     f"{_percent(fold['tour'])} | {fold['radar_c0']:.4f} | {_percent(fold['tour_radar'])} |")
    if structural:
        lines += ["", f"| variant | {head} | CD RMS at B&H rows never fitted (Re 3.8e4, S 0.3-1) |",
                  "|---" * (1 + head.count("|") + 2) + "|"]
        for title, run in sensitivities():
            lines.append(f"| {title} | {_constants(run['fit'])} | {_percent(run['tour'])} | {run['radar_c0']:.4f} | "
                         f"{_percent(run['tour_radar'])} | {run['high_spin']:.3f} |")
        reach = ", ".join(f"{re:.3g}: {top:.3f}" for re, top in zip(NARUO_RE, naruo_reach(NARUO_RE)))
        lines += ["", f"Naruo et al.'s largest S per Re (167 rev/s): {reach}", f"tables: {', '.join(TABLES)}"]
    return "\n".join(lines)


def main(argv=None) -> int:
    """``python -m validation.flight.aero_sources [--source NAME]``: the tables of :func:`format_report`; one source
    (no structural variants) with ``--source``; an unknown source or argument is one message and exit code 2."""
    import argparse

    parser = argparse.ArgumentParser(prog="python -m validation.flight.aero_sources",
                                     description="measured_fit cross-validated by source of the measured CD and CL.")
    parser.add_argument("--source", choices=list(SOURCES), help="leave out only this source")
    args = parser.parse_args(argv)
    print(format_report((args.source,), structural=False) if args.source else format_report())
    return 0


if __name__ == "__main__":  # pragma: no cover - prints the tables of notes/report_aeroloso.md
    raise SystemExit(main())
