"""The contract's invariants at random points of the valid input space (hypothesis), and the numpy fallback.

Every model, at random speed, loft (either sign), friction, restitution, incoming spin and club mass:
- energy never increases (the impact can only dissipate);
- linear momentum of ball plus club is conserved (checked through outputs derived separately: the ball's
  speed and launch angle against the club's speed after impact);
- mirror symmetry: the mirrored loft gives the mirrored launch and spin, the same speed;
- batch independence: a case's answer does not depend on the other cases in its batch.
Example counts are small so that the file takes a few seconds; the seed is derandomised so that CI is
reproducible (set HYPOTHESIS_PROFILE=explore to search more widely while developing).
"""

import os

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from impactlab.scene.materials import BALL_PRESETS
from impactlab.model.registry import get_model

settings.register_profile("ci", max_examples=12, deadline=None, derandomize=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.register_profile("explore", max_examples=300, deadline=None)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))

MODELS = {
    "maw": {"tolerance": 1e-3},
    "hertz_mindlin": {"tolerance": 1e-3},
    "dem_linear": {"tolerance": 1e-3},
    "rigid_coulomb": {},
    "restitution": {"tangential_restitution": 0.3},
}
OUTPUTS = ["ball_speed", "launch_angle", "spin_rate", "energy_loss", "club_speed_after", "normal_impulse"]

case = st.fixed_dictionaries({
    "speed": st.floats(5.0, 60.0),
    "angle": st.floats(-1.0, 1.0).filter(lambda a: abs(a) > 1e-3),  # rad, either sign
    "friction": st.floats(0.05, 0.8),
    "restitution": st.floats(0.5, 1.0),
    "spin": st.floats(-300.0, 300.0),  # rad/s
    "club_mass": st.sampled_from([0.15, 0.2, 0.3, np.inf]),
})


def scene(cases):
    ball = BALL_PRESETS["urethane_tour"]
    columns = {key: np.array([c[key] for c in cases], float) for key in cases[0]}
    n = len(cases)
    fixed = dict(ball_radius=ball.radius, ball_mass=ball.mass, ball_inertia_factor=ball.inertia_factor,
                 ball_youngs_modulus=ball.material.youngs_modulus, ball_poisson_ratio=ball.material.poisson_ratio,
                 face_youngs_modulus=np.inf, face_poisson_ratio=0.0)
    return {**{key: np.full(n, value) for key, value in fixed.items()}, **columns}


@pytest.mark.slow
@pytest.mark.parametrize("name", MODELS)
@given(cases=st.lists(case, min_size=1, max_size=4))
def test_energy_never_increases_and_momentum_of_ball_and_club_is_conserved(name, cases):
    inputs = scene(cases)
    result = get_model(name)(**MODELS[name]).compute(inputs, OUTPUTS)
    m, speed, club = inputs["ball_mass"], inputs["speed"], inputs["club_mass"]
    energy_in = 0.5 * m * speed**2 + 0.5 * inputs["ball_inertia_factor"] * m * (inputs["ball_radius"]
                                                                                 * inputs["spin"]) ** 2
    assert np.all(result["energy_loss"].values >= -1e-9 * energy_in)
    # momentum along and across the path: M V = m v cos(theta) + M v_club_parallel, 0 = m v sin(theta) + ...
    ball = result["ball_speed"].values
    theta = np.radians(result["launch_angle"].values)
    finite = np.isfinite(club)
    along = club[finite] * speed[finite] - m[finite] * ball[finite] * np.cos(theta[finite])
    across = m[finite] * ball[finite] * np.sin(theta[finite])
    np.testing.assert_allclose(club[finite] * result["club_speed_after"].values[finite], np.hypot(along, across),
                               rtol=1e-9)
    # a fixed face keeps its speed
    np.testing.assert_allclose(result["club_speed_after"].values[~finite], speed[~finite], rtol=1e-12)


@pytest.mark.parametrize("name", MODELS)
@given(cases=st.lists(case, min_size=1, max_size=3))
def test_a_mirrored_impact_gives_the_mirrored_launch(name, cases):
    inputs = scene(cases)
    mirrored = {**inputs, "angle": -inputs["angle"], "spin": -inputs["spin"]}
    model = get_model(name)(**MODELS[name])
    one, other = model.compute(inputs, OUTPUTS), model.compute(mirrored, OUTPUTS)
    scale = np.abs(one["spin_rate"].values).max() + 1.0
    np.testing.assert_allclose(other["ball_speed"], one["ball_speed"], rtol=1e-9)
    np.testing.assert_allclose(other["launch_angle"], -one["launch_angle"], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(other["spin_rate"], -one["spin_rate"], rtol=1e-9, atol=1e-9 * scale)


@pytest.mark.parametrize("name", MODELS)
@given(cases=st.lists(case, min_size=2, max_size=5))
def test_a_case_does_not_depend_on_its_batch(name, cases):
    model = get_model(name)(**MODELS[name])
    together = model.compute(scene(cases), OUTPUTS)
    reversed_batch = model.compute(scene(cases[::-1]), OUTPUTS)
    alone = model.compute(scene(cases[:1]), OUTPUTS)
    for output in OUTPUTS:
        np.testing.assert_allclose(reversed_batch[output].values[::-1], together[output].values, rtol=1e-12,
                                   atol=1e-12)
        np.testing.assert_allclose(alone[output].values[0], together[output].values[0], rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("name, options", [("maw", {"springs": 40, "steps": 160}),
                                           ("maw", {"method": "annuli", "rings": 10, "steps": 200}),
                                           ("maw", {"springs": 40, "steps": 160, "inelastic": "hysteretic"}),
                                           ("hertz_mindlin", {"steps": 400}), ("dem_linear", {"steps": 400}),
                                           ("rigid_coulomb", {})])
def test_the_numpy_fallback_gives_the_compiled_kernels_answers(name, options, golf_inputs, monkeypatch):
    # where numba cannot be installed (or IMPACTLAB_KERNELS=numpy) the numpy implementations run: the same
    # physics, summed in another order, so the answers agree to round-off
    from impactlab.physics import kernels as _kernels

    inputs = golf_inputs(angle=np.radians([3.0, 15.0, 40.0]), friction=0.35, restitution=[1.0, 0.8, 0.8],
                         club_mass=[np.inf, 0.2, 0.2])
    names = ["tangential_impulse", "normal_impulse", "spin_rate", "contact_time"]
    if name == "rigid_coulomb":
        names = names[:3]
    compiled = get_model(name)(**options).compute(inputs, names)
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    fallback = get_model(name)(**options).compute(inputs, names)
    for output in names:
        np.testing.assert_allclose(fallback[output], compiled[output], rtol=1e-9)
    assert abs(compiled["spin_rate"].values[1]) > 100.0  # a real impact, not zeros on both sides


@pytest.mark.slow
def test_impactlab_kernels_numpy_switches_the_kernels_off():
    import subprocess
    import sys

    code = "from impactlab.physics import kernels; print(kernels.HAVE_NUMBA)"
    done = subprocess.run([sys.executable, "-c", code], env={**os.environ, "IMPACTLAB_KERNELS": "numpy"},
                          capture_output=True, text=True, check=True)
    assert done.stdout.strip() == "False"


@pytest.mark.slow
@settings(max_examples=4)
@given(points=st.lists(st.tuples(st.floats(0.5, 4.0), st.floats(np.log(0.01), np.log(6.0))), min_size=3,
                       max_size=3))
def test_maws_resolution_rule_meets_its_bound_against_an_independent_mdr(points):
    # |d psi2| <= tol min(4 chi, psi1) at random (chi, psi1) over chi 0.5-4 (K^2 above about 0.2 for a rubbery
    # ball) and psi1 from 0.01 to 6 chi; the reference is the MDR written independently in
    # test_mutation_oracles.py. Beyond chi 4 at grazing lofts the rule misses its bound: see the strict xfail there.
    from test_mutation_oracles import reference_mdr_psi2

    from impactlab.physics import mdr
    from impactlab_models.maw import MawOptions

    chi = np.array([c for c, _ in points])
    psi1 = np.array([c * np.exp(p) for c, p in points])  # psi1 / chi log-uniform in [0.01, 6]
    tolerance = 1e-3
    options = MawOptions(tolerance=tolerance)
    reference = reference_mdr_psi2(chi, psi1, springs=300)
    for case in range(chi.size):
        springs, _ = options.resolution(float(chi[case]), psi1[case:case + 1])
        solved = mdr.solve_scaled(chi[case:case + 1], psi1[case:case + 1], springs=int(springs[0]),
                                  steps=options.resolution_steps(int(springs[0])))
        error = abs(solved.slip_change[0] + psi1[case] - reference[case])
        assert error <= tolerance * min(4 * chi[case], psi1[case]), (chi[case], psi1[case], error)
