"""impactlab: models of a ball leaving a striking face, side by side."""

from impactlab._version import __version__
from impactlab.errors import FieldError, ImpactLabError, ModelInputError, ModelNotFoundError, StudyError
from impactlab.scene.materials import BALL_PRESETS, FACE_PRESETS, MATERIAL_PRESETS, Ball, Face, Material
from impactlab.model.base import ImpactModel
from impactlab.scene.core import Contact, Impact, Scene

__all__ = [
    "__version__", "Ball", "Face", "Material", "Contact", "Impact", "Scene", "ImpactModel",
    "BALL_PRESETS", "FACE_PRESETS", "MATERIAL_PRESETS",
    "ImpactLabError", "FieldError", "StudyError", "ModelInputError", "ModelNotFoundError",
    "load_study", "run_study", "open_results", "get_model", "available_models", "fly",
]


def fly(ball_speed, launch_angle, spin_rate, spin_axis=0.0, launch_direction=0.0, conditions=None, **options):
    """Fly golf shots from their launch to landing: carry, offline, apex, landing angle, flight time (a Dataset).

    Numbers are SI (m/s, rad, rad/s), strings carry units (``"167 mph"``, ``"10.9 deg"``, ``"2686 rpm"``), pint
    quantities are converted; scalars or arrays (broadcast). ``conditions``: None (15 degC, 101 325 Pa, 50 %
    humidity, still air) or a mapping of ``temperature``, ``pressure``, ``relative_humidity``, ``altitude``,
    ``headwind``, ``crosswind``. See :func:`impactlab.scene.flight.fly` for every option and docs/flight.md for
    the model and its validation.

    Examples
    --------
    >>> import impactlab
    >>> shot = impactlab.fly(ball_speed="167 mph", launch_angle="10.9 deg", spin_rate="2686 rpm")
    >>> round(float(shot.carry_distance), 1), shot.carry_distance.attrs["units"]
    (227.8, 'm')
    """
    from impactlab.scene.flight import fly as _fly

    return _fly(ball_speed, launch_angle, spin_rate, spin_axis, launch_direction, conditions, **options)


def load_study(source, *, file=None):
    """Read and validate a study from a YAML path, YAML text or mapping (see :mod:`impactlab.study.core`)."""
    from impactlab.study.core import load_study as _load

    return _load(source, file=file)


def run_study(study, **options):
    """Run a study (path, mapping or :class:`~impactlab.study.core.Study`) and return one xarray Dataset.

    Keyword options (executor, workers, scheduler, chunk_size, progress_folder, show_progress, progress)
    are those of :func:`impactlab.run.runner.run_study`.
    """
    from impactlab.run.runner import run_study as _run

    return _run(study, **options)


def open_results(path):
    """Open a result file written by ``impactlab run`` as an xarray Dataset (loaded into memory)."""
    from impactlab.io.results import open_results as _open

    return _open(path)


def get_model(name):
    """The registered model class called ``name``."""
    from impactlab.model.registry import get_model as _get

    return _get(name)


def available_models():
    """Registered model classes by name."""
    from impactlab.model.registry import available

    return available()
