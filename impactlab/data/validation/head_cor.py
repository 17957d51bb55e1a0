"""The head COR each model runs a club with: the Rules' COR test simulated by the model itself.

The Rules bound a driver's coefficient of restitution with a ball at 0.830 (USGA/R&A Equipment Rules, Part 2, 5a:
0.822 plus the test's tolerance 0.008; a ball fired head-on at the face centre at 48.77 m/s). The package's wood and
hybrid presets carry a restitution gain fitted to TrackMan's tour tables (0.083 on the tour ball's 0.787: a pair e
of 0.870), and every model that adds that gain to the ball's e runs them as a head beyond the limit; the models with
the flexing face (``hertz_mindlin_face``, ``hertz_mindlin_slip``) size the face at the limit instead. A conforming
head cannot reach the tour tables' driver ball speed (docs/validation.md, issue 33 round 6), so a close ball-speed
agreement from a head beyond the limit must say so beside it: :func:`head_cor_note` is printed by ``impactlab
validate`` with its errors and kept in a scorecard.

The test is simulated, not computed from the inputs, so that it holds for any model, a plugin's too: the model's
normal impulse J_n of the head-on impact gives e = J_n / (m* V) - 1, m* the pair's effective mass along the normal
(head mass and turning about its centre of mass), V the test's speed.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import numpy as np

from impactlab.errors import ImpactLabError
from impactlab.model.registry import get_model
from impactlab.physics.contact import contact_state
from impactlab.physics.rate_laws import HEAD_COR_LIMIT
from impactlab.scene.catalogue import club_preset
from impactlab.scene.clubs import Strike
from impactlab.scene.core import Contact, Delivery, Scene
from impactlab.study.scene_blocks import build_ball

#: the COR test's ball speed [m/s]: 160 ft/s (USGA/R&A, Procedure for measuring the velocity ratio of a club head)
COR_TEST_SPEED = 48.77
#: a COR reported as beyond the limit only beyond this margin (the face models are sized at the limit to 1e-4)
MARGIN = 5e-4


def cor_test_inputs(club: str, ball_block: Mapping | None = None) -> dict:
    """Model inputs (SI arrays, one case) of the Rules' COR test on the club preset ``club``: the head moving at
    :data:`COR_TEST_SPEED` onto the ball at rest, loft, attack, path and face angle 0 (the relative impact of a ball
    fired head-on at the head at rest), struck at the face centre; the ball of ``ball_block`` (a study ``ball:``
    mapping; default the tour urethane ball), its restitution law at the test's normal speed plus the club's gain."""
    ball = build_ball(ball_block or {"preset": "urethane_tour"})
    head = club_preset(club)
    delivery = Delivery(COR_TEST_SPEED, path=0.0, face_angle=0.0, attack_angle=0.0, dynamic_loft=0.0,
                        handedness="right", loft_at="contact", club_reference="centre_of_mass")
    scene = Scene.from_delivery(ball, Scene.face_of(head), Contact(), delivery, 0.0, head, Strike(0.0, 0.0))
    return {name: np.atleast_1d(np.asarray(value, dtype=float)) for name, value in scene.inputs().items()}


def simulated_cor(model_name: str, club: str, ball_block: Mapping | None = None) -> float:
    """The head COR [1] that the registered model ``model_name`` (default options) gives the Rules' COR test on
    ``club`` with the ball of ``ball_block``: J_n / (m* V) - 1.

    Raises
    ------
    ImpactLabError
        The model could not compute the test (its message says why).
    """
    inputs = cor_test_inputs(club, ball_block)
    result = get_model(model_name)().compute(inputs, ["normal_impulse"])
    effective_mass = 1.0 / contact_state(inputs)["mobility"][0, 2, 2]
    return float(np.asarray(result["normal_impulse"].values)[0] / (effective_mass * COR_TEST_SPEED) - 1.0)


def spring_faced_clubs(clubs: Iterable[str]) -> list[str]:
    """The distinct club presets among ``clubs`` whose face carries a restitution gain (the woods and hybrids: the
    clubs whose head COR is a fitted number), in first-seen order."""
    seen: list[str] = []
    for club in clubs:
        if club not in seen and club_preset(club).restitution_gain > 0.0:
            seen.append(club)
    return seen


def head_cors(models: Iterable[str], clubs: Iterable[str], ball_block: Mapping | None = None) -> dict:
    """club -> model -> simulated head COR (NaN where the model could not run the test; ``reasons`` says why)."""
    out: dict = {}
    for club in spring_faced_clubs(clubs):
        out[club] = {}
        for name in models:
            try:
                out[club][name] = simulated_cor(name, club, ball_block)
            except (ImpactLabError, ValueError) as error:
                out[club][name] = float("nan")
                out.setdefault("reasons", {})[(club, name)] = str(error)
    return out


def head_cor_note(models: Iterable[str], clubs: Iterable[str], ball_block: Mapping | None = None) -> str:
    """One sentence for a report: the head COR each model runs each spring-faced club with, and which are beyond the
    Rules' limit ('' when the table has no such club or no model goes beyond it)."""
    models = list(models)
    cors = head_cors(models, clubs, ball_block)
    reasons = cors.pop("reasons", {})
    beyond = {club: [m for m, e in per.items() if e > HEAD_COR_LIMIT + MARGIN] for club, per in cors.items()}
    if not any(beyond.values()):
        return ""
    parts = []
    for club, per in cors.items():
        values = ", ".join(f"{m} {e:.3f}" if np.isfinite(e) else f"{m} not computed ({reasons[(club, m)]})"
                           for m, e in per.items())
        parts.append(f"{club}: {values}")
    over = sorted({m for names in beyond.values() for m in names})
    return (f"head COR at the Rules' test ({COR_TEST_SPEED} m/s, head-on at the face centre, simulated by each model "
            f"with this table's ball): {'; '.join(parts)}. Beyond the Rules' {HEAD_COR_LIMIT:.3f}: "
            f"{', '.join(over)}: their ball speeds are those of a non-conforming head (the club preset's restitution "
            "gain is a fit to TrackMan's tour tables, whose driver ball speed a head at the limit cannot reach; "
            "docs/validation.md, issue 33 round 6)")


__all__ = ["COR_TEST_SPEED", "MARGIN", "cor_test_inputs", "head_cor_note", "head_cors", "simulated_cor",
           "spring_faced_clubs"]
