"""Result files: xarray datasets in HDF5 (netCDF4 layout, h5netcdf engine), written atomically."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import xarray as xr

from .errors import StudyError

ENGINE = "h5netcdf"


def write_atomically(path: Path, payload: bytes) -> None:
    """Write ``payload`` to a temporary file beside ``path``, then rename it over ``path``."""
    temporary = path.with_name(f".{path.name}.tmp")
    temporary.write_bytes(payload)
    os.replace(temporary, path)


def write_results(dataset: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write ``dataset`` to ``path`` atomically.

    The data go to a temporary file in the same folder, which is renamed over
    ``path`` only once complete: an error or interruption never leaves a
    half-written file and never damages an existing one.
    """
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise StudyError(f"{path}: cannot write results: folder {folder} does not exist")
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".part", dir=folder)
    os.close(handle)
    try:
        dataset.to_netcdf(temporary, engine=ENGINE, invalid_netcdf=False)
        os.replace(temporary, path)
    except BaseException:
        Path(temporary).unlink(missing_ok=True)
        raise
    return path


def open_results(path: str | os.PathLike) -> xr.Dataset:
    """Load a result file fully into memory (the file is closed on return)."""
    path = Path(path)
    if not path.is_file():
        raise StudyError(f"{path}: no such result file")
    try:
        with xr.open_dataset(path, engine=ENGINE) as dataset:
            return dataset.load()
    except (OSError, ValueError) as exc:
        raise StudyError(f"{path}: not an impactlab result file ({exc})") from None
