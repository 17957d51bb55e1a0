"""A study's sweep checks build trial scenes that share all but the swept block with the base scene: each shared
block is read once per load (impactlab.study.scene_blocks.reusing_blocks), and nothing is kept past the load."""

import pytest

import impactlab
import impactlab.study.scene_blocks as blocks
from impactlab.errors import FieldError
from impactlab.study.scene_blocks import build_scene, reusing_blocks

STUDY = {
    "name": "two-fields",
    "ball": {"preset": "urethane_tour"},
    "face": {"preset": "steel"},
    "contact": {"friction": 0.4, "restitution": 0.8},
    "impact": {"speed": "80 mph", "angle": "20 deg"},
    "sweep": {"impact.angle": {"start": "1 deg", "stop": "60 deg", "num": 60}, "contact.friction": [0.1, 0.3, 0.5]},
    "models": ["rigid_coulomb"],
}


@pytest.fixture
def counted(monkeypatch):
    calls = {"ball": 0, "impact": 0, "contact": 0}
    for name in calls:
        real = getattr(blocks, f"build_{name}")

        def counting(value, path=name, real=real, name=name):
            calls[name] += 1
            return real(value, path)

        monkeypatch.setattr(blocks, f"build_{name}", counting)
    return calls


def test_a_sweep_reads_each_shared_block_once_and_each_swept_one_per_trial(counted):
    study = impactlab.load_study(STUDY)
    assert study.n_cases == 180
    # the base scene reads all three; the angle's two trials (1 and 60 deg) read a new impact each, the friction's
    # two (0.1 and 0.5) a new contact each; the ball is read once, not five times
    assert counted == {"ball": 1, "impact": 3, "contact": 3}


def test_a_bad_swept_value_is_refused_with_the_blocks_shared():
    bad = dict(STUDY, sweep={"impact.angle": ["10 deg", "95 deg"], "contact.friction": [0.1, -0.2]})
    with pytest.raises(FieldError, match=r"sweep.impact.angle\[1\]: expected .* \(for impact.angle\)"):
        impactlab.load_study(bad)
    bad = dict(STUDY, sweep={"contact.friction": [0.1, -0.2]})
    with pytest.raises(FieldError, match=r"sweep.contact.friction\[1\]: .*friction coefficient >= 0"):
        impactlab.load_study(bad)


def test_nothing_is_reused_outside_a_load_or_across_builders():
    document = {key: value for key, value in STUDY.items() if key != "sweep"}
    document["ball"] = {"preset": "urethane_tour", "mass": "45 g"}
    assert build_scene(document).ball.mass == pytest.approx(0.045)
    document["ball"]["mass"] = "46 g"  # the same object, changed: read again
    assert build_scene(document).ball.mass == pytest.approx(0.046)
    with reusing_blocks():  # an absent face and an absent contact are both None: each builder reads its own
        scene = build_scene({"ball": {"preset": "urethane_tour"}, "impact": {"speed": "40 m/s", "angle": "0 deg"}})
    assert scene.face == blocks.build_face(None) and scene.contact == blocks.build_contact(None)
