"""Result files: xarray datasets in HDF5 (netCDF4 layout, h5netcdf engine), written atomically."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Final

import xarray as xr

from impactlab.errors import StudyError
from impactlab.io.safe_output import write_atomically

ENGINE: Final = "h5netcdf"


def write_results(dataset: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``dataset`` to ``path`` atomically.

    The data go to a temporary file in the same folder, which is renamed over
    ``path`` only once complete: an error or interruption never leaves a
    half-written file and never damages an existing one.
    """
    # HDF5 is built in memory and written by Python: the HDF5 library, handed a full disk, fails in ways
    # (a RuntimeError, then a crash when the half-closed file is collected) that plain file writes do not
    payload = dataset.to_netcdf(engine=ENGINE, invalid_netcdf=False)
    return write_atomically(path, payload)


def open_results(path: str | os.PathLike) -> xr.Dataset:
    """Load a result file fully into memory (the file is closed on return)."""
    path = Path(path)
    if path.is_dir():
        raise StudyError(f"{path}: is a folder, not a result file; give the .h5 file inside it")
    if not path.is_file():
        raise StudyError(f"{path}: no such result file" if not path.exists() else
                         f"{path}: is not a regular file, not a result file")
    try:
        with xr.open_dataset(path, engine=ENGINE) as dataset:
            return dataset.load()
    except (OSError, ValueError, KeyError, TypeError) as exc:
        raise StudyError(f"{path}: not an impactlab result file ({type(exc).__name__}: {exc})") from None
