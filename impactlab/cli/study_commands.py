"""The commands on studies and their result files: ``run``, ``models``, ``show``, ``plot``, ``convergence``,
``paper`` and ``export``.

Each ``_cmd_*`` function takes the parsed arguments of its sub-command (:func:`impactlab.cli.build_parser`) and
returns the exit status; bad input raises an :mod:`impactlab.errors` error, which
:func:`impactlab.run.faults.run_command` turns into one message and exit status 2.
"""

from __future__ import annotations

import contextlib
import functools
import json
import re
import sys
import warnings
from pathlib import Path

import numpy as np
import xarray as xr

from impactlab.cli.data_commands import export_session
from impactlab.data.convergence import LADDER, work_precision
from impactlab.data.sessions.export import is_session
from impactlab.errors import FieldError, StudyError, shown
from impactlab.io.gspro_connect import parse_address, send_shots
from impactlab.io.interchange import checked_shots, write_gspro
from impactlab.io.results import open_results, write_results
from impactlab.io.stored import check_stored
from impactlab.io.safe_output import (JSON_SUFFIXES, PICTURE_SUFFIXES, REPORT_SUFFIXES, RESULT_SUFFIXES,
                                      check_outdir, check_output, name_in, refuse_clashes)
from impactlab.model.diagnostics import ValidityWarning, messages
from impactlab.model.registry import available
from impactlab.plot.analysis import plot_sensitivity, plot_work_precision
from impactlab.plot.figures import (TRAJECTORY_LAUNCH, check_shot_files, draw_declared, plot_histories, plot_results,
                                    plot_trajectories)
from impactlab.plot.paper import report
from impactlab.run.faults import set_interrupt_hint
from impactlab.run.runner import plan_study, run_study
from impactlab.study.core import load_study
from impactlab.study.limits import check as check_limits
from impactlab.vocabulary import FLIGHT_OUTPUTS, MODEL_DIM, is_history, is_scalar


def _cmd_run(args) -> int:
    # options that contradict each other: one of them would be dropped without a word
    if args.output and args.outdir:
        raise StudyError(f"-o {args.output} and --outdir {args.outdir}: -o names the result file, --outdir the folder "
                         "of STUDY_NAME.h5 files; give one (-o FOLDER/FILE.h5 puts one result in a folder)")
    if args.scheduler and args.executor not in ("auto", "dask"):
        raise StudyError(f"--scheduler runs the cases on a dask cluster, --executor {args.executor} here: give one")
    if args.workers and args.executor == "serial":
        raise StudyError("--workers counts worker processes, and --executor serial runs in this one: give one")
    if args.scheduler:
        _check_scheduler(args.scheduler)
        args.executor = "dask"
    if args.output and len(args.study) > 1:
        raise StudyError("-o/--output names one result file; with several studies use --outdir")
    studies = [load_study(Path(path)) for path in args.study]  # every file is checked before anything runs
    for study in studies:  # and the shot files its figures draw beside the curves
        check_shot_files(study)
    say = (lambda text: None) if args.quiet else (lambda text: print(text, file=sys.stderr))
    if args.plan:
        for study in studies:
            print(plan_study(study).describe())
        return 0
    # every output is checked before the first case runs: a bad path found after an hour loses the hour
    outdir = check_outdir(args.outdir) if args.outdir else None
    outputs = [Path(args.output) if args.output else name_in(outdir or Path("."), study.name, ".h5")
               for study in studies]
    refuse_clashes([(f"{study.file} (name {study.name!r})", output) for study, output in zip(studies, outputs)])
    # every study planned (limits checked, models planned) before the first runs; the run takes its plan
    plans = [plan_study(study) for study in studies]
    for study, plan in zip(studies, plans):
        _say_unused(study, plan)
    if outdir:
        outdir.mkdir(parents=True, exist_ok=True)
    for output in outputs:
        check_output(output, reads=args.study, formats=RESULT_SUFFIXES)
        if args.plot not in (None, True):
            _picture(args.plot, reads=[*args.study, output])
    for study, output, plan in zip(studies, outputs, plans):
        # finished chunks wait here until the result file is complete; a killed run resumes from them
        progress_folder = output.with_name(f"{output.name}.progress")
        set_interrupt_hint(functools.partial(_resume_hint, progress_folder))
        with _validity_notes() as notes:
            dataset = run_study(study, progress=say, executor=args.executor, workers=args.workers,
                                scheduler=args.scheduler, chunk_size=args.chunk_size,
                                progress_folder=progress_folder, show_progress=not args.quiet, output=output,
                                plan=plan)
        say(f"wrote {output}")
        _summarise_notes(notes, output, full=args.notes)
        if args.plot:
            for picture in _draw(dataset, output, None if args.plot is True else Path(args.plot)):
                say(f"wrote {picture}")
    return 0


def _say_unused(study, plan) -> None:
    """What a study asks for and will not get, said before it runs (the run would exit 0 with it all NaN or unused):
    an output every model leaves NaN, and air conditions no flight output reads."""
    where = study.file or study.name
    if plan.models:
        nowhere = set.intersection(*(set(output_plan.missing) for _, output_plan in plan.models))
        for name in (output for output in study.outputs if output in nowhere):
            reason = dict(plan.models[0][1].missing)[name]
            print(f"impactlab: warning: {where}: {name} will be NaN for every model ({reason}); `impactlab run "
                  f"--plan` says what each model gives", file=sys.stderr)
    if study.scene.conditions is not None and not any(name in FLIGHT_OUTPUTS for name in study.all_outputs):
        print(f"impactlab: warning: {where}: its conditions (the air) are read only by the flight outputs "
              f"({', '.join(FLIGHT_OUTPUTS)}), and it asks for none", file=sys.stderr)


def _resume_hint(progress_folder: Path) -> str:
    """What an interrupted run kept: its finished chunks, or (none had finished, the folder is gone) nothing."""
    if progress_folder.is_dir() and any(path.suffix == ".npz" for path in progress_folder.iterdir()):
        return (f"finished chunks are kept in {progress_folder}: run the same command again to compute only the "
                "rest")
    return "no chunk had finished and no result file was written or changed: run the same command again"


def _picture(path, reads) -> Path:
    """A picture's path, checked before any work: writable, a picture's suffix, none of the files read."""
    return check_output(Path(path), what="picture", suffix=".png", formats=PICTURE_SUFFIXES, reads=reads)


@contextlib.contextmanager
def _validity_notes():
    """Collect the run's ValidityWarnings instead of printing each: a golf study raises the same known notes
    every time (the contact is larger than Hertz's small-contact assumption, ball and face differ in Dundurs'
    beta), and repeated on every run they carry no signal. Every other warning is shown as it comes."""
    notes: list[str] = []
    shown = warnings.showwarning

    def collect(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, ValidityWarning):
            notes.append(str(message))
        else:
            shown(message, category, filename, lineno, file, line)

    warnings.showwarning = collect
    try:
        yield notes
    finally:
        warnings.showwarning = shown


def _summarise_notes(notes: list[str], output: Path, *, full: bool) -> None:
    """One line per result file for its validity notes (all of them with ``--notes``), on stderr."""
    if not notes:
        return
    if full:
        for text in notes:
            print(f"impactlab: note: {text}", file=sys.stderr)
        return
    print(f"impactlab: {len(notes)} validity note(s) on {output} (cases outside a model's assumptions); "
          f"`impactlab show {output}` lists them, or run with --notes", file=sys.stderr)


#: dask scheduler addresses: PROTOCOL://HOST[:PORT] or HOST:PORT
_SCHEDULER = re.compile(r"^(?:(tcp|tls|inproc|ucx|ws|wss)://[^\s/:]+(?::\d+)?|[A-Za-z0-9.\-]+:\d+)/?$")


def _check_scheduler(address: str) -> None:
    if not _SCHEDULER.match(address):
        raise FieldError("--scheduler", "a dask scheduler address such as tcp://HOST:8786 or HOST:8786", address)


def _draw(dataset, output: Path, png: Path | None) -> list[Path]:
    """The standard pictures of a result: scalar outputs, and each history if there is one."""
    png = png or output.with_suffix(".png")
    if dataset.attrs.get("study_type") == "sensitivity":
        return plot_sensitivity(dataset, png)
    if dataset.attrs.get("plots", "[]") not in ("", "[]"):
        pictures = draw_declared(dataset, png.parent, png.stem)
    else:
        pictures = [plot_results(dataset, png)]
        for name in dataset.data_vars:
            if is_history(name):
                pictures.append(plot_histories(dataset, png.with_name(f"{png.stem}_{name}.png"), name))
    if _has_flight(dataset):  # a golf result that asked for the flight: its paths, side and top
        pictures.append(plot_trajectories(dataset, png.with_name(f"{png.stem}_trajectories.png")))
    return pictures


def _has_flight(dataset) -> bool:
    return any(name in dataset.data_vars for name in FLIGHT_OUTPUTS) and all(
        name in dataset.data_vars for name in TRAJECTORY_LAUNCH) and bool(dataset["ball_speed"].notnull().any())


def _cmd_models(args) -> int:
    descriptions = [model.describe() for model in available().values()]
    if args.json:
        print(json.dumps(descriptions, indent=2))
        return 0
    for info in descriptions:
        print(f"{info['name']}: {info['label']}")
        print(f"  requires: {', '.join(info['requires'])}")
        if info["optional_inputs"]:
            print(f"  optional: {', '.join(info['optional_inputs'])}")
        print(f"  provides: {', '.join(info['provides'])} (+ launch, spin, velocities, beta, energy derived "
              "from the impulses)" if "normal_impulse" in info["provides"] else "")
        if info["options"]:
            print("  options:  " + ", ".join(f"{key}={value!r}" for key, value in info["options"].items()))
        capabilities = info["capabilities"]
        print("  capabilities: " + ", ".join(
            text for key, text in (("has_tolerance", "a tolerance option (work-precision studies)"),
                                   ("provides_histories", "force histories"),
                                   ("solves_3d", "3-D contacts (free heads struck off-centre, curved faces)"))
            if capabilities[key]) if any(capabilities.values()) else "  capabilities: none declared")
    return 0


def _cmd_show(args) -> int:
    dataset = open_results(args.file)
    print(f"{shown(args.file)}: study {dataset.attrs.get('study_name', '?')!r}, "
          f"impactlab {dataset.attrs.get('impactlab_version', '?')}, created {dataset.attrs.get('created', '?')}")
    for dim, size in dataset.sizes.items():
        coord = dataset[dim]
        if dim == "model" or coord.dtype.kind not in "iuf":  # names (models, labels, outputs, parameters)
            print(f"  {shown(dim):<10} {size:>5}  {', '.join(shown(value) for value in coord.values)}")
        else:
            print(f"  {dim:<10} {size:>5}  {float(coord.min()):g} .. {float(coord.max()):g} "
                  f"{coord.attrs.get('units', '')}")
    print("variables:")
    for name, variable in dataset.data_vars.items():
        missing = f"  (NaN for {variable.attrs['missing'].split(':')[0]}...)" if "missing" in variable.attrs else ""
        print(f"  {shown(name):<24} [{shown(variable.attrs.get('units', ''))}] "
              f"({', '.join(shown(dim) for dim in variable.dims)}){shown(missing)}")
    if dataset.attrs.get("study_type") == "sensitivity":
        print(f"sensitivity ({dataset.attrs['sampler']}, {dataset.attrs['analyser']}, SALib "
              f"{dataset.attrs['salib_version']}): {dataset.attrs['sensitivity']}")
    print("models:")
    for model in json.loads(dataset.attrs.get("models", "[]")):  # a file's text: shown escaped
        print(f"  {shown(model['id'])}: {shown(model['name'])} {json.dumps(model['options'])}")
    _print_validity_notes(dataset)
    return 0


def _print_validity_notes(dataset) -> None:
    if dataset.attrs.get("head_cor"):  # the club the models ran, not a case outside a model's assumptions
        print(f"note: {dataset.attrs['head_cor']}")
    notes = messages(dataset)
    if notes:
        print("validity notes (cases outside a model's assumptions; the `validity` variable flags each case):")
        for text in notes:
            print(f"  {text}")


def _cmd_plot(args) -> int:
    dataset = open_results(args.file)
    histories = [str(name) for name in dataset.data_vars if "time" in dataset[name].dims]
    if args.history and args.history not in histories:
        raise FieldError("--history", "a history held by the file", args.history, choices=histories)
    scalars = [str(name) for name in dataset.data_vars if is_scalar(str(name))]
    for name in args.variables or []:  # an unknown name would draw an empty picture and say "wrote"
        if name not in scalars:
            raise FieldError("-v", "a scalar output held by the file", name, choices=scalars)
    drawable = [name for name in (args.variables or scalars)
                if not bool(dataset[name].isnull().all())]
    if (args.variables or args.x or args.output) and not args.history and not drawable:
        raise FieldError("-v", "an output with at least one computed value", ", ".join(args.variables or scalars))
    if args.x is not None:
        dims = [str(dim) for dim in dataset.dims if dim not in (MODEL_DIM, "time")]
        if args.x not in dims + scalars:
            raise FieldError("--x", "a sweep dimension of the file (or a scalar output)", args.x,
                             choices=dims + scalars)
    if args.trajectories:
        default = Path(args.file).with_name(f"{Path(args.file).stem}_trajectories.png")
        output = _picture(args.output or default, reads=[args.file])
        for note in check_stored(dataset, args.file, aerodynamics_needed=True):  # a stored result is an input
            print(f"impactlab: note: {note}", file=sys.stderr)
        print(f"wrote {plot_trajectories(dataset, output)}", file=sys.stderr)
        return 0
    output = _picture(args.output or Path(args.file).with_suffix(".png"), reads=[args.file])
    if args.history:
        plot_histories(dataset, output, args.history)
    elif args.variables or args.x or args.output:
        plot_results(dataset, output, outputs=args.variables or None, x=args.x)
    else:
        for picture in _draw(dataset, Path(args.file), None):
            print(f"wrote {picture}", file=sys.stderr)
        return 0
    print(f"wrote {output}", file=sys.stderr)
    return 0


def _cmd_convergence(args) -> int:
    repeated = sorted({value for value in args.tolerances or () if args.tolerances.count(value) > 1})
    if repeated:  # two points of the ladder at one coordinate
        raise StudyError(f"--tolerances: each value once (a ladder point per tolerance), got {repeated[0]:g} twice")
    study = load_study(Path(args.study))
    check_limits(study)  # the study runs once per tolerance: refuse one too big for a single run
    say = (lambda text: None) if args.quiet else (lambda text: print(text, file=sys.stderr))
    output = check_output(args.output or name_in(Path("."), study.name, "-work-precision.h5"), reads=[args.study],
                          formats=RESULT_SUFFIXES)
    if args.plot not in (None, True):
        _picture(args.plot, reads=[args.study, output])
    dataset = work_precision(study, tolerances=args.tolerances or LADDER, repeats=args.repeats, progress=say)
    write_results(dataset, output)
    say(f"wrote {output}")
    if args.plot:
        picture = output.with_suffix(".png") if args.plot is True else Path(args.plot)
        plot_work_precision(dataset, picture)
        say(f"wrote {picture}")
    if not args.quiet:
        print(work_precision_table(dataset))
    return 0


def work_precision_table(dataset: xr.Dataset) -> str:
    """Markdown table: per model entry and tolerance, wall time per impact and the error of each output."""
    outputs = list(dataset.output.values)
    lines = ["| model | tolerance | us per impact | " + " | ".join(f"{name} error" for name in outputs) + " |",
             "|---|---|---|" + "---|" * len(outputs)]
    for model in dataset.model.values:
        for tolerance in dataset.tolerance.values:
            # a dict, because sel() has a keyword argument of its own called tolerance
            seconds = float(dataset.wall_time.sel({"model": model, "tolerance": tolerance}))
            if not np.isfinite(seconds):
                continue
            errors = [float(dataset.error.sel({"model": model, "tolerance": tolerance, "output": name}))
                      for name in outputs]
            if all(e == 0 for e in errors) and tolerance != dataset.tolerance.values[0]:
                continue  # a closed-form model: one row is enough
            lines.append(f"| {model} | {tolerance:g} | {1e6 * seconds:.1f} | "
                         + " | ".join(f"{e:.1e}" if e else "exact" for e in errors) + " |")
    return "\n".join(lines)


def _cmd_paper(args) -> int:
    results = Path(args.results)
    if not results.is_dir():
        raise StudyError(f"{results}: no such folder of results (run studies/paper/*.yaml into it first)")
    output = check_output(args.output, what="report", suffix=".md", reads=sorted(results.glob("*.h5")),
                          formats=REPORT_SUFFIXES)
    report(results, output, Path(args.figures) if args.figures else output.parent / "figures")
    print(f"wrote {output}", file=sys.stderr)
    return 0


def _checked_result(path) -> xr.Dataset:
    """A result file to export, its launch values, units, air and aerodynamic model checked (io.stored)."""
    dataset = open_results(path)
    for note in check_stored(dataset, path, aerodynamics_needed=False):
        print(f"impactlab: note: {note}", file=sys.stderr)
    return dataset


def _cmd_export(args) -> int:
    if is_session(args.file):  # measured shots of a launch-monitor export, not a result's
        return export_session(args)
    if args.strict or args.show_rows:
        raise StudyError("--strict and --show-rows apply to a session file's rows; a result file has none")
    if args.gspro is not None:
        host, port = parse_address(args.gspro)  # a bad address is said before the file is read
        shots = checked_shots(_checked_result(args.file), model=args.model, device_id=args.device_id)
        say = (lambda text: print(text, file=sys.stderr))
        if not shots:
            say("no shot to send: no case of the result has every ball value (all NaN)")
            return 0
        replies = send_shots(shots, host, port, timeout=args.timeout, progress=say)
        if replies.set_aside:  # a reply that answered no shot: which 200 answers which shot is not certain
            say(f"sent {len(shots)} shot(s) to GSPro Connect at {args.gspro}: each was answered with Code 200, and "
                f"{len(replies.set_aside)} more reply(ies) answered no shot (set aside, said above); if one of them "
                "was in fact a shot's answer, a shot's own 200 was taken for the next one: check GSPro's shot list")
        else:
            say(f"sent {len(shots)} shot(s) to GSPro Connect at {args.gspro}: every one accepted "
                f"(the last: {replies[-1].describe()})")
        return 0
    check_output(args.output, what="shot file", suffix=".json", reads=[args.file], formats=JSON_SUFFIXES)
    count = write_gspro(_checked_result(args.file), args.output, model=args.model, device_id=args.device_id)
    print(f"wrote {count} GSPro Open Connect shots to {args.output}", file=sys.stderr)
    return 0
