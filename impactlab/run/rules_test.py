"""The Rules' COR test run by a model: the head COR a model gives a club head with a ball.

The Rules bound a club head's coefficient of restitution with a ball at 0.830 (USGA/R&A Equipment Rules, Part 2,
5a: 0.822 plus the test's tolerance 0.008; a ball fired head-on at the face centre at 48.77 m/s). The package's wood
and hybrid presets carry a restitution gain fitted to TrackMan's tour tables (0.083 on the tour ball's 0.787: a pair
e of 0.870), and every model that adds that gain to the ball's e runs them as a head beyond the limit; the models
with the flexing face (``hertz_mindlin_face``, ``hertz_mindlin_slip``) size the face at the limit instead. A head
at the limit falls 1.9 % short of TrackMan's PGA Tour driver ball speed (docs/validation.md, issue 33 round 6), so
a result from a head beyond the limit says so: :func:`head_cor_note` is printed by ``impactlab validate``, kept in a
scorecard and in a study's result (attribute ``head_cor``).

The test is run by the model, not computed from its inputs, so that it holds for any model, a plugin's too, with
its options: the model's normal impulse J_n of the head-on impact gives the pair's e = J_n / (m* V) - 1, m* the
pair's effective mass along the normal (head mass and its turning about its centre of mass), V the test's speed.
The test runs without friction: a head-on impact has no slip to resist, and with a centre of mass off the normal
line the mobility's coupling would feed a friction impulse into J_n (+4e-4 in e on the 3-wood, more with a lower
centre of mass). What it reports is the pair's e with the table's or study's ball, not the Rules' reference ball's.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from impactlab.model.base import ImpactModel
from impactlab.physics.contact import contact_state
from impactlab.physics.rate_laws import HEAD_COR_LIMIT
from impactlab.scene.clubs import ClubHead, Strike
from impactlab.scene.core import Contact, Delivery, Scene
from impactlab.scene.materials import Ball

#: the COR test's ball speed [m/s]: 160 ft/s (USGA/R&A, Procedure for measuring the velocity ratio of a club head)
COR_TEST_SPEED = 48.77
#: a COR reported as beyond the limit only beyond this margin (the face models are sized at the limit to 1e-4)
MARGIN = 5e-4
#: why a report names the models beyond the limit
WHY = ("their results are those of a head livelier than the Rules allow, with this ball (the club presets' "
       "restitution gain is a fit to TrackMan's tour tables, whose PGA driver ball speed a head at the limit misses "
       "by 1.9 %; docs/validation.md, issue 33 round 6)")
#: the longest reason a note repeats for a model that could not run the test
REASON_LENGTH = 160


def cor_test_inputs(ball: Ball, head: ClubHead, contact: Contact | None = None) -> dict:
    """Model inputs (SI arrays, one case) of the Rules' COR test on ``head``: the head moving at
    :data:`COR_TEST_SPEED` onto ``ball`` at rest, loft, attack, path and face angle 0 (the relative impact of a ball
    fired head-on at the head at rest), struck at the face centre, without friction; the restitution of ``contact``
    where the caller's scene gives one, else the ball's law at the test's normal speed plus the club's gain."""
    delivery = Delivery(COR_TEST_SPEED, path=0.0, face_angle=0.0, attack_angle=0.0, dynamic_loft=0.0,
                        handedness="right", loft_at="contact", club_reference="centre_of_mass")
    frictionless = Contact(friction=0.0, restitution=contact.restitution if contact is not None else None)
    scene = Scene.from_delivery(ball, Scene.face_of(head), frictionless, delivery, 0.0, head, Strike(0.0, 0.0))
    return {name: np.atleast_1d(np.asarray(value, dtype=float)) for name, value in scene.inputs().items()}


def simulated_cor(model: ImpactModel, ball: Ball, head: ClubHead, contact: Contact | None = None) -> float:
    """The head COR [1] that ``model`` (an instance, with its options) gives the Rules' COR test on ``head`` with
    ``ball``: J_n / (m* V) - 1.

    Raises
    ------
    ImpactLabError
        The model could not run the test (its message says why).
    """
    inputs = cor_test_inputs(ball, head, contact)
    result = model.compute(inputs, ["normal_impulse"])
    effective_mass = 1.0 / contact_state(inputs)["mobility"][0, 2, 2]
    return float(np.asarray(result["normal_impulse"].values)[0] / (effective_mass * COR_TEST_SPEED) - 1.0)


def _reason(error: BaseException) -> str:
    text = str(error).strip().splitlines()[0] if str(error).strip() else type(error).__name__
    return text if len(text) <= REASON_LENGTH else text[:REASON_LENGTH - 3] + "..."


def head_cors(models: Mapping[str, ImpactModel], ball: Ball, heads: Mapping[str, ClubHead],
              contact: Contact | None = None) -> tuple[dict, dict]:
    """(club -> model -> simulated COR, (club, model) -> why not computed) for every head of ``heads`` whose face
    carries a restitution gain (the woods and hybrids: the heads whose COR is a fitted number); NaN, with its
    reason, where a model provides no normal impulse, gives none, or fails on the test (whatever it raises: a
    report's note never stops the report)."""
    cors: dict = {}
    reasons: dict = {}
    for club, head in heads.items():
        if head.restitution_gain <= 0.0:
            continue
        cors[club] = {}
        for name, model in models.items():
            value = float("nan")
            if "normal_impulse" not in type(model).provides:
                reasons[(club, name)] = "the model provides no normal impulse"
            else:
                try:
                    value = simulated_cor(model, ball, head, contact)
                except Exception as error:  # noqa: BLE001 (a plugin's failure on the test is reported, not raised)
                    reasons[(club, name)] = _reason(error)
                else:
                    if not np.isfinite(value):
                        reasons[(club, name)] = "the model gave no finite normal impulse"
            cors[club][name] = value
    return cors, reasons


def head_cor_note(models: Mapping[str, ImpactModel], ball: Ball, heads: Mapping[str, ClubHead],
                  contact: Contact | None = None, whose: str = "this table's ball") -> str:
    """One sentence for a report: the head COR each model gives each spring-faced head, which models are beyond the
    Rules' limit and which could not run the test ('' when there is no such head, or every model ran it within the
    limit)."""
    cors, reasons = head_cors(models, ball, heads, contact)
    over = sorted({m for per in cors.values() for m, e in per.items() if e > HEAD_COR_LIMIT + MARGIN})
    if not over and not reasons:
        return ""
    parts = [f"{club}: " + ", ".join(f"{m} {e:.3f}" if np.isfinite(e) else f"{m} not computed ({reasons[(club, m)]})"
                                     for m, e in per.items()) for club, per in cors.items()]
    verdict = (f"Beyond the Rules' {HEAD_COR_LIMIT:.3f}: {', '.join(over)}: {WHY}" if over
               else f"none beyond the Rules' {HEAD_COR_LIMIT:.3f} among the models that ran it")
    return (f"head COR at the Rules' test ({COR_TEST_SPEED} m/s, head-on at the face centre, run by each model with "
            f"{whose}): {'; '.join(parts)}. {verdict}")


__all__ = ["COR_TEST_SPEED", "MARGIN", "cor_test_inputs", "head_cor_note", "head_cors", "simulated_cor"]
