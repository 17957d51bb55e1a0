"""Values pinned, not only presence: the rules of the least-squares core in numbers worked by hand, a fitted offset
added to each row, per-row flags and handedness of session rows after a row is skipped, the units of a stored
result sent to a simulator, and the club catalogue's inertias against the numbers of their sources.

Each test was checked against a realistic bug planted in the code it covers (named in its docstring): the bug makes
it fail. The oracles are written from the documented rules and the sources' numbers, not from the code."""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from impactlab.data.fit import least_squares
from impactlab.data.fit.calibration import apply
from impactlab.data.sessions.reader import read_session_text
from impactlab.io.interchange import gspro_shots
from impactlab.scene.catalogue import CLUB_CATALOGUE

MPH_SI = 1609.344 / 3600.0  # m/s in a mile per hour (the international mile), written here independently
DEG = math.pi / 180.0


# -- least squares: the rules of the module docstring ------------------------------------------------------------
def test_identified_means_a_sigma_below_half_the_allowed_range_not_half_a_unit():
    """One residual (x - 0) / 0.8: sigma = 0.8 exactly. Range 2 (0.8 < 1.0): identified; range 1.5 (0.8 > 0.75):
    not, its uncertainty infinite. Kills: the range dropped from the rule (sigma < 0.5), or the rule's side flipped."""
    jacobian, residual = np.array([[1 / 0.8]]), np.array([0.0])
    wide = least_squares.analyse(jacobian, residual, np.array([0.0]), np.array([-1.0]), np.array([1.0]), True)
    assert wide["identified"].tolist() == [True] and wide["uncertainties"][0] == pytest.approx(0.8, rel=1e-12)
    narrow = least_squares.analyse(jacobian, residual, np.array([0.0]), np.array([-0.75]), np.array([0.75]), True)
    assert narrow["identified"].tolist() == [False] and math.isinf(narrow["uncertainties"][0])


def test_at_its_bound_is_a_thousandth_of_the_range_from_it():
    """Range 1000: 0.5 from the upper bound is at it (0.5 <= 1), 2 from it is not. Range 0.01: 1e-4 from the
    lower bound is not at it (1e-4 > 1e-5). Kills: the range dropped (distance <= 1e-3), the distance to the far
    bound taken, or the comparison's side flipped."""
    jacobian, residual = np.array([[1.0]]), np.array([0.0])
    low, high = np.array([0.0]), np.array([1000.0])
    assert least_squares.analyse(jacobian, residual, np.array([999.5]), low, high, True)["at_bound"].tolist() == [True]
    assert least_squares.analyse(jacobian, residual, np.array([998.0]), low, high, True)["at_bound"].tolist() == [False]
    assert least_squares.analyse(jacobian, residual, np.array([0.5]), low, high, True)["at_bound"].tolist() == [True]
    small = least_squares.analyse(np.array([[1e4]]), residual, np.array([1e-4]), np.array([0.0]), np.array([0.01]),
                                  True)
    assert small["at_bound"].tolist() == [False]


def test_uncertainties_without_sigmas_count_the_identified_parameters_in_the_degrees_of_freedom():
    """Unit weights, four residuals (1, -1, 1, -1) of slope 1 in x0, none in x1 (not identified): C = (J^T J)^-1
    s^2 with s^2 = SSR / (n - 1) = 4 / 3, so sigma(x0) = sqrt(1/4 * 4/3) = 0.5774; with sigmas stated, 0.5 (no
    rescale); with as many residuals as parameters, no rescale either. Kills: n - p (both parameters) instead of
    the identified ones, n instead of n - p, the rescale applied to weighted residuals, or the variance reported."""
    jacobian = np.array([[1.0, 0.0]] * 4)
    residuals = np.array([1.0, -1.0, 1.0, -1.0])
    values, low, high = np.array([0.0, 0.5]), np.array([-10.0, 0.0]), np.array([10.0, 1.0])
    unit = least_squares.analyse(jacobian, residuals, values, low, high, False)
    assert unit["identified"].tolist() == [True, False] and unit["scaled"]
    assert unit["uncertainties"][0] == pytest.approx(math.sqrt(1 / 3), rel=1e-12)
    stated = least_squares.analyse(jacobian, residuals, values, low, high, True)
    assert not stated["scaled"] and stated["uncertainties"][0] == pytest.approx(0.5, rel=1e-12)
    exact = least_squares.analyse(np.array([[2.0]]), np.array([3.0]), np.array([0.0]), np.array([-10.0]),
                                  np.array([10.0]), False)
    assert not exact["scaled"] and exact["uncertainties"][0] == pytest.approx(0.5, rel=1e-12)


def test_near_its_bound_is_within_one_sigma_and_not_at_it():
    """sigma 0.8 (as above), 0.5 from the bound: near; 1.0 from it: not near. Kills: near without the sigma."""
    jacobian, residual = np.array([[1 / 0.8]]), np.array([0.0])
    near = least_squares.analyse(jacobian, residual, np.array([0.5]), np.array([-9.0]), np.array([1.0]), True)
    assert near["near_bound"].tolist() == [True] and near["at_bound"].tolist() == [False]
    far = least_squares.analyse(jacobian, residual, np.array([0.0]), np.array([-9.0]), np.array([1.0]), True)
    assert far["near_bound"].tolist() == [False]


# -- a fitted offset is added to each row's measured value -------------------------------------------------------
def test_a_fitted_strike_offset_is_added_to_each_rows_measured_strike_and_friction_replaces_every_rows():
    """Kills: the offset replacing the measured strike (every row at the offset), the offset subtracted, or the
    face's gain given to an iron (a flat face: no spring-like gain)."""
    inputs = {"speed": np.array([40.0, 42.0, 44.0]), "strike_high": np.array([0.001, -0.002, 0.0]),
              "friction": np.array([0.3, 0.3, 0.3]),
              "face_bulge_radius": np.array([0.305, np.inf, np.inf])}  # a driver's bulge, then two flat irons
    out = apply(inputs, ("strike_high", "friction", "face_restitution_gain"), (0.003, 0.45, 0.08))
    assert out["strike_high"] == pytest.approx([0.004, 0.001, 0.003], abs=1e-15)
    assert out["friction"].tolist() == [0.45, 0.45, 0.45]
    assert out["club_restitution_gain"].tolist() == [0.08, 0.0, 0.0]
    assert inputs["strike_high"].tolist() == [0.001, -0.002, 0.0]  # the caller's arrays untouched


# -- per-row flags and handedness of session rows ----------------------------------------------------------------
def test_flags_and_handedness_stay_with_their_rows_when_a_row_before_them_is_skipped():
    """Row 1 names no club (skipped), row 2 is a left-hander's with an estimated spin, row 3 a right-hander's.
    Kills: flags or handedness indexed by position in the kept rows instead of the row (each shifts by one), the
    L/R spellings mapped the wrong way, a flagged value kept."""
    text = ("Club,Club Speed [mph],Attack Angle [deg],Dyn. Loft [deg],Ball Speed [mph],Launch Angle [deg],"
            "Spin Rate [rpm],Handedness,flags\n"
            ",90,-4,24,120,18,7000,R,\n"
            "7i,85,-4,24,118,17,6800,L,spin_rate:estimated\n"
            "7i,86,-3,25,121,16,6500,rh,\n")
    session = read_session_text(text, "s.csv")
    assert session.text["handedness"] == ("right", "left", "right")
    assert session.flags[("spin_rate", "estimated")].tolist() == [False, True, False]
    table = session.shot_table()
    assert table.handedness == ("left", "right") and table.labels == ("line 3", "line 4")
    assert np.isnan(table.measured["spin_rate"][0])  # the estimated spin left out of the comparison
    assert table.measured["spin_rate"][1] == pytest.approx(6500 * 2 * math.pi / 60)
    assert table.measured["ball_speed"] == pytest.approx([118 * MPH_SI, 121 * MPH_SI])
    every = session.shot_table(include_flagged=True)
    assert every.measured["spin_rate"] == pytest.approx([6800 * 2 * math.pi / 60, 6500 * 2 * math.pi / 60])


# -- the units of a stored result sent to a simulator ------------------------------------------------------------
def _result(ball_speed: float, speed_units: str, spin: float, spin_units: str, carry: float, carry_units: str):
    def scalar(value, units):
        return xr.DataArray([value], dims=("model",), attrs={"units": units})
    return xr.Dataset({"ball_speed": scalar(ball_speed, speed_units),
                       "vertical_launch_angle": scalar(12.0, "degree"),
                       "horizontal_launch_angle": scalar(-2.0, "degree"),
                       "spin_rate": scalar(spin, spin_units), "spin_axis": scalar(10.0, "degree"),
                       "carry_distance": scalar(carry, carry_units)}, coords={"model": ["maw"]})


def test_a_stored_result_reaches_the_simulator_in_mph_rpm_degrees_and_yards():
    """A result file stores m/s, rpm, degrees and metres (their ``units`` attributes): GSPro gets mph, rpm,
    degrees and yards, whatever units the file states. Kills: mph taken for knots or km/h, the units attribute
    ignored (an edited file's 134.2 mph sent as 300 mph), yards for metres, back and side spin swapped."""
    stored = gspro_shots(_result(60.0, "m/s", 2500.0, "rpm", 182.88, "m"))[0]["BallData"]
    assert stored["Speed"] == pytest.approx(round(60.0 / MPH_SI, 2), abs=1e-9)  # 134.22 mph
    assert stored["CarryDistance"] == pytest.approx(200.0, abs=1e-9)  # 182.88 m is 200 yd exactly
    assert (stored["VLA"], stored["HLA"], stored["TotalSpin"]) == (12.0, -2.0, 2500.0)
    assert stored["BackSpin"] == pytest.approx(round(2500 * math.cos(10 * DEG), 1), abs=1e-9)  # 2462.0
    assert stored["SideSpin"] == pytest.approx(round(2500 * math.sin(10 * DEG), 1), abs=1e-9)  # 434.1
    edited = gspro_shots(_result(134.22, "mph", 2500 * 2 * math.pi / 60, "rad/s", 600.0, "ft"))[0]["BallData"]
    assert edited["Speed"] == pytest.approx(134.22, abs=0.006)
    assert edited["TotalSpin"] == pytest.approx(2500.0, abs=0.06)
    assert edited["CarryDistance"] == pytest.approx(200.0, abs=0.06)  # 600 ft


# -- the club catalogue's inertias against their sources ---------------------------------------------------------
#: g cm^2 per oz in^2: 28.349523125 g (the avoirdupois ounce) x 2.54^2 cm^2
OZ_IN2_G_CM2 = 28.349523125 * 2.54**2


def _campau_up(number: int) -> float:
    """Campau's moment [g cm^2] of iron ``number``: 13.619 oz in^2 at the 2-iron, 16.423 at the 9-iron, linear."""
    return (13.619 + (number - 2) / 7 * (16.423 - 13.619)) * OZ_IN2_G_CM2


def _expected_moments() -> dict[str, dict[str, float]]:
    """Each club's six components [g cm^2] from the numbers its source text states (CLUB_SOURCES, the catalogue
    estimates' texts), independent of how the catalogue computes them."""
    # the measured driver (Proceedings 49 (2020) 47, Table 1), its x the face normal (target), y up, z the toe
    driver = {"toe": 4085.0, "up": 5679.0, "target": 2843.0, "toe_up": 0.5, "toe_target": 530.2,
              "up_target": -733.0}
    out = {"driver": driver}
    for index, key in enumerate(("3_wood", "5_wood", "7_wood")):  # (1800, 3300, 1700) at 212 g, scaled by mass
        scale = (212.0 + 5 * index) / 212.0
        out[key] = {"toe": 1800 * scale, "up": 3300 * scale, "target": 1700 * scale}
    for index, key in enumerate(("3_hybrid", "4_hybrid", "5_hybrid")):  # (1300, 2900, 2200) at 228 g
        scale = (228.0 + 5 * index) / 228.0
        out[key] = {"toe": 1300 * scale, "up": 2900 * scale, "target": 2200 * scale}
    # irons: up Campau's; toe 800 at the 6-iron, 20 a club; wedges from the pitching wedge's 900 (lob as sand);
    # target = up + toe - 200
    irons = {"3_iron": (3, 740.0), "4_iron": (4, 760.0), "5_iron": (5, 780.0), "6_iron": (6, 800.0),
             "7_iron": (7, 820.0), "8_iron": (8, 840.0), "9_iron": (9, 860.0), "pitching_wedge": (9, 900.0),
             "gap_wedge": (9, 920.0), "sand_wedge": (9, 940.0), "lob_wedge": (9, 940.0)}
    for key, (number, toe) in irons.items():
        up = _campau_up(number)
        out[key] = {"toe": toe, "up": up, "target": up + toe - 200.0}
    return out


def test_every_catalogue_club_has_the_moments_its_source_states():
    """Kills: the driver's axes mapped in another order (its 5679 about the toe), a product's sign dropped, the
    wood or hybrid moments not scaled by the mass (or scaled the wrong way), a toe/target swap, the iron estimate's
    200 g cm^2 added instead of taken off, g cm^2 taken as 1e-6 kg m^2."""
    expected = _expected_moments()
    assert set(expected) == set(CLUB_CATALOGUE)
    for key, head in CLUB_CATALOGUE.items():
        got = {name: value * 1e7 for name, value in head.inertia_components().items()}  # kg m^2 -> g cm^2
        want = {"toe_up": 0.0, "toe_target": 0.0, "up_target": 0.0, **expected[key]}
        assert got == pytest.approx(want, rel=1e-9, abs=1e-9), key
        tensor = np.asarray(head.inertia)
        assert np.allclose(tensor, tensor.T), key  # one tensor, symmetric


# -- the drag crisis of measured_fit, from its documented formula ------------------------------------------------
def test_the_drag_crisis_is_the_documented_logistic_step_in_re_moved_by_spin():
    """``measured_fit``'s drag: c0 + c_re Re/1e5 + k CL_sc^2 + d / (1 + exp((Re - Re_d exp(-m S)) / w_d)), with
    CL_sc = a S / (1 + b S) (the formula as aerodynamics.py and docs/flight.md write it; evaluated here with exp,
    the code uses tanh). Through the crisis (Re_d -+ 3 w_d) at S 0 and 0.1. Kills: the step twice as steep (tanh
    without its 1/2), the spin advance's sign, the width or the midpoint taken from the wrong constant."""
    from impactlab.physics import aerodynamics

    c = aerodynamics.MEASURED_FIT
    for s in (0.0, 0.1):
        midpoint = c["re_d"] * math.exp(-c["m"] * s)
        for re in (midpoint - 3 * c["w_d"], midpoint - c["w_d"], midpoint, midpoint + c["w_d"],
                   midpoint + 3 * c["w_d"]):
            lift = c["a"] * s / (1 + c["b"] * s)
            expected = (c["c0"] + c["c_re"] * re / 1e5 + c["k"] * lift**2
                        + c["d"] / (1 + math.exp((re - midpoint) / c["w_d"])))
            cd, _ = aerodynamics.aero_coefficients(s, re, model="measured_fit")
            assert float(cd) == pytest.approx(expected, rel=1e-9), (s, re)
