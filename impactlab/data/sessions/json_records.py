"""JSON shot records as table rows: a launch monitor's JSON read through the same column maps as its CSV.

Two JSON shapes carry shots: a stream of messages, one shot (or heartbeat) each, with no delimiter between them
(GSPro Open Connect v1: objects written back to back, with or without line ends, compact or indented), and a
document whose top-level objects hold a list of shot objects (Uneekor's Power U report: sessions, each with its
``shots``). :func:`json_rows` turns either into the rows of a table: a header of keys (nested objects dotted,
``BallData.Speed``; a session's own fields prefixed ``../``, ``../club_name``; keys matched case-insensitively, as
clients spell ``BackSpin`` and ``Backspin``) and one row per shot, each with the file line its object starts on, so
the reader's column maps, units, sentinels and flags apply unchanged.
"""

from __future__ import annotations

import bisect
import json
import re
from typing import Any

from impactlab.errors import StudyError
from impactlab.foreign import check_json_nesting, json_brackets
from impactlab.io.json_stream import json_values


#: file suffixes read as JSON shot records by ``validate --dataset`` and ``fit`` (``shots`` reads any file)
JSON_SESSIONS = (".json", ".jsonl", ".session")


def looks_like_json(text: str) -> bool:
    """True when the text starts (after a byte-order mark and blanks) with ``{`` or ``[``."""
    return text.lstrip("\ufeff \t\r\n")[:1] in ("{", "[")


def _values(text: str, file: str) -> list[tuple[int, Any]]:
    """(start offset, value) of every top-level JSON value of a stream (objects back to back)."""
    check_json_nesting(text, file)  # json recurses once per level: bounded before it does (impactlab.foreign)
    try:
        return [(start, value) for start, value, _ in json_values(text)]
    except json.JSONDecodeError as exc:
        raise StudyError(f"{file}:{exc.lineno}: not readable as JSON: {exc.msg} (column {exc.colno})") from None


def _object_starts(text: str, start: int) -> list[tuple[int, int, str]]:
    """(offset, depth, parent bracket) of every ``{`` of the JSON value at ``start`` (string-aware)."""
    out = []
    stack: list[str] = []
    for offset, char in json_brackets(text, start):  # outside strings (impactlab.foreign: one flat scan)
        if char in "{[":
            if char == "{":
                out.append((offset, len(stack) + 1, stack[-1] if stack else ""))
            stack.append(char)
        else:
            stack.pop()
            if not stack:
                return out
    return out


def _cell(value) -> str:
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value
    return json.dumps(value)


def _flatten(record: dict, prefix: str = "") -> dict[str, str]:
    out: dict[str, str] = {}
    for key, value in record.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            out.update(_flatten(value, f"{name}."))
        else:
            out[name] = _cell(value)
    return out


def _shot_lists(item: dict) -> list[str]:
    return [key for key, value in item.items()
            if isinstance(value, list) and value and all(isinstance(entry, dict) for entry in value)]


def json_rows(text: str, file: str) -> tuple[list[list[str]], list[int], list[str]]:
    """The shot records of a JSON text as table rows (see the module docstring).

    Parameters
    ----------
    text : str
        The file's text: JSON values back to back (a message stream), or one value.
    file : str
        The file's name, for messages.

    Returns
    -------
    rows : list of list of str
        Row 0 is the header (dotted keys, a session's keys prefixed ``../``); then one row per shot, every cell a
        string as written (``true``/``false`` for booleans, empty for null or an absent key).
    lines : list of int
        The file line each row's object starts on (1 for the header); the objects' order numbers instead when
        several start on one line (said in the notes).
    notes : list of str
        What the reader inferred, for the report.

    Raises
    ------
    StudyError
        At the line of a JSON syntax error; when a top-level value is neither an object nor a list of objects; when
        an object holds two lists of objects (which of them holds the shots is not guessed); when no object has a key.
    """
    records: list[dict[str, str]] = []
    lines: list[int] = []
    # the offsets of the line breaks, once: counting them from the start for every shot took a 20,000-message
    # capture 17 s (quadratic in the file)
    breaks = [match.start() for match in re.finditer("\n", text)]
    nested = 0
    for start, value in _values(text, file):
        items = value if isinstance(value, list) else [value]
        if not all(isinstance(item, dict) for item in items):
            got = type(next(item for item in items if not isinstance(item, dict))).__name__
            raise StudyError(f"{file}:{text.count(chr(10), 0, start) + 1}: expected JSON objects (shots, or "
                             f"sessions holding a list of shots), got a {got}")
        found = []
        for item in items:
            lists = _shot_lists(item)
            if len(lists) > 1:
                raise StudyError(f"{file}: an object holds several lists of objects ({', '.join(lists)}): which of "
                                 f"them holds the shots is not guessed")
            if lists:
                parent = _flatten({key: val for key, val in item.items() if key != lists[0]}, "../")
                found += [{**parent, **_flatten(shot)} for shot in item[lists[0]]]
                nested += 1
            else:
                found.append(_flatten(item))
        # the file line each shot object starts on: shots are the objects that are elements of a list, at the
        # depth the shape puts them (a stream's own objects: their start)
        if isinstance(value, dict) and not _shot_lists(value):
            starts = [start]
        else:
            depth = (1 if isinstance(value, dict) else 2) + (2 if any(_shot_lists(item) for item in items) else 0)
            starts = [offset for offset, level, parent in _object_starts(text, start)
                      if level == depth and parent == "["]
        if len(starts) != len(found):
            raise StudyError(f"{file}: shots nested at different depths; expected one list of shot objects")
        records += found
        lines += [bisect.bisect_left(breaks, offset) + 1 for offset in starts]  # line = line breaks before it + 1
    if not records:
        raise StudyError(f"{file}: no JSON object in the file")
    # keys are matched case-insensitively (clients spell BackSpin/Backspin, APIversion/APIVersion): the first
    # spelling names the column
    spelling: dict[str, str] = {}
    for record in records:
        for key in record:
            spelling.setdefault(key.lower(), key)
    names = list(spelling.values())
    if not names:  # objects without a single key: the CSV reader would call the file empty, which it is not
        raise StudyError(f"{file}: {len(records)} JSON object(s), none with a key: no shot fields to read")
    folded = [{key.lower(): value for key, value in record.items()} for record in records]
    rows = [names] + [[record.get(name.lower(), "") for name in names] for record in folded]
    notes = [f"JSON: {len(records)} object(s)" + (f" in {nested} session(s)" if nested else "")
             + "; keys of nested objects dotted (BallData.Speed), a session's own keys prefixed '../'"]
    if len(set(lines)) < len(lines):  # messages back to back on one line: number them instead
        lines = list(range(1, len(lines) + 1))
        notes.append("several objects start on one line: rows are numbered by object (1 = the first) where this "
                     "report says line")
    return rows, [1] + lines, notes
