"""The one least-squares core of `fit` and `calibrate`: exact answers of hand-solved problems, standard deviations
(not variances), the reduced chi-square rescale, the identified / at-bound / near-bound rules, physical limits,
and the fit reports that say them (text and JSON), with the rows a fit or a validation could not use named."""

import json
import math

import numpy as np
import pytest

from impactlab.cli import main
from impactlab.data.fit import least_squares
from impactlab.data.fit.calibration import calibrate
from impactlab.data.sessions.shots import read_csv
from impactlab.model.registry import get_model

# a straight line y = a + b t through 5 points with unequal sigmas, solved by hand below (Numerical Recipes, 3rd
# ed., eqs. 15.2.6-15.2.9: S = sum 1/s^2, Sx = sum t/s^2, Sxx = sum t^2/s^2, Sy, Sxy; Delta = S Sxx - Sx^2;
# a = (Sxx Sy - Sx Sxy)/Delta, b = (S Sxy - Sx Sy)/Delta, var a = Sxx/Delta, var b = S/Delta)
T = np.array([0.0, 1.0, 2.0, 3.0, 4.0])
Y = np.array([1.1, 2.9, 5.2, 6.8, 9.1])
SIG = np.array([0.5, 0.5, 1.0, 1.0, 2.0])


def _line_by_hand(t, y, s):
    w = 1.0 / s**2
    S, Sx, Sxx, Sy, Sxy = w.sum(), (w * t).sum(), (w * t * t).sum(), (w * y).sum(), (w * t * y).sum()
    delta = S * Sxx - Sx**2
    return ((Sxx * Sy - Sx * Sxy) / delta, (S * Sxy - Sx * Sy) / delta), (Sxx / delta, S / delta)


def test_a_weighted_straight_line_gives_the_hand_solution_and_standard_deviations():
    (a, b), (var_a, var_b) = _line_by_hand(T, Y, SIG)
    solution = least_squares.solve(lambda x: (x[0] + x[1] * T - Y) / SIG, [0.0, 0.0], [-10, -10], [10, 10],
                                   weighted=True)
    assert solution.values == pytest.approx([a, b], abs=1e-7)
    # standard deviations: a mutant reporting the variance (0.19 and 0.043 here, against 0.44 and 0.21) fails
    assert solution.uncertainties == pytest.approx([math.sqrt(var_a), math.sqrt(var_b)], rel=1e-6)
    assert not solution.scaled and solution.identified.all() and not solution.at_bound.any()
    # correlation of a and b: -Sx / sqrt(S Sxx) (NR eq. 15.2.10)
    w = 1 / SIG**2
    assert solution.correlation[0, 1] == pytest.approx(-(w * T).sum() / math.sqrt(w.sum() * (w * T**2).sum()),
                                                       rel=1e-6)


def test_unit_weights_rescale_the_covariance_by_the_reduced_chi_square():
    (a, b), (var_a, var_b) = _line_by_hand(T, Y, np.ones(5))
    ssr = float(np.sum((a + b * T - Y) ** 2))
    solution = least_squares.solve(lambda x: x[0] + x[1] * T - Y, [0.0, 0.0], [-10, -10], [10, 10],
                                   weighted=False)
    assert solution.scaled
    scale = ssr / (5 - 2)  # n - p degrees of freedom
    assert solution.uncertainties == pytest.approx([math.sqrt(var_a * scale), math.sqrt(var_b * scale)], rel=1e-6)


def test_an_optimum_on_its_bound_is_reported_at_the_bound():
    # the data's mean is 2.0; the bounds allow at most 1.5: the constrained optimum is 1.5
    data = np.array([1.9, 2.0, 2.1])
    solution = least_squares.solve(lambda x: (x[0] - data) / 0.1, [0.5], [0.0], [1.5], weighted=True)
    assert solution.values[0] == pytest.approx(1.5, abs=1e-6)
    assert solution.at_bound.tolist() == [True] and solution.near_bound.tolist() == [False]
    text = least_squares.state(solution.values[0], solution.uncertainties[0], True, True, False)
    assert "AT ITS BOUND" in text


def test_a_bound_within_one_sigma_is_near_but_not_at_it():
    # mean 1.0, sigma of the mean 0.3/sqrt(3) = 0.173; upper bound 1.1 is 0.1 away: near, not at
    data = np.array([0.7, 1.0, 1.3])
    solution = least_squares.solve(lambda x: (x[0] - data) / 0.3, [0.0], [-5.0], [1.1], weighted=True)
    assert solution.values[0] == pytest.approx(1.0, abs=1e-7)
    assert solution.uncertainties[0] == pytest.approx(0.3 / math.sqrt(3), rel=1e-6)
    assert solution.near_bound.tolist() == [True] and solution.at_bound.tolist() == [False]


def test_a_parameter_the_data_do_not_depend_on_or_pin_is_not_identified():
    # y depends on x0 only: x1 has a zero Jacobian column
    solution = least_squares.solve(lambda x: (x[0] + 0.0 * x[1] - Y) / SIG, [0.0, 0.3], [-10, 0], [10, 1],
                                   weighted=True)
    assert solution.identified.tolist() == [True, False] and math.isinf(solution.uncertainties[1])
    # y depends on x weakly: sigma = 1/(0.01 sqrt(sum 1/s^2)) = 27 exceeds half the range (1): not pinned
    weak = least_squares.solve(lambda x: 0.01 * x[0] / SIG, [0.5], [-1.0], [1.0], weighted=True)
    assert weak.identified.tolist() == [False]


def test_a_physical_limit_exceeded_is_said():
    limit = least_squares.PhysicalLimit("COR", lambda f: f["e"] + f.get("gain", 0.0), 0.830, "USGA")
    assert limit.check({"e": 0.80, "gain": 0.05}).startswith("COR = 0.850 beyond the limit 0.83")
    assert limit.check({"e": 0.80}) is None
    solution = least_squares.solve(lambda x: np.array([x[0] - 0.9]) / 0.01, [0.5], [0.0], [1.0], weighted=True,
                                   names=["e"], limits=[limit])
    assert len(solution.beyond_limit) == 1 and "COR = 0.900" in solution.beyond_limit[0]


def test_usable_rows_leave_out_only_a_measured_value_not_predicted():
    predicted = np.array([[1.0, np.nan], [np.nan, 2.0], [1.0, 2.0]])
    measured = np.array([[1.0, np.nan], [1.0, 2.0], [1.0, 2.0]])
    assert least_squares.usable_rows(predicted, measured).tolist() == [True, False, True]


# a hand-written session no golf ball can make: 250 mph of ball speed off a 100 mph driver (smash factor 2.5;
# a conforming driver gives about 1.5). The restitution the fit needs is beyond its bound and the driver COR
# beyond the USGA/R&A limit of 0.830.
IMPOSSIBLE = """Shot,Club,Club Speed [mph],Attack Angle [deg],Dyn. Loft (deg),Ball Speed [mph],Launch Angle [deg]
fast-1,driver,100,0,12,250,12
fast-2,driver,100,0,12,250,12
"""


#: the same rows as a table written by hand (a launch monitor's CSV with a smash factor no club gives has these rows
#: skipped by the row rules, issue 32; a table its user wrote is taken as written)
IMPOSSIBLE_YAML = """name: impossible
units: {club_speed: mph, attack_angle: deg, dynamic_loft: deg, ball_speed: mph, vertical_launch_angle: deg}
rows:
  - {label: fast-1, club: driver, club_speed: 100, attack_angle: 0, dynamic_loft: 12, ball_speed: 250,
     vertical_launch_angle: 12}
  - {label: fast-2, club: driver, club_speed: 100, attack_angle: 0, dynamic_loft: 12, ball_speed: 250,
     vertical_launch_angle: 12}
"""


def test_a_calibration_at_its_bound_and_beyond_the_cor_limit_says_so_in_text_and_json(tmp_path, capsys):
    path = tmp_path / "impossible.yaml"
    path.write_text(IMPOSSIBLE_YAML)
    out = tmp_path / "fit.json"
    # the wood face's gain on the tour ball's own law: at its upper bound 0.15, and the driver's COR beyond 0.830
    assert main(["fit", str(path), "--model", "rigid_coulomb", "--parameter", "face_restitution_gain",
                 "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "AT ITS BOUND" in text and "BEYOND A PHYSICAL LIMIT" in text and "0.83" in text
    [entry] = json.loads(out.read_text())
    assert entry["at_bound"] == [True] and entry["values"] == pytest.approx([0.15], abs=1e-4)
    assert len(entry["beyond_limit"]) == 1 and "COR" in entry["beyond_limit"][0]
    # a 6-iron (no face gain: e is the ball's own) the same: the ball's restitution at its upper bound 0.95; no
    # wood gain fitted, so no COR statement
    path.write_text(IMPOSSIBLE_YAML.replace("driver", "6_iron"))
    assert main(["fit", str(path), "--model", "rigid_coulomb", "--parameter", "restitution",
                 "--json", str(out)]) == 0
    assert "AT ITS BOUND" in capsys.readouterr().out
    [entry] = json.loads(out.read_text())
    assert entry["at_bound"] == [True] and entry["values"] == pytest.approx([0.95], abs=1e-4)
    assert entry["beyond_limit"] == []


def test_a_row_the_model_cannot_predict_is_left_out_and_named(monkeypatch):
    from impactlab.data.fit import calibration

    table = read_csv(IMPOSSIBLE.replace("250", "150") + "odd,driver,100,0,12,150,12\n")
    real = calibration.predict

    def predict(model, inputs):
        out = real(model, inputs)
        if len(out["ball_speed"]) == 3:
            out["ball_speed"][2] = np.nan  # the model cannot predict the third row
        return out

    monkeypatch.setattr(calibration, "predict", predict)
    result = calibrate(get_model("rigid_coulomb")(), table, ["restitution"])
    assert result.unused_rows == ("odd",)
    assert math.isfinite(result.values[0]) and math.isfinite(result.rms_after)
