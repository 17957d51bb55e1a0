"""Extension points, each declared by a plugin and none by editing impactlab (issue 34, item 3).

tests/plugin_pkg holds a plugin package (``impactlab_testplugin`` and its dist-info with entry_points.txt): put on
a fresh interpreter's path, it registers a model with an option, a scene field and a derived output through
entry points only. The study below sweeps the option and the field, asks for the output and draws a user's shot
file; a second interpreter checks the messages of what a user can get wrong.
"""

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import impactlab
from impactlab.errors import FieldError
from impactlab.scene.materials import BALL_PRESETS

PLUGIN = Path(__file__).parent / "plugin_pkg"

SHOTS = ("club,club_speed [mph],attack_angle [deg],dynamic_loft [deg],ball_speed [mph],spin_rate [rpm]\n"
         "Driver,90,0,15,133,2900\nDriver,100,0,15,148,2700\nDriver,110,0,15,,2600\n")

STUDY = textwrap.dedent("""\
    name: plug
    ball: {preset: urethane_tour}
    face: {rigid: true, mass: 200 g}
    contact: {friction: 0.4, restitution: 0.8}
    delivery: {club_speed: 100 mph, path: 0 deg, face_angle: 0 deg, attack_angle: 0 deg, dynamic_loft: 15 deg}
    plugin: {tack: 0.1}
    sweep:
      delivery.club_speed: [80 mph, 100 mph, 120 mph]
      plugin.tack: [0.0, 0.1]
      model_option.sticky_plugin.grip: [0.0, 0.2]
    models: [sticky_plugin, rigid_coulomb]
    outputs: [ball_speed, spin_rate, normal_impulse, tangential_impulse, impulse_ratio]
    plots:
      - {name: ratio, y: impulse_ratio, x: grip, select: {tack: 0.0, club_speed: 100 mph}}
      - {name: speed, y: ball_speed, x: club_speed, select: {tack: 0.0, grip: 0.2}, measured: [shots.csv]}
    """)


def _python(*args, path=(PLUGIN,), cwd=None, timeout=240):
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([*map(str, path), os.environ.get("PYTHONPATH", "")]))
    return subprocess.run([sys.executable, *args], capture_output=True, text=True, env=env, cwd=cwd, timeout=timeout)


@pytest.mark.slow
def test_a_plugin_package_sweeps_its_option_and_field_adds_an_output_and_draws_a_users_file(tmp_path):
    (tmp_path / "plug.yaml").write_text(STUDY)
    (tmp_path / "shots.csv").write_text(SHOTS)
    done = _python("-m", "impactlab", "run", "plug.yaml", "-o", "out.h5", "--plot", "-q", cwd=tmp_path)
    assert done.returncode == 0, done.stderr
    assert (tmp_path / "out_ratio.png").stat().st_size > 0 and (tmp_path / "out_speed.png").stat().st_size > 0
    assert not (tmp_path / "out.h5.progress").exists()  # each value's run kept its chunks there until the file
    with xr.open_dataset(tmp_path / "out.h5") as ds:  # the result reads without the plugin
        ratio = ds["impulse_ratio"]
        assert ratio.dims == ("model", "club_speed", "tack", "grip")
        assert ratio.attrs["units"] == "1" and "friction the impact used" in ratio.attrs["long_name"]
        assert ds["tack"].attrs["study_path"] == "plugin.tack"
        ours = ratio.sel(model="sticky_plugin").values
        # the output is the function of the model's own arrays
        np.testing.assert_allclose(ours, (ds["tangential_impulse"] / ds["normal_impulse"]).sel(
            model="sticky_plugin").values, rtol=1e-12)
        # by hand: the ball leaves gripping (the cap mu = 0.4 is far), J_t/J_n = (1 + beta) tan(15 deg)/(1 + e)
        # x W_nn/W_ss on a 200 g point-mass head, beta = grip + tack
        ball = BALL_PRESETS["urethane_tour"]
        m, k2, big_m = ball.mass, ball.inertia_factor, 0.2
        base = np.tan(np.radians(15.0)) / 1.8 * (1 / m + 1 / big_m) / ((1 + 1 / k2) / m + 1 / big_m)
        beta = ds["tack"].values[:, None] + ds["grip"].values[None, :]
        np.testing.assert_allclose(ours, np.broadcast_to(base * (1 + beta), ours.shape), rtol=1e-9)
        # rigid_coulomb has no grip option: the same along it, and at beta = 0 the plugin's rolling branch is its
        same = ratio.sel(model="rigid_coulomb").values
        assert np.all(same == same[..., :1]) and np.allclose(same, base, rtol=1e-9)


@pytest.mark.slow
def test_what_a_user_gets_wrong_with_a_plugin_is_named(tmp_path):
    broken = tmp_path / "broken_plugin-0.1.dist-info"
    broken.mkdir()
    (broken / "METADATA").write_text("Metadata-Version: 2.1\nName: broken-plugin\nVersion: 0.1\n")
    (broken / "entry_points.txt").write_text("[impactlab.outputs]\nbad_output = impactlab_testplugin:NOT_THERE\n"
                                             "launch_angle = impactlab_testplugin:IMPULSE_RATIO\n")
    (tmp_path / "shots.csv").write_text(SHOTS)
    script = textwrap.dedent(f"""
        import json, warnings, yaml
        warnings.simplefilter("always")
        with warnings.catch_warnings(record=True) as caught:
            import impactlab
        from impactlab.errors import FieldError
        from impactlab.vocabulary import PLUGIN_OUTPUTS
        base = yaml.safe_load({STUDY!r})
        out = {{"warnings": [str(w.message) for w in caught], "plugin_outputs": list(PLUGIN_OUTPUTS)}}
        for key, change in [("field", {{"plugin": {{"tak": 0.1}}}}),
                            ("range", {{"plugin": {{"tack": 0.9}}}}),
                            ("option", {{"sweep": {{"model_option.sticky_plugin.grp": [0.1]}}}}),
                            ("value", {{"sweep": {{"model_option.sticky_plugin.grip": [0.1, 2.0]}}}}),
                            ("entry", {{"sweep": {{"model_option.stiky.grip": [0.1]}}}})]:
            try:
                impactlab.load_study({{**base, **change}}, file={str(tmp_path / 'plug.yaml')!r})
                out[key] = "loaded"
            except FieldError as exc:
                out[key] = str(exc)
        print(json.dumps(out))
    """)
    done = _python("-c", script, path=(PLUGIN, tmp_path))
    assert done.returncode == 0, done.stderr
    out = json.loads(done.stdout.splitlines()[-1])
    assert out["plugin_outputs"] == ["impulse_ratio"]  # the broken ones skipped, the good one kept
    text = " | ".join(out["warnings"])
    assert "bad_output" in text and "NOT_THERE" in text and "the name is taken by impactlab's output" in text
    assert "plugin.tak" in out["field"] and "tack" in out["field"]
    assert "plugin.tack" in out["range"] and "0.9" in out["range"]
    assert "model_option.sticky_plugin.grp" in out["option"] and "grip" in out["option"]
    assert "model_option.sticky_plugin.grip[1]" in out["value"]
    assert "stiky" in out["entry"] and "sticky_plugin" in out["entry"]


# -- the same extension points with the built-in models, in this interpreter ----------------------------------------

OPTION_STUDY = {"name": "opt", "ball": {"preset": "urethane_tour"}, "face": {"rigid": True},
                "contact": {"friction": 0.3, "restitution": 0.8}, "impact": {"speed": "40 m/s", "angle": "20 deg"},
                "sweep": {"impact.angle": ["10 deg", "30 deg"],
                          "model_option.restitution.tangential_restitution": [0.0, 0.2, 0.4]},
                "models": ["restitution", "rigid_coulomb"], "outputs": ["spin_rate"]}


def test_a_model_option_is_swept_like_a_field():
    ds = impactlab.run_study(OPTION_STUDY)
    assert ds["spin_rate"].dims == ("model", "angle", "tangential_restitution")
    spin = ds["spin_rate"].sel(model="restitution").values
    # J_t = (1 + beta) m_t V_x below the Coulomb cap: the spin scales with 1 + beta, and beta = 0 is the rolling
    # branch of rigid_coulomb
    np.testing.assert_allclose(spin / spin[:, :1], np.broadcast_to([1.0, 1.2, 1.4], spin.shape), rtol=1e-12)
    np.testing.assert_allclose(spin[:, 0], ds["spin_rate"].sel(model="rigid_coulomb").values[:, 0], rtol=1e-12)


@pytest.mark.parametrize(("key", "values", "where"), [
    ("model_option.restitution.beta", [0.1], "sweep.model_option.restitution.beta"),
    ("model_option.nothere.tangential_restitution", [0.1], "sweep.model_option.nothere.tangential_restitution"),
    ("model_option.restitution.tangential_restitution", [0.1, 1.5],
     "sweep.model_option.restitution.tangential_restitution[1]"),
    ("model_option.restitution.tangential_restitution", [0.1, 0.1], "distinct values"),
])
def test_a_bad_option_sweep_is_refused_at_load_naming_it(key, values, where):
    study = {**OPTION_STUDY, "sweep": {"impact.angle": ["10 deg"], key: values}}
    with pytest.raises(FieldError, match=__import__("re").escape(where)):
        impactlab.load_study(study)


def test_a_figure_draws_a_users_shot_file_and_refuses_one_it_cannot(tmp_path):
    from impactlab.plot.figures import _shot_values, check_shot_files

    (tmp_path / "shots.csv").write_text(SHOTS)
    (tmp_path / "study.yaml").write_text(textwrap.dedent("""\
        name: s
        ball: {preset: urethane_tour}
        club: {preset: driver}
        contact: {friction: 0.4, restitution: 0.8}
        delivery: {club_speed: 100 mph, attack_angle: 0 deg, dynamic_loft: 15 deg}
        sweep: {delivery.club_speed: [90 mph, 110 mph]}
        models: [rigid_coulomb]
        outputs: [ball_speed]
        plots: [{name: a, y: ball_speed, x: club_speed, measured: [shots.csv]}]
        """))
    study = impactlab.load_study(tmp_path / "study.yaml")
    assert study.plots[0].measured == (str((tmp_path / "shots.csv").resolve()),)  # relative to the study file
    ys, xs, skipped = _shot_values(study.plots[0].measured[0], "ball_speed", "speed")
    # 133 and 148 mph at 90 and 100 mph club speed, in m/s; the third row has no ball speed and is skipped
    np.testing.assert_allclose(ys, np.array([133.0, 148.0]) * 0.44704)
    np.testing.assert_allclose(xs, np.array([90.0, 100.0]) * 0.44704)
    assert skipped == 1
    text = (tmp_path / "study.yaml").read_text()
    (tmp_path / "bad.yaml").write_text(text.replace("shots.csv", "missing.csv"))
    with pytest.raises(FieldError, match=r"plots\[0\]\.measured\[0\].*a shot file that exists"):
        impactlab.load_study(tmp_path / "bad.yaml")
    # a file that measures nothing the figure draws: refused before the run (impactlab run), exit 2, nothing written
    (tmp_path / "other.csv").write_text("club,club_speed [mph],spin_rate [rpm]\nDriver,100,2500\n")
    (tmp_path / "bad.yaml").write_text(text.replace("shots.csv", "other.csv"))
    with pytest.raises(FieldError, match=r"plots\[0\]\.measured\[0\].*measures an output the figure draws"):
        check_shot_files(impactlab.load_study(tmp_path / "bad.yaml"))
    from impactlab.cli import main

    assert main(["run", str(tmp_path / "bad.yaml"), "-o", str(tmp_path / "bad.h5"), "-q"]) == 2
    assert not (tmp_path / "bad.h5").exists()
