"""Running a study's cases in chunks: executors, progress, interruption and resume.

The work of a study is a list of chunks (one model entry, a contiguous slice
of cases). An executor computes chunks and yields them as they complete; only
the calling process assembles and writes results, so workers never touch a
file. Chunked results equal unchunked ones exactly: a model's result for a
case does not depend on the batch around it (conformance rule 5).

Executors: ``serial`` (in this process), ``processes`` (every core of this
machine), ``dask`` (a dask.distributed cluster: a scheduler address, or a
LocalCluster). With a progress folder, every finished chunk is saved there
atomically; a run killed at any point and started again with the same study
and output computes only the chunks that are missing.
"""

from __future__ import annotations

import ctypes
import fcntl
import hashlib
import io
import json
import os
import shutil
import signal
import sys
import time
import zipfile
from collections.abc import Callable, Iterator, Sequence
from typing import Any
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from pathlib import Path

import attrs
import numpy as np
from tqdm import tqdm

from impactlab.model.base import ImpactModel
from impactlab.model.case_inputs import CaseInputs
from impactlab.errors import EnvironmentFault, StudyError
from impactlab.run.faults import check_interrupt
from impactlab.io.safe_output import TEMPORARY_SUFFIX, write_atomically
from impactlab._version import __version__
from impactlab.vocabulary import is_history

EXECUTORS = ("auto", "serial", "processes", "dask")
#: below this many case-model evaluations, 'auto' runs in this process (starting workers costs more)
AUTO_PARALLEL_WORK = 20_000


@attrs.frozen
class Chunk:
    """A model entry and a slice of cases."""

    entry: int
    start: int
    stop: int

    @property
    def key(self) -> str:
        """The chunk's file name stem in a progress folder: model entry and case range."""
        return f"m{self.entry}-c{self.start}-{self.stop}"


#: layout of a saved chunk; a progress folder of another layout is started over, not misread
CHUNK_FORMAT = 3


def plan_chunks(n_models: int, n_cases: int, chunk_size: int) -> list[Chunk]:
    """Every (model entry, slice of at most ``chunk_size`` cases) of a run, model by model."""
    return [Chunk(entry, start, min(start + chunk_size, n_cases))
            for entry in range(n_models) for start in range(0, n_cases, chunk_size)]


def compute_chunk(model: ImpactModel, inputs: dict | CaseInputs, outputs: Sequence[str], chunk: Chunk,
                  plan: Any = None, paths: bool = False) -> dict:
    """Worker side: run ``model`` on the chunk's cases; plain arrays and the missing outputs' reasons come back.

    ``plan`` is the model's plan for the study (:func:`impactlab.run.runner.plan_study`), made once, not per chunk.
    ``paths``: also count the chunk's cases on one line (``one_line``, for the plan's sentence on the solver
    paths) from the chunk's contact state, the one the model has built already.
    """
    part: CaseInputs
    if isinstance(inputs, CaseInputs):  # in this process: checked once, one contact state for all models
        part = inputs.slice(chunk.start, chunk.stop)
    else:
        part = CaseInputs(_cases_of(inputs, chunk))
    result = model.compute_arrays(part, outputs, plan=plan)  # arrays inside: no Dataset built per chunk
    # what assembly needs and nothing else: the values in the vocabulary's units, the time axis, the reasons
    out: dict[str, Any] = {"data": {name: result.in_units(name) for name in result.values}, "time": result.time,
           "missing": dict(result.missing)}
    if paths:
        out["one_line"] = int(np.count_nonzero(part.contact_state()["one_dimensional"]))
    return out


def _cases_of(inputs: dict, chunk: Chunk) -> dict:
    """The chunk's slice of every input array (views)."""
    return {name: values[chunk.start:chunk.stop] for name, values in inputs.items()}


#: seconds to reach a dask scheduler before giving up
SCHEDULER_TIMEOUT = 10
PR_SET_PDEATHSIG = 1


def _worker_start(parent: int) -> None:
    """In each worker process: die with the parent, and leave Ctrl-C to it.

    Ctrl-C reaches every process of the terminal's group; the parent decides (it stops the pool), so a
    worker ignores SIGINT. If the parent is killed (even with kill -9) the kernel sends the worker
    SIGKILL (Linux prctl PR_SET_PDEATHSIG); a parent already gone before that was set is caught by
    comparing the parent pid.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # a forked worker inherits the parent's Ctrl-C-like handler
    if sys.platform.startswith("linux"):
        try:
            ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
        except (OSError, AttributeError):
            pass
    if os.getppid() != parent:
        os._exit(1)


class _Pool:
    def __init__(self, kind: str, workers: int | None, scheduler: str | None):
        self.kind = kind
        self.shared = None
        if kind == "processes":
            self.pool = ProcessPoolExecutor(max_workers=workers or os.cpu_count(), initializer=_worker_start,
                                            initargs=(os.getpid(),))
        else:
            try:  # dask is optional (impactlab[dask]) and heavy: imported only for the dask executor
                from dask.distributed import Client, LocalCluster
            except ImportError:
                raise StudyError("the dask executor needs dask.distributed: pip install 'impactlab[dask]'") from None
            if scheduler:
                try:
                    self.client = Client(scheduler, timeout=SCHEDULER_TIMEOUT)
                except (OSError, TimeoutError, ValueError) as exc:
                    raise EnvironmentFault(f"--scheduler {scheduler}: no dask scheduler answered within "
                                           f"{SCHEDULER_TIMEOUT} s ({type(exc).__name__}); check the address and "
                                           "that the scheduler runs, or leave --scheduler out") from None
                self.cluster = None
            else:
                self.cluster = LocalCluster(n_workers=workers or os.cpu_count(), threads_per_worker=1,
                                            processes=True, dashboard_address=None)
                self.client = Client(self.cluster)

    def run(self, model, inputs, outputs, chunks, plan=None, paths: bool = False) -> Iterator:
        if self.kind == "processes":
            # each task carries its own cases only: the whole inputs with every chunk pickled 320 MB per task
            # for 10^6 cases and made the pool 4x slower than one process
            futures: dict[Any, Chunk]  # concurrent.futures here, dask's futures below
            futures = {self.pool.submit(compute_chunk, model, _cases_of(inputs, chunk), outputs,
                                        attrs.evolve(chunk, start=0, stop=chunk.stop - chunk.start), plan,
                                        paths): chunk
                       for chunk in chunks}
            pending = set(futures)
            while pending:
                check_interrupt()  # waits are short, so that Ctrl-C stops the pool within a fraction of a second
                done, pending = wait(pending, timeout=0.2, return_when=FIRST_COMPLETED)
                for future in done:
                    yield futures[future], future.result()
        else:
            from dask.distributed import as_completed

            if self.shared is None:  # the case inputs travel to every worker once, as one object
                self.shared = self.client.scatter([inputs], broadcast=True, hash=False)[0]
            futures = {self.client.submit(compute_chunk, model, self.shared, outputs, chunk, plan, paths,
                                          pure=False): chunk
                       for chunk in chunks}
            for future in as_completed(list(futures)):
                check_interrupt()
                yield futures[future], future.result()

    def close(self, abort: bool = False):
        if self.kind == "processes":
            if abort:  # an interrupt or error: queued chunks are not wanted, running ones are stopped now
                for process in list(getattr(self.pool, "_processes", {}).values()):
                    process.terminate()
            self.pool.shutdown(wait=not abort, cancel_futures=True)
        else:
            self.client.close()
            if self.cluster is not None:
                self.cluster.close()


class Progress:
    """One progress bar on stderr, fed by completed chunks whatever the executor.

    On a terminal, a tqdm bar redrawn in place; where stderr is not a terminal (logs, CI) a line every tenth
    (tqdm's own meter as text), never carriage returns; nothing when not ``enabled``.
    """

    def __init__(self, total: int, enabled: bool, label: str = "cases"):
        self.total, self.done, self.enabled, self.label = total, 0, enabled, label
        self.start = time.perf_counter()
        self.tty = enabled and sys.stderr.isatty()
        self.last_tenth = -1
        # a bar only where one is drawn: a disabled tqdm still costs ~50 us to make, every run of a small study
        self.bar = tqdm(total=total, unit=f" {label}", file=sys.stderr, dynamic_ncols=True,
                        leave=True) if self.tty else None

    def advance(self, count: int) -> None:
        """Count ``count`` more cases done; redraw the bar (a line every tenth where stderr is not a terminal)."""
        self.done += count
        if not self.enabled:
            return
        if self.bar is not None:
            self.bar.update(count)
            if self.done >= self.total:
                self.close()
            return
        fraction = self.done / max(self.total, 1)
        if int(10 * fraction) > self.last_tenth:  # logs and CI: a line every tenth
            self.last_tenth = int(10 * fraction)
            meter = tqdm.format_meter(self.done, self.total, time.perf_counter() - self.start, unit=f" {self.label}")
            print(meter, file=sys.stderr, flush=True)

    def close(self) -> None:
        """End the bar (its line stays on the terminal); idempotent."""
        if self.bar is not None:
            self.bar.close()


class ProgressStore:
    """Finished chunks of one study run, saved atomically next to the result file.

    Used as a context manager it holds an exclusive lock (``fcntl.flock``) on the folder: a second run
    writing the same result is refused at once instead of racing this one. A chunk file that cannot
    be read back (truncated, damaged) is reported, deleted and computed again.
    """

    def __init__(self, folder: Path, fingerprint: str, say: Callable[[str], None], output=None):
        self.folder, self.fingerprint, self.say = Path(folder), fingerprint, say
        self.output = output or self.folder.with_suffix("")
        self._lock: int | None = None

    def __enter__(self) -> ProgressStore:
        self._lock = _lock_folder(self.folder, self.output)
        manifest = self.folder / "manifest.json"
        try:
            same = json.loads(manifest.read_text())["fingerprint"] == self.fingerprint
        except (OSError, ValueError, KeyError, TypeError):
            same = False
        entries = list(self.folder.iterdir())
        if not same and any(path.name != "manifest.json" for path in entries):
            self.say(f"{self.folder}: progress of a different study or version; starting over")
        for path in entries:
            # a different study's chunks, or the temporary file of a run killed while saving a chunk
            if not same or path.name.endswith(TEMPORARY_SUFFIX):
                shutil.rmtree(path) if path.is_dir() else path.unlink(missing_ok=True)
        if not same:
            write_atomically(manifest, json.dumps({"fingerprint": self.fingerprint}).encode())
        return self

    def __exit__(self, *exc) -> None:
        if self._lock is not None:
            try:  # a run that failed before its first chunk leaves no folder behind, only real progress stays
                if self.folder.is_dir() and {path.name for path in self.folder.iterdir()} <= {"manifest.json"}:
                    shutil.rmtree(self.folder, ignore_errors=True)
            finally:
                os.close(self._lock)
                self._lock = None

    def load(self, chunk: Chunk) -> dict | None:
        """The saved chunk, or None if it was not saved (or was damaged: then it is reported and deleted)."""
        path = self.folder / f"{chunk.key}.npz"
        if not path.exists():
            return None
        try:
            with np.load(path, allow_pickle=False) as archive:
                meta = json.loads(str(archive["__meta__"]))
                data = {name: archive[name] for name in meta["names"]}
                time_axis = archive["__time__"] if "__time__" in archive else None
                missing = dict(meta["missing"])
                one_line = meta.get("one_line")
        except (OSError, ValueError, KeyError, TypeError, EOFError, zipfile.BadZipFile) as exc:
            self.say(f"{path}: damaged ({type(exc).__name__}: {exc}); computing this chunk again")
            path.unlink(missing_ok=True)
            return None
        part = {"data": data, "time": time_axis, "missing": missing}
        if one_line is not None:
            part["one_line"] = int(one_line)
        return part

    def save(self, chunk: Chunk, part: dict) -> None:
        """Save a finished chunk atomically (a full disk shows here, and no half-written chunk remains)."""
        meta = {"names": list(part["data"]), "missing": part["missing"]}
        if "one_line" in part:
            meta["one_line"] = part["one_line"]
        arrays = dict(part["data"])
        if part["time"] is not None:
            arrays["__time__"] = part["time"]
        # built in memory and written by the one atomic writer, as result files are: a full disk or a kill
        # leaves at most its hidden temporary, which the next run removes
        buffer = io.BytesIO()
        np.savez(buffer, __meta__=np.array(json.dumps(meta)), **arrays)
        write_atomically(self.folder / f"{chunk.key}.npz", buffer.getbuffer())

    def clear(self) -> None:
        """Remove the folder: the result file is written, the progress is no longer needed."""
        shutil.rmtree(self.folder, ignore_errors=True)


def _lock_folder(folder: Path, output) -> int:
    """Create ``folder`` and lock it for this process; the lock goes with the descriptor returned."""
    for _ in range(3):  # another run may remove the folder between our mkdir and our lock: take the new one
        folder.mkdir(parents=True, exist_ok=True)
        handle = os.open(folder, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))
        try:
            fcntl.flock(handle, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(handle)
            raise EnvironmentFault(f"{output}: another impactlab run is computing this result now (its progress "
                                   f"folder {folder} is locked); wait for it to finish, or choose another -o") from None
        try:
            if os.stat(folder).st_ino == os.fstat(handle).st_ino:
                return handle
        except FileNotFoundError:
            pass
        os.close(handle)
    raise EnvironmentFault(f"{folder}: keeps disappearing while being locked; is another run clearing it?")


def fingerprint(study, outputs, extra: str = "") -> str:
    """SHA-256 of what decides a run's chunks: study text, outputs, models with options, version."""
    text = json.dumps({"source": study.source, "outputs": list(outputs), "version": __version__,
                       "chunk_format": CHUNK_FORMAT,
                       "models": [[entry.id, entry.model.options_dict()] for entry in study.models],
                       "extra": extra}, sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()


def choose_executor(kind: str, n_work: int, has_histories: bool) -> str:
    """The executor ``auto`` stands for: processes for large runs without histories on several cores, else serial."""
    if kind != "auto":
        return kind
    return "processes" if n_work >= AUTO_PARALLEL_WORK and not has_histories and (os.cpu_count() or 1) > 1 \
        else "serial"


def run_chunks(study, inputs: dict, outputs, *, executor: str = "auto", workers: int | None = None,
               scheduler: str | None = None, chunk_size: int | None = None, store: ProgressStore | None = None,
               show_progress: bool = False, plans: Sequence[Any] | None = None) -> list[dict]:
    """Compute every model entry on every case; per entry, its outputs joined over the cases (see ``_join``).

    ``plans``: one :class:`~impactlab.model.planning.OutputPlan` per model entry, made once for the study
    (default: each model plans its chunks itself)."""
    n_cases = study.n_cases
    has_histories = any(is_history(name) for name in outputs)
    kind = choose_executor(executor, n_cases * len(study.models), has_histories)
    if kind not in EXECUTORS:
        raise StudyError(f"unknown executor {kind!r}; choices: {', '.join(EXECUTORS)}")
    if has_histories:
        chunk_size = n_cases  # histories share one time axis per model: they are computed in one piece
    elif chunk_size is None:  # the cores are counted for a pool only (os.cpu_count reads /sys: ~50 us a call)
        chunk_size = max(256, min(8192, -(-n_cases // (4 * (workers or os.cpu_count() or 1))))) \
            if kind != "serial" else 8192
    chunks = plan_chunks(len(study.models), n_cases, chunk_size)
    parts: dict[Chunk, dict] = {}
    progress = Progress(n_cases * len(study.models), show_progress)
    if store is not None:
        for chunk in chunks:
            saved = store.load(chunk)
            if saved is not None:
                parts[chunk] = saved
                progress.advance(chunk.stop - chunk.start)
    todo = [chunk for chunk in chunks if chunk not in parts]
    pool = _Pool(kind, workers, scheduler) if todo and kind in ("processes", "dask") else None
    finished = False
    try:
        paths = study.scene.club is not None  # the plan's sentence on the solver paths counts one-line cases
        for chunk, part in _stream(study, inputs, outputs, todo, pool, plans or [None] * len(study.models), paths):
            if store is not None:
                store.save(chunk, part)
            parts[chunk] = part
            progress.advance(chunk.stop - chunk.start)
            check_interrupt()  # the safe point: this chunk is saved, the next has not started
        finished = True
    finally:
        progress.close()
        if pool is not None:
            pool.close(abort=not finished)
    return [_join([parts[chunk] for chunk in chunks if chunk.entry == index]) for index in range(len(study.models))]


def _stream(study, inputs: dict, outputs, todo: list[Chunk], pool, plans, paths: bool = False) -> Iterator:
    """Finished chunks as they come.

    In this process the cases are checked once and the models run chunk by chunk, every model on a
    chunk before the next, so they share the chunk's contact state and only one chunk's state is held;
    a pool takes one model's chunks at a time.
    """
    if pool is None:
        batch = CaseInputs(inputs, copy=False)  # the runner's own arrays, not changed during the run
        for chunk in sorted(todo, key=lambda chunk: (chunk.start, chunk.entry)):
            yield chunk, compute_chunk(study.models[chunk.entry].model, batch, outputs, chunk, plans[chunk.entry],
                                       paths and chunk.entry == 0)
        return
    for entry_index, entry in enumerate(study.models):
        mine = [chunk for chunk in todo if chunk.entry == entry_index]
        if mine:
            yield from pool.run(entry.model, inputs, outputs, mine, plans[entry_index], paths and entry_index == 0)


def _join(parts: list[dict]) -> dict:
    """One model entry's chunks joined along the cases: arrays in the vocabulary's units, no Dataset yet."""
    first = parts[0]
    # one chunk (a small study) is its own join: its arrays are the chunk's own, held by nothing else
    joined = {"data": dict(first["data"]) if len(parts) == 1 else
              {name: np.concatenate([part["data"][name] for part in parts]) for name in first["data"]},
              "time": first["time"],
              "missing": first["missing"]}
    if all("one_line" in part for part in parts):
        joined["one_line"] = sum(part["one_line"] for part in parts)
    return joined
