"""The head COR each registered model runs a table's clubs with (:mod:`impactlab.run.rules_test` by preset name).

``impactlab validate`` prints :func:`head_cor_note` beside its errors, and a session scorecard keeps it (attribute
``head_cor``, text and HTML), so that a ball-speed agreement reached with a head beyond the Rules' COR limit says so.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

from impactlab.model.registry import get_model
from impactlab.run.rules_test import COR_TEST_SPEED, MARGIN, head_cors, simulated_cor
from impactlab.run import rules_test
from impactlab.scene.catalogue import club_preset
from impactlab.study.scene_blocks import build_ball

_DEFAULT_BALL = {"preset": "urethane_tour"}


def model_cor(model_name: str, club: str, ball_block: Mapping | None = None) -> float:
    """The head COR [1] the registered model ``model_name`` (default options) gives the Rules' COR test on the club
    preset ``club`` with the ball of ``ball_block`` (a study ``ball:`` mapping; default the tour urethane ball)."""
    return simulated_cor(get_model(model_name)(), build_ball(ball_block or _DEFAULT_BALL), club_preset(club))


def spring_faced_clubs(clubs: Iterable[str]) -> list[str]:
    """The distinct club presets among ``clubs`` whose face carries a restitution gain, in first-seen order."""
    seen: list[str] = []
    for club in clubs:
        if club not in seen and club_preset(club).restitution_gain > 0.0:
            seen.append(club)
    return seen


def head_cor_note(models: Iterable[str], clubs: Iterable[str], ball_block: Mapping | None = None) -> str:
    """:func:`impactlab.run.rules_test.head_cor_note` for registered model names (default options), the club
    presets among ``clubs`` and a table's ``ball:`` block."""
    heads = {club: club_preset(club) for club in spring_faced_clubs(clubs)}
    if not heads:
        return ""
    return rules_test.head_cor_note({name: get_model(name)() for name in models},
                                    build_ball(ball_block or _DEFAULT_BALL), heads)


__all__ = ["COR_TEST_SPEED", "MARGIN", "head_cor_note", "head_cors", "model_cor", "spring_faced_clubs"]
