"""What a command says of the rows it did not use: one line per reason with its count (the lines on request), and
one line per column and reason of the unusual values it used."""

from __future__ import annotations

import contextlib
from collections import Counter
from contextvars import ContextVar


def _by_reason(skipped) -> tuple[Counter, dict]:
    """Rows per reason (a row's ``; ``-joined reasons each counted) and each reason's lines, in file order."""
    counts: Counter = Counter()
    lines: dict = {}
    for line, why in skipped:
        for reason in dict.fromkeys(why.split("; ")):
            counts[reason] += 1
            lines.setdefault(reason, []).append(int(line))
    return counts, lines


def reason_counts(skipped, most: int = 10, file: str = "") -> str:
    """The reasons of ``skipped`` ((line, reason) pairs) on one line: ``FILE:L: reason (N row(s)); ...`` (L: the
    reason's first line)."""
    counts, lines = _by_reason(skipped)
    text = "; ".join(f"{file}:{lines[reason][0]}: {reason} ({count} row(s))"
                     for reason, count in counts.most_common(most))
    return text + (f"; and {len(counts) - most} other reason(s)" if len(counts) > most else "")


def skip_lines(skipped, total: int, unusual=(), show_rows: bool = False, indent: str = "  ",
               used: str = "used") -> list[str]:
    """Lines saying how many of ``total`` rows were skipped and why, at most one per reason (``show_rows``: with
    every line number), then the unusual values ((reason, lines) pairs) kept, one line per column and reason.

    Parameters
    ----------
    skipped : sequence of (int, str)
        File line and reasons (``; ``-joined) of each row not used.
    total : int
        Rows read.
    unusual : sequence of (str, sequence of int)
        Reason and lines of the values counted as unusual.
    show_rows : bool
        List every line of each reason (else the first).
    """
    out = []
    if skipped:
        counts, lines = _by_reason(skipped)
        out.append(f"{indent}{len(skipped)} of {total} row(s) not {used}" + (
            " (a row may have several reasons):" if len(counts) > 1 else ":"))
        for reason, count in counts.most_common():
            where = (f"line(s) {', '.join(map(str, lines[reason]))}" if show_rows
                     else f"first line {lines[reason][0]}")
            out.append(f"{indent}  {reason}: {count} row(s) ({where})")
        if not show_rows:
            out.append(f"{indent}  (--show-rows lists every line)")
    for reason, rows in unusual:
        where = f"line(s) {', '.join(map(str, rows))}" if show_rows else f"first line {rows[0]}"
        out.append(f"{indent}unusual, used as given: {reason}: {len(rows)} row(s) ({where})")
    return out


_SHOW_ROWS: ContextVar[bool] = ContextVar("show_rows", default=False)


def show_rows_setting() -> bool:
    """Whether the running command lists every line of each reason (``--show-rows``)."""
    return _SHOW_ROWS.get()


@contextlib.contextmanager
def showing_rows(show: bool):
    """Within the block, summaries list every line of each reason (a command's ``--show-rows``)."""
    token = _SHOW_ROWS.set(bool(show))
    try:
        yield
    finally:
        _SHOW_ROWS.reset(token)
