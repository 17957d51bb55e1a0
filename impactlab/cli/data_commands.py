"""The commands on measured data: ``validate`` (every model against the cited datasets, benchmarks and shot
tables), ``fit`` (model parameters from data) and ``shots`` (read a launch-monitor export as exported).

The shot tables' calibration and the fits import scipy.optimize (about 0.2 s): ``impactlab.data.shot_report``
and ``impactlab.data.fit.fitting`` are imported inside ``validate`` and ``fit`` only, so no other command pays for
them.
"""

from __future__ import annotations

import json
import sys

import numpy as np

from impactlab.data.sessions.reader import describe as describe_session
from impactlab.data.sessions.export import session_messages
from impactlab.data.sessions.reader import read_session, write_normalised
from impactlab.data.sessions.summary import show_rows_setting, skip_lines
from impactlab.data.validation import DATASETS, get_dataset, load_dataset_study
from impactlab.data.validation import errors as dataset_errors
from impactlab.data.validation.benchmark_report import describe as describe_benchmark
from impactlab.data.validation.benchmark_report import format_table, over_budget
from impactlab.data.validation.benchmarks import BENCHMARKS, benchmark_errors
from impactlab.cli.club_options import refuse_unmatched, unmatched
from impactlab.errors import FieldError, StudyError
from impactlab.io.gspro_connect import parse_address, send_shots
from impactlab.io.safe_output import (JSON_SUFFIXES, TABLE_SUFFIXES, check_output, refuse_replacing_foreign,
                                      write_atomically)
from impactlab.model.registry import available
from impactlab.scene.catalogue import user_clubs
from impactlab.study.club_specs import read_club_spec
from impactlab.vocabulary import OUTPUTS


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


def _refuse_validate_outputs(args) -> None:
    """Refuse an unknown --model and an output file that would replace an input, before anything runs."""
    known = sorted(available())
    for model in args.model or ():  # said before anything runs (the datasets' tables would ignore it)
        if model not in known:
            raise FieldError("--model", "a registered model", model, choices=known)
    read = [*(args.dataset or ()), *(args.club or ())]  # an output there would replace the user's data
    if args.plot:  # refused before the models run, not after
        check_output(args.plot, what="--plot file", suffix=".png", reads=read, formats=(".png",))
    if args.csv:
        check_output(args.csv, what="--csv file", suffix=".csv", reads=[*read, *([args.plot] if args.plot else [])],
                     formats=TABLE_SUFFIXES)
        refuse_replacing_foreign(args.csv, "--csv file", args.force)
    if args.report:
        check_output(args.report, what="--report file", suffix=".html", reads=[*read, *(args.fit or ())],
                     formats=(".html", ".htm"))
        if len(args.dataset or ()) != 1:  # one page per run: a second session would replace the first's
            raise StudyError("--report writes the scorecard of one session: give exactly one --dataset FILE "
                             f"(given {len(args.dataset or ())})")
    if args.holdout is not None and not 0.0 < args.holdout < 1.0:  # said before any dataset runs
        raise FieldError("--holdout", "a share of the rows held out, between 0 and 1 (e.g. 0.3)", str(args.holdout))


def _print_dataset(name: str) -> list[str]:
    """Print a cited dataset beside every model of its study; return the ``dataset/model`` pairs over budget."""
    over: list[str] = []
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
    return over


def _refuse_unused_validate_options(args, drawn: bool, scored: bool) -> None:
    """Refuse the options for sessions or shot tables when the run validated none (said after the run)."""
    for option, given in (("--fit", args.fit), ("--report", args.report), ("--holdout", args.holdout is not None)):
        if given and not scored:
            raise StudyError(f"{option}: for sessions (a shot table file with --dataset FILE), and no session was "
                             "scored; give --dataset FILE.csv")
    if args.model and not drawn and not scored:
        raise StudyError(f"--model {' '.join(args.model)}: chooses the models compared on shot tables, and none was "
                         "validated (a dataset's table shows every model of its study); leave --model out")


def _write_validate_csv(path, rows: list[dict]) -> None:
    """Write the per-shot rows of --csv (measured beside predicted), or refuse when no shot table gave any."""
    from impactlab.data.shot_report import write_prediction_rows

    if not rows:
        raise StudyError("--csv: no shot table was validated (the per-shot table holds shot tables' rows: "
                         "give --dataset FILE.csv, a shot-table .yaml or trackman_tour)")
    write_prediction_rows(rows, path)
    print(f"wrote {path} ({len(rows)} shot-model row(s), measured beside predicted)", file=sys.stderr)


def _cmd_validate(args) -> int:
    # the shot tables' calibration imports scipy.optimize (about 0.2 s): only validate and fit pay for it
    from impactlab.data.shot_report import (
        HOLDOUT, MIN_ROWS, OBSERVATIONS, SHOT_MODELS, SHOT_TABLES, in_sample, load_fits, measured_carry,
        print_observations, print_scorecard, print_shot_errors, shot_table, write_report,
    )

    names = args.dataset or ([] if args.benchmark else sorted(DATASETS) + list(SHOT_TABLES) + [OBSERVATIONS])
    _refuse_validate_outputs(args)
    fits = []
    if args.fit:  # a bad fit file is refused before the models run
        for path in args.fit:
            fits += load_fits(path)
    over: list[str] = []
    specs = [read_club_spec(path) for path in args.club or ()]
    matched: set[str] = set()  # the --club sheets some row of a table validated names
    tables: list[str] = []
    seen: list[str] = []  # the clubs the tables' rows name
    rows: list[dict] = []  # per shot and model: measured beside predicted (--csv)
    drawn = False  # a shot table validated, whose figure --plot draws
    scored = False  # a session scored (a scorecard on held-out rows)
    report_parts: list = []  # what --report draws, written once every refusal has passed

    for name in names:
        if name == OBSERVATIONS:  # published differences between shots (gear effect, cover): ratios
            print_observations(args.model or SHOT_MODELS)
            continue
        with user_clubs(specs) as clubs:
            table = _strict(name, shot_table(name, args.include_flagged), args.strict)
            if table is not None and (table.size >= MIN_ROWS or fits or args.report):
                # a session: every model, the fits and the baselines on held-out rows (a scorecard)
                if args.plot:
                    raise StudyError(f"--plot draws a few shots row by row, and {name} has {table.size}: give "
                                     "--report report.html (density plots of every shot held out)")
                matched.update(set(args.club or ()) - set(unmatched(args.club or (), specs, clubs.added,
                                                                     table.clubs)))
                tables.append(name)
                seen.extend(table.clubs)
                # the report is written after the run's last refusal (below), never before it
                print_scorecard(table, args.model or SHOT_MODELS, fits,
                                HOLDOUT if args.holdout is None else args.holdout, None, rows,
                                in_sample(fits, name), measured_carry(name, table), keep=report_parts)
                scored = True
                continue
            if table is not None:
                matched.update(set(args.club or ()) - set(unmatched(args.club or (), specs, clubs.added,
                                                                     table.clubs)))
                tables.append(name)
                seen.extend(table.clubs)
                over += print_shot_errors(table, args.model or SHOT_MODELS, args.plot, rows)
                drawn = True
                continue
        over += _print_dataset(name)
    if args.benchmark or not args.dataset:
        over += _print_benchmarks(args.benchmark)
    _refuse_unused_validate_options(args, drawn, scored)
    unused = [path for path in args.club or () if path not in matched]
    if unused:  # said after the run: the tables are read one by one (a sheet may name the clubs of any of them)
        with user_clubs(specs) as clubs:
            refuse_unmatched(unused, [specs[list(args.club).index(path)] for path in unused],
                             [clubs.added[list(args.club).index(path)] for path in unused], seen,
                             ", ".join(tables) or "any shot table validated")
    if args.plot and not drawn:
        raise StudyError("--plot: no shot table was validated (the figure draws shot tables' rows: give --dataset "
                         "FILE.csv, a shot-table .yaml or trackman_tour); nothing was drawn")
    if args.csv:
        _write_validate_csv(args.csv, rows)
    if args.report and report_parts:
        print(f"wrote {write_report(args.report, *report_parts[0])}", file=sys.stderr)
    if over:
        print(f"impactlab: over budget: {', '.join(over)}", file=sys.stderr)
        return 1
    return 0


def _cmd_fit(args) -> int:
    # scipy.optimize (about 0.2 s) is imported by the fits: only validate and fit pay for it
    from impactlab.data.fit.fitting import describe, fit
    from impactlab.data.shot_report import fit_shots, shot_table

    if args.json:  # refused before minutes of fitting, not after
        check_output(args.json, what="--json file", suffix=".json", reads=[args.dataset, *(args.club or ())],
                     formats=JSON_SUFFIXES)

    if args.folds is not None and not args.cross_validate:
        raise StudyError(f"--folds {args.folds} says how many folds the cross-validation makes; add --cross-validate "
                         "(or leave --folds out)")
    if args.folds is not None and args.by == "row":
        raise StudyError("--folds: --by row leaves out one row at a time (in closed form), it has no folds; leave "
                         "--folds out or fold --by block or source")
    if args.by and not args.cross_validate:
        raise StudyError(f"--by {args.by} says what the cross-validation leaves out; add --cross-validate (or leave "
                         "--by out)")
    specs = [read_club_spec(path) for path in args.club or ()]
    with user_clubs(specs) as clubs:
        table = _strict(args.dataset, shot_table(args.dataset, args.include_flagged), args.strict)
        if table is not None:
            refuse_unmatched(args.club or (), specs, clubs.added, table.clubs, args.dataset)
            return fit_shots(table, args.model, args.parameter, args.cross_validate, args.json, args.by,
                             5 if args.folds is None else args.folds, args.dataset)
    ignored = [option for option, given in (("--cross-validate", args.cross_validate), ("--club", args.club),
                                            ("--include-flagged", args.include_flagged), ("--strict", args.strict),
                                            ("--show-rows", getattr(args, "show_rows", False))) if given]
    if ignored:
        them = "it" if len(ignored) == 1 else "them"
        raise StudyError(f"{', '.join(ignored)}: for shot tables, and {args.dataset} is a validation dataset of "
                         f"published values (impactlab validate lists them); leave {them} out")
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


def _strict(name: str, table, strict: bool):
    """``table``, after ``--strict``: a session's bad rows refuse it (a table written by hand is refused whole
    anyway)."""
    if strict and table is not None and table.unusual is not None:  # a session's rows were judged by the row rules
        read_session(name).refuse_bad_rows()
    return table


def export_session(args) -> int:
    """``impactlab export SESSION -o shots.json`` (or ``--gspro HOST:PORT``): the session's measured shots as GSPro
    Open Connect messages (:func:`impactlab.data.sessions.export.session_messages`), rows not sent said by reason."""
    if args.model is not None:
        raise StudyError(f"--model {args.model}: chooses a model's shots in a result file; {args.file} is a session "
                         "of measured shots (leave --model out)")
    if args.output is not None:
        check_output(args.output, what="shot file", suffix=".json", reads=[args.file], formats=JSON_SUFFIXES)
    address = parse_address(args.gspro) if args.gspro is not None else None  # said before the file is read
    session = read_session(args.file)
    if args.strict:
        session.refuse_bad_rows()
    shots, skipped, zeroed = session_messages(session, device_id=args.device_id)
    for line in skip_lines(skipped, session.size, (), show_rows_setting(), indent="", used="exported"):
        print(line, file=sys.stderr)
    if zeroed:
        print(f"{zeroed} shot(s) without a spin axis or launch direction: sent with 0 (GSPro needs both)",
              file=sys.stderr)
    if not shots:
        raise StudyError(f"{args.file}: no shot to export (each needs a ball speed, a launch angle and a spin rate)")
    if address is not None:
        replies = send_shots(shots, *address, timeout=args.timeout, progress=lambda text: print(text, file=sys.stderr))
        print(f"sent {len(shots)} shot(s) to GSPro Connect at {args.gspro} (the last: {replies[-1].describe()})",
              file=sys.stderr)
        return 0
    write_atomically(args.output, json.dumps(shots, indent=1).encode())
    print(f"wrote {len(shots)} GSPro Open Connect shots of {session.file} to {args.output}", file=sys.stderr)
    return 0


def _cmd_shots(args) -> int:
    if args.csv:
        check_output(args.csv, what="--csv file", suffix=".csv", reads=[args.file, *(args.club or ())],
                     formats=TABLE_SUFFIXES)
        refuse_replacing_foreign(args.csv, "--csv file", args.force)

    session = read_session(args.file, args.vendor)
    if args.strict:
        session.refuse_bad_rows()
    specs = [read_club_spec(path) for path in args.club or ()]
    with user_clubs(specs) as clubs:
        refuse_unmatched(args.club or (), specs, clubs.added, session.text.get("club", ()), args.file)
        print(describe_session(session, args.include_flagged))
    if args.csv:
        write_normalised(session, args.csv)
        print(f"wrote {args.csv} ({session.size} shot(s), the vocabulary's names and units)", file=sys.stderr)
    return 0
