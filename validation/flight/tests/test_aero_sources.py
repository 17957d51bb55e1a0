"""measured_fit cross-validated by source (validation.flight.aero_sources; aero_fit's exclude / data / own_k).

Oracles: the measurement file read here with yaml (row counts per stage from its own thresholds); the shipped model
(impactlab.physics.aerodynamics); a stage a source has no rows in is left bit-identical; a source whose rows are
duplicated under another block predicts itself; a ball group's own k and offset are the least squares of its rows
alone (numpy lstsq), given the shared Re slope; Naruo et al.'s largest spin ratio pi d N / U by hand; flight_fit's
fitted drag level.
"""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest
import yaml

from validation.flight import aero_fit, aero_sources, flight_fit
from impactlab.physics.aerodynamics import aero_coefficients


@pytest.fixture(scope="module")
def document():
    return yaml.safe_load(resources.files("impactlab.data.validation").joinpath("aero_coefficients.yaml").read_text())


@pytest.fixture(scope="module")
def full():
    return aero_fit.fit()


def _with(**changes) -> dict:
    return {**aero_fit.measurements(), **changes}


def test_every_block_belongs_to_one_source(document):
    listed = [block for blocks in aero_sources.SOURCES.values() for block in blocks]
    assert sorted(listed) == sorted(document["blocks"]) and len(set(listed)) == len(listed)
    with pytest.raises(ValueError, match="unknown source 'lyu'"):
        aero_sources.blocks_of("lyu")


def test_the_refit_machinery_flies_measured_fit_when_nothing_is_left_out(full):
    assert aero_fit.fit(exclude=(), own_k=()) == full
    s, re = np.meshgrid(np.linspace(0.0, 1.2, 13), np.geomspace(3e4, 3e5, 17))
    for mine, shipped in zip(aero_sources.coefficients(full)(s, re), aero_coefficients(s, re, "measured_fit")):
        np.testing.assert_allclose(mine, shipped, rtol=2e-5, atol=1e-6)  # the shipped constants have six figures


@pytest.mark.parametrize("source", ["naruo_2004", "bridgestone_patents"])
def test_leaving_out_a_source_drops_exactly_its_rows_from_each_stage(document, full, source):
    limits = document["supercritical_re"]
    rows = [(block["group"], row) for key in aero_sources.SOURCES[source] for block in [document["blocks"][key]]
            for row in block["rows"]]
    sc = [(g, r) for g, r in rows if r[0] is None or r[0] >= limits[g]]
    crisis = [(g, r) for g, r in rows if g == "modern" and r[0] is not None and r[0] < limits[g]]
    drop = {"lift supercritical": sum(r[3] is not None for _, r in sc),
            "drag supercritical": sum(r[2] is not None for _, r in sc),
            "drag crisis": sum(r[2] is not None for _, r in crisis),
            "lift crisis": sum(r[3] is not None for _, r in crisis)}
    refit = aero_fit.fit(exclude=aero_sources.blocks_of(source))
    assert {key: full["rows"][key] - refit["rows"][key] for key in drop} == drop
    assert drop["lift supercritical"] > 0


def test_a_source_without_lift_rows_leaves_the_lift_stage_untouched():
    # Acushnet's CL blanked: leaving it out can change the drag, never the lift fitted to the other rows
    m = aero_fit.measurements()
    acushnet = np.isin(m["block"], aero_sources.SOURCES["acushnet_us6729976"])
    data = _with(cl=np.where(acushnet, np.nan, m["cl"]))
    kept, left = aero_fit.fit(data=data), aero_fit.fit(data=data, exclude=aero_sources.SOURCES["acushnet_us6729976"])
    assert left["lift"] == kept["lift"]  # bit for bit
    assert left["offsets"]["modern"] != kept["offsets"]["modern"]
    # a ball group without rows has no offset, not the least-squares start value
    assert np.isnan(left["offsets"]["acushnet_invention"]) and np.isnan(left["offsets"]["acushnet_prior_art"])


def test_a_left_out_source_duplicated_elsewhere_predicts_itself(full):
    m = aero_fit.measurements()
    naruo = m["block"] == "naruo_2004"
    data = {key: (np.concatenate([value, value[naruo]]) if isinstance(value, np.ndarray) else value)
            for key, value in m.items()}
    data["block"] = np.concatenate([m["block"], np.full(int(naruo.sum()), "naruo_copy")])
    refit = aero_fit.fit(data=data, exclude=("naruo_2004",))
    for key in ("lift", "crisis"):
        np.testing.assert_allclose(refit[key], full[key], rtol=1e-6)
    assert refit["k"] == pytest.approx(full["k"], rel=1e-6)
    assert refit["offsets"]["naruo_2004"] == pytest.approx(full["offsets"]["naruo_2004"], rel=1e-6)
    for name in ("cd", "cl"):
        assert aero_sources.source_residuals(refit, ("naruo_2004",))[name] == pytest.approx(
            aero_sources.source_residuals(full, ("naruo_2004",))[name], rel=1e-5)


def test_the_residual_of_another_ball_is_its_supercritical_form_by_hand(document, full):
    rows = np.array(document["blocks"]["naruo_2004"]["rows"], float)
    a, b = full["lift"]
    lift = a * rows[:, 1] / (1 + b * rows[:, 1])
    cd = full["offsets"]["naruo_2004"] + full["c_re"] * rows[:, 0] / 1e5 + full["k"] * lift**2
    got = aero_sources.source_residuals(full, ("naruo_2004",), own_offset=True)
    assert got["cd"] == pytest.approx(np.sqrt(np.mean((cd - rows[:, 2]) ** 2)), rel=1e-12)
    assert got["cl"] == pytest.approx(np.sqrt(np.mean((lift - rows[:, 3]) ** 2)), rel=1e-12)
    assert (got["n_cd"], got["n_cl"]) == (13, 13)


def test_a_group_with_its_own_k_is_the_least_squares_of_its_rows_alone(document):
    result = aero_fit.fit(own_k=("bh_1976",))
    rows = np.array([r for r in document["blocks"]["bearman_harvey_1976"]["rows"]
                     if r[2] is not None and r[0] >= document["supercritical_re"]["bh_1976"]], float)
    a, b = result["lift"]
    design = np.column_stack([np.ones(len(rows)), (a * rows[:, 1] / (1 + b * rows[:, 1])) ** 2])
    offset, k = np.linalg.lstsq(design, rows[:, 2] - result["c_re"] * rows[:, 0] / 1e5, rcond=None)[0]
    assert result["offsets"]["bh_1976"] == pytest.approx(offset, rel=1e-5)
    assert result["k_groups"]["bh_1976"] == pytest.approx(k, rel=1e-4)
    assert result["k_groups"]["modern"] == result["k"] != result["k_groups"]["bh_1976"]


def test_a_left_out_set_that_empties_a_stage_is_refused_with_the_stage_named():
    crisis = ("lyu_2020_fig3_b330rx", "lyu_2020_fig3_chromesoft", "lyu_2020_fig3_prov1", "lyu_2018_fig3a",
              "bridgestone_patents")
    with pytest.raises(ValueError, match=r"stage 3 \(the modern balls' drag crisis\) without rows"):
        aero_fit.fit(exclude=crisis)
    with pytest.raises(ValueError, match="unknown block"):
        aero_fit.fit(exclude=("lyu_2020",))
    with pytest.raises(ValueError, match="unknown ball group"):
        aero_fit.fit(own_k=("tour",))


def test_naruo_rows_at_another_re(full):
    # 167 rev/s at 25 m/s (Re 7.09e4): S = pi d N / U by hand
    assert aero_sources.naruo_reach(70900.0) == pytest.approx(np.pi * 0.0427 * 167 / 25.0, rel=1e-12)
    assert aero_sources.naruo_reach(125000.0) == pytest.approx(np.pi * 0.0427 * 167 / (125000 / 2836), rel=1e-12)
    m = aero_sources.naruo_at(65000.0)  # below the ball's crisis end (7e4): the rows leave stages 1-2
    naruo = m["block"] == "naruo_2004"
    assert np.all(m["re"][naruo] == 65000.0) and not m["supercritical"][naruo].any()
    assert np.array_equal(m["re"][~naruo], aero_fit.measurements()["re"][~naruo], equal_nan=True)
    assert aero_fit.fit(data=m)["rows"]["lift supercritical"] == full["rows"]["lift supercritical"] - 13
    assert aero_sources.naruo_within_reach()["s"].size == aero_fit.measurements()["s"].size - 2  # S 1.0, 1.13


def test_the_advance_held_beyond_the_measured_spin_changes_no_fitted_row_only_the_high_spin(full):
    cap = aero_sources.ADVANCE_CAPS[0]
    m = aero_fit.measurements()
    crisis = (m["group"] == 0) & ~m["supercritical"] & np.isfinite(m["cd"])
    assert cap == pytest.approx(0.276) and m["s"][crisis].max() <= cap
    held, free = aero_sources.coefficients(full, advance_cap=cap), aero_sources.coefficients(full)
    assert np.array_equal(held(m["s"][crisis], m["re"][crisis])[0], free(m["s"][crisis], m["re"][crisis])[0])
    # at S 0.6 the held crisis sits at Re_d exp(-m 0.276): the logistic step there by hand
    re_l, sigma, beta, s_l, re_d, w_d, d, adv = full["crisis"]
    step = lambda mid: d / (1 + np.exp((5e4 - mid) / w_d))  # noqa: E731
    added = held(0.6, 5e4)[0] - free(0.6, 5e4)[0]
    assert added == pytest.approx(step(re_d * np.exp(-adv * cap)) - step(re_d * np.exp(-adv * 0.6)), rel=1e-9)
    assert np.array_equal(held(0.6, 5e4)[1], free(0.6, 5e4)[1])  # the lift is not the crisis step's


def test_the_drag_level_on_the_radar_seasons_is_flight_fits(full):
    assert aero_sources.radar_c0(full) == pytest.approx(flight_fit.FITTED["c0"], abs=2e-5)


@pytest.mark.parametrize("argv, message", [(["--source", "lyu"], "invalid choice"),
                                           (["naruo_2004"], "unrecognized arguments")])
def test_the_report_command_refuses_a_wrong_argument(argv, message, capsys):
    with pytest.raises(SystemExit) as raised:
        aero_sources.main(argv)
    assert raised.value.code == 2 and message in capsys.readouterr().err


def test_the_report_of_one_source(capsys):
    assert aero_sources.main(["--source", "bridgestone_patents"]) == 0
    out = capsys.readouterr().out
    assert out.count("| bridgestone_patents | 8 / 8 |") == 1 and "variant" not in out


def test_the_non_spinning_row_the_advance_rests_on_moved_or_counted_in_the_crisis(full):
    m, moved = aero_fit.measurements(), aero_sources.still_at_75k(0.05)
    changed = np.flatnonzero(~np.isclose(moved["cd"], m["cd"], equal_nan=True))
    assert changed.size == 1 and m["block"][changed[0]] == "lyu_2018_fig3a" and m["re"][changed[0]] == 75000.0
    assert moved["cd"][changed[0]] == pytest.approx(0.302 + 0.05)
    rows = aero_fit.fit(data=aero_sources.still_at_75k(in_crisis=True))["rows"]
    assert rows["drag supercritical"] == full["rows"]["drag supercritical"] - 1
    assert rows["drag crisis"] == full["rows"]["drag crisis"] + 1


def test_a_crisis_constant_left_on_its_search_bound_is_named(full):
    assert aero_fit.crisis_at_bounds(full["crisis"]) == []
    crisis = list(full["crisis"])
    crisis[4], crisis[7] = 3e4, 5.0  # Re_d on its lower bound, m on its upper
    assert aero_fit.crisis_at_bounds(crisis) == ["Re_d", "m"]
