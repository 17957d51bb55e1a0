"""Study blocks structured by cattrs: errors at the key's own line, with the study format's messages;
models given as classes or instances in a Python study."""

import re
import textwrap
from pathlib import Path

import pytest

import impactlab
from impactlab.errors import FieldError
from impactlab.study.core import build_scene
from impactlab.study.schema import BallBlock, ClubBlock, DeliveryBlock, FaceBlock, StrikeBlock, keys_of
from impactlab.study.structuring import structure
from impactlab_models.maw import MawModel
from impactlab_models.rigid_coulomb import RigidCoulombModel
from test_study import assert_one_clear_message

CLUB_STUDY = textwrap.dedent("""\
    name: strike
    ball: {preset: urethane_tour}
    club:
      preset: driver
      inertia: {toe: 2500 g*cm**2, up: 4500 g*cm**2, target: 3000 g*cm**2}
      center_of_mass: {toe: 2 mm, depth: 35 mm}
    strike:
      toe: 5 mm
      high: -2 mm
    delivery: {club_speed: 110 mph, path: 0 deg, face_angle: 0 deg, attack_angle: -1 deg, dynamic_loft: 13 deg}
    models: [rigid_coulomb]
    """)

#: the rest of what a club study may hold, for the wrong-kind sweep below
CLUB_EXTRAS = textwrap.dedent("""\
    contact: {friction: 0.4}
    impact: {spin: 0 rpm}
    outputs: [ball_speed, spin_rate]
    sweep:
      strike.toe: {start: -5 mm, stop: 5 mm, num: 2}
    plots:
      - {name: a, y: ball_speed, x: toe, kind: lines, xlim: [-4, 4], title: t, select: {model: rigid_coulomb}}
    """)

CLUB_BAD = [
    # (change, line, message fragments)
    (("target: 3000", "tagret: 3000"), 5,
     ["club.inertia.tagret: expected a key of club.inertia, got tagret", "Choices: toe, up, target",
      "did you mean 'target'"]),
    (("toe: 5 mm", "toe: 5 deg"), 8, ["strike.toe: expected a length", "deg do not convert to m", "got 5 deg"]),
    (("high: -2 mm", "hihg: -2 mm"), 9, ["strike.hihg", "Choices: toe, high", "did you mean 'high'"]),
    (("depth: 35 mm", "depth: 35 kg"), 6, ["club.center_of_mass.depth: expected a length", "got 35 kg"]),
    (("preset: driver", "preset: driver\n  rigid: 'no'"), 5, ["club.rigid: expected true or false, got no"]),
    (("inertia: {toe: 2500 g*cm**2, up: 4500 g*cm**2, target: 3000 g*cm**2}",
      "inertia: [[0.00025 kg*m**2, 0 kg*m**2, 0 kg*m**2], [0 kg*m**2, 0.00045 kg*m**2, 0 kg*m**2], "
      "[0 kg*m**2, 0 kg*m**2, 3 s]]"), 5,
     ["club.inertia[2][2]: expected a moment of inertia", "got 3 s"]),
    (("inertia: {toe: 2500 g*cm**2, up: 4500 g*cm**2, target: 3000 g*cm**2}",
      "inertia: {principal: 0.0004, axes: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]}"), 5,
     ["club.inertia.principal: expected three principal moments, got 0.0004"]),
    (("strike:\n  toe: 5 mm\n  high: -2 mm", "strike: 5 mm"), 7,
     ["strike: expected a mapping (the impact point on the face) with keys from: toe, high, got 5 mm"]),
]


def test_the_club_study_loads():
    study = impactlab.load_study(CLUB_STUDY)
    assert study.scene.strike.toe == pytest.approx(0.005) and study.scene.strike.high == pytest.approx(-0.002)
    high = impactlab.scene.catalogue.club_preset("driver").center_of_mass[1]  # a key left out keeps the preset's
    assert study.scene.club.center_of_mass == pytest.approx((0.002, high, 0.035))
    assert study.scene.club.inertia[0][0] == pytest.approx(2.5e-4)


@pytest.mark.parametrize("change, line, fragments", CLUB_BAD, ids=[case[0][1][:30] for case in CLUB_BAD])
def test_club_and_strike_errors_name_the_key_at_its_line(change, line, fragments):
    assert_one_clear_message(CLUB_STUDY, change, line, fragments)


def test_unknown_keys_are_reported_before_bad_values():
    # a misspelt key leaves its field absent; the misspelling is the news, not what the absence causes
    with pytest.raises(FieldError, match=r"^ball.raduis: expected a key of ball.*did you mean 'radius'"):
        structure({"raduis": "21 mm", "mass": "4 kg*m"}, BallBlock, "ball")


def test_a_sweep_range_and_a_figure_refuse_unknown_keys_at_their_line():
    text = CLUB_STUDY + "sweep:\n  strike.toe: {start: -5 mm, stop: 5 mm, nmu: 3}\n"
    with pytest.raises(FieldError, match=r"^study.yaml:13: sweep.strike.toe.nmu: .*did you mean 'num'"):
        impactlab.load_study(text, file="study.yaml")
    text = CLUB_STUDY + "plots:\n  - {name: a, y: launch_angle}\n  - {name: b, why: launch_angle}\n"
    with pytest.raises(FieldError, match=r"^study.yaml:14: plots\[1\].why: expected a key of plots\[1\]"):
        impactlab.load_study(text, file="study.yaml")


def test_restitution_law_items_are_located():
    with pytest.raises(FieldError, match=r"^ball.restitution.speeds\[1\]: expected a speed"):
        build_scene({"ball": {"preset": "urethane_tour",
                                        "restitution": {"law": "table", "speeds": ["20 m/s", "3 kg"],
                                                        "values": [0.8, 0.7]}},
                               "impact": {"speed": "40 m/s", "angle": "10 deg"}})


@pytest.mark.parametrize("block, heading", [(BallBlock, "ball"), (FaceBlock, "face"), (ClubBlock, "club"),
                                            (StrikeBlock, "strike"), (DeliveryBlock, "delivery")])
def test_every_key_a_block_accepts_is_documented(block, heading):
    guide = (Path(__file__).parents[1] / "docs" / "user-guide.md").read_text()
    for key in keys_of(block):
        assert re.search(rf"`{key}`|\b{key}:", guide), f"{heading}.{key} is accepted but not in the user guide"


MODELS_STUDY = {"ball": {"preset": "urethane_tour"}, "face": {"rigid": True},
                "contact": {"friction": 0.4, "restitution": 0.8}, "impact": {"speed": "80 mph", "angle": "20 deg"}}


def test_a_python_study_may_name_models_by_class_or_instance():
    models = [MawModel, RigidCoulombModel(), {"name": "maw", "id": "maw_tight", "tolerance": 1e-5},
              {"name": MawModel, "id": "maw_coarse", "springs": 50}, {"name": MawModel(springs=100), "id": "maw_100"}]
    study = impactlab.load_study({**MODELS_STUDY, "models": models})
    assert [entry.id for entry in study.models] == ["maw", "rigid_coulomb", "maw_tight", "maw_coarse", "maw_100"]
    assert study.models[1].model is models[1] and study.models[4].model is models[4]["name"]  # used as given
    assert study.models[3].model.options.springs == 50 and study.models[4].model.options.springs == 100
    # the study text kept as provenance names each model with its options
    assert "name: rigid_coulomb" in study.source and "springs: 100" in study.source
    ds = impactlab.run_study(study)
    assert list(ds.model.values) == ["maw", "rigid_coulomb", "maw_tight", "maw_coarse", "maw_100"]


def test_model_classes_and_instances_are_checked_like_names():
    with pytest.raises(FieldError, match=r"models\[0\].springs"):
        impactlab.load_study({**MODELS_STUDY, "models": [{"name": MawModel, "springs": -1}]})
    with pytest.raises(FieldError, match=r"models\[0\].springs: expected options of a model class or name"):
        impactlab.load_study({**MODELS_STUDY, "models": [{"name": MawModel(), "springs": 50}]})
    with pytest.raises(FieldError, match=r"models\[1\].name: .*give repeated models an id"):
        impactlab.load_study({**MODELS_STUDY, "models": [MawModel(), MawModel]})


@pytest.mark.parametrize("change, message", [
    ({"outputs": [["launch_angle"]]}, r"outputs\[0\]: expected an output name"),
    ({"models": [{"name": ["maw"]}]}, r"models\[0\].name: expected a registered model"),
    ({"plots": [{"y": "launch_angle", "measured": 3}]}, r"plots\[0\].measured: expected a shipped measured dataset"),
    ({"club": {"preset": "driver", "material": ["steel"]}, "face": None}, r"club.material: expected a material"),
])
def test_values_of_the_wrong_kind_are_field_errors_not_crashes(change, message):
    study = {key: value for key, value in {**MODELS_STUDY, "models": ["maw"], **change}.items() if value is not None}
    with pytest.raises(FieldError, match=message):
        impactlab.load_study(study)


def test_a_key_written_without_a_value_counts_as_left_out():
    study = impactlab.load_study("ball: {preset: urethane_tour, friction: }\nface: {rigid: true, preset: }\n"
                                 "impact: {speed: 40 m/s, angle: 10 deg, spin: }\nmodels: [rigid_coulomb]\n")
    assert study.scene.impact.spin == 0.0 and study.scene.face.rigid


def _leaves(node, path=()):
    """Every value's path in a document, and every key's (marked True)."""
    if isinstance(node, dict):
        for key, value in node.items():
            yield path + (key,), True
            yield from _leaves(value, path + (key,))
    elif isinstance(node, list):
        for index, value in enumerate(node):
            yield from _leaves(value, path + (index,))
    else:
        yield path, False


@pytest.mark.parametrize("name", ["club", "paper/inelastic.yaml", "approaches_golf.yaml"])
def test_any_value_of_the_wrong_kind_is_an_error_with_a_path_never_a_crash(name):
    # the check that found four TypeErrors the hand-written parser let through (a list as an output name...)
    import copy

    import yaml

    from impactlab.errors import ImpactLabError

    law = "{preset: urethane_tour, restitution: {law: linear, value: 0.8, reference_speed: 40 m/s, slope: -0.002 s/m}}"
    text = (CLUB_STUDY.replace("{preset: urethane_tour}", law) + CLUB_EXTRAS if name == "club"
            else (Path(__file__).parents[1] / "studies" / name).read_text())
    document = yaml.safe_load(text)
    for path, is_key in _leaves(document):
        if path[0] in ("name", "description", "sensitivity"):
            continue
        for bad in (["x"], {"a": 1}, "x", True) + (("rename",) if is_key else ()):
            changed = copy.deepcopy(document)
            node = changed
            for part in path[:-1]:
                node = node[part]
            if bad == "rename":
                node[f"{path[-1]}x"] = node.pop(path[-1])
            else:
                node[path[-1]] = bad
            try:
                impactlab.load_study(changed)
            except ImpactLabError:
                pass
