"""The core turning behind the shell (impactlab.physics.core_torsion and the compliant models' core options).

Oracles written apart from the code under test: published roots of the spherical Bessel functions (Lamb 1882's
free-sphere mode; the clamped sphere's j1 root), an onion of lumped spherical shells joined by shear springs
(a finite-difference model of the same core, solved as a generalised eigenproblem), hand solutions of a
one-mode rotor under a step torque, and an impact integrated in SI variables by classical RK4 here.
"""

import os

import impactlab
import numpy as np
import pytest
import scipy.linalg
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from impactlab.errors import FieldError, ModelInputError
from impactlab.model.registry import get_model
from impactlab.physics import core_torsion
from impactlab.testing import _complete, _with, parametrize_with_checks, reference_inputs, reference_inputs_3d

from test_ball_laws import kinetic_energy  # the energy oracle, from velocities

settings.register_profile("ci", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

MASS, RADIUS = 0.04593, 0.021335
TOTAL = 0.4 * MASS * RADIUS**2
CORE, DENSITY, SHEAR = 0.01905, 1150.0, 20e6
DRIVER_CASES = _complete(reference_inputs_3d())


def test_free_and_clamped_spheres_have_the_published_roots():
    """I_s = 0: j2(x) = 0, x_1 = 5.763459 (Lamb 1882; Murray & Saviot 2004 tabulate 5.763); I_s -> inf: the
    clamped sphere, j1(x) = 0, x = 4.493409, 7.725252 (Abramowitz & Stegun table 10.6)."""
    np.testing.assert_allclose(core_torsion.roots(0.0, 2), [5.763459, 9.095011], atol=2e-6)
    np.testing.assert_allclose(core_torsion.roots(1e12, 2), [4.493409, 7.725252], atol=2e-6)
    assert core_torsion.roots(0.0, 1)[0] == pytest.approx(core_torsion.FREE_SPHERE_ROOT, abs=1e-9)


def _onion(shell_inertia, cells=800):
    """Frequencies and shell participations of the core as `cells` lumped spherical shells (inertia
    (8 pi / 3) rho r^4 dr each) joined by torsional springs (8 pi / 3) G r^4 / dr, the rigid shell the last node."""
    h = CORE / cells
    r = (np.arange(cells) + 0.5) * h
    inertia = np.append(8.0 * np.pi / 3.0 * DENSITY * r**4 * h, shell_inertia)
    at = np.append(np.arange(1, cells) * h, CORE - 0.5 * h)
    spring = SHEAR * 8.0 * np.pi / 3.0 * at**4 / np.append(np.full(cells - 1, h), 0.5 * h)
    k = np.zeros((cells + 1, cells + 1))
    index = np.arange(cells)
    np.add.at(k, (index, index), spring)
    np.add.at(k, (index + 1, index + 1), spring)
    np.add.at(k, (index, index + 1), -spring)
    np.add.at(k, (index + 1, index), -spring)
    squared, vectors = scipy.linalg.eigh(k, np.diag(inertia), subset_by_index=[0, 3])
    return np.sqrt(np.abs(squared)), vectors[-1] ** 2, inertia.sum()


def test_modes_agree_with_a_lumped_onion_of_shells():
    modes = core_torsion.core_modes(total_inertia=TOTAL, core_radius=CORE, core_density=DENSITY,
                                    shear_modulus=SHEAR, modes=3)
    frequency, participation, total = _onion(modes.shell_inertia)
    assert total == pytest.approx(TOTAL, rel=1e-5)
    assert frequency[0] < 1.0  # the rigid mode
    assert participation[0] == pytest.approx(1.0 / TOTAL, rel=1e-5)  # it moves the shell as the whole ball
    np.testing.assert_allclose(frequency[1:], modes.frequency, rtol=1e-5)
    np.testing.assert_allclose(participation[1:], modes.inverse_inertia, rtol=1e-4)
    # c_s = sqrt(G / rho): doubling G raises every frequency by sqrt 2 and leaves the mobilities
    stiffer = core_torsion.core_modes(total_inertia=TOTAL, core_radius=CORE, core_density=DENSITY,
                                      shear_modulus=2 * SHEAR, modes=3)
    np.testing.assert_allclose(stiffer.frequency, np.sqrt(2) * modes.frequency, rtol=1e-12)


def test_the_mobilities_add_up_to_the_shells_own():
    """At the first instant the core has not moved: 1/I_tot + sum_k 1/I_k = 1/I_s; the tail falls as 1/N, so
    the partial sums at N and 2N are extrapolated."""
    modes = core_torsion.core_modes(total_inertia=TOTAL, core_radius=CORE, core_density=DENSITY,
                                    shear_modulus=SHEAR, modes=400)
    partial = [1.0 / TOTAL + modes.inverse_inertia[:count].sum() for count in (200, 400)]
    assert (2 * partial[1] - partial[0]) * modes.shell_inertia == pytest.approx(1.0, abs=2e-5)
    # the rigid limit of eq. (2): x -> 0 gives 1/I_tot
    mass_c = 4 / 3 * np.pi * DENSITY * CORE**3
    assert core_torsion.modal_inverse_inertia(1e-4, mass_c, CORE, modes.shell_inertia) == pytest.approx(
        1.0 / TOTAL, rel=1e-7)


def test_a_core_heavier_than_the_ball_is_refused():
    with pytest.raises(ValueError, match="more than the ball"):
        core_torsion.core_modes(total_inertia=TOTAL, core_radius=0.021, core_density=3000.0, shear_modulus=SHEAR)


def test_step_torque_on_one_mode_is_the_hand_solution():
    """A step torque M on a rigid rotor I_tot and one mode (omega, I_1): Omega_s = M t / I_tot + M sin(omega t) /
    (I_1 omega); L = M t; energy = work of the torque, and with damping it stays below that work."""
    one = core_torsion.CoreModes(TOTAL, 0.4 * TOTAL, 0.6 * TOTAL, np.array([3.0e4]), np.array([2.0 / TOTAL]),
                                 np.array([0.0]))
    dt, steps, moment = 2e-8, 20_000, 0.3
    torque = np.full(steps + 1, moment)
    torque[0] = moment  # a step at t = 0
    rate, momentum, energy = core_torsion.shell_response(one, torque, dt)
    t = np.arange(steps + 1) * dt
    hand = moment * t / TOTAL + moment * 2.0 / TOTAL * np.sin(3.0e4 * t) / 3.0e4
    np.testing.assert_allclose(rate, hand, rtol=0, atol=1e-5 * np.abs(hand).max())
    np.testing.assert_allclose(momentum, moment * t, rtol=1e-12, atol=1e-18)
    work = np.concatenate([[0.0], np.cumsum(0.5 * dt * moment * (rate[1:] + rate[:-1]))])
    np.testing.assert_allclose(energy, work, rtol=1e-3, atol=1e-9)
    damped = core_torsion.CoreModes(*[getattr(one, f) for f in ("total_inertia", "shell_inertia", "core_inertia",
                                                                "frequency", "inverse_inertia")],
                                    np.array([0.2 * 3.0e4]))
    rate_d, momentum_d, energy_d = core_torsion.shell_response(damped, torque, dt)
    work_d = np.concatenate([[0.0], np.cumsum(0.5 * dt * moment * (rate_d[1:] + rate_d[:-1]))])
    assert np.all(energy_d[1:] < work_d[1:])
    np.testing.assert_allclose(momentum_d, momentum, rtol=1e-12)


# -- the law in the compliant models ---------------------------------------------------------------------------------

def _plate(angle, friction=0.4, speed=40.0):
    inputs = _complete(reference_inputs())
    keep = np.arange(1)
    inputs = {key: np.asarray(value)[keep] for key, value in inputs.items()}
    return _with(inputs, angle=np.array([angle]), spin=np.array([0.0]), friction=np.array([friction]),
                 restitution=np.array([1.0]), speed=np.array([speed]))


def _oracle(inputs, modes, steps=12_000, loss=0.0, alpha=0.0):
    """The elastic impact of a ball with a core on a rigid fixed face, in SI, by classical RK4 (written here).

    Hertz normal force (4/3) E* sqrt(R) delta^1.5; one tangential spring dF/dt = 8 G* a v (Mindlin's stiffness,
    a = sqrt(R delta)), its force held to |F| <= mu F_n after each step; the ball translates (m: u' = -F / m),
    its whole rotation takes the torque T = -R F + C over I_tot and each mode T / I_k - omega_k^2 theta_k -
    loss omega_k theta_k'; the slip v is the contact point's, u + R (Omega_0 + sum theta_k'). With ``alpha`` a
    rolling couple C = -(3/16) alpha a F_n sign(Omega) opposes the shell's rotation Omega (on a fixed face the
    relative rolling; the spin never stops within these impacts). Returns J_n, J_t and the couple's angular
    impulse [N s, N s, N m s]."""
    m, r = float(inputs["ball_mass"][0]), float(inputs["ball_radius"][0])
    e_b, nu_b = float(inputs["ball_youngs_modulus"][0]), float(inputs["ball_poisson_ratio"][0])
    e_star, g_star = e_b / (1 - nu_b**2), (e_b / (2 * (1 + nu_b))) / (2 - nu_b)  # rigid face
    mu, speed, angle = float(inputs["friction"][0]), float(inputs["speed"][0]), float(inputs["angle"][0])
    inverse = np.asarray(modes.inverse_inertia)
    omega = np.asarray(modes.frequency)
    count = inverse.size
    k_n = 4.0 / 3.0 * e_star * np.sqrt(r)
    # Hertz contact time 2.94 delta_max / V, delta_max = (15 m V^2 / (16 k_n))^(2/5)
    dt = 1.2 * 2.94 * (15 * m * (speed * np.cos(angle)) ** 2 / (16 * k_n)) ** 0.4 / (speed * np.cos(angle)) / steps

    def derivative(y):  # y: delta, delta', u, Omega_0, F, J_n, J_t, J_c, angles (count), rates (count)
        delta, force = max(y[0], 0.0), y[4]
        normal = k_n * delta**1.5
        rates = y[8 + count:]
        spin = y[3] + rates.sum()
        couple = -3.0 / 16.0 * alpha * np.sqrt(r * delta) * normal * np.sign(spin)
        torque = -r * force + couple
        head = [y[1], -normal / m, -force / m, torque / modes.total_inertia,
                8 * g_star * np.sqrt(r * delta) * (y[2] + r * spin), normal, force, couple]
        return np.concatenate([head, rates, torque * inverse - omega**2 * y[8:8 + count] - loss * omega * rates])

    y = np.concatenate([[0.0, speed * np.cos(angle), speed * np.sin(angle)], np.zeros(5 + 2 * count)])
    for _ in range(steps):
        k1 = derivative(y)
        k2 = derivative(y + 0.5 * dt * k1)
        k3 = derivative(y + 0.5 * dt * k2)
        k4 = derivative(y + dt * k3)
        y = y + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        cap = mu * k_n * max(y[0], 0.0) ** 1.5
        y[4] = min(max(y[4], -cap), cap)
        if y[0] < 0.0 and y[1] < 0.0:
            break
    return y[5], y[6], y[7]


@pytest.mark.parametrize("angle, line, loss, alpha", [
    (0.25, True, 0.0, 0.0), (0.8, True, 0.0, 0.0), (0.25, False, 0.0, 0.0), (0.8, False, 0.0, 0.0),
    (0.8, True, 0.5, 0.0), (0.25, False, 0.5, 0.0), (0.25, False, 0.0, 0.6), (0.8, False, 0.3, 0.6)],
    ids=["driver 1-D", "wedge 1-D", "driver 3-D", "wedge 3-D", "wedge 1-D lossy core", "driver 3-D lossy core",
         "driver 3-D rolling couple", "wedge 3-D lossy core and rolling couple"])
@pytest.mark.slow
def test_the_kernel_agrees_with_an_rk4_impact_of_a_ball_with_a_core(angle, line, loss, alpha, monkeypatch):
    """A driver-like and a wedge-like spin loft, two modes: the 1-D solver (where a plate case goes) and the 3-D
    kernel with the core against the oracle; a lossy core; the rolling couple on the shell (3-D kernel)."""
    from impactlab_models.dem import HertzMindlinModel

    monkeypatch.setattr(HertzMindlinModel, "_planar_core", line)
    inputs = _plate(angle)
    laws = dict(rescale=False, tolerance=1e-6, rolling_hysteresis=alpha)
    options = dict(core_radius=CORE, core_shear_modulus=SHEAR, core_specific_gravity=DENSITY / 1000.0,
                   core_modes=2, core_loss=loss, **laws)
    names = ["normal_impulse", "tangential_impulse", "rolling_moment"]
    result = get_model("hertz_mindlin")(**options).compute(inputs, names)
    modes = core_torsion.core_modes(total_inertia=TOTAL, core_radius=CORE, core_density=DENSITY,
                                    shear_modulus=SHEAR, modes=2, loss=loss)
    jn, jt, jc = _oracle(inputs, modes, loss=loss, alpha=alpha)
    rigid = get_model("hertz_mindlin")(**laws).compute(inputs, names)
    rigid_jt = float(rigid["tangential_impulse"].values[0])
    assert float(result["normal_impulse"].values[0]) == pytest.approx(jn, rel=2e-4)
    model_jt = float(result["tangential_impulse"].values[0])
    assert abs(jt - rigid_jt) > 0.01 * abs(rigid_jt)  # the core matters here: the comparison can tell
    assert abs(model_jt - jt) <= 0.03 * abs(jt - rigid_jt), (model_jt, jt, rigid_jt)
    if alpha:  # the couple sits on its limit throughout: its angular impulse, (3/16) alpha int a F_n dt
        assert float(abs(result["rolling_moment"].values[0])) == pytest.approx(abs(jc), rel=1e-5)


def test_a_stiff_core_is_the_rigid_ball_and_no_core_is_todays_model():
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse"]
    today = get_model("hertz_mindlin")(tolerance=1e-4).compute(DRIVER_CASES, names)
    off = get_model("hertz_mindlin")(tolerance=1e-4, core_radius=0.0).compute(DRIVER_CASES, names)
    stiff = get_model("hertz_mindlin")(tolerance=1e-4, core_radius="19 mm", core_shear_modulus="10 GPa",
                                       core_modes=2).compute(DRIVER_CASES, names)
    for name in names:
        np.testing.assert_array_equal(off[name].values, today[name].values)
        np.testing.assert_allclose(stiff[name].values, today[name].values, rtol=0,
                                   atol=2e-4 * np.abs(today["normal_impulse"].values).max())
    # with the rolling couple as well (the couple that stops the rolling counts the modes' part of it)
    names += ["rolling_moment"]
    rolling = get_model("hertz_mindlin")(tolerance=1e-4, rolling_hysteresis=0.3).compute(DRIVER_CASES, names)
    stiff = get_model("hertz_mindlin")(tolerance=1e-4, rolling_hysteresis=0.3, core_radius="19 mm",
                                       core_shear_modulus="10 GPa", core_modes=2).compute(DRIVER_CASES, names)
    for name in names:
        scale = np.abs(rolling[name].values).max()
        np.testing.assert_allclose(stiff[name].values, rolling[name].values, rtol=0, atol=1e-3 * scale)


def test_options_take_units_and_refuse_what_does_not_fit():
    model = get_model("hertz_mindlin")(core_radius="19 mm", core_shear_modulus="20 MPa", core_specific_gravity=1.15)
    assert model.options.core_radius == pytest.approx(0.019)
    assert model.options.core_shear_modulus == pytest.approx(20e6)
    for bad in ({"core_radius": "30 mm"}, {"core_radius": -1.0}, {"core_shear_modulus": "20 kg"},
                {"core_loss": 3.0}, {"core_modes": 0}, {"core_specific_gravity": 9.0}):
        with pytest.raises(FieldError):
            get_model("hertz_mindlin")(**bad)
    heavy = get_model("hertz_mindlin")(core_radius="21 mm", core_specific_gravity=2.5)
    with pytest.raises(ModelInputError, match="core_radius"):
        heavy.compute(DRIVER_CASES, ["tangential_impulse"])


@given(friction=st.floats(0.05, 1.0), shear=st.floats(2e6, 60e6), loss=st.sampled_from([0.0, 0.3]),
       rolling=st.sampled_from([0.0, 0.3]), seed=st.integers(0, 2**16))
def test_energy_never_rises_with_a_core_on_off_centre_strikes(friction, shear, loss, rolling, seed):
    """Off-centre 3-D strikes of a free head, the core's spin taken as L / I_tot: the kinetic energy of ball and
    head after (velocities from the impulses) never exceeds what they had."""
    rng = np.random.default_rng(seed)
    n = DRIVER_CASES["speed"].size
    inputs = _with(DRIVER_CASES, restitution=rng.uniform(0.6, 1.0, n), friction=friction,
                   strike_toe=rng.uniform(-0.03, 0.03, n), strike_high=rng.uniform(-0.02, 0.02, n),
                   dynamic_loft=rng.uniform(0.05, 0.9, n), speed=rng.uniform(20.0, 55.0, n))
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse", "rolling_moment", "rolling_moment_slip"]
    result = get_model("hertz_mindlin")(core_radius="19 mm", core_shear_modulus=shear, core_loss=loss,
                                        rolling_hysteresis=rolling, tolerance=1e-3).compute(inputs, names)
    before, after = kinetic_energy(inputs), kinetic_energy(inputs, result)
    assert np.all(after <= before * (1.0 + 1e-9)), np.max((after - before) / before)


WITH_CORE = [get_model("hertz_mindlin")(core_radius="19 mm", core_shear_modulus="20 MPa", tolerance=1e-3),
             get_model("hertz_mindlin")(core_radius="19 mm", core_shear_modulus="10 MPa", core_loss=0.2,
                                        rolling_hysteresis="restitution", tolerance=1e-3),
             get_model("maw")(core_radius="19 mm", tolerance=1e-3)]


@pytest.mark.slow
@parametrize_with_checks(*WITH_CORE)
def test_conformance_with_the_core_law(model, check):
    """The shipped conformance suite with the core law on."""
    check(model)


def test_the_compiled_kernel_with_a_core_equals_its_numpy_reference(monkeypatch):
    from impactlab.physics import compliant3d, hertz
    from impactlab.physics import kernels as _kernels

    if not _kernels.HAVE_NUMBA:
        pytest.skip("numba is off: the numpy path is the only one")
    n = 3
    mobility = np.broadcast_to(np.diag([1 / MASS + RADIUS**2 / TOTAL] * 2 + [1 / MASS]), (n, 3, 3)).copy()
    modes = core_torsion.core_modes(total_inertia=TOTAL, core_radius=CORE, core_density=DENSITY,
                                    shear_modulus=SHEAR, loss=0.2, modes=3)
    core = (np.tile(modes.inverse_inertia, (n, 1)), np.tile(modes.frequency, (n, 1)), np.tile(modes.damping, (n, 1)),
            np.full(n, RADIUS))
    rolling = (np.zeros((n, 3, 2)), np.broadcast_to(np.eye(2) / TOTAL, (n, 2, 2)).copy(), np.zeros((n, 2)),
               np.full(n, 0.05))
    arguments = dict(friction=np.full(n, 0.4), kappa=np.full(n, 0.7), modulus=np.full(n, 1.5e8),
                     radius=np.full(n, RADIUS), normal=hertz.ELASTIC, springs=1, steps=300, law="mindlin",
                     core=core, rolling=rolling)
    speeds, slips = np.full(n, 40.0), np.array([5.0, 15.0, 40.0])
    compiled = compliant3d.solve_once(mobility, speeds, slips, **arguments)
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    reference = compliant3d.solve_once(mobility, speeds, slips, **arguments)
    for name in ("impulse", "moment", "work", "core_energy"):
        np.testing.assert_allclose(getattr(compiled, name), getattr(reference, name), rtol=1e-10, atol=1e-14)
    assert np.all(compiled.core_energy > 0.0)


def test_the_one_spring_kernel_with_a_core_equals_its_numpy_reference():
    from impactlab.physics import dem
    from impactlab.physics import kernels as _kernels

    if not _kernels.HAVE_NUMBA:
        pytest.skip("numba is off: the numpy path is the only one")
    chi, psi1 = np.array([0.3, 1.2, 2.0]), np.array([0.5, 3.0, 9.0])
    core = (np.full((3, 2), 0.9), np.array([[40.0, 150.0]] * 3), np.array([[0.0, 0.0], [1.0, 2.0], [0.5, 0.5]]))
    compiled = dem.solve_scaled(chi, psi1, steps=400, core=core)
    reference = dem.solve_scaled(chi, psi1, steps=400, core=core, _force_numpy=True)
    np.testing.assert_allclose(compiled.slip_change, reference.slip_change, rtol=1e-12)
    np.testing.assert_allclose(compiled.dissipation, reference.dissipation, rtol=1e-12)
    plain = dem.solve_scaled(chi, psi1, steps=400)
    assert np.all(np.abs(compiled.slip_change - plain.slip_change)[:2] > 1e-3)  # gripping cases feel the core
    np.testing.assert_allclose(compiled.slip_change[2], plain.slip_change[2], rtol=1e-12)  # a sliding one: not


STUDY = """name: core
ball: {preset: urethane_tour}
club: {preset: driver}
delivery: {club_speed: 115 mph, path: 0 deg, face_angle: 0 deg, attack_angle: -0.9 deg, dynamic_loft: 12.8 deg}
models:
  - hertz_mindlin
  - {name: hertz_mindlin, id: core, core_radius: 19.05 mm, core_shear_modulus: 10 MPa}
outputs: [spin_rate]
"""


@pytest.mark.parametrize("change, fragment", [
    (("10 MPa", "10 kg"), "models[1].core_shear_modulus: expected a modulus"),
    (("19.05 mm", "30 mm"), "models[1].core_radius: expected a core radius"),
    # a bare number's unit is never guessed in a study (before, 0.019 ran as metres, 10000000 as Pa)
    (("19.05 mm", "0.019"), "models[1].core_radius: expected a length with its unit"),
    (("10 MPa", "10000000"), "models[1].core_shear_modulus: expected a modulus (pressure) with its unit"),
])
def test_a_study_refuses_a_bad_core_option_at_its_line(change, fragment):
    from test_study import assert_one_clear_message

    impactlab.load_study(STUDY, file="study.yaml")  # as written, it loads
    assert_one_clear_message(STUDY, change, 7, [fragment])


def test_the_defaults_are_the_balls_own_shear_modulus_and_mean_density():
    """Left out, G = E / (2 (1 + nu)) of the ball's elastic constants and the ball's mass over its volume."""
    inputs = _plate(0.3)
    e, nu = float(inputs["ball_youngs_modulus"][0]), float(inputs["ball_poisson_ratio"][0])
    m, r = float(inputs["ball_mass"][0]), float(inputs["ball_radius"][0])
    names = ["tangential_impulse"]
    default = get_model("hertz_mindlin")(core_radius=CORE).compute(inputs, names)
    given = get_model("hertz_mindlin")(core_radius=CORE, core_shear_modulus=e / (2 * (1 + nu)),
                                       core_specific_gravity=m / (4 / 3 * np.pi * r**3) / 1000).compute(inputs, names)
    np.testing.assert_allclose(default["tangential_impulse"].values, given["tangential_impulse"].values, rtol=1e-12)
    other = get_model("hertz_mindlin")(core_radius=CORE, core_shear_modulus=e / (2 * (1 + nu)),
                                       core_specific_gravity=1.0).compute(inputs, names)
    assert abs(other["tangential_impulse"].values[0] - given["tangential_impulse"].values[0]) > 1e-6


# -- a stiff core on few steps (review5): the modes' leapfrog diverges for Omega_k dt > 2 --------------------------

@pytest.mark.parametrize("model, options", [("maw", {}), ("hertz_mindlin", {"steps": 200}),
                                            ("dem_linear", {"steps": 100})],
                         ids=["maw default steps", "hertz_mindlin 200 steps", "dem_linear 100 steps"])
@pytest.mark.parametrize("shear, loss", [("3 GPa", 0.0), ("10 GPa", 2.0)])
def test_a_stiff_core_is_the_rigid_ball_at_any_step_count(model, options, shear, loss):
    """A core of 3-10 GPa (within the option's range) is nearly rigid: the spin must be the rigid ball's (law off)
    to 0.1 %, on the centred strike (1-D solver) and off it (3-D kernel). Before the steps were raised for the
    modes, maw's default steps gave twice the rigid ball's spin and 100 steps of dem_linear about 20 rpm."""
    from test_ball_laws import _centred_head_cases

    inputs = _centred_head_cases([0.0, 1e-6])
    rigid = get_model(model)(**options).compute(inputs, ["spin_rate"])["spin_rate"].values
    core = get_model(model)(core_radius="19 mm", core_shear_modulus=shear, core_loss=loss,
                            **options).compute(inputs, ["spin_rate"])["spin_rate"].values
    np.testing.assert_allclose(core, rigid, rtol=1e-3)


def test_the_one_spring_solver_refuses_a_core_its_steps_cannot_carry():
    """dem.solve_scaled called directly: a mode with Omega dt above compliant3d.CORE_STEP is refused, not
    integrated into a diverging number."""
    from impactlab.physics import compliant3d, dem

    steps = 100
    omega = 3.0 * compliant3d.CORE_STEP * steps / dem.ELASTIC.tau_end
    with pytest.raises(ValueError, match="Omega dt"):
        dem.solve_scaled([1.0], [2.0], steps=steps, core=([[0.5]], [[omega**2]], [[0.0]]))


def test_maw_hysteretic_with_a_stiff_core_is_the_rigid_ball_and_keeps_the_limit_flag():
    """maw with inelastic="hysteretic": MDR breaks the 3-D Coulomb limit here (flag 64) and the 1-D path's
    correction is carried to the 3-D kernel. With a core every maw case takes the 3-D kernel; a nearly rigid core
    must still give the rigid ball's spin (to 1 rpm, not the 52 rpm of the uncorrected MDR) and the flag."""
    from test_ball_laws import _centred_head_cases

    inputs = _centred_head_cases([0.0, 1e-6, 0.01])
    names = ["spin_rate", "validity"]
    rigid = get_model("maw")(inelastic="hysteretic").compute(inputs, names)
    stiff = get_model("maw")(inelastic="hysteretic", core_radius="19 mm", core_shear_modulus="10 GPa",
                             core_modes=2).compute(inputs, names)
    np.testing.assert_allclose(stiff["spin_rate"].values, rigid["spin_rate"].values, rtol=0, atol=1.0)
    assert np.all(rigid["validity"].values.astype(int) & 64)
    assert np.all(stiff["validity"].values.astype(int) & 64)


@pytest.mark.parametrize("model, plate", [("hertz_mindlin", True), ("hertz_mindlin", False), ("maw", False),
                                          ("dem_linear", True)],
                         ids=["hertz_mindlin 1-D", "hertz_mindlin 3-D", "maw 3-D", "dem_linear 1-D"])
def test_a_cases_core_modes_do_not_depend_on_its_batch(model, plate):
    """With the default modes (those up to 20 kHz) a case keeps its own count: run beside a much softer ball (more
    modes below the cut-off) its result is bit-identical to its result alone. Before, every case of a batch kept
    the batch's largest count, which moved a driver's spin by 3e-4 (1.4 rpm) with what else was in the chunk."""
    source = _complete(reference_inputs()) if plate else DRIVER_CASES
    alone = {key: np.asarray(value)[:1] for key, value in source.items()}
    batch = {key: np.concatenate([value, value]) for key, value in alone.items()}
    batch["ball_youngs_modulus"] = np.array([alone["ball_youngs_modulus"][0], 5e6])
    if plate:  # a gripping plate case (the 1-D line)
        alone = _with(alone, angle=np.array([0.3]), spin=np.array([0.0]), friction=np.array([0.4]))
        batch = _with(batch, angle=np.full(2, 0.3), spin=np.zeros(2), friction=np.full(2, 0.4))
    names = ["tangential_impulse", "lateral_impulse"]
    run = get_model(model)(core_radius="19 mm", tolerance=1e-3)
    one, two = run.compute(alone, names), run.compute(batch, names)
    for name in names:
        assert two[name].values[0] == one[name].values[0], name
    assert abs(float(one["tangential_impulse"].values[0])) > 0.0


def test_an_inert_padding_mode_changes_nothing_in_either_kernel():
    """A mode of gain 0 (how a case with fewer modes than its batch is padded) leaves both solvers' results
    exactly as without it, compiled and numpy alike, lossy core included (no 0/0 in the energy taken)."""
    from impactlab.physics import compliant3d, dem, hertz

    chi, psi1 = np.array([0.3, 1.2, 2.0]), np.array([0.5, 3.0, 9.0])
    core = (np.full((3, 1), 0.9), np.full((3, 1), 40.0**2), np.array([[0.0], [1.0], [0.5]]))
    padded = tuple(np.concatenate([part, np.zeros((3, 1))], axis=1) for part in core)
    for numpy_only in (False, True):
        plain = dem.solve_scaled(chi, psi1, steps=400, core=core, _force_numpy=numpy_only)
        pad = dem.solve_scaled(chi, psi1, steps=400, core=padded, _force_numpy=numpy_only)
        np.testing.assert_array_equal(pad.slip_change, plain.slip_change)
        np.testing.assert_array_equal(pad.dissipation, plain.dissipation)
    n = 3
    mobility = np.broadcast_to(np.diag([1 / MASS + RADIUS**2 / TOTAL] * 2 + [1 / MASS]), (n, 3, 3)).copy()
    modes = core_torsion.core_modes(total_inertia=TOTAL, core_radius=CORE, core_density=DENSITY,
                                    shear_modulus=SHEAR, loss=0.2, modes=2)
    core3 = (np.tile(modes.inverse_inertia, (n, 1)), np.tile(modes.frequency, (n, 1)), np.tile(modes.damping, (n, 1)),
             np.full(n, RADIUS))
    padded3 = tuple(np.concatenate([part, np.zeros((n, 2))], axis=1) for part in core3[:3]) + (core3[3],)
    arguments = dict(friction=np.full(n, 0.4), kappa=np.full(n, 0.7), modulus=np.full(n, 1.5e8),
                     radius=np.full(n, RADIUS), normal=hertz.ELASTIC, springs=1, steps=300, law="mindlin")
    speeds, slips = np.full(n, 40.0), np.array([5.0, 15.0, 40.0])
    plain = compliant3d.solve_once(mobility, speeds, slips, core=core3, **arguments)
    pad = compliant3d.solve_once(mobility, speeds, slips, core=padded3, **arguments)
    for name in ("impulse", "work", "core_energy"):
        np.testing.assert_array_equal(getattr(pad, name), getattr(plain, name))


def test_shell_response_refuses_a_step_its_scheme_cannot_take():
    """Velocity Verlet is stable for omega dt <= 2 only: undamped, its free step's eigenvalues are
    1 - h^2/2 +- sqrt((1 - h^2/2)^2 - 1), h = omega dt (Hairer, Lubich & Wanner 2003, I.1.4), modulus 1 below
    h = 2 and |1 - h^2/2| + sqrt(...) above it; a damped mode at a small step decays as exp(-c dt / 2) per step,
    the continuous oscillator's envelope (to (c dt)^2 / 4). Beyond the limit shell_response refuses with one
    message, where it used to return a history growing step by step without a word."""
    omega = 3.0e4
    for h in (0.5, 1.0, 1.9, 1.999):
        assert core_torsion.verlet_growth([omega], [0.0], h / omega)[0] == pytest.approx(1.0, abs=1e-9)
    for h in (2.1, 2.5, 4.0):
        b = 1.0 - 0.5 * h * h
        assert core_torsion.verlet_growth([omega], [0.0], h / omega)[0] == pytest.approx(
            abs(b) + np.sqrt(b * b - 1.0), rel=1e-9)
    c, dt = 0.2 * omega, 0.001 / omega  # the explicit damping errs by (c dt)^2 / 4 per step: 1e-8 here
    assert core_torsion.verlet_growth([omega], [c], dt)[0] == pytest.approx(np.exp(-0.5 * c * dt), rel=3e-8)
    one = core_torsion.CoreModes(TOTAL, 0.4 * TOTAL, 0.6 * TOTAL, np.array([omega, 5.0 * omega]),
                                 np.array([2.0 / TOTAL, 1.0 / TOTAL]), np.array([0.0, 0.1 * omega]))
    torque = np.full(200, 0.3)
    with pytest.raises(ValueError, match="mode 2"):
        core_torsion.shell_response(one, torque, 2.1 / (5.0 * omega))
    rate, _, _ = core_torsion.shell_response(one, torque, 1.9 / (5.0 * omega))  # just inside: bounded
    assert np.all(np.isfinite(rate)) and np.abs(rate).max() < 1e3


@pytest.mark.parametrize("name, options", [("maw", {}), ("maw", {"inelastic": "hysteretic"}),
                                           ("hertz_mindlin", {"rolling_hysteresis": "restitution"})])
def test_the_core_is_continuous_across_the_centred_strike(monkeypatch, name, options):
    """The centred strike on a free head (on one line: the line kernel, kernels/line.py) and strikes 1 micrometre
    off it (the 3-D kernel) agree: J_t to 1e-6 of mu J_n (the offset's own effect is ~1e-11), and only the centred
    case took the line kernel; the core changes the spin on both paths."""
    from test_ball_laws import _centred_head_cases
    from test_face_flex import _line_spy

    inputs = _centred_head_cases([0.0, 1e-6, -1e-6])
    seen = _line_spy(monkeypatch)
    result = get_model(name)(core_radius="19 mm", core_shear_modulus="10 MPa", **options).compute(
        inputs, ["tangential_impulse", "normal_impulse", "spin_rate"])
    assert set(seen) == {0}
    jt, jn = result["tangential_impulse"].values, result["normal_impulse"].values
    assert np.max(np.abs(jt - jt[0])) <= 1e-6 * 0.15 * jn[0]
    rigid = get_model(name)(**options).compute(inputs, ["spin_rate"])["spin_rate"].values
    assert np.all(np.abs(result["spin_rate"].values - rigid) > 100.0)


def test_shell_responses_step_advice_holds_for_a_damped_core():
    """Damping lowers velocity Verlet's limit: the free step's polynomial z^2 - (2 - c dt - h^2) z + (1 - c dt)
    (h = omega dt) keeps both roots in the unit disc while h^2 + 2 c dt < 4 (Jury), i.e. h < sqrt(eta^2 + 4) - eta
    for c = eta omega (1.72 at eta = 0.3, not 2). The step the refusal advises must be one shell_response takes
    (before: 1.9 / omega, refused again at eta = 0.3); beyond c dt = 2 the growth is the root 1 - c dt (omega = 0:
    exactly c dt - 1), not an infinity."""
    import re

    omega, eta = 3.0e4, 0.3
    limit = np.sqrt(eta * eta + 4.0) - eta
    assert core_torsion.verlet_growth([omega], [eta * omega], 0.999 * limit / omega)[0] <= 1.0
    assert core_torsion.verlet_growth([omega], [eta * omega], 1.001 * limit / omega)[0] > 1.0
    assert core_torsion.verlet_step_limit([omega], [eta * omega])[0] == pytest.approx(limit / omega, rel=1e-12)
    assert core_torsion.verlet_growth([0.0], [3.0e4], 1.0e-4)[0] == pytest.approx(2.0, rel=1e-12)
    damped = core_torsion.CoreModes(TOTAL, 0.4 * TOTAL, 0.6 * TOTAL, np.array([omega]), np.array([2.0 / TOTAL]),
                                    np.array([eta * omega]))
    torque = np.full(200, 0.3)
    with pytest.raises(ValueError, match="take dt below") as refused:
        core_torsion.shell_response(damped, torque, 1.9 / omega)
    advised = float(re.search(r"take dt below about (\S+) s", str(refused.value)).group(1))
    rate, _, _ = core_torsion.shell_response(damped, torque, advised)
    assert np.all(np.isfinite(rate))
