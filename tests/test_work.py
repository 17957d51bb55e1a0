"""Only the work a scene needs: proved by counting solver calls and solved cases, never by timing."""

import numpy as np
import pytest

import impactlab
from impactlab.physics import mdr
from impactlab.model.registry import get_model


@pytest.fixture
def solver_calls(monkeypatch):
    calls = []
    real = mdr.solve_scaled

    def counting(chi, psi1, **kwargs):
        calls.append({"cases": np.size(chi), "record": kwargs.get("record", False), "springs": kwargs["springs"],
                      "normal": kwargs.get("normal")})
        return real(chi, psi1, **kwargs)

    monkeypatch.setattr(mdr, "solve_scaled", counting)
    return calls


def test_frictionless_and_slip_free_cases_skip_the_tangential_solve(golf_inputs, solver_calls):
    inputs = golf_inputs(friction=[0.0, 0.4, 0.0, 0.3, 0.4], angle=np.radians([20.0, 20.0, 30.0, 0.0, 15.0]))
    get_model("maw")().compute(inputs, ["launch_ratio"])
    assert [call["cases"] for call in solver_calls] == [2]  # mu = 0 twice, and head-on once, need no solve


def test_no_time_series_unless_histories_are_asked(golf_inputs, solver_calls):
    model = get_model("maw")()
    model.compute(golf_inputs(angle=np.radians([10.0, 30.0])), ["launch_ratio", "spin_rate"])
    model.compute(golf_inputs(angle=np.radians([10.0, 30.0])), ["normal_force"])  # normal history: closed form
    assert solver_calls and not any(call["record"] for call in solver_calls)
    model.compute(golf_inputs(angle=np.radians([10.0, 30.0])), ["tangential_force"])
    assert solver_calls[-1]["record"] is True


@pytest.mark.slow
def test_one_normal_solution_serves_every_case_with_the_same_restitution(golf_inputs, solver_calls):
    model = get_model("maw")(inelastic="hysteretic")
    e = np.repeat([0.6, 0.8, 0.9], 10)
    model.compute(golf_inputs(restitution=e, angle=np.radians(np.tile(np.linspace(5, 50, 10), 3)),
                              friction=np.tile([0.2, 0.4], 15)), ["launch_ratio"])
    # one damped normal history per distinct e, shared by its ten cases (solved in one batch per resolution)
    laws = {id(call["normal"]) for call in solver_calls}
    assert len(laws) == 3
    assert sorted(sum(call["cases"] for call in solver_calls if id(call["normal"]) == law) for law in laws) == \
        [10, 10, 10]


def test_elastic_cases_share_batched_solves_by_resolution_whatever_friction_or_speed(golf_inputs, solver_calls):
    # the resolution depends on chi and psi1 only, so speed never splits a batch and each rung of the
    # resolution ladder is one batched solve
    mu, alpha, speed = np.meshgrid([0.1, 0.3, 0.5], np.radians([5, 15, 30, 45]), [20.0, 40.0], indexing="ij")
    inputs = golf_inputs(friction=mu.ravel(), angle=alpha.ravel(), speed=speed.ravel())
    get_model("maw")().compute(inputs, ["launch_ratio"])
    assert sum(call["cases"] for call in solver_calls) == 24
    assert len({call["springs"] for call in solver_calls}) == len(solver_calls) <= 12  # 12 distinct psi1


def test_rigid_models_solve_nothing(golf_inputs, solver_calls):
    study = {"ball": {"radius": "21 mm", "mass": "46 g"}, "contact": {"friction": 0.3, "restitution": 0.8},
             "impact": {"speed": "40 m/s", "angle": "20 deg"}, "sweep": {"impact.angle": ["5 deg", "10 deg", "20 deg"]},
             "models": ["rigid_coulomb", "restitution"]}
    ds = impactlab.run_study(study)
    assert solver_calls == []
    assert np.all(ds.steps.values == 0)


def test_the_plan_says_what_runs_and_is_stored_with_the_result():
    study = {"ball": {"preset": "urethane_tour"}, "face": {"rigid": True}, "contact": {"friction": 0.3,
             "restitution": 0.8}, "impact": {"speed": "40 m/s", "angle": "20 deg"}, "models": ["maw", "rigid_coulomb"],
             "outputs": ["launch_ratio", "contact_time", "spin_axis"]}
    from impactlab.run.runner import plan_study

    text = plan_study(impactlab.load_study(study)).describe()
    assert "[maw] maw: computes" in text and "contact_time" in text
    assert "[rigid_coulomb]" in text and "leaves contact_time NaN (a rigid-body impulse model has no contact" in text
    assert "leaves spin_axis NaN (needs a golf delivery" in text
    ds = impactlab.run_study(study)
    assert ds.attrs["plan"] == text
