"""Stored results are inputs too: what the redraw (``plot --trajectories``) and the export read is checked first.

A result file can be edited (xarray, h5py) or written by an older impactlab. Its launch values are redrawn as
flights and sent to golf simulators, so they pass the rules that ``impactlab fly`` and studies apply to the same
quantities (issue 35), each refusal naming the file, the variable, the first case, the value in the unit its
``units`` attribute states and the range:

- every ``units`` attribute names a unit of its quantity (:func:`impactlab.vocabulary.output_unit_factor`);
- launch values lie in the ranges no golf shot leaves (:data:`impactlab.scene.flight.IMPOSSIBLE_LAUNCH`: ball
  speed up to 300 mph, spin up to 20,000 rpm; launch angles within +-90 deg, as ``fly`` refuses them);
- the spins agree with one another where the file holds them all: the spin axis is the angle of back and side
  spin (a ``rad`` attribute put on an axis stored in degrees breaks this), and the spin rate's magnitude is never
  below theirs;
- the stored air is an air :class:`impactlab.scene.air.Conditions` accepts (an air temperature of 5000 K is not);
- the aerodynamic model a flight output names is one of this impactlab (a retired one refused with why and what to
  use), and a fingerprint that differs from today's model is said.
"""

from __future__ import annotations

import json
import math
import os

import numpy as np
import xarray as xr

from impactlab.errors import FieldError, StudyError
from impactlab.foreign import shown
from impactlab.scene.air import Conditions
from impactlab.physics.aerodynamics import MODELS, model_fingerprint, retired_reason
from impactlab.scene.flight import IMPOSSIBLE_LAUNCH
from impactlab.vocabulary import FLIGHT_OUTPUTS, output_unit_factor

_MPH = 1.0 / 0.44704
#: launch outputs and the range no golf shot leaves, in the vocabulary's units (a result's): (low, high, words);
#: the ball speed and spin limits are ``fly``'s (IMPOSSIBLE_LAUNCH), the angles' its refusals of launch angles
STORED_RANGES = {
    "ball_speed": (0.0, IMPOSSIBLE_LAUNCH["ball_speed"][0], "m/s",
                   IMPOSSIBLE_LAUNCH["ball_speed"][1].replace("a ball speed", "a positive ball speed", 1)),
    "vertical_launch_angle": (-90.0, 90.0, "degree", "a launch angle between -90 and 90 deg (beyond, the ball "
                                                     "leaves backwards)"),
    "horizontal_launch_angle": (-90.0, 90.0, "degree", "a launch direction between -90 and 90 deg of the target "
                                                       "line"),
    # a result's spin rate is signed (negative: topspin, impactlab.physics.contact), its magnitude fly's limit
    "spin_rate": (-20000.0, 20000.0, "rpm", "a spin rate within +-20,000 rpm (negative: topspin; golf balls leave a "
                                            "club with at most about 12,000 rpm)"),
    "back_spin": (-20000.0, 20000.0, "rpm", "a back spin within +-20,000 rpm (golf balls leave a club with at most "
                                            "about 12,000 rpm)"),
    "side_spin": (-20000.0, 20000.0, "rpm", "a side spin within +-20,000 rpm"),
    "spin_axis": (-180.0, 180.0, "degree", "a spin axis within +-180 deg (an angle)"),
}
#: spins that disagree by more than this are not one spin (rounding in a file is far below)
SPIN_TOLERANCE = 0.01
AXIS_TOLERANCE_DEG = 0.5
#: stored air inputs (base_scene_si) -> the keyword of :class:`impactlab.scene.air.Conditions`
_AIR = {"air_temperature": "temperature", "air_pressure": "pressure", "relative_humidity": "relative_humidity",
        "altitude": "altitude", "headwind": "headwind", "crosswind": "crosswind"}


def _refuse(path, text: str) -> StudyError:
    return StudyError(f"{shown(path)}: {text}; the file was altered or is not impactlab's result as written (run "
                      "the study again)")


def launch_in_vocabulary_units(dataset: xr.Dataset, path: str | os.PathLike, names) -> dict[str, xr.DataArray]:
    """Each launch output of ``names`` the file holds, in the vocabulary's units, after its ``units`` attribute is
    checked; a StudyError names an attribute that is not a unit of the quantity."""
    out = {}
    for name in names:
        if name not in dataset.data_vars:
            continue
        units = dataset[name].attrs.get("units")
        try:
            factor = output_unit_factor(name, units)
        except FieldError as exc:
            raise _refuse(path, f"its units attribute is not a unit of the output's quantity: {exc}") from None
        out[name] = dataset[name] * factor
    return out


def _first_case(values: xr.DataArray, bad: np.ndarray) -> str:
    index = np.unravel_index(int(np.flatnonzero(bad.ravel())[0]), bad.shape)
    parts = [f"{dim} {values[dim].values[i]}" if dim in values.coords else f"{dim} {i}"
             for dim, i in zip(values.dims, index)]
    return ", ".join(parts)


def check_stored(dataset: xr.Dataset, path: str | os.PathLike, aerodynamics_needed: bool = True) -> list[str]:
    """Refuse a result whose launch values, units attributes, air or aerodynamic model no study could have written.

    Parameters
    ----------
    dataset : xarray.Dataset
        A result read with :func:`impactlab.io.results.open_results`.
    path : str or path-like
        The file, for messages.
    aerodynamics_needed : bool
        Whether the command uses the aerodynamic model (a redraw flies with it; an export sends the stored carry).

    Returns
    -------
    list of str
        Notes to say (a fingerprint that differs from today's model): the command goes on.

    Raises
    ------
    StudyError
        The first value, attribute or model refused, with the variable, the case, the value and the range.
    """
    notes: list[str] = []
    values = launch_in_vocabulary_units(dataset, path, STORED_RANGES)
    for name, (low, high, unit, words) in STORED_RANGES.items():
        if name not in values:
            continue
        array = np.asarray(values[name].values, dtype=float)
        finite = np.isfinite(array)
        bad = finite & ((array < low) | (array > high) | ((array <= 0) if name == "ball_speed" else False))
        bad |= np.isinf(array)
        if bad.any():
            value = float(array.ravel()[np.flatnonzero(bad.ravel())[0]])
            stated = dataset[name].attrs.get("units")
            shown_value = f"{value * _MPH:.6g} mph" if name == "ball_speed" else f"{value:.6g} {unit}"
            as_stored = (f" ({float(dataset[name].values.ravel()[np.flatnonzero(bad.ravel())[0]]):.6g} "
                         f"{shown(stated)} as its units attribute states)" if stated and stated != unit else "")
            raise _refuse(path, f"{name} at {_first_case(values[name], bad)}: {shown_value}{as_stored}; expected "
                                f"{words}, as impactlab fly and studies refuse it")
    _check_spins(values, path)
    _check_air(dataset, path)
    notes += _check_aerodynamics(dataset, path, aerodynamics_needed)
    return notes


def _check_spins(values: dict, path) -> None:
    """Spin rate, back spin, side spin and spin axis of one case are one spin (impactlab.physics.contact): the axis
    is atan2(side, back) exactly, and the spin rate's magnitude is the whole spin's, never below the part across
    the flight, hypot(back, side) (the rest is rifle spin along the flight, which a wedge's launch carries)."""
    if not all(name in values for name in ("back_spin", "side_spin")):
        return
    back, side = xr.broadcast(values["back_spin"], values["side_spin"])
    across = np.hypot(back, side)
    if "spin_rate" in values:
        rate, magnitude = xr.broadcast(values["spin_rate"], across)
        rate_v, magnitude_v = np.abs(np.asarray(rate.values, float)), np.asarray(magnitude.values, float)
        bad = np.isfinite(rate_v) & np.isfinite(magnitude_v) & (
            rate_v < magnitude_v - SPIN_TOLERANCE * np.maximum(magnitude_v, 100.0))
        if bad.any():
            index = np.flatnonzero(bad.ravel())[0]
            raise _refuse(path, f"spin_rate at {_first_case(rate, bad)}: {rate_v.ravel()[index]:.6g} rpm, below the "
                                f"{magnitude_v.ravel()[index]:.6g} rpm its back and side spin make (the spin rate is "
                                "the magnitude of the whole spin); a units attribute or a value was changed")
    if "spin_axis" in values:
        axis, angle, size = xr.broadcast(values["spin_axis"], np.degrees(np.arctan2(side, back)), across)
        axis_v, angle_v = np.asarray(axis.values, float), np.asarray(angle.values, float)
        spinning = np.isfinite(axis_v) & np.isfinite(angle_v) & (np.asarray(size.values, float) > 1.0)
        difference = np.abs((axis_v - angle_v + 180.0) % 360.0 - 180.0)
        bad = spinning & (difference > AXIS_TOLERANCE_DEG)
        if bad.any():
            index = np.flatnonzero(bad.ravel())[0]
            raise _refuse(path, f"spin_axis at {_first_case(axis, bad)}: {axis_v.ravel()[index]:.6g} deg, where its "
                                f"back and side spin tilt the axis {angle_v.ravel()[index]:.6g} deg (the axis is "
                                "atan2(side, back)); a units attribute or a value was changed")


def _check_air(dataset: xr.Dataset, path) -> None:
    """The stored base scene's air is an air ``fly`` accepts (its ranges: impactlab.scene.air.Conditions)."""
    try:
        scene = json.loads(dataset.attrs.get("base_scene_si", "{}") or "{}")
    except (TypeError, ValueError):
        raise _refuse(path, "its base_scene_si attribute is not JSON") from None
    if not isinstance(scene, dict):
        raise _refuse(path, "its base_scene_si attribute is not a JSON mapping")
    air = {}
    for name, key in _AIR.items():
        if name not in scene:
            continue
        value = scene[name]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(float(value)):
            raise _refuse(path, f"base_scene_si {name}: expected a finite number in SI units, got {shown(value)!s}")
        air[key] = float(value)
    try:
        Conditions(**air)
    except FieldError as exc:
        shown_value = exc.given
        if exc.path == "temperature" and isinstance(exc.given, float):
            shown_value = f"{exc.given:.6g} K"
        raise _refuse(path, f"the stored air, {exc.path}: expected {exc.expected}, got {shown(shown_value)}"
                      ) from None


def _check_aerodynamics(dataset: xr.Dataset, path, needed: bool) -> list[str]:
    """The aerodynamic model each flight output names: a model of this impactlab, not a retired one; a fingerprint
    other than today's model's is said (the stored carries were computed with other constants)."""
    notes = []
    flown = [name for name in FLIGHT_OUTPUTS if name in dataset.data_vars]
    for name in flown:
        model = dataset[name].attrs.get("aerodynamic_model")
        if model is None:
            continue
        reason = retired_reason(model)
        if reason:
            doing = "the paths would be flown with it" if needed else f"its {name} was computed with it"
            raise StudyError(f"{shown(path)}: {name} was computed with an aerodynamic model impactlab no longer has: "
                             f"{reason}; {doing}: run "
                             "the study again (its launches are unchanged; its flight is computed with today's "
                             "models)")
        if not isinstance(model, str) or model not in MODELS:
            raise _refuse(path, f"{name}: its aerodynamic_model attribute {shown(model)!s} is not an aerodynamic "
                                f"model of this impactlab (choices: {', '.join(MODELS)})")
        stored = dataset[name].attrs.get("aerodynamic_fingerprint")
        if stored is not None and str(stored) != model_fingerprint(model):
            notes.append(f"{shown(path)}: {name} was computed with {model}'s constants of fingerprint "
                         f"{shown(stored)}; today's are {model_fingerprint(model)} (the model was refitted since): "
                         + ("the paths are flown with today's constants and may not land on the stored carries"
                            if needed else "the stored values are used as they are"))
    return sorted(set(notes))


def drawable_cases(values: dict[str, xr.DataArray], names) -> tuple[np.ndarray, list[str]]:
    """Which cases have every launch value of ``names`` (finite), and the names NaN in every case."""
    arrays = xr.broadcast(*(values[name] for name in names))
    finite = np.logical_and.reduce([np.isfinite(np.asarray(array.values, float)) for array in arrays])
    empty = [name for name, array in zip(names, arrays) if not np.isfinite(np.asarray(array.values, float)).any()]
    return finite, empty


__all__ = ["check_stored", "STORED_RANGES", "launch_in_vocabulary_units", "drawable_cases"]
