"""Validation by source: per-source errors, leave-one-source-out cross-validation, warm starts, observations."""

import math

import attrs
import numpy as np
import pytest

from impactlab.data.fit.calibration import calibrate, cross_validate, source_folds
from impactlab.data.sessions.shots import errors_by_source, read_yaml, shot_errors
from impactlab.model.registry import get_model

RPM = 2 * math.pi / 60

TABLE = """
name: hand
source: hand-made rows for the tests (not a measurement)
units: {club_speed: m/s, ball_speed: m/s, attack_angle: deg, dynamic_loft: deg, spin_rate: rpm,
        vertical_launch_angle: deg}
rows:
  - {label: a1, source: A, club: driver, club_speed: 50, attack_angle: 0, dynamic_loft: 12, ball_speed: 50,
     spin_rate: 3000, vertical_launch_angle: 10}
  - {label: a2, source: A, club: 6_iron, club_speed: 40, attack_angle: -3, dynamic_loft: 20, ball_speed: 60,
     spin_rate: 6000, vertical_launch_angle: 14}
  - {label: b1, source: B, club: driver, club_speed: 45, attack_angle: 2, dynamic_loft: 14, ball_speed: 40,
     spin_rate: 2000, vertical_launch_angle: 12}
"""


def test_errors_per_source_against_hand_values():
    table = read_yaml(TABLE)
    assert table.sources == ("A", "A", "B")
    predicted = {"ball_speed": np.array([51.0, 57.0, 40.4]), "spin_rate": np.array([3300.0, 6000.0, 1800.0]) * RPM,
                 "vertical_launch_angle": np.radians([11.0, 14.0, 9.0]),
                 "horizontal_launch_angle": np.zeros(3), "spin_axis": np.zeros(3)}
    by_source = errors_by_source(shot_errors(predicted, table), table)
    assert list(by_source) == ["A", "B"]
    # by hand: A's ball speed +2 % and -5 % -> sqrt((4 + 25) / 2); spin +10 % and 0 -> sqrt(50); launch 1 and 0
    assert by_source["A"]["ball_speed [%]"] == pytest.approx(math.sqrt(14.5), rel=1e-9)
    assert by_source["A"]["spin [%]"] == pytest.approx(math.sqrt(50.0), rel=1e-9)
    assert by_source["A"]["launch angle [deg]"] == pytest.approx(math.sqrt(0.5), rel=1e-9)
    # B: ball speed +1 %, spin -10 %, launch -3 deg (one row: the RMS is the error's size)
    assert by_source["B"]["ball_speed [%]"] == pytest.approx(1.0, rel=1e-9)
    assert by_source["B"]["spin [%]"] == pytest.approx(10.0, rel=1e-9)
    assert by_source["B"]["launch angle [deg]"] == pytest.approx(3.0, rel=1e-9)
    assert math.isnan(by_source["B"]["spin axis [deg]"])  # not measured anywhere


def _pulled_table(pull=1.05):
    """Source A's ball speeds are the restitution model's at e = 0.78; source B's are ``pull`` times the model's."""
    from impactlab.data.fit.calibration import apply
    from impactlab.data.sessions.shots import predict, table_inputs

    table = read_yaml(TABLE.replace("b1, source: B", "b1, source: B").replace(
        "  - {label: b1", "  - {label: b2, source: B, club: 6_iron, club_speed: 38, attack_angle: -4, dynamic_loft: 22,"
        " ball_speed: 50}\n  - {label: b1"))
    keep = {key: np.full(table.size, math.nan) for key in table.measured}
    model = get_model("restitution")()
    exact = predict(model, apply(table_inputs(table), ("restitution",), (0.78,)))["ball_speed"]
    factor = np.where(np.asarray(table.sources) == "B", pull, 1.0)
    keep["ball_speed"] = exact * factor
    return attrs.evolve(table, measured=keep), model


def test_leave_one_source_out_excludes_the_held_out_source():
    table, model = _pulled_table(1.05)
    held = cross_validate(model, table, ("restitution",), by="source")
    assert held["folds"] == source_folds(table) == [[0, 1], [2, 3]]
    # fitted on A alone, the model is exact there: e = 0.78, so B's rows miss by 1/1.05 - 1 (had B's rows been
    # in the fit, they would have pulled e up and the held-out error would be smaller)
    assert held["fits"][1]["restitution"] == pytest.approx(0.78, abs=2e-3)
    b = held["errors"]["ball_speed [%]"][2:]
    np.testing.assert_allclose(b, 100 * (1 / 1.05 - 1), atol=0.15)
    assert held["by_source"]["B"]["ball_speed [%]"] == pytest.approx(100 * (1 - 1 / 1.05), abs=0.15)
    # and the other way round: fitted on B alone (ball speeds 5 % up), A is predicted about 5 % high
    assert np.all(held["errors"]["ball_speed [%]"][:2] > 4.0)
    assert held["fits"][0]["restitution"] > 0.8


def test_one_source_cannot_be_left_out():
    from impactlab.errors import FieldError

    table = attrs.evolve(read_yaml(TABLE), row_sources=())
    with pytest.raises(FieldError, match="one source"):
        cross_validate(get_model("restitution")(), table, ("restitution",), by="source")


def test_warm_start_reaches_the_cold_optimum():
    from impactlab.data.shot_report import shot_table

    table = shot_table("trackman_tour")
    model = get_model("hertz_mindlin")()
    names = ("friction", "restitution")
    full = calibrate(model, table, names)
    train = table.subset([0, 1])  # the PGA rows
    cold = calibrate(model, train, names)
    warm = calibrate(model, train, names, start=dict(zip(full.parameters, full.values)))
    np.testing.assert_allclose(warm.values, cold.values, rtol=2e-2, atol=2e-3)
    assert warm.rms_after == pytest.approx(cold.rms_after, rel=1e-2, abs=1e-3)


def test_observations_say_what_was_assumed():
    from impactlab.data.validation.observations import cover_effect, describe, gear_effect, load_observations

    observations = load_observations()
    driver = observations["gear_effect"][0]
    # TrackMan (2009): 14 deg from 1 dimple (0.14 in) to 1/2 in off centre
    assert math.degrees(driver.published) == pytest.approx(14.0)
    assert driver.offsets == pytest.approx((0.14 * 0.0254, 0.5 * 0.0254))
    assert "ASSUMED" in describe(driver) and driver.kind == "measurement"
    cover = observations["cover"][0]
    assert cover.published == pytest.approx(8300 / 5600 - 1)  # Titleist WedgeCraft: Pro V1 vs two-piece Surlyn
    model = get_model("rigid_coulomb")()
    result = gear_effect(model, driver)
    assert result["ratio"] == pytest.approx(result["predicted"] / 14.0)
    assert result["toe"] > 0 and result["heel"] > 0
    # a rigid model has no cover: the two balls spin the same
    assert cover_effect(model, cover)["ratio"] == pytest.approx(0.0, abs=1e-3)


def test_the_vertical_gear_effect_observation_is_loaded_as_published_and_compared():
    from impactlab.data.validation.observations import describe, load_observations, vertical_gear_effect

    clydebank = load_observations()["vertical_gear_effect"][0]
    # Clydebank Post (2014-11-23): "just 15mm higher on the face", "four degrees higher", "800 rpm less backspin"
    assert clydebank.offsets[1] - clydebank.offsets[0] == pytest.approx(0.015)
    assert clydebank.published == pytest.approx(-800 * 2 * math.pi / 60)
    assert clydebank.published_launch == pytest.approx(math.radians(4.0))
    assert clydebank.kind == "measurement" and clydebank.loft_at == "centre" and "ASSUMED" in describe(clydebank)
    model = get_model("rigid_coulomb")()
    result = vertical_gear_effect(model, clydebank)
    # physics, not numbers from the code: a strike higher on a rolled face (loft held at the face centre) has more
    # loft where it lands and sits above the centre of mass: it launches higher and spins less
    assert result["launch_change"] > 0 > result["spin_change"]
    assert result["ratio"] == pytest.approx(result["spin_change"] / -800.0)
    assert result["ratio_launch"] == pytest.approx(result["launch_change"] / 4.0)
    # held at the contact point instead, the roll's extra loft is taken out: the launch barely changes (the
    # definition matters; the observation's own is the face centre's)
    held = vertical_gear_effect(model, clydebank, loft_at="contact")
    assert held["launch_change"] < 0.5 * result["launch_change"]


def test_rolling_hysteresis_is_fitted_as_a_model_option():
    from impactlab.data.fit.calibration import apply
    from impactlab.data.shot_report import shot_table
    from impactlab.data.sessions.shots import predict, table_inputs
    from impactlab.errors import FieldError

    table = shot_table("trackman_tour")
    # measurements made by the model itself at alpha = 0.3 (and e = 0.78): the fit must find alpha again
    truth = get_model("rigid_coulomb")(rolling_hysteresis=0.3)
    made = predict(truth, apply(table_inputs(table), ("restitution",), (0.78,)))
    measured = {key: (made[key] if key in ("ball_speed", "vertical_launch_angle", "spin_rate")
                      else np.full(table.size, math.nan)) for key in table.measured}
    synthetic = attrs.evolve(table, measured=measured)
    result = calibrate(get_model("rigid_coulomb")(), synthetic, ("restitution", "rolling_hysteresis"))
    assert result.values == pytest.approx((0.78, 0.3), abs=5e-3)
    with pytest.raises(FieldError, match="rolling_hysteresis"):
        calibrate(get_model("restitution")(), synthetic, ("restitution", "rolling_hysteresis"))


def test_cli_per_source_table_and_leave_one_source_out(capsys, tmp_path):
    from impactlab.cli import main

    assert main(["validate", "--dataset", "trackman_tour", "--dataset", "observations",
                 "--model", "rigid_coulomb", "--csv", str(tmp_path / "rows.csv")]) == 0
    out = capsys.readouterr().out
    assert "per source" in out and "TrackMan PGA Tour" in out and "TrackMan LPGA Tour" in out
    assert "trackman2009_driver spin-axis change" in out and "ASSUMED" in out
    assert "clydebank2014_driver spin change" in out and "clydebank2014_driver launch change" in out
    assert (tmp_path / "rows.csv").read_text().count("\n") == 5  # header + four shots, --csv still works
    assert main(["fit", "trackman_tour", "--cross-validate", "--model", "restitution",
                 "--parameter", "restitution"]) == 0
    out = capsys.readouterr().out
    assert "leave-one-out by source" in out and "held out TrackMan LPGA Tour (2 rows)" in out


def test_cli_by_source_needs_several_sources(capsys, tmp_path):
    from impactlab.cli import main

    path = tmp_path / "one.yaml"
    path.write_text(TABLE.replace("source: A, ", "").replace("source: B, ", ""))
    assert main(["fit", str(path), "--cross-validate", "--by", "source", "--model", "restitution",
                 "--parameter", "restitution"]) == 2
    err = capsys.readouterr().err
    assert "--by" in err and "several sources" in err and "Traceback" not in err
