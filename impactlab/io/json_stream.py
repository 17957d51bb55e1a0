"""JSON values written back to back with no framing, split by :meth:`json.JSONDecoder.raw_decode`: one splitter
for a whole text (a launch monitor's JSON export, :mod:`impactlab.data.sessions.json_records`) and for a byte
stream read piece by piece (GSPro Connect's replies, :mod:`impactlab.io.gspro_connect`).

The standard library's decoder finds where each value ends; nothing here counts braces. A stream read in pieces
needs one thing more: telling a value cut short by the end of what has arrived (wait for more) from one that no
continuation can make valid (refuse now). :func:`cut_short` says which, from the decoder's error.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterator
from typing import Any

from impactlab.foreign import MAX_NESTING, json_depth_exceeded, json_value_end

#: what may stand between values: blanks, and a byte-order mark at the start of a file
BLANKS = "\ufeff \t\r\n"
_DECODER = json.JSONDecoder()
#: the prefix of a number, a literal or a \u escape, cut by the end of the text: the decoder stops at its start
#: (or, for a number, after its integer part), and more text can complete it
_CUT_TOKEN = re.compile(r"-?\d*(\.\d*)?([eE][-+]?\d*)?|-?I(n(f(i(n(i(ty?)?)?)?)?)?)?|N(aN?)?|t(r(ue?)?)?"
                        r"|f(a(l(se?)?)?)?|n(u(ll?)?)?|u[0-9a-fA-F]{0,4}")


def json_values(text: str, start: int = 0) -> Iterator[tuple[int, Any, int]]:
    """Each top-level JSON value of a text of values written back to back (blanks between them skipped).

    Parameters
    ----------
    text : str
        The values, compact or indented, with or without line ends between them.
    start : int
        Where to start reading.

    Yields
    ------
    tuple of (int, object, int)
        The offset where the value starts, the value, and the offset just after it.

    Raises
    ------
    json.JSONDecodeError
        Where the text stops being JSON (its ``lineno``, ``colno`` and ``pos`` locate it).
    """
    position = start
    while True:
        while position < len(text) and text[position] in BLANKS:
            position += 1
        if position >= len(text):
            return
        value, end = _DECODER.raw_decode(text, position)
        yield position, value, end
        position = end


def cut_short(text: str, error: json.JSONDecodeError) -> bool:
    """Whether the decoder's ``error`` on ``text`` is only the text ending early (more may make it valid).

    Parameters
    ----------
    text : str
        What was decoded.
    error : json.JSONDecodeError
        What :func:`json_values` (or ``raw_decode``) raised on it.

    Returns
    -------
    bool
        True when the text ran out (inside a string, a number, a literal or between tokens); False when a
        character that no continuation can make valid stopped the decoder.
    """
    if error.pos >= len(text) or error.msg.startswith("Unterminated string"):
        return True
    return _CUT_TOKEN.fullmatch(text, error.pos) is not None


class NotJsonError(ValueError):
    """Bytes in a stream that are not a JSON object; ``text`` holds them (shortened)."""

    def __init__(self, data: bytes | bytearray, why: str):
        self.text = _show(data)
        super().__init__(f"{why}: {self.text}")


def _show(data: bytes | bytearray, limit: int = 80) -> str:
    text = repr(bytes(data[:limit]))
    return text + (f" ... ({len(data)} bytes)" if len(data) > limit else "")


class JsonObjectStream:
    """Split a byte stream into the JSON objects written back to back in it, however it was cut into reads.

    Bytes go in as they arrive (:meth:`feed`); each complete top-level object comes out as its bytes, in order.
    Blanks between objects are skipped, and so is ``skip`` (a greeting the sender may write between objects).
    Anything else outside an object, an object that is not valid JSON, and an object longer than ``limit`` bytes
    raise :class:`NotJsonError`.

    Parameters
    ----------
    limit : int
        The longest object taken, in bytes.
    skip : bytes
        Text tolerated between objects (empty: none).
    """

    def __init__(self, limit: int, skip: bytes = b""):
        self.limit = limit
        self.skip = skip
        self._buffer = bytearray()

    @property
    def pending(self) -> bool:
        """Whether part of an object (or of the skipped text) has arrived and waits for the rest."""
        return bool(self._buffer)

    def feed(self, data: bytes) -> list[bytes]:
        """Take the next bytes of the stream; return the objects they complete (possibly none)."""
        self._buffer += data
        found = []
        while (item := self._next()) is not None:
            found.append(item)
        return found

    def _next(self) -> bytes | None:
        """The next complete object taken off the buffer, or None (the buffer empty or an object incomplete)."""
        buffer = self._buffer
        while True:
            blank = len(buffer) - len(buffer.lstrip(b" \t\r\n"))
            del buffer[:blank]
            if self.skip and buffer.startswith(self.skip):
                del buffer[:len(self.skip)]
                continue
            break
        if not buffer or (self.skip and self.skip.startswith(buffer)):
            return None
        if buffer[:1] != b"{":
            raise NotJsonError(buffer, "text that is not a JSON object")
        try:
            text = buffer.decode("utf-8")
        except UnicodeDecodeError as exc:  # a character cut by the read: decode up to it, wait for its rest
            if exc.reason != "unexpected end of data":
                raise NotJsonError(buffer, "a reply that is not JSON") from None
            text = buffer[:exc.start].decode("utf-8")
        # json recurses once per level: a reply 30,000 deep (under the size limit) was a RecursionError. The depth is
        # measured flat; such an object is read to its end (found flat too) and refused whole, so that the stream
        # stays in step and the sender is not cut off mid-write
        if json_depth_exceeded(text):  # the buffer may hold a good object and, after it, the deep one
            end = json_value_end(text)
            if end < 0:
                if len(buffer) > self.limit:
                    raise NotJsonError(buffer, f"an object longer than {self.limit} bytes")
                return None
            if json_depth_exceeded(text[:end]):  # the first object itself is the deep one
                size = len(text[:end].encode("utf-8"))
                refused = bytes(buffer[:size])
                del buffer[:size]
                raise NotJsonError(refused, f"a reply whose JSON nests more than {MAX_NESTING} levels deep")
        try:
            _, end = _DECODER.raw_decode(text)
        except json.JSONDecodeError as exc:
            if not cut_short(text, exc):
                raise NotJsonError(buffer, "a reply that is not JSON") from None
            if len(buffer) > self.limit:
                raise NotJsonError(buffer, f"an object longer than {self.limit} bytes") from None
            return None
        size = len(text[:end].encode("utf-8"))
        if size > self.limit:
            raise NotJsonError(buffer[:size], f"an object longer than {self.limit} bytes")
        item = bytes(buffer[:size])
        del buffer[:size]
        return item


__all__ = ["BLANKS", "JsonObjectStream", "NotJsonError", "cut_short", "json_values"]
