"""Measured data the project can cite, the studies that reproduce them, and model-by-model error budgets.

Each :class:`MeasuredData` names its source, the quantity measured, the points
(with their stated uncertainty where the source gives one), the study that
reproduces the measurement, and an error budget per model: the largest RMS
error (in the quantity's units) that model is allowed. ``impactlab validate``
runs them all; tests/test_validation.py asserts every model stays inside its
budget and that budgets only ever tighten.

Only tabulated data are included. Data published only as figures (the
paper's Fig. 3 air-cannon angles; oblique impacts of spheres such as Kharaz,
Gorham & Salman 2001) are not digitised here and are listed in
docs/validation.md as wanted.
"""

from __future__ import annotations

from importlib import resources

import attrs
import numpy as np

from ..errors import FieldError
from ..runner import case_inputs
from ..study import Study, load_study


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

    def load_study(self) -> Study:
        text = resources.files(__package__).joinpath(self.study).read_text()
        return load_study(text, file=f"impactlab/validation/{self.study}")

    @property
    def measured(self) -> np.ndarray:
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
    if name not in DATASETS:
        raise FieldError("dataset", "a validation dataset", name, choices=sorted(DATASETS))
    return DATASETS[name]


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
    """Model id -> {rms, max, residuals} of prediction minus measurement."""
    result = {}
    for model, predicted in predictions(data, models).items():
        residuals = predicted - data.measured
        result[model] = {"rms": float(np.sqrt(np.mean(residuals**2))), "max": float(np.max(np.abs(residuals))),
                         "residuals": residuals, "predicted": predicted}
    return result
