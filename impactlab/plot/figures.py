"""Plots drawn from result datasets (never from in-memory model state), so any saved file can be redrawn."""

from __future__ import annotations

import json
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from impactlab.data.sessions.reader import read_session
from impactlab.errors import FieldError, StudyError
from impactlab.vocabulary import INPUT_BY_PATH, INPUTS, MODEL_DIM, OUTPUTS, TIME_DIM, is_scalar
from impactlab.study.datasets import DATASETS
from impactlab.plot.style import _MARKERS, _STYLES, _axis_label, _display, _save, conditions
# the ball-flight figure has its own module; the CLI and users import it from here
from impactlab.plot.trajectories import (MAX_TRAJECTORIES as MAX_TRAJECTORIES,
                                         TRAJECTORY_LAUNCH as TRAJECTORY_LAUNCH,
                                         plot_trajectories as plot_trajectories)


def check_shot_files(study) -> None:
    """Every user's shot file a study's figures name (``measured:``) reads as a launch-monitor export or shot table
    and measures an output its figure draws; checked before the study runs (``impactlab run``), not after.

    Raises
    ------
    FieldError
        At ``plots[i].measured[j]`` of the study's file, saying what the file gives.
    """
    for index, plot in enumerate(study.plots):
        for position, name in enumerate(plot.measured):
            if name in DATASETS:
                continue
            where = f"plots[{index}].measured[{position}]"
            try:
                session = read_session(name)
            except (StudyError, FieldError, OSError, ValueError) as exc:
                raise FieldError(where, f"a shot file impactlab reads ({exc})", name).at(file=study.file) from None
            measured = [y for y in plot.y if y in session.values and np.isfinite(session.values[y]).any()]
            if not measured:
                given = sorted(field for field, values in session.values.items() if np.isfinite(values).any())
                raise FieldError(where, f"a shot file that measures an output the figure draws ({', '.join(plot.y)})",
                                 f"{name} (its columns give {', '.join(given)})").at(file=study.file)


def _shot_values(path: str, output: str, x_input: str | None) -> tuple[np.ndarray, np.ndarray | None, int]:
    """A user's shot file (impactlab.data.sessions): the shots' ``output`` in the vocabulary's units, their x (the
    swept input's display units) where the file gives it, and the number of rows without the output (skipped)."""
    session = read_session(path)
    ys = np.asarray(session.values.get(output, np.full(session.size, np.nan)), float) * OUTPUTS[output].factor
    field = {"speed": "club_speed"}.get(x_input or "", x_input)
    xs = None
    if x_input and field and field in session.values and np.isfinite(session.values[field]).any():
        xs = np.asarray(session.values[field], float) * INPUTS[x_input].display_factor
    keep = np.isfinite(ys) & (np.isfinite(xs) if xs is not None else True)
    return ys[keep], None if xs is None else xs[keep], int(np.sum(~keep))


def _draw_measured(axis, output: str, names, xs, x_input: str | None = None) -> None:
    """Measured values of ``output`` at the right of the curves: one column per dataset, a point per label.

    A name that is not a shipped dataset is a user's shot file: its shots are drawn at their own x where the file
    gives the swept quantity (a club-speed sweep beside the shots' club speeds), else as a column of mean +- SD.
    """
    step = (xs.max() - xs.min()) / max(xs.size - 1, 1) if xs.size > 1 else 1.0
    files = [name for name in names if name not in DATASETS]
    names = [name for name in names if name in DATASETS]
    for path in files:
        ys, shot_xs, skipped = _shot_values(path, output, x_input)
        label = f"measured: {Path(path).name} ({ys.size} shots" + (f", {skipped} without it" if skipped else "")
        if shot_xs is not None:
            axis.plot(shot_xs, ys, "k.", markersize=4, alpha=0.6, zorder=4, label=label + ")")
        elif ys.size:
            names.append(("file", path, ys, label))
    for column, name in enumerate(names):
        if isinstance(name, tuple):  # a shot file without the swept quantity: its mean +- SD in a column
            _, path, ys, label = name
            where = xs.max() + step * (0.6 + 1.2 * column)
            axis.errorbar([where], [float(np.mean(ys))], yerr=[float(np.std(ys, ddof=1)) if ys.size > 1 else 0.0],
                          fmt="kD", markersize=5, capsize=3, zorder=4, label=label + ", mean +- SD)")
            continue
        data = DATASETS[name]
        if data.quantity != output:
            continue
        # the labels side by side inside the dataset's column, so that overlapping error bars stay apart
        positions = xs.max() + step * (0.6 + 1.2 * column + 0.35 * np.arange(len(data.values)))
        sigma = np.asarray(data.sigma, float) if data.sigma is not None else None
        what = "mean +- SD" if sigma is not None else "no uncertainty stated"
        axis.errorbar(positions, np.asarray(data.values, float), yerr=sigma,
                      fmt="k*" if sigma is None else "ks", markersize=6, capsize=3, zorder=4,
                      label=f"measured: {name} ({what})")
        for label, value, where in zip(data.labels, data.values, positions):
            axis.annotate(label, (where, value), xytext=(4, 0), textcoords="offset points", fontsize=6,
                          va="center", rotation=0)
    if not names:
        return
    # the measured points sit right of a rule: they were taken at no stated friction, not at the x there
    axis.axvline(xs.max() + 0.3 * step, color="0.6", linewidth=0.8, label="_separator")
    axis.annotate("measured", (xs.max() + 0.35 * step, 1.0), xycoords=("data", "axes fraction"), xytext=(0, -10),
                  textcoords="offset points", fontsize=7, color="0.3")
    axis.set_xlim(right=xs.max() + step * (0.6 + 1.2 * len(names) + 0.6))


def _zoom(axis, xlim) -> None:
    """Show xlim only, with the vertical range of what lies inside it (5 % margins)."""
    low, high = xlim
    inside = []
    for line in axis.get_lines():
        xs, ys = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        keep = (xs >= low) & (xs <= high) & np.isfinite(ys)
        inside.extend(ys[keep])
    axis.set_xlim(low, high)
    if inside:
        bottom, top = min(inside), max(inside)
        margin = 0.05 * (top - bottom) or 0.05 * abs(top) or 0.05
        axis.set_ylim(bottom - margin, top + margin)


def _relation(other: str) -> str:
    return other.replace("partly ", "partly on ", 1) if other.startswith("partly ") else f"on {other}"


def _lies_on(drawn, xs, ys, tolerance) -> tuple[str | None, float]:
    """The earlier line (label) this one lies on: wholly (share 1.0), else over the largest share >= half its points."""
    best, share = None, 0.0
    for other_xs, other_ys, other in drawn:
        if np.shape(other_xs) != np.shape(xs) or not np.allclose(other_xs, xs):
            continue
        both = np.isfinite(other_ys) & np.isfinite(ys)
        same = np.abs(np.where(both, other_ys - ys, 0.0)) <= tolerance
        if np.array_equal(np.isnan(other_ys), np.isnan(ys)) and np.all(same):
            return other, 1.0
        if both.any() and 0.5 <= np.mean(same[both]) > share:
            best, share = other, float(np.mean(same[both]))
    return best, share


def coincidence_note(dataset: xr.Dataset, names: Sequence[str], dims: Sequence[str]) -> str:
    """The title line of a figure whose lines coincide along a dimension, or "" (each of ``dims`` whose every value
    draws the same curve, of every model and output ``names``, within 2e-3 of the output's span)."""
    same = [dim for dim in dims if dataset.sizes[dim] > 1 and all(_flat_along(dataset[name], dim) for name in names)]
    return "; ".join(f"the curves of {dim} = {', '.join(_text(v) for v in dataset[dim])} coincide (one curve per "
                     "model)" for dim in same)


def _flat_along(variable: xr.DataArray, dim: str, tolerance: float = 2e-3) -> bool:
    """Whether ``variable`` is the same at every value of ``dim`` (within ``tolerance`` of its span; NaN alike)."""
    values = np.moveaxis(np.asarray(variable.values, float), variable.dims.index(dim), 0)
    finite = values[np.isfinite(values)]
    span = float(finite.max() - finite.min()) if finite.size else 0.0
    first = values[:1]
    both = np.isfinite(values) & np.isfinite(first)
    return bool(np.array_equal(np.isnan(values), np.broadcast_to(np.isnan(first), values.shape))
                and np.all(np.abs(np.where(both, values - first, 0.0)) <= tolerance * span + 1e-300))


def _text(coordinate) -> str:
    value = coordinate.item()
    return f"{value:g}" if isinstance(value, (int, float)) else str(value)


def draw_declared(dataset: xr.Dataset, folder: Path, stem: str) -> list[Path]:
    """Draw every figure the study declared (``plots`` attribute) to FOLDER/STEM_NAME.png."""
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
            plot_results(selected, path, outputs=spec["y"], x=spec.get("x"), title=spec.get("title", ""),
                         xlim=spec.get("xlim"), measured=spec.get("measured") or ())
        pictures.append(path)
    return pictures


def plot_results(dataset: xr.Dataset, path: str | os.PathLike, outputs: Sequence[str] | None = None,
                 x: str | None = None, title: str = "", xlim: Sequence[float] | None = None,
                 measured: Sequence[str] = ()) -> Path:
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
    xlim : (float, float), optional
        A zoomed view of the horizontal axis; the vertical axis follows the data inside it.
    measured : sequence of str
        Shipped measured datasets (:data:`impactlab.study.datasets.DATASETS`) of a drawn output: their
        values, with error bars where the source states them, beside the curves at the right; or paths of a
        user's shot files (launch-monitor exports, shot tables): their shots at their own x where the file gives
        the swept quantity, else their mean +- SD at the right.
    """
    # a bare Figure, no pyplot: drawing never changes the caller's backend or open figures; matplotlib is
    # imported where a figure is drawn (it is heavy: a run that draws nothing never loads it)
    import matplotlib
    from matplotlib.figure import Figure

    names = [str(name) for name in (outputs or dataset.data_vars) if is_scalar(str(name))
             and not bool(np.all(np.isnan(dataset[name].values)))][:6]
    sweep_dims = [str(dim) for dim in dataset[names[0]].dims if dim != MODEL_DIM] if names else []
    along_output = x is not None and x in dataset.data_vars
    along = x
    if (x is None or along_output) and sweep_dims:
        along = max(sweep_dims, key=lambda dim: dataset.sizes[dim])
        x = x or along
    others = [dim for dim in sweep_dims if dim != along]
    columns = min(len(names), 3) or 1
    rows = max(1, -(-len(names) // columns))
    size = (8.0, 5.2) if len(names) == 1 else (5.2 * columns, 3.8 * rows + 0.6)
    figure = Figure(figsize=size)
    # one panel per output, not xarray's FacetGrid: its facets are the values of one dimension of one DataArray
    # on shared axes, while these panels are different outputs (each its own units, scale and measured data),
    # and the lines of a panel are told apart by the coincidence analysis below; FacetGrid also draws through
    # pyplot, which would change the caller's backend and open figures
    axes = figure.subplots(rows, columns, squeeze=False)
    colours = matplotlib.rcParams["axes.prop_cycle"].by_key()["color"]
    # lines that lie on an earlier line, per label: the panels where they do (named in the legend)
    coincide: dict[str, dict[str, list[str]]] = {}
    for panel, (axis, name) in enumerate(zip(axes.flat, names)):
        _draw_panel(axis, panel, dataset, name, x, along_output, others, colours, coincide)
        if len(names) > 1:
            axis.set_title(f"({chr(97 + panel)})", fontsize=9, loc="left")
        _label_axes(axis, dataset, name, x, along_output)
        if measured and x and not along_output:
            _draw_measured(axis, name, measured, np.asarray(dataset[x].values, float),
                           INPUT_BY_PATH.get(dataset[x].attrs.get("study_path", "")))
        if xlim is not None:
            _zoom(axis, xlim)
    for axis in list(axes.flat)[len(names):]:
        axis.set_visible(False)
    _name_coincidences(axes, names, coincide)
    heading = title or dataset.attrs.get("title", "")
    # a dimension whose every value draws the same curve (of each model, in each panel) is said in the title, not
    # only in the legend: a reader must not take three coinciding curves for one (Fig. 5's club speeds)
    note = coincidence_note(dataset, names, others)
    if note:
        heading += "\n" + note
    context = conditions(dataset)
    figure.suptitle(heading + (f"\n{context}" if context else ""), fontsize=10)
    _legend(figure, axes, names, size)
    path = _save(figure, path)
    return path


def _draw_panel(axis, panel: int, dataset: xr.Dataset, name: str, x, along_output: bool, others: list, colours,
                coincide: dict) -> None:
    """The lines of one output's panel: one per model and value of the other sweep dimensions; a line lying on an
    earlier one is noted in ``coincide`` (label -> the line it lies on -> panels)."""
    single_model = dataset.sizes[MODEL_DIM] == 1
    variable = dataset[name]
    units, scale = _display(OUTPUTS[name].units, name)
    drawn: list[tuple] = []  # (xs, ys, label) of the lines on this axis, to name the ones a later line hides
    span = float(np.nanmax(variable.values) - np.nanmin(variable.values)) * scale if variable.size else 0.0
    line_index = 0
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
                xs = dataset[x].values if x else np.zeros(1)
            # one model: a colour per line; several: a colour per model, a line style per other value
            colour = colours[(l_index if single_model else m_index) % len(colours)]
            style = "-" if single_model else _STYLES[l_index % len(_STYLES)]
            ys = np.atleast_1d(line.values) * scale
            hidden, part = _lies_on(drawn, xs, ys, 2e-3 * span + 1e-300)
            drawn.append((xs, ys, label))
            if hidden is not None:
                key = hidden if part == 1.0 else f"partly {hidden}"
                coincide.setdefault(label, {}).setdefault(key, []).append(f"({chr(97 + panel)})")
            # every line its own marker, spread along the line and offset from the others' so that a curve
            # lying on another still shows; a line drawn later and thinner keeps the one below visible
            every = max(1, len(xs) // 7)
            look = dict(color=colour, marker=_MARKERS[line_index % len(_MARKERS)],
                        markersize=5 if hidden is None else 8,
                        markerfacecolor="none" if hidden is not None else colour,
                        markevery=(line_index % every, every) if len(xs) > 1 else None)
            axis.plot(xs, ys, linestyle=style, label=label, linewidth=1.6 if hidden is None else 1.0, **look)
            # the markers again above every line, so that a curve covered by a later one still shows
            axis.plot(xs, ys, linestyle="none", label="_markers", zorder=3, **look)
            line_index += 1


def _label_axes(axis, dataset: xr.Dataset, name: str, x, along_output: bool) -> None:
    """A panel's axis labels (long names and units) and grid."""
    units, _ = _display(OUTPUTS[name].units, name)
    axis.set_ylabel(_axis_label(OUTPUTS[name].long_name, units), fontsize=8)
    if x:
        if along_output:
            x_units, _ = OUTPUTS[x].units, 1.0
            axis.set_xlabel(_axis_label(OUTPUTS[x].long_name, x_units, 60), fontsize=8)
        else:
            attrs_x = dataset[x].attrs
            axis.set_xlabel(_axis_label(attrs_x.get("long_name", x), attrs_x.get("units", ""), 60), fontsize=8)
    axis.grid(True, alpha=0.3)


def _name_coincidences(axes, names: list, coincide: dict) -> None:
    """The legend names the lines that lie on others, and where."""
    for axis in axes.flat[:len(names)]:
        for line in axis.get_lines():
            notes = coincide.get(line.get_label()) if not line.get_label().startswith("_") else None
            if notes:
                # whole coincidences first; at most two relations, so that the legend stays readable
                ordered = sorted(notes.items(), key=lambda item: (item[0].startswith("partly "), -len(item[1])))
                where = "; ".join(_relation(other) + (f" in {' '.join(panels)}" if len(names) > 1 else "")
                                  for other, panels in ordered[:2]) + ("; ..." if len(ordered) > 2 else "")
                line.set_label(f"{line.get_label()} ({where})")


def _legend(figure, axes, names: list, size: tuple) -> None:
    """One panel with few lines: its own legend; otherwise one legend below the panels, where it hides no data."""
    if len(names) == 1 and len(axes.flat[0].lines) <= 4:
        axes.flat[0].legend(fontsize=7)
        figure.tight_layout(rect=(0, 0, 1, 0.95))
    elif names:  # many entries: below the panels, where they hide no data
        handles, labels = axes.flat[0].get_legend_handles_labels()
        # as many columns as the longest entry leaves room for (about 14 characters of 8-point text per inch)
        width = int(size[0] * 14)
        columns_of_legend = max(1, min(3 if len(names) > 1 else 2, len(labels), width // max(map(len, labels))))
        legend_rows = -(-len(labels) // columns_of_legend)
        # the figure grows by the legend's height (0.17 in per row), so the panels keep their size
        legend_height = 0.17 * legend_rows + 0.15
        figure.set_figheight(size[1] + legend_height)
        figure.legend(handles, labels, loc="lower center", ncol=columns_of_legend, fontsize=8, frameon=False)
        figure.tight_layout(rect=(0, (legend_height + 0.1) / (size[1] + legend_height), 1, 0.95))


def plot_histories(dataset: xr.Dataset, path: str | os.PathLike, output: str = "tangential_force",
                   select: dict | None = None, title: str = "") -> Path:
    """Draw a force history against time for every model that has it and every remaining sweep value."""
    # a bare Figure, no pyplot: drawing never changes the caller's backend or open figures
    from matplotlib.figure import Figure

    variable = dataset[output].sel(select or {}, method="nearest")
    others = [dim for dim in variable.dims if dim not in (MODEL_DIM, TIME_DIM)]
    units, scale = _display(OUTPUTS[output].units)
    figure = Figure(figsize=(7, 4.5))
    axis = figure.subplots()
    line_index = 0
    for model in variable[MODEL_DIM].values:
        per_model = variable.sel({MODEL_DIM: model})
        if bool(np.all(np.isnan(per_model.values))):
            continue
        stacked = per_model.stack(_line=others) if others else per_model.expand_dims(_line=[0])
        for index in range(stacked.sizes["_line"]):
            line = stacked.isel(_line=index)
            label = f"{model} " + ", ".join(f"{dim}={_text(line[dim])}" for dim in others)
            times = dataset[TIME_DIM].values * 1e6
            every = max(1, times.size // 8)
            axis.plot(times, line.values * scale, label=label.strip(), marker=_MARKERS[line_index % len(_MARKERS)],
                      markevery=(line_index * every // 4 % every, every), markersize=4,
                      linestyle=_STYLES[line_index % len(_STYLES)])
            line_index += 1
    axis.axhline(0.0, color="0.5", lw=0.8, label="_zero")
    axis.set_xlabel("time from first contact [us]")
    axis.set_ylabel(_axis_label(OUTPUTS[output].long_name, units))
    context = conditions(dataset.sel(select or {}, method="nearest") if select else dataset)
    axis.set_title((title or OUTPUTS[output].long_name) + (f"\n{context}" if context else ""), fontsize=10)
    axis.legend(fontsize=8)
    axis.grid(True, alpha=0.3)
    figure.tight_layout()
    path = _save(figure, path)
    return path

