"""The coefficients of the ``measured_fit`` aerodynamic model, fitted to measured golf-ball lift and drag only.

The measurements are impactlab/data/validation/aero_coefficients.yaml: wind-tunnel, indoor-test-range and free-flight
CD and CL of golf balls against the spin ratio S and the Reynolds number Re, with their sources. TrackMan's carry
tables are never used here: they are what the model is validated on (:mod:`impactlab.data.carry`).

The fit has three least-squares stages, each on the rows its physics concerns:

1. supercritical lift of every ball (Re above its drag crisis): ``CL = a S / (1 + b S)``, zero at S = 0 and
   saturating at ``a / b`` (Naruo et al. 2004's and Bearman & Harvey's rows carry the saturation, S up to 1.13);
2. supercritical drag: ``CD = c_ball + c_re Re/1e5 + k CL_sc(S)^2``, one offset ``c_ball`` per ball group (measured
   balls differ by up to 0.04 in drag at equal S), the Re slope and the spin (induced) drag ``k`` shared; the model
   takes the modern balls' offset;
3. the drag crisis and the lift lost in it (reverse Magnus), on the modern balls' rows below Re 7.4e4 together with
   their supercritical rows: ``CD += d / (1 + exp((Re - Re_d exp(-m S)) / w_d))`` (a crisis reached at a lower Re the
   more the ball spins: the non-spinning 13-ball mean is still subcritical at Re 7.5e4 where three balls at 2250 rpm
   are not) and ``CL *= 1 - beta exp(-ln(Re/Re_l)^2 / (2 sigma^2)) exp(-S / s_l)``.

:func:`fit` can leave blocks out (``exclude``), fit another table of rows (``data``) or give a ball group its own
induced-drag factor (``own_k``): the cross-validation by source of :mod:`validation.flight.aero_sources`.

``python -m validation.flight.aero_fit`` prints the fitted constants and the residuals of each stage; the constants
written in :mod:`impactlab.physics.aerodynamics` are these (tests/test_flight.py refits and compares).
"""

from __future__ import annotations

import functools
from importlib import resources

import numpy as np
import yaml

#: the model's drag level is the offset of this ball group
MODEL_GROUP = "modern"
#: the ball groups of the measurements file, each with its own supercritical drag offset
GROUPS = ("modern", "usga_1998", "bh_1976", "naruo_2004", "acushnet_invention", "acushnet_prior_art")


@functools.cache
def measurements() -> dict:
    """The measured rows: ``re``, ``s``, ``cd``, ``cl`` (NaN where not measured), ``group`` (index into
    :data:`GROUPS`), ``block`` (the source block's key) and ``supercritical`` (Re at or above the group's crisis end),
    plus the document's ``blocks`` (citations) and ``supercritical_re`` (each group's crisis end)."""
    document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath(
        "aero_coefficients.yaml").read_text())
    assert document["kind"] == "measurement", document["kind"]
    rows, groups, blocks = [], [], []
    for key, block in document["blocks"].items():
        for row in block["rows"]:
            rows.append([np.nan if value is None else float(value) for value in row])
            groups.append(GROUPS.index(block["group"]))
            blocks.append(key)
    data = np.array(rows)
    group = np.array(groups)
    limit = np.array([document["supercritical_re"][name] for name in GROUPS])[group]
    # a row without Re (Lyu 2018 Fig. 4a) was measured at 32-91 m/s, Re above 9e4: supercritical
    supercritical = np.where(np.isnan(data[:, 0]), True, data[:, 0] >= limit)
    return {"re": data[:, 0], "s": data[:, 1], "cd": data[:, 2], "cl": data[:, 3], "group": group,
            "block": np.array(blocks), "supercritical": supercritical, "blocks": document["blocks"],
            "supercritical_re": dict(document["supercritical_re"])}


def lift_supercritical(s, a, b):
    """``a S / (1 + b S)``: the lift above the drag crisis."""
    return a * s / (1.0 + b * s)


def crisis_terms(s, re, re_l, sigma, beta, s_l, re_d, w_d, d, spin_advance=0.0):
    """(added drag, lift factor) of the drag crisis at ``re`` and ``s``.

    ``spin_advance`` (m) moves the drag step's midpoint with the spin ratio, ``Re_d exp(-m S)``: m > 0 is a crisis
    reached at a lower Re the more the ball spins (``measured_fit``'s m, :func:`fit`); m = 0 a crisis where it is
    without spin.
    """
    midpoint = re_d * np.exp(-spin_advance * s)
    drag = d * 0.5 * (1.0 - np.tanh(0.5 * (re - midpoint) / w_d))  # d / (1 + exp((Re - Re_d) / w_d)), no overflow
    lift = 1.0 - beta * np.exp(-0.5 * (np.log(re / re_l) / sigma) ** 2) * np.exp(-s / s_l)
    return drag, lift


#: stage 3's start, scale and bounds per parameter (Re_l, sigma, beta, s_l, Re_d, w_d, d), then the spin advance m
_CRISIS_START = [6.3e4, 0.1, 1.5, 0.2, 5.8e4, 5e3, 0.3]
_CRISIS_SCALE = [1e4, 0.05, 0.5, 0.1, 1e4, 1e3, 0.1]
_CRISIS_BOUNDS = ([4e4, 0.02, 0, 0.02, 3e4, 500, 0], [1e5, 0.5, 5, 2, 1e5, 3e4, 1])
#: the spin advance's start, scale and bounds (either sign allowed: the data decide the direction)
_ADVANCE = (0.5, 0.5, (-5.0, 5.0))


def crisis_at_bounds(crisis) -> list:
    """The names of stage 3's constants (Re_l, sigma, beta, s_l, Re_d, w_d, d, m) that a fit left on a bound of
    its search: not determined by the rows (a refit without the rows that place the crisis)."""
    names = ("Re_l", "sigma", "beta", "s_l", "Re_d", "w_d", "d", "m")
    low, high = [*_CRISIS_BOUNDS[0], _ADVANCE[2][0]], [*_CRISIS_BOUNDS[1], _ADVANCE[2][1]]
    return [name for name, value, lo, hi in zip(names, crisis, low, high) if np.isclose(value, lo, rtol=1e-6, atol=0)
            or np.isclose(value, hi, rtol=1e-6, atol=0)]


def _rms(x) -> float:
    return float(np.sqrt(np.mean(np.square(x))))


def _supercritical_stages(m: dict, own_k=()):
    """Stages 1 and 2: the lift (a, b), the drag (offsets per group, c_re, k and one k per group of ``own_k``) and
    their row masks. A group without drag rows gets no offset (NaN)."""
    from scipy.optimize import least_squares  # scipy-heavy: only when fitting

    re, s, cd, cl, group, sc = m["re"], m["s"], m["cd"], m["cl"], m["group"], m["supercritical"]
    lift_rows = sc & np.isfinite(cl)
    lift = least_squares(lambda p: lift_supercritical(s[lift_rows], *p) - cl[lift_rows], [2.0, 4.0]).x
    drag_rows = sc & np.isfinite(cd)
    present = [g for g in range(len(GROUPS)) if np.any(drag_rows & (group == g))]
    n = len(present)
    slot = np.full(len(GROUPS), -1)
    slot[present] = np.arange(n)
    # the induced-drag factor of each group: the shared one (n + 1) or its own (n + 2, ...)
    k_slot = np.full(len(GROUPS), n + 1)
    k_slot[[GROUPS.index(name) for name in own_k]] = n + 2 + np.arange(len(own_k))

    def drag_model(p, rows):
        k = p[n + 1] if not own_k else p[k_slot[group[rows]]]
        return p[slot[group[rows]]] + p[n] * re[rows] / 1e5 + k * lift_supercritical(s[rows], *lift) ** 2

    fitted = least_squares(lambda p: drag_model(p, drag_rows) - cd[drag_rows], [0.22] * n + [0.0, 1.0]
                           + [1.0] * len(own_k)).x
    rms = {"lift supercritical": _rms(lift_supercritical(s[lift_rows], *lift) - cl[lift_rows]),
           "drag supercritical": _rms(drag_model(fitted, drag_rows) - cd[drag_rows])}
    offsets = np.array([fitted[slot[g]] if slot[g] >= 0 else np.nan for g in range(len(GROUPS))])
    drag = {"offsets": offsets, "c_re": fitted[n], "k": fitted[k_slot]}  # k per group
    return lift, drag, lift_rows, rms


def _crisis_stage(m: dict, lift, drag, lift_rows, spin_advance: bool):
    """Stage 3 on the modern balls' rows: the crisis constants (plus the spin advance m when asked), their standard
    errors from the Jacobian, and the residual RMS per row set."""
    from scipy.optimize import least_squares  # scipy-heavy: only when fitting

    re, s, cd, cl, group, sc = m["re"], m["s"], m["cd"], m["cl"], m["group"], m["supercritical"]
    model = GROUPS.index(MODEL_GROUP)
    offset, c_re, k = drag["offsets"][model], drag["c_re"], drag["k"][model]
    modern = group == GROUPS.index(MODEL_GROUP)
    low_cd = modern & ~sc & np.isfinite(cd)
    low_cl = modern & ~sc & np.isfinite(cl)
    high_cd = modern & sc & np.isfinite(cd)

    def coefficients(p, rows):
        # rows without Re are supercritical (above 9e4): the crisis terms vanish there, take 1e6
        r = np.where(np.isnan(re[rows]), 1e6, re[rows])
        extra, factor = crisis_terms(s[rows], r, *p)
        return (offset + c_re * r / 1e5 + k * lift_supercritical(s[rows], *lift) ** 2 + extra,
                lift_supercritical(s[rows], *lift) * factor)

    def residuals(p):
        return np.concatenate([coefficients(p, low_cd)[0] - cd[low_cd], coefficients(p, low_cl)[1] - cl[low_cl],
                               coefficients(p, high_cd)[0] - cd[high_cd],
                               coefficients(p, lift_rows)[1] - cl[lift_rows]])

    start, scale, (low, high) = list(_CRISIS_START), list(_CRISIS_SCALE), _CRISIS_BOUNDS
    if spin_advance:
        start, scale = start + [_ADVANCE[0]], scale + [_ADVANCE[1]]
        low, high = [*low, _ADVANCE[2][0]], [*high, _ADVANCE[2][1]]
    solution = least_squares(residuals, start, x_scale=scale, bounds=(low, high))
    # standard errors: (J^T J)^-1 times the residual variance (least_squares' Jacobian at the solution)
    variance = float(solution.fun @ solution.fun) / (solution.fun.size - solution.x.size)
    errors = np.sqrt(np.diag(np.linalg.pinv(solution.jac.T @ solution.jac)) * variance)
    p = solution.x
    rms = {"drag crisis (modern, Re < 7.4e4)": _rms(coefficients(p, low_cd)[0] - cd[low_cd]),
           "lift crisis (modern, Re < 7.4e4)": _rms(coefficients(p, low_cl)[1] - cl[low_cl]),
           "drag supercritical (modern)": _rms(coefficients(p, high_cd)[0] - cd[high_cd]),
           "lift crisis without the crisis terms": _rms(lift_supercritical(s[low_cl], *lift) - cl[low_cl])}
    rows = {"drag crisis": int(low_cd.sum()), "lift crisis": int(low_cl.sum())}
    return p, errors, rms, rows


def select(m: dict, exclude=(), own_k=()) -> dict:
    """:func:`measurements` (or another table ``m`` of the same keys) without the rows of the blocks ``exclude``.

    Raises
    ------
    ValueError
        A block or group name the table does not have, or rows left that leave a stage of :func:`fit` without what it
        fits: the supercritical lift or drag, a drag offset for ``own_k``, or the modern balls' crisis (drag and lift
        below their crisis end) and drag level.
    """
    blocks = sorted(str(name) for name in set(m["block"]))
    unknown = sorted(set(exclude) - set(blocks))
    if unknown:
        raise ValueError(f"unknown block {unknown}; the measurement blocks are {blocks}")
    if not set(own_k) <= set(GROUPS):
        raise ValueError(f"unknown ball group {sorted(set(own_k) - set(GROUPS))}; the groups are {list(GROUPS)}")
    keep = ~np.isin(m["block"], list(exclude))
    kept = {key: (value[keep] if isinstance(value, np.ndarray) else value) for key, value in m.items()}
    sc, modern = kept["supercritical"], kept["group"] == GROUPS.index(MODEL_GROUP)
    needs = {"stage 1 (supercritical lift)": sc & np.isfinite(kept["cl"]),
             "stage 2 (supercritical drag)": sc & np.isfinite(kept["cd"]),
             "stage 2 (the modern balls' drag level)": modern & sc & np.isfinite(kept["cd"]),
             "stage 3 (the modern balls' drag crisis)": modern & ~sc & np.isfinite(kept["cd"]),
             "stage 3 (the modern balls' lift crisis)": modern & ~sc & np.isfinite(kept["cl"])}
    needs.update({f"stage 2 (the own k of {name})": sc & np.isfinite(kept["cd"]) & (
        kept["group"] == GROUPS.index(name)) for name in own_k})
    empty = [stage for stage, rows in needs.items() if not rows.any()]
    if empty:
        raise ValueError(f"leaving out {sorted(exclude)} leaves {', '.join(empty)} without rows: nothing to fit there")
    return kept


def fit(spin_advance: bool = True, exclude=(), data: dict | None = None, own_k=()) -> dict:
    """Fit the three stages (module docstring) to :func:`measurements`.

    Parameters
    ----------
    spin_advance : bool
        Fit the crisis midpoint's spin advance m (``measured_fit``); False holds m = 0, the crisis of a ball without
        spin at every S (the model before 2026-11-24, kept to show what m changes).
    exclude : collection of str
        Blocks of the measurements file left out (cross-validation by source, :mod:`validation.flight.aero_sources`).
    data : dict, optional
        A table of :func:`measurements`' keys fitted instead of the file's (a sensitivity, e.g. rows at another Re).
    own_k : collection of str
        Ball groups given their own induced-drag factor k (a structural sensitivity); the others share one.

    Returns
    -------
    dict
        ``lift`` (a, b); ``offsets`` (the supercritical drag offset of each group of :data:`GROUPS`, NaN for a group
        without rows), ``c_re`` and ``k`` (the modern balls'); ``crisis`` (Re_l, sigma, beta, s_l, Re_d, w_d, d and,
        with ``spin_advance``, m) and its standard errors ``errors`` (from the Jacobian); ``rms`` residuals per stage
        and quantity; ``rows`` counted per stage; with ``own_k`` also ``k_groups`` (k of each group).

    Raises
    ------
    ValueError
        From :func:`select`: an unknown block or group, or a stage left without rows.
    """
    m = measurements() if data is None else data
    if exclude or own_k:
        m = select(m, exclude, own_k)
    lift, drag, lift_rows, rms = _supercritical_stages(m, tuple(own_k))
    crisis, errors, crisis_rms, crisis_rows = _crisis_stage(m, lift, drag, lift_rows, spin_advance=spin_advance)
    rms.update(crisis_rms)
    model = GROUPS.index(MODEL_GROUP)
    out = {"lift": tuple(float(v) for v in lift),
           "offsets": {name: float(drag["offsets"][index]) for index, name in enumerate(GROUPS)},
           "c_re": float(drag["c_re"]), "k": float(drag["k"][model]),
           "crisis": tuple(float(v) for v in crisis), "errors": tuple(float(v) for v in errors), "rms": rms,
           "rows": {"lift supercritical": int(lift_rows.sum()), "drag supercritical": int(np.sum(
               m["supercritical"] & np.isfinite(m["cd"]))), **crisis_rows}}
    if own_k:
        out["k_groups"] = {name: float(drag["k"][index]) for index, name in enumerate(GROUPS)}
    return out


@functools.cache
def fit_without_spin_advance() -> dict:
    """:func:`fit` with m = 0, computed once per process (what the spin advance changes)."""
    return fit(spin_advance=False)


if __name__ == "__main__":  # pragma: no cover - prints the constants of docs/flight.md
    names = ("Re_l", "sigma", "beta", "s_l", "Re_d", "w_d", "d", "m")
    for advance in (True, False):
        result = fit(spin_advance=advance)
        print("with the spin advance m (measured_fit):" if advance else "\nwith m = 0 (the crisis without spin):")
        print("lift a, b:", ", ".join(f"{v:.4g}" for v in result["lift"]))
        print("drag offsets", {name: round(value, 4) for name, value in result["offsets"].items()},
              f"c_re {result['c_re']:.4g}, k {result['k']:.4g}")
        pairs = zip(names, result["crisis"], result["errors"])
        print("crisis:", ", ".join(f"{n} {v:.4g} +- {e:.2g}" for n, v, e in pairs))
        for key, value in result["rms"].items():
            print(f"rms {key}: {value:.4f}")
        print(result["rows"])
