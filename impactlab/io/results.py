"""Result files: xarray datasets in HDF5 (netCDF4 layout, h5netcdf engine), written atomically."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Final

import xarray as xr

from impactlab.errors import StudyError
from impactlab.foreign import MAX_NESTING, json_depth_exceeded, shown
from impactlab.io.safe_output import write_atomically
from impactlab.vocabulary import TIME_DIM
from impactlab._version import __version__

ENGINE: Final = "h5netcdf"
#: the name of the time axis of histories in a file: CF keeps a coordinate called "time" for calendar time
#: (units "s since EPOCH"), and this axis is the time elapsed since first contact (``time`` in memory)
FILE_TIME_DIM: Final = "time_since_contact"
#: the version of the CF metadata conventions result files follow (cfconventions.org; checked in the tests
#: by the IOOS compliance checker)
CF_CONVENTIONS: Final = "CF-1.8"
#: the layout of the result datasets (and files) this impactlab makes and reads, carried as the attribute
#: ``impactlab_format`` (files written before it was introduced carry ``impactlab_version`` only: format 1);
#: raised when a change would make an older impactlab misread a newer file, which then refuses it ("written by
#: a newer impactlab")
RESULT_FORMAT: Final = 1


def write_results(dataset: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``dataset`` to ``path`` atomically.

    The data go to a temporary file in the same folder, which is renamed over
    ``path`` only once complete: an error or interruption never leaves a
    half-written file and never damages an existing one.
    """
    # HDF5 is built in memory and written by Python: the HDF5 library, handed a full disk, fails in ways
    # (a RuntimeError, then a crash when the half-closed file is collected) that plain file writes do not
    dataset = _cf_metadata(dataset)
    payload = dataset.to_netcdf(engine=ENGINE, invalid_netcdf=False)
    return write_atomically(path, payload)


def _cf_metadata(dataset: xr.Dataset) -> xr.Dataset:
    """A shallow copy of ``dataset`` with what CF asks of a file: ``Conventions``, a ``history`` line, and
    coordinates without ``_FillValue`` (CF 2.5.1: a coordinate is never missing; xarray gives float ones NaN)."""
    import datetime as _dt

    dataset = dataset.copy()
    if TIME_DIM in dataset.dims and FILE_TIME_DIM not in dataset.variables:
        dataset = dataset.rename({TIME_DIM: FILE_TIME_DIM})
    for name in dataset.coords:
        dataset[name].encoding["_FillValue"] = None
    # a dataset made by impactlab carries both already (its provenance); others (sensitivity, convergence) get them
    if "history" not in dataset.attrs:
        now = _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds")
        dataset.attrs["history"] = f"{now} impactlab {__version__}: wrote {dataset.attrs.get('title', 'a result')}"
    dataset.attrs.setdefault("Conventions", CF_CONVENTIONS)
    return dataset


def open_results(path: str | os.PathLike) -> xr.Dataset:
    """Load a result file fully into memory (the file is closed on return)."""
    path = Path(path)
    if path.is_dir():
        raise StudyError(f"{path}: is a folder, not a result file; give the .h5 file inside it")
    if not path.is_file():
        raise StudyError(f"{path}: no such result file" if not path.exists() else
                         f"{path}: is not a regular file, not a result file")
    try:
        # phony_dims: an HDF5 file of another program (datasets without netCDF dimensions) is refused below by its
        # attributes, without h5netcdf's warning about the dimension names it would invent
        with xr.open_dataset(path, engine=ENGINE, phony_dims="access") as dataset:
            check_result(dataset, path)  # on the attributes, before the data are read (a 10 GB file of another
            loaded = dataset.load()      # program was loaded whole to be refused)
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise StudyError(f"{path}: not an impactlab result file ({type(exc).__name__}: {exc})") from None
    if FILE_TIME_DIM in loaded.dims and TIME_DIM not in loaded.variables:
        loaded = loaded.rename({FILE_TIME_DIM: TIME_DIM})
    return loaded


#: attributes held as JSON, and the Python type each decodes to
_JSON_ATTRIBUTES = {"models": list, "plots": list, "base_scene_si": dict, "sensitivity": dict}
#: attributes a sensitivity result must have (``impactlab show`` and ``plot`` read them)
_SENSITIVITY_ATTRIBUTES = ("sensitivity", "sampler", "analyser", "salib_version")


def check_result(dataset: xr.Dataset, path: str | os.PathLike = "<dataset>") -> None:
    """Refuse a dataset impactlab did not write, one from a newer format, or one whose attributes were altered.

    Parameters
    ----------
    dataset : xarray.Dataset
        A dataset read from ``path``.
    path : str or path-like
        The file, for messages.

    Raises
    ------
    StudyError
        "not an impactlab result" (no ``impactlab_version`` attribute: an HDF5 or netCDF file of another
        program), "written by a newer impactlab" (an ``impactlab_format`` above :data:`RESULT_FORMAT`), or the
        attribute whose shape is not what impactlab writes (a ``models`` attribute that is not a JSON list, a
        sensitivity result without its ``sampler``...).
    """
    attributes = dataset.attrs
    if "impactlab_version" not in attributes:
        raise StudyError(f"{path}: not an impactlab result (an HDF5/netCDF file without the impactlab_version "
                         "attribute every impactlab result carries); give a file written by impactlab run")
    written = attributes.get("impactlab_format", 1)
    try:
        written = int(written)
    except (TypeError, ValueError):
        raise StudyError(f"{path}: not an impactlab result (impactlab_format {written!r} is not a format "
                         "number)") from None
    if written > RESULT_FORMAT:
        raise StudyError(f"{path}: written by a newer impactlab ({attributes['impactlab_version']}, result format "
                         f"{written}); this is impactlab {__version__}, which reads formats up to {RESULT_FORMAT}: "
                         "upgrade impactlab to read it")
    for name, kind in _JSON_ATTRIBUTES.items():
        if name not in attributes:
            continue
        try:
            # an altered attribute nested thousands deep made json recurse to a RecursionError: bounded first
            value = (None if isinstance(attributes[name], str) and json_depth_exceeded(attributes[name]) else
                     json.loads(attributes[name]) if attributes[name] != "" else kind())
        except (TypeError, ValueError):
            value = None
        if not isinstance(value, kind) or (name == "models" and not all(
                isinstance(entry, dict) and isinstance(entry.get("id"), str) and isinstance(entry.get("name"), str)
                and isinstance(entry.get("options", {}), dict) for entry in value)):
            shape = "JSON list of models, each with id, name and options" if name == "models" else \
                f"JSON {'list' if kind is list else 'mapping'}"
            raise StudyError(f"{shown(path)}: not an impactlab result as written: its {name!r} attribute is not the "
                             f"{shape} impactlab writes (got {str(attributes[name])[:60]!r}"
                             + (f", nesting more than {MAX_NESTING} levels deep" if isinstance(attributes[name], str)
                                and json_depth_exceeded(attributes[name]) else "") + "); the file was altered")
    if attributes.get("study_type") == "sensitivity":
        missing = [name for name in _SENSITIVITY_ATTRIBUTES if not isinstance(attributes.get(name), str)]
        if missing:
            raise StudyError(f"{path}: a sensitivity result without its {', '.join(missing)} attribute(s), which "
                             "impactlab writes in every sensitivity result; the file was altered")
