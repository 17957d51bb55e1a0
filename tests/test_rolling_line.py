"""The closed-form rolling impact on one line (impactlab.physics.rolling_line) against independent oracles.

Oracles: the integrator over the normal impulse (ball_laws.rolling_impulses, a different method: energy-minimising
steps by projected Gauss-Seidel) at 32000 plain steps and extrapolated; the hand solution of test_ball_laws; the
kinetic energy summed from the generalised mobility; and the same model 1 micrometre off the line (integrator).
"""

import numpy as np
import pytest

from impactlab.model.registry import get_model
from impactlab.physics import ball_laws, rolling_line
from impactlab.physics.contact import contact_state, couple_mobility
from impactlab.testing import reference_inputs

from test_ball_laws import hand_line_cases


def _line_cases(n=240, seed=7):
    """Seeded random cases on one line: a ball on a fixed face or a point-mass head, lofts 1-89 deg, mu 0.02-1
    (log-uniform, so that the rolling can be held while the ball slides), e 0-1, arms 0-2 mm, spin +-900 rad/s."""
    rng = np.random.default_rng(seed)
    template = reference_inputs()
    inputs = {key: np.repeat(value[:1], n) for key, value in template.items()}
    inputs["angle"] = np.radians(rng.uniform(1.0, 89.0, n))
    inputs["friction"] = np.exp(rng.uniform(np.log(0.02), 0.0, n))
    inputs["restitution"] = rng.uniform(0.0, 1.0, n)
    inputs["spin"] = rng.uniform(-900.0, 900.0, n)
    inputs["club_mass"] = np.where(rng.random(n) < 0.5, np.inf, rng.uniform(0.15, 0.4, n))
    state = contact_state(inputs)
    b, d, rates = couple_mobility(state, inputs["ball_mass"], inputs["ball_radius"], inputs["ball_inertia_factor"])
    arm = rng.uniform(0.0, 2e-3, n)
    return (state["initial_velocity"], state["mobility"], b, d, rates, inputs["friction"], inputs["restitution"],
            arm)


CASES = _line_cases()


def test_every_case_is_on_the_line_and_every_regime_occurs():
    assert np.all(rolling_line.on_line(*CASES[:5]))
    impulse, moment, flags, visited = rolling_line.rolling_line_impulses(*CASES, regimes=True)
    assert not np.any(flags)
    for bit in (rolling_line.BOTH_SLIDE, rolling_line.SLIP_HELD, rolling_line.ROLLING_HELD, rolling_line.BOTH_HELD,
                rolling_line.CROSSING):
        assert np.sum((visited & bit) > 0) >= 3, f"regime bit {bit} visited by fewer than 3 cases"


@pytest.mark.parametrize(("steps", "extrapolate", "normal_tol", "slip_tol", "couple_tol"),
                         [(32000, False, 1e-7, 2e-5, 1.5e-4), (4000, True, 1e-5, 1e-4, 5e-4)])
def test_closed_form_matches_the_integrator(steps, extrapolate, normal_tol, slip_tol, couple_tol):
    """To the integrator's error: first order in 1/steps where a regime changes within a step (measured 7e-6 of
    mu J_n and 6e-5 of d J_n at 32000 plain steps on these cases; the integrator's J_n ends inside a step, 2.7e-8
    plain at 32000, 2.4e-6 extrapolated at 4000)."""
    impulse, moment, _ = rolling_line.rolling_line_impulses(*CASES)
    reference, reference_moment, flags = ball_laws.rolling_impulses(*CASES, steps=steps, extrapolate=extrapolate)
    assert not np.any(flags)
    jn = impulse[:, 2]
    mu, arm = CASES[5], CASES[7]
    np.testing.assert_allclose(jn, reference[:, 2], rtol=normal_tol)
    assert np.all(np.abs(impulse[:, 0] - reference[:, 0]) <= slip_tol * mu * jn)
    assert np.all(np.abs(moment[:, 1] - reference_moment[:, 1]) <= couple_tol * arm * jn + 1e-18)
    assert np.all(impulse[:, 1] == 0.0) and np.all(moment[:, 0] == 0.0)
    assert np.all(np.abs(reference[:, 1]) <= 1e-15) and np.all(np.abs(reference_moment[:, 0]) <= 1e-18)


def test_closed_form_is_the_hand_solution():
    arguments, (jn, jt, couple) = hand_line_cases()
    impulse, moment, flags = rolling_line.rolling_line_impulses(*arguments)
    assert not np.any(flags)
    np.testing.assert_allclose(impulse[:, 2], jn, rtol=1e-12)
    np.testing.assert_allclose(-impulse[:, 0], jt, rtol=1e-12)
    np.testing.assert_allclose(moment[:, 1], couple, rtol=1e-12)


def test_energy_never_rises():
    """Kinetic energy change of the generalised coordinates, x0 . y + y^T M y / 2 with M = [[W, B], [B^T, D]] and
    y = (J, C): never positive (the normal's share is -(1 - e^2) m_n V_n^2 / 2, the rest friction and couple)."""
    initial, mobility, b, d, rates, mu, e, arm = CASES
    impulse, moment, _ = rolling_line.rolling_line_impulses(*CASES)
    matrix = np.block([[mobility, b], [np.swapaxes(b, 1, 2), d]])
    x0, y = np.concatenate([initial, rates], -1), np.concatenate([impulse, moment], -1)
    change = np.einsum("ni,ni->n", x0, y) + 0.5 * np.einsum("ni,nij,nj->n", y, matrix, y)
    normal = -0.5 * (1.0 - e**2) * initial[:, 2] ** 2 / mobility[:, 2, 2]
    scale = 0.5 * np.einsum("ni,ni->n", initial, initial) / mobility[:, 2, 2]
    assert np.all(change - normal <= 1e-12 * scale)


def _centred_head(offset):
    """A driver-like free head struck on its centre-of-mass line (on the line) or ``offset`` [m] towards the toe."""
    from impactlab.scene.catalogue import CLUB_PRESETS
    from impactlab.scene.clubs import ClubHead, Strike
    from impactlab.scene.core import Contact, Delivery, Scene
    from impactlab.scene.materials import BALL_PRESETS
    from impactlab.testing import _complete

    head = ClubHead(mass=0.2, inertia=(3.0e-4, 4.5e-4, 2.5e-4), center_of_mass=(0.0, 0.0, 0.035), loft=0.2,
                    material=CLUB_PRESETS["driver"].material)
    scenes = [Scene.from_delivery(BALL_PRESETS["urethane_tour"], Scene.face_of(head), Contact(friction, 0.8),
                                  Delivery(45.0, dynamic_loft=np.radians(loft), loft_at="centre"), 0.0, head,
                                  Strike(offset, 0.0))
              for loft in (4.0, 15.0, 35.0, 55.0) for friction in (0.05, 0.2, 0.5)]
    return _complete({key: np.array([scene.inputs()[key] for scene in scenes]) for key in scenes[0].inputs()})


def test_model_continuous_across_the_line():
    """rigid_coulomb + rolling on the line (closed form) and 1 micrometre off it (integrator, 200 steps
    extrapolated): the same impact to the integrator's error (measured: 4.9e-6 in every output, the integrator's
    J_n ending inside a step; the couple changes spin by up to 2000 rpm on these cases)."""
    model = get_model("rigid_coulomb")(rolling_hysteresis="restitution")
    outputs = ["spin_rate", "ball_speed", "launch_angle", "rolling_moment", "steps"]
    on, off = model.compute(_centred_head(0.0), outputs), model.compute(_centred_head(1e-6), outputs)
    assert np.all(on["steps"].values == 0.0) and np.all(off["steps"].values > 0.0)
    for name in ("spin_rate", "ball_speed", "rolling_moment"):
        np.testing.assert_allclose(on[name].values, off[name].values, rtol=2e-5, err_msg=name)
    np.testing.assert_allclose(on["launch_angle"].values, off["launch_angle"].values, atol=2e-4)


def test_frictionless_couple_stops_the_rolling_by_hand():
    """mu = 0: no friction impulse; the couple d dP opposes the rolling until it stops, C = -sgn(r0) min(d J_n,
    |r0| / D_ll) (hand solution: r falls at d D_ll per unit P, the couple then holds it at zero)."""
    initial, mobility, b, d, rates, _, e, arm = CASES
    impulse, moment, flags = rolling_line.rolling_line_impulses(initial, mobility, b, d, rates, 0.0, e, arm)
    reference, reference_moment, _ = ball_laws.rolling_impulses(initial, mobility, b, d, rates, 0.0, e, arm,
                                                                steps=4000)
    jn = (1.0 + e) * (-initial[:, 2]) / mobility[:, 2, 2]
    expected = -np.sign(rates[:, 1]) * np.minimum(arm * jn, np.abs(rates[:, 1]) / d[:, 1, 1])
    assert not np.any(flags) and np.all(impulse[:, 0] == 0.0)
    np.testing.assert_allclose(moment[:, 1], expected, rtol=1e-12, atol=1e-20)
    np.testing.assert_allclose(reference_moment[:, 1], expected, rtol=1e-3, atol=1e-3 * np.max(np.abs(expected)))
