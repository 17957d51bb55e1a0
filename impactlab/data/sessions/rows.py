"""The row rules of a measured session: one set for every command that reads shots (``shots``, ``fly``,
``validate``, ``fit``, ``export``) and for the Python API.

A session is written by an instrument, not by its user: a row the models cannot take is skipped with its reason and
the other rows are used (a study, written by its user, keeps refusing such a value:
:mod:`impactlab.scene.plausibility`).
A row is skipped when a value it holds is

- not a finite number (``inf``), or a cell that is not a number at all;
- beyond any golf shot: the golf scene's refusal ranges (:data:`impactlab.scene.plausibility.GOLF_LIMITS`), the
  flight's (:data:`impactlab.scene.flight.IMPOSSIBLE_LAUNCH`), launch angles of 90 deg or more, and bounds of the
  monitor's own flight values far beyond any measured shot (:data:`FLIGHT_LIMITS`);
- a magnitude below zero (a ball speed or spin of -70);
- a strike off the club's face (the catalogue club's face size, as a study would refuse it);
- a smash factor no club gives (:func:`smash_limit`);
- or a speed the export's own smash factor contradicts (:mod:`impactlab.data.sessions.consistency`).

Values that are only unusual (beyond measured shots, within what a golf shot can be) are counted per column and
reason, never skipped. No-value markers (sentinels) are not bad rows: they are missing values, and a row that lacks
what a command needs is skipped for that (``no spin rate``).
"""

from __future__ import annotations

import functools
import math
from collections import Counter

import attrs
import numpy as np

from impactlab.scene import flight
from impactlab.scene.catalogue import club_key, club_preset
from impactlab.scene.plausibility import GOLF_LIMITS, strike_limits

#: the Rules' limit of a driver's coefficient of restitution, 0.830, with the test's tolerance, 0.008 (USGA/R&A
#: Equipment Rules, Part 2, 5a and the Pendulum Test Protocol; rules text)
COR_LIMIT = 0.838
#: a golf ball's largest mass, 45.93 g (Equipment Rules, Part 3; rules text)
BALL_MASS = 0.04593
#: impactlab's allowance for a smash factor measured from two speeds, each to about 1 % (an assumption of this
#: project, not a manufacturer's figure)
SMASH_ALLOWANCE = 0.02
#: the monitor's flight values: (low, high) in SI, display unit, factor, why. impactlab's bounds, far beyond any
#: measured shot (long-drive carries are under 400 m, hang times under 10 s), so only a misread is beyond them
FLIGHT_LIMITS = {
    "carry_distance": (0.0, 500.0, "m", 1.0), "total_distance": (0.0, 600.0, "m", 1.0),
    "apex_height": (0.0, 150.0, "m", 1.0), "flight_time": (0.0, 20.0, "s", 1.0),
    "landing_angle": (0.0, math.pi / 2, "deg", 180.0 / math.pi), "tracked_time": (0.0, 20.0, "s", 1.0),
    "landing_ball_speed": (0.0, 300.0 * 0.44704, "mph", 1 / 0.44704),
}
_DEG, _MPH, _RPM = 180.0 / math.pi, 1 / 0.44704, 30.0 / math.pi
#: the launch: (low, high) in SI (exclusive of a launch at 90 deg), display unit, factor
LAUNCH_LIMITS = {
    "ball_speed": (0.0, flight.IMPOSSIBLE_LAUNCH["ball_speed"][0], "mph", _MPH),
    "spin_rate": (0.0, flight.IMPOSSIBLE_LAUNCH["spin_rate"][0], "rpm", _RPM),
    "vertical_launch_angle": (-math.pi / 2, math.pi / 2, "deg", _DEG),
    "horizontal_launch_angle": (-math.pi / 2, math.pi / 2, "deg", _DEG),
    "spin_axis": (-math.pi / 2, math.pi / 2, "deg", _DEG),
}
#: unusual launch values (counted, not skipped): above these
UNUSUAL = {name: (limit, unit, factor) for name, (unit, factor, limit, _) in flight.UNUSUAL_LAUNCH.items()}


@functools.cache
def smash_limit(club: str) -> float:
    """The largest smash factor the catalogue club ``club`` can give, with :data:`SMASH_ALLOWANCE`.

    A free head of mass M at the Rules' COR limit e striking a ball of mass m head-on gives the ball
    (1 + e) M / (M + m) of its speed; loft and off-centre strikes give less. For the catalogue's 204 g driver:
    1.838 x 0.816 = 1.500, 1.530 with the allowance.
    """
    mass = club_preset(club).mass
    return (1.0 + COR_LIMIT) * mass / (mass + BALL_MASS) * (1.0 + SMASH_ALLOWANCE)


@attrs.frozen
class RowVerdict:
    """The rule breaches of a session's rows.

    Attributes
    ----------
    bad : ndarray of bool
        Rows skipped by every command.
    reasons : list of (str, ndarray of bool, ndarray of float)
        Each reason (stable text, one line of a summary), its rows, and the value per row in the reason's display
        unit (NaN where no single value says it).
    unusual : list of (str, ndarray of bool)
        Values beyond measured shots but within what a golf shot can be: counted per column and reason.
    """

    bad: np.ndarray
    reasons: list
    unusual: list

    def of_row(self, index: int) -> list[str]:
        """The reasons of one row, each with its value."""
        return [reason + ("" if not np.isfinite(value[index]) else f": {value[index]:.6g}")
                for reason, mask, value in self.reasons if mask[index]]


def _column_names(used: list) -> dict:
    return {field: header for header, field, _, _ in used}


def row_verdict(values: dict, clubs: tuple, used: list, flags: dict) -> RowVerdict:
    """The :class:`RowVerdict` of a session's SI ``values`` (``clubs``: each row's club name, ``used``: the
    session's columns, ``flags``: its flags)."""
    size = len(clubs)
    names = _column_names(used)
    reasons: list = []
    unusual: list = []

    def add(reason, mask, value):
        mask = mask & ~np.isinf(value)  # an infinite value is said once, as not finite
        if mask.any():
            reasons.append((reason, mask, np.where(mask, value, np.nan)))

    for (field, kind), mask in flags.items():  # cells no number could be read from
        if kind == "unreadable":
            add(f"{names.get(field, field)}: a cell that is not a number", mask, np.full(size, np.nan))
    for field, header in names.items():
        value = values.get(field)
        if value is None or value.dtype.kind != "f":
            continue
        infinite = np.isinf(value)
        if infinite.any():
            reasons.append((f"{header}: not a finite number", infinite, np.full(size, np.nan)))
    with np.errstate(invalid="ignore"):
        _ranges(values, names, add, unusual)
        _strikes_and_smash(values, clubs, names, add, unusual)
    if ("club_speed", "inconsistent") in flags:  # which of the two speeds is wrong is not known
        add("club speed and ball speed disagree with the stated smash factor", flags[("club_speed", "inconsistent")],
            np.full(size, np.nan))
    bad = np.zeros(size, bool)
    for _, mask, _ in reasons:
        bad |= mask
    return RowVerdict(bad=bad, reasons=reasons, unusual=unusual)


def _ranges(values, names, add, unusual) -> None:
    """Delivery, launch and flight values beyond any golf shot (skipped), or beyond measured shots (counted)."""
    for field, header in names.items():
        limit = GOLF_LIMITS.get(f"delivery.{field}")
        if limit is not None:
            shown = values[field] * limit.factor
            low, high = limit.impossible
            add(f"{header} beyond any golf shot ({low:g} to {high:g} {limit.unit})", (shown < low) | (shown > high),
                shown)
            low_u, high_u = limit.unusual
            rare = ((shown < low_u) | (shown > high_u)) & (shown >= low) & (shown <= high)
            if rare.any():
                unusual.append((f"{header}: unusual for golf (measured shots lie within {low_u:g} to {high_u:g} "
                                f"{limit.unit})", rare))
        for table in (LAUNCH_LIMITS, FLIGHT_LIMITS):
            if field in table:
                low, high, unit, factor = table[field]
                shown = values[field] * factor
                if low == 0.0:
                    add(f"{header} below 0 (a magnitude)", values[field] < 0, shown)
                    add(f"{header} beyond any golf shot (above {high * factor:g} {unit})", values[field] > high, shown)
                else:
                    add(f"{header} beyond any golf shot ({low * factor:g} to {high * factor:g} {unit})",
                        np.abs(values[field]) >= high, shown)
        if field in UNUSUAL:
            above, unit, factor = UNUSUAL[field]
            rare = (values[field] > above) & (values[field] <= LAUNCH_LIMITS[field][1])
            if rare.any():
                unusual.append((f"{header}: unusual for golf (above {above * factor:g} {unit})", rare))


def _strikes_and_smash(values, clubs, names, add, unusual) -> None:
    """Strikes off the row's club's face and smash factors no club gives, per club of the catalogue."""
    keys = {name: club_key(name) if name else None for name in set(clubs)}
    rows_of = Counter(keys[name] for name in clubs)
    club_of = np.array([keys[name] or "" for name in clubs], dtype=object)
    smash = values.get("smash_factor")
    stated = smash is not None and "smash_factor" in names
    ratio = smash if stated else values["ball_speed"] / values["club_speed"]
    if stated:  # a row without a stated smash factor: its speeds say it
        ratio = np.where(np.isfinite(smash), smash, values["ball_speed"] / values["club_speed"])
    for key in rows_of:
        if key is None:
            continue
        rows = club_of == key
        club = club_preset(key)
        for limit, field in zip(strike_limits(club), ("strike_toe", "strike_high")):
            if field not in names:
                continue
            shown = values[field] * limit.factor
            low, high = limit.impossible
            add(f"strike off the {key}'s face ({names[field]} beyond {high:.0f} mm of its centre)",
                rows & ((shown < low) | (shown > high)), shown)
            low_u, high_u = limit.unusual
            rare = rows & ((shown < low_u) | (shown > high_u)) & (shown >= low) & (shown <= high)
            if rare.any():
                unusual.append((f"{names[field]}: unusual for golf (beyond {high_u:.0f} mm of the "
                                f"{key}'s face centre)", rare))
        largest = smash_limit(key)
        add(f"a smash factor no {key} gives (above {largest:.3f}: the Rules' COR limit, the head's "
            f"mass, {100 * SMASH_ALLOWANCE:g} % for measurement)", rows & (ratio > largest), ratio)
