"""Golf delivery geometry (physics brief 7): signs, symmetry, and agreement with the 2-D impact."""

import numpy as np
import pytest

import impactlab
from impactlab.errors import FieldError

GOLF = ["spin_loft", "vertical_launch_angle", "horizontal_launch_angle", "vertical_launch_ratio",
        "horizontal_launch_ratio", "spin_axis", "launch_ratio", "spin_rate", "ball_speed"]


def deliveries(**sweep):
    base = {"ball": {"preset": "urethane_tour"}, "face": {"rigid": True}, "contact": {"friction": 0.4,
            "restitution": 0.8}, "delivery": {"club_speed": "95 mph", "path": "0 deg", "face_angle": "0 deg",
                                              "attack_angle": "-3 deg", "dynamic_loft": "14 deg"},
            "sweep": {field: [f"{value} deg" for value in values] for field, values in sweep.items()},
            "models": ["maw", "rigid_coulomb", "restitution"], "outputs": GOLF}
    return base


@pytest.mark.slow
def test_square_delivery_stays_on_the_target_line():
    ds = impactlab.run_study(deliveries(**{"delivery.dynamic_loft": [10, 20, 30]}))
    np.testing.assert_allclose(ds.horizontal_launch_angle, 0.0, atol=1e-9)
    np.testing.assert_allclose(ds.spin_axis, 0.0, atol=1e-9)
    np.testing.assert_allclose(ds.spin_loft.sel(model="maw"), ds.dynamic_loft + 3.0, rtol=1e-12)
    # in the vertical plane the vertical launch ratio is the 2-D launch ratio
    np.testing.assert_allclose(ds.vertical_launch_ratio, ds.launch_ratio, rtol=1e-10)
    assert np.all(ds.spin_rate > 0)  # backspin


def test_open_face_to_path_starts_right_and_curves_right_for_a_right_handed_golfer():
    ds = impactlab.run_study(deliveries(**{"delivery.face_angle": [-4.0, 4.0], "delivery.path": [-2.0, 2.0]}))
    open_face = ds.sel(face_angle=4.0, path=-2.0)  # face right of path: a fade/slice
    closed_face = ds.sel(face_angle=-4.0, path=2.0)  # face left of path: a draw/hook
    assert np.all(open_face.horizontal_launch_angle > 0) and np.all(open_face.spin_axis > 0)
    assert np.all(closed_face.horizontal_launch_angle < 0) and np.all(closed_face.spin_axis < 0)
    # the ball starts between path and face, nearer the face
    ratio = ds.horizontal_launch_ratio.sel(face_angle=4.0, path=-2.0)
    assert np.all((ratio > 0.5) & (ratio < 1.0))


def test_mirrored_deliveries_mirror():
    ds = impactlab.run_study(deliveries(**{"delivery.face_angle": [-3.0, 3.0], "delivery.path": [-5.0, 5.0]}))
    a, b = ds.sel(face_angle=3.0, path=-5.0), ds.sel(face_angle=-3.0, path=5.0)
    for name in ("horizontal_launch_angle", "spin_axis"):
        np.testing.assert_allclose(a[name], -b[name], rtol=1e-12, atol=1e-12)
    for name in ("vertical_launch_angle", "spin_rate", "ball_speed", "horizontal_launch_ratio", "spin_loft"):
        np.testing.assert_allclose(a[name], b[name], rtol=1e-12)


def test_zero_face_to_path_gives_no_horizontal_offset():
    # face = path: n and v share their azimuth, so the impact plane is vertical and holds the launch
    both = impactlab.run_study(deliveries(**{"delivery.path": [-4.0, 3.0], "delivery.face_angle": [-4.0, 3.0]}))
    for path in (-4.0, 3.0):
        case = both.sel(path=path, face_angle=path)
        np.testing.assert_allclose(case.spin_axis, 0.0, atol=1e-9)
        np.testing.assert_allclose(case.horizontal_launch_angle, path, atol=1e-9)


def test_left_handed_golfer_mirrors_the_right_handed_one():
    right = impactlab.run_study(deliveries(**{"delivery.face_angle": [2.0, 5.0]}))
    left_study = deliveries(**{"delivery.face_angle": [2.0, 5.0]})
    left_study["delivery"] = dict(left_study["delivery"], handedness="left")
    left = impactlab.run_study(left_study)
    for name in ("horizontal_launch_angle", "spin_axis"):
        np.testing.assert_allclose(left[name], -right[name], rtol=1e-12)
    np.testing.assert_allclose(left.horizontal_launch_ratio, right.horizontal_launch_ratio, rtol=1e-12)
    assert np.all(left.horizontal_launch_angle < 0)  # an open face sends a left-hander's ball left


def test_delivery_outputs_without_a_delivery_are_nan_with_a_reason():
    study = {"ball": {"preset": "urethane_tour"}, "face": {"rigid": True}, "contact": {"friction": 0.4,
             "restitution": 1.0}, "impact": {"speed": "40 m/s", "angle": "20 deg"}, "models": ["rigid_coulomb"],
             "outputs": ["spin_axis", "launch_ratio"]}
    ds = impactlab.run_study(study)
    assert np.isnan(ds.spin_axis.item()) and "needs a golf delivery" in ds.spin_axis.attrs["missing"]
    assert np.isfinite(ds.launch_ratio.item())


def test_delivery_and_impact_angle_are_exclusive():
    study = deliveries()
    study["impact"] = {"angle": "20 deg"}
    with pytest.raises(FieldError, match="impact.angle: expected either a delivery or impact speed and angle"):
        impactlab.load_study(study)
    study = deliveries()
    study["delivery"] = dict(study["delivery"], handedness="both")
    with pytest.raises(FieldError, match="delivery.handedness.*Choices: right, left"):
        impactlab.load_study(study)
