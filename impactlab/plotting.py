"""Plots drawn from result datasets (never from in-memory model state), so any saved file can be redrawn."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from .vocabulary import HISTORY, MODEL_DIM, OUTPUTS, TIME_DIM

_STYLES = ("-", "--", ":", "-.")


def plot_results(dataset: xr.Dataset, path: str | os.PathLike, outputs=None, x: str | None = None) -> Path:
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
        Sweep dimension for the horizontal axis (default: the longest).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [name for name in (outputs or dataset.data_vars) if name in OUTPUTS and OUTPUTS[name].kind != HISTORY
             and not bool(np.all(np.isnan(dataset[name].values)))][:6]
    sweep_dims = [dim for dim in dataset[names[0]].dims if dim != MODEL_DIM] if names else []
    if x is None and sweep_dims:
        x = max(sweep_dims, key=lambda dim: dataset.sizes[dim])
    others = [dim for dim in sweep_dims if dim != x]
    columns = min(len(names), 3) or 1
    rows = max(1, -(-len(names) // columns))
    figure, axes = plt.subplots(rows, columns, figsize=(5.2 * columns, 3.8 * rows), squeeze=False)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for axis, name in zip(axes.flat, names):
        variable = dataset[name]
        for m_index, model in enumerate(dataset[MODEL_DIM].values):
            per_model = variable.sel({MODEL_DIM: model})
            stacked = per_model.stack(_line=others) if others else per_model.expand_dims(_line=[0])
            for l_index in range(stacked.sizes["_line"]):
                line = stacked.isel(_line=l_index)
                label = str(model)
                if others:
                    label += " " + ", ".join(f"{dim}={float(line[dim]):g}" for dim in others)
                xs = dataset[x].values if x else [0.0]
                axis.plot(xs, np.atleast_1d(line.values), _STYLES[l_index % len(_STYLES)],
                          color=colours[m_index % len(colours)], label=label, marker="" if x else "o")
        axis.set_title(OUTPUTS[name].long_name, fontsize=9)
        axis.set_ylabel(f"{name} [{OUTPUTS[name].units}]")
        if x:
            axis.set_xlabel(f"{x} [{dataset[x].attrs.get('units', '')}]")
        axis.grid(True, alpha=0.3)
    for axis in list(axes.flat)[len(names):]:
        axis.set_visible(False)
    if names:
        handles, labels = axes.flat[0].get_legend_handles_labels()
        figure.legend(handles, labels, loc="lower center", ncol=min(4, len(labels)), fontsize=8, frameon=False)
    figure.suptitle(dataset.attrs.get("title", ""), fontsize=11)
    figure.tight_layout(rect=(0, 0.04 + 0.025 * (len(labels) // 4 if names else 0), 1, 0.96))
    path = Path(path)
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def plot_histories(dataset: xr.Dataset, path: str | os.PathLike, output: str = "tangential_force",
                   select: dict | None = None) -> Path:
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
            label = f"{model} " + ", ".join(f"{dim}={float(line[dim]):g}" for dim in others)
            axis.plot(dataset[TIME_DIM].values * 1e6, line.values, label=label)
    axis.axhline(0.0, color="0.5", lw=0.8)
    axis.set_xlabel("time [us]")
    axis.set_ylabel(f"{output} [{OUTPUTS[output].units}]")
    axis.set_title(OUTPUTS[output].long_name, fontsize=10)
    axis.legend(fontsize=8)
    axis.grid(True, alpha=0.3)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path
