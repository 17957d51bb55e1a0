"""Result files: HDF5 round trip, plain-xarray readability, atomic writes."""

import errno
import h5py
import numpy as np
import pytest
import xarray as xr

import impactlab
from impactlab.errors import StudyError
from impactlab.io.results import write_results

STUDY = {"name": "io", "ball": {"preset": "urethane_tour"}, "face": {"preset": "steel", "mass": "200 g"},
         "contact": {"friction": 0.35, "restitution": 0.8}, "impact": {"speed": "100 mph", "angle": "12 deg"},
         "sweep": {"impact.angle": {"start": "5 deg", "stop": "45 deg", "num": 5}, "contact.friction": [0.2, 0.4]},
         "models": ["maw", "rigid_coulomb", {"name": "restitution", "tangential_restitution": 0.15}],
         "outputs": ["launch_angle", "spin_rate", "contact_time", "tangential_force"]}


@pytest.fixture(scope="module")
def dataset():
    return impactlab.run_study(STUDY)


def test_round_trip_is_identical(dataset, tmp_path):
    path = write_results(dataset, tmp_path / "out.h5")
    xr.testing.assert_identical(impactlab.open_results(path), dataset)
    with xr.open_dataset(path, engine="h5netcdf") as plain:
        # plain xarray reads the same, but for the history axis's name in the file (CF keeps "time" for calendars)
        xr.testing.assert_identical(plain.load().rename(time_since_contact="time"), dataset)
    with h5py.File(path) as handle:  # a real HDF5 file, readable without xarray
        assert handle["launch_angle"].shape == dataset.launch_angle.shape


def test_failed_write_leaves_the_existing_file_intact(dataset, tmp_path, monkeypatch):
    path = write_results(dataset, tmp_path / "out.h5")
    before = path.read_bytes()

    def explode(descriptor):  # the HDF5 image is written, then the disk turns out full
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr("impactlab.io.safe_output.os.fsync", explode)
    with pytest.raises(OSError):
        write_results(dataset.isel(angle=0), path)
    assert path.read_bytes() == before
    assert [p.name for p in tmp_path.iterdir()] == ["out.h5"]  # no temporary left behind


def test_open_results_refuses_other_files_clearly(tmp_path):
    with pytest.raises(StudyError, match="no such result file"):
        impactlab.open_results(tmp_path / "absent.h5")
    junk = tmp_path / "junk.h5"
    junk.write_text("not hdf5")
    with pytest.raises(StudyError, match="not an impactlab result file"):
        impactlab.open_results(junk)


def test_missing_reason_survives_the_file(dataset, tmp_path):
    back = impactlab.open_results(write_results(dataset, tmp_path / "out.h5"))
    assert "rigid_coulomb" in back.contact_time.attrs["missing"]
    assert np.all(np.isnan(back.tangential_force.sel(model="restitution").values))
