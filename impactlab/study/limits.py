"""Resource limits: how big a study (or a YAML document) may be, estimated before anything is allocated.

A study is refused, with the estimate and the way to raise the limit, when

* its sweep has more than ``max_cases`` cases (checked while the study is
  read, before a range of values is even generated), or
* its estimated memory exceeds ``max_memory`` (checked when it is planned,
  before its inputs are built): inputs, results and their copies while they
  are assembled and written, force histories, and the kernel grids of expert
  resolution options (``springs``, ``rings``, ``steps``), whose size grows
  with springs x steps.

A YAML document may not expand (through aliases) to more than
``max_yaml_nodes`` nodes.

Defaults are below; override them with the environment variables
``IMPACTLAB_MAX_CASES``, ``IMPACTLAB_MAX_MEMORY`` (e.g. ``16GiB``) and
``IMPACTLAB_MAX_YAML_NODES``, or ``impactlab run --max-cases/--max-memory``.
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterator
from typing import TYPE_CHECKING

import attrs

from impactlab.errors import ResourceLimitError
from impactlab.model.base import HISTORY_LENGTH
from impactlab.vocabulary import INPUTS, is_history

if TYPE_CHECKING:  # study.core imports this module
    from impactlab.study.core import Study

DEFAULT_MAX_CASES = 10_000_000
DEFAULT_MAX_MEMORY = 4 * 2**30
DEFAULT_MAX_YAML_NODES = 100_000

#: set by the command line; they win over the environment
_overrides: dict[str, int] = {}

_UNITS = {"": 1, "b": 1, "k": 2**10, "kb": 10**3, "kib": 2**10, "m": 2**20, "mb": 10**6, "mib": 2**20,
          "g": 2**30, "gb": 10**9, "gib": 2**30, "t": 2**40, "tb": 10**12, "tib": 2**40}


def parse_size(text: str | int) -> int:
    """'4GiB', '500 MB', '2g' or a number of bytes -> bytes."""
    if isinstance(text, int):
        return text
    match = re.fullmatch(r"\s*([0-9]+(?:\.[0-9]*)?)\s*([a-zA-Z]*)\s*", str(text))
    if not match or match.group(2).lower() not in _UNITS:
        raise ValueError(f"a size such as 4GiB, 500MB or 2000000000, got {text!r}")
    return int(float(match.group(1)) * _UNITS[match.group(2).lower()])


def format_size(count: float) -> str:
    """A byte count in words: '1.5 GiB', '12 KiB', '300 B'."""
    for unit, size in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if count >= size:
            return f"{count / size:.1f} {unit}"
    return f"{int(count)} B"


def configure(**values: int | None) -> None:
    """Set this process's overrides (``max_cases``, ``max_memory``, ``max_yaml_nodes``), replacing earlier ones;
    None leaves a limit to the environment and the default."""
    _overrides.clear()
    for key, value in values.items():
        if value is not None:
            _overrides[key] = int(value)


@contextlib.contextmanager
def configured(**values: int | None) -> Iterator[None]:
    """:func:`configure` for the length of a block; the overrides before it come back after it.

    ``impactlab.cli.main`` runs each command inside one, so a caller of ``main`` keeps its own limits.
    """
    saved = dict(_overrides)
    configure(**values)
    try:
        yield
    finally:
        _overrides.clear()
        _overrides.update(saved)


def _limit(key: str, default: int, parse=int) -> int:
    if key in _overrides:
        return _overrides[key]
    text = os.environ.get(f"IMPACTLAB_{key.upper()}")
    if not text:
        return default
    try:
        return parse(text)
    except ValueError:
        raise ResourceLimitError(f"IMPACTLAB_{key.upper()}={text!r}: not a valid limit") from None


def max_cases() -> int:
    """Largest number of cases a study may have (``--max-cases``, IMPACTLAB_MAX_CASES, or the default)."""
    return _limit("max_cases", DEFAULT_MAX_CASES)


def max_memory() -> int:
    """Largest memory estimate in bytes a run may have (``--max-memory``, IMPACTLAB_MAX_MEMORY, or the default)."""
    return _limit("max_memory", DEFAULT_MAX_MEMORY, parse_size)


def max_yaml_nodes() -> int:
    """Most nodes a study's YAML may expand to through aliases (IMPACTLAB_MAX_YAML_NODES, or the default)."""
    return _limit("max_yaml_nodes", DEFAULT_MAX_YAML_NODES)


def check_cases(count: int, where: str) -> None:
    """Refuse a sweep (or range) of more than ``max_cases`` values before it is generated."""
    limit = max_cases()
    if count > limit:
        raise ResourceLimitError(f"{where}: {count:,} cases, above the limit of {limit:,}; make the sweep coarser, "
                                 f"or raise the limit with --max-cases {count} (or IMPACTLAB_MAX_CASES)")


@attrs.frozen
class Estimate:
    """What a study will take: cases, case-model evaluations and bytes at the peak."""

    cases: int
    evaluations: int
    memory: int
    #: the part of ``memory`` taken by kernel grids of expert resolution options
    kernel_memory: int = 0

    def describe(self) -> str:
        """The estimate and the limits it is held against, in one line (``impactlab run --plan``)."""
        return (f"estimate: {self.cases:,} case(s), {self.evaluations:,} evaluation(s), about "
                f"{format_size(self.memory)} of memory (limits: {max_cases():,} cases, {format_size(max_memory())}; "
                "raise with --max-cases/--max-memory)")


#: copies of each result array alive at the peak: the chunks, the joined per-model arrays, the unfolded and
#: concatenated study arrays, and the HDF5 image written from memory
RESULT_COPIES = 5
#: float arrays per spring and time point of a tabulated kernel grid (times, nodes, loads, inside flags)
GRID_ARRAYS = 4


def estimate(study: Study) -> Estimate:
    """Peak memory of running ``study``, from its sizes alone (nothing is allocated)."""
    cases = study.n_cases
    models = len(study.models)
    points = max([entry.model.history_length() for entry in study.models] or [HISTORY_LENGTH])
    histories = [name for name in study.all_outputs if is_history(name)]
    per_case = len(study.all_outputs) - len(histories) + len(histories) * points
    memory = 8 * cases * len(INPUTS) + RESULT_COPIES * 8 * cases * models * per_case
    kernel = 0
    for entry in study.models:
        grid = entry.model.expert_resolution()
        if grid is not None:
            springs, steps = grid
            kernel = max(kernel, 8 * GRID_ARRAYS * (steps + 1) * springs
                         + (16 * cases * (steps + 1) if histories else 0))  # histories on every step, then resampled
    return Estimate(cases, cases * models, memory + kernel, kernel)


def check(study: Study) -> Estimate:
    """The estimate of ``study``, or ResourceLimitError if it needs more than the limits allow."""
    found = estimate(study)
    check_cases(found.cases, f"study {study.name!r}")
    limit = max_memory()
    if found.memory > limit:
        cause = (f"the expert resolution options (springs x steps) alone take {format_size(found.kernel_memory)}; "
                 "lower them, or leave them out and set a tolerance" if found.kernel_memory > limit / 2
                 else "make the sweep coarser or ask for fewer outputs")
        raise ResourceLimitError(f"study {study.name!r} ({study.file or 'given in Python'}) needs about "
                                 f"{format_size(found.memory)} of memory ({found.cases:,} case(s) x "
                                 f"{len(study.models)} "
                                 f"model(s)), above the limit of {format_size(limit)}: {cause}; or raise the limit "
                                 f"with --max-memory (or IMPACTLAB_MAX_MEMORY)")
    return found
