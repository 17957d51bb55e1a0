"""Measured data the project can cite, the studies that reproduce them, and model-by-model error budgets.

Each :class:`MeasuredData` names its source, the quantity measured, the points
(with their stated uncertainty where the source gives one), the study that
reproduces the measurement, and an error budget per model: the largest RMS
error (in the quantity's units) that model is allowed. ``impactlab validate``
runs them all; tests/test_validation.py asserts every model stays inside its
budget and that budgets only ever tighten.

Only tabulated data are included here. Curves published as figures enter only
as digitised by a source that can be cited: the Chung & Ooi (2011) benchmarks
and Kharaz, Gorham & Salman's (2001) experiment, in :mod:`.benchmarks`
(docs/benchmarks.md). The paper's Fig. 3 air-cannon angles are still wanted.
"""

from __future__ import annotations

import math

import os
from importlib import resources
from pathlib import Path
from collections.abc import Iterable
from typing import Any, NoReturn

import numpy as np

from impactlab.data.documents import MeasuredDataBlock, structure_document
from impactlab.errors import FieldError
from impactlab.study.arrays import case_inputs
from impactlab.study.core import Study, load_study
from impactlab.study.datasets import DATASETS, TABLE1, MeasuredData
from impactlab.vocabulary import SCALAR_OUTPUTS
from impactlab.study.yaml_lines import line_of, load_yaml, parse_path, read_text_file


def load_dataset_study(data: MeasuredData) -> Study:
    """The study that computes a dataset's quantity under its conditions.

    Parameters
    ----------
    data : MeasuredData
        A shipped dataset (its study read from this package) or one read by :func:`load_measured` (its study
        read from ``data.folder``).

    Returns
    -------
    Study
    """
    if data.folder is not None:
        return load_study(Path(data.folder) / data.study)
    text = resources.files(__package__).joinpath(data.study).read_text()
    return load_study(text, file=f"impactlab/data/validation/{data.study}")


def get_dataset(name: str) -> MeasuredData:
    """A shipped dataset by name, or a measured-data file (.yaml) of the user's."""
    if str(name).endswith((".yaml", ".yml")) or os.path.sep in str(name):
        return load_measured(name)
    if name not in DATASETS:
        raise FieldError("dataset", "a validation dataset or a measured-data file (.yaml)", name,
                         choices=sorted(DATASETS))
    return DATASETS[name]


def load_measured(path: str | os.PathLike[str]) -> MeasuredData:
    """Read measured data from YAML: your own launch data to validate against or fit to.

    ::

        name: my-session
        source: launch monitor session, 2026-10-01, 40 shots per club (mean +- SD)
        quantity: vertical_launch_ratio          # an output of impactlab
        study: my_clubs.yaml                     # the study that reproduces it (relative to this file)
        dimension: club                          # its labelled sweep along which the points lie
        points:
          - {label: driver, value: 0.84, sigma: 0.03}
          - {label: 7-iron, value: 0.79, sigma: 0.03}
        budgets: {maw: 0.05}                     # optional: largest RMS error allowed per model id

    ``sigma`` is optional, but given for every point or for none.
    """
    path = Path(path)
    if not path.is_file():
        raise FieldError("dataset", "a measured-data file that exists", str(path))
    file = str(path)
    document, lines = load_yaml(read_text_file(path, "measured-data file"), file)  # UTF-8, said otherwise

    def fail(where: str, expected: str, given: Any, choices: Any = None) -> NoReturn:
        raise FieldError(where, expected, given, choices=choices, file=file, line=line_of(lines, parse_path(where)))

    # the shape of every key (unknown keys refused, required ones present, numbers where numbers belong) at its
    # file:line, structured like a study's blocks
    block = structure_document(document, MeasuredDataBlock, file, lines)
    quantity = block.quantity
    scalars = list(SCALAR_OUTPUTS)
    if quantity not in scalars:
        fail("quantity", "a scalar output of impactlab", quantity, scalars)
    if not block.points:
        fail("points", "a list of {label, value, sigma}", [])
    labels = [point.label for point in block.points]
    values = [point.value for point in block.points]
    sigmas = [point.sigma for point in block.points]
    given = [sigma is not None for sigma in sigmas]
    if any(given) and not all(given):
        fail("points", "a sigma for every point or for none", f"{sum(given)} of {len(given)}")
    budgets = block.budgets or {}
    data = MeasuredData(
        name=block.name if block.name is not None else path.stem, source=block.source, quantity=quantity,
        labels=tuple(labels), values=tuple(values), sigma=tuple(float(s) for s in sigmas) if all(given) else None,
        study=block.study, dimension=block.dimension, budgets=dict(budgets),
        note=block.note or "", folder=str(path.parent))
    study = load_dataset_study(data)
    axes = {axis.dim: axis for axis in study.sweep}
    swept_labels = axes[data.dimension].labels if data.dimension in axes else None
    if swept_labels is None:
        fail("dimension", "a labelled sweep of the study", data.dimension,
             [dim for dim, axis in axes.items() if axis.labels is not None])
    missing = [label for label in data.labels if label not in swept_labels]
    if missing:
        fail("points", f"labels of the study's sweep {data.dimension!r}", ", ".join(missing), list(swept_labels))
    if len(study.sweep) != 1:
        fail("study", "a study with one sweep (the points' own)", [axis.dim for axis in study.sweep])
    return data


def point_order(data: MeasuredData, study: Study) -> list[int]:
    """Case index of each measured point in the study's (one-axis) sweep."""
    labels = next(axis for axis in study.sweep if axis.dim == data.dimension).labels
    assert labels is not None, "a measured dataset's sweep is labelled (load_measured checks it)"
    return [list(labels).index(label) for label in data.labels]


def predictions(data: MeasuredData, models: Iterable[str] | None = None) -> dict[str, np.ndarray]:
    """Each model's prediction at the measured points: model id -> values (the quantity's units)."""
    study = load_dataset_study(data)
    inputs = case_inputs(study)
    order = point_order(data, study)
    out = {}
    for entry in study.models:
        if models is not None and entry.id not in models:
            continue
        out[entry.id] = entry.model.compute(inputs, [data.quantity])[data.quantity].values[order]
    return out


def errors(data: MeasuredData, models: Iterable[str] | None = None) -> dict[str, dict]:
    """Model id -> {rms, max, residuals, predicted, unused} of prediction minus measurement.

    ``rms`` and ``max`` are over the points the model could predict; ``unused`` names the others (a non-finite
    prediction), which are never folded silently into a NaN or left out unsaid.
    """
    result = {}
    for model, predicted in predictions(data, models).items():
        residuals = predicted - data.measured
        finite = np.isfinite(residuals)
        used = residuals[finite]
        result[model] = {"rms": float(np.sqrt(np.mean(used**2))) if used.size else math.nan,
                         "max": float(np.max(np.abs(used))) if used.size else math.nan,
                         "residuals": residuals, "predicted": predicted,
                         "unused": tuple(str(label) for label, ok in zip(data.labels, finite) if not ok)}
    return result


__all__ = ["DATASETS", "TABLE1", "MeasuredData", "errors", "get_dataset", "load_dataset_study", "load_measured",
           "point_order", "predictions"]
