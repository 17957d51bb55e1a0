"""A study's cases as arrays: the model inputs over the Cartesian product of its sweep, in SI."""

from __future__ import annotations

import numpy as np

from impactlab.errors import FieldError
from impactlab.scene.core import ball_restitution, complete_inputs
from impactlab.study.core import Study


def ball_law_applies(study: Study) -> bool:
    """Whether the restitution comes from the ball's law (the study's own or, swept, each preset's)."""
    if study.scene.contact.restitution is not None or "contact.restitution" in {
            field.path for axis in study.sweep for field in axis.fields}:
        return False
    swept = [axis.balls for axis in study.sweep if axis.balls is not None]
    if swept:
        return any(ball.restitution is not None for ball in swept[0])
    return study.scene.ball.restitution is not None


def case_inputs(study: Study) -> dict[str, np.ndarray]:
    """Input arrays over the Cartesian product of the sweep, flattened in C order (first axis slowest).

    Parameters
    ----------
    study : Study

    Returns
    -------
    dict of str to numpy.ndarray
        Every input the scene gives and every input derived from them (:func:`impactlab.scene.core.complete_inputs`),
        one value per case, in SI units (the vocabulary's, :data:`impactlab.vocabulary.INPUTS`).

    Raises
    ------
    FieldError
        A swept delivery whose face would meet the ball (spin loft of 90 deg or more).
    """
    base = study.scene.inputs()
    grids = np.meshgrid(*[np.arange(axis.size) for axis in study.sweep], indexing="ij") if study.sweep else []
    # the scene fields plugins declare (a study's plugin: block) come with the scene's own
    base = {**base, **dict(study.plugin_inputs)}
    inputs = {name: np.full(study.n_cases, value, dtype=float) for name, value in base.items()}
    for axis, grid in zip(study.sweep, grids):
        for field in axis.fields:
            inputs[field.input] = np.asarray(field.values, dtype=float)[grid.reshape(-1)]
    complete_inputs(inputs)
    if ball_law_applies(study):
        ball_axes = [(axis, grid) for axis, grid in zip(study.sweep, grids) if axis.balls is not None]
        if ball_axes:  # a swept ball preset: each case's ball's own law at its own normal speed
            (axis, grid), = ball_axes
            assert axis.balls is not None, "ball_axes holds the axes with balls"
            if any(ball.restitution is None for ball in axis.balls):
                raise FieldError("sweep.ball.preset", "balls that all have a restitution law, or a "
                                 "contact.restitution for all", "a ball without one")
            laws = [ball_restitution(ball, inputs) for ball in axis.balls]
            inputs["restitution"] = np.choose(grid.reshape(-1), laws)
        else:
            # the ball's restitution law at each case's own normal speed
            inputs["restitution"] = ball_restitution(study.scene.ball, inputs)
    if np.any(inputs["angle"] >= np.pi / 2):
        case = int(np.argmax(inputs["angle"] >= np.pi / 2))
        raise FieldError("sweep", "deliveries whose face meets the ball (spin loft below 90 deg)",
                         f"spin loft {np.degrees(inputs['angle'][case]):.1f} deg in case {case}")
    return inputs
