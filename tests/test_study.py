"""Study files: the documented shape, sweeps, presets, and one clear message for every bad input."""

import textwrap

import numpy as np
import pytest

import impactlab
from impactlab.errors import FieldError, ModelInputError, StudyError

ISSUE_EXAMPLE = textwrap.dedent("""\
    name: friction-sweep
    ball: {radius: 21.335 mm, mass: 45.93 g, inertia_factor: 0.4, youngs_modulus: 136 MPa, poisson_ratio: 0.45}
    face: {rigid: true}                 # or youngs_modulus + poisson_ratio; optional mass: 200 g
    contact: {friction: 0.4, restitution: 1.0}
    impact: {speed: 80 mph, angle: 15 deg, spin: 0 rpm}
    sweep:                              # keys are dotted paths into the fields above
      impact.angle: {start: 1 deg, stop: 60 deg, num: 60}
      contact.friction: [0.15, 0.25, 0.35]
    models:
      - name: maw
      - name: rigid_coulomb
      - name: restitution
        tangential_restitution: 0.1     # model options sit beside the name
    outputs: [launch_angle, launch_ratio, rebound_angle, spin_rate, ball_speed]
    """)

MINIMAL = {"ball": {"preset": "urethane_tour"}, "face": {"rigid": True}, "contact": {"friction": 0.4,
           "restitution": 1.0}, "impact": {"speed": "80 mph", "angle": "15 deg"}, "models": ["maw"]}


@pytest.fixture(scope="module")
def example_result():
    return impactlab.run_study(ISSUE_EXAMPLE)


def test_issue_example_runs_with_the_promised_dimensions(example_result):
    ds = example_result
    assert dict(ds.sizes) == {"model": 3, "angle": 60, "friction": 3}
    assert list(ds.model.values) == ["maw", "rigid_coulomb", "restitution"]
    assert ds.angle.attrs["units"] == "degree" and ds.angle.values[0] == pytest.approx(1.0)
    assert ds.friction.values.tolist() == [0.15, 0.25, 0.35]
    assert list(ds.data_vars) == ["launch_angle", "launch_ratio", "rebound_angle", "spin_rate", "ball_speed",
                                  "steps", "energy_error", "validity"]  # the stability report comes with every result
    assert ds.launch_angle.attrs["units"] == "degree" and ds.spin_rate.attrs["units"] == "rpm"
    assert ds.launch_angle.dims == ("model", "angle", "friction")
    assert np.all(np.isfinite(ds.launch_ratio.values))


def test_results_carry_provenance(example_result):
    attrs = example_result.attrs
    assert attrs["study_name"] == "friction-sweep"
    assert "tangential_restitution: 0.1" in attrs["study_source"]
    assert attrs["impactlab_version"] == impactlab.__version__
    assert '"tangential_restitution": 0.1' in attrs["models"]
    assert '"tolerance": 0.0001' in attrs["models"]  # resolved defaults are recorded, not just what was written
    assert "maw" in attrs["plan"]


def test_sweep_matches_single_scene_runs(example_result):
    single = impactlab.run_study({**MINIMAL, "ball": {"radius": "21.335 mm", "mass": "45.93 g", "inertia_factor": 0.4,
                                                      "youngs_modulus": "136 MPa", "poisson_ratio": 0.45},
                                  "contact": {"friction": 0.25, "restitution": 1.0},
                                  "impact": {"speed": "80 mph", "angle": "30 deg"},
                                  "models": ["maw", "rigid_coulomb"], "outputs": ["launch_ratio"]})
    swept = example_result.launch_ratio.sel(angle=30.0, friction=0.25)
    assert single.launch_ratio.sel(model="maw").item() == pytest.approx(swept.sel(model="maw").item(), rel=1e-12)
    assert single.launch_ratio.sel(model="rigid_coulomb").item() == pytest.approx(
        swept.sel(model="rigid_coulomb").item(), rel=1e-12)


def test_missing_outputs_are_nan_and_say_why():
    ds = impactlab.run_study({**MINIMAL, "models": ["maw", "rigid_coulomb"], "outputs": ["contact_time"]})
    assert np.isnan(ds.contact_time.sel(model="rigid_coulomb").item())
    assert np.isfinite(ds.contact_time.sel(model="maw").item())
    assert "rigid_coulomb: a rigid-body impulse model has no contact duration" in ds.contact_time.attrs["missing"]


def test_histories_share_a_time_axis_padded_with_nan():
    from impactlab.model.diagnostics import ValidityWarning

    with pytest.warns(ValidityWarning, match="maw: in 2 of 2 case.s. the contact radius exceeds 0.3 R"):
        ds = impactlab.run_study({**MINIMAL, "sweep": {"impact.speed": ["20 m/s", "60 m/s"]},
                                  "models": ["maw", "rigid_coulomb"], "outputs": ["normal_force", "contact_time"]})
    assert ds.normal_force.dims == ("model", "speed", "time")
    assert ds.time.attrs["units"] == "s"
    fast = ds.normal_force.sel(model="maw", speed=60.0)
    assert np.isnan(fast.values[-1])  # the faster impact ends sooner
    assert np.all(np.isnan(ds.normal_force.sel(model="rigid_coulomb").values))


def test_presets_and_overrides():
    study = impactlab.load_study({**MINIMAL, "ball": {"preset": "surlyn_distance", "mass": "45 g"},
                                  "face": {"preset": "titanium", "mass": "200 g"}})
    assert study.scene.ball.mass == pytest.approx(0.045)
    assert study.scene.ball.material.youngs_modulus == impactlab.BALL_PRESETS["surlyn_distance"].material.youngs_modulus
    assert study.scene.face.mass == pytest.approx(0.2)
    assert study.scene.face.material.name == "Ti-6Al-4V"


def test_dimension_names_clash_falls_back_to_full_paths():
    study = impactlab.load_study({**MINIMAL, "sweep": {"ball.mass": ["40 g", "46 g"], "face.mass": ["0.2 kg", "1 kg"]}})
    assert [axis.dim for axis in study.sweep] == ["ball_mass", "face_mass"]


def test_rigid_models_need_no_elastic_moduli():
    ds = impactlab.run_study({"ball": {"radius": "21 mm", "mass": "46 g"}, "contact": {"friction": 0.3,
                              "restitution": 0.8}, "impact": {"speed": "40 m/s", "angle": "20 deg"},
                              "models": ["rigid_coulomb", "restitution"]})
    assert np.all(np.isfinite(ds.launch_angle.values))


def test_a_model_missing_an_input_is_refused_naming_model_and_input():
    study = {"ball": {"radius": "21 mm", "mass": "46 g"}, "contact": {"friction": 0.3, "restitution": 0.8},
             "impact": {"speed": "40 m/s", "angle": "20 deg"}, "models": ["rigid_coulomb", "maw"]}
    with pytest.raises(ModelInputError, match=r"model 'maw' needs ball.poisson_ratio .*ball.youngs_modulus"):
        impactlab.run_study(study)


BAD = [
    # (change to the YAML text, line, expected message fragments)
    (("radius: 21.335 mm", "raduis: 21.335 mm"), 2, ["ball.raduis", "Choices:", "did you mean 'radius'"]),
    (("radius: 21.335 mm", "radius: -21.335 mm"), 2, ["ball.radius", "positive", "got -21.335 mm"]),
    (("poisson_ratio: 0.45", "poisson_ratio: 0.7"), 2, ["ball.poisson_ratio", "-1 < nu <= 0.5", "got 0.7"]),
    (("- name: rigid_coulomb", "- name: rigid_colomb"), 11, ["models[1].name", "registered model",
                                                             "did you mean 'rigid_coulomb'"]),
    (("rebound_angle,", "rebound_angel,"), 14, ["outputs[2]", "got rebound_angel", "did you mean 'rebound_angle'"]),
    (("speed: 80 mph", "speed: 80 kg"), 5, ["impact.speed", "a speed", "got 80 kg"]),
    (("tangential_restitution: 0.1", "tangential_restitution: 1.5"), 13,
     ["models[2].tangential_restitution", "-1 <= beta <= 1", "got 1.5"]),
    (("tangential_restitution: 0.1", "tangental_restitution: 0.1"), 13,
     ["models[2].tangental_restitution", "did you mean 'tangential_restitution'"]),
    (("contact.friction: [0.15, 0.25, 0.35]", "contact.friction: [0.15, -0.25]"), 8,
     ["sweep.contact.friction[1]", "friction coefficient >= 0", "got -0.25"]),
    (("impact.angle: {", "impact.angel: {"), 7, ["sweep.impact.angel", "did you mean 'impact.angle'"]),
    (("num: 60", "num: 6.5"), 7, ["sweep.impact.angle.num", "whole number"]),
    (("face: {rigid: true}", "face: {rigid: true, youngs_modulus: 200 GPa, poisson_ratio: 0.3}"), 3,
     ["face.rigid", "not both"]),
    (("face: {rigid: true}", "face: {youngs_modulus: 200 GPa}"), 3, ["face.poisson_ratio", "together"]),
    (("name: friction-sweep", "name: friction-sweep\ncolour: red"), 2, ["colour", "Choices: name"]),
]


def assert_one_clear_message(study: str, change: tuple[str, str], line: int, fragments: list[str]) -> None:
    """``study`` with ``change`` made is refused with one message at ``line`` holding every fragment."""
    text = study.replace(*change)
    assert text != study
    with pytest.raises(FieldError) as info:
        impactlab.load_study(text, file="study.yaml")
    message = str(info.value)
    assert message.startswith(f"study.yaml:{line}: "), message
    for fragment in fragments:
        assert fragment in message, message


@pytest.mark.parametrize("change, line, fragments", BAD, ids=[case[0][1][:30] for case in BAD])
def test_bad_study_gives_one_clear_message(change, line, fragments):
    assert_one_clear_message(ISSUE_EXAMPLE, change, line, fragments)


def test_yaml_syntax_and_duplicate_keys_are_reported_with_line():
    with pytest.raises(StudyError, match=r"study.yaml:3: not valid YAML: .*flow mapping on line 2"):
        impactlab.load_study("name: x\nball: {radius: 1 mm, mass: 45 g\nimpact: {speed: 1}\n", file="study.yaml")
    with pytest.raises(StudyError, match=r"study.yaml:2: models: key given twice"):
        impactlab.load_study("models: [maw]\nmodels: [maw]\n", file="study.yaml")


def test_same_model_twice_needs_an_id():
    with pytest.raises(FieldError, match="give repeated models an id"):
        impactlab.load_study({**MINIMAL, "models": ["maw", "maw"]})
    study = impactlab.load_study({**MINIMAL, "models": ["maw", {"name": "maw", "id": "maw_coarse", "springs": 20}]})
    ds = impactlab.run_study(study)
    assert list(ds.model.values) == ["maw", "maw_coarse"]


def test_missing_study_file_is_a_clear_error(tmp_path):
    with pytest.raises(StudyError, match="no such study file"):
        impactlab.load_study(tmp_path / "absent.yaml")


GROUPED = {**MINIMAL, "face": {"preset": "steel"}, "impact": None,
           "delivery": {"club_speed": "90 mph", "attack_angle": "-4 deg", "dynamic_loft": "24 deg"},
           "sweep": {"club": {"labels": ["driver", "7-iron", "pitching wedge"],
                              "delivery.club_speed": ["112 mph", "90 mph", "83 mph"],
                              "delivery.dynamic_loft": ["13 deg", "24 deg", "33 deg"]},
                     "contact.friction": [0.3, 0.4]},
           "models": ["maw", "rigid_coulomb"], "outputs": ["vertical_launch_ratio", "spin_loft"]}


def test_fields_swept_together_share_one_labelled_dimension(tmp_path):
    study = {key: value for key, value in GROUPED.items() if value is not None}
    ds = impactlab.run_study(study)
    assert dict(ds.sizes) == {"model": 2, "club": 3, "friction": 2}
    assert list(ds.club.values) == ["driver", "7-iron", "pitching wedge"]
    assert ds.dynamic_loft.dims == ("club",) and ds.dynamic_loft.values.tolist() == [13.0, 24.0, 33.0]
    assert ds.club_speed.attrs["units"] == "m/s"
    # each label's fields really went together: spin loft = dynamic loft - attack angle
    np.testing.assert_allclose(ds.spin_loft.sel(model="maw", friction=0.3), ds.dynamic_loft + 4.0, rtol=1e-12)
    from impactlab.io.results import write_results

    back = impactlab.open_results(write_results(ds, tmp_path / "grouped.h5"))
    import xarray as xr

    xr.testing.assert_identical(back, ds)


def test_grouped_sweep_errors_name_the_field():
    study = {key: value for key, value in GROUPED.items() if value is not None}
    bad = {**study, "sweep": {"club": {"delivery.club_speed": ["1 m/s", "2 m/s"],
                                      "delivery.dynamic_loft": ["10 deg", "20 deg", "30 deg"]}}}
    with pytest.raises(FieldError, match=r"sweep.club: expected lists of one length"):
        impactlab.load_study(bad)
    bad = {**study, "sweep": {"club": {"delivery.club_sped": ["1 m/s", "2 m/s"]}}}
    with pytest.raises(FieldError, match=r"sweep.club.delivery.club_sped: .*did you mean 'delivery.club_speed'"):
        impactlab.load_study(bad)
    bad = {**study, "sweep": {"club": {"delivery.dynamic_loft": ["10 deg", "95 deg"]}}}
    with pytest.raises(FieldError, match=r"sweep.club\[1\]: expected a dynamic loft between -90 and 90 deg"):
        impactlab.load_study(bad)


def test_a_large_sweep_is_validated_with_a_bounded_number_of_scenes(monkeypatch):
    # each field's validity is an interval: its ends and the first value decide, not one scene per value
    import impactlab.study.core as study_module
    import impactlab.study.sweeps as sweeps_module

    built = []
    real = study_module.build_scene
    for module in (study_module, sweeps_module):  # the base scene, and the scenes that check the sweep's values
        monkeypatch.setattr(module, "build_scene", lambda document: built.append(1) or real(document))
    sweep = {"impact.angle": {"start": "1 deg", "stop": "60 deg", "num": 20000}}
    study = impactlab.load_study({**MINIMAL, "sweep": sweep})
    assert study.n_cases == 20000 and len(built) <= 5
    # a bad value anywhere is still reported at its own index, with the field's own message
    values = [f"{angle} deg" for angle in (10, 20, -95, 30, 95)]
    with pytest.raises(FieldError, match=r"sweep.impact.angle\[2\]: expected .* \(for impact.angle\)"):
        impactlab.load_study({**MINIMAL, "sweep": {"impact.angle": values}})
    with pytest.raises(FieldError, match=r"sweep.ball.mass\[1\]"):
        impactlab.load_study({**MINIMAL, "sweep": {"ball.mass": ["40 g", "nan g", "46 g"]}})
