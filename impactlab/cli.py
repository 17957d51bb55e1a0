"""The ``impactlab`` command line: run studies, list models, show and plot result files.

Bad input ends with one message on stderr (what, where, expected, given,
choices) and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import re
import sys
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import xarray as xr

from impactlab._version import __version__
from impactlab.data.convergence import LADDER, work_precision
from impactlab.data.validation import DATASETS, get_dataset, load_dataset_study
from impactlab.data.validation import errors as dataset_errors
from impactlab.data.validation.benchmark_report import describe as describe_benchmark
from impactlab.data.validation.benchmark_report import format_table, over_budget
from impactlab.data.validation.benchmarks import BENCHMARKS, benchmark_errors
from impactlab.errors import FieldError, StudyError
from impactlab.io.gspro_connect import parse_address, send_shots
from impactlab.io.interchange import checked_shots, write_gspro
from impactlab.io.results import open_results, write_results
from impactlab.io.safe_output import check_outdir, check_output, name_in, refuse_clashes, write_atomically
from impactlab.model.registry import available
from impactlab.plot.analysis import plot_sensitivity, plot_work_precision
from impactlab.plot.figures import draw_declared, plot_histories, plot_results
from impactlab.plot.paper import report
from impactlab.run.faults import EXIT_BAD_INPUT, EXIT_ENVIRONMENT, EXIT_INTERRUPTED  # noqa: F401  (the exit statuses)
from impactlab.run.faults import run_command, set_interrupt_hint
from impactlab.run.runner import plan_study, run_study
from impactlab.study import limits
from impactlab.scene.clubs import user_clubs
from impactlab.study.club_specs import read_club_spec
from impactlab.study.core import load_study
from impactlab.study.limits import check as check_limits
from impactlab.study.limits import parse_size
from impactlab.vocabulary import MODEL_DIM, OUTPUTS, is_history, is_scalar


def _count(text: str) -> int:
    """argparse type: a whole number >= 1 (workers, cases per chunk, repeats), refused at once otherwise."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 1, got {value}")
    return value


def _size(text: str) -> int:
    try:
        return parse_size(text)
    except ValueError as exc:
        raise argparse.ArgumentTypeError(f"expected {exc}") from None


def _cmd_run(args) -> int:
    if args.scheduler:
        _check_scheduler(args.scheduler)
        args.executor = "dask"
    if args.output and len(args.study) > 1:
        raise StudyError("-o/--output names one result file; with several studies use --outdir")
    studies = [load_study(Path(path)) for path in args.study]  # every file is checked before anything runs
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
    if outdir:
        outdir.mkdir(parents=True, exist_ok=True)
    for output in outputs:
        check_output(output)
        if args.plot not in (None, True):
            check_output(Path(args.plot), what="picture", suffix=".png")
    for study, output, plan in zip(studies, outputs, plans):
        # finished chunks wait here until the result file is complete; a killed run resumes from them
        progress_folder = output.with_name(f"{output.name}.progress")
        set_interrupt_hint(f"finished chunks are kept in {progress_folder}: run the same command again to "
                           "compute only the rest")
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


@contextlib.contextmanager
def _validity_notes():
    """Collect the run's ValidityWarnings instead of printing each: a golf study raises the same known notes
    every time (the contact is larger than Hertz's small-contact assumption, ball and face differ in Dundurs'
    beta), and repeated on every run they carry no signal. Every other warning is shown as it comes."""
    import warnings

    from impactlab.model.diagnostics import ValidityWarning

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
        from impactlab.plot.figures import plot_trajectories

        pictures.append(plot_trajectories(dataset, png.with_name(f"{png.stem}_trajectories.png")))
    return pictures


def _has_flight(dataset) -> bool:
    from impactlab.plot.figures import TRAJECTORY_LAUNCH
    from impactlab.vocabulary import FLIGHT_OUTPUTS

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
    print(f"{args.file}: study {dataset.attrs.get('study_name', '?')!r}, "
          f"impactlab {dataset.attrs.get('impactlab_version', '?')}, created {dataset.attrs.get('created', '?')}")
    for dim, size in dataset.sizes.items():
        coord = dataset[dim]
        if dim == "model" or coord.dtype.kind not in "iuf":  # names (models, labels, outputs, parameters)
            print(f"  {dim:<10} {size:>5}  {', '.join(map(str, coord.values))}")
        else:
            print(f"  {dim:<10} {size:>5}  {float(coord.min()):g} .. {float(coord.max()):g} "
                  f"{coord.attrs.get('units', '')}")
    print("variables:")
    for name, variable in dataset.data_vars.items():
        missing = f"  (NaN for {variable.attrs['missing'].split(':')[0]}...)" if "missing" in variable.attrs else ""
        print(f"  {name:<24} [{variable.attrs.get('units', '')}] ({', '.join(map(str, variable.dims))}){missing}")
    if dataset.attrs.get("study_type") == "sensitivity":
        print(f"sensitivity ({dataset.attrs['sampler']}, {dataset.attrs['analyser']}, SALib "
              f"{dataset.attrs['salib_version']}): {dataset.attrs['sensitivity']}")
    print("models:")
    for model in json.loads(dataset.attrs.get("models", "[]")):
        print(f"  {model['id']}: {model['name']} {json.dumps(model['options'])}")
    _print_validity_notes(dataset)
    return 0


def _print_validity_notes(dataset) -> None:
    from impactlab.model.diagnostics import messages

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
        from impactlab.plot.figures import plot_trajectories

        default = Path(args.file).with_name(f"{Path(args.file).stem}_trajectories.png")
        output = check_output(args.output or default, what="picture", suffix=".png")
        print(f"wrote {plot_trajectories(dataset, output)}", file=sys.stderr)
        return 0
    output = check_output(args.output or Path(args.file).with_suffix(".png"), what="picture", suffix=".png")
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
    study = load_study(Path(args.study))
    check_limits(study)  # the study runs once per tolerance: refuse one too big for a single run
    say = (lambda text: None) if args.quiet else (lambda text: print(text, file=sys.stderr))
    output = check_output(args.output or name_in(Path("."), study.name, "-work-precision.h5"))
    if args.plot not in (None, True):
        check_output(args.plot, what="picture", suffix=".png")
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
    output = check_output(args.output, what="report", suffix=".md")
    report(results, output, Path(args.figures) if args.figures else output.parent / "figures")
    print(f"wrote {output}", file=sys.stderr)
    return 0


def _cmd_export(args) -> int:
    if args.gspro is not None:
        host, port = parse_address(args.gspro)  # a bad address is said before the file is read
        shots = checked_shots(open_results(args.file), model=args.model, device_id=args.device_id)
        say = (lambda text: print(text, file=sys.stderr))
        if not shots:
            say("no shot to send: no case of the result has every ball value (all NaN)")
            return 0
        replies = send_shots(shots, host, port, timeout=args.timeout, progress=say)
        say(f"sent {len(shots)} shot(s) to GSPro Connect at {args.gspro}: every one accepted "
            f"(the last: {replies[-1].describe()})")
        return 0
    check_output(args.output, what="shot file", suffix=".json")
    count = write_gspro(open_results(args.file), args.output, model=args.model, device_id=args.device_id)
    print(f"wrote {count} GSPro Open Connect shots to {args.output}", file=sys.stderr)
    return 0


def _seconds(text: str) -> float:
    """argparse type: a positive, finite number of seconds."""
    import math

    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text}")
    return value


def _print_benchmarks(keys) -> list[str]:
    """Run the Chung & Ooi / Kharaz benchmarks for every model, print the table; return what is over budget."""
    keys = None if not keys or "all" in keys else keys
    for key in keys or ():
        if key not in BENCHMARKS:
            raise FieldError("benchmark", "a benchmark of impactlab validate", key, choices=sorted(BENCHMARKS))
    errors = benchmark_errors(keys)
    if keys:
        print("\n".join(describe_benchmark(key) for key in keys))
    print(format_table(errors))
    print()
    return over_budget(errors)


def _cmd_validate(args) -> int:
    # the shot tables' calibration imports scipy.optimize (about 0.2 s): only validate and fit pay for it
    from impactlab.data.shot_report import (
        OBSERVATIONS, SHOT_MODELS, SHOT_TABLES, print_observations, print_shot_errors, shot_table,
    )

    names = args.dataset or ([] if args.benchmark else sorted(DATASETS) + list(SHOT_TABLES) + [OBSERVATIONS])
    if args.plot:  # refused before the models run, not after
        check_output(args.plot, what="--plot file", suffix=".png")
    if args.csv:
        check_output(args.csv, what="--csv file", suffix=".csv")
    over: list[str] = []
    rows: list[dict] = []

    for name in names:
        if name == OBSERVATIONS:  # published differences between shots (gear effect, cover): ratios
            print_observations(args.model or SHOT_MODELS)
            continue
        with user_clubs(read_club_spec(path) for path in args.club or ()):
            table = shot_table(name, args.include_flagged)
            if table is not None:
                over += print_shot_errors(table, args.model or SHOT_MODELS, args.plot, rows)
                continue
        data = get_dataset(name)
        units = OUTPUTS[data.quantity].units
        print(f"{data.name}: {data.quantity} [{units}] at {', '.join(data.labels)}")
        print(f"  measured  {'  '.join(f'{v:8.3f}' for v in data.values)}"
              + (f"   (+- {', '.join(f'{s:g}' for s in data.sigma)})" if data.sigma else ""))
        print(f"  source: {data.source}")
        print(f"  {'model':<16}{'predicted':>{9 * len(data.labels) + 1}}{'rms':>9}{'max':>9}{'budget':>9}")
        for model, error in dataset_errors(data).items():
            budget = data.budgets.get(model)
            # two different statements: the data's own uncertainty says whether the model agrees with the
            # measurement; the budget only says the model has not got worse since it was set
            if data.sigma is not None:
                agreement = ("within the data's sigma" if error["rms"] <= float(np.sqrt(np.mean(np.square(
                    data.sigma)))) else "outside the data's sigma")
            else:
                agreement = "no uncertainty stated"
            if error["unused"]:
                over.append(f"{name}/{model}")
                verdict = f"COULD NOT PREDICT {', '.join(error['unused'])} (not used in rms and max); {agreement}"
            elif budget is not None and error["rms"] > budget:
                over.append(f"{name}/{model}")
                verdict = f"OVER ITS REGRESSION BUDGET; {agreement}"
            else:
                verdict = f"{agreement} (regression budget kept)" if budget is not None else agreement
            predicted = " ".join(f"{v:8.3f}" for v in error["predicted"])
            print(f"  {model:<16} {predicted}{error['rms']:9.4f}{error['max']:9.4f}"
                  f"{budget if budget is not None else float('nan'):9.3f}  {verdict}")
        print()
    if args.benchmark or not args.dataset:
        over += _print_benchmarks(args.benchmark)
    if args.csv:
        from impactlab.data.shot_report import write_prediction_rows

        if not rows:
            from impactlab.errors import StudyError

            raise StudyError("--csv: no shot table was validated (the per-shot table holds shot tables' rows: "
                             "give --dataset FILE.csv, a shot-table .yaml or trackman_tour)")
        write_prediction_rows(rows, args.csv)
        print(f"wrote {args.csv} ({len(rows)} shot-model row(s), measured beside predicted)", file=sys.stderr)
    if over:
        print(f"impactlab: over budget: {', '.join(over)}", file=sys.stderr)
        return 1
    return 0


def _cmd_fit(args) -> int:
    # scipy.optimize (about 0.2 s) is imported by the fits: only validate and fit pay for it
    from impactlab.data.fitting import describe, fit
    from impactlab.data.shot_report import fit_shots, shot_table

    if args.json:  # refused before minutes of fitting, not after
        check_output(args.json, what="--json file", suffix=".json")

    with user_clubs(read_club_spec(path) for path in args.club or ()):
        table = shot_table(args.dataset, args.include_flagged)
        if table is not None:
            return fit_shots(table, args.model, args.parameter, args.cross_validate, args.json, args.by)
    data = get_dataset(args.dataset)
    known = [entry.id for entry in load_dataset_study(data).models]
    models = args.model or known
    for model in models:
        if model not in known:
            raise FieldError("--model", "a model of the dataset's study", model, choices=known)
    results = []
    print(f"{data.name}: fitting {data.quantity} at {', '.join(data.labels)} "
          f"({'weights 1/sigma^2' if data.sigma else 'no stated uncertainty: unit weights, scaled covariance'})")
    for model in models:
        result = fit(data, model, args.parameter)
        results.append(result.as_dict())
        residuals = " ".join(f"{r:+.3f}" for r in result.residuals)
        print(f"  {model:<16} {describe(result)}")
        print(f"  {'':<16} residuals {residuals}; rms {result.rms:.4f} (before the fit {result.start_rms:.4f})")
    if args.json:
        write_atomically(args.json, json.dumps(results, indent=1).encode())
        print(f"wrote {args.json}", file=sys.stderr)
    return 0


def _cmd_shots(args) -> int:
    from impactlab.data.session import describe, read_session, write_normalised
    from impactlab.io.safe_output import check_output

    if args.csv:
        check_output(args.csv, what="--csv file", suffix=".csv")

    session = read_session(args.file, args.vendor)
    with user_clubs(read_club_spec(path) for path in args.club or ()):
        print(describe(session, args.include_flagged))
    if args.csv:
        write_normalised(session, args.csv)
        print(f"wrote {args.csv} ({session.size} shot(s), the vocabulary's names and units)", file=sys.stderr)
    return 0


CLUB_HELP = "a club from its spec sheet (YAML: loft, lie, mass, moi, cg and the names launch monitors give it)"


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``impactlab`` command, one sub-command per job (run, plot, fit, validate...)."""
    parser = argparse.ArgumentParser(prog="impactlab", description="Compare models of a ball leaving a face.")
    parser.add_argument("--version", action="version", version=f"impactlab {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the Python traceback of an error")
    commands = parser.add_subparsers(dest="command", required=True)

    run = commands.add_parser("run", help="run a study file and write its results (HDF5)")
    run.add_argument("study", nargs="+", help="study YAML file(s)")
    run.add_argument("-o", "--output", help="result file (.h5) of a single study; default: STUDY_NAME.h5")
    run.add_argument("--outdir", help="folder for the results, one STUDY_NAME.h5 per study (created if needed)")
    run.add_argument("--plot", metavar="PNG", nargs="?", const=True,
                     help="also draw the results (to PNG, default: next to the result file)")
    run.add_argument("--plan", action="store_true", help="print what would run, and why, then stop")
    run.add_argument("--executor", choices=("auto", "serial", "processes", "dask"), default="auto",
                     help="where cases run: auto (serial for small studies, every core for large), serial, "
                          "processes, dask; results are identical")
    run.add_argument("--workers", type=_count, help="worker processes (default: every core)")
    run.add_argument("--scheduler", metavar="ADDRESS", help="dask.distributed scheduler (implies --executor dask)")
    run.add_argument("--chunk-size", type=_count, help="cases per unit of work")
    run.add_argument("--max-cases", type=_count, help="refuse studies of more cases than this (default 10,000,000; "
                                                       "also IMPACTLAB_MAX_CASES)")
    run.add_argument("--max-memory", type=_size, help="refuse studies estimated to need more memory than this, e.g. "
                                                       "16GiB (default 4GiB; also IMPACTLAB_MAX_MEMORY)")
    run.add_argument("--notes", action="store_true",
                     help="print every validity note in full (default: one line per result file with their count)")
    run.add_argument("-q", "--quiet", action="store_true")
    run.set_defaults(handler=_cmd_run)

    models = commands.add_parser("models", help="list the registered models, what they need and provide")
    models.add_argument("--json", action="store_true")
    models.set_defaults(handler=_cmd_models)

    show = commands.add_parser("show", help="describe a result file")
    show.add_argument("file")
    show.set_defaults(handler=_cmd_show)

    plot = commands.add_parser("plot", help="draw a result file as PNG (by default the figures its study declares)")
    plot.add_argument("file")
    plot.add_argument("-o", "--output", help="PNG file (default: next to the result file)")
    plot.add_argument("--x", help="sweep dimension for the horizontal axis")
    plot.add_argument("--history", metavar="OUTPUT", help="draw this history (e.g. tangential_force) against time")
    plot.add_argument("-v", "--variable", dest="variables", action="append",
                      help="a scalar output to draw (repeatable; default: all)")
    plot.add_argument("--trajectories", action="store_true",
                      help="draw the ball flight after each model's launch, side and top view (a golf result "
                           "holding ball_speed, vertical/horizontal_launch_angle, back_spin, side_spin, spin_axis)")
    plot.set_defaults(handler=_cmd_plot)
    convergence = commands.add_parser("convergence", help="error against run time for every model of a study")
    convergence.add_argument("study", help="study YAML file (its cases and outputs are used)")
    convergence.add_argument("-o", "--output", help="result file (.h5); default: STUDY_NAME-work-precision.h5")
    convergence.add_argument("--plot", metavar="PNG", nargs="?", const=True,
                             help="draw the work-precision diagram (default: next to the result file)")
    convergence.add_argument("--repeats", type=_count, default=3, help="timed repeats per point (median)")
    convergence.add_argument("--tolerances", type=float, nargs="+", help="ladder of tolerances")
    convergence.add_argument("-q", "--quiet", action="store_true")
    convergence.set_defaults(handler=_cmd_convergence)

    export = commands.add_parser("export", help="export a delivery result's shots to golf simulators (a file, or "
                                                "GSPro Open Connect live)")
    export.add_argument("file", help="result file (.h5) of a study with a delivery block")
    where = export.add_mutually_exclusive_group(required=True)
    where.add_argument("-o", "--output", help="JSON file: an array of shot messages")
    where.add_argument("--gspro", metavar="HOST:PORT",
                       help="send each shot to GSPro Open Connect at HOST:PORT (port 921 if left out) and wait "
                            "for its reply")
    export.add_argument("--timeout", type=_seconds, default=5.0, metavar="SECONDS",
                        help="--gspro: seconds to wait for the connection and for each reply (default 5)")
    export.add_argument("--format", choices=("gspro",), default="gspro",
                        help="gspro: GSPro Open Connect v1 (Speed mph, SpinAxis/HLA positive right, VLA, spins rpm; "
                             "club speed mph, attack angle, path, face, dynamic loft in deg)")
    export.add_argument("--model", help="only this model's shots (default: every model)")
    export.add_argument("--device-id", default="impactlab", help="DeviceID of the messages")
    export.set_defaults(handler=_cmd_export)

    validate = commands.add_parser("validate", help="every model against the measured data the project cites")
    validate.add_argument("--dataset", action="append",
                          help="only this dataset, or a shot table file (.csv, .yaml) (repeatable; default: all)")
    validate.add_argument("--model", action="append", help="models to compare on shot tables (default: all)")
    validate.add_argument("--plot", help="shot tables: draw measured beside predicted launch to this PNG")
    validate.add_argument("--benchmark", action="append",
                          help="only this Chung & Ooi / Kharaz benchmark, or 'all' (repeatable; default: all, "
                               "unless --dataset is given)")
    validate.add_argument("--csv", help="shot tables: write every shot's measured launch beside each model's "
                                        "prediction to this CSV file")
    validate.add_argument("--include-flagged", action="store_true",
                          help="shot tables: compare estimated and clamped values too (left out by default)")
    validate.add_argument("--club", action="append", help=CLUB_HELP)
    validate.set_defaults(handler=_cmd_validate)

    shots = commands.add_parser("shots", help="read a launch-monitor export as exported and say what was read")
    shots.add_argument("file", help="a session file: TrackMan, Garmin Golf, Foresight FSX, Rapsodo, FlightScope "
                                    "export, or an impactlab shot-table CSV")
    shots.add_argument("--csv", help="write the normalised table (the vocabulary's names, units in the header)")
    shots.add_argument("--vendor", help="read with this vendor layout (default: recognised from the header)")
    shots.add_argument("--include-flagged", action="store_true",
                       help="count estimated and clamped values as usable (left out of fits by default)")
    shots.add_argument("--club", action="append", help=CLUB_HELP)
    shots.set_defaults(handler=_cmd_shots)

    fitting = commands.add_parser("fit", help="estimate model parameters (friction; beta for restitution) from data")
    fitting.add_argument("dataset", help="a validation dataset (impactlab validate lists them), or a shot table "
                                         "(.csv, .yaml, or trackman_tour)")
    fitting.add_argument("--cross-validate", action="store_true",
                         help="shot tables: also fit on all rows but one and report the error on the one left out")
    fitting.add_argument("--by", choices=("source", "row"),
                         help="shot tables: leave out one source's rows at a time (default when the rows name "
                              "several sources) or one row")
    fitting.add_argument("--model", action="append", help="a model id of the dataset's study (default: every one)")
    fitting.add_argument("--parameter", action="append",
                         help="parameter to fit (repeatable; default: friction, and beta for restitution)")
    fitting.add_argument("--json", help="also write the fits to this JSON file")
    fitting.add_argument("--include-flagged", action="store_true",
                         help="shot tables: fit estimated and clamped values too (left out by default)")
    fitting.add_argument("--club", action="append", help=CLUB_HELP)
    fitting.set_defaults(handler=_cmd_fit)

    paper = commands.add_parser("paper", help="write the Henrikson et al. (2020) reproduction report")
    paper.add_argument("results", help="folder holding the result files of studies/paper/*.yaml")
    paper.add_argument("-o", "--output", default="docs/paper.md", help="report file (markdown)")
    paper.add_argument("--figures", help="folder for the figures (default: figures/ beside the report)")
    paper.set_defaults(handler=_cmd_paper)
    for command in commands.choices.values():  # --debug after the command too; SUPPRESS keeps a global one
        command.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                             help="show the Python traceback of an error")
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run one command; every failure ends as one message and an exit status (impactlab.run.faults)."""
    args = build_parser().parse_args(argv)
    # the limits and the warning hook (run_command) are the command's own: both are put back on return
    with limits.configured(max_cases=getattr(args, "max_cases", None), max_memory=getattr(args, "max_memory", None)):
        return run_command(lambda: args.handler(args), debug=args.debug)


if __name__ == "__main__":
    sys.exit(main())
