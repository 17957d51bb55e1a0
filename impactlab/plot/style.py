"""What every figure shares: line styles and markers, the units a reader thinks in, and the audit of a drawn
figure (empty panels, legend entries with nothing drawn) run before it is saved."""

from __future__ import annotations

import json
import textwrap
import warnings
from collections.abc import Iterable
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from impactlab.io.safe_output import write_figure
from impactlab.units import MPH, YARD

_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)))
#: one marker per line, so that a curve lying on another stays visible by its markers
_MARKERS = ("o", "s", "^", "v", "D", "P", "X", "<", ">", "*")
#: units a reader thinks in: millimetres for contact radii, microseconds for contact times, kilonewtons
_DISPLAY_UNITS = {"m": ("mm", 1e3), "s": ("us", 1e6), "N": ("kN", 1e-3)}


class FigureWarning(UserWarning):
    """A figure that does not show what it claims: an empty panel or a legend entry with nothing drawn."""


#: outputs shown in other units than their unit's default: the ball flight's distances in yards, as golfers read them
_DISPLAY_BY_NAME = {"carry_distance": ("yd", 1 / YARD), "offline_distance": ("yd", 1 / YARD),
                    "apex_height": ("yd", 1 / YARD)}


def _display(units: str, name: str | None = None) -> tuple[str, float]:
    if name in _DISPLAY_BY_NAME:
        return _DISPLAY_BY_NAME[name]
    return _DISPLAY_UNITS.get(units, (units, 1.0))


def _axis_label(long_name: str, units: str, width: int = 42) -> str:
    return "\n".join(textwrap.wrap(f"{long_name} [{units}]", width))


def audit(figure: Any) -> list[str]:
    """What is wrong with a drawn figure: panels with nothing finite drawn, legend entries with nothing drawn."""
    problems = []
    for index, axis in enumerate(figure.axes):
        if not axis.get_visible():
            continue
        lines = [line for line in axis.get_lines() if line.get_label() and not line.get_label().startswith("_")]
        finite = [line for line in axis.get_lines()
                  if np.any(np.isfinite(np.asarray(line.get_ydata(), float)))
                  and np.any(np.isfinite(np.asarray(line.get_xdata(), float)))]
        collections = [c for c in axis.collections if len(c.get_offsets()) or len(c.get_paths())]
        # bars (patches with an extent) and images (an index map) are drawn data as well as lines are
        bars = [patch for patch in axis.patches if patch.get_width() != 0 or patch.get_height() != 0] \
            if hasattr(axis, "patches") else []
        if not finite and not collections and not bars and not axis.images:
            problems.append(f"panel {index + 1} ({axis.get_ylabel()!r}) has nothing drawn")
        for line in lines:
            ys = np.asarray(line.get_ydata(), float)
            if not np.any(np.isfinite(ys)):
                problems.append(f"legend entry {line.get_label()!r} has nothing drawn")
    return problems


def _save(figure, path) -> Path:
    problems = audit(figure)
    if problems:
        warnings.warn(f"{path}: " + "; ".join(problems), FigureWarning, stacklevel=3)
    return write_figure(figure, path, dpi=110)


def conditions(dataset: xr.Dataset, skip: Iterable[str] = ()) -> str:
    """The scene's fixed conditions in words (speed, friction, restitution, face, club), leaving out swept ones."""
    try:
        scene = json.loads(dataset.attrs.get("base_scene_si", "{}") or "{}")
    except ValueError:
        return ""
    # swept fields (dimensions, fields a labelled dimension sets) vary between the lines, and a selected value
    # is named in the title or legend: only what no coordinate carries is a condition of the whole figure
    swept = set(dataset.dims) | set(dataset.coords) | set(skip)
    if "club_speed" in swept:  # a delivery's impact speed follows its club speed
        swept.add("speed")
    words = []

    def value(key):
        item = scene.get(key)
        if key in swept or item is None:
            return None
        return float(item) if not isinstance(item, str) else float(item)

    if (speed := value("club_speed")) is not None:
        words.append(f"club speed {speed / MPH:.0f} mph")
    elif (speed := value("speed")) is not None:
        words.append(f"{speed / MPH:.0f} mph")
    # a golf delivery's angles: loft and attack, and path and face where the club is not square
    for key, label in (("dynamic_loft", "loft"), ("attack_angle", "attack"), ("path", "path"), ("face_angle", "face")):
        angle = value(key)
        if angle is not None and (angle != 0.0 or key in ("dynamic_loft", "attack_angle")):
            words.append(f"{label} {np.degrees(angle):.3g} deg")
    for key, text in (("friction", "friction {:g}"), ("restitution", "e {:g}"),
                      ("tangential_loss", "cover loss {:g}")):
        item = value(key)
        if item is not None and not (key == "tangential_loss" and item == 0.0):
            words.append(text.format(item))
    face, club = value("face_youngs_modulus"), value("club_mass")
    stiffness = None if face is None else "rigid" if np.isinf(face) else f"E {face / 1e9:.0f} GPa"
    if club is not None and np.isinf(club):
        words.append(f"fixed face ({stiffness})" if stiffness else "fixed face")
    else:
        if stiffness:
            words.append(f"{stiffness} face")
        if club is not None:
            words.append(f"{club * 1e3:.0f} g head")
    # the air model that flew the ball, where the result holds a flight output (each names its model)
    air_models = sorted({str(variable.attrs["aerodynamic_model"]) for variable in dataset.data_vars.values()
                         if "aerodynamic_model" in variable.attrs})
    if air_models:
        words.append(f"{' / '.join(air_models)} aerodynamics")
    return ", ".join(words)
