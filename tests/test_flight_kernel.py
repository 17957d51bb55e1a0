"""The compiled flight kernel (impactlab.physics.kernels.flight) against oracles written here: a converged scipy
integration of the same equations (the error bound docs/flight.md states), the previous numpy integrator on the docs'
shots and TrackMan's tour launches, and the numpy coefficient formulas (its cost: a CPU-time ratio in
tests/test_flight.py)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from impactlab.data.carry import RPM, TABLES, carry_table
from impactlab.physics import aerodynamics, atmosphere, flight
from impactlab.physics import kernels as _kernels
from impactlab.units import MPH

pytestmark = pytest.mark.skipif(not _kernels.HAVE_NUMBA, reason="numba is not installed")

#: (speed m/s, launch deg, spin rpm, axis deg, direction deg, wind (public frame) m/s, temperature K): a driver, a
#: 7-iron, a wedge, a low-spin knuckler, a sky-high lob, a slice into a crosswind, a punch into a headwind
ENVELOPE = [(74.7, 10.9, 2686, 0.0, 0.0, (0, 0, 0), 288.15), (53.6, 16.3, 7097, -4.0, 1.0, (0, 0, 0), 298.15),
            (45.0, 30.0, 9500, 0.0, 0.0, (0, 0, 0), 288.15), (70.0, 8.0, 800, 0.0, 0.0, (0, 0, 0), 288.15),
            (30.0, 55.0, 6000, 0.0, 0.0, (0, 0, 0), 278.15), (75.0, 12.0, 3200, 25.0, -3.0, (0, -6, 0), 288.15),
            (55.0, 12.0, 6000, 0.0, 0.0, (-8, 0, 0), 303.15)]


def _converged(v0, launch, spin, axis, direction, wind, temperature, model):
    """The same equations written again from docs/flight.md, in the right-handed frame x to the target, y LEFT, z
    up (lift along w x v_r), solved by DOP853 at rtol 1e-10: carry, apex, flight time, landing angle."""
    rho = atmosphere.air_density(temperature, 101325.0, 0.5)
    mu = atmosphere.air_viscosity(temperature)
    radius, mass = aerodynamics.BALL_RADIUS, aerodynamics.BALL_MASS
    k = rho * np.pi * radius**2 / (2 * mass)
    th, psi, alpha = np.radians(launch), -np.radians(direction), np.radians(axis)  # psi: to the left
    v_hat = np.array([np.cos(th) * np.cos(psi), np.cos(th) * np.sin(psi), np.sin(th)])
    right = np.array([np.sin(psi), -np.cos(psi), 0.0])  # backspin: (-y) x (+x) = +z, the lift is up
    up = np.cross(right, v_hat)
    w_hat = np.cos(alpha) * right - np.sin(alpha) * up  # tilted right: w x v gains a -y (right) part
    wind = np.array([wind[0], -wind[1], wind[2]], dtype=float)
    function = aerodynamics.MODELS[model][0]

    def rates(t, y):
        v_r = y[3:6] - wind
        speed = np.linalg.norm(v_r)
        across = np.cross(w_hat, v_r / speed)
        sine = np.linalg.norm(across)
        cd, cl = function(np.array(radius * y[6] * sine / speed), np.array(rho * speed * 2 * radius / mu))
        lift = k * cl * speed**2 * across / sine if sine > 0 else 0.0
        acceleration = -k * cd * speed * v_r + lift - np.array([0.0, 0.0, atmosphere.G0])
        return np.concatenate([y[3:6], acceleration, [-2.0e-5 * rho / 1.225 * speed * y[6] / radius]])

    def landing(t, y):
        return y[2]

    def apex(t, y):
        return y[5]

    landing.terminal, landing.direction, apex.direction = True, -1, -1
    y0 = np.concatenate([[0.0, 0.0, 0.0], v0 * v_hat, [spin * RPM]])
    solution = solve_ivp(rates, (0.0, 20.0), y0, method="DOP853", rtol=1e-10, atol=1e-10,
                         events=(landing, apex), first_step=1e-4)
    end = solution.y_events[0][0]
    return (np.hypot(end[0], end[1]), solution.y_events[1][0][2], solution.t_events[0][0],
            np.arctan2(-end[5], np.hypot(end[3], end[4])))


def _kernel(model, **options):
    columns = list(zip(*ENVELOPE))
    wind = np.array(columns[5], dtype=float)
    return flight.fly(np.array(columns[0]), np.radians(columns[1]), np.array(columns[2]) * RPM,
                      np.radians(columns[3]), np.radians(columns[4]), wind=wind, temperature=np.array(columns[6]),
                      model=model, **options)


@pytest.mark.parametrize("model", ["measured_fit", "smits_smith_1994", "lyu_2018"])
def test_default_step_keeps_the_carry_within_1_mm_of_a_converged_integration(model):
    """docs/flight.md's bound: at the default tolerance the carry is within 1 mm of the converged flight (measured
    0.2 um for the smooth models, 0.2 mm for lyu_2018 whose drag fit jumps at Re 7.5e4); apex and landing likewise."""
    result = _kernel(model)
    reference = np.array([_converged(*shot, model) for shot in ENVELOPE])
    np.testing.assert_allclose(result["carry_distance"], reference[:, 0], rtol=0, atol=1e-3)
    np.testing.assert_allclose(result["apex_height"], reference[:, 1], rtol=0, atol=1e-3)
    np.testing.assert_allclose(result["flight_time"], reference[:, 2], rtol=0, atol=1e-4)
    np.testing.assert_allclose(result["landing_angle"], reference[:, 3], rtol=0, atol=1e-5)
    if model != "lyu_2018":  # a smooth model: the bound holds with a margin of 1000
        np.testing.assert_allclose(result["carry_distance"], reference[:, 0], rtol=0, atol=1e-6)
    # a looser tolerance takes longer steps and is further off: the bound is the step's doing, not luck
    loose = _kernel(model, tolerance=1e-4)
    assert np.max(np.abs(loose["carry_distance"] - reference[:, 0])) > np.max(np.abs(
        result["carry_distance"] - reference[:, 0]))


def _tour_and_docs_launches():
    """The launches of the three tour tables and of the docs' examples (README, docs/flight.md): speed, angle,
    spin, axis, direction (SI) and the air keywords."""
    launches = []
    for name in TABLES:
        table = carry_table(name)
        for i in range(len(table.clubs)):
            launches.append(((table.ball_speed[i], table.launch_angle[i], table.spin_rate[i], 0.0, 0.0), table.air))
    docs = [((167 * MPH, np.radians(10.9), 2686 * RPM, np.radians(-4), np.radians(1)),
             {"temperature": 298.15, "altitude": 300.0, "wind": (-5 * MPH, 0.0, 0.0)}),
            ((167 * MPH, np.radians(10.9), 2686 * RPM, np.radians(3), 0.0),
             {"temperature": 298.15, "altitude": 1600.0, "wind": (-5 * MPH, 0.0, 0.0)}),
            ((120 * MPH, np.radians(16.3), 7097 * RPM, np.radians(3), 0.0),
             {"temperature": 298.15, "altitude": 1600.0, "wind": (-5 * MPH, 0.0, 0.0)})]
    for temperature in (278.15, 293.15, 308.15):
        docs.append(((120 * MPH, np.radians(16), 7000 * RPM, 0.0, 0.0), {"temperature": temperature,
                                                                        "pressure": 101000.0}))
    return launches + docs


@pytest.mark.parametrize("model", ["measured_fit", "smits_smith_1994"])
def test_kernel_flies_as_the_previous_numpy_integrator_on_the_docs_and_tour_shots(model, monkeypatch):
    """The numpy RK4 integrator (fixed 0.02 s, the implementation before the kernel, kept for callables and where
    numba is off) and the kernel: carry, apex, landing angle and hang time within the documented bound."""
    launches = _tour_and_docs_launches()
    columns = [np.array(column) for column in zip(*(launch for launch, _ in launches))]
    air = {"temperature": np.array([a.get("temperature", 288.15) for _, a in launches]),
           "relative_humidity": np.array([a.get("relative_humidity", 0.5) for _, a in launches]),
           "pressure": np.array([a.get("pressure", atmosphere.pressure_at_altitude(a.get("altitude", 0.0)))
                                 for _, a in launches]),
           "wind": np.array([a.get("wind", (0.0, 0.0, 0.0)) for _, a in launches])}
    compiled = flight.fly(*columns, model=model, **air)
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    previous = flight.fly(*columns, model=model, **air)
    for name, bound in (("carry_distance", 1e-3), ("offline_distance", 1e-3), ("apex_height", 1e-3),
                        ("landing_angle", 1e-5), ("flight_time", 1e-4)):
        np.testing.assert_allclose(compiled[name], previous[name], rtol=0, atol=bound, err_msg=name)
    # both are far closer than the bound: 1e-6 m on these smooth models
    np.testing.assert_allclose(compiled["carry_distance"], previous["carry_distance"], rtol=0, atol=1e-5)
    assert len(launches) == 41 and np.all(compiled["carry_distance"] > 50.0)


def test_a_callable_model_flies_as_the_registered_one_through_the_numpy_integrator():
    """A caller's function is flown by the numpy integrator; the same formula named is flown compiled: the same
    carries within the bound."""
    def mine(s, re):
        return aerodynamics.model_function("measured_fit")(s, re)

    args = (np.array([74.7, 53.6, 45.0]), np.radians([10.9, 16.3, 30.0]), np.array([2686, 7097, 9500]) * RPM)
    np.testing.assert_allclose(flight.fly(*args, model=mine)["carry_distance"],
                               flight.fly(*args, model="measured_fit")["carry_distance"], rtol=0, atol=1e-5)


def test_compiled_coefficients_are_the_numpy_formulas_and_read_todays_constants(monkeypatch):
    from impactlab.physics.kernels import flight as kernel

    s, re = (grid.ravel() for grid in np.meshgrid(np.linspace(0.0, 2.0, 21), np.geomspace(1e4, 5e5, 31)))
    for model, (function, _) in aerodynamics.MODELS.items():
        number, constants = kernel.kernel_model(model)
        cd, cl = np.empty(s.size), np.empty(s.size)
        kernel._coefficient_grid_kernel(number, constants, s, re, cd, cl)
        want_cd, want_cl, _ = np.broadcast_arrays(*function(s, re), s)
        np.testing.assert_allclose(cd, want_cd, rtol=1e-13, atol=1e-15, err_msg=model)
        np.testing.assert_allclose(cl, want_cl, rtol=1e-13, atol=1e-15, err_msg=model)
    # a refit's constants fly at once (they are passed at each call, not compiled in)
    before = flight.fly(74.7, np.radians(10.9), 2686 * RPM)["carry_distance"]
    monkeypatch.setitem(aerodynamics.MEASURED_FIT, "c0", aerodynamics.MEASURED_FIT["c0"] + 0.01)
    after = flight.fly(74.7, np.radians(10.9), 2686 * RPM)["carry_distance"]
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    assert after < before - 1.0
    assert float(after) == pytest.approx(float(flight.fly(74.7, np.radians(10.9), 2686 * RPM)["carry_distance"]),
                                         abs=1e-5)


def test_compiled_coefficients_that_differ_from_numpys_fly_numpy_with_a_warning(monkeypatch):
    """A numba cache older than an edit of aerodynamics.py's formulas would fly yesterday's coefficients: the check
    says so and the flight is the numpy integrator's, never a silent wrong carry. Injected: wrong constants."""
    from impactlab.physics.kernels import flight as kernel

    wrong = np.array(aerodynamics._measured_fit_constants()) * 1.01
    monkeypatch.setattr(kernel, "_model_constants", lambda function: wrong)
    monkeypatch.setattr(kernel, "_checked", {})
    with pytest.warns(RuntimeWarning, match="differ from impactlab.physics.aerodynamics"):
        result = flight.fly(74.7, np.radians(10.9), 2686 * RPM)
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    assert float(result["carry_distance"]) == float(flight.fly(74.7, np.radians(10.9), 2686 * RPM)["carry_distance"])


def test_landing_and_apex_are_the_roots_of_the_flight():
    """At the landing z is 0 to round-off and the landing state is the flight's at that time (a run to exactly
    that time with a step limit agrees); the apex is the top: no sampled height of the path exceeds it."""
    r = flight.fly(53.6, np.radians(16.3), 7097 * RPM, return_trajectories=True, dt=0.001)
    apex = float(r["apex_height"])
    assert np.max(r["z"]) <= apex + 1e-9 and np.max(r["z"]) > apex - 1e-4  # 1 ms apart: within vz dt^2 g / 8
    coarse = flight.fly(53.6, np.radians(16.3), 7097 * RPM)
    assert float(coarse["flight_time"]) == pytest.approx(float(r["flight_time"]), abs=1e-6)
    assert float(coarse["apex_height"]) == pytest.approx(apex, abs=1e-6)


def test_a_flight_the_step_cannot_follow_ends_not_landed_as_the_numpy_integrators(monkeypatch):
    """The USGA patent's regression lifts a 9-iron launch (TrackMan's classic table) until the ball stops in the air,
    where its lift turns at once: the steps shrink without end. The kernel gives up (NaN: not landed), as the numpy
    integrator's 15 s limit does, and returns; the longer clubs land where the numpy integrator lands them."""
    table = carry_table()
    compiled = flight.fly(table.ball_speed, table.launch_angle, table.spin_rate, model="usga_patent_2001")
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    previous = flight.fly(table.ball_speed, table.launch_angle, table.spin_rate, model="usga_patent_2001")
    np.testing.assert_array_equal(np.isnan(compiled["carry_distance"]), np.isnan(previous["carry_distance"]))
    assert np.isnan(compiled["carry_distance"][-1]) and np.isfinite(compiled["carry_distance"][0])
    np.testing.assert_allclose(compiled["carry_distance"], previous["carry_distance"], rtol=0, atol=1e-5)
