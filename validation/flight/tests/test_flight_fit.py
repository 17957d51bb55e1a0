"""The ball's drag level settled on measured flights that are not TrackMan's tour tables, and the tables held out
(validation.flight.flight_fit; docs/flight.md, "Settling the drag level on measured flights").

Oracles: the numbers of the cited source table (PGA TOUR radar season averages as tabulated in jhoblitt/tmelevation
provenance.md @ 98f8a49, section 5), written here from that table; TrackMan's 2023 PGA driver row; a fit that must
recover a drag level it was given; the measured balls' drag offsets as bounds.
"""

from __future__ import annotations

import functools
from importlib import resources

import attrs
import numpy as np
import pytest
import yaml

from validation.flight import flight_fit
from impactlab.data.carry import TABLES, YARD, carry_table, validate_carry
from impactlab.physics import aerodynamics, flight
from impactlab.physics.atmosphere import air_density
from impactlab.units import MPH

RPM = np.pi / 30.0


@functools.cache
def _fit():
    return flight_fit.fit()


@functools.cache
def _folds():
    return flight_fit.leave_one_out()


def _document():
    path = resources.files("impactlab.data.validation").joinpath("pgatour_radar_driver.yaml")
    return yaml.safe_load(path.read_text())


def test_radar_seasons_file_is_a_measurement_with_its_source_and_caveats():
    document = _document()
    assert document["kind"] == "measurement"
    for word in ("PGA TOUR", "TrackMan", "ground impact", "jhoblitt/tmelevation", "98f8a49"):
        assert word in document["source"], word
    # what is measured and what is not, and that the driver rows of the tour tables share these shots
    assert "ground" in document["measured"] and "model" in document["measured"]
    assert "NOT independent" in document["independence"]
    assert set(document["units"]) == {"ball_speed", "launch_angle", "spin_rate", "max_height", "flight_time", "carry"}


def test_radar_seasons_are_the_cited_numbers():
    # provenance.md section 5, "PGA TOUR radar statistics": season, ball mph, launch deg, spin rpm, apex yd, hang s,
    # carry yd (2018-19 hang time: the published average is a data error, the 6.35 s there is derived: not shipped)
    cited = {"2008": (165.22, 11.26, 2670, 30.2, 6.2, 268.8), "2013-14": (167.18, 11.01, 2619, 32.7, 6.2, 272.6),
             "2017-18": (169.17, 11.06, 2641, 35.1, 6.3, 277.6), "2018-19": (170.25, 9.98, 2637, 33.1, None, 279.8),
             "2022-23": (172.85, 10.49, 2571, 34.0, 6.4, 283.8)}
    table = carry_table("pgatour_radar_driver")
    assert flight_fit.labels("pgatour_radar_driver") == tuple(cited)
    for i, (ball, launch, spin, apex, hang, carry) in enumerate(cited.values()):
        assert table.ball_speed[i] == pytest.approx(ball * MPH)
        assert np.degrees(table.launch_angle[i]) == pytest.approx(launch)
        assert table.spin_rate[i] == pytest.approx(spin * RPM)
        assert table.max_height[i] == pytest.approx(apex * YARD)
        assert table.carry[i] == pytest.approx(carry * YARD)
        assert np.isnan(table.flight_time[i]) if hang is None else table.flight_time[i] == pytest.approx(hang)
    assert np.all(np.isnan(table.land_angle))  # PGA TOUR publishes no descent angle
    assert _document()["rows"][-1]["attempts"] == [113979, 121740]


def test_radar_2022_23_season_agrees_with_trackmans_2023_driver_row():
    # the source's cross-check, restated: TrackMan's 2023 PGA driver row is the same competition tee shots
    season, row = carry_table("pgatour_radar_driver"), carry_table("trackman_carry_pga_2023")
    assert row.clubs[0] == "Driver"
    assert season.ball_speed[-1] == pytest.approx(row.ball_speed[0], rel=0.015)
    assert np.degrees(season.launch_angle[-1] - row.launch_angle[0]) == pytest.approx(0.0, abs=0.2)
    assert season.spin_rate[-1] == pytest.approx(row.spin_rate[0], rel=0.015)
    assert season.carry[-1] == pytest.approx(row.carry[0], rel=0.01)


def test_radar_seasons_fly_in_the_air_of_the_season_mean_density():
    table = carry_table("pgatour_radar_driver")
    assert table.air == {"temperature": pytest.approx(298.15), "relative_humidity": 0.5, "altitude": 0.0}
    # altitude-evidence.md section 2: season-mean density 0.992 of dry sea-level air at 25 degC (1.184 kg/m^3)
    assert float(air_density(298.15, 101325.0, 0.5)) == pytest.approx(0.992 * 1.184, rel=0.005)
    # the tour tables state no air: flown in the standard air as before
    assert all(carry_table(name).air == {} for name in TABLES)


def test_c0_bounds_are_the_measured_balls_drag_offsets():
    assert flight_fit.C0_BOUNDS == (aerodynamics.MEASURED_FIT_OFFSETS["modern"],
                                    aerodynamics.MEASURED_FIT_OFFSETS["bh_1976"])
    assert flight_fit.C0_BOUNDS == pytest.approx((0.1913, 0.2346), abs=1e-4)


def test_coefficients_with_the_fitted_models_own_c0_fly_measured_fit_exactly():
    table = carry_table("trackman_carry")
    # the named model flown as a Python function too, so that both take the same (numpy) integrator: the compiled
    # kernel flies a name, and tests/test_flight_kernel.py holds the kernel to the numpy path
    named = validate_carry(lambda s, re: aerodynamics.aero_coefficients(s, re, "measured_fit"), table)
    again = validate_carry(flight_fit.coefficients(), table)
    np.testing.assert_array_equal(named["carry"], again["carry"])
    # c0 enters the drag additively: 0.01 more drag at the same S and Re
    cd0, cl0 = aerodynamics.aero_coefficients(0.1, 1.5e5, "measured_fit")
    cd1, cl1 = flight_fit.coefficients(aerodynamics.MEASURED_FIT["c0"] + 0.01, 1.1)(np.array(0.1), np.array(1.5e5))
    assert cd1 == pytest.approx(cd0 + 0.01) and cl1 == pytest.approx(1.1 * cl0)


def test_fly_takes_a_coefficient_function_and_refuses_anything_else():
    none = flight.fly(60.0, 0.3, 300.0, model=lambda s, re: (np.zeros_like(s), np.zeros_like(s)), spin_decay=0.0)
    vacuum = flight.fly(60.0, 0.3, 300.0, model="vacuum")
    assert none["carry_distance"] == pytest.approx(vacuum["carry_distance"], rel=1e-9)
    with pytest.raises(ValueError, match="unknown model"):
        flight.fly(60.0, 0.3, 300.0, model=3)


def test_fit_reproduces_its_constants_from_the_yaml():
    result = _fit()
    assert result["c0"] == pytest.approx(flight_fit.FITTED["c0"], rel=1e-4)
    assert not result["at_bound"] and result["lift_scale"] == 1.0 and result["rows"] == 5
    # measured: RMS 0.69 % over the five seasons (carry to ground impact, 25 degC)
    assert result["rms_carry_error"] < 0.01


def test_fit_recovers_a_drag_level_it_was_given():
    # flights made with c0 = 0.225 and taken as measured: the least squares must return 0.225
    table = carry_table("pgatour_radar_driver")
    made = validate_carry(flight_fit.coefficients(0.225), table)["carry"]
    result = flight_fit.fit(tables={"pgatour_radar_driver": attrs.evolve(table, carry=made)})
    assert result["c0"] == pytest.approx(0.225, abs=2e-5) and result["rms_carry_error"] < 1e-4


def test_fit_stays_inside_the_measured_balls_range():
    # carries 30 % short of the seasons' want more drag than any measured ball has: the fit stops at the bound
    table = carry_table("pgatour_radar_driver")
    result = flight_fit.fit(tables={"pgatour_radar_driver": attrs.evolve(table, carry=0.7 * table.carry)})
    assert result["c0"] == pytest.approx(flight_fit.C0_BOUNDS[1]) and result["at_bound"]


def test_fit_refuses_what_it_cannot_fit():
    with pytest.raises(ValueError, match="parameters"):
        flight_fit.fit(parameters=("lift_scale",))
    with pytest.raises(ValueError, match="observables"):
        flight_fit.fit(observables=("land_angle",))
    with pytest.raises(ValueError, match="no row left"):
        flight_fit.fit(exclude=("pgatour_radar_driver",))
    with pytest.raises(ValueError, match="two groups"):
        flight_fit.leave_one_out(by="source")


def test_leave_one_season_out_regression_guard():
    # measured: c0 0.1945-0.1962 without each season; the season held out within -1.5..+1.0 %
    folds = _folds()
    assert [fold["group"] for fold in folds] == list(flight_fit.labels("pgatour_radar_driver"))
    for fold in folds:
        assert fold["c0"] == pytest.approx(flight_fit.FITTED["c0"], abs=0.0015), fold["group"]
        assert abs(fold["c0"] - flight_fit.FITTED["c0"]) > 5e-5, fold["group"]  # the season really was left out
        assert abs(fold["carry_error"][0]) < 0.02, fold["group"]


def test_lift_scale_bounds_are_the_spread_of_the_measured_lift_rows():
    low, high = flight_fit.lift_scale_bounds()
    assert 0.6 < low < 1.0 < high < 1.4  # measured: 0.76-1.19 (10th-90th percentile at S <= 0.2)


def test_tour_tables_held_out_regression_guard_and_what_stays_wrong():
    # measured (docs/flight.md): classic 2.23 %, PGA 2023 2.67 %, LPGA 2023 2.13 % RMS with c0 fitted on the radar
    # seasons; no row beyond 5.9 % (the PGA 2023 PW short); what stays wrong: the woods, hybrids and 3-5 irons land
    # 3.7-9.4 deg shallower than the tables say, with heights within 6.2 yd
    checks = flight_fit.held_out(flight_fit.FITTED["c0"])
    for name, rms in (("trackman_carry", 0.0235), ("trackman_carry_pga_2023", 0.028),
                      ("trackman_carry_lpga_2023", 0.0225)):
        check = checks[name]
        assert check["rms_carry_error"] <= rms, name
        assert check["rms_without_driver"] <= 0.03, name  # the held-out rows without the drivers meet it too
        assert np.all(np.abs(check["carry_error"]) <= 0.06), name
        assert np.all(np.abs(check["height_error"]) <= 6.5 * YARD), name
        assert np.all(np.abs(np.degrees(check["land_error"])) <= 10.0), name
        long_shots = [i for i, club in enumerate(check["table"].clubs) if club in ("5-wood", "Hybrid", "5-iron")]
        assert np.all(np.degrees(check["land_error"][long_shots]) < -3.5), name


def test_a_lift_scale_fitted_with_the_apex_is_contradicted_by_the_hang_times():
    # c0 and a lift scale fitted to the seasons' carries and apex heights (measured: 0.2064, 1.118) fly the seasons
    # 0.42-0.54 s longer than their measured hang times, where c0 alone is within 0.21 s: not shipped
    both = flight_fit.fit(parameters=("c0", "lift_scale"), observables=("carry", "max_height"))
    assert both["c0"] == pytest.approx(0.2064, abs=0.001) and both["lift_scale"] == pytest.approx(1.118, abs=0.005)
    table = carry_table("pgatour_radar_driver")
    timed = np.isfinite(table.flight_time)
    scaled = flight_fit.coefficients(both["c0"], both["lift_scale"])
    late = validate_carry(scaled, table)["flight_time"] - table.flight_time
    alone = validate_carry(flight_fit.coefficients(flight_fit.FITTED["c0"]), table)["flight_time"] - table.flight_time
    assert np.all(late[timed] > 0.35) and np.all(np.abs(alone[timed]) < 0.25)


def test_held_out_drag_level_meets_3_percent_on_every_tour_table():
    """The issue's target with the drag level fitted only to measured flights that are not the tour tables (the PGA
    TOUR radar seasons): 2.23 / 2.67 / 2.13 % on the classic, PGA 2023 and LPGA 2023 tables."""
    checks = flight_fit.held_out(flight_fit.FITTED["c0"])
    assert all(check["rms_carry_error"] <= 0.03 for check in checks.values())


@pytest.mark.parametrize("function, fragment", [
    (lambda s, re: (np.full_like(s, np.nan), 0.1 + 0 * s), "returned CD nan"),
    (lambda s, re: (-0.2 + 0 * s, 0.1 + 0 * s), "returned CD -0.2"),
    (lambda s, re: (0.25 + 0 * s, np.full_like(s, np.inf)), "CL inf"),
    (lambda s, re: 0.25 + 0 * s, "must return (CD, CL)"),
    (lambda s, re: (s, s, s), "must return (CD, CL)"),
    (lambda s, re: (np.ones(7), np.ones(7)), "must return (CD, CL)"),
], ids=["nan", "negative drag", "infinite lift", "one array", "three arrays", "wrong shape"])
def test_fly_refuses_a_coefficient_function_with_a_wrong_answer(function, fragment):
    """A caller's (S, Re) -> (CD, CL) answering NaN, a negative drag or the wrong shape is one ValueError naming
    what it returned: before, NaN gave NaN carries and CD -0.2 a 279 m 'carry' (drag pushing the ball), silently;
    with two shots, a single array of CD was unpacked as CD and CL."""
    speeds, angles, spins = np.array([70.0, 75.0]), np.radians([11.0, 12.0]), np.array([270.0, 260.0])
    with pytest.raises(ValueError, match=r"model: the function .*" + fragment.replace("(", r"\(").replace(")", r"\)")):
        flight.fly(speeds, angles, spins, model=function)
    # two numbers, and a stacked (2, n) array, are answers
    constant = flight.fly(speeds, angles, spins, model=lambda s, re: (0.25, 0.15))
    stacked = flight.fly(speeds, angles, spins, model=lambda s, re: np.stack([0.25 + 0 * s, 0.15 + 0 * s]))
    np.testing.assert_array_equal(constant["carry_distance"], stacked["carry_distance"])


GOOD_TABLE = {"name": "t", "kind": "measurement", "source": "a test table",
              "units": {"ball_speed": "mph", "launch_angle": "deg", "spin_rate": "rpm", "carry": "yd"},
              "rows": [{"club": "Driver", "ball_speed": 167.0, "launch_angle": 10.9, "spin_rate": 2686, "carry": 275}]}


@pytest.mark.parametrize("change, fragment", [
    ({"kind": "model output"}, "kind: expected 'measurement'"),
    ({"units": {**GOOD_TABLE["units"], "carry": "m"}}, "carry: 'm' not accepted"),
    ({"units": {**GOOD_TABLE["units"], "max_height": "ft"}}, "max_height: 'ft' not accepted"),
    ({"units": {k: v for k, v in GOOD_TABLE["units"].items() if k != "spin_rate"}}, "missing ['spin_rate']"),
    ({"rows": [{**GOOD_TABLE["rows"][0], "carry": None}]}, "row 1 (Driver): no carry"),
    ({"rows": [{k: v for k, v in GOOD_TABLE["rows"][0].items() if k != "ball_speed"}]},
     "row 1 (Driver): no ball_speed"),
    ({"air": {"temperature_degF": 77}}, "air: unknown ['temperature_degF']"),
    ({"air": {"relative_humidity": 50}}, "relative_humidity: expected a number from 0 to 1, got 50"),
    ({"air": {"temperature_degC": "25 degC"}}, "temperature_degC: expected a number"),
], ids=["kind", "carry in m", "height in ft", "no spin column", "empty carry", "no ball speed", "air key",
        "humidity in percent", "temperature as text"])
def test_a_malformed_carry_table_is_one_clear_message(tmp_path, monkeypatch, change, fragment):
    """Tables may lack the optional columns and state their air, but a wrong unit, a missing required cell or an
    unknown air key is refused naming the file: before, a missing carry cell was read as NaN (an RMS of NaN), an
    unknown air key was dropped (the table flown in standard air) and the rest were bare asserts (gone under -O)."""
    from impactlab.data import carry

    (tmp_path / "bad.yaml").write_text(yaml.safe_dump({**GOOD_TABLE, **change}))
    (tmp_path / "good.yaml").write_text(yaml.safe_dump({**GOOD_TABLE, "air": {"temperature_degC": 25}}))
    monkeypatch.setattr(carry.resources, "files", lambda package: tmp_path)
    good = carry.carry_table.__wrapped__("good")
    assert good.air == {"temperature": pytest.approx(298.15)} and np.isnan(good.max_height[0])
    with pytest.raises(ValueError, match="impactlab/data/validation/bad.yaml: ") as caught:
        carry.carry_table.__wrapped__("bad")
    assert fragment in str(caught.value)


@pytest.mark.parametrize("module, argv, fragment", [
    ("impactlab.data.carry", ["nosuch"], "unknown model nosuch"),
    ("impactlab.data.carry", ["measured_fit", "--bogus"], "unrecognized arguments: --bogus"),
    ("validation.flight.flight_fit", ["measured_fit"], "unrecognized arguments: measured_fit"),
])
def test_the_flight_commands_refuse_a_wrong_argument_with_exit_code_2(module, argv, fragment, capsys):
    """python -m impactlab.data.carry / validation.flight.flight_fit: before, an unknown model was a ValueError
    traceback (exit 1) and flight_fit ignored any argument and ran its 6-second report."""
    import importlib

    with pytest.raises(SystemExit) as caught:
        importlib.import_module(module).main(argv)
    assert caught.value.code == 2
    err = capsys.readouterr().err
    assert fragment in err and "Traceback" not in err


# -- oracles added with the flight_fit mutants (benchmarks/mutation.py -k flightfit carry-air; review5) ------------

def _fly_rows(table, c0, **air):
    """The table's launches flown directly by flight.fly with measured_fit at drag level c0 (not through
    validate_carry or flight_fit's bookkeeping)."""
    return flight.fly(table.ball_speed, table.launch_angle, table.spin_rate, model=flight_fit.coefficients(c0), **air)


def test_each_fold_reports_its_own_season_flown_without_it():
    """Leave-one-out: each fold's held-out error is that one season's carry error, flown in the season's air
    with the c0 fitted without it."""
    table = carry_table("pgatour_radar_driver")
    for i, fold in enumerate(_folds()):
        assert fold["carry_error"].shape == (1,), fold["group"]
        carry = _fly_rows(table, fold["c0"], temperature=298.15, relative_humidity=0.5, altitude=0.0)["carry_distance"]
        assert fold["carry_error"][0] == pytest.approx(carry[i] / table.carry[i] - 1.0, rel=1e-9, abs=1e-12)


def test_explicit_air_overrides_the_air_a_table_states():
    """validate_carry(..., temperature=...) flies at that temperature, the table's other air kept: the fit's
    15 degC sensitivity (docs/flight.md) must not silently fly at the table's 25 degC."""
    table = carry_table("pgatour_radar_driver")
    cold = validate_carry("measured_fit", table, temperature=288.15)["carry"]
    direct = flight.fly(table.ball_speed, table.launch_angle, table.spin_rate, temperature=288.15,
                        relative_humidity=0.5, altitude=0.0)["carry_distance"]
    np.testing.assert_allclose(cold, direct, rtol=1e-12)
    assert np.all(validate_carry("measured_fit", table)["carry"] > cold)  # 25 degC air is thinner: longer


def test_held_out_height_and_land_errors_are_model_minus_table():
    """As docs/flight.md states them: the PGA 2023 table flown directly in the standard air, minus the table."""
    table = carry_table("trackman_carry_pga_2023")
    direct = _fly_rows(table, flight_fit.FITTED["c0"])
    check = flight_fit.held_out(flight_fit.FITTED["c0"], tables=("trackman_carry_pga_2023",))
    check = check["trackman_carry_pga_2023"]
    np.testing.assert_allclose(check["height_error"], direct["apex_height"] - table.max_height, rtol=1e-12)
    np.testing.assert_allclose(check["land_error"], direct["landing_angle"] - table.land_angle, rtol=1e-12)


def test_lift_scale_bounds_are_the_documented_spread():
    """docs/flight.md: 0.76-1.19, the 10th-90th percentile of measured over fitted CL at S <= 0.2."""
    assert flight_fit.lift_scale_bounds() == pytest.approx((0.76, 1.19), abs=0.006)
