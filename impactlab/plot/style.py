"""What every figure shares: line styles and markers, the units a reader thinks in, and the audit of a drawn
figure (empty panels, legend entries with nothing drawn) run before it is saved."""

from __future__ import annotations

import textwrap
import warnings
from pathlib import Path
from typing import Any

import numpy as np

_STYLES = ("-", "--", ":", "-.", (0, (5, 1, 1, 1, 1, 1)))
#: one marker per line, so that a curve lying on another stays visible by its markers
_MARKERS = ("o", "s", "^", "v", "D", "P", "X", "<", ">", "*")
#: units a reader thinks in: millimetres for contact radii, microseconds for contact times, kilonewtons
_DISPLAY_UNITS = {"m": ("mm", 1e3), "s": ("us", 1e6), "N": ("kN", 1e-3)}


class FigureWarning(UserWarning):
    """A figure that does not show what it claims: an empty panel or a legend entry with nothing drawn."""


#: outputs shown in other units than their unit's default: the ball flight's distances in yards, as golfers read them
_DISPLAY_BY_NAME = {"carry_distance": ("yd", 1 / 0.9144), "offline_distance": ("yd", 1 / 0.9144),
                    "apex_height": ("yd", 1 / 0.9144)}


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
    path = Path(path)
    figure.savefig(path, dpi=110)
    return path
