"""A user's club from a spec sheet in YAML (loft, lie, mass, moments, centre of mass), read at file:line.

The sheet is structured by the project's one converter (:func:`impactlab.study.structuring.document_converter`),
as a study's blocks and measured-data documents are: its keys are those of
:data:`impactlab.scene.catalogue.SPEC_KEYS` (an unknown key is refused with the keys a sheet takes); the values,
with their units, are read by :func:`impactlab.scene.catalogue.club_from_spec`.
"""

from __future__ import annotations

import functools
from pathlib import Path
from typing import NewType

import attrs
from cattrs.errors import BaseValidationError, ForbiddenExtraKeysError

from impactlab.errors import FieldError
from impactlab.scene.catalogue import SPEC_KEYS, club_from_spec
from impactlab.scene.plausibility import club_limits, refuse_impossible
from impactlab.scene.clubs import ClubHead
from impactlab.study.structuring import document_converter, field_error
from impactlab.study.yaml_lines import line_of, load_yaml, read_text_file

#: a value as the sheet writes it (its unit and shape are club_from_spec's to read)
Raw = NewType("Raw", object)

#: a club spec sheet: one field per key of SPEC_KEYS
ClubSpecSheet = attrs.make_class("ClubSpecSheet", {
    key: attrs.field(default=None, type=Raw | None,  # type: ignore[arg-type]
                     metadata={"expected": f"the sheet's {key} ({what})"})
    for key, what in SPEC_KEYS.items()}, frozen=True)
ClubSpecSheet.__doc__ = "A club spec sheet as written: one field per key of SPEC_KEYS, its value as the sheet gives it."
ClubSpecSheet._what = "a club spec"  # type: ignore[attr-defined]
ClubSpecSheet._key_of = "a club spec"  # type: ignore[attr-defined]


@functools.cache
def _converter():
    converter = document_converter()
    converter.register_structure_hook(Raw, lambda value, _: value)
    return converter


def read_club_spec(path) -> tuple[ClubHead, tuple[str, ...]]:
    """:func:`club_from_spec` of a YAML file (errors at file:line through the study loader's YAML reader)."""
    path = Path(path)
    document, lines = load_yaml(read_text_file(path, "club spec"), str(path))
    try:
        if isinstance(document, dict):
            _check_keys(document)
        head, names = club_from_spec(document, "club")
        check_golf_ranges(head)
        return head, names
    except FieldError as exc:
        given, where = exc.given, exc.path
        if where in _SPEC_KEY and isinstance(document, dict) and _SPEC_KEY[where] in document:
            # the club head refused a value it holds in SI (a loft of 95 deg shown as 1.6580627893946132, with no
            # line): named by the sheet's key, at its line, as the sheet writes it
            where, given = f"club.{_SPEC_KEY[where]}", document[_SPEC_KEY[where]]
        keys = tuple(where.split(".")[1:])
        if keys and keys[0] in _SPEC_KEY and len(keys) > 1:  # a component refused by its range: the sheet's key
            keys = (_SPEC_KEY[keys[0]], *keys[1:])
            where = "club." + ".".join(keys)
        line = line_of(lines, keys) if keys else None
        raise FieldError(where, exc.expected, given, exc.choices, file=str(path), line=line) from None


def _check_keys(document: dict) -> None:
    """The sheet structured by the converter: FieldError at ``club.KEY`` for a key no sheet takes."""
    try:
        _converter().structure(document, ClubSpecSheet)
    except (BaseValidationError, ForbiddenExtraKeysError) as exc:
        raise field_error(exc, document, "club", (), ClubSpecSheet, None) from None


#: a club head's attribute -> the spec sheet's key that sets it
_SPEC_KEY = {"loft": "loft", "lie": "lie", "mass": "mass", "inertia": "moi", "center_of_mass": "cg",
             "bulge_radius": "bulge", "roll_radius": "roll", "restitution_gain": "restitution_gain"}


#: the nearest a head's mass can lie, on the whole, to an axis through its centre of mass [m]: a club head's mass
#: is spread over a body some centimetres across, never within a few millimetres of one axis
MIN_GYRATION_RADIUS = 0.005
#: the farthest [m]: the Rules' longest head, a putter's 7 in (178 mm) heel to toe (R&A/USGA Equipment Rules,
#: Part 2, 4b; rules text): no part of a head, let alone its whole mass, lies farther from its centre of mass
MAX_GYRATION_RADIUS = 0.178


def check_golf_ranges(head) -> None:
    """Refuse a spec sheet's values no golf club head has (FieldError at ``club.<key>``, with the range and why).

    The mass, the centre of mass and the face's curvature by the limits a golf scene applies
    (:func:`impactlab.scene.plausibility.club_limits`); each principal moment of inertia (``moi.toe``, ``up``,
    ``target``) between the head's mass at :data:`MIN_GYRATION_RADIUS` and at :data:`MAX_GYRATION_RADIUS` from the
    axis. A moment typed in kg m^2 where g cm^2 was meant is 10^7 times too large and is refused by that range; the
    range is shown in g cm^2, the unit spec sheets use (drivers 4000-5900 g cm^2 about the vertical axis; the
    Rules' limit for woods is 5900 g cm^2 about the vertical axis, USGA Equipment Rules).
    """
    if head.is_sphere:
        return
    for limit, value in club_limits(head):
        refuse_impossible(limit, value)  # the scene's one rule and wording
    g_cm2 = 1e7  # g cm^2 per kg m^2
    low = head.mass * MIN_GYRATION_RADIUS ** 2 * g_cm2
    high = head.mass * MAX_GYRATION_RADIUS ** 2 * g_cm2
    for name, value in head.inertia_components().items():
        if "_" in name:  # products of inertia may be zero or negative
            continue
        if not low <= value * g_cm2 <= high:
            raise FieldError(f"club.inertia.{name}", f"a moment of inertia between {low:.6g} and {high:.6g} g cm^2 for "
                             f"this {head.mass * 1e3:.0f} g head (its mass at 5 to 178 mm from the axis: no head is "
                             "smaller, and the Rules' longest, a putter's, is 178 mm heel to toe; drivers have "
                             "4000-5900 g cm^2)", f"{value * g_cm2:.6g} g cm^2 ({value:.6g} kg m^2)")
