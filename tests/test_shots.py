"""Launch-monitor shot tables: reading with units, bad rows reported, predictions, calibration, cross-validation."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from impactlab.data.fit.calibration import apply, calibrate, cross_validate
from impactlab.cli import main
from impactlab.errors import StudyError
from impactlab.physics.contact import contact_state
from impactlab.model.registry import get_model
from impactlab.data.shot_report import shot_table
from impactlab.data.sessions.reader import read_session_text
from impactlab.data.sessions.shots import ERROR_KEYS, predict, read_csv, read_yaml, shot_errors, summary, table_inputs

RATCHET = Path(__file__).parent / "data" / "validation_budgets.json"
MPH = 0.44704  # m/s, by definition (1 mile = 1609.344 m, 1 h = 3600 s)
RPM = 2 * math.pi / 60

CSV = """Shot,Club,Club Speed [mph],Attack Angle [deg],Dyn. Loft (deg),Club Path [deg],Face Angle [deg],\
Ball Speed [mph],Launch Angle [deg],Launch Direction [deg],Spin Rate [rpm],Spin Axis [deg]
A,driver,115,-0.9,12.8,0,0,171,10.4,,2545,
B,6_iron,94,-3.7,20.2,2,1,130,14.0,1.4,6204,-3
"""


def test_csv_units_in_the_header_are_converted_to_si():
    table = read_csv(CSV, "shots.csv")
    assert table.labels == ("A", "B") and table.clubs == ("driver", "6_iron")
    assert table.delivery["club_speed"][0] == pytest.approx(115 * MPH, rel=1e-12)
    assert table.delivery["dynamic_loft"][1] == pytest.approx(math.radians(20.2), rel=1e-12)
    assert table.delivery["path"][1] == pytest.approx(math.radians(2.0))
    assert table.measured["spin_rate"][0] == pytest.approx(2545 * RPM, rel=1e-12)
    assert table.measured["spin_axis"][1] == pytest.approx(math.radians(-3.0))
    # an empty cell is "not measured", never zero
    assert np.isnan(table.measured["horizontal_launch_angle"][0]) and np.isnan(table.measured["spin_axis"][0])


def test_a_bad_cell_or_a_ragged_row_skips_that_row_with_its_reason_and_the_file_is_refused_only_if_none_is_left():
    # an instrument's bad row never sinks the file (issue 32): each is skipped with its column, the rest are used
    bad = CSV.replace("115,-0.9", "115,minus one") + "C,putter,80\n"
    table = read_csv(bad, "shots.csv")
    assert table.labels == ("B",)
    assert dict(table.skipped) == {2: "Attack Angle [deg]: a cell that is not a number"}
    session = read_session_text(bad, "shots.csv")
    assert dict(session.skipped)[4].startswith("a row of 3 cells under a header of 12 columns")
    assert session.bad_rows() == [(2, "Attack Angle [deg]: a cell that is not a number"),
                                  (4, dict(session.skipped)[4])]
    # no row left: refused, each reason at its file:line
    worse = bad.replace("130,14.0", "130 furlongs,14.0")
    with pytest.raises(StudyError) as caught:
        read_csv(worse, "shots.csv")
    message = str(caught.value)
    assert "shots.csv:2: Attack Angle [deg]: a cell that is not a number (1 row(s))" in message
    assert "shots.csv:3: Ball Speed [mph]: a cell that is not a number (1 row(s))" in message


def test_a_row_without_a_delivery_or_a_measurement_is_skipped_with_its_reason_and_the_rest_used():
    text = CSV.replace("A,driver,115,-0.9,12.8,0,0,171,10.4,,2545,", "A,driver,115,-0.9,,0,0,,,,,")
    table = read_csv(text, "shots.csv")
    assert table.labels == ("B",)  # row A skipped, row B used
    (line, reason), = table.skipped
    assert line == 2 and "no dynamic loft" in reason and "no measured launch quantity" in reason
    only_bad = CSV.splitlines()[0] + "\nA,driver,115,-0.9,,0,0,,,,,\n"
    with pytest.raises(StudyError, match=r"no row the impact models can use .*shots.csv:2: no dynamic loft \(1 row"):
        read_csv(only_bad, "shots.csv")


def test_an_unknown_column_is_named_in_a_warning():
    with pytest.warns(UserWarning, match="Wind Speed"):
        read_csv(CSV.replace("Spin Axis [deg]", "Wind Speed [mph]"), "shots.csv")


def test_yaml_tables_check_their_keys_with_lines():
    text = """name: t
units: {club_sped: mph}
colour: blue
rows:
  - {club: driver, club_speed: 50 m/s, attack_angle: 0 deg, dynamic_loft: 12 deg, ball_spede: 70 m/s}
"""
    with pytest.raises(StudyError) as caught:
        read_yaml(text, "t.yaml")
    message = str(caught.value)
    assert "t.yaml:2: units.club_sped" in message and "t.yaml:3: colour" in message
    assert "t.yaml:5: rows[0].ball_spede" in message


def test_a_launch_monitors_loft_is_the_loft_of_the_face_where_the_ball_meets_it():
    # TrackMan's dynamic loft is that of the face at the contact point: on the rolled driver face a strike 10 mm
    # high meets the face at the measured loft, so the face centre's loft is atan(10/254) less
    text = CSV.splitlines()[0] + ",Impact Height [mm]\n" + CSV.splitlines()[1] + ",10\n"
    table = read_csv(text, "shots.csv")
    inputs = table_inputs(table)
    normal = contact_state(inputs)["normal"][0]
    assert math.degrees(math.asin(normal[2])) == pytest.approx(12.8, abs=1e-9)
    # the rows keep the measured loft and say where it is (the models turn the head: the face centre's loft is
    # atan(10/254) less, exactly so for a strike on the heel-toe centre line)
    assert inputs["dynamic_loft"][0] == pytest.approx(math.radians(12.8), rel=1e-12)
    assert inputs["loft_at_contact"][0] == 1.0
    from impactlab.physics.delivery import centre_face
    centre_loft, _ = centre_face(inputs["dynamic_loft"], inputs["face_angle"], inputs["strike_toe"],
                                 inputs["strike_high"], inputs["face_bulge_radius"], inputs["face_roll_radius"])
    assert centre_loft[0] == pytest.approx(math.radians(12.8) - math.atan(0.010 / 0.254), rel=1e-12)


def test_the_face_gain_raises_the_balls_restitution_law_on_woods_only():
    table = shot_table("trackman_tour")
    inputs = table_inputs(table)
    ball_e = 0.787  # the urethane_tour preset's constant law
    wood = np.array([club == "driver" for club in table.clubs])
    assert np.allclose(inputs["restitution"][wood], ball_e + 0.083, atol=1e-12)
    assert np.allclose(inputs["restitution"][~wood], ball_e, atol=1e-12)
    changed = apply(inputs, ["face_restitution_gain"], [0.02])
    assert np.allclose(changed["restitution"], inputs["restitution"])  # no ball given: e stays as the inputs had it
    from impactlab.scene.materials import ball_preset
    changed = apply(inputs, ["face_restitution_gain"], [0.02], ball_preset("urethane_tour"))
    assert np.allclose(changed["restitution"], np.where(wood, ball_e + 0.02, ball_e), atol=1e-12)


def test_errors_are_in_the_datas_own_units():
    table = shot_table("trackman_tour")
    predicted = {key: value.copy() for key, value in table.measured.items()}
    predicted["ball_speed"] *= 1.01
    predicted["vertical_launch_angle"] += math.radians(0.5)
    predicted["spin_rate"] *= 0.9
    rms = summary(shot_errors(predicted, table))
    assert rms["ball_speed [%]"] == pytest.approx(1.0)
    assert rms["launch angle [deg]"] == pytest.approx(0.5)
    assert rms["spin [%]"] == pytest.approx(10.0)
    assert math.isnan(rms["spin axis [deg]"])  # not measured in this table


def synthetic_table(model, truth):
    """TrackMan's deliveries and a few more, with the model's own launches at known parameters as 'measurements'."""
    rows = "\n".join(
        f"  - {{label: r{i}, club: {club}, club_speed: {speed}, attack_angle: {attack}, dynamic_loft: {loft}, "
        f"ball_speed: 1, vertical_launch_angle: 1, spin_rate: 1}}"
        for i, (club, speed, attack, loft) in enumerate([
            ("driver", 115, -0.9, 12.8), ("6_iron", 94, -3.7, 20.2), ("driver", 96, 2.8, 15.5),
            ("6_iron", 80, -2.3, 23.6), ("driver", 105, 0.0, 11.0), ("6_iron", 88, -5.0, 27.0)]))
    text = ("name: synthetic\nunits: {club_speed: mph, attack_angle: deg, dynamic_loft: deg, ball_speed: m/s, "
            "vertical_launch_angle: rad, spin_rate: rad/s}\nsigma: {ball_speed: 1 mph, vertical_launch_angle: "
            "0.5 deg, spin_rate: 150 rpm}\nrows:\n" + rows + "\n")
    table = read_yaml(text, "synthetic.yaml")
    from impactlab.scene.materials import ball_preset
    predicted = predict(model, apply(table_inputs(table), list(truth), list(truth.values()),
                                     ball_preset("urethane_tour")))
    for key in ("ball_speed", "vertical_launch_angle", "spin_rate"):
        table.measured[key][:] = predicted[key]
    return table


def test_calibration_recovers_known_parameters_and_says_what_it_cannot_identify():
    model = get_model("hertz_mindlin")()
    truth = {"friction": 0.3, "restitution": 0.76, "face_restitution_gain": 0.05}
    table = synthetic_table(model, truth)
    result = calibrate(model, table, list(truth))
    for name, value, sigma in zip(result.parameters, result.values, result.uncertainties):
        assert value == pytest.approx(truth[name], abs=max(3 * sigma, 2e-3)), name
    assert result.rms_after < 1e-2 < result.rms_before
    # a rigid body leaves rolling whatever its friction: the data cannot tell mu, and the fit says so
    rigid = calibrate(get_model("rigid_coulomb")(), table, ["friction", "restitution"])
    assert rigid.identified == (False, True) and math.isinf(rigid.uncertainties[0])


@pytest.mark.slow
def test_cross_validation_reports_the_error_on_rows_it_did_not_fit():
    model = get_model("hertz_mindlin")()
    table = synthetic_table(model, {"friction": 0.3, "restitution": 0.76})
    table.measured["ball_speed"][1] *= 1.05  # one row 5 % off: a fit that saw it absorbs part of it
    held = cross_validate(model, table, ["friction", "restitution"])
    fitted = calibrate(model, table, ["friction", "restitution"])
    in_sample = shot_errors(predict(model, apply(table_inputs(table), fitted.parameters, fitted.values)), table)
    assert abs(held["errors"]["ball_speed [%]"][1]) > abs(in_sample["ball_speed [%]"][1]) + 0.3
    # the fold that left the odd row out recovers the truth; the others are pulled towards the odd row
    assert held["fits"][1]["restitution"] == pytest.approx(0.76, abs=1e-3)
    assert all(fit["restitution"] > 0.762 for index, fit in enumerate(held["fits"]) if index != 1)
    assert set(held["summary"]) == set(ERROR_KEYS)


def test_the_shipped_tour_table_stays_inside_its_budgets_which_only_tighten():
    table = shot_table("trackman_tour")
    record = json.loads(RATCHET.read_text())["trackman_tour"]
    inputs = table_inputs(table)
    for name, budget in table.budgets.items():
        rms = summary(shot_errors(predict(get_model(name)(), inputs), table))
        for key, limit in budget.items():
            assert limit <= record[name][key], f"{name} {key}: budget loosened from {record[name][key]}"
            assert rms[key] <= limit, f"{name} {key}: rms {rms[key]:.3f} > {limit}"


def test_validate_and_fit_take_a_users_csv(tmp_path, capsys):
    path = tmp_path / "session.csv"
    path.write_text(CSV)
    assert main(["validate", "--dataset", str(path), "--model", "rigid_coulomb"]) == 0
    out = capsys.readouterr().out
    assert "session: 2 row(s)" in out and "rigid_coulomb" in out and "data 1-sigma" in out
    result = tmp_path / "fit.json"
    assert main(["fit", str(path), "--model", "restitution", "--parameter", "restitution",
                 "--cross-validate", "--json", str(result)]) == 0
    written = json.loads(result.read_text())
    assert written[0]["parameters"] == ["restitution"] and "cross_validation" in written[0]
    assert "leave-one-out" in capsys.readouterr().out


def test_a_bad_row_is_skipped_by_validate_and_strict_refuses_it_in_one_message_and_exit_2(tmp_path, capsys):
    path = tmp_path / "session.csv"
    path.write_text(CSV.replace("171", "fast"))
    assert main(["validate", "--dataset", str(path), "--model", "rigid_coulomb"]) == 0
    out = capsys.readouterr().out
    assert "1 of 2 row(s) not used" in out
    assert "Ball Speed [mph]: a cell that is not a number: 1 row(s) (first line 2)" in out
    assert main(["validate", "--dataset", str(path), "--model", "rigid_coulomb", "--strict"]) == 2
    err = capsys.readouterr().err
    assert "session.csv: --strict: 1 bad row(s): " in err and "session.csv:2: Ball Speed [mph]: a cell that is not a " \
        "number" in err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1


def test_the_validation_figure_draws_the_measured_values_and_every_model():
    from impactlab.data.shot_report import shots_figure

    table = shot_table("trackman_tour")
    predictions = {"a": {key: value * 1.1 for key, value in table.measured.items()},
                   "b": {key: value * 0.9 for key, value in table.measured.items()}}
    figure = shots_figure(table, predictions)
    speed, launch, spin = figure.axes[:3]
    assert speed.get_ylabel() == "ball speed [mph]" and spin.get_ylabel() == "spin rate [rpm]"
    drawn = {line.get_label(): line.get_ydata() for line in spin.get_lines() if not line.get_label().startswith("_")}
    np.testing.assert_allclose(drawn["a"], 1.1 * table.measured["spin_rate"] / RPM)
    np.testing.assert_allclose(drawn["b"], 0.9 * table.measured["spin_rate"] / RPM)
    measured = spin.containers[0].lines[0].get_ydata()  # the error-bar container: its data line
    np.testing.assert_allclose(measured, [2545, 6204, 2506, 5904])
    legend = [text.get_text() for text in speed.get_legend().get_texts()]
    assert set(legend) == {"a", "b", "measured (+- 1 sigma)"}


def test_a_number_without_a_unit_is_refused_not_guessed():
    # 115 could be mph or m/s: a launch-monitor export without units is refused, naming the cell
    with pytest.raises(StudyError, match=r"shots.csv:1:3 \(Club Speed\): expected a unit for the club speed"):
        read_csv(CSV.replace("Club Speed [mph]", "Club Speed"), "shots.csv")
    with pytest.raises(StudyError, match="ball_speed_sigma: expected a positive uncertainty"):
        read_csv(CSV.replace("Spin Axis [deg]", "Ball Speed Sigma [mph]").replace("2545,", "2545,0"), "shots.csv")


@pytest.mark.parametrize(("block", "line", "key"), [
    ("budgets: [maw, 1.0]", 2, "budgets"), ("sigma: [1 mph]", 2, "sigma"), ("units: [mph, deg]", 2, "units"),
    ("ball: [tour_urethane]", 2, "ball"), ("budgets: {maw: [1, 2]}", 2, "budgets.maw"),
    ("budgets: {maw: {'ball_speed [%]': -1}}", 2, "budgets.maw")
])
def test_a_yaml_shot_table_block_of_the_wrong_shape_is_one_message_at_its_line(tmp_path, capsys, block, line, key):
    """Issue 23: a list where a mapping belongs was an internal error (exit 1); now a message at file:line."""
    path = tmp_path / "t.yaml"
    path.write_text(f"name: t\n{block}\nrows:\n  - {{club: driver, club_speed: 50 m/s, attack_angle: 0 deg, "
                    "dynamic_loft: 12 deg, ball_speed: 70 m/s}\n")
    assert main(["validate", "--dataset", str(path)]) == 2
    err = capsys.readouterr().err
    assert f"t.yaml:{line}: {key}: expected" in err and "internal error" not in err and "Traceback" not in err


# the same three shots, as a hand-written YAML table and as launch-monitor exports: one assembly, one table
SAME_YAML = """name: session
units: {club_speed: mph, attack_angle: deg, path: deg, face_angle: deg, face_to_path: deg, dynamic_loft: deg,
        strike_toe: mm, strike_high: mm, ball_speed: mph, vertical_launch_angle: deg, horizontal_launch_angle: deg,
        spin_rate: rpm, spin_axis: deg}
rows:
  - {label: s1, club: Driver, club_speed: 115, attack_angle: -0.9, path: 2, face_angle: 1, face_to_path: -1,
     dynamic_loft: 12.8, strike_toe: 10, strike_high: 3, ball_speed: 171, vertical_launch_angle: 10.4,
     horizontal_launch_angle: 1.2, spin_rate: 2545, spin_axis: -2.5}
  - {label: s2, club: 7 Iron, club_speed: 90, attack_angle: -4.2, path: -1.5, face_to_path: 3, dynamic_loft: 22,
     ball_speed: 120, vertical_launch_angle: 16.3, horizontal_launch_angle: 0.4, spin_rate: 7097, spin_axis: 4}
  - {label: s3, club: PW, club_speed: 83, attack_angle: -5, path: 0, face_angle: 0, dynamic_loft: 30,
     ball_speed: 102, spin_rate: 9304}
"""
SAME_TRACKMAN = """sep=,
Date,Club,Club Speed,Attack Angle,Club Path,Dyn. Loft,Face Angle,Face To Path,Ball Speed,Smash Factor,\
Launch Angle,Launch Direction,Spin Rate,Spin Rate Type,Spin Axis,Impact Offset,Impact Height
[],[],[mph],[deg],[deg],[deg],[deg],[deg],[mph],[],[deg],[deg],[rpm],[],[deg],[mm],[mm]
s1,Driver,115,-0.9,2,12.8,1,-1,171,1.49,10.4,1.2,2545,Measured,-2.5,10,3
s2,7 Iron,90,-4.2,-1.5,22,-,3,120,1.33,16.3,0.4,7097,Measured,4,-,-
s3,PW,83,-5,0,30,0,-,102,1.23,-,-,9304,Measured,-,-,-
"""


def _assert_same_shots(one, other):
    assert (one.labels, one.clubs, one.handedness, one.loft_at) == (other.labels, other.clubs, other.handedness,
                                                                    other.loft_at)
    for part in ("delivery", "measured", "sigma"):
        mine, theirs = getattr(one, part), getattr(other, part)
        assert mine.keys() == theirs.keys()
        for key in mine:
            np.testing.assert_array_equal(mine[key], theirs[key], err_msg=f"{part}.{key}")


def test_a_yaml_tables_instrument_is_a_known_maker_or_refused_at_its_line():
    # the scorecard prints TrackMan's accuracy claims beside 'trackman' rows only: a maker spelled otherwise would
    # silently lose them, so an unknown word is refused at its line, with the makers a table may name
    text = SAME_YAML.replace("name: session\n", "name: session\ninstrument: TrackMan\n")
    assert read_yaml(text, "session.yaml").instrument == "trackman"
    assert read_yaml(SAME_YAML, "session.yaml").instrument == ""
    with pytest.raises(StudyError, match=r"session.yaml:2: instrument: expected the maker of the monitor, one of "
                                         r"flightscope, .*trackman.*, got 'TrackMan 4'"):
        read_yaml(SAME_YAML.replace("name: session\n", "name: session\ninstrument: TrackMan 4\n"), "session.yaml")


def test_the_same_shots_as_a_yaml_table_and_as_an_export_give_the_same_table():
    yaml_table = read_yaml(SAME_YAML, "session.yaml")
    _assert_same_shots(yaml_table, read_csv(SAME_TRACKMAN, "session.csv"))
    # by hand: the face angle that s2 leaves out is club path + face to path; its strike is centred
    assert yaml_table.clubs == ("driver", "7_iron", "pitching_wedge")
    assert yaml_table.delivery["club_speed"][0] == pytest.approx(115 * MPH, rel=1e-15)
    assert yaml_table.delivery["face_angle"][1] == pytest.approx(math.radians(1.5), rel=1e-12)
    assert yaml_table.delivery["strike_toe"].tolist() == [pytest.approx(0.010, rel=1e-12), 0.0, 0.0]
    assert np.isnan(yaml_table.measured["vertical_launch_angle"][2])
    assert yaml_table.sigma["ball_speed"].tolist() == [0.5] * 3  # no uncertainty given: the default
    # impactlab's own CSV layout, with per-row uncertainties (the YAML's sigma block: every row's unless it gives
    # its own) and the spin loft instead of the dynamic loft
    with_sigma = SAME_YAML.replace("ball_speed: 120,", "ball_speed: 120, ball_speed_sigma: 1.5 mph,").replace(
        "dynamic_loft: 30,", "spin_loft: 30,").replace("dynamic_loft: deg,", "dynamic_loft: deg, spin_loft: deg,"
                                                       ).replace("rows:", "sigma: {ball_speed: 2 mph}\nrows:")
    generic = """label,club,club_speed [mph],attack_angle [deg],path [deg],face_angle [deg],face_to_path [deg],\
dynamic_loft [deg],spin_loft [deg],strike_toe [mm],strike_high [mm],ball_speed [mph],ball_speed_sigma [mph],\
vertical_launch_angle [deg],horizontal_launch_angle [deg],spin_rate [rpm],spin_axis [deg]
s1,Driver,115,-0.9,2,1,-1,12.8,,10,3,171,2,10.4,1.2,2545,-2.5
s2,7 Iron,90,-4.2,-1.5,,3,22,,,,120,1.5,16.3,0.4,7097,4
s3,PW,83,-5,0,0,,,30,,,102,2,,,9304,
"""
    table = read_yaml(with_sigma, "session.yaml")
    _assert_same_shots(table, read_csv(generic, "session.csv"))
    assert table.sigma["ball_speed"].tolist() == pytest.approx(np.array([2, 1.5, 2]) * MPH, rel=1e-15)
    # square and straight: the spin loft of s3 is its dynamic loft less the attack angle (30 = loft + 5)
    assert table.delivery["dynamic_loft"][2] == pytest.approx(math.radians(25.0), rel=1e-12)


def test_a_yaml_row_is_square_unless_it_says_otherwise_and_an_exports_row_is_not_guessed_square():
    # a hand-written row states its delivery: no path or face angle is a square one, so its launch direction is
    # compared; an export's empty face angle is no measurement, and the launch direction is left out
    text = ("name: t\nrows:\n  - {club: driver, club_speed: 50 m/s, attack_angle: 0 deg, dynamic_loft: 12 deg, "
            "ball_speed: 70 m/s, horizontal_launch_angle: 0.5 deg}\n")
    table = read_yaml(text, "t.yaml")
    assert table.delivery["face_angle"][0] == 0.0 and table.delivery["path"][0] == 0.0
    assert table.measured["horizontal_launch_angle"][0] == pytest.approx(math.radians(0.5), rel=1e-12)
    export = read_csv(CSV.replace("115,-0.9,12.8,0,0,171,10.4,,2545,", "115,-0.9,12.8,,,171,10.4,0.5,2545,"))
    assert export.delivery["face_angle"][0] == 0.0 and np.isnan(export.measured["horizontal_launch_angle"][0])
    # a YAML sigma block that is no uncertainty is refused at its line, once, not once per row
    with pytest.raises(StudyError, match=r"t.yaml:2: sigma.spin_rate: expected a positive uncertainty, got 0"):
        read_yaml(text.replace("rows:", "sigma: {spin_rate: 0 rpm}\nrows:"), "t.yaml")


def test_a_yaml_rows_bare_zero_is_read_and_any_other_bare_number_refused():
    row = ("name: t\nrows:\n  - {club: driver, club_speed: 50 m/s, attack_angle: 0, path: 0, dynamic_loft: 12 deg, "
           "ball_speed: 70 m/s}\n")
    table = read_yaml(row, "t.yaml")
    assert table.delivery["attack_angle"][0] == 0.0 and table.delivery["path"][0] == 0.0
    with pytest.raises(StudyError, match=r"t.yaml:3: rows\[0\].path: expected a value with its unit \(in the column "
                                         r"header, the units: block or the value\), got 1"):
        read_yaml(row.replace("path: 0", "path: 1"), "t.yaml")
