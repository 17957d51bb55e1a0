"""Fault injection: every failure a user can cause ends as one message and an exit status, damaging nothing.

Each test asserts the exit status, the message, that no traceback is printed and, where a result file
already existed, that it is byte-identical afterwards. Commands run in this process (``main``) unless
signals, kill -9 or orphaned workers are the point.
"""

import errno
import os
import signal
import stat
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import impactlab
import impactlab.run.execution
from impactlab.cli import main

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "studies" / "compare_models.yaml"
OLD = b"old results that must survive"


def study_text(**replace) -> str:
    text = EXAMPLE.read_text().replace("num: 60", "num: 4")
    for old, new in replace.items():
        assert old in text, old  # a replacement that misses would test the unchanged study
        text = text.replace(old, new)
    return text


def write_study(folder: Path, name="study.yaml", **replace) -> Path:
    path = folder / name
    path.write_text(study_text(**replace))
    return path


def cli(capsys, *args):
    """Run the command line in this process: (exit status, stderr)."""
    code = main([str(arg) for arg in args])
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code, err


@pytest.fixture
def old_result(tmp_path):
    path = tmp_path / "old.h5"
    path.write_bytes(OLD)
    return path


def same_results(a: xr.Dataset, b: xr.Dataset) -> None:
    """Identical data and coordinates; attributes differ only by creation time."""
    xr.testing.assert_identical(a.drop_attrs(deep=False), b.drop_attrs(deep=False))


# -- input files -----------------------------------------------------------------------------------------------
@pytest.mark.parametrize("content, fragment", [
    (b"\x00\x01\x02\x89PNG binary", "is a binary file"),
    ("name: x\n".encode("utf-16"), "is UTF-16 text; save the study file as UTF-8"),
    (b"name: caf\xe9\n", "is not UTF-8 text"),
    (b"x: &x [*x]\n", "a recursive alias"),
])
def test_unreadable_study_files_are_named_and_refused(tmp_path, capsys, old_result, content, fragment):
    study = tmp_path / "bad.yaml"
    study.write_bytes(content)
    code, err = cli(capsys, "run", study, "-o", old_result)
    assert code == 2 and fragment in err and str(study) in err
    assert old_result.read_bytes() == OLD


def test_alias_bomb_is_refused_quickly_even_under_an_unknown_key(tmp_path, capsys):
    # ten levels of ten aliases: 10^10 nodes once expanded, a few hundred bytes written
    lines = ['a0: &a0 ["x","x","x","x","x","x","x","x","x","x"]']
    lines += [f"a{k}: &a{k} [" + ",".join([f"*a{k - 1}"] * 10) + "]" for k in range(1, 10)]
    study = tmp_path / "bomb.yaml"
    study.write_text(study_text() + "unknown:\n" + "\n".join("  " + line for line in lines) + "\n")
    start = time.process_time()  # CPU time: a loaded machine does not inflate it as it does the clock's
    code, err = cli(capsys, "run", study, "--plan")
    assert code == 2 and "expands (through its aliases) to more than 100,000 nodes" in err
    assert time.process_time() - start < 20  # expanding 10^10 nodes takes hours of CPU


@pytest.mark.parametrize("kind", ["txt", "upper", "folder", "devnull"])
def test_a_path_is_read_as_a_file_never_as_yaml_text(tmp_path, capsys, kind):
    if kind == "txt":  # a study in a .txt file is still a study file
        path = tmp_path / "base.txt"
        path.write_text(study_text())
        code, err = cli(capsys, "run", path, "--plan")
        assert code == 0
        return
    if kind == "upper":
        path = tmp_path / "S.YAML"
        path.write_text(study_text())
        assert impactlab.load_study(str(path)).name == "compare-models"  # the Python API reads it as a path too
        code, err = cli(capsys, "run", path, "--plan")
        assert code == 0
        return
    path = tmp_path if kind == "folder" else Path("/dev/null")
    code, err = cli(capsys, "run", path)
    assert code == 2 and "<text>" not in err
    assert ("is a folder, not a study file" if kind == "folder" else "is not a regular file") in err


def test_shot_tables_and_result_files_are_checked_the_same_way(tmp_path, capsys):
    """A shot table saved as UTF-16 (what Windows exports write) is read as exported, the same values as its UTF-8
    twin (issue 22); a file that is not a result file is refused by ``show`` with one clear message."""
    text = "club,club_speed [mph],ball_speed [mph],back_spin [rpm]\n7 Iron,87.0,120.0,7097\nDriver,113.0,167.0,2686\n"
    (tmp_path / "utf8.csv").write_text(text, encoding="utf-8")
    (tmp_path / "utf16.csv").write_bytes(text.encode("utf-16"))  # with its byte-order mark, as exported
    described = {}
    for name in ("utf8", "utf16"):
        code = main(["shots", str(tmp_path / f"{name}.csv"), "--csv", str(tmp_path / f"{name}-read.csv")])
        out, err = capsys.readouterr()
        assert code == 0 and "Traceback" not in err, err
        described[name] = out.replace(f"{name}.csv", "FILE")
    assert described["utf16"] == described["utf8"] and "2 shot(s); clubs: 7 Iron x1, Driver x1" in described["utf8"]
    read = (tmp_path / "utf16-read.csv").read_text().splitlines()
    assert read == (tmp_path / "utf8-read.csv").read_text().splitlines()
    # the values in SI by hand: 1 mph = 0.44704 m/s exactly (the international mile); spin stays in rpm
    assert read[0] == "line,club,club_speed [m/s],ball_speed [m/s],back_spin [rpm],flags"
    for row, (club, club_mph, ball_mph, spin) in zip(read[1:], [("7 Iron", 87.0, 120.0, 7097),
                                                                 ("Driver", 113.0, 167.0, 2686)]):
        cells = row.split(",")
        assert cells[1] == club and float(cells[4]) == spin
        assert float(cells[2]) == pytest.approx(club_mph * 0.44704, rel=1e-12)
        assert float(cells[3]) == pytest.approx(ball_mph * 0.44704, rel=1e-12)
    code, err = cli(capsys, "show", tmp_path / "utf16.csv")
    assert code == 2 and "not an impactlab result file" in err and "Traceback" not in err
    code, err = cli(capsys, "show", tmp_path)
    assert code == 2 and "is a folder, not a result file" in err
    code, err = cli(capsys, "show", "/dev/null")
    assert code == 2 and "is not a regular file" in err


def test_a_text_file_that_is_not_a_study_is_reported_by_its_name(tmp_path, capsys):
    path = tmp_path / "notes.txt"
    path.write_text("hello\n")
    code, err = cli(capsys, "run", path)
    assert code == 2 and f"{path}:1:" in err and "<text>" not in err


# -- size ------------------------------------------------------------------------------------------------------
def test_a_billion_cases_are_refused_before_any_value_is_made(tmp_path, capsys):
    study = write_study(tmp_path, **{"num: 4": "num: 1000000000"})
    start = time.process_time()  # CPU time: a loaded machine does not inflate it as it does the clock's
    code, err = cli(capsys, "run", study, "--plan")
    assert code == 2 and "1,000,000,000 cases, above the limit of 10,000,000" in err and "--max-cases" in err
    assert time.process_time() - start < 20  # making 10^9 scenes takes hours of CPU


def test_a_product_of_sweeps_is_refused_and_the_limit_can_be_raised(tmp_path, capsys):
    # two ranges of 4000: each fine alone, 16 million together
    study = write_study(tmp_path, **{"num: 4": "num: 4000",
                                     "contact.friction: [0.15, 0.25, 0.35]":
                                         "contact.friction: {start: 0.1, stop: 0.9, num: 4000}"})
    start = time.process_time()  # CPU time: a loaded machine does not inflate it as it does the clock's
    code, err = cli(capsys, "run", study, "--plan")
    assert code == 2 and "16,000,000 cases, above the limit" in err
    # ranges are checked at their ends, not value by value (16 million scenes would take hours of CPU)
    assert time.process_time() - start < 30
    small = write_study(tmp_path, "small.yaml")
    code, err = cli(capsys, "run", small, "--plan", "--max-cases", "5")
    assert code == 2 and "12 cases, above the limit of 5" in err
    code, _ = cli(capsys, "run", small, "--plan")  # the override lasts one command
    assert code == 0


def test_plan_shows_the_estimate_and_runaway_resolution_options_are_refused(tmp_path, capsys, old_result):
    code = main(["run", str(write_study(tmp_path)), "--plan"])
    out = capsys.readouterr().out
    assert code == 0 and "estimate: 12 case(s), 36 evaluation(s), about" in out and "limits:" in out
    study = write_study(tmp_path, "steps.yaml", **{"  - name: maw": "  - {name: maw, steps: 100000000}"})
    code, err = cli(capsys, "run", study, "-o", old_result)
    assert code == 2 and "the expert resolution options (springs x steps) alone take" in err
    assert old_result.read_bytes() == OLD
    code, err = cli(capsys, "run", write_study(tmp_path), "--plan", "--max-memory", "1KiB")
    assert code == 2 and "above the limit of 1.0 KiB" in err


# -- output paths ----------------------------------------------------------------------------------------------
def test_output_folder_is_refused_before_computing(tmp_path, capsys, monkeypatch):
    folder = tmp_path / "adir"
    folder.mkdir()
    monkeypatch.setattr("impactlab.cli.study_commands.run_study",
                        lambda *a, **k: pytest.fail("computed before refusing"))
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", folder)
    assert code == 2 and "is a folder; give a file name inside it" in err
    assert list(tmp_path.glob("adir.progress")) == [] and list(folder.iterdir()) == []


@pytest.mark.parametrize("args, fragment", [
    (["-o", "{tmp}/nodir/x.h5"], "folder {tmp}/nodir does not exist"),
    (["--outdir", "{old}"], "is a file, not a folder"),
    (["-o", "{tmp}/x.h5", "--plot", "{tmp}/nodir/x.png"], "folder {tmp}/nodir does not exist"),
    (["-o", "/dev/full"], "is not a regular file"),
])
def test_bad_output_paths_are_refused_before_running(tmp_path, capsys, old_result, monkeypatch, args, fragment):
    monkeypatch.setattr("impactlab.cli.study_commands.run_study",
                        lambda *a, **k: pytest.fail("computed before refusing"))
    args = [arg.format(tmp=tmp_path, old=old_result) for arg in args]
    code, err = cli(capsys, "run", write_study(tmp_path), *args)
    assert code == 2 and fragment.format(tmp=tmp_path) in err
    assert old_result.read_bytes() == OLD
    assert stat.S_ISCHR(os.stat("/dev/full").st_mode)  # the device is still a device


def test_export_and_fit_outputs_are_checked_first(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("impactlab.data.fit.fitting.fit", lambda *a, **k: pytest.fail("fitted before refusing"))
    code, err = cli(capsys, "fit", "wood2018", "--json", tmp_path)
    assert code == 2 and "is a folder; give a file name inside it, e.g." in err and ".json" in err
    code, err = cli(capsys, "export", tmp_path / "absent.h5", "-o", tmp_path / "nodir" / "x.json")
    assert code == 2 and "does not exist" in err


def test_study_names_cannot_leave_outdir_or_collide(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr("impactlab.cli.study_commands.run_study",
                        lambda *a, **k: pytest.fail("computed before refusing"))
    outdir = tmp_path / "deep" / "results"
    escaping = write_study(tmp_path, "escape.yaml", **{"name: compare-models": "name: ../../x"})
    code, err = cli(capsys, "run", escaping, "--outdir", outdir)
    assert code == 2 and "study name '../../x' cannot name a file" in err
    assert not (tmp_path / "x.h5").exists() and not (tmp_path / "deep" / "x.h5").exists()
    first, second = write_study(tmp_path, "one.yaml"), write_study(tmp_path, "two.yaml")
    code, err = cli(capsys, "run", first, second, "--outdir", outdir)
    assert code == 2 and "would both write" in err and "give the studies distinct names" in err
    assert not outdir.exists() or list(outdir.iterdir()) == []


@pytest.mark.slow
@pytest.mark.parametrize("mask, mode", [(0o022, 0o644), (0o027, 0o640)])
def test_result_files_honour_the_umask(tmp_path, capsys, mask, mode):
    previous = os.umask(mask)
    try:
        code, _ = cli(capsys, "run", write_study(tmp_path), "-o", tmp_path / "r.h5", "-q")
    finally:
        os.umask(previous)
    assert code == 0 and stat.S_IMODE((tmp_path / "r.h5").stat().st_mode) == mode


@pytest.fixture
def tiny_tmpfs(tmp_path):
    """A 256 KiB tmpfs (root only); the tests that need it skip elsewhere, their patched twins still run."""
    mount = tmp_path / "tiny"
    mount.mkdir()
    if subprocess.run(["mount", "-t", "tmpfs", "-o", "size=256k", "tmpfs", str(mount)],
                      capture_output=True).returncode != 0:
        pytest.skip("cannot mount a tmpfs here")
    yield mount
    subprocess.run(["umount", "-l", str(mount)], check=False)


def test_read_only_folder_is_an_environment_fault(tiny_tmpfs, tmp_path, capsys):
    old = tiny_tmpfs / "old.h5"
    old.write_bytes(OLD)
    subprocess.run(["mount", "-o", "remount,ro", str(tiny_tmpfs)], check=True)
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", old)
    assert code == 3 and "is not writable" in err
    assert old.read_bytes() == OLD


@pytest.mark.parametrize("free_kib, chunks_kept", [(4, 0), (24, 3)])
def test_a_real_full_disk_is_reported_and_damages_nothing(tiny_tmpfs, tmp_path, capsys, free_kib, chunks_kept):
    # tmpfs counts 4 KiB pages. 4 KiB: the progress manifest takes it, the first chunk does not fit; 24 KiB: the
    # manifest and the three chunks (4 KiB each) fit, the 31 KB result does not
    old = tiny_tmpfs / "old.h5"
    old.write_bytes(OLD)
    (tiny_tmpfs / "filler").write_bytes(b"\0" * ((256 - 4 - free_kib) * 1024))
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", old, "-q")
    assert code == 3 and "the disk is full" in err and str(tiny_tmpfs) in err  # and where
    assert old.read_bytes() == OLD
    assert not [path for path in tiny_tmpfs.rglob("*") if path.name.endswith((".part", ".tmp.npz"))]
    assert len(list(tiny_tmpfs.glob("old.h5.progress/*.npz"))) == chunks_kept  # kept for the next run


def _full_disk(*args, **kwargs):
    raise OSError(errno.ENOSPC, "No space left on device")


@pytest.mark.parametrize("where", ["chunk", "result"])
def test_disk_full_while_saving_leaves_no_temporary_and_the_old_file(tmp_path, capsys, old_result, monkeypatch,
                                                                     where):
    if where == "chunk":  # numpy writes part of the archive, then the disk is full
        def savez(stream, **arrays):
            stream.write(b"PK partial")
            _full_disk()
        monkeypatch.setattr("impactlab.run.execution.np.savez", savez)
    else:
        monkeypatch.setattr("impactlab.io.safe_output.os.fsync", _full_disk)
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", old_result, "-q")
    assert code == 3 and "the disk is full: free some space" in err
    assert old_result.read_bytes() == OLD
    leftovers = [path.name for path in tmp_path.rglob("*") if path.name.endswith((".part", ".tmp.npz"))]
    assert leftovers == []


# -- progress folder: lock and damaged chunks -----------------------------------------------------------------
def test_a_second_writer_is_refused_while_the_first_holds_the_folder(tmp_path, capsys, old_result):
    from impactlab.run.execution import ProgressStore

    with ProgressStore(tmp_path / "old.h5.progress", "someone else's", print, output=old_result):
        code, err = cli(capsys, "run", write_study(tmp_path), "-o", old_result, "-q")
    assert code == 3 and "another impactlab run is computing this result now" in err
    assert old_result.read_bytes() == OLD
    code, _ = cli(capsys, "run", write_study(tmp_path), "-o", old_result, "-q")  # free again once released
    assert code == 0 and not (tmp_path / "old.h5.progress").exists()


def test_a_truncated_chunk_is_reported_and_computed_again(tmp_path, capsys):
    study = write_study(tmp_path)
    reference = impactlab.run_study(study)
    folder = tmp_path / "r.h5.progress"
    impactlab.run_study(study, progress_folder=folder, chunk_size=4)  # no output: the chunks stay
    chunk = sorted(folder.glob("*.npz"))[1]
    chunk.write_bytes(chunk.read_bytes()[:100])
    code, err = cli(capsys, "run", study, "-o", tmp_path / "r.h5", "--chunk-size", "4")
    assert code == 0 and f"{chunk}: damaged" in err and "computing this chunk again" in err
    same_results(impactlab.open_results(tmp_path / "r.h5"), reference)


# -- interrupts and processes (real signals, so real processes) -----------------------------------------------
ANNULI = {"num: 4": "num: {num}", "  - name: maw": "  - {{name: maw, method: annuli}}"}


def _annuli_study(folder: Path, num: int) -> Path:
    return write_study(folder, "annuli.yaml", **{key: value.format(num=num) for key, value in ANNULI.items()})


def _start(*args, cwd):
    return subprocess.Popen([sys.executable, "-m", "impactlab", *map(str, args)], cwd=cwd, text=True,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            env={**os.environ, "MPLBACKEND": "Agg"})


def _wait_for(condition, seconds=60.0, what="the condition"):
    """Poll ``condition`` until it holds; the bound is generous (a loaded 2-core machine), never a fixed sleep."""
    deadline = time.monotonic() + seconds
    while not condition():
        assert time.monotonic() < deadline, f"timed out after {seconds:g} s waiting for {what}"
        time.sleep(0.05)


#: maw on annular strips at tolerance 1e-6 costs about 0.14 s per case on a quiet core: a chunk of 1500 cases
#: takes minutes, so a process that stops within STOP_BOUND seconds did not wait for its chunk, however loaded
#: the machine (the bounds below are generous for load and still far below a chunk's time)
LONG_CHUNK = {"tolerance": "1.0e-6", "cases": 1500}
STOP_BOUND = 30.0


def _long_study(folder: Path) -> Path:
    return write_study(folder, "long.yaml", **{"num: 4": "num: 1000",
                                                "  - name: maw": "  - {name: maw, method: annuli, tolerance: "
                                                                 f"{LONG_CHUNK['tolerance']}}}"})


def _cpu_seconds(pid: int) -> float:
    """CPU time (user + system) a process has used, from /proc (0 once it is gone)."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rpartition(")")[2].split()
    except (FileNotFoundError, ProcessLookupError):
        return 0.0
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@pytest.mark.slow
def test_ctrl_c_inside_a_compiled_kernel_stops_promptly_and_says_how_to_resume(tmp_path):
    # one chunk of 1500 annuli cases runs minutes inside numba, where Python cannot act on a signal: the
    # watchdog must end the process after its grace period (INTERRUPT_GRACE, 3 s), not when the chunk ends
    process = _start("run", _long_study(tmp_path), "-o", "r.h5", "--executor", "serial",
                     "--chunk-size", LONG_CHUNK["cases"], cwd=tmp_path)
    try:
        _wait_for(lambda: (tmp_path / "r.h5.progress" / "manifest.json").exists() or process.poll() is not None,
                  120, "the run to start its first chunk")
        assert process.poll() is None, process.communicate()[1]
        started = _cpu_seconds(process.pid)
        _wait_for(lambda: _cpu_seconds(process.pid) > started + 1.0, 120, "a second of computing in the chunk")
        process.send_signal(signal.SIGINT)
        # the evidence that it did not wait for its chunk (minutes) is an event, not the clock: the message below
        # says no chunk had finished (the timeout only keeps a hung process from hanging the suite)
        _, err = process.communicate(timeout=3 * STOP_BOUND)
        assert process.returncode == 130 and "Traceback" not in err and "SystemError" not in err
        # stopped inside its first chunk: no chunk had finished (before trust7 it said 'finished chunks are kept
        # in r.h5.progress', of a folder holding none)
        assert "interrupted; no chunk had finished and no result file was written or changed: run the same " \
               "command again" in err
        assert not list((tmp_path / "r.h5.progress").glob("*.npz"))
        assert not (tmp_path / "r.h5").exists()
    finally:
        if process.poll() is None:
            process.kill()
            process.communicate()


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text().split()[2] not in ("Z", "X")
    except (FileNotFoundError, ProcessLookupError):
        return False


def _children(pid: int) -> list[int]:
    return [int(p) for p in subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True).stdout.split()]


def _workers(pid: int) -> list[int]:
    """The pool's worker processes: the children forked from ``pid``, whose command line is the parent's (not
    multiprocessing's resource tracker, a child started with a command line of its own)."""
    try:
        own = Path(f"/proc/{pid}/cmdline").read_bytes()
    except (FileNotFoundError, ProcessLookupError):
        return []
    workers = []
    for child in _children(pid):
        try:
            if Path(f"/proc/{child}/cmdline").read_bytes() == own:
                workers.append(child)
        except (FileNotFoundError, ProcessLookupError):
            pass
    return workers


def _start_long_pool_run(folder: Path):
    """A run whose two process workers each compute one chunk of minutes of compiled code, both started."""
    process = _start("run", _long_study(folder), "-o", "r.h5", "--executor", "processes", "--workers", "2",
                     "--chunk-size", LONG_CHUNK["cases"], cwd=folder)
    _wait_for(lambda: len(_workers(process.pid)) >= 2 or process.poll() is not None, 120, "two pool workers")
    assert process.poll() is None, process.communicate()[1]
    workers = _workers(process.pid)
    # each worker inside its chunk: it has computed for a while (a forked process's CPU time starts at 0)
    _wait_for(lambda: all(_cpu_seconds(pid) > 0.5 for pid in workers), 120, "both workers computing")
    return process, workers


def _stop_everything(process, workers):
    """A failing test must not leave its processes behind."""
    for pid in workers:
        if _alive(pid):
            os.kill(pid, signal.SIGKILL)
    if process.poll() is None:
        process.kill()
    process.communicate()


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_signal_to_the_parent_stops_process_workers_at_once(tmp_path, signum):
    process, workers = _start_long_pool_run(tmp_path)
    try:
        process.send_signal(signum)  # to the parent alone, as kill does: the parent must stop its workers
        # the running chunks (minutes each) are not waited for, nor the queued ones: the parent ends (an event;
        # the timeout only keeps a hung process from hanging the suite) and no result was written
        _, err = process.communicate(timeout=3 * STOP_BOUND)
        assert not (tmp_path / "r.h5").exists()
        assert process.returncode == 130 and "Traceback" not in err and "run the same command again" in err
        _wait_for(lambda: not any(_alive(pid) for pid in workers), STOP_BOUND, "the workers to be gone")
    finally:
        _stop_everything(process, workers)


@pytest.mark.slow
def test_kill_9_of_the_parent_leaves_no_orphan_worker(tmp_path):
    process, workers = _start_long_pool_run(tmp_path)
    assert len(workers) == 2
    try:
        process.kill()
        process.wait()  # not communicate(): orphans would hold its pipes open
        # gone long before their chunk (minutes) would end: they die with the parent, not when the chunk is done
        _wait_for(lambda: not any(_alive(pid) for pid in workers), STOP_BOUND, "the orphaned workers to be gone")
    finally:
        _stop_everything(process, workers)


@pytest.mark.slow
def test_kill_9_then_resume_equals_an_uninterrupted_run(tmp_path, capsys, monkeypatch):
    study = _annuli_study(tmp_path, 200)
    process = _start("run", study, "-o", "r.h5", "--executor", "serial", "--chunk-size", "30", cwd=tmp_path)
    _wait_for(lambda: len(list(tmp_path.glob("r.h5.progress/m0-*.npz"))) >= 2)
    process.kill()
    process.communicate()
    # finished chunks only: a kill during a save leaves a hidden temporary (.NAME.tmp.npz), which is not a chunk
    kept = len([path for path in tmp_path.glob("r.h5.progress/*.npz") if not path.name.startswith(".")])
    assert not (tmp_path / "r.h5").exists() and kept >= 2
    computed = []
    real = impactlab.run.execution.compute_chunk

    def counting(model, inputs, outputs, chunk, *rest):  # rest: the study's plan, paths flag
        computed.append(chunk)
        return real(model, inputs, outputs, chunk, *rest)

    monkeypatch.setattr("impactlab.run.execution.compute_chunk", counting)
    code, _ = cli(capsys, "run", study, "-o", tmp_path / "r.h5", "--executor", "serial", "--chunk-size", "30")
    assert code == 0 and len(computed) == 3 * 600 // 30 - kept  # only the missing chunks
    monkeypatch.setattr("impactlab.run.execution.compute_chunk", real)
    same_results(impactlab.open_results(tmp_path / "r.h5"), impactlab.run_study(study, chunk_size=600))


# -- the other commands ----------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def result_file(tmp_path_factory):
    folder = tmp_path_factory.mktemp("result")
    path = folder / "r.h5"
    assert main(["run", str(write_study(folder)), "-o", str(path), "-q"]) == 0
    return path


def test_dependency_warnings_are_shown_and_never_fatal(tmp_path, capsys, monkeypatch):
    import warnings

    import h5py

    plain = tmp_path / "plain.h5"
    with h5py.File(plain, "w") as handle:
        handle["x"] = [1, 2, 3]
    # h5netcdf warned of the phony dimensions of such a file until impactlab asked for them (trust7): the
    # library's warning is injected where it came from, the file's opening
    opened = xr.open_dataset

    def open_with_a_warning(*args, **kwargs):
        warnings.warn("The 'phony_dims' kwarg now defaults to 'access'", UserWarning, stacklevel=2)
        return opened(*args, **kwargs)

    monkeypatch.setattr(xr, "open_dataset", open_with_a_warning)
    code, err = cli(capsys, "show", plain)
    # the library's warning on reading it is shown in one line and is not what ends the command: the file is
    # refused because impactlab did not write it
    assert code == 2 and "impactlab: warning from" in err and "formatwarning" not in err
    assert "not an impactlab result" in err


def test_plot_refuses_names_the_file_does_not_hold(result_file, tmp_path, capsys):
    png = tmp_path / "p.png"
    code, err = cli(capsys, "plot", result_file, "-v", "nonsense", "-o", png)
    assert code == 2 and "-v: expected a scalar output held by the file, got nonsense" in err and not png.exists()
    for x in ("nothing", "model"):
        code, err = cli(capsys, "plot", result_file, "--x", x, "-o", png)
        assert code == 2 and f"--x: expected a sweep dimension of the file (or a scalar output), got {x}" in err
        assert "Choices: angle, friction" in err and not png.exists()


def test_a_declared_plot_of_an_unknown_model_is_refused_before_the_run(tmp_path, capsys):
    plots = "plots: [{y: launch_ratio, x: angle, select: {model: maww}}]\noutputs:"
    study = write_study(tmp_path, **{"outputs:": plots})
    code, err = cli(capsys, "run", study, "-o", tmp_path / "r.h5")
    assert code == 2 and "select.model: expected a model of the study, got maww" in err
    assert not (tmp_path / "r.h5").exists()


@pytest.mark.parametrize("args, fragment", [
    (["--workers", "-2"], "argument --workers: expected a whole number >= 1, got -2"),
    (["--chunk-size", "0"], "argument --chunk-size: expected a whole number >= 1, got 0"),
    (["--max-memory", "lots"], "argument --max-memory: expected a size such as 4GiB"),
])
def test_bad_options_are_refused_at_once(tmp_path, capsys, args, fragment):
    with pytest.raises(SystemExit) as stop:  # argparse's own exit: status 2 and one usage line
        main(["run", str(write_study(tmp_path)), *args])
    assert stop.value.code == 2 and fragment in capsys.readouterr().err


def test_convergence_refuses_zero_repeats(tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        main(["convergence", str(write_study(tmp_path)), "--repeats", "0"])
    assert stop.value.code == 2 and "expected a whole number >= 1, got 0" in capsys.readouterr().err


def test_schedulers_bad_or_unreachable_are_said_quickly(tmp_path, capsys, monkeypatch, old_result):
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", old_result, "--scheduler", "notaurl")
    assert code == 2 and "--scheduler: expected a dask scheduler address" in err
    monkeypatch.setattr("impactlab.run.execution.SCHEDULER_TIMEOUT", 1)
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", old_result, "--scheduler", "tcp://127.0.0.1:9")
    assert code == 3 and "no dask scheduler answered within 1 s" in err
    assert old_result.read_bytes() == OLD  # "within 1 s" is the scheduler timeout's event, said above
    assert not (tmp_path / "old.h5.progress").exists()  # nothing computed, nothing left to resume


def test_debug_shows_the_traceback_and_internal_errors_say_so(tmp_path, capsys, monkeypatch):
    def broken(*args, **kwargs):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr("impactlab.cli.study_commands.run_study", broken)
    code, err = cli(capsys, "run", write_study(tmp_path), "-o", tmp_path / "r.h5")
    assert code == 1 and "internal error: ZeroDivisionError: a bug (run again with --debug" in err
    code = main(["--debug", "run", str(write_study(tmp_path)), "-o", str(tmp_path / "r.h5")])
    assert code == 1 and "Traceback" in capsys.readouterr().err


# -- silent misreadings ----------------------------------------------------------------------------------------
def test_hertz_spin_is_turns_per_second(tmp_path):
    study = impactlab.load_study(study_text(**{"spin: 0 rpm": "spin: 50 Hz"}))
    assert study.scene.impact.spin * 60 / (2 * np.pi) == pytest.approx(3000)
    assert impactlab.load_study(study_text(**{"spin: 0 rpm": "spin: 300 rad/s"})).scene.impact.spin == 300


@pytest.mark.parametrize("replace, fragment", [
    ({"angle: 15 deg": 'angle: "50 %"'}, "impact.angle: expected an angle"),
    ({"friction: 0.4": "friction: 30 deg"}, "an angle unit does not belong here"),
    ({"[0.15, 0.25, 0.35]": "[0.15, 0.25, 0.25]"}, "sweep.contact.friction[2]: expected distinct values"),
    ({"start: 1 deg, stop: 60 deg": "start: 5 deg, stop: 5 deg"}, "a range whose start and stop differ"),
])
def test_misreadings_are_refused(tmp_path, capsys, replace, fragment):
    code, err = cli(capsys, "run", write_study(tmp_path, **replace), "--plan")
    assert code == 2 and fragment in err


def test_fields_changing_together_may_repeat_a_value():
    text = study_text(**{"  impact.angle: {start: 1 deg, stop: 60 deg, num: 4}":
                         "  club:\n    impact.angle: [10 deg, 20 deg]\n    impact.speed: [40 m/s, 40 m/s]"})
    assert impactlab.load_study(text).n_cases == 6


DELIVERY = """name: export-me
ball: {preset: urethane_tour}
face: {rigid: true}
contact: {friction: 0.4, restitution: 0.8}
delivery: {club_speed: 112 mph, path: 0 deg, face_angle: 0 deg, attack_angle: -1 deg, dynamic_loft: 13 deg}
sweep:
  delivery.attack_angle: [-1 deg, 5 deg]
  delivery.dynamic_loft: [13 deg, 3 deg]
models: [rigid_coulomb]
outputs: [ball_speed, vertical_launch_angle, horizontal_launch_angle, spin_rate, spin_axis]
"""


def test_export_warns_of_shots_no_club_makes(tmp_path, capsys):
    fixed = tmp_path / "fixed.yaml"
    fixed.write_text(DELIVERY)
    assert main(["run", str(fixed), "-o", str(tmp_path / "fixed.h5"), "-q"]) == 0
    code, err = cli(capsys, "export", tmp_path / "fixed.h5", "-o", tmp_path / "shots.json")
    assert code == 0 and "smash factor above 1.6" in err and "spin forwards" in err
    heavy = tmp_path / "heavy.yaml"  # a real head mass and a loft above the attack: nothing to say
    heavy.write_text(DELIVERY.replace("{rigid: true}", "{rigid: true, mass: 200 g}")
                     .replace("[13 deg, 3 deg]", "[13 deg, 15 deg]"))
    assert main(["run", str(heavy), "-o", str(tmp_path / "heavy.h5"), "-q"]) == 0
    code, err = cli(capsys, "export", tmp_path / "heavy.h5", "-o", tmp_path / "shots.json")
    assert code == 0 and "warning" not in err


# -- provenance ------------------------------------------------------------------------------------------------
def test_results_record_dependency_versions_commit_and_integer_flags(result_file):
    import h5py

    attrs = impactlab.open_results(result_file).attrs
    for package in ("numba", "scipy", "h5py", "pint", "numpy", "xarray", "h5netcdf"):
        assert attrs[f"{package}_version"] not in ("", "not installed")
    head = subprocess.run(["git", "-C", str(ROOT), "rev-parse", "HEAD"], capture_output=True, text=True)
    if head.returncode == 0:
        assert attrs["git_commit"].startswith(head.stdout.strip())
    with h5py.File(result_file) as handle:
        validity = handle["validity"]
        assert validity.dtype.kind == "i"
        from impactlab.model.diagnostics import FLAGS

        assert list(validity.attrs["flag_values"]) == sorted(FLAGS) and all(  # one bit each, as CF flag masks
            bit & (bit - 1) == 0 for bit in FLAGS)
        assert validity.attrs["flag_meanings"].split()[0] == "large_contact"


def test_a_reader_that_goes_away_ends_the_command_quietly(monkeypatch, capsys):
    """``impactlab models | head``: the pipe closes under the writer; no traceback, no error line, status 141."""
    from impactlab.cli import main

    class ClosedPipe:
        def write(self, text):
            raise BrokenPipeError(errno.EPIPE, "Broken pipe")

        def flush(self):
            raise BrokenPipeError(errno.EPIPE, "Broken pipe")

    monkeypatch.setattr(sys, "stdout", ClosedPipe())
    code = main(["models", "--json"])
    monkeypatch.undo()
    assert code == 141 and capsys.readouterr().err == ""


def test_a_broken_pipe_that_is_not_stdout_is_an_error(monkeypatch, capsys):
    """Only a closed stdout ends quietly: a peer's pipe breaking is said, with exit 3."""
    from impactlab import cli as cli_module

    def peer_gone(args):
        raise BrokenPipeError(errno.EPIPE, "Broken pipe", "a worker's pipe")

    monkeypatch.setattr(cli_module, "_cmd_models", peer_gone)
    code = cli_module.main(["models"])
    err = capsys.readouterr().err
    assert code == 3 and "error:" in err and "Traceback" not in err


def test_progress_saved_in_another_chunk_layout_is_computed_again(tmp_path, monkeypatch):
    """A progress folder from a version whose chunks lack a field is recomputed, never a crash."""
    import json

    from impactlab.run import execution

    study = write_study(tmp_path)
    folder = tmp_path / "progress"
    first = impactlab.run_study(str(study), executor="serial", progress_folder=folder)
    for path in folder.glob("*.npz"):  # the layout before CHUNK_FORMAT 2: no "missing" in the metadata
        with np.load(path) as archive:
            arrays = {name: archive[name] for name in archive.files}
        meta = json.loads(str(arrays.pop("__meta__")))
        del meta["missing"]
        np.savez(path, __meta__=np.array(json.dumps(meta)), **arrays)
    messages = []
    again = impactlab.run_study(str(study), executor="serial", progress_folder=folder, progress=messages.append)
    assert sum("damaged" in text for text in messages) == 3
    same_results(first, again)
    # and a new layout changes the fingerprint, so an older folder is started over as a whole
    before = execution.fingerprint(impactlab.load_study(str(study)), ["launch_angle"])
    monkeypatch.setattr(execution, "CHUNK_FORMAT", execution.CHUNK_FORMAT + 1)
    assert execution.fingerprint(impactlab.load_study(str(study)), ["launch_angle"]) != before
