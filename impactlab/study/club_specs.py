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
        keys = tuple(exc.path.split(".")[1:])
        line = line_of(lines, keys) if keys else None
        raise FieldError(exc.path, exc.expected, exc.given, exc.choices, file=str(path), line=line) from None
