"""The command line's one error path: every failure becomes one message and an exit status.

Commands raise; only :func:`run_command` catches. It maps

* :class:`~impactlab.errors.ImpactLabError` to its ``exit_code`` (2 bad input, 3 environment),
* ``OSError`` (a folder that refuses writes, a full disk...) to 3, in words,
* ``MemoryError`` to 3,
* Ctrl-C and SIGTERM to 130, with the hint the command registered (how to resume),
* anything else to 1 as an internal error,

and prints a traceback only with ``--debug``. Dependency warnings are printed
on one line and never raise.
"""

from __future__ import annotations

import contextlib
import errno
import os
import select
import signal
import sys
import threading
import traceback
import warnings
from collections.abc import Callable, Iterator
from typing import Any

from impactlab.errors import ImpactLabError, PlausibilityWarning, PluginWarning
from impactlab.foreign import TerminalGuard, terminal_safe
from impactlab.model.diagnostics import ValidityWarning
from impactlab.io.safe_output import remove_temporaries

EXIT_OK = 0
EXIT_INTERNAL = 1
EXIT_BAD_INPUT = 2
EXIT_ENVIRONMENT = 3
EXIT_INTERRUPTED = 130
#: the reader of the output closed the pipe (128 + SIGPIPE, as a shell reports a tool killed by it)
EXIT_BROKEN_PIPE = 141

#: what to tell the user after an interrupt; a command that keeps partial work says how to resume it
_interrupt_hint: list = ["no result file was written or changed"]


def set_interrupt_hint(text: str | Callable[[], str]) -> None:
    """What the message after Ctrl-C says about the result files (set by each command before it runs); a callable
    is asked when the interrupt is reported (whether any chunk had finished is known only then)."""
    _interrupt_hint[0] = text


def _hint() -> str:
    hint = _interrupt_hint[0]
    if callable(hint):
        try:
            return hint()
        except Exception:  # noqa: BLE001 - the interrupt must be reported whatever the hint finds
            return "no result file was written or changed"
    return hint


#: errno -> what to do about it
_ADVICE = {
    errno.ENOSPC: "the disk is full: free some space (or write elsewhere) and run again",
    errno.EDQUOT: "the disk quota is exhausted: free some space (or write elsewhere) and run again",
    errno.EACCES: "permission denied: choose a folder you can write to",
    errno.EPERM: "operation not permitted: choose a folder you can write to",
    errno.EROFS: "the file system is read-only: choose another folder",
    errno.ENOENT: "no such file or folder: check the path",
    errno.EISDIR: "it is a folder: give a file name",
    errno.ENOTDIR: "a part of the path is not a folder: check the path",
    errno.EEXIST: "it already exists and is not a folder",
    errno.ENAMETOOLONG: "the name is too long",
}


def describe_os_error(exc: OSError) -> str:
    """'PATH: what happened; what to do' for an OSError, without Python's repr."""
    where = exc.filename if exc.filename is not None else ""
    advice = _ADVICE[exc.errno] if exc.errno in _ADVICE else exc.strerror or str(exc)
    if exc.errno in (errno.EACCES, errno.EPERM) and where:
        # an input the user may not read: 'choose a folder you can write to' would send them the wrong way
        advice = _read_denied(where) or advice
    return f"{where}: {advice}" if where else advice


def _read_denied(path) -> str | None:
    """What to do when ``path`` cannot be read: it exists unreadable, or a folder on its way may not be entered."""
    try:
        if os.path.exists(path) and not os.access(path, os.R_OK):
            return "permission denied: you may not read it; check its permissions (ls -l) or copy it somewhere you can"
        folder = os.path.dirname(os.path.abspath(path))
        while folder and not os.path.exists(folder):
            folder = os.path.dirname(folder)
        if folder and os.path.isdir(folder) and not os.access(folder, os.X_OK):
            return f"permission denied: you may not enter the folder {folder}; check its permissions (ls -ld)"
    except (OSError, ValueError, TypeError):
        pass
    return None


def _caused_by_interrupt(exc: BaseException | None) -> bool:
    """A SystemError that numba raises when Ctrl-C arrives inside a compiled kernel hides a KeyboardInterrupt."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


def show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int, file: Any = None,
                 line: str | None = None) -> None:
    """Replacement for ``warnings.showwarning``: one line on stderr, never an exception."""
    if issubclass(category, _own_warnings()):
        text = f"impactlab: warning: {terminal_safe(str(message))}\n"
    else:  # a dependency's warning: say where it came from, as Python would, but on one line
        text = f"impactlab: warning from {filename}:{lineno}: {category.__name__}: {terminal_safe(str(message))}\n"
    try:
        (file or sys.stderr).write(text)
    except (OSError, ValueError):  # stderr closed or a broken pipe: a warning must not end the run
        pass


def _own_warnings() -> tuple[type, ...]:
    return (ValidityWarning, PluginWarning, PlausibilityWarning)


#: seconds the main thread has, after Ctrl-C or SIGTERM, to stop at a safe point before the process is ended
INTERRUPT_GRACE = 3.0

_stop = threading.Event()


def check_interrupt() -> None:
    """Raise KeyboardInterrupt if Ctrl-C or SIGTERM arrived: called at safe points (between chunks)."""
    if _stop.is_set():
        raise KeyboardInterrupt


def _request_stop(signum, frame):
    if _stop.is_set():  # a second Ctrl-C: the user does not want to wait for the safe point
        _hard_exit()
    _stop.set()


def _hard_exit() -> None:
    remove_temporaries()  # a result being written when the process ends leaves no temporary file
    try:
        sys.stderr.write(f"\nimpactlab: interrupted; {_hint()}\n")
        sys.stderr.flush()
    finally:
        os._exit(EXIT_INTERRUPTED)


@contextlib.contextmanager
def deferred_interrupts(grace: float = INTERRUPT_GRACE) -> Iterator[None]:
    """Ctrl-C and SIGTERM stop the command at its next safe point, or end the process after ``grace`` s.

    Raising KeyboardInterrupt wherever the main thread happens to be is not safe: inside a numba
    kernel or numba's compiler it surfaces as a SystemError or leaves the process to crash at exit
    (seen: exit by SIGSEGV), and a compiled kernel does not return to Python for many seconds anyway.
    So the handlers only set a flag that the run checks between chunks (:func:`check_interrupt`).
    The C-level handler also writes the signal number to a wakeup descriptor at once; a thread
    reading it gives the main thread ``grace`` seconds to reach a safe point, then removes any
    temporary file, prints the interrupt message and ends the process with 130. Finished chunks are
    saved atomically, so nothing finished is lost either way.
    """
    _stop.clear()
    try:
        previous = {number: signal.signal(number, _request_stop) for number in (signal.SIGINT, signal.SIGTERM)}
    except ValueError:  # not the main thread (a test runner's worker): Python's defaults stay
        yield
        return
    read, write = os.pipe()
    os.set_blocking(write, False)
    previous_fd = signal.set_wakeup_fd(write, warn_on_full_buffer=False)
    done = threading.Event()

    def watch():
        while True:
            try:
                data = os.read(read, 64)
            except OSError:
                return
            if not data or done.is_set():
                return
            if any(number in (signal.SIGINT, signal.SIGTERM) for number in data) and not done.wait(grace):
                _hard_exit()

    thread = threading.Thread(target=watch, name="impactlab-interrupt-watchdog", daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        signal.set_wakeup_fd(previous_fd)
        for number, handler in previous.items():
            signal.signal(number, handler)
        os.close(write)  # wakes the thread with end-of-file
        thread.join(1.0)
        os.close(read)
        _stop.clear()


def _stdout_closed() -> bool:
    """Whether standard output is a pipe whose reader has gone (poll reports an error on it)."""
    try:
        descriptor = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # not a file (a test's stand-in): ask it by flushing
        try:
            sys.stdout.flush()
        except BrokenPipeError:
            return True
        except (OSError, ValueError):
            return False
        return False

    poller = select.poll()
    poller.register(descriptor, select.POLLOUT)
    return any(events & select.POLLERR for _, events in poller.poll(0))


@contextlib.contextmanager
def _guarded_streams() -> Iterator[None]:
    """stdout and stderr written through :class:`impactlab.foreign.TerminalGuard` while a command runs."""
    out, err = sys.stdout, sys.stderr
    sys.stdout = TerminalGuard(out) if out is not None and not isinstance(out, TerminalGuard) else out
    sys.stderr = TerminalGuard(err, keep_cr=True) if err is not None and not isinstance(err, TerminalGuard) else err
    try:
        yield
    finally:
        sys.stdout, sys.stderr = out, err


def run_command(call: Callable[[], int], *, debug: bool = False) -> int:
    """Run ``call()`` (a command returning its exit status) and turn every failure into message and status."""
    _interrupt_hint[0] = "no result file was written or changed"

    def fail(text: str, code: int) -> int:
        if debug:
            traceback.print_exc()
        print(f"impactlab: {terminal_safe(text)}", file=sys.stderr)
        return code

    # catch_warnings puts the caller's showwarning and filters back when the command returns or raises; the
    # guards escape any control character a file or a server put in the text written (issue 35), the progress
    # bar's carriage return on stderr excepted
    with warnings.catch_warnings(), _guarded_streams():
        warnings.showwarning = show_warning
        warnings.simplefilter("default")
        try:
            with deferred_interrupts():
                return call()
        except ImpactLabError as exc:
            return fail(f"error: {exc}", exc.exit_code)
        except KeyboardInterrupt:
            return fail(f"interrupted; {_hint()}", EXIT_INTERRUPTED)
        except BrokenPipeError as exc:
            if not _stdout_closed():  # another pipe broke (a peer process, a socket): an error like any other
                return fail(f"error: {describe_os_error(exc)}", EXIT_ENVIRONMENT)
            # the reader of our output went away (``impactlab models | head``): stop quietly, as the standard
            # tools do; stdout goes to /dev/null so the interpreter's last flush does not complain either
            with contextlib.suppress(OSError, ValueError, AttributeError):  # a stdout without a descriptor
                os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            return EXIT_BROKEN_PIPE
        except OSError as exc:
            return fail(f"error: {describe_os_error(exc)}", EXIT_ENVIRONMENT)
        except MemoryError:
            return fail("error: out of memory: make the study smaller (impactlab run --plan shows its estimate)",
                        EXIT_ENVIRONMENT)
        except Exception as exc:  # noqa: BLE001 - the last line of defence: a bug, said as one
            if _caused_by_interrupt(exc):
                return fail(f"interrupted; {_hint()}", EXIT_INTERRUPTED)
            return fail(f"internal error: {type(exc).__name__}: {exc} (run again with --debug for the traceback, "
                        "and please report it)", EXIT_INTERNAL)
