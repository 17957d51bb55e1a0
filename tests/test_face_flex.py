"""The club face flexing behind the contact (impactlab.physics.face_flex and the one-spring models' face options).

Oracles written apart from the code under test: the clamped circular plate's frequency equation solved here
(J0 I1 + I0 J1 = 0; Leissa 1969's lambda^2 = 10.2158), its mode shape integrated by adaptive quadrature, the
limits of a pendulum on a soft spring (pi sqrt(m/k)) and on a rigid face (Hertz), and an impact of a ball on a
face oscillator integrated in SI variables by classical RK4 here.
"""

import os

import impactlab
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy import integrate, optimize, special

from impactlab.data.fit.calibration import DEFAULT_PARAMETERS, calibrate
from impactlab.data.shot_report import shot_table
from impactlab.errors import FieldError, ModelInputError
from impactlab.model.registry import get_model
from impactlab.physics import compliant3d, face_flex, hertz
from impactlab.testing import _complete, _with, parametrize_with_checks, reference_inputs, reference_inputs_3d

from test_ball_laws import kinetic_energy  # the energy oracle, from velocities

settings.register_profile("ci", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

DRIVER_CASES = _complete(reference_inputs_3d())
FACE = {"face_frequency": "4 kHz", "face_modal_mass": "8 g"}
#: a face marked spring-like with a negligible gain: the ball's own e is then 1 - 1e-9 (an elastic oracle)
MARK = 1e-9


# -- the plate and the pendulum ---------------------------------------------------------------------------------------

def test_the_clamped_plate_has_leissas_root_and_its_modal_mass():
    root = optimize.brentq(lambda x: special.j0(x) * special.i1(x) + special.i0(x) * special.j1(x), 2.5, 4.0)
    assert root**2 == pytest.approx(10.2158, abs=1e-4)  # Leissa 1969, Table 2.1
    assert face_flex.CLAMPED_ROOT == pytest.approx(root, rel=1e-10)

    def shape(s):
        return special.j0(root * s) - special.j0(root) / special.i0(root) * special.i0(root * s)

    ratio = 2.0 * integrate.quad(lambda s: shape(s) ** 2 * s, 0.0, 1.0)[0] / shape(0.0) ** 2
    assert face_flex.clamped_modal_mass_ratio() == pytest.approx(ratio, rel=1e-9)
    # a 2.5 mm titanium disc of 33 mm radius: f from Leissa's formula, k = m_f omega^2 near the static 16 pi D / a^2
    a, h, e, nu, rho = 0.033, 2.5e-3, 114e9, 0.34, 4430.0
    d = e * h**3 / (12 * (1 - nu**2))
    f, m, k = face_flex.clamped_plate_mode(a, h, e, nu, rho)
    assert f == pytest.approx(10.2158 / (2 * np.pi * a**2) * np.sqrt(d / (rho * h)), rel=1e-5)
    assert m == pytest.approx(ratio * rho * h * np.pi * a**2, rel=1e-9)
    assert 1.0 < k / (16 * np.pi * d / a**2) < 1.3  # a one-mode model is a little stiffer than the static plate


def test_the_pendulum_on_a_soft_face_and_on_a_rigid_one():
    steel_tip = face_flex.hertz_constant(0.0127, 200e9, 0.3, 114e9, 0.34)
    # a heavy pendulum on a light face's soft spring: half the period of the mass on the spring
    soft = face_flex.pendulum_contact_time(1e6, 1e-4, 0.2, 0.3, steel_tip)
    assert soft == pytest.approx(np.pi * np.sqrt(0.2 / 1e6), rel=0.02)
    # a face that cannot move (a huge modal mass on a spring of the same frequency): Hertz's contact time
    rigid = face_flex.pendulum_contact_time(1e3 * (2 * np.pi * 5e3) ** 2, 1e3, 0.1, 0.3, steel_tip)
    approach = (5 * 0.1 * 0.3**2 / (4 * steel_tip)) ** 0.4  # Johnson 1985, ch. 11: t = 2.943 delta_max / V
    assert rigid == pytest.approx(2.943 * approach / 0.3, rel=2e-3)


@pytest.mark.slow
def test_the_ct_test_round_trips_and_the_kernel_simulates_it():
    """The stiffness derived from a CT of 239 us gives that CT back, and the 3-D kernel (the pendulum as the
    'ball', no friction) gives the same contact time: its separation and re-contact logic is the test's."""
    tip, mass, speed, modal = face_flex.hertz_constant(0.0127, 200e9, 0.3, 114e9, 0.34), 0.1, 0.3, 0.008
    k = face_flex.stiffness_for_contact_time(239e-6, modal, mass, speed, tip)
    assert face_flex.pendulum_contact_time(k, modal, mass, speed, tip) == pytest.approx(239e-6, rel=1e-6)
    modulus = 3.0 * tip / (4.0 * np.sqrt(0.0127))
    mobility = np.diag([1.0, 1.0, 1.0]) / mass
    solved = compliant3d.solve(mobility[None], np.array([speed]), np.array([0.0]), friction=np.zeros(1),
                               kappa=np.full(1, 0.7), modulus=np.full(1, modulus), radius=np.full(1, 0.0127),
                               normal=hertz.ELASTIC, springs=1, steps=2000, law="mindlin",
                               face=face_flex.modal_inputs(k, modal))
    assert solved.contact_time[0] == pytest.approx(239e-6, rel=2e-3)
    assert not solved.unfinished[0]


# -- the law in the compliant models ---------------------------------------------------------------------------------

def _plate(angle, friction=0.4, speed=40.0):
    inputs = _complete(reference_inputs())
    inputs = {key: np.asarray(value)[:1] for key, value in inputs.items()}
    return _with(inputs, angle=np.array([angle]), spin=np.array([0.0]), friction=np.array([friction]),
                 restitution=np.array([1.0]), speed=np.array([speed]), club_restitution_gain=np.array([MARK]))


def _oracle(inputs, stiffness, modal, loss=0.0, steps=16_000, damping=0.0):
    """A ball striking a fixed body's face oscillator, elastic ball, in SI by classical RK4 (written here).

    Bodies' approach r (r'' = -F / m), the face's deflection y (m_f y'' = F - k_f y - eta m_f omega y'), Hertz
    F = (4/3) E* sqrt(R) (r - y)^1.5; one tangential spring dF_t/dt = 8 G* a v (Mindlin's stiffness,
    a = sqrt(R (r - y))), held to |F_t| <= mu F after each step; the ball's translation and rotation take F_t.
    Runs until the ball has left and the face's swing cannot reach it. With ``damping`` c [s/m] the ball's
    Hunt-Crossley law F = (4/3) E* sqrt(R) delta^1.5 max(1 + c delta', 0) on the ball's own compression rate.
    Returns J_n, J_t [N s], the face's energy left [J], the contact time [s] and how many contacts there were."""
    m, r = float(inputs["ball_mass"][0]), float(inputs["ball_radius"][0])
    e_b, nu_b = float(inputs["ball_youngs_modulus"][0]), float(inputs["ball_poisson_ratio"][0])
    e_star, g_star = e_b / (1 - nu_b**2), (e_b / (2 * (1 + nu_b))) / (2 - nu_b)  # a rigid face's materials
    inertia = float(inputs["ball_inertia_factor"][0]) * m * r**2
    mu, speed, angle = float(inputs["friction"][0]), float(inputs["speed"][0]), float(inputs["angle"][0])
    k_n, omega = 4.0 / 3.0 * e_star * np.sqrt(r), np.sqrt(stiffness / modal)
    dt = 3.0 * 2.94 * (15 * m * (speed * np.cos(angle)) ** 2 / (16 * k_n)) ** 0.4 / (speed * np.cos(angle)) / steps

    def derivative(s):  # s: r, r', y, y', u, Omega, F_t, J_n, J_t
        delta = max(s[0] - s[2], 0.0)
        normal = k_n * delta**1.5 * max(1.0 + damping * (s[1] - s[3]), 0.0)
        return np.array([s[1], -normal / m, s[3], (normal - stiffness * s[2] - loss * modal * omega * s[3]) / modal,
                         -s[6] / m, -r * s[6] / inertia, 8 * g_star * np.sqrt(r * delta) * (s[4] + r * s[5]),
                         normal, s[6]])

    s = np.array([0.0, speed * np.cos(angle), 0.0, 0.0, speed * np.sin(angle), 0.0, 0.0, 0.0, 0.0])
    last, contacts, touching = 0.0, 0, False
    for step in range(3 * steps):
        k1 = derivative(s)
        k2 = derivative(s + 0.5 * dt * k1)
        k3 = derivative(s + 0.5 * dt * k2)
        k4 = derivative(s + dt * k3)
        s = s + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        cap = mu * k_n * max(s[0] - s[2], 0.0) ** 1.5 * max(1.0 + damping * (s[1] - s[3]), 0.0)
        s[6] = min(max(s[6], -cap), cap)
        if s[0] > s[2] and 1.0 + damping * (s[1] - s[3]) > 0.0:  # a force on the ball: still in contact
            last = (step + 1) * dt
            contacts += not touching
            touching = True
        else:
            touching = False
            if s[1] < 0.0 and s[0] + np.hypot(s[2], s[3] / omega) < 0.0:
                break
    energy = 0.5 * modal * s[3] ** 2 + 0.5 * stiffness * s[2] ** 2
    return s[7], s[8], energy, last, contacts


@pytest.mark.parametrize("angle, frequency, loss", [(0.25, 4e3, 0.0), (0.25, 3e3, 0.0), (0.8, 5e3, 0.0),
                                                    (0.25, 4e3, 0.2)],
                         ids=["driver 4 kHz", "driver 3 kHz", "wedge 5 kHz", "driver lossy face"])
def test_the_kernel_agrees_with_an_rk4_impact_on_a_face_oscillator(angle, frequency, loss):
    inputs = _plate(angle)
    modal = 0.008
    stiffness = modal * (2 * np.pi * frequency) ** 2
    options = dict(rescale=False, tolerance=1e-6, face_frequency=f"{frequency} Hz", face_modal_mass=modal,
                   face_loss=loss)
    names = ["normal_impulse", "tangential_impulse", "contact_time"]
    result = get_model("hertz_mindlin")(**options).compute(inputs, names)
    rigid = get_model("hertz_mindlin")(rescale=False, tolerance=1e-6).compute(inputs, names)
    jn, jt, _, duration, _ = _oracle(inputs, stiffness, modal, loss)
    assert float(result["normal_impulse"].values[0]) == pytest.approx(jn, rel=5e-4)
    assert float(result["contact_time"].values[0]) == pytest.approx(duration, rel=2e-3)
    model_jt, rigid_jt = float(result["tangential_impulse"].values[0]), float(rigid["tangential_impulse"].values[0])
    assert abs(jt - rigid_jt) > 0.01 * abs(rigid_jt)  # the face matters here: the comparison can tell
    assert abs(model_jt - jt) <= 0.03 * abs(jt - rigid_jt), (model_jt, jt, rigid_jt)


@pytest.mark.parametrize("restitution, frequency", [(0.75, 4e3), (0.3, 2e3)], ids=["tour ball", "dead ball"])
def test_a_lossy_ball_on_the_face_agrees_with_the_rk4_impact(restitution, frequency):
    """The hysteretic law on a face oscillator: the ball's loss follows its own compression rate (the trampoline);
    a dead ball leaves slowly, so the face's swing may meet it again after it has passed the face's rest plane."""
    inputs = _with(_plate(0.25), restitution=restitution + MARK, club_restitution_gain=MARK)
    modal = 0.008
    stiffness = modal * (2 * np.pi * frequency) ** 2
    names = ["normal_impulse", "tangential_impulse", "contact_time"]
    result = get_model("hertz_mindlin")(rescale=False, tolerance=1e-6, inelastic="hysteretic",
                                        face_frequency=f"{frequency} Hz", face_modal_mass=modal).compute(inputs, names)
    speed = float(inputs["speed"][0]) * np.cos(0.25)
    c = hertz.damping_for_restitution(restitution) / speed  # the scaled law's L = 1 + c h' with rates in V_z
    jn, jt, _, duration, _ = _oracle(inputs, stiffness, modal, damping=c)
    rigid_jn = (1 + restitution) * float(inputs["ball_mass"][0]) * speed
    assert abs(jn - rigid_jn) > 0.01 * rigid_jn  # the face changes the normal impulse here
    assert float(result["normal_impulse"].values[0]) == pytest.approx(jn, rel=1e-3)
    assert float(result["tangential_impulse"].values[0]) == pytest.approx(jt, rel=2e-2)
    assert float(result["contact_time"].values[0]) == pytest.approx(duration, rel=3e-3)


def _three_d_kernel_only(monkeypatch):
    """Every case through the 3-D kernel, none through its form on one line (kernels/line.py)."""
    original = compliant3d.solve
    monkeypatch.setattr(compliant3d, "solve", lambda *a, **k: original(*a, **dict(k, line=False)))


@pytest.mark.parametrize("line", [True, False])
def test_a_slow_face_meets_the_ball_again_after_it_has_left(monkeypatch, line):
    """A ball on a slow face (20 g, 1 kHz) bounces off the face's mass, passes the face's rest plane on its way
    out, and the face swinging back meets it again (three contacts in all): the kernel follows them (the contact
    time is the end of the last one); the line kernel (the centred plate case) and the 3-D kernel alike."""
    if not line:
        _three_d_kernel_only(monkeypatch)
    inputs = _plate(0.0, friction=0.0)
    modal, frequency = 0.02, 1e3
    jn, _, _, duration, contacts = _oracle(inputs, modal * (2 * np.pi * frequency) ** 2, modal, steps=40_000)
    result = get_model("hertz_mindlin")(tolerance=1e-6, face_frequency="1 kHz", face_modal_mass="20 g").compute(
        inputs, ["normal_impulse", "contact_time"])
    assert contacts >= 2  # the case does what it is meant to: the face meets the ball again
    assert float(result["contact_time"].values[0]) == pytest.approx(duration, rel=5e-3)
    assert float(result["normal_impulse"].values[0]) == pytest.approx(jn, rel=2e-3)


@pytest.mark.parametrize("line", [True, False])
def test_an_elastic_ball_loses_to_the_face_exactly_what_the_face_holds(monkeypatch, line):
    """Head fixed, elastic ball, no friction: ball energy lost = the face's vibration energy (kernel and oracle);
    the line kernel (the centred plate case) and the 3-D kernel alike."""
    if not line:
        _three_d_kernel_only(monkeypatch)
    inputs = _plate(0.0, friction=0.0)
    m, speed = float(inputs["ball_mass"][0]), float(inputs["speed"][0])
    modal, frequency = 0.008, 4e3
    stiffness = modal * (2 * np.pi * frequency) ** 2
    jn, _, held, _, _ = _oracle(inputs, stiffness, modal)
    result = get_model("hertz_mindlin")(tolerance=1e-6, face_frequency="4 kHz", face_modal_mass=modal).compute(
        inputs, ["normal_impulse"])
    after = float(result["normal_impulse"].values[0]) / m - speed
    lost = 0.5 * m * (speed**2 - after**2)
    assert held > 1e-3 * 0.5 * m * speed**2  # the face keeps a share worth measuring
    assert lost == pytest.approx(held, rel=5e-3)
    assert after < speed  # on an elastic ball the face can only take energy


def test_no_face_is_todays_model_irons_stay_rigid_and_a_stiff_face_is_rigid():
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse", "contact_time"]
    today = get_model("hertz_mindlin")(tolerance=1e-4).compute(DRIVER_CASES, names)
    off = get_model("hertz_mindlin")(tolerance=1e-4, face_frequency=0.0, face_modal_mass=0.0).compute(
        DRIVER_CASES, names)
    rigid_faced = _with(DRIVER_CASES, club_restitution_gain=0.0)  # an iron's face: the law leaves it alone
    on_iron = get_model("hertz_mindlin")(tolerance=1e-4, **FACE).compute(rigid_faced, names)
    plain_iron = get_model("hertz_mindlin")(tolerance=1e-4).compute(rigid_faced, names)
    for name in names:
        np.testing.assert_array_equal(off[name].values, today[name].values)
        np.testing.assert_array_equal(on_iron[name].values, plain_iron[name].values)
    # a very stiff, light face (1 MHz, 0.1 g) is the rigid face with the ball's own e (e - gain)
    gained = _with(DRIVER_CASES, club_restitution_gain=0.05)
    ball_own = _with(DRIVER_CASES, club_restitution_gain=0.0, restitution=DRIVER_CASES["restitution"] - 0.05)
    stiff = get_model("hertz_mindlin")(tolerance=1e-4, face_frequency="1 MHz", face_modal_mass="0.1 g").compute(
        gained, names[:3])
    rigid = get_model("hertz_mindlin")(tolerance=1e-4).compute(ball_own, names[:3])
    scale = np.abs(rigid["normal_impulse"].values).max()
    for name in names[:3]:
        np.testing.assert_allclose(stiff[name].values, rigid[name].values, rtol=0, atol=2e-3 * scale)


def test_maw_with_the_face_agrees_with_the_rk4_impact_on_one_line():
    """maw's MDR springs under the face: on one line its normal impulse is the oracle's (the normal problem does
    not depend on the tangential law there), and the face moves its J_t as it moves the one-spring law's, the
    same way (the oracle's single Mindlin spring is not Maw's microslip law, so only the direction is shared)."""
    inputs = _plate(0.25)
    modal, frequency = 0.008, 4e3
    result = get_model("maw")(tolerance=1e-5, face_frequency="4 kHz", face_modal_mass=modal).compute(
        inputs, ["normal_impulse", "tangential_impulse"])
    rigid = get_model("maw")(tolerance=1e-5).compute(inputs, ["tangential_impulse"])
    jn, jt, _, _, _ = _oracle(inputs, modal * (2 * np.pi * frequency) ** 2, modal)
    rigid_jt = float(rigid["tangential_impulse"].values[0])
    assert float(result["normal_impulse"].values[0]) == pytest.approx(jn, rel=5e-4)
    spring_rigid = float(get_model("hertz_mindlin")(tolerance=1e-5, rescale=False).compute(
        inputs, ["tangential_impulse"])["tangential_impulse"].values[0])
    change = float(result["tangential_impulse"].values[0]) - rigid_jt
    assert abs(change) > 0.1 * abs(rigid_jt) and np.sign(change) == np.sign(jt - spring_rigid)


def test_the_options_take_units_and_refuse_half_a_face():
    model = get_model("hertz_mindlin")(face_frequency="4 kHz", face_modal_mass="8 g")
    assert model.options.face_frequency == pytest.approx(2 * np.pi * 4000)
    assert model.options.face_modal_mass == pytest.approx(0.008)
    for bad in ({"face_frequency": "4 kg"}, {"face_modal_mass": "8 mm"}, {"face_modal_mass": "1 kg"},
                {"face_loss": 2.0}):
        with pytest.raises(FieldError):
            get_model("hertz_mindlin")(**bad)
    # half a face is refused with the options (a study's line), not when the model runs
    for half in ({"face_frequency": "4 kHz"}, {"face_modal_mass": "8 g"}, {"face_frequency": "4 kHz",
                                                                           "face_modal_mass": 0.0}):
        with pytest.raises(FieldError, match="frequency and its modal mass both"):
            get_model("hertz_mindlin")(**half)


@given(friction=st.floats(0.05, 1.0), frequency=st.floats(2e3, 8e3), modal=st.floats(0.002, 0.03),
       loss=st.sampled_from([0.0, 0.2]), rolling=st.sampled_from([0.0, 0.3]),
       inelastic=st.sampled_from(["adjusted_speed", "hysteretic"]), seed=st.integers(0, 2**16))
def test_energy_never_rises_with_a_flexing_face_on_off_centre_strikes(friction, frequency, modal, loss, rolling,
                                                                     inelastic, seed):
    """Off-centre 3-D strikes of a free head with a flexing face: ball and head never leave with more kinetic
    energy than they had (the face's vibration is energy they lost)."""
    rng = np.random.default_rng(seed)
    n = 16
    inputs = _with({key: np.asarray(value)[:n] for key, value in DRIVER_CASES.items()},
                   restitution=rng.choice([0.6, 0.8, 1.0], n), friction=friction,
                   strike_toe=rng.uniform(-0.03, 0.03, n), strike_high=rng.uniform(-0.02, 0.02, n),
                   dynamic_loft=rng.uniform(0.05, 0.9, n), speed=rng.uniform(20.0, 55.0, n),
                   club_restitution_gain=rng.choice([0.0, 0.05], n))
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse", "rolling_moment", "rolling_moment_slip"]
    result = get_model("hertz_mindlin")(face_frequency=frequency * 2 * np.pi, face_modal_mass=modal,
                                        face_loss=loss, rolling_hysteresis=rolling, inelastic=inelastic,
                                        tolerance=1e-3).compute(inputs, names)
    before, after = kinetic_energy(inputs), kinetic_energy(inputs, result)
    assert np.all(after <= before * (1.0 + 1e-9)), np.max((after - before) / before)


def test_a_lossy_ball_gains_speed_from_the_face_and_an_elastic_one_loses_it():
    """The trampoline effect: under the hysteretic law the ball, compressed less, loses less, so a flexing face
    raises the ball's speed over the rigid face with the ball's own e; on an elastic ball it can only lower it."""
    lossy = _with(_plate(0.2), restitution=0.78, club_restitution_gain=MARK)
    elastic = _plate(0.2)
    for inputs, rises in ((lossy, True), (elastic, False)):
        names = ["normal_impulse"]
        flexing = get_model("hertz_mindlin")(inelastic="hysteretic", **FACE).compute(inputs, names)
        rigid = get_model("hertz_mindlin")(inelastic="hysteretic").compute(inputs, names)
        assert (float(flexing["normal_impulse"].values[0]) > float(rigid["normal_impulse"].values[0])) == rises


WITH_FACE = [get_model("hertz_mindlin")(tolerance=1e-3, **FACE),
             get_model("hertz_mindlin")(tolerance=1e-3, inelastic="hysteretic", face_loss=0.1,
                                        rolling_hysteresis="restitution", **FACE),
             get_model("dem_linear")(tolerance=1e-3, **FACE),
             get_model("maw")(tolerance=1e-3, **FACE)]


@pytest.mark.slow
@parametrize_with_checks(*WITH_FACE)
def test_conformance_with_the_face_law(model, check):
    """The shipped conformance suite with the face law on."""
    check(model)


def test_the_compiled_kernel_with_a_face_equals_its_numpy_reference(monkeypatch):
    from impactlab.physics import kernels as _kernels

    if not _kernels.HAVE_NUMBA:
        pytest.skip("numba is off: the numpy path is the only one")
    n, mass, radius = 3, 0.04593, 0.021335
    mobility = np.broadcast_to(np.diag([1 / mass + 1 / (0.4 * mass)] * 2 + [1 / mass + 1 / 0.2]), (n, 3, 3)).copy()
    face = face_flex.modal_inputs(np.array([5e6, 8e6, 1.2e7]), np.array([0.008, 0.006, 0.01]), 0.1)
    arguments = dict(friction=np.full(n, 0.4), kappa=np.full(n, 0.7), modulus=np.full(n, 1.5e8),
                     radius=np.full(n, radius), normal=hertz.DampedNormal(0.3), springs=1, steps=300,
                     law="mindlin", face=face)
    speeds, slips = np.full(n, 40.0), np.array([5.0, 15.0, 40.0])
    compiled = compliant3d.solve_once(mobility, speeds, slips, **arguments)
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    reference = compliant3d.solve_once(mobility, speeds, slips, **arguments)
    for name in ("impulse", "work", "face_energy", "contact_time"):
        np.testing.assert_allclose(getattr(compiled, name), getattr(reference, name), rtol=1e-10, atol=1e-14)
    assert np.all(compiled.face_energy > 0.0)


STUDY = """name: face
ball: {preset: urethane_tour}
club: {preset: driver}
delivery: {club_speed: 115 mph, path: 0 deg, face_angle: 0 deg, attack_angle: -0.9 deg, dynamic_loft: 12.8 deg}
models:
  - hertz_mindlin
  - {name: hertz_mindlin, id: face, face_frequency: 4 kHz, face_modal_mass: 8 g}
outputs: [spin_rate]
"""


@pytest.mark.parametrize("change, fragment", [
    (("4 kHz", "4 kg"), "models[1].face_frequency: expected"),
    (("8 g", "8 mm"), "models[1].face_modal_mass: expected a mass"),
    # bare numbers: their unit is never guessed (before, 4000 ran as 4000 rad/s = 637 Hz, 0.008 as kg)
    (("4 kHz", "4000"), "models[1].face_frequency: expected a frequency with its unit, e.g. 4 kHz"),
    (("4 kHz", "'4000'"), "models[1].face_frequency: expected a frequency with its unit"),
    # half a face, at its line (before, a ModelInputError without a line once the model ran)
    (("8 g", "0 g"), "models[1].face_modal_mass: expected the flexing face's first-mode frequency and its modal"),
    (("face_frequency: 4 kHz, ", ""), "models[1].face_frequency: expected the flexing face's first-mode frequency"),
    (("8 g", "0.008"), "models[1].face_modal_mass: expected a mass with its unit"),
])
def test_a_study_refuses_a_bad_face_option_at_its_line(change, fragment):
    from test_study import assert_one_clear_message

    impactlab.load_study(STUDY, file="study.yaml")  # as written, it loads
    impactlab.load_study(STUDY.replace("4 kHz", "0").replace("8 g", "0"), file="study.yaml")  # a bare 0 is read
    assert_one_clear_message(STUDY, change, 7, [fragment])


def test_a_gain_above_the_pairs_e_on_a_flexing_face_is_refused_not_clipped():
    """The ball's own e = e - gain on a flexing face: a pair's e below the club's gain has none. Before, it was
    clipped to 0 without a word (a perfectly plastic ball on the face, whatever the user meant)."""
    inputs = _with({key: np.asarray(value)[:2] for key, value in DRIVER_CASES.items()}, restitution=[0.05, 0.8],
                   club_restitution_gain=0.083)
    with pytest.raises(ModelInputError, match="club_restitution_gain.*1 case"):
        get_model("hertz_mindlin")(**FACE).compute(inputs, ["normal_impulse"])
    # the face off, or an iron's face (no gain), leaves the pair's e as given
    get_model("hertz_mindlin")().compute(inputs, ["normal_impulse"])
    get_model("hertz_mindlin")(**FACE).compute(_with(inputs, club_restitution_gain=0.0), ["normal_impulse"])


@pytest.mark.parametrize("tail, line, fragment, refused", [
    ("sweep: {club.restitution_gain: [0, 0.04, 0.083]}\n", 9, "sweep.club.restitution_gain: expected", True),
    ("sweep: {g: {club.restitution_gain: [0, 0.083], club.loft: [10 deg, 12 deg]}}\n", 9,
     "sweep.g.club.restitution_gain: expected", True),
    ("sensitivity: {samples: 8, parameters: {club.restitution_gain: {low: 0, high: 0.1}}}\n", 9,
     "sensitivity.parameters.club.restitution_gain: expected", True),
    ("sweep: {club.restitution_gain: [0.02, 0.083]}\n", 0, "", False),  # all flexing: the gain's own effect
    ("sweep: {club.preset: [driver, 7_iron]}\n", 0, "", False),  # irons beside woods: each club's own face
    ("sensitivity: {samples: 8, parameters: {club.restitution_gain: {spread: 0.01}}}\n", 0, "", False),
])
def test_a_gain_swept_through_zero_with_the_face_on_is_refused_at_its_line(tail, line, fragment, refused):
    """club_restitution_gain > 0 marks the faces that flex: gains 0 and 1e-9 differ by the whole face law (J_t of
    a driver strike by 5 %, measured below), so a sweep or a sensitivity range through 0 would draw that switch
    as the gain's effect. Before, it ran and showed the jump without a word."""
    one = {key: np.asarray(value)[:2] for key, value in DRIVER_CASES.items()}
    jumps = get_model("hertz_mindlin")(**FACE).compute(_with(one, club_restitution_gain=[0.0, MARK]),
                                                       ["tangential_impulse"])["tangential_impulse"].values
    assert abs(jumps[1] - jumps[0]) > 0.01 * abs(jumps[0])  # what the refusal is for
    study = STUDY + tail
    if not refused:
        impactlab.load_study(study, file="study.yaml")
        impactlab.load_study(study.replace("  - {name: hertz_mindlin, id: face, face_frequency: 4 kHz, "
                                           "face_modal_mass: 8 g}\n", ""), file="study.yaml")
        return
    with pytest.raises(FieldError) as info:
        impactlab.load_study(study, file="study.yaml")
    assert str(info.value).startswith(f"study.yaml:{line}: {fragment}"), str(info.value)
    assert "switches the face law on and off" in str(info.value)
    # the same study without the flexing face runs the sweep: the gain's effect is then the rigid face's
    impactlab.load_study(study.replace("face_frequency: 4 kHz, face_modal_mass: 8 g", "tolerance: 0.01"),
                         file="study.yaml")


@pytest.mark.parametrize("line", [True, False])
@pytest.mark.parametrize("loss", [0.0, 0.1])
def test_the_face_energy_the_kernel_reports_is_what_an_elastic_ball_lost(loss, line):
    """Energy conservation, an oracle apart from the face's bookkeeping: an elastic ball without friction on a
    flexing face loses exactly what the face holds at separation plus what its loss took, so the reported
    face_energy equals -work (the rigid bodies' loss, summed from the contact force on their approach) to the
    integration's error; a lossy ball loses more than the face takes. Before, no test read face_energy's value
    (a halved held energy, or the loss's share dropped, passed). The cases are on one line: with ``line`` False
    the 3-D kernel's own bookkeeping is checked, not its form on the line (kernels/line.py)."""
    n, mass = 4, 0.04593
    mobility = np.broadcast_to(np.diag([1 / mass + 1 / (0.4 * mass)] * 2 + [1 / mass + 1 / 0.2]), (n, 3, 3)).copy()
    face = face_flex.modal_inputs(np.array([5e6, 8e6, 1.2e7, 3e6]), np.array([0.008, 0.006, 0.01, 0.012]), loss)
    arguments = dict(friction=np.zeros(n), kappa=np.full(n, 0.7), modulus=np.full(n, 1.5e8),
                     radius=np.full(n, 0.021335), springs=1, steps=300, law="mindlin", face=face)
    arguments["line"] = line
    elastic = compliant3d.solve(mobility, np.full(n, 40.0), np.zeros(n), normal=hertz.ELASTIC, **arguments)
    kinetic = 0.5 * 40.0**2 / mobility[0, 2, 2]
    assert np.all(elastic.face_energy > 1e-3 * kinetic)
    np.testing.assert_allclose(elastic.face_energy, -elastic.work, rtol=1e-3)
    lossy = compliant3d.solve(mobility, np.full(n, 40.0), np.zeros(n), normal=hertz.DampedNormal(0.3), **arguments)
    assert np.all((lossy.face_energy > 0.0) & (lossy.face_energy < -lossy.work))


def test_the_force_history_of_a_flexing_face_integrates_to_its_normal_impulse():
    """outputs [normal_force] alone on the 3-D kernel's cases (every flexing face's): before, the kernel was run
    without recording (the 1-D solvers draw the normal force from their law), and the model raised a TypeError
    where the same driver strike on a rigid face gave its history. Oracle: impulse-momentum, int F dt = J_n."""
    inputs = _with(_plate(0.25), club_restitution_gain=0.083, restitution=0.87)
    off_centre = {key: np.asarray(value)[:3] for key, value in DRIVER_CASES.items()}  # 3-D, face off too
    for case, options in ((inputs, FACE), (off_centre, FACE), (off_centre, {})):
        result = get_model("hertz_mindlin")(**options).compute(case, ["normal_impulse", "normal_force"])
        force, time = result["normal_force"].values, result["time"].values
        np.testing.assert_allclose(np.trapezoid(np.nan_to_num(force), time, axis=-1),
                                   result["normal_impulse"].values, rtol=1e-4)


def test_maw_annuli_names_the_flexing_face_when_it_refuses_a_case():
    """maw's annuli solve one line only; a centre strike on a fixed flexing face is such a line, yet takes the 3-D
    kernel: the refusal says so instead of listing only reasons the case does not have."""
    inputs = _with(_plate(0.25), club_restitution_gain=0.083, restitution=0.87)
    with pytest.raises(ModelInputError, match="a flexing face"):
        get_model("maw")(method="annuli", **FACE).compute(inputs, ["normal_impulse"])


@pytest.mark.parametrize("model, tolerance", [("maw", 1e-2), ("maw", 1e-3), ("hertz_mindlin", 1e-2)])
def test_a_stiff_face_on_few_steps_is_the_rigid_face_not_a_divergence(model, tolerance):
    """The face's mode rides on the kernel's leapfrog, which diverges for Omega_eff dt > 2 (Omega_eff^2 = Omega^2
    + (15/8) g, the contact's stiffness included). Before, a 200 kHz or 1 MHz face (inside the option's range) on
    a model's coarse 3-D steps gave NaN or 1e280 impulses, in maw without a flag. Oracle: the stiff limit, the
    rigid face with the ball's own e (e - gain)."""
    cases = {key: np.asarray(value)[:4] for key, value in DRIVER_CASES.items()}
    gained = _with(cases, club_restitution_gain=0.05)
    ball_own = _with(cases, club_restitution_gain=0.0, restitution=cases["restitution"] - 0.05)
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse"]
    rigid = get_model(model)(tolerance=tolerance).compute(ball_own, names)
    scale = np.abs(rigid["normal_impulse"].values).max()
    for frequency in ("200 kHz", "1 MHz"):
        stiff = get_model(model)(tolerance=tolerance, face_frequency=frequency, face_modal_mass="8 g").compute(
            gained, names)
        for name in names:
            np.testing.assert_allclose(stiff[name].values, rigid[name].values, rtol=0, atol=2e-3 * scale)


def test_a_face_option_on_a_study_without_a_spring_like_face_is_refused_not_ignored():
    """The face law acts where club_restitution_gain > 0: on a custom club without a gain (a spec-sheet driver
    typed in), or irons only, it changed nothing and the study ran as a rigid face, the option silently void."""
    for club in ("club: {preset: 7_iron}", "club: {preset: driver, restitution_gain: 0}"):
        with pytest.raises(FieldError) as info:
            impactlab.load_study(STUDY.replace("club: {preset: driver}", club), file="study.yaml")
        message = str(info.value)
        assert message.startswith("study.yaml:7: models[1].face_frequency: expected a study with a spring-like face")
        assert "would change nothing" in message
    # a woods-and-irons sweep flexes the woods: it runs
    impactlab.load_study(STUDY.replace("club: {preset: driver}", "club: {preset: 7_iron}")
                         + "sweep: {club.preset: [7_iron, driver]}\n", file="study.yaml")


def test_maw_hysteretic_with_a_stiff_face_keeps_the_rigid_faces_limit_correction_and_flag():
    """maw's hysteretic law corrects MDR where it breaks the 3-D Coulomb limit (flag 64, the annular strips'
    correction) on the rigid face; its flexing-face cases skipped it, so a 1 MHz face (a rigid one) gave 28 rpm more
    spin than the rigid face with the same ball's e, and the flag vanished. Oracle: the stiff limit."""
    cases = {key: np.asarray(value)[:2] for key, value in DRIVER_CASES.items()}
    names = ["tangential_impulse", "normal_impulse", "validity"]
    rigid = get_model("maw")(inelastic="hysteretic").compute(_with(cases, club_restitution_gain=0.0,
                                                                    restitution=0.75), names)
    stiff = get_model("maw")(inelastic="hysteretic", face_frequency="1 MHz", face_modal_mass="8 g").compute(
        _with(cases, club_restitution_gain=0.05, restitution=0.8), names)
    assert np.all(rigid["validity"].values.astype(int) & 64)  # the cases this is about
    np.testing.assert_array_equal(stiff["validity"].values, rigid["validity"].values)
    np.testing.assert_allclose(stiff["tangential_impulse"].values, rigid["tangential_impulse"].values, rtol=1e-3)


def test_the_calibration_refuses_to_fit_the_gain_the_flexing_face_replaces():
    """With the face on, the gain only marks the faces that flex: a fit of face_restitution_gain was flat in it
    (it stayed at its start and inflated the other parameters' uncertainty threefold), its COR check added it to
    the ball's law, and at its bound 0 it would switch the face off. Before, it was fitted without a word."""
    model = get_model("hertz_mindlin")(**FACE)
    with pytest.raises(FieldError, match="without face_restitution_gain.*flexing face"):
        calibrate(model, shot_table("trackman_tour"), DEFAULT_PARAMETERS)


@pytest.mark.parametrize("model", ["hertz_mindlin", "maw"])
def test_energy_never_rises_with_the_face_the_core_rolling_and_the_adhesion_law_together(model):
    """The face with every other law of the compliant models on at once (core behind the shell, rolling couple
    1 - e^2, friction_law adhesion on a rough dry face), off-centre strikes of a free head: ball and head never
    leave with more kinetic energy than they had (velocities' oracle, test_ball_laws.kinetic_energy)."""
    rng = np.random.default_rng(11)
    n = 16
    inputs = _with({key: np.asarray(value)[:n] for key, value in DRIVER_CASES.items()},
                   restitution=rng.choice([0.6, 0.8, 0.95], n), strike_toe=rng.uniform(-0.03, 0.03, n),
                   strike_high=rng.uniform(-0.02, 0.02, n), dynamic_loft=rng.uniform(0.05, 0.9, n),
                   speed=rng.uniform(20.0, 55.0, n), club_restitution_gain=rng.choice([0.0, 0.05, 0.083], n),
                   ball_shear_strength=rng.uniform(2e6, 8e6, n), ball_cover_modulus=2e8, face_roughness_slope=0.1,
                   ball_cover_melt_rise=np.inf, face_roughness=2e-6, face_groove_land=np.inf, face_water_film=0.0)
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse", "rolling_moment", "rolling_moment_slip"]
    result = get_model(model)(face_frequency="5 kHz", face_modal_mass="9 g", face_loss=0.1, core_radius="19 mm",
                              rolling_hysteresis="restitution", inelastic="hysteretic", friction_law="adhesion",
                              tolerance=1e-3).compute(inputs, names)
    before, after = kinetic_energy(inputs), kinetic_energy(inputs, result)
    assert np.all(np.isfinite(after)) and np.all(after <= before * (1.0 + 1e-9)), np.max((after - before) / before)


def _line_spy(monkeypatch):
    """Record the cases each call of the line kernel solves (compliant3d.solve_once's cases on one line)."""
    from impactlab.physics import kernels as _kernels

    seen = []
    name = "line_cases" if _kernels.HAVE_NUMBA else "_line_cases"
    original = getattr(_kernels, name)

    def spy(*arguments):
        seen.extend(int(row) for row in arguments[-1])
        return original(*arguments)

    monkeypatch.setattr(_kernels, name, spy)
    return seen


@pytest.mark.parametrize("name, options", [
    ("hertz_mindlin", {}), ("dem_linear", {"inelastic": "hysteretic"}),
    ("hertz_mindlin", {"rolling_hysteresis": "restitution", "face_loss": 0.1})])
def test_the_face_is_continuous_across_the_centred_strike(monkeypatch, name, options):
    """The centred strike on a free head (on one line: the line kernel, kernels/line.py) and strikes 1 micrometre
    off it (the 3-D kernel) agree: J_t to 1e-6 of mu J_n (the offset's own effect is ~1e-11), J_n and the spin
    likewise, and only the centred case took the line kernel."""
    from test_ball_laws import _centred_head_cases

    inputs = _centred_head_cases([0.0, 1e-6, -1e-6])
    inputs["club_restitution_gain"] = np.full(3, 0.05)
    seen = _line_spy(monkeypatch)
    model = get_model(name)(face_frequency="5 kHz", face_modal_mass="10 g", **options)
    result = model.compute(inputs, ["tangential_impulse", "normal_impulse", "spin_rate"])
    assert set(seen) == {0}
    jt, jn = result["tangential_impulse"].values, result["normal_impulse"].values
    assert np.max(np.abs(jt - jt[0])) <= 1e-6 * 0.15 * jn[0]
    assert np.max(np.abs(jn - jn[0])) <= 1e-6 * jn[0]
    rigid = get_model(name)(**options).compute(inputs, ["spin_rate"])["spin_rate"].values
    assert abs(result["spin_rate"].values[0] - rigid[0]) > 100.0  # the face acts on both paths
