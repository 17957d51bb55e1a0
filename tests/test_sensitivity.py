"""Sensitivity and model-form studies (impactlab.study.sensitivity, impactlab.run.sensitivity): indices of analytic
cases, ranges, bad input."""

from pathlib import Path

import numpy as np
import pytest

import impactlab
from impactlab.cli import main
from impactlab.errors import FieldError
from impactlab.io.results import open_results, write_results

ROOT = Path(__file__).resolve().parent.parent

#: a solid sphere on a fixed rigid face at 20 deg: rolling for every mu >= 0.3 and e >= 0.7, since the slip
#: V sin(a) stops when tan(a) < mu (1 + e)(1 + 1/K^2) = 1.79 at the smallest (docs/models.md, rigid_coulomb)
ROLLING = """
name: rolling
ball: {radius: 0.021335 m, mass: 0.04593 kg, inertia_factor: 0.4}
face: {rigid: true}
contact: {friction: 0.4, restitution: 0.8}
impact: {speed: 35 m/s, angle: 20 deg}
models: [rigid_coulomb, {name: restitution, tangential_restitution: 0.0}]
outputs: [spin_rate, ball_speed, tangential_restitution]
sensitivity:
  method: METHOD
  samples: 64
  seed: 3
  parameters:
    contact.friction: {low: 0.3, high: 0.5}
    contact.restitution: {low: 0.7, high: 0.9}
    impact.speed: {low: 30 m/s, high: 40 m/s}
  choices:
    rolling_laws: [rigid_coulomb, restitution]
"""


def rolling(method="sobol"):
    return impactlab.run_study(ROLLING.replace("METHOD", method))


@pytest.mark.slow
def test_an_output_of_one_input_has_its_whole_variance_in_that_input():
    """Rolling regime: spin = (5/7) V sin(a) / R whatever mu and e, so speed carries all of its variance."""
    ds = rolling()
    assert np.all(np.abs(ds.sampled.sel(model="rigid_coulomb", output="tangential_restitution")) < 1e-12)
    spin = dict(model="rigid_coulomb", output="spin_rate")
    s1, st = ds.S1.sel(**spin), ds.ST.sel(**spin)
    assert float(s1.sel(parameter="impact.speed")) == pytest.approx(1.0, abs=0.05)
    assert float(st.sel(parameter="impact.speed")) == pytest.approx(1.0, abs=0.05)
    for name in ("contact.friction", "contact.restitution"):  # friction does not matter above the rolling threshold
        assert abs(float(s1.sel(parameter=name))) < 1e-9 and abs(float(st.sel(parameter=name))) < 1e-9
    # ball speed: e and V both matter, friction not at all
    speed = ds.ST.sel(model="rigid_coulomb", output="ball_speed")
    assert float(speed.sel(parameter="contact.friction")) < 1e-9
    assert float(speed.sel(parameter="contact.restitution")) > 0.05 and float(speed.sel(parameter="impact.speed")) > 0.5
    # beta does not move: no indices, zero spread
    assert np.all(np.isnan(ds.ST.sel(model="rigid_coulomb", output="tangential_restitution")))
    assert float(ds.spread.sel(model="rigid_coulomb", output="tangential_restitution")) == 0.0


def test_morris_effect_of_speed_on_rolling_spin_is_the_closed_form():
    """Spin is linear in V: every elementary effect is (5/7) sin(a) (40 - 30 m/s) / R, with no scatter."""
    ds = rolling("morris")
    spin = dict(model="rigid_coulomb", output="spin_rate")
    expected = 5.0 / 7.0 * np.sin(np.radians(20.0)) * 10.0 / 0.021335 * 60.0 / (2.0 * np.pi)
    assert float(ds.mu_star.sel(parameter="impact.speed", **spin)) == pytest.approx(expected, rel=1e-9)
    assert float(ds.sigma.sel(parameter="impact.speed", **spin)) < 1e-6 * expected
    assert float(ds.mu_star.sel(parameter="contact.friction", **spin)) < 1e-9


def test_model_form_range_and_numerical_error():
    """Two laws that agree in the rolling regime have no model-form range; a closed form has no numerical error."""
    ds = rolling()
    assert np.all(np.abs(ds.model_form_range.sel(choice="rolling_laws").values) < 1e-9)
    assert np.all(ds.numerical_error.values == 0.0)
    # nominal spin is the closed form
    expected = 5.0 / 7.0 * 35.0 * np.sin(np.radians(20.0)) / 0.021335 * 60.0 / (2.0 * np.pi)
    assert float(ds.nominal.sel(model="rigid_coulomb", output="spin_rate")) == pytest.approx(expected, rel=1e-12)


@pytest.mark.slow
def test_elastic_impact_makes_the_inelastic_laws_one_and_maw_reports_its_error(tmp_path):
    """At e = 1 the adjusted speed and the hysteretic law are the same elastic problem: no model-form range.

    ``maw``'s numerical error (tolerance against a tenth of it) is positive and below its tolerance's bound on beta.
    """
    text = """
ball: {preset: urethane_tour}
face: {rigid: true}
contact: {friction: 0.4, restitution: 1.0}
impact: {speed: 35 m/s, angle: 25 deg}
models: [maw, {name: maw, id: maw_hysteretic, inelastic: hysteretic}, rigid_coulomb]
outputs: [spin_rate, tangential_restitution]
sensitivity:
  samples: 8
  parameters:
    contact.friction: {low: 0.3, high: 0.5}
    ball.poisson_ratio: {low: 0.45, high: 0.49}
  choices:
    inelastic_law: [maw, maw_hysteretic]
  models: [maw]
"""
    ds = impactlab.run_study(text)
    beta = dict(output="tangential_restitution")
    assert float(ds.model_form_range.sel(choice="inelastic_law", **beta)) < 2e-4
    # maw grips (beta > 0), the rigid model leaves rolling: the tangential law moves beta by maw's beta
    assert float(ds.model_form_range.sel(choice="all models", **beta)) == pytest.approx(
        float(ds.nominal.sel(model="maw", **beta)), abs=1e-12)
    error = float(ds.numerical_error.sel(model="maw", **beta))
    assert 0.0 < error < 1e-4
    # the file keeps the indices and the provenance
    path = write_results(ds, tmp_path / "s.h5")
    back = open_results(path)
    assert back.attrs["study_type"] == "sensitivity" and "SALib" in back.attrs["analyser"]
    assert back.attrs["salib_version"] and "inelastic_law" in back.attrs["sensitivity"]
    np.testing.assert_allclose(back.ST.values, ds.ST.values)


@pytest.mark.parametrize("block, path, words", [
    ("parameters: {contact.friciton: {low: 0.3, high: 0.5}}", "sensitivity.parameters.contact.friciton",
     "contact.friction"),
    ("parameters: {contact.friction: {low: 0.5, high: 0.3}}", "sensitivity.parameters.contact.friction", "low below"),
    ("parameters: {contact.friction: {low: -0.1, high: 0.3}}", "sensitivity.parameters.contact.friction.low",
     "[0, inf)"),
    ("{samples: 12, parameters: {contact.friction: {low: 0.3, high: 0.5}}}", "sensitivity.samples", "power of 2"),
    ("{method: sobel, parameters: {contact.friction: {low: 0.3, high: 0.5}}}", "sensitivity.method", "sobol"),
    ("{choices: {law: [maw, mwa]}, parameters: {contact.friction: {low: 0.3, high: 0.5}}}",
     "sensitivity.choices.law[1]", "maw"),
    ("parameters: {impact.speed: {low: 30 m/s, high: 40 m/s}}", "sensitivity.parameters.impact.speed", "spread"),
    # structured by cattrs: unknown keys refused at each level, with the keys the block takes
    ("{sampels: 64, parameters: {contact.friction: {low: 0.3, high: 0.5}}}", "sensitivity.sampels",
     "a key of the sensitivity block"),
    ("parameters: {contact.friction: {low: 0.3, hihg: 0.5}}", "sensitivity.parameters.contact.friction.hihg",
     "low, high, spread"),
    ("{choices: [maw], parameters: {contact.friction: {low: 0.3, high: 0.5}}}", "sensitivity.choices",
     "a mapping from a choice's name"),
])
def test_bad_sensitivity_block_gives_one_message(block, path, words):
    text = f"""
ball: {{preset: urethane_tour}}
face: {{rigid: true}}
contact: {{friction: 0.4, restitution: 0.8}}
impact: {{speed: 35 m/s, angle: 25 deg}}
sweep: {{impact.speed: [30 m/s, 40 m/s]}}
models: [maw, rigid_coulomb]
sensitivity: {block if block.startswith("{") else "{" + block + "}"}
"""
    with pytest.raises(FieldError) as caught:
        impactlab.load_study(text)
    message = str(caught.value)
    assert path in message and words in message


def test_bad_spread_is_one_line_on_the_command_line(tmp_path, capsys):
    study = tmp_path / "bad.yaml"
    study.write_text(ROLLING.replace("METHOD", "sobol").replace("contact.friction: {low: 0.3, high: 0.5}",
                                                                  "impact.angle: {spread: 80 deg}"))
    assert main(["run", str(study), "-o", str(tmp_path / "bad.h5"), "-q"]) == 2
    error = capsys.readouterr().err.strip()
    assert error.count("\n") == 0 and "sensitivity.parameters.impact.angle.spread" in error and "high end" in error
    assert not (tmp_path / "bad.h5").exists()


def test_shipped_study_parses_with_its_golf_deliveries():
    study = impactlab.load_study(ROOT / "studies" / "sensitivity.yaml")
    spec = study.sensitivity
    assert study.n_cases == 3 and spec.method == "sobol" and spec.samples <= 64
    assert {name for name, _ in spec.choices} == {"inelastic_law", "tangential_law"}
    assert len(spec.parameters) == 6


@pytest.mark.slow
def test_command_line_writes_shows_and_draws_a_sensitivity_study(tmp_path, capsys):
    study = tmp_path / "rolling.yaml"
    study.write_text(ROLLING.replace("METHOD", "morris").replace("samples: 64", "samples: 6"))
    assert main(["run", str(study), "-o", str(tmp_path / "r.h5"), "--plot", "-q"]) == 0
    assert sorted(path.name for path in tmp_path.glob("*.png")) == ["r.png", "r_indices.png"]
    assert all(path.stat().st_size > 20_000 for path in tmp_path.glob("*.png"))
    assert main(["show", str(tmp_path / "r.h5")]) == 0
    shown = capsys.readouterr().out
    assert "parameter      3  contact.friction, contact.restitution, impact.speed" in shown
    assert "SALib.analyze.morris" in shown and "30 to 40 m/s" in shown


def test_nominal_validity_flags_are_kept():
    """The rigid rolling ball leaves no assumption of its model: no flags, with their meanings kept in the file."""
    ds = rolling()
    assert np.all(ds.validity.values == 0) and "dundurs_coupling" in ds.validity.attrs["flag_meanings"]
