"""``hertz_mindlin_slip``: hertz_mindlin_face with friction rising with the slip speed (issue 33, round 4).

Oracles: the plain models themselves (the registered default is the option spelled out; the vanishing setting is
hertz_mindlin_face exactly), the law's closed form at the reference slip (u = 10 m/s: mu = mu_0, the face model
unchanged), and the direction the law exists for: at a fixed driver delivery the spin grows more slowly with the club
speed than hertz_mindlin_face's, while an iron (rigid face) gets the same law without the face.
"""

import attrs
import numpy as np
import pytest

from impactlab.data.sessions.shots import predict, table_inputs
from impactlab.data.shot_report import shot_table
from impactlab.model.registry import available, get_model
from impactlab.physics import rate_laws


@pytest.fixture(scope="module")
def drivers():
    table = shot_table("trackman_tour")
    return table.subset([i for i, label in enumerate(table.labels) if "driver" in label])


def test_it_is_registered_with_its_fitted_exponent_on_the_face_model():
    from impactlab_models.dem import FITTED_SLIP_EXPONENT

    assert "hertz_mindlin_slip" in available()
    options = get_model("hertz_mindlin_slip")().options
    face = get_model("hertz_mindlin_face")().options
    assert options.friction_slip_exponent == FITTED_SLIP_EXPONENT
    assert (options.face_frequency, options.face_modal_mass, options.inelastic) == (
        face.face_frequency, face.face_modal_mass, face.inelastic)


def test_vanishing_setting_and_spelled_out_defaults(drivers):
    inputs = table_inputs(drivers)
    off = predict(get_model("hertz_mindlin_slip")(friction_slip_exponent=0.0), inputs)
    face = predict(get_model("hertz_mindlin_face")(), inputs)
    named = predict(get_model("hertz_mindlin_slip")(), inputs)
    spelled = predict(get_model("hertz_mindlin_face")(friction_slip_exponent=1.0), inputs)
    for key in off:
        np.testing.assert_array_equal(off[key], face[key])
        np.testing.assert_array_equal(named[key], spelled[key])


def test_the_law_is_mu_zero_at_the_reference_slip(drivers):
    """A case whose slip scale is 10 m/s sees mu_0 whatever m: the face model with the same friction."""
    from impactlab.physics.contact import contact_state
    from impactlab_models.shared import characteristic_slip

    inputs = table_inputs(drivers)
    slip = characteristic_slip(contact_state(inputs), inputs["restitution"])
    # both the initial slip and the slip the normal impulse couples in scale with the speed
    scaled = dict(inputs, speed=np.asarray(inputs["speed"]) * rate_laws.REFERENCE_SLIP_SPEED / slip)
    with_law = predict(get_model("hertz_mindlin_slip")(), scaled)
    without = predict(get_model("hertz_mindlin_face")(), scaled)
    np.testing.assert_allclose(with_law["spin_rate"], without["spin_rate"], rtol=1e-9)


def test_spin_grows_more_slowly_with_club_speed_than_on_the_face_model(drivers):
    def exponent(name):
        spins = []
        for mph in (96.0, 115.0):
            delivery = dict(drivers.delivery, club_speed=np.full(drivers.size, mph * 0.44704))
            spins.append(predict(get_model(name)(), table_inputs(attrs.evolve(drivers, delivery=delivery)))[
                "spin_rate"])
        return np.log(spins[1] / spins[0]) / np.log(115.0 / 96.0)

    slip, face = exponent("hertz_mindlin_slip"), exponent("hertz_mindlin_face")
    assert np.all(slip < face - 0.1)
    assert np.all((slip > 0.3) & (slip < 1.0))
