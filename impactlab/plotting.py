"""Plots drawn from result datasets (never from in-memory model state), so any saved file can be redrawn."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from .vocabulary import HISTORY, MODEL_DIM, OUTPUTS, TIME_DIM

_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)))


def _text(coordinate) -> str:
    value = coordinate.item()
    return f"{value:g}" if isinstance(value, (int, float)) else str(value)


def draw_declared(dataset: xr.Dataset, folder: Path, stem: str) -> list[Path]:
    """Draw every figure the study declared (``plots`` attribute) to FOLDER/STEM_NAME.png."""
    import json

    pictures = []
    for spec in json.loads(dataset.attrs.get("plots", "[]") or "[]"):
        path = folder / f"{stem}_{spec['name']}.png"
        selected = dataset.sel(spec.get("select") or {})
        if MODEL_DIM not in selected.dims:  # one model chosen: keep it as a one-long dimension
            selected = selected.expand_dims({MODEL_DIM: [selected[MODEL_DIM].item()]})
        if spec.get("kind") == "history":
            for output in spec["y"]:
                plot_histories(selected, path if len(spec["y"]) == 1 else path.with_stem(f"{path.stem}_{output}"),
                               output, title=spec.get("title", ""))
        else:
            plot_results(selected, path, outputs=spec["y"], x=spec.get("x"), title=spec.get("title", ""))
        pictures.append(path)
    return pictures


def plot_results(dataset: xr.Dataset, path: str | os.PathLike, outputs=None, x: str | None = None,
                 title: str = "") -> Path:
    """Draw scalar outputs against one sweep dimension, one colour per model, one line style per other value.

    Parameters
    ----------
    dataset : xarray.Dataset
        A study result.
    path : path
        PNG file to write.
    outputs : list of str, optional
        Scalar outputs to draw (default: every scalar output in the dataset, at most six).
    x : str, optional
        Sweep dimension for the horizontal axis (default: the longest), or a scalar output: each
        line is then drawn against that output along the longest sweep dimension (psi2 against
        psi1, say).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [name for name in (outputs or dataset.data_vars) if name in OUTPUTS and OUTPUTS[name].kind != HISTORY
             and not bool(np.all(np.isnan(dataset[name].values)))][:6]
    sweep_dims = [dim for dim in dataset[names[0]].dims if dim != MODEL_DIM] if names else []
    along_output = x is not None and x in dataset.data_vars
    along = x
    if (x is None or along_output) and sweep_dims:
        along = max(sweep_dims, key=lambda dim: dataset.sizes[dim])
        x = x or along
    others = [dim for dim in sweep_dims if dim != along]
    columns = min(len(names), 3) or 1
    rows = max(1, -(-len(names) // columns))
    size = (8.0, 5.2) if len(names) == 1 else (5.2 * columns, 3.8 * rows + 0.6)
    figure, axes = plt.subplots(rows, columns, figsize=size, squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    single_model = dataset.sizes[MODEL_DIM] == 1
    for axis, name in zip(axes.flat, names):
        variable = dataset[name]
        drawn = []  # (xs, ys, label) of the lines on this axis, to name the ones a later line hides
        span = float(np.nanmax(variable.values) - np.nanmin(variable.values)) if variable.size else 0.0
        for m_index, model in enumerate(dataset[MODEL_DIM].values):
            per_model = variable.sel({MODEL_DIM: model})
            stacked = per_model.stack(_line=others) if others else per_model.expand_dims(_line=[0])
            for l_index in range(stacked.sizes["_line"]):
                line = stacked.isel(_line=l_index)
                label = str(model)
                if others:
                    label += " " + ", ".join(f"{dim}={_text(line[dim])}" for dim in others)
                if along_output:
                    horizontal = dataset[x].sel({MODEL_DIM: model})
                    horizontal = horizontal.stack(_line=others) if others else horizontal.expand_dims(_line=[0])
                    xs = horizontal.isel(_line=l_index).values
                else:
                    xs = dataset[x].values if x else [0.0]
                # one model: a colour per line; several: a colour per model, a line style per other value
                colour = colours[(l_index if single_model else m_index) % len(colours)]
                style = "-" if single_model else _STYLES[l_index % len(_STYLES)]
                ys = np.atleast_1d(line.values)
                hidden = next((other for other_xs, other_ys, other in drawn
                               if np.shape(other_xs) == np.shape(xs) and np.allclose(other_xs, xs)
                               and np.allclose(other_ys, ys, rtol=0, atol=2e-3 * span + 1e-300, equal_nan=True)),
                              None)
                drawn.append((xs, ys, label))
                if hidden is not None:
                    # the same curve as one drawn before: say so, and mark it so that both stay visible
                    label += f" (on {hidden})"
                axis.plot(xs, ys, linestyle=style, color=colour, label=label,
                          marker=("x" if hidden is not None else "") if x else "o",
                          markevery=max(1, len(xs) // 8) if hidden is not None else None)
        axis.set_title(OUTPUTS[name].long_name, fontsize=9)
        axis.set_ylabel(f"{name} [{OUTPUTS[name].units}]")
        if x:
            units = OUTPUTS[x].units if along_output else dataset[x].attrs.get("units", "")
            axis.set_xlabel(f"{x} [{units}]")
        axis.grid(True, alpha=0.3)
    for axis in list(axes.flat)[len(names):]:
        axis.set_visible(False)
    figure.suptitle(title or dataset.attrs.get("title", ""), fontsize=11)
    if len(names) == 1:
        axes.flat[0].legend(fontsize=7, ncol=2 if len(axes.flat[0].lines) > 6 else 1)
        figure.tight_layout(rect=(0, 0, 1, 0.95))
    elif names:
        handles, labels = axes.flat[0].get_legend_handles_labels()
        columns_of_legend = min(4, len(labels))
        legend_rows = -(-len(labels) // columns_of_legend)
        figure.legend(handles, labels, loc="lower center", ncol=columns_of_legend, fontsize=8, frameon=False)
        figure.tight_layout(rect=(0, 0.02 + 0.03 * legend_rows, 1, 0.96))
    path = Path(path)
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def plot_histories(dataset: xr.Dataset, path: str | os.PathLike, output: str = "tangential_force",
                   select: dict | None = None, title: str = "") -> Path:
    """Draw a force history against time for every model that has it and every remaining sweep value."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    variable = dataset[output].sel(select or {}, method="nearest")
    others = [dim for dim in variable.dims if dim not in (MODEL_DIM, TIME_DIM)]
    figure, axis = plt.subplots(figsize=(7, 4.5))
    for model in variable[MODEL_DIM].values:
        per_model = variable.sel({MODEL_DIM: model})
        if bool(np.all(np.isnan(per_model.values))):
            continue
        stacked = per_model.stack(_line=others) if others else per_model.expand_dims(_line=[0])
        for index in range(stacked.sizes["_line"]):
            line = stacked.isel(_line=index)
            label = f"{model} " + ", ".join(f"{dim}={_text(line[dim])}" for dim in others)
            axis.plot(dataset[TIME_DIM].values * 1e6, line.values, label=label)
    axis.axhline(0.0, color="0.5", lw=0.8)
    axis.set_xlabel("time [us]")
    axis.set_ylabel(f"{output} [{OUTPUTS[output].units}]")
    axis.set_title(title or OUTPUTS[output].long_name, fontsize=10)
    axis.legend(fontsize=8)
    axis.grid(True, alpha=0.3)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path
