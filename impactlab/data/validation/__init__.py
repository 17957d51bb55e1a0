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

import attrs
import numpy as np

from impactlab.data.documents import MeasuredDataBlock, structure_document
from impactlab.errors import FieldError
from impactlab.run.runner import case_inputs
from impactlab.study.core import Study, load_study
from impactlab.vocabulary import SCALAR_OUTPUTS
from impactlab.study.yaml_lines import line_of, load_yaml, parse_path


@attrs.frozen
class MeasuredData:
    """A citable measurement and how impactlab reproduces it.

    Attributes
    ----------
    name : str
    source : str
        The citation.
    quantity : str
        Output name in impactlab's vocabulary (its units).
    labels : tuple of str
        One per point, matching the study's sweep labels.
    values : tuple of float
        Measured values, in the output's units.
    sigma : tuple of float or None
        Stated uncertainty of each point (None: the source gives none).
    study : str
        File name of the study (in impactlab/validation) that reproduces the points.
    dimension : str
        The study's sweep dimension along which the points lie.
    budgets : dict
        Model id -> largest allowed RMS error over the points.
    note : str
    """

    name: str
    source: str
    quantity: str
    labels: tuple[str, ...]
    values: tuple[float, ...]
    sigma: tuple[float, ...] | None
    study: str
    dimension: str
    budgets: dict = attrs.field(factory=dict)
    note: str = ""
    folder: str | None = None  # where ``study`` lives; None: shipped with impactlab

    def load_study(self) -> Study:
        """The study that computes this dataset's quantity under its conditions."""
        if self.folder is not None:
            return load_study(Path(self.folder) / self.study)
        text = resources.files(__package__).joinpath(self.study).read_text()
        return load_study(text, file=f"impactlab/data/validation/{self.study}")

    @property
    def measured(self) -> np.ndarray:
        """The measured values as an array, in the dataset's units."""
        return np.asarray(self.values, dtype=float)


TABLE1 = ("E. Henrikson, P. Wood, C. Broadie, T. Nuttall, The role of friction and tangential compliance on the "
          "resultant launch angle of a golf ball, Proceedings 49 (2020) 27, Table 1")

DATASETS: dict[str, MeasuredData] = {
    "wood2018": MeasuredData(
        name="wood2018",
        source=f"{TABLE1}; measured by P. Wood et al. (2018): 157 golfers, Vicon club kinematics and a GC2 launch "
               "monitor (731 driver, 745 7-iron, 99 wedge shots); mean +- SD",
        quantity="vertical_launch_ratio", labels=("driver", "7-iron", "pitching wedge"),
        values=(0.83, 0.81, 0.72), sigma=(0.08, 0.05, 0.06),
        study="table1_clubs.yaml", dimension="club",
        budgets={"maw": 0.035, "hertz_mindlin": 0.035, "dem_linear": 0.12, "rigid_coulomb": 0.06,
                 "restitution": 0.05},
        note="the paper's text says the wedge shots were hit with a 58 deg wedge; its table says pitching wedge",
    ),
    "trackman": MeasuredData(
        name="trackman",
        source=f"{TABLE1}; TrackMan values published by D. Dewhurst, The Golf Club: Engineering and Physics "
               "(2018); no uncertainty stated",
        quantity="vertical_launch_ratio", labels=("driver", "7-iron", "pitching wedge"),
        values=(0.87, 0.75, 0.70), sigma=None,
        study="table1_clubs.yaml", dimension="club",
        budgets={"maw": 0.045, "hertz_mindlin": 0.06, "dem_linear": 0.115, "rigid_coulomb": 0.085,
                 "restitution": 0.075},
    ),
}


def get_dataset(name: str) -> MeasuredData:
    """A shipped dataset by name, or a measured-data file (.yaml) of the user's."""
    if str(name).endswith((".yaml", ".yml")) or os.path.sep in str(name):
        return load_measured(name)
    if name not in DATASETS:
        raise FieldError("dataset", "a validation dataset or a measured-data file (.yaml)", name,
                         choices=sorted(DATASETS))
    return DATASETS[name]


def load_measured(path) -> MeasuredData:
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
    document, lines = load_yaml(path.read_text(), file)

    def fail(where, expected, given, choices=None):
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
    study = data.load_study()
    axes = {axis.dim: axis for axis in study.sweep}
    if data.dimension not in axes or axes[data.dimension].labels is None:
        fail("dimension", "a labelled sweep of the study", data.dimension,
             [dim for dim, axis in axes.items() if axis.labels is not None])
    missing = [label for label in data.labels if label not in axes[data.dimension].labels]
    if missing:
        fail("points", f"labels of the study's sweep {data.dimension!r}", ", ".join(missing),
             list(axes[data.dimension].labels))
    if len(study.sweep) != 1:
        fail("study", "a study with one sweep (the points' own)", [axis.dim for axis in study.sweep])
    return data


def point_order(data: MeasuredData, study: Study) -> list[int]:
    """Case index of each measured point in the study's (one-axis) sweep."""
    labels = next(axis for axis in study.sweep if axis.dim == data.dimension).labels
    return [list(labels).index(label) for label in data.labels]


def predictions(data: MeasuredData, models=None) -> dict[str, np.ndarray]:
    """Each model's prediction at the measured points: model id -> values (the quantity's units)."""
    study = data.load_study()
    inputs = case_inputs(study)
    order = point_order(data, study)
    out = {}
    for entry in study.models:
        if models is not None and entry.id not in models:
            continue
        out[entry.id] = entry.model.compute(inputs, [data.quantity])[data.quantity].values[order]
    return out


def errors(data: MeasuredData, models=None) -> dict[str, dict]:
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
