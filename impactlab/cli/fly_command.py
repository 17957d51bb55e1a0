"""``impactlab fly``: yards from a launch, or from every shot of a launch-monitor session.

Two forms:

- ``impactlab fly --ball-speed "167 mph" --launch-angle "10.9 deg" --spin-rate "2686 rpm"`` flies the launch (or
  launches: each option takes several values, which broadcast) given on the command line;
- ``impactlab fly SESSION`` flies each shot of an export with its measured launch
  (:func:`impactlab.data.sessions.flight.fly_session`) and prints the monitor's own carry beside the prediction.

Every value carries its unit (a bare number is refused: no unit is guessed). The air is the standard air unless
``--temperature``, ``--pressure`` or ``--altitude``, ``--humidity``, ``--headwind``, ``--crosswind`` say otherwise;
a session's shots fly in the air their export states (Garmin's weather columns, TrackMan's Condition) unless an
option of the air itself (``--temperature``, ``--pressure``, ``--altitude``, ``--humidity``: they then set the whole
air of every shot) or ``--standard-air`` is given; ``--headwind`` and ``--crosswind`` alone blow through each shot's
own air.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import warnings

import numpy as np
import xarray as xr

from impactlab.data.sessions.reader import read_session
from impactlab.data.sessions.flight import MONITOR, PREDICTED, fly_session
from impactlab.data.sessions.summary import skip_lines
from impactlab.errors import FieldError, PlausibilityWarning, StudyError
from impactlab.foreign import shown
from impactlab.io.safe_output import (TABLE_SUFFIXES, check_output, refuse_overwriting, refuse_replacing_foreign,
                                      write_atomically)
from impactlab.physics.aerodynamics import DEFAULT_MODEL, MODEL_REFERENCES, MODELS, retired_reason
from impactlab.scene import flight
from impactlab.units import DIMENSIONS, MPH, YARD, registry

#: command-line option -> key of impactlab.fly's ``conditions``
AIR_OPTIONS = {"temperature": "temperature", "pressure": "pressure", "altitude": "altitude",
               "humidity": "relative_humidity", "headwind": "headwind", "crosswind": "crosswind"}
#: command-line option -> argument of impactlab.fly (the launch)
LAUNCH_OPTIONS = {"ball_speed": "ball speed", "launch_angle": "launch angle", "spin_rate": "spin rate",
                  "spin_axis": "spin axis (positive: curving right)",
                  "launch_direction": "launch direction (positive: right of the target)"}
#: printed columns: (title, variable, factor from the dataset's unit, format)
#: the launch options' dimensions (impactlab.units.DIMENSIONS)
LAUNCH_DIMENSIONS = {"ball_speed": "speed", "launch_angle": "angle", "spin_rate": "angular_speed",
                     "spin_axis": "angle", "launch_direction": "angle"}
#: the launch flown, in the result: (option, variable, factor from SI, unit)
LAUNCH_COLUMNS = [("ball_speed", "ball_speed", 1.0, "m/s"), ("launch_angle", "vertical_launch_angle", 180 / np.pi,
                                                             "degree"),
                  ("spin_rate", "spin_rate", 30 / np.pi, "rpm"), ("spin_axis", "spin_axis", 180 / np.pi, "degree")]
COLUMNS = [("carry yd", "carry_distance", 1 / YARD, "{:.1f}"), ("offline yd", "offline_distance", 1 / YARD, "{:+.1f}"),
           ("apex yd", "apex_height", 1 / YARD, "{:.1f}"), ("land deg", "landing_angle", 1.0, "{:.1f}"),
           ("time s", "flight_time", 1.0, "{:.2f}")]


def _model_name(name: str) -> str:
    """``--model``'s value: a retired model is refused with why and what to use (argparse's choices say neither)."""
    if retired_reason(name):
        raise argparse.ArgumentTypeError(retired_reason(name))
    return name


def add_parser(commands) -> None:
    """The ``fly`` subcommand's arguments."""
    fly = commands.add_parser("fly", help="carry, offline, apex, landing angle and flight time of a launch, or of "
                                          "every shot of a launch-monitor session beside the monitor's own")
    fly.add_argument("file", nargs="?", help="a session file as exported (any `impactlab shots` reads); or give a "
                                             "launch with --ball-speed, --launch-angle and --spin-rate")
    for option, words in LAUNCH_OPTIONS.items():
        fly.add_argument(f"--{option.replace('_', '-')}", nargs="+", metavar="VALUE",
                         help=f"{words}, with its unit (e.g. {_EXAMPLES[option]}); several values broadcast")
    for option, key in AIR_OPTIONS.items():
        # argparse %-formats help texts: a literal % (humidity's '50 %') is written %%
        fly.add_argument(f"--{option}", metavar="VALUE", help=f"the air: {_AIR_WORDS[key]}".replace("%", "%%"))
    fly.add_argument("--model", default=DEFAULT_MODEL, choices=sorted(MODELS), type=_model_name,
                     help=f"aerodynamic model (default {DEFAULT_MODEL}; docs/flight.md)")
    fly.add_argument("--vendor", help="a session: read with this vendor layout (default: recognised)")
    fly.add_argument("--include-flagged", action="store_true",
                     help="a session: also fly shots whose launch the monitor marks estimated or clamped")
    fly.add_argument("--standard-air", action="store_true",
                     help="a session: fly every shot in the standard air, not in the air its export states "
                          "(Garmin's Temperature, Air Pressure, Relative Humidity)")
    fly.add_argument("--csv", help="also write the table (every value in the units its header names)")
    fly.add_argument("--force", action="store_true",
                     help="--csv: replace an existing file that is not a table impactlab wrote (refused by default)")
    fly.add_argument("--strict", action="store_true",
                     help="a session: refuse the file (exit 2) if any row is bad (a value beyond any golf shot, not a "
                          "number...); by default bad rows are not flown, with their reason")
    fly.add_argument("--show-rows", action="store_true",
                     help="a session: list the file line of every row not flown or unusual (default: counts per "
                          "reason)")
    fly.set_defaults(handler=_cmd_fly)


_EXAMPLES = {"ball_speed": "'167 mph'", "launch_angle": "'10.9 deg'", "spin_rate": "'2686 rpm'",
             "spin_axis": "'-3 deg'", "launch_direction": "'1.5 deg'"}
_AIR_WORDS = {"temperature": "temperature (e.g. '25 degC'; default 15 degC)",
              "pressure": "station pressure (e.g. '1013 hPa'; default the ISA pressure at --altitude)",
              "altitude": "height of the tee above sea level (e.g. '5280 ft'; sets the ISA pressure)",
              "relative_humidity": "relative humidity (e.g. '50 %'; default 50 %)",
              "headwind": "wind against the shot (e.g. '10 mph'; negative: a tailwind)",
              "crosswind": "wind across the shot, positive blowing to the right (e.g. '5 mph')"}


def _cmd_fly(args) -> int:
    if args.csv:
        check_output(args.csv, what="--csv file", suffix=".csv", formats=TABLE_SUFFIXES)
        if args.file:
            refuse_overwriting(args.csv, args.file, "--csv file")
        refuse_replacing_foreign(args.csv, "--csv file", args.force)
    given = {option: getattr(args, option) for option in LAUNCH_OPTIONS if getattr(args, option) is not None}
    conditions = {key: getattr(args, option) for option, key in AIR_OPTIONS.items()
                  if getattr(args, option) is not None}
    if args.file and given:
        raise StudyError("impactlab fly: give a session file or a launch (--ball-speed, --launch-angle, "
                         "--spin-rate), not both")
    session_only = [option for option, given_ in (("--vendor", args.vendor), ("--include-flagged",
                                                                                 args.include_flagged),
                                                   ("--standard-air", args.standard_air), ("--strict", args.strict),
                                                   ("--show-rows", args.show_rows)) if given_]
    if not args.file and session_only:
        raise StudyError(f"impactlab fly: {session_only[0]} applies to a session file, and none is given (a launch "
                         "typed in has no vendor, no flags and no air of its own)")
    if args.standard_air and conditions:
        raise StudyError("impactlab fly: --standard-air and " + ", ".join(
            f"--{option}" for option in AIR_OPTIONS if getattr(args, option) is not None) + " both set the air; give "
            "one (the options alone already replace the export's air)")
    try:
        if args.file:
            session = read_session(args.file, args.vendor)
            if args.strict:
                session.refuse_bad_rows()
            result = fly_session(session, model=args.model, conditions=conditions,
                                 include_flagged=args.include_flagged, session_air=not args.standard_air)
        else:
            result = _fly_launch(given, conditions, args.model)
    except FieldError as exc:  # a value's path in the command's words: conditions.temperature -> --temperature
        raise _as_option(exc) from None
    print(describe(result, args.model, args.show_rows))
    if args.csv:
        write_atomically(args.csv, table_csv(result).encode())
        print(f"wrote {args.csv} ({result.sizes['shot']} shot(s))")
    return 0


def _fly_launch(given: dict, conditions: dict, model: str) -> xr.Dataset:
    missing = [option for option in ("ball_speed", "launch_angle", "spin_rate") if option not in given]
    if missing:
        raise StudyError("impactlab fly: a launch needs " + ", ".join(f"--{m.replace('_', '-')}" for m in missing)
                         + " (each with its unit), or give a session file")
    # each value read once, to SI (its unit required); fly checks them and the broadcast, and flies them
    launch = {name: flight.quantity_array(texts[0] if len(texts) == 1 else texts, LAUNCH_DIMENSIONS[name], name)
              for name, texts in given.items()}
    # flown as quantities in SI units (not bare numbers, which fly reads as SI and says so in its messages), and
    # its warnings named by the options the user typed
    si = {name: registry().Quantity(value, DIMENSIONS[LAUNCH_DIMENSIONS[name]][0]) for name, value in launch.items()}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", PlausibilityWarning)
        result = flight.fly(conditions=conditions, model=model, **si)
    for warning in caught:
        text = str(warning.message)
        stem = text.split("[")[0].split(":")[0]
        if stem in LAUNCH_OPTIONS:
            text = "--" + stem.replace("_", "-") + text[len(stem):]
        warnings.warn(text, warning.category, stacklevel=2)
    shape = result["carry_distance"].shape
    out = {name: ("shot", np.asarray(result[name].values, float).ravel(), dict(result[name].attrs))
           for name in PREDICTED}
    for name, column, factor, unit in LAUNCH_COLUMNS:
        value = launch.get(name, np.zeros(()))
        out[column] = ("shot", (np.broadcast_to(value, shape) * factor).ravel(), {"units": unit})
    return xr.Dataset(out, attrs=dict(result.attrs))


def _as_option(exc: FieldError) -> FieldError:
    path = exc.path or ""
    key = path.split(".", 1)[1] if path.startswith("conditions.") else path
    names = {value: option for option, value in AIR_OPTIONS.items()} | {o: o for o in LAUNCH_OPTIONS}
    stem = key.split("[")[0]
    if stem not in names:
        return exc
    option = "--" + names[stem].replace("_", "-") + key[len(stem):]
    expected = exc.expected
    if isinstance(exc.given, str) and flight.is_number_text(exc.given):
        # what impactlab.fly says of text without a unit offers 'or a number in SI': a Python number; on the command
        # line every value is text and a number alone is never read
        words, unit = _PLAIN[names[stem]]
        example = "60 %" if unit == "%" else f"{exc.given} {unit}"  # 0.6 and 60 both mean 60 %: not '0.6 %'
        expected = f"{words} with its unit, e.g. '{example}' (a number alone is not read: its unit is never guessed)"
    return FieldError(option, expected, exc.given, exc.choices, file=exc.file, line=exc.line)


#: option -> (what it is, the unit of the example a number alone is refused with)
_PLAIN = {"ball_speed": ("a ball speed", "mph"), "launch_angle": ("a launch angle", "deg"),
          "spin_rate": ("a spin rate", "rpm"), "spin_axis": ("a spin axis", "deg"),
          "launch_direction": ("a launch direction", "deg"), "temperature": ("a temperature", "degC"),
          "pressure": ("a pressure", "hPa"), "altitude": ("an altitude", "m"),
          "humidity": ("a relative humidity", "%"), "headwind": ("a wind speed", "mph"),
          "crosswind": ("a wind speed", "mph")}


def describe(result: xr.Dataset, model: str, show_rows: bool = False) -> str:
    """The printed table: one row per shot, the launch flown, the predictions in yards and degrees, and for a
    session the monitor's carry beside each with the error summary."""
    a = result.attrs
    out = [f"model: {model} ({MODEL_REFERENCES.get(model, '')})"]
    if "air_temperature_K" in a:  # one air for every shot
        out.append(f"air: {a['air_temperature_K'] - 273.15:.1f} degC, {a['air_pressure_Pa'] / 100:.1f} hPa, "
                   f"{100 * a['air_relative_humidity']:.0f} % humidity (density {a['air_density_kg_m3']:.4f} "
                   f"kg/m^3), headwind {a['headwind_m_s'] / MPH:+.1f} mph, crosswind {a['crosswind_m_s'] / MPH:+.1f} "
                   "mph")
    else:
        density = result.air_density.values
        headwind, crosswind = a.get("headwind_m_s", 0.0) / MPH, a.get("crosswind_m_s", 0.0) / MPH
        out.append(f"air: density {density.min():.4f}-{density.max():.4f} kg/m^3 over the shots, headwind "
                   f"{headwind:+.1f} mph, crosswind {crosswind:+.1f} mph")
    if a.get("air_source"):
        out[-1] += f"; {a['air_source']}"
    session = "line" in result.coords
    if session:
        out.insert(0, f"{shown(result.attrs['file'])}: {shown(result.attrs['vendor'])}, {result.sizes['shot']} shot(s) "
                      "flown")
    monitor = MONITOR + "carry_distance" in result
    tracked = MONITOR + "measured" in result
    titles = (["line", "club"] if session else ["shot"]) + ["ball mph", "launch deg", "spin rpm", "axis deg"] + [
        title for title, *_ in COLUMNS] + (["monitor carry yd", "model - monitor"] if monitor else []) + (
        ["monitor's flight"] if tracked else [])
    out += ["", "| " + " | ".join(titles) + " |", "|" + "---|" * len(titles)]
    count = result.sizes["shot"]
    # a terminal table of a few hundred thousand rows is no table (a file of repeated rows printed 134 MB): the
    # first and last rows are shown, the rest said; --csv writes every one
    shown_rows = range(count) if count <= MAX_PRINTED_ROWS else [
        *range(MAX_PRINTED_ROWS // 2), -1, *range(count - MAX_PRINTED_ROWS // 2, count)]
    for index in shown_rows:
        if index < 0:
            out.append(f"| ... {count - 2 * (MAX_PRINTED_ROWS // 2):,} shot(s) not shown (--csv FILE writes every "
                       "one) |")
            continue
        cells = ([str(int(result.line[index])), shown(result.club.values[index]) or "-"] if session
                 else [str(index + 1)])
        cells += [_cell(result.ball_speed[index] / MPH, "{:.1f}"), _cell(result.vertical_launch_angle[index],
                                                                          "{:.1f}"),
                  _cell(result.spin_rate[index], "{:.0f}"), _cell(result.spin_axis[index], "{:+.1f}")]
        cells += [_cell(result[name][index] * factor, form) for _, name, factor, form in COLUMNS]
        if monitor:
            reported = float(result[MONITOR + "carry_distance"][index])
            cells += [_cell(reported / YARD, "{:.1f}"),
                      _cell(100 * (float(result.carry_distance[index]) / reported - 1), "{:+.1f} %")
                      if np.isfinite(reported) and reported > 0 else "-"]
        if tracked:
            cells.append("measured" if bool(result[MONITOR + "measured"][index]) else "model")
        out.append("| " + " | ".join(cells) + " |")
    if monitor:
        out += _monitor_statistics(result)
    repeated = _repeated_launches(result)
    if repeated:
        out.append(f"{repeated:,} of {count:,} shot(s) repeat an earlier shot's launch exactly (ball speed, launch "
                   "angle, spin and axis): a file of copied rows?")
    unflown = ~np.isfinite(result.carry_distance.values)
    if unflown.any():
        names = ([f"line {int(line)}" for line in result.line.values[unflown][:MAX_LISTED]] if session
                 else [f"shot {index + 1}" for index in np.flatnonzero(unflown)[:MAX_LISTED]])
        if unflown.sum() > MAX_LISTED:
            names.append(f"{int(unflown.sum()) - MAX_LISTED:,} more")
        out.append(f"no carry for {', '.join(names)}: still in the air after the flight's 15 s limit, or a flight "
                   "that could not be integrated (a launch far outside golf's); nothing is given for it")
    downward = np.flatnonzero(np.asarray(result.vertical_launch_angle.values) < 0.0)
    if not session and downward.size:
        listed = [str(index + 1) for index in downward[:MAX_LISTED]] + (
            [f"{downward.size - MAX_LISTED:,} more"] if downward.size > MAX_LISTED else [])
        out.append(f"shot {', '.join(listed)}: launched below the horizontal, from "
                   "the ground it meets the ground at once (carry 0; the landing angle is the launch's)")
    if session and np.isnan(result.offline_distance.values).any():
        out.append("offline not given for shots without a spin axis or launch direction (flown as 0)")
    if session and ("skipped_rows" in result.attrs or "unusual_rows" in result.attrs):
        skipped = [tuple(pair) for pair in json.loads(result.attrs.get("skipped_rows", "[]"))]
        unusual = [tuple(pair) for pair in json.loads(result.attrs.get("unusual_rows", "[]"))]
        lines = skip_lines(skipped, result.sizes["shot"] + len(skipped), unusual, show_rows, indent="",
                           used="flown")
        out += [""] + lines if lines else []
    return "\n".join(out)


#: rows of the printed table (more are said by their count: --csv writes every one), and lines named in a note
MAX_PRINTED_ROWS = 200
MAX_LISTED = 20


def _repeated_launches(result: xr.Dataset) -> int:
    """How many shots repeat an earlier shot's launch exactly (ball speed, launch angle, spin rate and axis)."""
    names = [name for name in ("ball_speed", "vertical_launch_angle", "spin_rate", "spin_axis") if name in result]
    if result.sizes["shot"] < 2 or not names:
        return 0
    launch = np.stack([np.asarray(result[name].values, dtype=float) for name in names], axis=1)
    launch = launch[np.isfinite(launch).all(axis=1)]
    return int(len(launch) - len(np.unique(launch, axis=0))) if len(launch) else 0


def _monitor_statistics(result: xr.Dataset) -> list[str]:
    """The model's carry against the monitor's, over the flights the monitor measured where the export says which
    (TrackMan's tracked time), else over every shot with a carry (and said so)."""
    monitor_carry = np.asarray(result[MONITOR + "carry_distance"].values, dtype=float)
    usable = np.isfinite(monitor_carry) & (monitor_carry > 0) & np.isfinite(result.carry_distance.values)
    if MONITOR + "measured" in result and (usable & result[MONITOR + "measured"].values).any():
        measured = np.asarray(result[MONITOR + "measured"].values, dtype=bool)
        words = (f"the flights the monitor measured ({int((usable & measured).sum())} of {int(usable.sum())} with a "
                 f"carry; the others are its model output, left out)")
        usable &= measured
    elif MONITOR + "measured" in result:
        words = "the monitor's model output: none of these flights was tracked long enough to be measured"
    else:
        words = ("every shot with a carry (the export does not say which flights the monitor tracked: measured where "
                 "a radar tracked the flight, its own model indoors or when normalised)")
    if not usable.any():
        return ["", f"model against the monitor's carry: no shot to compare over {words}"]
    error = result.carry_distance.values[usable] / monitor_carry[usable] - 1
    rms = 100 * np.sqrt(np.mean(error ** 2))
    return ["", f"model against the monitor's carry, {int(usable.sum())} shot(s): mean {100 * error.mean():+.1f} %, "
                f"median {100 * np.median(error):+.1f} %, RMS {rms:.1f} %, over {words}"]


def _cell(value, form: str) -> str:
    value = float(value)
    return form.format(value) if np.isfinite(value) else "-"


def table_csv(result: xr.Dataset) -> str:
    """``result`` as CSV, one row per shot, each header naming its unit (``carry_distance [m]``)."""
    names = [name for name in result.data_vars if result[name].dims == ("shot",)]
    coords = [name for name in ("line", "club") if name in result.coords]
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    # the first columns are impactlab's marker (io.safe_output.TABLE_MARKERS): a session's line and club, or the
    # launch's number, as the printed table has them
    first = coords or ["shot"]
    writer.writerow(first + [f"{name} [{result[name].attrs['units']}]" if "units" in result[name].attrs else name
                             for name in names])
    for index in range(result.sizes["shot"]):
        row = [str(result[name].values[index]) for name in coords] if coords else [str(index + 1)]
        for name in names:
            value = result[name].values[index]
            row.append(str(bool(value)) if result[name].dtype == bool else
                       ("" if not np.isfinite(value) else f"{float(value):.10g}"))
        writer.writerow(row)
    return buffer.getvalue()
