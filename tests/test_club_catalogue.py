"""The club catalogue: every club of a set, its published numbers pinned as typed from the sources, launch-monitor
names mapped onto it, and a user's club from a spec sheet."""

import math

import numpy as np
import pytest

from impactlab.cli import main
from impactlab.errors import FieldError
from impactlab.scene.catalogue import CLUB_CATALOGUE, club_from_spec, club_key, user_clubs
from impactlab.study.club_specs import read_club_spec

SET = ("driver", "3_wood", "5_wood", "7_wood", "3_hybrid", "4_hybrid", "5_hybrid", "3_iron", "4_iron", "5_iron",
       "6_iron", "7_iron", "8_iron", "9_iron", "pitching_wedge", "gap_wedge", "sand_wedge", "lob_wedge")


def test_every_club_of_a_set_is_in_the_catalogue_with_its_source():
    assert set(SET) <= set(CLUB_CATALOGUE)
    for key in SET:
        club = CLUB_CATALOGUE[key]
        assert club.source, key
        if key != "driver":  # only the driver head is a measurement; everything else says it is estimated
            assert "estimate" in club.source.lower() or "Estimate" in club.source, key


def test_lofts_are_the_published_standard_lofts():
    # tellmemoregolf.com 'Golf Club Loft Chart' (woods, hybrids, irons, pitching wedge) and golfah.com (gap, sand,
    # lob wedge); the driver: the measured head's 9.8 deg (Proceedings 49 (2020) 47)
    published = {"driver": 9.8, "3_wood": 15, "5_wood": 19, "7_wood": 22, "3_hybrid": 20, "4_hybrid": 23,
                 "5_hybrid": 26, "3_iron": 21, "4_iron": 24, "5_iron": 27, "6_iron": 30, "7_iron": 34, "8_iron": 38,
                 "9_iron": 42, "pitching_wedge": 46, "gap_wedge": 52, "sand_wedge": 56, "lob_wedge": 60}
    for key, loft in published.items():
        assert math.degrees(CLUB_CATALOGUE[key].loft) == pytest.approx(loft, abs=1e-9), key


def test_iron_head_masses_follow_maltbys_standard():
    # R. Maltby: a 5-iron head of about 254 g, 7 g steps through the set (ralphmaltby.com)
    grams = {"3_iron": 240, "4_iron": 247, "5_iron": 254, "6_iron": 261, "7_iron": 268, "8_iron": 275,
             "9_iron": 282, "pitching_wedge": 289}
    for key, mass in grams.items():
        assert CLUB_CATALOGUE[key].mass == pytest.approx(mass * 1e-3, abs=1e-12), key
    # the measured driver head: 204 g (Proceedings 49 (2020) 47, Table 1)
    assert CLUB_CATALOGUE["driver"].mass == pytest.approx(0.204)


def test_iron_lies_span_the_published_set():
    # TaylorMade P7-MB 3-iron to pitching wedge: lie 60.5 to 64 deg (manufacturer specification)
    assert math.degrees(CLUB_CATALOGUE["3_iron"].lie) == pytest.approx(60.5)
    assert math.degrees(CLUB_CATALOGUE["pitching_wedge"].lie) == pytest.approx(64.0)
    lies = [CLUB_CATALOGUE[f"{n}_iron"].lie for n in range(3, 10)]
    assert all(b > a for a, b in zip(lies, lies[1:]))  # longer clubs lie flatter


def test_a_more_lofted_iron_sends_the_ball_off_slower_and_higher():
    # one delivery (40 m/s, level, face at its static loft) through the irons: physics, not numbers from the code:
    # more loft means a smaller normal speed, hence a slower, higher-launched ball with more spin
    from impactlab.data.shots import predict
    from impactlab.model.registry import get_model
    from impactlab.scene.clubs import Strike
    from impactlab.scene.core import Contact, Delivery, Scene
    from impactlab.scene.materials import ball_preset

    keys = [f"{n}_iron" for n in range(3, 10)] + ["pitching_wedge", "gap_wedge", "sand_wedge", "lob_wedge"]
    per_scene = []
    for key in keys:
        club = CLUB_CATALOGUE[key]
        delivery = Delivery(40.0, attack_angle=0.0, dynamic_loft=club.loft)
        scene = Scene.from_delivery(ball_preset("urethane_tour"), Scene.face_of(club), Contact(), delivery, 0.0, club,
                                    Strike())
        per_scene.append(scene.inputs())
    common = set.intersection(*(set(v) for v in per_scene))
    inputs = {k: np.array([v[k] for v in per_scene]) for k in common}
    out = predict(get_model("rigid_coulomb")(), inputs)
    assert np.all(np.diff(out["ball_speed"]) < 0)
    assert np.all(np.diff(out["vertical_launch_angle"]) > 0)
    assert np.all(np.diff(out["spin_rate"]) > 0)


def test_launch_monitor_names_map_onto_the_catalogue():
    names = {"Driver": "driver", "1w": "driver", "Dr": "driver", "3 Wood": "3_wood", "5w": "5_wood",
             "4 Hybrid": "4_hybrid", "3h": "3_hybrid", "8 Iron": "8_iron", "7i": "7_iron", "Eisen 7": "7_iron",
             "PW": "pitching_wedge", "Pitching Wedge": "pitching_wedge", "GW": "gap_wedge", "AW": "gap_wedge",
             "SW": "sand_wedge", "LW": "lob_wedge", "56°": "sand_wedge", "60 Degree": "lob_wedge",
             "52": "gap_wedge", "58": "lob_wedge"}
    for name, key in names.items():
        assert club_key(name) == key, name
    assert club_key("Putter") is None and club_key("12 Iron") is None


SPEC = """name: my driver
names: [Driver, 1w]
source: the maker's spec sheet
loft: 10.5 deg
lie: 58 deg
mass: 203 g
moi: {up: 5200 g cm^2, toe: 2900 g cm^2, target: 4000 g cm^2}
cg: {toe: 0 mm, high: 2 mm, depth: 38 mm}
bulge: 305 mm
roll: 254 mm
face: titanium
restitution_gain: 0.08
"""


def test_a_users_club_from_its_spec_sheet(tmp_path):
    path = tmp_path / "driver.yaml"
    path.write_text(SPEC)
    head, names = read_club_spec(path)
    assert names == ("Driver", "1w")
    assert head.mass == pytest.approx(0.203) and head.loft == pytest.approx(math.radians(10.5))
    assert head.inertia_components()["up"] == pytest.approx(5200e-7) and head.center_of_mass[2] == pytest.approx(0.038)
    with user_clubs([read_club_spec(path)]):
        assert club_key("Driver") == "user_1" and club_key("1W") == "user_1"
    assert club_key("Driver") == "driver"  # put back
    with pytest.raises(FieldError, match=r"driver.yaml:6: club.mass: expected a value with its unit \(e.g. 203 g\)"):
        path.write_text(SPEC.replace("203 g", "203"))
        read_club_spec(path)
    # what a sheet leaves out comes from the catalogue club it names as its base
    head, _ = club_from_spec({"base": "7_iron", "loft": "33 deg", "mass": "270 g"})
    assert head.inertia == CLUB_CATALOGUE["7_iron"].inertia and head.mass == pytest.approx(0.270)


def test_validate_uses_a_users_club_for_the_rows_that_name_it(tmp_path, capsys):
    spec = tmp_path / "driver.yaml"
    spec.write_text(SPEC)
    table = tmp_path / "s.csv"
    table.write_text("Club,Club Speed [mph],Attack Angle [deg],Dyn. Loft [deg],Ball Speed [mph]\n"
                     "Driver,110,2,13,163\n8 Iron,80,-4,30,105\n")
    assert main(["validate", "--dataset", str(table), "--model", "rigid_coulomb", "--club", str(spec),
                 "--csv", str(tmp_path / "p.csv")]) == 0
    text = (tmp_path / "p.csv").read_text()
    assert ",user_1," in text and ",8_iron," in text


def test_a_spec_sheets_bare_zero_is_read_and_any_other_bare_number_refused():
    # zero is zero in every unit (units.to_si decides): a centred CG needs no unit, a CG 2 mm high does
    head, _ = club_from_spec({"base": "driver", "cg": {"toe": 0, "high": "2 mm", "depth": "38 mm"}})
    assert head.center_of_mass[0] == 0.0 and head.center_of_mass[1] == pytest.approx(0.002)
    with pytest.raises(FieldError, match=r"club spec.cg.high: expected a value with its unit \(e.g. 2 mm\)"):
        club_from_spec({"base": "driver", "cg": {"toe": 0, "high": 2, "depth": "38 mm"}})
