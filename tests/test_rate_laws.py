"""The ball laws with a scale of their own (impactlab.physics.rate_laws; issue 33).

Oracles apart from the code: Hertz's closed forms for the relaxation-time limits, the rigid rolling impact with a
couple solved by hand, kinetic energies summed from the velocities, and exact reductions to the plain models.
"""

import math

import numpy as np
import pytest

from impactlab.model.registry import get_model
from impactlab.physics import hertz, rate_laws
from impactlab.testing import _complete, _with, reference_inputs, reference_inputs_3d

from test_ball_laws import kinetic_energy  # the energy of ball and head from their velocities, couple included

M, R, K2 = 0.04593, 0.021335, 0.4
E_STAR = 150e6


@pytest.mark.parametrize("g", [0.2, 0.6, 0.9])
def test_sls_limits_are_the_elastic_hertz_impacts_of_the_relaxed_and_instantaneous_moduli(g):
    """tau -> 0: elastic of E_inf = (1 - g) E_0; tau -> inf: elastic of E_0 (e = 1, Hertz's t_c, closed form)."""
    speed = np.array([20.0, 45.0])
    for tau, modulus in ((0.0, (1.0 - g) * E_STAR), (np.inf, E_STAR)):
        e, tc = rate_laws.sls_restitution(g, tau, speed, M, R, E_STAR)
        np.testing.assert_allclose(e, 1.0, atol=2e-5)
        np.testing.assert_allclose(tc, hertz.contact_time(M, R, modulus, speed), rtol=2e-4)
    # and the integration itself approaches both limits as theta leaves the loss's range (1 - e ~ theta, 1/theta)
    e, tau = rate_laws.sls_scaled(np.full(2, g), np.array([1e-4, 1e4]))
    np.testing.assert_allclose(e, 1.0, atol=3e-3)
    np.testing.assert_allclose(tau, hertz.TAU_CONTACT * np.array([(1.0 - g) ** -0.4, 1.0]), rtol=3e-3)


def test_sls_elastic_when_nothing_relaxes_and_the_integrator_is_hertz():
    """g = 0: the elastic Hertz impact for every theta (restitution 1, duration 2.9432 in scaled time)."""
    e, tau = rate_laws.sls_scaled(np.zeros(3), np.array([0.0, 1.0, np.inf]))
    np.testing.assert_allclose(e, 1.0, atol=1e-5)
    np.testing.assert_allclose(tau, hertz.TAU_CONTACT, rtol=1e-4)


def test_sls_never_creates_energy_and_dissipates_most_near_theta_one():
    theta = np.geomspace(1e-2, 1e2, 41)
    for g in (0.1, 0.5, 0.9):
        e, _ = rate_laws.sls_scaled(np.full(theta.size, g), theta)
        assert np.all(e <= 1.0 + 1e-6) and np.all(e > 0.0)
        assert 0.1 < theta[np.argmin(e)] < 10.0
    # more relaxing arm, more loss at the same theta
    e = [rate_laws.sls_scaled(np.array([g]), np.array([0.7]))[0][0] for g in (0.2, 0.5, 0.8)]
    assert e[0] > e[1] > e[2]


def test_sls_table_agrees_with_the_direct_integration():
    speed = np.linspace(15.0, 65.0, 40)
    e_table, tc_table = rate_laws.sls_restitution(0.5, 40e-6, speed, M, R, E_STAR)
    e_direct, tc_direct = rate_laws.sls_restitution(0.5, 40e-6, speed[::4], M, R, E_STAR, direct=True)
    np.testing.assert_allclose(e_table[::4], e_direct, atol=2e-4)
    np.testing.assert_allclose(tc_table[::4], tc_direct, rtol=2e-4)


def test_restitution_shape_keeps_the_input_at_the_reference_speed_and_vanishes_when_off():
    speed = np.array([25.0, 40.0, 55.0])
    e = rate_laws.restitution_shape(0.8, 0.5, 30e-6, speed, M, R, E_STAR, reference_speed=40.0)
    assert e[1] == pytest.approx(0.8, abs=1e-12)
    assert not np.allclose(e, 0.8)
    for g, tau in ((0.0, 30e-6), (0.5, 0.0)):
        np.testing.assert_array_equal(rate_laws.restitution_shape(0.8, g, tau, speed, M, R, E_STAR), 0.8)


def test_tangential_loss_of_a_dashpot_time_by_hand():
    """eta = omega tau_t with omega = pi / t_c: 20 us over a 450 us contact is 0.1396."""
    assert rate_laws.tangential_loss_of_time(20e-6, 450e-6) == pytest.approx(math.pi * 20 / 450, rel=1e-12)
    assert rate_laws.tangential_loss_of_time(0.0, 450e-6) == 0.0


def test_pressure_friction_by_hand():
    """mu_0 (p / 10 MPa)^(-n); the mean pressure F_max / (pi a_max^2) from Hertz's closed forms."""
    speed = 40.0
    delta = (15 * M * speed**2 / (16 * E_STAR * math.sqrt(R))) ** 0.4
    force = 4 / 3 * E_STAR * math.sqrt(R) * delta**1.5
    pressure = force / (math.pi * R * delta)
    assert rate_laws.mean_pressure(M, R, E_STAR, speed) == pytest.approx(pressure, rel=1e-12)
    assert rate_laws.pressure_friction(0.4, 0.5, pressure) == pytest.approx(0.4 * (pressure / 10e6) ** -0.5)
    assert rate_laws.pressure_friction(0.4, 0.0, pressure) == 0.4


def test_slip_friction_by_hand():
    """mu_0 (|u| / 10 m/s)^m; the slip's direction does not matter; m = 0 is Coulomb."""
    u = np.array([-20.0, 5.0, 10.0, 40.0])
    np.testing.assert_allclose(rate_laws.slip_friction(0.4, 0.7, u), 0.4 * (np.abs(u) / 10.0) ** 0.7, rtol=1e-12)
    np.testing.assert_array_equal(rate_laws.slip_friction(0.4, 0.0, u), np.full(4, 0.4))
    assert rate_laws.slip_friction(0.3, 1.0, 10.0) == pytest.approx(0.3)
    # no friction cap (the restitution model without a friction input) stays none, even at zero slip
    np.testing.assert_array_equal(rate_laws.slip_friction(np.inf, 0.7, np.array([0.0, 5.0])), [np.inf, np.inf])
    assert rate_laws.slip_friction(0.4, 0.7, 0.0) == 0.0


def test_restitution_model_without_friction_and_no_slip_gives_numbers():
    """Head-on central impacts, no friction input (no cap): the slip law must not turn the missing cap into NaN."""
    cases = {k: v for k, v in fixed_face_cases(np.radians([0.0, 20.0])).items() if k != "friction"}
    out = get_model("restitution")(tangential_restitution=0.2, friction_slip_exponent=0.8).compute_arrays(cases, OUT)
    plain = get_model("restitution")(tangential_restitution=0.2).compute_arrays(cases, OUT)
    for key in OUT:
        np.testing.assert_allclose(out[key], plain[key], rtol=1e-12, atol=1e-15, err_msg=key)


def test_slip_friction_in_a_sliding_impact_by_hand():
    """A rigid ball sliding throughout on a fixed face: |J_t| = mu J_n with mu = mu_0 (V sin a / 10 m/s)^m, and
    J_n = (1 + e) m V cos a (Coulomb's sliding impact, Stronge 2000)."""
    angles = np.radians([40.0, 55.0, 70.0])
    mu0, m, speed, e = 0.05, 1.0, 40.0, 0.8
    cases = fixed_face_cases(angles, speed=speed, restitution=e, friction=mu0)
    out = get_model("rigid_coulomb")(friction_slip_exponent=m).compute_arrays(cases, OUT)
    mu = mu0 * (speed * np.sin(angles) / 10.0) ** m
    mass = cases["ball_mass"]
    np.testing.assert_allclose(out["normal_impulse"], (1 + e) * mass * speed * np.cos(angles), rtol=1e-6)
    np.testing.assert_allclose(np.abs(out["tangential_impulse"]), mu * out["normal_impulse"], rtol=1e-6)
    # the same impact at half the speed slides at half the slip: half the friction coefficient
    slow = get_model("rigid_coulomb")(friction_slip_exponent=m).compute_arrays(
        fixed_face_cases(angles, speed=speed / 2, restitution=e, friction=mu0), OUT)
    np.testing.assert_allclose(np.abs(slow["tangential_impulse"]) / slow["normal_impulse"], mu / 2, rtol=1e-6)


def test_slip_friction_reads_the_whole_slip_with_an_incoming_spin():
    """Backspin or topspin of R w moves the contact's slip to V sin a -+ R w: the two spins' friction coefficients
    (sliding throughout, |J_t| / J_n) are mu_0 (|V sin a + R w| / 10)^m and mu_0 (|V sin a - R w| / 10)^m."""
    angle, speed, mu0, m, omega = np.radians(50.0), 40.0, 0.05, 0.8, 300.0
    measured = []
    for spin in (omega, -omega):
        cases = _with(fixed_face_cases([angle], speed=speed, friction=mu0), spin=spin)
        out = get_model("rigid_coulomb")(friction_slip_exponent=m).compute_arrays(cases, OUT)
        measured.append(float(np.abs(out["tangential_impulse"][0]) / out["normal_impulse"][0]))
    radius = float(fixed_face_cases([angle])["ball_radius"][0])
    expected = [mu0 * (abs(speed * math.sin(angle) + sign * radius * omega) / 10.0) ** m for sign in (1, -1)]
    assert sorted(measured) == pytest.approx(sorted(expected), rel=1e-6)


def test_slip_and_pressure_friction_multiply():
    """Both laws on: mu = mu_0 (u / 10 m/s)^m (p_mean / 10 MPa)^(-n), sliding throughout on a fixed face."""
    angles = np.radians([45.0, 60.0])
    speed, mu0, m, n = 40.0, 0.05, 0.7, 0.4
    cases = fixed_face_cases(angles, speed=speed, friction=mu0)
    out = get_model("rigid_coulomb")(friction_slip_exponent=m, friction_pressure_exponent=n).compute_arrays(
        cases, OUT)
    modulus = hertz.effective_modulus(cases["ball_youngs_modulus"], cases["ball_poisson_ratio"],
                                      cases["face_youngs_modulus"], cases["face_poisson_ratio"])
    pressure = rate_laws.mean_pressure(cases["ball_mass"], cases["ball_radius"], modulus, speed * np.cos(angles))
    mu = mu0 * (speed * np.sin(angles) / 10.0) ** m * (pressure / 10e6) ** (-n)
    np.testing.assert_allclose(np.abs(out["tangential_impulse"]) / out["normal_impulse"], mu, rtol=1e-6)


def test_slip_friction_keeps_the_gear_effect_of_a_strike_without_initial_slip():
    """Head-on (no loft, path or face angle) off-centre strikes on a free head: no initial slip, but the normal
    impulse couples into the tangential directions, so the contact slides and friction acts (the gear effect). The
    law reads that coupled slip: it must not take the friction away."""
    head_on = _with(CASES_3D, angle=0.0, path=0.0, face_angle=0.0, dynamic_loft=0.0, attack_angle=0.0)
    wanted = ["tangential_impulse", "lateral_impulse"]
    for name in ("rigid_coulomb", "hertz_mindlin"):
        plain = get_model(name)().compute_arrays(head_on, wanted)
        with_law = get_model(name)(friction_slip_exponent=0.9).compute_arrays(head_on, wanted)
        size = np.hypot(plain["tangential_impulse"], plain["lateral_impulse"])
        law = np.hypot(with_law["tangential_impulse"], with_law["lateral_impulse"])
        struck = size > 1e-3
        assert struck.sum() >= 4, name
        assert np.all(law[struck] > 0.2 * size[struck]), (name, law[struck] / size[struck])


def test_slip_friction_refuses_a_friction_law_with_its_own_sliding_dependence():
    from impactlab.errors import ModelInputError

    with pytest.raises(ModelInputError, match="friction_slip_exponent.*friction_law 'adhesion'"):
        get_model("rigid_coulomb")(friction_slip_exponent=0.5, friction_law="adhesion").compute_arrays(
            CASES_3D, OUT)


def test_compression_ratio_of_the_hertz_history():
    """int h^(5/2) / int h^(3/2) over the elastic history, computed here by the energy integral dtau = dh / h'."""
    h = np.linspace(0.0, 1.0, 200001)[1:-1]
    rate = np.sqrt(1.0 - h**2.5)  # h'^2 = 1 - h^(5/2)
    ratio = np.trapezoid(h**2.5 / rate, h) / np.trapezoid(h**1.5 / rate, h)
    assert rate_laws.compression_ratio() == pytest.approx(ratio, rel=2e-3)


def test_head_cor_refused_beyond_the_rules():
    rate_laws.check_head_cor(0.830)
    with pytest.raises(ValueError, match="0.830"):
        rate_laws.check_head_cor(0.8301)
    with pytest.raises(ValueError, match="unphysical"):
        rate_laws.check_head_cor(np.array([0.80, 0.87]))


# -- the laws in the models ---------------------------------------------------------------------------------------

OUT = ["normal_impulse", "tangential_impulse", "lateral_impulse", "ball_speed", "spin_rate"]
CASES_1D = _complete(reference_inputs(4))
CASES_3D = _complete(reference_inputs_3d())
OFF = [{"relaxation_time": 0.0}, {"relaxed_fraction": 0.0, "relaxation_time": 3e-5},
       {"friction_pressure_exponent": 0.0}, {"compression_lever": 0.0}, {"tangential_relaxation_time": 0.0},
       {"friction_slip_exponent": 0.0}]


def accepts(name, options):
    """Whether the model takes these options (the lever needs a couple, the dashpot a tangential spring)."""
    import attrs

    return set(options) <= set(attrs.fields_dict(get_model(name).Options))


@pytest.mark.parametrize("name", ["rigid_coulomb", "hertz_mindlin", "restitution", "maw"])
@pytest.mark.parametrize("options", OFF)
def test_each_law_at_its_vanishing_setting_is_the_plain_model(name, options):
    if not accepts(name, options):
        assert name in ("rigid_coulomb", "restitution")  # every compliant model takes every law
        return
    for cases in (CASES_1D, CASES_3D):
        plain = get_model(name)().compute_arrays(cases, OUT)
        off = get_model(name)(**options).compute_arrays(cases, OUT)
        for key in OUT:
            np.testing.assert_array_equal(off[key], plain[key], err_msg=f"{name} {options} {key}")


def fixed_face_cases(angles, speed=40.0, restitution=0.8, friction=0.4):
    """Rolling-prone cases on a rigid fixed face (the 1-D batch's first face), no incoming spin."""
    base = {k: np.asarray(v)[:1] for k, v in CASES_1D.items()}
    n = len(angles)
    cases = {k: np.repeat(v, n, axis=0) for k, v in base.items()}
    return _with(cases, angle=np.asarray(angles), speed=speed, spin=0.0, restitution=restitution, friction=friction)


def test_lever_spin_by_hand_on_a_fixed_face():
    """A rolling exit with a couple d J_n against the rolling: omega R (1 + K^2) = V sin(a) - d (1 + e) V cos(a) / R."""
    angles = np.radians([10.0, 15.0, 25.0])
    cases = fixed_face_cases(angles)
    assert np.all(np.isinf(cases["club_mass"])) or np.all(cases["club_mass"] > 1e3)
    lever = 0.1
    out = get_model("rigid_coulomb")(compression_lever=lever).compute_arrays(cases, OUT)
    speed, e, r, k2 = 40.0, 0.8, cases["ball_radius"], cases["ball_inertia_factor"]
    modulus = hertz.effective_modulus(cases["ball_youngs_modulus"], cases["ball_poisson_ratio"],
                                      cases["face_youngs_modulus"], cases["face_poisson_ratio"])
    arm = lever * rate_laws.compression_ratio() * hertz.max_approach(cases["ball_mass"], r, modulus,
                                                                      speed * np.cos(angles))
    spin = (speed * np.sin(angles) - arm * (1 + e) * speed * np.cos(angles) / r) / (r * (1 + k2))
    np.testing.assert_allclose(out["spin_rate"], spin, rtol=1e-6)
    plain = get_model("rigid_coulomb")().compute_arrays(cases, OUT)
    assert np.all(out["spin_rate"] < plain["spin_rate"])


def test_lever_spin_grows_slower_than_speed():
    """The lever's share of the spin grows as delta_max ~ V^(4/5): spin / V falls with V at a fixed loft."""
    angles = np.radians([12.0])
    spins = [get_model("rigid_coulomb")(compression_lever=0.1).compute_arrays(fixed_face_cases(angles, v),
                                                                             ["spin_rate"])["spin_rate"][0] / v
             for v in (30.0, 45.0)]
    assert spins[1] < spins[0]


@pytest.mark.parametrize("options", [{"compression_lever": 0.3}, {"relaxation_time": 3e-5, "relaxed_fraction": 0.6},
                                     {"friction_pressure_exponent": 0.8}, {"tangential_relaxation_time": 2e-5},
                                     {"friction_slip_exponent": 1.0}])
def test_no_law_creates_energy(options):
    """Ball plus free head on the 3-D batch (heel to toe, sole to crown, e 1 and 0.8), at 20 and 60 m/s."""
    wanted = ["normal_impulse", "tangential_impulse", "lateral_impulse", "rolling_moment", "rolling_moment_slip"]
    for speed in (20.0, 60.0):
        cases = _with(CASES_3D, speed=speed)
        before = kinetic_energy(cases)
        for name in ("rigid_coulomb", "hertz_mindlin", "restitution"):
            if not accepts(name, options):
                continue
            model = get_model(name)(**options) if name != "restitution" else get_model(name)(
                tangential_restitution=0.3, **options)
            result = model.compute(cases, [w for w in wanted if w in model.provides])
            after = kinetic_energy(cases, result)
            assert np.all(after <= before * (1 + 1e-6) + 1e-9), (name, options, np.max(after - before))


@pytest.mark.parametrize("name", ["rigid_coulomb", "hertz_mindlin"])
def test_laws_keep_left_right_mirror_symmetry(name):
    """Mirrored deliveries (path, face angle, strike toe negated) give the same spin and mirrored lateral values."""
    cases = CASES_3D
    # the batch's head symmetric heel to toe (CG on the centre line, no toe products of inertia)
    rows = ((cases["club_cg_toe"] == 0.0) & (cases["club_inertia_toe_up"] == 0.0)
            & (cases["club_inertia_toe_target"] == 0.0))
    assert rows.sum() >= 8
    model = get_model(name)(compression_lever=0.1, relaxation_time=3e-5, friction_pressure_exponent=0.3,
                            friction_slip_exponent=0.5)
    out = model.compute_arrays(cases, ["spin_rate", "lateral_impulse", "horizontal_launch_angle", "normal_impulse"])
    mirror = dict(cases)
    for key in ("path", "face_angle", "strike_toe"):
        mirror[key] = -np.asarray(cases[key])
    flipped = model.compute_arrays(mirror, ["spin_rate", "lateral_impulse", "horizontal_launch_angle",
                                            "normal_impulse"])
    np.testing.assert_allclose(flipped["spin_rate"][rows], out["spin_rate"][rows], rtol=1e-6)
    np.testing.assert_allclose(flipped["normal_impulse"][rows], out["normal_impulse"][rows], rtol=1e-6)
    np.testing.assert_allclose(flipped["lateral_impulse"][rows], -out["lateral_impulse"][rows], atol=1e-9)
    np.testing.assert_allclose(flipped["horizontal_launch_angle"][rows], -out["horizontal_launch_angle"][rows],
                               atol=1e-9)


def test_the_registered_form_is_rigid_coulomb_with_its_fitted_laws():
    from impactlab_models.rigid_coulomb import FITTED_LEVER, FITTED_RELAXATION

    registered = get_model("rigid_coulomb_lever")
    for cases in (CASES_1D, CASES_3D):
        same = get_model("rigid_coulomb")(compression_lever=FITTED_LEVER, relaxation_time=FITTED_RELAXATION[0],
                                          relaxed_fraction=FITTED_RELAXATION[1]).compute_arrays(cases, OUT)
        out = registered().compute_arrays(cases, OUT)
        off = registered(compression_lever=0.0, relaxation_time=0.0).compute_arrays(cases, OUT)
        plain = get_model("rigid_coulomb")().compute_arrays(cases, OUT)
        for key in OUT:
            np.testing.assert_array_equal(out[key], same[key])
            np.testing.assert_array_equal(off[key], plain[key])
