"""Text and data that come from outside (files, a simulator's replies, stored results): bounded and shown escaped.

Two rules for every reader and every message (issue 35):

- **Nesting is bounded before a parser recurses.** Python's ``json`` and PyYAML's constructors recurse once per
  level: a document nested 100,000 deep (a few hundred kilobytes) ended in ``internal error: RecursionError``.
  :func:`check_json_nesting` counts bracket depth outside strings in one flat pass (no recursion) and refuses
  beyond :data:`MAX_NESTING` levels with the words the YAML readers use (``nests more than 100 levels deep``).
- **Foreign text is shown escaped.** A server's ``Message``, a column header, a club name or a file name may
  hold escape sequences (clear screen, colours), a bell, or CR LF that forge lines of impactlab's own output.
  :func:`shown` (defined in :mod:`impactlab.errors`, whose messages use it) writes every control character as
  its escape (``\\x1b``, ``\\r``, ``\\n``, ``\\x07``) and the Unicode direction overrides as ``\\u202e``;
  :class:`TerminalGuard` applies the same table, line breaks and
  tabs excepted, to everything the command line writes, so a path that forgot :func:`shown` still reaches the
  terminal without a raw control character.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from typing import Any

from impactlab.errors import _TERMINAL, StudyError, has_control, shown, terminal_safe

#: the deepest nesting of any structured input (YAML, JSON files, JSON replies): a study nests about 6 levels,
#: a GSPro message 2, a Uneekor report 4
MAX_NESTING = 100
#: the largest input file impactlab reads (a study, a shot table, a launch-monitor export, a club spec sheet)
#: [bytes]: 64 MiB holds about 200,000 TrackMan rows (100,000 rows are 30.7 MiB, benchmarks/bench_sessions.py),
#: more than any session a launch monitor exports; refused by its size before a byte of it is read
MAX_INPUT_BYTES = 64 * 2**20
MAX_INPUT_WORDS = "64 MiB"


class TerminalGuard:
    """A text stream that writes through :func:`terminal_safe` (carriage returns kept with ``keep_cr``: a
    progress bar's redraw on stderr) and passes every other attribute to the stream it wraps."""

    def __init__(self, stream, keep_cr: bool = False):
        self._stream = stream
        self._table = dict(_TERMINAL)
        if keep_cr:
            self._table.pop(ord("\r"), None)

    @property
    def wrapped(self):
        """The stream written to."""
        return self._stream

    def write(self, text: str) -> int:
        """Write ``text`` with its control characters escaped (line breaks, tabs and a kept CR aside)."""
        self._stream.write(text.translate(self._table) if isinstance(text, str) else text)
        return len(text)

    def writelines(self, lines) -> None:
        """Write each of ``lines`` as :meth:`write` does."""
        for line in lines:
            self.write(line)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


_JSON_SPECIAL = re.compile(r'["\\\[\]{}]')


def json_brackets(text: str, start: int = 0) -> Iterator[tuple[int, str]]:
    """(offset, bracket) of every JSON bracket of ``text`` from ``start`` outside string literals, in order.

    The one flat scan behind the bounds on foreign JSON: a backslash escapes the next character inside a string,
    only quotes, backslashes and brackets are looked at (a regular expression finds them at C speed), and nothing
    recurses, so a document of any depth is scanned in one pass.
    """
    in_string = False
    skip = -1  # the offset of a character escaped by a backslash
    for match in _JSON_SPECIAL.finditer(text, start):
        offset, char = match.start(), match.group()
        if offset == skip:
            continue
        if in_string:
            if char == "\\":
                skip = offset + 1
            elif char == '"':
                in_string = False
        elif char == '"':
            in_string = True
        else:
            yield offset, char


def json_value_end(text: str) -> int:
    """The offset just past the first top-level JSON object or array of ``text`` (which starts with it), found by
    :func:`json_brackets` (no recursion, whatever its depth); -1 while it is incomplete."""
    depth = 0
    for offset, char in json_brackets(text):
        depth += 1 if char in "[{" else -1
        if depth == 0:
            return offset + 1
    return -1


def json_depth_exceeded(text: str, limit: int = MAX_NESTING) -> int:
    """The 1-based line where the JSON ``text`` first opens more than ``limit`` brackets, or 0 if it never does.

    Brackets inside strings do not count (:func:`json_brackets`); the scan is flat, so a document of any depth is
    measured without recursion. Text holding fewer than ``limit`` opening brackets needs no scan (counted at C
    speed).
    """
    if text.count("[") + text.count("{") <= limit:
        return 0
    depth = 0
    for offset, char in json_brackets(text):
        if char in "[{":
            depth += 1
            if depth > limit:
                return text.count("\n", 0, offset) + 1
        else:
            depth = max(depth - 1, 0)
    return 0


def nesting_message(kind: str = "JSON", limit: int = MAX_NESTING) -> str:
    """The one wording of a refusal by nesting depth (the YAML readers' and the JSON readers')."""
    return (f"the {kind} nests more than {limit} levels deep (a study nests about 6, a shot message 2-4); write "
            "the data flatter")


def check_json_nesting(text: str, where: str, limit: int = MAX_NESTING) -> None:
    """Refuse JSON ``text`` nested deeper than ``limit`` before a parser recurses into it.

    Parameters
    ----------
    text : str
        The JSON document (or stream of documents).
    where : str
        The file (or the source) named in the message.
    limit : int
        The deepest nesting accepted.

    Raises
    ------
    StudyError
        ``FILE:LINE: the JSON nests more than 100 levels deep ...`` (exit status 2).
    """
    line = json_depth_exceeded(text, limit)
    if line:
        raise StudyError(f"{shown(where)}:{line}: {nesting_message('JSON', limit)}")


def loads_json(text: str, where: str) -> Any:
    """``json.loads`` of foreign text, its nesting bounded first; a StudyError (not a traceback) for bad JSON."""
    check_json_nesting(text, where)
    try:
        return json.loads(text)
    except ValueError as exc:
        raise StudyError(f"{shown(where)}: not readable as JSON: {exc}") from None


__all__ = ["json_brackets", "json_value_end", "MAX_NESTING", "MAX_INPUT_BYTES", "shown", "terminal_safe", "has_control",
           "TerminalGuard",
           "json_depth_exceeded", "check_json_nesting", "loads_json", "nesting_message"]
