"""Contact properties, impact conditions and the scene that joins them to a ball and a face."""

from __future__ import annotations

import functools
import math
from typing import Any

import attrs
import numpy as np

from impactlab.validators import check, finite, in_range, positive, to_float
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.errors import FieldError
from impactlab.units import si_angle, si_angular_speed, si_speed
from impactlab.scene.materials import Ball, Face
from impactlab.scene.plausibility import check_scene
from impactlab.physics.contact import CLUB_REFERENCES, approach_state
from impactlab.physics.delivery import DELIVERY_INPUTS, loft_for_spin_loft, spin_loft
from impactlab.vocabulary import INPUTS


@attrs.frozen
class Contact:
    """Properties of the ball-face pair.

    Parameters
    ----------
    friction : float, optional
        Coulomb coefficient mu >= 0 (dimensionless), the same for static and kinetic friction.
    restitution : float, optional
        Normal coefficient of restitution e, 0 <= e <= 1 (dimensionless).
    """

    friction: float | None = attrs.field(
        default=None, converter=to_float,
        validator=in_range(0.0, math.inf, "a friction coefficient >= 0", high_open=True, optional=True))
    restitution: float | None = attrs.field(
        default=None, converter=to_float,
        validator=in_range(0.0, 1.0, "a coefficient of restitution with 0 <= e <= 1", optional=True))


@attrs.frozen
class Impact:
    """How the ball meets the face.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    speed : float
        Club speed along the path relative to the ball [m/s] (in the plate
        experiment: the ball's speed towards the plate).
    angle : float
        Face normal relative to path alpha [rad], -90 deg < alpha < 90 deg
        (the spin loft of a golf delivery; the plate's incidence angle).
    spin : float
        Incoming ball spin [rad/s], counted like the output ``spin_rate``:
        positive in the sense friction gives a ball sliding along the face
        (backspin for a lofted club). The contact-point slip speed is
        ``V sin(alpha) - R * spin``.
    club_spin : float
        Spin of the striking body [rad/s] about the same axis, counted the same
        way; it matters for a striker with inertia (a free sphere,
        :meth:`impactlab.scene.clubs.ClubHead.sphere`): the slip speed gains
        ``-(lever) * club_spin``, ``-R2 * club_spin`` for a sphere of radius R2.
    """

    speed: float = attrs.field(converter=si_speed, validator=positive("a positive, finite speed in m/s"))
    angle: float = attrs.field(
        converter=si_angle,
        validator=in_range(-math.pi / 2, math.pi / 2, "an angle between -90 and 90 deg", low_open=True,
                           high_open=True))
    spin: float = attrs.field(default=0.0, converter=si_angular_speed, validator=finite("a finite spin rate"))
    #: spin of the striking body [rad/s] about the same axis and counted like ``spin`` (a sphere striker,
    #: ClubHead.sphere; a club head's is taken as zero): it moves the striker's contact point by w x lever
    club_spin: float = attrs.field(default=0.0, converter=si_angular_speed,
                                  validator=finite("a finite spin rate"))


HANDEDNESS = ("right", "left")
#: where the delivery's dynamic loft and face angle are the face's (physics.contact.LOFT_AT)
LOFT_AT = ("contact", "centre")
#: largest difference between a given spin loft and the one the given angles make [rad]: launch monitors print
#: angles to 0.1 deg, so four rounded angles may disagree with a rounded spin loft by up to about 0.2 deg
SPIN_LOFT_TOLERANCE = math.radians(0.2)


def _rotation(value):
    try:
        values = tuple(float(x) for x in value)
    except (TypeError, ValueError):
        return value
    return values


def _check_rotation(instance, attribute, value):
    if not isinstance(value, tuple) or len(value) != 3 or not all(math.isfinite(x) for x in value):
        raise FieldError(attribute.name, "an angular velocity (toe, up, target) in rad/s, finite", value)


@attrs.frozen
class Delivery:
    """A golf delivery: how the club head meets the ball, as a golfer or launch monitor describes it.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    club_speed : float
        Club-head speed at the face centre [m/s].
    path, face_angle : float
        Horizontal directions of the club velocity (in-to-out positive) and of
        the face normal (open positive) [rad], each relative to the target line
        and counted towards the golfer's trail side: right for a right-handed
        golfer, left for a left-handed one.
    attack_angle : float
        Vertical direction of the club velocity, upwards positive [rad].
    dynamic_loft : float
        Elevation of the face normal above the horizontal at impact [rad].
    handedness : str
        ``"right"`` or ``"left"``.
    loft_at : str
        Where ``dynamic_loft`` and ``face_angle`` are the face's: ``"contact"`` (default), at the strike point,
        as launch monitors report them (TrackMan, Data Parameter Definitions: dynamic loft and face angle "at
        the center-point of contact between the club and ball at the time of maximum compression"), so that a
        strike off the centre of a bulged or rolled face turns the head, not the launch; ``"centre"``, at the
        face centre, the strike point's bulge and roll tilting the face further
        (:func:`impactlab.physics.delivery.centre_face` converts one into the other). The same on a flat face
        or a centred strike.
    club_reference : str
        The point of the head whose velocity ``club_speed``, ``path`` and ``attack_angle`` give:
        ``"centre_of_mass"`` (default; TrackMan reports them "relative to the CoG, or more precisely at the
        geometric center of the club head", typically within 6 mm of it: C. Hahn, "Club Data Definitions",
        blog.trackmangolf.com/club-data-definitions), ``"face_centre"`` (optical monitors, "since it is where the
        reflective markers are positioned", same source) or ``"contact"``. It matters only for a turning head
        (``head_rotation``): the velocity is carried to every other point rigidly, v = v_ref + w x r.
    head_rotation : (toe, up, target)
        Angular velocity of the head at first contact about its toe, up and target axes (the head frame of
        :mod:`impactlab.scene.clubs`, turned with the head at impact) [rad/s]; right-hand rule, so + toe turns
        the face upwards (adds loft), + up closes it, + target moves the toe down. A left-handed golfer's head is
        the mirror image: the same numbers (closing is + up whoever swings). Default zero (the head moves as a
        point); it needs a club head.
    """

    club_speed: float = attrs.field(converter=si_speed,
                                   validator=positive("a positive, finite club speed in m/s"))
    path: float = attrs.field(default=0.0, converter=si_angle, validator=in_range(
        -math.pi / 2, math.pi / 2, "a club path between -90 and 90 deg", low_open=True, high_open=True))
    face_angle: float = attrs.field(default=0.0, converter=si_angle, validator=in_range(
        -math.pi / 2, math.pi / 2, "a face angle between -90 and 90 deg", low_open=True, high_open=True))
    attack_angle: float = attrs.field(default=0.0, converter=si_angle, validator=in_range(
        -math.pi / 2, math.pi / 2, "an attack angle between -90 and 90 deg", low_open=True, high_open=True))
    dynamic_loft: float = attrs.field(default=0.0, converter=si_angle, validator=in_range(
        -math.pi / 2, math.pi / 2, "a dynamic loft between -90 and 90 deg", low_open=True, high_open=True))
    handedness: str = attrs.field(default="right", validator=check(lambda v: v in HANDEDNESS,
                                                                   "right or left"))
    loft_at: str = attrs.field(default="contact", validator=check(lambda v: v in LOFT_AT, "contact or centre"))
    club_reference: str = attrs.field(default="centre_of_mass", validator=check(
        lambda v: v in CLUB_REFERENCES, "centre_of_mass, face_centre or contact"))
    head_rotation: tuple = attrs.field(default=(0.0, 0.0, 0.0), converter=_rotation, validator=_check_rotation)

    def __attrs_post_init__(self):
        if not self.spin_loft < math.pi / 2:
            raise FieldError("dynamic_loft", "a delivery whose face meets the ball (spin loft below 90 deg)",
                             f"spin loft {math.degrees(self.spin_loft):.1f} deg")

    @classmethod
    def from_spin_loft(cls, club_speed: float, spin_loft: float, *, face_to_path: float | None = None,
                       face_angle: float | None = None, path: float = 0.0, attack_angle: float = 0.0,
                       dynamic_loft: float | None = None, **fields) -> Delivery:
        """A delivery given by its 3-D spin loft [rad] (TrackMan's: the angle between the club's velocity and the
        face normal), with the face given by ``face_to_path`` (face angle minus path) or ``face_angle``.

        The dynamic loft follows (:func:`impactlab.physics.delivery.loft_for_spin_loft`). Given as well, it
        must agree with the spin loft to :data:`SPIN_LOFT_TOLERANCE`; otherwise, or where no loft makes that
        spin loft, a FieldError says which numbers disagree.
        """
        if face_to_path is not None and face_angle is not None \
                and abs(face_angle - path - face_to_path) > SPIN_LOFT_TOLERANCE:
            raise FieldError("face_to_path", "face_angle - path (or only one of face_to_path, face_angle)",
                             f"{math.degrees(face_to_path):.2f} deg against face_angle - path = "
                             f"{math.degrees(face_angle - path):.2f} deg")
        face = face_angle if face_angle is not None else path + (face_to_path or 0.0)
        loft = float(loft_for_spin_loft(spin_loft, path, face, attack_angle))
        if not math.isfinite(loft):
            raise FieldError("spin_loft", "a spin loft at least the angle between face and path "
                             f"({math.degrees(abs(face - path)):.2f} deg here) and one the attack angle allows",
                             f"{math.degrees(spin_loft):.2f} deg")
        if dynamic_loft is not None:
            implied = cls(club_speed, path=path, face_angle=face, attack_angle=attack_angle,
                          dynamic_loft=dynamic_loft, **fields).spin_loft
            if abs(implied - spin_loft) > SPIN_LOFT_TOLERANCE:
                raise FieldError(
                    "spin_loft", f"the spin loft the delivery's angles make, within "
                    f"{math.degrees(SPIN_LOFT_TOLERANCE):.1f} deg ({math.degrees(implied):.2f} deg from dynamic "
                    f"loft {math.degrees(dynamic_loft):.2f}, attack {math.degrees(attack_angle):.2f}, face "
                    f"{math.degrees(face):.2f}, path {math.degrees(path):.2f} deg), or only one of spin_loft and "
                    "dynamic_loft", f"{math.degrees(spin_loft):.2f} deg")
            loft = dynamic_loft
        return cls(club_speed, path=path, face_angle=face, attack_angle=attack_angle, dynamic_loft=loft, **fields)

    @property
    def reference_code(self) -> int:
        """``club_reference`` as the number the models' input ``club_reference`` carries."""
        return CLUB_REFERENCES.index(self.club_reference)

    @property
    def sign(self) -> float:
        """+1 for a right-handed golfer, -1 for a left-handed one (lateral quantities are mirrored)."""
        return 1.0 if self.handedness == "right" else -1.0

    @property
    def spin_loft(self) -> float:
        """Angle between face normal and club velocity [rad]."""
        return float(spin_loft(self.path, self.face_angle, self.attack_angle, self.dynamic_loft, self.sign))


@attrs.frozen
class Scene:
    """One impact: ball, face, contact and impact conditions, and the golf delivery they come from, if any.

    With a delivery, ``impact`` holds the club speed and the spin loft
    (use :meth:`from_delivery`).
    """

    ball: Ball
    face: Face
    contact: Contact
    impact: Impact
    delivery: Delivery | None = None
    #: a free club head behind the face (None: the face is fixed or a point mass, ``face.mass``)
    club: ClubHead | None = None
    #: where the ball meets the face of ``club``
    strike: Strike = Strike()
    #: the air the ball flies through after launch (impactlab.scene.flight.Conditions; None: the standard air),
    #: used only by the ball-flight outputs
    conditions: Any = None

    def __attrs_post_init__(self):
        if self.club is not None and (self.face.mass != self.club.mass or self.face.material != self.club.material):
            raise FieldError("face", "the club head's mass and face material (use Scene.with_club)",
                             f"mass {self.face.mass:g} kg")
        if self.club is None and self.strike != Strike():
            raise FieldError("strike", "a club head to strike off centre (a club block)", "no club")
        if self.club is None and self.delivery is not None and any(self.delivery.head_rotation):
            raise FieldError("delivery.head_rotation", "a club head to turn (a club block)", "no club")
        if getattr(self.conditions, "shape", ()):  # a Conditions of one air per shot: impactlab.fly's, not a scene's
            raise FieldError("conditions", "one air for the scene (numbers; a study varies the air with its sweep: "
                             "block, e.g. conditions.temperature: [10 degC, 30 degC])",
                             f"arrays of shape {self.conditions.shape}")
        check_scene(self)  # values no golf shot can have (a golf scene's limits by role)
        if self.delivery is not None and (abs(self.impact.angle - self.delivery.spin_loft) > 1e-9
                                          or self.impact.speed != self.delivery.club_speed):
            raise FieldError("impact", "the club speed and spin loft of the delivery (use Scene.from_delivery)",
                             f"speed {self.impact.speed:g} m/s, angle {math.degrees(self.impact.angle):g} deg")

    @classmethod
    def from_delivery(cls, ball: Ball, face: Face, contact: Contact, delivery: Delivery, spin: float = 0.0,
                      club: ClubHead | None = None, strike: Strike = Strike()) -> Scene:
        """The scene of a golf delivery: impact speed = club speed, impact angle = spin loft."""
        return cls(ball, face, contact, Impact(delivery.club_speed, delivery.spin_loft, spin), delivery, club, strike)

    @staticmethod
    def face_of(club: ClubHead) -> Face:
        """The face a club head presents: its material (rigid without one) and its mass."""
        return Face(material=club.material, rigid=club.material is None, mass=club.mass, name=club.name,
                    source=club.source, surface=club.surface)

    def inputs(self) -> dict[str, float]:
        """The model inputs this scene can supply, by vocabulary name (SI).

        Inputs the scene does not define (a ball without a material, no
        friction given) are left out; which of them a model needs is
        decided per model. Computed once per scene (a run asks three times: its plan, its case arrays, its
        provenance), a new dict each call.
        """
        return dict(self._inputs)

    @functools.cached_property
    def _inputs(self) -> dict[str, float]:
        values = {}
        for name, spec in INPUTS.items():
            value = spec.getter(self)
            if value is not None:
                values[name] = value
        if "restitution" not in values and self.ball.restitution is not None:
            values["restitution"] = float(ball_restitution(self.ball, complete_inputs(
                {name: np.atleast_1d(value) for name, value in values.items()}))[0])
        return values


def complete_inputs(inputs: dict) -> dict:
    """Fill inputs that follow from others: a delivery's spin loft is the impact angle (arrays, SI)."""
    if all(name in inputs for name in DELIVERY_INPUTS):
        inputs["angle"] = spin_loft(*(inputs[name] for name in DELIVERY_INPUTS))
    return inputs


def ball_restitution(ball: Ball, inputs: dict) -> np.ndarray:
    """The ball's restitution law at each case's normal approach speed (arrays, SI) [1].

    The normal approach speed is that of the contact (club speed along the contact normal, so that a lofted,
    open or curved face meets the ball more slowly than its club speed). Callers ask only for a ball with a law
    (``ball.restitution`` not None); asked for one without, it raises ValueError.
    """
    if ball.restitution is None:
        raise ValueError("ball_restitution: the ball has no restitution law")
    gain = np.asarray(inputs.get("club_restitution_gain", 0.0), dtype=float)
    # the approach speeds only: the (n, 3, 3) mobility is built once per chunk, where the models need it
    return np.clip(ball.restitution(approach_state(inputs)["normal_speed"]) + gain, 0.0, 1.0)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["Contact", "Impact", "HANDEDNESS", "LOFT_AT", "SPIN_LOFT_TOLERANCE", "Delivery", "Scene",
           "complete_inputs", "ball_restitution"]
