"""The ball's flight after each model's launch, side and top view, flown again from a result's stored launch."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import xarray as xr

from impactlab.errors import FieldError
from impactlab.units import YARD
from impactlab.vocabulary import FLIGHT_OUTPUTS, MODEL_DIM, output_unit_factor
from impactlab.physics.aerodynamics import (BALL_MASS, BALL_RADIUS, DEFAULT_MODEL, MODELS, model_fingerprint,
                                           retired_reason)
from impactlab.physics.flight import fly
from impactlab.scene.flight import air_arrays
from impactlab.model.derive import FLIGHT_INPUTS
from impactlab.plot.style import _MARKERS, _STYLES, _save, conditions

#: the air model of every flight output written before the outputs named theirs (impactlab before 2026-11-23)
UNRECORDED_AIR_MODEL = "smits_smith_1994"

#: the launch a trajectory figure needs in a result file (a golf study that asks for them)
TRAJECTORY_LAUNCH = ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "back_spin", "side_spin",
                     "spin_axis")
#: most shots drawn per model (more would be a blur): evenly spaced over the cases, and the title says so
MAX_TRAJECTORIES = 12


def plot_trajectories(dataset: xr.Dataset, path: str | os.PathLike, title: str = "") -> Path:
    """Side and top views of the ball flight after each model's launch, one colour per model, one style per case.

    Parameters
    ----------
    dataset : xarray.Dataset
        A golf study's result holding the launch outputs of :data:`TRAJECTORY_LAUNCH` (ball speed in m/s,
        angles in degree, spins in rpm, as a result file stores them).
    path : path
        The PNG to write.
    title : str
        Above the panels; default names the study and the air.

    Returns
    -------
    Path

    Raises
    ------
    FieldError
        The result lacks a launch output, or sweeps the air (the paths are flown in its base conditions).

    Notes
    -----
    The paths are flown again from the stored launch with :func:`impactlab.physics.flight.fly` (the study's
    ball, the air of its ``conditions`` block, or the standard air without one), so they land where the result's
    ``carry_distance`` says when it holds one. Distances in metres, with yards on the top axis.
    """
    # imported where a figure is drawn (heavy: a run that draws nothing never loads it); a bare Figure, no
    # pyplot: drawing never changes the caller's backend or open figures
    from matplotlib.figure import Figure

    scene = _flyable_scene(dataset)
    if MODEL_DIM not in dataset.dims:
        dataset = dataset.expand_dims({MODEL_DIM: [str(dataset.attrs.get("model", "model"))]})
    air = air_arrays({name: float(scene[name]) for name in FLIGHT_INPUTS if name in scene})
    aerodynamics, changed = _air_model(dataset)
    mass = float(scene.get("ball_mass", BALL_MASS))
    radius = float(scene.get("ball_radius", BALL_RADIUS))
    stacked, computed = _launch_cases(dataset)
    n_cases = stacked.sizes["case"]
    shown = np.unique(np.linspace(0, n_cases - 1, min(n_cases, MAX_TRAJECTORIES)).round().astype(int))
    figure = Figure(figsize=(10.5, 7.5))
    side, top = figure.subplots(2, 1, sharex=True)
    drawn = _draw_paths(side, top, stacked, shown, dict(ball_mass=mass, ball_radius=radius, model=aerodynamics,
                                                        return_trajectories=True, **air))
    if not drawn:
        raise FieldError("--trajectories", "a result with at least one computed launch", "only NaN launches")
    _label_axes(side, top)
    figure.legend(*side.get_legend_handles_labels(), fontsize=7, loc="center right", title="model, case",
                  title_fontsize=7)
    default = _default_title(dataset, air, aerodynamics, changed, len(shown), n_cases, computed)
    figure.suptitle(title or default, fontsize=9)
    longest = max(len(text) for text in side.get_legend_handles_labels()[1])
    figure.tight_layout(rect=(0.0, 0.0, 0.80 if longest <= 28 else 0.72, 1.0))  # room for the legend's words
    return _save(figure, path)


def _flyable_scene(dataset: xr.Dataset) -> dict:
    """The result's base scene (SI), after refusing a result without the launch or whose air is swept."""
    absent = [name for name in TRAJECTORY_LAUNCH if name not in dataset.data_vars]
    if absent:
        raise FieldError("--trajectories", "a golf result holding the launch (add these to the study's outputs: "
                         + ", ".join(absent) + ")", "a result without them")
    scene = json.loads(dataset.attrs.get("base_scene_si", "{}") or "{}")
    swept_air = [name for name in FLIGHT_INPUTS
                 if name in dataset.coords or INPUT_COORDS.get(name, name) in dataset.coords]
    if swept_air:
        raise FieldError("--trajectories", "a result whose air is not swept (the paths are flown in one air); "
                         "select one value first", ", ".join(swept_air))
    return scene


def _air_model(dataset: xr.Dataset) -> tuple[str, str]:
    """The aerodynamic model the paths are flown with, and the title's words when its constants changed since."""
    # the air model the result's flight outputs were computed with (they record it); flight outputs that record
    # none come from a file written before they did, when every flight was Smits & Smith's; a result holding only
    # the launch is flown with today's default. The title says which.
    flown = [name for name in FLIGHT_OUTPUTS if name in dataset.data_vars]
    recorded = [dataset[name].attrs["aerodynamic_model"] for name in flown
                if "aerodynamic_model" in dataset[name].attrs]
    aerodynamics = recorded[0] if recorded else UNRECORDED_AIR_MODEL if flown else DEFAULT_MODEL
    # the constants the stored flight was computed with (a refit keeps the model's name): the paths are flown with
    # today's, and the title says so when they differ (results written before fingerprints were recorded say nothing)
    stored = {str(dataset[name].attrs["aerodynamic_fingerprint"]) for name in flown
              if "aerodynamic_fingerprint" in dataset[name].attrs}
    if aerodynamics not in MODELS:  # a result written before its model was retired (or an altered attribute)
        raise FieldError("--trajectories", "a result whose flight outputs name an aerodynamic model of this impactlab"
                         + (f" ({retired_reason(aerodynamics)})" if retired_reason(aerodynamics) else ""),
                         str(aerodynamics), choices=MODELS)
    today = model_fingerprint(aerodynamics)
    changed = (f" (today's constants, {today}; the stored carries were computed with {', '.join(sorted(stored))})"
               if stored - {today} else "")
    return aerodynamics, changed


def _launch_cases(dataset: xr.Dataset) -> tuple[xr.Dataset, np.ndarray]:
    """The launch in the vocabulary's units, stacked along ``case`` (and model), and which model-cases have every
    launch value computed; refuses a result where none has."""
    case_dims = [dim for dim in dataset["ball_speed"].dims if dim != MODEL_DIM]
    # each launch value in the units its attribute states (a result edited with xarray), turned to the vocabulary's
    launch = dataset[list(TRAJECTORY_LAUNCH)]
    launch = launch.assign({name: launch[name] * output_unit_factor(name, launch[name].attrs.get("units"))
                            for name in TRAJECTORY_LAUNCH})
    stacked = launch.stack(case=case_dims) if case_dims else launch.expand_dims(case=[0])
    # a case is drawn when every launch value is computed: a NaN spin axis flew a NaN path, and a figure of
    # empty panels was written without a word
    computed = np.logical_and.reduce([np.isfinite(np.asarray(stacked[name].values, dtype=float))
                                      for name in TRAJECTORY_LAUNCH])
    if not computed.any():
        nowhere = [name for name in TRAJECTORY_LAUNCH
                   if not np.isfinite(np.asarray(stacked[name].values, dtype=float)).any()]
        raise FieldError("--trajectories", "a result with at least one case whose launch is computed (the figure "
                         "would be empty)", f"{', '.join(nowhere) or 'a NaN launch value'} NaN in every case"
                         if nowhere else "every case lacking one launch value (NaN)")
    return stacked, computed


def _draw_paths(side, top, stacked: xr.Dataset, shown: np.ndarray, flight: dict) -> list:
    """Fly and draw the shown cases of every model in both views; return (x, height, offline, label) of each path
    drawn. ``flight``: the keywords of :func:`impactlab.physics.flight.fly` (ball, air model, air)."""
    from matplotlib import rcParams

    colours = rcParams["axes.prop_cycle"].by_key()["color"]
    drawn: list = []  # (x, height, offline, label) of each path drawn
    for m, model in enumerate(stacked[MODEL_DIM].values):
        row = stacked.sel({MODEL_DIM: model}).isel(case=shown)
        spin = np.hypot(row["back_spin"].values, row["side_spin"].values) * np.pi / 30.0
        finite = np.logical_and.reduce([np.isfinite(np.asarray(row[name].values, dtype=float))
                                        for name in TRAJECTORY_LAUNCH]) & (row["ball_speed"].values > 0)
        if not finite.any():
            continue
        result = fly(row["ball_speed"].values[finite], np.radians(row["vertical_launch_angle"].values[finite]),
                     spin[finite], np.radians(row["spin_axis"].values[finite]),
                     np.radians(row["horizontal_launch_angle"].values[finite]), **flight)
        labels = [_case_label(row, int(index)) for index in np.nonzero(finite)[0]]
        for k in range(result["x"].shape[0]):
            style = _STYLES[k % len(_STYLES)]
            label = f"{model}" + (f", {labels[k]}" if labels[k] else "")
            flown = _flown_part(result["x"][k], result["z"][k], result["y"][k])
            below = _lies_on(drawn, *flown)
            drawn.append((*flown, (str(model), labels[k])))
            # a marker per model at the landing point, so that a path lying on another model's stays visible; the
            # legend names the model whose path of the same case this one covers
            legend = label if below is None else \
                f"{label} (on {below[0]}{'' if below[1] == labels[k] else ', ' + below[1]})"
            marks = dict(color=colours[m % len(colours)], linestyle=style, marker=_MARKERS[m % len(_MARKERS)],
                         markevery=[-1], markersize=5, markerfacecolor="none")
            side.plot(result["x"][k], result["z"][k], label=legend, **marks)
            top.plot(result["x"][k], result["y"][k], label=legend, **marks)
    return drawn


def _label_axes(side, top) -> None:
    """The side and top views' labels, titles, grids and yard axes."""
    side.set_ylabel("height [m]")
    side.set_ylim(bottom=0.0)
    side.set_title("side view (heights not to scale with distances)")
    top.set_ylabel("offline, right of the target\nline downwards [m]")
    top.set_xlabel("along the target line [m]")
    top.axhline(0.0, color="0.6", linewidth=0.8)
    top.invert_yaxis()  # seen from above, with the target to the right, the golfer's right is down the page
    top.set_title("top view (from above, target to the right)")
    side.set_xlabel("along the target line [m]")
    side.tick_params(labelbottom=True)
    for axis in (side, top):
        axis.grid(True, alpha=0.3)
        yards = axis.secondary_xaxis("top", functions=(lambda v: v / YARD, lambda v: v * YARD))
        yards.set_xlabel("[yd]", fontsize=8)


def _default_title(dataset: xr.Dataset, air: dict, aerodynamics: str, changed: str, n_shown: int, n_cases: int,
                   computed: np.ndarray) -> str:
    """The figure's title when the caller gives none: the study, the delivery and contact, the air and its model,
    and how many cases are drawn."""
    air_words = (f"air {air['temperature'] - 273.15:.0f} degC, {float(air['pressure']) / 100:.0f} hPa, "
                 f"{100 * float(air['relative_humidity']):.0f} % RH")
    wind = np.asarray(air["wind"], dtype=float).reshape(-1)
    if np.any(wind):
        air_words += f", headwind {-wind[0]:g} m/s, crosswind {wind[1]:g} m/s"
    count = "" if n_shown == n_cases else f"; {n_shown} of {n_cases} cases per model"
    if not computed.all():
        count += f"; {int((~computed).sum())} model-case(s) without a computed launch (NaN) not drawn"
    scene = conditions(dataset)  # the delivery and contact the launches come from (what no coordinate carries)
    # conditions() names the air model when the result records one; a launch-only result is flown with the default
    air_model = "" if "aerodynamics" in scene and not changed else f"{aerodynamics} aerodynamics{changed}, "
    return (f"Ball flight after each model's launch ({dataset.attrs.get('study_name', '')})\n"
            + (f"{scene}\n" if scene else "") + f"{air_model}{air_words}{count}")


#: coordinate names a swept air field takes in a result (its last path component)
INPUT_COORDS = {"air_temperature": "temperature", "air_pressure": "pressure"}


def _flown_part(x, z, y):
    """A path's points up to its landing (the integrator holds the landing point to the end of the array)."""
    moving = np.concatenate([[True], np.diff(x) > 0.0])
    return x[moving], z[moving], y[moving]


def _lies_on(drawn, x, z, y) -> tuple[str, str] | None:
    """The model and case of an earlier path this one lies on (and so hides), within about a line's width in both views
    (0.4 % of the larger of its apex, its largest offline distance and 10 m; its landing within 0.4 % of its
    carry), or None."""
    width = 0.004 * max(float(np.max(z)), float(np.max(np.abs(y))), 10.0)
    for other_x, other_z, other_y, label in drawn:
        if abs(other_x[-1] - x[-1]) > 0.004 * max(abs(x[-1]), abs(other_x[-1]), 1.0):
            continue
        inside = (x >= other_x[0]) & (x <= other_x[-1])
        if inside.any() and np.max(np.abs(np.interp(x[inside], other_x, other_z) - z[inside])) <= width \
                and np.max(np.abs(np.interp(x[inside], other_x, other_y) - y[inside])) <= width:
            return label
    return None


def _case_label(row, index: int) -> str:
    """The case's coordinates in words (``toe -10 mm``-like: 'toe -0.01'), for a legend."""
    if "case" not in row.coords or row.sizes.get("case", 0) <= 1:
        return ""
    parts = []
    for name in row["case"].to_index().names if hasattr(row["case"].to_index(), "names") else []:
        if name is None or name == "case":
            continue
        value = row[name].values[index]
        units = row[name].attrs.get("units", "")
        units = "" if units in ("", "1") else f" {units}"
        parts.append(f"{name} {value:g}{units}" if isinstance(value, (int, float, np.floating)) else f"{name} {value}")
    return ", ".join(parts)
