"""The explicit contract: declared capabilities, the Protocols the models share, and no side effects on callers."""

import subprocess
import sys
import textwrap
import warnings

import attrs
import numpy as np
import pytest

import impactlab
from impactlab.data.convergence import work_precision
from impactlab.errors import ModelContractError
from impactlab.study.limits import estimate
from impactlab.physics import hertz
from impactlab.model.registry import available
from impactlab.testing import check_capabilities, check_model
from impactlab.vocabulary import HISTORY_OUTPUTS, OUTPUTS, SCALAR_OUTPUTS, is_history, is_scalar
from impactlab_models.shared import CompliantOptions
from impactlab_models.rigid_coulomb import RigidCoulombModel


@attrs.frozen
class _TolerantOptions:
    tolerance: float = 1e-3


def test_the_split_of_outputs_is_decided_once():
    assert set(SCALAR_OUTPUTS) | set(HISTORY_OUTPUTS) == set(OUTPUTS)
    assert not set(SCALAR_OUTPUTS) & set(HISTORY_OUTPUTS)
    assert is_history("tangential_force") and not is_scalar("tangential_force")
    assert is_scalar("launch_angle") and not is_history("launch_angle")
    assert not is_scalar("no_such_output") and not is_history("no_such_output")


def test_capabilities_are_declared_on_the_builtin_models():
    models = available()
    compliant = {"maw", "hertz_mindlin", "dem_linear", "hertz_mindlin_lever", "hertz_mindlin_face",
                 "hertz_mindlin_slip"}
    assert {name for name, cls in models.items() if cls.has_tolerance} == compliant
    assert {name for name, cls in models.items() if cls.provides_histories} == compliant
    for cls in models.values():
        assert cls.has_tolerance == ("tolerance" in {field.name for field in attrs.fields(cls.Options)})


def test_provides_histories_follows_provides_in_every_subclass():
    class Forces(RigidCoulombModel):
        name = "forces"
        provides = RigidCoulombModel.provides | {"normal_force"}

    assert Forces.provides_histories and not RigidCoulombModel.provides_histories


def test_conformance_catches_a_tolerance_field_without_the_declaration():
    class Undeclared(RigidCoulombModel):
        """Has a tolerance option but does not say so. References: none."""

        name = "undeclared"
        Options = _TolerantOptions

    with pytest.raises(AssertionError, match="declare has_tolerance = True"):
        check_capabilities(Undeclared())


def test_conformance_catches_a_declared_tolerance_without_the_field():
    class Claims(RigidCoulombModel):
        """Declares a tolerance it has no option for. References: none."""

        name = "claims"
        has_tolerance = True

    with pytest.raises(AssertionError, match="capabilities: has_tolerance is declared but Options has no field"):
        check_model(Claims)


def test_conformance_catches_histories_without_time():
    class NoTime(RigidCoulombModel):
        """Declares a force history and returns it without its time axis. References: none."""

        name = "no_time"
        provides = RigidCoulombModel.provides | {"normal_force"}

        def _compute(self, inputs, outputs):
            result = super()._compute(inputs, outputs - {"normal_force"}) if outputs - {"normal_force"} else {}
            if "normal_force" in outputs:
                result["normal_force"] = np.zeros((inputs["speed"].size, 3))
            return result

    with pytest.raises(AssertionError, match="without 'time'"):
        check_capabilities(NoTime())


def test_a_compliant_model_refuses_options_that_miss_the_protocol():
    from impactlab_models.maw import MawModel

    @attrs.frozen
    class Partial:
        tolerance: float = 1e-4

    class Broken(MawModel):
        name = "broken"
        Options = Partial

    with pytest.raises(ModelContractError, match="CompliantOptions"):
        Broken()
    for name in ("maw", "hertz_mindlin", "dem_linear"):
        assert isinstance(available()[name]().options, CompliantOptions)


def test_the_normal_laws_share_one_protocol():
    assert isinstance(hertz.ELASTIC, hertz.NormalLaw)
    assert isinstance(hertz.DampedNormal(0.2), hertz.NormalLaw)


def test_reference_options_need_a_declared_tolerance():
    with pytest.raises(ModelContractError, match="has_tolerance"):
        RigidCoulombModel().reference_options(1e-6)


STUDY = {"name": "wp", "ball": {"preset": "urethane_tour"}, "face": {"rigid": True},
         "contact": {"friction": 0.3, "restitution": 1.0}, "impact": {"speed": "40 m/s", "angle": "20 deg"},
         "sweep": {"impact.angle": ["10 deg", "30 deg"]}, "outputs": ["tangential_impulse"]}


def test_convergence_sweeps_exactly_the_models_that_declare_a_tolerance():
    class Tolerant(RigidCoulombModel):
        """A closed form that declares a tolerance: convergence must sweep it. References: none."""

        name = "tolerant"
        has_tolerance = True
        Options = _TolerantOptions

    study = impactlab.load_study({**STUDY, "models": ["rigid_coulomb", "dem_linear"]})
    ds = work_precision(study, tolerances=(1e-2, 1e-3), repeats=1)
    notes = ds.attrs["reference"]
    assert "closed form" in notes.split('"rigid_coulomb"')[1].split(",")[0]
    assert "reference" in notes.split('"dem_linear"')[1]
    # the declaration, not the options' fields, decides: a model that declares it is swept like dem_linear
    study = attrs.evolve(study, models=(attrs.evolve(study.models[0], model=Tolerant()),))
    notes = work_precision(study, tolerances=(1e-2,), repeats=1).attrs["reference"]
    assert "closed form" not in notes and "Tolerant" in notes


def test_the_memory_estimate_counts_declared_expert_resolutions():
    from impactlab_models.dem import DemLinearModel
    from impactlab_models.maw import MawModel

    assert MawModel().expert_resolution() is None and DemLinearModel().expert_resolution() is None
    steps = MawModel(springs=100).options.resolution_steps(100)  # mdr: the steps follow the springs
    assert MawModel(springs=100).expert_resolution() == (100, steps)
    assert MawModel(method="annuli", rings=20, steps=500).expert_resolution() == (20, 500)
    assert DemLinearModel(steps=4000).expert_resolution() == (1, 4000)
    assert RigidCoulombModel().expert_resolution() is None
    small = impactlab.load_study({**STUDY, "models": ["maw"]})
    big = impactlab.load_study({**STUDY, "models": [{"name": "maw", "springs": 400, "steps": 4000}]})
    assert estimate(small).kernel_memory == 0 < estimate(big).kernel_memory


@pytest.mark.slow
def test_library_plots_leave_the_callers_backend_alone(tmp_path):
    # a fresh interpreter: the test session's own backend cannot hide a library call that switches it
    script = textwrap.dedent(f"""
        import sys
        import matplotlib
        matplotlib.use("svg")
        import impactlab
        from impactlab.plot.figures import plot_histories, plot_results
        from impactlab.data.convergence import work_precision
        from impactlab.plot.analysis import plot_work_precision
        study = {{"name": "p", "ball": {{"preset": "urethane_tour"}}, "face": {{"rigid": True}},
                 "contact": {{"friction": 0.3, "restitution": 1.0}}, "impact": {{"speed": "40 m/s", "angle": "20 deg"}},
                 "sweep": {{"impact.angle": ["10 deg", "30 deg"]}}, "models": ["maw", "rigid_coulomb"],
                 "outputs": ["launch_angle", "tangential_force"]}}
        ds = impactlab.run_study(study)
        plot_results(ds, r"{tmp_path / 'a.png'}")
        plot_histories(ds, r"{tmp_path / 'b.png'}")
        wp = work_precision(impactlab.load_study({{**study, "outputs": ["launch_angle"]}}), tolerances=(1e-2,),
                            repeats=1)
        plot_work_precision(wp, r"{tmp_path / 'c.png'}")
        print(matplotlib.get_backend(), "matplotlib.pyplot" in sys.modules)
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split()[-2:] == ["svg", "False"]
    assert all((tmp_path / name).stat().st_size > 0 for name in ("a.png", "b.png", "c.png"))


def test_no_library_module_selects_a_backend_or_uses_pyplot():
    from pathlib import Path

    root = Path(impactlab.__file__).parent
    offenders = [str(path.relative_to(root)) for path in root.rglob("*.py")
                 if "matplotlib.use(" in path.read_text() or "import matplotlib.pyplot" in path.read_text()]
    assert not offenders


def test_cli_main_puts_the_warning_hook_and_limits_back(capsys):
    from impactlab.study import limits
    from impactlab.cli import main

    def mine(*args, **kwargs):
        pass

    with warnings.catch_warnings():
        warnings.showwarning = mine
        before_filters = list(warnings.filters)
        limits.configure(max_cases=12345)
        try:
            assert main(["models"]) == 0
            assert warnings.showwarning is mine
            assert warnings.filters == before_filters
            assert main(["run", "/no/such/study.yaml", "--max-cases", "7"]) == 2  # a failing command too
            assert warnings.showwarning is mine and warnings.filters == before_filters
            assert limits.max_cases() == 12345
        finally:
            limits.configure()
    capsys.readouterr()


def test_unit_constants_are_pints():
    from impactlab import units

    ureg = units.registry()
    assert units.RAD_TO_DEG == ureg.Quantity(1.0, "rad").to("deg").magnitude
    assert units.RADS_TO_RPM == ureg.Quantity(1.0, "rad/s").to("rpm").magnitude
    assert units.MPH == ureg.Quantity(1.0, "mph").to("m/s").magnitude
    for factor, unit in ((units.YARD, "yard"), (units.FOOT, "foot"), (units.INCH, "inch")):
        assert factor == pytest.approx(ureg.Quantity(1.0, unit).to("m").magnitude, rel=1e-15), unit


def test_table1_is_stored_once():
    from impactlab.plot.paper import table1
    from impactlab.data.validation import DATASETS

    published = table1()
    assert list(published) == list(DATASETS["wood2018"].labels)
    assert published["driver"] == {"trackman": 87.0, "wood": (83.0, 8.0)}
    assert published["pitching wedge"] == {"trackman": 70.0, "wood": (72.0, 6.0)}


# -- rule 9: a 3-D contact is seen whole or refused (issue 34) ------------------------------------------------------

def _forgetful(base=RigidCoulombModel, **attributes):
    """rigid_coulomb's physics in a plugin that declares what a plate experiment needs and no more (as issue 34's
    researcher did): it never hears of the strike point, the head's body or the delivery."""
    from impactlab.physics.contact import CONTACT_STATE_INPUTS

    namespace = {"__doc__": "Forgets the 3-D inputs. References: none.", "name": "forgetful",
                 "optional_inputs": base.optional_inputs - (CONTACT_STATE_INPUTS - {"spin", "club_mass"}),
                 **attributes}
    if "provides" in attributes:  # a model on one line: gives only what it provides
        def _compute(self, inputs, outputs):
            return {key: value for key, value in base._compute(self, inputs, outputs).items() if key in self.provides}

        namespace["_compute"] = _compute
    return type("Forgetful", (base,), namespace)


def _driver_strikes():
    from impactlab.testing import reference_inputs_3d

    inputs = reference_inputs_3d()
    keep = (inputs["club_inertia_toe_up"] != 0.0) & (inputs["face_angle"] == 0.0) & (inputs["friction"] == 0.4)
    return {key: value[keep] for key, value in inputs.items()}


def test_a_model_that_does_not_see_the_3d_contact_is_refused_naming_the_inputs():
    from impactlab.errors import ModelInputError

    Forgetful = _forgetful(provides=frozenset({"normal_impulse", "tangential_impulse"}))
    with pytest.raises(ModelInputError) as info:
        Forgetful().compute(_driver_strikes(), ["spin_axis"])
    message = str(info.value)
    for name, path in (("strike_toe", "strike.toe"), ("club_inertia_toe", "club.inertia.toe"),
                       ("face_angle", "delivery.face_angle"), ("face_bulge_radius", "club.bulge_radius")):
        assert f"{name} ({path})" in message
    assert "takes_contact_state" in message and "CONTACT_STATE_INPUTS" in message
    # planned in a study: refused before the first case runs (exit 2 on the command line)
    study = impactlab.load_study({**GOLF, "models": [{"name": Forgetful()}]})
    from impactlab.run.runner import plan_study

    with pytest.raises(ModelInputError, match="strike_toe"):
        plan_study(study)


def test_on_a_plate_the_same_model_runs_as_before():
    from impactlab.testing import reference_inputs

    inputs = reference_inputs(n_angles=3)
    Forgetful = _forgetful(provides=frozenset({"normal_impulse", "tangential_impulse"}))
    a = Forgetful().compute(inputs, ["normal_impulse", "tangential_impulse"])
    b = RigidCoulombModel().compute(inputs, ["normal_impulse", "tangential_impulse"])
    assert np.array_equal(a["tangential_impulse"].values, b["tangential_impulse"].values)


def test_a_model_that_takes_the_contact_state_sees_the_whole_scene():
    """The silent error of issue 34: without the strike point the forgetful model posed centre strikes. Taking
    the framework's contact state it gives rigid_coulomb's answer exactly, heel and toe spinning opposite ways."""
    Taking = _forgetful(takes_contact_state=True)
    inputs = _driver_strikes()
    names = ["lateral_impulse", "spin_axis"]
    ours, reference = Taking().compute(inputs, names), RigidCoulombModel().compute(inputs, names)
    np.testing.assert_array_equal(ours["spin_axis"].values, reference["spin_axis"].values)
    toe = inputs["strike_toe"]
    axis = ours["spin_axis"].values
    # gear effect: a toe strike draws (axis < 0, curving left), a heel strike fades
    assert np.all(axis[toe > 0.005] < axis[toe < -0.005].min())


def test_plugins_are_checked_when_they_load():
    from importlib import metadata

    from impactlab.errors import PluginWarning
    from impactlab.model import registry

    module = type(sys)("contract_plugins")
    module.Forgetful3D = _forgetful()  # provides lateral_impulse: claims 3-D contacts it cannot see
    module.Misspelt = type("Misspelt", (RigidCoulombModel,), {"name": "misspelt", "__doc__": "References: x.",
                                                              "requires": RigidCoulombModel.requires | {"spinn"}})
    module.Fine = _forgetful(takes_contact_state=True, name="fine")
    sys.modules["contract_plugins"] = module
    real = list(metadata.entry_points(group=registry.ENTRY_POINT_GROUP))
    fakes = [metadata.EntryPoint(name, f"contract_plugins:{attr}", registry.ENTRY_POINT_GROUP)
             for name, attr in (("forgetful", "Forgetful3D"), ("misspelt", "Misspelt"), ("fine", "Fine"))]
    try:
        with pytest.MonkeyPatch.context() as patch:
            patch.setattr(registry, "_entry_points", lambda: real + fakes)
            with pytest.warns(PluginWarning) as caught:
                found = registry.refresh()
    finally:
        del sys.modules["contract_plugins"]
        registry.refresh()
    text = " | ".join(str(w.message) for w in caught)
    assert "forgetful" not in found and "misspelt" not in found and "fine" in found
    assert "provides lateral_impulse (3-D contacts) but does not declare" in text and "strike_toe" in text
    assert "requires names spinn, unknown to the vocabulary's inputs" in text


GOLF = {"name": "golf", "ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
        "contact": {"friction": 0.4, "restitution": 0.8},
        "delivery": {"club_speed": "45 m/s", "path": "0 deg", "face_angle": "0 deg", "attack_angle": "0 deg",
                     "dynamic_loft": "12 deg"},
        "strike": {"toe": "10 mm", "high": "0 mm"}, "outputs": ["spin_axis"]}


def test_the_conformance_suite_names_the_missing_3d_inputs():
    from impactlab.testing import check_declarations

    with pytest.raises(AssertionError, match=r"provides lateral_impulse \(3-D contacts\) but does not declare .*"
                                             r"strike_toe"):
        check_declarations(_forgetful()())
    check_declarations(_forgetful(takes_contact_state=True)())  # taking the framework's state is the other way
