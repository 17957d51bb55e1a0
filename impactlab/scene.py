"""Contact properties, impact conditions and the scene that joins them to a ball and a face."""

from __future__ import annotations

import math

import attrs

from ._validate import finite, in_range, positive, to_float
from .materials import Ball, Face


@attrs.frozen
class Contact:
    """Properties of the ball-face pair.

    Parameters
    ----------
    friction : float, optional
        Coulomb coefficient mu >= 0 [1], the same for static and kinetic friction.
    restitution : float, optional
        Normal coefficient of restitution e in [0, 1] [1].
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
    """

    speed: float = attrs.field(converter=to_float, validator=positive("a positive, finite speed in m/s"))
    angle: float = attrs.field(
        converter=to_float,
        validator=in_range(-math.pi / 2, math.pi / 2, "an angle between -90 and 90 deg", low_open=True,
                           high_open=True))
    spin: float = attrs.field(default=0.0, converter=to_float, validator=finite("a finite spin rate"))


@attrs.frozen
class Scene:
    """One impact: ball, face, contact and impact conditions."""

    ball: Ball
    face: Face
    contact: Contact
    impact: Impact

    def inputs(self) -> dict[str, float]:
        """The model inputs this scene can supply, by vocabulary name (SI).

        Inputs the scene does not define (a ball without a material, no
        friction given) are left out; which of them a model needs is
        decided per model.
        """
        from .vocabulary import INPUTS

        values = {}
        for name, spec in INPUTS.items():
            value = spec.getter(self)
            if value is not None:
                values[name] = value
        return values
