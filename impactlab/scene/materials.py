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

    @property
    def moment_of_inertia(self) -> float:
        """I = K^2 m R^2 [kg m^2]."""
        return self.inertia_factor * self.mass * self.radius**2


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
    """

    material: Material | None = None
    rigid: bool = attrs.field(default=False, validator=attrs.validators.instance_of(bool))
    mass: float = attrs.field(default=math.inf, converter=si_mass,
                              validator=positive_or_inf("a positive club-head mass in kg (inf: a fixed face)"))
    name: str = ""
    source: str = ""

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

BALL_PRESETS: dict[str, Ball] = {
    # the tour urethane ball with its contact data against a steel face (a study may leave out contact:; a
    # study's contact: block overrides them)
    "urethane_tour": Ball(0.021335, 0.04593, 0.400, MATERIAL_PRESETS["urethane_cover"],
                          "urethane tour ball (calibrated contact data)",
                          " ".join([MATERIAL_PRESETS["urethane_cover"].source, _BALL_INERTIA,
                                    _SLED.format(mu=0.40, cover="urethane"), _FITTED]),
                          friction=0.40, restitution=FITTED_RESTITUTION, tangential_loss=0.0),
    "surlyn_distance": Ball(0.021335, 0.04593, 0.4, MATERIAL_PRESETS["surlyn_cover"], "surlyn distance ball",
                            MATERIAL_PRESETS["surlyn_cover"].source),
    "two_piece_ionomer": Ball(0.021335, 0.04593, 0.400, MATERIAL_PRESETS["surlyn_cover"],
                              "two-piece ionomer ball (contact data partly assumed)",
                              " ".join([MATERIAL_PRESETS["surlyn_cover"].source, _BALL_INERTIA,
                                        _SLED.format(mu=0.35, cover="surlyn"),
                                        "Restitution: no shot data of this ball with a stated delivery were found; "
                                        "the tour urethane ball's fitted e = 0.787 is taken (an assumption). "
                                        "Tangential loss 0."]),
                              friction=0.35, restitution=FITTED_RESTITUTION, tangential_loss=0.0),
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
