"""Export a delivery study's ball data to the formats golf simulators read (GSPro Open Connect v1).

GSPro Open Connect (https://gsprogolf.com/GSProConnectV1.html) takes one JSON
message per shot over a socket. Ball data and the signs used here:

========== ====== ==============================================================
field      unit   meaning and sign (impactlab output it comes from)
========== ====== ==============================================================
Speed      mph    ball speed, ground frame (``ball_speed``)
VLA        deg    vertical launch angle above the horizontal (``vertical_launch_angle``)
HLA        deg    horizontal launch angle, positive right of the target line
                  (``horizontal_launch_angle``; a right-handed golfer's push or fade start)
TotalSpin  rpm    spin rate (``spin_rate``)
SpinAxis   deg    tilt of the spin axis, positive curving right (``spin_axis``)
BackSpin   rpm    TotalSpin cos(SpinAxis)
SideSpin   rpm    TotalSpin sin(SpinAxis), positive curving right
========== ====== ==============================================================

impactlab's own conventions (docs/conventions.md) already use these signs, so
no value changes sign on the way out; only speed changes unit (m/s -> mph).
"""

from __future__ import annotations

import json
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from impactlab.errors import FieldError, PlausibilityWarning, StudyError
from impactlab.io.safe_output import write_atomically
from impactlab.units import MPH, to_si
from impactlab.vocabulary import MODEL_DIM

#: outputs a GSPro shot needs
GSPRO_OUTPUTS = ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis")


def gspro_shots(dataset: xr.Dataset, model: str | None = None, device_id: str = "impactlab",
                first_shot: int = 1) -> list[dict]:
    """One GSPro Open Connect v1 message per case of a delivery result (every model, or ``model``).

    Each message carries ``ShotNumber``, the ball data above and, as
    ``impactlab`` extras ignored by GSPro, the model and the sweep values of
    the case so a shot can be traced back to its scene.
    """
    missing = [name for name in GSPRO_OUTPUTS if name not in dataset.data_vars]
    if missing:
        raise StudyError(f"a GSPro shot needs {', '.join(GSPRO_OUTPUTS)}; the file lacks {', '.join(missing)} "
                         "(run a study with a delivery block that asks for them)")
    models = [str(value) for value in dataset[MODEL_DIM].values]
    if model is not None:
        if model not in models:
            raise FieldError("--model", "a model of the result file", model, choices=models)
        models = [model]
    shots = []
    number = first_shot
    for name in models:
        subset = dataset.sel({MODEL_DIM: name})
        stacked = {output: subset[output].values.ravel() for output in GSPRO_OUTPUTS}
        dims = list(subset[GSPRO_OUTPUTS[0]].dims)
        grid = np.meshgrid(*[subset[dim].values for dim in dims], indexing="ij") if dims else []
        for index in range(stacked["ball_speed"].size):
            values = {output: float(stacked[output][index]) for output in GSPRO_OUTPUTS}
            if not all(np.isfinite(list(values.values()))):
                continue  # a case the model could not compute has no shot
            axis = np.radians(values["spin_axis"])
            shots.append({
                "DeviceID": device_id,
                "Units": "Yards",
                "ShotNumber": number,
                "APIversion": "1",
                "BallData": {
                    "Speed": round(values["ball_speed"] / MPH, 2),
                    "SpinAxis": round(values["spin_axis"], 2),
                    "TotalSpin": round(values["spin_rate"], 1),
                    "BackSpin": round(values["spin_rate"] * np.cos(axis), 1),
                    "SideSpin": round(values["spin_rate"] * np.sin(axis), 1),
                    "HLA": round(values["horizontal_launch_angle"], 2),
                    "VLA": round(values["vertical_launch_angle"], 2),
                },
                "ShotDataOptions": {"ContainsBallData": True, "ContainsClubData": False},
                "impactlab": {"model": name, **{dim: _plain(grid[k].ravel()[index]) for k, dim in enumerate(dims)}},
            })
            number += 1
    return shots


def _plain(value):
    return value.item() if hasattr(value, "item") else value


#: ball speed over club speed beyond which no real club delivers (conforming drivers reach about 1.50-1.52;
#: a face fixed in space, i.e. an infinitely heavy club, gives up to about 1.9)
MAX_SMASH_FACTOR = 1.6


def _club_speed(dataset: xr.Dataset) -> xr.DataArray | float | None:
    """Club speed of every case in m/s: a swept coordinate, or the base scene's."""
    for name in ("club_speed", "speed"):
        if name in dataset.coords:
            units = dataset[name].attrs.get("units", "m/s")
            return dataset[name] * to_si(f"1 {units}", "speed")
    try:
        return float(json.loads(dataset.attrs.get("base_scene_si", "{}"))["speed"])
    except (KeyError, ValueError, TypeError):
        return None


def implausible_shots(dataset: xr.Dataset, model: str | None = None) -> list[str]:
    """Sentences about shots no real club and ball would make, per model: a simulator would fly them anyway."""
    found = []
    club = _club_speed(dataset)
    models = [model] if model is not None else [str(value) for value in dataset[MODEL_DIM].values]
    for name in models:
        subset = dataset.sel({MODEL_DIM: name})
        smash = subset["smash_factor"] if "smash_factor" in subset else (
            subset["ball_speed"] / club if club is not None else None)
        if smash is not None:
            over = int((smash > MAX_SMASH_FACTOR).sum())
            if over:
                found.append(f"{name}: {over} shot(s) have a smash factor above {MAX_SMASH_FACTOR} (up to "
                             f"{float(smash.max()):.2f}); no real club does that: a face fixed in space or a very "
                             "heavy head? (give the study a club or a face mass)")
        if "back_spin" in subset:
            backwards = int((subset["back_spin"] < 0).sum())
        else:
            backwards = int((np.abs(subset["spin_axis"]) > 90).sum())
        if backwards:
            found.append(f"{name}: {backwards} shot(s) spin forwards (negative backspin, spin axis beyond 90 deg): "
                         "a loft below the attack angle? simulators fly such shots, but they are not golf shots")
    return found


def write_gspro(dataset: xr.Dataset, path: str | os.PathLike, **options: Any) -> int:
    """Write the shots as a JSON array to ``path`` (atomically); return how many.

    Physically implausible shots are written as computed, with a PlausibilityWarning for each kind.
    """
    shots = gspro_shots(dataset, **options)
    for text in implausible_shots(dataset, options.get("model")):
        warnings.warn(text, PlausibilityWarning, stacklevel=2)
    write_atomically(Path(path), json.dumps(shots, indent=1).encode())
    return len(shots)
