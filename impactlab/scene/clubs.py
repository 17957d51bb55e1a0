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

from impactlab.validators import in_range, positive, positive_or_inf, to_float
from impactlab.errors import FieldError
from impactlab.units import converter
from impactlab.scene.plausibility import HEAD_HEIGHT_LIMIT, HEAD_LENGTH_LIMIT
from impactlab.scene.materials import MATERIAL_PRESETS, Material

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

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (:func:`impactlab.units.converter`).

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

    mass: float = attrs.field(converter=converter("mass"), validator=positive("a positive, finite head mass in kg"))
    inertia: tuple = attrs.field(converter=_tensor, validator=_check_inertia)
    center_of_mass: tuple = attrs.field(converter=_vector3, validator=_check_center)
    loft: float = attrs.field(default=0.0, converter=converter("angle"), validator=in_range(
        0.0, math.pi / 2, "a static loft between 0 and 90 deg", high_open=True))
    lie: float = attrs.field(default=math.radians(60.0), converter=converter("angle"), validator=in_range(
        0.0, math.pi / 2, "a lie angle between 0 and 90 deg", high_open=True))
    bulge_radius: float = attrs.field(default=math.inf, converter=converter("length"),
                                      validator=positive_or_inf("a bulge radius > 0 m (inf: flat)"))
    roll_radius: float = attrs.field(default=math.inf, converter=converter("length"),
                                     validator=positive_or_inf("a roll radius > 0 m (inf: flat)"))
    material: Material | None = None
    name: str = ""
    source: str = ""
    restitution_gain: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        0.0, 0.2, "a restitution gain of the face 0 <= de <= 0.2", high_open=False))
    face_width: float = attrs.field(default=HEAD_LENGTH_LIMIT, converter=converter("length"),
                                    validator=positive("a positive, finite face width in m"))
    face_height: float = attrs.field(default=HEAD_HEIGHT_LIMIT, converter=converter("length"),
                                     validator=positive("a positive, finite face height in m"))
    #: a free sphere as the striker (:meth:`sphere`): the general contact scene, not a golf head
    is_sphere: bool = False

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
    def from_principal(cls, moments, axes, **fields) -> ClubHead:
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
    with a unit (``"45.93 g"``) or a pint quantity is converted (:func:`impactlab.units.converter`).

    Parameters
    ----------
    toe : float
        Towards the toe (negative: towards the heel) [m].
    high : float
        Up the face (negative: towards the sole) [m].
    """

    toe: float = attrs.field(default=0.0, converter=converter("length"), validator=in_range(
        -0.1, 0.1, "a strike offset within 100 mm of the face centre", low_open=True, high_open=True))
    high: float = attrs.field(default=0.0, converter=converter("length"), validator=in_range(
        -0.1, 0.1, "a strike offset within 100 mm of the face centre", low_open=True, high_open=True))


G_CM2 = 1e-7  # kg m^2 per g cm^2
MM = 1e-3

#: Proceedings 49 (2020) 47 (ISEA 2020), https://www.mdpi.com/2504-3900/49/1/47,
#: Table 1, a measured driver head. Its frame (Figure 1 there) has x along the face normal towards the ball (the ball's
#: impact point lies at x = -21.3 mm from its centre, the head's CG at x = -42.3 mm); we take y vertical and z towards
#: the toe (y: the largest moment, 5679 g cm^2, as a driver's about its vertical axis is, near the USGA limit of
#: 5900; x, y, z right-handed puts z at the toe of a right-handed head), and the tensor's axes parallel to the head
#: frame at address. Those two readings are ours, not the paper's words.
DRIVER_2020 = dict(mass=0.204, center=(1.0, 2.9, 42.3),
                   tensor=[[2843.0, -733.0, 530.2], [-733.0, 5679.0, 0.5], [530.2, 0.5, 4085.0]])


def _driver_2020_tensor():
    published = np.array(DRIVER_2020["tensor"])
    order = [2, 1, 0]  # toe <- z, up <- y, target <- x
    return published[np.ix_(order, order)] * G_CM2


_ESTIMATE = ("Estimate, not a measurement: {what}. Moments: {moments}. Mass: {mass}. CG: {cg}. Sources of the "
             "anchors: Golf Digest (Stachura 2008; 2010) quote manufacturers' iron MOIs of 2400-3000 g cm^2 about the "
             "vertical axis (Ping S56 7-iron 2400, K15 3000; a typical cavity back about 2600); R. Maltby (Golf "
             "Club Design, Fitting, Alteration and Repair; ralphmaltby.com) gives a standard 5-iron head of 254 g "
             "with 7 g steps through the set. Lofts and lies: typical manufacturer specifications.")

CLUB_SOURCES = {
    "driver": (
        "Measured head (measurement): Proceedings 49 (2020) 47, https://www.mdpi.com/2504-3900/49/1/47, Table 1: "
        "mass 204 g, CG [-42.3, 2.9, 1.0] mm from the face centre, inertia tensor [[2843, -733, 530.2], [-733, "
        "5679, 0.5], [530.2, 0.5, 4085]] g cm^2, loft 9.8 deg, bulge 305 mm. The mapping of its axes to toe/up/"
        "target is ours (docs/clubs.md). Roll 254 mm and lie 58 deg: typical manufacturer specifications, not "
        "measured on this head. Face Ti-6Al-4V. Restitution gain 0.083: fitted (impactlab fit trackman_tour: maw "
        "0.082 +- 0.018, hertz_mindlin 0.084 +- 0.014) beside the tour_urethane ball's e = 0.787, a model output; it "
        "puts the driver's e at about 0.87, above the USGA's COR limit of 0.830, so it also stands in for what the "
        "models leave out of a driver's smash factor (Proceedings 49 (2020) 47 needed under 3 g more head mass with "
        "e = 0.83; the shaft's share of the club mass is not modelled)."),
    "fairway_wood": _ESTIMATE.format(
        what="a 15 deg 3-wood scaled from the measured driver",
        moments="up 3300, toe 1800, target 1700 g cm^2, the driver's scaled by mass and by (head size)^2 ~ 0.6 "
                "(a 3-wood head of 150-180 cm^3 against 460)",
        mass="212 g, typical of 3-wood heads (manufacturer specifications 205-220 g)",
        cg="25 mm behind the face and 5 mm below its centre (fairway woods put the CG low to launch off the turf)"
        ) + (" Bulge 300 mm, roll 280 mm: typical specifications. Face 17-4PH steel. Restitution gain 0.083: the "
             "calibration's gain of a bulged (wood) face, fitted on driver rows only (no fairway-wood shots with a "
             "published dynamic loft were found): an assumption for this club."),
    "6_iron": _ESTIMATE.format(
        what="a cavity-back 6-iron, 30 deg, lie 62 deg",
        moments="up 2600 (the typical cavity back above), toe 800 and target 3200 from a perimeter-weighted plate "
                "75 x 45 mm (the perpendicular-axis theorem: I_target ~ I_up + I_toe less the thickness term)",
        mass="261 g (Maltby: 254 g + 7 g)", cg="6 mm behind the face, 2 mm towards the heel and 2 mm low"),
    "7_iron": _ESTIMATE.format(
        what="a cavity-back 7-iron, 34 deg, lie 62.5 deg",
        moments="up 2650 (between Ping's 2400 and 3000), toe 820, target 3250 (plate, as for the 6-iron)",
        mass="268 g (Maltby: 254 g + 2 x 7 g)", cg="6 mm behind the face, 2 mm towards the heel and 2 mm low"),
    "pitching_wedge": _ESTIMATE.format(
        what="a cavity-back pitching wedge, 46 deg, lie 64 deg",
        moments="up 2800, toe 900, target 3500 (plate, as for the 6-iron; the wedge's head is taller)",
        mass="289 g (Maltby: 254 g + 5 x 7 g)", cg="5 mm behind the face, 2 mm towards the heel and 1 mm low"),
}


#: face width x height [mm] of each preset: estimates, not measurements (the irons' are the 75 x 45 mm plate of
#: their inertia estimate, the wedge's taller; the woods' those of typical 460 cm^3 and 3-wood faces, inside the
#: USGA's head limits of 127 x 71.12 mm). They bound where a strike may land (scene/plausibility.py).
FACE_SIZES = {"driver": (110.0, 60.0), "fairway_wood": (95.0, 40.0), "6_iron": (75.0, 45.0),
              "7_iron": (75.0, 45.0), "pitching_wedge": (75.0, 50.0)}
CLUB_SOURCES = {key: text + (f" Face {FACE_SIZES[key][0]:.0f} x {FACE_SIZES[key][1]:.0f} mm (heel-toe x sole-crown): "
                             "an estimate, used to refuse strikes off the face.")
                for key, text in CLUB_SOURCES.items()}


def _face(key):
    return {"face_width": FACE_SIZES[key][0] * MM, "face_height": FACE_SIZES[key][1] * MM}


def _iron(mass, moments, loft, lie, center, name, key):
    return ClubHead(mass=mass, inertia=tuple(m * G_CM2 for m in moments),
                    center_of_mass=tuple(c * MM for c in center), loft=math.radians(loft), lie=math.radians(lie),
                    material=MATERIAL_PRESETS["steel"], name=name, source=CLUB_SOURCES[key], **_face(key))


CLUB_PRESETS: dict[str, ClubHead] = {
    "driver": ClubHead(
        mass=DRIVER_2020["mass"], inertia=_driver_2020_tensor(),
        center_of_mass=tuple(c * MM for c in DRIVER_2020["center"]), loft=math.radians(9.8), lie=math.radians(58.0),
        bulge_radius=0.305, roll_radius=0.254, material=MATERIAL_PRESETS["titanium"],
        name="driver (measured head, 2020)", source=CLUB_SOURCES["driver"], restitution_gain=0.083, **_face("driver")),
    "fairway_wood": ClubHead(
        mass=0.212, inertia=tuple(m * G_CM2 for m in (1800.0, 3300.0, 1700.0)), center_of_mass=(0.0, -0.005, 0.025),
        loft=math.radians(15.0), lie=math.radians(57.0), bulge_radius=0.300, roll_radius=0.280,
        material=MATERIAL_PRESETS["steel"], name="3-wood (estimate)", source=CLUB_SOURCES["fairway_wood"],
        restitution_gain=0.083, **_face("fairway_wood")),
    "6_iron": _iron(0.261, (800.0, 2600.0, 3200.0), 30.0, 62.0, (-2.0, -2.0, 6.0), "6-iron (estimate)", "6_iron"),
    "7_iron": _iron(0.268, (820.0, 2650.0, 3250.0), 34.0, 62.5, (-2.0, -2.0, 6.0), "7-iron (estimate)", "7_iron"),
    "pitching_wedge": _iron(0.289, (900.0, 2800.0, 3500.0), 46.0, 64.0, (-2.0, -1.0, 5.0), "pitching wedge (estimate)",
                            "pitching_wedge"),
}


def club_preset(name: str) -> ClubHead:
    """The club-head preset called ``name``."""
    try:
        return CLUB_PRESETS[name]
    except (KeyError, TypeError):
        raise FieldError("preset", "a club preset name", name, choices=CLUB_PRESETS) from None
