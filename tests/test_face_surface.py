"""The face's surface as a study input of the friction law (report_review.md, "Bigger problems", first item).

A custom club used to get a smooth, dry face under ``friction_law: adhesion`` without a word, a melting ball on it
stopped on a face effusivity no study key could give, and one scene without a surface removed it from every case
of a batch of scenes. Each fault is injected here.
"""

import math
import re

import attrs
import numpy as np
import pytest

import impactlab
from impactlab.cli import main
from impactlab.errors import FieldError, ModelInputError
from impactlab.model.case_inputs import CaseInputs
from impactlab.model.registry import get_model
from impactlab.scene.catalogue import CLUB_PRESETS, club_from_spec
from impactlab.scene.core import Contact, Delivery, Scene
from impactlab.scene.materials import BALL_PRESETS, FACE_SURFACES

#: a custom wedge: numbers only, no preset (hence no surface)
CUSTOM = {"mass": "300 g", "loft": "56 deg", "center_of_mass": {"depth": "10 mm"},
          "inertia": {"toe": "1000 g*cm**2", "up": "2800 g*cm**2", "target": "2900 g*cm**2"}}
DELIVERY = {"club_speed": "70 mph", "attack_angle": "-4 deg", "dynamic_loft": "50 deg"}
LAW = [{"name": "rigid_coulomb", "friction_law": "adhesion"}]


def _study(club, ball="urethane_tour", models=LAW, **more):
    return dict({"ball": {"preset": ball}, "club": club, "delivery": DELIVERY, "models": models,
                 "outputs": ["spin_rate", "launch_angle"]}, **more)


@pytest.mark.parametrize("ball", ["urethane_tour", "two_piece_ionomer"])
def test_a_custom_club_without_a_surface_is_refused_under_the_law(ball):
    """Not a smooth, dry face in silence, and for the melting ionomer not a missing effusivity no key can give:
    the refusal names the block, the club and the surfaces to choose from."""
    with pytest.raises(FieldError) as refused:
        impactlab.load_study(_study(CUSTOM, ball))
    assert refused.value.path == "club.surface"
    assert "has no surface" in str(refused.value) and "smooth and dry" in str(refused.value)
    assert set(refused.value.choices) == set(FACE_SURFACES)
    # Coulomb friction reads no surface: the same club loads and runs
    study = impactlab.load_study(_study(CUSTOM, ball, models=["rigid_coulomb"]))
    assert np.isfinite(impactlab.run_study(study)["spin_rate"].values).all()
    # given its surface, the melting ball runs on it (the face effusivity comes with the surface)
    given = impactlab.load_study(_study(dict(CUSTOM, surface="grooved_blasted_steel"), ball))
    assert np.isfinite(impactlab.run_study(given)["spin_rate"].values).all()


def test_the_cli_refuses_a_club_without_a_surface_at_its_line(tmp_path, capsys):
    path = tmp_path / "custom.yaml"
    path.write_text("ball: {preset: urethane_tour}\n"
                    "club:\n  mass: 300 g\n  loft: 56 deg\n"
                    "  inertia: {toe: 1000 g*cm**2, up: 2800 g*cm**2, target: 2900 g*cm**2}\n"
                    "  center_of_mass: {depth: 10 mm}\n"
                    "delivery: {club_speed: 70 mph, dynamic_loft: 50 deg}\n"
                    "models: [{name: rigid_coulomb, friction_law: adhesion}]\n")
    assert main(["run", str(path), "-o", str(tmp_path / "never.h5"), "-q"]) == 2
    err = capsys.readouterr().err
    assert re.search(rf"{re.escape(str(path))}:[23]: club.surface: ", err) and "Traceback" not in err
    assert not (tmp_path / "never.h5").exists()


def test_a_wet_face_given_by_the_study_changes_spin_as_the_law_says():
    """Analytic limit: on a smooth face (s = 0: no ploughing) without grooves, a 100 um film is not squeezed below the
    0.4 um roughness within the contact (Reynolds' disc squeeze: ~2 ms to clear against a ~0.5 ms contact), so there
    is no adhesion and no friction at all: the ball leaves exactly as a frictionless (mu = 0) Coulomb impact, with no
    spin; dry, the same face grips. The grooved iron face drains the same film through its grooves and keeps its
    dry grip (within 2 %)."""
    smooth = dict(CUSTOM, surface={"preset": "smooth_steel"})
    study = impactlab.load_study(_study(smooth, sweep={"club.surface.water_film": ["0 um", "100 um"]}))
    result = impactlab.run_study(study)
    assert result["water_film"].values.tolist() == pytest.approx([0.0, 1e-4])
    spin = result["spin_rate"].values.ravel()
    frictionless = impactlab.run_study(impactlab.load_study(
        _study(CUSTOM, models=["rigid_coulomb"], contact={"friction": 0.0})))
    assert spin[0] > 2000.0
    assert spin[1] == pytest.approx(0.0, abs=1e-9)
    assert result["launch_angle"].values.ravel()[1] == pytest.approx(
        float(frictionless["launch_angle"].values.ravel()[0]), abs=1e-9)
    grooved = impactlab.run_study(impactlab.load_study(_study(
        dict(CUSTOM, surface="grooved_blasted_steel"), sweep={"club.surface.water_film": ["0 um", "100 um"]})))
    dry, wet = grooved["spin_rate"].values.ravel()
    assert wet == pytest.approx(dry, rel=0.02) and wet > 2000.0


def test_a_study_surface_field_lays_over_the_club_presets_own():
    """``club: {preset: sand_wedge, surface: {water_film: ...}}`` keeps the wedge's grooves and wets them; a club
    preset sweep under that key wets each club's own surface (the driver stays smooth titanium)."""
    study = impactlab.load_study(_study({"preset": "sand_wedge", "surface": {"water_film": "20 um"}}))
    surface = study.scene.face.surface
    grooved = FACE_SURFACES["grooved_blasted_steel"]
    assert surface.water_film == pytest.approx(20e-6)
    assert (surface.roughness_slope, surface.groove_land) == (grooved.roughness_slope, grooved.groove_land)
    swept = impactlab.load_study(_study({"preset": "sand_wedge", "surface": {"water_film": "20 um"}},
                                        sweep={"club.preset": ["driver", "sand_wedge"]}))
    inputs = impactlab.study.arrays.case_inputs(swept)
    np.testing.assert_allclose(inputs["face_water_film"], [20e-6, 20e-6])
    np.testing.assert_allclose(inputs["face_roughness_slope"], [0.0, grooved.roughness_slope])
    np.testing.assert_allclose(inputs["face_effusivity"], [FACE_SURFACES["smooth_titanium"].effusivity,
                                                           grooved.effusivity])


@pytest.mark.parametrize(("surface", "path", "words"), [
    ("sandblasted", "club.surface", "face surface preset"),
    ({"preset": "grooved_blasted_steel", "water_film": 20}, "club.surface.water_film", "with its unit"),
    ({"water_film": "20 um"}, "club.surface.roughness_slope", "surface preset"),
    ({"preset": "smooth_steel", "wetness": 1}, "club.surface.wetness", "a key of club.surface"),
    ({"preset": "smooth_steel", "water_film": "2 mm"}, "club.surface.water_film", "between 0 and 1 mm"),
    ({"preset": "smooth_steel", "effusivity": 8000}, "club.surface.effusivity", "with its unit"),
])
def test_a_bad_surface_is_refused_at_its_key(surface, path, words):
    with pytest.raises(FieldError, match=words) as refused:
        impactlab.load_study(_study(dict(CUSTOM, surface=surface)))
    assert refused.value.path == path


def test_the_effusivity_reads_with_its_unit():
    study = impactlab.load_study(_study(dict(CUSTOM, surface={"preset": "smooth_steel",
                                                              "effusivity": "3950 J/(m**2*K*s**0.5)"})))
    assert study.scene.face.surface.effusivity == pytest.approx(3950.0)


def test_a_club_spec_sheet_names_its_surface():
    head, _ = club_from_spec({"base": "7_iron", "surface": {"preset": "smooth_steel", "water_film": "5 um"}})
    assert head.surface.water_film == pytest.approx(5e-6)
    assert head.surface.roughness_slope == FACE_SURFACES["smooth_steel"].roughness_slope
    over_base, _ = club_from_spec({"base": "7_iron", "surface": {"water_film": "5 um"}})
    assert over_base.surface.groove_land == FACE_SURFACES["grooved_blasted_steel"].groove_land
    for bad, path in (({"base": "7_iron", "surface": "rough"}, "club spec.surface"),
                      ({"base": "7_iron", "surface": {"water_film": 5}}, "club spec.surface.water_film")):
        with pytest.raises(FieldError) as refused:
            club_from_spec(bad)
        assert refused.value.path == path


def _scenes():
    wedge = CLUB_PRESETS["sand_wedge"]
    custom = attrs.evolve(wedge, surface=None, name="my wedge")
    delivery = Delivery(31.0, attack_angle=math.radians(-4.0), dynamic_loft=math.radians(50.0))
    return [Scene.from_delivery(BALL_PRESETS["urethane_tour"], Scene.face_of(club), Contact(), delivery, 0.0, club)
            for club in (wedge, custom)]


def test_one_scene_without_a_surface_does_not_drop_the_others():
    """A batch of scenes keeps each surface that is given (NaN: not given); the law refuses the case without one,
    naming it, and computes the others as alone; Coulomb friction runs the whole batch."""
    with_surface, without = _scenes()
    batch = CaseInputs([with_surface, without])
    assert batch["face_roughness_slope"][0] == FACE_SURFACES["grooved_blasted_steel"].roughness_slope
    assert math.isnan(batch["face_roughness_slope"][1])
    law = get_model("rigid_coulomb")(friction_law="adhesion")
    with pytest.raises(ModelInputError, match=r"case\(s\) 1 has none"):
        law.compute([with_surface, without], ["spin_rate"])
    alone = law.compute([with_surface], ["spin_rate"])["spin_rate"].values
    both = law.compute([with_surface, with_surface], ["spin_rate"])["spin_rate"].values
    np.testing.assert_allclose(both, [alone[0], alone[0]], rtol=1e-12)
    coulomb = get_model("rigid_coulomb")().compute([with_surface, without], ["spin_rate"])["spin_rate"].values
    assert coulomb[0] == pytest.approx(coulomb[1], rel=1e-12)  # the surface is not Coulomb's business


def test_a_face_block_takes_a_surface_and_sweeps_its_water():
    """``face: {preset: steel, surface: ...}`` (a fixed face, no club) carries the surface like a club's."""
    study = impactlab.load_study({
        "ball": {"preset": "urethane_tour"}, "face": {"preset": "steel", "surface": "grooved_blasted_steel"},
        "impact": {"speed": "30 m/s", "angle": "40 deg"}, "models": LAW,
        "sweep": {"face.surface.water_film": ["0 um", "10 um"]}})
    inputs = impactlab.study.arrays.case_inputs(study)
    np.testing.assert_allclose(inputs["face_water_film"], [0.0, 1e-5])
    np.testing.assert_allclose(inputs["face_groove_land"], FACE_SURFACES["grooved_blasted_steel"].groove_land)
    with pytest.raises(FieldError) as refused:
        impactlab.load_study({"ball": {"preset": "urethane_tour"}, "face": {"preset": "steel"},
                              "impact": {"speed": "30 m/s", "angle": "40 deg"}, "models": LAW})
    assert refused.value.path == "face.surface"


def test_a_club_preset_sweep_gives_a_custom_base_club_each_presets_surface():
    """The study's own club has numbers and no surface, but every swept preset brings its own: not refused, and each
    case reads its preset's surface (the refusal is for a case that would run without one)."""
    head = dict(CUSTOM, inertia={"toe": "2900 g*cm**2", "up": "5000 g*cm**2", "target": "3500 g*cm**2"})
    study = impactlab.load_study(_study(head, sweep={"club.preset": ["driver", "sand_wedge"]}))
    inputs = impactlab.study.arrays.case_inputs(study)
    np.testing.assert_allclose(inputs["face_roughness_slope"],
                               [0.0, FACE_SURFACES["grooved_blasted_steel"].roughness_slope])
