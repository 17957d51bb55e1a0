"""GSPro Open Connect export: units, signs and the message layout."""

import json

import numpy as np
import pytest

import impactlab
from impactlab.cli import main
from impactlab.io.interchange import MPH, gspro_shots

STUDY = {
    "name": "gspro",
    "ball": {"preset": "urethane_tour"}, "face": {"preset": "steel", "mass": "200 g"},  # a 7-iron head
    "contact": {"friction": 0.4, "restitution": 0.78},
    "delivery": {"club_speed": "90 mph", "attack_angle": "-4 deg", "dynamic_loft": "24 deg", "path": "0 deg",
                 "face_angle": "0 deg"},
    "sweep": {"delivery.face_angle": ["-3 deg", "0 deg", "3 deg"]},
    "models": ["maw", "rigid_coulomb"],
    "outputs": ["ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis"],
}


@pytest.fixture(scope="module")
def result():
    return impactlab.run_study(impactlab.load_study(STUDY), executor="serial")


def test_every_case_of_every_model_becomes_one_numbered_shot(result):
    shots = gspro_shots(result)
    assert [shot["ShotNumber"] for shot in shots] == list(range(1, 7))
    assert {shot["impactlab"]["model"] for shot in shots} == {"maw", "rigid_coulomb"}
    for shot in shots:
        assert shot["APIversion"] == "1" and shot["ShotDataOptions"]["ContainsBallData"] is True
        assert set(shot["BallData"]) == {"Speed", "SpinAxis", "TotalSpin", "BackSpin", "SideSpin", "HLA", "VLA"}


def test_units_and_spin_components(result):
    shots = gspro_shots(result, model="maw")
    speed = result["ball_speed"].sel(model="maw").values
    for shot, metres_per_second in zip(shots, speed):
        ball = shot["BallData"]
        assert ball["Speed"] == pytest.approx(metres_per_second / MPH, abs=0.01)
        assert 100 < ball["Speed"] < 140  # a 90 mph 7-iron-like strike launches at ~120 mph
        assert np.hypot(ball["BackSpin"], ball["SideSpin"]) == pytest.approx(ball["TotalSpin"], abs=0.2)
        assert np.degrees(np.arctan2(ball["SideSpin"], ball["BackSpin"])) == pytest.approx(ball["SpinAxis"], abs=0.05)


def test_an_open_face_starts_right_and_curves_right_a_closed_face_the_mirror(result):
    shots = {shot["impactlab"]["face_angle"]: shot["BallData"] for shot in gspro_shots(result, model="maw")}
    closed, square, opened = shots[-3.0], shots[0.0], shots[3.0]
    assert opened["HLA"] > 0 and opened["SpinAxis"] > 0 and opened["SideSpin"] > 0
    assert closed["HLA"] < 0 and closed["SpinAxis"] < 0 and closed["SideSpin"] < 0
    assert square["HLA"] == pytest.approx(0.0, abs=1e-6) and square["SpinAxis"] == pytest.approx(0.0, abs=1e-6)
    assert opened["HLA"] == pytest.approx(-closed["HLA"], rel=1e-9)
    assert opened["VLA"] == pytest.approx(closed["VLA"], rel=1e-9)


def test_cli_writes_json_and_names_what_a_plain_study_lacks(result, tmp_path, capsys):
    from impactlab.io.results import write_results

    path = tmp_path / "gspro.h5"
    write_results(result, path)
    out = tmp_path / "shots.json"
    assert main(["export", str(path), "-o", str(out), "--model", "rigid_coulomb"]) == 0
    assert len(json.loads(out.read_text())) == 3
    assert main(["export", str(path), "-o", str(out), "--model", "mav"]) != 0
    assert "choices: maw, rigid_coulomb" in capsys.readouterr().err.lower()
    plain = impactlab.run_study(impactlab.load_study({**{k: v for k, v in STUDY.items() if k != "delivery"},
                                                      "impact": {"speed": "40 m/s", "angle": "20 deg"},
                                                      "sweep": {"impact.angle": ["10 deg", "20 deg"]},
                                                      "outputs": ["launch_angle"]}), executor="serial")
    write_results(plain, tmp_path / "plain.h5")
    assert main(["export", str(tmp_path / "plain.h5"), "-o", str(tmp_path / "x.json")]) != 0
    assert "lacks ball_speed" in capsys.readouterr().err
    assert not (tmp_path / "x.json").exists()


def test_each_shot_carries_the_club_data_of_its_delivery(result):
    """ClubData in GSPro's units (mph, deg) from the study's delivery: 90 mph, -4 deg attack, 24 deg loft."""
    for shot in gspro_shots(result):
        face = shot["impactlab"]["face_angle"]  # the swept coordinate, in deg
        assert shot["ClubData"] == {"Speed": 90.0, "AngleOfAttack": -4.0, "FaceToTarget": face, "Loft": 24.0,
                                    "Path": 0.0}
        assert shot["ShotDataOptions"] == {"ContainsBallData": True, "ContainsClubData": True,
                                           "LaunchMonitorIsReady": True, "LaunchMonitorBallDetected": True,
                                           "IsHeartBeat": False}
