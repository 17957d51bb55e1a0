"""The base class of impact models: the plugin contract.

Writing a model means subclassing :class:`ImpactModel`, declaring what it
needs and gives, and filling one hook. The base class's public
:meth:`ImpactModel.compute` does the rest.
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterable, Mapping
from typing import Any, ClassVar

import attrs
import numpy as np
import xarray as xr

from impactlab._version import __version__
from impactlab.model.case_inputs import CaseInputs
from impactlab.errors import FieldError, ModelContractError
from impactlab.model.planning import OutputPlan, plan_outputs, require_inputs
from impactlab.model.derive import NEEDS, derive
from impactlab.vocabulary import (CASE_DIM, EVERY_SCALAR_OUTPUT, INPUTS, OUTPUTS, TIME_DIM, check_output_names,
                                  is_history)


#: samples of a history when a model does not say (rule 8, :meth:`ImpactModel.history_length`)
HISTORY_LENGTH = 256


@attrs.frozen
class NoOptions:
    """Options of a model that has none."""



def _options_data(options: Any) -> dict[str, Any]:
    """Options as plain data (JSON-ready): the fields of the model's own Options class first, then those of each
    class it inherits from, nearest first (the laws several models share come last), each in its declared order."""
    values = attrs.asdict(options)
    names = [field.name for klass in type(options).__mro__ if attrs.has(klass)
             for field in attrs.fields(klass) if not field.inherited]
    return {name: _jsonable(values[name]) for name in dict.fromkeys(names)}

class ImpactModel:
    """Base class of every impact model.

    The contract, in numbered rules:

    1. **Declarations are class attributes.** ``name`` (a Python identifier,
       the registry key and the study's ``models[].name``), ``label`` (a few
       words), ``references`` (tuple of citations), ``requires`` (input names
       from :data:`impactlab.vocabulary.INPUTS` that must be given),
       ``optional_inputs`` (inputs used when given), ``provides`` (output
       names from :data:`impactlab.vocabulary.OUTPUTS`) and ``Options`` (a
       frozen attrs class whose every field has a default and a validator).
       ``not_provided`` may map outputs the model cannot give to the reason.
    2. **One hook.** A model implements ``_compute(self, inputs, outputs)``
       and nothing else of the run; ``self.options`` holds its validated
       options.
    3. **What the hook receives.** ``inputs`` is a
       :class:`~impactlab.model.case_inputs.CaseInputs`: a read-only mapping of
       each declared input that was given (all of ``requires``, and only
       those of ``optional_inputs`` present: an absent optional input is
       absent, not defaulted) to a read-only 1-D float array; all arrays
       have the same length n, one entry per case, SI units (angles in rad,
       spin in rad/s). ``inputs.contact_state()`` gives the contact frame,
       approach velocity and mobility of the batch, computed once and shared
       with the framework's derivation. ``outputs`` is a non-empty
       frozenset, a subset of ``provides``.
    4. **What the hook returns.** A dict with every key of ``outputs``
       (other keys from ``provides`` are allowed and dropped, so a cheap
       model may always return all it has): scalar outputs as float arrays
       of shape (n,) in SI;
       history outputs as arrays of shape (n, n_time) plus the key ``"time"``,
       a 1-D array of n_time increasing instants in seconds, shared by all
       cases (pad a case that ended sooner with NaN).
    5. **Vectorised and pure.** The hook handles a whole batch at once, does
       not change its inputs and gives the same scalar results for the same
       inputs, whatever the batch around a case; histories are sampled on the
       batch's one ``time`` axis (rule 4), so their instants depend on the batch.
    6. **Physics, not bookkeeping.** A model that provides ``normal_impulse``
       and ``tangential_impulse`` gets launch angle, spin, velocities,
       tangential restitution and energy loss derived by the framework; it
       computes them itself only by also declaring them in ``provides``.
    7. **Conformance.** ``impactlab.testing.check_model`` must pass: declared
       names exist, energy never increases for a fixed face, frictionless and
       head-on impacts give no tangential impulse, mirrored impacts mirror,
       declared capabilities hold, and reference values: J_t = mu J_n in gross
       slip, the rigid-body closed form, a 3-D off-centre strike against an
       independent rigid-body solution.
    8. **Capabilities are declared, never guessed.** The framework reads them
       from the class, not from the options' fields:
       ``has_tolerance`` (class attribute, default False): ``Options`` has a
       field ``tolerance`` that sets the numerical error, so work-precision
       studies sweep it (:mod:`impactlab.data.convergence`); such a model may
       override :meth:`reference_options` and :meth:`can_reach`.
       ``provides_histories`` (derived from ``provides`` when the class is
       made): the hook returns ``"time"`` with its histories, and
       :meth:`history_length` says how many samples they have.
       :meth:`solves_3d` (this configuration solves 3-D contacts) and
       :meth:`expert_resolution` (a resolution the options fix by hand, which
       the memory estimate of :mod:`impactlab.study.limits` counts) are methods
       with defaults for models that have neither.
    9. **A 3-D contact is seen whole, or refused.** On a 3-D scene (a golf
       delivery, a club head's body, a strike point, a curved face) the hook
       must see every input of
       :data:`impactlab.physics.contact.CONTACT_STATE_INPUTS` the scene gives:
       declare them (``optional_inputs``), or set ``takes_contact_state = True``
       and read the geometry only through ``inputs.contact_state()``, which is
       then the whole scene's. A model that does neither is refused on 3-D
       scenes when it is planned, naming the inputs
       (:mod:`impactlab.model.contract`); its declarations are checked
       against the vocabulary when the plugin loads.

    The public :meth:`compute` validates inputs, hands the hook only what it
    declared, checks what came back, derives the rest, converts to the
    units of the vocabulary and wraps it all as an :class:`xarray.Dataset`
    with provenance.
    """

    name: ClassVar[str] = ""
    label: ClassVar[str] = ""
    references: ClassVar[tuple[str, ...]] = ()
    requires: ClassVar[frozenset[str]] = frozenset()
    optional_inputs: ClassVar[frozenset[str]] = frozenset()
    provides: ClassVar[frozenset[str]] = frozenset()
    not_provided: ClassVar[Mapping[str, str]] = {}
    Options: ClassVar[type[Any]] = NoOptions
    #: rule 8: ``Options`` has a field ``tolerance`` that sets the numerical error (checked by the conformance suite)
    has_tolerance: ClassVar[bool] = False
    #: rule 8: ``provides`` names a history output; set from ``provides`` for every subclass, never by hand
    provides_histories: ClassVar[bool] = False
    #: rule 9: the hook reads the contact geometry only through ``inputs.contact_state()``, which then is the
    #: state of the whole scene whatever the model declared (otherwise it must declare the contact-state inputs)
    takes_contact_state: ClassVar[bool] = False
    #: the ``Options`` fields that switch on a law of the ball or face (rolling resistance, a friction law, a turning
    #: core, a flexing face...), each with the value that switches it off: the reference-value checks hold for the
    #: plain ball (:meth:`ball_laws_on`)
    ball_law_options: ClassVar[Mapping[str, Any]] = {}

    def __init_subclass__(cls, **kwargs: Any):
        super().__init_subclass__(**kwargs)
        # derived once here so that no caller re-derives it from the vocabulary (and none can disagree)
        cls.provides_histories = any(is_history(name) for name in cls.provides)

    def __init__(self, options: Any = None, **option_values: Any):
        if options is not None and option_values:
            raise TypeError("pass either an Options instance or option keywords, not both")
        if options is None:
            options = self.make_options(option_values)
        elif not isinstance(options, self.Options):
            raise TypeError(f"options of {self.name!r} must be {self.Options.__name__}, got {type(options).__name__}")
        self.options = options

    # -- declarations -------------------------------------------------------------------------------------------
    @classmethod
    def make_options(cls, values: Mapping[str, Any]) -> Any:
        """Validated options from a mapping; unknown keys and bad values raise FieldError naming the option."""
        known = [field.name for field in attrs.fields(cls.Options)]
        for key in values:
            if key not in known:
                raise FieldError(str(key), f"an option of model {cls.name!r}", str(key),
                                 choices=known or ["(this model takes no options)"])
        try:
            return cls.Options(**values)
        except FieldError:
            raise
        except (TypeError, ValueError) as exc:
            raise FieldError("", f"valid options for model {cls.name!r}", str(exc)) from None

    @classmethod
    def why_not_provided(cls, output: str) -> str:
        """The reason, stored with the NaN results, that this model cannot give ``output``."""
        return cls.not_provided.get(output, f"model {cls.name!r} does not provide {output}")

    @classmethod
    def describe(cls) -> dict[str, Any]:
        """Declarations in plain data (for ``impactlab models`` and provenance)."""
        return {
            "name": cls.name,
            "label": cls.label,
            "requires": sorted(INPUTS[name].path for name in cls.requires),
            "optional_inputs": sorted(INPUTS[name].path for name in cls.optional_inputs),
            "provides": sorted(cls.provides),
            # the defaults as an instance sees them (a default may depend on another option)
            "options": _options_data(cls.Options()),
            "references": list(cls.references),
            # declared capabilities (rule 8); whether a configuration solves 3-D contacts is the instance's to say
            "capabilities": {"has_tolerance": cls.has_tolerance, "provides_histories": cls.provides_histories,
                             "solves_3d": cls().solves_3d()},
        }

    def reference_options(self, tolerance: float) -> Any:
        """Options of the converged reference run for a work-precision study (see impactlab.data.convergence).

        Only for a model that declares ``has_tolerance`` (rule 8); the default sets the ``tolerance`` option.
        """
        if not self.has_tolerance:
            raise ModelContractError(f"model {self.name!r} declares no tolerance (has_tolerance is False), so it has "
                                     "no reference run")
        return attrs.evolve(self.options, tolerance=tolerance)

    def ball_laws_on(self) -> tuple[str, ...]:
        """The ball and face laws this configuration switches on: the options named in :attr:`ball_law_options`
        whose values differ from the value that switches each off (``()``: the plain ball).

        The conformance suite's reference-value checks (``full_sliding``, ``rigid_limit``, ``arriving_rolling``,
        ``3d_sideways_impulse``: closed forms of a rigid sphere under Coulomb friction) hold for the plain ball only;
        a law such as the cover's rolling resistance or a friction law changes the impulses on purpose, so those
        checks are not applied to a configuration with a law on (the other checks are).
        """
        return tuple(name for name, off in self.ball_law_options.items() if getattr(self.options, name) != off)

    def solves_3d(self) -> bool:
        """Whether this configuration solves 3-D contacts (a free head struck off-centre, a curved face).

        A model does by providing ``lateral_impulse``; a configuration of it may not (and then refuses such
        scenes with a message saying what does).
        """
        return "lateral_impulse" in self.provides

    def can_reach(self, tolerance: float) -> bool:
        """Whether this configuration resolves ``tolerance`` without hitting a resolution cap."""
        return True

    def history_length(self) -> int:
        """Samples on the time axis of this configuration's histories (rule 8); a model without options for it
        gives :data:`HISTORY_LENGTH`, which is also what the memory estimate assumes for a model without histories.
        """
        return HISTORY_LENGTH

    def expert_resolution(self) -> tuple[int, int] | None:
        """(springs, time steps) fixed by hand in the options, or None when a tolerance (or nothing) sets them.

        Tolerance-driven resolutions are capped by each method; expert options are not, so they are what
        :func:`impactlab.study.limits.estimate` counts against the memory limit.
        """
        return None

    def options_dict(self) -> dict[str, Any]:
        """The resolved options as plain data (JSON-ready; infinities as strings), for provenance."""
        return _options_data(self.options)

    # -- the public entry point ---------------------------------------------------------------------------------
    def plan(self, outputs: Iterable[str], given_inputs: Iterable[str] | None = None) -> OutputPlan:
        """What a run with these outputs (and, if known, these inputs) computes, derives and leaves NaN."""
        outputs = list(check_output_names(outputs))
        return plan_outputs(type(self), outputs, None if given_inputs is None else set(given_inputs))

    def compute(self, inputs: Mapping[str, Any], outputs: Iterable[str] | None = None) -> xr.Dataset:
        """Run the model on a batch of cases.

        Parameters
        ----------
        inputs : mapping or Scene or sequence of Scene
            Input name -> scalar or 1-D array (SI), or scenes.
        outputs : iterable of str, optional
            Names from :data:`impactlab.vocabulary.OUTPUTS`; default: what the
            model provides and what derives from it, histories and the ball flight
            (computed only when named) excluded.

        Returns
        -------
        xarray.Dataset
            One variable per requested output on dimension ``case`` (and
            ``time`` for histories), in the vocabulary's units; outputs the
            model cannot give are NaN with the reason in ``missing_reason``.
        """
        return self.compute_arrays(inputs, outputs).to_dataset()

    def compute_arrays(self, inputs: Mapping[str, Any], outputs: Iterable[str] | None = None, *,
                       plan: OutputPlan | None = None) -> ModelResult:
        """:meth:`compute` without the Dataset: the outputs as SI arrays in a light :class:`ModelResult`.

        For callers that evaluate a model many times (fits, executors): the same validation and derivation,
        and no xarray object until one is asked for (:meth:`ModelResult.to_dataset`). ``plan``: this model's
        :meth:`plan` of ``outputs`` for inputs of these names, when the caller has made it already (the runner
        plans once per study, not per chunk).
        """
        batch = inputs if isinstance(inputs, CaseInputs) else CaseInputs(inputs)  # checked once per batch
        if outputs is None:
            outputs = list(EVERY_SCALAR_OUTPUT)
        if plan is None:
            plan = self.plan(outputs, batch)
        self._check_needed(batch, plan)
        n_cases = batch.n_cases
        raw = {}
        if plan.from_model:
            raw = self._compute(batch.only(self.requires | self.optional_inputs,
                                           share_contact=self.takes_contact_state), plan.from_model)
            self._check_returned(raw, plan, n_cases)
            keep = set(plan.from_model)
            if any(is_history(name) for name in keep):
                keep.add("time")
            raw = {name: value for name, value in raw.items() if name in keep}
        raw.update(derive(plan.derived, raw, batch))
        for name in plan.plugin:  # outputs plugins derive from the model's arrays (impactlab.vocabulary)
            raw[name] = _plugin_output(name, raw, n_cases)
        time = np.asarray(raw.pop("time"), dtype=float) if "time" in raw else None
        values = {}
        for name in plan.requested:
            if name in raw:
                values[name] = np.asarray(raw[name], dtype=float)
            else:
                history = is_history(name) and time is not None
                values[name] = np.full((n_cases, time.size) if history and time is not None else (n_cases,), np.nan)
        return ModelResult(self, values, time, {name: plan.missing[name] for name in plan.requested
                                                 if name not in raw})

    def _compute(self, inputs: CaseInputs, outputs: frozenset[str]) -> dict[str, np.ndarray]:
        raise NotImplementedError(f"model {self.name!r} does not implement _compute")

    # -- bookkeeping --------------------------------------------------------------------------------------------
    def _check_needed(self, batch: CaseInputs, plan: OutputPlan) -> None:
        """Every input the model requires, and those the derivation of ``plan`` needs, must be given.

        No defaults are filled in: an absent spin or club mass is absent for the hook (rule 3); the physics
        functions take a ball without spin and a fixed face where they are absent.
        """
        needed = set(self.requires)
        if plan.derived:
            needed |= NEEDS["impulses"]  # no spin given: the ball arrives without spin
        require_inputs(f"model {self.name!r}", needed, batch)

    def _check_returned(self, raw: Mapping[str, np.ndarray], plan: OutputPlan, n_cases: int) -> None:
        if not isinstance(raw, Mapping):
            raise ModelContractError(f"model {self.name!r}: _compute returned {type(raw).__name__}, not a dict")
        keys = set(raw) - {"time"}
        if not plan.from_model <= keys or not keys <= self.provides:
            raise ModelContractError(
                f"model {self.name!r}: _compute returned {sorted(keys)}; expected {sorted(plan.from_model)} "
                f"and nothing outside what it provides ({sorted(self.provides)})")
        histories = [name for name in plan.from_model if is_history(name)]
        n_time = None
        if histories:
            if "time" not in raw:
                raise ModelContractError(f"model {self.name!r}: histories returned without 'time'")
            time = np.asarray(raw["time"])
            if time.ndim != 1 or (time.size > 1 and np.any(np.diff(time) <= 0)):
                raise ModelContractError(f"model {self.name!r}: 'time' must be 1-D and increasing")
            n_time = time.size
        for name in plan.from_model:
            value = np.asarray(raw[name])
            shape = (n_cases, n_time) if is_history(name) else (n_cases,)
            if value.shape != shape:
                raise ModelContractError(
                    f"model {self.name!r}: output {name!r} has shape {value.shape}, expected {shape}")


@attrs.frozen
class ModelResult:
    """One model run's outputs as plain arrays: what :meth:`ImpactModel.compute_arrays` returns.

    Attributes
    ----------
    model : ImpactModel
    values : dict of ndarray
        Output name -> SI values, shape (n,) or (n, n_time) for histories; NaN where not given.
    time : ndarray or None
        The histories' shared time axis [s].
    missing : dict of str
        Output name -> why the model cannot give it.
    """

    model: ImpactModel
    values: dict = attrs.field(eq=False)
    time: np.ndarray | None = attrs.field(eq=False)
    missing: dict = attrs.field(eq=False)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.values[name]

    def in_units(self, name: str) -> np.ndarray:
        """The output in the vocabulary's units (deg, rpm...)."""
        return self.values[name] * OUTPUTS[name].factor

    def to_dataset(self) -> xr.Dataset:
        """The result as an xarray Dataset on dimension ``case`` (and ``time``), in the vocabulary's units."""
        coords = {}
        if self.time is not None:
            coords[TIME_DIM] = (TIME_DIM, self.time, {"units": "s", "long_name": "time since first contact"})
        data_vars = {}
        for name, values in self.values.items():
            spec = OUTPUTS[name]
            attributes = {"units": spec.units, "long_name": spec.long_name}
            if name in self.missing:
                attributes["missing_reason"] = self.missing[name]
            dims = (CASE_DIM, TIME_DIM) if values.ndim == 2 else (CASE_DIM,)
            data_vars[name] = (dims, values * spec.factor, attributes)
        return xr.Dataset(data_vars, coords=coords, attrs=self.provenance())

    def provenance(self) -> dict[str, str]:
        """The model's name, label, resolved options, references and impactlab's version."""
        model = self.model
        return {
            "model": model.name,
            "model_label": model.label,
            "model_options": json.dumps(model.options_dict(), sort_keys=True),
            "model_references": "; ".join(model.references),
            "impactlab_version": __version__,
        }


def _plugin_output(name: str, raw: Mapping[str, np.ndarray], n_cases: int) -> np.ndarray:
    """A plugin's derived output (:class:`impactlab.vocabulary.DerivedOutput`) from the SI arrays it needs."""
    spec = OUTPUTS[name]
    assert spec.function is not None, "only plugin outputs are computed here"
    try:
        value = np.asarray(spec.function(**{need: np.asarray(raw[need], dtype=float) for need in spec.needs}),
                           dtype=float)
    except Exception as exc:  # the plugin's own error, named as such
        raise ModelContractError(f"derived output {name!r} (a plugin's, impactlab.outputs) failed: "
                                 f"{type(exc).__name__}: {exc}") from None
    if value.shape != (n_cases,):
        raise ModelContractError(f"derived output {name!r} (a plugin's, impactlab.outputs) returned shape "
                                 f"{value.shape}, expected ({n_cases},): one value per case")
    return value


def _jsonable(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    return str(value)


#: the public names of this module (a plugin reaches them through impactlab.model: docs/writing-a-model.md)
__all__ = ["HISTORY_LENGTH", "NoOptions", "ImpactModel", "ModelResult"]
