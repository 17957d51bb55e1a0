"""One vocabulary for what models take and what they give.

Inputs are per-scene SI values handed to models. Outputs are what results
hold: each name has one unit, one long name and one shape everywhere in
impactlab (model hooks, datasets, HDF5 files, plots, docs).

Sign conventions (face frame, see docs/conventions.md): ``x`` lies in the
face along the incoming slip of the contact point, ``z`` is the face normal
pointing away from the face. Backspin (the spin friction gives a ball sliding
up a lofted face) is positive.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import attrs

from impactlab.units import RAD_TO_DEG, RADS_TO_RPM
from impactlab.validators import inside

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

    def out_of_range(self, values):
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
    "speed": InputSpec("impact.speed", "m/s", "speed", "impact speed V along the path", _attr("impact", "speed"),
                       low=0.0, low_open=True, high_open=True),
    "angle": InputSpec("impact.angle", "rad", "angle", "face normal relative to path alpha",
                       _attr("impact", "angle"), "deg", RAD_TO_DEG, low=-math.pi / 2, high=math.pi / 2,
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


_HALF_TURN = dict(low=-math.pi / 2, high=math.pi / 2, low_open=True, high_open=True)
INPUTS.update({
    "path": InputSpec("delivery.path", "rad", "angle", "club path, horizontal, in-to-out positive",
                      _delivery_value("path"), "deg", RAD_TO_DEG, **_HALF_TURN),
    "face_angle": InputSpec("delivery.face_angle", "rad", "angle", "face angle, horizontal, open positive",
                            _delivery_value("face_angle"), "deg", RAD_TO_DEG, **_HALF_TURN),
    "attack_angle": InputSpec("delivery.attack_angle", "rad", "angle", "attack angle, upwards positive",
                              _delivery_value("attack_angle"), "deg", RAD_TO_DEG, **_HALF_TURN),
    "dynamic_loft": InputSpec("delivery.dynamic_loft", "rad", "angle", "dynamic loft of the face normal",
                              _delivery_value("dynamic_loft"), "deg", RAD_TO_DEG, **_HALF_TURN),
    "handedness": InputSpec("delivery.handedness", "1", "dimensionless", "+1 right-handed golfer, -1 left-handed",
                            _delivery_value("handedness"), low=-1.0, high=1.0),
})


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
    "club_loft": InputSpec("club.loft", "rad", "angle", "static loft of the club head", _club_value("loft"), "deg",
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

#: study path -> input name (a delivery's club speed is the impact speed)
INPUT_BY_PATH: dict[str, str] = {spec.path: name for name, spec in INPUTS.items() if name != "handedness"}
INPUT_BY_PATH["delivery.club_speed"] = "speed"
INPUT_BY_PATH["club.mass"] = "club_mass"
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


OUTPUTS: dict[str, OutputSpec] = {
    "launch_angle": OutputSpec("deg", "launch angle relative to path (theta)", factor=RAD_TO_DEG),
    "launch_ratio": OutputSpec("1", "launch ratio theta/alpha"),
    "rebound_angle": OutputSpec("deg", "rebound angle from the face normal, face frame (specular = alpha)",
                                factor=RAD_TO_DEG),
    "total_angle": OutputSpec("deg", "total angle: incidence plus rebound angle (plate experiment)",
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
    "spin_loft": OutputSpec("deg", "spin loft: angle between face normal and club velocity", factor=RAD_TO_DEG),
    "vertical_launch_angle": OutputSpec("deg", "vertical launch angle above the horizontal", factor=RAD_TO_DEG),
    "horizontal_launch_angle": OutputSpec("deg", "horizontal launch angle, right of the target line positive",
                                          factor=RAD_TO_DEG),
    "vertical_launch_ratio": OutputSpec("1", "vertical launch ratio (launch - attack)/(dynamic loft - attack)"),
    "horizontal_launch_ratio": OutputSpec("1", "horizontal launch ratio (launch - path)/(face - path)"),
    "spin_axis": OutputSpec("deg", "spin axis tilt from horizontal, positive curving right", factor=RAD_TO_DEG),
    "back_spin": OutputSpec("rpm", "back spin: spin about the horizontal axis across the flight",
                            factor=RADS_TO_RPM),
    "side_spin": OutputSpec("rpm", "side spin: spin about the axis across the flight perpendicular to the back-spin "
                            "axis, positive curving right", factor=RADS_TO_RPM),
    "smash_factor": OutputSpec("1", "smash factor: ball speed over club speed"),
    "club_speed_after": OutputSpec("m/s", "club-head centre-of-mass speed after impact"),
    "club_angular_velocity": OutputSpec("rpm", "club-head angular speed after impact", factor=RADS_TO_RPM),
    "face_rotation": OutputSpec("deg", "rotation of the club head during contact", factor=RAD_TO_DEG),
}

#: outputs with one value per case, in vocabulary order (diagnostics included)
SCALAR_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.kind == SCALAR)
DIAGNOSTIC_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.diagnostic)
#: outputs with values over the shared ``time`` axis, in vocabulary order
HISTORY_OUTPUTS = tuple(name for name, spec in OUTPUTS.items() if spec.kind == HISTORY)
_SCALARS, _HISTORIES = frozenset(SCALAR_OUTPUTS), frozenset(HISTORY_OUTPUTS)


def is_scalar(name: str) -> bool:
    """Whether ``name`` is a scalar output (one value per case); False for names outside the vocabulary."""
    return name in _SCALARS


def is_history(name: str) -> bool:
    """Whether ``name`` is a history output (values over the ``time`` axis); False for names outside the vocabulary.

    The one place the scalar/history split is decided: callers filter names with it (or take
    :data:`SCALAR_OUTPUTS`, :data:`HISTORY_OUTPUTS`) instead of comparing ``OUTPUTS[name].kind``.
    """
    return name in _HISTORIES


def check_output_names(names, path: str = "outputs") -> tuple[str, ...]:
    """``names`` as a tuple, each checked against the vocabulary (the one check of output names).

    Raises
    ------
    FieldError
        At ``path[i]`` for the first entry that is not an output name, with the vocabulary as choices.
    """
    from impactlab.errors import FieldError

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
