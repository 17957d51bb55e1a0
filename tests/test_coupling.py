"""Dundurs' second constant and the estimate of the normal-tangential coupling the compliant models neglect."""

import math

import numpy as np
import pytest

from impactlab.physics import hertz
from impactlab.physics.coupling import coupling_estimate, coupling_ratio, dundurs_beta
from impactlab.model.registry import get_model

URETHANE = (136e6, 0.45)
STEEL = (196e9, 0.272)


def test_dundurs_beta_of_the_project_pairs():
    # a urethane ball on steel: +0.09 (issue 12); a rigid face: (1 - 2 nu) / (2 (1 - nu)) exactly
    assert dundurs_beta(*URETHANE, *STEEL) == pytest.approx(0.0906, abs=5e-4)
    assert dundurs_beta(*URETHANE, np.inf, 0.0) == pytest.approx(0.1 / 1.1, rel=1e-12)
    # identical materials and two incompressible ones are uncoupled; swapping the bodies flips the sign
    assert dundurs_beta(*STEEL, *STEEL) == 0.0
    assert dundurs_beta(1e6, 0.5, 1e9, 0.5) == 0.0
    assert dundurs_beta(*STEEL, *URETHANE) == pytest.approx(-dundurs_beta(*URETHANE, *STEEL), rel=1e-12)


def test_radial_mismatch_of_a_hertz_contact_is_four_over_three_pi_beta_delta():
    """Step 1 of impactlab.physics.coupling, from Johnson's surface displacement under a Hertz pressure.

    u_r(r) = -(1 - 2 nu) / (6 G) (a^2 / r) [1 - (1 - r^2/a^2)^(3/2)] p0 on each body; the two surfaces differ at
    r = a by (4 / (3 pi)) beta_D delta, delta = a^2 / R.
    """
    radius, force = 0.021335, 8000.0
    modulus = hertz.effective_modulus(*URETHANE, *STEEL)
    a = (3.0 * force * radius / (4.0 * modulus)) ** (1.0 / 3.0)
    p0 = 2.0 * modulus * a / (math.pi * radius)

    def u_r(youngs, poisson, r):
        shear = youngs / (2.0 * (1.0 + poisson))
        return -(1.0 - 2.0 * poisson) / (6.0 * shear) * a**2 / r * (1.0 - (1.0 - r**2 / a**2) ** 1.5) * p0

    mismatch = u_r(*URETHANE, a) - u_r(*STEEL, a)
    assert abs(mismatch) == pytest.approx(4.0 / (3.0 * math.pi) * dundurs_beta(*URETHANE, *STEEL) * a**2 / radius,
                                          rel=1e-12)


def test_coupling_estimate_is_second_order_and_zero_without_a_mismatch():
    kappa = hertz.tangential_modulus(*URETHANE, *STEEL) / hertz.effective_modulus(*URETHANE, *STEEL)
    beta = dundurs_beta(*URETHANE, *STEEL)
    ratio = coupling_ratio(beta, kappa, 0.4)
    assert ratio == pytest.approx(0.068, abs=1e-3)
    assert coupling_estimate(beta, kappa, 0.4) == pytest.approx(0.5 * ratio**2, rel=1e-12)  # 2.3e-3 of mu J_n
    # even in beta (the bodies swapped), and quadrupled by halving mu (r_c ~ 1/mu)
    assert coupling_estimate(-beta, kappa, 0.4) == coupling_estimate(beta, kappa, 0.4)
    assert coupling_estimate(beta, kappa, 0.2) == pytest.approx(4.0 * coupling_estimate(beta, kappa, 0.4))
    assert coupling_estimate(0.0, kappa, 0.4) == 0.0 and coupling_estimate(beta, kappa, 0.0) == 1.0  # capped


@pytest.mark.parametrize("model", ["maw", "hertz_mindlin", "dem_linear"])
def test_flag_fires_where_the_estimate_exceeds_the_tolerance(golf_inputs, model):
    urethane = golf_inputs(angle=np.radians(45.0), face_youngs_modulus=STEEL[0], face_poisson_ratio=STEEL[1],
                           restitution=0.8)
    steel_ball = dict(urethane, ball_youngs_modulus=np.array([STEEL[0]]), ball_poisson_ratio=np.array([STEEL[1]]))
    tight = get_model(model)(tolerance=1e-4).compute(urethane, ["validity", "coupling_estimate"])
    assert int(tight.validity.item()) & 16 and tight.coupling_estimate.item() == pytest.approx(2.3e-3, abs=1e-4)
    loose = get_model(model)(tolerance=1e-2).compute(urethane, ["validity"])  # 2.3e-3 < 1e-2: within what was asked
    assert not int(loose.validity.item()) & 16
    same = get_model(model)(tolerance=1e-4).compute(steel_ball, ["validity", "coupling_estimate"])
    assert not int(same.validity.item()) & 16 and same.coupling_estimate.item() == 0.0
