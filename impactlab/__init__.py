"""impactlab: models of a ball leaving a striking face, side by side.

The names a study author, a plugin author or a user of launch-monitor data needs, importable from ``impactlab``.
The domain objects, the model contract and the errors are imported with the package; the study, run, result
and data functions are imported when first used (:func:`load_study` and friends below, and the shot-table and
calibration names through the module's ``__getattr__``), so ``import impactlab`` stays as quick as its core.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

from impactlab._version import __version__
from impactlab.errors import (FieldError, ImpactLabError, ModelContractError, ModelInputError, ModelNotFoundError,
                              StudyError)
from impactlab.scene.materials import BALL_PRESETS, FACE_PRESETS, MATERIAL_PRESETS, Ball, Face, Material
from impactlab.model.base import ImpactModel
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.core import Contact, Delivery, Impact, Scene
from impactlab.scene.flight import fly as _fly

if TYPE_CHECKING:  # what the lazy names below are, for type checkers and editors (nothing is imported at run time)
    import xarray as xr

    from impactlab.data.fit.calibration import Calibration, calibrate, cross_validate
    from impactlab.data.fit.fitting import FitResult, fit
    from impactlab.data.sessions.shots import ShotTable, predict, read_shots, table_inputs
    from impactlab.data.validation import get_dataset
    from impactlab.study.core import Study

__all__ = [
    "__version__", "Ball", "Face", "Material", "ClubHead", "Strike", "Delivery", "Contact", "Impact", "Scene",
    "ImpactModel", "BALL_PRESETS", "FACE_PRESETS", "MATERIAL_PRESETS",
    "ImpactLabError", "FieldError", "StudyError", "ModelInputError", "ModelNotFoundError", "ModelContractError",
    "load_study", "run_study", "open_results", "get_model", "available_models", "fly",
    # launch-monitor shot tables, calibration to them, and fits to measured datasets (imported on first use)
    "read_shots", "ShotTable", "table_inputs", "predict", "calibrate", "cross_validate", "Calibration",
    "get_dataset", "fit", "FitResult",
]

#: names imported from their module on first use: the calibration and the fits import scipy.optimize
_LAZY = {
    "read_shots": "impactlab.data.sessions.shots", "ShotTable": "impactlab.data.sessions.shots",
    "table_inputs": "impactlab.data.sessions.shots", "predict": "impactlab.data.sessions.shots",
    "calibrate": "impactlab.data.fit.calibration", "cross_validate": "impactlab.data.fit.calibration",
    "Calibration": "impactlab.data.fit.calibration",
    "get_dataset": "impactlab.data.validation",
    "fit": "impactlab.data.fit.fitting", "FitResult": "impactlab.data.fit.fitting",
}


def __getattr__(name: str) -> Any:
    """A lazy name of :data:`__all__`, imported from its module on first use (then kept in the package)."""
    if name not in _LAZY:
        raise AttributeError(f"module 'impactlab' has no attribute {name!r}")
    value = getattr(importlib.import_module(_LAZY[name]), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


def fly(ball_speed: Any, launch_angle: Any, spin_rate: Any, spin_axis: Any = 0.0, launch_direction: Any = 0.0,
        conditions: Mapping[str, Any] | None = None, **options: Any) -> xr.Dataset:
    """Fly golf shots from their launch to landing: carry, offline, apex, landing angle, flight time (a Dataset).

    Numbers are SI (m/s, rad, rad/s), strings carry units (``"167 mph"``, ``"10.9 deg"``, ``"2686 rpm"``), pint
    quantities are converted; scalars or arrays (broadcast). ``conditions``: None (15 degC, 101 325 Pa, 50 %
    humidity, still air) or a mapping of ``temperature``, ``pressure``, ``relative_humidity``, ``altitude``,
    ``headwind``, ``crosswind``, each one value for every shot or an array of one per shot (broadcast with the
    launch). See :func:`impactlab.scene.flight.fly` for every option and docs/flight.md for the model and its
    validation.

    Examples
    --------
    >>> import impactlab
    >>> shot = impactlab.fly(ball_speed="167 mph", launch_angle="10.9 deg", spin_rate="2686 rpm")
    >>> round(float(shot.carry_distance), 1), shot.carry_distance.attrs["units"]
    (251.1, 'm')
    """
    return _fly(ball_speed, launch_angle, spin_rate, spin_axis, launch_direction, conditions, **options)


def load_study(source: str | os.PathLike[str] | Mapping[str, Any] | Study, *, file: str | None = None) -> Study:
    """Read and validate a study from a YAML path, YAML text or mapping (see :mod:`impactlab.study.core`)."""
    from impactlab.study.core import load_study as _load

    return _load(source, file=file)


def run_study(study: str | os.PathLike[str] | Mapping[str, Any] | Study, **options: Any) -> xr.Dataset:
    """Run a study (path, mapping or :class:`~impactlab.study.core.Study`) and return one xarray Dataset.

    Keyword options (executor, workers, scheduler, chunk_size, progress_folder, show_progress, progress)
    are those of :func:`impactlab.run.runner.run_study`.
    """
    from impactlab.run.runner import run_study as _run

    return _run(study, **options)


def open_results(path: str | os.PathLike[str]) -> xr.Dataset:
    """Open a result file written by ``impactlab run`` as an xarray Dataset (loaded into memory)."""
    from impactlab.io.results import open_results as _open

    return _open(path)


def get_model(name: str) -> type[ImpactModel]:
    """The registered model class called ``name``."""
    from impactlab.model.registry import get_model as _get

    return _get(name)


def available_models() -> dict[str, type[ImpactModel]]:
    """Registered model classes by name."""
    from impactlab.model.registry import available

    return available()


# the inputs and outputs plugins declare (entry points impactlab.inputs, impactlab.outputs), once impactlab is whole:
# a plugin's module may import impactlab itself
from impactlab.model.extensions import load_plugins as _load_plugins  # noqa: E402

_load_plugins()
