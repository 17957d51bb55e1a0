"""Assemble per-model results (dimension ``case``) into one study dataset (sweep dimensions and ``model``)."""

from __future__ import annotations

import datetime as _dt
import json
import platform

import numpy as np
import xarray as xr

from ._version import __version__
from .diagnostics import flag_attributes
from .vocabulary import CASE_DIM, INPUTS, MODEL_DIM, OUTPUTS, TIME_DIM, is_history


def _unfold_cases(dataset: xr.Dataset, study) -> xr.Dataset:
    """Replace the flat ``case`` dimension by the sweep dimensions."""
    dataset = dataset.drop_attrs(deep=False)
    if not study.sweep:
        return dataset.isel({CASE_DIM: 0}, drop=True)
    index = [axis.dim for axis in study.sweep]
    unfolded = {}
    for name, variable in dataset.data_vars.items():
        extra = [dim for dim in variable.dims if dim != CASE_DIM]
        values = variable.values.reshape(study.shape + tuple(variable.sizes[dim] for dim in extra))
        unfolded[name] = (index + extra, values, variable.attrs)
    return xr.Dataset(unfolded, coords={name: coord for name, coord in dataset.coords.items()})


def assemble(study, plan, results: list[xr.Dataset]) -> xr.Dataset:
    """One dataset for the whole study, with sweep coordinates, the model coordinate and provenance."""
    per_model = [_unfold_cases(result, study) for result in results]
    times = [ds[TIME_DIM] for ds in per_model if TIME_DIM in ds.coords]
    if times:
        reference = times[0]
        for index, ds in enumerate(per_model):
            for name in ds.data_vars:
                if is_history(name) and TIME_DIM not in ds[name].dims:
                    # a model without histories: NaN over the time axis of those that have them
                    ds = ds.assign({name: ds[name].expand_dims({TIME_DIM: reference.values}, axis=-1).copy()})
            per_model[index] = ds
    missing = {name: [] for name in study.all_outputs}
    for entry, result in zip(study.models, results):
        for name in study.all_outputs:
            reason = result[name].attrs.get("missing_reason")
            if reason:
                missing[name].append(f"{entry.id}: {reason}")
    for ds in per_model:
        for name in ds.data_vars:
            ds[name].attrs = {}
    combined = xr.concat(per_model, dim=MODEL_DIM, join="outer", coords="minimal", compat="override",
                         combine_attrs="drop")
    combined = combined.assign_coords({MODEL_DIM: [entry.id for entry in study.models]})
    combined[MODEL_DIM].attrs = {"long_name": "model",
                                 "model_names": json.dumps([entry.name for entry in study.models])}
    for axis in study.sweep:
        if axis.grouped:
            labels = list(axis.labels) if axis.labels else list(range(axis.size))
            combined = combined.assign_coords({axis.dim: labels})
            combined[axis.dim].attrs = {"long_name": f"{axis.dim} (sets {', '.join(f.path for f in axis.fields)})"}
        for field in axis.fields:
            spec = INPUTS[field.input]
            # 12 significant digits: 30 deg stays 30.0 after its round trip through radians
            values = [float(f"{value * spec.display_factor:.12g}") for value in field.values]
            combined = combined.assign_coords({field.coord: (axis.dim, values)})
            combined[field.coord].attrs = {"units": spec.display_unit or spec.unit, "long_name": spec.description,
                                           "study_path": field.path}
    if TIME_DIM in combined.coords:
        combined[TIME_DIM].attrs = {"units": "s", "long_name": "time since first contact"}
    order = [MODEL_DIM] + [axis.dim for axis in study.sweep]
    combined = combined.transpose(*order, ...)
    for name in study.all_outputs:
        spec = OUTPUTS[name]
        attrs = {"units": spec.units, "long_name": spec.long_name}
        if missing[name]:
            attrs["missing"] = "; ".join(missing[name])
        if name == "validity":
            attrs.update(flag_attributes())
            combined[name] = _integer_flags(combined[name])
        combined[name].attrs = attrs
    combined = combined[list(study.all_outputs)]
    combined.attrs = provenance(study, plan)
    return combined


#: in the file, a case a model did not compute has this validity (CF _FillValue)
VALIDITY_FILL = -1


def _integer_flags(variable: xr.DataArray) -> xr.DataArray:
    """Validity bits as the integers CF flag variables are (models compute them as floats, NaN where absent)."""
    values = variable.values
    if not np.isnan(values).any():
        return variable.copy(data=values.astype(np.int16))
    variable = variable.copy()
    variable.encoding.update(dtype="int16", _FillValue=VALIDITY_FILL)  # stored as int16; NaN read back
    return variable


def versions() -> dict[str, str]:
    """Versions of everything that shapes a result: the numerics (numpy, scipy, numba), units (pint), storage."""
    from importlib import metadata

    found = {"impactlab_version": __version__, "python_version": platform.python_version()}
    for package in ("numpy", "scipy", "numba", "xarray", "pint", "h5py", "h5netcdf"):
        try:
            found[f"{package}_version"] = metadata.version(package)
        except metadata.PackageNotFoundError:
            found[f"{package}_version"] = "not installed"
    return found


def git_commit() -> str:
    """The commit of the checkout impactlab runs from ('' if installed from a package), '-dirty' if edited."""
    import subprocess
    from pathlib import Path

    here = Path(__file__).resolve().parent
    try:
        commit = subprocess.run(["git", "-C", str(here), "rev-parse", "HEAD"], capture_output=True, text=True,
                                timeout=5, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(here), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=5, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return ""
    return f"{commit}-dirty" if dirty else commit


def provenance(study, plan) -> dict[str, str | int]:
    """What made this result: the study, its models with resolved options, versions, the plan."""
    models = [{"id": entry.id, "name": entry.name, "label": entry.model.label, "options": entry.model.options_dict(),
               "references": list(entry.model.references)} for entry in study.models]
    scene = {name: (value if np.isfinite(value) else str(value)) for name, value in study.scene.inputs().items()}
    return {
        "title": f"impactlab study {study.name}",
        "study_name": study.name,
        "study_description": study.description,
        "study_file": study.file or "",
        "study_source": study.source,
        "base_scene_si": json.dumps(scene, sort_keys=True),
        "models": json.dumps(models),
        "plan": plan.describe(),
        "plots": json.dumps([plot.as_dict() for plot in study.plots]),
        **versions(),
        "git_commit": git_commit(),
        "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
        "conventions": "impactlab vocabulary (docs/conventions.md): face frame x along incoming slip, "
                       "z away from face; backspin positive",
    }
