"""Validity flags and the warnings they raise: where a result leaves its model's assumptions.

Each flag is a bit of the ``validity`` output (CF style: ``flag_masks`` and
``flag_meanings`` attributes). A study run warns once per flag, in words, naming the
models and the number of their cases concerned.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

#: bit -> (short name, what it means)
FLAGS: dict[int, tuple[str, str]] = {
    1: ("large_contact", "the contact radius exceeds 0.3 R, where Hertz's paraboloid misses the sphere's surface "
                         "by more than 2 % at the contact edge (golf impacts reach 0.38-0.56 R: 4-9 %)"),
    2: ("soft_face", "the face is more compliant than the ball, so the half-space idealisation of the face is "
                     "strained"),
    4: ("tolerance_not_met", "the requested tolerance needs more resolution than the method allows; the result is "
                             "less accurate than asked"),
    8: ("unfinished", "the 3-D integration reached its step limit before the bodies separated; the impulses are "
                      "those of an unfinished contact"),
    16: ("dundurs_coupling", "the normal-tangential coupling the model neglects (ball and face differ in Dundurs' "
                             "beta) is estimated to change the tangential impulse by more than the tolerance asked "
                             "for (output coupling_estimate; docs/models.md)"),
    32: ("energy_capped", "the kinematic restitution coefficients asked for an impulse that creates kinetic energy "
                          "(a coupled mobility); the impulse was scaled down along its direction to the largest "
                          "that creates none (impactlab.physics.rigid.energy_cap)"),
    64: ("friction_limit_3d", "the compliant solution breaks the 3-D Coulomb limit of the contact (MDR springs "
                              "carrying more than mu p(r) where the damped law's pressure falls fastest, at the "
                              "centre) by more than the tolerance; J_t carries the annular strips' correction (exact "
                              "on one line, first order off it; models/maw.py)"),
}
#: a_max / R above which ``large_contact`` is raised. Hertz's theory replaces the sphere's gap R - sqrt(R^2 - r^2)
#: by the paraboloid r^2 / (2 R) and the ball by a half-space; both need a << R (Johnson, Contact Mechanics, 1985,
#: section 4.2). The paraboloid's gap at the contact edge is short of the sphere's by (1 - sqrt(1 - rho^2)) / 2
#: relative, rho = a/R (:func:`paraboloid_error`): 2.3 % at 0.3, 3.8 % at 0.38, 8.5 % at 0.56 (maw's a_max/R over
#: studies/approaches_golf.yaml, gear_effect.yaml and sensitivity.yaml: 0.38-0.56). The error passes 2 %, the
#: size of the effects the project's validations resolve, at 0.28; 0.3 is the round number above it. Before 2026-11
#: the flag fired only above 0.6 and so never for a golf impact.
LARGE_CONTACT_RATIO = 0.3


def paraboloid_error(ratio: ArrayLike) -> np.ndarray:
    """Relative shortfall of Hertz's paraboloid gap against the sphere's at the contact edge.

    Parameters
    ----------
    ratio : array_like
        Contact radius over sphere radius a/R [1], 0 <= a/R <= 1.

    Returns
    -------
    ndarray
        1 - (r^2 / 2R) / (R - sqrt(R^2 - r^2)) at r = a = (1 - sqrt(1 - rho^2)) / 2 [1]; about rho^2 / 4 for a
        small contact. A geometric statement, exact; what it does to the force needs a finite-strain solution, which
        impactlab does not have.
    """
    rho = np.asarray(ratio, dtype=float)
    return (1.0 - np.sqrt(1.0 - rho**2)) / 2.0


class ValidityWarning(UserWarning):
    """Some cases of a result lie outside the assumptions of the model that computed them."""


def flag_attributes() -> dict[str, object]:
    """CF attributes of the ``validity`` flag variable: ``flag_masks``, ``flag_values`` and ``flag_meanings``."""
    # bit flags in CF: with flag_masks and flag_values both given, flag i is set when value & mask_i == value_i
    bits = np.array(sorted(FLAGS), dtype=np.int16)
    return {"flag_masks": bits, "flag_values": bits.copy(),
            "flag_meanings": " ".join(FLAGS[bit][0] for bit in sorted(FLAGS))}


def messages(dataset: xr.Dataset) -> list[str]:
    """One sentence per flag that some case raised, naming the models and how many of their cases.

    One sentence per flag, not per flag and model: a golf study of five models would otherwise print the
    same two sentences five times.
    """
    if "validity" not in dataset:
        return []
    # the variables themselves, no DataArray with its coordinates: this runs after every study
    flags = dataset.variables["validity"]
    per_model = "model" in flags.dims
    values = flags.values
    # models first, every case of a model on one row (plain arrays; numpy's Python-level helpers only where needed:
    # after a model's kernel their code is cold, ~20-40 us a call)
    axis = flags.dims.index("model") if per_model else None
    values = values[None] if axis is None else np.moveaxis(values, axis, 0) if axis else values
    values = values.reshape(values.shape[0], -1)
    if values.dtype.kind == "f":  # a result read back from a file: NaN where a model did not compute a case
        values = np.nan_to_num(values)
    values = values.astype(np.int64)
    model = dataset.variables["model"] if "model" in dataset.coords else None
    names: Any
    if per_model:  # a model dimension without labels (not one impactlab writes) counts its models from 0
        names = model.values if model is not None else np.arange(values.shape[0])
    else:  # one model's selection keeps its name as a scalar coordinate
        names = [model.values.item() if model is not None and model.ndim == 0 else "model"]
    found = []
    present = int(np.bitwise_or.reduce(values, axis=None)) if values.size else 0  # the flags any case raised
    for bit, (_, meaning) in FLAGS.items():
        if not present & bit:  # no case raised it: nothing to count (most flags, most runs)
            continue
        counts = np.count_nonzero(values & bit, axis=1)
        raised = [(str(model), int(count), values.shape[1]) for model, count in zip(names, counts) if count]
        if len({(count, size) for _, count, size in raised}) == 1:
            _, count, size = raised[0]
            models = ", ".join(model for model, _, _ in raised)
            found.append(f"{models}: in {count} of {size} case(s){' each' if len(raised) > 1 else ''} {meaning}")
        elif raised:
            counts = ", ".join(f"{model} ({count} of {size} cases)" for model, count, size in raised)
            found.append(f"{counts}: {meaning}")
    return found


def warn(dataset: xr.Dataset) -> None:
    """Issue one :class:`ValidityWarning` per sentence of :func:`messages`."""
    for text in messages(dataset):
        warnings.warn(text, ValidityWarning, stacklevel=3)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["FLAGS", "LARGE_CONTACT_RATIO", "paraboloid_error", "ValidityWarning", "flag_attributes", "messages",
           "warn"]
