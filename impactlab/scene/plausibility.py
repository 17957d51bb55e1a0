"""Plausibility by role: values no golf shot can have are refused, with the range and why; unusual ones warned once.

A value can be valid for the framework (a positive speed, an angle below 90 deg) and still be one no golf shot
has: a club speed of 10^6 m/s, a centre of mass 3 m behind the face, a strike 99 mm off a 6-iron's centre. Such
values run and return numbers, so they are refused here, by the role the value plays in the scene and by the
scene's kind:

- **golf**: a golf delivery (``delivery`` block) or a golf club head (``club`` block, not a sphere). The limits
  of :data:`GOLF_LIMITS` apply, and those a club head sets itself (its own face size, its head's size).
- **contact**: a ball fired at a fixed face or plate (``impact`` block, no club) or at a free sphere
  (:meth:`impactlab.scene.clubs.ClubHead.sphere`): the framework's general contact use (sphere-on-sphere and
  sphere-on-plate benchmarks such as Chung & Ooi 2011, speeds of mm/s to m/s, spheres of any size). Only the
  validators of the value objects apply (positive masses and radii, angles within +-90 deg...).

docs/user-guide.md ("Plausibility limits") lists the same table in words. Refused values raise
:class:`~impactlab.errors.FieldError` at the value's field path (so a study names its file and line); unusual
values raise a :class:`~impactlab.errors.PlausibilityWarning`, once per message in a process.
"""

from __future__ import annotations

import math
import warnings

import attrs

from impactlab.errors import FieldError, PlausibilityWarning
from impactlab.units import MPH

GOLF, CONTACT = "golf", "contact"

#: the USGA's size limits of a wood's head (Equipment Rules, Part 2, 4b(i)): heel to toe at most 5 in (127 mm),
#: sole to crown at most 2.8 in (71.12 mm), and face to back shorter than heel to toe; rules text, exact
HEAD_LENGTH_LIMIT = 0.127
HEAD_HEIGHT_LIMIT = 0.07112


@attrs.frozen
class Limit:
    """Where one role's values are refused and where they are only unusual (display units).

    Parameters
    ----------
    path : str
        The field path (as a study writes it).
    words : str
        What the value is, for messages.
    unit : str
        Display unit of ``impossible`` and ``unusual``.
    factor : float
        Display unit per SI unit.
    impossible : (float, float)
        Values outside are refused.
    unusual : (float, float)
        Values outside (and inside ``impossible``) are warned about.
    why : str
        The reason and its source.
    """

    path: str
    words: str
    unit: str
    factor: float
    impossible: tuple[float, float]
    unusual: tuple[float, float]
    why: str


_MPH = 1.0 / MPH
_DEG = 180.0 / math.pi
_RPM = 30.0 / math.pi

#: the limits of a golf scene by role (display units). Refused: beyond anything a golfer, a club or a ball can
#: do; warned: beyond what measured shots show.
GOLF_LIMITS: dict[str, Limit] = {limit.path: limit for limit in (
    Limit("delivery.club_speed", "a club speed", "mph", _MPH, (1.0, 200.0), (40.0, 150.0),
          "the fastest measured club speeds are about 150 mph (long-drive competitors, TrackMan, measured); a "
          "human swing does not reach 200 mph"),
    Limit("delivery.attack_angle", "an attack angle", "deg", _DEG, (-30.0, 30.0), (-12.0, 12.0),
          "a club swung on an arc meets the ball within about +-10 deg of level (TrackMan tour averages -5 to "
          "+3 deg, long drivers up to +10 deg, measured); beyond +-30 deg the head would strike the ground or "
          "pass over the ball"),
    Limit("delivery.path", "a club path", "deg", _DEG, (-45.0, 45.0), (-15.0, 15.0),
          "measured club paths lie within about +-10 deg of the target line; beyond +-45 deg the ball is hit "
          "sideways off the face (a shank), which the models do not describe"),
    Limit("delivery.face_angle", "a face angle", "deg", _DEG, (-45.0, 45.0), (-15.0, 15.0),
          "measured face angles lie within about +-10 deg of the target line; beyond +-45 deg the ball is hit "
          "sideways off the face"),
    Limit("delivery.dynamic_loft", "a dynamic loft", "deg", _DEG, (-10.0, 75.0), (0.0, 65.0),
          "lofts are 2-4 deg (putters) to 64 deg (lob wedges); a delivery adds or takes off some 10 deg "
          "(shaft lean), so no shot has a dynamic loft below -10 or above 75 deg"),
    # the Rules' ball (R&A/USGA Equipment Rules, Part 3: a diameter of at least 1.680 in, a weight of at most
    # 1.620 oz; rules text, exact): a golf scene's ball that is no golf ball at all (a 2 m ball struck by a driver
    # ran without a word) is refused; no measured spread of balls is at hand to warn by, so none is warned about
    Limit("ball.radius", "a golf ball's radius", "mm", 1e3, (10.0, 45.0), (10.0, 45.0),
          "the Rules' ball is at least 42.67 mm across (radius 21.335 mm; R&A/USGA Equipment Rules, Part 3); no ball "
          "a golf club strikes is under 20 or over 90 mm across"),
    Limit("ball.mass", "a golf ball's mass", "g", 1e3, (10.0, 100.0), (10.0, 100.0),
          "the Rules' ball weighs at most 45.93 g (R&A/USGA Equipment Rules, Part 3); no ball a golf club strikes "
          "weighs under 10 or over 100 g"),
    Limit("impact.spin", "an incoming ball spin", "rpm", _RPM, (-20000.0, 20000.0), (-12000.0, 12000.0),
          "golf balls leave a club with at most about 12,000 rpm (wedges, measured); a ball arriving at the "
          "face spins far less (0 for a teed ball). 20,000 rpm is beyond any shot"),
)}


def scene_kind(scene) -> str:
    """``"golf"`` for a delivery or a golf club head, ``"contact"`` for a fixed face, plate or sphere striker."""
    if scene.delivery is not None:
        return GOLF
    if scene.club is not None and not scene.club.is_sphere:
        return GOLF
    return CONTACT


_warned: set[str] = set()


def _warn_once(text: str) -> None:
    if text not in _warned:
        _warned.add(text)
        warnings.warn(text, PlausibilityWarning, stacklevel=4)


def refuse_impossible(limit: Limit, value: float | None) -> None:
    """Refuse ``value`` [SI] beyond ``limit``'s impossible range with a FieldError naming the range and why (a
    missing or non-finite value is not judged here).

    Raises
    ------
    FieldError
        At ``limit.path``: the range in the limit's display unit, its reason, and the value given.
    """
    if value is None or not math.isfinite(value):
        return
    shown = value * limit.factor
    low, high = limit.impossible
    if not low <= shown <= high:
        span = f"at least {low:g}" if high == math.inf else f"between {low:g} and {high:g}"
        raise FieldError(limit.path, f"{limit.words} {span} {limit.unit} ({limit.why})", f"{shown:.6g} {limit.unit}")


def _judge(limit: Limit, value: float | None) -> None:
    refuse_impossible(limit, value)
    if value is None or not math.isfinite(value):
        return
    shown = value * limit.factor
    low, high = limit.unusual
    if not low <= shown <= high:
        _warn_once(f"{limit.path}: {shown:.6g} {limit.unit} is unusual for golf (measured shots lie within "
                   f"{low:g} to {high:g} {limit.unit}); computed as given")


def club_limits(club) -> list[tuple[Limit, float | None]]:
    """The limits a golf club head sets itself, each with the value it judges: its face and head size."""
    mm = 1e3
    face = (f"the {club.name or 'club'}'s face is {club.face_width * mm:.0f} x {club.face_height * mm:.0f} mm "
            "(ClubHead.face_width/face_height)")
    toe, high, depth = club.center_of_mass
    half_width, half_height = club.face_width / 2 * mm, club.face_height / 2 * mm
    head = (f"a conforming head is at most {HEAD_LENGTH_LIMIT * mm:.0f} mm heel to toe and "
            f"{HEAD_HEIGHT_LIMIT * mm:.2f} mm sole to crown, and shorter face to back than heel to toe (USGA "
            "Equipment Rules, Part 2, 4b)")
    return [
        (Limit("club.center_of_mass.toe", "a centre of mass inside the head", "mm", mm,
               (-HEAD_LENGTH_LIMIT / 2 * mm, HEAD_LENGTH_LIMIT / 2 * mm), (-15.0, 15.0), head), toe),
        (Limit("club.center_of_mass.high", "a centre of mass inside the head", "mm", mm,
               (-HEAD_HEIGHT_LIMIT / 2 * mm, HEAD_HEIGHT_LIMIT / 2 * mm), (-15.0, 15.0), head), high),
        (Limit("club.center_of_mass.depth", "a centre of mass inside the head", "mm", mm,
               (0.0, HEAD_LENGTH_LIMIT * mm), (2.0, 50.0), head), depth),
        (Limit("club.bulge_radius", "a bulge radius no smaller than half the face's width", "mm", mm,
               (half_width, math.inf), (150.0, math.inf),
               f"a face curved more tightly than its own half-width cannot span it; {face}; drivers' bulge radii "
               "are 200-500 mm"), club.bulge_radius),
        (Limit("club.roll_radius", "a roll radius no smaller than half the face's height", "mm", mm,
               (half_height, math.inf), (150.0, math.inf),
               f"a face curved more tightly than its own half-height cannot span it; {face}; drivers' roll radii "
               "are 200-500 mm"), club.roll_radius),
        (Limit("club.mass", "a club-head mass", "g", 1e3, (50.0, 1000.0), (150.0, 450.0),
               "golf heads weigh 190-210 g (drivers) to 300-370 g (putters); no club head weighs under 50 g or "
               "over 1 kg"), club.mass),
    ]


def strike_limits(club) -> list[Limit]:
    """The strike offsets a golf club's own face allows: within its half-width and half-height."""
    mm = 1e3
    face = (f"the {club.name or 'club'}'s face is {club.face_width * mm:.0f} x {club.face_height * mm:.0f} mm "
            "(ClubHead.face_width/face_height), so a ball struck further from its centre misses the face")
    half_width, half_height = club.face_width / 2 * mm, club.face_height / 2 * mm
    return [Limit("strike.toe", "a strike on the club's face", "mm", mm, (-half_width, half_width),
                  (-0.6 * half_width, 0.6 * half_width), face),
            Limit("strike.high", "a strike on the club's face", "mm", mm, (-half_height, half_height),
                  (-0.6 * half_height, 0.6 * half_height), face)]


#: measured quantities that are magnitudes: a value below zero is a sign or column error, never a shot
MAGNITUDES = {"ball_speed": "a ball speed is a magnitude (its direction is the launch angles)",
              "spin_rate": "the total spin is a magnitude (its direction is the spin axis)"}
#: how a refused magnitude is shown: the usual unit, its factor from SI, the SI unit
_MAGNITUDE_UNITS = {"ball_speed": ("mph", _MPH, "m/s"), "spin_rate": ("rpm", _RPM, "rad/s")}


def wrong_sign(measured: dict, index: int, where: str) -> list[str]:
    """Messages for one measured row's magnitudes given below zero (a ball speed of -70 mph).

    Parameters
    ----------
    measured : dict of ndarray
        Measured quantities by field [SI], NaN where not measured.
    index : int
        The row.
    where : str
        ``file:line`` of the row.

    Returns
    -------
    list of str
    """
    problems = []
    for key, why in MAGNITUDES.items():
        value = measured.get(key)
        if value is not None and value[index] < 0:
            unit, factor, si_unit = _MAGNITUDE_UNITS[key]  # 'got -67.056 (SI)' read as -67 of the file's mph
            problems.append(f"{where}: {key}: expected a value >= 0 ({why}), got {value[index] * factor:.6g} {unit} "
                            f"({value[index]:.6g} {si_unit})")
    return problems


def check_scene(scene) -> None:
    """Refuse a golf scene's impossible values (FieldError at the field path); warn of unusual ones, once.

    Parameters
    ----------
    scene : impactlab.scene.core.Scene

    Raises
    ------
    FieldError
        For a value no golf shot can have, with the range and why.
    """
    if scene_kind(scene) != GOLF:
        return
    delivery = scene.delivery
    if delivery is not None:
        for name in ("club_speed", "attack_angle", "path", "face_angle", "dynamic_loft"):
            _judge(GOLF_LIMITS[f"delivery.{name}"], getattr(delivery, name))
    _judge(GOLF_LIMITS["impact.spin"], scene.impact.spin)
    _judge(GOLF_LIMITS["ball.radius"], scene.ball.radius)
    _judge(GOLF_LIMITS["ball.mass"], scene.ball.mass)
    club = scene.club
    if club is not None and not club.is_sphere:
        for limit, value in club_limits(club):
            _judge(limit, value)
        toe_limit, high_limit = strike_limits(club)
        _judge(toe_limit, scene.strike.toe)
        _judge(high_limit, scene.strike.high)


__all__ = ["refuse_impossible", "GOLF", "CONTACT", "GOLF_LIMITS", "Limit", "MAGNITUDES", "wrong_sign", "scene_kind",
           "check_scene", "club_limits", "strike_limits", "HEAD_LENGTH_LIMIT", "HEAD_HEIGHT_LIMIT"]
