"""Figures of the analysis studies: the error sources of a sensitivity study, and error against run time."""

from __future__ import annotations

import os
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from impactlab.io.safe_output import write_figure
from impactlab.plot.style import _axis_label, _save
from impactlab.vocabulary import OUTPUTS

def _case_labels(dataset: xr.Dataset) -> list[tuple[dict, str]]:
    dims = [dim for dim in dataset["nominal"].dims if dim not in ("model", "output")]
    if not dims:
        return [({}, "")]
    grids = np.meshgrid(*[np.arange(dataset.sizes[d]) for d in dims], indexing="ij")
    labels = []
    for flat in range(grids[0].size):
        where = {d: int(g.reshape(-1)[flat]) for d, g in zip(dims, grids)}
        text = ", ".join(str(dataset[d].values[i]) for d, i in where.items())
        labels.append((where, text))
    return labels


def plot_sensitivity(dataset: xr.Dataset, path: str | os.PathLike[str]) -> list[Path]:
    """Two figures: the three error sources side by side per output and case, and the indices of each model.

    ``path`` names the first PNG; the second gets ``_indices`` added to its stem.
    """
    path = Path(path)
    cases = _case_labels(dataset)
    analysed = [m for m in dataset.model.values if np.any(np.isfinite(dataset["spread"].sel(model=m).values))]
    write_figure(_error_sources_figure(dataset, cases, analysed), path, dpi=110)
    second = path.with_name(f"{path.stem}_indices.png")
    write_figure(_indices_figure(dataset, cases, analysed), second, dpi=110, bbox_inches="tight")
    return [path, second]


def _error_sources_figure(dataset: xr.Dataset, cases: list, analysed: list):
    """The numerical error, parameter uncertainty and model form of each output and case, side by side."""
    # matplotlib is imported where a figure is drawn (it is heavy: a run that draws nothing never loads it)
    import matplotlib.ticker
    # a bare Figure, no pyplot: drawing never changes the caller's backend or open figures
    from matplotlib.figure import Figure

    outputs = list(dataset.output.values)
    figure = Figure(figsize=(max(4.6 * len(cases), 9.0), 2.9 * len(outputs)))
    axes = figure.subplots(len(outputs), len(cases), squeeze=False)
    colours = {"numerical": "tab:grey", "parameter": "tab:blue", "form": "tab:red"}
    for row, output in enumerate(outputs):
        unit = str(dataset.output_units.sel(output=output).values)
        for column, (where, label) in enumerate(cases):
            axis = axes[row, column]
            bars = []
            error = dataset["numerical_error"].isel(where).sel(output=output)
            for model in dataset.model.values:
                value = float(error.sel(model=model))
                bars.append((f"numerical: {model}", value, "numerical"))
            for model in analysed:
                bars.append((f"parameters: {model}", float(dataset["spread"].isel(where).sel(model=model,
                                                                                          output=output)), "parameter"))
            for choice in dataset.choice.values:
                bars.append((f"model form: {choice}", float(dataset["model_form_range"].isel(where).sel(
                    choice=choice, output=output)), "form"))
            positives = [value for _, value, _ in bars if np.isfinite(value) and value > 0]
            floor = (min(positives) if positives else 1.0) / 30.0
            for position, (_, value, kind) in enumerate(bars):
                shown = value if np.isfinite(value) and value > 0 else floor
                axis.barh(position, shown, color=colours[kind], alpha=1.0 if np.isfinite(value) and value > 0
                          else 0.25)
                if not (np.isfinite(value) and value > 0):
                    words = {"numerical": " exact (closed form)", "parameter": " 0 (does not move)",
                             "form": " 0 (the models agree)"}[kind] if value == 0 \
                        else " not measured (tolerance not met)"
                    axis.text(shown, position, words, va="center", fontsize=6)
            axis.set_yticks(range(len(bars)))
            axis.set_yticklabels([text for text, _, _ in bars] if column == 0 else [], fontsize=6)
            axis.invert_yaxis()
            axis.set_xscale("log")
            axis.grid(True, axis="x", which="major", alpha=0.3)
            axis.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
            axis.tick_params(axis="x", labelsize=7)
            axis.set_xlabel(f"{output} [{unit}]", fontsize=8)
            if row == 0:
                axis.set_title(label, fontsize=9)
    from matplotlib.patches import Patch

    figure.legend(handles=[Patch(color=colours["numerical"], label="numerical error (|tolerance - tolerance/10|)"),
                           Patch(color=colours["parameter"], label="parameter uncertainty (5-95 % range over the "
                                                                    "sampled inputs)"),
                           Patch(color=colours["form"], label="model form (max - min over the choice's models)")],
                  loc="lower center", ncol=3 if len(cases) > 2 else 1, fontsize=8, frameon=False)
    figure.suptitle(f"{dataset.attrs.get('study_name', '')}: numerical error, parameter uncertainty and model form "
                    "(log scale)", fontsize=10)
    figure.tight_layout(rect=(0, 0.03 if len(cases) > 2 else 0.08, 1, 0.97))
    return figure


def _indices_figure(dataset: xr.Dataset, cases: list, analysed: list):
    """Each model's sensitivity indices (Sobol ST, or Morris mu*) of each parameter and output, per case."""
    from matplotlib.figure import Figure

    outputs = list(dataset.output.values)
    total = "ST" if "ST" in dataset else "mu_star"
    parameters = list(dataset.parameter.values)
    figure = Figure(figsize=(4.2 * len(cases), 0.5 + 0.45 * len(parameters) * len(analysed) + 0.6 * len(analysed)))
    axes = figure.subplots(len(analysed), len(cases), squeeze=False)
    for row, model in enumerate(analysed):
        for column, (where, label) in enumerate(cases):
            axis = axes[row, column]
            values = dataset[total].isel(where).sel(model=model).transpose("parameter", "output").values
            with warnings.catch_warnings(), np.errstate(all="ignore"):  # an output that does not move: all NaN
                warnings.simplefilter("ignore")
                scaled = values if total == "ST" else values / np.nanmax(np.abs(values), axis=0, keepdims=True)
            image = axis.imshow(np.nan_to_num(scaled, nan=0.0), vmin=0, vmax=1, cmap="Blues", aspect="auto")
            for i in range(len(parameters)):
                for j in range(len(outputs)):
                    value = values[i, j]
                    axis.text(j, i, "n/a" if not np.isfinite(value) else f"{value:.2f}" if total == "ST"
                              else f"{value:.3g}", ha="center", va="center", fontsize=7,
                              color="white" if np.isfinite(scaled[i, j]) and scaled[i, j] > 0.6 else "black")
            axis.set_xticks(range(len(outputs)))
            labels = [f"{name} [{unit}]" for name, unit in zip(outputs, dataset.output_units.values)]
            axis.set_xticklabels(labels if row == len(analysed) - 1 else [], rotation=30, ha="right", fontsize=7)
            axis.set_yticks(range(len(parameters)))
            axis.set_yticklabels(parameters if column == 0 else [], fontsize=7)
            axis.set_title(f"{model}, {label}" if label else str(model), fontsize=8)
    figure.colorbar(image, ax=axes, shrink=0.6, label="Sobol total index ST [1]" if total == "ST"
                    else "Morris mu* / largest mu* of the output [1]")
    figure.suptitle(f"{dataset.attrs.get('study_name', '')}: "
                    + ("Sobol total indices (share of each output's variance involving each input)" if total == "ST"
                       else "Morris mu* (output units; shading relative per output)")
                    + "; n/a: the output does not move over the sample", fontsize=10)
    return figure


def plot_work_precision(dataset: xr.Dataset, path: str | os.PathLike[str]) -> None:
    """Error against wall time per impact, log-log, one panel per output and one line per model entry."""
    # a bare Figure, no pyplot: drawing never changes the caller's backend or open figures
    from matplotlib.figure import Figure

    outputs = list(dataset.output.values)
    columns = min(2, len(outputs))
    rows = -(-len(outputs) // columns)
    figure = Figure(figsize=(6.0 * columns, 4.2 * rows))
    axes = figure.subplots(rows, columns, squeeze=False)
    for axis, output in zip(axes.flat, outputs):
        closed = 0
        for model in dataset.model.values:
            times = dataset.wall_time.sel(model=model).values * 1e6
            errors = dataset.error.sel(model=model, output=output).values
            keep = np.isfinite(times) & np.isfinite(errors)
            if keep.any() and np.all(errors[keep] == 0):
                # exact: no error to draw, only its cost (a vertical rule, named in the legend)
                axis.axvline(np.nanmedian(times), linestyle=(0, (1, 2 + closed)), color=("0.2", "0.55")[closed % 2],
                             label=f"{model} (closed form, exact)")
                closed += 1
                continue
            line, = axis.plot(times[keep], errors[keep], "o-", label=str(model), markersize=3)
            # tolerances label their points on alternate sides: the fast end of a rule bunches up in time
            for index, (t, e, tol) in enumerate(zip(times[keep], errors[keep], dataset.tolerance.values[keep])):
                right = index % 2 == 0
                axis.annotate(f"{tol:g}", (t, e), fontsize=6, xytext=(4 if right else -4, 0),
                              textcoords="offset points", ha="left" if right else "right", va="center",
                              color=line.get_color())
        axis.set_xscale("log")
        axis.set_yscale("log")
        axis.set_xlabel("wall time per impact [us] (one core, warm)")
        axis.set_ylabel(_axis_label(f"error of {OUTPUTS[output].long_name} / its largest |value|", "1", 48),
                        fontsize=8)
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=7)
    for axis in list(axes.flat)[len(outputs):]:
        axis.set_visible(False)
    figure.suptitle(dataset.attrs.get("title", "") + f" ({int(dataset.attrs.get('cases', 0))} impacts; "
                    "point labels: requested tolerance)", fontsize=10)
    figure.tight_layout()
    _save(figure, path)
