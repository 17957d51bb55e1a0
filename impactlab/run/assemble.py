"""Assemble per-model results (dimension ``case``) into one study dataset (sweep dimensions and ``model``)."""

from __future__ import annotations

import datetime as _dt
import functools
import json
import math
import platform
import subprocess
from importlib import metadata
from pathlib import Path
from collections.abc import Hashable
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr
from xarray.indexes import PandasIndex

from impactlab._version import __version__
from impactlab.io.results import CF_CONVENTIONS, RESULT_FORMAT
from impactlab.physics.aerodynamics import DEFAULT_MODEL, MODEL_REFERENCES, model_fingerprint
from impactlab.model.diagnostics import flag_attributes
from impactlab.run.rules_test import head_cor_note
from impactlab.study.core import Study
from impactlab.vocabulary import FLIGHT_OUTPUTS, INPUTS, MODEL_DIM, OUTPUTS, TIME_DIM, is_history

if TYPE_CHECKING:  # run.runner imports this module
    from impactlab.run.runner import StudyPlan


def assemble(study: Study, plan: StudyPlan, results: list[dict]) -> xr.Dataset:
    """One dataset for the whole study, with sweep coordinates, the model coordinate and provenance.

    ``results`` holds, per model entry, its outputs over the flat cases as arrays in the vocabulary's
    units (:func:`impactlab.run.execution.run_chunks`). The dataset is built once, here, from stacked arrays:
    xarray is the edge of the framework, not its inside.
    """
    shape = study.shape if study.sweep else ()
    sweep_dims = [axis.dim for axis in study.sweep]
    time = _common_time([result["time"] for result in results])
    data_vars = {}
    # which air model flew the ball, once for every flight output: the default can change between versions, and a
    # refit keeps its name (the fingerprint of its coefficients tells)
    air_model = ({"aerodynamic_model": DEFAULT_MODEL, "aerodynamic_references": MODEL_REFERENCES[DEFAULT_MODEL],
                  "aerodynamic_fingerprint": model_fingerprint(DEFAULT_MODEL)}
                 if set(FLIGHT_OUTPUTS).intersection(study.all_outputs) else {})
    for name in study.all_outputs:
        spec = OUTPUTS[name]
        history = time is not None and is_history(name)
        # np.stack's result (the models' arrays have one shape), without its Python-level wrapper: ~30 us cold
        stacked = np.array([_on_time(result, name, time, history) for result in results])
        stacked = stacked.reshape((len(results),) + shape + ((time.size,) if history and time is not None else ()))
        attributes: dict[str, object] = {"units": spec.units, "long_name": spec.long_name}
        if name in FLIGHT_OUTPUTS:
            attributes.update(air_model)
        reasons = [f"{entry.id}: {result['missing'][name]}" for entry, result in zip(study.models, results)
                   if name in result["missing"]]
        if reasons:
            attributes["missing"] = "; ".join(reasons)
        dims = [MODEL_DIM] + sweep_dims + ([TIME_DIM] if history else [])
        encoding = None
        if name == "validity":
            stacked, encoding = _integer_flags(stacked)
            attributes.update(flag_attributes())
        data_vars[name] = xr.Variable(dims, stacked, attributes, encoding)
    coords = {MODEL_DIM: xr.Variable(MODEL_DIM, [entry.id for entry in study.models],
                                     {"long_name": "model",
                                      "model_names": json.dumps([entry.name for entry in study.models])})}
    for axis in study.sweep:
        if axis.grouped:
            labels = list(axis.labels) if axis.labels else list(range(axis.size))
            coords[axis.dim] = xr.Variable(axis.dim, labels, {
                "long_name": f"{axis.dim} (sets {', '.join(f.path for f in axis.fields)})"})
        for field in axis.fields:
            input_spec = INPUTS[field.input]  # an input's display units, not the output spec above
            # 12 significant digits: 30 deg stays 30.0 after its round trip through radians
            values = [float(f"{value * input_spec.display_factor:.12g}") for value in field.values]
            coords[field.coord] = xr.Variable(axis.dim, values, {"units": input_spec.display_unit or input_spec.unit,
                                                                 "long_name": input_spec.description,
                                                                 "study_path": field.path})
    if time is not None:
        # no CF standard_name "time": CF gives it calendar units (s since an epoch); this is elapsed time
        coords[TIME_DIM] = xr.Variable(TIME_DIM, time, {"units": "s", "long_name": "time since first contact"})
    return labelled_dataset(data_vars, coords, provenance(study, plan))


def labelled_dataset(data_vars: dict[str, xr.Variable], coords: dict[str, xr.Variable],
                     attributes: dict) -> xr.Dataset:
    """``xr.Dataset(data_vars, coords=coords, attrs=attributes)``, built without xarray's merge and alignment.

    The variables of a study's result share their dimensions by construction, so there is nothing to align: the
    dimension coordinates get their pandas indexes here (xarray's own :class:`xarray.indexes.PandasIndex`, as the
    constructor makes them) and the Dataset is put together from its parts, about a third of the constructor's
    time (~0.1-0.3 ms of the ~3 ms the framework spends around a 540-case study's physics). Where xarray lacks the
    direct constructor (a private one), or its signature has changed, the public one builds the same Dataset
    (tests/test_framework_arrays.py compares the two, so a release that changes what it builds fails there).

    Parameters
    ----------
    data_vars, coords : dict of str to xarray.Variable
        The data variables and the coordinates (a coordinate named after its dimension gets an index).
    attributes : dict
        The Dataset's attributes.

    Returns
    -------
    xarray.Dataset
    """
    construct = getattr(xr.Dataset, "_construct_direct", None)
    if construct is None:  # pragma: no cover - every xarray impactlab supports has it
        return xr.Dataset(data_vars, coords=coords, attrs=attributes)
    variables: dict[str, xr.Variable] = dict(data_vars)
    indexes = {}
    for name, variable in coords.items():
        if variable.dims == (name,):
            index = PandasIndex.from_variables({name: variable}, options={})
            variables.update(index.create_variables({name: variable}))
            indexes[name] = index
        else:
            variables[name] = variable
    sizes: dict[Hashable, int] = {}
    for variable in variables.values():
        for dim, size in zip(variable.dims, variable.shape):
            if sizes.setdefault(dim, size) != size:
                raise ValueError(f"dimension {dim!r} has sizes {sizes[dim]} and {size}")  # never, by construction
    try:
        return construct(variables, set(coords), sizes, attributes, indexes)
    except (TypeError, ValueError):  # pragma: no cover - a private constructor whose signature a release changed
        return xr.Dataset(data_vars, coords=coords, attrs=attributes)


def _common_time(times: list) -> np.ndarray | None:
    """The time axis of the study's histories: the union of the models' own (an outer join; None without any)."""
    present = [np.asarray(time, dtype=float) for time in times if time is not None]
    if not present:
        return None
    if all(time.shape == present[0].shape and np.array_equal(time, present[0]) for time in present[1:]):
        return present[0]
    return functools.reduce(np.union1d, present)


def _on_time(result: dict, name: str, time: np.ndarray | None, history: bool) -> np.ndarray:
    """One model's values of ``name`` (cases first), placed on the common time axis with NaN where it has none."""
    values = result["data"][name]
    if not history:
        return values
    assert time is not None, "a history is placed on the study's time axis"
    if values.ndim == 1:  # a model without histories: NaN over the time axis of those that have them
        return np.full((values.shape[0], time.size), np.nan)
    own = np.asarray(result["time"], dtype=float)
    if own.shape == time.shape and np.array_equal(own, time):
        return values
    placed = np.full((values.shape[0], time.size), np.nan)
    placed[:, np.searchsorted(time, own)] = values
    return placed


#: in the file, a case a model did not compute has this validity (CF _FillValue)
VALIDITY_FILL = -1


def _integer_flags(values: np.ndarray) -> tuple[np.ndarray, dict | None]:
    """Validity bits as the integers CF flag variables are (models compute them as floats, NaN where absent).

    Returns the values and the variable's encoding: int16 values where every case has its bits; else the float
    values (NaN where a model did not compute a case), stored as int16 with the fill value :data:`VALIDITY_FILL`.
    """
    if not np.isnan(values).any():
        return values.astype(np.int16), None
    return values, {"dtype": "int16", "_FillValue": VALIDITY_FILL}  # stored as int16; NaN read back


def versions() -> dict[str, str | int]:
    """Versions of everything that shapes a result: the numerics (numpy, scipy, numba), units (pint), storage.

    Read once per process (reading package metadata costs ~10 ms, more than a small study's physics);
    the packages a process has imported do not change under it.
    """
    return dict(_versions())


@functools.cache
def _versions() -> dict[str, str | int]:
    found: dict[str, str | int] = {"impactlab_version": __version__, "impactlab_format": RESULT_FORMAT,
                                   "python_version": platform.python_version()}
    for package in ("numpy", "scipy", "numba", "xarray", "pint", "h5py", "h5netcdf"):
        try:
            found[f"{package}_version"] = metadata.version(package)
        except metadata.PackageNotFoundError:
            found[f"{package}_version"] = "not installed"
    return found


@functools.cache
def git_commit() -> str:
    """The commit of the checkout impactlab runs from ('' if installed from a package), '-dirty' if edited.

    Asked once per process (two git calls cost ~5 ms): the code a process runs is what it imported,
    so the first answer is also the right one for a later edit of the checkout.
    """
    here = Path(__file__).resolve().parent
    try:
        commit = subprocess.run(["git", "-C", str(here), "rev-parse", "HEAD"], capture_output=True, text=True,
                                timeout=5, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(here), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=5, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""
    return f"{commit}-dirty" if dirty else commit


def study_head_cor(study: Study) -> str:
    """The head COR each of the study's models (with its options) gives its base scene's club at the Rules' test,
    when some model goes beyond the limit ('' otherwise, and for a scene without a spring-faced club):
    :func:`impactlab.run.rules_test.head_cor_note`. A sweep over clubs or balls is judged at its base scene only."""
    scene = study.scene
    if scene.club is None or scene.club.restitution_gain <= 0.0:
        return ""
    name = scene.club.name or "the study's club"
    note = head_cor_note({entry.id: entry.model for entry in study.models}, scene.ball, {name: scene.club},
                         scene.contact, whose="the study's ball and contact, at its base scene")
    swept = sorted({field.path for axis in study.sweep for field in axis.fields
                    if field.path.split(".")[0] in ("ball", "club", "face") or field.path == "contact.restitution"})
    if note and swept:  # what the base scene says need not hold where the sweep changes the ball, head or e
        note += f" (judged at the base scene only: the study sweeps {', '.join(swept)})"
    return note


def provenance(study: Study, plan: StudyPlan) -> dict[str, str | int]:
    """What made this result: the study, its models with resolved options, versions, the plan."""
    models = [{"id": entry.id, "name": entry.name, "label": entry.model.label, "options": entry.model.options_dict(),
               "references": list(entry.model.references)} for entry in study.models]
    # math.isfinite: the same answer for a float as np.isfinite, at a tenth of its cost on ~60 scalars a run
    scene = {name: (value if math.isfinite(value) else str(value)) for name, value in study.scene.inputs().items()}
    created = _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
    return {
        "title": f"impactlab study {study.name}",
        "study_name": study.name,
        "study_description": study.description,
        "study_file": study.file or "",
        "study_source": study.source,
        "base_scene_si": json.dumps(scene, sort_keys=True),
        "models": json.dumps(models),
        "head_cor": study_head_cor(study),
        "plan": plan.describe(),
        "plots": json.dumps([plot.as_dict() for plot in study.plots]),
        **versions(),
        "git_commit": git_commit(),
        "created": created,
        "Conventions": CF_CONVENTIONS,  # CF metadata (checked by the IOOS compliance checker in the tests)
        "history": f"{created} impactlab {__version__}: impactlab run {study.file or study.name}",
        "frame_conventions": "impactlab vocabulary (docs/conventions.md): face frame x along incoming slip, "
                             "z away from face; backspin positive",
    }
