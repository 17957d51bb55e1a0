"""``--club SPEC.yaml``: a spec sheet that matches no row of the table read changes nothing, and is said (issue 35).

A spec sheet's club answers to the names it lists (``names:``, default its ``name``); a table whose rows name their
clubs otherwise (``Driver`` against a sheet that answers to ``My Driver`` only) ran as if the option were absent.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

from impactlab.errors import StudyError
from impactlab.foreign import shown
from impactlab.scene.catalogue import club_key

#: the most club names of a table listed in the message
SHOWN_CLUBS = 8


def unmatched(paths: Sequence[str], specs: Sequence, added: Sequence[str], clubs: Iterable[str]) -> list[str]:
    """The spec sheets (their paths) whose club no row of ``clubs`` names.

    Parameters
    ----------
    paths : sequence of str
        The ``--club`` files, in the order their specs were registered.
    specs : sequence of (ClubHead, tuple of str)
        What :func:`impactlab.study.club_specs.read_club_spec` read from each.
    added : sequence of str
        The catalogue keys :class:`impactlab.scene.catalogue.user_clubs` gave them (``user_1``...), inside its
        context, where :func:`club_key` maps a row's club name to them.
    clubs : iterable of str
        Each row's club name ('' where a row names none), or its catalogue key (a shot table's).
    """
    names = {club for club in clubs if club}
    keys = {club_key(club) for club in names} | names  # a shot table's rows hold catalogue keys already
    return [path for path, key in zip(paths, added) if key not in keys]


def refuse_unmatched(paths: Sequence[str], specs: Sequence, added: Sequence[str], clubs: Iterable[str],
                     source: str) -> None:
    """Refuse (exit 2) when a ``--club`` sheet matches no row of ``source``: the option would change nothing."""
    clubs = [club for club in clubs if club]
    missing = unmatched(paths, specs, added, clubs)
    if not missing:
        return
    named = sorted(set(clubs))
    table = (", ".join(repr(shown(club)) for club in named[:SHOWN_CLUBS])
             + (f" and {len(named) - SHOWN_CLUBS} more" if len(named) > SHOWN_CLUBS else "")) if named else ""
    parts = []
    for path in missing:
        names = specs[list(paths).index(path)][1]
        parts.append(f"--club {shown(path)} (it answers to {', '.join(repr(shown(name)) for name in names)})")
    rows = f"its rows name {table}" if table else "its rows name no club"
    raise StudyError(f"{'; '.join(parts)}: matches no row of {shown(source)} ({rows}), so it would change nothing; "
                     "list the table's name under the sheet's names:, or leave --club out")
