"""Training and held-out parts of a session, and cross-validation folds: never shuffled rows.

Neighbouring shots of one player are not independent, so rows are held out by whole groups where the table has
them (a player, a session, a date: a row's ``source:`` or ``groups=``) and otherwise by contiguous blocks of rows
in file order (:func:`holdout_split`, :func:`folds`). Used by the scorecard (:mod:`.scorecard`) and by
``impactlab fit --cross-validate``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import attrs
import numpy as np

from impactlab.data.sessions.shots import ShotTable
from impactlab.errors import FieldError

#: default fraction of the rows held out
HOLDOUT = 0.3
#: contiguous blocks a table without groups is cut into (a fraction of them held out, spread over the file)
BLOCKS = 10
#: fewest rows a scorecard is made of (a training part and a held-out part of several shots each)
MIN_ROWS = 20


# -- the held-out part -------------------------------------------------------------------------------------------
@attrs.frozen
class Split:
    """Rows of a table for training and rows held out (indices into the table), and how they were chosen.

    ``by`` is ``group`` (whole groups held out: every row of a group is on one side) or ``block`` (contiguous
    blocks of rows); ``held_out`` names the groups or blocks held out."""

    train: np.ndarray = attrs.field(eq=False)
    test: np.ndarray = attrs.field(eq=False)
    by: str
    held_out: tuple[str, ...]

    def describe(self) -> str:
        """One line: how the rows were split and how many are on each side."""
        what = ("whole groups" if self.by == "group" else
                f"contiguous blocks of the usable rows (of {BLOCKS}, in file order)")
        return (f"held out {self.test.size} of {self.train.size + self.test.size} rows by {what}: "
                f"{', '.join(self.held_out)}; baselines fitted on the other {self.train.size} rows")


def _groups_of(table: ShotTable, groups: Sequence | None) -> list | None:
    """The group label of each row, or None when the table has no grouping (one source, no ``groups``)."""
    if groups is not None:
        labels = list(groups)
        if len(labels) != table.size:
            raise FieldError("groups", f"one group label per row ({table.size})", f"{len(labels)} labels")
        return labels
    if len(set(table.sources)) > 1:
        return list(table.sources)
    return None


def _spread(count: int, fraction: float) -> list[int]:
    """Indices of ``round(count * fraction)`` items (at least one, at most count - 1) spread evenly over
    ``range(count)``: item j is chosen when floor((j + 1) f) > floor(j f) (the last one always)."""
    chosen = [j for j in range(count) if math.floor((j + 1) * fraction + 1e-9) > math.floor(j * fraction + 1e-9)]
    if not chosen:
        chosen = [count - 1]
    if len(chosen) == count:
        chosen = chosen[1:]
    return chosen


def holdout_split(table: ShotTable, fraction: float = HOLDOUT, groups: Sequence | None = None,
                  blocks: int = BLOCKS) -> Split:
    """Split ``table``'s rows into a training part and a held-out part, never by shuffled rows.

    Parameters
    ----------
    table : ShotTable
    fraction : float
        The share of the groups (or blocks) held out, 0 < fraction < 1 (default :data:`HOLDOUT`).
    groups : sequence, optional
        A group label per row (a player, a session, a date). Default: the rows' sources where the table names
        several (:attr:`ShotTable.sources`), otherwise none.
    blocks : int
        With no groups, the rows are cut into this many contiguous blocks in file order.

    Returns
    -------
    Split
        With groups, whole groups are held out (spread over their order of first appearance), so no group is
        split between the two parts; without, whole blocks (spread over the file).
    """
    if not 0.0 < fraction < 1.0:
        raise FieldError("--holdout", "a fraction of the rows strictly between 0 and 1", fraction)
    labels = _groups_of(table, groups)
    index = np.arange(table.size)
    if labels is not None:
        order = list(dict.fromkeys(labels))
        if len(order) < 2:
            raise FieldError("groups", "at least two groups to hold one out", f"{len(order)} group")
        held = {order[j] for j in _spread(len(order), fraction)}
        test = np.array([label in held for label in labels])
        return Split(train=index[~test], test=index[test], by="group",
                     held_out=tuple(str(g) for g in order if g in held))
    if table.size < MIN_ROWS:
        raise FieldError("shot table", f"at least {MIN_ROWS} rows for a training part and a held-out part",
                         f"{table.size} rows")
    edges = np.linspace(0, table.size, blocks + 1).round().astype(int)
    chosen = _spread(blocks, fraction)
    test = np.zeros(table.size, bool)
    for j in chosen:
        test[edges[j]:edges[j + 1]] = True
    return Split(train=index[~test], test=index[test], by="block",
                 held_out=tuple(f"{table.labels[edges[j]]} to {table.labels[edges[j + 1] - 1]}" for j in chosen))


def folds(table: ShotTable, k: int = 5, groups: Sequence | None = None,
          by: str = "auto") -> tuple[str, list[np.ndarray]]:
    """K folds of a cross-validation, never shuffled rows: ``(by, folds)``, each fold the row indices it holds out.

    With groups (``groups`` or the table's several sources; ``by="auto"`` or ``"group"``) every group is in
    exactly one fold (groups in their order of first appearance, cut into ``k`` runs of about equal rows; ``k`` is
    at most the number of groups); without groups or with ``by="block"``, ``k`` contiguous blocks of rows."""
    if k < 2:
        raise FieldError("--folds", "at least 2 folds", k)
    labels = None if by == "block" else _groups_of(table, groups)
    if by == "group" and labels is None:
        raise FieldError("--by", "groups among the table's rows (several sources) to fold by group",
                         f"one source in {table.name}")
    if labels is None:
        k = min(k, table.size)
        edges = np.linspace(0, table.size, k + 1).round().astype(int)
        return "block", [np.arange(edges[j], edges[j + 1]) for j in range(k) if edges[j + 1] > edges[j]]
    order = list(dict.fromkeys(labels))
    k = min(k, len(order))
    counts = np.array([labels.count(g) for g in order])
    start = np.concatenate([[0], np.cumsum(counts)[:-1]])
    fold_of = {g: min(int(s * k // len(labels)), k - 1) for g, s in zip(order, start)}
    rows = np.array([fold_of[g] for g in labels])
    return "group", [np.flatnonzero(rows == j) for j in range(k) if (rows == j).any()]
