"""Declarations shared by the built-in models."""

import attrs
import numpy as np

from impactlab.errors import FieldError, ModelInputError
from impactlab.units import si_angular_speed, si_length, si_mass, si_pressure, si_speed, to_si
from impactlab.validators import check, in_range, to_float

from impactlab.physics import core_torsion, face_flex

from impactlab.physics import friction_laws
from impactlab.scene.materials import FACE_SURFACES

from impactlab.physics.contact import GEOMETRY_INPUTS
from impactlab.physics.delivery import DELIVERY_INPUTS

RIGID_BODY_INPUTS = frozenset({"ball_mass", "ball_radius", "ball_inertia_factor", "speed", "angle"})
#: the club head's body and face, the strike point and the delivery's orientation make the 3-D contact
RIGID_BODY_OPTIONAL = frozenset({"spin", "club_mass"} | set(GEOMETRY_INPUTS) | set(DELIVERY_INPUTS))
IMPULSES = frozenset({"normal_impulse", "tangential_impulse"})
#: the impulse components of a model that solves the 3-D contact
IMPULSES_3D = IMPULSES | {"lateral_impulse"}

RIGID_NOT_PROVIDED = {
    "contact_time": "a rigid-body impulse model has no contact duration",
    "normal_force": "a rigid-body impulse model gives impulses, not force histories",
    "tangential_force": "a rigid-body impulse model gives impulses, not force histories",
    "face_rotation": "a rigid-body impulse model has no contact duration in which the head could turn",
}

STRONGE = "W. J. Stronge, Impact Mechanics, Cambridge University Press (2000), ch. 5"

#: the stability report of a closed-form model: no steps, no energy residual, no flags
CLOSED_FORM_DIAGNOSTICS = frozenset({"steps", "energy_error", "validity"})


def closed_form_diagnostics(size: int) -> dict:
    return {name: np.zeros(size) for name in CLOSED_FORM_DIAGNOSTICS}


def impulse_outputs(impulse) -> dict:
    """The models' impulse outputs from a contact-frame impulse (s, l, n) on the ball (tangential: opposing slip)."""
    return {"normal_impulse": impulse[:, 2], "tangential_impulse": -impulse[:, 0], "lateral_impulse": impulse[:, 1]}


#: inputs a ball law reads when it is switched on (the rolling arm needs the Hertz contact radius)
MATERIAL_OPTIONAL = frozenset({"ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                               "face_poisson_ratio"})
#: what a model with a rolling law gives besides its impulses
ROLLING_OUTPUTS = frozenset({"rolling_moment", "rolling_moment_slip"})


def _hysteresis(value) -> bool:
    if isinstance(value, str):
        return value == "restitution"
    return isinstance(value, (int, float)) and not isinstance(value, bool) and 0.0 <= float(value) <= 1.0


#: validator of the option ``rolling_hysteresis`` (impactlab.physics.ball_laws)
ROLLING_HYSTERESIS = check(_hysteresis, "a hysteresis fraction 0 <= alpha <= 1, or 'restitution' (alpha = 1 - e^2)")
ROLLING_HYSTERESIS_DOC = """rolling_hysteresis : float or str
        Rolling resistance of the viscoelastic cover (impactlab.physics.ball_laws): the normal force acts
        d = (3/16) alpha a ahead of the contact centre (Greenwood & Tabor; Johnson 1985, ch. 8), a couple
        d F_n opposing the relative rolling of ball and face. alpha, the fraction of a loading-unloading
        cycle's energy the cover loses, is a number in [0, 1] or ``"restitution"`` for 1 - e_ball^2 (the normal
        impact is that cycle; no free parameter; e_ball = e - club_restitution_gain, the ball's own e against a
        rigid face). Default 0: no couple, the paper's model unchanged."""


def rolling_on(value) -> bool:
    """Whether a ``rolling_hysteresis`` option switches the rolling law on."""
    return isinstance(value, str) or float(value) > 0.0


#: validator of the option ``friction_law`` (impactlab.physics.friction_laws)
FRICTION_LAW = check(lambda v: v in friction_laws.FRICTION_LAWS,
                     f"one of {', '.join(friction_laws.FRICTION_LAWS)} (impactlab.physics.friction_laws)")
FRICTION_LAW_DOC = """friction_law : str
        Which Coulomb coefficient the impact sees (:mod:`impactlab.physics.friction_laws`). ``"coulomb"`` (default):
        the ``friction`` input, today's model exactly. ``"adhesion"``: Bowden & Tabor's adhesion on the real
        contact area (Persson's area on the face's texture, set by the cover's modulus) plus ploughing, over the
        case's Hertz history; a water film squeezed out through the grooves; the cover's shear strength softened by
        its flash temperature where the ball gives a melting cover. Reads the ball's ``shear_strength`` and
        ``cover_modulus`` and the face's surface (club presets carry one)."""
#: the face surface's inputs the friction law needs (face_effusivity as well where the cover melts)
SURFACE_INPUTS = ("face_roughness_slope", "face_roughness", "face_groove_land", "face_water_film")
#: inputs the friction law reads when it is switched on (besides the ball's and face's elastic constants)
FRICTION_INPUTS = frozenset(friction_laws.LAW_INPUTS)


def law_friction(options, inputs, state, restitution=None) -> np.ndarray:
    """The friction coefficient of each case under the model's ``friction_law`` option (a model's Options may lack
    it: then the ``friction`` input, as before the law existed)."""
    law = getattr(options, "friction_law", "coulomb")
    n = state["normal_speed"].size
    if law == "coulomb":
        return np.broadcast_to(np.asarray(inputs["friction"], float), (n,))
    needed = {"ball_shear_strength", "ball_cover_modulus"} | MATERIAL_OPTIONAL
    melting = "ball_cover_melt_rise" in inputs and np.any(np.isfinite(inputs["ball_cover_melt_rise"]))
    if melting:
        needed |= {"ball_cover_effusivity"}
    missing = sorted(needed - set(inputs))
    if missing:
        raise ModelInputError(
            f"friction_law: {law} needs the ball's cover (shear_strength, cover_modulus: the urethane_tour and "
            f"two_piece_ionomer presets carry them), the ball's and face's elastic constants"
            f"{' and the cover effusivity (a melting cover)' if melting else ''}; missing: {', '.join(missing)}")
    surface = SURFACE_INPUTS + (("face_effusivity",) if melting else ())
    # a face without a surface is not taken as smooth and dry: the law's answer rests on it (docs/models.md)
    lacking = np.zeros(n, bool)
    for name in surface:
        lacking |= np.isnan(np.broadcast_to(np.asarray(inputs[name], float), (n,))) if name in inputs else True
    if np.any(lacking):
        cases = np.flatnonzero(lacking)
        which = "every case" if cases.size == n else "case(s) " + ", ".join(str(i) for i in cases[:5]) + (
            " ..." if cases.size > 5 else "")
        raise ModelInputError(
            f"friction_law: {law} needs the face's surface (its texture, grooves, water and effusivity), and the "
            f"club of {which} has none; give it one: in a study, club: {{surface: "
            f"{' | '.join(FACE_SURFACES)}}} or its fields (roughness_slope, roughness, groove_land, effusivity; "
            f"water_film for a wet face), or surface: in a club spec sheet; in Python, Face(surface=...) or "
            f"ClubHead(surface=...) with impactlab.scene.materials.FACE_SURFACES. A face is never assumed smooth "
            f"and dry")
    return friction_laws.effective_friction(law, inputs, state, restitution)


# -- the core turning behind the shell (impactlab.physics.core_torsion) ----------------------------------------------

#: field metadata of a dimensional option: a study refuses a bare number for it (impactlab.study.core; its unit is
#: never guessed), where Python keywords take SI
#: (and what it expects instead, where the dimension's own words would mislead: a frequency is not a spin rate)
LENGTH, PRESSURE, MASS = ({"dimension": name} for name in ("length", "pressure", "mass"))
FREQUENCY = {"dimension": "angular_speed", "expected": "a frequency with its unit, e.g. 4 kHz (a bare number's unit "
             "is never guessed: Hz or rad/s)"}


def _named(converter, name: str):
    """``converter`` whose refusal names the option (a unit converter's FieldError has no field of its own)."""
    def convert(value):
        try:
            return converter(value)
        except FieldError as exc:
            raise FieldError(name, exc.expected, exc.given, exc.choices) from None
    return convert


def cover_thickness_field():
    """Option ``cover_thickness`` [m] of ``maw`` (the cover in the tangential compliance): 0 (default), the
    homogeneous ball. With its unit in a study, as every dimensional option."""
    return attrs.field(default=0.0, converter=_named(si_length, "cover_thickness"), metadata=LENGTH, validator=in_range(
        0.0, 0.005, "a cover thickness in m between 0 and 0.005 (e.g. '0.8 mm')"))


def cover_modulus_field():
    """Option ``cover_modulus`` [Pa] of ``maw``; None: the ball's Young's modulus."""
    return attrs.field(default=None, converter=_named(si_pressure, "cover_modulus"), metadata=PRESSURE,
                       validator=in_range(1e6, 1e10, "a cover Young's modulus in Pa between 1e6 and 1e10 (e.g. "
                                          "'70 MPa'; or leave it out: the ball's)", optional=True))


def core_radius_field():
    """Option ``core_radius`` [m]: 0 (default) is the rigid ball, the paper's model unchanged."""
    return attrs.field(default=0.0, converter=_named(si_length, "core_radius"), metadata=LENGTH, validator=in_range(
        0.0, 0.0213, "a core radius in m between 0 (no core law) and the ball's radius (e.g. '19 mm')"))


def core_shear_modulus_field():
    """Option ``core_shear_modulus`` [Pa]; None: the ball's, E / (2 (1 + nu)) of its elastic constants."""
    return attrs.field(default=None, converter=_named(si_pressure, "core_shear_modulus"), metadata=PRESSURE,
                       validator=in_range(1e5, 1e10, "a core shear modulus in Pa between 0.1 MPa and 10 GPa (e.g. "
                                          "'20 MPa'), or leave it out for the ball's E / (2 (1 + nu))", optional=True))


def core_specific_gravity_field():
    """Option ``core_specific_gravity`` [1]; None: the ball's mean density (mass over volume)."""
    return attrs.field(default=None, converter=to_float, validator=in_range(
        0.5, 3.0, "a specific gravity between 0.5 and 3 (patents give 1.10-1.40), or leave it out for the ball's "
        "mean density", optional=True))


def core_loss_field():
    """Option ``core_loss`` [1]: the core's loss factor in shear (0: elastic)."""
    return attrs.field(default=0.0, converter=to_float, validator=in_range(0.0, 2.0, "a loss factor 0 <= eta <= 2"))


def core_modes_field():
    """Option ``core_modes``: how many of the core's rotatory modes the law carries; None: those up to
    :data:`impactlab.physics.core_torsion.CUTOFF_FREQUENCY` (at least 4)."""
    return attrs.field(default=None, validator=check(
        lambda v: v is None or (isinstance(v, int) and not isinstance(v, bool) and 1 <= v <= 64),
        "an integer from 1 to 64, or leave it out for the modes up to 20 kHz"))


CORE_TORSION_DOC = """core_radius, core_shear_modulus, core_specific_gravity, core_loss, core_modes
        The ball's core turning behind its shell (:mod:`impactlab.physics.core_torsion`): a uniform elastic core of
        radius b [m] (``core_radius``; 0, the default, is the rigid ball, today's model exactly), shear modulus G
        [Pa] (default: the ball's E / (2 (1 + nu))), specific gravity (default: the ball's mean density) and loss
        factor eta (default 0), bonded inside a rigid shell that holds the rest of the ball's inertia K^2 m R^2.
        The contact's force turns the shell; the core follows through ``core_modes`` of its rotatory modes
        (default: those up to 20 kHz, at least 4). The spin reported is the whole ball's angular momentum over
        K^2 m R^2 (the spin once the core's vibration has died). The one-spring models carry the modes in their
        1-D solver too; otherwise cases with a core take the 3-D kernel."""


def core_inputs(options, inputs, friction) -> tuple | None:
    """The 3-D kernel's ``core`` tuple (compliant3d.solve) per case under a model's core options, or None when off.

    The ball's inertia K^2 m R^2, its mass and radius, and its elastic constants (for the default shear modulus)
    come from the inputs; cases with equal values share one solve of the frequency equation.
    """
    radius = float(getattr(options, "core_radius", 0.0) or 0.0)
    if radius <= 0.0:
        return None
    n = np.asarray(friction).size

    def column(name):
        return np.broadcast_to(np.asarray(inputs[name], float), (n,))

    mass, ball_radius, factor = column("ball_mass"), column("ball_radius"), column("ball_inertia_factor")
    modulus, poisson = column("ball_youngs_modulus"), column("ball_poisson_ratio")
    shear = options.core_shear_modulus
    shear = modulus / (2.0 * (1.0 + poisson)) if shear is None else np.full(n, float(shear))
    gravity = options.core_specific_gravity
    density = mass / (4.0 / 3.0 * np.pi * ball_radius**3) if gravity is None else np.full(n, 1000.0 * gravity)
    if np.any(radius >= ball_radius):
        raise ModelInputError(f"core_radius: a core of radius {radius * 1e3:.2f} mm does not fit inside a ball of "
                              f"radius {float(np.min(ball_radius)) * 1e3:.3f} mm")
    keys = np.stack([mass, ball_radius, factor, shear, density], -1)
    unique, which = np.unique(keys, axis=0, return_inverse=True)
    # the modes each case keeps: its own, never its batch's (a case's result must not depend on the cases run with
    # it); a case with fewer than the widest is padded with inert modes (gain 0) that the kernels skip
    counts = [options.core_modes if options.core_modes is not None else core_torsion.modes_below(
        core_torsion.CUTOFF_FREQUENCY, total_inertia=k2 * m * r**2, core_radius=radius, core_density=rho,
        shear_modulus=g) for m, r, k2, g, rho in unique]
    width = max(counts)
    inverse, frequency, damping = np.zeros((n, width)), np.zeros((n, width)), np.zeros((n, width))
    for index, ((m, r, k2, g, rho), count) in enumerate(zip(unique, counts)):
        try:
            modes = core_torsion.core_modes(total_inertia=k2 * m * r**2, core_radius=radius, core_density=rho,
                                            shear_modulus=g, loss=options.core_loss, modes=count)
        except ValueError as exc:
            raise ModelInputError(f"core_radius, core_specific_gravity: {exc}; a smaller or lighter core, or a "
                                  f"ball with more inertia") from None
        rows = which.ravel() == index
        inverse[rows, :count], frequency[rows, :count] = modes.inverse_inertia, modes.frequency
        damping[rows, :count] = modes.damping
    return inverse, frequency, damping, ball_radius.copy()


# -- the face flexing behind the contact (impactlab.physics.face_flex) ---------------------------------------------

def face_frequency_field(default: float = 0.0):
    """Option ``face_frequency`` [rad/s; '4 kHz' reads as 2 pi 4000 rad/s]: 0 (default) is the rigid face."""
    return attrs.field(default=default, converter=_named(si_angular_speed, "face_frequency"), metadata=FREQUENCY,
                       validator=in_range(0.0, 2.0 * np.pi * 1e6, "the face's first-mode frequency with its unit "
                                          "between 0 (a rigid face) and 1 MHz (e.g. '4 kHz')"))


def face_modal_mass_field(default: float = 0.0):
    """Option ``face_modal_mass`` [kg]: the face mode's modal mass at the strike; 0 (default) with a rigid face."""
    return attrs.field(default=default, converter=_named(si_mass, "face_modal_mass"), metadata=MASS,
                       validator=[in_range(0.0, 0.2, "the face's modal mass with its unit between 0 (a rigid face) "
                                           "and 200 g (e.g. '8 g')"), _whole_face])


def _whole_face(options, attribute, mass) -> None:
    """Both the face's frequency and its modal mass, or neither: refused with the options (a study's line), not
    when the model runs (attrs runs validators once every field is set, face_frequency before this one)."""
    omega = float(getattr(options, "face_frequency", 0.0) or 0.0)
    if (omega > 0.0) != (float(mass) > 0.0):
        given = "face_modal_mass 0" if omega > 0.0 else "face_frequency 0"
        raise FieldError("face_frequency" if omega == 0.0 else "face_modal_mass", "the flexing face's first-mode "
                         "frequency and its modal mass both (e.g. face_frequency: 4 kHz, face_modal_mass: 8 g), or "
                         "neither for a rigid face", given)


def face_loss_field():
    """Option ``face_loss`` [1]: loss factor of the face's mode (0: elastic)."""
    return attrs.field(default=0.0, converter=to_float, validator=in_range(0.0, 1.0, "a loss factor 0 <= eta <= 1"))


FACE_FLEX_DOC = """face_frequency, face_modal_mass, face_loss
        The face flexing behind the contact (:mod:`impactlab.physics.face_flex`): one modal oscillator of the face
        along the contact normal, of first-mode frequency ``face_frequency`` (with its unit, '4 kHz'), modal mass
        ``face_modal_mass`` ('8 g') and loss factor ``face_loss`` (default 0), in series with the ball's Hertz
        contact. Both 0 (the default): a rigid face, today's model exactly; one without the other is refused. It
        applies to the faces a club marks as spring-like (``club_restitution_gain`` > 0: the woods and hybrids;
        irons stay rigid), and on those the normal law takes the ball's own restitution e - club_restitution_gain:
        the flexing face replaces the fitted gain, so ball speed is not counted twice (a pair's e below the gain
        is refused; a study sweeping the gain through 0 too, as that switches the face on). Cases with a flexing
        face take the 3-D kernel."""



# -- laws with a speed, time or pressure scale of their own (impactlab.physics.rate_laws; issue 33) ------------------

TIME = {"dimension": "time", "expected": "a time with its unit, e.g. 30 us (a bare number's unit is never guessed)"}
SPEED = {"dimension": "speed"}


def _si_time(value):
    """A time as an SI float [s] (a bare number is SI; text with a unit converted), as the units' converters do."""
    if isinstance(value, bool) or value is None:
        return value
    if isinstance(value, int):
        return float(value)
    return to_si(value, "time", bare="si") if isinstance(value, str) else value


def relaxation_time_field(name: str, high: float, default: float = 0.0):
    """A relaxation time option [s] (0, the default: the law off, the plain model exactly)."""
    return attrs.field(default=default, converter=_named(_si_time, name), metadata=TIME, validator=in_range(
        0.0, high, f"a relaxation time in s between 0 (off) and {high:g} s (e.g. '30 us')"))


def relaxed_fraction_field(default: float = 0.5):
    """Option ``relaxed_fraction`` g = E_1 / E_0 of the SLS normal law [1]."""
    return attrs.field(default=default, converter=to_float, validator=in_range(0.0, 0.95, "a relaxed fraction "
                                                                                "0 <= g <= 0.95"))


def reference_speed_field():
    """Option ``relaxation_reference_speed`` [m/s]: the normal speed at which e(v) equals the restitution input."""
    return attrs.field(default=40.0, converter=_named(si_speed, "relaxation_reference_speed"),
                       metadata=SPEED, validator=in_range(1.0, 100.0, "a normal speed in m/s between 1 and 100 "
                                                          "(e.g. '40 m/s')"))


def pressure_exponent_field():
    """Option ``friction_pressure_exponent`` n of mu = mu_0 (p / 10 MPa)^(-n) [1] (0: Coulomb)."""
    return attrs.field(default=0.0, converter=to_float, validator=in_range(0.0, 1.0, "an exponent 0 <= n <= 1 "
                                                                               "(1: constant shear strength)"))


def slip_exponent_field(default: float = 0.0):
    """Option ``friction_slip_exponent`` m of mu = mu_0 (u / 10 m/s)^m [1] (0: Coulomb)."""
    return attrs.field(default=default, converter=to_float, validator=in_range(0.0, 1.0, "an exponent 0 <= m <= 1 "
                                                                                "(1: friction stress ~ slip speed)"))


def lever_field(default: float = 0.0):
    """Option ``compression_lever`` lambda = d / delta of the normal force's offset [1] (0: none)."""
    return attrs.field(default=default, converter=to_float, validator=in_range(0.0, 0.5, "a lever 0 <= lambda <= 0.5 "
                                                                               "(d = lambda delta)"))


RATE_LAWS_DOC = """relaxation_time, relaxed_fraction, relaxation_reference_speed, friction_pressure_exponent,
    friction_slip_exponent, compression_lever
        Laws with a scale of their own (:mod:`impactlab.physics.rate_laws`, issue 33), each off by default.
        ``relaxation_time`` tau [s] (with its unit, '30 us') and ``relaxed_fraction`` g: the ball's normal contact a
        standard linear solid under Hertz (Lee & Radok), whose restitution falls or rises with the normal speed;
        the restitution input is e at ``relaxation_reference_speed`` (40 m/s) and e(v) = e_in e_sls(v) /
        e_sls(v_ref). ``friction_pressure_exponent`` n: mu = mu_0 (p_mean / 10 MPa)^(-n). ``friction_slip_exponent``
        m: mu = mu_0 (u / 10 m/s)^m, u the impact's slip speed (:func:`characteristic_slip`; Arakawa's 2017 model:
        m = 1 with n = 1). ``compression_lever``
        lambda: the normal force's line offset d = lambda delta by the ball's deformation, a couple opposing the
        relative rolling (the rolling couple of impactlab.physics.ball_laws with this arm)."""


def characteristic_slip(state, restitution) -> np.ndarray:
    """The slip speed of each impact that the slip-speed friction law reads [m/s]: the larger of the contact's
    initial tangential slip and the slip a frictionless impact would leave it with.

    On a central strike the two are equal (the normal impulse moves no tangential velocity: the mobility is diagonal)
    and the law reads the initial slip u = V sin(angle). An off-centre strike on a free head couples the normal impulse
    into the tangential directions (the gear effect), so a strike with no initial slip still slides during the
    contact: its slip scale is that coupled slip, not 0 (which would take the friction, and the gear effect, away).
    """
    initial = state["initial_velocity"]
    mobility = state["mobility"]
    normal_impulse = (1.0 + np.asarray(restitution, float)) * state["normal_speed"] / mobility[:, 2, 2]
    after = initial[:, :2] + mobility[:, :2, 2] * normal_impulse[:, None]
    return np.maximum(np.hypot(initial[:, 0], initial[:, 1]), np.hypot(after[:, 0], after[:, 1]))


def rate_law_state(options, inputs, state, restitution, friction):
    """(restitution, friction, lever arm [m] or None, modulus E*) of each case under the rate-law options.

    Each law off returns its input unchanged (the plain model exactly). The laws read the ball's and face's elastic
    constants (the Hertz scale): refused with a clear message where they are missing.
    """
    from impactlab.physics import hertz, rate_laws

    tau = float(getattr(options, "relaxation_time", 0.0) or 0.0)
    exponent = float(getattr(options, "friction_pressure_exponent", 0.0) or 0.0)
    lever = float(getattr(options, "compression_lever", 0.0) or 0.0)
    slip_exponent = float(getattr(options, "friction_slip_exponent", 0.0) or 0.0)
    if slip_exponent:  # the slip's scale needs no elastic constant
        if getattr(options, "friction_law", "coulomb") != "coulomb":
            raise ModelInputError("friction_slip_exponent scales the Coulomb friction input; friction_law "
                                  f"'{options.friction_law}' has its own dependence on the sliding (its flash "
                                  "heating): use one of them")
        friction = rate_laws.slip_friction(friction, slip_exponent, characteristic_slip(state, restitution))
    if not (tau or exponent or lever):
        return restitution, friction, None
    missing = sorted(MATERIAL_OPTIONAL - set(inputs))
    if missing:
        raise ModelInputError(f"relaxation_time, friction_pressure_exponent, compression_lever need the Hertz "
                              f"contact, hence the ball's and face's elastic constants; missing: {', '.join(missing)} "
                              f"(give ball and face materials)")
    moduli = [inputs[name] for name in ("ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                                        "face_poisson_ratio")]
    n = state["normal_speed"].size
    modulus = np.broadcast_to(hertz.effective_modulus(*moduli), (n,))
    mass, radius, speed = 1.0 / state["mobility"][:, 2, 2], state["contact_radius"], state["normal_speed"]
    if tau:
        restitution = rate_laws.restitution_shape(restitution, options.relaxed_fraction, tau, speed, mass, radius,
                                                  modulus, options.relaxation_reference_speed)
    if exponent:
        friction = rate_laws.pressure_friction(friction, exponent, rate_laws.mean_pressure(mass, radius, modulus,
                                                                                           speed))
    arm = rate_laws.compression_arm(lever, mass, radius, modulus, speed) if lever else None
    return restitution, friction, arm


#: the option of each ball and face law of BallLawOptions with the value that switches the law off (the plain ball:
#: ImpactModel.ball_law_options); a law's other options (a core's modulus, the face's loss...) act only when it is on
PLAIN_BALL = {"rolling_hysteresis": 0.0, "friction_law": "coulomb", "core_radius": 0.0, "face_frequency": 0.0,
              "relaxation_time": 0.0, "friction_pressure_exponent": 0.0, "friction_slip_exponent": 0.0,
              "compression_lever": 0.0}


@attrs.frozen(kw_only=True)
class BallLawOptions:
    """The ball and face laws every compliant model takes, declared once (``maw``'s and the DEM models' Options
    subclass it; docs/models.md, "Ball laws"). Each is off by default: the paper's model unchanged."""

    #: rolling resistance of the cover (ROLLING_HYSTERESIS_DOC); 0: none
    rolling_hysteresis: float | str = attrs.field(default=0.0, validator=ROLLING_HYSTERESIS)
    #: the friction law (FRICTION_LAW_DOC); "coulomb": the friction input
    friction_law: str = attrs.field(default="coulomb", validator=FRICTION_LAW)
    #: the core turning behind the shell (CORE_TORSION_DOC); core_radius 0: a rigid ball
    core_radius: float = core_radius_field()
    core_shear_modulus: float | None = core_shear_modulus_field()
    core_specific_gravity: float | None = core_specific_gravity_field()
    core_loss: float = core_loss_field()
    core_modes: int = core_modes_field()
    #: laws with a scale (RATE_LAWS_DOC); each 0: off
    relaxation_time: float = relaxation_time_field("relaxation_time", 0.01)
    relaxed_fraction: float = relaxed_fraction_field()
    relaxation_reference_speed: float = reference_speed_field()
    friction_pressure_exponent: float = pressure_exponent_field()
    friction_slip_exponent: float = slip_exponent_field()
    compression_lever: float = lever_field()
    tangential_relaxation_time: float = relaxation_time_field("tangential_relaxation_time", 0.001)
    #: the face flexing behind the contact (FACE_FLEX_DOC); 0: a rigid face
    face_frequency: float = face_frequency_field()
    face_modal_mass: float = face_modal_mass_field()
    face_loss: float = face_loss_field()

def face_on(options) -> bool:
    """Whether a model's options switch the face law on; one of frequency and modal mass without the other is
    refused (ModelInputError)."""
    omega = float(getattr(options, "face_frequency", 0.0) or 0.0)
    mass = float(getattr(options, "face_modal_mass", 0.0) or 0.0)
    if (omega > 0.0) != (mass > 0.0):
        raise ModelInputError("face_frequency, face_modal_mass: the flexing face needs both its first-mode "
                              "frequency and its modal mass (e.g. face_frequency: 4 kHz, face_modal_mass: 8 g), or "
                              "neither for a rigid face")
    return omega > 0.0


def face_inputs(options, inputs, size: int):
    """(the 3-D kernel's ``face`` tuple, flexing cases) under a model's face options, or None when off.

    A case's face flexes where its club marks a spring-like face (input ``club_restitution_gain`` > 0).
    """
    if not face_on(options):
        return None
    gain = np.broadcast_to(np.asarray(inputs.get("club_restitution_gain", 0.0), float), (size,))
    flexing = gain > 0.0
    if not np.any(flexing):
        return None
    omega = float(options.face_frequency)
    inverse, omega_f, damping = face_flex.modal_inputs(options.face_modal_mass * omega**2,
                                                       options.face_modal_mass, options.face_loss)
    return (np.where(flexing, inverse, 0.0), np.full(size, float(omega_f)), np.where(flexing, damping, 0.0)), flexing


def face_restitution(face, p, restitution):
    """The normal law's restitution per case: on a flexing face the ball's own e (e - club_restitution_gain, at most
    1), the face's mode returning what the fitted gain stood for, so ball speed is not counted twice; e elsewhere
    (``face`` from :func:`face_inputs`, None when the law is off). A flexing case whose e is below its gain (a
    ``contact.restitution`` given below the club's gain) has no ball's own e: refused (ModelInputError), not
    clipped to 0."""
    if face is None:
        return restitution
    gain = np.broadcast_to(np.asarray(p.get("club_restitution_gain", 0.0), float), restitution.shape)
    below = face[1] & (restitution < gain)
    if np.any(below):
        case = int(np.argmax(below))
        raise ModelInputError(f"restitution, club_restitution_gain: with the flexing face (face_frequency) the ball's "
                              f"own e is e - club_restitution_gain, negative in {int(below.sum())} case(s) (e.g. e "
                              f"{float(restitution[case]):.3g}, gain {float(gain[case]):.3g}); give the pair's e "
                              f"(contact.restitution) at least the club's gain, or leave it to the ball's law")
    return np.where(face[1], np.minimum(restitution - gain, 1.0), restitution)
