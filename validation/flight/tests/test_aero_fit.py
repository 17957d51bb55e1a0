"""The constants of ``measured_fit`` (impactlab.physics.aerodynamics) are the fit of validation.flight.aero_fit to the
shipped measurements: refitted here, where the research lives (moved from tests/test_flight.py, issue 31)."""

from __future__ import annotations

from importlib import resources

import numpy as np
import pytest
import yaml

from impactlab.physics import aerodynamics


def _measured(block):
    """Rows [Re, S, CD, CL] of one block of the shipped measurement file, read here independently of the code."""
    document = yaml.safe_load(resources.files("impactlab.data.validation").joinpath(
        "aero_coefficients.yaml").read_text())
    return np.array([[np.nan if x is None else x for x in row] for row in document["blocks"][block]["rows"]], float)


def test_measured_fit_constants_are_the_fit_of_the_measurements_file():
    from validation.flight import aero_fit

    fitted = aero_fit.fit()
    values = dict(zip(("a", "b"), fitted["lift"]))
    values.update(c0=fitted["offsets"]["modern"], c_re=fitted["c_re"], k=fitted["k"])
    values.update(zip(("re_l", "sigma", "beta", "s_l", "re_d", "w_d", "d", "m"), fitted["crisis"]))
    assert set(values) == set(aerodynamics.MEASURED_FIT)
    for key, value in values.items():
        assert aerodynamics.MEASURED_FIT[key] == pytest.approx(value, rel=2e-5), key
    assert set(aerodynamics.MEASURED_FIT_OFFSETS) == set(aero_fit.GROUPS)
    for group, value in fitted["offsets"].items():
        assert aerodynamics.MEASURED_FIT_OFFSETS[group] == pytest.approx(value, rel=2e-5), group
    # the USGA-ball variant differs only by that offset
    cd, cl = aerodynamics.aero_coefficients(0.15, [7e4, 1.5e5], model="measured_fit")
    cd_u, cl_u = aerodynamics.aero_coefficients(0.15, [7e4, 1.5e5], model="measured_fit_usga_ball")
    np.testing.assert_allclose(cl_u, cl, rtol=1e-15)
    np.testing.assert_allclose(cd_u - cd, fitted["offsets"]["usga_1998"] - fitted["offsets"]["modern"], rtol=1e-4)
    # the file's rows, read independently: the fit reproduces the USGA ITR lift within its residual
    usga = _measured("usga_itr_example")
    assert usga.shape == (42, 4)
    a, b = fitted["lift"]
    assert np.sqrt(np.mean((a * usga[:, 1] / (1 + b * usga[:, 1]) - usga[:, 3]) ** 2)) < 0.03
    assert fitted["rms"]["lift supercritical"] < 0.03 and fitted["rms"]["drag supercritical"] < 0.025
    # the crisis terms are what the measurements below Re 7.4e4 need (lift residual 0.18 -> 0.07)
    rms = fitted["rms"]
    assert rms["lift crisis (modern, Re < 7.4e4)"] < 0.5 * rms["lift crisis without the crisis terms"]

def test_measured_fit_flies_the_function_that_was_fitted():
    """aerodynamics writes the fitted model out a second time; across the drag crisis and beyond it, at any spin, its
    CD and CL must be aero_fit's functions (the ones the constants were fitted with) at those constants."""
    from validation.flight import aero_fit

    c = aerodynamics.MEASURED_FIT
    s, re = np.meshgrid(np.linspace(0.0, 0.8, 17), np.geomspace(3e4, 2.5e5, 41))
    extra, factor = aero_fit.crisis_terms(s, re, c["re_l"], c["sigma"], c["beta"], c["s_l"], c["re_d"], c["w_d"],
                                          c["d"], c["m"])
    lift = aero_fit.lift_supercritical(s, c["a"], c["b"])
    cd, cl = aerodynamics.aero_coefficients(s, re, model="measured_fit")
    np.testing.assert_allclose(cd, c["c0"] + c["c_re"] * re / 1e5 + c["k"] * lift**2 + extra, rtol=1e-12)
    np.testing.assert_allclose(cl, lift * factor, rtol=1e-12, atol=1e-15)
