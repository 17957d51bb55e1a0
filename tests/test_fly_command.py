"""``impactlab fly``: a launch or a launch-monitor session in, yards out (issue 22: "yards and a simulator out").

Oracles: the projectile in a vacuum (carry v^2 sin 2a / g, apex v^2 sin^2 a / 2g, time 2 v sin a / g, landing at the
launch angle), the export's own cells read from the file here, and the directions the physics fixes (a headwind
shortens, thin air lengthens, a wind from the left pushes right). Every user error: one message, exit 2.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from impactlab.cli import main

DATA = Path(__file__).parent / "data" / "vendors"
G = 9.80665
MPH, YARD = 0.44704, 0.9144


def _csv(path):
    with open(path, newline="") as stream:
        return list(csv.DictReader(stream))


def test_a_launch_in_a_vacuum_is_the_projectile(tmp_path, capsys):
    out = tmp_path / "fly.csv"
    assert main(["fly", "--ball-speed", "120 mph", "60 mph", "--launch-angle", "30 deg", "--spin-rate", "0 rpm",
                 "--model", "vacuum", "--csv", str(out)]) == 0
    printed = capsys.readouterr().out
    rows = _csv(out)
    assert len(rows) == 2
    for row, mph in zip(rows, (120.0, 60.0)):
        v, a = mph * MPH, math.radians(30.0)
        assert float(row["carry_distance [m]"]) == pytest.approx(v * v * math.sin(2 * a) / G, rel=2e-3)
        assert float(row["apex_height [m]"]) == pytest.approx((v * math.sin(a)) ** 2 / (2 * G), rel=2e-3)
        assert float(row["flight_time [s]"]) == pytest.approx(2 * v * math.sin(a) / G, rel=2e-3)
        assert float(row["landing_angle [degree]"]) == pytest.approx(30.0, abs=0.05)
        assert float(row["offline_distance [m]"]) == pytest.approx(0.0, abs=1e-9)
    # the printed table is in yards: the 120 mph shot's carry
    carry_yd = (120 * MPH) ** 2 * math.sin(math.radians(60)) / G / YARD
    line = next(text for text in printed.splitlines() if text.startswith("| 1 |"))
    assert float(line.split("|")[6]) == pytest.approx(carry_yd, abs=0.2)


def test_the_air_moves_the_carry_the_way_physics_says(tmp_path):
    launch = ["--ball-speed", "160 mph", "--launch-angle", "11 deg", "--spin-rate", "2700 rpm"]

    def flown(*extra):
        out = tmp_path / f"f{len(list(tmp_path.iterdir()))}.csv"
        assert main(["fly", *launch, *extra, "--csv", str(out)]) == 0
        row = _csv(out)[0]
        return float(row["carry_distance [m]"]), float(row["offline_distance [m]"])

    still, _ = flown()
    assert flown("--headwind", "10 mph")[0] < still < flown("--headwind", "-10 mph")[0]
    assert flown("--altitude", "1600 m")[0] > still  # thinner air: less drag (and less lift)
    assert flown("--crosswind", "10 mph")[1] > 1.0  # blowing towards the right
    assert flown("--temperature", "35 degC")[0] > still


def test_a_session_is_flown_beside_the_monitors_own_carry(tmp_path, capsys):
    path = DATA / "garmin_r10.csv"
    out = tmp_path / "session.csv"
    assert main(["fly", str(path), "--csv", str(out), "--show-rows"]) == 0
    printed = capsys.readouterr().out
    # the file, read here: line 6 is the only row with a measured spin ('Measured') whose spin axis is not at the
    # R10's +-30 deg clamp (line 5's is 30.0): the only one flown by default
    raw = _csv_rows(path)
    shot = raw[6 - 3]  # data rows start at file line 3 (header, units row)
    assert shot["Spin Rate Type"] == "Measured" and abs(float(shot["Spin Axis"])) < 30.0
    assert raw[5 - 3]["Spin Rate Type"] == "Measured" and float(raw[5 - 3]["Spin Axis"]) == 30.0
    rows = _csv(out)
    assert [row["line"] for row in rows] == ["6"]
    assert float(rows[0]["monitor_carry_distance [m]"]) == pytest.approx(float(shot["Carry Distance"]) * YARD)
    assert float(rows[0]["ball_speed [m/s]"]) == pytest.approx(float(shot["Ball Speed"]) * MPH)
    assert float(rows[0]["spin_rate [rpm]"]) == pytest.approx(float(shot["Spin Rate"]))
    assert "spin rate estimated by the monitor (--include-flagged flies it): 2 row(s) (line(s) 3, 4)" in printed
    assert "spin axis clamped by the monitor (--include-flagged flies it): 1 row(s) (line(s) 5)" in printed
    assert "model against the monitor's carry, 1 shot(s)" in printed
    # the flagged shots fly when asked
    assert main(["fly", str(path), "--include-flagged", "--csv", str(out)]) == 0
    assert [row["line"] for row in _csv(out)] == ["3", "4", "5", "6"]


def _csv_rows(path):
    with open(path, newline="") as stream:
        lines = stream.read().splitlines()
    return list(csv.DictReader([lines[0]] + lines[2:]))


def test_a_shot_without_spin_axis_has_no_offline(tmp_path):
    table = tmp_path / "shots.csv"
    table.write_text("club,ball_speed [mph],vertical_launch_angle [deg],spin_rate [rpm],carry_distance [yd]\n"
                     "Driver,165,11,2600,270\n")
    out = tmp_path / "out.csv"
    assert main(["fly", str(table), "--csv", str(out)]) == 0
    row = _csv(out)[0]
    assert row["offline_distance [m]"] == "" and float(row["carry_distance [m]"]) > 200.0


@pytest.mark.parametrize("args, says", [
    (["--ball-speed", "167", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm"],
     "--ball-speed: expected a ball speed with its unit, e.g. '167 mph'"),
    (["--ball-speed", "167 mph", "--launch-angle", "10 deg"], "a launch needs --spin-rate"),
    ([str(DATA / "garmin_r10.csv"), "--ball-speed", "167 mph"], "not both"),
    (["--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--temperature", "25"],
     "--temperature: expected a temperature"),
    (["--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--humidity", "0.5"],
     "with its unit, e.g. '60 %'"),
    (["--ball-speed", "167 mph", "150 mph", "140 mph", "--launch-angle", "10 deg", "12 deg", "--spin-rate",
      "2500 rpm"], "broadcast together"),
    (["--ball-speed", "-167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm"], "-74.6557 m/s"),
    (["--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--altitude", "1 km",
      "--pressure", "900 hPa"], "--altitude: expected either a pressure or an altitude"),
    ([str(DATA / "garmin_r10_b.csv")], "no shot to fly"),
    (["--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--vendor", "garmin_golf"],
     "--vendor applies to a session file"),  # was silently ignored
    (["--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm", "--include-flagged"],
     "--include-flagged applies to a session file"),
])
def test_every_user_error_is_one_message_and_exit_2(args, says, tmp_path, capsys):
    out = tmp_path / "never.csv"
    assert main(["fly", *args, "--csv", str(out)]) == 2
    err = capsys.readouterr().err
    assert says in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert not out.exists()


@pytest.mark.parametrize("args", [["--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm"],
                                  [str(DATA / "trackman_tps.csv")]])
def test_a_retired_model_is_refused_with_why_not_as_an_invalid_choice(args, capsys):
    with pytest.raises(SystemExit) as exit_:  # argparse's refusal: one line, status 2
        main(["fly", *args, "--model", "measured_fit_late_crisis"])
    err = capsys.readouterr().err
    assert exit_.value.code == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert "'measured_fit_late_crisis' was retired on 2026-11-24" in err and "use 'measured_fit'" in err


def test_the_python_api_refuses_launches_that_do_not_broadcast():
    import impactlab
    from impactlab.errors import FieldError

    with pytest.raises(FieldError, match="broadcast together"):
        impactlab.fly(ball_speed=[70.0, 60.0, 50.0], launch_angle=[0.2, 0.3], spin_rate=300.0)
    shots = impactlab.fly(ball_speed=[70.0, 60.0], launch_angle=0.2, spin_rate=[300.0, 250.0])
    assert np.all(shots.carry_distance.values > 100.0)


def test_the_monitors_landing_angle_and_apex_stand_in_the_results_units(tmp_path):
    path = DATA / "trackman_tps_drivers.csv"
    out = tmp_path / "tm.csv"
    assert main(["fly", str(path), "--csv", str(out)]) == 0
    with open(path, newline="") as stream:
        lines = stream.read().splitlines()
    raw = list(csv.DictReader([lines[1]] + lines[3:]))  # 'sep=,', the header, the units row ([deg], [ft], [yds])
    assert lines[2].split(",")[lines[1].split(",").index("Carry Flat - Land. Angle")] == "[deg]"
    by_line = {int(row["line"]): row for row in _csv(out)}
    compared = 0
    for line, cells in enumerate(raw, start=4):
        if line not in by_line or not cells["Carry Flat - Land. Angle"]:
            continue
        compared += 1
        row = by_line[line]
        assert float(row["monitor_landing_angle [degree]"]) == pytest.approx(float(cells["Carry Flat - Land. Angle"]))
        assert float(row["monitor_apex_height [m]"]) == pytest.approx(float(cells["Max Height - Height"]) * 0.3048)
        assert float(row["monitor_carry_distance [m]"]) == pytest.approx(float(cells["Carry Flat - Length"]) * YARD)
    assert compared == 7


def test_the_air_given_in_a_garmin_rows_units_has_the_density_garmin_states(capsys):
    """Garmin's export states each shot's air and its density (the fixture: 73 degF, 99.25728 kPa, 83 %, 1.1582365
    g/L); given as options in those units, the flight's air has Garmin's density (degF's offset, kPa, percent)."""
    raw = _csv_rows(DATA / "garmin_r10.csv")[3]
    temperature, pressure, humidity = raw["Temperature"], raw["Air Pressure"], raw["Relative Humidity"]
    assert main(["fly", "--ball-speed", "131 mph", "--launch-angle", "11 deg", "--spin-rate", "3361 rpm",
                 "--temperature", f"{temperature} degF", "--pressure", f"{pressure} kPa", "--humidity",
                 f"{humidity} %"]) == 0
    air = next(line for line in capsys.readouterr().out.splitlines() if line.startswith("air:"))
    assert f"(density {float(raw['Air Density']):.4f} kg/m^3)" in air


def test_a_topped_shot_and_a_topspin_shot_are_not_flown(tmp_path, capsys):
    """Square Golf's G-Wedge row at line 10 was launched below the horizontal with negative back spin (the file:
    Launch Angle -0.2, Back Spin -1266): from the ground the ball meets the ground at once, and a carry of 0 beside
    the monitor's 0.5 yd put -100 % into the session's mean. A row with topspin (back spin below 0) would be flown
    as backspin from its spin rate and axis. Neither is flown; each is listed with its reason."""
    path = DATA / "square_golf.csv"
    with open(path, newline="") as stream:
        lines = stream.read().splitlines()
    header = lines[2].split(",")
    cells = lines[9].split(",")  # file line 10
    assert float(cells[header.index("Launch Angle")]) < 0 and float(cells[header.index("Back Spin")]) < 0
    out = tmp_path / "sq.csv"
    assert main(["fly", str(path), "--csv", str(out), "--show-rows"]) == 0
    printed = capsys.readouterr().out
    assert "10" not in [row["line"] for row in _csv(out)]
    assert "launched below the horizontal (it meets the ground at once: no carry to predict): 1 row(s) (line(s) 10)" \
        in printed
    assert f"model against the monitor's carry, {len(_csv(out))} shot(s)" in printed
    table = tmp_path / "shots.csv"
    table.write_text("club,ball_speed [mph],vertical_launch_angle [deg],spin_rate [rpm],back_spin [rpm],"
                     "side_spin [rpm]\nDriver,150,8,1500,-1500,0\nDriver,150,12,2500,2500,0\n")
    assert main(["fly", str(table), "--csv", str(out), "--show-rows"]) == 0
    assert [row["line"] for row in _csv(out)] == ["3"]
    assert "back spin below 0 (topspin, which a spin rate and axis do not carry): 1 row(s) (line(s) 2)" in \
        capsys.readouterr().out


def test_a_spin_rate_derived_from_measured_back_and_side_spin_is_flown(tmp_path, capsys):
    """PiTrac's message (line 3 of the GSPro fixture) sends TotalSpin 0.0, a placeholder, beside its measured
    BackSpin 5300 and SideSpin 372.4: the reader takes the spin rate as their hypot and marks the placeholder 'no
    data'. That shot is measured and is flown by default (it was left out as 'estimated or clamped')."""
    out = tmp_path / "gspro.csv"
    assert main(["fly", str(DATA / "gspro_open_connect.json"), "--csv", str(out)]) == 0
    assert "line 3" not in capsys.readouterr().out
    row = {row["line"]: row for row in _csv(out)}["3"]
    assert float(row["spin_rate [rpm]"]) == pytest.approx(math.hypot(5300.0, 372.4))
    assert row["flagged"] == "False"


def test_offline_follows_the_launch_direction_and_the_spin_axis_in_the_vocabularys_sign(tmp_path, capsys):
    """In a vacuum the ball lands on the launch direction at the projectile's range R: offline = R sin(direction),
    whatever the spin axis (no lift); in air a spin axis tilted right (positive) curves the ball right. A session's
    launch direction and spin axis, each sign and not swapped, and the printed offline in yards."""
    table = tmp_path / "shots.csv"
    table.write_text("club,ball_speed [mph],vertical_launch_angle [deg],horizontal_launch_angle [deg],"
                     "spin_rate [rpm],spin_axis [deg]\n"
                     "7 Iron,100,20,3,0,15\n7 Iron,100,20,-3,0,-15\n")
    out = tmp_path / "out.csv"
    assert main(["fly", str(table), "--model", "vacuum", "--csv", str(out)]) == 0
    v, a = 100 * MPH, math.radians(20.0)
    for row, sign in zip(_csv(out), (1, -1)):
        reach = v * v * math.sin(2 * a) / G
        assert float(row["carry_distance [m]"]) == pytest.approx(reach, rel=2e-3)
        assert float(row["offline_distance [m]"]) == pytest.approx(sign * reach * math.sin(math.radians(3)), rel=5e-3)
    table.write_text("club,ball_speed [mph],vertical_launch_angle [deg],horizontal_launch_angle [deg],"
                     "spin_rate [rpm],spin_axis [deg]\nDriver,150,12,0,2500,10\nDriver,150,12,0,2500,-10\n")
    assert main(["fly", str(table), "--csv", str(out)]) == 0
    right, left = (float(row["offline_distance [m]"]) for row in _csv(out))
    assert right > 5.0 and left == pytest.approx(-right)
    capsys.readouterr()
    assert main(["fly", "--ball-speed", "150 mph", "--launch-angle", "12 deg", "--spin-rate", "2500 rpm",
                 "--spin-axis", "10 deg", "-10 deg", "--csv", str(out)]) == 0
    printed = capsys.readouterr().out
    typed = [float(row["offline_distance [m]"]) for row in _csv(out)]
    assert typed == pytest.approx([right, left])
    for index, offline in enumerate(typed, start=1):
        cells = next(text for text in printed.splitlines() if text.startswith(f"| {index} |")).split("|")
        assert float(cells[7]) == pytest.approx(offline / YARD, abs=0.06)


def test_the_printed_mean_and_rms_are_those_of_the_table(tmp_path, capsys):
    out = tmp_path / "tm.csv"
    assert main(["fly", str(DATA / "trackman_tps_drivers.csv"), "--csv", str(out)]) == 0
    printed = capsys.readouterr().out
    error = np.array([float(row["carry_distance [m]"]) / float(row["monitor_carry_distance [m]"]) - 1
                      for row in _csv(out)])
    assert error.std() > 0.01  # the mean and the RMS differ here
    summary = next(text for text in printed.splitlines() if text.startswith("model against the monitor's carry"))
    assert f"mean {100 * error.mean():+.1f} %, median {100 * np.median(error):+.1f} %, " \
           f"RMS {100 * np.sqrt(np.mean(error ** 2)):.1f} %" in summary


@pytest.mark.parametrize("option, given, says", [
    ("--temperature", "200 degC", "got 473.15 K (given as '200 degC')"),  # 200 + 273.15
    ("--pressure", "-5 hPa", "got -500 Pa (given as '-5 hPa')"),
    ("--headwind", "200 mph", "got 89.408 m/s (given as '200 mph')"),  # 200 x 0.44704
    ("--altitude", "50 km", "got 50000 m (given as '50 km')"),
])
def test_an_air_value_out_of_range_is_shown_with_its_unit(option, given, says, capsys):
    """The air's range checks run on SI values: the refused value is shown with its SI unit and as the user wrote
    it (before: 'got 473.15' for '200 degC', which reads as the user's number in the user's unit)."""
    assert main(["fly", "--ball-speed", "167 mph", "--launch-angle", "10 deg", "--spin-rate", "2500 rpm",
                 option, given]) == 2
    err = capsys.readouterr().err
    assert f"{option}: expected" in err and says in err and len(err.strip().splitlines()) == 1


def test_a_launch_without_a_landing_says_so(capsys):
    """300 mph (the fastest ball speed fly takes) at 89 deg: in a vacuum it would stay up 2 v sin(a) / g = 27.3 s,
    past the flight's 15 s limit, and drag does not bring it down by then; its row showed only dashes, with exit 0
    and no word why. (Found at 1000 mph at 80 deg, 89.8 s in a vacuum, which fly now refuses: no golf shot.)"""
    v, a = 300 * MPH, math.radians(89.0)
    assert 2 * v * math.sin(a) / G > 15.0
    assert main(["fly", "--ball-speed", "300 mph", "150 mph", "--launch-angle", "89 deg", "--spin-rate",
                 "500 rpm"]) == 0
    printed = capsys.readouterr().out
    assert "no carry for shot 1: still in the air after the flight's 15 s limit" in printed
    assert "shot 2" not in printed


@pytest.mark.parametrize("command", ["fly", "shots"])
def test_the_table_written_never_replaces_the_export_read(command, tmp_path, capsys):
    """`impactlab fly session.csv --csv session.csv` (or `shots`) replaced the user's export by the result table,
    exit 0; refused, the export untouched. Through another spelling of the same path too."""
    export = tmp_path / "session.csv"
    export.write_bytes((DATA / "garmin_r10.csv").read_bytes())
    before = export.read_bytes()
    for output in (export, tmp_path / "." / "session.csv"):
        assert main([command, str(export), "--csv", str(output)]) == 2
        err = capsys.readouterr().err
        assert "is the file read" in err and len(err.strip().splitlines()) == 1
        assert export.read_bytes() == before


def test_a_refused_value_in_a_long_launch_is_named_alone(capsys):
    """One bad value among 2000 ball speeds: the message named every value (29 kB for one NaN); it names the one
    refused, at its index."""
    speeds = [f"{100 + index / 100:g} mph" for index in range(2000)]
    for bad, says in (("nan mph", "--ball-speed[2000]: expected finite values, got nan"),
                      ("-5 mph", "--ball-speed[2000]: expected a positive ball speed, got -2.2352 m/s")):
        assert main(["fly", "--ball-speed", *speeds, bad, "--launch-angle", "12 deg", "--spin-rate",
                     "2500 rpm"]) == 2
        err = capsys.readouterr().err
        assert says in err and len(err) < 300


def test_a_launch_typed_below_the_horizontal_is_said(tmp_path, capsys):
    """-5 deg from tee height: the ball is at the ground going down, carry 0 (the flight's definition, to tee
    height); the row alone read as a prediction of no distance with no word why."""
    out = tmp_path / "low.csv"
    assert main(["fly", "--ball-speed", "100 mph", "--launch-angle", "-5 deg", "12 deg", "--spin-rate", "3000 rpm",
                 "--csv", str(out)]) == 0
    rows = _csv(out)
    assert float(rows[0]["carry_distance [m]"]) == 0.0 and float(rows[1]["carry_distance [m]"]) > 100.0
    printed = capsys.readouterr().out
    assert "shot 1: launched below the horizontal" in printed and "shot 2:" not in printed


def test_fly_help_prints(capsys):
    """`impactlab fly --help` ended in a traceback (argparse %-formats help texts, and --humidity's said '50 %')."""
    with pytest.raises(SystemExit) as done:
        main(["fly", "--help"])
    assert done.value.code == 0
    printed = capsys.readouterr().out
    assert "relative humidity (e.g. '50 %'; default 50 %)" in printed and "--include-flagged" in printed


@pytest.mark.parametrize("command", ["run", "models", "show", "plot", "convergence", "export", "validate", "shots",
                                     "fly", "fit", "paper"])
def test_every_commands_help_prints(command, capsys):
    with pytest.raises(SystemExit) as done:
        main([command, "--help"])
    assert done.value.code == 0 and "usage: impactlab" in capsys.readouterr().out


def test_a_no_data_spin_axis_flies_the_shot_without_offline(tmp_path, capsys):
    """Foresight's no-data sentinel 16777215 in one shot's SpinAxis_DEG (an FSX session): the axis is missing,
    flagged 'no data'. The shot flies straight with its measured total spin and no offline, as docs/vendors.md says;
    it was left out as 'launch values flagged by the monitor (estimated or clamped)'."""
    text = (DATA / "foresight_fsx.session").read_text()
    assert text.count('"SpinAxis_DEG":1.866554') == 1  # shot 2850
    export = tmp_path / "player.session"
    export.write_text(text.replace('"SpinAxis_DEG":1.866554', '"SpinAxis_DEG":16777215'))
    out = tmp_path / "out.csv"
    assert main(["fly", str(export), "--csv", str(out)]) == 0
    rows = _csv(out)
    assert len(rows) == 4
    row = rows[0]
    assert row["offline_distance [m]"] == "" and row["spin_axis [degree]"] == "" and row["flagged"] == "False"
    assert float(row["spin_rate [rpm]"]) == pytest.approx(5249.0)  # the file's TotalSpin_RPM
    assert "offline not given" in capsys.readouterr().out


def test_a_garmin_session_flies_each_shot_in_the_air_its_row_states(tmp_path, capsys):
    """Garmin states each shot's air (the fixture's lines 3-6: 60 degF, 100.40956 kPa, 39 % and 73 degF, 99.25728
    kPa, 83 %). Each shot is flown in its own: its carry is a launch typed in with that row's cells as options
    (the file's cells read here, in the units of its units row), not the standard air's; --standard-air flies the
    standard air, and options replace the export's air for every shot."""
    rows = _csv_rows(DATA / "garmin_r10.csv")
    out, standard, options = (tmp_path / name for name in ("own.csv", "standard.csv", "options.csv"))
    assert main(["fly", str(DATA / "garmin_r10.csv"), "--include-flagged", "--csv", str(out)]) == 0
    assert "the export's own, per shot" in capsys.readouterr().out
    assert main(["fly", str(DATA / "garmin_r10.csv"), "--include-flagged", "--standard-air", "--csv",
                 str(standard)]) == 0
    assert "the standard air (the export's own air, stated for 4 shot(s) flown, not used)" in capsys.readouterr().out
    assert main(["fly", str(DATA / "garmin_r10.csv"), "--include-flagged", "--temperature", "30 degC", "--csv",
                 str(options)]) == 0
    assert "the options (the export's own air" in capsys.readouterr().out
    own, plain, optioned = _csv(out), _csv(standard), _csv(options)
    assert len(own) == 4
    for flown, still, with_options in zip(own, plain, optioned):
        raw = rows[int(flown["line"]) - 3]  # file line 3 is the first shot (header, units row)
        launch = tmp_path / f"launch{flown['line']}.csv"
        assert main(["fly", "--ball-speed", f"{raw['Ball Speed']} mph", "--launch-angle", f"{raw['Launch Angle']} deg",
                     "--spin-rate", f"{flown['spin_rate [rpm]']} rpm", "--spin-axis",
                     f"{flown['spin_axis [degree]']} deg", "--launch-direction", f"{raw['Launch Direction']} deg",
                     "--temperature", f"{raw['Temperature']} degF", "--pressure", f"{raw['Air Pressure']} kPa",
                     "--humidity", f"{raw['Relative Humidity']} %", "--csv", str(launch)]) == 0
        typed = _csv(launch)[0]
        assert float(flown["carry_distance [m]"]) == pytest.approx(float(typed["carry_distance [m]"]), rel=1e-9)
        assert float(flown["air_density [kg/m^3]"]) == pytest.approx(float(raw["Air Density"]), rel=1e-3)
        # Garmin's air (1.158-1.208 kg/m^3) is not the standard 1.2211 kg/m^3: the carries differ (in either
        # direction: a slow shot's Reynolds number falls into the drag crisis in thinner air)
        assert float(flown["carry_distance [m]"]) != pytest.approx(float(still["carry_distance [m]"]), rel=1e-3)
        assert float(still["air_density [kg/m^3]"]) == pytest.approx(1.2211, abs=1e-4)
        assert float(with_options["air_density [kg/m^3]"]) < 1.19  # 30 degC at sea level, 50 %


def test_a_temperature_in_the_wrong_unit_is_caught_by_the_density_garmin_states(tmp_path, capsys):
    """The second fixture states [deg C] (18.33 degC, 99.49 kPa, 94 %, 1.180137 g/L). Relabelled [deg F], its
    temperature would be -7.6 degC and its air 10 % denser than the density the row states: the reader flags the
    air inconsistent, and the shots fly in the standard air, said, never in the misread air."""
    text = (DATA / "garmin_r10_b.csv").read_text()
    good = tmp_path / "metric.csv"
    good.write_text(text)
    assert main(["shots", str(good)]) == 0
    assert "air density: as its temperature, pressure and humidity give it, within 1 %" in capsys.readouterr().out
    bad = tmp_path / "relabelled.csv"
    bad.write_text(text.replace("[deg C]", "[deg F]"))
    assert main(["shots", str(bad)]) == 0
    report = capsys.readouterr().out
    assert "air density differs from the density of its temperature" in report
    assert "1.1801 kg/m^3 stated, 1.3035 computed from -7.6 degC" in report
    assert main(["fly", str(bad), "--include-flagged"]) == 0
    printed = capsys.readouterr().out
    assert "air: 15.0 degC, 1013.2 hPa, 50 % humidity" in printed
    assert "the air of 3 shot(s) is flagged inconsistent by the reader" in printed


def test_the_normalised_table_writes_garmins_temperature_in_degc(tmp_path):
    """60 degF is 15.5556 degC and 73 degF 22.7778 degC (an offset, not a factor: (F - 32) 5/9); 39 % is 0.39."""
    out = tmp_path / "normalised.csv"
    assert main(["shots", str(DATA / "garmin_r10.csv"), "--csv", str(out)]) == 0
    rows = _csv(out)
    assert float(rows[0]["air_temperature [degC]"]) == pytest.approx((60.0 - 32.0) * 5.0 / 9.0, abs=1e-7)
    assert float(rows[3]["air_temperature [degC]"]) == pytest.approx((73.0 - 32.0) * 5.0 / 9.0, abs=1e-7)
    assert float(rows[0]["air_pressure [kPa]"]) == pytest.approx(100.40956)
    assert float(rows[0]["relative_humidity [1]"]) == pytest.approx(0.39)
    assert float(rows[0]["air_density [kg/m^3]"]) == pytest.approx(1.208465)


@pytest.mark.parametrize("argv, message", [
    (["--standard-air", "--ball-speed", "160 mph", "--launch-angle", "11 deg", "--spin-rate", "2700 rpm"],
     "--standard-air applies to a session file"),
    ([str(DATA / "garmin_r10.csv"), "--standard-air", "--altitude", "300 m"], "--standard-air and --altitude"),
])
def test_standard_air_is_refused_where_it_means_nothing(argv, message, capsys):
    assert main(["fly", *argv]) == 2
    captured = capsys.readouterr()
    assert message in captured.err and "Traceback" not in captured.err


def test_air_the_flight_cannot_take_is_refused_at_its_line(tmp_path, capsys):
    """A row stating 200 degF (93 degC, beyond the flight's 77 degC) is refused with its file and line, not flown
    in some other air; its density is set to agree so that the reader's check passes it on."""
    text = (DATA / "garmin_r10.csv").read_text().splitlines()
    cells = text[5].split(",")
    header = text[0].split(",")
    cells[header.index("Temperature")] = "200.0"
    cells[header.index("Air Density")] = "0.7064"  # what 200 degF, 99.25728 kPa, 83 % give (within 1 %)
    text[5] = ",".join(cells)
    hot = tmp_path / "hot.csv"
    hot.write_text("\n".join(text) + "\n")
    assert main(["fly", str(hot)]) == 2
    err = capsys.readouterr().err
    assert f"{hot}:6: air.temperature: expected an air temperature between" in err
    assert "got 93.3 degC (366.48 K)" in err  # (200 - 32) 5/9 degC, said in degC, not as a bare SI float
    assert "Traceback" not in err


def test_a_table_in_impactlabs_own_names_flies_in_the_air_it_states(tmp_path):
    """fly's own names (launch_angle, launch_direction) are read as column names too, and the air columns in any
    units (70 degF = 21.11 degC, 29.92 inHg = 101.32 kPa, 40 %): the same carry as the launch typed in."""
    table = tmp_path / "own.csv"
    table.write_text("ball_speed [mph],launch_angle [deg],launch_direction [deg],spin_rate [rpm],"
                     "air_temperature [degF],air_pressure [inHg],relative_humidity [%]\n150,12,1.5,2500,70,29.92,40\n")
    session, typed = tmp_path / "session.csv", tmp_path / "typed.csv"
    assert main(["fly", str(table), "--csv", str(session)]) == 0
    assert main(["fly", "--ball-speed", "150 mph", "--launch-angle", "12 deg", "--launch-direction", "1.5 deg",
                 "--spin-rate", "2500 rpm", "--temperature", "21.1111 degC", "--pressure", "101.3206 kPa",
                 "--humidity", "40 %", "--csv", str(typed)]) == 0
    flown, launch = _csv(session)[0], _csv(typed)[0]
    assert float(flown["carry_distance [m]"]) == pytest.approx(float(launch["carry_distance [m]"]), rel=1e-5)
    assert float(flown["air_density [kg/m^3]"]) == pytest.approx(1.1950, abs=2e-4)


def test_a_normalised_trackman_export_flies_in_the_air_its_condition_column_states(tmp_path, capsys):
    """TrackMan's normalised rows say in words what air its model flew them in (the fixture's Condition: "Data are
    normalized to no wind conditions at 0 ft altitude, 76.99999999999994 ℉ with a Premium ball"): 25.0 degC at sea
    level, so each row flies as the launch typed in with --temperature "77 degF" --altitude "0 ft" (humidity not
    stated: the standard 50 %, said)."""
    out = tmp_path / "tm.csv"
    assert main(["fly", str(DATA / "trackman_tps_drivers.csv"), "--csv", str(out)]) == 0
    printed = capsys.readouterr().out
    assert "air: 25.0 degC, 1013.2 hPa, 50 % humidity" in printed
    assert "humidity not stated for 7 shot(s): 50 % taken" in printed
    first = _csv(out)[0]
    typed = tmp_path / "typed.csv"
    assert main(["fly", "--ball-speed", f"{float(first['ball_speed [m/s]'])} m/s", "--launch-angle",
                 f"{first['vertical_launch_angle [degree]']} deg", "--spin-rate", f"{first['spin_rate [rpm]']} rpm",
                 "--spin-axis", f"{first['spin_axis [degree]']} deg", "--temperature", "76.99999999999994 degF",
                 "--altitude", "0 ft", "--csv", str(typed)]) == 0
    assert float(first["carry_distance [m]"]) == pytest.approx(float(_csv(typed)[0]["carry_distance [m]"]), rel=1e-9)


@pytest.mark.parametrize("condition, expected", [
    ("at 0 ft altitude, 77 F with", "condition.csv:4:"),  # F is the farad to pint: refused at the cell
    ("at 1500 m altitude, 20 °C with", "air: 20.0 degC, 845.6 hPa"),  # ISA pressure at 1500 m: 84 556 Pa
    ("without the air in words", "the standard air (the export states no air)"),
])
def test_trackman_condition_text_is_read_with_its_units_or_refused(tmp_path, capsys, condition, expected):
    text = (DATA / "trackman_tps.csv").read_text(encoding="utf-8-sig")
    path = tmp_path / "condition.csv"
    path.write_text(text.replace("at 0 ft altitude, 76.99999999999994 ℉ with", condition), encoding="utf-8")
    code = main(["fly", str(path)])
    captured = capsys.readouterr()
    assert expected in (captured.out if code == 0 else captured.err)
    assert code == (2 if "condition.csv:4" in expected else 0) and "Traceback" not in captured.err


def test_a_wind_option_blows_through_each_shots_own_air(tmp_path, capsys):
    """--headwind alone adds wind to the air each Garmin row states (review9: it used to replace that air with the
    standard air): the row's carry is the launch typed in with the row's own temperature, pressure and humidity
    and the same headwind; an option of the air itself (--temperature) still replaces the export's air."""
    rows = _csv_rows(DATA / "garmin_r10.csv")
    out = tmp_path / "wind.csv"
    assert main(["fly", str(DATA / "garmin_r10.csv"), "--headwind", "5 mph", "--csv", str(out)]) == 0
    assert "the options' wind in every shot's air" in capsys.readouterr().out
    flown = _csv(out)[0]
    raw = rows[int(flown["line"]) - 3]
    typed = tmp_path / "typed.csv"
    assert main(["fly", "--ball-speed", f"{raw['Ball Speed']} mph", "--launch-angle", f"{raw['Launch Angle']} deg",
                 "--spin-rate", f"{flown['spin_rate [rpm]']} rpm", "--spin-axis", f"{flown['spin_axis [degree]']} deg",
                 "--launch-direction", f"{raw['Launch Direction']} deg", "--temperature", f"{raw['Temperature']} degF",
                 "--pressure", f"{raw['Air Pressure']} kPa", "--humidity", f"{raw['Relative Humidity']} %",
                 "--headwind", "5 mph", "--csv", str(typed)]) == 0
    assert float(flown["carry_distance [m]"]) == pytest.approx(float(_csv(typed)[0]["carry_distance [m]"]), rel=1e-9)
    assert main(["fly", str(DATA / "garmin_r10.csv"), "--headwind", "5 mph", "--temperature", "20 degC"]) == 0
    assert "the options (the export's own air, stated for 1 shot(s) flown, not used)" in capsys.readouterr().out


def test_a_row_whose_air_is_flagged_flies_in_the_standard_air_beside_rows_flown_in_their_own(tmp_path, capsys):
    """Line 4 of the Garmin fixture (73 degF, 99.25728 kPa, 83 %; 1.158 kg/m^3) with its stated density changed to
    1.30 kg/m^3 disagrees with its own temperature, pressure and humidity by 12 %: the reader flags that row's air.
    In the one per-shot flight, that row must take the whole standard air (15 degC, 101 325 Pa, 50 %: 1.2211 kg/m^3,
    the ideal-gas value of tests/test_flight_air.py), not its stated pressure with the standard temperature, while
    line 3 keeps its own (60 degF, 100.40956 kPa, 39 %: Garmin states 1.208465 kg/m^3)."""
    text = (DATA / "garmin_r10.csv").read_text().splitlines()
    header = text[0].split(",")
    cells = text[3].split(",")  # file line 4
    cells[header.index("Air Density")] = "1.30"
    text[3] = ",".join(cells)
    export = tmp_path / "one_flagged.csv"
    export.write_text("\n".join(text) + "\n")
    out = tmp_path / "out.csv"
    assert main(["fly", str(export), "--include-flagged", "--csv", str(out)]) == 0
    assert "the air of 1 shot(s) is flagged inconsistent by the reader" in capsys.readouterr().out
    density = {row["line"]: float(row["air_density [kg/m^3]"]) for row in _csv(out)}
    assert density["4"] == pytest.approx(1.2211, abs=1e-4)
    assert density["3"] == pytest.approx(1.208465, rel=2e-3)
