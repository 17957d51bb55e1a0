"""The shot table: its fields, their units and aliases, and :class:`ShotTable` (rows of measured shots in SI).

The definitions the readers share: :mod:`impactlab.data.sessions.shots` (impactlab's YAML and CSV tables, predictions
and their errors) and :mod:`impactlab.data.sessions.reader` (launch-monitor exports as exported) read their files into
these fields; :meth:`impactlab.data.sessions.reader.Session.shot_table` is the one place a :class:`ShotTable` is
assembled from them (a YAML table's rows become a session first).
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import Any

import attrs
import numpy as np

from impactlab.physics.delivery import loft_for_spin_loft, spin_loft
from impactlab.scene.core import SPIN_LOFT_TOLERANCE

#: field -> physical dimension (a value always comes with its unit: a bare mph/m/s mix-up is the classic misreading)
DELIVERY_FIELDS = {
    "club_speed": "speed", "attack_angle": "angle", "path": "angle", "face_angle": "angle", "dynamic_loft": "angle",
    "face_to_path": "angle", "spin_loft": "angle", "strike_toe": "length", "strike_high": "length",
}
MEASURED_FIELDS = {
    "ball_speed": "speed", "vertical_launch_angle": "angle", "horizontal_launch_angle": "angle",
    "spin_rate": "angular_speed", "spin_axis": "angle",
}
TEXT_FIELDS = ("label", "club", "handedness", "source")
#: usual launch-monitor column names -> field (lower case, single spaces)
ALIASES = {
    "club speed": "club_speed", "clubspeed": "club_speed", "club head speed": "club_speed",
    "attack angle": "attack_angle", "aoa": "attack_angle", "angle of attack": "attack_angle",
    "club path": "path", "face angle": "face_angle", "dynamic loft": "dynamic_loft", "dyn. loft": "dynamic_loft",
    "dyn loft": "dynamic_loft", "impact offset": "strike_toe", "impact height": "strike_high",
    "spin loft": "spin_loft", "face to path": "face_to_path",
    "ball speed": "ball_speed", "launch angle": "vertical_launch_angle", "launch direction": "horizontal_launch_angle",
    "spin rate": "spin_rate", "total spin": "spin_rate", "spin axis": "spin_axis", "shot": "label", "name": "label",
}
#: the errors of a prediction against a shot table, in the data's own units
ERROR_KEYS = ("ball_speed [%]", "launch angle [deg]", "launch direction [deg]", "spin [%]", "spin axis [deg]")
#: default one-sigma uncertainty of a shot (SI), used where a table gives none: this project's assumption of how well
#: one launch-monitor shot or average represents its delivery, not a manufacturer's figure
DEFAULT_SIGMA = {"ball_speed": 0.5, "vertical_launch_angle": math.radians(0.3),
                 "horizontal_launch_angle": math.radians(0.3), "spin_rate": 200.0 * 2 * math.pi / 60,
                 "spin_axis": math.radians(1.0)}


@attrs.frozen
class ShotTable:
    """Rows of measured shots, SI values (NaN: not measured), with the table's provenance.

    Attributes
    ----------
    name, source : str
        What the table is, and where each number comes from (measurement or model output).
    labels, clubs, handedness : tuple of str
    delivery : dict of ndarray
        ``DELIVERY_FIELDS`` per row [SI].
    measured, sigma : dict of ndarray
        ``MEASURED_FIELDS`` per row and their one-sigma uncertainties [SI].
    ball : dict
        The ball block the table names (a study ``ball:`` mapping), or empty.
    loft_at : str
        Where the table's dynamic loft and face angle were measured: ``contact`` (default; what a launch
        monitor reports: TrackMan defines dynamic loft as the loft "at the center-point of contact between the
        club and ball") or ``centre`` (the face centre). It is the rows' ``Delivery.loft_at``: on a bulged and
        rolled face a strike off the centre meets a face turned by its bulge and roll, and a ``contact`` row's
        head is turned so that the face at the strike point has the measured loft and face angle
        (:func:`impactlab.physics.delivery.centre_face`).
    """

    name: str
    source: str
    labels: tuple[str, ...]
    clubs: tuple[str, ...]
    handedness: tuple[str, ...]
    delivery: dict = attrs.field(eq=False)
    measured: dict = attrs.field(eq=False)
    sigma: dict = attrs.field(eq=False)
    ball: dict = attrs.field(factory=dict, eq=False)
    loft_at: str = attrs.field(default="contact", validator=attrs.validators.in_(("contact", "centre")))
    #: model id -> {error key of :data:`ERROR_KEYS` -> largest allowed RMS}: regression budgets, not the data's
    #: uncertainty (tests/test_shots.py holds them and checks they only tighten)
    budgets: dict = attrs.field(factory=dict, eq=False)
    #: (file line, reason) of every row of the file the impact models could not use (a session's other rows are)
    skipped: tuple = attrs.field(default=(), eq=False)
    #: (reason, file lines) of values beyond measured shots but within a golf shot, counted per column and reason
    #: (a session's rows); None: not counted (a table written by hand, whose scenes warn as a study's do)
    unusual: tuple | None = attrs.field(default=None, eq=False)
    #: where each row comes from (a row's ``source:``; empty: every row is the table's own ``name``): the unit of
    #: the per-source errors of ``impactlab validate`` and of leave-one-source-out cross-validation
    row_sources: tuple = attrs.field(default=(), eq=False)
    #: per row, whether the file gave the strike location (where it did not, the strike fields hold the face
    #: centre, 0); None: not recorded, every strike taken as given (the scorecard's strike zones use it)
    strike_known: np.ndarray | None = attrs.field(default=None, eq=False)
    #: the maker of the monitor that measured the rows, as the layout's id begins ('trackman', 'flightscope', ...);
    #: '' where not stated. The scorecard's instrument floor is a claim about one maker's monitor, so it is printed
    #: only beside rows of that maker.
    instrument: str = attrs.field(default="", eq=False)
    #: each row's ball setting on the monitor (TrackMan's Ball column: Premium, Limited Distance Soft...); () where
    #: the export names none. Text that groups the scorecard's rows; the models' ball is the table's ``ball``.
    ball_settings: tuple = attrs.field(default=(), eq=False)

    @ball_settings.validator
    def _one_setting_per_row(self, attribute, value):
        if value and len(value) != len(self.labels):
            raise ValueError(f"ball_settings: {len(value)} settings for {len(self.labels)} rows (one per row, or none)")

    @property
    def sources(self) -> tuple[str, ...]:
        """The source of every row (the table's name where the rows name none)."""
        return self.row_sources or (self.name,) * self.size

    @property
    def size(self) -> int:
        """Number of shots (rows)."""
        return len(self.labels)

    def subset(self, rows: Any) -> ShotTable:
        """The table of rows ``rows`` (an index or mask): a fold of a cross-validation."""
        rows = np.asarray(rows)
        index = np.arange(self.size)[rows]
        return attrs.evolve(self, labels=tuple(self.labels[i] for i in index),
                            clubs=tuple(self.clubs[i] for i in index),
                            handedness=tuple(self.handedness[i] for i in index),
                            delivery={k: v[index] for k, v in self.delivery.items()},
                            measured={k: v[index] for k, v in self.measured.items()},
                            sigma={k: v[index] for k, v in self.sigma.items()}, skipped=(),
                            strike_known=None if self.strike_known is None else self.strike_known[index],
                            row_sources=tuple(self.sources[i] for i in index),
                            ball_settings=tuple(self.ball_settings[i] for i in index) if self.ball_settings else ())


def _field_of(header: str) -> tuple[str | None, str | None]:
    """(field, unit) of a column header like 'Club Speed [mph]', 'spin_rate (rpm)' or 'ball_speed_sigma [mph]'."""
    match = re.match(r"^\s*(.*?)\s*(?:[\[(]\s*(.*?)\s*[\])])?\s*$", header)
    assert match is not None, "every part of the pattern is optional: it matches any header"
    name, unit = match.group(1), match.group(2)
    key = re.sub(r"\s+", " ", name.strip().lower())
    sigma = key.endswith("_sigma") or key.endswith(" sigma")
    if sigma:
        key = key[:-6].strip(" _")
    key = ALIASES.get(key, key.replace(" ", "_"))
    known = key in DELIVERY_FIELDS or key in MEASURED_FIELDS or key in TEXT_FIELDS
    if not known or (sigma and key not in MEASURED_FIELDS):
        return None, unit
    return (f"{key}_sigma" if sigma else key), unit


def _resolve_spin_loft(delivery: dict, lines: Sequence | np.ndarray, file: str) -> list[tuple[int, str, str]]:
    """Rows that give the face to path instead of the face angle, or the 3-D spin loft instead of the dynamic loft
    (TrackMan exports both, "Face To Path" and "Spin Loft"): the missing angle follows, in place; where both are
    given they must agree (:data:`impactlab.scene.core.SPIN_LOFT_TOLERANCE`). ``lines``: each row's file line, for
    messages. Returns the problems found."""
    problems = []
    path = np.nan_to_num(delivery["path"])
    f2p, face = delivery["face_to_path"], delivery["face_angle"]
    disagree = np.isfinite(f2p) & np.isfinite(face) & (np.abs(face - path - f2p) > SPIN_LOFT_TOLERANCE)
    for index in np.flatnonzero(disagree).tolist():
        problems.append((index, "face to path disagrees with face angle - club path",
                         f"{file}:{lines[index]}: face_to_path: expected face_angle - path "
                         f"({math.degrees(face[index] - path[index]):.2f} deg), got "
                         f"{math.degrees(f2p[index]):.2f} deg"))
    delivery["face_angle"] = np.where(np.isnan(face) & np.isfinite(f2p), path + f2p, face)
    given = delivery["spin_loft"]
    face, attack, loft = np.nan_to_num(delivery["face_angle"]), delivery["attack_angle"], delivery["dynamic_loft"]
    implied = loft_for_spin_loft(given, path, face, attack)
    with np.errstate(invalid="ignore"):
        made = spin_loft(path, face, attack, loft)
    for index in np.flatnonzero(np.isfinite(given)).tolist():
        where = f"{file}:{lines[index]}: spin_loft"
        if np.isnan(loft[index]) and np.isnan(implied[index]) and np.isfinite(attack[index]):
            problems.append((index, "spin loft below the angle between face and path",
                             f"{where}: expected a spin loft at least the angle between face and path, got "
                             f"{math.degrees(given[index]):.2f} deg"))
        elif np.isfinite(loft[index]) and abs(made[index] - given[index]) > SPIN_LOFT_TOLERANCE:
            problems.append((index, "spin loft disagrees with the row's angles",
                             f"{where}: expected the spin loft the row's angles make ({math.degrees(made[index]):.2f} "
                             f"deg, within {math.degrees(SPIN_LOFT_TOLERANCE):.1f}), got "
                             f"{math.degrees(given[index]):.2f} deg"))
    delivery["dynamic_loft"] = np.where(np.isnan(loft), implied, loft)
    return problems
