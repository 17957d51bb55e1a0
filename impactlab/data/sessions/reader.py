"""Launch-monitor sessions read as exported: vendor layouts as data, one normalised table out.

A session file is a table a launch monitor's software wrote (TrackMan, Garmin Golf, Foresight FSX, Rapsodo, FlightScope,
Square Golf), JSON shot records (GSPro Open Connect messages, Uneekor's report; read as rows by
:mod:`impactlab.data.sessions.json_records`) or a table in impactlab's own vocabulary (``Club Speed [mph]``,
``ball_speed (m/s)``). Each vendor's layout is a YAML column map in ``impactlab/data/sessions/vendors/``
(:func:`vendor_maps`): the header names that recognise it, where its units are (a units row under the header, inside the
header names, or implied by the layout), its column names in the vocabulary of :data:`FIELDS`, per-column signs, no-data
sentinels, estimated-value flags, clamped values, placeholders (values that stand for "not measured"), rows that are no
shot, values a layout requires, the point of the club head its club data describe, and for an export in another language
the layout it translates (``base``, ``headers``). A map key ``Name [unit]`` matches the column ``Name`` only when the
header gives it a unit (FlightScope's ``Club`` is the club's name, ``Club (mph)`` its speed).

The reader (:func:`read_session`) never guesses: the separator comes from a ``sep=`` line or the header; decimal
commas are recognised per file (a quoted ``"-0,9"`` is -0.9) and a file that mixes decimal marks is refused; a
number without a unit is refused; two columns that give one quantity (``Ball Speed [mph]`` and ``Ball Speed
[m/s]``) are refused, naming both; a column no cell of which is a number is refused with its file:line:column.
A bad row never sinks the file: a cell that is not a number, a row of another width, a value beyond any golf shot
(:mod:`impactlab.data.sessions.rows`, one set of row rules for every command) skip that row with their reason.
Values are flagged, not dropped: no-data sentinels become missing, estimated, clamped, inconsistent and modelled
values are kept in the session but left out of fits and comparisons unless asked (:meth:`Session.shot_table`), and
the rows a model cannot use are skipped with their reason while the rest of the session is used.

All values are SI (angles in rad, spins in rad/s) with the signs of :mod:`impactlab.vocabulary`: horizontal
angles, spin axis, side spin and offline distance positive to the right of the target line.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import attrs
import numpy as np

from impactlab.scene.plausibility import GOLF_LIMITS, wrong_sign
from impactlab.data.sessions.rows import row_verdict
from impactlab.errors import FieldError, StudyError
from impactlab.scene.catalogue import club_key
from impactlab.data.sessions.shot_table import (DEFAULT_SIGMA, DELIVERY_FIELDS, MEASURED_FIELDS, ShotTable,
                                               _resolve_spin_loft)
from impactlab.data.sessions.columns import _column_plan
from impactlab.data.sessions.layouts import (DESCRIPTIONS, GENERIC, VendorMap, _header_index, maker_of,
                                            _norm, _recognise, split_header)
from impactlab.data.sessions.air import _air_from_text, _check_air
from impactlab.data.sessions.consistency import check_consistency
from impactlab.data.sessions.steps import (clamp_flags, flag_tracked, handedness_of, read_columns, read_header,
                                          read_rows, read_units)
from impactlab.data.sessions.values import (_check_spin_signs, _club_names, _derive, _flag_all_zero, _flag_estimated,
                                           _flag_excluded, _flag_no_data, _flag_without, _legacy_text, _read_bytes,
                                           _read_flags)
# the report and the normalised table of a session, importable from here (the CLI and users import them so)
from impactlab.data.sessions.report import describe as describe, write_normalised as write_normalised

#: the delivery the impact models need in every row
NEEDED_DELIVERY = ("club_speed", "attack_angle", "dynamic_loft")
#: the launch the impact models predict (what a row is compared on)
PREDICTED = ("ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis")


# -- the session -----------------------------------------------------------------------------------------------
@attrs.frozen
class Session:
    """A launch-monitor session read as exported, normalised to :data:`FIELDS` (SI) with what was done to it.

    Attributes
    ----------
    file : str
    vendor : VendorMap
    values : dict of ndarray
        Field -> per-row SI values (NaN: not in the file or no data).
    text : dict of tuple of str
        ``label``, ``club`` and ``handedness`` per row ('' where not given); a YAML table whose rows name their
        sources also ``source`` (every row's, the table's name where a row names none).
    lines : ndarray of int
        The file line of each row.
    flags : dict of ndarray of bool
        ``(field, kind)`` -> per-row mask; kind ``estimated``, ``clamped`` or ``no data`` (a sentinel).
    used : list of (header, field, unit, sign)
        Each column used, the field it gives, the unit it was read in and the sign applied.
    unused : list of str
        Columns not used.
    skipped : list of (line, reason)
        Rows that are no shot at all (summary rows).
    notes : list of str
        What the reader inferred (separator, decimal mark, units row, derived values).
    """

    file: str
    vendor: VendorMap
    values: dict = attrs.field(eq=False)
    text: dict = attrs.field(eq=False)
    lines: np.ndarray = attrs.field(eq=False)
    flags: dict = attrs.field(eq=False)
    used: list = attrs.field(eq=False)
    unused: list = attrs.field(eq=False)
    skipped: list = attrs.field(eq=False)
    notes: list = attrs.field(eq=False)

    @property
    def size(self) -> int:
        """Number of shots read."""
        return len(self.lines)

    def flagged(self, field: str) -> np.ndarray:
        """Rows whose ``field`` is flagged (estimated or clamped; no-data values are already missing)."""
        mask = np.zeros(self.size, bool)
        for (name, kind), rows in self.flags.items():
            if name == field and kind in ("estimated", "clamped", "inconsistent"):
                mask |= rows
        return mask

    def carry_measured(self) -> np.ndarray:
        """Rows whose carry the monitor measured: a carry given, not flagged estimated or clamped, and, where the
        layout says which flights its monitor tracked (``tracked``: TrackMan's tracked time against the hang time),
        tracked long enough, both times known (a flight of unknown tracking is not counted as measured)."""
        carry = self.values.get("carry_distance")
        if carry is None:
            return np.zeros(self.size, bool)
        measured = np.isfinite(carry) & ~self.flagged("carry_distance")
        rule = self.vendor.tracked
        if rule:
            known = np.isfinite(self.values[rule["time"]]) & np.isfinite(self.values[rule["of"]])
            measured &= known & ~self.flags.get(("carry_distance", "modelled"), np.zeros(self.size, bool))
        return measured

    def verdict(self):
        """The row rules' :class:`~impactlab.data.sessions.rows.RowVerdict` of this session (one set of rules for
        every command)."""
        return row_verdict(self.values, self.text["club"], self.used, self.flags)

    def bad_rows(self) -> list[tuple[int, str]]:
        """(line, reason) of every row an instrument should not have written: a breach of the row rules (a value
        beyond any golf shot, not finite, not a number, off the face...) or a row of another width than the header.
        Rows that merely lack a value, and no-value markers, are not bad. What ``--strict`` refuses."""
        verdict = self.verdict()
        bad = [(int(self.lines[row]), "; ".join(verdict.of_row(row))) for row in np.flatnonzero(verdict.bad)]
        bad += [(line, why) for line, why in self.skipped if why.startswith("a row of ")]
        return sorted(bad)

    def refuse_bad_rows(self) -> None:
        """``--strict``: a StudyError naming every bad row (:meth:`bad_rows`, at most 20), if there is one."""
        bad = self.bad_rows()
        if bad:
            shown = "; ".join(f"{self.file}:{line}: {why}" for line, why in bad[:20])
            raise StudyError(f"{self.file}: --strict: {len(bad)} bad row(s): {shown}"
                             + (f" (and {len(bad) - 20} more)" if len(bad) > 20 else ""))

    def row_reasons(self, include_flagged: bool = False, rules: bool = True) -> list[list[str]]:
        """Why each row cannot be used by the impact models (empty: usable); see :meth:`usable`."""
        reasons: list[list[str]] = [[] for _ in range(self.size)]
        keys = {name: club_key(name) if name else None for name in set(self.text["club"])}  # once per name
        for index, name in enumerate(self.text["club"]):
            if not name:
                reasons[index].append("no club named")
            elif keys[name] is None:
                reasons[index].append(f"club {name!r} is not in the club catalogue")
        for index in np.flatnonzero(self.flags.get(("row", "excluded"), np.zeros(self.size, bool))).tolist():
            reasons[index].append("marked not to use in the file" + (
                f" ({self.vendor.excluded['column']} = {', '.join(map(str, self.vendor.excluded['values']))})"
                if self.vendor.excluded else ""))
        for field in NEEDED_DELIVERY:
            given = np.isfinite(self.values[field]) | self.flags.get((field, "unreadable"), False)  # said below
            if field == "dynamic_loft" and "spin_loft" in self.values:  # the spin loft gives the dynamic loft
                given |= np.isfinite(self.values["spin_loft"])
            for index in np.flatnonzero(~given).tolist():
                reasons[index].append(f"no {DESCRIPTIONS[field]}")
        measured, given = np.zeros(self.size, bool), np.zeros(self.size, bool)
        for field in PREDICTED:
            ok = np.isfinite(self.values[field])
            given |= ok
            if not include_flagged:
                ok &= ~self.flagged(field)
            measured |= ok
        for index in np.flatnonzero(~measured).tolist():
            reasons[index].append("no measured launch quantity" + (" that is not flagged" if given[index] else ""))
        if rules:
            for reason, mask, _ in self.verdict().reasons:
                for index in np.flatnonzero(mask).tolist():
                    reasons[index].append(reason)
        return reasons

    def usable(self, include_flagged: bool = False, rules: bool = True) -> tuple[np.ndarray, list]:
        """Rows the impact models can use, and ``(line, reason)`` of every row they cannot (reasons ``; ``-joined).

        A row needs a club the catalogue knows, the club speed, attack angle and dynamic loft, and at least one
        measured launch quantity that is not flagged (unless ``include_flagged``); with ``rules``, no breach of the
        row rules (:mod:`impactlab.data.sessions.rows`: values beyond any golf shot, off the face, not finite...).
        """
        reasons = self.row_reasons(include_flagged, rules)
        keep = np.array([not why for why in reasons], dtype=bool)
        return keep, [(int(self.lines[index]), "; ".join(why)) for index, why in enumerate(reasons) if why]

    def shot_table(self, include_flagged: bool = False, every_row: bool = False):
        """The :class:`~impactlab.data.sessions.shots.ShotTable` of the rows the impact models can use.

        The one assembly of a shot table: launch-monitor exports and impactlab's YAML tables
        (:func:`impactlab.data.sessions.shots.read_yaml`) both come here as a session. Flagged values (estimated,
        clamped) are left out of the comparison unless ``include_flagged``; a row without face angle or club path keeps
        its ball speed, launch angle and spin but not its launch direction and spin axis (a square face would be a
        guess). A row the models cannot use (:meth:`usable`, the row rules, a spin loft or face to path that disagrees
        with the row's angles, a magnitude below zero, an uncertainty that is not positive) is skipped with its reason,
        or, with ``every_row`` (a table written by hand, where such a row is the author's slip), refused. Raises
        StudyError, listing every problem at its file:line, when no row is usable (or a hand-written row is bad).
        """
        keep, skipped = self.usable(include_flagged, rules=not every_row)
        if every_row:
            problems = [f"{self.file}:{line}: a row the impact models cannot use: {why}" for line, why in skipped]
            keep, skipped = np.ones(self.size, bool), []
        else:
            problems = []
            self._refuse_if_empty(keep, skipped)
        index = np.flatnonzero(keep)
        delivery, measured, sigma, found = self._table_arrays(index, include_flagged)
        if every_row:
            problems += [message for _, _, message in found]
        elif found:  # a session's rows with a problem are skipped with it, the others kept
            bad = sorted({row for row, _, _ in found})
            why = {row: "; ".join(reason for r, reason, _ in found if r == row) for row in bad}
            skipped = sorted([*skipped, *((int(self.lines[index[row]]), why[row]) for row in bad)])
            keep[index[bad]] = False
            self._refuse_if_empty(keep, skipped, [message for _, _, message in found])
            rest = np.setdiff1d(np.arange(index.size), bad)
            index = index[rest]
            delivery, measured, sigma = ({key: value[rest] for key, value in part.items()}
                                         for part in (delivery, measured, sigma))
        if problems:
            raise StudyError("; ".join(problems))
        return self._assemble(index, delivery, measured, sigma, tuple(skipped), unusual=None if every_row else
                              tuple((reason, tuple(int(line) for line in self.lines[mask & keep]))
                                    for reason, mask in self.verdict().unusual if (mask & keep).any()))

    def _refuse_if_empty(self, keep: np.ndarray, skipped: list, details: tuple | list = ()) -> None:
        """A StudyError when no row is kept: each reason at its first file:line, then the first ``details``."""
        if keep.any():
            return
        counts = Counter(reason for _, why in skipped for reason in why.split("; "))
        reasons = "; ".join(f"{self.file}:{next(line for line, why in skipped if reason in why.split('; '))}: "
                            f"{reason} ({count} row(s))" for reason, count in counts.most_common(10))
        more = f" (and {len(counts) - 10} other reasons)" if len(counts) > 10 else ""
        shown = "".join(f"; {detail}" for detail in details[:10])
        raise StudyError(f"{self.file}: no row the impact models can use ({self.size} shot(s) read): "
                         f"{reasons}{more}{shown}")

    def _table_arrays(self, index: np.ndarray, include_flagged: bool):
        """(delivery, measured, sigma) of the rows ``index`` and the problems found in them: (position in
        ``index``, reason, message)."""
        # a field no layout of this vendor maps (the 3-D spin loft) is absent: NaN, as an empty cell
        delivery = {key: (self.values[key][index].copy() if key in self.values else np.full(index.size, np.nan))
                    for key in DELIVERY_FIELDS}
        found = _resolve_spin_loft(delivery, self.lines[index], self.file)
        square = ~(np.isfinite(delivery["face_angle"]) & np.isfinite(delivery["path"]))
        for key in ("path", "face_angle", "strike_toe", "strike_high"):
            delivery[key] = np.nan_to_num(delivery[key])
        for key in ("face_angle", "dynamic_loft"):  # derived above: checked as a measured one is
            limit = GOLF_LIMITS[f"delivery.{key}"]
            with np.errstate(invalid="ignore"):
                shown = delivery[key] * limit.factor
            for row in np.flatnonzero((shown < limit.impossible[0]) | (shown > limit.impossible[1])).tolist():
                found.append((row, f"{DESCRIPTIONS[key]} beyond any golf shot (as derived)",
                              f"{self.file}:{self.lines[index[row]]}: {key}: {shown[row]:.6g} {limit.unit}"))
        measured = {}
        for key in MEASURED_FIELDS:
            values = self.values[key][index].copy()
            if not include_flagged:
                values[self.flagged(key)[index]] = np.nan
            if key in ("horizontal_launch_angle", "spin_axis"):
                values[square] = np.nan
            measured[key] = values
        # a magnitude below zero is no measurement (a ball speed of -70 mph), naming each row
        found += [(row, "a magnitude below zero", problem) for row in range(index.size)
                  for problem in wrong_sign(measured, row, f"{self.file}:{self.lines[index[row]]}")]
        sigma = {}
        for key in MEASURED_FIELDS:
            given = self.values[f"{key}_sigma"][index]
            bad = np.isfinite(given) & ~(given > 0)
            found += [(row, f"{key}_sigma: expected a positive uncertainty",
                       f"{self.file}:{self.lines[index[row]]}: {key}_sigma: expected a positive uncertainty, got "
                       f"{given[row]:g}") for row in np.flatnonzero(bad).tolist()]
            sigma[key] = np.where(np.isfinite(given), given, DEFAULT_SIGMA[key])
        return delivery, measured, sigma, found

    def _assemble(self, index, delivery, measured, sigma, skipped: tuple, unusual):
        # where the file gave the strike (the delivery fills a missing one with the face's centre, 0)
        strike_known = np.ones(index.size, dtype=bool)
        for key in ("strike_toe", "strike_high"):
            strike_known &= np.isfinite(self.values[key][index]) if key in self.values else False
        labels = tuple(self.text["label"][i] or f"line {self.lines[i]}" for i in index)
        # every kept row's club is in the catalogue (usable() refuses the others)
        keys = {name: known for name in {self.text["club"][i] for i in index} if (known := club_key(name)) is not None}
        source = f"read from {self.file} ({self.vendor.name})"
        if self.vendor.club_reference_point != "unknown":
            source += f"; club data at the head's {self.vendor.club_reference_point.replace('_', ' ')}"
        elif self.vendor is not GENERIC:
            source += "; the point of the head its club data describe is not stated"
        return ShotTable(name=Path(self.file).stem, source=source,
                         labels=labels, clubs=tuple(keys[self.text["club"][i]] for i in index),
                         handedness=tuple(self.text["handedness"][i] or "right" for i in index),
                         delivery=delivery, measured=measured, sigma=sigma, loft_at=self.vendor.loft_at,
                         skipped=skipped, unusual=unusual, strike_known=strike_known,
                         row_sources=tuple(self.text["source"][i] for i in index) if "source" in self.text else (),
                         instrument=self._instrument(),
                         ball_settings=tuple(self.text["ball_setting"][i] for i in index)
                         if any(self.text.get("ball_setting", ())) else ())

    def _instrument(self) -> str:
        """The monitor's maker its layout names (layouts.maker_of; '' for impactlab's own tables and GSPro's relay)."""
        return maker_of(self.vendor.id)


#: session datasets shipped with impactlab: name -> file in impactlab/data/sessions/datasets (README.md there)
DATASETS = {"trackman_driver_sessions": "trackman_driver_sessions.csv.gz"}


def dataset_path(name: str) -> Path:
    """The file of a session dataset shipped with impactlab (:data:`DATASETS`), e.g. ``trackman_driver_sessions``
    (10,169 TrackMan driver shots, MIT; its README and LICENSE lie beside it).

    Raises
    ------
    FieldError
        ``name`` is no shipped dataset.
    """
    from importlib import resources

    if name not in DATASETS:
        raise FieldError("dataset", "a session dataset shipped with impactlab", name, choices=sorted(DATASETS))
    return Path(str(resources.files("impactlab.data.sessions").joinpath("datasets", DATASETS[name])))


def read_session(path, vendor: str | None = None) -> Session:
    """Read a launch-monitor export (or an impactlab shot-table CSV) as exported; see the module docstring.

    Parameters
    ----------
    path : str or Path
        The file, or the name of a shipped dataset (:data:`DATASETS`, e.g. ``"trackman_driver_sessions"``) when no
        file of that name exists.
    vendor : str, optional
        A vendor id of :func:`vendor_maps` (default: recognised from the header).
    """
    name = str(path)
    path = dataset_path(name) if name in DATASETS and not Path(name).exists() else Path(path)
    try:
        text, encoding = _read_bytes(path)
        legacy = ""
    except StudyError as exc:  # not UTF-8: read in a legacy encoding only where a layout says its exports use one
        text, legacy = _legacy_text(path, exc, lambda rows: _recognise(
            [cell.strip() for cell in rows[_header_index(rows, vendor)]], vendor, str(path)))
        encoding = ""
    session = read_session_text(text, name if name in DATASETS else str(path), vendor)
    if legacy:
        session.notes.insert(0, f"read as {legacy} text (not UTF-8), the encoding of {session.vendor.name} files")
    if encoding:
        session.notes.insert(0, f"read as {encoding} text")
    if name in DATASETS:
        session.notes.insert(0, f"the dataset {name} shipped with impactlab ({path.name}; its README and LICENSE "
                                f"lie beside it)")
    return session


def read_session_text(text: str, file: str = "<csv>", vendor: str | None = None) -> Session:
    """A :class:`Session` from the text of an export (see :func:`read_session`): the header and its layout, the
    units, the rows, each column's numbers, the flags the layout implies, the air and the text fields, one step
    each (:mod:`impactlab.data.sessions.steps`)."""
    reading = read_header(text, file, vendor)
    read_units(reading)
    layout, header = reading.layout, reading.header
    plan, unused, repeated = _column_plan(header, layout, reading.units_row, file, reading.header_line)
    _layout_notes(reading, plan, unused)
    read_rows(reading, {field: column for column, _, field, *_ in plan})
    columns, values, text_values, flags, used = read_columns(reading, plan, repeated)
    notes, lines = reading.notes, reading.shot_lines
    for (field, cell), cells in reading.unreadable.items():
        flags[(field, "unreadable")] = np.isin(np.arange(len(lines)), list(cells))
        notes.append(f"{cell}: {len(cells)} cell(s) that are not numbers (first: line {lines[min(cells)]}, "
                     f"{cells[min(cells)]!r}): their rows are skipped")
    _flag_estimated(layout, header, columns, values, flags, used, unused, notes)
    _flag_excluded(layout, header, columns, flags, used, unused)
    _flag_no_data(layout, header, columns, values, flags, used, unused)
    _air_from_text(layout, header, columns, values, used, unused, notes, file, lines)
    if layout is GENERIC and "flags" in [_norm(cell) for cell in header]:
        _read_flags(header, columns, flags, used, unused, file, lines)
    clamp_flags(layout, values, flags)
    _flag_all_zero(layout, values, flags, notes)
    _flag_without(layout, values, flags, notes)
    flag_tracked(layout, values, flags, notes)
    _derive(values, used, notes, flags)
    _check_spin_signs(layout, values, used, notes, flags)
    check_consistency(values, used, notes, flags, np.asarray(lines))
    _check_air(values, notes, flags)
    if layout.club_rows:
        text_values["club"] = tuple(reading.shot_clubs)
    text_values["club"] = _club_names(layout, text_values["club"], notes)
    text_values["handedness"] = handedness_of(text_values["handedness"], file)
    return Session(file=file, vendor=layout, values=values, text=text_values,
                   lines=np.array(lines, dtype=np.int64), flags=flags, used=used, unused=unused,
                   skipped=reading.skipped, notes=notes)


def _layout_notes(reading, plan: list, unused: list) -> None:
    """Say what the layout implies: units taken from the layout, or no layout recognised at all."""
    layout, header = reading.layout, reading.header
    in_row = set() if reading.units_row is None else {column for column, cell in enumerate(reading.units_row)
                                                      if cell}
    implied = [f"{cell} [{unit}]" for column, cell, field, unit, _, factor in plan
               if layout.units == "implied" and factor is not None and unit and split_header(cell)[1] is None
               and column not in in_row]
    named = [cell for cell in header if cell]
    if layout is GENERIC and len(unused) * 2 > len(named):  # most columns unknown: a vendor export not recognised?
        reading.notes.append(f"no vendor layout recognises this header ({len(unused)} of {len(named)} columns "
                             f"unknown): read in impactlab's own layout, whose signs are the vocabulary's (side spin, "
                             f"spin axis and directions positive to the right); if a launch monitor wrote it, name it "
                             f"with --vendor")
    if implied:
        reading.notes.append(f"units not in the file for {', '.join(implied)}: taken from the {layout.name} layout "
                             f"({layout.source})")
