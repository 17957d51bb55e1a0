"""The CG projection of a club head: the face point whose normal passes through the centre of mass.

Oracles, written independently of :func:`impactlab.physics.delivery.cg_projection`: a flat face's projection by
hand; the defining property (the lever from the centre of mass to the contact point parallel to the contact normal)
checked on the contact geometry the models use (:func:`impactlab.physics.contact.contact_state`); and the rigid-body
consequence (Stronge 2000, ch. 4: a frictionless impulse whose line passes through the centre of mass gives the
body no angular velocity and meets its largest effective mass), on the shipped driver.
"""

import math

import numpy as np
import pytest

import impactlab
from impactlab.physics.contact import contact_state
from impactlab.physics.delivery import cg_projection
from impactlab.scene.catalogue import CLUB_PRESETS, DRIVER_2020
from impactlab.scene.clubs import ClubHead

MM = 1e-3


def test_a_flat_face_projects_the_centre_of_mass_along_its_normal():
    toe, high = cg_projection(1.5 * MM, -2.0 * MM, 30 * MM, math.inf, math.inf)
    assert (float(toe), float(high)) == (1.5 * MM, -2.0 * MM)


def test_a_rolled_face_projects_further_from_the_centre_than_the_centre_of_mass_by_hand():
    # roll R = 254 mm, CG 2.9 mm up and 42.3 mm deep (the driver preset): to first order s = c R / (R - d) =
    # 2.9 x 254 / 211.7 = 3.4795 mm; the sag (s^2 / 2R = 0.024 mm) moves it by under 0.001 mm
    _, high = cg_projection(0.0, 2.9 * MM, 42.3 * MM, math.inf, 0.254)
    assert float(high) == pytest.approx(2.9 * 254 / (254 - 42.3) * MM, abs=1e-6 * MM * 1e3)
    assert float(high) == pytest.approx(3.4795 * MM, abs=0.001 * MM)


def test_the_driver_preset_projects_3_5_mm_up_and_1_2_mm_towards_the_toe():
    # the preset's centre of mass as typed from Proceedings 49 (2020) 47, Table 1, [-42.3, 2.9, 1.0] mm
    assert DRIVER_2020["center"] == (1.0, 2.9, 42.3)
    toe, high = CLUB_PRESETS["driver"].cg_projection
    assert high == pytest.approx(3.48 * MM, abs=0.01 * MM)
    assert toe == pytest.approx(1.0 * 305 / (305 - 42.3) * MM, abs=0.01 * MM)  # bulge 305 mm


@pytest.mark.parametrize("centre", [(1.0, 2.9, 42.3), (-8.0, 6.0, 30.0), (5.0, -10.0, 20.0)])
def test_the_normal_at_the_projection_passes_through_the_centre_of_mass_on_the_models_face(centre):
    c_toe, c_high, c_depth = (c * MM for c in centre)
    s_toe, s_high = cg_projection(c_toe, c_high, c_depth, 0.305, 0.254)
    inputs = {"speed": np.array([50.0]), "dynamic_loft": np.array([math.radians(12.0)]),
              "face_angle": np.array([0.0]), "path": np.array([0.0]), "attack_angle": np.array([0.0]),
              "face_bulge_radius": np.array([0.305]), "face_roll_radius": np.array([0.254]),
              "strike_toe": np.array([float(s_toe)]), "strike_high": np.array([float(s_high)]),
              "club_cg_toe": np.array([c_toe]), "club_cg_high": np.array([c_high]),
              "club_cg_depth": np.array([c_depth]), "club_mass": np.array([0.2]),
              **{f"club_inertia_{a}": np.array([3e-4]) for a in ("toe", "up", "target")},
              **{f"club_inertia_{a}": np.array([0.0]) for a in ("toe_up", "toe_target", "up_target")},
              "ball_mass": np.array([0.04593]), "ball_radius": np.array([0.021335]),
              "ball_inertia_factor": np.array([0.4])}
    state = contact_state(inputs)
    lever, normal = state["lever"][0], state["normal"][0]
    assert np.linalg.norm(lever) > 15 * MM  # the head is a rigid body here, not a point mass
    assert np.linalg.norm(np.cross(lever, normal)) < 1e-9 * np.linalg.norm(lever)
    # and a strike 1 mm higher does not: the oracle can fail
    inputs["strike_high"] = inputs["strike_high"] + 1 * MM
    moved = contact_state(inputs)
    assert np.linalg.norm(np.cross(moved["lever"][0], moved["normal"][0])) > 0.5 * MM  # (R - d)/R of 1 mm on the roll


def _frictionless_strikes(highs_mm, toes_mm):
    document = {"ball": {"preset": "urethane_tour"}, "club": {"preset": "driver"},
                "contact": {"friction": 0.0, "restitution": 0.8},
                "delivery": {"club_speed": "115 mph", "attack_angle": "0 deg", "dynamic_loft": "12 deg",
                             "loft_at": "contact"},
                "strike": {"toe": f"{toes_mm[0]} mm", "high": f"{highs_mm[0]} mm"},
                "sweep": {"strike.high": [f"{h} mm" for h in highs_mm], "strike.toe": [f"{t} mm" for t in toes_mm]},
                "models": ["rigid_coulomb"], "outputs": ["ball_speed", "club_angular_velocity", "spin_rate"]}
    ds = impactlab.run_study(impactlab.load_study(document))
    return ds.sel(model="rigid_coulomb")


def test_a_frictionless_strike_at_the_projection_leaves_the_head_unturned_and_meets_its_largest_effective_mass():
    toe, high = (v / MM for v in CLUB_PRESETS["driver"].cg_projection)
    ds = _frictionless_strikes([high - 1.0, high, high + 1.0], [toe - 1.0, toe, toe + 1.0])
    turn = ds.club_angular_velocity.transpose("high", "toe").values.squeeze()
    speed = ds.ball_speed.transpose("high", "toe").values.squeeze()
    assert abs(turn[1, 1]) < 1e-6 * np.max(np.abs(turn))  # no turn at the projection, some 1 mm off it
    assert np.all(np.abs(np.delete(turn.ravel(), 4)) > 1e-3 * np.max(np.abs(turn)))
    assert speed[1, 1] == pytest.approx(np.max(speed), rel=1e-12)
    assert np.all(np.delete(speed.ravel(), 4) < speed[1, 1])
    assert np.all(np.abs(ds.spin_rate.values) < 1e-6)  # no friction: no spin in any case


def test_club_head_property_uses_its_own_face():
    flat = ClubHead(mass=0.26, inertia=(8e-5, 2.8e-4, 3.4e-4), center_of_mass=(-2 * MM, -2 * MM, 3.5 * MM))
    assert flat.cg_projection == (-2 * MM, -2 * MM)
