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
    "load_study", "run_study", "open_results", "get_model", "available_models",
]


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
