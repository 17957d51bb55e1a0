"""Plan the work before running it: which outputs a model computes, which the framework derives, which are missing.

A model declares the outputs it *provides*. Most result variables follow
from the two impulses by rigid-body bookkeeping
(:func:`impactlab.physics.contact.after_impact`), so the framework derives
them for any model that provides ``normal_impulse`` and
``tangential_impulse``. The plan is computed from declarations alone, so it
can be shown (and stored) before anything runs.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

import attrs

from impactlab.model.derive import FROM_DELIVERY, FROM_FLIGHT, FROM_MATERIALS, IMPULSES, NEEDS, derivable
from impactlab.model.derive import DERIVATION_OPTIONAL, FLIGHT_INPUTS
from impactlab.errors import ModelInputError
from impactlab.model.contract import require_contact_inputs
from impactlab.physics.aerodynamics import DEFAULT_MODEL as DEFAULT_AIR_MODEL
from impactlab.vocabulary import INPUTS, OUTPUTS

if TYPE_CHECKING:  # model.base imports this module
    from impactlab.model.base import ImpactModel


@attrs.frozen
class OutputPlan:
    """What one model run will compute.

    Attributes
    ----------
    model : str
    requested : tuple of str
        The outputs asked for, in order.
    from_model : frozenset of str
        Outputs the model's hook is asked for.
    derived : frozenset of str
        Outputs the framework derives from the impulses.
    missing : dict
        Output -> reason, for outputs that will be NaN.
    inputs : frozenset of str
        Inputs the run needs (hook's declared inputs plus those of the derivation).
    """

    model: str
    requested: tuple[str, ...]
    from_model: frozenset[str]
    derived: frozenset[str]
    missing: dict[str, str]
    inputs: frozenset[str]
    #: outputs plugins derive from the model's arrays (impactlab.vocabulary.DerivedOutput), after the model ran
    plugin: tuple[str, ...] = ()

    def describe(self) -> str:
        """One paragraph in words."""
        parts = [f"{self.model}: computes {', '.join(sorted(self.from_model)) or 'nothing'}"]
        if self.derived - FROM_FLIGHT:
            parts.append(f"derives {', '.join(sorted(self.derived - FROM_FLIGHT))} from the impulses")
        if self.derived & FROM_FLIGHT:
            parts.append(f"flies the launch for {', '.join(sorted(self.derived & FROM_FLIGHT))} ({DEFAULT_AIR_MODEL} "
                         "aerodynamics; the study's conditions or 15 degC, 101 325 Pa, 50 % humidity, still air)")
        for name, reason in self.missing.items():
            parts.append(f"leaves {name} NaN ({reason})")
        return "; ".join(parts)


def require_inputs(who: str, needed: Iterable[str], given: Iterable[str], source: str = "the scene") -> None:
    """Raise ModelInputError naming, with their paths and meanings, the inputs of ``needed`` not in ``given``.

    The one check and message of a missing input, before a study runs (:func:`impactlab.run.runner.plan_study`)
    and when a model is computed.
    """
    absent = sorted(set(needed) - set(given))
    if absent:
        names = ", ".join(f"{INPUTS[name].path} ({INPUTS[name].description})" for name in absent)
        raise ModelInputError(f"{who} needs {names}, which {source} does not give; add it or use another model")


def plan_outputs(model_cls: type[ImpactModel], requested: Iterable[str],
                 given_inputs: Iterable[str] | None = None) -> OutputPlan:
    """Plan the outputs ``requested`` from a model class (set logic on declarations only).

    ``given_inputs``, when known, lets the plan tell outputs that need inputs
    the scene lacks (a golf delivery) from those it can give; on a 3-D scene it
    refuses a model whose hook would not see the whole contact state
    (:func:`impactlab.model.contract.require_contact_inputs`, ModelInputError).
    """
    requested = tuple(dict.fromkeys(requested))
    if given_inputs is not None:  # on a 3-D scene the hook must see the whole contact (impactlab.model.contract)
        require_contact_inputs(model_cls, given_inputs)
    provides = frozenset(model_cls.provides)
    from_model, derived, missing = set(), set(), {}
    plugin = tuple(name for name in requested if OUTPUTS[name].function is not None)
    # a plugin's output is planned through the outputs it needs (asked of the model or derived like any other)
    needs = tuple(dict.fromkeys(need for name in plugin for need in OUTPUTS[name].needs))
    for name in tuple(name for name in requested if name not in plugin) + tuple(
            need for need in needs if need not in requested):
        if name in provides:
            from_model.add(name)
            continue
        possible, reason = derivable(name, provides, given_inputs)
        if possible:
            derived.add(name)
            from_model |= IMPULSES | (provides & {"lateral_impulse", "rolling_moment", "rolling_moment_slip"})
        else:
            missing[name] = reason or model_cls.why_not_provided(name)
    kept = []
    for name in plugin:
        lacking = [need for need in OUTPUTS[name].needs if need in missing]
        if lacking:
            missing[name] = "; ".join(f"needs {need}: {missing[need]}" for need in lacking)
        else:
            kept.append(name)
    for need in needs:  # a need nobody asked for is not reported missing on its own
        if need not in requested:
            missing.pop(need, None)
    inputs = set(model_cls.requires) | (set(model_cls.optional_inputs) & set(INPUTS))
    if derived:
        inputs |= NEEDS["impulses"] | DERIVATION_OPTIONAL
    if derived & FROM_DELIVERY:
        inputs |= NEEDS["delivery"]
    if derived & FROM_FLIGHT:
        inputs |= NEEDS["flight"] | set(FLIGHT_INPUTS)
    if derived & FROM_MATERIALS:
        inputs |= NEEDS["materials"]
    return OutputPlan(model_cls.name, requested, frozenset(from_model), frozenset(derived), missing,
                      frozenset(inputs), tuple(kept))


#: the public names of this module (a plugin reaches them through impactlab.model: docs/writing-a-model.md)
__all__ = ["OutputPlan", "require_inputs", "plan_outputs"]
