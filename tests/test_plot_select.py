"""A plot's ``select`` takes a quantity with its unit (issue 34: ``select: {high: 0 mm}`` was an internal error)."""

import textwrap

import numpy as np
import pytest
import xarray as xr
import yaml

import impactlab
from impactlab.cli import main
from impactlab.errors import FieldError

STUDY = textwrap.dedent("""\
    name: sel
    ball: {preset: urethane_tour}
    club: {preset: driver}
    contact: {friction: 0.4, restitution: 0.8}
    delivery: {club_speed: 115 mph, path: 0 deg, face_angle: 0 deg, attack_angle: -0.9 deg, dynamic_loft: 12.8 deg}
    sweep:
      strike.toe: {start: -20 mm, stop: 20 mm, num: 3}
      strike.high: {start: -10 mm, stop: 10 mm, num: 3}
    models: [rigid_coulomb]
    outputs: [spin_axis]
    plots:
      - {name: a, y: spin_axis, x: toe, select: {high: SELECT}}
    """)


def _study(select):
    return impactlab.load_study(yaml.safe_load(STUDY.replace("SELECT", select)))


def test_a_quantity_with_its_unit_selects_the_coordinate_in_its_own_unit():
    # 1 cm is 10 mm: the coordinate holds millimetres, so the plan must hold 10.0, not 1 or 0.01
    assert dict(_study("1 cm").plots[0].select) == {"high": 10.0}
    assert dict(_study("0 mm").plots[0].select) == {"high": 0.0}
    assert dict(_study("-0.01 m").plots[0].select) == {"high": -10.0}
    assert dict(_study("0").plots[0].select) == {"high": 0.0}  # a bare number: the coordinate's value as stored


@pytest.mark.parametrize("select", ["3 mm", "10 deg", "[0 mm, 2 mm]", "{a: 1}"])
def test_a_value_not_swept_is_refused_at_load_naming_the_choices(select):
    with pytest.raises(FieldError, match=r"plots\[0\]\.select\.high") as info:
        _study(select)
    if select == "3 mm":
        assert "-10 mm, 0 mm, 10 mm" in str(info.value)


def test_the_cli_draws_the_figure_and_refuses_before_running(tmp_path, capsys):
    path = tmp_path / "sel.yaml"
    path.write_text(STUDY.replace("SELECT", "0 mm"))
    assert main(["run", str(path), "-o", str(tmp_path / "out.h5"), "--plot", "-q"]) == 0
    assert (tmp_path / "out_a.png").stat().st_size > 0
    with xr.open_dataset(tmp_path / "out.h5") as ds:
        # the figure's line is the centre-height row of the result: heel and toe strikes curve opposite ways
        row = ds["spin_axis"].sel(high=0.0).squeeze().values
        assert np.sign(row[0]) == -np.sign(row[-1]) != 0
    path.write_text(STUDY.replace("SELECT", "3 mm"))
    assert main(["run", str(path), "-o", str(tmp_path / "bad.h5"), "-q"]) == 2
    assert not (tmp_path / "bad.h5").exists()
    assert "internal error" not in capsys.readouterr().err


def test_a_list_selects_several_values_each_converted():
    assert dict(_study("[-1 cm, 10 mm]").plots[0].select) == {"high": [-10.0, 10.0]}
