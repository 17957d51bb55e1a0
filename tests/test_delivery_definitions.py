"""Deliveries as launch monitors define them: loft at the contact point or the face centre, the head's reference
point and rotation, and the 3-D spin loft (issue 21). Oracles: rotation matrices and vector algebra written here,
independently of impactlab's formulas."""

import math

import numpy as np
import pytest

from impactlab.errors import FieldError
from impactlab.model.registry import get_model
from impactlab.physics.contact import after_impact, contact_state, impulse_vector
from impactlab.physics.delivery import centre_face, contact_face, loft_for_spin_loft
from impactlab.scene.clubs import Strike
from impactlab.scene.catalogue import CLUB_PRESETS
from impactlab.scene.core import Contact, Delivery, Scene, complete_inputs
from impactlab.scene.materials import BALL_PRESETS
from impactlab.study.core import build_delivery, build_scene

BALL = BALL_PRESETS["urethane_tour"]
DRIVER = CLUB_PRESETS["driver"]
RNG = np.random.default_rng(21)


def _rot_y(angle):
    """Rotation about the ground Y axis (left) by ``angle``: X tilts towards +Z for a negative angle."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def _rot_z(angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _hand_normal(centre_loft, centre_face_angle, toe, high, bulge, roll):
    """The contact normal by rotation matrices: the face frame at address (normal X, toe -Y, up Z) lofted about
    the toe line and turned open (to the right, -Y) about the vertical; the bulge and roll tilt the normal by the
    slopes toe/R_b and high/R_r of the paraboloid face (its gradient)."""
    turn = _rot_z(-centre_face_angle) @ _rot_y(-centre_loft)
    normal, toe_axis, up = turn @ [1.0, 0.0, 0.0], turn @ [0.0, -1.0, 0.0], turn @ [0.0, 0.0, 1.0]
    vector = normal + toe / bulge * toe_axis + high / roll * up
    return vector / np.linalg.norm(vector)


def _elevation_and_opening(normal):
    """Loft (elevation) and face angle (open = to the right, -Y) of a unit normal [rad]."""
    return math.asin(normal[2]), math.atan2(-normal[1], normal[0])


@pytest.mark.parametrize("bulge, roll", [(0.305, 0.254), (0.305, math.inf), (math.inf, 0.254), (0.15, 0.4)])
def test_contact_point_and_face_centre_definitions_round_trip(bulge, roll):
    """On bulged and rolled faces, off-centre strikes: the contact-point loft and face angle turned back to the
    face centre and forward again are the same orientation, and both match the normal built by hand."""
    n = 40
    loft = np.radians(RNG.uniform(5.0, 50.0, n))
    face = np.radians(RNG.uniform(-8.0, 8.0, n))
    toe, high = RNG.uniform(-0.03, 0.03, n), RNG.uniform(-0.02, 0.02, n)
    centre_loft, centre_angle = centre_face(loft, face, toe, high, bulge, roll)
    back_loft, back_angle = contact_face(centre_loft, centre_angle, toe, high, bulge, roll)
    np.testing.assert_allclose(back_loft, loft, atol=1e-12)
    np.testing.assert_allclose(back_angle, face, atol=1e-12)
    for i in range(n):
        hand = _elevation_and_opening(_hand_normal(centre_loft[i], centre_angle[i], toe[i], high[i], bulge, roll))
        np.testing.assert_allclose(hand, (loft[i], face[i]), atol=1e-12)
    # and the other way round: a face-centre orientation forward and back
    again = centre_face(*contact_face(loft, face, toe, high, bulge, roll), toe, high, bulge, roll)
    np.testing.assert_allclose(again, (loft, face), atol=1e-12)


def _scene(toe=0.0, high=0.0, loft_at="contact", face_angle=0.0, path=0.0, loft=12.8, attack=-0.9, speed=51.4,
           rotation=(0.0, 0.0, 0.0), reference="centre_of_mass", handedness="right", club=DRIVER):
    delivery = Delivery(speed, path=math.radians(path), face_angle=math.radians(face_angle),
                        attack_angle=math.radians(attack), dynamic_loft=math.radians(loft), handedness=handedness,
                        loft_at=loft_at, head_rotation=rotation, club_reference=reference)
    return Scene.from_delivery(BALL, Scene.face_of(club), Contact(0.4, 0.8), delivery, 0.0, club, Strike(toe, high))


def _inputs(scenes):
    keys = scenes[0].inputs().keys()
    return complete_inputs({key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys})


def test_the_models_see_the_contact_point_face_that_the_delivery_states():
    """loft_at: contact gives the contact normal the stated loft and face angle at any strike; loft_at: centre
    gives them to the face centre, and the strike's bulge and roll tilt the contact normal by hand's amount."""
    strikes = [(0.01, 0.0), (-0.015, 0.008), (0.02, -0.01)]
    for toe, high in strikes:
        contact = contact_state(_inputs([_scene(toe, high, "contact", face_angle=2.0)]))
        np.testing.assert_allclose(_elevation_and_opening(contact["normal"][0]),
                                   (math.radians(12.8), math.radians(2.0)), atol=1e-12)
        centre = contact_state(_inputs([_scene(toe, high, "centre", face_angle=2.0)]))
        hand = _hand_normal(math.radians(12.8), math.radians(2.0), toe, high, DRIVER.bulge_radius,
                            DRIVER.roll_radius)
        np.testing.assert_allclose(centre["normal"][0], hand, atol=1e-12)
    # centred, the two definitions are one
    one, other = (contact_state(_inputs([_scene(0.0, 0.0, at)])) for at in ("contact", "centre"))
    np.testing.assert_array_equal(one["normal"], other["normal"])


def test_loft_at_is_read_from_a_study_and_contact_is_the_default():
    base = dict(ball={"preset": "urethane_tour"}, club={"preset": "driver"}, strike={"toe": "10 mm"},
                delivery={"club_speed": "115 mph", "dynamic_loft": "12.8 deg"})
    assert build_scene(base).delivery.loft_at == "contact"
    assert build_scene(dict(base, delivery=dict(base["delivery"], loft_at="centre"))).inputs()["loft_at_contact"] == 0
    with pytest.raises(FieldError) as error:
        build_delivery({"club_speed": "115 mph", "loft_at": "center"})
    assert error.value.path == "delivery.loft_at" and "contact" in str(error.value)


# -- the head's rotation and reference point ---------------------------------------------------------------------
@pytest.mark.parametrize("model", ["rigid_coulomb", "maw"])
def test_zero_head_rotation_is_todays_result_exactly(model):
    """A head that does not turn gives bit-identical results whichever point the club speed belongs to, and the
    same as inputs that carry no rotation at all (what every study gave before)."""
    scenes = [_scene(toe, high, "centre", face_angle=2.0) for toe, high in ((0.0, 0.0), (0.012, -0.006))]
    inputs = _inputs(scenes)
    plain = {key: value for key, value in inputs.items() if not key.startswith("head_rotation")
             and key != "club_reference"}
    outputs = ["ball_speed", "spin_rate", "spin_axis", "vertical_launch_angle", "club_speed_after"]
    reference = get_model(model)().compute_arrays(plain, outputs)
    for code in (0.0, 1.0, 2.0):
        result = get_model(model)().compute_arrays(dict(inputs, club_reference=np.full(2, code)), outputs)
        for name in outputs:
            np.testing.assert_array_equal(result[name], reference[name])


def test_a_turning_head_moves_its_contact_point_rigidly():
    """v_contact = v_ref + w x (contact - reference) for each reference point, w in the head's axes."""
    rotation = (20.0, 35.0, -10.0)  # rad/s about toe, up, target
    toe, high = 0.012, -0.005
    for reference in ("centre_of_mass", "face_centre", "contact"):
        state = contact_state(_inputs([_scene(toe, high, rotation=rotation, reference=reference)]))
        # positions from the face centre: the face-centre frame lofted by the dynamic loft (contact definition,
        # so the face centre's loft is turned back by the roll at this strike)
        centre_loft, centre_angle = centre_face(math.radians(12.8), 0.0, toe, high, DRIVER.bulge_radius,
                                                DRIVER.roll_radius)
        heading = _rot_z(-float(centre_angle))
        # the head's axes at impact, by hand: the head frame turned by (face-centre - static) loft about the toe
        # line, and by the face centre's face angle about the vertical
        turn = heading @ _rot_y(-(float(centre_loft) - DRIVER.loft))
        axes = np.column_stack([turn @ [0.0, -1.0, 0.0], turn @ [0.0, 0.0, 1.0], turn @ [1.0, 0.0, 0.0]])
        omega = axes @ np.array(rotation)
        frame = heading @ _rot_y(-float(centre_loft))
        t_axis, u_axis, n_axis = frame @ [0.0, -1.0, 0.0], frame @ [0.0, 0.0, 1.0], frame @ [1.0, 0.0, 0.0]
        cg_toe, cg_high, cg_depth = DRIVER.center_of_mass
        cg = cg_toe * t_axis + cg_high * u_axis - cg_depth * n_axis
        a, b = toe / DRIVER.bulge_radius, high / DRIVER.roll_radius
        contact = toe * t_axis + high * u_axis - 0.5 * (toe * a + high * b) * n_axis
        ref = {"centre_of_mass": cg, "face_centre": np.zeros(3), "contact": contact}[reference]
        v_ref = 51.4 * np.array([math.cos(math.radians(-0.9)), 0.0, math.sin(math.radians(-0.9))])
        np.testing.assert_allclose(state["club_velocity"][0], v_ref + np.cross(omega, cg - ref), atol=1e-12)
        np.testing.assert_allclose(state["contact_velocity"][0], v_ref + np.cross(omega, contact - ref), atol=1e-12)
        np.testing.assert_allclose(state["head_spin"][0], omega, atol=1e-12)
        # the relative velocity the models start from: ball at rest minus the head's contact point
        relative = np.einsum("ia,i->a", state["frame"][0], -state["contact_velocity"][0])
        np.testing.assert_allclose(state["initial_velocity"][0], relative, atol=1e-12)
        assert abs(relative[1]) < 1e-12  # the slip direction follows the contact point's own velocity


def test_trackman_face_centre_moves_one_degree_more_upward_for_the_derived_rotation():
    """TrackMan (C. Hahn, Club Data Definitions): the driver's face centre moves about 1 deg more upward than its
    CoG. The rotation about the toe axis that gives it, w = v tan(1 deg)/d (d the CoG's depth), does."""
    speed, depth = 51.4, DRIVER.center_of_mass[2]
    w_toe = speed * math.tan(math.radians(1.0)) / depth  # about 21 rad/s
    state = contact_state(_inputs([_scene(rotation=(w_toe, 0.0, 0.0), attack=0.0, loft=DRIVER.loft * 180 / math.pi,
                                          reference="centre_of_mass")]))
    # the face centre is the contact point here (a centred strike): v_cg + w x (face centre - CoG)
    face_centre_velocity = state["club_velocity"][0] + np.cross(state["head_spin"][0], state["lever"][0])
    np.testing.assert_allclose(face_centre_velocity, state["contact_velocity"][0], atol=1e-12)
    cg_attack = math.degrees(math.atan2(state["club_velocity"][0][2], state["club_velocity"][0][0]))
    face_attack = math.degrees(math.atan2(state["contact_velocity"][0][2], state["contact_velocity"][0][0]))
    assert cg_attack == pytest.approx(0.0, abs=1e-12)
    # the CoG is 1 mm up the face and 42 mm behind at a 9.8 deg loft: the offset is not purely horizontal
    assert face_attack - cg_attack == pytest.approx(1.0, abs=0.1)


@pytest.mark.parametrize("model", ["rigid_coulomb", "maw", "restitution", "hertz_mindlin", "dem_linear"])
def test_a_turning_head_keeps_momentum_and_energy_books(model):
    """With w != 0: linear momentum of ball + head, angular momentum about a fixed point (the head's spin
    I w included) and the kinetic energy lost (the models' energy_loss) balance to round-off."""
    scenes = [_scene(toe, high, rotation=(21.0, 40.0, -8.0), face_angle=1.5) for toe, high in
              ((0.0, 0.0), (0.015, 0.006), (-0.02, -0.008))]
    inputs = _inputs(scenes)
    names = ["normal_impulse", "tangential_impulse", "lateral_impulse"]
    result = get_model(model)().compute_arrays(inputs, names + ["energy_loss"])
    state = contact_state(inputs)
    impulse = impulse_vector(state, *(result[name] for name in names))
    after = after_impact(state, impulse, **inputs)
    m, big_m = inputs["ball_mass"][:, None], inputs["club_mass"][:, None]
    v0, w0 = state["club_velocity"], state["head_spin"]
    np.testing.assert_allclose(m * after["ball_velocity"] + big_m * after["club_velocity"], big_m * v0,
                               rtol=1e-12, atol=1e-12)
    head_inertia = np.linalg.inv(state["head_inverse_inertia"])
    ball_inertia = (inputs["ball_inertia_factor"] * inputs["ball_mass"] * inputs["ball_radius"] ** 2)[:, None]
    origin = np.array([0.1, -0.3, 0.2])
    ball_centre = inputs["ball_radius"][:, None] * state["normal"]
    head_centre = -state["lever"]
    before = big_m * np.cross(head_centre - origin, v0) + np.einsum("nij,nj->ni", head_inertia, w0)
    after_l = (m * np.cross(ball_centre - origin, after["ball_velocity"]) + ball_inertia * after["ball_spin_vector"]
               + big_m * np.cross(head_centre - origin, after["club_velocity"])
               + np.einsum("nij,nj->ni", head_inertia, after["club_spin"]))
    np.testing.assert_allclose(after_l, before, atol=1e-12 * np.abs(before).max())

    def kinetic(v, w):
        return 0.5 * big_m[:, 0] * np.sum(v * v, -1) + 0.5 * np.einsum("ni,nij,nj->n", w, head_inertia, w)

    ball_energy = (0.5 * m[:, 0] * np.sum(after["ball_velocity"] ** 2, -1)
                   + 0.5 * ball_inertia[:, 0] * np.sum(after["ball_spin_vector"] ** 2, -1))
    lost = kinetic(v0, w0) - kinetic(after["club_velocity"], after["club_spin"]) - ball_energy
    np.testing.assert_allclose(result["energy_loss"], lost, rtol=1e-9, atol=1e-9)
    assert np.all(lost > 0.0)


def test_head_rotation_from_a_study_with_units_and_needs_a_club():
    delivery = build_delivery({"club_speed": "115 mph", "head_rotation": {"toe": "1200 deg/s", "up": "30 rad/s"}})
    assert delivery.head_rotation == pytest.approx((math.radians(1200.0), 30.0, 0.0))
    with pytest.raises(FieldError) as error:
        build_scene({"ball": {"preset": "urethane_tour"}, "face": {"preset": "steel"},
                     "delivery": {"club_speed": "115 mph", "head_rotation": {"up": "30 rad/s"}}})
    assert error.value.path == "delivery.head_rotation"


# -- spin loft ---------------------------------------------------------------------------------------------------
def _hand_spin_loft(loft, attack, face, path):
    """Angle between the velocity (attack, path) and the normal (loft, face), by vectors [deg in, deg out]."""
    v = np.array([math.cos(math.radians(attack)) * math.cos(math.radians(path)),
                  math.cos(math.radians(attack)) * math.sin(math.radians(path)), math.sin(math.radians(attack))])
    n = np.array([math.cos(math.radians(loft)) * math.cos(math.radians(face)),
                  math.cos(math.radians(loft)) * math.sin(math.radians(face)), math.sin(math.radians(loft))])
    return math.degrees(math.acos(float(v @ n)))


@pytest.mark.parametrize("loft, attack, face, path", [(10.0, -3.0, 0.0, 0.0), (10.0, -3.0, 4.0, 0.0),
                                                      (12.8, -0.9, 3.0, -2.0), (45.0, -5.0, -6.0, 3.0)])
def test_spin_loft_is_the_three_dimensional_angle(loft, attack, face, path):
    delivery = Delivery(50.0, path=math.radians(path), face_angle=math.radians(face),
                        attack_angle=math.radians(attack), dynamic_loft=math.radians(loft))
    expected = _hand_spin_loft(loft, attack, face, path)
    assert math.degrees(delivery.spin_loft) == pytest.approx(expected, abs=1e-10)
    if face == path:  # the 2-D case: loft minus attack
        assert expected == pytest.approx(loft - attack, abs=1e-10)
    else:  # the face-to-path makes it larger than loft minus attack
        assert expected > loft - attack + 0.05
    # and back: the dynamic loft that spin loft needs
    assert math.degrees(float(loft_for_spin_loft(math.radians(expected), math.radians(path), math.radians(face),
                                                 math.radians(attack)))) == pytest.approx(loft, abs=1e-9)


def test_hand_case_ten_degrees_loft_three_down_four_open():
    """10 deg loft, -3 deg attack: 13 deg square; 4 deg face to path: cos S = cos(-3) cos 10 cos 4 + sin(-3) sin 10,
    13.597 deg, close to but not acos(cos 13 cos 4) = 13.591 deg (the face turns about the vertical, not about the
    plane's normal)."""
    square = Delivery(50.0, attack_angle=math.radians(-3.0), dynamic_loft=math.radians(10.0))
    assert math.degrees(square.spin_loft) == pytest.approx(13.0, abs=1e-12)
    open_face = Delivery(50.0, face_angle=math.radians(4.0), attack_angle=math.radians(-3.0),
                         dynamic_loft=math.radians(10.0))
    cos_s = (math.cos(math.radians(-3)) * math.cos(math.radians(10)) * math.cos(math.radians(4))
             + math.sin(math.radians(-3)) * math.sin(math.radians(10)))
    assert math.degrees(open_face.spin_loft) == pytest.approx(math.degrees(math.acos(cos_s)), abs=1e-12)
    assert math.degrees(open_face.spin_loft) == pytest.approx(13.5967, abs=1e-4)
    assert math.degrees(math.acos(math.cos(math.radians(13)) * math.cos(math.radians(4)))) == pytest.approx(
        13.5913, abs=1e-4)


def test_spin_loft_in_a_study_gives_the_dynamic_loft_and_refuses_a_contradiction():
    delivery = build_delivery({"club_speed": "115 mph", "attack_angle": "-0.9 deg", "spin_loft": "14.7 deg",
                               "face_to_path": "3 deg", "path": "-1 deg"})
    assert math.degrees(delivery.spin_loft) == pytest.approx(14.7, abs=1e-9)
    assert math.degrees(delivery.face_angle) == pytest.approx(2.0, abs=1e-12)
    # given with a dynamic loft that agrees (to the 0.2 deg of rounded monitor values): kept
    agreeing = build_delivery({"club_speed": "115 mph", "attack_angle": "-0.9 deg", "dynamic_loft": "12.8 deg",
                               "spin_loft": "13.75 deg"})
    assert math.degrees(agreeing.dynamic_loft) == pytest.approx(12.8)
    with pytest.raises(FieldError) as error:
        build_delivery({"club_speed": "115 mph", "attack_angle": "-0.9 deg", "dynamic_loft": "12.8 deg",
                        "spin_loft": "14.7 deg"})
    assert error.value.path == "delivery.spin_loft"
    assert "13.70 deg" in str(error.value) and "14.70" in str(error.value)
    with pytest.raises(FieldError) as error:  # 5 deg of face to path alone exceeds a 4 deg spin loft
        build_delivery({"club_speed": "115 mph", "spin_loft": "4 deg", "face_to_path": "5 deg"})
    assert error.value.path == "delivery.spin_loft"


def test_trackman_pga_driver_spin_loft_needs_a_face_to_path_of_about_five_degrees():
    """TrackMan's PGA driver averages: 12.8 deg loft, -0.9 deg attack (loft - attack = 13.7) and a 3-D spin loft
    of 14.7 deg. Square, the conversion gives 13.7; the 1 deg difference is a face to path of 5.4 deg (any sign):
    an average over shots whose face-to-path scatters that much carries it."""
    square = Delivery(51.4, attack_angle=math.radians(-0.9), dynamic_loft=math.radians(12.8))
    assert math.degrees(square.spin_loft) == pytest.approx(13.7, abs=1e-9)
    for sign in (1.0, -1.0):
        delivery = Delivery.from_spin_loft(51.4, math.radians(14.7), face_to_path=sign * math.radians(5.37),
                                           attack_angle=math.radians(-0.9))
        assert math.degrees(delivery.dynamic_loft) == pytest.approx(12.8, abs=0.05)


# -- presets as labelled sweep dimensions -------------------------------------------------------------------------
def test_ball_and_club_presets_sweep_as_labelled_dimensions(monkeypatch):
    """sweep: {ball.preset: [...], club.preset: [...]} gives string-labelled dimensions ``ball`` and ``club`` whose
    every case equals the study run with those presets named outright, each ball with its own restitution law."""
    import attrs

    import impactlab
    from impactlab.scene.materials import BALL_PRESETS, RestitutionLaw

    ionomer = attrs.evolve(BALL_PRESETS["two_piece_ionomer"], restitution=RestitutionLaw("constant", value=0.75))
    monkeypatch.setitem(BALL_PRESETS, "two_piece_ionomer", ionomer)
    base = {"club": {"preset": "driver"}, "strike": {"toe": "8 mm"},
            "delivery": {"club_speed": "100 mph", "attack_angle": "-2 deg", "dynamic_loft": "20 deg",
                         "loft_at": "contact"},
            "models": ["rigid_coulomb"], "outputs": ["spin_rate", "ball_speed", "spin_axis"]}
    balls, clubs = ["urethane_tour", "two_piece_ionomer"], ["driver", "7_iron"]
    swept = impactlab.run_study(impactlab.load_study(
        dict(base, ball={"preset": "urethane_tour"}, sweep={"ball.preset": balls, "club.preset": clubs})))
    assert list(swept.ball.values) == balls and list(swept.club.values) == clubs
    assert swept.spin_rate.dims == ("model", "ball", "club")
    for ball in balls:
        for club in clubs:
            alone = impactlab.run_study(impactlab.load_study(
                dict(base, ball={"preset": ball}, club={"preset": club})))
            for name in ("spin_rate", "ball_speed", "spin_axis"):
                np.testing.assert_allclose(swept[name].sel(ball=ball, club=club).values, alone[name].values.ravel(),
                                           rtol=1e-12, atol=1e-12)
    # the balls differ in e: their ball speeds do
    speeds = swept.ball_speed.sel(club="driver").values.ravel()
    assert speeds[0] > speeds[1] + 0.5
    with pytest.raises(FieldError) as error:
        impactlab.load_study(dict(base, ball={"preset": "urethane_tour"}, sweep={"ball.preset": ["urethane_tour",
                                                                                               "rubber"]}))
    assert error.value.path.startswith("sweep.ball.preset[1]")


def test_shot_tables_take_spin_loft_and_face_to_path_columns():
    """A TrackMan export's Spin Loft and Face To Path give the dynamic loft and face angle a row leaves out; given
    beside them they must agree, else the row is refused with its line."""
    from impactlab.data.sessions.shots import read_csv
    from impactlab.errors import StudyError

    header = ("Club,Club Speed [mph],Attack Angle [deg],Club Path [deg],Face To Path [deg],Spin Loft [deg],"
              "Dyn. Loft [deg],Spin Rate [rpm]\n")
    table = read_csv(header + "driver,115,-0.9,-2,3,14.7,,2545\n", "s.csv")
    loft, face = table.delivery["dynamic_loft"][0], table.delivery["face_angle"][0]
    assert math.degrees(face) == pytest.approx(1.0, abs=1e-12)
    assert _hand_spin_loft(math.degrees(loft), -0.9, 1.0, -2.0) == pytest.approx(14.7, abs=1e-9)
    with pytest.raises(StudyError, match=r"s.csv:2: spin_loft: expected the spin loft the row's angles make "
                                         r"\(14.0[0-9] deg"):
        read_csv(header + "driver,115,-0.9,-2,3,14.7,12.8,2545\n", "s.csv")


def test_head_rotation_sweeps_and_needs_a_club_in_a_sweep_too():
    import impactlab

    base = {"ball": {"preset": "urethane_tour"}, "delivery": {"club_speed": "100 mph", "dynamic_loft": "14 deg"},
            "sweep": {"delivery.head_rotation.toe": ["0 deg/s", "1200 deg/s"]}, "models": ["rigid_coulomb"],
            "outputs": ["spin_rate"]}
    with pytest.raises(FieldError) as error:
        impactlab.load_study(dict(base, face={"preset": "steel"}))
    assert error.value.path == "sweep.delivery.head_rotation.toe[1]" and "club" in str(error.value)
    ds = impactlab.run_study(impactlab.load_study(dict(base, club={"preset": "driver"})))
    assert list(ds.toe.values) == pytest.approx([0.0, 1200.0])  # the coordinate in deg/s
    spin = ds.spin_rate.values.ravel()
    assert spin[1] < spin[0] - 100.0  # the face moving up faster than the CoG lowers the spin loft at contact


def test_a_left_handed_head_turning_by_the_same_numbers_mirrors_the_right_handed_one():
    scenes = [_scene(0.01, -0.004, rotation=(20.0, 40.0, -8.0), face_angle=2.0, path=-1.0, handedness=hand)
              for hand in ("right", "left")]
    result = get_model("rigid_coulomb")().compute_arrays(_inputs(scenes), ["spin_rate", "spin_axis",
                                                                          "horizontal_launch_angle", "ball_speed"])
    np.testing.assert_allclose(result["spin_rate"][1], result["spin_rate"][0], rtol=1e-12)
    np.testing.assert_allclose(result["ball_speed"][1], result["ball_speed"][0], rtol=1e-12)
    np.testing.assert_allclose(result["spin_axis"][1], -result["spin_axis"][0], rtol=1e-12)
    np.testing.assert_allclose(result["horizontal_launch_angle"][1], -result["horizontal_launch_angle"][0],
                               rtol=1e-12)


def test_a_turning_rate_without_its_unit_is_refused_not_guessed():
    """2000 could be deg/s (a closure rate) or rpm (impactlab's spin): a bare number other than 0 is refused, in
    the block and in a sweep."""
    import impactlab

    with pytest.raises(FieldError) as error:
        build_delivery({"club_speed": "115 mph", "head_rotation": {"up": 2000}})
    assert error.value.path == "delivery.head_rotation.up" and "deg/s" in str(error.value)
    assert build_delivery({"club_speed": "115 mph", "head_rotation": {"up": 0}}).head_rotation == (0.0, 0.0, 0.0)
    with pytest.raises(FieldError) as error:
        impactlab.load_study({"ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
                              "delivery": {"club_speed": "100 mph", "dynamic_loft": "14 deg"},
                              "sweep": {"delivery.head_rotation.up": [0, 1000]}, "models": ["rigid_coulomb"]})
    assert error.value.path == "sweep.delivery.head_rotation.up[1]"


def test_a_left_handers_spin_loft_is_the_mirror_of_a_right_handers():
    """Mirror symmetry: a left-hander's path and face are counted in the golfer's own words, so the angle between
    club velocity and face normal is the right-hander's for the same numbers. Hand-built vectors, y to the
    golfer's right mirrored for the left-hander: both vectors flip their y, their dot product does not."""
    from impactlab.physics.delivery import spin_loft
    from impactlab.scene.core import Delivery

    path, face, attack, loft = map(math.radians, (4.0, -2.0, -1.5, 12.0))

    def unit(horizontal, vertical, sign):
        return np.array([math.cos(vertical) * math.cos(horizontal), sign * math.cos(vertical) * math.sin(horizontal),
                         math.sin(vertical)])

    for sign in (1.0, -1.0):
        expected = math.acos(float(unit(path, attack, sign) @ unit(face, loft, sign)))
        assert float(spin_loft(path, face, attack, loft, sign)) == pytest.approx(expected, abs=1e-12)
    right = Delivery(50.0, path=path, face_angle=face, attack_angle=attack, dynamic_loft=loft, handedness="right")
    left = Delivery(50.0, path=path, face_angle=face, attack_angle=attack, dynamic_loft=loft, handedness="left")
    assert left.spin_loft == pytest.approx(right.spin_loft, abs=1e-12)
    assert math.degrees(right.spin_loft) == pytest.approx(math.degrees(expected), abs=1e-9)
