"""Checks an export allows on itself: columns that restate one another must agree.

- a stated smash factor against ball speed / club speed (a file whose ``Ball Speed`` and ``Club Speed`` headers are
  swapped states 1.45 where its columns give 0.69);
- a total spin against its back- and side-spin components (Foresight writes all three);
- a speed column's unit against the monitor's own carry: no ball carries farther than it would in a vacuum launched
  at 45 deg, v^2 / g, so a carry beyond that says the ball speed was read in too small a unit (``[km/h]`` on values
  in mph reads 150 mph as 93 mph).

Each disagreement is said once per column, with its first rows; the disagreeing values are flagged ``inconsistent``
(left out of comparisons and not flown, unless asked) and never corrected: which column is wrong is not known.
"""

from __future__ import annotations

import numpy as np


#: a stated smash factor and a total spin agree with what their columns give within this fraction (exports round the
#: smash factor to 2-4 digits: 1.45 for 1.4537 is 0.3 %)
RESTATED_TOLERANCE = 0.02


def _lines(lines: np.ndarray, mask: np.ndarray, most: int = 10) -> str:
    shown = ", ".join(str(line) for line in lines[mask][:most].tolist())
    return shown + (f" and {int(mask.sum()) - most} more" if mask.sum() > most else "")


def _flag(flags: dict, field: str, mask: np.ndarray) -> None:
    flags[(field, "inconsistent")] = flags.get((field, "inconsistent"), np.zeros_like(mask)) | mask


def check_consistency(values: dict, used: list, notes: list, flags: dict, lines: np.ndarray) -> None:
    """Run the checks of the module docstring on a session's SI ``values``; notes and flags in place."""
    given = {field for _, field, _, _ in used}
    _check_smash(values, given, notes, flags, lines)
    _check_total_spin(values, given, notes, flags, lines)
    _check_speed_unit(values, given, notes, flags, lines, {field: unit for _, field, unit, _ in used})


def _check_smash(values, given, notes, flags, lines) -> None:
    if not {"smash_factor", "ball_speed", "club_speed"} <= given:
        return
    stated, ball, club = values["smash_factor"], values["ball_speed"], values["club_speed"]
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = ball / club
        off = np.isfinite(stated) & np.isfinite(ratio) & (np.abs(stated / ratio - 1.0) > RESTATED_TOLERANCE)
        swapped = off & (np.abs(stated * ratio - 1.0) <= RESTATED_TOLERANCE)
    if not off.any():
        return
    for field in ("ball_speed", "club_speed"):
        _flag(flags, field, off)
    first = int(np.flatnonzero(off)[0])
    why = (f"in {int(swapped.sum())} of them it is club speed / ball speed: the Ball Speed and Club Speed columns "
           f"look swapped" if swapped.any() else "a speed column or its unit is wrong")
    notes.append(f"Smash Factor disagrees with ball speed / club speed by more than {100 * RESTATED_TOLERANCE:g} % in "
                 f"{int(off.sum())} row(s) (line(s) {_lines(lines, off)}; line {lines[first]}: {stated[first]:.4g} "
                 f"stated, {ratio[first]:.4g} from the speeds); {why}: their ball and club speeds are flagged "
                 f"inconsistent and left out")


def _check_total_spin(values, given, notes, flags, lines) -> None:
    if not {"spin_rate", "back_spin", "side_spin"} <= given:
        return
    with np.errstate(invalid="ignore", divide="ignore"):
        components = np.hypot(values["back_spin"], values["side_spin"])
        off = np.isfinite(values["spin_rate"]) & np.isfinite(components) & (
            np.abs(values["spin_rate"] / components - 1.0) > RESTATED_TOLERANCE)
    if not off.any():
        return
    _flag(flags, "spin_rate", off)
    first = int(np.flatnonzero(off)[0])
    rpm = 30.0 / np.pi
    notes.append(f"spin rate differs from hypot(back spin, side spin) by more than {100 * RESTATED_TOLERANCE:g} % in "
                 f"{int(off.sum())} row(s) (line(s) {_lines(lines, off)}; line {lines[first]}: "
                 f"{values['spin_rate'][first] * rpm:.0f} rpm stated, back {values['back_spin'][first] * rpm:.0f} and "
                 f"side {values['side_spin'][first] * rpm:.0f} rpm give {components[first] * rpm:.0f}): their spin "
                 f"rate is flagged inconsistent and not flown or compared")


def _check_speed_unit(values, given, notes, flags, lines, units) -> None:
    """A carry beyond v^2 / g (the longest a ball launched at speed v flies, in a vacuum at 45 deg; drag only
    shortens it and a golf ball's lift does not make up for its drag) in most rows says the ball speed's unit is
    too small for its numbers."""
    if not {"carry_distance", "ball_speed"} <= given:
        return
    ball, carry = values["ball_speed"], values["carry_distance"]
    with np.errstate(invalid="ignore", divide="ignore"):
        reach = carry * 9.80665 / ball ** 2
    known = np.isfinite(reach) & (carry > 0)
    beyond = known & (reach > 1.0)
    if not known.any() or beyond.sum() * 2 <= known.sum():  # a misread row is a row's problem, not the unit's
        return
    _flag(flags, "ball_speed", beyond)
    notes.append(f"Ball Speed [{units.get('ball_speed', '?')}]: in {int(beyond.sum())} of {int(known.sum())} row(s) "
                 f"(line(s) {_lines(lines, beyond)}) the monitor's carry is longer than a ball launched at that speed "
                 f"could fly even in a vacuum (v^2/g): the speeds are in a larger unit than the units row says (mph "
                 f"read as km/h?); those ball speeds are flagged inconsistent and not flown or compared")
