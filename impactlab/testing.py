"""Conformance suite for impact models, shipped for plugin authors.

Every registered model must pass it; run it on your own plugin with::

    from impactlab.testing import check_model
    check_model(MyModel)                 # raises AssertionError listing failures

or, one pytest test per model and check::

    from impactlab.testing import parametrize_with_checks

    @parametrize_with_checks(MyModel, MyModel(some_option=2))
    def test_conformance(model, check):
        check(model)

Besides the declarations and capabilities (rules 1 and 8 of
:class:`~impactlab.model.base.ImpactModel`), the checks are physics every impact
model must respect whatever its approximations: energy of a fixed-face impact never increases, a frictionless
or head-on impact gives no tangential impulse, mirrored impacts mirror, the
normal impulse lies between 0 and that of an elastic impact, beta lies in
[-1, 1], a case's result does not depend on the batch around it, and an
optional input not given is absent (rule 3): no spin, a fixed face.

Invariants let a wrong model pass (2 mu, a dropped sideways impulse), so the suite also holds every model to
reference values written here apart from the models: gross slip gives J_t = mu J_n exactly (``full_sliding``); the
rigid-body closed form of Stronge (``rigid_limit``, :func:`rigid_coulomb_closed_form`); a ball arriving rolling
gets no tangential impulse (``arriving_rolling``); an off-centre strike on a free head against an independent
rigid-body solution (``3d_sideways_impulse``, :func:`flat_head_mobility`, :func:`sliding_impulse_3d`). Each
failure names the likely cause.
"""

from __future__ import annotations

import functools
import json
import keyword
import warnings
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

import attrs
import numpy as np

from impactlab.errors import ModelContractError, PlausibilityWarning
from impactlab.scene.materials import BALL_PRESETS, FACE_PRESETS, FACE_SURFACES
from impactlab.model.base import ImpactModel
from impactlab.model.contract import declaration_problems
from impactlab.physics.mechanics import effective_mass
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.catalogue import CLUB_PRESETS
from impactlab.scene.core import Contact, Delivery, Impact, Scene, complete_inputs
from impactlab.units import RAD_TO_DEG, RADS_TO_RPM
from impactlab.vocabulary import CASE_DIM, EVERY_SCALAR_OUTPUT, INPUTS, OUTPUTS, TIME_DIM, is_history

if TYPE_CHECKING:  # pytest is a test dependency: imported at run time only by parametrize_with_checks
    import pytest

#: relative round-off allowed in energy and impulse bounds
RTOL = 1e-9


def reference_inputs(n_angles: int = 7) -> dict[str, np.ndarray]:
    """A batch of golf-like cases on rigid and steel faces, frictions 0.1-0.6, lofts 2-70 deg, with and without spin."""
    scenes = []
    # each face with a surface for the friction law (none is ever assumed): grooved steel irons, a smooth driver
    steel = FACE_SURFACES["grooved_blasted_steel"]
    for face in (attrs.evolve(FACE_PRESETS["rigid"], surface=steel), attrs.evolve(FACE_PRESETS["steel"], surface=steel),
                 attrs.evolve(FACE_PRESETS["titanium"], mass=0.2, surface=FACE_SURFACES["smooth_titanium"])):
        for friction in (0.1, 0.4, 0.6):
            for angle in np.radians(np.linspace(2.0, 70.0, n_angles)):
                for spin in (0.0, 200.0):
                    scenes.append(Scene(BALL_PRESETS["urethane_tour"], face, Contact(friction, 0.8 if spin else 1.0),
                                        Impact(40.0, float(angle), spin)))
    keys = scenes[0].inputs().keys()
    return {key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys}


def reference_inputs_3d() -> dict[str, np.ndarray]:
    """Golf deliveries on free club heads: the driver preset and a head symmetric heel-to-toe, struck across the face.

    Strikes from heel to toe and sole to crown, square and open faces, frictions 0.1-0.6, e 0.8 and 1: the
    cases where the mobility couples the normal and tangential directions and the slip turns.
    """
    symmetric = ClubHead(mass=0.2, inertia=(3.0e-4, 4.5e-4, 2.5e-4), center_of_mass=(0.0, -0.003, 0.035),
                         loft=np.radians(10.0), bulge_radius=0.3, material=CLUB_PRESETS["driver"].material,
                         surface=FACE_SURFACES["smooth_titanium"])
    scenes = []
    for club in (CLUB_PRESETS["driver"], symmetric):
        face = Scene.face_of(club)
        for toe, high in ((-0.02, 0.0), (0.015, 0.005), (0.0, -0.01), (0.01, 0.01)):
            for friction, restitution in ((0.1, 1.0), (0.4, 0.8), (0.6, 0.8)):
                for face_angle in (0.0, 0.06):
                    delivery = Delivery(45.0, path=0.02, face_angle=face_angle, attack_angle=-0.02,
                                        dynamic_loft=0.22)
                    scenes.append(Scene.from_delivery(BALL_PRESETS["urethane_tour"], face,
                                                      Contact(friction, restitution), delivery, 0.0, club,
                                                      Strike(toe, high)))
    # the inputs every scene gives
    keys = set.intersection(*(set(scene.inputs()) for scene in scenes))
    return {key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys}


def _complete(inputs: dict) -> dict:
    return complete_inputs(dict(inputs))


#: a model class (made with its default options) or a configured model
ModelLike = ImpactModel | type[ImpactModel]


def _model(model: ModelLike) -> ImpactModel:
    return model() if isinstance(model, type) else model


def _with(inputs: dict, **changes) -> dict:
    out = {key: np.array(value, dtype=float) for key, value in inputs.items()}
    for key, value in changes.items():
        out[key] = np.broadcast_to(np.asarray(value, dtype=float), out["speed"].shape).copy()
    return out


def _scalar_outputs(model, inputs) -> list[str]:
    wanted = list(EVERY_SCALAR_OUTPUT)
    plan = model.plan(wanted, inputs)
    return [name for name in wanted if name not in plan.missing]


def check_declarations(model: ImpactModel) -> None:
    """Declarations (rule 1): name an identifier, label and references given, declared inputs and outputs in the
    vocabulary, Options a frozen attrs class with defaults, references in the docstring."""
    cls = type(model)
    problems = declaration_problems(cls)  # what the registry checks when a plugin loads (rule 9 included)
    assert not problems, "; ".join(problems)
    assert isinstance(cls.name, str) and cls.name.isidentifier() and not keyword.iskeyword(cls.name), \
        f"name must be a Python identifier, got {cls.name!r}"
    assert isinstance(cls.label, str) and cls.label, "label must be a non-empty string"
    assert isinstance(cls.references, tuple) and cls.references and all(
        isinstance(ref, str) and ref for ref in cls.references), "references must be a non-empty tuple of citations"
    for attribute, vocabulary in (("requires", INPUTS), ("optional_inputs", INPUTS), ("provides", OUTPUTS)):
        declared = getattr(cls, attribute)
        assert isinstance(declared, frozenset), f"{attribute} must be a frozenset"
        unknown = sorted(set(declared) - set(vocabulary))
        assert not unknown, f"{attribute} names unknown to the vocabulary: {unknown}"
    assert cls.provides, "provides must not be empty"
    assert not (cls.requires & cls.optional_inputs), "an input is both required and optional"
    assert attrs.has(cls.Options), "Options must be an attrs class"
    assert all(field.default is not attrs.NOTHING for field in attrs.fields(cls.Options)), \
        "every option needs a default"
    options, fields = cls.Options(), attrs.fields(cls.Options)
    if fields:
        try:
            setattr(options, fields[0].name, getattr(options, fields[0].name))
        except attrs.exceptions.FrozenInstanceError:
            pass
        else:
            raise AssertionError("Options must be frozen (attrs.frozen)")
    json.dumps(model.options_dict())
    assert model.__doc__ and "References" in model.__doc__, "the model docstring must cite its references"


def check_capabilities(model: ImpactModel) -> None:
    """Declared capabilities (rule 8) hold: ``has_tolerance`` exactly when Options has a ``tolerance`` field (and
    then the reference options are Options at the asked tolerance); ``provides_histories`` exactly when
    ``provides`` names a history, and then the histories come back on a ``time`` axis of ``history_length()``
    samples; ``solves_3d`` only with ``lateral_impulse``; ``expert_resolution`` None or two positive integers."""
    cls = type(model)
    assert isinstance(cls.has_tolerance, bool), "has_tolerance must be True or False"
    fields = {field.name for field in attrs.fields(cls.Options)}
    if cls.has_tolerance:
        assert "tolerance" in fields, "has_tolerance is declared but Options has no field 'tolerance'"
        reference = model.reference_options(1e-6)
        assert isinstance(reference, cls.Options) and reference.tolerance == 1e-6, \
            "reference_options(tolerance) must give Options at that tolerance"
        assert isinstance(model.can_reach(1e-3), bool), "can_reach must return True or False"
    else:
        assert "tolerance" not in fields, "Options has a field 'tolerance': declare has_tolerance = True"
    histories = sorted(name for name in cls.provides if is_history(name))
    assert cls.provides_histories == bool(histories), \
        f"provides_histories is {cls.provides_histories} but provides names histories {histories}"
    if histories:
        inputs = {key: value[:4] for key, value in reference_inputs(n_angles=2).items()}
        try:
            result = model.compute(inputs, histories)
        except ModelContractError as exc:
            raise AssertionError(f"histories asked for: {exc}") from None
        assert TIME_DIM in result.coords, "histories returned without a 'time' axis"
        assert result.sizes[TIME_DIM] == model.history_length(), \
            f"histories have {result.sizes[TIME_DIM]} samples, history_length() says {model.history_length()}"
        for name in histories:
            assert result[name].dims == (CASE_DIM, TIME_DIM), f"history {name} is not on (case, time)"
    solves_3d = model.solves_3d()
    assert isinstance(solves_3d, bool), "solves_3d() must return True or False"
    assert not solves_3d or "lateral_impulse" in cls.provides, "a model that solves 3-D contacts provides " \
        "lateral_impulse"
    grid = model.expert_resolution()
    assert grid is None or (len(grid) == 2 and all(isinstance(n, int) and n > 0 for n in grid)), \
        f"expert_resolution() must be None or (springs, steps), got {grid!r}"


def check_runs_finite(model: ImpactModel) -> None:
    """Every scalar output the model can give on the reference batch (fixed, point-mass and rigid faces, loft
    0-75 deg) is finite."""
    inputs = reference_inputs()
    names = _scalar_outputs(model, inputs)
    result = model.compute(inputs, names)
    for name in names:
        values = result[name].values
        assert np.all(np.isfinite(values)), f"{name} has non-finite values"


def check_energy_never_increases(model: ImpactModel) -> None:
    """Kinetic energy after impact never exceeds that before (``energy_loss`` >= 0 to round-off)."""
    inputs = reference_inputs()
    result = model.compute(inputs, ["energy_loss", "ball_speed"])
    kinetic = 0.5 * inputs["ball_mass"] * inputs["speed"] ** 2
    loss = result["energy_loss"].values
    assert np.all(loss >= -RTOL * kinetic * 10), f"energy rises: min energy_loss/KE = {np.min(loss / kinetic):.3g}"


def check_normal_impulse_bounds(model: ImpactModel) -> None:
    """The normal impulse lies in (0, 2 m_eff V_n]: positive, and at most that of an elastic impact."""
    inputs = reference_inputs()
    jn = model.compute(inputs, ["normal_impulse"])["normal_impulse"].values
    elastic = 2.0 * effective_mass(inputs["ball_mass"], inputs["club_mass"]) * inputs["speed"] * np.cos(inputs["angle"])
    assert np.all(jn > 0.0), "normal impulse must be positive"
    assert np.all(jn <= elastic * (1 + 1e-6)), "normal impulse exceeds that of an elastic impact"


def check_tangential_restitution_bounds(model: ImpactModel) -> None:
    """Tangential restitution beta lies in [-1, 1] (it cannot reverse the contact slip faster than it came in).

    The bound follows from energy when only a contact force acts. A rolling-resistance couple (outputs
    ``rolling_moment``) stops the ball's rolling at low loft while the contact still grips, so the contact point
    can leave faster than it came with less kinetic energy than it had (e.g. maw at 2 deg: beta 1.4 with the
    tangential and rotational energy down by a quarter); cases with a couple are held to the energy checks only.
    """
    names = ["tangential_restitution"] + [name for name in ("rolling_moment", "rolling_moment_slip")
                                          if name in model.provides]
    result = model.compute(reference_inputs(), names)
    beta = result["tangential_restitution"].values
    couple = np.zeros(beta.shape, dtype=bool)
    for name in names[1:]:
        couple |= result[name].values != 0.0
    beta = beta[~couple]
    assert np.all((beta >= -1 - 1e-9) & (beta <= 1 + 1e-9)), f"beta outside [-1, 1]: {beta.min():.4g}..{beta.max():.4g}"


def _without_tangential_impulse(model, what: str, outputs: list[str], **changes):
    """Run the reference batch with ``changes``; assert J_t vanishes; return the result."""
    inputs = _with(reference_inputs(), spin=0.0, **changes)
    result = model.compute(inputs, ["tangential_impulse", *outputs])
    scale = inputs["ball_mass"] * inputs["speed"]
    assert np.all(np.abs(result["tangential_impulse"].values) <= 1e-12 * scale), f"{what} impact has J_t != 0"
    return result


def check_frictionless(model: ImpactModel) -> None:
    """With mu = 0 there is no tangential impulse, no spin, and beta = -1 (the slip passes unchanged).

    Frictionless in every friction law: mu = 0, and the friction law's interface (zero shear strength on a smooth
    face, so neither adhesion nor ploughing; :mod:`impactlab.physics.friction_laws`).
    """
    result = _without_tangential_impulse(model, "frictionless", ["spin_rate", "tangential_restitution"],
                                         friction=0.0, ball_shear_strength=0.0, face_roughness_slope=0.0)
    assert np.allclose(result["spin_rate"].values, 0.0, atol=1e-9), "frictionless impact spins the ball"
    assert np.allclose(result["tangential_restitution"].values, -1.0), "frictionless impact must give beta = -1"


def check_head_on(model: ImpactModel) -> None:
    """A head-on impact (angle 0, no spin) gives no tangential impulse and launches along the path."""
    result = _without_tangential_impulse(model, "head-on", ["launch_angle"], angle=0.0)
    assert np.allclose(result["launch_angle"].values, 0.0, atol=1e-9), "head-on impact launches off the path"


def check_mirror_symmetry(model: ImpactModel) -> None:
    """Mirroring the impact (angle and spin negated) keeps J_n and flips J_t and the launch angle."""
    inputs = reference_inputs()
    mirrored = _with(inputs, angle=-inputs["angle"], spin=-inputs["spin"])
    a = model.compute(inputs, ["normal_impulse", "tangential_impulse", "launch_angle"])
    b = model.compute(mirrored, ["normal_impulse", "tangential_impulse", "launch_angle"])
    assert np.allclose(a["normal_impulse"], b["normal_impulse"], rtol=1e-12), "mirroring changes J_n"
    assert np.allclose(a["tangential_impulse"], -b["tangential_impulse"], rtol=1e-12, atol=1e-15), \
        "mirroring must flip J_t"
    assert np.allclose(a["launch_angle"], -b["launch_angle"], rtol=1e-12, atol=1e-12), "mirroring must flip theta"


def check_batch_independence(model: ImpactModel) -> None:
    """A case computed alone equals the same case inside a batch (rule 5), to 1e-12."""
    inputs = reference_inputs(n_angles=3)
    names = [name for name in ("normal_impulse", "tangential_impulse") if name in model.provides] or \
        sorted(model.provides)[:1]
    whole = model.compute(inputs, names)
    for case in (0, len(inputs["speed"]) // 2, len(inputs["speed"]) - 1):
        single = model.compute({key: value[case:case + 1] for key, value in inputs.items()}, names)
        for name in names:
            assert np.allclose(whole[name].values[case], single[name].values[0], rtol=1e-12, atol=0), \
                f"{name} of case {case} depends on the batch around it"


def check_3d_energy_never_increases(model: ImpactModel) -> None:
    """On free club heads struck off-centre, no model may create kinetic energy (ball plus head, rotation included)."""
    if not model.solves_3d():
        return  # a model on one line: its derived outputs on a free head are NaN with the reason (plan)
    inputs = _complete(reference_inputs_3d())
    result = model.compute(inputs, ["energy_loss", "lateral_impulse"])
    kinetic = 0.5 * inputs["ball_mass"] * inputs["speed"] ** 2
    loss = result["energy_loss"].values
    assert np.all(np.isfinite(loss)), "3-D energy loss is not finite"
    assert np.all(loss >= -1e-6 * kinetic), \
        f"3-D impact creates energy: min energy_loss/KE = {np.min(loss / kinetic):.3g}"


def check_3d_heel_toe_mirror(model: ImpactModel) -> None:
    """A head symmetric heel-to-toe, square face, path along the target: heel and toe strikes are mirror images."""
    if not model.solves_3d():
        return
    inputs = reference_inputs_3d()
    symmetric = (inputs["club_inertia_toe_up"] == 0.0) & (inputs["face_angle"] == 0.0)
    inputs = _complete(_with({key: value[symmetric] for key, value in inputs.items()}, path=0.0))
    mirrored = _complete(_with(inputs, strike_toe=-inputs["strike_toe"]))
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse"]
    a, b = model.compute(inputs, names), model.compute(mirrored, names)
    scale = inputs["ball_mass"] * inputs["speed"]
    for name, sign in zip(names, (1.0, 1.0, -1.0)):
        assert np.allclose(a[name].values, sign * b[name].values, rtol=1e-9, atol=1e-12 * scale.max()), \
            f"heel and toe strikes do not mirror in {name}"


def check_3d_batch_independence(model: ImpactModel) -> None:
    """On free heads struck off-centre, a case computed alone equals the same case inside a batch."""
    if not model.solves_3d():
        return
    inputs = _complete(reference_inputs_3d())
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse"]
    whole = model.compute(inputs, names)
    for case in (0, len(inputs["speed"]) // 2, len(inputs["speed"]) - 1):
        single = model.compute({key: value[case:case + 1] for key, value in inputs.items()}, names)
        for name in names:
            assert np.allclose(whole[name].values[case], single[name].values[0], rtol=1e-12, atol=0), \
                f"3-D {name} of case {case} depends on the batch around it"


def check_inputs_untouched(model: ImpactModel) -> None:
    """The model leaves its input arrays as it found them (rule 5)."""
    inputs = reference_inputs(n_angles=3)
    copies = {key: value.copy() for key, value in inputs.items()}
    model.compute(inputs, sorted(model.provides))
    for key in inputs:
        assert np.array_equal(inputs[key], copies[key]), f"input {key} was changed"


# -- reference values (issue 34: invariants alone let a model with 2 mu, or without its sideways impulse, pass) -------

def _sliding_inputs() -> dict[str, np.ndarray]:
    """Gross slip for every model: e 0.8, mu 0.05 and 0.1, spin lofts 55-75 deg, a fixed rigid face and a free
    titanium point-mass face (0.2 kg). The rigid criterion tan(alpha) >= mu (1 + e)(1 + 1/K^2 + m/M) holds with
    a margin of 2 or more, so no tangential law can stop the slip."""
    steel = FACE_SURFACES["grooved_blasted_steel"]
    scenes = []
    for face in (attrs.evolve(FACE_PRESETS["rigid"], surface=steel),
                 attrs.evolve(FACE_PRESETS["titanium"], mass=0.2, surface=steel)):
        for friction in (0.05, 0.1):
            for angle in (55.0, 65.0, 75.0):
                scenes.append(Scene(BALL_PRESETS["urethane_tour"], face, Contact(friction, 0.8),
                                    Impact(40.0, float(np.radians(angle)), 0.0)))
    keys = scenes[0].inputs().keys()
    return {key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys}


def rigid_coulomb_closed_form(speed, angle, ball_mass, inertia_factor, club_mass, friction, restitution):
    """Stronge's rigid-body Coulomb impact of a ball without spin on a face (physics brief section 4), written
    here apart from the models (impactlab.physics.rigid) so that the conformance suite is an independent oracle.

    J_n = (1 + e) m* V cos(alpha), 1/m* = 1/m + 1/M; the ball slides throughout when
    V sin(alpha) >= mu J_n (1 + 1/K^2 + m/M)/m, and then J_t = mu J_n; otherwise it leaves rolling,
    J_t = V sin(alpha) m / (1 + 1/K^2 + m/M). On a fixed face (M = inf) the ball leaves, relative to the path
    (the club's velocity), at theta = alpha - atan(J_t / ((1 + e) m V cos alpha)) with the backspin
    omega = J_t / (K^2 m R) (divide by R outside) and the speed sqrt(((1 + e) V cos alpha)^2 + (J_t/m)^2).

    Parameters
    ----------
    speed, angle : array
        Impact speed V [m/s] and face normal relative to path alpha [rad].
    ball_mass, inertia_factor, club_mass : array
        m [kg], K^2 [-], M [kg] (inf: a fixed face).
    friction, restitution : array
        mu and e.

    Returns
    -------
    dict of ndarray
        ``normal_impulse``, ``tangential_impulse`` [N s], ``sliding`` (bool) and, for a fixed face,
        ``launch_angle`` [rad], ``ball_speed`` [m/s] and ``spin_times_radius`` [m/s] (omega R).

    References
    ----------
    W. J. Stronge, Impact Mechanics, Cambridge University Press (2000), ch. 5; R. M. Brach, Mechanical Impact
    Dynamics, Wiley (1991).
    """
    m, k2, big_m = (np.asarray(v, float) for v in (ball_mass, inertia_factor, club_mass))
    ratio = np.where(np.isinf(big_m), 0.0, m / np.where(np.isinf(big_m), 1.0, big_m))
    reduced = m / (1.0 + ratio)
    vz, vx = speed * np.cos(angle), speed * np.sin(angle)
    jn = (1.0 + restitution) * reduced * vz
    tangential_mobility = (1.0 + 1.0 / k2 + ratio) / m
    sliding = vx >= friction * jn * tangential_mobility
    jt = np.where(sliding, friction * jn, vx / tangential_mobility)
    normal_out = (1.0 + restitution) * vz  # ground-frame normal speed of the ball on a fixed face
    return {"normal_impulse": jn, "tangential_impulse": jt, "sliding": sliding,
            "launch_angle": angle - np.arctan2(jt / m, normal_out), "ball_speed": np.hypot(normal_out, jt / m),
            "spin_times_radius": jt / (k2 * m)}


def check_full_sliding(model: ImpactModel) -> None:
    """In gross slip the friction force is mu times the normal force throughout, so J_t = mu J_n exactly, with
    the sign that opposes the slip (positive: backspin), on fixed and free faces, for any tangential law."""
    inputs = _sliding_inputs()
    result = model.compute(inputs, ["normal_impulse", "tangential_impulse"])
    jn, jt = result["normal_impulse"].values, result["tangential_impulse"].values
    ratio = jt / (inputs["friction"] * jn)
    worst = int(np.argmax(np.abs(ratio - 1.0)))
    assert np.all(np.abs(ratio - 1.0) <= 2e-3), (
        f"in gross slip J_t/(mu J_n) = {ratio[worst]:.4g} (mu {inputs['friction'][worst]:g}, alpha "
        f"{np.degrees(inputs['angle'][worst]):.0f} deg), expected 1: "
        + ("the tangential impulse has the wrong sign (it must oppose the slip: positive for backspin)"
           if ratio[worst] < 0 else "mu is applied with a factor (2 mu?) or another input than friction"
           if abs(abs(ratio[worst]) - round(abs(ratio[worst]))) < 0.05 and round(abs(ratio[worst])) > 1
           else "the slip stops (or is capped) where it must not, or the friction law is not Coulomb's in gross slip"))


def check_rigid_limit(model: ImpactModel) -> None:
    """Against the rigid-body closed form (:func:`rigid_coulomb_closed_form`), in gross slip where every tangential
    law agrees with it: J_n = (1 + e) m* V_z on fixed and point-mass faces (for a model that takes the
    restitution input), and on a fixed face the launch angle, ball speed and spin the two impulses give."""
    inputs = _sliding_inputs()
    names = ["normal_impulse", "tangential_impulse", "launch_angle", "ball_speed", "spin_rate"]
    result = model.compute(inputs, names)
    closed = rigid_coulomb_closed_form(inputs["speed"], inputs["angle"], inputs["ball_mass"],
                                       inputs["ball_inertia_factor"], inputs["club_mass"], inputs["friction"],
                                       inputs["restitution"])
    assert np.all(closed["sliding"]), "reference batch must slide throughout"
    if "restitution" in model.requires | model.optional_inputs:
        jn = result["normal_impulse"].values
        ratio = jn / closed["normal_impulse"]
        free = np.isfinite(inputs["club_mass"])
        assert np.allclose(ratio, 1.0, rtol=2e-3), (
            f"J_n/((1 + e) m* V_z) = {ratio.min():.4g}..{ratio.max():.4g} (fixed faces "
            f"{ratio[~free].min():.4g}, free faces {ratio[free].min():.4g}), expected 1: "
            + ("the club's mass is left out of m* (1/m* = 1/m + 1/M)" if np.allclose(ratio[~free], 1.0, rtol=2e-3)
               else "the restitution input is not applied as e = V_z'/V_z"))
    fixed = np.isinf(inputs["club_mass"])
    # the derived outputs from the model's own J_n (a model without the restitution input has its own e)
    jn = result["normal_impulse"].values[fixed]
    jt = inputs["friction"][fixed] * jn
    m, vz = inputs["ball_mass"][fixed], inputs["speed"][fixed] * np.cos(inputs["angle"][fixed])
    normal_out = jn / m - vz + vz  # ground-frame normal speed of the ball: J_n/m on a fixed face
    expected = {"launch_angle": (inputs["angle"][fixed] - np.arctan2(jt / m, normal_out)) * RAD_TO_DEG,
                "ball_speed": np.hypot(normal_out, jt / m),
                "spin_rate": jt / (inputs["ball_inertia_factor"][fixed] * m * inputs["ball_radius"][fixed])
                * RADS_TO_RPM}
    causes = {"launch_angle": "the launch angle is measured from another direction than the path, or J_t enters "
                              "it with the wrong sign",
              "ball_speed": "the ball's velocity is not J/m from rest",
              "spin_rate": "the spin is not R J_t / I (a wrong inertia, the sign flipped: friction gives backspin "
                           "+, or the incoming spin counted the other way)"}
    for name, values in expected.items():
        got = result[name].values[fixed]
        assert np.allclose(got, values, rtol=2e-3, atol=1e-6), \
            f"{name} {got[0]:.5g} against the rigid closed form {values[0]:.5g} in gross slip: {causes[name]}"


def check_arriving_rolling(model: ImpactModel) -> None:
    """A ball that arrives rolling on the face (incoming spin V sin(alpha) / R, counted like ``spin_rate``) has no
    slip to oppose: no tangential impulse and its spin unchanged, for any tangential law. A model that counts
    the incoming spin the other way doubles the slip instead."""
    inputs = _sliding_inputs()
    inputs["spin"] = inputs["speed"] * np.sin(inputs["angle"]) / inputs["ball_radius"]
    result = model.compute(inputs, ["normal_impulse", "tangential_impulse"])
    ratio = np.abs(result["tangential_impulse"].values / result["normal_impulse"].values)
    assert np.all(ratio <= 1e-9), (
        f"a ball arriving rolling gets |J_t|/J_n = {ratio.max():.3g}: the incoming spin is counted with the wrong "
        "sign (positive spin is the backspin a lofted face gives, which reduces the slip) or not at all")


def _flat_head_inputs(friction: float = 0.05):
    """Off-centre strikes on a flat, unlofted free head (the 3-D frame is then the ground frame, so the reference
    needs no face geometry): CG 35 mm behind the face centre, principal axes along toe, up and target, struck
    20 mm toward toe or heel and 10 mm up, club 45 m/s along the target line descending 30 deg (spin loft 30 deg,
    gross slip at mu 0.05)."""
    head = ClubHead(mass=0.2, inertia=(3.0e-4, 4.5e-4, 2.5e-4), center_of_mass=(0.0, 0.0, 0.035), loft=0.0,
                    material=CLUB_PRESETS["driver"].material, surface=FACE_SURFACES["smooth_titanium"])
    with warnings.catch_warnings():  # a 30 deg descent is no golf shot: it is chosen for a large, steady slip
        warnings.simplefilter("ignore", PlausibilityWarning)
        scenes = [Scene.from_delivery(BALL_PRESETS["urethane_tour"], Scene.face_of(head), Contact(friction, 0.8),
                                      Delivery(45.0, attack_angle=-np.radians(30.0), dynamic_loft=0.0), 0.0, head,
                                      Strike(toe, 0.01))
                  for toe in (0.02, -0.02, 0.0)]
    keys = set.intersection(*(set(scene.inputs()) for scene in scenes))
    return {key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys}, head


def sliding_impulse_3d(initial_velocity, mobility, friction, normal_impulse):
    """The impulse (3-vector) of a contact that slides throughout, as a function of its normal impulse.

    Integrates dv/dp = W (n - mu s(v)) from v(0) to p = ``normal_impulse`` with scipy's adaptive Runge-Kutta
    (s: the unit slip direction, which turns where W couples normal and tangential directions; physics brief
    section 10). Written apart from impactlab.physics.rigid, in the frame (x, y, z) with n = z.

    Returns
    -------
    impulse : ndarray, shape (3,)
    min_slip : float
        The smallest slip speed on the way [m/s]; gross slip needs it above 0.
    """
    from scipy.integrate import solve_ivp

    def rate(_, state):
        slip = state[:2]
        direction = slip / np.linalg.norm(slip)
        push = np.array([-friction * direction[0], -friction * direction[1], 1.0])
        return np.concatenate([mobility @ push, push])

    solution = solve_ivp(rate, (0.0, normal_impulse), np.concatenate([initial_velocity, np.zeros(3)]),
                         rtol=1e-10, atol=1e-12, method="DOP853")
    return solution.y[3:, -1], float(np.min(np.linalg.norm(solution.y[:2], axis=0)))


def flat_head_mobility(inputs: dict, head: ClubHead, case: int) -> np.ndarray:
    """The mobility W of ball plus free head at the strike point of :func:`_flat_head_inputs`'s case, in the
    contact frame (s, l, n), written here apart from impactlab.physics.contact (physics brief section 10):
    W = (1/m) [1 + (1 - n n^T)/K^2] + (1/M) 1 + [r]^T I_G^-1 [r], r from the head's CG to the strike point."""
    m, k2 = inputs["ball_mass"][case], inputs["ball_inertia_factor"][case]
    # (s, l, n): n the target axis (flat, unlofted face), s up the face (the club descends, so the ball slides up
    # it), l = n x s: the toe axis (a right-handed golfer's toe points left of the target line, target x up = left)
    to_contact = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])  # rows: s, l, n in (toe, up, target)
    inertia = to_contact @ np.diag([head.inertia[0][0], head.inertia[1][1], head.inertia[2][2]]) @ to_contact.T
    lever = np.array([inputs["strike_high"][case], inputs["strike_toe"][case], head.center_of_mass[2]])
    cross = np.array([[0.0, -lever[2], lever[1]], [lever[2], 0.0, -lever[0]], [-lever[1], lever[0], 0.0]])
    return (np.eye(3) + np.diag([1.0, 1.0, 0.0]) / k2) / m + np.eye(3) / head.mass \
        + cross.T @ np.linalg.inv(inertia) @ cross


#: the flat head's club speed [m/s] and descent [rad]: the ball meets it at (sin, 0, -cos) x speed in (s, l, n)
_FLAT_SPEED, _FLAT_DESCENT = 45.0, np.radians(30.0)


def check_3d_sideways_impulse(model: ImpactModel) -> None:
    """Off-centre strikes on a free head against an independent rigid-body solution (:func:`flat_head_mobility`).

    Without friction the normal impulse is (1 + e) V_n / W_nn, the off-centre effective mass of Cross & Nathan
    (a model that takes the restitution input; to 2e-3). In gross slip (mu 0.05) the tangential impulse is
    mu J_n along the turning slip, and the sideways one that of the slip integrated over the normal impulse
    (:func:`sliding_impulse_3d`, up to the model's own J_n): the tangential one to 2 %, the sideways one with its
    sign and within a factor 2, because the tangential laws differ there: a rigid Coulomb integration agrees to
    4e-4, a tangential spring lags the turning slip (maw, hertz_mindlin, dem_linear 8-18 % lower on these
    strikes), and the restitution model's cap aims at no lateral slip at separation (66 % higher).
    """
    if not model.solves_3d():
        return
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse"]
    velocity = _FLAT_SPEED * np.array([np.sin(_FLAT_DESCENT), 0.0, -np.cos(_FLAT_DESCENT)])
    if "restitution" in model.requires | model.optional_inputs:
        inputs, head = _flat_head_inputs(0.0)
        jn = model.compute(inputs, names)["normal_impulse"].values
        expected = np.array([(1.0 + inputs["restitution"][case]) * -velocity[2]
                             / flat_head_mobility(inputs, head, case)[2, 2] for case in range(jn.size)])
        assert np.allclose(jn, expected, rtol=2e-3), (
            f"frictionless off-centre J_n {jn[0]:.5g} N s against (1 + e) V_n / W_nn = {expected[0]:.5g} N s: "
            "the head is taken as a point mass (its inertia and the lever from its CG to the strike point missing "
            "from the mobility), or the strike point is misplaced")
    inputs, head = _flat_head_inputs(0.05)
    result = model.compute(inputs, names)
    for case in range(len(inputs["speed"])):
        toe, jn = inputs["strike_toe"][case], result["normal_impulse"].values[case]
        impulse, min_slip = sliding_impulse_3d(velocity, flat_head_mobility(inputs, head, case), 0.05, jn)
        assert min_slip > 1.0, "the reference strike must slide throughout"
        where = f"(strike {toe * 1e3:+.0f} mm toe, J_n {jn:.4g} N s)"
        got = result["tangential_impulse"].values[case]
        assert abs(got + impulse[0]) <= 0.02 * abs(impulse[0]), (
            f"tangential_impulse {got:.5g} N s against the rigid-body solution {-impulse[0]:.5g} N s {where}: "
            "friction is not mu J_n in gross slip, or the impulse has the wrong sign")
        got, expected = result["lateral_impulse"].values[case], impulse[1]
        if abs(expected) <= 1e-9 * jn:  # a centred strike: no sideways impulse
            assert abs(got) <= 1e-6 * jn, f"lateral_impulse {got:.3g} N s on a centred strike {where}: " \
                "a sideways impulse without an off-centre lever (the contact frame or the lever is wrong)"
            continue
        ratio = got / expected
        assert 0.5 <= ratio <= 2.0, (
            f"lateral_impulse {got:.4g} N s against the rigid-body solution {expected:.4g} N s {where}: "
            + ("the sideways impulse is dropped, or the head is taken as a point mass (no lever from its CG)"
               if abs(ratio) < 0.05 else "the sideways impulse has the wrong sign (toe and heel swapped, or l is "
               "not n x s)" if ratio < 0 else "the sideways impulse is far from the slip the coupled mobility turns"))


#: optional inputs whose absence has one meaning for every model: a ball without spin, a face that does not move
NEUTRAL_WHEN_ABSENT = {"spin": 0.0, "club_mass": np.inf}


def check_optional_inputs_absent(model: ImpactModel) -> None:
    """Rule 3: an optional input that was not given is absent, and the model runs without it.

    Without ``spin`` and ``club_mass`` (where optional), results equal those with the ball given no spin and
    the face an infinite mass; a model that reads ``inputs["spin"]`` unguarded fails here.
    """
    inputs = reference_inputs(n_angles=3)
    dropped = [name for name in NEUTRAL_WHEN_ABSENT if name in model.optional_inputs and name not in model.requires]
    if not dropped:
        return
    absent = {name: value for name, value in inputs.items() if name not in dropped}
    neutral = dict(absent, **{name: np.full(inputs["speed"].shape, NEUTRAL_WHEN_ABSENT[name]) for name in dropped})
    outputs = _scalar_outputs(model, neutral)
    try:
        without = model.compute(absent, outputs)
    except KeyError as exc:
        raise AssertionError(f"the hook read the optional input {exc} that was not given; "
                             "read optional inputs with inputs.get(name, default)") from None
    given = model.compute(neutral, outputs)
    for name in outputs:
        assert np.allclose(without[name].values, given[name].values, rtol=1e-12, atol=0, equal_nan=True), \
            f"{name} without {', '.join(dropped)} differs from the same cases with no spin and a fixed face"


CHECKS: dict[str, Callable[[ImpactModel], None]] = {
    "declarations": check_declarations,
    "capabilities": check_capabilities,
    "runs_finite": check_runs_finite,
    "energy_never_increases": check_energy_never_increases,
    "normal_impulse_bounds": check_normal_impulse_bounds,
    "tangential_restitution_bounds": check_tangential_restitution_bounds,
    "frictionless": check_frictionless,
    "head_on": check_head_on,
    "mirror_symmetry": check_mirror_symmetry,
    "batch_independence": check_batch_independence,
    "inputs_untouched": check_inputs_untouched,
    "optional_inputs_absent": check_optional_inputs_absent,
    "full_sliding": check_full_sliding,
    "rigid_limit": check_rigid_limit,
    "arriving_rolling": check_arriving_rolling,
    "3d_energy_never_increases": check_3d_energy_never_increases,
    "3d_sideways_impulse": check_3d_sideways_impulse,
    "3d_heel_toe_mirror": check_3d_heel_toe_mirror,
    "3d_batch_independence": check_3d_batch_independence,
}


def iter_checks(model: ModelLike) -> Iterator[tuple[str, Callable[[], None]]]:
    """(name, zero-argument callable) for each conformance check of ``model`` (class or instance)."""
    instance = _model(model)
    for name, check in CHECKS.items():
        yield name, functools.partial(check, instance)


def parametrize_with_checks(*models: ModelLike) -> pytest.MarkDecorator:
    """A ``pytest.mark.parametrize`` over every (model, check) pair, one test each, as scikit-learn's is.

    Examples
    --------
    >>> from impactlab.testing import parametrize_with_checks
    >>> @parametrize_with_checks(MyModel, MyModel(option=2))            # doctest: +SKIP
    ... def test_conformance(model, check):
    ...     check(model)
    """
    # pytest is a test dependency, not one of impactlab's: imported only when a plugin's tests ask for this
    import pytest

    cases, ids = [], []
    for model in models:
        instance = _model(model)
        for name, check in CHECKS.items():
            cases.append((instance, check))
            ids.append(f"{instance.name}-{name}")
    return pytest.mark.parametrize(("model", "check"), cases, ids=ids)


def check_model(model: ModelLike) -> None:
    """Run every conformance check; raise AssertionError listing all that failed."""
    failures = []
    for name, run in iter_checks(model):
        try:
            run()
        except AssertionError as exc:
            failures.append(f"{name}: {exc}")
    if failures:
        raise AssertionError(f"model {_model(model).name!r} fails conformance:\n  " + "\n  ".join(failures))
