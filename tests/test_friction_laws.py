"""The friction law of the ball-face pair (issue 21 item 3, second bullet; impactlab.physics.friction_laws).

Oracles written apart from the code: quadrature of the area integral, the Hertz impact integrated as an ODE with
scipy (not hertz.scaled_approach), a squeeze film integrated as its own ODE, exact reductions to today's model,
the flash temperature's self-consistency, and kinetic energies summed from the velocities.
"""

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy import integrate, special

from impactlab.errors import ModelInputError
from impactlab.model.case_inputs import CaseInputs
from impactlab.model.registry import get_model
from impactlab.physics import friction_laws as fl
from impactlab.physics import hertz
from impactlab.scene.materials import BALL_PRESETS, FACE_SURFACES
from impactlab.testing import _complete, _with, parametrize_with_checks, reference_inputs, reference_inputs_3d

settings.register_profile("ci", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

from test_ball_laws import kinetic_energy  # noqa: E402  (the energy oracle, from velocities)

REFERENCE_1D = _complete(reference_inputs())
DRIVER_CASES = _complete(reference_inputs_3d())
OUTPUTS = ["normal_impulse", "tangential_impulse", "lateral_impulse", "spin_rate", "launch_angle"]
MODELS = [("rigid_coulomb", {}), ("maw", {"tolerance": 1e-3}), ("hertz_mindlin", {"tolerance": 1e-3}),
          ("dem_linear", {"tolerance": 1e-3}), ("restitution", {})]


def _hertz_ode(m, radius, modulus, speed):
    """(t, delta) of an elastic Hertz impact, m delta'' = -(4/3) E* sqrt(R) delta^(3/2), integrated by scipy."""
    def rhs(_, y):
        return [y[1], -4.0 / 3.0 * modulus * np.sqrt(radius) * max(y[0], 0.0) ** 1.5 / m]

    def out(_, y):
        return y[0] + 1e-15 if y[1] < 0 else 1.0
    out.terminal, out.direction = True, -1
    run = integrate.solve_ivp(rhs, (0.0, 1e-2), [0.0, speed], events=out, rtol=1e-11, atol=1e-16,
                              dense_output=True, max_step=1e-6)
    t = np.linspace(0.0, run.t[-1], 20001)
    return t, np.clip(run.sol(t)[0], 0.0, None)


WEDGE = dict(m=1.0 / (1.0 / 0.04593 + 1.0 / 0.289), radius=0.021335, speed=22.9,
             modulus=float(hertz.effective_modulus(136e6, 0.45, 196e9, 0.272)))


def test_area_fraction_is_the_area_integral():
    """Phi(k) against quadrature of int_0^1 2 w erf(k w) dw, and its limits (smooth: 1; light load: 4k/(3 sqrt pi))."""
    for k in (1e-5, 5e-4, 0.02, 0.3, 1.0, 2.5, 10.0):
        oracle = integrate.quad(lambda w: 2.0 * w * special.erf(k * w), 0.0, 1.0, epsabs=0, epsrel=1e-13)[0]
        assert fl.area_fraction(k) == pytest.approx(oracle, rel=1e-9)
    assert fl.area_fraction(np.inf) == 1.0
    assert fl.area_fraction(1e-6) == pytest.approx(4e-6 / (3.0 * np.sqrt(np.pi)), rel=1e-9)


def test_smooth_face_adhesion_is_tau_times_the_hertz_area_impulse():
    """On a smooth face mu = tau int pi a^2 dt / int F dt, with the Hertz history integrated here as an ODE; it
    falls with load as Schallamach's N^(-1/3): with a_max ~ V^(2/5), mu ~ V^(-2/5)."""
    tau = 5e6
    t, delta = _hertz_ode(WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], WEDGE["speed"])
    area = np.pi * WEDGE["radius"] * delta
    force = 4.0 / 3.0 * WEDGE["modulus"] * np.sqrt(WEDGE["radius"]) * delta**1.5
    oracle = tau * np.trapezoid(area, t) / np.trapezoid(force, t)
    mu, wet = fl.adhesion_friction(tau, 70e6, 0.45, 0.0, WEDGE["m"], WEDGE["radius"], WEDGE["modulus"],
                                   WEDGE["speed"])
    assert mu == pytest.approx(oracle, rel=2e-4)
    assert wet == 0.0
    faster, _ = fl.adhesion_friction(tau, 70e6, 0.45, 0.0, WEDGE["m"], WEDGE["radius"], WEDGE["modulus"],
                                     2.0 * WEDGE["speed"])
    assert faster / mu == pytest.approx(2.0 ** -0.4, rel=1e-9)


def test_rough_face_at_light_load_is_persson_and_the_sled_fit_round_trips():
    """Light load on a rough face: mu = sqrt(8/pi) tau / (E_c* s), load-independent; the presets' tau taken from a
    sled friction gives that friction back (adhesion + ploughing) at a sled-like load."""
    tau, modulus, slope = 4e6, 69e6, 0.2
    stiff = modulus / (1 - 0.45**2)
    slow = [fl.adhesion_friction(tau, modulus, 0.45, slope, WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], v)[0]
            for v in (1e-7, 2e-7)]
    assert slow[0] == pytest.approx(np.sqrt(8.0 / np.pi) * tau / (stiff * slope), rel=1e-4)
    assert slow[1] == pytest.approx(slow[0], rel=1e-4)
    e = 0.787
    tau_sled = fl.shear_strength_from_sled(0.40, modulus, 0.45, slope, e)
    back = fl.adhesion_friction(tau_sled, modulus, 0.45, slope, WEDGE["m"], WEDGE["radius"], WEDGE["modulus"],
                                1e-7)[0] + fl.ploughing_friction(slope, e)
    assert back == pytest.approx(0.40, rel=1e-4)
    # the presets: tau from the sled, a soft urethane cover and a stiff ionomer one
    assert BALL_PRESETS["urethane_tour"].shear_strength == pytest.approx(
        fl.shear_strength_from_sled(0.40, 68.9e6, 0.45, 0.2, 0.787))
    assert BALL_PRESETS["two_piece_ionomer"].cover_modulus == 330e6


def test_squeezed_water_film_against_its_own_ode():
    """The wet fraction of the impulse: the film thinned by Reynolds' disc squeeze, dh/dt = -2 p_m h^3 / (3 eta a^2),
    integrated along the ODE's Hertz history until h reaches the roughness; grooves drain faster (less wet)."""
    h0, rq = 20e-6, 2.2e-6
    t, delta = _hertz_ode(WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], WEDGE["speed"])
    a2 = WEDGE["radius"] * np.clip(delta, 1e-30, None)
    force = 4.0 / 3.0 * WEDGE["modulus"] * np.sqrt(WEDGE["radius"]) * delta**1.5
    # d(h^-2)/dt = -2 h^-3 dh/dt = 4 p_m / (3 eta a^2), p_m = F / (pi a^2)
    rate = 4.0 * (force / (np.pi * a2)) / (3.0 * fl.WATER_VISCOSITY * a2)
    growth = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])
    film = 1.0 / np.sqrt(h0**-2 + growth)
    wet_oracle = np.trapezoid(np.where(film > rq, force, 0.0), t) / np.trapezoid(force, t)
    common = (3e6, 69e6, 0.45, 0.2, WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], WEDGE["speed"])
    _, wet = fl.adhesion_friction(*common, rq, np.inf, h0)
    assert 0.05 < wet_oracle < 0.95
    assert wet == pytest.approx(wet_oracle, abs=0.03)  # 400 midpoints against the ODE: 0.017
    _, grooved = fl.adhesion_friction(*common, rq, 1.35e-3, h0)
    assert grooved < wet
    dry_mu, dry = fl.adhesion_friction(*common, rq, 1.35e-3, 0.0)
    assert dry == 0.0
    # a thick film on a smooth face never clears: no adhesion at all
    none, all_wet = fl.adhesion_friction(*common, 0.5e-6, np.inf, 200e-6)
    assert none == 0.0 and all_wet == pytest.approx(1.0, abs=1e-12)
    assert fl.adhesion_friction(*common, rq, 1.35e-3, h0)[0] < dry_mu


def test_flash_temperature_softening_is_self_consistent():
    """The softened coefficient mu satisfies mu = mu_a (1 - dT(mu) / dT_s) with dT the flash temperature it heats;
    a cover that does not melt (dT_s = inf) keeps mu_a."""
    mu_a, pressure, slip, time, rise = 0.31, 26.6e6, 17.9, 4.6e-4, 66.0
    mu = fl.thermal_factor(mu_a, pressure, slip, time, rise, 718.0, 8030.0)
    heat = fl.flash_temperature(mu, pressure, slip, time, 718.0, 8030.0)
    assert mu == pytest.approx(mu_a * (1.0 - heat / rise), rel=1e-12)
    # hand number: K = 2 p v/2 sqrt(t) / (sqrt(pi) (e_c + e_f))
    k = 2.0 * pressure * 0.5 * slip * np.sqrt(time) / (np.sqrt(np.pi) * (718.0 + 8030.0))
    assert mu == pytest.approx(mu_a / (1.0 + k * mu_a / rise), rel=1e-12)
    assert fl.thermal_factor(mu_a, pressure, slip, time, np.inf, 718.0, 8030.0) == mu_a


@pytest.mark.parametrize(("name", "options"), MODELS)
def test_coulomb_law_is_exactly_todays_model(name, options):
    """friction_law: coulomb (the default) is the friction input: bit-identical results on 1-D and 3-D cases."""
    for inputs in (REFERENCE_1D, DRIVER_CASES):
        plain = get_model(name)(**options).compute(inputs, OUTPUTS)
        law = get_model(name)(friction_law="coulomb", **options).compute(inputs, OUTPUTS)
        for output in OUTPUTS:
            np.testing.assert_array_equal(law[output].values, plain[output].values)


@pytest.mark.parametrize(("name", "options"), MODELS[:3])
def test_adhesion_law_in_its_constant_limit_is_coulomb_with_that_mu(name, options):
    """Analytic limit: a cover stiff enough to stay in Persson's light-load regime at any load gives the constant
    mu = sqrt(8/pi) tau / (E_c* s) + (3/16)(1 - e^2) s; with tau chosen for mu = 0.3 the model is today's model at
    friction 0.3 (to the law's series error, k^2 / 5 ~ 1e-8; e the ball's own, without the face's gain)."""
    inputs = dict(DRIVER_CASES)
    n = inputs["speed"].size
    slope, modulus = 0.2, 1e12
    stiff = modulus / (1.0 - inputs["ball_poisson_ratio"] ** 2)
    e_ball = inputs["restitution"] - inputs.get("club_restitution_gain", 0.0)  # the ball's own e (ploughing's loss)
    ploughing = 3.0 / 16.0 * (1.0 - e_ball**2) * slope
    tau = (0.3 - ploughing) * stiff * slope / np.sqrt(8.0 / np.pi)
    law_inputs = dict(inputs, ball_shear_strength=tau, ball_cover_modulus=np.full(n, modulus),
                      face_roughness_slope=np.full(n, slope), ball_cover_melt_rise=np.full(n, np.inf),
                      face_roughness=0.0, face_groove_land=np.inf, face_water_film=0.0)  # a dry face, given
    law = get_model(name)(friction_law="adhesion", **options).compute(law_inputs, OUTPUTS)
    plain = get_model(name)(**options).compute(_with(inputs, friction=0.3), OUTPUTS)
    for output in OUTPUTS:
        np.testing.assert_allclose(law[output].values, plain[output].values, rtol=2e-6, atol=1e-9)


def test_the_law_refuses_a_ball_without_cover_data():
    inputs = {key: value for key, value in REFERENCE_1D.items() if key != "ball_shear_strength"}
    with pytest.raises(ModelInputError, match="shear_strength") as refused:
        get_model("rigid_coulomb")(friction_law="adhesion").compute(inputs, ["spin_rate"])
    # the presets the message offers are presets (not a former name a study would be warned about)
    named = [word for word in str(refused.value).replace(",", " ").split() if "_" in word and word.islower()
             and word.split("_")[0] in ("urethane", "two", "tour", "surlyn")]
    assert named and all(name in BALL_PRESETS for name in named), named


def test_the_cover_and_the_face_move_friction_the_way_the_physics_says():
    """Wedge delivery: the ionomer's stiffer cover keeps more of its cold adhesion at impact load than urethane
    (its real area saturates later), its melting cover then loses most of it to the flash temperature; a wet,
    polished face loses adhesion entirely and a grooved one keeps part of it."""
    wedge = dict(DRIVER_CASES)
    keep = np.arange(2)
    wedge = {key: value[keep] for key, value in wedge.items()}
    state = CaseInputs(wedge).contact_state()
    groove = FACE_SURFACES["grooved_blasted_steel"]
    surface = {"face_roughness_slope": groove.roughness_slope, "face_roughness": groove.roughness,
               "face_groove_land": groove.groove_land, "face_effusivity": groove.effusivity,
               "face_water_film": groove.water_film}

    def mu(ball, **changes):
        b = BALL_PRESETS[ball]
        values = dict(wedge, **surface, ball_shear_strength=b.shear_strength, ball_cover_modulus=b.cover_modulus,
                      ball_cover_melt_rise=b.cover_melt_rise, ball_cover_effusivity=b.cover_effusivity)
        values.update(changes)
        return fl.effective_friction("adhesion", values, state, wedge["restitution"])

    cold_u, cold_i = mu("urethane_tour"), mu("two_piece_ionomer", ball_cover_melt_rise=np.inf)
    assert np.all(cold_i > cold_u)
    assert np.all(mu("two_piece_ionomer") < 0.5 * cold_i)
    assert np.all(mu("urethane_tour", face_water_film=20e-6) < cold_u)
    # a smooth, polished face (R_q 0.4 um, no grooves): the squeezed film never gets thinner than the roughness
    smooth_wet = mu("urethane_tour", face_water_film=20e-6, face_groove_land=np.inf, face_roughness=0.4e-6)
    ploughing = fl.ploughing_friction(groove.roughness_slope, wedge["restitution"] - wedge["club_restitution_gain"])
    np.testing.assert_allclose(smooth_wet, ploughing, rtol=1e-12)


@given(friction=st.floats(0.05, 0.8), film=st.floats(0.0, 50e-6), slope=st.floats(0.0, 0.5),
       melt=st.floats(20.0, 400.0), seed=st.integers(0, 2**16))
@settings(max_examples=6)
@pytest.mark.parametrize(("name", "options"), [("rigid_coulomb", {}), ("maw", {"tolerance": 1e-3}),
                                               ("maw", {"tolerance": 1e-3, "rolling_hysteresis": "restitution"})])
def test_friction_law_never_creates_energy_off_centre(name, options, friction, film, slope, melt, seed):
    """Energy after (ball and head, rotations included) never exceeds energy before, off-centre strikes on free
    heads, any surface, film and melting cover."""
    rng = np.random.default_rng(seed)
    n = DRIVER_CASES["speed"].size
    b = BALL_PRESETS["two_piece_ionomer"]
    inputs = _with(DRIVER_CASES, friction=friction, strike_toe=rng.uniform(-0.03, 0.03, n),
                   strike_high=rng.uniform(-0.02, 0.02, n), dynamic_loft=rng.uniform(0.05, 0.9, n),
                   speed=rng.uniform(20.0, 55.0, n), ball_shear_strength=rng.uniform(0.0, 2.0, n) * b.shear_strength,
                   ball_cover_modulus=b.cover_modulus, face_roughness_slope=slope, face_roughness=2e-6,
                   face_groove_land=1.35e-3, face_water_film=film, ball_cover_melt_rise=melt,
                   ball_cover_effusivity=b.cover_effusivity, face_effusivity=4000.0)
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse", "rolling_moment", "rolling_moment_slip"]
    result = get_model(name)(friction_law="adhesion", **options).compute(inputs, names)
    before, after = kinetic_energy(inputs), kinetic_energy(inputs, result)
    assert np.all(after <= before * (1.0 + 1e-9)), np.max((after - before) / before)


WITH_LAW = [get_model("rigid_coulomb")(friction_law="adhesion"),
            get_model("maw")(friction_law="adhesion", tolerance=1e-3),
            get_model("maw")(friction_law="adhesion", inelastic="hysteretic", rolling_hysteresis="restitution",
                             tolerance=1e-3),
            get_model("hertz_mindlin")(friction_law="adhesion", tolerance=1e-3),
            get_model("dem_linear")(friction_law="adhesion", tolerance=1e-3),
            get_model("restitution")(friction_law="adhesion")]


@pytest.mark.slow
@parametrize_with_checks(*WITH_LAW)
def test_conformance_with_the_friction_law(model, check):
    """The shipped conformance suite with the friction law on in every model."""
    check(model)


def test_a_study_selects_the_law_per_model_entry_and_sweeps_the_balls():
    """A study's model entry takes friction_law; a ball-preset sweep carries each cover's data to it. The wedge
    observation's delivery: the law separates the covers, the constant mu (0.40 and 0.35, both gripping) does not."""
    import impactlab

    study = impactlab.load_study({
        "ball": {"preset": "urethane_tour"}, "club": {"preset": "lob_wedge"},
        "delivery": {"club_speed": "65 mph", "attack_angle": "-4 deg", "dynamic_loft": "34 deg"},
        "sweep": {"ball.preset": ["urethane_tour", "two_piece_ionomer"]},
        "models": ["rigid_coulomb", {"name": "rigid_coulomb", "id": "rigid_friction", "friction_law": "adhesion"}],
        "outputs": ["spin_rate"]})
    spin = impactlab.run_study(study)["spin_rate"]
    plain, law = spin.sel(model="rigid_coulomb").values, spin.sel(model="rigid_friction").values
    assert plain[0] == pytest.approx(plain[1], rel=1e-6)  # both balls roll off the face
    assert law[0] == pytest.approx(plain[0], rel=1e-6)  # urethane still rolls (mu 0.17)
    assert law[1] < 0.7 * law[0]  # the ionomer slides (mu 0.08 with its flash temperature)


def test_hertz_scales_of_the_law_against_the_ode():
    """a_max, p_0, the impulse-weighted mean pressure int F (F / pi a^2) dt / int F dt and the contact time, from the
    Hertz impact integrated here as an ODE (a = sqrt(R delta), p_0 = 2 E* a / (pi R)): what the flash temperature
    heats with."""
    t, delta = _hertz_ode(WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], WEDGE["speed"])
    area = np.pi * WEDGE["radius"] * np.clip(delta, 1e-30, None)
    force = 4.0 / 3.0 * WEDGE["modulus"] * np.sqrt(WEDGE["radius"]) * delta**1.5
    a_max = np.sqrt(WEDGE["radius"] * delta.max())
    mean_oracle = np.trapezoid(force * force / area, t) / np.trapezoid(force, t)
    a, p0, mean, duration = fl.hertz_means(WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], WEDGE["speed"])
    assert a == pytest.approx(a_max, rel=1e-6)
    assert p0 == pytest.approx(2.0 * WEDGE["modulus"] * a_max / (np.pi * WEDGE["radius"]), rel=1e-6)
    assert mean == pytest.approx(mean_oracle, rel=1e-4)
    assert duration == pytest.approx(t[-1], rel=1e-4)


def test_grooves_drain_the_film_as_strips_against_their_own_ode():
    """Between grooves of half-land b the film drains sideways as from a long strip of width 2 b: Reynolds gives
    p(x) = 6 eta (-dh/dt) (b^2 - x^2) / h^3, a mean pressure 4 eta (-dh/dt) b^2 / h^3, so d(h^-2)/dt = p_m / (2 eta
    b^2) (Hamrock et al. 2004, ch. 16, derived here); the film drains by whichever of strip and disc is faster."""
    h0, rq, land = 20e-6, 2.2e-6, 3e-3
    t, delta = _hertz_ode(WEDGE["m"], WEDGE["radius"], WEDGE["modulus"], WEDGE["speed"])
    a2 = WEDGE["radius"] * np.clip(delta, 1e-30, None)
    force = 4.0 / 3.0 * WEDGE["modulus"] * np.sqrt(WEDGE["radius"]) * delta**1.5
    pressure = force / (np.pi * a2)
    rate = np.maximum(4.0 * pressure / (3.0 * fl.WATER_VISCOSITY * a2), pressure / (2.0 * fl.WATER_VISCOSITY * land**2))
    growth = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))])
    film = 1.0 / np.sqrt(h0**-2 + growth)
    wet_oracle = np.trapezoid(np.where(film > rq, force, 0.0), t) / np.trapezoid(force, t)
    disc_only = np.trapezoid(np.where(1.0 / np.sqrt(h0**-2 + np.concatenate([[0.0], np.cumsum(
        0.5 * (4.0 * pressure[1:] / (3.0 * fl.WATER_VISCOSITY * a2[1:]) + 4.0 * pressure[:-1] / (
            3.0 * fl.WATER_VISCOSITY * a2[:-1])) * np.diff(t))])) > rq, force, 0.0), t) / np.trapezoid(force, t)
    assert wet_oracle < disc_only - 0.1  # the strips, not the disc, decide here
    _, wet = fl.adhesion_friction(3e6, 69e6, 0.45, 0.2, WEDGE["m"], WEDGE["radius"], WEDGE["modulus"],
                                  WEDGE["speed"], rq, land, h0)
    assert wet == pytest.approx(wet_oracle, abs=0.01)  # measured 0.0024 (400 midpoints against the ODE)


@pytest.mark.parametrize(("name", "options"), [("rigid_coulomb", {}), ("maw", {"tolerance": 1e-3})])
def test_the_law_on_a_mirrored_strike_mirrors(name, options):
    """Mirror symmetry with every term of the law on (a melting ionomer cover heated by its slip, a grooved, wet
    face): negating the angle and the spin keeps J_n and flips J_t, as a left-handed golfer's mirrored strike must.
    The flash temperature heats with the slip's magnitude, whatever its sign."""
    b = BALL_PRESETS["two_piece_ionomer"]
    groove = FACE_SURFACES["grooved_blasted_steel"]
    inputs = _with(REFERENCE_1D, ball_shear_strength=b.shear_strength, ball_cover_modulus=b.cover_modulus,
                   ball_cover_melt_rise=b.cover_melt_rise, ball_cover_effusivity=b.cover_effusivity,
                   face_roughness_slope=groove.roughness_slope, face_roughness=groove.roughness,
                   face_groove_land=groove.groove_land, face_water_film=5e-6, face_effusivity=groove.effusivity)
    mirrored = _with(inputs, angle=-inputs["angle"], spin=-inputs["spin"])
    model = get_model(name)(friction_law="adhesion", **options)
    a = model.compute(inputs, ["normal_impulse", "tangential_impulse"])
    m = model.compute(mirrored, ["normal_impulse", "tangential_impulse"])
    np.testing.assert_allclose(m["normal_impulse"].values, a["normal_impulse"].values, rtol=1e-10)
    np.testing.assert_allclose(m["tangential_impulse"].values, -a["tangential_impulse"].values, rtol=1e-10,
                               atol=1e-12)
    # the mirrored cases soften as much as the right-handed ones: the law's mu is the same per case
    plain = model.compute(_with(inputs, ball_cover_melt_rise=np.inf), ["tangential_impulse"])
    assert np.any(np.abs(a["tangential_impulse"].values) < np.abs(plain["tangential_impulse"].values) - 1e-6)


def test_a_club_preset_sweep_carries_each_presets_face_surface():
    """Sweeping club.preset must give each case its own club's face: the lob wedge's grooved, blasted steel beside the
    driver's smooth titanium, whatever club the study's base block names (the surface was the base club's for every
    case, silently: the wedge on a smooth face spun 1,769 rpm instead of 3,321 with the ionomer ball)."""
    import impactlab

    def spins(base):
        study = impactlab.load_study({
            "ball": {"preset": "two_piece_ionomer"}, "club": {"preset": base},
            "delivery": {"club_speed": "65 mph", "attack_angle": "-4 deg", "dynamic_loft": "34 deg"},
            "sweep": {"club.preset": ["driver", "lob_wedge"]},
            "models": [{"name": "rigid_coulomb", "friction_law": "adhesion"}], "outputs": ["spin_rate"]})
        return impactlab.run_study(study)["spin_rate"].values.ravel()

    np.testing.assert_allclose(spins("driver"), spins("lob_wedge"), rtol=1e-12)


def test_a_ball_without_cover_data_still_sweeps_beside_one_with_it_unless_the_law_reads_them():
    """surlyn_distance has no cover data for the friction law: sweeping it beside urethane_tour worked before the law
    existed and must still work with Coulomb friction (same spin: the same contact); with friction_law: adhesion it
    is refused, naming the missing cover, rather than given the other ball's cover."""
    import impactlab
    from impactlab.errors import FieldError

    def study(models):
        return {"ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
                "contact": {"friction": 0.4, "restitution": 0.78},
                "delivery": {"club_speed": "100 mph", "attack_angle": "2 deg", "dynamic_loft": "12 deg"},
                "sweep": {"ball.preset": ["urethane_tour", "surlyn_distance"]}, "models": models,
                "outputs": ["spin_rate"]}

    spin = impactlab.run_study(impactlab.load_study(study(["rigid_coulomb"])))["spin_rate"].values.ravel()
    assert spin.size == 2 and spin[0] == pytest.approx(spin[1], rel=1e-12)
    with pytest.raises(FieldError, match="shear_strength.*friction_law"):
        impactlab.load_study(study([{"name": "rigid_coulomb", "friction_law": "adhesion"}]))
