"""No silent wrong answer and no crash (issue 23): units never guessed, malformed YAML and foreign result files.

Each hostile input a careless or unlucky user might give ends in one clear message and exit code 2 (checked
through ``impactlab.cli.main``, which prints what a user sees), never a number and never a crash.
"""

import json
import math

import numpy as np
import pytest
import xarray as xr

import impactlab
from impactlab.cli import main
from impactlab.errors import FieldError, StudyError
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.core import Delivery, Impact
from impactlab.scene.materials import Ball, Material
from impactlab.units import registry

BASE = {"name": "t", "ball": {"preset": "urethane_tour"}, "face": {"rigid": True},
        "contact": {"friction": 0.4, "restitution": 0.8}, "impact": {"speed": "80 mph", "angle": "15 deg"},
        "models": ["rigid_coulomb"]}


def _refused(document) -> str:
    with pytest.raises(FieldError) as info:
        impactlab.load_study(document)
    return str(info.value)


# --- 1. no unit is guessed -------------------------------------------------------------------------------------

@pytest.mark.parametrize("block, key, value, words, example", [
    ("club", "mass", 200, "a mass", "200 g or 0.2 kg"),
    ("ball", "radius", 21.335, "a length", "21.335 mm or 0.021335 m"),
    ("impact", "speed", 110, "a speed", "110 mph or 49.1744 m/s"),
    ("impact", "angle", 15, "an angle", "15 deg"),
    ("impact", "spin", 3000, "a spin rate", "3000 rpm"),
    ("ball", "youngs_modulus", 136, "a modulus (pressure)", "136 MPa or 1.36e+08 Pa"),
])
def test_a_bare_dimensional_number_is_refused_with_field_quantity_and_example(block, key, value, words, example):
    document = json.loads(json.dumps(BASE))
    if block == "club":
        del document["face"]
        document["club"] = {"preset": "driver"}
    document[block][key] = value
    message = _refused(document)
    assert f"{block}.{key}: expected {words} with its unit, e.g. {example}" in message
    assert "never guessed" in message


def test_a_bare_number_written_as_text_is_refused_too():
    document = {**BASE, "impact": {"speed": "110", "angle": "15 deg"}}
    assert "impact.speed: expected a speed with its unit" in _refused(document)


def test_sweeps_sensitivity_ranges_and_restitution_slopes_want_units():
    assert "sweep.impact.angle.start: expected an angle with its unit" in _refused(
        {**BASE, "sweep": {"impact.angle": {"start": 5, "stop": "10 deg", "num": 3}}})
    assert "sweep.impact.speed[1]: expected a speed with its unit" in _refused(
        {**BASE, "sweep": {"impact.speed": ["80 mph", 90]}})
    ball = {"preset": "urethane_tour", "restitution": {"law": "linear", "value": 0.8, "reference_speed": 40,
                                                       "slope": "-0.002 s/m"}}
    assert "ball.restitution.reference_speed: expected a speed with its unit" in _refused({**BASE, "ball": ball})


@pytest.mark.parametrize("value", [0, 0.0, "0", "-0.0"])
def test_a_bare_zero_is_read_where_zero_is_the_same_in_every_unit(value):
    # 0 mph = 0 m/s, 0 deg = 0 rad, 0 mm = 0 in: an exact zero needs no unit, so none is guessed
    from impactlab.units import to_si

    for dimension in ("length", "mass", "pressure", "speed", "angle", "angular_speed", "time", "inertia",
                      "inverse_speed"):
        assert to_si(value, dimension, "x") == 0.0
    study = impactlab.load_study({**BASE, "impact": {"speed": "80 mph", "angle": value, "spin": value}})
    assert study.scene.impact.angle == 0.0 and study.scene.impact.spin == 0.0
    document = {**BASE, "sweep": {"impact.angle": [value, "10 deg"]}}
    assert list(impactlab.load_study(document).sweep[0].fields[0].values) == pytest.approx([0.0, math.radians(10.0)])


@pytest.mark.parametrize("value", [0, "0", 1e-300, "0.0001"])
def test_a_bare_temperature_is_refused_even_zero_and_a_bare_number_near_zero_is_no_zero(value):
    # degC and degF are offset units: a bare 0 could be 273.15 K, 255.37 K or 0 K; any other bare number is refused
    # as before (1e-300 m is not 0)
    from impactlab.units import to_si

    with pytest.raises(FieldError, match=r"t: expected a temperature with its unit, e.g. \S+ degC or \S+ K "
                                         r"\(a bare number's unit is never guessed; not even 0: 0 degC is 273.15 K"):
        to_si(value, "temperature", "t")
    if value not in (0, "0"):
        with pytest.raises(FieldError, match="expected a length with its unit"):
            to_si(value, "length", "x")
    assert to_si("0 degC", "temperature") == pytest.approx(273.15, abs=1e-12)


def test_dimensionless_quantities_stay_bare():
    study = impactlab.load_study({**BASE, "ball": {"preset": "urethane_tour", "inertia_factor": 0.38,
                                                   "poisson_ratio": 0.46},
                                  "contact": {"friction": 0.35, "restitution": 0.75}})
    assert study.scene.ball.inertia_factor == 0.38 and study.scene.contact.friction == 0.35


def test_cli_exits_2_with_the_unit_message(tmp_path, capsys):
    path = tmp_path / "s.yaml"
    path.write_text("name: s\nball: {preset: urethane_tour}\nclub: {preset: driver, mass: 200}\n"
                    "delivery: {club_speed: 115 mph}\nmodels: [rigid_coulomb]\n")
    assert main(["run", str(path), "-o", str(tmp_path / "r.h5"), "-q"]) == 2
    err = capsys.readouterr().err
    assert f"{path}:3: club.mass: expected a mass with its unit, e.g. 200 g or 0.2 kg" in err
    assert "Traceback" not in err and not (tmp_path / "r.h5").exists()


def test_value_objects_take_si_numbers_strings_with_units_and_pint_quantities():
    ureg = registry()
    assert Ball(radius="21.335 mm", mass=ureg.Quantity(45.93, "g")) == Ball(radius=0.021335, mass=0.04593)
    assert Delivery(club_speed="100 mph", attack_angle="-2 deg").club_speed == pytest.approx(44.704)
    assert Delivery(club_speed=44.704, attack_angle=math.radians(-2.0)) == \
        Delivery(club_speed="100 mph", attack_angle="-2 deg")
    assert Impact(speed="80 mph", angle="15 deg", spin="3000 rpm").spin == pytest.approx(100.0 * math.pi)
    assert Strike(toe="8 mm").toe == pytest.approx(0.008)
    assert Material(youngs_modulus="136 MPa", poisson_ratio=0.45).youngs_modulus == pytest.approx(136e6)
    head = ClubHead(mass="204 g", inertia=(3e-4, 5e-4, 4e-4), center_of_mass=(0.0, 0.0, 0.04), loft="10 deg")
    assert head.mass == pytest.approx(0.204) and head.loft == pytest.approx(math.radians(10.0))
    with pytest.raises(FieldError, match="with its unit"):
        Delivery(club_speed="115")  # text without a unit: not guessed in Python either
    with pytest.raises(FieldError, match="not an angle unit"):
        Delivery(club_speed="100 mph", attack_angle="3 m")


# --- 3. malformed documents ----------------------------------------------------------------------------------

@pytest.mark.parametrize("text", ["[" * 50_000 + "]" * 50_000, "- " * 50_000 + "x",
                                  "{a: " * 50_000 + "1" + "}" * 50_000,
                                  "".join(" " * i + "a:\n" for i in range(150)) + " " * 150 + "b: 1\n"])
def test_yaml_nested_50000_deep_is_refused_before_the_parser_can_crash(tmp_path, capsys, text):
    # before the depth scan, the first three killed the process with a segmentation fault in libyaml's composer
    path = tmp_path / "deep.yaml"
    path.write_text(text)
    assert main(["run", str(path), "-q"]) == 2
    err = capsys.readouterr().err
    assert "nests more than 100 levels deep" in err and "Traceback" not in err


def test_the_depth_scan_is_never_below_the_real_depth_and_lets_studies_through():
    from impactlab.study.yaml_lines import nesting_depth
    assert nesting_depth("a:\n  b:\n    c: [1, [2, {x: 3}]]\n")[0] >= 5
    assert nesting_depth("- - - x\n")[0] >= 3
    # brackets in quoted or plain text do not count
    assert nesting_depth('title: "[[[[[[[[[[[[[["\nname: x[[[[[[\n')[0] <= 2
    from pathlib import Path
    for study in Path(__file__).resolve().parents[1].glob("studies/**/*.yaml"):
        assert nesting_depth(study.read_text()) == (nesting_depth(study.read_text())[0], 0)


# --- 3. foreign result files -----------------------------------------------------------------------------------

@pytest.fixture(scope="module")
def result_file(tmp_path_factory):
    folder = tmp_path_factory.mktemp("result")
    path = folder / "r.h5"
    study = folder / "s.yaml"
    study.write_text("name: s\nball: {preset: urethane_tour}\nface: {rigid: true}\n"
                     "contact: {friction: 0.4, restitution: 0.8}\nimpact: {speed: 80 mph, angle: 15 deg}\n"
                     "sweep: {impact.angle: [10 deg, 20 deg]}\nmodels: [rigid_coulomb]\n")
    assert main(["run", str(study), "-o", str(path), "-q"]) == 0
    return path


def _altered(result_file, tmp_path, **attributes):
    dataset = xr.open_dataset(result_file, engine="h5netcdf").load()
    for key, value in attributes.items():
        if value is None:
            dataset.attrs.pop(key, None)
        else:
            dataset.attrs[key] = value
    path = tmp_path / "altered.h5"
    dataset.to_netcdf(path, engine="h5netcdf")
    return path


def _refused_by_every_reader(path, capsys, words):
    for command in (["show", str(path)], ["plot", str(path), "-o", str(path.with_suffix(".png"))],
                    ["export", str(path), "-o", str(path.with_suffix(".json"))]):
        assert main(command) == 2, command
        err = capsys.readouterr().err
        assert words in err and "Traceback" not in err and "please report" not in err, (command, err)


def test_a_result_file_carries_its_format(result_file):
    from impactlab.io.results import RESULT_FORMAT
    assert int(impactlab.open_results(result_file).attrs["impactlab_format"]) == RESULT_FORMAT


def test_hdf5_and_netcdf_files_impactlab_did_not_write(tmp_path, capsys):
    foreign = xr.Dataset({"temperature": ("x", np.arange(3.0))}, attrs={"title": "weather"})
    for name in ("other.h5", "other.nc"):
        foreign.to_netcdf(tmp_path / name, engine="h5netcdf")
        _refused_by_every_reader(tmp_path / name, capsys, "not an impactlab result")
    import h5py
    with h5py.File(tmp_path / "plain.h5", "w") as handle:
        handle["data"] = np.arange(4)
    _refused_by_every_reader(tmp_path / "plain.h5", capsys, "not an impactlab result")


def test_a_file_from_a_newer_format(result_file, tmp_path, capsys):
    _refused_by_every_reader(_altered(result_file, tmp_path, impactlab_format=99, impactlab_version="9.0"), capsys,
                             "written by a newer impactlab (9.0, result format 99)")


@pytest.mark.parametrize("attributes, words", [
    ({"models": "not json"}, "its 'models' attribute is not the JSON list of models"),
    ({"models": json.dumps({"id": "x"})}, "its 'models' attribute is not the JSON list of models"),
    ({"plots": "[{"}, "its 'plots' attribute is not the JSON list"),
    ({"study_type": "sensitivity", "sensitivity": "{}"}, "without its sampler, analyser, salib_version"),
])
def test_result_attributes_of_another_shape(result_file, tmp_path, capsys, attributes, words):
    _refused_by_every_reader(_altered(result_file, tmp_path, **attributes), capsys, words)


def test_open_results_in_python_says_the_same(tmp_path):
    xr.Dataset({"a": ("x", [1.0])}).to_netcdf(tmp_path / "f.h5", engine="h5netcdf")
    with pytest.raises(StudyError, match="not an impactlab result"):
        impactlab.open_results(tmp_path / "f.h5")


# --- 2. plausibility by role -----------------------------------------------------------------------------------

GOLF = {"name": "g", "ball": {"preset": "urethane_tour"}, "club": {"preset": "6_iron"},
        "contact": {"friction": 0.4, "restitution": 0.8},
        "delivery": {"club_speed": "94 mph", "attack_angle": "-3.7 deg", "dynamic_loft": "20.2 deg"},
        "models": ["rigid_coulomb"]}


def _golf(**blocks):
    document = json.loads(json.dumps(GOLF))
    for block, values in blocks.items():
        document[block] = {**document.get(block, {}), **values}
    return document


@pytest.mark.parametrize("blocks, words", [
    # the absurd inputs, each run before and returned numbers
    ({"strike": {"toe": "99 mm"}}, "strike.toe: expected a strike on the club's face between -37.5 and 37.5 mm"),
    ({"strike": {"high": "-30 mm"}}, "strike.high: expected a strike on the club's face between -22.5 and 22.5 mm"),
    ({"club": {"preset": "driver", "center_of_mass": {"depth": "3 m"}}},
     "club.center_of_mass.depth: expected a centre of mass inside the head between 0 and 127 mm"),
    ({"club": {"preset": "driver", "center_of_mass": {"toe": "80 mm", "depth": "40 mm"}}},
     "club.center_of_mass.toe: expected a centre of mass inside the head between -63.5 and 63.5 mm"),
    ({"club": {"preset": "driver", "bulge_radius": "1 mm"}},
     "club.bulge_radius: expected a bulge radius no smaller than half the face's width at least 55 mm"),
    ({"club": {"preset": "driver", "roll_radius": "20 mm"}},
     "club.roll_radius: expected a roll radius no smaller than half the face's height at least 30 mm"),
    ({"delivery": {"attack_angle": "89 deg", "dynamic_loft": "10 deg"}},
     "delivery.attack_angle: expected an attack angle between -30 and 30 deg"),
    ({"delivery": {"club_speed": "1000000 m/s"}}, "delivery.club_speed: expected a club speed between 1 and 200 mph"),
    ({"impact": {"spin": "1e9 rpm"}}, "impact.spin: expected an incoming ball spin between -20000 and 20000 rpm"),
    ({"club": {"preset": "6_iron", "mass": "200 kg"}}, "club.mass: expected a club-head mass between 50 and 1000 g"),
])
def test_values_no_golf_shot_can_have_are_refused_with_range_and_why(blocks, words):
    message = _refused(_golf(**blocks))
    assert words in message and "(" in message.split(words)[1]  # the reason follows the range


def test_the_strike_limit_is_the_clubs_own_face():
    # 40 mm towards the toe is on a driver's face (110 mm wide) and off a 6-iron's (75 mm)
    impactlab.load_study(_golf(club={"preset": "driver"}, strike={"toe": "40 mm"}))
    assert "between -37.5 and 37.5 mm" in _refused(_golf(strike={"toe": "40 mm"}))
    # a user's head of given face size
    head = {"preset": "6_iron", "face_width": "60 mm"}
    assert "between -30 and 30 mm" in _refused(_golf(club=head, strike={"toe": "31 mm"}))


def test_a_refused_sweep_value_is_named_by_its_index():
    document = _golf(sweep={"strike.toe": ["0 mm", "10 mm", "60 mm"]})
    message = _refused(document)
    assert "sweep.strike.toe[2]" in message and "a strike on the club's face" in message


def test_unusual_values_are_warned_once_and_computed(recwarn):
    from impactlab.errors import PlausibilityWarning
    document = _golf(delivery={"attack_angle": "-14 deg"}, sweep={"contact.friction": [0.3, 0.4]})
    ds = impactlab.run_study(document)
    assert np.isfinite(ds.ball_speed.values).all()
    ours = [w for w in recwarn.list if issubclass(w.category, PlausibilityWarning)]
    assert len(ours) == 1 and "delivery.attack_angle: -14 deg is unusual for golf" in str(ours[0].message)
    impactlab.load_study(document)  # again: not warned twice in one process
    assert len([w for w in recwarn.list if issubclass(w.category, PlausibilityWarning)]) == 1


def test_general_contact_scenes_keep_their_wide_ranges():
    # a 0.1 m/s sphere-on-plate impact and a 1 m steel sphere on a sphere (Chung & Ooi style): not golf
    from impactlab.scene.core import Contact, Scene
    from impactlab.scene.plausibility import scene_kind
    plate = impactlab.load_study({"name": "p", "ball": {"radius": "0.1 m", "mass": "8 kg", "youngs_modulus": "200 GPa",
                                                        "poisson_ratio": 0.3},
                                  "face": {"rigid": True}, "contact": {"friction": 0.1, "restitution": 0.9},
                                  "impact": {"speed": "0.1 m/s", "angle": "60 deg", "spin": "100000 rpm"},
                                  "models": ["rigid_coulomb"]})
    assert scene_kind(plate.scene) == "contact"
    sphere = ClubHead.sphere(radius=1.0, mass=30000.0)
    scene = Scene(plate.scene.ball, Scene.face_of(sphere), Contact(friction=0.1, restitution=0.9),
                  Impact(speed="0.2 m/s", angle="30 deg", spin="100000 rpm"), club=sphere)
    assert scene_kind(scene) == "contact"  # the sphere's "CG" 1 m behind its face and its 1 m "bulge" are fine


def test_measured_magnitudes_below_zero_are_refused(tmp_path):
    from impactlab.data.sessions.shots import read_csv
    text = ("label,club,Club Speed [mph],Attack Angle [deg],Dynamic Loft [deg],Ball Speed [mph],Spin Rate [rpm]\n"
            "a,driver,110,-1,12,-160,2500\nb,driver,110,-1,12,160,-2500\n")
    with pytest.raises(StudyError) as info:
        read_csv(text, file="t.csv")
    message = str(info.value)
    # a session's rows are skipped with the reason (issue 32), and with no row left the file is refused naming both
    assert "t.csv:2: Ball Speed [mph] below 0 (a magnitude)" in message
    assert "t.csv:3: Spin Rate [rpm] below 0 (a magnitude)" in message
