"""Unit parsing, value objects, and the exact Hertz normal solution."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from impactlab import Ball, Face, Material
from impactlab.errors import FieldError
from impactlab.physics import hertz
from impactlab.units import to_si


@pytest.mark.parametrize("value, dimension, expected", [
    ("80 mph", "speed", 35.7632), (35, "speed", 35.0), ("21.335 mm", "length", 0.021335),
    ("45.93 g", "mass", 0.04593), ("136 MPa", "pressure", 136e6), (15, "angle", math.radians(15)),
    ("0.5 rad", "angle", 0.5), ("3000 rpm", "angular_speed", 100 * math.pi),
    (2500, "angular_speed", 2500 * math.pi / 30),
    ("0.4", "dimensionless", 0.4),
])
def test_quantities_convert_to_si(value, dimension, expected):
    assert to_si(value, dimension) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("value", ["80 kg", "fast", True, None, [1]])
def test_bad_quantities_name_the_field(value):
    with pytest.raises(FieldError, match="impact.speed: expected a speed"):
        to_si(value, "speed", "impact.speed")


def test_value_objects_validate_with_expected_and_given():
    with pytest.raises(FieldError, match=r"poisson_ratio: expected a Poisson ratio with -1 < nu <= 0.5, got 0.7"):
        Material(1e9, 0.7)
    with pytest.raises(FieldError, match="inertia_factor"):
        Ball(0.02, 0.045, 0.9)
    with pytest.raises(FieldError, match="rigid"):
        Face(Material(2e11, 0.3), rigid=True)
    with pytest.raises(FieldError, match="club-head mass"):
        Face(mass=-1.0)
    ball = Ball(0.02, 0.045)
    with pytest.raises(AttributeError):
        ball.radius = 1.0  # frozen


def test_universal_hertz_curve_matches_direct_integration():
    tau = np.linspace(0.0, hertz.TAU_CONTACT, 41)
    ode = solve_ivp(lambda t, y: [y[1], -1.25 * max(y[0], 0.0) ** 1.5], [0, hertz.TAU_CONTACT], [0.0, 1.0],
                    rtol=1e-12, atol=1e-14, dense_output=True)
    np.testing.assert_allclose(hertz.scaled_approach(tau), ode.sol(tau)[0], atol=1e-10)
    assert hertz.TAU_CONTACT == pytest.approx(2.9432, abs=1e-4)  # Johnson (1985) eq. 11.24
    np.testing.assert_allclose(hertz.time_to_reach(hertz.scaled_approach(tau[:21])), tau[:21], atol=1e-12)


def test_contact_moduli_for_a_rigid_face_reduce_to_the_ball_terms():
    e, nu = 136e6, 0.45
    assert hertz.effective_modulus(e, nu, np.inf, 0.0) == pytest.approx(e / (1 - nu**2))
    kappa = hertz.tangential_modulus(e, nu, np.inf, 0.0) / hertz.effective_modulus(e, nu, np.inf, 0.0)
    assert kappa == pytest.approx(2 * (1 - nu) / (2 - nu))
