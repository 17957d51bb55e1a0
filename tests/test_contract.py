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
from impactlab_models._compliant import CompliantOptions
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
    assert {name for name, cls in models.items() if cls.has_tolerance} == {"maw", "hertz_mindlin", "dem_linear",
                                                                          "hertz_mindlin_lever", "hertz_mindlin_face"}
    assert {name for name, cls in models.items() if cls.provides_histories} == {"maw", "hertz_mindlin", "dem_linear",
                                                                                "hertz_mindlin_lever",
                                                                                "hertz_mindlin_face"}
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


def test_table1_is_stored_once():
    from impactlab.plot.paper import table1
    from impactlab.data.validation import DATASETS

    published = table1()
    assert list(published) == list(DATASETS["wood2018"].labels)
    assert published["driver"] == {"trackman": 87.0, "wood": (83.0, 8.0)}
    assert published["pitching wedge"] == {"trackman": 70.0, "wood": (72.0, 6.0)}
