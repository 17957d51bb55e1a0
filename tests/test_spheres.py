"""Sphere-on-sphere impacts: a free sphere as the striking body (ClubHead.sphere), in every model.

Oracles: the Hertz closed forms with m* = m/2 and R* = R/2; momentum exchange of equal masses; the rigid-body
impulses with the two-sphere mobility; Maw, Barber & Fawcett's (1976) observation that two identical spheres
in their variables are a sphere on a half-space of the same material; the half-space as the limit of a large,
heavy sphere.
"""

import math

import numpy as np
import pytest

from impactlab.scene.clubs import ClubHead
from impactlab.errors import FieldError
from impactlab.physics.contact import contact_state
from impactlab.model.registry import get_model
from impactlab.data.validation.benchmarks import SPHERES, plate_inputs, two_sphere_inputs

GLASS = SPHERES["glass"]
MODELS = ("maw", "hertz_mindlin", "dem_linear", "rigid_coulomb")


def test_sphere_mobility_and_hertz_radius():
    inputs = two_sphere_inputs(GLASS, GLASS, speed=[5.0, 5.0], angle=[0.0, 0.5])
    state = contact_state(inputs)
    m, k2 = GLASS.mass, 0.4
    # W = W_ball + W_striker = 2 (1/m) [1 + (1 - n n^T)/K^2] in the contact frame (s, l, n)
    expected = np.diag([2 * (1 + 1 / k2) / m, 2 * (1 + 1 / k2) / m, 2 / m])
    for mobility in state["mobility"]:
        np.testing.assert_allclose(mobility, expected, rtol=1e-12, atol=1e-9 / m)
    np.testing.assert_allclose(state["contact_radius"], GLASS.radius / 2, rtol=1e-12)
    assert np.all(state["one_dimensional"])


@pytest.mark.parametrize("model", MODELS)
def test_equal_spheres_head_on_exchange_velocities_and_follow_hertz(model):
    ds = get_model(model)().compute(two_sphere_inputs(GLASS, GLASS, speed=20.0),
                                    ["ball_speed", "normal_impulse"]
                                    + (["contact_time"] if model != "rigid_coulomb" else []))
    m = GLASS.mass
    assert float(ds.ball_speed.values[0]) == pytest.approx(20.0, rel=1e-12)  # equal masses swap velocities
    assert float(ds.normal_impulse.values[0]) == pytest.approx(2 * (m / 2) * 20.0, rel=1e-12)
    if model != "rigid_coulomb":
        modulus = GLASS.youngs_modulus / (2 * (1 - GLASS.poisson_ratio**2))
        hertz = 2.8682 * ((m / 2) ** 2 / (GLASS.radius / 2 * modulus**2 * 20.0)) ** 0.2
        assert float(ds.contact_time.values[0]) == pytest.approx(hertz, rel=2e-4)


@pytest.mark.parametrize("model", MODELS)
def test_identical_spheres_are_a_sphere_on_a_half_space_of_the_same_material(model):
    # Maw, Barber & Fawcett (1976): with m*/m_t = 1 + 1/K^2 for both, beta depends on psi1 alone
    angles = np.radians([8.0, 20.0, 35.0, 60.0, 80.0])
    outputs = ["tangential_restitution", "normalised_incidence"]
    pair = get_model(model)().compute(two_sphere_inputs(GLASS, GLASS, speed=20.0, angle=angles, friction=0.35),
                                      outputs)
    wall = get_model(model)().compute(plate_inputs(GLASS, speed=20.0, angle=angles, friction=0.35, face=GLASS),
                                      outputs)
    np.testing.assert_allclose(pair.normalised_incidence.values, wall.normalised_incidence.values, rtol=1e-12)
    np.testing.assert_allclose(pair.tangential_restitution.values, wall.tangential_restitution.values, atol=1e-6)


@pytest.mark.parametrize("model", MODELS)
def test_oblique_equal_spheres_match_rigid_body_impulses_in_gross_slip_and_rigid_rolling(model):
    m, radius, mu = GLASS.mass, GLASS.radius, 0.35
    angle = math.radians(80.0)  # psi1 = 12.6 > 4 chi = 6.2: slides throughout
    ds = get_model(model)().compute(two_sphere_inputs(GLASS, GLASS, speed=20.0, angle=angle, friction=mu),
                                    ["spin_rate", "tangential_impulse"])
    normal = 2 * (m / 2) * 20.0 * math.cos(angle)
    tolerance = 1e-4  # maw's default (the time integration); the other models are exact here
    assert float(ds.tangential_impulse.values[0]) == pytest.approx(mu * normal, rel=tolerance)
    # the struck sphere spins at R J_t / (K^2 m R^2)
    assert float(ds.spin_rate.values[0]) * math.pi / 30 == pytest.approx(mu * normal / (0.4 * m * radius),
                                                                          rel=tolerance)
    if model == "rigid_coulomb":  # the slip stops: J_t = V_s / W_ss with W_ss = 2 (1 + 1/K^2)/m = 7/m
        angle = math.radians(10.0)
        ds = get_model(model)().compute(two_sphere_inputs(GLASS, GLASS, speed=20.0, angle=angle, friction=mu),
                                        ["tangential_impulse", "tangential_restitution"])
        assert float(ds.tangential_impulse.values[0]) == pytest.approx(m * 20.0 * math.sin(angle) / 7, rel=1e-12)
        assert abs(float(ds.tangential_restitution.values[0])) < 1e-12


@pytest.mark.parametrize("model", MODELS)
def test_a_large_heavy_rigid_sphere_is_a_fixed_rigid_plane(model):
    from impactlab.scene.materials import Ball, Material
    from impactlab.scene.core import Contact, Impact, Scene

    s = SPHERES["aluminium_oxide"]
    ball = Ball(s.radius, s.mass, 0.4, Material(s.youngs_modulus, s.poisson_ratio))
    wall = ClubHead.sphere(1e4 * s.radius, 1e10 * s.mass)  # rigid: no material
    angles = np.radians([10.0, 25.0, 60.0])
    scenes = [Scene(ball, Scene.face_of(wall), Contact(0.092, 0.98), Impact(3.9, a), club=wall) for a in angles]
    outputs = ["tangential_restitution", "spin_rate", "normal_velocity"]
    big = get_model(model)().compute(scenes, outputs)
    plane = get_model(model)().compute(plate_inputs(s, speed=3.9, angle=angles, friction=0.092, restitution=0.98),
                                       outputs)
    for name in outputs:
        np.testing.assert_allclose(big[name].values, plane[name].values, rtol=2e-4, atol=1e-4)


@pytest.mark.parametrize("model", MODELS)
def test_equal_and_opposite_spins_of_equal_spheres_leave_no_slip(model):
    # Chung & Ooi's test-7 geometry: the contact points move together, so nothing changes the spins
    w = 30.0
    ds = get_model(model)().compute(two_sphere_inputs(GLASS, GLASS, speed=0.4, spin=w, club_spin=-w, friction=0.4),
                                    ["tangential_impulse", "spin_rate", "club_angular_velocity"])
    assert abs(float(ds.tangential_impulse.values[0])) < 1e-15
    assert float(ds.spin_rate.values[0]) * math.pi / 30 == pytest.approx(w, rel=1e-12)
    assert float(ds.club_angular_velocity.values[0]) * math.pi / 30 == pytest.approx(w, rel=1e-12)


@pytest.mark.parametrize("model", MODELS)
def test_a_spinning_striker_acts_through_the_slip_it_adds(model):
    # the impulse depends on the relative contact velocity only: a striker of radius 2R spinning at w adds the
    # slip -2R w, as the struck ball spinning at 2w would
    big = SPHERES["glass"]
    import attrs

    striker = attrs.evolve(big, radius=2 * big.radius)
    angles, w = np.radians([0.0, 15.0, 40.0]), 40.0
    outputs = ["tangential_impulse", "normal_impulse"]
    by_striker = get_model(model)().compute(two_sphere_inputs(big, striker, speed=5.0, angle=angles, club_spin=w,
                                                              friction=0.3), outputs)
    by_ball = get_model(model)().compute(two_sphere_inputs(big, striker, speed=5.0, angle=angles, spin=2 * w,
                                                           friction=0.3), outputs)
    for name in outputs:
        np.testing.assert_allclose(by_striker[name].values, by_ball[name].values, rtol=1e-9, atol=1e-15)
    assert np.all(np.abs(by_striker["tangential_impulse"].values) > 0.0)


def test_sphere_striker_refuses_impossible_spheres():
    with pytest.raises(FieldError):
        ClubHead.sphere(-1.0, 1.0)
    with pytest.raises(FieldError):
        ClubHead.sphere(0.01, 1.0, inertia_factor=0.9)
