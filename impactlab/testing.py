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
failure names the likely cause. They live in :mod:`impactlab.model.reference` and run from here.
"""

from __future__ import annotations

import functools
import json
import keyword
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING

import attrs
import numpy as np

from impactlab.errors import ModelContractError
from impactlab.scene.materials import BALL_PRESETS, FACE_PRESETS, FACE_SURFACES
from impactlab.model.base import ImpactModel
from impactlab.model.contract import declaration_problems
# the reference values' oracles are re-exported here, beside the checks that use them, for plugins' own tests
from impactlab.model.reference import (check_3d_sideways_impulse, check_arriving_rolling, check_full_sliding,  # noqa: F401
                                       check_rigid_limit, flat_head_mobility, rigid_coulomb_closed_form,
                                       sliding_impulse_3d)
from impactlab.physics.mechanics import effective_mass
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.catalogue import CLUB_PRESETS
from impactlab.scene.core import Contact, Delivery, Impact, Scene, complete_inputs
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


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["RTOL", "reference_inputs", "reference_inputs_3d", "ModelLike", "check_declarations",
           "check_capabilities", "check_runs_finite", "check_energy_never_increases", "check_normal_impulse_bounds",
           "check_tangential_restitution_bounds", "check_frictionless", "check_head_on", "check_mirror_symmetry",
           "check_batch_independence", "check_3d_energy_never_increases", "check_3d_heel_toe_mirror",
           "check_3d_batch_independence", "check_inputs_untouched", "NEUTRAL_WHEN_ABSENT",
           "check_optional_inputs_absent", "check_full_sliding", "check_rigid_limit",
           "check_arriving_rolling", "check_3d_sideways_impulse", "rigid_coulomb_closed_form", "flat_head_mobility",
           "sliding_impulse_3d", "CHECKS", "iter_checks", "parametrize_with_checks", "check_model"]
