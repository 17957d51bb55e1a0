"""The scorecard of a session: every model, a fit applied to it and two baselines, against shots they never saw.

``impactlab validate --dataset FILE`` (and :func:`scorecard`) splits a launch-monitor session into a training part
and a held-out part (:func:`holdout_split`: whole groups where the table has them, contiguous blocks of rows
otherwise, never shuffled rows: neighbouring shots of one player are not independent), fits the baselines
(:mod:`impactlab.data.validation.baselines`) on the training part only, and evaluates every model, every applied
fit and both baselines on the same held-out rows. Per output (ball speed and spin rate as a relative error [%],
launch angle, launch direction and spin axis in degrees) it gives

- ``n``: the held-out rows where the output was measured and predicted;
- ``median_abs`` and ``p90_abs``: the median and 90th percentile of the absolute error (numpy's default
  percentile, linear interpolation between order statistics: Hyndman & Fan's definition 7);
- ``bias``: the MEDIAN of the signed error (prediction minus measurement; robust to the mishits a session holds);
- ``rms``: the root mean square of the error;

overall, per club-speed band (:data:`SPEED_BANDS`) and per strike zone where the strike location is known
(:func:`strike_zones`), and beside them the instrument's floor (:data:`INSTRUMENT_FLOOR`): what the monitor's own
repeatability allows, with its source, so that a reader sees when a model is as good as the measurement permits.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping, Sequence

import numpy as np
import xarray as xr

from impactlab.data.sessions.shots import ERROR_KEYS, ShotTable, predict, shot_errors, table_inputs
from impactlab.data.validation import baselines as baseline_models
from impactlab.data.validation.head_cor import head_cor_note
from impactlab.data.validation.splits import (  # noqa: F401 (the splits are the scorecard's: importable from here)
    BLOCKS, HOLDOUT, MIN_ROWS, Split, folds, holdout_split,
)
from impactlab.model.registry import available, get_model
from impactlab.scene.flight import fly
from impactlab.units import MPH

#: the statistics of each output's error (coordinate ``statistic``)
STATISTICS = ("n", "median_abs", "p90_abs", "bias", "rms")
#: what each statistic is, in words (the Dataset's ``statistic`` attrs and the printed table's legend)
STATISTIC_MEANING = {
    "n": "held-out rows where the output was measured and predicted",
    "median_abs": "median of |predicted - measured|",
    "p90_abs": "90th percentile of |predicted - measured| (linear interpolation, numpy's default)",
    "bias": "median of (predicted - measured): a median, not a mean",
    "rms": "root mean square of (predicted - measured)",
}
#: the scorecard's row of the monitor's own launch flown (with a measured carry)
FLOWN = "launch flown"
#: club-speed bands [mph] (TrackMan's unit of club speed; the lower edge included)
SPEED_BANDS = ((0.0, 80.0), (80.0, 90.0), (90.0, 100.0), (100.0, 110.0), (110.0, math.inf))
#: a strike within this distance of the face centre along both axes is "centre" [m]
STRIKE_CENTRE = 0.010
#: strike zones in the order printed
STRIKE_ZONES = ("centre", "toe", "heel", "high", "low")

#: The instrument's floor: how well the monitor itself measures each output (one standard deviation or the
#: stated accuracy), in the units of the output's error, with its source and what kind of number it is. TrackMan
#: publishes no per-parameter accuracy table that this project could find; an independent validation exists
#: (Leach R.J., Forrester S.E., Mears A.C., Roberts J.R. 2017, "How valid and accurate are measurements of golf
#: impact parameters obtained using commercially available radar and stereoscopic optical launch monitors?",
#: Measurement 112:125-136) but its limits of agreement were not retrieved (/work/notes/lit33.md section 5).
INSTRUMENT_FLOOR: dict[str, tuple[float, str]] = {
    "ball_speed [%]": (0.5, "CLAIM, secondary and unsourced (no TrackMan statement found): two TrackMan units side "
                            "by side agree to about +-0.5 % in ball speed (golflaunchlab.com guide; lit33 section 5)"),
    "launch angle [deg]": (math.nan, "not found: no published TrackMan accuracy for launch angle (Leach et al. "
                                     "2017, Measurement 112:125, has limits of agreement; not retrieved)"),
    "launch direction [deg]": (math.nan, "not found: no published TrackMan accuracy for launch direction (Leach et "
                                         "al. 2017 not retrieved)"),
    "spin [%]": (math.nan, "VENDOR CLAIM, weak provenance: spin rate 'within 20 rpm' (a repost of TrackMan's "
                           "technical text, skyfert.blogg.se 2022; lit33 section 5): 20 rpm as a percentage of the "
                           "held-out rows' median spin"),
    "spin axis [deg]": (math.nan, "not found: no published TrackMan accuracy for spin axis (Leach et al. 2017 not "
                                  "retrieved)"),
}
#: the spin-rate claim [rpm] behind the spin floor (a percentage of each table's median spin)
SPIN_FLOOR_RPM = 20.0


# -- statistics --------------------------------------------------------------------------------------------------
def error_statistics(errors) -> np.ndarray:
    """The :data:`STATISTICS` of signed errors (NaN entries: not measured or not predicted, left out).

    Returns
    -------
    ndarray, shape (5,)
        n, median |e|, 90th percentile |e|, median e (the bias), RMS of e; NaN (and n = 0) when no error is
        finite.
    """
    values = np.asarray(errors, dtype=float)
    values = values[np.isfinite(values)]
    if values.size == 0:
        return np.array([0.0, math.nan, math.nan, math.nan, math.nan])
    size = np.abs(values)
    return np.array([float(values.size), float(np.median(size)), float(np.percentile(size, 90)),
                     float(np.median(values)), float(np.sqrt(np.mean(values**2)))])


def speed_band_labels() -> list[str]:
    """The labels of :data:`SPEED_BANDS` ('<80 mph', '80-90 mph', ..., '>=110 mph')."""
    out = []
    for low, high in SPEED_BANDS:
        out.append(f"<{high:g} mph" if low == 0 else (f">={low:g} mph" if math.isinf(high) else
                                                       f"{low:g}-{high:g} mph"))
    return out


def speed_bands(club_speed) -> np.ndarray:
    """The :data:`SPEED_BANDS` index of each club speed [m/s] (-1: unknown)."""
    mph = np.asarray(club_speed, dtype=float) / MPH
    out = np.full(mph.shape, -1)
    for j, (low, high) in enumerate(SPEED_BANDS):
        out[(mph >= low) & (mph < high)] = j
    return out


def strike_zones(strike_toe, strike_high) -> np.ndarray:
    """The :data:`STRIKE_ZONES` index of each strike (-1: location unknown).

    Within :data:`STRIKE_CENTRE` of the face centre along both axes: ``centre``; otherwise the direction of the
    larger offset: ``toe`` / ``heel`` (towards the toe positive) or ``high`` / ``low`` (up the face positive)
    [m]."""
    toe = np.asarray(strike_toe, dtype=float)
    high = np.asarray(strike_high, dtype=float)
    out = np.full(toe.shape, -1)
    known = np.isfinite(toe) & np.isfinite(high)
    centre = known & (np.abs(toe) <= STRIKE_CENTRE) & (np.abs(high) <= STRIKE_CENTRE)
    sideways = known & ~centre & (np.abs(toe) >= np.abs(high))
    out[centre] = 0
    out[sideways & (toe > 0)] = 1
    out[sideways & (toe <= 0)] = 2
    upwards = known & ~centre & ~sideways
    out[upwards & (high > 0)] = 3
    out[upwards & (high <= 0)] = 4
    return out


# -- the scorecard ---------------------------------------------------------------------------------------------
#: the carry's error key (an output of the scorecard when a measured carry is given)
CARRY = "carry [m]"
INSTRUMENT_FLOOR[CARRY] = (math.nan, "not found: no published TrackMan accuracy for a tracked carry (Leach et al. "
                                     "2017 not retrieved)")


def carry_errors(test: ShotTable, predicted: dict, measured: np.ndarray, tracked: np.ndarray) -> np.ndarray:
    """Per held-out row: the carry of the predicted launch, flown by impactlab's flight model in standard air
    (:func:`impactlab.scene.flight.fly`), minus the monitor's measured carry [m]; NaN where the carry was not
    tracked or the launch cannot be flown (no speed, launch or spin above zero)."""
    out = np.full(test.size, math.nan)
    speed, launch, spin = (predicted[k] for k in ("ball_speed", "vertical_launch_angle", "spin_rate"))
    rows = np.flatnonzero(tracked & np.isfinite(measured) & np.isfinite(speed) & (launch > 0) & (spin > 0))
    if rows.size:
        with warnings.catch_warnings():  # mishits' unusual launches are flown as given
            warnings.simplefilter("ignore")
            flown = fly(speed[rows], launch[rows], spin[rows], np.nan_to_num(predicted["spin_axis"][rows]),
                        np.nan_to_num(predicted["horizontal_launch_angle"][rows]))
        out[rows] = flown["carry_distance"].values - measured[rows]
    return out


#: the monitor whose claims :data:`INSTRUMENT_FLOOR` holds (``ShotTable.instrument``)
FLOOR_INSTRUMENT = "trackman"


def _floor(table: ShotTable, outputs: Sequence[str]) -> tuple[np.ndarray, list[str]]:
    """The instrument's floor beside each output: TrackMan's claims for TrackMan's rows only; for another monitor's
    rows (or rows whose monitor is not stated) no floor, and the line says so, rather than another maker's claim."""
    values, sources = [], []
    if table.instrument != FLOOR_INSTRUMENT:
        which = f"this table's monitor ({table.instrument})" if table.instrument else "a monitor not stated"
        note = (f"not known for {which}: the floors this project found are TrackMan's claims, which say nothing "
                "of another monitor")
        return np.full(len(outputs), math.nan), [note] * len(outputs)
    for key in outputs:
        value, source = INSTRUMENT_FLOOR[key]
        if key == "spin [%]":
            spin = table.measured["spin_rate"][np.isfinite(table.measured["spin_rate"])] * 60.0 / (2 * math.pi)
            value = 100.0 * SPIN_FLOOR_RPM / float(np.median(spin)) if spin.size else math.nan
        values.append(value)
        sources.append(source)
    return np.array(values), sources


def _predict_held_out(train: ShotTable, test: ShotTable, models: Sequence[str], fit: Sequence | None,
                      baselines: bool) -> tuple[list[str], list[str], dict[str, dict], list[str], str]:
    """The held-out rows' launches by every model, every applied fit and the baselines fitted on ``train``: the
    names, their kinds, the predicted arrays per name, the notes (a baseline that could not be fitted) and the
    regression's coefficients in words."""
    names: list[str] = []
    kinds: list[str] = []
    predicted: dict[str, dict] = {}
    notes: list[str] = []
    inputs = table_inputs(test)
    for name in models or sorted(available()):
        predicted[name] = predict(get_model(name)(), inputs)
        names.append(name)
        kinds.append("model")
    for fitted in fit or ():
        label = fitted.label
        predicted[label] = fitted.predict(test, inputs)
        names.append(label)
        kinds.append("fit")
    coefficients = ""
    if baselines:
        regression = baseline_models.PhysicsRegression.fitted(train)
        predicted[baseline_models.REGRESSION] = regression.predict(test)
        names.append(baseline_models.REGRESSION)
        kinds.append("baseline")
        coefficients = regression.describe()
        flexible = baseline_models.flexible_baseline(train)
        if isinstance(flexible, str):
            notes.append(flexible)
        else:
            predicted[baseline_models.FLEXIBLE] = flexible.predict(test)
            names.append(baseline_models.FLEXIBLE)
            kinds.append("baseline")
    return names, kinds, predicted, notes, coefficients


def _error_tables(test: ShotTable, names: Sequence[str], outputs: Sequence[str], predicted: Mapping[str, dict],
                  groupings: Sequence[tuple[np.ndarray, int]], measured_carry: np.ndarray | None,
                  tracked: np.ndarray | None) -> tuple[np.ndarray, list[np.ndarray]]:
    """The error statistics of each name and output on the held-out rows: overall (name, output, statistic), and per
    group of each grouping (codes per row, -1 for none, and the number of groups: club-speed band, strike zone, ball
    setting), a fourth axis each."""
    shape = (len(names), len(outputs), len(STATISTICS))
    overall = np.full(shape, np.nan)
    grouped = [np.full((*shape, count), np.nan) for _, count in groupings]
    for i, name in enumerate(names):
        errors = shot_errors(predicted[name], test)
        if measured_carry is not None and tracked is not None:
            errors[CARRY] = carry_errors(test, predicted[name], measured_carry, tracked)
            if name == FLOWN:  # the monitor's launch against itself: no launch error, only the flight's
                errors.update({key: np.full(test.size, np.nan) for key in ERROR_KEYS})
        for j, key in enumerate(outputs):
            values = np.asarray(errors[key], dtype=float)
            if key in ("launch direction [deg]", "spin axis [deg]"):  # angles: the short way round
                values = (values + 180.0) % 360.0 - 180.0
            overall[i, j] = error_statistics(values)
            for table, (codes, count) in zip(grouped, groupings):
                for g in range(count):
                    table[i, j, :, g] = error_statistics(values[codes == g])
    return overall, grouped


def scorecard(table: ShotTable, models: Sequence[str] = (), fit: Sequence | None = None,
              holdout: float | Split = HOLDOUT, groups: Sequence | None = None,
              baselines: bool = True, predictions: dict | None = None, carry: Mapping | None = None) -> xr.Dataset:
    """Every model, applied fit and baseline against the same held-out rows of ``table``.

    Parameters
    ----------
    table : ShotTable
        A session (thousands of shots are the use; at least :data:`MIN_ROWS` without groups).
    models : sequence of str
        Registered model names (any, the plugins' too; default: every registered model).
    fit : sequence of FittedModel, optional
        Fits made on other shots (:func:`impactlab.data.validation.fits.load_fits`), applied to the held-out rows.
    holdout : float or Split
        The fraction held out (:func:`holdout_split`) or a split of the caller's.
    groups : sequence, optional
        A group label per row (player, session, date): whole groups are held out.
    baselines : bool
        Fit and evaluate the baselines (:mod:`impactlab.data.validation.baselines`).
    predictions : dict, optional
        Filled with name -> predicted arrays (SI) of the held-out rows, for a report.
    carry : mapping, optional
        The monitor's carry per row of ``table``: ``measured`` [m] (NaN: none) and ``tracked`` (bool: the radar
        followed the flight; default every measured carry). Adds the output ``carry [m]``: each launch flown in
        standard air minus the measured carry, on the tracked held-out rows only, and a row ``launch flown``: the
        monitor's own launch flown, the flight model's share of the carry error.

    Returns
    -------
    xarray.Dataset
        ``error`` (model, output, statistic), ``error_by_speed`` (..., speed_band), ``error_by_strike`` (...,
        strike_zone), ``error_by_ball`` (..., ball_setting: the export's ball settings, none if it names none),
        ``floor`` and ``floor_source`` (output), ``kind`` (model: model, fit or baseline); attrs say the split, the
        bias's definition, the baselines' coefficients and what could not be computed.
    """
    split = holdout if isinstance(holdout, Split) else holdout_split(table, holdout, groups)
    train, test = table.subset(split.train), table.subset(split.test)
    names, kinds, predicted, notes, coefficients = _predict_held_out(train, test, models, fit, baselines)
    outputs = list(ERROR_KEYS)
    measured_carry = tracked = None
    if carry is not None:
        measured_carry = np.asarray(carry["measured"], dtype=float)[split.test]
        tracked = np.asarray(carry.get("tracked", np.ones(table.size, bool)), dtype=bool)[split.test]
        outputs.append(CARRY)
        predicted[FLOWN] = {key: test.measured[key] for key in test.measured}
        names.append(FLOWN)
        kinds.append("flight")
    if predictions is not None:  # the models' launches (the monitor's own is the table's)
        predictions.update({name: values for name, values in predicted.items() if name != FLOWN})
    bands = speed_bands(test.delivery["club_speed"])
    zones = strike_zones(test.delivery["strike_toe"], test.delivery["strike_high"])
    if test.strike_known is not None:  # a strike the file did not give is the face centre in the table: unknown
        zones[~test.strike_known] = -1
    band_labels = speed_band_labels()
    settings = sorted({s for s in test.ball_settings if s})
    balls = np.array([settings.index(s) if s else -1 for s in test.ball_settings] if test.ball_settings
                     else np.full(test.size, -1), dtype=int)
    overall, (by_speed, by_strike, by_ball) = _error_tables(
        test, names, outputs, predicted, [(bands, len(SPEED_BANDS)), (zones, len(STRIKE_ZONES)),
                                          (balls, len(settings))], measured_carry, tracked)
    floor, sources = _floor(test, outputs)
    statistic_attrs = {"meaning": "; ".join(f"{k}: {v}" for k, v in STATISTIC_MEANING.items())}
    return xr.Dataset(
        {"error": (("model", "output", "statistic"), overall),
         "error_by_speed": (("model", "output", "statistic", "speed_band"), by_speed),
         "error_by_strike": (("model", "output", "statistic", "strike_zone"), by_strike),
         "error_by_ball": (("model", "output", "statistic", "ball_setting"), by_ball),
         "floor": (("output",), floor, {"meaning": "the instrument's stated or measured accuracy, in the units of "
                                                   "the output's error (NaN: none found)"}),
         "floor_source": (("output",), np.array(sources, dtype=object)),
         "kind": (("model",), np.array(kinds, dtype=object)),
         "rows_in_speed_band": (("speed_band",), np.bincount(bands[bands >= 0], minlength=len(SPEED_BANDS))),
         "rows_in_strike_zone": (("strike_zone",), np.bincount(zones[zones >= 0], minlength=len(STRIKE_ZONES))),
         "rows_in_ball_setting": (("ball_setting",), np.bincount(balls[balls >= 0], minlength=len(settings)))},
        coords={"model": names, "output": outputs, "statistic": (("statistic",), list(STATISTICS),
                                                                          statistic_attrs),
                "speed_band": band_labels, "strike_zone": list(STRIKE_ZONES), "ball_setting": settings},
        attrs={"table": table.name, "source": table.source, "split": split.describe(), "split_by": split.by,
               "held_out_rows": int(split.test.size), "training_rows": int(split.train.size),
               "bias": "median of the signed error (predicted - measured)",
               "errors": "ball speed and spin: 100 (predicted / measured - 1) [%]; angles: predicted - measured "
                         "[deg], launch direction and spin axis the short way round",
               "baseline_coefficients": coefficients, "notes": "; ".join(notes),
               "head_cor": head_cor_note([n for n, k in zip(names, kinds) if k == "model"], test.clubs, table.ball),
               "carry": "" if carry is None else (
                   "each launch flown by impactlab's flight model in standard air (15 degC, 1013.25 hPa, 50 %, no "
                   "wind) against the monitor's carry on the held-out shots it tracked; the monitor flew in its own "
                   "air, not stated in the file: 'launch flown' is the monitor's launch flown, the flight's share")})


# -- printing ----------------------------------------------------------------------------------------------------
def _cell(value: float, width: int = 9, spec: str = ".2f") -> str:
    return f"{'-':>{width}}" if not math.isfinite(value) else f"{value:{width}{spec}}"


def format_scorecard(card: xr.Dataset, breakdowns: bool = True) -> str:
    """The scorecard as text: per output a table (rows: models, fits, baselines, the instrument's floor;
    columns: the statistics), then the median |error| per club-speed band and per strike zone."""
    lines = [f"scorecard of {card.attrs['table']}: {card.attrs['split']}",
             f"  bias = {card.attrs['bias']}; errors: {card.attrs['errors']}"]
    if card.attrs.get("baseline_coefficients"):
        lines.append(f"  baselines fitted on the training rows: {card.attrs['baseline_coefficients']}")
    if card.attrs.get("notes"):
        lines.append(f"  NOTE: {card.attrs['notes']}")
    if card.attrs.get("head_cor"):
        lines.append(f"  NOTE: {card.attrs['head_cor']}")
    if card.attrs.get("carry"):
        lines.append(f"  carry: {card.attrs['carry']}")
    models = [str(m) for m in card["model"].values]
    kinds = dict(zip(models, card["kind"].values))
    width = max(22, *(len(m) + 13 for m in models))
    for output in card["output"].values:
        lines.append("")
        lines.append(f"  {output:<{width}}{'n':>7}{'median|e|':>11}{'p90|e|':>10}{'bias':>10}{'rms':>10}")
        for model in models:
            n, median, p90, bias, rms = card["error"].sel(model=model, output=output).values
            tag = {"baseline": " (baseline)", "fit": ""}.get(str(kinds[model]), "")
            lines.append(f"  {model + tag:<{width}}{int(n):7d}{_cell(median, 11)}{_cell(p90, 10)}{_cell(bias, 10)}"
                         f"{_cell(rms, 10)}")
        floor = float(card["floor"].sel(output=output))
        source = str(card["floor_source"].sel(output=output).values)
        lines.append(f"  {'instrument floor':<{width}}{'':7}{_cell(floor, 11)}   {source}")
    if breakdowns:
        for variable, dimension, counts, title in (
                ("error_by_speed", "speed_band", "rows_in_speed_band", "median |error| by club-speed band"),
                ("error_by_strike", "strike_zone", "rows_in_strike_zone",
                 f"median |error| by strike zone (centre: within {STRIKE_CENTRE * 1e3:g} mm of the face centre; "
                 "held-out rows with a known strike only)"),
                ("error_by_ball", "ball_setting", "rows_in_ball_setting",
                 "median |error| by the monitor's ball setting (the export's; every model runs the same ball)")):
            if variable not in card:  # a scorecard written before the breakdown existed
                continue
            present = [str(b) for b, c in zip(card[dimension].values, card[counts].values) if c > 0]
            if dimension == "ball_setting" and len(present) < 2:
                continue  # one ball setting or none: the overall table is its breakdown
            if not present:
                lines += ["", f"  {title}: no held-out row has one"]
                continue
            rows = {str(b): int(c) for b, c in zip(card[dimension].values, card[counts].values)}
            lines += ["", f"  {title}:"]
            columns = [max(18, len(f"{b} ({rows[b]})") + 2) for b in present]  # long ball settings widen theirs
            for output in card["output"].values:
                lines.append(f"  {output:<{width}}" + "".join(f"{b + f' ({rows[b]})':>{w}}"
                                                               for b, w in zip(present, columns)))
                for model in models:
                    cells = card[variable].sel(model=model, output=output, statistic="median_abs")
                    lines.append(f"    {model:<{width - 2}}" + "".join(_cell(float(cells.sel({dimension: b})), w)
                                                                for b, w in zip(present, columns)))
    return "\n".join(lines)


def losers(card: xr.Dataset, statistic: str = "median_abs") -> dict[str, dict[str, list[str]]]:
    """Per model (or fit), per baseline: the outputs on which the baseline's ``statistic`` is smaller (better)."""
    out: dict[str, dict[str, list[str]]] = {}
    kinds = dict(zip((str(m) for m in card["model"].values), card["kind"].values))
    base = [m for m, k in kinds.items() if k == "baseline"]
    for model, kind in kinds.items():
        if kind in ("baseline", "flight"):
            continue
        for output in card["output"].values:
            value = float(card["error"].sel(model=model, output=output, statistic=statistic))
            for b in base:
                if float(card["error"].sel(model=b, output=output, statistic=statistic)) < value:
                    out.setdefault(model, {}).setdefault(b, []).append(str(output).split(" [")[0])
    return out


def named(card: Mapping, model: str) -> dict:
    """The overall statistics of one model as a plain mapping output -> statistic -> value (tests, reports)."""
    error = card["error"].sel(model=model)
    return {str(o): {str(s): float(error.sel(output=o, statistic=s)) for s in STATISTICS}
            for o in error["output"].values}
