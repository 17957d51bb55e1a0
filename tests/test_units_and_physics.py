"""Unit parsing, value objects, and the exact Hertz normal solution."""

import math
import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from impactlab import Ball, Face, Material
from impactlab.errors import FieldError
from impactlab.physics import hertz
from impactlab.units import to_si


@pytest.mark.parametrize("value, dimension, expected", [
    ("80 mph", "speed", 35.7632), ("35 m/s", "speed", 35.0), ("21.335 mm", "length", 0.021335),
    ("45.93 g", "mass", 0.04593), ("136 MPa", "pressure", 136e6), ("15 deg", "angle", math.radians(15)),
    ("0.5 rad", "angle", 0.5), ("3000 rpm", "angular_speed", 100 * math.pi),
    ("2500 rpm", "angular_speed", 2500 * math.pi / 30), ("-0.002 s/m", "inverse_speed", -0.002),
    ("0.4", "dimensionless", 0.4), (0.4, "dimensionless", 0.4),
])
def test_quantities_convert_to_si(value, dimension, expected):
    assert to_si(value, dimension) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("value, dimension, example", [
    (35, "speed", "35 mph or 15.6464 m/s"), (15, "angle", "15 deg or 0.261799 rad"),
    (2500, "angular_speed", "2500 rpm or 261.799 rad/s"), ("200", "mass", "200 g or 0.2 kg"),
    (0.021335, "length", "0.021335 m or 21.335 mm"), (136, "pressure", "136 MPa or 1.36e+08 Pa"),
    (25, "temperature", "25 degC or 298.15 K"),
])
def test_a_bare_number_of_a_dimension_is_never_given_a_unit(value, dimension, example):
    with pytest.raises(FieldError, match=f"x.y: expected .* with its unit, e.g. {re.escape(example)}"):
        to_si(value, dimension, "x.y")
    # where a bare number is declared SI (a Python value object's argument), it is taken as SI
    if not isinstance(value, str):
        assert to_si(value, dimension, "x.y", bare="si") == value


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


def test_incoming_spin_sign_in_the_users_frames():
    """docs/conventions.md: impact.spin is positive for the backspin a lofted face gives (club frame) and for
    topspin about the flight of a ball arriving at a plate; a ball landing with backspin about its flight is negative.

    Face frame (x up the face along the incoming slip, z the face normal, y = z x x): a positive spin_rate is a
    rotation about +y, whose contact point (at -R z) moves along -x. Rigid body, rolling regime, fixed face: the
    tangential impulse is m_t times the contact-point slip, so it measures the slip directly.
    """
    from impactlab.model.registry import get_model

    radius, mass, k2, speed, alpha, w = 0.021335, 0.04593, 0.4, 20.0, np.radians(30.0), 300.0
    m_t = mass / (1.0 + 1.0 / k2)
    inputs = dict(ball_radius=radius, ball_mass=mass, ball_inertia_factor=k2, friction=0.8, restitution=0.8,
                  speed=speed, angle=alpha)
    x, y, z = np.eye(3)

    def slip(spin_vector):  # contact-point velocity of a ball arriving at the resting face, along x
        velocity = speed * (np.sin(alpha) * x - np.cos(alpha) * z)
        return float((velocity + np.cross(spin_vector, -radius * z)) @ x)

    def impulse(spin):
        return float(get_model("rigid_coulomb")().compute(dict(inputs, spin=spin), ["tangential_impulse"])
                     ["tangential_impulse"][0])

    # the ball's flight along the face is +x: backspin about it moves the bottom of the ball along +x
    landing_backspin = -w * y   # bottom velocity w x (-R z) = +R w x: along the flight
    assert np.cross(landing_backspin, -radius * z) @ x > 0
    assert impulse(-w) == pytest.approx(m_t * slip(landing_backspin), rel=1e-12)
    assert slip(landing_backspin) > speed * np.sin(alpha)          # backspin on landing: more slip
    assert impulse(+w) == pytest.approx(m_t * slip(+w * y), rel=1e-12)
    assert slip(+w * y) < speed * np.sin(alpha)                     # topspin about the flight: less slip
    # club frame: a shot's own spin is positive, and a ball already spinning that way leaves with more of it
    spin_out = get_model("rigid_coulomb")().compute(dict(inputs, spin=np.array([0.0, w])), ["spin_rate"])["spin_rate"]
    assert spin_out.values[0] > 0 and spin_out.values[1] > spin_out.values[0]


def test_offset_units_convert_as_an_affine_map():
    """0 degF = 459.67 R x 5/9 = 255.3722 K and a degF step is 5/9 K (NIST SP 811, B.8); 0 degC = 273.15 K."""
    from impactlab.units import unit_affine

    scale, offset = unit_affine("degF", "K")
    assert scale == pytest.approx(5.0 / 9.0, rel=1e-12)
    assert offset == pytest.approx(459.67 * 5.0 / 9.0, rel=1e-12)
    assert unit_affine("degC", "K") == pytest.approx((1.0, 273.15))
    assert unit_affine("kPa", "Pa") == pytest.approx((1000.0, 0.0))


@pytest.mark.parametrize("unit", ["F", "C", "deg"])
def test_a_temperature_column_in_no_temperature_unit_is_refused(tmp_path, unit):
    """'[F]' is pint's farad and '[C]' its coulomb, '[deg]' an angle: none is read as a temperature (never
    guessed); the row and column are named."""
    from impactlab.data.sessions.reader import read_session
    from impactlab.errors import StudyError

    path = tmp_path / "air.csv"
    path.write_text(f"ball_speed [mph],launch_angle [deg],spin_rate [rpm],air_temperature [{unit}]\n"
                    "150,12,2500,70\n")
    with pytest.raises(StudyError, match=r"air\.csv:1:4 \(air_temperature"):
        read_session(path)
