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
"""

from __future__ import annotations

import math

import attrs
import numpy as np

from ._validate import in_range, positive, positive_or_inf, to_float
from .errors import FieldError
from .materials import MATERIAL_PRESETS, Material

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
    return tuple(tuple(float(x) for x in row) for row in array)


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
    name, source : str
    """

    mass: float = attrs.field(converter=to_float, validator=positive("a positive, finite head mass in kg"))
    inertia: tuple = attrs.field(converter=_tensor, validator=_check_inertia)
    center_of_mass: tuple = attrs.field(converter=_vector3, validator=_check_center)
    loft: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        0.0, math.pi / 2, "a static loft between 0 and 90 deg", high_open=True))
    lie: float = attrs.field(default=math.radians(60.0), converter=to_float, validator=in_range(
        0.0, math.pi / 2, "a lie angle between 0 and 90 deg", high_open=True))
    bulge_radius: float = attrs.field(default=math.inf, converter=to_float,
                                      validator=positive_or_inf("a bulge radius > 0 m (inf: flat)"))
    roll_radius: float = attrs.field(default=math.inf, converter=to_float,
                                     validator=positive_or_inf("a roll radius > 0 m (inf: flat)"))
    material: Material | None = None
    name: str = ""
    source: str = ""

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
    def from_principal(cls, moments, axes, **fields) -> "ClubHead":
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

    Parameters
    ----------
    toe : float
        Towards the toe (negative: towards the heel) [m].
    high : float
        Up the face (negative: towards the sole) [m].
    """

    toe: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        -0.1, 0.1, "a strike offset within 100 mm of the face centre", low_open=True, high_open=True))
    high: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        -0.1, 0.1, "a strike offset within 100 mm of the face centre", low_open=True, high_open=True))


G_CM2 = 1e-7  # kg m^2 per g cm^2
MM = 1e-3


def _driver_2020():
    """The measured driver of Proceedings 49 (2020) 47, in the head frame (see docs/clubs.md for the mapping)."""
    # published: CG [-42.3, 2.9, 1.0] mm from the face centre and the tensor below [g cm^2], in the paper's
    # (x: towards the target, y: vertical, z: heel-toe) axes; reordered here to (toe, up, target)
    published = np.array([[2843.0, -733.0, 530.0], [-733.0, 5679.0, 0.5], [530.0, 0.5, 4085.0]])
    order = [2, 1, 0]  # toe <- z, up <- y, target <- x
    tensor = published[np.ix_(order, order)] * G_CM2
    return tensor


CLUB_SOURCES = {
    "driver": (
        "Measured head: Proceedings 49 (2020) 47 (ISEA 2020): mass 204 g, CG [-42.3, 2.9, 1.0] mm from the face "
        "centre, inertia tensor [[2843, -733, 530], [-733, 5679, 0.5], [530, 0.5, 4085]] g cm^2, loft 9.8 deg, "
        "bulge 305 mm (measurement). Axis mapping to toe/up/target is ours (docs/clubs.md). Roll 254 mm and "
        "lie 58 deg: typical manufacturer specifications (not measured on this head). Face Ti-6Al-4V."),
}


CLUB_PRESETS: dict[str, ClubHead] = {
    "driver": ClubHead(
        mass=0.204, inertia=_driver_2020(), center_of_mass=(1.0 * MM, 2.9 * MM, 42.3 * MM),
        loft=math.radians(9.8), lie=math.radians(58.0), bulge_radius=0.305, roll_radius=0.254,
        material=MATERIAL_PRESETS["titanium"], name="driver (measured head, 2020)", source=CLUB_SOURCES["driver"]),
}


def club_preset(name: str) -> ClubHead:
    """The club-head preset called ``name``."""
    try:
        return CLUB_PRESETS[name]
    except (KeyError, TypeError):
        raise FieldError("preset", "a club preset name", name, choices=CLUB_PRESETS) from None
