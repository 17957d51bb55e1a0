"""Exceptions and warnings that carry a message fit to show a user.

Every error impactlab raises for bad input derives from :class:`ImpactLabError`.
Its ``str`` is the whole message the CLI prints: where (file, line, field
path), what was expected, what was given and, where there is a finite set,
the choices.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class ImpactLabError(Exception):
    """Base class of every user-facing impactlab error.

    ``exit_code`` is the status the command line ends with: 2 for bad input
    (the default), 3 for a fault of the environment (see :class:`EnvironmentFault`).
    """

    exit_code = 2


class EnvironmentFault(ImpactLabError):
    """The input is fine but the machine is not: a folder is unwritable, the disk is full, a lock is held."""

    exit_code = 3


class ResourceLimitError(ImpactLabError):
    """A study (or file) would need more cases, memory or nodes than the configured limit allows."""


class FieldError(ImpactLabError, ValueError):
    """A value that does not fit its field.

    Parameters
    ----------
    path : str
        Dotted path of the field (``ball.radius``); may be extended by callers
        as the error travels outwards (see :meth:`at`).
    expected : str
        What the field accepts, in words.
    given : object
        What was given (shown with ``repr`` unless already a string).
    choices : iterable of str, optional
        The allowed values, listed in the message; the closest one to
        ``given`` is suggested.
    """

    def __init__(self, path: str, expected: str, given: object = None, choices: Iterable[str] | None = None,
                 file: str | None = None, line: int | None = None):
        self.path = path
        # an expectation worded by its field (units.unit_missing: an air pressure's example in hPa, a modulus' in
        # MPa) is worded again when the path is known
        self.expected = expected.for_path(path) if hasattr(expected, "for_path") else expected
        self.given = given
        self.choices = tuple(choices) if choices is not None else None
        self.file = file
        self.line = line
        super().__init__(self._message())

    def _message(self) -> str:
        where = ""
        if self.file:  # a file's name, a key and a value read from it: foreign text, shown escaped
            where = f"{shown(self.file)}:{self.line}: " if self.line else f"{shown(self.file)}: "
        given = shown(self.given) if isinstance(self.given, str) else shown(repr(self.given))
        text = f"{where}{shown(self.path or '<top>')}: expected {self.expected}, got {given}"
        if self.choices:
            text += f". Choices: {', '.join(shown(choice) for choice in self.choices)}"
            close = closest(str(self.given), self.choices)
            if close:
                text += f" (did you mean {close!r}?)"
        return text

    def at(self, prefix: str | None = None, file: str | None = None, line: int | None = None) -> FieldError:
        """Return a copy located under ``prefix`` and in ``file`` at ``line``."""
        path = self.path
        if prefix:
            path = f"{prefix}.{path}" if path else prefix
        return FieldError(path, self.expected, self.given, self.choices,
                          file=file or self.file, line=line or self.line)

    def __reduce__(self):
        return (FieldError, (self.path, self.expected, self.given, self.choices, self.file, self.line))


class StudyError(ImpactLabError):
    """A study that cannot be read or run (file missing, YAML syntax...)."""


class ModelNotFoundError(ImpactLabError, KeyError):
    """An unknown model name."""

    def __init__(self, name: str, available: Iterable[str]):
        self.name = name
        self.available = tuple(sorted(available))
        text = f"unknown model {name!r}. Choices: {', '.join(self.available) or '(none registered)'}"
        close = closest(name, self.available)
        if close:
            text += f" (did you mean {close!r}?)"
        self.message = text
        super().__init__(text)

    def __str__(self) -> str:  # KeyError would quote the message
        return self.message


class ModelInputError(ImpactLabError):
    """A model was asked to run without an input it declares as required."""


class ModelContractError(ImpactLabError):
    """A model's hook broke the plugin contract (wrong keys, shapes...)."""


class PlausibilityWarning(UserWarning):
    """A result computed as asked that no real shot would produce (e.g. sent to a golf simulator)."""


class PluginWarning(UserWarning):
    """A plugin could not be loaded or clashes with another; it was skipped."""


def closest(word: str, choices: Iterable[str]) -> str | None:
    """The choice closest to ``word``, or None when nothing is close."""
    match = difflib.get_close_matches(word, list(choices), n=1, cutoff=0.6)
    return match[0] if match else None


# ---- foreign text shown escaped (issue 35; impactlab.foreign gathers the rules for outside input) ----

def _escape_table(keep: str = "") -> dict[int, str]:
    table: dict[int, str] = {}
    for code in list(range(0x00, 0x20)) + [0x7F] + list(range(0x80, 0xA0)):
        char = chr(code)
        if char in keep:
            continue
        table[code] = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}.get(char, f"\\x{code:02x}")
    # characters that reorder or hide the text around them (bidirectional overrides and isolates, the
    # zero-width marks): a file name can read differently from what it is (Trojan Source, CVE-2021-42574)
    for code in (0x061C, 0x200B, 0x200E, 0x200F, *range(0x202A, 0x202F), *range(0x2066, 0x206A), 0xFEFF):
        table[code] = f"\\u{code:04x}"
    table[0x2028] = "\\u2028"
    table[0x2029] = "\\u2029"
    return table


_SHOWN = _escape_table()
_TERMINAL = _escape_table(keep="\n\t")


def shown(text: object) -> str:
    """``text`` (or ``str(text)``) fit to put in a message: every control character escaped.

    Parameters
    ----------
    text : object
        Text from outside impactlab (a reply, a header, a club or file name).

    Returns
    -------
    str
        The text with C0/C1 control characters written as ``\\x1b``, ``\\r``, ``\\n``, ``\\t``, ``\\x07``..., and the
        Unicode direction and zero-width marks as ``\\u202e``...; printable text is unchanged.

    Examples
    --------
    >>> shown("Hi\\x1b[2J\\r\\nimpactlab: error: forged\\x07")
    'Hi\\\\x1b[2J\\\\r\\\\nimpactlab: error: forged\\\\x07'
    """
    return str(text).translate(_SHOWN)


def terminal_safe(text: str) -> str:
    """:func:`shown` with line breaks and tabs kept: for whole messages and tables impactlab writes."""
    return text.translate(_TERMINAL)


def has_control(text: str) -> bool:
    """Whether ``text`` holds a character :func:`shown` escapes."""
    return text.translate(_SHOWN) != text


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["ImpactLabError", "EnvironmentFault", "ResourceLimitError", "FieldError", "StudyError",
           "ModelNotFoundError", "ModelInputError", "ModelContractError", "PlausibilityWarning", "PluginWarning",
           "closest"]
