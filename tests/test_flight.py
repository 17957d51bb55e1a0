"""The ball flight (impactlab.physics.flight, impactlab.fly, a study's flight outputs) against oracles written
independently of the code: the vacuum projectile, an independent scipy DOP853 integration, published air tables
(ISA, Buck), the published coefficient formulas, symmetries, and TrackMan's measured tour carries."""

import time

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from impactlab.data.carry import RPM, YARD, carry_table, validate_carry
from impactlab.physics import aerodynamics, atmosphere, flight
from impactlab.units import MPH

G = atmosphere.G0
DRIVER = {"ball_speed": 167 * MPH, "launch_angle": np.radians(10.9), "spin_rate": 2686 * RPM}
SEVEN = {"ball_speed": 120 * MPH, "launch_angle": np.radians(16.3), "spin_rate": 7097 * RPM}


# --------------------------------------------------------------------------
# Air
# --------------------------------------------------------------------------
def test_air_density_isa_sea_level():
    # ISA: 1.2250 kg/m^3 at 288.15 K, 101325 Pa, dry.
    assert atmosphere.air_density(288.15, 101325.0, 0.0) == pytest.approx(1.2250, abs=5e-4)


def test_air_density_humid_air_is_lighter_and_vectorised():
    rh = np.array([0.0, 0.5, 1.0])
    rho = atmosphere.air_density(303.15, 101325.0, rh)
    assert rho.shape == (3,)
    assert np.all(np.diff(rho) < 0)
    # 30 degC saturated air: about 1.145 kg/m^3 (dry 1.164); e_s(30 C) = 4.24 kPa.
    assert atmosphere.saturation_vapour_pressure(303.15) == pytest.approx(4246, rel=2e-3)
    assert rho[2] == pytest.approx(1.1455, abs=2e-3)


def test_pressure_at_altitude_isa_table():
    # ISO 2533 tabulated values: 1000 m 89 874.6 Pa, 5000 m 54 019.9 Pa, 11 000 m 22 632 Pa.
    p = atmosphere.pressure_at_altitude(np.array([0.0, 1000.0, 5000.0, 11000.0]))
    np.testing.assert_allclose(p, [101325.0, 89874.6, 54019.9, 22632.1], rtol=2e-4)


def test_viscosity_sutherland():
    assert atmosphere.air_viscosity(288.15) == pytest.approx(1.7894e-5, rel=1e-3)


# --------------------------------------------------------------------------
# Aerodynamic coefficients
# --------------------------------------------------------------------------
def test_smits_smith_coefficients_as_published():
    # CD = 0.24 + 0.18 S + 0.06 sin(pi (Re - 9e4)/2e5); CL = 0.54 S^0.4
    cd, cl = aerodynamics.aero_coefficients([0.1, 0.2], [9.0e4, 1.9e5], model="smits_smith_1994")
    np.testing.assert_allclose(cd, [0.24 + 0.018, 0.24 + 0.036 + 0.06], rtol=1e-12)
    np.testing.assert_allclose(cl, [0.54 * 0.1**0.4, 0.54 * 0.2**0.4], rtol=1e-12)


def test_lyu_coefficients_as_published():
    cd, cl = aerodynamics.aero_coefficients([0.2], [1.0e5], model="lyu_2018")
    assert cd[0] == pytest.approx(1.91e-11 * 1e10 - 5.40e-6 * 1e5 + 0.56)
    assert cl[0] == pytest.approx(-3.25 * 0.04 + 1.99 * 0.2)


def test_usga_patent_coefficients_reproduce_patent_data_points():
    # US 6,186,002 example data: S 0.218, Re 0.812e5 -> CL 0.278, CD 0.305;
    # S 0.092, Re 2.0e5 -> CL 0.153, CD 0.241 (regression R^2 0.99).
    cd, cl = aerodynamics.aero_coefficients([0.218, 0.092], [0.812e5, 2.0e5], model="usga_patent_2001")
    np.testing.assert_allclose(cl, [0.278, 0.153], atol=0.005)
    np.testing.assert_allclose(cd, [0.305, 0.241], atol=0.01)


def test_composite_models_as_documented():
    # lift held at the peak of Lyu et al. 2018's published fit, -3.25 S^2 + 1.99 S: 1.99^2 / 13 = 0.3046 at S 0.306
    cd, cl = aerodynamics.aero_coefficients([0.1, 0.5], [1.5e5, 1.5e5], model="smits_smith_lift_capped")
    assert cl[0] == pytest.approx(0.54 * 0.1**0.4) and cl[1] == pytest.approx(0.3046, abs=1e-4)
    assert cd[1] == pytest.approx(0.24 + 0.18 * 0.5 + 0.06 * np.sin(np.pi * 0.3))
    # induced drag fitted on the USGA ITR example data: CD = a + b Re + k CL^2 reproduces the patent's measured
    # condition means (CD 0.223..0.305, shot SD <= 0.006) within 0.01
    data = np.array(aerodynamics.USGA_ITR_EXAMPLE)
    design = np.column_stack([np.ones(len(data)), data[:, 0], data[:, 3] ** 2])
    fit = design @ np.linalg.lstsq(design, data[:, 2], rcond=None)[0]
    np.testing.assert_allclose(fit, data[:, 2], atol=0.01)
    assert 1.2 < aerodynamics.INDUCED_DRAG_FACTOR < 1.7
    cd_l, cl_l = aerodynamics.aero_coefficients([0.2], [1.5e5], model="lyu_2018")
    cd_i, cl_i = aerodynamics.aero_coefficients([0.2], [1.5e5], model="lyu_2018_induced_drag")
    assert cl_i[0] == cl_l[0] and cd_i[0] == pytest.approx(cd_l[0] + aerodynamics.INDUCED_DRAG_FACTOR * cl_l[0] ** 2)




def test_measured_fit_by_hand_at_published_points():
    c = aerodynamics.MEASURED_FIT
    # the formula of docs/flight.md worked by hand at S 0.2, Re 1.5e5 (the crisis terms are below 1e-8 there)
    lift = c["a"] * 0.2 / (1 + c["b"] * 0.2)
    drag = c["c0"] + c["c_re"] * 1.5 + c["k"] * lift**2
    cd, cl = aerodynamics.aero_coefficients(0.2, 1.5e5, model="measured_fit")
    assert cl == pytest.approx(lift, rel=1e-7) and cd == pytest.approx(drag, rel=1e-7)
    assert 0.22 < cl < 0.26 and 0.24 < cd < 0.28  # Lyu et al. 2018 Fig. 4a: CL 0.25 at S 0.185 (13 balls)
    # USGA ITR example ball (US 6,186,002), condition means: Re 1.23e5 S 0.153 CL 0.213; Re 2.0e5 S 0.092 CL 0.153
    _, cl = aerodynamics.aero_coefficients([0.153, 0.092], [1.23e5, 2.0e5], model="measured_fit")
    np.testing.assert_allclose(cl, [0.213, 0.153], atol=0.03)
    # Lyu, Kensrud & Smith 2020 Fig. 3, Pro V1 at 2250 rpm: Re 1.51e5 S 0.090 CD 0.186, CL 0.121 (the model's drag is
    # the modern balls'; the 1998 USGA ball measured 0.23 there)
    cd, cl = aerodynamics.aero_coefficients(0.090, 1.51e5, model="measured_fit")
    assert cd == pytest.approx(0.186, abs=0.03) and cl == pytest.approx(0.121, abs=0.03)
    # reverse Magnus in the drag crisis: Lyu 2020 Fig. 4, Pro V1 at Re 6e4, CL -0.011..-0.065 at S 0.11-0.125 and
    # Fig. 5 at Re 6.5e4, CL -0.02..-0.14 at S 0.11-0.15 (three balls), against 0.16-0.20 above the crisis
    _, cl = aerodynamics.aero_coefficients([0.11, 0.125], 6.0e4, model="measured_fit")
    assert np.all(cl < 0) and np.all(cl > -0.1)
    _, cl = aerodynamics.aero_coefficients([0.11, 0.15], 6.5e4, model="measured_fit")
    _, above = aerodynamics.aero_coefficients([0.11, 0.15], 2.0e5, model="measured_fit")
    assert np.all(cl < 0.2 * above)
    # drag crisis, Lyu et al. 2018 Fig. 3a without spin: 13 balls span 0.385-0.53 at Re 5e4 (mean 0.477); 0.215 at 1e5
    cd, _ = aerodynamics.aero_coefficients(0.0, [5e4, 1e5], model="measured_fit")
    assert 0.385 < cd[0] < 0.53 and cd[1] == pytest.approx(0.215, abs=0.03)
    # Bearman & Harvey 1976: Re 8.24e4 S 0.46 CL 0.352, CD 0.391. Their 1976 ball's drag sits 0.043 above the
    # modern balls' at equal S (the fit's group offsets 0.2346 and 0.1913)
    cd, cl = aerodynamics.aero_coefficients(0.460, 82369.0, model="measured_fit")
    assert cl == pytest.approx(0.352, abs=0.03) and cd + (0.2346 - 0.1913) == pytest.approx(0.391, abs=0.03)
    # Naruo, Mizota & Shimozono 2004 eqs. 12-13 (Bridgestone Skyway, wind tunnel, Re 7.09e4-1.25e5), worked here from
    # the paper's polynomials: S 0.5 CD 0.4137, CL 0.3879; S 0.3 CD 0.3266, CL 0.3141; their ball's offset 0.2228.
    # Checked at both ends of their Re for the drag, at 1.25e5 for the lift: the model keeps the modern balls' lift
    # loss near Re 7e4 (12 % at S 0.5), which their ball did not show
    for s, cd_paper, cl_paper in ((0.5, 0.7510 / 16 - 1.760 / 8 + 1.098 / 4 + 0.2148 / 2 + 0.2049,
                                   -0.2158 / 16 + 1.006 / 8 - 1.644 / 4 + 1.250 / 2 + 0.0616),
                                  (0.3, 0.7510 * 0.3**4 - 1.760 * 0.3**3 + 1.098 * 0.09 + 0.2148 * 0.3 + 0.2049,
                                   -0.2158 * 0.3**4 + 1.006 * 0.3**3 - 1.644 * 0.09 + 1.250 * 0.3 + 0.0616)):
        for re in (7.09e4, 1.25e5):
            cd, cl = aerodynamics.aero_coefficients(s, re, model="measured_fit")
            assert cd + (0.2228 - 0.1913) == pytest.approx(cd_paper, abs=0.03)
            assert re < 1e5 or cl == pytest.approx(cl_paper, abs=0.03)
    # Acushnet US 6,729,976 Table 3 (invention ball, indoor test range): Re 69 000 S 0.284 CD 0.305/0.309 (two
    # orientations); its offset is the modern balls' (0.1920). Its CL there (0.278/0.290) shows no lift loss, where
    # the model keeps the loss Lyu 2020 measured on three tour balls near Re 7e4 (ball-specific, docs/flight.md)
    cd, cl = aerodynamics.aero_coefficients(0.284, 69000.0, model="measured_fit")
    assert cd == pytest.approx(0.307, abs=0.03) and cl < 0.278


def test_measured_fit_limits():
    re = np.array([3e4, 6e4, 1e5, 2.5e5])
    cd, cl = aerodynamics.aero_coefficients(0.0, re, model="measured_fit")
    np.testing.assert_array_equal(cl, 0.0)  # no spin, no lift at any Re
    assert np.all(cd > 0.17)
    s = np.linspace(0.0, 3.0, 301)
    cd, cl = aerodynamics.aero_coefficients(s, 1.5e5, model="measured_fit")
    assert np.all(np.diff(cl) > 0) and np.all(np.diff(cd) > 0)  # supercritical: lift and drag rise with spin
    c = aerodynamics.MEASURED_FIT
    assert cl[-1] < c["a"] / c["b"] < 0.6  # lift saturates at a / b
    # the drag crisis: drag falls with Re through it, then is nearly flat
    cd, _ = aerodynamics.aero_coefficients(0.1, np.array([4e4, 5.5e4, 6.5e4, 8e4, 2e5]), model="measured_fit")
    assert np.all(np.diff(cd) < 0) and cd[0] - cd[-1] > 0.15 and cd[3] - cd[4] < 0.02






def test_measurements_file_says_measurement_and_cites_every_block():
    from importlib import resources

    import yaml

    document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath(
        "aero_coefficients.yaml").read_text())
    assert document["kind"] == "measurement"
    for key, block in document["blocks"].items():
        assert block["group"] in document["groups"] and block["source"] and block["method"], key
        assert all(len(row) == 4 for row in block["rows"]), key
    assert "TrackMan" not in yaml.safe_dump(document["blocks"])  # nothing of the validation tables is fitted


# --------------------------------------------------------------------------
# Analytic projectile (vacuum) limit
# --------------------------------------------------------------------------
@pytest.mark.parametrize("deg", [5.0, 20.0, 45.0, 70.0])
def test_vacuum_matches_analytic_projectile(deg):
    v, th = 50.0, np.radians(deg)
    r = flight.fly(v, th, 3000 * RPM, np.radians(15), np.radians(7), model="vacuum")
    rng = v**2 * np.sin(2 * th) / G
    assert r["carry_distance"] == pytest.approx(rng, rel=1e-9)
    assert r["apex_height"] == pytest.approx((v * np.sin(th)) ** 2 / (2 * G), rel=1e-9)
    assert r["flight_time"] == pytest.approx(2 * v * np.sin(th) / G, rel=1e-9)
    assert r["landing_angle"] == pytest.approx(th, rel=1e-9)
    # launched 7 deg right, no curvature in vacuum
    assert r["offline_distance"] == pytest.approx(rng * np.sin(np.radians(7)), rel=1e-9)
    assert r["carry_x"] == pytest.approx(rng * np.cos(np.radians(7)), rel=1e-9)


# --------------------------------------------------------------------------
# Independent integrator cross-check (scipy adaptive RK45/DOP853)
# --------------------------------------------------------------------------
def _scipy_reference(v0, th, w0, alpha, model="smits_smith_1994", lam=2.0e-5, T=288.15, rh=0.5):
    """Straightforward re-implementation, y LEFT internally, solved by DOP853."""
    rho = atmosphere.air_density(T, 101325.0, rh)
    mu = atmosphere.air_viscosity(T)
    R, m = aerodynamics.BALL_RADIUS, aerodynamics.BALL_MASS
    k = rho * np.pi * R**2 / (2 * m)
    vhat = np.array([np.cos(th), 0.0, np.sin(th)])
    right = np.array([0.0, -1.0, 0.0])
    up = np.cross(right, vhat)
    axis = np.cos(alpha) * right - np.sin(alpha) * up

    def f(t, y):
        v = y[3:6]
        sp = np.linalg.norm(v)
        c = np.cross(axis, v / sp)
        sa = np.linalg.norm(c)
        s = R * y[6] * sa / sp
        re = rho * sp * 2 * R / mu
        cd, cl = aerodynamics.aero_coefficients(s, re, model)
        a = -k * cd * sp * v + k * cl * sp**2 * c / sa - np.array([0, 0, G])
        return np.concatenate([v, a, [-lam * rho / 1.225 * sp * y[6] / R]])

    def hit(t, y):
        return y[2]

    def top(t, y):
        return y[5]

    hit.terminal, hit.direction = True, -1
    top.direction = -1
    y0 = np.concatenate([[0, 0, 0], v0 * vhat, [w0]])
    sol = solve_ivp(f, (0, 20), y0, method="DOP853", rtol=1e-11, atol=1e-11,
                    events=(hit, top), first_step=1e-3)
    ye = sol.y_events[0][0]
    apex = sol.y_events[1][0][2]
    return np.hypot(ye[0], ye[1]), -ye[1], sol.t_events[0][0], apex


@pytest.mark.parametrize("alpha_deg", [0.0, 25.0])
def test_matches_scipy_dop853(alpha_deg):
    a = np.radians(alpha_deg)
    r = flight.fly(DRIVER["ball_speed"], DRIVER["launch_angle"], DRIVER["spin_rate"], a, model="smits_smith_1994")
    carry, off, tf, _ = _scipy_reference(DRIVER["ball_speed"], DRIVER["launch_angle"],
                                         DRIVER["spin_rate"], a)
    assert r["carry_distance"] == pytest.approx(carry, abs=1e-4)
    assert r["offline_distance"] == pytest.approx(off, abs=1e-4)
    assert r["flight_time"] == pytest.approx(tf, abs=1e-5)


def test_step_size_convergence():
    kw = dict(SEVEN, spin_axis=np.radians(-12), wind=(-4.0, 3.0, 0.0))
    a = flight.fly(**kw, dt=0.02)
    b = flight.fly(**kw, dt=0.002)
    for key in ("carry_distance", "offline_distance", "apex_height", "flight_time", "landing_angle"):
        assert a[key] == pytest.approx(b[key], abs=1e-5)


# --------------------------------------------------------------------------
# Symmetries and signs
# --------------------------------------------------------------------------
def test_spin_axis_mirror_symmetry():
    ax = np.radians([-30, -10, 10, 30])
    r = flight.fly(**DRIVER, spin_axis=ax)
    np.testing.assert_allclose(r["offline_distance"], -r["offline_distance"][::-1], atol=1e-9)
    np.testing.assert_allclose(r["carry_distance"], r["carry_distance"][::-1], rtol=1e-12)
    # positive axis = tilted right = curves right
    assert r["offline_distance"][3] > r["offline_distance"][2] > 0


def test_launch_direction_and_crosswind_signs():
    r = flight.fly(**DRIVER, launch_direction=np.radians(3))
    assert r["offline_distance"] > 0
    calm = flight.fly(**SEVEN)
    from_left = flight.fly(**SEVEN, wind=(0.0, 5.0, 0.0))  # blowing toward the right
    assert from_left["offline_distance"] > 1.0
    head = flight.fly(**SEVEN, wind=(-5.0, 0.0, 0.0))
    tail = flight.fly(**SEVEN, wind=(5.0, 0.0, 0.0))
    assert head["carry_distance"] < calm["carry_distance"] < tail["carry_distance"]


def test_zero_spin_gives_no_lift():
    # With zero spin the spin axis is meaningless: no sideways force, and the
    # flight equals a drag-only flight solved independently.
    r = flight.fly(50.0, np.radians(20), 0.0, spin_axis=np.radians([-40.0, 0.0, 40.0]), model="smits_smith_1994")
    np.testing.assert_allclose(r["offline_distance"], 0.0, atol=1e-12)
    np.testing.assert_allclose(r["carry_distance"], r["carry_distance"][1], rtol=1e-12)
    carry, _, _, apex = _scipy_reference(50.0, np.radians(20), 0.0, 0.0)
    assert r["carry_distance"][1] == pytest.approx(carry, abs=1e-4)
    assert r["apex_height"][1] == pytest.approx(apex, abs=1e-5)
    # and any spin at all adds lift: higher apex than the zero-spin shot
    spun = flight.fly(50.0, np.radians(20), 3000 * RPM)
    assert spun["apex_height"] > r["apex_height"][1]


def test_more_backspin_raises_apex():
    spins = np.array([1000, 2000, 3000, 4000, 6000, 8000]) * RPM
    r = flight.fly(SEVEN["ball_speed"], SEVEN["launch_angle"], spins)
    assert np.all(np.diff(r["apex_height"]) > 0)
    assert np.all(np.diff(r["landing_angle"]) > 0)


def test_higher_altitude_carries_further():
    alts = np.array([0.0, 500.0, 1609.0, 2240.0])  # sea level ... Denver, Mexico City
    for club in (DRIVER, SEVEN):
        r = flight.fly(**club, altitude=alts)
        assert np.all(np.diff(r["carry_distance"]) > 0)
    # Denver driver gain is several percent (TrackMan and USGA both quote
    # roughly 6-10 %; not an oracle for the exact figure).
    r = flight.fly(**DRIVER, altitude=[0.0, 1609.0])
    gain = r["carry_distance"][1] / r["carry_distance"][0] - 1
    assert 0.03 < gain < 0.12


def test_energy_never_increases_without_wind():
    r = flight.fly(**DRIVER, spin_axis=np.radians(20), return_trajectories=True)
    e = 0.5 * (r["vx"] ** 2 + r["vy"] ** 2 + r["vz"] ** 2) + G * r["z"]
    assert np.all(np.diff(e, axis=1) <= 1e-9 * np.abs(e[:, :-1]))
    assert e[0, -1] < e[0, 0]


def test_spin_decay():
    r = flight.fly(**DRIVER)
    assert 0.6 < r["landing_spin"] / DRIVER["spin_rate"] < 0.9  # Penner: ~75 % for a drive
    r0 = flight.fly(**DRIVER, spin_decay=0.0)
    assert r0["landing_spin"] == pytest.approx(DRIVER["spin_rate"])
    assert r0["apex_height"] > r["apex_height"]


# --------------------------------------------------------------------------
# Vectorisation and speed
# --------------------------------------------------------------------------
def test_broadcasting_and_scalar_consistency():
    v = np.array([[60.0], [70.0]])
    th = np.radians([10.0, 14.0, 18.0])
    r = flight.fly(v, th, 3000 * RPM)
    assert r["carry_distance"].shape == (2, 3)
    single = flight.fly(70.0, np.radians(14.0), 3000 * RPM)
    assert r["carry_distance"][1, 1] == pytest.approx(float(single["carry_distance"]), rel=1e-12)
    tr = flight.fly(v, th, 3000 * RPM, return_trajectories=True)
    assert tr["x"].shape[0] == 6
    np.testing.assert_allclose(tr["x"][:, -1], r["carry_x"].ravel(), rtol=1e-12)


def test_ten_thousand_shots_cost_linear_cpu_time():
    """10 000 random shots all land; their CPU time is about 10x that of 1000 (linear; per-shot Python loops or a
    quadratic working set would be ~100x). A ratio measured in one run, never a clock against a constant: the
    per-shot cost is printed by benchmarks/bench_flight.py."""
    rng = np.random.default_rng(1)

    def shots(n):
        return (rng.uniform(40, 80, n), np.radians(rng.uniform(8, 30, n)), rng.uniform(2000, 10000, n) * RPM,
                np.radians(rng.uniform(-20, 20, n)))

    small, large = shots(1_000), shots(10_000)
    flight.fly(*shots(3))  # compile the kernel (or load it from numba's cache) outside the measurement
    start = time.process_time()
    flight.fly(*small)
    middle = time.process_time()
    r = flight.fly(*large)
    end = time.process_time()
    assert np.all(np.isfinite(r["carry_distance"]))
    assert (end - middle) / max(middle - start, 1e-3) < 30.0


def test_rejects_bad_input():
    with pytest.raises(ValueError):
        flight.fly(-1.0, 0.2, 100.0)
    with pytest.raises(ValueError):
        flight.fly(60.0, 0.2, 100.0, model="nope")


# --------------------------------------------------------------------------
# Validation against TrackMan PGA Tour averages (measurements; impactlab/data/validation/trackman_carry.yaml)
# --------------------------------------------------------------------------
def test_carry_table_is_the_published_table():
    table = carry_table()
    assert len(table.clubs) == 12 and table.clubs[0] == "Driver" and table.clubs[-1] == "PW"
    # cells confirmed as text (Golf Monthly 2023-12-05): driver 167 mph / 275 yd / 32 yd, 7-iron 120 mph / 172 yd
    assert table.ball_speed[0] == pytest.approx(167 * MPH) and table.carry[0] == pytest.approx(275 * YARD)
    assert table.max_height[0] == pytest.approx(32 * YARD)
    assert table.ball_speed[8] == pytest.approx(120 * MPH) and table.carry[8] == pytest.approx(172 * YARD)
    assert "TrackMan" in table.source and "not normalised" in table.source


def test_carry_table_file_says_measurement_and_is_shipped():
    from importlib import resources

    import yaml

    document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath("trackman_carry.yaml").read_text())
    assert document["kind"] == "measurement"


def test_default_model_carries_within_3_percent_rms_of_every_tour_table():
    """The issue's target, on the model fitted to measured CD and CL only (no carry, no TrackMan row in its fit):
    2.40 / 2.85 / 2.57 % RMS on the classic, PGA 2023 and LPGA 2023 tables (docs/flight.md)."""
    for name in ("trackman_carry", "trackman_carry_pga_2023", "trackman_carry_lpga_2023"):
        assert validate_carry(table=carry_table(name))["rms_carry_error"] <= 0.03, name


def test_trackman_pga_regression_guard():
    # Locks in the measured skill of the best published model so that a code change cannot silently make it
    # worse (measured: RMS 5.0 %, every club within -9.4..+6.8 %; heights +1..+8 yd, land angles 3..8 deg shallow).
    check = validate_carry("smits_smith_1994")
    table = check["table"]
    assert check["rms_carry_error"] <= 0.052
    assert np.all(np.abs(check["carry_error"]) <= 0.10)
    assert np.all(np.abs(check["apex_height"] - table.max_height) <= 9 * YARD)
    assert np.all(np.abs(np.degrees(check["landing_angle"] - table.land_angle)) <= 9.0)


def test_composite_models_regression_guard():
    # measured (docs/flight.md): lift capped 3.1 % RMS (driver -9.4 %); Lyu + induced drag 5.0 % (all -3..-7 %)
    assert validate_carry("smits_smith_lift_capped")["rms_carry_error"] <= 0.032
    check = validate_carry("lyu_2018_induced_drag")
    assert check["rms_carry_error"] <= 0.052
    assert np.all(np.abs(check["apex_height"] - check["table"].max_height) <= 5 * YARD)


def test_measured_fit_regression_guard_on_three_tables():
    # measured (docs/flight.md): classic PGA 2.40 %, PGA 2023 2.85 %, LPGA 2023 2.57 % RMS, every club within 5.4 %;
    # heights within 6 yd (the 2023 drivers 6 yd low), land angles 0-10 deg shallow (LPGA 3-wood, whose table spin is
    # 2595 rpm, the most). Fitted to measured CD and CL only, not to these.
    for name, rms in (("trackman_carry", 0.0245), ("trackman_carry_pga_2023", 0.029),
                      ("trackman_carry_lpga_2023", 0.0262)):
        check = validate_carry("measured_fit", carry_table(name))
        table = check["table"]
        assert check["rms_carry_error"] <= rms, name
        assert np.all(np.abs(check["carry_error"]) <= 0.055), name
        assert np.all(np.abs(check["apex_height"] - table.max_height) <= 6.5 * YARD), name
        land = np.degrees(check["landing_angle"] - table.land_angle)
        assert np.all(land <= 0.0) and np.all(land >= -10.0), name


def test_2023_tables_are_the_published_tables():
    pga, lpga = carry_table("trackman_carry_pga_2023"), carry_table("trackman_carry_lpga_2023")
    assert len(pga.clubs) == 12 and len(lpga.clubs) == 11 and "3-iron" not in lpga.clubs
    # Golf Monthly (2024 update) quotes the PGA driver at 171 mph, 35 yd high, 282 yd carry and the 3-wood at 249 yd;
    # trackman_tour.yaml has the LPGA driver launch from the same release (143 mph, 12.6 deg, 2506 rpm)
    assert pga.ball_speed[0] == pytest.approx(171 * MPH) and pga.carry[0] == pytest.approx(282 * YARD)
    assert pga.max_height[0] == pytest.approx(35 * YARD) and pga.carry[1] == pytest.approx(249 * YARD)
    assert lpga.ball_speed[0] == pytest.approx(143 * MPH) and lpga.spin_rate[0] == pytest.approx(2506 * RPM)
    assert np.degrees(lpga.launch_angle[0]) == pytest.approx(12.6)
    for table in (pga, lpga):
        assert "TrackMan" in table.source and "2023" in table.source


def test_session_carry_flies_each_exported_shot():
    from importlib import resources

    import yaml

    from impactlab.data.carry import session_carry

    for name in ("trackman_carry_pga_2023", "trackman_carry_lpga_2023"):
        document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath(f"{name}.yaml").read_text())
        assert document["kind"] == "measurement"
    # the TrackMan TPS export's 7 Iron row (copied from a real session, tests/data/vendors/README.md): 123.79 mph,
    # 15.35 deg, 5492 rpm, carry 177.2 yd; its Driver row has no carry
    check = session_carry("tests/data/vendors/trackman_tps.csv", "measured_fit")
    assert check["club"] == ["7 Iron"] and check["vendor_carry"][0] == pytest.approx(177.21028090888305 * YARD)
    alone = flight.fly(check["ball_speed"], check["launch_angle"], check["spin_rate"], check["spin_axis"],
                       model="measured_fit")
    np.testing.assert_allclose(check["carry"], alone["carry_distance"], rtol=1e-12)
    assert abs(check["carry_error"][0]) < 0.10  # measured: +7.3 % (TrackMan's 7 Iron row, standard air)


def test_session_carry_refuses_a_negative_magnitude_or_a_carry_that_is_not_positive(tmp_path):
    """A spin of -2500 rpm flown would curve the other way and a carry of 0 would give an infinite error: each row is
    named at its line instead."""
    from impactlab.data.carry import session_carry
    from impactlab.errors import StudyError

    path = tmp_path / "s.csv"
    path.write_text("ball_speed [mph],vertical_launch_angle [deg],spin_rate [rpm],carry_distance [yd]\n"
                    "140,12,2500,240\n140,12,-2500,240\n-140,12,2500,240\n140,12,2500,0\n")
    with pytest.raises(StudyError) as refused:
        session_carry(path, "measured_fit")
    message = str(refused.value)
    assert "s.csv:3: spin_rate" in message and "s.csv:4: ball_speed" in message
    assert "s.csv:5: carry_distance" in message and "s.csv:2" not in message
    path.write_text("ball_speed [mph],vertical_launch_angle [deg],spin_rate [rpm],carry_distance [yd]\n"
                    "140,12,2500,240\n")
    assert session_carry(path, "measured_fit")["carry"][0] > 0


def test_smits_smith_is_the_best_published_model_on_the_classic_table():
    rms = {m: validate_carry(m)["rms_carry_error"] for m in aerodynamics.PUBLISHED_MODELS}
    rms = {m: (v if np.isfinite(v) else np.inf) for m, v in rms.items()}
    assert min(rms, key=rms.get) == "smits_smith_1994"


def test_default_model_is_the_fit_to_measured_coefficients_and_gets_the_driver_right():
    # the default is impactlab's fit to measured CD and CL (never to a carry table); it was chosen over Smits &
    # Smith (1994) for what the tables show beside the RMS: TrackMan's drivers (the shot a fitter compares first)
    # within 3 % on all three tables where Smits & Smith is 9 % short on the classic one, and the heights within
    # 2 yd on average where Smits & Smith is 3-4 yd high (docs/flight.md)
    assert aerodynamics.DEFAULT_MODEL in aerodynamics.MEASUREMENT_FITS
    for name in ("trackman_carry", "trackman_carry_pga_2023", "trackman_carry_lpga_2023"):
        table = carry_table(name)
        default = validate_carry(table=table)
        driver = table.clubs.index("Driver")
        assert abs(default["carry_error"][driver]) < 0.03, name
        assert abs(np.mean(default["apex_height"] - table.max_height)) < 2.0 * YARD, name
    smits = validate_carry("smits_smith_1994")
    assert smits["carry_error"][carry_table().clubs.index("Driver")] < -0.08


# --------------------------------------------------------------------------
# impactlab.fly: units, arrays, the air
# --------------------------------------------------------------------------
def test_fly_takes_units_numbers_and_quantities_alike():
    import pint

    import impactlab

    ureg = pint.UnitRegistry()
    by_text = impactlab.fly(ball_speed="167 mph", launch_angle="10.9 deg", spin_rate="2686 rpm",
                            spin_axis="5 deg", launch_direction="-2 deg")
    by_si = impactlab.fly(167 * MPH, np.radians(10.9), 2686 * RPM, np.radians(5), np.radians(-2))
    by_pint = impactlab.fly(ureg.Quantity(167, "mph"), ureg.Quantity(10.9, "deg"), ureg.Quantity(2686, "rpm"),
                            ureg.Quantity(5, "deg"), ureg.Quantity(-2, "deg"))
    physics = flight.fly(167 * MPH, np.radians(10.9), 2686 * RPM, np.radians(5), np.radians(-2))
    for result in (by_text, by_si, by_pint):
        assert float(result.carry_distance) == pytest.approx(float(physics["carry_distance"]), rel=1e-12)
        assert float(result.landing_angle) == pytest.approx(np.degrees(float(physics["landing_angle"])), rel=1e-12)
    assert by_text.carry_distance.attrs["units"] == "m"
    assert by_text.landing_angle.attrs["units"] == "degree"
    assert by_text.flight_time.attrs["units"] == "s"


def test_fly_broadcasts_arrays():
    import impactlab

    result = impactlab.fly(ball_speed=[60.0, 70.0], launch_angle=np.radians([[10.0], [14.0], [18.0]]),
                           spin_rate="3000 rpm")
    assert result.carry_distance.shape == (3, 2)
    single = flight.fly(70.0, np.radians(14.0), 3000 * RPM)
    assert float(result.carry_distance[1, 1]) == pytest.approx(float(single["carry_distance"]), rel=1e-12)


def test_fly_conditions_are_the_air_they_say():
    import impactlab

    # 25 degC, 1013.25 hPa, dry: the same flight as the physics function given that air directly
    air = {"temperature": "25 degC", "pressure": "1013.25 hPa", "relative_humidity": "0 %", "headwind": "10 mph",
           "crosswind": "5 mph"}
    result = impactlab.fly("120 mph", "16.3 deg", "7097 rpm", conditions=air)
    direct = flight.fly(120 * MPH, np.radians(16.3), 7097 * RPM, temperature=298.15, pressure=101325.0,
                        relative_humidity=0.0, wind=(-10 * MPH, 5 * MPH, 0.0))
    assert float(result.carry_distance) == pytest.approx(float(direct["carry_distance"]), rel=1e-12)
    assert float(result.offline_distance) > 0  # a wind blowing to the right pushes the ball right
    assert result.attrs["air_density_kg_m3"] == pytest.approx(101325.0 / (287.05 * 298.15), rel=1e-3)
    # altitude alone sets the ISA pressure: Denver (1609 m) is 83.4 kPa (ISO 2533)
    denver = impactlab.fly("167 mph", "10.9 deg", "2686 rpm", conditions={"altitude": "5280 ft"})
    assert denver.attrs["air_pressure_Pa"] == pytest.approx(83.4e3, rel=2e-3)


@pytest.mark.parametrize("kwargs, words", [
    (dict(ball_speed="167", launch_angle=0.2, spin_rate=300.0), "has no unit"),
    (dict(ball_speed="167 deg", launch_angle=0.2, spin_rate=300.0), "do not convert"),
    (dict(ball_speed=-5.0, launch_angle=0.2, spin_rate=300.0), "positive ball speed"),
    (dict(ball_speed=70.0, launch_angle="10 mph", spin_rate=300.0), "not an angle unit"),
    (dict(ball_speed=70.0, launch_angle=0.2, spin_rate=-1.0), "spin rate >= 0"),
    (dict(ball_speed=70.0, launch_angle=0.2, spin_rate=300.0, conditions={"temp": "20 degC"}), "conditions.temp"),
    (dict(ball_speed=70.0, launch_angle=0.2, spin_rate=300.0,
          conditions={"pressure": "1000 hPa", "altitude": "100 m"}), "not both"),
    (dict(ball_speed=70.0, launch_angle=0.2, spin_rate=300.0, conditions={"relative_humidity": 60}), "between 0 and 1"),
])
def test_fly_refuses_bad_values_with_one_message(kwargs, words):
    import impactlab
    from impactlab.errors import FieldError

    with pytest.raises(FieldError, match=words):
        impactlab.fly(**kwargs)


# --------------------------------------------------------------------------
# A study asks for the flight after any impact model
# --------------------------------------------------------------------------
def _golf_study(outputs, **extra):
    return {"name": "flight", "ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
            "contact": {"friction": 0.4, "restitution": 0.8},
            "delivery": {"club_speed": "110 mph", "path": "2 deg", "face_angle": "-1 deg", "attack_angle": "-1 deg",
                         "dynamic_loft": "13 deg"},
            "sweep": {"strike.toe": ["-10 mm", "0 mm", "10 mm"]},
            "models": ["rigid_coulomb", {"name": "restitution", "tangential_restitution": 0.1}],
            "outputs": outputs, **extra}


LAUNCH = ["ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "back_spin", "side_spin", "spin_axis"]
FLIGHT = ["carry_distance", "offline_distance", "apex_height", "landing_angle", "flight_time"]


def test_study_flight_equals_fly_on_the_models_launch():
    import impactlab

    air = {"temperature": "30 degC", "altitude": "400 m", "relative_humidity": "70 %", "headwind": "3 m/s",
           "crosswind": "-2 m/s"}
    result = impactlab.run_study(_golf_study(LAUNCH + FLIGHT, conditions=air))
    ball = impactlab.load_study(_golf_study(LAUNCH)).scene.ball
    for model in result.model.values:
        row = result.sel(model=model)
        spin = np.hypot(row.back_spin.values, row.side_spin.values) * RPM  # the spin across the flight
        alone = impactlab.fly(row.ball_speed.values, np.radians(row.vertical_launch_angle.values), spin,
                              np.radians(row.spin_axis.values), np.radians(row.horizontal_launch_angle.values),
                              conditions=air, ball_mass=ball.mass, ball_radius=ball.radius)
        for name in FLIGHT:
            np.testing.assert_allclose(row[name].values, alone[name].values, rtol=1e-9, err_msg=name)
    assert np.all(result.carry_distance.values > 150) and result.carry_distance.attrs["units"] == "m"
    assert result.landing_angle.attrs["units"] == "degree"
    # each flight variable names the air model that flew it (the default can change between versions)
    for name in FLIGHT:
        assert result[name].attrs["aerodynamic_model"] == aerodynamics.DEFAULT_MODEL


def test_the_plan_names_the_air_model_the_run_flies_with():
    """`impactlab run --plan` said 'Smits & Smith 1994 aerodynamics' after measured_fit became the default: the plan's
    words must name the model the result then records on its flight variables, and no other air model."""
    import impactlab
    from impactlab.run.runner import plan_study

    study = _golf_study(LAUNCH + ["carry_distance"])
    text = plan_study(impactlab.load_study(study)).describe()
    flown = impactlab.run_study(study).carry_distance.attrs["aerodynamic_model"]
    assert f"({flown} aerodynamics" in text
    assert not any(other in text for other in aerodynamics.MODELS if other != flown and flown not in other), text


@pytest.mark.slow
def test_trajectories_fly_with_the_air_model_the_result_names(tmp_path, monkeypatch):
    """A result computed with another air model (an older file) is redrawn with that model, and says so."""
    import impactlab
    from impactlab.plot import trajectories
    from impactlab.plot.style import conditions

    result = impactlab.run_study(_golf_study(LAUNCH + ["carry_distance"]))
    assert f"{aerodynamics.DEFAULT_MODEL} aerodynamics" in conditions(result)
    result.carry_distance.attrs["aerodynamic_model"] = "smits_smith_1994"
    used = []
    original = trajectories.fly
    monkeypatch.setattr(trajectories, "fly", lambda *a, **k: used.append(k["model"]) or original(*a, **k))
    trajectories.plot_trajectories(result, tmp_path / "t.png")
    assert used and set(used) == {"smits_smith_1994"}
    assert "smits_smith_1994 aerodynamics" in conditions(result)
    # a file from before the outputs named their model was flown with Smits & Smith, the default then
    del result.carry_distance.attrs["aerodynamic_model"]
    used.clear()
    trajectories.plot_trajectories(result, tmp_path / "t2.png")
    assert set(used) == {"smits_smith_1994"}
    # a result holding only the launch is flown with today's default
    used.clear()
    trajectories.plot_trajectories(result.drop_vars("carry_distance"), tmp_path / "t3.png")
    assert set(used) == {aerodynamics.DEFAULT_MODEL}


def test_study_not_asking_for_the_flight_does_not_compute_it(monkeypatch):
    import impactlab
    from impactlab.model import derive

    calls = []
    original = flight.fly
    # the name the study's derivation calls (derive's own): a stub on impactlab.physics.flight would not reach it
    monkeypatch.setattr(derive, "fly", lambda *a, **k: calls.append(1) or original(*a, **k))
    impactlab.run_study(_golf_study(LAUNCH), executor="serial")
    assert calls == []
    impactlab.run_study(_golf_study(LAUNCH + ["carry_distance"]), executor="serial")
    assert len(calls) == 2  # once per model (one chunk each)
    # nor does a model computed without named outputs
    model = impactlab.get_model("rigid_coulomb")()
    model.compute(impactlab.load_study(_golf_study(LAUNCH)).scene.inputs())
    assert len(calls) == 2


def test_study_conditions_sweep_and_no_delivery():
    import impactlab

    study = _golf_study(["carry_distance"], conditions={"temperature": "20 degC"})
    study["sweep"] = {"conditions.altitude": ["0 m", "1609 m"]}
    result = impactlab.run_study(study)
    carry = result.carry_distance.values  # (model, altitude)
    assert np.all(carry[:, 1] > carry[:, 0] * 1.03)  # thinner air carries further (Denver: several percent)
    plate = {"name": "plate", "ball": {"preset": "urethane_tour"}, "face": {"preset": "steel"},
             "contact": {"friction": 0.4, "restitution": 0.8}, "impact": {"speed": "40 m/s", "angle": "30 deg"},
             "models": ["rigid_coulomb"], "outputs": ["ball_speed", "carry_distance"]}
    result = impactlab.run_study(plate)
    assert np.isnan(result.carry_distance.values).all()
    assert "golf delivery" in result.carry_distance.attrs["missing"]


@pytest.mark.parametrize("conditions, words", [
    ({"temperature": 25}, "with its unit"),
    ({"temperature": 0}, "not even 0: 0 degC is 273.15 K"),  # an offset unit: a bare 0 would be a guess too
    ({"altitude": 1600}, "with its unit"),
    ({"humidity": "50 %"}, "conditions.humidity"),
    ({"pressure": "1000 hPa", "altitude": "100 m"}, "not both"),
    ({"temperature": "25 m"}, "do not convert"),
])
def test_study_conditions_block_refuses_with_its_path(conditions, words):
    import impactlab
    from impactlab.errors import FieldError

    with pytest.raises(FieldError, match=words) as caught:
        impactlab.load_study(_golf_study(["carry_distance"], conditions=conditions))
    assert "conditions" in str(caught.value)


# --------------------------------------------------------------------------
# Trajectory figures
# --------------------------------------------------------------------------
def test_trajectory_figure_lands_where_the_result_says(tmp_path, monkeypatch):
    import impactlab
    from impactlab.plot import trajectories

    result = impactlab.run_study(_golf_study(LAUNCH + FLIGHT, conditions={"temperature": "10 degC"}))
    captured = []
    # the name plot_trajectories calls (its module's): a stub elsewhere would not reach it
    monkeypatch.setattr(trajectories, "_save", lambda figure, path: captured.append(figure) or path)
    trajectories.plot_trajectories(result, tmp_path / "t.png")
    side, top = captured[0].axes[:2]
    ends = np.array([[line.get_xdata()[-1], line.get_ydata()[-1]] for line in top.get_lines()
                     if len(line.get_xdata()) > 2])
    carry = result.carry_distance.transpose("model", ...).values.reshape(-1)
    offline = result.offline_distance.transpose("model", ...).values.reshape(-1)
    np.testing.assert_allclose(np.hypot(ends[:, 0], ends[:, 1]), carry, rtol=1e-9)
    np.testing.assert_allclose(ends[:, 1], offline, atol=1e-9)
    heights = [np.max(line.get_ydata()) for line in side.get_lines()]
    np.testing.assert_allclose(np.sort(heights), np.sort(result.apex_height.values.reshape(-1)), rtol=1e-3)


@pytest.mark.slow
def test_cli_draws_trajectories_and_refuses_a_result_without_launch(tmp_path, capsys):
    import impactlab
    from impactlab.cli import main

    good, bad = tmp_path / "good.h5", tmp_path / "bad.h5"
    impactlab.run_study(_golf_study(LAUNCH + ["carry_distance"]), output=good)
    assert main(["plot", str(good), "--trajectories"]) == 0
    assert (tmp_path / "good_trajectories.png").stat().st_size > 10_000
    impactlab.run_study(_golf_study(["ball_speed", "carry_distance"]), output=bad)
    assert main(["plot", str(bad), "--trajectories"]) == 2
    err = capsys.readouterr().err
    assert "vertical_launch_angle" in err and "Traceback" not in err


@pytest.mark.parametrize("page", ["README.md", "docs/flight.md"])
def test_documented_fly_examples_run(page, capsys):
    import re
    from pathlib import Path

    text = (Path(__file__).resolve().parents[1] / page).read_text()
    blocks = [block for block in re.findall(r"```python\n(.*?)```", text, flags=re.S) if "impactlab.fly(" in block]
    assert blocks
    for block in blocks:
        exec(compile(block, page, "exec"), {})  # noqa: S102 - our own documentation
    assert "yd" in capsys.readouterr().out or page == "README.md"


def test_a_trajectory_lying_on_another_models_says_so_in_the_legend(tmp_path, monkeypatch):
    """Two models with the same launch fly the same path; the later one covers the earlier, and its legend entry
    names the model it lies on (standards: no curve hidden under another without saying so). A path a metre off
    is not marked."""
    import xarray as xr

    import impactlab
    from impactlab.plot import trajectories

    result = impactlab.run_study(_golf_study(LAUNCH))
    copy = result.sel(model=["rigid_coulomb"]).assign_coords(model=["rigid_copy"])
    both = xr.concat([result.sel(model=["rigid_coulomb"]), copy], dim="model")
    both.attrs = result.attrs
    figures = []
    monkeypatch.setattr(trajectories, "_save", lambda figure, path: figures.append(figure) or path)
    trajectories.plot_trajectories(both, tmp_path / "t.png")
    labels = [text.get_text() for text in figures[0].legends[0].get_texts()]
    assert [label for label in labels if "(on " in label] == [
        f"rigid_copy, {case} (on rigid_coulomb)" for case in ("toe -10 mm", "toe 0 mm", "toe 10 mm")], labels
    # the test of coincidence by hand: the same path is on; one raised by a metre, or landing 2 m longer, is not
    x = np.linspace(0.0, 250.0, 200)
    z = 30.0 * np.sin(np.pi * x / 250.0)
    y = -0.0005 * x**2
    drawn = [(x, z, y, ("a", "case"))]
    assert trajectories._lies_on(drawn, x, z + 0.05, y) == ("a", "case")
    assert trajectories._lies_on(drawn, x, z + 1.0, y) is None
    assert trajectories._lies_on(drawn, x * 1.008, z, y) is None


def test_a_flight_shorter_than_one_step_lands_where_the_projectile_does():
    """A 0.2 mph lob at 45 deg in a vacuum lands after 2 v sin(a) / g = 0.0129 s, inside the integrator's first
    0.02 s step: carry v^2 sin(2a) / g, landing at the launch angle. The landing search took the interpolant's root
    at the tee (the launch itself): carry 0, time 0 and the landing angle of the launch, sign flipped (-45 deg)."""
    import impactlab

    mph = np.array([0.2, 0.5, 3.0])
    shots = impactlab.fly(ball_speed=mph * 0.44704, launch_angle=np.radians(45.0), spin_rate=0.0, model="vacuum")
    v, g = mph * 0.44704, 9.80665
    np.testing.assert_allclose(shots.carry_distance.values, v * v / g, rtol=1e-9)
    np.testing.assert_allclose(shots.flight_time.values, 2 * v * np.sin(np.radians(45.0)) / g, rtol=1e-9)
    np.testing.assert_allclose(shots.landing_angle.values, 45.0, atol=1e-6)


@pytest.mark.slow
def test_trajectories_read_a_launch_edited_into_other_units(tmp_path, monkeypatch):
    """A result whose ball speed was converted to mph and spins to rad/s with xarray (units attributes with them)
    flies the same launch as the file as written: the figure reads each value in the unit it states (trust7 left
    this: 100 mph was flown as 100 m/s); a units attribute of the wrong kind is refused."""
    import impactlab
    from impactlab.errors import FieldError
    from impactlab.plot import trajectories

    result = impactlab.run_study(_golf_study(LAUNCH + ["carry_distance"]))
    flown = []
    original = trajectories.fly
    monkeypatch.setattr(trajectories, "fly", lambda *a, **k: flown.append(np.concatenate([a[0], a[2]]))  # speed, spin
                        or original(*a, **k))
    trajectories.plot_trajectories(result, tmp_path / "a.png")
    edited = result.copy()
    edited["ball_speed"] = result.ball_speed / 0.44704
    edited["ball_speed"].attrs = dict(result.ball_speed.attrs, units="mph")
    for name in ("back_spin", "side_spin"):
        edited[name] = result[name] * np.pi / 30.0
        edited[name].attrs = dict(result[name].attrs, units="rad/s")
    trajectories.plot_trajectories(edited, tmp_path / "b.png")
    assert len(flown) >= 2 and all(np.allclose(a, b, rtol=1e-12) for a, b in zip(flown[:len(flown) // 2],
                                                                                  flown[len(flown) // 2:]))
    edited["ball_speed"].attrs["units"] = "deg"
    with pytest.raises(FieldError, match=r"ball_speed\.units"):
        trajectories.plot_trajectories(edited, tmp_path / "c.png")


def test_a_retired_model_is_refused_with_why_and_what_to_use():
    import impactlab
    from impactlab.errors import FieldError

    with pytest.raises(FieldError, match="retired on 2026-11-24.*use 'measured_fit'"):
        impactlab.fly(70.0, 0.2, 300.0, model="measured_fit_late_crisis")
    with pytest.raises(ValueError, match="retired on 2026-11-24"):
        flight.fly(70.0, 0.2, 300.0, model="measured_fit_late_crisis")
    assert not set(aerodynamics.RETIRED_MODELS) & set(aerodynamics.MODELS)


def test_the_coefficients_of_a_retired_or_unknown_model_are_refused_with_why():
    # aero_coefficients is public: a model name that is not shipped is a ValueError naming it (a retired one with
    # why and what to use), never a bare KeyError
    with pytest.raises(ValueError, match="retired on 2026-11-24.*use 'measured_fit'"):
        aerodynamics.aero_coefficients(0.2, 1.0e5, model="measured_fit_late_crisis")
    with pytest.raises(ValueError, match="unknown model 'no_such_model'.*measured_fit"):
        aerodynamics.aero_coefficients(0.2, 1.0e5, model="no_such_model")


def test_the_carry_command_says_why_a_retired_model_is_refused(capsys):
    from impactlab.data import carry

    with pytest.raises(SystemExit) as exit_:
        carry.main(["measured_fit_late_crisis"])
    err = capsys.readouterr().err
    assert exit_.value.code == 2 and "retired on 2026-11-24" in err and "use 'measured_fit'" in err


@pytest.mark.slow
def test_a_result_records_its_air_models_constants_and_the_figure_says_when_they_changed(tmp_path, monkeypatch):
    """A refit keeps the model's name (measured_fit, 2026-11-24): a result records a fingerprint of the coefficients
    its flight was computed with, and the trajectory figure, which flies the stored launches again with today's
    constants, says so when they differ from the stored ones."""
    import impactlab
    from impactlab.plot import trajectories

    today = aerodynamics.model_fingerprint("measured_fit")
    assert today == aerodynamics.model_fingerprint("measured_fit")  # the same constants, the same fingerprint
    assert today != aerodynamics.model_fingerprint("measured_fit_usga_ball")  # only c0 differs there
    monkeypatch.setitem(aerodynamics.MEASURED_FIT, "m", aerodynamics.MEASURED_FIT["m"] + 1e-3)
    assert aerodynamics.model_fingerprint("measured_fit") != today  # any constant changed shows
    monkeypatch.undo()
    result = impactlab.run_study(_golf_study(LAUNCH + ["carry_distance"]))
    assert result.carry_distance.attrs["aerodynamic_fingerprint"] == today
    assert impactlab.fly(70.0, 0.2, 300.0).attrs["aerodynamic_fingerprint"] == today
    titles = []
    monkeypatch.setattr(trajectories, "_save", lambda figure, path: titles.append(figure._suptitle.get_text()))
    trajectories.plot_trajectories(result, tmp_path / "t.png")
    assert "stored carries" not in titles[-1]
    result.carry_distance.attrs["aerodynamic_fingerprint"] = "0123456789ab"  # a result of other constants
    trajectories.plot_trajectories(result, tmp_path / "t.png")
    assert f"today's constants, {today}; the stored carries were computed with 0123456789ab" in titles[-1]
