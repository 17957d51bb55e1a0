"""The benchmark table ``impactlab validate`` prints, and the figures of docs/benchmarks.md."""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

from impactlab.io.safe_output import write_figure
from impactlab.data.validation.benchmarks import (
    BENCHMARKS, MODELS, kharaz_quantities, make_model, read_reference, chung_ooi_5_quantities, chung_ooi_6_incidence,
    chung_ooi_6_quantities,
)
from impactlab.data.validation.benchmarks import _normal_cases


def over_budget(errors: dict) -> list[str]:
    """``key/model`` of every benchmark error above its budget."""
    return [f"{key}/{model}" for key, per_model in errors.items() for model, error in per_model.items()
            if model in BENCHMARKS[key].budgets and not error["rms"] <= BENCHMARKS[key].budgets[model]]


def format_table(errors: dict) -> str:
    """The RMS error of every model on every benchmark, with each budget, as text."""
    models = list(next(iter(errors.values())))
    lines = ["Benchmarks (Chung & Ooi 2011 tests 1-6 and 8; test 4 = Kharaz et al. 2001): RMS error (budget)",
             f"  {'test':<32}{'units':<7}{'reference':<14}" + "".join(f"{model:>19}" for model in models)]
    for key, per_model in errors.items():
        bench = BENCHMARKS[key]
        kind = {"model output (FEM)": "FEM (model)", "model output (DEM)": "DEM (model)"}.get(bench.kind, bench.kind)
        cells = []
        for model in models:
            rms, budget = per_model[model]["rms"], bench.budgets.get(model)
            if math.isnan(rms):
                cells.append(f"{'n/a':>19}")
                continue
            mark = "" if budget is None or rms <= budget else "!"
            cells.append(f"{f'{rms:.3g}' + ('' if budget is None else f' ({budget:g})') + mark:>19}")
        units = "rel." if bench.relative else bench.units
        lines.append(f"  {key:<32}{units:<7}{kind[:13]:<14}" + "".join(cells))
    lines.append("  n/a: the model has no contact time or force history; !: over budget. "
                 "Conditions and sources: docs/benchmarks.md")
    return "\n".join(lines)


def describe(key: str) -> str:
    """One benchmark's conditions and reference, for the printout."""
    bench = BENCHMARKS[key]
    return (f"{key}: {bench.test}, {bench.quantity} [{bench.units}]\n  conditions: {bench.conditions}\n"
            f"  reference ({bench.kind}): {bench.reference}")


# -- figures ------------------------------------------------------------------------------------------------------
STYLE = {"maw": ("C0", "-"), "maw_hysteretic": ("C0", ":"), "hertz_mindlin": ("C1", "-"), "dem_linear": ("C2", "-"),
         "rigid_coulomb": ("C3", "--"), "restitution": ("C4", ":")}
MARKERS = {"measurement": ("o", "k"), "model output": ("s", "0.45")}


def _label(model_id, y, drawn):
    """The legend label of a model curve: says which earlier curve it lies on (0.2 % of the range) or nearly."""
    scale = max(float(np.nanmax(np.abs(y))), 1e-300)
    label = model_id
    for other, values in drawn:
        if values.shape != y.shape:
            continue
        gap = np.nanmax(np.abs(values - y))
        if gap <= 2e-3 * scale:
            label = f"{model_id} (lies on {other})"
            break
        if gap <= 2e-2 * scale and label == model_id:
            label = f"{model_id} (within 2 % of {other})"
    drawn.append((model_id, y))
    return label


def _reference_points(ax, file, transform=None, only=None):
    for name, series in read_reference(file).series.items():
        if only is not None and name not in only:
            continue
        marker, colour = MARKERS[series.kind]
        if name == "fem":
            marker = "D"
        y = series.y if transform is None else transform(series.y)
        label = {"experiment": "Kharaz et al. 2001 (measured)", "fem": "FEM (model output)"}.get(
            name, "a DEM code, " + name.removeprefix("dem_").replace("_", " ") + " (model output)")
        if name == "published":
            label = "Chung & Ooi's curve (digitised)"
        ax.plot(series.x, y, marker, color=colour, mfc="none" if name.startswith("dem") else colour,
                ms=5, ls="none", label=label, zorder=5)


def _model_curves(ax, x, compute, quantity, models, transform=None, at=None):
    drawn = []
    for model_id in models:
        colour, style = STYLE[model_id]
        y = compute(make_model(model_id), x if at is None else at(x))[quantity]
        y = y if transform is None else transform(y)
        ax.plot(x, y, color=colour, ls=style, lw=1.4, label=_label(model_id, y, drawn))


def _curve_panels(axes, x, compute, panels, models) -> None:
    """One panel per (quantity, reference file, y label, transform of the reference): model curves and data."""
    for ax, (quantity, file, label, transform) in zip(axes, panels):
        _model_curves(ax, x, compute, quantity, models)
        _reference_points(ax, file, transform)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)


def _save(figure, path: Path, written: list) -> None:
    write_figure(figure, path, dpi=110)
    written.append(path)


def plot_figures(outdir: str | os.PathLike[str], models: Iterable[str] | None = None) -> list[Path]:
    """Write the benchmark figures (PNG) into ``outdir``; returns their paths."""
    models = list(models or MODELS)
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    for draw in (_tests_1_2, _test_4, _test_5, _test_6):
        draw(outdir, models, written)
    return written


def _tests_1_2(outdir: Path, models: list, written: list) -> None:
    """Tests 1 and 2: force against time, beside the published curves."""
    # no pyplot: the caller's backend and figures stay untouched; matplotlib (heavy) is imported only to draw
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 4.5), layout="tight")
    axes = fig.subplots(1, 2)
    for ax, test, file in ((axes[0], 1, "chung_ooi_test1_force.csv"), (axes[1], 2, "chung_ooi_test2_force.csv")):
        sphere, inputs = _normal_cases(test)[0][:2]
        drawn: list[tuple] = []
        for model_id in models:
            model = make_model(model_id)
            if "normal_force" not in type(model).provides:
                continue
            ds = model.compute(inputs, ["normal_force"])
            colour, style = STYLE[model_id]
            force = np.nan_to_num(ds["normal_force"].values[0] / 1e3)
            ax.plot(ds["time"].values * 1e6, force, color=colour, ls=style, lw=1.4,
                    label=_label(model_id, force, drawn))
        _reference_points(ax, file)
        ax.set_xlabel("time from first contact [us]")
        ax.set_ylabel("normal contact force [kN]")
        ax.set_title(f"test {test}: {sphere.name}, "
                     + ("two spheres, 10 m/s each" if test == 1 else "0.2 m/s on a rigid plane"), fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc="lower center")
    fig.suptitle("Chung & Ooi tests 1-2: elastic normal impact (the rigid models have no force history)")
    _save(fig, outdir / "benchmark_tests12_force.png", written)



def _test_4(outdir: Path, models: list, written: list) -> None:
    """Test 4: Kharaz, Gorham & Salman's measurements."""
    from matplotlib.figure import Figure

    angles = np.linspace(1.0, 88.0, 88)
    fig = Figure(figsize=(16, 4.8), layout="tight")
    axes = fig.subplots(1, 3)
    panels: tuple[tuple[str, str, str, Callable | None], ...] = (
              ("tangential_restitution", "chung_ooi_test4_tangential_restitution.csv",
               "tangential restitution of the centre v_t'/v_t [1]", None),
              ("spin", "chung_ooi_test4_spin.csv", "spin after impact [rad/s] (friction's sense positive)",
               lambda y: -y),
              ("rebound_angle", "chung_ooi_test4_rebound_angle.csv", "contact-patch rebound angle [deg]", None))
    _curve_panels(axes, angles, kharaz_quantities, panels, models)
    for ax in axes:
        ax.set_xlabel("incident angle from the normal [deg]")
    axes[0].legend(fontsize=7, loc="lower right")
    fig.suptitle("Chung & Ooi test 4 = Kharaz, Gorham & Salman (2001): Al2O3 sphere, R 2.5 mm, 3.9 m/s, "
                 "mu 0.092, e 0.98, rigid plane")
    _save(fig, outdir / "benchmark_test4_kharaz.png", written)



def _test_5(outdir: Path, models: list, written: list) -> None:
    """Test 5: the finite-element curve."""
    from matplotlib.figure import Figure

    incidence = np.linspace(0.02, 19.0, 160)
    fig = Figure(figsize=(12, 4.8), layout="tight")
    axes = fig.subplots(1, 2)
    panels = (("rebound", "chung_ooi_test5_rebound.csv", "normalised rebound (v_t' - R w')/(mu v_n') [1]", None),
              ("spin", "chung_ooi_test5_spin.csv", "normalised spin R w'/(mu v_n) [1] (friction's sense positive)",
               lambda y: -y))
    _curve_panels(axes, incidence, chung_ooi_5_quantities, panels, models)
    for ax in axes:
        ax.set_xlabel("normalised incidence v_t/(mu v_n) [1]")
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("Chung & Ooi test 5: steel sphere, v_n 5 m/s, mu 0.3, e 1, rigid plane "
                 "(reference curves are model outputs: FEM and a DEM code)")
    _save(fig, outdir / "benchmark_test5_fem.png", written)



def _test_6(outdir: Path, models: list, written: list) -> None:
    """Test 6: spin only."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(12, 4.8), layout="tight")
    axes = fig.subplots(1, 2)
    special = np.geomspace(0.15, 25.0, 120)
    _model_curves(axes[0], special, chung_ooi_6_quantities, "beta", models, at=chung_ooi_6_incidence)
    _reference_points(axes[0], "chung_ooi_test6_beta.csv")
    axes[0].set_xscale("log")
    axes[0].set_xlabel("3.5 mu (1 + e) v_n / v_t [1] (v_t = R w0, log scale)")
    axes[0].set_ylabel("contact-point tangential restitution beta [1]")
    tangent = np.linspace(0.05, 6.2, 120)
    _model_curves(axes[1], tangent, chung_ooi_6_quantities, "recoil", models)
    _reference_points(axes[1], "chung_ooi_test6_recoil.csv")
    axes[1].set_xlabel("tangent of the contact point's incidence v_t/v_n [1]")
    axes[1].set_ylabel("tangent of the contact point's recoil v_t'/v_n' [1]")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7, loc="lower left")
    fig.suptitle("Chung & Ooi test 6: spinning Al-alloy sphere, R 0.1 m, v_n 0.2 m/s, mu 0.4, e 0.5, rigid plane "
                 "(reference: a DEM code's output)")
    _save(fig, outdir / "benchmark_test6_spin.png", written)
