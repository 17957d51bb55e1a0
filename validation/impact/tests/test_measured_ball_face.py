"""validation.impact.measured_ball_face and face_mechanisms: the face sizing, the ball's e per row, the bounds.

Oracles: the registered face at the COR limit (6.88 kHz, 10.9 g) was sized by benchmarks/measure_face_flex.py with
the tour ball's e 0.787 (docs/models.md), so solving for the frequency with that e must land on it; Chou & Yang's line
through its two measured points; the face's e_ball cap from face_bounds.
"""

import warnings

import numpy as np
import pytest

from validation.impact import face_bounds as fb
from validation.impact import face_mechanisms as fl
from validation.impact import measured_ball_face as mbf


@pytest.fixture(autouse=True)
def _quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def test_sizing_with_the_tour_ball_finds_the_registered_face():
    assert mbf.face_at_limit(0.787, 0.0109) == pytest.approx(6880.0, rel=0.02)


def test_a_less_lively_ball_needs_a_softer_face_at_the_limit():
    # the measured line's e at 48.8 m/s (0.769) is below 0.787: the face must give more, so it is softer
    soft = mbf.face_at_limit(0.769, 0.0109)
    assert soft < 6880.0 * 0.98
    assert fb.head_cor(0.769, mbf.face_options(soft, 0.0109)) == pytest.approx(0.830, abs=1e-3)


def test_each_rows_e_is_the_measured_line_at_its_normal_speed_rounded():
    speed = np.linspace(30.0, 55.0, 40)
    angle = np.radians(np.full(40, 60.0))  # normal speed = speed / 2
    out = mbf.on_line({"speed": speed, "angle": angle, "club_restitution_gain": np.zeros(40)})
    exact = 0.85 + (0.78 - 0.85) * (speed / 2 - 20.0) / 25.0
    assert np.max(np.abs(out["restitution"] - exact)) <= mbf.E_QUANTUM / 2 + 1e-12
    assert np.unique(out["restitution"]).size < 40


def test_the_lever_form_is_bounded_within_the_rules_and_mcnallys_range():
    limits = fl.bounds()
    assert limits["e_ball"][1] == pytest.approx(fb.e_ball_at_limit(), abs=2e-3)
    assert fb.head_cor(limits["e_ball"][1]) <= 0.830 + 1e-3
    from validation.impact import rate_laws as rl

    assert limits["compression_lever"][:2] == (0.0, pytest.approx(rl.lever_bound()))
