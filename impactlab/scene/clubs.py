"""Club heads and strike locations: the free rigid body behind the face, and where on the face the ball lands.

A :class:`ClubHead` is a rigid body (mass, inertia tensor about its centre of
mass, centre-of-mass position) carrying a face (loft, lie, bulge and roll radii,
material). A :class:`Strike` is the impact point on the face. Together with a
golf delivery they give the 3-D contact of :mod:`impactlab.physics.contact`.

Frames (docs/clubs.md has figures in words and the sign checks):

- **Head frame** (inertia tensor): the head at address with the face square,
  axes ``toe`` (horizontal, from heel to toe), ``up`` (vertical) and
  ``target`` (horizontal, towards the target). Products of inertia are tensor
  components, I_ab = -integral(a b dm).
- **Face axes** (centre of mass, strike): from the face centre, ``toe`` along
  the face towards the toe, ``high`` up the face (along the lofted face, not
  vertical), ``depth`` behind the face along its normal (positive behind).

All values SI. A left-handed golfer's head is the mirror image of a
right-handed one: the same numbers describe it in the same named axes.

The presets, the club catalogue, launch-monitor club names and user spec sheets are in
:mod:`impactlab.scene.catalogue`.
"""

from __future__ import annotations

import math
from typing import Any

import attrs
import numpy as np
from numpy.typing import ArrayLike

from impactlab.validators import in_range, positive, positive_or_inf, to_float
from impactlab.errors import FieldError
from impactlab.units import si_angle, si_length, si_mass
from impactlab.physics.delivery import cg_projection
from impactlab.scene.plausibility import HEAD_HEIGHT_LIMIT, HEAD_LENGTH_LIMIT
from impactlab.scene.materials import FaceSurface, Material

#: the order of the six independent tensor components as inputs and in :meth:`ClubHead.inertia_components`
INERTIA_AXES = ("toe", "up", "target")
INERTIA_COMPONENTS = ("toe", "up", "target", "toe_up", "toe_target", "up_target")


def _tensor(value) -> tuple[tuple[float, float, float], ...]:
    """Converter: a 3x3 nested sequence (or 3 principal moments about the head axes) -> nested tuples of floats."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return value  # the validator reports it
    if array.shape == (3,):
        array = np.diag(array)
    if array.shape != (3, 3):
        return value
    return tuple((float(row[0]), float(row[1]), float(row[2])) for row in array)


def _check_inertia(instance, attribute, value):
    expected = ("a symmetric, positive-definite 3x3 inertia tensor in kg m^2 (axes toe, up, target) whose "
                "principal moments satisfy the triangle inequality")
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise FieldError(attribute.name, expected, value) from None
    if array.shape != (3, 3) or not np.all(np.isfinite(array)):
        raise FieldError(attribute.name, expected, value)
    if not np.allclose(array, array.T, rtol=1e-9, atol=0.0):
        raise FieldError(attribute.name, expected, "a tensor that is not symmetric")
    moments = np.linalg.eigvalsh(array)
    if moments[0] <= 0.0:
        raise FieldError(attribute.name, expected, f"principal moments {moments.tolist()} (not all positive)")
    # a rigid body's principal moments: each at most the sum of the other two (equal only for a flat body)
    if moments[2] > (moments[0] + moments[1]) * (1.0 + 1e-9):
        raise FieldError(attribute.name, expected,
                         f"principal moments {moments.tolist()}: {moments[2]:.4g} > {moments[0]:.4g} + "
                         f"{moments[1]:.4g}, which no rigid body has")


def _check_center(instance, attribute, value):
    expected = "a centre of mass (toe, high, depth) in m with depth > 0 (behind the face)"
    if (not isinstance(value, tuple) or len(value) != 3
            or not all(isinstance(x, float) and math.isfinite(x) for x in value)):
        raise FieldError(attribute.name, expected, value)
    if value[2] <= 0.0:
        raise FieldError(f"{attribute.name}.depth", "a depth behind the face > 0 m", value[2])


def _vector3(value):
    try:
        return tuple(float(x) for x in value)
    except (TypeError, ValueError):
        return value


@attrs.frozen
class ClubHead:
    """A club head: a free rigid body with a (possibly curved) face.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    mass : float
        Head mass M [kg].
    inertia : 3x3 nested sequence, or 3 moments
        Inertia tensor about the centre of mass [kg m^2] in the head frame
        (axes toe, up, target; see the module docstring). Three numbers are
        principal moments about those axes.
    center_of_mass : (toe, high, depth)
        Centre of mass from the face centre along the face axes [m]; depth
        behind the face, > 0.
    loft, lie : float
        Static loft and lie [rad]. The loft turns the head frame into the face
        frame (the face normal is the target axis tilted up by the loft); at
        impact the face normal is the delivery's (dynamic loft, face angle), and
        the head turns with it. The lie is kept as data: at impact the face's
        heel-toe line is taken as horizontal.
    bulge_radius, roll_radius : float
        Face curvature radii heel-to-toe and sole-to-crown [m]; ``inf`` (the
        default) for a flat face.
    material : Material, optional
        The face material; None for a rigid face.
    face_width, face_height : float
        Size of the face heel to toe and sole to crown [m]: a strike further from the face centre than half
        of it misses the face and is refused (:mod:`impactlab.scene.plausibility`). Default: the USGA's limits
        of a wood's head, 127 x 71.12 mm (Equipment Rules, Part 2, 4b), which no face exceeds.
    restitution_gain : float
        Rise of the normal restitution over the ball's own law (measured against a rigid steel plate) that this
        face gives by its spring-like ("trampoline") effect [1]: a thin, hollow-backed wood face flexes and gives
        back energy the ball would lose. 0 for a rigid face (irons). Used where the ball's restitution law
        applies (a study that gives ``contact.restitution`` gives the pair's e outright). The USGA limits the
        resulting coefficient of restitution of a driver to 0.830 at 48.8 m/s (Equipment Rules, Part 2, 5a).
    name, source : str
    """

    mass: float = attrs.field(converter=si_mass, validator=positive("a positive, finite head mass in kg"))
    inertia: tuple = attrs.field(converter=_tensor, validator=_check_inertia)
    center_of_mass: tuple = attrs.field(converter=_vector3, validator=_check_center)
    loft: float = attrs.field(default=0.0, converter=si_angle, validator=in_range(
        0.0, math.pi / 2, "a static loft between 0 and 90 deg", high_open=True))
    lie: float = attrs.field(default=math.radians(60.0), converter=si_angle, validator=in_range(
        0.0, math.pi / 2, "a lie angle between 0 and 90 deg", high_open=True))
    bulge_radius: float = attrs.field(default=math.inf, converter=si_length,
                                      validator=positive_or_inf("a bulge radius > 0 m (inf: flat)"))
    roll_radius: float = attrs.field(default=math.inf, converter=si_length,
                                     validator=positive_or_inf("a roll radius > 0 m (inf: flat)"))
    material: Material | None = None
    name: str = ""
    source: str = ""
    restitution_gain: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        0.0, 0.2, "a restitution gain of the face 0 <= de <= 0.2", high_open=False))
    face_width: float = attrs.field(default=HEAD_LENGTH_LIMIT, converter=si_length,
                                    validator=positive("a positive, finite face width in m"))
    face_height: float = attrs.field(default=HEAD_HEIGHT_LIMIT, converter=si_length,
                                     validator=positive("a positive, finite face height in m"))
    #: a free sphere as the striker (:meth:`sphere`): the general contact scene, not a golf head
    is_sphere: bool = False
    #: the face's texture, grooves and water for the friction law (materials.FACE_SURFACES); None: not given
    surface: FaceSurface | None = None

    @property
    def cg_projection(self) -> tuple[float, float]:
        """The strike point whose face normal passes through the centre of mass (toe, high) [m]: the "CG
        projection" of club designers, where the normal impulse turns the head about neither face axis
        (:func:`impactlab.physics.delivery.cg_projection`). The ``driver`` preset's is 3.5 mm up the face (its
        2.9 mm CG, 42.3 mm deep, projected along the normals of its 254 mm roll)."""
        toe, high, depth = self.center_of_mass
        s_toe, s_high = cg_projection(toe, high, depth, self.bulge_radius, self.roll_radius)
        return float(s_toe), float(s_high)

    def inertia_components(self) -> dict[str, float]:
        """The six independent tensor components by input suffix (``toe``, ``up``, ..., ``up_target``) [kg m^2]."""
        tensor = self.inertia
        index = {axis: i for i, axis in enumerate(INERTIA_AXES)}
        out = {}
        for name in INERTIA_COMPONENTS:
            a, _, b = name.partition("_")
            out[name] = tensor[index[a]][index[b or a]]
        return out

    @classmethod
    def sphere(cls, radius: float, mass: float, inertia_factor: float = 0.4, material: Material | None = None,
               name: str = "", source: str = "") -> ClubHead:
        """A free sphere as the striking body: the two-sphere impact of discrete-element benchmarks.

        A sphere is a rigid body with the isotropic inertia K^2 M R^2 whose contact point lies at -R along the
        contact normal from its centre: here a head with that inertia, its centre of mass R behind the face
        centre, and a face of bulge and roll radii R, struck at the face centre. The contact's Hertz radius
        is then R1 R2/(R1 + R2) and its mobility W_head = (1/M) [1 + (1 - n n^T)/K^2] (Stronge 2000, ch. 5);
        R -> inf with M -> inf is a fixed half-space. Impact speed and angle give its velocity relative to
        the ball; ``Impact.spin`` is the ball's spin and ``Impact.club_spin`` the striker's.

        Parameters
        ----------
        radius : float
            Sphere radius R [m].
        mass : float
            Sphere mass M [kg].
        inertia_factor : float
            K^2 = I/(M R^2) [1] (0.4: a solid sphere).
        material : Material, optional
            The sphere's material (None: rigid).
        """
        radius, mass, inertia_factor = float(radius), float(mass), float(inertia_factor)
        if not (radius > 0.0 and math.isfinite(radius)):
            raise FieldError("radius", "a positive, finite sphere radius in m", radius)
        if not 0.0 < inertia_factor <= 2.0 / 3.0:
            raise FieldError("inertia_factor", "K^2 of a sphere, 0 < K^2 <= 2/3", inertia_factor)
        moment = inertia_factor * mass * radius**2
        return cls(mass=mass, inertia=(moment, moment, moment), center_of_mass=(0.0, 0.0, radius), loft=0.0,
                   bulge_radius=radius, roll_radius=radius, material=material, name=name or "sphere",
                   source=source or "a free sphere (ClubHead.sphere)", face_width=2.0 * radius,
                   face_height=2.0 * radius, is_sphere=True)

    @classmethod
    def from_principal(cls, moments: ArrayLike, axes: ArrayLike, **fields: Any) -> ClubHead:
        """A head from principal moments [kg m^2] and their axes (rows: unit vectors in toe, up, target)."""
        axes = np.asarray(axes, dtype=float)
        if axes.shape != (3, 3) or not np.allclose(axes @ axes.T, np.eye(3), atol=1e-6):
            raise FieldError("inertia.axes", "three orthonormal axes (rows) in the toe, up, target frame",
                             axes.tolist())
        tensor = axes.T @ np.diag(np.asarray(moments, dtype=float)) @ axes
        return cls(inertia=0.5 * (tensor + tensor.T), **fields)


@attrs.frozen
class Strike:
    """Where the ball meets the face, from the face centre along the face axes [m].

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    toe : float
        Towards the toe (negative: towards the heel) [m].
    high : float
        Up the face (negative: towards the sole) [m].
    """

    toe: float = attrs.field(default=0.0, converter=si_length, validator=in_range(
        -0.1, 0.1, "a strike offset within 100 mm of the face centre", low_open=True, high_open=True))
    high: float = attrs.field(default=0.0, converter=si_length, validator=in_range(
        -0.1, 0.1, "a strike offset within 100 mm of the face centre", low_open=True, high_open=True))


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["INERTIA_AXES", "INERTIA_COMPONENTS", "ClubHead", "Strike"]
