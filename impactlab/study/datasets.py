"""The measured datasets impactlab ships: plain data (citation, points, budgets), no code that runs a study.

Studies name these datasets (a figure's ``measured:`` list), so the registry lives in the study layer;
:mod:`impactlab.data.validation` loads the study that reproduces each one and compares the models with it.
"""

from __future__ import annotations

import attrs
import numpy as np


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
        File name of the study that reproduces the points (in ``folder``; shipped ones in
        impactlab/data/validation, read by :func:`impactlab.data.validation.load_dataset_study`).
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
        source=f"{TABLE1}; TrackMan values as published by P. Dewhurst, The Science of the Perfect Swing, 1st ed., "
               "Oxford University Press, New York (2015) (the paper's reference 4); no uncertainty stated",
        quantity="vertical_launch_ratio", labels=("driver", "7-iron", "pitching wedge"),
        values=(0.87, 0.75, 0.70), sigma=None,
        study="table1_clubs.yaml", dimension="club",
        budgets={"maw": 0.045, "hertz_mindlin": 0.06, "dem_linear": 0.115, "rigid_coulomb": 0.085,
                 "restitution": 0.075},
    ),
}
