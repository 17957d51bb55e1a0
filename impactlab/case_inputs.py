"""The inputs of a batch of cases, as a model's hook receives them (rule 3 of the model contract).

A read-only mapping from input name to a read-only 1-D float array (SI), one entry per case, that also
carries what is computed from the inputs once per batch and used on both sides of the hook: the contact
frame, approach velocity and mobility of :func:`impactlab.physics.contact.contact_state`. A compliant
model needs that state to pose its contact problem and the framework needs it again to turn the model's
impulses into launch conditions (rule 6); computing it once saves about a millisecond per 500 cases per
model, which on a small sweep is a sizeable part of what the framework costs around the physics.
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping

import numpy as np

from .physics.contact import CONTACT_STATE_INPUTS, contact_state


class CaseInputs(Mapping):
    """Input name -> read-only SI array (n cases), with the batch's contact state computed once.

    Parameters
    ----------
    arrays : mapping of str to ndarray
        1-D float arrays of one length (names from :data:`impactlab.vocabulary.INPUTS`). They are not
        copied: the caller hands them over and must not change them afterwards.

    Examples
    --------
    >>> import numpy as np
    >>> batch = CaseInputs({"speed": np.array([40.0]), "angle": np.array([0.3]), "ball_mass": np.array([0.0459]),
    ...                     "ball_radius": np.array([0.02135])})
    >>> float(batch.contact_state()["normal_speed"][0]) > 0.0
    True
    """

    __slots__ = ("_arrays", "_state")

    def __init__(self, arrays: Mapping[str, np.ndarray], *, _state: list | None = None):
        self._arrays = dict(arrays)
        # a one-element cell, shared with the views (``only``) that see the same contact inputs
        self._state = [None] if _state is None else _state

    def __getitem__(self, name: str) -> np.ndarray:
        return self._arrays[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._arrays)

    def __len__(self) -> int:
        return len(self._arrays)

    def __repr__(self) -> str:
        return f"CaseInputs({sorted(self._arrays)})"

    def contact_state(self) -> dict:
        """:func:`impactlab.physics.contact.contact_state` of these inputs, computed at most once per batch.

        The arrays of the returned dict are read-only: the state is shared between the model's hook and the
        framework's derivation, so a change by one would be a wrong answer in the other.
        """
        if self._state[0] is None:
            state = contact_state(self._arrays)
            for value in state.values():
                if isinstance(value, np.ndarray):
                    value.setflags(write=False)
            self._state[0] = state
        return self._state[0]

    def only(self, names: Iterable[str]) -> CaseInputs:
        """The inputs among ``names`` (what a model declared).

        The view shares this batch's contact state where it keeps every input that state reads; otherwise
        (a model that does not declare, say, the club's inertia) its state is its own, from what it sees.
        """
        names = set(names)
        kept = {name: array for name, array in self._arrays.items() if name in names}
        same_contact = all(name in names for name in CONTACT_STATE_INPUTS if name in self._arrays)
        return CaseInputs(kept, _state=self._state if same_contact else None)


__all__ = ["CaseInputs"]
