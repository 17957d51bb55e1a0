"""Contact properties, impact conditions and the scene that joins them to a ball and a face."""

from __future__ import annotations

import math

import attrs
import numpy as np

from impactlab.validators import check, finite, in_range, positive, to_float
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.errors import FieldError
from impactlab.units import converter
from impactlab.scene.materials import Ball, Face


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
    with a unit (``"45.93 g"``) or a pint quantity is converted (:func:`impactlab.units.converter`).

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

    speed: float = attrs.field(converter=converter("speed"), validator=positive("a positive, finite speed in m/s"))
    angle: float = attrs.field(
        converter=converter("angle"),
        validator=in_range(-math.pi / 2, math.pi / 2, "an angle between -90 and 90 deg", low_open=True,
                           high_open=True))
    spin: float = attrs.field(default=0.0, converter=converter("angular_speed"), validator=finite("a finite spin rate"))
    #: spin of the striking body [rad/s] about the same axis and counted like ``spin`` (a sphere striker,
    #: ClubHead.sphere; a club head's is taken as zero): it moves the striker's contact point by w x lever
    club_spin: float = attrs.field(default=0.0, converter=converter("angular_speed"),
                                  validator=finite("a finite spin rate"))


HANDEDNESS = ("right", "left")


@attrs.frozen
class Delivery:
    """A golf delivery: how the club head meets the ball, as a golfer or launch monitor describes it.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (:func:`impactlab.units.converter`).

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
    """

    club_speed: float = attrs.field(converter=converter("speed"),
                                   validator=positive("a positive, finite club speed in m/s"))
    path: float = attrs.field(default=0.0, converter=converter("angle"), validator=in_range(
        -math.pi / 2, math.pi / 2, "a club path between -90 and 90 deg", low_open=True, high_open=True))
    face_angle: float = attrs.field(default=0.0, converter=converter("angle"), validator=in_range(
        -math.pi / 2, math.pi / 2, "a face angle between -90 and 90 deg", low_open=True, high_open=True))
    attack_angle: float = attrs.field(default=0.0, converter=converter("angle"), validator=in_range(
        -math.pi / 2, math.pi / 2, "an attack angle between -90 and 90 deg", low_open=True, high_open=True))
    dynamic_loft: float = attrs.field(default=0.0, converter=converter("angle"), validator=in_range(
        -math.pi / 2, math.pi / 2, "a dynamic loft between -90 and 90 deg", low_open=True, high_open=True))
    handedness: str = attrs.field(default="right", validator=check(lambda v: v in HANDEDNESS,
                                                                   "right or left"))

    def __attrs_post_init__(self):
        if not self.spin_loft < math.pi / 2:
            raise FieldError("dynamic_loft", "a delivery whose face meets the ball (spin loft below 90 deg)",
                             f"spin loft {math.degrees(self.spin_loft):.1f} deg")

    @property
    def sign(self) -> float:
        """+1 for a right-handed golfer, -1 for a left-handed one (lateral quantities are mirrored)."""
        return 1.0 if self.handedness == "right" else -1.0

    @property
    def spin_loft(self) -> float:
        """Angle between face normal and club velocity [rad]."""
        from impactlab.physics.delivery import spin_loft

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

    def __attrs_post_init__(self):
        if self.club is not None and (self.face.mass != self.club.mass or self.face.material != self.club.material):
            raise FieldError("face", "the club head's mass and face material (use Scene.with_club)",
                             f"mass {self.face.mass:g} kg")
        if self.club is None and self.strike != Strike():
            raise FieldError("strike", "a club head to strike off centre (a club block)", "no club")
        from impactlab.scene.plausibility import check_scene

        check_scene(self)  # values no golf shot can have (a golf scene's limits by role)
        if self.delivery is not None and (abs(self.impact.angle - self.delivery.spin_loft) > 1e-9
                                          or self.impact.speed != self.delivery.club_speed):
            raise FieldError("impact", "the club speed and spin loft of the delivery (use Scene.from_delivery)",
                             f"speed {self.impact.speed:g} m/s, angle {math.degrees(self.impact.angle):g} deg")

    @classmethod
    def from_delivery(cls, ball: Ball, face: Face, contact: Contact, delivery: Delivery, spin: float = 0.0,
                      club: ClubHead | None = None, strike: Strike = Strike()):
        """The scene of a golf delivery: impact speed = club speed, impact angle = spin loft."""
        return cls(ball, face, contact, Impact(delivery.club_speed, delivery.spin_loft, spin), delivery, club, strike)

    @staticmethod
    def face_of(club: ClubHead) -> Face:
        """The face a club head presents: its material (rigid without one) and its mass."""
        return Face(material=club.material, rigid=club.material is None, mass=club.mass, name=club.name,
                    source=club.source)

    def inputs(self) -> dict[str, float]:
        """The model inputs this scene can supply, by vocabulary name (SI).

        Inputs the scene does not define (a ball without a material, no
        friction given) are left out; which of them a model needs is
        decided per model.
        """
        from impactlab.vocabulary import INPUTS

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
    from impactlab.physics.delivery import DELIVERY_INPUTS, spin_loft

    if all(name in inputs for name in DELIVERY_INPUTS):
        inputs["angle"] = spin_loft(*(inputs[name] for name in DELIVERY_INPUTS))
    return inputs


def ball_restitution(ball, inputs: dict):
    """The ball's restitution law at each case's normal approach speed (arrays, SI), or None without a law.

    The normal approach speed is that of the contact (club speed along the contact normal, so that a lofted,
    open or curved face meets the ball more slowly than its club speed).
    """
    from impactlab.physics.contact import contact_state

    if ball.restitution is None:
        return None
    gain = np.asarray(inputs.get("club_restitution_gain", 0.0), dtype=float)
    return np.clip(ball.restitution(contact_state(inputs)["normal_speed"]) + gain, 0.0, 1.0)
