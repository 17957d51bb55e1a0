"""The inputs of a batch of cases, as a model's hook receives them (rule 3 of the model contract).

A read-only mapping from input name to a read-only 1-D float array (SI), one entry per case, that also
carries what is computed from the inputs once per batch and used on both sides of the hook: the contact
frame, approach velocity and mobility of :func:`impactlab.physics.contact.contact_state`. A compliant
model needs that state to pose its contact problem and the framework needs it again to turn the model's
impulses into launch conditions (rule 6); computing it once saves about a millisecond per 500 cases per
model, which on a small sweep is a sizeable part of what the framework costs around the physics.
"""

from __future__ import annotations

import types
from collections.abc import Iterable, Iterator, Mapping
from typing import Any

import numpy as np

from impactlab.errors import FieldError, ModelInputError
from impactlab.physics.contact import CONTACT_STATE_INPUTS, contact_state, launch_plane
from impactlab.vocabulary import INPUTS
from impactlab.scene.core import Scene


class CaseInputs(Mapping):
    """Input name -> read-only SI array (n cases), checked once, with the batch's contact state computed once.

    Parameters
    ----------
    values : mapping, Scene or sequence of Scene
        Input name -> scalar or 1-D array (SI), or scenes (their common inputs; the face surface's inputs where
        any scene gives them, NaN for a scene without a surface, which a friction law refuses). Names must come from
        :data:`impactlab.vocabulary.INPUTS`, arrays have one length (scalars are repeated), and every value
        must lie in its input's range; the arrays are copied and made read-only.
    copy : bool
        False: keep read-only views of float arrays of full length instead of copies (the runner's own
        case arrays: a million-case study would otherwise hold its inputs twice). The caller must not
        change them while the batch is in use.

    Raises
    ------
    FieldError
        An unknown input name, or a value out of its input's range (naming the input's study path).
    ModelInputError
        Arrays of different lengths, or not 1-D.

    Notes
    -----
    Several models run on one batch (a study's models on a chunk of its cases) check the inputs and build
    the contact state once between them: pass the same ``CaseInputs`` to each
    :meth:`~impactlab.model.base.ImpactModel.compute_arrays`.

    Examples
    --------
    >>> import numpy as np
    >>> batch = CaseInputs({"speed": [40.0, 50.0], "angle": 0.3, "ball_mass": 0.0459, "ball_radius": 0.02135})
    >>> batch.n_cases, float(batch.contact_state()["normal_speed"][0]) > 0.0
    (2, True)
    """

    __slots__ = ("_arrays", "_state", "n_cases", "_last_slice")

    def __init__(self, values: Any, *, copy: bool = True):
        self._arrays, self.n_cases = _checked_arrays(values, copy)
        # a cell for the contact state and its launch plane, shared with the views (``only``) that see the same contact
        self._state: list[Mapping[str, Any] | None] = [None, None]
        self._last_slice: tuple[tuple[int, int], CaseInputs] | None = None

    @classmethod
    def _view(cls, arrays: dict, n_cases: int, state: list | None) -> CaseInputs:
        """A batch of arrays already checked (no copy, no second check)."""
        view = cls.__new__(cls)
        view._arrays, view.n_cases, view._state = arrays, n_cases, [None, None] if state is None else state
        view._last_slice = None
        return view

    def __getitem__(self, name: str) -> np.ndarray:
        return self._arrays[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._arrays)

    def __len__(self) -> int:
        return len(self._arrays)

    def __repr__(self) -> str:
        return f"CaseInputs({self.n_cases} case(s): {', '.join(sorted(self._arrays))})"

    def contact_state(self) -> Mapping:
        """:func:`impactlab.physics.contact.contact_state` of these inputs, computed at most once per batch.

        The mapping and its arrays are read-only: the state is shared between models' hooks and the
        framework's derivation, so a change by one would be a wrong answer in another (and a different one
        with each executor, which gives each worker its own).
        """
        cached = self._state[0]
        if cached is None:
            state = contact_state(self._arrays)
            for value in state.values():
                if isinstance(value, np.ndarray):
                    value.setflags(write=False)
            cached = self._state[0] = types.MappingProxyType(state)
        return cached

    def launch_plane(self) -> Mapping:
        """:func:`impactlab.physics.contact.launch_plane` of :meth:`contact_state`, computed at most once per batch.

        The derivation of every model run on the batch measures its launch angle in this plane (read-only, as the
        state it comes from).
        """
        cached = self._state[1]
        if cached is None:
            plane = launch_plane(self.contact_state())
            for value in plane.values():
                value.setflags(write=False)
            cached = self._state[1] = types.MappingProxyType(plane)
        return cached

    def only(self, names: Iterable[str], share_contact: bool = False) -> CaseInputs:
        """The inputs among ``names`` (what a model declared).

        The view shares this batch's contact state where it keeps every input that state reads, or where
        ``share_contact`` (a model that takes the framework's contact state, ``takes_contact_state``); otherwise
        its state is its own, from what it sees (on a 3-D scene the planner refuses a model in that case,
        :mod:`impactlab.model.contract`).
        """
        names = set(names)
        kept = {name: array for name, array in self._arrays.items() if name in names}
        same_contact = all(name in names for name in CONTACT_STATE_INPUTS if name in self._arrays)
        if share_contact and not same_contact:
            self.contact_state()  # filled from this batch's arrays: the view must not compute it from fewer
            same_contact = True
        return CaseInputs._view(kept, self.n_cases, self._state if same_contact else None)

    def slice(self, start: int, stop: int) -> CaseInputs:
        """Cases ``start:stop`` (a chunk of a study), checked already, with a contact state of its own.

        The last slice is kept and given again for the same bounds, so the models run one after another
        on a chunk share its contact state (and only one chunk's state is held).
        """
        if self._last_slice is not None and self._last_slice[0] == (start, stop):
            return self._last_slice[1]
        arrays = {name: array[start:stop] for name, array in self._arrays.items()}
        view = CaseInputs._view(arrays, len(range(self.n_cases)[start:stop]), None)
        self._last_slice = ((start, stop), view)
        return view


def _checked_arrays(values: Any, copy: bool = True) -> tuple[dict[str, np.ndarray], int]:
    """Read-only float arrays of one length from a mapping or scenes, every value in its input's range."""
    if isinstance(values, Scene):
        values = [values]
    if not isinstance(values, Mapping):
        scenes = list(values)
        if not scenes or not all(isinstance(scene, Scene) for scene in scenes):
            raise TypeError("inputs must be a mapping of input arrays, a Scene or a sequence of Scenes")
        per_scene = [scene.inputs() for scene in scenes]
        common = set.intersection(*(set(each) for each in per_scene))
        # the face's surface is read only by a friction law, which refuses the cases without one: NaN says "not
        # given" for those, rather than one scene without a surface dropping it from every case
        partial = {name for each in per_scene for name in each if INPUTS[name].path.startswith("face.surface.")}
        values = {name: np.array([each.get(name, np.nan) for each in per_scene], dtype=float)
                  for name in common | partial}
        unset = partial - common
    else:
        unset = set()
    arrays = {}
    for name, value in values.items():
        if name not in INPUTS:
            raise FieldError(str(name), "an input name", name, choices=INPUTS)
        array = np.atleast_1d(np.asarray(value, dtype=float))
        if array.ndim != 1:
            raise ModelInputError(f"input {name!r} must be a scalar or 1-D array, got shape {array.shape}")
        arrays[name] = array
    sizes = {array.size for array in arrays.values() if array.size != 1}
    if len(sizes) > 1:
        raise ModelInputError(f"inputs have different lengths {sorted(sizes)}; give scalars or arrays of one length")
    n_cases = sizes.pop() if sizes else 1
    for name, array in arrays.items():
        spec = INPUTS[name]
        bad = spec.out_of_range(array)
        if name in unset:
            bad &= ~np.isnan(array)
        if np.any(bad):
            raise FieldError(spec.path, spec.range_text(), float(array[np.argmax(bad)]))
        if copy or array.size != n_cases:
            array = np.array(np.broadcast_to(array, (n_cases,)), dtype=float)  # a copy the caller cannot change
        else:
            array = array.view()
        array.setflags(write=False)  # a view's flag leaves the caller's array as it was
        arrays[name] = array
    return arrays, n_cases


__all__ = ["CaseInputs"]
