"""The paper's claims (physics brief 8), checked on the shipped studies of studies/paper/."""

from pathlib import Path

import pytest

import impactlab
from impactlab.plot.paper import fig6_claims, fig7_claims, table1_claims

PAPER = Path(__file__).resolve().parents[1] / "studies" / "paper"


@pytest.fixture(scope="module")
def fig6():
    return impactlab.run_study(PAPER / "fig6_friction.yaml")


@pytest.fixture(scope="module")
def fig7():
    return impactlab.run_study(PAPER / "fig7_tangential_force.yaml")


@pytest.fixture(scope="module")
def table1():
    return impactlab.run_study(PAPER / "table1_vertical_launch_ratio.yaml")


def _check(claim):
    assert claim.holds, f"{claim.source}: {claim.statement}: {claim.detail}"


@pytest.mark.parametrize("index", range(4))
def test_fig6_claims(fig6, index):
    _check(fig6_claims(fig6)[index])


@pytest.mark.parametrize("model", ["maw", "maw_annuli"])
@pytest.mark.parametrize("index", range(3))
def test_fig7_claims_with_both_methods(fig7, model, index):
    _check(fig7_claims(fig7, model)[index])


@pytest.mark.parametrize("index", range(3))
def test_table1_claims(table1, index):
    _check(table1_claims(table1)[index])


def test_claims_can_fail(fig6):
    # the rigid model cannot show the low-friction reversal of Fig. 6: the check must say so
    claims = fig6_claims(fig6, model="rigid_coulomb")
    assert not claims[2].holds or not claims[3].holds


@pytest.mark.slow
def test_report_is_written_from_result_files(tmp_path, fig6, fig7, table1):
    from impactlab.cli import main
    from impactlab.io.results import write_results

    results = tmp_path / "results"
    results.mkdir()
    for name in ("fig3_plate",):
        write_results(impactlab.run_study(PAPER / f"{name}.yaml"), results / "fig3-plate.h5")
    write_results(fig6, results / "fig6-friction.h5")
    write_results(fig7, results / "fig7-tangential-force.h5")
    write_results(table1, results / "table1-vertical-launch-ratio.h5")
    assert main(["paper", str(results), "-o", str(tmp_path / "paper.md")]) == 0
    text = (tmp_path / "paper.md").read_text()
    assert "| Table 1 |" in text and "**no**" not in text
    assert "| driver | " in text
