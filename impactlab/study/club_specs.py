"""A user's club from a spec sheet in YAML (loft, lie, mass, moments, centre of mass), read at file:line."""

from __future__ import annotations

from pathlib import Path

from impactlab.errors import FieldError
from impactlab.scene.clubs import ClubHead
from impactlab.scene.catalogue import club_from_spec
from impactlab.study.yaml_lines import line_of, load_yaml, read_text_file


def read_club_spec(path) -> tuple[ClubHead, tuple[str, ...]]:
    """:func:`club_from_spec` of a YAML file (errors at file:line through the study loader's YAML reader)."""
    path = Path(path)
    document, lines = load_yaml(read_text_file(path, "club spec"), str(path))
    try:
        return club_from_spec(document, "club")
    except FieldError as exc:
        given, where = exc.given, exc.path
        if where in _SPEC_KEY and isinstance(document, dict) and _SPEC_KEY[where] in document:
            # the club head refused a value it holds in SI (a loft of 95 deg shown as 1.6580627893946132, with no
            # line): named by the sheet's key, at its line, as the sheet writes it
            where, given = f"club.{_SPEC_KEY[where]}", document[_SPEC_KEY[where]]
        keys = tuple(where.split(".")[1:])
        line = line_of(lines, keys) if keys else None
        raise FieldError(where, exc.expected, given, exc.choices, file=str(path), line=line) from None


#: a club head's attribute -> the spec sheet's key that sets it
_SPEC_KEY = {"loft": "loft", "lie": "lie", "mass": "mass", "inertia": "moi", "center_of_mass": "cg",
             "bulge_radius": "bulge", "roll_radius": "roll", "restitution_gain": "restitution_gain"}
