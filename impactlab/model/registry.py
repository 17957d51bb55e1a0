"""Discovery of model plugins through the ``impactlab.models`` entry-point group.

Built-in models register exactly like third-party ones (see pyproject.toml).
Discovery is lazy and cached; :func:`refresh` rediscovers. A plugin that fails
to import, is not an :class:`~impactlab.model.base.ImpactModel` subclass, has
declarations that do not hold (:func:`impactlab.model.contract.declaration_problems`:
names unknown to the vocabulary, options without defaults, a 3-D model that
cannot see the 3-D contact) or reuses a taken name is skipped with a :class:`~impactlab.errors.PluginWarning`;
it never breaks the registry for the others.
"""

from __future__ import annotations

import functools
import warnings
from importlib import metadata

from impactlab.errors import ModelNotFoundError, PluginWarning
from impactlab.model.base import ImpactModel
from impactlab.model.contract import declaration_problems

ENTRY_POINT_GROUP = "impactlab.models"

def _entry_points():
    return metadata.entry_points(group=ENTRY_POINT_GROUP)


@functools.cache  # discovered once; refresh() clears it (a failed discovery is not cached)
def _discover() -> dict[str, type[ImpactModel]]:
    found: dict[str, type[ImpactModel]] = {}
    origin: dict[str, str] = {}
    for entry_point in sorted(_entry_points(), key=lambda ep: (ep.name, ep.value)):
        where = f"{entry_point.name} = {entry_point.value}"
        try:
            model_cls = entry_point.load()
        except Exception as exc:  # a broken plugin must not take the others down
            warnings.warn(f"impactlab model plugin '{where}' failed to load and is skipped: "
                          f"{type(exc).__name__}: {exc}", PluginWarning, stacklevel=3)
            continue
        if not (isinstance(model_cls, type) and issubclass(model_cls, ImpactModel)):
            warnings.warn(f"impactlab model plugin '{where}' is not an ImpactModel subclass and is skipped",
                          PluginWarning, stacklevel=3)
            continue
        problems = declaration_problems(model_cls)  # checked when it loads, not when it first computes
        if problems:
            warnings.warn(f"impactlab model plugin '{where}' is skipped: its declarations do not hold: "
                          + "; ".join(problems), PluginWarning, stacklevel=3)
            continue
        name = model_cls.name or entry_point.name
        if name != entry_point.name:
            warnings.warn(f"impactlab model plugin '{where}' declares name {model_cls.name!r}, which differs "
                          f"from its entry-point name; it is skipped", PluginWarning, stacklevel=3)
            continue
        if name in found:
            warnings.warn(f"impactlab model plugin '{where}' duplicates the name {name!r} already taken by "
                          f"'{origin[name]}'; the later one is skipped", PluginWarning, stacklevel=3)
            continue
        found[name] = model_cls
        origin[name] = where
    return found


def available() -> dict[str, type[ImpactModel]]:
    """Registered models by name (discovered on first use, then cached)."""
    return dict(_discover())


def refresh() -> dict[str, type[ImpactModel]]:
    """Forget the cache and discover the plugins again."""
    _discover.cache_clear()
    return available()


def get_model(name: str) -> type[ImpactModel]:
    """The model class registered as ``name``; unknown names raise with the choices and the closest match."""
    models = available()
    try:
        return models[name]
    except (KeyError, TypeError):
        raise ModelNotFoundError(str(name), models) from None


#: the public names of this module (a plugin reaches them through impactlab.model: docs/writing-a-model.md)
__all__ = ["ENTRY_POINT_GROUP", "available", "refresh", "get_model"]
