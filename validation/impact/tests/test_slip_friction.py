"""validation.impact.slip_friction: the forms' bounds and the fit honouring a form's own bounds.

Oracles: the package's reference pressure (10 MPa) against a driver's contact (about 40 MPa), so Arakawa's mu_0 range
is round 1's driver range times 4; a fit whose objective wants friction far outside a form's bounds must end on them.
"""

import numpy as np
import pytest

from validation.impact import rate_laws as rl
from validation.impact import slip_friction as sf


def test_arakawas_form_bounds_mu0_so_that_a_drivers_mu_keeps_round_1s_range():
    forms = {form.name: form for form in sf.forms()}
    arakawa = next(form for name, form in forms.items() if "Arakawa" in name and "face" in name)
    low, high = rl.BOUNDS["friction"][:2]
    assert arakawa.bounds["friction"][:2] == (pytest.approx(4 * low), pytest.approx(4 * high))
    assert arakawa.options["friction_slip_exponent"] == 1.0
    assert arakawa.options["friction_pressure_exponent"] == 1.0
    fitted = next(form for name, form in forms.items() if "m fitted" in name)
    assert "friction_slip_exponent" in fitted.fitted


def test_the_fit_ends_on_the_forms_own_bounds(monkeypatch):
    """An objective that wants friction 5 lands at the form's upper bound, not at BOUNDS'."""
    def fake_run(form, values, inputs):
        n = len(inputs["speed"])
        spin = np.full(n, values["friction"])  # spin grows with friction; the measured spin asks for 5
        return {"spin_rate": spin, "ball_speed": np.ones(n)}

    monkeypatch.setattr(rl, "run", fake_run)
    form = rl.Form("test", "hertz_mindlin", {}, ("friction",), bounds={"friction": (0.8, 2.4, 1.6, "test")})
    inputs = {"speed": np.ones(5)}
    measured = {"spin_rate": np.full(5, 5.0), "ball_speed": np.ones(5)}
    values, at_bound = rl.fit(form, inputs, measured, dict(rl.BOUNDS), rigid_face_head=False)
    assert values["friction"] == pytest.approx(2.4, abs=1e-3)
    assert at_bound == ["friction"]
