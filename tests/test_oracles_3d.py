"""Oracles written independently of the 3-D code under test (issue 23, item 6).

- A small 3-D rigid-impact solver written here from Stronge's integration over the normal impulse (Stronge,
  *Impact Mechanics*, 2000, ch. 5), with its own geometry and mobility (not ``contact_state``), checked against
  closed forms (one-line Coulomb impact; the frictionless off-centre impulse with Cross & Nathan's effective
  mass, Am. J. Phys. 77 (2009) 36) and then compared to ``rigid_coulomb`` on random off-centre strikes.
- The 1-D/3-D path choice on a head whose only coupling is vertical (struck 8 mm high on the CG's line).
- Energy on 3-D cases: none created, and none lost by a frictionless elastic impact.
- A left-handed golfer's launch direction and spin axis, mirrored, on the 3-D path.
- A ball with a lossy cover in shear (a Kelvin-Voigt spring-dashpot in series with a Coulomb slider, linear or
  Mindlin), which takes the 3-D kernel: against a stick-slip ODE integrated here with scipy's solve_ivp.
- Club-preset data pinned against their cited sources (numbers typed here from the sources).
"""

import math

import numpy as np
import pytest

from impactlab.model.registry import get_model
from impactlab.physics.contact import contact_state
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.catalogue import CLUB_PRESETS
from impactlab.scene.core import Contact, Delivery, Scene, complete_inputs
from impactlab.scene.core import Impact
from impactlab.scene.materials import BALL_PRESETS, FACE_PRESETS, MATERIAL_PRESETS

BALL = BALL_PRESETS["urethane_tour"]
G_CM2 = 1e-7


# --- the independent solver ------------------------------------------------------------------------------------

def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _add(a, b, s=1.0):
    return (a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2])


def _mul(matrix, v):
    return tuple(_dot(row, v) for row in matrix)


def _tangent_basis(n):
    a = (0.0, 1.0, 0.0) if abs(n[1]) < 0.9 else (1.0, 0.0, 0.0)
    a = _add(a, n, -_dot(a, n))
    norm = math.sqrt(_dot(a, a))
    a = (a[0] / norm, a[1] / norm, a[2] / norm)
    b = (n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2], n[0] * a[1] - n[1] * a[0])
    return a, b


def stronge(v0, mobility, n, mu, e, steps=4000):
    """Impulse on the ball (ground frame) of a rigid impact: relative contact velocity ``v0`` (ball minus head),
    mobility ``W`` (dv = W dJ), contact normal ``n`` towards the ball; Coulomb friction ``mu``, Stronge's
    energetic restitution ``e`` (the normal force's work in restitution is e^2 times minus its work in
    compression). Integrated over the normal impulse p with the midpoint rule; where the slip stops the impact
    sticks if the tangential impulse that keeps the slip at zero lies inside the friction cone, and otherwise
    slips on in the direction the slip grows (Stronge 2000, section 5.3)."""
    a, b = _tangent_basis(n)
    wn = _mul(mobility, n)
    p_end = (1.0 + e) * -_dot(v0, n) / _dot(n, wn)  # the frictionless normal impulse: the step's scale
    dp = p_end / steps
    impulse = (0.0, 0.0, 0.0)
    compression = restitution = 0.0
    stuck = None  # the tangential impulse rate that keeps a stuck contact stuck

    def velocity(j):
        return _add(v0, _mul(mobility, j))

    def rate_of(v):
        if stuck is not None:
            return stuck
        slip = _add(v, n, -_dot(v, n))
        size = math.sqrt(_dot(slip, slip))
        return _add(n, slip, -mu / size) if size > 0 else n

    for _ in range(100 * steps):
        v = velocity(impulse)
        vn = _dot(v, n)
        slip = _add(v, n, -vn)
        size = math.sqrt(_dot(slip, slip))
        step = dp
        if stuck is None and mu > 0 and size < 1e-3 * abs(_dot(v0, n)) / steps:
            # the slip has stopped: stick if the cone allows (solve W_tt x = -W_tn in the tangent plane)
            wtt = [[_dot(u, _mul(mobility, w)) for w in (a, b)] for u in (a, b)]
            wtn = [_dot(u, wn) for u in (a, b)]
            det = wtt[0][0] * wtt[1][1] - wtt[0][1] * wtt[1][0]
            x = ((-wtn[0] * wtt[1][1] + wtn[1] * wtt[0][1]) / det, (-wtn[1] * wtt[0][0] + wtn[0] * wtt[1][0]) / det)
            if math.hypot(*x) <= mu:
                stuck = _add(_add(n, a, x[0]), b, x[1])
            else:  # slips on: the direction s where d(slip)/dp = W (n - mu s) is along +s
                best, direction = -math.inf, None
                for k in range(3600):
                    angle = 2 * math.pi * k / 3600
                    s = _add(_add((0.0, 0.0, 0.0), a, math.cos(angle)), b, math.sin(angle))
                    growth = _mul(mobility, _add(n, s, -mu))
                    growth = _add(growth, n, -_dot(growth, n))
                    score = _dot(growth, s) / (math.sqrt(_dot(growth, growth)) + 1e-300)
                    if score > best:
                        best, direction = score, s
                impulse = _add(impulse, _add(n, direction, -mu), dp)
                continue
        elif stuck is None and mu > 0:
            # a step that would carry the slip through zero is cut where it stops (linear in p)
            change = _mul(mobility, rate_of(v))
            change = _add(change, n, -_dot(change, n))
            towards = -_dot(change, slip) / size
            if towards > 0 and size / towards < dp:
                step = max(size / towards, 1e-12 * dp)
        middle = _add(impulse, rate_of(v), 0.5 * step)
        rate = rate_of(velocity(middle))
        new = _add(impulse, rate, step)
        vn_new = _dot(velocity(new), n)
        work = 0.5 * (vn + vn_new) * _dot(rate, n) * step
        if vn_new <= 0 or vn < 0:
            compression += min(work, 0.0)
            restitution += max(work, 0.0)
        else:
            restitution += work
        if restitution >= e * e * -compression and vn_new > 0:
            over = restitution - e * e * -compression  # the last step's excess work, taken back linearly
            fraction = 1.0 - over / work if work > 0 else 1.0
            return _add(impulse, rate, fraction * step)
        impulse = new
    raise AssertionError("the impact did not end")


def _head_axes(loft):
    """Ground frame (X target, Y left, Z up), right-handed golfer, square face, path and attack 0: the face's
    toe, up-the-face and normal for a dynamic loft, typed from the geometry (docs/clubs.md)."""
    toe = (0.0, -1.0, 0.0)
    up = (-math.sin(loft), 0.0, math.cos(loft))
    normal = (math.cos(loft), 0.0, math.sin(loft))
    return toe, up, normal


def independent_impact(head: ClubHead, strike: Strike, loft: float, speed: float, mu: float, e: float,
                       spin: float = 0.0):
    """Ball velocity and spin (ground frame) of a flat-faced head whose static loft equals the dynamic loft;
    ``spin`` [rad/s] is the ball's incoming backspin (docs/conventions.md: positive as friction spins a ball
    sliding up a lofted face, i.e. about -Y, the golfer's right, for a ball going towards +X)."""
    toe, up, normal = _head_axes(loft)
    m, radius, k2 = BALL.mass, BALL.radius, BALL.inertia_factor
    # head frame at address (toe, vertical, target) in ground axes: with static loft = dynamic loft the head
    # stands as at address
    axes = np.array([toe, (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)]).T
    inertia = axes @ np.array(head.inertia) @ axes.T
    cg_toe, cg_high, cg_depth = head.center_of_mass
    centre = np.array(toe) * cg_toe + np.array(up) * cg_high - np.array(normal) * cg_depth
    point = np.array(toe) * strike.toe + np.array(up) * strike.high
    r = point - centre
    skew = np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])
    nn = np.outer(normal, normal)
    w_ball = (np.eye(3) + (np.eye(3) - nn) / k2) / m
    w_head = np.eye(3) / head.mass + skew.T @ np.linalg.inv(inertia) @ skew
    mobility = [tuple(row) for row in (w_ball + w_head)]
    spin_before = np.array([0.0, -spin, 0.0])
    # the ball's contact point (at -R n from its centre) minus the head's contact point moving along X
    v0 = tuple(np.cross(spin_before, -radius * np.array(normal)) - np.array([speed, 0.0, 0.0]))
    impulse = np.array(stronge(v0, mobility, normal, mu, e))
    velocity = impulse / m
    spin_after = spin_before + np.cross(-radius * np.array(normal), impulse) / (k2 * m * radius**2)
    return velocity, spin_after, impulse, mobility


def golf_terms(velocity, spin):
    """Ball speed [m/s], vertical and horizontal launch [deg], back and side spin [rpm] by the documented
    definitions (docs/conventions.md): horizontal positive right, side spin positive curving right."""
    horizontal = math.degrees(math.atan2(-velocity[1], velocity[0]))
    vertical = math.degrees(math.atan2(velocity[2], math.hypot(velocity[0], velocity[1])))
    back_axis = np.cross([velocity[0], velocity[1], 0.0], [0.0, 0.0, 1.0])
    back_axis /= np.linalg.norm(back_axis)
    flight = velocity / np.linalg.norm(velocity)
    up_axis = np.cross(back_axis, flight)
    rpm = 30.0 / math.pi
    return {"ball_speed": float(np.linalg.norm(velocity)), "vertical_launch_angle": vertical,
            "horizontal_launch_angle": horizontal, "back_spin": float(spin @ back_axis) * rpm,
            "side_spin": -float(spin @ up_axis) * rpm}


def _scene(head, strike, loft, speed, mu, e, handedness="right", face_angle=0.0, spin=0.0, path=0.0):
    delivery = Delivery(speed, dynamic_loft=loft, face_angle=face_angle, handedness=handedness, path=path)
    return Scene.from_delivery(BALL, Scene.face_of(head), Contact(mu, e), delivery, spin, head, strike)


def _run(model, scenes, outputs, **options):
    keys = scenes[0].inputs().keys()
    inputs = complete_inputs({key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys})
    return inputs, get_model(model)(**options).compute(inputs, outputs)


# --- the oracle's own checks -----------------------------------------------------------------------------------

def test_the_oracle_equals_the_one_line_closed_form():
    """A ball on a fixed face (W diagonal): J_n = (1 + e) m V_n; J_t = min(mu J_n, m_t V_t), 1/m_t = (1 + 1/K^2)/m
    (Stronge 2000, ch. 5; the rolling branch keeps 5/7 of the tangential speed for K^2 = 0.4)."""
    m, k2 = BALL.mass, BALL.inertia_factor
    n = (0.0, 0.0, 1.0)
    mobility = [(1 / m + 1 / (k2 * m), 0.0, 0.0), (0.0, 1 / m + 1 / (k2 * m), 0.0), (0.0, 0.0, 1 / m)]
    for slip, normal, mu, e in [(10.0, 30.0, 0.4, 0.8), (30.0, 10.0, 0.2, 0.6), (20.0, 20.0, 0.3, 1.0)]:
        impulse = stronge((slip, 0.0, -normal), mobility, n, mu, e)
        jn = (1 + e) * m * normal
        jt = min(mu * jn, slip / (1 / m + 1 / (k2 * m)))
        assert impulse[2] == pytest.approx(jn, rel=1e-6)
        assert -impulse[0] == pytest.approx(jt, rel=1e-6)
        assert abs(impulse[1]) < 1e-12 * jn


@pytest.mark.parametrize("toe, high, moment", [(0.02, 0.0, 5.6e-4), (0.0, 0.012, 2.8e-4), (-0.015, 0.0, 5.6e-4)])
def test_the_oracle_and_rigid_coulomb_give_cross_and_nathans_effective_mass_without_friction(toe, high, moment):
    """Frictionless strike b off the CG line, on a principal axis of the head: J = (1 + e) M_e V_n with
    1/M_e = 1/m + 1/M + b^2/I_a, I_a the head's moment about the principal axis through the CG perpendicular to
    the offset and the normal (Cross & Nathan 2009, eq. 2, for a bat; the same rigid-body algebra). A square,
    unlofted face (loft 0) keeps the head's principal axes along the face: an offset towards the toe turns the
    head about its vertical axis (5.6e-4 kg m^2), one up the face about its heel-toe axis (2.8e-4 kg m^2)."""
    speed, e = 45.0, 0.8
    head = ClubHead(mass=0.2, inertia=(2.8e-4, 5.6e-4, 4.1e-4), center_of_mass=(0.0, 0.0, 0.04), loft=0.0,
                    material=MATERIAL_PRESETS["titanium"])
    b = math.hypot(toe, high)
    effective = 1.0 / (1.0 / BALL.mass + 1.0 / head.mass + b**2 / moment)
    expected = (1 + e) * effective * speed
    strike = Strike(toe=toe, high=high)
    _, _, impulse, _ = independent_impact(head, strike, 0.0, speed, 0.0, e)
    assert np.linalg.norm(impulse) == pytest.approx(expected, rel=1e-6)
    _, result = _run("rigid_coulomb", [_scene(head, strike, 0.0, speed, 0.0, e)], ["normal_impulse"])
    assert result["normal_impulse"].values[0] == pytest.approx(expected, rel=1e-6)


# --- rigid_coulomb against the oracle ----------------------------------------------------------------------------

def _random_head(rng):
    """A driver- or iron-like head with products of inertia: the preset's principal moments on turned axes."""
    base = CLUB_PRESETS["driver"] if rng.random() < 0.5 else CLUB_PRESETS["6_iron"]
    moments = np.linalg.eigvalsh(np.array(base.inertia))
    turn = np.linalg.qr(np.eye(3) + 0.3 * rng.standard_normal((3, 3)))[0]
    tensor = turn @ np.diag(moments) @ turn.T
    centre = (rng.uniform(-0.004, 0.004), rng.uniform(-0.004, 0.004), rng.uniform(0.006, 0.04))
    return base, tensor, centre


def test_rigid_coulomb_equals_the_independent_solver_on_random_off_centre_strikes():
    rng = np.random.default_rng(23)
    scenes, expected = [], []
    for _ in range(8):
        base, tensor, centre = _random_head(rng)
        loft = math.radians(rng.uniform(8.0, 35.0))
        head = ClubHead(mass=base.mass, inertia=tensor, center_of_mass=centre, loft=loft, material=base.material,
                        face_width=base.face_width, face_height=base.face_height)
        strike = Strike(toe=rng.uniform(-0.02, 0.02), high=rng.uniform(-0.01, 0.01))
        speed, mu, e = rng.uniform(35.0, 50.0), rng.uniform(0.15, 0.6), rng.uniform(0.6, 0.9)
        spin_in = rng.uniform(-300.0, 300.0)  # incoming spin, rad/s (about +-2900 rpm)
        scenes.append(_scene(head, strike, loft, speed, mu, e, spin=spin_in))
        velocity, spin, _, _ = independent_impact(head, strike, loft, speed, mu, e, spin_in)
        expected.append(golf_terms(velocity, spin))
    names = ["ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "back_spin", "side_spin"]
    inputs, result = _run("rigid_coulomb", scenes, names, steps=40000)
    assert not np.any(contact_state(inputs)["one_dimensional"])  # the 3-D integration, not the closed form
    for name in names:
        got = result[name].values
        want = np.array([case[name] for case in expected])
        scale = {"ball_speed": 0.2, "vertical_launch_angle": 0.01, "horizontal_launch_angle": 0.01,
                 "back_spin": 2.0, "side_spin": 2.0}[name]  # m/s, deg, rpm: 1e-3 to 1e-4 of the values
        np.testing.assert_allclose(got, want, rtol=0, atol=scale, err_msg=name)


def test_the_contact_time_on_a_curved_face_is_hertz_with_the_equivalent_radius():
    """A centred, frictionless, elastic strike on the measured driver's bulged and rolled face: the contact
    time is Hertz's, t_c = 2.8682 (m*^2 / (R_e E*^2 V_n))^(1/5) (physics brief section 2), with the equivalent
    radius of two convex bodies, 1/R' = 1/R + 1/R_bulge and 1/R'' = 1/R + 1/R_roll, R_e = sqrt(R' R'')
    (Johnson, Contact Mechanics, 1985, section 4.2): a convex face shortens the radius, a flat one keeps R."""
    driver = CLUB_PRESETS["driver"]
    head = ClubHead(mass=driver.mass, inertia=(3e-4, 5e-4, 4e-4), center_of_mass=(0.0, 0.0, 0.04),
                    loft=math.radians(10.0), bulge_radius=driver.bulge_radius, roll_radius=driver.roll_radius,
                    material=driver.material)
    speed, loft = 45.0, math.radians(10.0)
    scene = _scene(head, Strike(), loft, speed, 0.0, 1.0)
    _, result = _run("maw", [scene], ["contact_time"], tolerance=1e-6)
    ball, face = BALL.material, driver.material
    modulus = 1.0 / ((1 - ball.poisson_ratio**2) / ball.youngs_modulus + (1 - face.poisson_ratio**2)
                     / face.youngs_modulus)
    radius = BALL.radius
    r1, r2 = 1.0 / (1.0 / radius + 1.0 / driver.bulge_radius), 1.0 / (1.0 / radius + 1.0 / driver.roll_radius)
    mass = 1.0 / (1.0 / BALL.mass + 1.0 / head.mass)
    expected = 2.8682 * (mass**2 / (math.sqrt(r1 * r2) * modulus**2 * speed * math.cos(loft))) ** 0.2
    assert result["contact_time"].values[0] == pytest.approx(expected, rel=2e-3)


@pytest.mark.parametrize("model", ["maw", "hertz_mindlin", "dem_linear", "rigid_coulomb"])
def test_the_tangential_law_is_isotropic_in_the_face_plane(model):
    """Head-on (no incoming slip, unlofted face), a head whose moments about the toe and vertical axes are equal:
    a strike b towards the toe is the strike b up the face turned by 90 deg about the normal. The coupling makes
    the slip grow along the offset, and the friction impulse it gets must be the same whichever tangential
    axis of the contact frame it falls on (the frame's slip axis s is up the face here, its lateral axis l the
    toe): a law that weighs its two tangential components differently breaks this symmetry."""
    head = ClubHead(mass=0.2, inertia=(3.0e-4, 3.0e-4, 4.5e-4), center_of_mass=(0.0, 0.0, 0.03), loft=0.0,
                    material=MATERIAL_PRESETS["titanium"])
    scenes = [_scene(head, Strike(toe=0.015), 0.0, 45.0, 0.3, 0.8), _scene(head, Strike(high=0.015), 0.0, 45.0,
                                                                          0.3, 0.8)]
    _, result = _run(model, scenes, ["normal_impulse", "tangential_impulse", "lateral_impulse", "spin_rate"])
    normal, tangential, lateral = (result[name].values for name in ("normal_impulse", "tangential_impulse",
                                                                    "lateral_impulse"))
    assert normal[0] == pytest.approx(normal[1], rel=1e-9)
    assert abs(lateral[0]) > 0.01 * normal[0]  # friction acts: the test is not empty
    assert abs(lateral[0]) == pytest.approx(abs(tangential[1]), rel=1e-6)
    assert abs(tangential[0]) < 1e-9 * normal[0] and abs(lateral[1]) < 1e-9 * normal[0]
    assert abs(result["spin_rate"].values[0]) == pytest.approx(abs(result["spin_rate"].values[1]), rel=1e-6)


# --- the 1-D/3-D path: a head whose only coupling is vertical ---------------------------------------------------

def _vertical_only_head():
    """Principal axes along the head axes, CG on the face normal through the centre: a strike up the face couples
    the normal and up-the-face directions only."""
    return ClubHead(mass=0.204, inertia=(2.8e-4, 5.7e-4, 4.1e-4), center_of_mass=(0.0, 0.0, 0.035),
                    loft=math.radians(12.0), material=MATERIAL_PRESETS["titanium"])


def test_a_strike_8_mm_high_keeps_its_vertical_gear_effect():
    head, loft = _vertical_only_head(), math.radians(12.0)
    high = [_scene(head, Strike(high=0.008), loft, 50.0, 0.4, 0.8)]
    inputs, rigid = _run("rigid_coulomb", high, ["spin_rate", "vertical_launch_angle"], steps=40000)
    mobility = contact_state(inputs)["mobility"][0]
    assert abs(mobility[0, 2]) > 1e-3 * mobility[2, 2] and abs(mobility[1, 2]) < 1e-12 * mobility[2, 2]
    assert not contact_state(inputs)["one_dimensional"][0]  # the normal-slip coupling must not be dropped
    velocity, spin, _, _ = independent_impact(head, Strike(high=0.008), loft, 50.0, 0.4, 0.8)
    want = golf_terms(velocity, spin)
    assert rigid["spin_rate"].values[0] == pytest.approx(want["back_spin"], abs=2.0)
    # a compliant model: the high strike alone and with a 1 um toe offset (which no path test can call 1-D)
    # agree: the result is continuous across the path choice
    nudged = [_scene(head, Strike(high=0.008, toe=1e-6), loft, 50.0, 0.4, 0.8)]
    for model in ("maw", "hertz_mindlin"):
        a = _run(model, high, ["spin_rate"])[1]["spin_rate"].values[0]
        b = _run(model, nudged, ["spin_rate"])[1]["spin_rate"].values[0]
        assert a == pytest.approx(b, rel=2e-3), model
        centre = _run(model, [_scene(head, Strike(), loft, 50.0, 0.4, 0.8)], ["spin_rate"])[1]
        assert a < 0.95 * centre["spin_rate"].values[0]  # above the CG: less backspin (vertical gear effect)


# --- energy on 3-D cases ----------------------------------------------------------------------------------------

def _kinetic_energy_after(scene, impulse_ground, velocity_before):
    """Ball + head kinetic energy after an impulse (ground frame), computed here from the impulse alone."""
    head, ball = scene.club, scene.ball
    loft = scene.delivery.dynamic_loft
    toe, up, normal = (np.array(v) for v in _head_axes(loft))
    axes = np.array([toe, (0.0, 0.0, 1.0), (1.0, 0.0, 0.0)]).T
    inertia = axes @ np.array(head.inertia) @ axes.T
    cg = head.center_of_mass
    r = toe * scene.strike.toe + up * scene.strike.high - (toe * cg[0] + up * cg[1] - normal * cg[2])
    ball_velocity = impulse_ground / ball.mass
    ball_spin = np.cross(-ball.radius * normal, impulse_ground) / ball.moment_of_inertia
    head_velocity = velocity_before - impulse_ground / head.mass
    head_spin = -np.linalg.solve(inertia, np.cross(r, impulse_ground))
    return 0.5 * (ball.mass * ball_velocity @ ball_velocity + ball.moment_of_inertia * ball_spin @ ball_spin
                  + head.mass * head_velocity @ head_velocity + head_spin @ inertia @ head_spin)


@pytest.mark.parametrize("model", ["rigid_coulomb", "maw", "hertz_mindlin", "dem_linear"])
def test_energy_is_never_created_on_3d_cases_and_kept_without_friction_and_loss(model):
    head, loft, speed = CLUB_PRESETS["driver"], math.radians(12.0), 50.0
    flat = ClubHead(mass=head.mass, inertia=head.inertia, center_of_mass=head.center_of_mass, loft=loft,
                    material=head.material)
    strikes = [Strike(toe=0.02, high=0.006), Strike(toe=-0.015, high=-0.008), Strike(toe=0.0, high=0.01)]
    for mu, e in ((0.4, 0.8), (0.0, 1.0)):
        scenes = [_scene(flat, strike, loft, speed, mu, e) for strike in strikes]
        _, result = _run(model, scenes, ["ball_speed", "energy_loss"])
        before = 0.5 * flat.mass * speed**2
        losses = result["energy_loss"].values
        assert np.all(losses > -1e-4 * before), (model, mu, e, losses / before)  # none created
        if mu == 0.0:  # frictionless and elastic: nothing lost beyond the model's own error
            assert np.all(np.abs(losses) < 2e-3 * before), (model, losses / before)


def test_the_energy_loss_output_is_the_kinetic_energy_the_bodies_lose():
    head, loft, speed = CLUB_PRESETS["driver"], math.radians(12.0), 50.0
    flat = ClubHead(mass=head.mass, inertia=head.inertia, center_of_mass=head.center_of_mass, loft=loft,
                    material=head.material)
    scene = _scene(flat, Strike(toe=0.02, high=0.006), loft, speed, 0.4, 0.8)
    velocity, spin, impulse, _ = independent_impact(flat, scene.strike, loft, speed, 0.4, 0.8)
    lost = 0.5 * flat.mass * speed**2 - _kinetic_energy_after(scene, impulse, np.array([speed, 0.0, 0.0]))
    _, result = _run("rigid_coulomb", [scene], ["energy_loss"], steps=40000)
    assert lost > 0 and result["energy_loss"].values[0] == pytest.approx(lost, rel=2e-3)


# --- a left-handed golfer on the 3-D path ------------------------------------------------------------------------

@pytest.mark.parametrize("model", ["rigid_coulomb", "maw"])
def test_a_left_handed_golfer_is_the_mirror_image_on_a_free_head(model):
    head, loft = CLUB_PRESETS["driver"], math.radians(12.0)
    names = ["horizontal_launch_angle", "spin_axis", "side_spin", "vertical_launch_angle", "back_spin", "ball_speed",
             "spin_loft"]
    cases = [(0.015, 0.004, math.radians(3.0), 0.0), (-0.01, -0.005, math.radians(-2.0), math.radians(4.0))]
    right = _run(model, [_scene(head, Strike(toe, high), loft, 50.0, 0.4, 0.8, "right", face, path=path)
                         for toe, high, face, path in cases], names)[1]
    left = _run(model, [_scene(head, Strike(toe, high), loft, 50.0, 0.4, 0.8, "left", face, path=path)
                        for toe, high, face, path in cases], names)[1]
    for name in names[:3]:  # lateral: mirrored (positive right, whoever swings)
        np.testing.assert_allclose(left[name].values, -right[name].values, rtol=1e-9, atol=1e-9, err_msg=name)
    for name in names[3:]:
        np.testing.assert_allclose(left[name].values, right[name].values, rtol=1e-9, err_msg=name)
    # absolute: a left-hander's face open by 3 deg (towards the trail side, the left) with a toe strike starts
    # the ball left of the target; a right-hander's, right
    assert left["horizontal_launch_angle"].values[0] < 0 < right["horizontal_launch_angle"].values[0]


# --- a lossy cover in shear: a stick-slip ODE integrated here ---------------------------------------------------

def _hertz_duration(m, modulus, radius, speed):
    """Duration of the elastic Hertz impact, m d'' = -(4/3) E* R^0.5 d^1.5, integrated to separation [s]."""
    from scipy.integrate import solve_ivp

    def apart(t, y):
        return y[0]

    apart.terminal, apart.direction = True, -1
    solved = solve_ivp(lambda t, y: [y[1], -4.0 / 3.0 * modulus * math.sqrt(radius) * max(y[0], 0.0) ** 1.5 / m],
                       [0.0, 1.0], [0.0, speed], events=apart, rtol=1e-12, atol=[1e-16, 1e-12], method="DOP853",
                       max_step=1e-5)
    return float(solved.t_events[0][0])


def _lossy_stick_slip(m, m_t, modulus, radius, normal_speed, slip, mu, stiffness, relaxation, rescale):
    """Tangential impulse on a sphere striking a fixed rigid plate through a lossy tangential contact [N s].

    Hertz normal force F_n = (4/3) E* R^0.5 d^1.5 on m (the plate does not move); the slip velocity v of the
    contact point changes by m_t v' = -F_t with 1/m_t = 1/m + R^2/I. The tangential contact is a spring of
    stiffness k(d) storing a force S, a dashpot k tau beside it (Kelvin-Voigt: F_t = S + k tau v, tau =
    ``relaxation``), in series with a Coulomb slider |F_t| <= mu F_n. Sticking, S' = k v (plus S a'/a while the
    contact shrinks, with ``rescale``: S scales with the contact radius a ~ d^0.5); sliding with sign s,
    F_t = s mu F_n and S = s mu F_n - k tau v. Slip starts when |F_t| reaches mu F_n; the slider sticks again
    when the force a sticking contact would build grows slower than the limit,
    s (S' + k' tau v + k tau v') < mu F_n' (the continuous form of DEM's reset-to-the-cap rule). Integrated
    phase by phase with events (solve_ivp, DOP853, rtol 1e-11); ends when d returns to 1e-9 of its largest.
    ``stiffness(d)`` gives (k, dk/dd).
    """
    from scipy.integrate import solve_ivp

    scale = math.sqrt(radius) * modulus
    depth = (15.0 * m * normal_speed**2 / (16.0 * scale)) ** 0.4  # Hertz's largest approach

    def normal(d):
        return 4.0 / 3.0 * scale * max(d, 0.0) ** 1.5

    def spring_rate(d, rate, v, stored):
        shrink = stored * rate / (2.0 * d) if rescale and rate < 0.0 and d > 0.0 else 0.0
        return stiffness(d)[0] * v + shrink

    def apart(t, y):
        return y[0] - 1e-9 * depth if t > 0.0 else 1.0

    apart.terminal, apart.direction = True, -1
    y, t, sticking, side = [0.0, normal_speed, slip, 0.0], 0.0, False, math.copysign(1.0, slip)
    for _ in range(20):
        if sticking:
            def rhs(t, y):
                return [y[1], -normal(y[0]) / m, -(y[3] + stiffness(y[0])[0] * relaxation * y[2]) / m_t,
                        spring_rate(*y)]

            def switch(t, y):
                return abs(y[3] + stiffness(y[0])[0] * relaxation * y[2]) - mu * normal(y[0])

            switch.direction = 1
        else:
            def rhs(t, y, s=side):
                return [y[1], -normal(y[0]) / m, -s * mu * normal(y[0]) / m_t, 0.0]

            def switch(t, y, s=side):
                d, rate, v = y[0], y[1], y[2]
                k, dk = stiffness(d)
                stored = s * mu * normal(d) - k * relaxation * v
                building = spring_rate(d, rate, v, stored) + dk * rate * relaxation * v \
                    - k * relaxation * s * mu * normal(d) / m_t
                return s * building - mu * 2.0 * scale * math.sqrt(max(d, 0.0)) * rate

            switch.direction = -1
        switch.terminal = True
        solved = solve_ivp(rhs, [t, t + 1.0], y, events=[switch, apart], rtol=1e-11, method="DOP853",
                           atol=[1e-15, 1e-10, 1e-10, 1e-12], max_step=2e-6)
        t, y = float(solved.t[-1]), list(solved.y[:, -1])
        if solved.t_events[1].size:
            return m_t * (slip - y[2])
        k = stiffness(y[0])[0]
        if sticking:
            side = math.copysign(1.0, y[3] + k * relaxation * y[2])
        else:
            y[3] = side * mu * normal(y[0]) - k * relaxation * y[2]
        sticking = not sticking
    raise AssertionError("the stick-slip integration did not end")


@pytest.mark.parametrize(("model", "options"), [("hertz_mindlin", {}), ("hertz_mindlin", {"rescale": False}),
                                                ("dem_linear", {})])
def test_a_lossy_cover_matches_a_stick_slip_ode_integrated_here(model, options):
    """A tour ball at 40 m/s on a fixed rigid plate, 10-40 deg from the normal, mu 0.4, e = 1, with a cover loss
    factor eta = 0.3 in shear: a lossy cover takes the 3-D kernel. The loss factor at the contact's frequency
    omega = pi / t_c (the half-sine pulse of the Hertz impact) makes the dashpot's relaxation time
    tau = eta / omega = eta t_c / pi (Kelvin-Voigt). Hand data: E* = E / (1 - nu^2) on the rigid plate;
    Mindlin's k_t = 8 G a / (2 - nu) with a = (R d)^0.5, G = E / (2 (1 + nu)) (Johnson 1985, section 7.2);
    dem_linear's k_t = (2/7) 2 E* a_max. Measured agreement 7e-8 of mu J_n; a relaxation time off by pi^2
    moves J_t by 1-11 % of mu J_n, which the elastic cover also does (the case depends on the loss)."""
    ball, mu, eta, speed = BALL, 0.4, 0.3, 40.0
    angles = np.radians([10.0, 25.0, 40.0])
    scenes = [Scene(ball, FACE_PRESETS["rigid"], Contact(mu, 1.0), Impact(speed, float(angle), 0.0))
              for angle in angles]
    inputs = {key: np.array([scene.inputs()[key] for scene in scenes]) for key in scenes[0].inputs()}
    nu, radius, m = inputs["ball_poisson_ratio"][0], inputs["ball_radius"][0], inputs["ball_mass"][0]
    young = inputs["ball_youngs_modulus"][0]
    modulus, shear = young / (1.0 - nu**2), young / (2.0 * (1.0 + nu))
    m_t = 1.0 / (1.0 / m + 1.0 / (inputs["ball_inertia_factor"][0] * m))
    names = ["tangential_impulse", "normal_impulse"]
    elastic = get_model(model)(**options).compute(inputs, names)
    inputs["tangential_loss"] = np.full(angles.size, eta)
    lossy = get_model(model)(**options).compute(inputs, names)
    for case, angle in enumerate(angles):
        normal_speed, slip = speed * math.cos(angle), speed * math.sin(angle)
        if model == "dem_linear":
            depth = (15.0 * m * normal_speed**2 / (16.0 * modulus * math.sqrt(radius))) ** 0.4
            k_linear = 2.0 / 7.0 * 2.0 * modulus * math.sqrt(radius * depth)

            def stiffness(d, k=k_linear):
                return k, 0.0
        else:
            def stiffness(d):
                return (8.0 * shear / (2.0 - nu) * math.sqrt(radius * max(d, 0.0)),
                        4.0 * shear / (2.0 - nu) * math.sqrt(radius / max(d, 1e-300)))
        relaxation = eta * _hertz_duration(m, modulus, radius, normal_speed) / math.pi
        expected = _lossy_stick_slip(m, m_t, modulus, radius, normal_speed, slip, mu, stiffness, relaxation,
                                     rescale=model == "hertz_mindlin" and options.get("rescale", True))
        bound = mu * lossy["normal_impulse"].values[case]
        assert lossy["tangential_impulse"].values[case] == pytest.approx(expected, abs=1e-5 * bound)
        assert abs(elastic["tangential_impulse"].values[case] - expected) > 1e-3 * bound


# --- club presets against their sources ---------------------------------------------------------------------------

def test_the_measured_driver_is_the_published_head():
    """Proceedings 49 (2020) 47, Table 1 (measured): mass 204 g; CG [x, y, z] = [-42.3, 2.9, 1.0] mm (x along the
    face normal, y vertical, z towards the toe); inertia [[Ixx, Ixy, Ixz], ...] = [[2843, -733, 530.2], [-733,
    5679, 0.5], [530.2, 0.5, 4085]] g cm^2; loft 9.8 deg; bulge 305 mm (typed here from the paper)."""
    driver = CLUB_PRESETS["driver"]
    assert driver.mass == pytest.approx(0.204)
    assert driver.center_of_mass == pytest.approx((0.0010, 0.0029, 0.0423))  # toe <- z, high <- y, depth <- -x
    components = driver.inertia_components()
    assert components["toe"] == pytest.approx(4085 * G_CM2)  # I_zz
    assert components["up"] == pytest.approx(5679 * G_CM2)  # I_yy
    assert components["target"] == pytest.approx(2843 * G_CM2)  # I_xx
    assert components["toe_up"] == pytest.approx(0.5 * G_CM2)  # I_zy
    assert components["toe_target"] == pytest.approx(530.2 * G_CM2)  # I_zx
    assert components["up_target"] == pytest.approx(-733 * G_CM2)  # I_yx
    assert driver.loft == pytest.approx(math.radians(9.8)) and driver.bulge_radius == pytest.approx(0.305)
    # typical specifications (not measured on this head): roll 254 mm (10 in), lie 58 deg
    assert driver.roll_radius == pytest.approx(0.254) and driver.lie == pytest.approx(math.radians(58.0))


@pytest.mark.parametrize("name, mass_g, loft, lie, moments, centre_mm", [
    # Maltby's 254 g 5-iron with 7 g steps through the set; CG depth and the moment about the vertical axis from
    # Campau's patent (US 4,420,156: 2-iron 0.171 in, 13.619 oz in^2; 9-iron 0.114 in, 16.423 oz in^2), by hand:
    # 6-iron 4/7 of the way (3.5161 mm, 2783.97 g cm^2), 7-iron 5/7 (0.130286 in = 3.3093 mm, 15.622 oz in^2 =
    # 2857.25 g cm^2), the wedge the 9-iron's (2.8956 mm, 3003.76); toe moments estimates, target = up + toe - 200
    ("6_iron", 261.0, 30.0, 62.0, (800.0, 2783.97, 3383.97), (-2.0, -2.0, 3.5161)),
    ("7_iron", 268.0, 34.0, 62.5, (820.0, 2857.25, 3477.25), (-2.0, -2.0, 3.3093)),
    ("pitching_wedge", 289.0, 46.0, 64.0, (900.0, 3003.76, 3703.76), (-2.0, -1.0, 2.8956)),
])
def test_iron_presets_are_their_stated_estimates(name, mass_g, loft, lie, moments, centre_mm):
    club = CLUB_PRESETS[name]
    assert club.mass == pytest.approx(mass_g / 1000.0)
    assert mass_g == 254.0 + 7.0 * {"6_iron": 1, "7_iron": 2, "pitching_wedge": 5}[name]  # Maltby's steps
    assert club.loft == pytest.approx(math.radians(loft)) and club.lie == pytest.approx(math.radians(lie))
    assert club.loft < club.lie  # a loft-lie swap would put 62 deg of loft on a 6-iron
    components = club.inertia_components()
    assert (components["toe"], components["up"], components["target"]) == pytest.approx(
        tuple(m * G_CM2 for m in moments), abs=0.02 * G_CM2)
    assert 2400 <= moments[1] <= 3010  # inside Golf Digest's quoted range about the vertical axis (3000 rounded)
    assert club.center_of_mass == pytest.approx(tuple(c / 1000.0 for c in centre_mm), abs=1e-7)


def test_ball_presets_are_the_rules_limits_and_the_measured_inertia():
    """Rules of Golf: R >= 21.335 mm (1.68 in), m <= 45.93 g (1.620 oz); Proceedings 49 (2020) 47, Table 1: a ball
    of 45.9 g with I = 83.63 g cm^2 (measured), K^2 = I/(m R^2) = 0.400."""
    for name in ("urethane_tour", "two_piece_ionomer"):
        ball = BALL_PRESETS[name]
        assert ball.radius == pytest.approx(1.68 * 0.0254 / 2, rel=1e-4) and ball.mass == pytest.approx(0.04593)
    assert 83.63e-7 / (0.0459 * 0.021335**2) == pytest.approx(BALL_PRESETS["urethane_tour"].inertia_factor,
                                                            abs=1e-3)
