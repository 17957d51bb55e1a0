"""Result files follow the CF metadata conventions: checked by an independent checker (IOOS compliance-checker).

The oracle is the checker and the UDUNITS-2 database it carries, not impactlab's own code; the second test
reads the file back with h5py, below xarray, so that what xarray would hide (a coordinate's _FillValue) is seen.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import h5py
import pytest

import impactlab
from impactlab.io.results import write_results
from impactlab.model.diagnostics import ValidityWarning

ROOT = Path(__file__).resolve().parents[1]
STUDIES = {
    "histories": ROOT / "studies" / "paper" / "fig7_tangential_force.yaml",  # a time axis and force histories
    "golf": ROOT / "studies" / "paper" / "table1_vertical_launch_ratio.yaml",  # deliveries, degrees and rpm
}


@pytest.fixture(scope="module")
def result_files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("cf")
    files = {}
    for key, study in STUDIES.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ValidityWarning)  # the known notes of a golf-sized contact
            dataset = impactlab.run_study(study)
        files[key] = write_results(dataset, folder / f"{key}.nc")  # cf checkers want the .nc suffix
    return files


@pytest.mark.slow
@pytest.mark.parametrize("key", sorted(STUDIES))
def test_a_result_file_passes_the_cf_compliance_checker(result_files, key, tmp_path):
    runner = pytest.importorskip("compliance_checker.runner")
    report = tmp_path / "report.json"
    runner.CheckSuite.load_all_available_checkers()
    passed, errors = runner.ComplianceChecker.run_checker(
        str(result_files[key]), ["cf:1.8"], 0, "normal", output_filename=str(report), output_format="json")
    findings = json.loads(report.read_text())["cf:1.8"]
    failed = [message for priority in ("high_priorities", "medium_priorities")
              for check in findings[priority] if check["value"][0] < check["value"][1] for message in check["msgs"]]
    assert passed and not failed, failed


def test_coordinates_carry_no_fill_value_and_the_file_names_its_conventions(result_files):
    with h5py.File(result_files["histories"], "r") as file:
        assert file.attrs["Conventions"] == "CF-1.8"
        history = file.attrs["history"]
        assert "impactlab" in (history.decode() if isinstance(history, bytes) else history)
        dims = [name for name in file if "CLASS" in file[name].attrs]  # netCDF dimension scales
        # CF keeps a coordinate named "time" for calendar time; elapsed time since contact has its own name
        assert {"time_since_contact", "model"} <= set(dims) and "time" not in file
        for name in dims:
            assert "_FillValue" not in file[name].attrs, name
        assert file["time_since_contact"].attrs["units"] in (b"s", "s")
        assert "standard_name" not in file["time_since_contact"].attrs  # CF's "time" would demand "s since EPOCH"


def test_angles_are_spelled_as_udunits_spells_them(result_files):
    with h5py.File(result_files["golf"], "r") as file:
        units = {name: file[name].attrs.get("units") for name in file if "units" in file[name].attrs}
    units = {name: (unit.decode() if isinstance(unit, bytes) else unit) for name, unit in units.items()}
    assert units["vertical_launch_angle"] == "degree" and units["spin_rate"] == "rpm"
    assert "deg" not in units.values()  # not a UDUNITS unit


def test_a_file_reads_back_with_its_time_axis_named_as_in_memory(result_files):
    dataset = impactlab.open_results(result_files["histories"])
    assert "time" in dataset.dims and "time_since_contact" not in dataset.variables
    assert float(dataset.time[0]) == 0.0 and dataset.time.attrs["units"] == "s"
