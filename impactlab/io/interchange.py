"""Export a delivery study's shots to the format golf simulators read (GSPro Open Connect v1).

GSPro Open Connect (https://gsprogolf.com/GSProConnectV1.html, the vendor's one page) takes one
JSON message per shot over a TCP socket; :mod:`impactlab.io.gspro_connect` sends the messages
built here, and :func:`write_gspro` writes the same messages to a file. The vendor states no
units and no signs: those below are what every working client sends, as surveyed in
PinPoint-Golf/libgspro ``docs/protocol.md`` §3.2-3.6 (commit 543a801, MIT, M. Liversedge, 2026)
and gathered in the project's notes on vendors (GSPro Open Connect API v1).

Ball data (``BallData``), all from impactlab outputs:

| field | unit | meaning and sign (impactlab output it comes from) |
|---|---|---|
| Speed | mph | ball speed, ground frame (``ball_speed``; 1 mph = 0.44704 m/s exactly) |
| VLA | deg | vertical launch angle above the horizontal (``vertical_launch_angle``) |
| HLA | deg | horizontal launch angle, positive right of the target line (``horizontal_launch_angle``) |
| TotalSpin | rpm | spin rate (``spin_rate``) |
| SpinAxis | deg | tilt of the spin axis, positive curving right, a right-hander's fade (``spin_axis``) |
| BackSpin | rpm | TotalSpin cos(SpinAxis) |
| SideSpin | rpm | TotalSpin sin(SpinAxis): the sign of SpinAxis, as GSPro's clients send it |
| CarryDistance | yd | carry (``carry_distance``), only when the result has it |

Club data (``ClubData``), from the study's delivery (a swept coordinate, or the base scene):

| field | unit | meaning and sign (study field it comes from) |
|---|---|---|
| Speed | mph | club-head speed at the face centre (``delivery.club_speed``) |
| AngleOfAttack | deg | attack angle, positive upwards (``delivery.attack_angle``) |
| Loft | deg | dynamic loft (``delivery.dynamic_loft``) |
| Path | deg | club path, positive right of the target line (``delivery.path``; in-to-out, right-handed) |
| FaceToTarget | deg | face angle, positive right of the target line (``delivery.face_angle``; open, right-handed) |

Left out, so that no number is guessed: ``Lie`` (impactlab keeps the heel-toe line level and
knows no dynamic lie), ``ClosureRate`` (the head's rotation before impact is not modelled),
``SpeedAtImpact`` (no source says how it differs from ``Speed``) and ``HorizontalFaceImpact`` /
``VerticalFaceImpact`` (their unit is stated nowhere: one client's notes say inches, another's
millimetres, and their signs are unknown).

impactlab's own conventions (docs/conventions.md) are those signs for every ball value, so no
ball value changes sign on the way out; speeds change unit (m/s -> mph), carry m -> yd. GSPro's
handling of a left-handed golfer's club data is not documented (libgspro §3.5): the horizontal
club angles are sent right-positive, like HLA and SpinAxis.
"""

from __future__ import annotations

import json
import math
import os
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from impactlab.errors import FieldError, PlausibilityWarning, StudyError
from impactlab.io.safe_output import write_atomically
from impactlab.units import MPH, YARD, to_si
from impactlab.vocabulary import INPUT_BY_PATH, INPUTS, MODEL_DIM, TIME_DIM, output_unit_factor

#: outputs a GSPro shot needs
GSPRO_OUTPUTS = ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis")
#: ClubData key -> the delivery input it carries (module docstring: units and signs)
GSPRO_CLUB_DATA = {"Speed": "speed", "AngleOfAttack": "attack_angle", "FaceToTarget": "face_angle",
                   "Loft": "dynamic_loft", "Path": "path"}
#: inputs that only a golf delivery has: without them a result has no club data
_DELIVERY_ONLY = ("attack_angle", "dynamic_loft")
#: the key of the message's traceability block (model and sweep values): written to files, never sent to GSPro
TRACE_KEY = "impactlab"


def gspro_shots(dataset: xr.Dataset, model: str | None = None, device_id: str = "impactlab",
                first_shot: int = 1) -> list[dict]:
    """One GSPro Open Connect v1 message per case of a delivery result (every model, or ``model``).

    Parameters
    ----------
    dataset : xarray.Dataset
        A result of a study with a delivery block that asks for :data:`GSPRO_OUTPUTS`
        (``carry_distance`` too, if present, becomes ``CarryDistance``).
    model : str, optional
        Only this model's shots (default: every model, one after the other).
    device_id : str
        ``DeviceID`` of the messages.
    first_shot : int
        ``ShotNumber`` of the first message; the others count up from it.

    Returns
    -------
    list of dict
        Messages with ``DeviceID``, ``Units`` ("Yards"), ``ShotNumber``, ``APIversion`` ("1"),
        ``BallData`` (Speed mph, spins rpm, angles deg), ``ClubData`` (club speed mph, angles deg)
        when the result holds a delivery, and ``ShotDataOptions``; units and signs in the module
        docstring. Each also carries, under ``"impactlab"``, the model and the sweep values of its
        case so a shot can be traced back to its scene (:func:`wire_message` drops it). A case a
        model could not compute (a NaN ball value) has no message.

    Raises
    ------
    StudyError
        The result lacks an output a shot needs.
    FieldError
        ``model`` is not a model of the result.
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
    scene = _base_scene(dataset)
    shots = []
    number = first_shot
    for name in models:
        subset = dataset.sel({MODEL_DIM: name})
        reference = subset[GSPRO_OUTPUTS[0]]
        ball = {output: _flat(subset[output], reference) * _to_vocabulary_units(subset[output])
                for output in GSPRO_OUTPUTS}
        carry = _carry_yards(subset, reference)
        club = _club_data(subset, reference, scene)
        trace = {key: _flat(coord, reference) for key, coord in subset.coords.items()
                 if key not in (MODEL_DIM, TIME_DIM) and set(coord.dims) <= set(reference.dims) and coord.dims}
        for index in range(reference.size):
            values = {output: float(ball[output][index]) for output in GSPRO_OUTPUTS}
            if not all(np.isfinite(list(values.values()))):
                continue  # a case the model could not compute has no shot
            axis = math.radians(values["spin_axis"])
            ball_data = {
                "Speed": round(values["ball_speed"] / MPH, 2),
                "SpinAxis": round(values["spin_axis"], 2),
                "TotalSpin": round(values["spin_rate"], 1),
                "BackSpin": round(values["spin_rate"] * math.cos(axis), 1),
                "SideSpin": round(values["spin_rate"] * math.sin(axis), 1),
                "HLA": round(values["horizontal_launch_angle"], 2),
                "VLA": round(values["vertical_launch_angle"], 2),
            }
            if carry is not None and np.isfinite(carry[index]):
                ball_data["CarryDistance"] = round(float(carry[index]), 1)
            club_data = {key: round(float(column[index]), 2) for key, column in club.items()
                         if np.isfinite(column[index])}
            message = {
                "DeviceID": device_id,
                "Units": "Yards",
                "ShotNumber": number,
                "APIversion": "1",
                "BallData": ball_data,
            }
            if club_data:
                message["ClubData"] = club_data
            message["ShotDataOptions"] = {"ContainsBallData": True, "ContainsClubData": bool(club_data),
                                          "LaunchMonitorIsReady": True, "LaunchMonitorBallDetected": True,
                                          "IsHeartBeat": False}
            message[TRACE_KEY] = {"model": name, **{key: _plain(column[index]) for key, column in trace.items()}}
            shots.append(message)
            number += 1
    return shots


def wire_message(message: dict) -> bytes:
    """The bytes GSPro Open Connect receives for ``message``: compact UTF-8 JSON, no delimiter.

    The traceability block (``"impactlab"``) is left out: the protocol does not have it. Most
    clients GSPro works with send compact JSON without a trailing newline (libgspro
    ``docs/protocol.md`` §2).
    """
    sent = {key: value for key, value in message.items() if key != TRACE_KEY}
    return json.dumps(sent, separators=(",", ":"), allow_nan=False).encode("utf-8")


def _to_vocabulary_units(values: xr.DataArray) -> float:
    """The factor from a ball output's ``units`` to the vocabulary's: 1 for impactlab's own file (and for a dataset
    made in Python without units attributes, which :func:`gspro_shots` reads in the vocabulary's units). A result
    edited with xarray (ball_speed converted to mph, its units attribute with it) was read as m/s, and 100 mph was
    sent as 224 mph without a word."""
    return output_unit_factor(str(values.name), values.attrs.get("units"))


def _flat(values: xr.DataArray, reference: xr.DataArray) -> np.ndarray:
    """``values`` over every case of ``reference``, flattened in the same order."""
    return values.broadcast_like(reference).transpose(*reference.dims).values.ravel()


def _plain(value):
    return value.item() if hasattr(value, "item") else value


def _base_scene(dataset: xr.Dataset) -> dict:
    """The base scene's SI inputs stored in the result (empty if the file has none)."""
    try:
        scene = json.loads(dataset.attrs.get("base_scene_si", "{}") or "{}")
    except (ValueError, TypeError):
        return {}
    return scene if isinstance(scene, dict) else {}


def _input_values(subset: xr.Dataset, reference: xr.DataArray, scene: dict, name: str) -> np.ndarray | None:
    """SI value of input ``name`` for every case: its sweep coordinate, else the base scene's; None if neither."""
    spec = INPUTS[name]
    for coord in subset.coords.values():
        if INPUT_BY_PATH.get(coord.attrs.get("study_path")) != name:
            continue
        units = coord.attrs.get("units", spec.display_unit or spec.unit)
        factor = 1.0 / spec.display_factor if units == (spec.display_unit or spec.unit) else \
            to_si(f"1 {units}", spec.dimension, path=f"coordinate {coord.name}")
        return _flat(coord * factor, reference).astype(float)
    value = scene.get(name)
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return np.full(reference.size, float(value))
    return None


def _club_data(subset: xr.Dataset, reference: xr.DataArray, scene: dict) -> dict[str, np.ndarray]:
    """ClubData columns (GSPro units and signs) of a delivery result; empty without a delivery."""
    inputs = {name: _input_values(subset, reference, scene, name) for name in (*GSPRO_CLUB_DATA.values(),
                                                                                "handedness")}
    if any(inputs[name] is None for name in _DELIVERY_ONLY):
        return {}
    columns = {}
    for key, name in GSPRO_CLUB_DATA.items():
        values = inputs[name]
        if values is None:
            continue
        if name == "speed":
            columns[key] = values / MPH
            continue
        degrees = np.degrees(values)
        if name in ("path", "face_angle"):  # golfer's words (in-to-out, open) -> right of the target line
            if inputs["handedness"] is None:
                continue  # which way is right is unknown: leave the angle out rather than guess
            degrees = degrees * np.sign(inputs["handedness"])
        columns[key] = degrees
    return columns


def _carry_yards(subset: xr.Dataset, reference: xr.DataArray) -> np.ndarray | None:
    """Carry of every case in yards, if the result has ``carry_distance`` (in its ``units``)."""
    if "carry_distance" not in subset.data_vars:
        return None
    carry = subset["carry_distance"]
    units = carry.attrs.get("units")
    if not units:
        raise StudyError("carry_distance has no units attribute: its values cannot be sent in yards")
    metres = 1.0 if units == "m" else to_si(f"1 {units}", "length", path="carry_distance.units")
    return _flat(carry, reference).astype(float) * metres / YARD


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


def checked_shots(dataset: xr.Dataset, **options: Any) -> list[dict]:
    """:func:`gspro_shots`, with a PlausibilityWarning for each kind of shot no real club makes.

    Implausible shots are kept as computed: the warning says what they are, the simulator flies them.
    The one path from a result to messages, for the file and for the live connection alike.
    """
    shots = gspro_shots(dataset, **options)
    for text in implausible_shots(dataset, options.get("model")):
        warnings.warn(text, PlausibilityWarning, stacklevel=3)
    return shots


def write_gspro(dataset: xr.Dataset, path: str | os.PathLike, **options: Any) -> int:
    """Write the shots as a JSON array to ``path`` (atomically); return how many.

    The messages are those :mod:`impactlab.io.gspro_connect` sends, each with its ``"impactlab"``
    block (model and sweep values) kept; physically implausible shots are written as computed,
    with a PlausibilityWarning for each kind.
    """
    shots = checked_shots(dataset, **options)
    write_atomically(Path(path), json.dumps(shots, indent=1).encode())
    return len(shots)
