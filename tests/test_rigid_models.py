"""Analytic limits of the rigid Coulomb and restitution models (physics brief sections 4 and 5)."""

import numpy as np
import pytest

from impactlab.model.registry import get_model

RIGID = get_model("rigid_coulomb")()


def test_rolling_branch_keeps_five_sevenths_of_tangential_speed(golf_inputs):
    # solid sphere, fixed face, no spin, high friction: slip stops, v_t' = (5/7) v_t
    inputs = golf_inputs(friction=2.0, angle=np.radians([5, 20, 40]), ball_inertia_factor=0.4)
    result = RIGID.compute(inputs, ["tangential_velocity", "tangential_restitution", "spin_rate"])
    vt = inputs["speed"] * np.sin(inputs["angle"])
    np.testing.assert_allclose(result["tangential_velocity"], 5.0 / 7.0 * vt, rtol=1e-12)
    np.testing.assert_allclose(result["tangential_restitution"], 0.0, atol=1e-12)
    # rolling: omega R equals the centre's tangential speed
    omega = result["spin_rate"].values * 2 * np.pi / 60
    np.testing.assert_allclose(omega * inputs["ball_radius"], result["tangential_velocity"], rtol=1e-12)


def test_sliding_branch_gives_mu_times_normal_impulse(golf_inputs):
    # threshold: tan(alpha) >= mu (1 + e)(1 + 1/K^2) = 0.595, alpha >= 30.8 deg
    inputs = golf_inputs(friction=0.1, restitution=0.7, angle=np.radians([31, 45, 60]))
    result = RIGID.compute(inputs, ["normal_impulse", "tangential_impulse", "tangential_restitution"])
    jn = 1.7 * inputs["ball_mass"] * inputs["speed"] * np.cos(inputs["angle"])
    np.testing.assert_allclose(result["normal_impulse"], jn, rtol=1e-12)
    np.testing.assert_allclose(result["tangential_impulse"], 0.1 * jn, rtol=1e-12)
    assert np.all(result["tangential_restitution"].values < 0.0)  # still sliding at separation


def test_branches_meet_at_the_threshold(golf_inputs):
    # V_x = mu J_n mu_t  <=>  tan(alpha) = mu (1+e)(1 + 1/K^2): both branches give the same J_t there
    e, mu, k2 = 1.0, 0.2, 0.4
    alpha = np.arctan(mu * (1 + e) * (1 + 1 / k2))
    around = golf_inputs(friction=mu, restitution=e, angle=[alpha * (1 - 1e-9), alpha * (1 + 1e-9)])
    jt = RIGID.compute(around, ["tangential_impulse"])["tangential_impulse"].values
    assert jt[0] == pytest.approx(jt[1], rel=1e-6)


def test_finite_club_mass_conserves_momentum_and_loses_no_energy_when_elastic_frictionless(golf_inputs):
    club = 0.2
    inputs = golf_inputs(friction=0.0, restitution=1.0, club_mass=club, angle=np.radians([0.0, 20.0]))
    result = RIGID.compute(inputs, ["normal_impulse", "normal_velocity", "energy_loss", "ball_speed"])
    m, v = inputs["ball_mass"], inputs["speed"]
    # head-on elastic two-body collision: ball leaves at 2 M V/(m + M)
    assert result["ball_speed"].values[0] == pytest.approx(2 * club * v[0] / (m[0] + club), rel=1e-12)
    # relative normal velocity reverses fully (e = 1)
    np.testing.assert_allclose(result["normal_velocity"], v * np.cos(inputs["angle"]), rtol=1e-12)
    np.testing.assert_allclose(result["energy_loss"], 0.0, atol=1e-9 * 0.5 * m[0] * v[0] ** 2)


def test_lighter_club_gives_a_slower_ball(golf_inputs):
    speeds = [RIGID.compute(golf_inputs(club_mass=mass), ["ball_speed"])["ball_speed"].item()
              for mass in (0.15, 0.2, 0.3, np.inf)]
    assert speeds == sorted(speeds)


def test_restitution_with_beta_zero_equals_rigid_rolling(golf_inputs):
    rolling = get_model("restitution")(tangential_restitution=0.0)
    inputs = golf_inputs(friction=5.0, restitution=0.75, angle=np.radians(np.linspace(1, 60, 9)), club_mass=0.2)
    names = ["normal_impulse", "tangential_impulse", "launch_angle", "spin_rate"]
    a, b = rolling.compute(inputs, names), RIGID.compute(inputs, names)
    for name in names:
        np.testing.assert_allclose(a[name], b[name], rtol=1e-12)


def test_restitution_returns_the_requested_beta_unless_capped(golf_inputs):
    model = get_model("restitution")(tangential_restitution=0.3)
    inputs = golf_inputs(friction=10.0, angle=np.radians([10, 30]))
    beta = model.compute(inputs, ["tangential_restitution"])["tangential_restitution"].values
    np.testing.assert_allclose(beta, 0.3, rtol=1e-12)
    capped = model.compute(golf_inputs(friction=0.05, angle=np.radians(40)), ["tangential_impulse",
                                                                                "normal_impulse"])
    assert capped["tangential_impulse"].item() == pytest.approx(0.05 * capped["normal_impulse"].item(), rel=1e-12)


def test_restitution_without_friction_is_uncapped(golf_inputs):
    model = get_model("restitution")(tangential_restitution=0.2)
    inputs = golf_inputs(angle=np.radians(50))
    del inputs["friction"]
    beta = model.compute(inputs, ["tangential_restitution"])["tangential_restitution"].item()
    assert beta == pytest.approx(0.2, rel=1e-12)


def test_incoming_backspin_reduces_slip(golf_inputs):
    # a ball already rolling on the face (R omega0 = V sin alpha) has no slip: no tangential impulse
    alpha, speed, radius = np.radians(20), 30.0, 0.021335
    inputs = golf_inputs(angle=alpha, speed=speed, spin=speed * np.sin(alpha) / radius, ball_radius=radius)
    jt = RIGID.compute(inputs, ["tangential_impulse"])["tangential_impulse"].item()
    assert abs(jt) < 1e-14
