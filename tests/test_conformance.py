"""The shipped conformance suite, run over every registered model."""

import re

import pytest

from impactlab.model.registry import available
from impactlab.testing import check_model, parametrize_with_checks

MODELS = sorted(available())


def test_builtin_models_are_registered():
    assert {"maw", "rigid_coulomb", "restitution"} <= set(MODELS)


@parametrize_with_checks(*(available()[name] for name in MODELS))
def test_conformance(model, check):
    check(model)


def test_conformance_catches_a_model_that_creates_energy():
    from impactlab_models.rigid_coulomb import RigidCoulombModel

    class Bouncy(RigidCoulombModel):
        """Returns 1.5 times the elastic normal impulse. References: none."""

        name = "bouncy"

        def _compute(self, inputs, outputs):
            result = super()._compute(inputs, outputs)
            result["normal_impulse"] = result["normal_impulse"] * 1.5
            return result

    with pytest.raises(AssertionError, match="energy_never_increases"):
        check_model(Bouncy)


def test_conformance_catches_a_model_that_ignores_mirror_symmetry():
    from impactlab_models.rigid_coulomb import RigidCoulombModel

    class OneSided(RigidCoulombModel):
        """Friction that only ever pushes one way. References: none."""

        name = "one_sided"

        def _compute(self, inputs, outputs):
            result = super()._compute(inputs, outputs)
            result["tangential_impulse"] = abs(result["tangential_impulse"])
            return result

    with pytest.raises(AssertionError, match="mirror_symmetry"):
        check_model(OneSided)


def test_conformance_catches_a_model_that_reads_an_absent_optional_input():
    from impactlab_models.rigid_coulomb import RigidCoulombModel

    class Unguarded(RigidCoulombModel):
        """Reads the spin as if it were always given (rule 3 says it is absent when not). References: none."""

        name = "unguarded"

        def _compute(self, inputs, outputs):
            assert inputs["spin"].shape == inputs["speed"].shape
            return super()._compute(inputs, outputs)

    with pytest.raises(AssertionError, match="optional_inputs_absent: the hook read the optional input 'spin'"):
        check_model(Unguarded)


def test_conformance_catches_a_model_whose_absent_club_is_not_a_fixed_face():
    from impactlab_models.rigid_coulomb import RigidCoulombModel

    class PointMassByDefault(RigidCoulombModel):
        """Takes a 0.2 kg head where none is given. References: none."""

        name = "point_mass_by_default"

        def _compute(self, inputs, outputs):
            if "club_mass" not in inputs:
                inputs = dict(inputs, club_mass=inputs["speed"] * 0 + 0.2)
                from impactlab.model.case_inputs import CaseInputs

                inputs = CaseInputs(inputs)
            return super()._compute(inputs, outputs)

    with pytest.raises(AssertionError, match="optional_inputs_absent: .* differs"):
        check_model(PointMassByDefault)


# -- reference values: deliberately broken variants of rigid_coulomb, each caught, each with its likely cause ----

def _variant(name, change):
    from impactlab_models.rigid_coulomb import RigidCoulombModel

    def _compute(self, inputs, outputs):
        return change(self, inputs, outputs)

    return type(name, (RigidCoulombModel,), {"name": name.lower(), "__doc__": f"{name}. References: none.",
                                              "_compute": _compute})


def _with_inputs(inputs, **changes):
    from impactlab.model import CaseInputs

    return CaseInputs({**{name: inputs[name] for name in inputs}, **changes})


def _parent(self, inputs, outputs):
    from impactlab_models.rigid_coulomb import RigidCoulombModel

    return RigidCoulombModel._compute(self, inputs, outputs)


def _two_mu(self, inputs, outputs):
    return _parent(self, _with_inputs(inputs, friction=2.0 * inputs["friction"]), outputs)


def _no_lateral(self, inputs, outputs):
    result = _parent(self, inputs, outputs)
    result["lateral_impulse"] = 0.0 * result["lateral_impulse"]
    return result


def _spin_flipped(self, inputs, outputs):
    return _parent(self, _with_inputs(inputs, spin=-inputs["spin"]) if "spin" in inputs else inputs, outputs)


def _point_mass_head(self, inputs, outputs):
    from impactlab.model import CaseInputs
    from impactlab.physics.contact import INERTIA_INPUTS

    return _parent(self, CaseInputs({name: inputs[name] for name in inputs if name not in INERTIA_INPUTS}), outputs)


@pytest.mark.parametrize(("change", "check", "cause"), [
    (_two_mu, "full_sliding", "a factor (2 mu?)"),
    (_no_lateral, "3d_sideways_impulse", "sideways impulse is dropped"),
    (_spin_flipped, "arriving_rolling", "incoming spin is counted with the wrong sign"),
    (_point_mass_head, "3d_sideways_impulse", "taken as a point mass"),
])
def test_the_suite_catches_each_broken_variant_naming_the_cause(change, check, cause):
    from impactlab.testing import CHECKS

    model = _variant(change.__name__.strip("_").title().replace("_", ""), change)()
    with pytest.raises(AssertionError, match=re.escape(cause)):
        CHECKS[check](model)


def test_the_reference_values_hold_for_the_builtin_models_with_their_margins():
    """The oracles are independent of the models: rigid_coulomb meets them to its integration error."""
    import numpy as np

    from impactlab.model.registry import get_model
    from impactlab.model.reference import _flat_head_inputs
    from impactlab.testing import flat_head_mobility, rigid_coulomb_closed_form, sliding_impulse_3d

    inputs, head = _flat_head_inputs(0.05)
    result = get_model("rigid_coulomb")().compute(inputs, ["normal_impulse", "tangential_impulse",
                                                           "lateral_impulse"])
    velocity = 45.0 * np.array([np.sin(np.radians(30.0)), 0.0, -np.cos(np.radians(30.0))])
    impulse, _ = sliding_impulse_3d(velocity, flat_head_mobility(inputs, head, 0), 0.05,
                                    result["normal_impulse"].values[0])
    # Stronge's integration over 2000 steps of the normal impulse: first order in 1/steps where the slip turns
    assert result["lateral_impulse"].values[0] == pytest.approx(impulse[1], rel=1e-3)
    assert result["tangential_impulse"].values[0] == pytest.approx(-impulse[0], rel=1e-4)
    # the closed form by hand: 40 m/s at 60 deg on a fixed face, m 45.9 g, K^2 0.4, mu 0.1, e 0.8: sliding,
    # J_n = 1.8 * 0.0459 * 20 = 1.6524 N s, J_t = 0.16524 N s, spin R omega = J_t/(K^2 m) = 9.0 m/s
    closed = rigid_coulomb_closed_form(40.0, np.radians(60.0), 0.0459, 0.4, np.inf, 0.1, 0.8)
    assert closed["sliding"] and closed["normal_impulse"] == pytest.approx(1.6524)
    assert closed["tangential_impulse"] == pytest.approx(0.16524) and closed["spin_times_radius"] == pytest.approx(9.0)


def test_reference_checks_apply_to_the_plain_ball_and_only_a_declared_law_lifts_them():
    """ball_laws_on names the laws a configuration switches on; with none on, the rigid-limit check still catches a
    model whose spin is off, and with the rolling law on (which changes the spin on purpose) it is not applied."""
    from impactlab.model.reference import check_rigid_limit
    from impactlab.model.registry import get_model

    assert get_model("maw")().ball_laws_on() == ()
    assert get_model("maw")(rolling_hysteresis=0.3).ball_laws_on() == ("rolling_hysteresis",)
    assert get_model("rigid_coulomb")(rolling_hysteresis="restitution").ball_laws_on() == ("rolling_hysteresis",)
    assert get_model("rigid_coulomb")().ball_laws_on() == ()
    assert get_model("restitution")(friction_law="adhesion").ball_laws_on() == ("friction_law",)
    # a parameter of a law that is off does not switch it on; a registered model whose law is on by default is on
    assert get_model("maw")(core_loss=0.2).ball_laws_on() == ()
    assert "compression_lever" in get_model("rigid_coulomb_lever")().ball_laws_on()
    assert get_model("rigid_coulomb_lever")(compression_lever=0.0, relaxation_time=0.0).ball_laws_on() == ()
    plain = get_model("rigid_coulomb")()
    check_rigid_limit(plain)

    class HalfSpin(type(plain)):
        """The rigid model with its spin halved (a dropped factor 2 in R J_t / I), no law declared."""

        def _compute(self, inputs, outputs):
            result = super()._compute(inputs, outputs)
            return {key: (0.5 * value if key == "tangential_impulse" else value) for key, value in result.items()}

    with pytest.raises(AssertionError, match="rigid closed form"):
        check_rigid_limit(HalfSpin())
