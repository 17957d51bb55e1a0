"""docs/testing.md quotes the committed mutation results, and the record keeps the rules of benchmarks/mutation.py:
a kill is confirmed on the unmutated tree, a timeout is never a kill."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "benchmarks"))
import mutation  # noqa: E402

RECORDS = ["benchmarks/mutation_results.json", "benchmarks/mutation_results_pinned.json"]


@pytest.mark.parametrize("name", RECORDS)
def test_the_docs_quote_each_committed_record(name):
    record = json.loads((ROOT / name).read_text())
    assert mutation.describe(record, name) in (ROOT / "docs" / "testing.md").read_text()


@pytest.mark.parametrize("name", RECORDS)
def test_every_kill_was_confirmed_and_no_timeout_counts_as_one(name):
    record = json.loads((ROOT / name).read_text())
    for mutant in record["mutants"]:
        if mutant["status"] == "killed":
            assert mutant["detail"].endswith("(passes unmutated)"), mutant
        assert not (mutant["status"] == "killed" and "timeout" in mutant["detail"]), mutant
    assert mutation.counts(record["mutants"]) == record["counts"]


def test_a_timeout_is_undecided_and_an_unconfirmed_failure_is_no_kill(monkeypatch):
    """The verdicts of mutation.py on planted pytest outcomes (no subprocess): a timeout, a pass, a failure."""
    outcomes = {"timeout": None, "pass": (0, "1 passed\n"), "fail": (1, "FAILED tests/a.py::t - boom\n")}
    for kind, expected in (("timeout", "undecided"), ("pass", "survived"), ("fail", "pending")):
        monkeypatch.setattr(mutation, "_pytest", lambda *args, kind=kind: outcomes[kind])
        status, detail = mutation._verdict(sys.executable, ROOT, {}, ["tests/a.py"], 1.0)
        assert status == expected, (kind, status, detail)
    assert mutation._verdict.__module__ == "mutation"
    assert "mdr-error-constant" not in mutation.EQUIVALENT
