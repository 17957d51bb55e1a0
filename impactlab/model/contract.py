"""What the framework checks of a model's declarations: when the model loads, and when it is planned on a scene.

Two checks, both on declarations alone (no model is run):

* :func:`declaration_problems`, when a plugin loads (:mod:`impactlab.model.registry`): the names it declares
  exist in the vocabulary, its options are a frozen attrs class with defaults, and a model that claims 3-D
  contacts (``lateral_impulse`` in ``provides``) can see the 3-D contact (below). A plugin with a problem is
  skipped with a :class:`~impactlab.errors.PluginWarning` naming it, never half-registered.
* :func:`require_contact_inputs`, when a model is planned on a scene (:func:`impactlab.model.planning.plan_outputs`):
  on a 3-D scene (a golf delivery, a club head's body, a strike point, a curved face) the model must see every
  input of the contact state the scene gives, :data:`impactlab.physics.contact.CONTACT_STATE_INPUTS`. A hook
  receives only what its model declares (rule 3 of :class:`~impactlab.model.base.ImpactModel`), so a model that
  forgot, say, the strike point would pose a centre strike while the framework derives the launch from the
  off-centre one: a wrong answer with no warning (issue 34 measured spin axes of -15.7/0/+15.7 deg for heel, centre
  and toe strikes that are +4.65/1.09/-2.42 deg). Such a model is refused on 3-D scenes, naming the inputs.

A model sees the contact in one of two ways: it declares those inputs (in ``requires`` or ``optional_inputs``), or
it sets ``takes_contact_state = True``, reads the geometry only through ``inputs.contact_state()``, and the
framework gives it the state of the whole scene, whatever it declared.
"""

from __future__ import annotations

import keyword
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import attrs

from impactlab.errors import ModelInputError
from impactlab.physics.contact import CONTACT_STATE_INPUTS
from impactlab.vocabulary import INPUTS, OUTPUTS

if TYPE_CHECKING:  # model.base imports this module
    from impactlab.model.base import ImpactModel

#: contact-state inputs of an impact on one line (a plate experiment: ball, speed, angle, spin, a striking mass)
ONE_LINE_INPUTS = frozenset({"speed", "angle", "spin", "ball_mass", "ball_radius", "ball_inertia_factor",
                             "club_mass", "club_spin"})
#: the inputs whose presence makes a scene 3-D: a delivery's orientation, the head's body, the strike, the face shape
THREE_D_INPUTS = CONTACT_STATE_INPUTS - ONE_LINE_INPUTS


def sees_contact(model_cls: type[ImpactModel]) -> bool:
    """Whether the model's hook sees the whole contact state (it takes the framework's, or declares every input)."""
    return bool(getattr(model_cls, "takes_contact_state", False)) or not unseen_contact_inputs(model_cls,
                                                                                              CONTACT_STATE_INPUTS)


def unseen_contact_inputs(model_cls: type[ImpactModel], given: Iterable[str]) -> list[str]:
    """The contact-state inputs among ``given`` that the model's hook would not see (sorted; empty when it takes
    the framework's contact state)."""
    if getattr(model_cls, "takes_contact_state", False):
        return []
    declared = set(model_cls.requires) | set(model_cls.optional_inputs)
    return sorted((set(given) & CONTACT_STATE_INPUTS) - declared)


def is_three_d(given: Iterable[str]) -> bool:
    """Whether inputs of these names make a 3-D scene (any input of :data:`THREE_D_INPUTS`)."""
    return bool(set(given) & THREE_D_INPUTS)


def _described(names: Iterable[str]) -> str:
    return ", ".join(f"{name} ({INPUTS[name].path})" for name in names)


def require_contact_inputs(model_cls: type[ImpactModel], given: Iterable[str], who: str | None = None) -> None:
    """Refuse a model on a 3-D scene whose contact its hook would not see in full (ModelInputError, exit 2).

    Parameters
    ----------
    model_cls : type of ImpactModel
    given : iterable of str
        The names of the scene's inputs.
    who : str, optional
        How to name the model in the message (default: ``model 'NAME'``).

    Raises
    ------
    ModelInputError
        Naming each input the scene gives and the model does not declare, and the two ways to fix it.
    """
    given = set(given)
    if not is_three_d(given):
        return
    missing = unseen_contact_inputs(model_cls, given)
    if missing:
        raise ModelInputError(
            f"{who or f'model {model_cls.name!r}'} does not declare {_described(missing)}, which this 3-D scene "
            "gives and the contact state is computed from: its hook would pose another contact than the one the "
            "framework derives the launch from. Declare them (optional_inputs |= "
            "impactlab.physics.contact.CONTACT_STATE_INPUTS) or set takes_contact_state = True and read the "
            "geometry through inputs.contact_state() (docs/writing-a-model.md)")


def declaration_problems(model_cls: type[ImpactModel]) -> list[str]:
    """What is wrong with a model class's declarations, checked against the vocabulary when the plugin loads.

    Returns
    -------
    list of str
        One sentence per problem, empty when the declarations hold: ``name`` an identifier; ``requires``,
        ``optional_inputs`` and ``provides`` frozensets of names the vocabulary knows (``provides`` not empty);
        no input both required and optional; ``not_provided`` keys outputs; ``Options`` an attrs class whose
        every field has a default; ``takes_contact_state`` True or False; a model that provides
        ``lateral_impulse`` (3-D contacts) sees the whole contact state.
    """
    problems = []
    name = getattr(model_cls, "name", "")
    if not (isinstance(name, str) and name.isidentifier() and not keyword.iskeyword(name)):
        problems.append(f"name must be a Python identifier, got {name!r}")
    for attribute, vocabulary, kind in (("requires", INPUTS, "input"), ("optional_inputs", INPUTS, "input"),
                                        ("provides", OUTPUTS, "output")):
        declared: Any = getattr(model_cls, attribute, None)
        if not isinstance(declared, frozenset):
            problems.append(f"{attribute} must be a frozenset of {kind} names, got {type(declared).__name__}")
            continue
        unknown = sorted(str(item) for item in declared if item not in vocabulary)
        if unknown:
            problems.append(f"{attribute} names {', '.join(unknown)}, unknown to the vocabulary's {kind}s "
                            f"(impactlab.vocabulary.{'INPUTS' if kind == 'input' else 'OUTPUTS'})")
    if not problems:
        if not model_cls.provides:
            problems.append("provides is empty: a model gives at least one output")
        both = sorted(model_cls.requires & model_cls.optional_inputs)
        if both:
            problems.append(f"{', '.join(both)} both required and optional")
    unknown = sorted(str(key) for key in getattr(model_cls, "not_provided", {}) if key not in OUTPUTS)
    if unknown:
        problems.append(f"not_provided names {', '.join(unknown)}, unknown to the vocabulary's outputs")
    options = getattr(model_cls, "Options", None)
    if not (isinstance(options, type) and attrs.has(options)):
        problems.append("Options must be an attrs class")
    elif any(field.default is attrs.NOTHING for field in attrs.fields(options)):
        problems.append("every field of Options needs a default")
    if not isinstance(getattr(model_cls, "takes_contact_state", False), bool):
        problems.append("takes_contact_state must be True or False")
    elif not problems and "lateral_impulse" in model_cls.provides and not sees_contact(model_cls):
        missing = unseen_contact_inputs(model_cls, CONTACT_STATE_INPUTS)
        problems.append(f"it provides lateral_impulse (3-D contacts) but does not declare {', '.join(missing)}: its "
                        "hook would pose a centre strike on a fixed-orientation face whatever the scene; declare "
                        "impactlab.physics.contact.CONTACT_STATE_INPUTS or set takes_contact_state = True")
    return problems
