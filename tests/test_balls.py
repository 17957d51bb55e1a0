"""Real balls: restitution laws of the impact speed, tangential losses of the cover, and per-case hysteretic laws."""

import numpy as np
import pytest

import impactlab
from impactlab.errors import FieldError
from impactlab.scene.materials import RestitutionLaw
from impactlab.physics import hertz
from impactlab.model.registry import get_model
from impactlab.testing import reference_inputs

COMPLIANT = ["maw", "hertz_mindlin", "dem_linear"]


def test_restitution_laws_follow_their_formulas():
    speeds = np.array([10.0, 40.0, 55.0])
    np.testing.assert_allclose(RestitutionLaw("constant", 0.8)(speeds), 0.8)
    np.testing.assert_allclose(RestitutionLaw("linear", 0.8, 40.0, slope=-0.004)(speeds), [0.92, 0.8, 0.74])
    np.testing.assert_allclose(RestitutionLaw("power", 0.8, 40.0, exponent=0.2)(speeds),
                               np.minimum(0.8 * (speeds / 40.0) ** -0.2, 1.0))  # clipped at 1
    np.testing.assert_allclose(RestitutionLaw("table", speeds=(20.0, 50.0), values=(0.9, 0.75))(speeds),
                               [0.9, 0.8, 0.75])
    assert RestitutionLaw("linear", 0.8, 40.0, slope=-0.05)(np.array([100.0]))[0] == 0.05  # clipped, never < 0
    with pytest.raises(FieldError, match="increasing"):
        RestitutionLaw("table", speeds=(50.0, 20.0), values=(0.9, 0.75))


STUDY = """
ball: {preset: urethane_tour, friction: 0.3, restitution: {law: power, value: 0.8, reference_speed: 40 m/s,
       exponent: 0.15}}
face: {preset: steel}
impact: {speed: 40 m/s, angle: 20 deg}
sweep: {impact.speed: [20 m/s, 35 m/s, 50 m/s, 65 m/s]}
models: [rigid_coulomb, restitution]
outputs: [normal_impulse, normal_velocity]
"""


def test_a_ball_law_gives_each_case_the_restitution_of_its_own_normal_speed():
    ds = impactlab.run_study(STUDY)
    speed = np.array([20.0, 35.0, 50.0, 65.0])
    normal_speed = speed * np.cos(np.radians(20.0))
    e = 0.8 * (normal_speed / 40.0) ** -0.15
    for model in ("rigid_coulomb", "restitution"):
        # a fixed steel face: the rebound normal speed is e V_z
        np.testing.assert_allclose(ds["normal_velocity"].sel(model=model), e * normal_speed, rtol=1e-12)
    assert np.all(np.diff(ds["normal_velocity"].sel(model="rigid_coulomb") / normal_speed) < 0)


def test_a_contact_block_overrides_the_ball_data():
    ds = impactlab.run_study(STUDY.replace("face: {preset: steel}", "face: {preset: steel}\ncontact: "
                                                                    "{restitution: 0.7, friction: 0.5}"))
    speed = np.array([20.0, 35.0, 50.0, 65.0]) * np.cos(np.radians(20.0))
    np.testing.assert_allclose(ds["normal_velocity"].sel(model="rigid_coulomb"), 0.7 * speed, rtol=1e-12)
    with pytest.raises(FieldError, match="ball.restitution.law"):
        impactlab.load_study(STUDY.replace("law: power", "law: cubic"))


def test_a_study_without_contact_takes_the_balls_data_and_the_faces_gain():
    # a driver and a 6-iron on the calibrated ball: the ball's friction and restitution law, plus the wood face's
    # gain on the driver only
    base = """
ball: {preset: urethane_tour}
club: {preset: PRESET}
delivery: {club_speed: 45 m/s, attack_angle: 0 deg, dynamic_loft: 15 deg}
models: [rigid_coulomb]
outputs: [normal_velocity, ball_speed]
"""
    from impactlab.scene.materials import ball_preset
    from impactlab.study.arrays import case_inputs
    ball = ball_preset("urethane_tour")
    assert ball.friction == 0.40  # the sled measurement (Henrikson et al. 2020)
    for preset, gain in (("driver", 0.083), ("6_iron", 0.0)):
        study = impactlab.load_study(base.replace("PRESET", preset))
        inputs = case_inputs(study)
        assert inputs["friction"][0] == 0.40
        assert inputs["restitution"][0] == pytest.approx(ball.restitution(40.0) + gain, abs=1e-12)
    driver = impactlab.run_study(base.replace("PRESET", "driver"))["ball_speed"].item()
    iron = impactlab.run_study(base.replace("PRESET", "6_iron"))["ball_speed"].item()
    assert driver > iron  # the lighter driver head, but the springier face


def _lossy(loss, **changes):
    inputs = reference_inputs(n_angles=5)
    inputs.update({key: np.broadcast_to(value, inputs["speed"].shape).copy() for key, value in changes.items()})
    inputs["tangential_loss"] = np.full(inputs["speed"].shape, float(loss))
    return inputs


@pytest.mark.slow
@pytest.mark.parametrize("model", COMPLIANT)
def test_a_lossy_cover_never_creates_energy(model):
    instance = get_model(model)()
    elastic = instance.compute(_lossy(0.0), ["energy_loss", "tangential_restitution"])
    lossy = instance.compute(_lossy(0.4), ["energy_loss", "tangential_restitution", "energy_error"])
    kinetic = 0.5 * _lossy(0.0)["ball_mass"] * _lossy(0.0)["speed"] ** 2
    assert np.all(lossy["energy_loss"].values >= -1e-9 * kinetic)
    # more loss where the contact sticks (not everywhere: the dashpot also changes how much the contact slips)
    assert np.any(lossy["energy_loss"].values > elastic["energy_loss"].values + 1e-3 * kinetic)
    # the integration's energy balance still closes (the dashpot's work is in the contact forces' work)
    assert np.all(np.abs(lossy["energy_error"].values) < 1e-5)


@pytest.mark.parametrize("model", COMPLIANT)
def test_an_almost_elastic_cover_takes_the_3d_kernel_and_matches_the_elastic_1d_solver(model):
    instance = get_model(model)(tolerance=1e-6)
    names = ["normal_impulse", "tangential_impulse"]
    elastic = instance.compute(_lossy(0.0), names)
    nearly = instance.compute(_lossy(1e-12), names)
    scale = _lossy(0.0)["friction"] * elastic["normal_impulse"].values
    np.testing.assert_allclose(nearly["tangential_impulse"].values, elastic["tangential_impulse"].values,
                               rtol=0, atol=2e-6 * scale.max())


def test_the_loss_lowers_maws_grip_and_leaves_gross_slip_alone():
    maw = get_model("maw")()
    # at golf incidences (psi1 ~ 1-2, microslip): the dashpot takes energy the springs would give back. Deep in
    # stick (low loft) a large loss mostly stiffens the contact (Kelvin-Voigt) and beta need not fall.
    for friction in (0.3, 0.5):
        grip = {"angle": np.radians(30.0), "friction": friction, "spin": 0.0, "restitution": 1.0}
        beta = [float(maw.compute(_lossy(loss, **grip), ["tangential_restitution"])["tangential_restitution"][0])
                for loss in (0.0, 0.1, 0.2, 0.5)]
        assert beta[0] > beta[1] > beta[2] > beta[3] > 0.0, beta
    # gross slip throughout: every spring sits on its Coulomb circle, the dashpot changes nothing, J_t = mu J_n
    slide = {"angle": np.radians(60.0), "friction": 0.1, "spin": 0.0, "restitution": 1.0}
    results = [maw.compute(_lossy(loss, **slide), ["tangential_impulse", "normal_impulse"]) for loss in (0.0, 0.5)]
    for result in results:
        np.testing.assert_allclose(result["tangential_impulse"], 0.1 * result["normal_impulse"], rtol=1e-4)


@pytest.mark.slow
def test_tabulated_damping_matches_the_per_law_solution():
    for e in (0.95, 0.8, 0.5):
        c, tau = hertz.damping_for_restitutions([e])
        law = hertz.DampedNormal(hertz.damping_for_restitution(e))
        assert abs(c[0] / law.damping - 1) < 1e-5
        assert abs(tau[0] / law.tau_end - 1) < 1e-6


@pytest.mark.slow
def test_hysteretic_law_per_case_equals_the_grouped_solution():
    maw = get_model("maw")(inelastic="hysteretic")
    inputs = reference_inputs(n_angles=3)
    inputs["restitution"] = np.linspace(0.6, 0.95, inputs["speed"].size)  # every case its own e
    names = ["normal_impulse", "tangential_impulse", "energy_loss"]
    together = maw.compute(inputs, names)
    for case in (0, 11, 30, inputs["speed"].size - 1):
        alone = maw.compute({key: value[case:case + 1] for key, value in inputs.items()}, names)  # one law
        for name in ("normal_impulse", "tangential_impulse"):
            scale = inputs["friction"][case] * float(alone["normal_impulse"][0]) if name != "normal_impulse" \
                else float(alone["normal_impulse"][0])
            assert abs(float(together[name][case]) - float(alone[name][0])) < 2e-5 * scale, (name, case)
    assert np.all(together["energy_loss"].values > 0)


def test_one_name_per_ball_the_former_name_is_an_alias_that_says_so():
    from impactlab.scene.materials import BALL_PRESETS, PresetAliasNote, ball_preset

    assert "tour_urethane" not in BALL_PRESETS  # one preset per ball
    with pytest.warns(PresetAliasNote, match="'tour_urethane' is a former name of 'urethane_tour'"):
        ball = ball_preset("tour_urethane")
    assert ball is BALL_PRESETS["urethane_tour"]
    # the kept ball carries the calibrated contact data: the sled's friction (Henrikson et al. 2020, 0.40)
    assert ball.friction == 0.40 and ball.restitution is not None
    with pytest.warns(PresetAliasNote):
        study = impactlab.load_study("ball: {preset: tour_urethane}\nclub: {preset: driver}\n"
                                     "delivery: {club_speed: 45 m/s, attack_angle: 0 deg, dynamic_loft: 15 deg}\n"
                                     "models: [rigid_coulomb]\n")
    assert study is not None
