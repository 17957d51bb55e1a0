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


def test_iron_heads_carry_campaus_patent_numbers_as_typed():
    """US 4,420,156 (Campau 1983), abstract: 'the center of gravity for clubs 2 through 9 varied from 0.171 to 0.114
    inch behind the striking face, the moment of inertia varied from 13.619 to 16.423 ounce (wt.)-in.2, and the
    radius of gyration varied between 1.271 and 1.291 inch' (typed in here, not read from the code)."""
    from impactlab.scene.catalogue import CAMPAU_1983, CAMPAU_SOURCE, GOLF_DIGEST_IRON_MOI, campau_iron

    assert CAMPAU_1983["cg_depth_in"] == {2: 0.171, 9: 0.114}
    assert CAMPAU_1983["moi_oz_in2"] == {2: 13.619, 9: 16.423}
    assert CAMPAU_1983["gyration_in"] == (1.271, 1.291)
    assert "0.171 to 0.114 inch" in CAMPAU_SOURCE and "13.619 to 16.423" in CAMPAU_SOURCE
    # Golf Digest (2010, 2008): Ping S56 7-iron 2400, K15 3000, Eye2 about 2600 g cm^2 (manufacturers' figures)
    assert GOLF_DIGEST_IRON_MOI == {"Ping S56 7-iron": 2400.0, "Ping K15 7-iron": 3000.0, "Ping Eye2 (1983)": 2600.0}
    # by hand: 1 oz in^2 = 28.349523125 g x 6.4516 cm^2 = 182.8997 g cm^2; the 2-iron 13.619 -> 2490.91, the 9-iron
    # 16.423 -> 3003.76 g cm^2; depths 0.171 in = 4.3434 mm, 0.114 in = 2.8956 mm
    assert campau_iron(2) == pytest.approx((4.3434, 2490.91), abs=0.01)
    assert campau_iron(9) == pytest.approx((2.8956, 3003.76), abs=0.01)
    # the 6-iron, 4/7 of the way: 0.171 - 4/7 x 0.057 = 0.138429 in = 3.5161 mm; 13.619 + 4/7 x 2.804 = 15.2213
    # oz in^2 = 2783.97 g cm^2 (an interpolation between the patent's two ends: an estimate)
    assert campau_iron(6) == pytest.approx((3.5161, 2783.97), abs=0.01)
    with pytest.raises(FieldError):
        campau_iron(10)  # the patent has no wedges: no extrapolation
    # the heads use them: the 6-iron's CG 3.516 mm behind the face, 2784 g cm^2 about its vertical axis; the moment
    # lies inside Golf Digest's manufacturer range for 7-irons (2400-3000)
    six = CLUB_CATALOGUE["6_iron"]
    assert six.center_of_mass[2] == pytest.approx(3.5161e-3, abs=1e-7)
    assert six.inertia_components()["up"] == pytest.approx(2783.97e-7, abs=1e-9)
    for key in [f"{n}_iron" for n in range(3, 10)]:
        up = CLUB_CATALOGUE[key].inertia_components()["up"] * 1e7
        assert 2400 <= up <= 3010, key
    depths = [CLUB_CATALOGUE[f"{n}_iron"].center_of_mass[2] for n in range(3, 10)]
    assert all(b < a for a, b in zip(depths, depths[1:]))  # deeper CG the longer the iron (the patent's words)
    # the wedges carry the 9-iron's values (the patent has no wedges), said in their source
    assert CLUB_CATALOGUE["lob_wedge"].center_of_mass[2] == pytest.approx(2.8956e-3, abs=1e-7)
    assert "9-iron's values" in CLUB_CATALOGUE["lob_wedge"].source


def test_campaus_moments_and_gyration_radii_imply_maltbys_head_masses():
    # an independent check of reading the patent's pairs (2-iron: 13.619 oz in^2, k = 1.271 in): m = I / k^2 in
    # ounces, 13.619 / 1.271^2 = 8.430 oz = 239.0 g, 16.423 / 1.291^2 = 9.854 oz = 279.3 g, against Maltby's standard
    # 240 g 3-iron and 282 g 9-iron (the 2-iron one step lighter still: 233 g)
    assert 13.619 / 1.271**2 * 28.349523125 == pytest.approx(239.0, abs=0.1)
    assert 16.423 / 1.291**2 * 28.349523125 == pytest.approx(279.3, abs=0.1)
    assert CLUB_CATALOGUE["9_iron"].mass * 1e3 == pytest.approx(279.3, rel=0.01)


def test_a_more_lofted_iron_sends_the_ball_off_slower_and_higher():
    # one delivery (40 m/s, level, face at its static loft) through the irons: physics, not numbers from the code:
    # more loft means a smaller normal speed, hence a slower, higher-launched ball with more spin
    from impactlab.data.sessions.shots import predict
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
