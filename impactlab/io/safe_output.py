"""Where impactlab may write, checked before any work, and how it writes.

Rules: only regular files are created or replaced (never a device such as
/dev/full, never a folder); a name taken from a study cannot leave its output
folder; every file is written to a temporary file beside its target and
renamed over it only when complete, with the permissions the umask gives (not
the 0600 of a temporary file); on any failure (a full disk included) the
temporary file is removed and the old target is untouched.
"""

from __future__ import annotations

import csv
import os
import re
import stat
import tempfile
from collections.abc import Iterable
from pathlib import Path

from impactlab.errors import EnvironmentFault, StudyError, has_control, shown


#: how the temporary file of a write ends (a folder cleaned up after a killed run looks for it)
TEMPORARY_SUFFIX = ".part"
#: temporary files being written now: removed if the process must end at once (impactlab.run.faults)
_temporaries: set[str] = set()


def remove_temporaries() -> None:
    """Delete every temporary file a write in progress left (called on interrupt and at exit)."""
    for name in list(_temporaries):
        try:
            os.unlink(name)
        except OSError:
            pass


def _umask() -> int:
    # os.umask can only be read by setting it; put it straight back
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


#: the suffixes of each kind of output (check_output's ``formats``)
RESULT_SUFFIXES = (".h5", ".hdf5", ".hdf", ".nc", ".nc4")
TABLE_SUFFIXES = (".csv", ".txt")
JSON_SUFFIXES = (".json",)
REPORT_SUFFIXES = (".md", ".markdown", ".txt")
#: the picture files a figure is written as, by their suffix (matplotlib's writers without a TeX or plugin need)
PICTURE_SUFFIXES = (".png", ".pdf", ".svg", ".svgz", ".eps", ".ps", ".jpg", ".jpeg", ".tif", ".tiff", ".webp")


def check_output(path: str | os.PathLike, what: str = "result file", suffix: str = ".h5",
                 reads: Iterable[str | os.PathLike] = (), formats: Iterable[str] | None = None) -> Path:
    """Refuse, before any work, an output path impactlab could not or must not write.

    Bad paths (a folder, a device, a missing folder, a file the command reads: ``reads``, a name whose suffix
    is not one of ``formats``) are input errors (exit 2); a folder that refuses writes is an environment fault
    (exit 3).
    """
    path = Path(path)
    flag = f" ({what})" if what else ""
    for source in reads:  # the user's study, session or result replaced by the output: the only copy lost
        if Path(source).is_file():
            refuse_overwriting(path, source, what)
    try:
        info = path.stat()
    except FileNotFoundError:
        info = None
    except OSError as exc:
        raise EnvironmentFault(f"{path}{flag}: cannot be examined: {exc.strerror}") from None
    if info is not None and stat.S_ISDIR(info.st_mode):
        raise StudyError(f"{path}{flag}: is a folder; give a file name inside it, e.g. {path / ('result' + suffix)}")
    if info is not None and not stat.S_ISREG(info.st_mode):
        raise StudyError(f"{path}{flag}: is not a regular file (a device, pipe or socket); impactlab only writes "
                         "regular files: give a file name")
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise StudyError(f"{path}{flag}: cannot write: folder {folder} does not exist (create it first)")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise EnvironmentFault(f"{path}{flag}: cannot write: folder {folder} is not writable (permissions or a "
                               "read-only file system); choose another folder")
    if formats is not None and path.suffix.lower() not in tuple(formats):
        # the suffix says what is written: an HDF5 result sent to 'session.csv' by a slip of tab completion
        # replaced the user's export with no word
        raise StudyError(f"{path}{flag}: expected a file name ending in {' or '.join(formats)} (the suffix says "
                         f"what is written), e.g. {path.with_suffix(suffix).name}")
    return path


def check_outdir(folder: str | os.PathLike) -> Path:
    """An output folder: it may not exist yet (it is created), but must not be a file."""
    folder = Path(folder)
    if folder.exists() and not folder.is_dir():
        raise StudyError(f"--outdir {folder}: is a file, not a folder; give a folder name")
    parent = next((p for p in [folder, *folder.parents] if p.exists()), Path("."))
    if not os.access(parent, os.W_OK | os.X_OK):
        raise EnvironmentFault(f"--outdir {folder}: cannot write in {parent} (permissions or a read-only file "
                               "system); choose another folder")
    return folder


def name_in(folder: Path, name: str, suffix: str) -> Path:
    """FOLDER/NAME+SUFFIX for a name taken from a study, refused if it would leave FOLDER or hide itself."""
    if not name or name in (".", "..") or name.startswith(".") or "/" in name or "\\" in name or has_control(name):
        raise StudyError(f"study name {name!r} cannot name a file in {folder} (it has a slash or a control "
                         "character, starts with a dot or is empty); rename the study, or give -o")
    return folder / f"{name}{suffix}"


def refuse_overwriting(output: str | os.PathLike, source: str | os.PathLike, what: str) -> None:
    """An output that names the file the command reads would replace the user's data with the result: refuse."""
    output, source = Path(output), Path(source)
    try:
        same = os.path.samefile(output, source)
    except OSError:  # one of them does not exist (yet)
        same = os.path.normcase(os.path.abspath(output)) == os.path.normcase(os.path.abspath(source))
    if same:
        raise StudyError(f"{output} ({what}): is the file read ({source}); writing there would replace it: give "
                         "another name")


def refuse_clashes(outputs: list[tuple[str, Path]]) -> None:
    """Two studies of one run writing the same file would overwrite each other: refuse before running either."""
    seen: dict[str, str] = {}
    for label, path in outputs:
        key = os.path.normcase(os.path.abspath(path))
        if key in seen:
            raise StudyError(f"{label} and {seen[key]} would both write {path}; give the studies distinct names")
        seen[key] = label


def write_atomically(path: str | os.PathLike, payload: bytes | memoryview) -> Path:
    """Write ``payload`` to ``path`` through a temporary file and a rename; nothing is left behind on failure."""
    path = check_output(path, what="")
    folder = path.parent if str(path.parent) else Path(".")
    handle, temporary = tempfile.mkstemp(prefix=f".{path.name}.", suffix=TEMPORARY_SUFFIX, dir=folder)
    _temporaries.add(temporary)
    try:
        with os.fdopen(handle, "wb") as stream:
            stream.write(payload)
            stream.flush()
            os.fsync(stream.fileno())  # a full disk shows here, not later after the rename
        os.chmod(temporary, 0o666 & ~_umask())  # mkstemp makes 0600; the result honours the umask
        os.replace(temporary, path)
    except BaseException as exc:
        Path(temporary).unlink(missing_ok=True)
        if isinstance(exc, OSError) and exc.filename is None:  # writes through a stream do not say where
            raise OSError(exc.errno, exc.strerror, str(path)) from None
        raise
    finally:
        _temporaries.discard(temporary)
    return path


def write_figure(figure, path: str | os.PathLike, **options) -> Path:
    """Save a matplotlib figure to ``path`` atomically, in the format its suffix names (PNG without one).

    ``figure.savefig(path)`` writes straight into the target: a full disk or an interrupt there leaves a truncated
    picture in place of the old one. The figure is drawn in memory and written by :func:`write_atomically`.
    """
    import io

    path = Path(path)
    buffer = io.BytesIO()
    buffer.name = str(path)  # where it goes, for whoever watches savefig (the tests' figure audit)
    figure.savefig(buffer, format=path.suffix[1:].lower() or "png", **options)
    return write_atomically(path, buffer.getbuffer())


#: the first header cells of each table impactlab writes (its marker): ``shots --csv`` (the normalised session,
#: ending with ``flags``), ``validate --csv`` (measured beside predicted) and ``fly --csv`` (a session's shots, or the
#: launches typed in, numbered by ``shot``)
TABLE_MARKERS = {"shots": (("line",), ("flags",)), "validate": (("table", "shot", "club", "handedness", "model"), ()),
                 "fly": (("line", "club"), ()), "fly launch": (("shot",), ())}
#: every other header cell of an impactlab table: a lower-case name with its unit in brackets, or a text column
_TABLE_CELL = re.compile(r"^[a-z][a-z0-9_]*( measured| predicted)? \[[^\]]*\]$")
#: (the session text fields, impactlab.data.sessions.layouts.TEXT_FIELDS, are among them: tests/test_trust_outside.py)
_TEXT_CELLS = {"line", "label", "club", "handedness", "ball_setting", "source", "flags", "flagged", "table", "shot",
               "model"}
#: how much of an existing file is read to find its header (a header longer than this is no table of impactlab's)
_HEADER_BYTES = 64 * 1024


def written_by_impactlab(path: str | os.PathLike) -> bool:
    """Whether ``path`` holds a table impactlab wrote (``shots``, ``fly`` or ``validate --csv``), by its header.

    The header is impactlab's marker: it starts with the text columns one of impactlab's writers puts first
    (:data:`TABLE_MARKERS`) and every other cell is a vocabulary name with its unit in brackets
    (``ball_speed [m/s]``). A launch-monitor export names its columns as its vendor does (``Ball Speed``), and a
    hand-written table does not start with these columns.
    """
    try:
        with open(path, "rb") as stream:
            head = stream.read(_HEADER_BYTES)
    except OSError:
        return False
    line = head.split(b"\n", 1)[0].rstrip(b"\r")
    try:
        cells = next(csv.reader([line.decode("utf-8")]))
    except (UnicodeDecodeError, csv.Error, StopIteration):
        return False
    for first, last in TABLE_MARKERS.values():
        if tuple(cells[:len(first)]) == first and (not last or tuple(cells[-len(last):]) == last) \
                and all(cell in _TEXT_CELLS or _TABLE_CELL.match(cell) for cell in cells):
            return True
    return False


def refuse_replacing_foreign(path: str | os.PathLike, what: str, force: bool = False) -> None:
    """Refuse (exit 2) to replace an existing file that is not a table impactlab wrote, unless ``force``.

    ``--csv OUT`` replaced whatever OUT was, another raw launch-monitor export included: only a previous output of
    impactlab's (:func:`written_by_impactlab`) is replaced without ``--force``.
    """
    path = Path(path)
    if force or not path.is_file() or written_by_impactlab(path):
        return
    try:
        with open(path, "rb") as stream:
            first = stream.read(80).split(b"\n", 1)[0].decode("utf-8", "replace").rstrip("\r")
    except OSError:
        first = ""
    raise StudyError(f"{shown(path)} ({what}): exists and is not a table impactlab wrote (it begins "
                     f"'{shown(first)}'): replacing it would lose it; give another name, or add --force to replace "
                     "it")
