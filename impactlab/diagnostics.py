"""Validity flags and the warnings they raise: where a result leaves its model's assumptions.

Each flag is a bit of the ``validity`` output (CF style: ``flag_masks`` and
``flag_meanings`` attributes). A study run warns once per flag and model, in
words, with the number of cases concerned.
"""

from __future__ import annotations

import warnings

import numpy as np

#: bit -> (short name, what it means)
FLAGS: dict[int, tuple[str, str]] = {
    1: ("large_contact", "the contact radius exceeds 0.6 R, beyond Hertz's small-contact assumption"),
    2: ("soft_face", "the face is more compliant than the ball, so the half-space idealisation of the face is "
                     "strained"),
    4: ("tolerance_not_met", "the requested tolerance needs more resolution than the method allows; the result is "
                             "less accurate than asked"),
    8: ("unfinished", "the 3-D integration reached its step limit before the bodies separated; the impulses are "
                      "those of an unfinished contact"),
}
LARGE_CONTACT_RATIO = 0.6


class ValidityWarning(UserWarning):
    """Some cases of a result lie outside the assumptions of the model that computed them."""


def flag_attributes() -> dict[str, object]:
    # bit flags in CF: with flag_masks and flag_values both given, flag i is set when value & mask_i == value_i
    bits = np.array(sorted(FLAGS), dtype=np.int16)
    return {"flag_masks": bits, "flag_values": bits.copy(),
            "flag_meanings": " ".join(FLAGS[bit][0] for bit in sorted(FLAGS))}


def messages(dataset) -> list[str]:
    """One sentence per flag and model that some case raised."""
    if "validity" not in dataset:
        return []
    found = []
    flags = dataset["validity"]
    for model in flags["model"].values if "model" in flags.dims else [None]:
        values = np.nan_to_num(np.asarray(flags.sel(model=model).values if model is not None else flags.values))
        values = values.astype(np.int64)
        for bit, (_, meaning) in FLAGS.items():
            count = int(np.count_nonzero(values & bit))
            if count:
                found.append(f"{model}: in {count} of {values.size} case(s) {meaning}")
    return found


def warn(dataset) -> None:
    for text in messages(dataset):
        warnings.warn(text, ValidityWarning, stacklevel=3)
