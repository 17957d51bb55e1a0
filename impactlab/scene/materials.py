"""Ball, face and material value objects shared by every model, and presets.

All values are SI. Objects are frozen: a study sweep makes new objects
(``attrs.evolve``) rather than changing shared ones.
"""

from __future__ import annotations

import math

import attrs
import numpy as np
from numpy.typing import ArrayLike

from impactlab.validators import in_range, positive, positive_or_inf, to_float
from impactlab.errors import FieldError
from impactlab.units import si_inverse_speed, si_length, si_mass, si_pressure, si_speed
from impactlab.physics.friction_laws import shear_strength_from_sled

#: Largest possible I/(m R^2) of a sphere whose mass lies within its radius
#: (all mass in a thin shell at R).
MAX_INERTIA_FACTOR = 2.0 / 3.0


@attrs.frozen
class Material:
    """Isotropic linear-elastic material.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    youngs_modulus : float
        Young's modulus E [Pa], positive and finite.
    poisson_ratio : float
        Poisson's ratio nu [1], -1 < nu <= 0.5 (0.5: incompressible).
    name, source : str
        Label and where the numbers come from.
    """

    youngs_modulus: float = attrs.field(converter=si_pressure,
                                        validator=positive("a positive, finite modulus in Pa"))
    poisson_ratio: float = attrs.field(
        converter=to_float, validator=in_range(-1.0, 0.5, "a Poisson ratio with -1 < nu <= 0.5", low_open=True))
    name: str = ""
    source: str = ""

    @property
    def shear_modulus(self) -> float:
        """G = E / (2 (1 + nu)) [Pa]."""
        return self.youngs_modulus / (2.0 * (1.0 + self.poisson_ratio))


RESTITUTION_LAWS = ("constant", "linear", "power", "table")


def _tuple_of_floats(value):
    try:
        return tuple(float(x) for x in value)
    except (TypeError, ValueError):
        return value


@attrs.frozen
class RestitutionLaw:
    """Normal coefficient of restitution of a ball against a steel face as a function of the normal impact speed.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    kind : str
        ``constant``: e = value. ``linear``: e = value + slope (v - reference_speed). ``power``:
        e = value (v / reference_speed)^(-exponent). ``table``: linear interpolation in ``speeds``/``values``,
        constant beyond the ends. Every law is clipped to [0.05, 1].
    value : float
        e at ``reference_speed`` [1].
    reference_speed : float
        Normal speed where e = value [m/s].
    slope : float
        de/dv of the linear law [s/m].
    exponent : float
        Exponent of the power law [1].
    speeds, values : tuple of float
        The table: increasing normal speeds [m/s] and e there.
    source : str
        Where the law and its numbers come from (measurement, fit, and to what).
    """

    kind: str = attrs.field(default="constant", validator=attrs.validators.in_(RESTITUTION_LAWS))
    value: float = attrs.field(default=0.8, converter=to_float,
                               validator=in_range(0.0, 1.0, "a coefficient of restitution 0 <= e <= 1"))
    reference_speed: float = attrs.field(default=40.0, converter=si_speed,
                                         validator=positive("a positive reference speed in m/s"))
    slope: float = attrs.field(default=0.0, converter=si_inverse_speed, validator=in_range(
        -1.0, 1.0, "a slope de/dv within +-1 s/m"))
    exponent: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        -2.0, 2.0, "an exponent within +-2"))
    speeds: tuple = attrs.field(default=(), converter=_tuple_of_floats)
    values: tuple = attrs.field(default=(), converter=_tuple_of_floats)
    source: str = ""

    def __attrs_post_init__(self):
        if self.kind == "table":
            speeds, values = np.asarray(self.speeds, float), np.asarray(self.values, float)
            if speeds.size < 2 or speeds.shape != values.shape or np.any(np.diff(speeds) <= 0) \
                    or np.any(speeds < 0) or np.any((values < 0) | (values > 1)):
                raise FieldError("restitution", "a table of at least two increasing speeds [m/s] and as many "
                                 "restitutions in [0, 1]", f"speeds {self.speeds}, values {self.values}")

    def __call__(self, normal_speed: ArrayLike) -> np.ndarray:
        """e at the normal approach speed(s) [m/s]."""
        v = np.asarray(normal_speed, dtype=float)
        if self.kind == "constant":
            e = np.full_like(v, self.value)
        elif self.kind == "linear":
            e = self.value + self.slope * (v - self.reference_speed)
        elif self.kind == "power":
            e = self.value * (np.maximum(v, 1e-9) / self.reference_speed) ** (-self.exponent)
        else:
            e = np.interp(v, self.speeds, self.values)
        return np.clip(e, 0.05, 1.0)


@attrs.frozen
class Ball:
    """A sphere: radius R [m], mass m [kg], inertia factor K^2 = I/(m R^2) and, for compliant models, its material.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).
    """

    radius: float = attrs.field(converter=si_length, validator=positive("a positive, finite radius in m"))
    mass: float = attrs.field(converter=si_mass, validator=positive("a positive, finite mass in kg"))
    inertia_factor: float = attrs.field(
        default=0.4, converter=to_float,
        validator=in_range(0.0, MAX_INERTIA_FACTOR,
                           "an inertia factor I/(m R^2) with 0 < K^2 <= 2/3 (0.4 = uniform solid sphere)",
                           low_open=True))
    material: Material | None = None
    name: str = ""
    source: str = ""
    #: contact data against a steel face, used where the study's contact block leaves them out
    friction: float | None = attrs.field(default=None, converter=to_float, validator=in_range(
        0.0, math.inf, "a friction coefficient >= 0", high_open=True, optional=True))
    restitution: RestitutionLaw | None = None
    #: loss factor (tan delta) of the ball's cover in tangential shear; 0: elastic (the paper's model)
    tangential_loss: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        0.0, 2.0, "a loss factor 0 <= eta <= 2"))
    #: the cover as the friction law sees it (impactlab.physics.friction_laws; None: not given): the interfacial
    #: shear strength tau of cover and face [Pa], the cover's Young's modulus [Pa], the rise of the interface's
    #: temperature at which the cover melts [K] (inf: it does not) and its thermal effusivity [J m^-2 K^-1 s^-1/2]
    shear_strength: float | None = attrs.field(default=None, converter=si_pressure, validator=in_range(
        0.0, 1e9, "an interfacial shear strength in Pa between 0 and 1 GPa", high_open=True, optional=True))
    cover_modulus: float | None = attrs.field(default=None, converter=si_pressure, validator=in_range(
        1e6, 1e10, "a cover Young's modulus in Pa between 1 MPa and 10 GPa", optional=True))
    cover_melt_rise: float | None = attrs.field(default=None, converter=to_float, validator=in_range(
        0.0, math.inf, "a temperature rise in K > 0 (inf: the cover does not melt)", low_open=True, optional=True))
    cover_effusivity: float | None = attrs.field(default=None, converter=to_float, validator=in_range(
        0.0, math.inf, "a thermal effusivity sqrt(k rho c) > 0 in J m^-2 K^-1 s^-1/2", low_open=True,
        high_open=True, optional=True))

    @property
    def moment_of_inertia(self) -> float:
        """I = K^2 m R^2 [kg m^2]."""
        return self.inertia_factor * self.mass * self.radius**2


@attrs.frozen
class FaceSurface:
    """The face's surface as the friction law sees it (:mod:`impactlab.physics.friction_laws`).

    Parameters
    ----------
    roughness_slope : float
        r.m.s. slope s of the face's texture [1]; 0: smooth (the real contact area is the Hertz area).
    roughness : float
        r.m.s. roughness R_q [m]: a water film thinner than it no longer separates cover and face.
    groove_land : float
        Half the land between grooves, the distance water drains to a groove [m]; inf: no grooves.
    water_film : float
        Water on the face before impact [m]; 0: dry.
    effusivity : float
        Thermal effusivity sqrt(k rho c) of the face's material [J m^-2 K^-1 s^-1/2].
    """

    roughness_slope: float = attrs.field(default=0.0, converter=to_float, validator=in_range(
        0.0, 2.0, "an r.m.s. slope 0 <= s <= 2"))
    roughness: float = attrs.field(default=0.0, converter=si_length, validator=in_range(
        0.0, 1e-3, "an r.m.s. roughness in m between 0 and 1 mm"))
    groove_land: float = attrs.field(default=math.inf, converter=si_length, validator=in_range(
        0.0, math.inf, "half a groove land in m > 0 (inf: no grooves)", low_open=True))
    water_film: float = attrs.field(default=0.0, converter=si_length, validator=in_range(
        0.0, 1e-3, "a water film in m between 0 and 1 mm"))
    effusivity: float = attrs.field(default=8000.0, converter=to_float, validator=in_range(
        0.0, math.inf, "a thermal effusivity > 0", low_open=True, high_open=True))
    name: str = ""
    source: str = ""


_EFFUSIVITY = ("Thermal effusivity sqrt(k rho c) from typical handbook values ({what}), not measured on a club.")
_SLOPE = ("The r.m.s. slope of a blasted or milled wedge face is not published; s = 0.2 is an assumption (docs/"
          "models.md shows 0.1 and 0.4).")
#: face surfaces by kind of club (:class:`FaceSurface`)
FACE_SURFACES: dict[str, FaceSurface] = {
    "grooved_blasted_steel": FaceSurface(
        0.2, 5.7e-6, 1.35e-3, 0.0, 8030.0, "grooved, blasted steel iron face",
        "Grooves: the Rules' limits, width <= 0.9 mm and edges >= 3 widths apart, give a land of 2.7 mm (half 1.35 mm; "
        "USGA Equipment Rules, Part 2, 5c). Roughness: the Rules allow no more than decorative sandblasting or fine "
        "milling (Part 2, 5b); R_q 5.7 um is R_a 4.57 um (180 microinch, the figure usually quoted for that limit; "
        "not found in the stored text) times 1.25 (a Gaussian surface). " + _SLOPE + " "
        + _EFFUSIVITY.format(what="17-4PH: k 18 W/m K, rho 7800 kg/m^3, c 460 J/kg K")),
    "smooth_titanium": FaceSurface(
        0.0, 0.4e-6, math.inf, 0.0, 3950.0, "smooth titanium driver face",
        "A driver face taken as smooth (s = 0: the real contact area is the Hertz area) and without grooves; R_q "
        "0.4 um assumed. " + _EFFUSIVITY.format(what="Ti-6Al-4V: k 6.7 W/m K, rho 4430 kg/m^3, c 526 J/kg K")),
    "smooth_steel": FaceSurface(
        0.0, 0.4e-6, math.inf, 0.0, 8030.0, "smooth steel wood face",
        "A fairway-wood face taken as smooth and without grooves; R_q 0.4 um assumed. "
        + _EFFUSIVITY.format(what="17-4PH: k 18 W/m K, rho 7800 kg/m^3, c 460 J/kg K")),
}


@attrs.frozen
class Face:
    """The striking face: a material, or rigid; and the club-head mass behind it.

    Physical values are SI floats; a bare number given is read as SI (angles in rad, spin in rad/s), and a string
    with a unit (``"45.93 g"``) or a pint quantity is converted (the ``si_*`` converters of :mod:`impactlab.units`).

    Parameters
    ----------
    material : Material, optional
        Elastic face. Leave out for a rigid face or for models that need none.
    rigid : bool
        True for a face that does not deform; excludes ``material``.
    mass : float
        Club-head mass M [kg]; ``inf`` (default) for a face fixed in space.
    surface : FaceSurface, optional
        Texture, grooves, water and effusivity for the friction law (:data:`FACE_SURFACES`).
    """

    material: Material | None = None
    rigid: bool = attrs.field(default=False, validator=attrs.validators.instance_of(bool))
    mass: float = attrs.field(default=math.inf, converter=si_mass,
                              validator=positive_or_inf("a positive club-head mass in kg (inf: a fixed face)"))
    name: str = ""
    source: str = ""
    #: the surface the friction law reads (None: not given; the law then refuses the face, never smooth and dry)
    surface: FaceSurface | None = None

    def __attrs_post_init__(self):
        if self.rigid and self.material is not None:
            raise FieldError("rigid", "either rigid: true or a face material, not both", "rigid: true with a material")


_BALL_SOURCE = ("Size and mass at the Rules of Golf limits (R >= 21.335 mm, m <= 45.93 g). Ball moduli are not "
                "published; {E} with nu = {nu} puts the Hertz contact time against a steel face near the "
                "450-500 us measured at club speeds (Henrikson et al. 2020, physics brief section 1). K^2 = 0.4: a "
                "multi-layer ball is close to a uniform sphere.")

MATERIAL_PRESETS: dict[str, Material] = {
    "urethane_cover": Material(136e6, 0.45, "urethane-cover ball (equivalent)",
                               _BALL_SOURCE.format(E="E = 136 MPa", nu=0.45)),
    "surlyn_cover": Material(160e6, 0.45, "surlyn-cover ball (equivalent)",
                             _BALL_SOURCE.format(E="E = 160 MPa (a firmer, distance ball)", nu=0.45)),
    "steel": Material(196e9, 0.272, "17-4PH stainless steel",
                      "Typical handbook values for 17-4PH (H900): E = 196 GPa, nu = 0.272 (ASM handbook)."),
    "titanium": Material(113.8e9, 0.342, "Ti-6Al-4V",
                         "Typical handbook values for annealed Ti-6Al-4V: E = 113.8 GPa, nu = 0.342 (ASM handbook)."),
}

_BALL_INERTIA = ("Inertia: a measured ball, I = 83.63 g cm^2 with m = 45.9 g (Proceedings 49 (2020) 47, Table 1, "
                 "measurement), K^2 = I/(m R^2) = 0.400 at R = 21.335 mm.")
_SLED = ("Friction {mu}: Henrikson et al. (2020), section 2.2, a sled of three {cover}-covered balls pulled over a "
         "grooved, blasted iron-type plate (measurement, at loads far below an impact's).")
#: the ball restitution fitted to TrackMan's tour averages with the club presets (impactlab fit trackman_tour;
#: docs/validation.md): maw 0.788 +- 0.013, hertz_mindlin 0.787 +- 0.011 at a normal speed of 40 m/s
FITTED_RESTITUTION = RestitutionLaw(
    "linear", 0.787, 40.0, slope=0.0,
    source="fitted (impactlab fit trackman_tour, models maw and hertz_mindlin agree to 0.001) to TrackMan's PGA and "
           "LPGA driver and 6-iron averages with the driver's face gain fitted beside it; a model output, not a "
           "measurement of e. The slope is not identified by four deliveries (two normal speeds per club) and "
           "is left at 0.")
_FITTED = ("Restitution: e = 0.787 at any normal speed against a rigid steel face, fitted to TrackMan's tour averages "
           "(docs/validation.md). Tangential loss 0: the same fit leaves it unidentified (0.08 +- 0.25 with "
           "hertz_mindlin), so the paper's elastic cover is kept.")

#: the covers as the friction law sees them: Young's modulus [Pa] (datasheet, 23 degC, quasi-static), melting
#: point's rise above 20 degC [K] and thermal effusivity [J m^-2 K^-1 s^-1/2]; tau from the sled (below)
_COVERS = {
    "urethane": (68.9e6, math.inf, 657.0,
                 "Cover modulus 68.9 MPa: flexural modulus of a Shore D 43 thermoplastic urethane (Texin 245 "
                 "datasheet, 9990 psi at 73 degF; urethane covers are Shore D 40-53, physics_lit 5.5), a "
                 "representative cover material, not the ball's measured cover. Melting: none (the Pro V1's "
                 "cover is cast thermoset urethane that 'will not re-melt', Titleist Learning Lab, 'Surlyn and "
                 "urethane in golf balls', titleist.com; a thermoplastic urethane cover would soften from its "
                 "Vicat point, 104 degC for Estane 2103-55D). Effusivity from typical TPU values (k 0.2 W/m K, "
                 "rho 1200 kg/m^3, c 1800 J/kg K)."),
    "ionomer": (330e6, 66.0, 718.0,
                "Cover modulus 330 MPa: flexural modulus of Surlyn 9910, a zinc ionomer the datasheet names for golf "
                "ball covers (73 degF; 731 MPa at -4 degF); melting point 86 degC (DSC, same datasheet), 66 K above "
                "20 degC. Effusivity from its density 970 kg/m^3 and typical ionomer k 0.24 W/m K, c 2200 J/kg K."),
}
#: the face texture the sled's grooved, blasted plate is taken to have (FACE_SURFACES' iron face)
_SLED_SLOPE = 0.2


def _cover(kind: str, sled_friction: float, poisson: float) -> dict:
    """The friction law's fields of a ball with this cover: tau from the sled friction (friction_laws)."""
    modulus, melt, effusivity, _ = _COVERS[kind]
    tau = shear_strength_from_sled(sled_friction, modulus, poisson, _SLED_SLOPE, FITTED_RESTITUTION.value)
    return {"shear_strength": tau, "cover_modulus": modulus, "cover_melt_rise": melt,
            "cover_effusivity": effusivity}


_TAU = ("Interfacial shear strength from the sled friction {mu} by the friction law's light-load limit, tau = "
        "(mu - (3/16)(1 - e^2) s) E_c* s / sqrt(8/pi) with the plate's slope s = 0.2 (assumed; "
        "impactlab.physics.friction_laws.shear_strength_from_sled): {tau:.2f} MPa, fitted on the sled, not on "
        "impact data.")

BALL_PRESETS: dict[str, Ball] = {
    # the tour urethane ball with its contact data against a steel face (a study may leave out contact:; a
    # study's contact: block overrides them)
    "urethane_tour": Ball(0.021335, 0.04593, 0.400, MATERIAL_PRESETS["urethane_cover"],
                          "urethane tour ball (calibrated contact data)",
                          " ".join([MATERIAL_PRESETS["urethane_cover"].source, _BALL_INERTIA,
                                    _SLED.format(mu=0.40, cover="urethane"), _FITTED, _COVERS["urethane"][3],
                                    _TAU.format(mu=0.40, tau=_cover("urethane", 0.40, 0.45)["shear_strength"] / 1e6)]),
                          friction=0.40, restitution=FITTED_RESTITUTION, tangential_loss=0.0,
                          **_cover("urethane", 0.40, 0.45)),
    "surlyn_distance": Ball(0.021335, 0.04593, 0.4, MATERIAL_PRESETS["surlyn_cover"], "surlyn distance ball",
                            MATERIAL_PRESETS["surlyn_cover"].source),
    "two_piece_ionomer": Ball(0.021335, 0.04593, 0.400, MATERIAL_PRESETS["surlyn_cover"],
                              "two-piece ionomer ball (contact data partly assumed)",
                              " ".join([MATERIAL_PRESETS["surlyn_cover"].source, _BALL_INERTIA,
                                        _SLED.format(mu=0.35, cover="surlyn"),
                                        "Restitution: no shot data of this ball with a stated delivery were found; "
                                        "the tour urethane ball's fitted e = 0.787 is taken (an assumption). "
                                        "Tangential loss 0.", _COVERS["ionomer"][3],
                                        _TAU.format(mu=0.35, tau=_cover("ionomer", 0.35, 0.45)["shear_strength"]
                                                    / 1e6)]),
                              friction=0.35, restitution=FITTED_RESTITUTION, tangential_loss=0.0,
                              **_cover("ionomer", 0.35, 0.45)),
}

FACE_PRESETS: dict[str, Face] = {
    "rigid": Face(rigid=True, name="rigid face", source="Idealisation: the face does not deform."),
    "steel": Face(MATERIAL_PRESETS["steel"], name="steel face", source=MATERIAL_PRESETS["steel"].source),
    "titanium": Face(MATERIAL_PRESETS["titanium"], name="titanium face", source=MATERIAL_PRESETS["titanium"].source),
}


#: former names of ball presets -> the one name kept (a note says so when one is used)
BALL_ALIASES: dict[str, str] = {
    # two presets of one ball, 'urethane_tour' (no contact data) and 'tour_urethane' (with the calibrated contact
    # data), were merged into 'urethane_tour' with the contact data: a study's contact: block still overrides them
    "tour_urethane": "urethane_tour",
}


class PresetAliasNote(UserWarning):
    """A preset was named by a former name: the preset it now stands for is used, and the note says which."""


def ball_preset(name: str) -> Ball:
    """The ball preset called ``name`` (a former name in :data:`BALL_ALIASES` gives its preset, with a note)."""
    if isinstance(name, str) and name in BALL_ALIASES:
        import warnings

        kept = BALL_ALIASES[name]
        warnings.warn(f"ball preset {name!r} is a former name of {kept!r} (the same ball with its calibrated "
                      f"contact data); write {kept!r}", PresetAliasNote, stacklevel=2)
        name = kept
    try:
        return BALL_PRESETS[name]
    except (KeyError, TypeError):
        raise FieldError("preset", "a ball preset name", name, choices=BALL_PRESETS) from None


def face_preset(name: str) -> Face:
    """The face preset called ``name``."""
    try:
        return FACE_PRESETS[name]
    except (KeyError, TypeError):
        raise FieldError("preset", "a face preset name", name, choices=FACE_PRESETS) from None


#: the fields of a :class:`FaceSurface` a study or a club spec sheet may give
SURFACE_FIELDS = ("roughness_slope", "roughness", "groove_land", "water_film", "effusivity")
#: what a surface given without a preset to start from must say (left out, water_film is 0: a dry face)
SURFACE_REQUIRED = ("roughness_slope", "roughness", "groove_land", "effusivity")


def face_surface(preset: str | None, fields: dict, base: FaceSurface | None = None, where: str = "surface",
                 preset_path: str | None = None) -> FaceSurface:
    """A face's surface for the friction law: a preset of :data:`FACE_SURFACES` (or ``base``, the club preset's
    own), with the fields given over it.

    Parameters
    ----------
    preset : str or None
        A name of :data:`FACE_SURFACES`; None: start from ``base``.
    fields : dict
        Fields of :data:`SURFACE_FIELDS` in SI (roughness, groove_land and water_film [m], effusivity
        [J m^-2 K^-1 s^-1/2], roughness_slope [1]) that replace the preset's.
    base : FaceSurface, optional
        The surface the club already has (a club preset's). Without it or a preset, every field of
        :data:`SURFACE_REQUIRED` must be given: a smooth or dry face is never assumed.
    where, preset_path : str
        Paths of the surface and of its preset name for error messages.

    Raises
    ------
    FieldError
        An unknown preset, a missing field, or a value out of its range.
    """
    if preset is not None:
        if not isinstance(preset, str) or preset not in FACE_SURFACES:
            raise FieldError(preset_path or f"{where}.preset", "a face surface preset", preset, choices=FACE_SURFACES)
        base = FACE_SURFACES[preset]
    if base is None:
        missing = [key for key in SURFACE_REQUIRED if key not in fields]
        if missing:
            raise FieldError(f"{where}.{missing[0]}", f"the face's {missing[0]} (or a surface preset: "
                             f"{', '.join(FACE_SURFACES)}), with its unit", "nothing")
        base = FaceSurface(name="a surface given in full", source="given in the study or spec sheet")
    if not fields:
        return base
    given = "; ".join(f"{key} {value:g}" for key, value in fields.items())
    try:
        return attrs.evolve(base, **fields, source=f"{base.source} Given over it (SI): {given}.".strip())
    except FieldError as exc:
        raise exc.at(prefix=where) from None


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["MAX_INERTIA_FACTOR", "Material", "RESTITUTION_LAWS", "RestitutionLaw", "Ball", "FaceSurface",
           "FACE_SURFACES", "Face", "MATERIAL_PRESETS", "FITTED_RESTITUTION", "BALL_PRESETS", "FACE_PRESETS",
           "BALL_ALIASES", "PresetAliasNote", "ball_preset", "face_preset", "SURFACE_FIELDS", "SURFACE_REQUIRED",
           "face_surface"]
