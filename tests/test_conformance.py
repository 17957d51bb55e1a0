"""The shipped conformance suite, run over every registered model."""

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
