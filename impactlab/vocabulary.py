"""One vocabulary for what models take and what they give.

Inputs are per-scene SI values handed to models. Outputs are what results
hold: each name has one unit, one long name and one shape everywhere in
impactlab (model hooks, datasets, HDF5 files, plots, docs).

Sign conventions (face frame, see docs/conventions.md): ``x`` lies in the
face along the incoming slip of the contact point at a positive angle (a ball
without spin; up a lofted face), fixed by the geometry: at a negative angle the
slip runs along -x and the tangential outputs change sign; ``z`` is the face
normal pointing away from the face. Backspin (the spin friction gives a ball sliding
up a lofted face) is positive.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import Any

import attrs

from impactlab.units import DIMENSIONS, RAD_TO_DEG, RADS_TO_RPM, registry, to_si
from impactlab.validators import inside
from impactlab.errors import FieldError

SCALAR = "scalar"
HISTORY = "history"


@attrs.frozen
class InputSpec:
    """A model input: its study path, SI unit, physical dimension and description."""

    path: str
    unit: str
    dimension: str
    description: str
    getter: Callable[[Any], float | None] = attrs.field(repr=False)
    #: unit and factor of a sweep coordinate in a dataset (angles in deg, spin in rpm)
    display_unit: str = ""
    display_factor: float = 1.0
    #: allowed SI range, for inputs handed over as arrays rather than built from validated objects
    low: float = -math.inf
    high: float = math.inf
    low_open: bool = False
    high_open: bool = False

    def out_of_range(self, values: Any) -> Any:
        """Boolean mask of the values outside the allowed range (NaN counts as outside)."""
        return ~inside(values, self.low, self.high, self.low_open, self.high_open)

    def range_text(self) -> str:
        """The admissible range in words, for error messages: 'a value in (0, inf) m/s'."""
        left = "(" if self.low_open else "["
        right = ")" if self.high_open else "]"
        return f"a value in {left}{self.low:g}, {self.high:g}{right} {self.unit}"


def _material_value(part: str, attribute: str):
    def getter(scene):
        holder = getattr(scene, part)
        if part == "face" and holder.rigid:
            # A rigid face has no compliance term: 1/E* loses its (1 - nu^2)/E part whatever nu is.
            return math.inf if attribute == "youngs_modulus" else 0.0
        material = holder.material
        return None if material is None else getattr(material, attribute)

    return getter


def _attr(part: str, attribute: str):
    return lambda scene: getattr(getattr(scene, part), attribute)


def _surface_value(attribute: str):
    def getter(scene):
        surface = getattr(scene.face, "surface", None)
        return None if surface is None else getattr(surface, attribute)

    return getter


INPUTS: dict[str, InputSpec] = {
    "ball_radius": InputSpec("ball.radius", "m", "length", "ball radius R", _attr("ball", "radius"), low=0.0,
                             low_open=True, high_open=True),
    "ball_mass": InputSpec("ball.mass", "kg", "mass", "ball mass m", _attr("ball", "mass"), low=0.0, low_open=True,
                           high_open=True),
    "ball_inertia_factor": InputSpec("ball.inertia_factor", "1", "dimensionless",
                                     "ball inertia factor K^2 = I/(m R^2)", _attr("ball", "inertia_factor"), low=0.0,
                                     high=2.0 / 3.0, low_open=True),
    "ball_youngs_modulus": InputSpec("ball.youngs_modulus", "Pa", "pressure", "ball Young's modulus",
                                     _material_value("ball", "youngs_modulus"), low=0.0, low_open=True,
                                     high_open=True),
    "ball_poisson_ratio": InputSpec("ball.poisson_ratio", "1", "dimensionless", "ball Poisson's ratio",
                                    _material_value("ball", "poisson_ratio"), low=-1.0, high=0.5, low_open=True),
    "face_youngs_modulus": InputSpec("face.youngs_modulus", "Pa", "pressure",
                                     "face Young's modulus (inf for a rigid face)",
                                     _material_value("face", "youngs_modulus"), low=0.0, low_open=True),
    "face_poisson_ratio": InputSpec("face.poisson_ratio", "1", "dimensionless",
                                    "face Poisson's ratio (0 for a rigid face, where it has no effect)",
                                    _material_value("face", "poisson_ratio"), low=-1.0, high=0.5, low_open=True),
    "club_mass": InputSpec("face.mass", "kg", "mass", "club-head mass M (inf: fixed face)", _attr("face", "mass"),
                           low=0.0, low_open=True),
    "friction": InputSpec("contact.friction", "1", "dimensionless", "Coulomb friction coefficient mu",
                          lambda scene: scene.contact.friction if scene.contact.friction is not None
                          else scene.ball.friction, low=0.0, high_open=True),
    "restitution": InputSpec("contact.restitution", "1", "dimensionless", "normal coefficient of restitution e",
                             _attr("contact", "restitution"), low=0.0, high=1.0),
    "tangential_loss": InputSpec("ball.tangential_loss", "1", "dimensionless",
                                 "loss factor of the ball's cover in tangential shear (0: elastic)",
                                 _attr("ball", "tangential_loss"), low=0.0, high=2.0),
    # the friction law's inputs (impactlab.physics.friction_laws): the cover's and the face surface's
    "ball_shear_strength": InputSpec("ball.shear_strength", "Pa", "pressure",
                                     "interfacial shear strength tau of the ball's cover on the face",
                                     _attr("ball", "shear_strength"), low=0.0, high_open=True),
    "ball_cover_modulus": InputSpec("ball.cover_modulus", "Pa", "pressure", "Young's modulus of the ball's cover",
                                    _attr("ball", "cover_modulus"), low=0.0, low_open=True, high_open=True),
    "ball_cover_melt_rise": InputSpec("ball.cover_melt_rise", "K", "temperature",
                                      "rise of the interface's temperature at which the cover melts (inf: never)",
                                      _attr("ball", "cover_melt_rise"), low=0.0, low_open=True),
    "ball_cover_effusivity": InputSpec("ball.cover_effusivity", "J m-2 K-1 s-1/2", "dimensionless",
                                       "thermal effusivity sqrt(k rho c) of the ball's cover",
                                       _attr("ball", "cover_effusivity"), low=0.0, low_open=True, high_open=True),
    "face_roughness_slope": InputSpec("face.surface.roughness_slope", "1", "dimensionless",
                                      "r.m.s. slope of the face's texture (0: smooth)",
                                      _surface_value("roughness_slope"), low=0.0, high=2.0),
    "face_roughness": InputSpec("face.surface.roughness", "m", "length", "r.m.s. roughness of the face",
                                _surface_value("roughness"), low=0.0, high=1e-3),
    "face_groove_land": InputSpec("face.surface.groove_land", "m", "length",
                                  "half the land between grooves, where water drains (inf: no grooves)",
                                  _surface_value("groove_land"), low=0.0, low_open=True),
    "face_water_film": InputSpec("face.surface.water_film", "m", "length", "water film on the face (0: dry)",
                                 _surface_value("water_film"), low=0.0, high=1e-3),
    "face_effusivity": InputSpec("face.surface.effusivity", "J m-2 K-1 s-1/2", "effusivity",
                                 "thermal effusivity sqrt(k rho c) of the face", _surface_value("effusivity"),
                                 low=0.0, low_open=True, high_open=True),
    "speed": InputSpec("impact.speed", "m/s", "speed", "impact speed V along the path", _attr("impact", "speed"),
                       low=0.0, low_open=True, high_open=True),
    "angle": InputSpec("impact.angle", "rad", "angle", "face normal relative to path alpha",
                       _attr("impact", "angle"), "degree", RAD_TO_DEG, low=-math.pi / 2, high=math.pi / 2,
                       low_open=True, high_open=True),
    "spin": InputSpec("impact.spin", "rad/s", "angular_speed",
                      "incoming spin, counted like spin_rate (positive: the backspin a lofted face gives; topspin "
                      "about the flight of a ball arriving at a plate)",
                      _attr("impact", "spin"), "rpm", RADS_TO_RPM, low_open=True, high_open=True),
    "club_spin": InputSpec("impact.club_spin", "rad/s", "angular_speed",
                           "incoming spin of the striking body about the ball's spin axis (a sphere striker)",
                           _attr("impact", "club_spin"), "rpm", RADS_TO_RPM, low_open=True, high_open=True),
}



def _delivery_value(attribute: str):
    def getter(scene):
        delivery = scene.delivery
        if delivery is None:
            return None
        return delivery.sign if attribute == "handedness" else getattr(delivery, attribute)

    return getter


def _conditions_value(attribute: str):
    def getter(scene):
        conditions = getattr(scene, "conditions", None)
        return None if conditions is None else getattr(conditions, attribute)

    return getter


_HALF_TURN: dict[str, Any] = dict(low=-math.pi / 2, high=math.pi / 2, low_open=True, high_open=True)
INPUTS.update({
    "path": InputSpec("delivery.path", "rad", "angle", "club path, horizontal, in-to-out positive",
                      _delivery_value("path"), "degree", RAD_TO_DEG, **_HALF_TURN),
    "face_angle": InputSpec("delivery.face_angle", "rad", "angle", "face angle, horizontal, open positive",
                            _delivery_value("face_angle"), "degree", RAD_TO_DEG, **_HALF_TURN),
    "attack_angle": InputSpec("delivery.attack_angle", "rad", "angle", "attack angle, upwards positive",
                              _delivery_value("attack_angle"), "degree", RAD_TO_DEG, **_HALF_TURN),
    "dynamic_loft": InputSpec("delivery.dynamic_loft", "rad", "angle", "dynamic loft of the face normal",
                              _delivery_value("dynamic_loft"), "degree", RAD_TO_DEG, **_HALF_TURN),
    "handedness": InputSpec("delivery.handedness", "1", "dimensionless", "+1 right-handed golfer, -1 left-handed",
                            _delivery_value("handedness"), low=-1.0, high=1.0),
    "loft_at_contact": InputSpec(
        "delivery.loft_at", "1", "dimensionless",
        "1: dynamic loft and face angle are the face's at the contact point (loft_at: contact, as launch monitors "
        "report them); 0: at the face centre (loft_at: centre)",
        lambda scene: None if scene.delivery is None else float(scene.delivery.loft_at == "contact"),
        low=0.0, high=1.0),
    "club_reference": InputSpec(
        "delivery.club_reference", "1", "dimensionless",
        "the point of the head the club speed, path and attack angle belong to: 0 centre of mass, 1 face centre, "
        "2 contact point (physics.contact.CLUB_REFERENCES)",
        lambda scene: None if scene.delivery is None else float(scene.delivery.reference_code),
        low=0.0, high=2.0),
})
for _index, (_key, _words) in enumerate((("toe", "about the head's toe axis (+: the face turns upwards, adding loft)"),
                                         ("up", "about the head's up axis (+: the face closes)"),
                                         ("target", "about the head's target axis (+: the toe moves down)"))):
    INPUTS[f"head_rotation_{_key}"] = InputSpec(
        f"delivery.head_rotation.{_key}", "rad/s", "angular_speed",
        f"angular velocity of the club head at first contact, {_words}",
        (lambda index: lambda scene: None if scene.delivery is None or scene.club is None
         else scene.delivery.head_rotation[index])(_index),
        "deg/s", RAD_TO_DEG, low_open=True, high_open=True)


def _club_value(attribute: str, index: int | str | None = None):
    def getter(scene):
        club = getattr(scene, "club", None)
        if club is None:
            return None
        value = getattr(club, attribute)
        if attribute == "inertia":
            return club.inertia_components()[index]
        return value if index is None else value[index]

    return getter


def _strike_value(attribute: str):
    def getter(scene):
        strike = getattr(scene, "strike", None)
        return None if strike is None or getattr(scene, "club", None) is None else getattr(strike, attribute)

    return getter


_INERTIA_WORDS = {"toe": "about the heel-toe axis", "up": "about the vertical axis", "target": "about the target axis"}
for _component in ("toe", "up", "target", "toe_up", "toe_target", "up_target"):
    _a, _, _b = _component.partition("_")
    _words = _INERTIA_WORDS[_a] if not _b else f"product of inertia {_a}-{_b} (tensor component)"
    INPUTS[f"club_inertia_{_component}"] = InputSpec(
        f"club.inertia.{_component}", "kg m^2", "inertia", f"club-head inertia about its centre of mass, {_words}",
        _club_value("inertia", _component), low=-math.inf, high_open=True, low_open=True)
for _index, (_key, _words) in enumerate((("toe", "towards the toe"), ("high", "up the face"),
                                         ("depth", "behind the face"))):
    INPUTS[f"club_cg_{_key}"] = InputSpec(
        f"club.center_of_mass.{_key}", "m", "length", f"club-head centre of mass from the face centre, {_words}",
        _club_value("center_of_mass", _index), "mm", 1e3, low_open=True, high_open=True)
INPUTS.update({
    "club_loft": InputSpec("club.loft", "rad", "angle", "static loft of the club head", _club_value("loft"), "degree",
                           RAD_TO_DEG, low=0.0, high=math.pi / 2, high_open=True),
    "face_bulge_radius": InputSpec("club.bulge_radius", "m", "length", "face bulge radius (heel to toe; inf: flat)",
                                   _club_value("bulge_radius"), "mm", 1e3, low=0.0, low_open=True),
    "face_roll_radius": InputSpec("club.roll_radius", "m", "length", "face roll radius (sole to crown; inf: flat)",
                                  _club_value("roll_radius"), "mm", 1e3, low=0.0, low_open=True),
    "club_restitution_gain": InputSpec(
        "club.restitution_gain", "1", "dimensionless",
        "rise of the restitution over the ball's law from the face's spring-like effect (0: rigid face)",
        _club_value("restitution_gain"), low=0.0, high=0.2),
    "strike_toe": InputSpec("strike.toe", "m", "length", "impact point from the face centre towards the toe",
                            _strike_value("toe"), "mm", 1e3, low=-0.1, high=0.1, low_open=True, high_open=True),
    "strike_high": InputSpec("strike.high", "m", "length", "impact point from the face centre up the face",
                             _strike_value("high"), "mm", 1e3, low=-0.1, high=0.1, low_open=True, high_open=True),
})

# the air a golf shot flies through (a study's ``conditions`` block; impactlab.scene.flight.Conditions): used only by
# the ball flight, which only a study asking for a flight output computes
INPUTS.update({
    "air_temperature": InputSpec("conditions.temperature", "K", "temperature", "air temperature",
                                 _conditions_value("temperature"), low=150.0, high=350.0),
    "air_pressure": InputSpec("conditions.pressure", "Pa", "pressure",
                              "station air pressure (absent: the ISA pressure at the altitude)",
                              _conditions_value("pressure"), low=0.0, low_open=True, high=2e5),
    "relative_humidity": InputSpec("conditions.relative_humidity", "1", "dimensionless",
                                   "relative humidity of the air, a fraction 0-1",
                                   _conditions_value("relative_humidity"), low=0.0, high=1.0),
    "altitude": InputSpec("conditions.altitude", "m", "length",
                          "height of the tee above sea level (sets the ISA pressure when no pressure is given)",
                          _conditions_value("altitude"), low=-500.0, high=11000.0),
    "headwind": InputSpec("conditions.headwind", "m/s", "speed",
                          "wind against the shot, along the target line (negative: a tailwind)",
                          _conditions_value("headwind"), low=-50.0, high=50.0),
    "crosswind": InputSpec("conditions.crosswind", "m/s", "speed",
                           "wind across the target line, blowing towards the right (left to right) positive",
                           _conditions_value("crosswind"), low=-50.0, high=50.0),
})

#: study path -> input name (a delivery's club speed is the impact speed)
INPUT_BY_PATH: dict[str, str] = {spec.path: name for name, spec in INPUTS.items() if name != "handedness"}
INPUT_BY_PATH["delivery.club_speed"] = "speed"
INPUT_BY_PATH["club.mass"] = "club_mass"
#: words, not numbers: a study says them once (a swept definition would mix two meanings of one number)
for _path in ("delivery.loft_at", "delivery.club_reference"):
    del INPUT_BY_PATH[_path]
#: the face's surface is a study input of the club block (club.surface.*, as face.surface.* of a face block); the
#: cover's melting and effusivity come with the ball preset: no study key sets them (a temperature rise is not a
#: temperature)
for _path in [path for path in INPUT_BY_PATH if path.startswith("face.surface.")]:
    INPUT_BY_PATH["club" + _path[len("face"):]] = INPUT_BY_PATH[_path]
for _path in ("ball.cover_melt_rise", "ball.cover_effusivity"):
    del INPUT_BY_PATH[_path]
#: swept paths a study may not set (they are parts of a tensor or vector checked as a whole)
for _path in [path for path in INPUT_BY_PATH if path.startswith(("club.inertia.", "club.center_of_mass."))]:
    del INPUT_BY_PATH[_path]


@attrs.frozen
class OutputSpec:
    """A result variable.

    ``factor`` converts the SI value a model hook returns into ``units``.
    """

    units: str
    long_name: str
    kind: str = SCALAR
    factor: float = 1.0
    #: part of the stability report that every study result carries
    diagnostic: bool = False
    #: computed only when asked for by name (the ball flight): left out of "every output" defaults
    on_request: bool = False
    #: a plugin's output (impactlab.model.extensions.DerivedOutput): the outputs it is computed from, and how
    needs: tuple[str, ...] = ()
    function: Callable[..., Any] | None = attrs.field(default=None, eq=False)


OUTPUTS: dict[str, OutputSpec] = {
    "launch_angle": OutputSpec("degree", "launch angle relative to path (theta)", factor=RAD_TO_DEG),
    "launch_ratio": OutputSpec("1", "launch ratio theta/alpha"),
    "rebound_angle": OutputSpec("degree", "rebound angle from the face normal, face frame (specular = alpha)",
                                factor=RAD_TO_DEG),
    "total_angle": OutputSpec("degree", "total angle: incidence plus rebound angle (plate experiment)",
                              factor=RAD_TO_DEG),
    "ball_speed": OutputSpec("m/s", "ball speed after impact, ground frame"),
    "spin_rate": OutputSpec("rpm", "ball spin after impact (backspin positive)", factor=RADS_TO_RPM),
    "normal_velocity": OutputSpec("m/s", "ball-centre velocity after impact along the face normal, face frame"),
    "tangential_velocity": OutputSpec("m/s",
                                      "ball-centre velocity after impact along the incoming slip, face frame"),
    "tangential_restitution": OutputSpec("1", "contact-point tangential restitution beta = -Vx'/Vx"),
    "normalised_incidence": OutputSpec("1", "normalised incidence psi1 = kappa Vx/(mu Vz) (Maw, Barber & Fawcett)"),
    "normalised_rebound": OutputSpec("1", "normalised rebound psi2 = kappa Vx'/(mu Vz'), contact-point slip after"),
    "normal_impulse": OutputSpec("N s", "normal impulse on the ball"),
    "tangential_impulse": OutputSpec("N s", "tangential impulse on the ball, positive opposing the incoming slip"),
    "lateral_impulse": OutputSpec("N s", "tangential impulse on the ball across the incoming slip, along n x s "
                                  "(0 when the slip stays on one line)"),
    "rolling_moment": OutputSpec("N m s", "angular impulse on the ball of the rolling-resistance couple about "
                                 "n x s, the backspin axis (0 without a rolling law; the head takes the opposite)"),
    "rolling_moment_slip": OutputSpec("N m s", "angular impulse on the ball of the rolling-resistance couple about "
                                      "the incoming slip direction s (0 without a rolling law or off one line)"),
    "contact_time": OutputSpec("s", "contact duration"),
    "energy_loss": OutputSpec("J", "kinetic energy lost in the impact (ball and club)"),
    "normal_force": OutputSpec("N", "normal contact force", kind=HISTORY),
    "tangential_force": OutputSpec("N", "tangential contact force, positive opposing the incoming slip",
                                   kind=HISTORY),
    "stick_radius": OutputSpec("m", "radius of the stuck central region of the contact (0 in gross slip)",
                               kind=HISTORY),
    "contact_radius_ratio": OutputSpec("1", "largest contact radius over ball radius, a_max/R"),
    "coupling_estimate": OutputSpec("1", "estimated change of the tangential impulse from the neglected normal-"
                                    "tangential coupling, over mu J_n: (1/2) ((4/(3 pi)) |beta_D| kappa / mu)^2"),
    # the stability report (added to every study result)
    "steps": OutputSpec("1", "time steps of the tangential solution (0: none needed or closed form)",
                        diagnostic=True),
    "energy_error": OutputSpec("1", "energy-balance residual over the initial kinetic energy (0: closed form)",
                               diagnostic=True),
    "validity": OutputSpec("1", "validity flags, bits of flag_masks (0: within the model's assumptions)",
                           diagnostic=True),
    # golf deliveries (3-D, ground frame; horizontal angles positive to the right of the target line)
    "spin_loft": OutputSpec("degree", "spin loft: angle between face normal and club velocity", factor=RAD_TO_DEG),
    "vertical_launch_angle": OutputSpec("degree", "vertical launch angle above the horizontal", factor=RAD_TO_DEG),
    "horizontal_launch_angle": OutputSpec("degree", "horizontal launch angle, right of the target line positive",
                                          factor=RAD_TO_DEG),
    "vertical_launch_ratio": OutputSpec("1", "vertical launch ratio (launch - attack)/(dynamic loft - attack)"),
    "horizontal_launch_ratio": OutputSpec("1", "horizontal launch ratio (launch - path)/(face - path)"),
    "spin_axis": OutputSpec("degree", "spin axis tilt from horizontal, positive curving right", factor=RAD_TO_DEG),
    "back_spin": OutputSpec("rpm", "back spin: spin about the horizontal axis across the flight",
                            factor=RADS_TO_RPM),
    "side_spin": OutputSpec("rpm", "side spin: spin about the axis across the flight perpendicular to the back-spin "
                            "axis, positive curving right", factor=RADS_TO_RPM),
    "smash_factor": OutputSpec("1", "smash factor: ball speed over club speed"),
    "club_speed_after": OutputSpec("m/s", "club-head centre-of-mass speed after impact"),
    "club_angular_velocity": OutputSpec("rpm", "club-head angular speed after impact", factor=RADS_TO_RPM),
    "face_rotation": OutputSpec("degree", "rotation of the club head during contact", factor=RAD_TO_DEG),
    # the ball flight after the launch (impactlab.physics.flight; docs/flight.md), computed only when asked for
    "carry_distance": OutputSpec("m", "carry: horizontal distance from the tee to where the ball comes back to tee "
                                 "height", on_request=True),
    "offline_distance": OutputSpec("m", "landing point from the target line, right positive", on_request=True),
    "apex_height": OutputSpec("m", "apex: greatest height above the tee", on_request=True),
    "landing_angle": OutputSpec("degree", "landing angle: descent below the horizontal at landing",
                                factor=RAD_TO_DEG, on_request=True),
    "flight_time": OutputSpec("s", "flight time from launch to landing", on_request=True),
}



#: outputs plugins derive from a model's arrays (impactlab.model.extensions.DerivedOutput), computed only when named
#: (filled by :func:`impactlab.model.extensions.load_plugins` when impactlab is imported)
PLUGIN_OUTPUTS: tuple[str, ...] = ()

#: outputs with one value per case, in vocabulary order (diagnostics included)
SCALAR_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.kind == SCALAR)
DIAGNOSTIC_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.diagnostic)
#: outputs with values over the shared ``time`` axis, in vocabulary order
HISTORY_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.kind == HISTORY)
_SCALARS, _HISTORIES = frozenset(SCALAR_OUTPUTS), frozenset(HISTORY_OUTPUTS)
#: the scalar outputs a run gives when none are named: all but those computed only on request (the ball flight)
EVERY_SCALAR_OUTPUT = tuple(name for name in SCALAR_OUTPUTS
                            if not OUTPUTS[name].on_request and OUTPUTS[name].function is None)
#: the ball-flight outputs
FLIGHT_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.on_request)


def refresh_output_names() -> None:
    """Make the tuples of output names again after outputs joined :data:`OUTPUTS` (plugins' derived outputs,
    :func:`impactlab.model.extensions.load_plugins`): :data:`SCALAR_OUTPUTS`, :data:`PLUGIN_OUTPUTS` and what
    :func:`is_scalar` reads. Read them as ``vocabulary.NAME`` where plugins' outputs matter."""
    global SCALAR_OUTPUTS, PLUGIN_OUTPUTS, _SCALARS
    PLUGIN_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.function is not None)
    SCALAR_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.kind == SCALAR)
    _SCALARS = frozenset(SCALAR_OUTPUTS)


def is_scalar(name: str) -> bool:
    """Whether ``name`` is a scalar output (one value per case); False for names outside the vocabulary."""
    return name in _SCALARS  # a module global: plugins' outputs join it when impactlab is imported


def is_history(name: str) -> bool:
    """Whether ``name`` is a history output (values over the ``time`` axis); False for names outside the vocabulary.

    The one place the scalar/history split is decided: callers filter names with it (or take
    :data:`SCALAR_OUTPUTS`, :data:`HISTORY_OUTPUTS`) instead of comparing ``OUTPUTS[name].kind``.
    """
    return name in _HISTORIES


def output_unit_factor(name: str, units: str | None) -> float:
    """The factor that turns values of output ``name`` written in ``units`` into the vocabulary's unit
    (``OUTPUTS[name].units``): 1 where ``units`` is missing or already that unit.

    A result edited with xarray (``ball_speed`` converted to mph, its ``units`` attribute with it) is read in the
    units it states; every reader of a result's values (the GSPro export, the trajectory figure) goes through this.

    Raises
    ------
    FieldError
        At ``<name>.units`` when ``units`` is not a unit of the output's quantity.
    """
    expected = OUTPUTS[name].units
    if not units or units == expected:
        return 1.0
    dimensionality = registry().Unit(expected).dimensionality
    dimension = next(name for name, (si_unit, _, _) in DIMENSIONS.items()  # angle (rad) before dimensionless
                     if registry().Unit(si_unit).dimensionality == dimensionality)
    return to_si(f"1 {units}", dimension, path=f"{name}.units") / to_si(f"1 {expected}", dimension)


def check_output_names(names: Iterable[str], path: str = "outputs") -> tuple[str, ...]:
    """``names`` as a tuple, each checked against the vocabulary (the one check of output names).

    Raises
    ------
    FieldError
        At ``path[i]`` for the first entry that is not an output name, with the vocabulary as choices.
    """
    names = tuple(names)
    for index, name in enumerate(names):
        if not isinstance(name, str) or name not in OUTPUTS:
            raise FieldError(f"{path}[{index}]", "an output name", str(name), choices=OUTPUTS)
    return names


#: the default outputs of a study that names none
DEFAULT_OUTPUTS = ("launch_angle", "launch_ratio", "rebound_angle", "ball_speed", "spin_rate",
                   "tangential_restitution", "normal_impulse", "tangential_impulse", "contact_time", "energy_loss")

TIME_DIM = "time"
CASE_DIM = "case"
MODEL_DIM = "model"


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["SCALAR", "HISTORY", "InputSpec", "INPUTS", "INPUT_BY_PATH", "OutputSpec", "OUTPUTS", "SCALAR_OUTPUTS",
           "DIAGNOSTIC_OUTPUTS", "HISTORY_OUTPUTS", "EVERY_SCALAR_OUTPUT", "FLIGHT_OUTPUTS", "is_scalar",
           "is_history", "output_unit_factor", "check_output_names", "DEFAULT_OUTPUTS", "TIME_DIM", "CASE_DIM",
           "MODEL_DIM"]
