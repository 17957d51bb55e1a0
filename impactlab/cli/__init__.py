"""The ``impactlab`` command line: run studies, list models, show and plot result files, validate and fit the
models against measured data.

This package holds the parser and :func:`main` (the ``impactlab`` entry point); the commands live by concern in
:mod:`impactlab.cli.study_commands` (run, models, show, plot, convergence, paper, export) and
:mod:`impactlab.cli.data_commands` (validate, fit, shots).

Bad input ends with one message on stderr (what, where, expected, given,
choices) and exit status 2, never a traceback.
"""

from __future__ import annotations

import argparse
import difflib
import math
import re
from collections.abc import Sequence
from typing import NoReturn

from impactlab._version import __version__
from impactlab.cli.data_commands import _cmd_fit, _cmd_shots, _cmd_validate
from impactlab.cli.fly_command import add_parser as add_fly_parser
from impactlab.data.sessions.summary import showing_rows
from impactlab.cli.study_commands import (_cmd_convergence, _cmd_export, _cmd_models, _cmd_paper, _cmd_plot,
                                          _cmd_run, _cmd_show)
from impactlab.run.faults import EXIT_BAD_INPUT, EXIT_ENVIRONMENT, EXIT_INTERRUPTED  # noqa: F401  (the exit statuses)
from impactlab.errors import shown
from impactlab.run.faults import run_command
from impactlab.study import limits
from impactlab.study.limits import parse_size


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



#: the longest --timeout: GSPro answers a shot in well under a second; a socket's timeout of 1e12 s does not fit the
#: platform's time_t (an OverflowError inside the connection, which leaked its socket: exit 1, 'internal error')
MAX_TIMEOUT = 3600.0


def _seconds(text: str) -> float:
    """argparse type: a positive, finite number of seconds, at most :data:`MAX_TIMEOUT`."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text!r}") from None
    if not (math.isfinite(value) and 0 < value <= MAX_TIMEOUT):
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0 and at most {MAX_TIMEOUT:g} (an hour), "
                                         f"got {text}")
    return value



def _tolerance(text: str) -> float:
    """argparse type: a tolerance of the work-precision ladder. The reference runs at a 120th of the finest (the
    finest / 30, extrapolated with the finest / 120) and a model takes 1e-9 to 0.1: 5 was refused as 'tolerance:
    ... got 0.1667', a value never typed, after the models were built."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a tolerance (a number), got {text!r}") from None
    if not (math.isfinite(value) and 120 * 1e-9 <= value <= 0.1):
        raise argparse.ArgumentTypeError(f"expected a tolerance between 1.2e-07 and 0.1 (a model takes 1e-9 to 0.1, "
                                         f"and the reference runs at a 120th of the finest), got {text}")
    return value


class _Parser(argparse.ArgumentParser):
    """argparse's parser, its errors on one line like every other failure: ``impactlab: error: run: argument
    --executor: invalid choice: 'foo' (choose from ...; did you mean 'auto'?); see impactlab run --help``, status 2
    (argparse prints its usage block and ``impactlab run: error: ...``, and offers no closest choice)."""

    def error(self, message: str) -> NoReturn:
        found = re.search(r"invalid choice: '?([^'\s]+)'? \(choose from (.*)\)", message)
        if found:
            choices = [choice.strip(" '\"") for choice in found.group(2).split(",")]
            close = difflib.get_close_matches(found.group(1), choices, n=1)
            if close:
                message += f" (did you mean {close[0]!r}?)"
        option = re.match(r"argument (--[\w-]+): expected (one|at least one) argument", message)
        if option:  # '--spin-axis -3deg': argparse takes '-3deg' for an option, and says the value is missing
            message += (f" (a value starting with '-' reads as an option: join it with '=', {option.group(1)}=-VALUE, "
                        "or write a space before its unit, '-5 deg')")
        command = self.prog.split(" ", 1)[1] + ": " if " " in self.prog else ""
        # argparse quotes arguments as given (a file name from a glob may hold escape sequences): shown escaped
        self.exit(2, f"impactlab: error: {command}{shown(message)}; see `{self.prog} --help`\n")


FORCE_HELP = "--csv: replace an existing file that is not a table impactlab wrote (refused by default)"
def _row_options(command, prefix: str = "") -> None:
    """--strict and --show-rows of every command that reads a session's rows (one set of row rules)."""
    command.add_argument("--strict", action="store_true",
                         help=prefix + "refuse the file (exit 2) if any row is bad (a value beyond any golf shot, not "
                                       "a number, off the face...); by default bad rows are skipped with their reason")
    command.add_argument("--show-rows", action="store_true",
                         help=prefix + "list the file line of every row skipped or unusual (default: counts per "
                                       "reason)")


CLUB_HELP = "a club from its spec sheet (YAML: loft, lie, mass, moi, cg and the names launch monitors give it)"


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``impactlab`` command, one sub-command per job (run, plot, fit, validate...)."""
    parser = _Parser(prog="impactlab", description="Compare models of a ball leaving a face.")
    parser.add_argument("--version", action="version", version=f"impactlab {__version__}")
    parser.add_argument("--debug", action="store_true", help="show the Python traceback of an error")
    commands = parser.add_subparsers(dest="command", required=True)
    # the sub-commands in the order ``impactlab --help`` lists them
    _add_run(commands)
    _add_result_commands(commands)
    _add_data_commands(commands)
    add_fly_parser(commands)
    _add_fit_and_paper(commands)
    for command in commands.choices.values():  # --debug after the command too; SUPPRESS keeps a global one
        command.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                             help="show the Python traceback of an error")
    return parser


def _add_run(commands) -> None:
    """``impactlab run``."""
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


def _add_result_commands(commands) -> None:
    """The commands that read or send a result file: models, show, plot, convergence, export."""
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
    convergence.add_argument("--tolerances", type=_tolerance, nargs="+", help="ladder of tolerances")
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
    _row_options(export, "a session file (CSV or JSON export, or a shipped session dataset): ")
    export.set_defaults(handler=_cmd_export)


def _add_data_commands(commands) -> None:
    """The commands of measured data: validate, shots."""
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
    validate.add_argument("--force", action="store_true", help=FORCE_HELP)
    _row_options(validate, "shot tables: ")
    validate.add_argument("--fit", action="append", metavar="JSON",
                          help="shot tables: apply the fits of this file (impactlab fit TRAIN --json) to the held-out "
                               "shots beside the models (repeatable)")
    validate.add_argument("--report", metavar="HTML",
                          help="shot tables: write the scorecard and its figures as one self-contained HTML page")
    validate.add_argument("--holdout", type=float, default=None, metavar="FRACTION",
                          help="sessions: share of the groups (or contiguous blocks of rows) held out for the "
                               "scorecard (default 0.3)")
    validate.set_defaults(handler=_cmd_validate)

    shots = commands.add_parser("shots", help="read a launch-monitor export as exported and say what was read")
    shots.add_argument("file", help="a session file as exported: TrackMan, Garmin Golf, Foresight FSX (CSV or "
                                    ".session), Rapsodo, FlightScope, Square Golf, a Uneekor report or GSPro Open "
                                    "Connect messages (JSON), or an impactlab shot-table CSV")
    shots.add_argument("--csv", help="write the normalised table (the vocabulary's names, units in the header)")
    shots.add_argument("--vendor", help="read with this vendor layout (default: recognised from the header)")
    shots.add_argument("--include-flagged", action="store_true",
                       help="count estimated and clamped values as usable (left out of fits by default)")
    shots.add_argument("--club", action="append", help=CLUB_HELP)
    shots.add_argument("--force", action="store_true", help=FORCE_HELP)
    _row_options(shots)
    shots.set_defaults(handler=_cmd_shots)


def _add_fit_and_paper(commands) -> None:
    """``impactlab fit`` and ``impactlab paper``."""
    fitting = commands.add_parser("fit", help="estimate model parameters (friction; beta for restitution) from data")
    fitting.add_argument("dataset", help="a validation dataset (impactlab validate lists them), or a shot table "
                                         "(.csv, .yaml, or trackman_tour)")
    fitting.add_argument("--cross-validate", action="store_true",
                         help="shot tables: also fit on all folds but one and report the errors on the fold left out")
    fitting.add_argument("--by", choices=("source", "block", "row"),
                         help="shot tables: folds of whole sources (default when the rows name several), of "
                              "contiguous blocks of rows (default otherwise), or one row at a time (leave-one-out "
                              "in closed form from the full fit: one Gauss-Newton step per row, no refits)")
    fitting.add_argument("--folds", type=_count, default=None, metavar="K",
                         help="shot tables: number of cross-validation folds (default 5)")
    fitting.add_argument("--model", action="append", help="a model id of the dataset's study (default: every one)")
    fitting.add_argument("--parameter", action="append",
                         help="parameter to fit (repeatable; default: friction, and beta for restitution)")
    fitting.add_argument("--json", help="also write the fits to this JSON file")
    fitting.add_argument("--include-flagged", action="store_true",
                         help="shot tables: fit estimated and clamped values too (left out by default)")
    fitting.add_argument("--club", action="append", help=CLUB_HELP)
    _row_options(fitting, "shot tables: ")
    fitting.set_defaults(handler=_cmd_fit)

    paper = commands.add_parser("paper", help="write the Henrikson et al. (2020) reproduction report")
    paper.add_argument("results", help="folder holding the result files of studies/paper/*.yaml")
    paper.add_argument("-o", "--output", default="docs/paper.md", help="report file (markdown)")
    paper.add_argument("--figures", help="folder for the figures (default: figures/ beside the report)")
    paper.set_defaults(handler=_cmd_paper)


def main(argv: Sequence[str] | None = None) -> int:
    """Run one command; every failure ends as one message and an exit status (impactlab.run.faults)."""
    args = build_parser().parse_args(argv)
    # the limits and the warning hook (run_command) are the command's own: both are put back on return
    with limits.configured(max_cases=getattr(args, "max_cases", None), max_memory=getattr(args, "max_memory", None)):
        with showing_rows(getattr(args, "show_rows", False)):  # summaries of skipped rows: every line, or counts
            return run_command(lambda: args.handler(args), debug=args.debug)

