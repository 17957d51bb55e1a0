"""What ``impactlab validate`` and ``impactlab fit`` print for launch-monitor shot tables.

Kept apart from the command line's argument handling: these functions take
plain values and print the tables, so that Python users can call them too.
"""

from __future__ import annotations

import io
import json
import math
import re
import os
import sys
from collections.abc import Iterable, Sequence
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from impactlab.errors import FieldError
from impactlab.units import MPH, RAD_TO_DEG, RADS_TO_RPM
from impactlab.data.sessions.shots import (
    ERROR_KEYS, MEASURED_FIELDS, ShotTable, errors_by_source, predict, read_shots, read_yaml, shot_errors, summary,
    table_inputs,
)
from impactlab.data.validation.head_cor import head_cor_note
from impactlab.data.validation.observations import (cover_effect, describe, gear_effect, load_observations,
                                                    vertical_gear_effect)
from impactlab.io.safe_output import write_atomically
from impactlab.model.registry import get_model
from impactlab.data.fit.calibration import DEFAULT_PARAMETERS, calibrate
from impactlab.data.sessions.json_records import JSON_SESSIONS
from impactlab.data.sessions.reader import DATASETS as SESSION_DATASETS
from impactlab.data.sessions.summary import skip_lines, show_rows_setting
from impactlab.data.sessions.reader import read_session
from impactlab.data.fit.calibration import cross_validate as leave_one_out
from impactlab.data.fit.calibration import leave_one_row_out
from impactlab.data.validation.fits import bounds_of, in_sample as in_sample, load_fits as load_fits, provenance
from impactlab.data.validation.report import write_report as write_report
from impactlab.data.validation.scorecard import format_scorecard, losers, scorecard
from impactlab.data.validation.splits import HOLDOUT, MIN_ROWS as MIN_ROWS, holdout_split
from impactlab.data.validation.splits import folds as make_folds
from impactlab.data.fit.least_squares import usable_rows

if TYPE_CHECKING:  # matplotlib is imported where a figure is drawn
    from matplotlib.figure import Figure

#: shot tables shipped with impactlab (impactlab/data/validation/NAME.yaml)
SHOT_TABLES = ("trackman_tour",)
#: the models compared against shot tables by default
SHOT_MODELS = ("maw", "hertz_mindlin", "dem_linear", "rigid_coulomb", "restitution")
#: the models fitted by default (the others: rigid_coulomb's spin is fixed by rolling, restitution's by beta)
FIT_MODELS = ("maw", "hertz_mindlin", "rigid_coulomb")


def _is_shot_yaml(path: Path) -> bool:
    """Whether a YAML file is a shot table (top-level ``rows:``) rather than a measured-data file (``points:``)."""
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError):
        return True  # the shot reader says what is wrong with it
    return re.search(r"^rows\s*:", text, flags=re.MULTILINE) is not None


def _is_shot_json(path: Path) -> bool:
    """Whether a JSON file holds shots (GSPro messages, a Uneekor report, an FSX session) rather than measured data
    (a mapping with ``points:``)."""
    try:
        value, _ = json.JSONDecoder().raw_decode(path.read_text(encoding="utf-8").lstrip("\ufeff \t\r\n"))
    except (OSError, UnicodeDecodeError, ValueError, RecursionError):
        return True  # the session reader says what is wrong with it, at its line (a nesting too deep included)
    return not (isinstance(value, dict) and "points" in value)


def shot_table(name: str, include_flagged: bool = False) -> ShotTable | None:
    """A shot table: a .csv file (a launch-monitor export as exported, or impactlab's layout), a JSON session
    (.json, .jsonl, .session: GSPro Open Connect messages, a Uneekor report, an FSX session), a .yaml file with
    ``rows:``, or a shipped table by name; None otherwise. ``include_flagged`` keeps estimated and clamped values
    in the comparison (left out by default)."""
    path = Path(name)
    suffix = path.suffix.lower()
    if suffix == ".csv" or (suffix in (".yaml", ".yml") and _is_shot_yaml(path)) or (
            suffix in JSON_SESSIONS and _is_shot_json(path)):
        return read_shots(path, include_flagged)
    if name in SESSION_DATASETS and not path.exists():  # a launch-monitor export shipped with impactlab
        return read_shots(name, include_flagged)
    if name in SHOT_TABLES:
        text = resources.files("impactlab.data.validation").joinpath(f"{name}.yaml").read_text()
        return read_yaml(text, f"impactlab/data/validation/{name}.yaml")
    return None


def data_uncertainty(table: ShotTable) -> dict:
    """The table's one-sigma uncertainty in the units of :data:`ERROR_KEYS` (RMS over the rows measuring each)."""
    m, s = table.measured, table.sigma
    with np.errstate(invalid="ignore", divide="ignore"):
        values = {
            "ball_speed [%]": 100.0 * s["ball_speed"] / m["ball_speed"],
            "launch angle [deg]": np.degrees(np.where(np.isfinite(m["vertical_launch_angle"]),
                                                      s["vertical_launch_angle"], np.nan)),
            "launch direction [deg]": np.degrees(np.where(np.isfinite(m["horizontal_launch_angle"]),
                                                          s["horizontal_launch_angle"], np.nan)),
            "spin [%]": 100.0 * s["spin_rate"] / m["spin_rate"],
            "spin axis [deg]": np.degrees(np.where(np.isfinite(m["spin_axis"]), s["spin_axis"], np.nan)),
        }
    return summary(values)


#: display units of the measured quantities on the validation figure: (label, factor from SI)
_PANELS = (("ball_speed", "ball speed [mph]", 1.0 / MPH), ("vertical_launch_angle", "launch angle [deg]", RAD_TO_DEG),
           ("spin_rate", "spin rate [rpm]", RADS_TO_RPM))


def plot_shots(table: ShotTable, predictions: dict, path: str | os.PathLike[str]) -> Path:
    """Draw :func:`shots_figure` to the PNG ``path``."""
    buffer = io.BytesIO()
    shots_figure(table, predictions).savefig(buffer, format="png", dpi=110)
    return write_atomically(path, buffer.getvalue())


def shots_figure(table: ShotTable, predictions: dict) -> Figure:
    """Measured values (with their one-sigma bars) beside each model's prediction, one panel per quantity.

    ``predictions`` maps a model id to :func:`impactlab.data.sessions.shots.predict`'s arrays (SI). Returns a matplotlib
    ``Figure`` (no pyplot state is touched).
    """
    # no pyplot: the caller's backend and figures stay untouched; matplotlib (heavy) is imported only to draw
    from matplotlib.figure import Figure

    panels = [entry for entry in _PANELS if np.isfinite(table.measured[entry[0]]).any()]
    figure = Figure(figsize=(4.2 * len(panels), 4.2), layout="constrained")
    axes = figure.subplots(1, len(panels), squeeze=False)[0]
    rows = np.arange(table.size)
    markers = ("o", "s", "^", "D", "v", "P", "X")
    width = 0.6 / max(len(predictions), 1)
    for axis, (key, label, factor) in zip(axes, panels):
        axis.errorbar(rows, table.measured[key] * factor, yerr=table.sigma[key] * factor, fmt="k_", ms=22, mew=2,
                      capsize=4, label="measured (+- 1 sigma)", zorder=3)
        for index, (name, predicted) in enumerate(predictions.items()):
            offset = (index - (len(predictions) - 1) / 2) * width
            axis.plot(rows + offset, predicted[key] * factor, markers[index % len(markers)], ls="none", label=name)
        axis.set_xticks(rows, table.labels, rotation=20)
        axis.set_ylabel(label)
        axis.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    figure.suptitle(f"{table.name}: measured launch beside each model (ball and club presets, square centred "
                    f"strikes unless the table says otherwise)", fontsize=10)
    return figure


def labels_text(labels, most: int = 8) -> str:
    """The row labels of a table for a report: all of a small table, the first and last few of a large one."""
    labels = list(labels)
    if len(labels) <= most:
        return ", ".join(labels)
    return f"{', '.join(labels[:most // 2])}, ..., {', '.join(labels[-2:])}"


def skipped_text(table: ShotTable) -> list[str]:
    """Lines saying how many rows of the file were not used and why, one per reason (every line with
    ``--show-rows``), and the unusual values used, one line per column and reason."""
    return skip_lines(table.skipped, table.size + len(table.skipped), table.unusual or (), show_rows_setting())


def print_shot_errors(table: ShotTable, models: Iterable[str], plot: str | None = None,
                      rows: list | None = None) -> list[str]:
    """Print each model's RMS error per measured quantity; return ``table/model`` entries over their budget.

    ``rows``, when given a list, receives the per-shot table (:func:`prediction_rows`) of every model.
    """
    print(f"{table.name}: {table.size} row(s) ({labels_text(table.labels)})")
    print(f"  source: {table.source}")
    for line in skipped_text(table):
        print(line)
    keys = [key for key, value in data_uncertainty(table).items() if math.isfinite(value)]
    # a space before every column: 'launch direction [deg]' fills 22 and ran into the column before it
    print(f"  {'RMS error':<16}" + "".join(f" {key:>22}" for key in keys))
    sigma = data_uncertainty(table)
    print(f"  {'data 1-sigma':<16}" + "".join(f" {sigma[key]:22.2f}" for key in keys))
    inputs = table_inputs(table)
    over, predictions = [], {}
    for name in models:
        predictions[name] = predict(get_model(name)(), inputs)
        rms = summary(shot_errors(predictions[name], table))
        budget = table.budgets.get(name, {})
        cells = []
        for key in keys:
            mark = "" if rms[key] <= sigma[key] else ("" if rms[key] <= budget.get(key, math.inf) else " OVER")
            if key in budget and rms[key] > budget[key]:
                over.append(f"{table.name}/{name}")
            cells.append(" " + f"{rms[key]:.2f}{'*' if rms[key] <= sigma[key] else ''}{mark}".rjust(22))
        print(f"  {name:<16}" + "".join(cells))
        unused = _unpredicted(predictions[name], table)
        if unused:
            over.append(f"{table.name}/{name}")
            print(f"  {'':<16}rows not used (the model cannot predict them; OVER): {', '.join(unused)}")
    print("  (* within the data's uncertainty; OVER: beyond its regression budget, which only keeps a model from "
          "getting worse)")
    note = head_cor_note(predictions, table.clubs, table.ball)
    if note:
        print(f"  NOTE: {note}")
    print_source_table(table, predictions)
    print()
    if rows is not None:
        rows.extend(prediction_rows(table, predictions))
    if plot:
        print(f"wrote {plot_shots(table, predictions, plot)}", file=sys.stderr)
    return sorted(set(over))


#: the per-source table's columns: error key -> short heading
SOURCE_COLUMNS = {"ball_speed [%]": "speed %", "launch angle [deg]": "launch deg", "spin [%]": "spin %",
                  "launch direction [deg]": "direction deg", "spin axis [deg]": "axis deg"}


def source_table(table: ShotTable, predictions: dict) -> dict:
    """source -> model -> {error key -> RMS over the source's rows}
    (:func:`impactlab.data.sessions.shots.errors_by_source`)."""
    out: dict = {}
    for model, predicted in predictions.items():
        for source, rms in errors_by_source(shot_errors(predicted, table), table).items():
            out.setdefault(source, {})[model] = rms
    return out


def format_source_table(errors: dict, keys=None) -> list[str]:
    """Lines of a table: one row per source, one column group per model, RMS of each error key."""
    models = list(next(iter(errors.values())))
    keys = keys or [key for key in SOURCE_COLUMNS
                    if any(math.isfinite(errors[s][m][key]) for s in errors for m in errors[s])]
    width = 11 * len(keys) + 2
    lines = [f"  {'source':<22}" + "".join(f"{model:>{width}}" for model in models),
             f"  {'':<22}" + "".join("  " + "".join(f"{SOURCE_COLUMNS[k]:>11}" for k in keys) for _ in models)]
    for source, by_model in errors.items():
        lines.append(f"  {source:<22}" + "".join("  " + "".join(f"{by_model[m][k]:11.2f}" for k in keys)
                                                 for m in models))
    return lines


def print_source_table(table: ShotTable, predictions: dict) -> None:
    """Print the RMS errors per source (rows) and model (columns)."""
    print("  per source (RMS over the source's rows; rows = source, columns = model):")
    for line in format_source_table(source_table(table, predictions)):
        print(line)


#: the per-shot table's quantities: (field, unit, factor from SI)
_CSV_QUANTITIES = (("ball_speed", "m/s", 1.0), ("vertical_launch_angle", "deg", RAD_TO_DEG),
                   ("horizontal_launch_angle", "deg", RAD_TO_DEG), ("spin_rate", "rpm", RADS_TO_RPM),
                   ("spin_axis", "deg", RAD_TO_DEG))


def prediction_rows(table: ShotTable, predictions: dict) -> list[dict]:
    """One row per shot and model: the shot's delivery, each measured quantity beside the model's prediction.

    ``predictions`` maps a model id to :func:`impactlab.data.sessions.shots.predict`'s arrays (SI). Keys carry their
    unit (``ball_speed measured [m/s]``); a quantity the table does not measure is an empty cell.
    """
    out = []
    for model, predicted in predictions.items():
        for index in range(table.size):
            row = {"table": table.name, "shot": table.labels[index], "club": table.clubs[index],
                   "handedness": table.handedness[index], "model": model,
                   "club_speed [m/s]": table.delivery["club_speed"][index],
                   "attack_angle [deg]": table.delivery["attack_angle"][index] * RAD_TO_DEG,
                   "dynamic_loft [deg]": table.delivery["dynamic_loft"][index] * RAD_TO_DEG,
                   "path [deg]": table.delivery["path"][index] * RAD_TO_DEG,
                   "face_angle [deg]": table.delivery["face_angle"][index] * RAD_TO_DEG}
            for field, unit, factor in _CSV_QUANTITIES:
                measured = table.measured[field][index] * factor
                value = predicted[field][index] * factor
                row[f"{field} measured [{unit}]"] = measured
                row[f"{field} predicted [{unit}]"] = value
            out.append(row)
    return out


def write_prediction_rows(rows: list[dict], path) -> Path:
    """Write :func:`prediction_rows` as CSV (measured beside predicted; empty cells: not measured)."""
    import csv
    import io

    columns = ["table", "shot", "club", "handedness", "model", "club_speed [m/s]", "attack_angle [deg]",
               "dynamic_loft [deg]", "path [deg]", "face_angle [deg]"]
    for field, unit, _ in _CSV_QUANTITIES:
        columns += [f"{field} measured [{unit}]", f"{field} predicted [{unit}]"]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow(["" if isinstance(row[key], float) and not math.isfinite(row[key])
                         else (f"{row[key]:.6g}" if isinstance(row[key], float) else row[key])
                         for key in columns])
    return write_atomically(path, buffer.getvalue().encode())


def _unpredicted(predicted: dict, table: ShotTable) -> list[str]:
    """Labels of the rows whose prediction of a measured value is not finite (left out of every RMS)."""
    usable = usable_rows(np.stack([predicted[key] for key in MEASURED_FIELDS], axis=1),
                         np.stack([table.measured[key] for key in MEASURED_FIELDS], axis=1))
    return [label for label, ok in zip(table.labels, usable) if not ok]


def fit_shots(table: ShotTable, models: Sequence[str] | None = None, parameters: Sequence[str] | None = None,
              cross_validate: bool = False,
              json_path: str | None = None, by: str | None = None, folds: int = 5,
              path: str | None = None) -> int:
    """Calibrate ``models`` on ``table`` (and cross-validate); print the fits; optionally write them as JSON.

    ``by`` is what a cross-validation fold holds out: ``source`` (whole sources; the default when the table's rows
    name several), ``block`` (contiguous blocks of rows; the default otherwise), both in ``folds`` folds refitted
    from the full fit's values (a warm start), or ``row``: leave-one-row-out in closed form from the full fit
    (:func:`impactlab.data.fit.calibration.leave_one_row_out`, no refits). The JSON file holds each fit's model,
    parameters, values, bounds and provenance (``path``'s SHA-256): ``impactlab validate --fit`` applies it."""
    sources = len(set(table.sources))
    if by is None:
        by = "source" if sources > 1 else "block"
    if cross_validate and by == "source" and sources < 2:
        raise FieldError("--by", "several sources among the table's rows (a row's source:) to leave one out",
                         f"source ({sources} source in {table.name})")
    results = []
    for name in models or FIT_MODELS:
        model = get_model(name)()
        names = parameters or [p for p in DEFAULT_PARAMETERS
                               if p != "tangential_loss" or "tangential_loss" in model.optional_inputs]
        result = calibrate(model, table, names)
        print(f"{name} on {table.name} ({table.size} rows): {result.describe()}")
        if name == (models or FIT_MODELS)[0]:
            for line in skipped_text(table):
                print(line)
        if result.unused_rows:
            print(f"  rows not used (the model cannot predict them): {labels_text(result.unused_rows)}")
        keys = [key for key in ERROR_KEYS if math.isfinite(result.errors_after[key])]
        print("  RMS errors before: " + ", ".join(f"{k} {result.errors_before[k]:.2f}" for k in keys))
        print("  RMS errors after:  " + ", ".join(f"{k} {result.errors_after[k]:.2f}" for k in keys))
        print("  correlation: " + "; ".join(f"{a}-{b} {result.correlation[i][j]:+.2f}"
                                           for i, a in enumerate(result.parameters)
                                           for j, b in enumerate(result.parameters) if j > i))
        entry = result.as_dict()
        entry["bounds"] = bounds_of(result.parameters)
        entry["provenance"] = provenance(path, table)
        if cross_validate and table.size > 1 and by == "row":
            held = leave_one_row_out(model, table, result)
            print("  leave-one-out by row, in closed form (one Gauss-Newton step per row from the full fit, no "
                  "refits; errors on the row left out): " + ", ".join(f"{k} {held['summary'][k]:.2f}" for k in keys))
            if len(held["labels"]) <= 20:
                for index, label in enumerate(held["labels"]):
                    print(f"    {label:<20}" + "  ".join(f"{k.split(' [')[0]} {held['errors'][k][index]:+.2f}"
                                                         for k in keys))
            entry["cross_validation"] = {"by": "row", "method": held["method"], "summary": held["summary"],
                                         "fits": held["fits"], "by_source": held["by_source"],
                                         "errors": {k: v.tolist() for k, v in held["errors"].items()}}
        elif cross_validate and table.size > 1:
            kind, parts = make_folds(table, folds, by="group" if by == "source" else "block")
            held = leave_one_out(model, table, names, folds=parts, start=dict(zip(result.parameters, result.values)))
            units = [sorted(set(table.sources[i] for i in part)) if kind == "group" else part for part in parts]
            single = all(len(unit) == 1 for unit in units)
            unit_name = "whole sources" if kind == "group" else "contiguous blocks of rows"
            what = ("leave-one-out by " + ("source" if kind == "group" else "row") if single
                    else f"{len(parts)}-fold cross-validation by {unit_name}")
            print(f"  {what} (errors on the rows not fitted; each fold refitted from the full fit's values): "
                  + ", ".join(f"{k} {held['summary'][k]:.2f}" for k in keys))
            for part, unit, calibration in zip(parts, units, held["calibrations"]):
                errors = summary({key: values[part] for key, values in held["errors"].items()})
                named = (", ".join(unit) if kind == "group" else
                         f"{table.labels[part[0]]}" + (f" to {table.labels[part[-1]]}" if len(part) > 1 else ""))
                print(f"    held out {named} ({len(part)} rows): " + ", ".join(f"{k} {errors[k]:.2f}" for k in keys))
                print(f"      fitted on the others: {calibration.describe()}")
            entry["cross_validation"] = {"by": by, "summary": held["summary"], "fits": held["fits"],
                                         "by_source": held["by_source"], "folds": held["folds"],
                                         "errors": {k: v.tolist() for k, v in held["errors"].items()}}
        results.append(entry)
    if json_path:
        write_atomically(json_path, json.dumps(results, indent=1, default=float).encode())
        print(f"wrote {json_path} (apply it to other shots: impactlab validate --dataset OTHER.csv --fit "
              f"{json_path})", file=sys.stderr)
    return 0


#: the pseudo-dataset ``impactlab validate --dataset observations``: published differences between shots
OBSERVATIONS = "observations"


def print_observations(models: Sequence[str], options: dict | None = None) -> None:
    """Print each model's ratio to the published gear-effect and cover observations
    (:mod:`impactlab.data.validation.observations`), rows = observation, columns = model; 1 is agreement.

    ``options`` maps a model id to its options (default: none, the paper's models)."""
    observations = load_observations()
    print("observations: model / published (1 = agreement; target 0.5-1.5)")
    for members in observations.values():
        for observation in members:
            print(f"  {describe(observation)}")
    print(f"  {'observation':<50}" + "".join(f"{model:>16}" for model in models))
    rows = (("gear_effect", gear_effect, "spin-axis change", "ratio"),
            ("vertical_gear_effect", vertical_gear_effect, "spin change", "ratio"),
            ("vertical_gear_effect", vertical_gear_effect, "launch change", "ratio_launch"),
            ("cover", cover_effect, "wedge cover difference", "ratio"))
    for family, compute, what, key in rows:
        for observation in observations[family]:
            cells = [compute(get_model(m)(**(options or {}).get(m, {})), observation)[key] for m in models]
            print(f"  {observation.name + ' ' + what:<50}" + "".join(f"{c:16.3f}" for c in cells))
    print()


def print_scorecard(table: ShotTable, models: Sequence[str] = (), fits: Sequence | None = None,
                    holdout: float = HOLDOUT, report: str | None = None, rows: list | None = None,
                    in_sample: Sequence[str] = (), carry: dict | None = None, keep: list | None = None) -> xr.Dataset:
    """Print :func:`scorecard` of ``table`` (and write the HTML report ``report``); return the Dataset.

    ``rows``, when given a list, receives the per-shot table of the held-out rows
    (:func:`impactlab.data.shot_report.prediction_rows`); ``in_sample`` names fits made on this very file;
    ``carry`` is the monitor's carry of each row (:func:`measured_carry`); ``keep``, when given a list, receives
    the arguments of :func:`impactlab.data.validation.report.write_report` after ``path`` (table, split, card,
    predictions), for a caller that writes the report later (the command line, after its last refusal)."""
    print(f"{table.name}: {table.size} row(s) ({labels_text(table.labels)})")
    print(f"  source: {table.source}")
    for line in skipped_text(table):
        print(line)
    split = holdout_split(table, holdout)
    predicted: dict = {}
    card = scorecard(table, models, fits, split, predictions=predicted, carry=carry)
    print(format_scorecard(card))
    for label in in_sample:
        print(f"  NOTE: {label} was fitted on this very file: its errors here are in-sample, not a test")
    lost = losers(card)
    if lost:
        print("  models whose median |error| is worse than a baseline's (fitted on the training rows only):")
        for model, beaten in lost.items():
            print(f"    {model}: " + "; ".join(f"{b} beats it on {', '.join(outputs)}"
                                           for b, outputs in beaten.items()))
    print()
    if rows is not None:
        rows.extend(prediction_rows(table.subset(split.test), predicted))
    if keep is not None:
        keep.append((table, split, card, predicted))
    if report:
        print(f"wrote {write_report(report, table, split, card, predicted)}", file=sys.stderr)
    return card


def measured_carry(path: str, table: ShotTable) -> dict | None:
    """The monitor's carry of each row of ``table`` read from the session file ``path`` [m], and whether it was
    measured: a carry the export flags estimated, clamped or modelled (a monitor's own flight model: TrackMan's
    flights tracked for less than 90 % of their hang time) is not.

    None when the file gives no carry, is no session export, or its rows cannot be matched to the table's (a label
    column replaces the ``line N`` labels)."""
    shipped = path in SESSION_DATASETS and not Path(path).exists()
    if not shipped and Path(path).suffix.lower() not in (".csv", ".gz", *JSON_SESSIONS):
        return None
    session = read_session(path)
    values = session.values.get("carry_distance")
    if values is None or not np.isfinite(values).any():
        return None
    row_of = {f"line {line}": index for index, line in enumerate(session.lines.tolist())}
    index = [row_of.get(label) for label in table.labels]
    if any(i is None for i in index):
        return None
    rows = np.array(index)
    # tracked: a carry the monitor measured (not flagged, not its model output of a flight tracked too briefly or
    # of unknown tracking): one rule with fly's (Session.carry_measured)
    return {"measured": values[rows], "tracked": session.carry_measured()[rows]}
