"""From a session file's text to per-column values: bytes and rows, decimal marks, numbers, flags, derived values.

The steps of :func:`impactlab.data.sessions.reader.read_session_text` below the column plan: reading the file's bytes
(UTF-8 or UTF-16, never a binary file), splitting rows with the separator the file states or its header implies,
telling decimal commas from points (a file mixing both is refused), reading a column's cells as numbers, and
the flags and derived values (spin from back and side spin, face angle from face to path) a layout implies.
"""

from __future__ import annotations

import csv
import io
import math
import re
import sys
from pathlib import Path

import numpy as np

from impactlab.errors import StudyError
from impactlab.foreign import MAX_INPUT_BYTES
from impactlab.study.yaml_lines import checked_bytes, utf8_text
from impactlab.data.sessions.layouts import FIELDS, VendorMap, _norm, split_header

#: the largest file read as a session [bytes]: impactlab's one limit on input files (impactlab.foreign)
MAX_SESSION_BYTES = MAX_INPUT_BYTES
#: rows above which a progress bar is drawn (on a terminal)
PROGRESS_ROWS = 20_000


def _read_bytes(path: Path) -> tuple[str, str]:
    """The text of a session file: UTF-8, or UTF-16 / UTF-32 with or without a byte-order mark (named as they are),
    gzip-compressed or not; never a binary file or a workbook. Returns (text, the encoding's name when not
    UTF-8)."""
    data = checked_bytes(path, "shot table", MAX_SESSION_BYTES, missing=" (a launch-monitor export, .csv or .yaml)")
    if data.startswith(b"\x1f\x8b"):  # gzip (the shipped datasets): at most the size limit, uncompressed
        data = _gunzip(data, path)
    workbook = _workbook_kind(data)
    if workbook:
        raise StudyError(f"{path}: is {workbook}, not a text export; save the sheet as CSV (UTF-8) from the "
                         f"spreadsheet program, or export CSV from the launch monitor's software, and read that file")
    encoding, named = _wide_encoding(data)
    if encoding:
        try:
            return data.decode(encoding).lstrip("\ufeff"), named
        except UnicodeDecodeError:
            raise StudyError(f"{path}: is not {named or encoding.upper()} text (it starts like it, then holds bytes "
                             f"that are not)") from None
    if b"\0" in data:
        raise StudyError(f"{path}: is a binary file (it holds NUL bytes), not a shot table")
    return utf8_text(data, path, "shot table"), ""


def _gunzip(data: bytes, path: Path) -> bytes:
    import gzip
    import zlib

    try:
        with gzip.GzipFile(fileobj=io.BytesIO(data)) as stream:
            plain = stream.read(MAX_SESSION_BYTES + 1)
    except (OSError, EOFError, zlib.error) as exc:
        raise StudyError(f"{path}: is not a readable gzip file ({exc})") from None
    if len(plain) > MAX_SESSION_BYTES:
        raise StudyError(f"{path}: holds more than {MAX_SESSION_BYTES:,} bytes uncompressed, too large for a shot "
                         f"table")
    return plain


#: byte-order marks, longest first (UTF-32 LE's mark begins with UTF-16 LE's)
_MARKS = ((b"\xff\xfe\x00\x00", "utf-32"), (b"\x00\x00\xfe\xff", "utf-32"), (b"\xff\xfe", "utf-16"),
          (b"\xfe\xff", "utf-16"))


def _wide_encoding(data: bytes) -> tuple[str, str]:
    """(codec, name) of UTF-16 or UTF-32 text, with its byte-order mark (name '': the mark says it) or without one
    (text of Latin letters and digits then has a NUL in the same places of every 2 or 4 bytes); ('', '') for any
    other bytes."""
    for mark, codec in _MARKS:  # a byte-order mark names its encoding: read, not said
        if data.startswith(mark):
            return codec, ""
    sample = data[:4096]
    if len(sample) < 8 or b"\0" not in sample:
        return "", ""
    sample = sample[:len(sample) // 4 * 4]
    for codec, name, nul in (("utf-32-le", "UTF-32 (little-endian, no byte-order mark)", (1, 2, 3)),
                             ("utf-32-be", "UTF-32 (big-endian, no byte-order mark)", (0, 1, 2)),
                             ("utf-16-le", "UTF-16 (little-endian, no byte-order mark)", (1, 3)),
                             ("utf-16-be", "UTF-16 (big-endian, no byte-order mark)", (0, 2))):
        text = [sample[k::4] for k in range(4) if k not in nul]  # the bytes of the characters: printable text
        printable = sum(sum(32 <= byte < 127 or byte in (9, 10, 13) for byte in part) for part in text)
        if all(sample[k::4].count(0) >= 0.9 * len(sample[k::4]) for k in nul) and \
                printable >= 0.9 * sum(len(part) for part in text):
            return codec, name
    return "", ""


def _workbook_kind(data: bytes) -> str:
    """What spreadsheet ``data`` is ('' for none): an .xlsx or .ods is a ZIP archive holding xl/ or an
    OpenDocument mimetype; an .xls (Excel 97-2003) a Compound File (magic D0 CF 11 E0 A1 B1 1A E1)."""
    if data.startswith(b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1"):
        return "an Excel 97-2003 workbook (.xls)"
    if data.startswith(b"PK\x03\x04"):
        head = data[:4096]
        if b"xl/" in data or b"[Content_Types].xml" in head:
            return "an Excel workbook (.xlsx)"
        if b"opendocument.spreadsheet" in head:
            return "an OpenDocument spreadsheet (.ods)"
        return "a ZIP archive"
    return ""


def _row_key(cells) -> tuple:
    """A row's cells for comparing rows (case, spaces and trailing empty cells aside)."""
    key = [_norm(cell) for cell in cells]
    while key and not key[-1]:
        key.pop()
    return tuple(key)


def _units_difference(header, first, other) -> str:
    """The first column whose unit differs between two units rows, said as 'Carry [m], was [Yards]'."""
    for column, name in enumerate(header):
        was = first[column].strip() if column < len(first) else ""
        now = other[column].strip() if column < len(other) else ""
        if _norm(was) != _norm(now):
            return f"{name!r} {now or '(none)'}, was {was or '(none)'}"
    return "a column beyond the header"


def _legacy_text(path: Path, error: StudyError, recognise) -> tuple[str, str]:
    """The text of a file that is not UTF-8, decoded in the legacy encoding of the layout that recognises its header
    (``recognise(rows)`` -> VendorMap; FlightScope's simulator writes Windows-1252); else ``error`` is raised: no
    encoding is guessed for a file no layout claims."""
    data = checked_bytes(path, "shot table", MAX_SESSION_BYTES)
    if b"\0" in data or data.startswith((b"\xff\xfe", b"\xfe\xff")):
        raise error
    for encoding in ("windows-1252",):
        try:
            text = data.decode(encoding)
        except UnicodeDecodeError:
            continue
        rows = _rows_of(text, str(path))[0]
        if rows and recognise(rows).encoding == encoding:
            return text, encoding
    raise error


def _merge_repeated(columns: list, repeated: list, layout, header: list, notes: list) -> list:
    """Columns written twice under one header (``layout.merge_repeated_columns``): the first's cell, the second's
    where the first is empty; said once per column."""
    for first, second in repeated:
        empty = set(layout.missing)
        columns[first] = tuple(a if a.strip() not in empty else b for a, b in zip(columns[first], columns[second]))
        notes.append(f"column {header[first]!r} is written twice (columns {first + 1} and {second + 1}): the first's "
                     f"value is read, the second's where the first is empty")
    return columns


def _rows_of(text: str, file: str) -> tuple[list[list[str]], list[int], list[str]]:
    """Rows (cells) with their file lines, after the ``sep=`` line; the separator said in notes."""
    notes = []
    text = text.lstrip("\ufeff")
    first_end = text.find("\n")
    first = text if first_end < 0 else text[:first_end]
    delimiter = None
    line_offset = 0
    match = re.match(r'^\s*"?sep=(.)"?\s*$', first.rstrip("\r"))
    if match:
        delimiter = match.group(1)
        notes.append(f"separator {delimiter!r} (from the file's 'sep=' line)")
        text = "" if first_end < 0 else text[first_end + 1:]
        line_offset = 1
    sample = [line for line in text[:20000].splitlines() if line.strip()][:6]
    if delimiter is None:
        # the separator that splits the header (the widest of the first lines: a title line may come first)
        # into the most columns, then the one whose other lines agree with that width
        scores = {}
        for candidate in (",", ";", "\t"):
            widths = [len(next(csv.reader([line], delimiter=candidate))) for line in sample] or [1]
            widest = max(widths)
            scores[candidate] = (widest, sum(width == widest for width in widths), candidate == ",")
        delimiter = max(scores, key=lambda candidate: scores[candidate])
        if scores[delimiter][0] <= 1:
            delimiter = ","
        if delimiter != ",":
            notes.append(f"separator {delimiter!r} (the header splits into {scores[delimiter][0]} columns with it)")
    reader = csv.reader(io.StringIO(text, newline=""), delimiter=delimiter, skipinitialspace=True)
    rows, lines = [], []
    try:
        for cells in reader:
            rows.append(cells)
            lines.append(reader.line_num + line_offset)
    except csv.Error as exc:
        raise StudyError(f"{file}:{reader.line_num + line_offset}: not readable as a table: {exc}") from None
    return rows, lines, notes


_UNITS_CELL = re.compile(r"^\s*\[[^\]]*\]\s*$")
_NUMBER_POINT = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")
_NUMBER_COMMA = re.compile(r"^[+-]?\d+,\d+$")


def _progress(total: int, label: str):
    """A tqdm bar on a terminal for large sessions; a do-nothing stand-in otherwise."""
    if total < PROGRESS_ROWS or not sys.stderr.isatty():
        class _Quiet:
            def update(self, n):
                pass

            def close(self):
                pass
        return _Quiet()
    from tqdm import tqdm

    return tqdm(total=total, desc=label, unit="row", file=sys.stderr, leave=False)


def _decimal_mark(columns: list, file: str) -> str:
    """'.' or ',' for the numbers of the file; StudyError when both occur (never read one as the other)."""
    import pandas as pd

    comma_example = point_example = None
    for raw in columns:
        cells = pd.Series(raw, dtype=object).astype(str).str.strip().str.rstrip("LRlr ").str.strip()
        commas = cells[cells.str.match(_NUMBER_COMMA.pattern)]
        points = cells[cells.str.contains(".", regex=False) & cells.str.match(_NUMBER_POINT.pattern)]
        if comma_example is None and len(commas):
            comma_example = commas.iloc[0]
        if point_example is None and len(points):
            point_example = points.iloc[0]
        if comma_example and point_example:
            raise StudyError(f"{file}: numbers are written with both decimal marks ({point_example!r} and "
                             f"{comma_example!r}); the file cannot be read without guessing which is meant")
    return "," if comma_example else "."


def _to_numbers(raw, layout: VendorMap, decimal: str):
    """(values, missing mask, indices of bad cells) of one column's text cells, vectorised."""
    import pandas as pd

    series = pd.Series(raw, dtype=object).astype(str).str.strip()
    missing = series.isin(list(layout.missing)) | series.str.upper().isin(["NAN", "N/A", "NA"])
    cleaned = series
    if layout.left_right_suffix or layout.left_right_prefix:
        if layout.left_right_suffix:
            side = cleaned.str.extract(r"^(.*?)\s*([LRlr])$")
            letter, number = side[1], side[0]
        else:
            side = cleaned.str.extract(r"^([LRlr])\s*(.*?)$")
            letter, number = side[0], side[1]
        has = letter.notna()
        cleaned = cleaned.where(~has, number)
        signs: np.ndarray | float = np.where(has & letter.str.upper().eq("L"), -1.0, 1.0)
    else:
        signs = 1.0
    if decimal == ",":
        cleaned = cleaned.str.replace(",", ".", regex=False)
    numbers = pd.to_numeric(cleaned.where(~missing, "nan"), errors="coerce").to_numpy(dtype=float)
    bad = np.flatnonzero(np.isnan(numbers) & ~missing.to_numpy())
    return numbers * signs, missing.to_numpy(), bad.tolist()


def _rule_marks(rule, header, columns, used, unused, meaning: str):
    """Rows whose cell in a layout rule's column is one of its values (None: no rule or no such column); the
    column is counted as used, for ``meaning``."""
    if not rule:
        return None
    names = [_norm(split_header(c)[0]) for c in header]
    if _norm(rule["column"]) not in names:
        return None
    column = names.index(_norm(rule["column"]))
    if header[column] in unused:
        unused.remove(header[column])
        used.append((header[column], meaning, "", 1.0))
    marks = {_norm(v) for v in rule["values"]}
    return np.array([_norm(cell) in marks for cell in columns[column]])


def _flag_estimated(layout, header, columns, values, flags, used, unused, notes) -> None:
    """Rows whose estimated-flag column holds one of the layout's ``values``; where the layout also lists the
    values that mean measured, a value in neither list (a localised export's word the layout does not know, a value
    a new app version writes) cannot be told from an estimate: those rows are flagged estimated too, and said."""
    rule = layout.estimated
    estimated = _rule_marks(rule, header, columns, used, unused, rule and (
        "estimated flag: " + " or ".join(map(str, rule["values"])) + " marks " + ", ".join(rule["fields"])
        + " as estimated"))
    if estimated is None:
        return
    if rule.get("measured") is not None:
        names = [_norm(split_header(c)[0]) for c in header]
        cells = [_norm(cell) for cell in columns[names.index(_norm(rule["column"]))]]
        known = {_norm(v) for v in (*rule["values"], *rule["measured"])} | {""}
        unknown = np.array([cell not in known for cell in cells])
        if unknown.any():
            seen = sorted({cell for cell in cells if cell not in known})
            notes.append(f"{rule['column']}: {int(unknown.sum())} row(s) hold {', '.join(map(repr, seen[:5]))}, "
                         f"neither a value that marks an estimate ({', '.join(map(repr, rule['values'])) or 'none'}) "
                         f"nor one that marks a measurement ({', '.join(map(repr, rule['measured'])) or 'none'}) "
                         f"in this layout: their {', '.join(rule['fields'])} are flagged estimated (not told apart "
                         f"from an estimate)")
            estimated = estimated | unknown
    if estimated.any():
        for field in rule["fields"]:
            present = estimated & np.isfinite(values[field])
            if present.any():
                flags[(field, "estimated")] = present


def _flag_no_data(layout, header, columns, values, flags, used, unused) -> None:
    """Fields a row says it does not carry (GSPro's ContainsClubData = false): missing, flagged ``no data``."""
    rule = layout.no_data
    marked = _rule_marks(rule, header, columns, used, unused, rule and (
        "no-data flag: " + " or ".join(map(str, rule["values"])) + " marks " + ", ".join(rule["fields"])
        + " as not carried"))
    if marked is None or not marked.any():
        return
    for field in rule["fields"]:
        present = marked & np.isfinite(values[field])
        if present.any():
            values[field] = np.where(marked, np.nan, values[field])
            flags[(field, "no data")] = flags.get((field, "no data"), np.zeros_like(marked)) | present


def _flag_excluded(layout, header, columns, flags, used, unused) -> None:
    rule = layout.excluded
    excluded = _rule_marks(rule, header, columns, used, unused,
                           rule and "rows marked not to use: " + " or ".join(map(str, rule["values"])))
    if excluded is not None and excluded.any():
        flags[("row", "excluded")] = excluded


def _read_flags(header, columns, flags, used, unused, file, lines) -> None:
    """The ``flags`` column of impactlab's normalised table (``spin_rate:estimated;spin_axis:clamped``)."""
    column = [_norm(cell) for cell in header].index("flags")
    unused.remove(header[column])
    used.append((header[column], "flags (field:estimated, field:clamped, field:no data)", "", 1.0))
    for index, cell in enumerate(columns[column]):
        for item in filter(None, (part.strip() for part in cell.split(";"))):
            field, _, kind = item.partition(":")
            if (field, kind) != ("row", "excluded") and (field not in FIELDS
                                                          or kind not in ("estimated", "clamped", "no data",
                                                                          "inconsistent", "modelled", "unreadable")):
                raise StudyError(f"{file}:{lines[index]}: flags: expected field:estimated, field:clamped or "
                                 f"field:no data with a field of the vocabulary, got {item!r}")
            flags.setdefault((field, kind), np.zeros(len(lines), bool))[index] = True


def _derive(values: dict, used: list, notes: list, flags: dict) -> None:
    """Fill what follows from other columns: spin rate and axis from back and side spin, the face angle from
    face-to-path and path; say each, and check face to path where both sides are given."""
    back, side = values["back_spin"], values["side_spin"]
    given = {field for _, field, _, _ in used}
    if "spin_rate" not in given and np.isfinite(back).any():
        values["spin_rate"] = np.hypot(back, side)
        notes.append("spin rate = hypot(back spin, side spin) (no spin-rate column)")
        _inherit(flags, "spin_rate", ("back_spin", "side_spin"))
    elif (fill := np.isnan(values["spin_rate"]) & np.isfinite(back) & np.isfinite(side)).any():
        values["spin_rate"] = np.where(fill, np.hypot(back, side), values["spin_rate"])
        notes.append(f"spin rate = hypot(back spin, side spin) in {int(fill.sum())} row(s) without one")
        _inherit(flags, "spin_rate", ("back_spin", "side_spin"))
    if "spin_axis" not in given and np.isfinite(back).any() and np.isfinite(side).any():
        values["spin_axis"] = np.arctan2(side, back)
        notes.append("spin axis = atan(side spin / back spin) (no spin-axis column; both positive curving right)")
        _inherit(flags, "spin_axis", ("back_spin", "side_spin"))
    # a spin rate given beside back and side spin is checked against them in consistency.check_consistency
    if "face_angle" not in given and "face_to_path" in given and "path" in given:
        values["face_angle"] = values["path"] + values["face_to_path"]
        notes.append("face angle = club path + face to path (no face-angle column)")
        _inherit(flags, "face_angle", ("path", "face_to_path"))
    elif {"face_angle", "face_to_path", "path"} <= given:
        with np.errstate(invalid="ignore"):
            off = np.abs(values["face_angle"] - values["path"] - values["face_to_path"]) > math.radians(0.05)
        if off.any():
            notes.append(f"face to path differs from face angle - club path by more than 0.05 deg in {int(off.sum())}"
                         f" row(s) (kept as measured; face angle and path are used)")


def _check_spin_signs(layout, values, used, notes, flags) -> None:
    """Side spin and spin axis describe one tilt: in the vocabulary both are positive curving right. Where a file
    gives both, rows whose signs disagree (both clearly non-zero: 50 rpm, 0.5 deg) are a convention the layout does
    not describe: a layout whose axis follows its side spin has its axis turned when every such row disagrees;
    otherwise the disagreeing rows' spin axis and side spin are flagged ``inconsistent`` (left out like estimated
    values) and the report says how many."""
    given = {field for _, field, _, _ in used}
    if not {"spin_axis", "side_spin"} <= given:
        return
    side, axis = values["side_spin"], values["spin_axis"]
    with np.errstate(invalid="ignore"):
        clear = (np.abs(side) > 50 * 2 * math.pi / 60) & (np.abs(axis) > math.radians(0.5))
        disagree = clear & (np.sign(side) != np.sign(axis))
    if not disagree.any():
        return
    if layout.spin_axis_follows_side_spin and disagree.sum() == clear.sum():
        values["spin_axis"] = -axis
        notes.append(f"spin axis: its sign disagrees with the side spin's in all {int(clear.sum())} row(s) with "
                     f"clear spin, so this export counts the axis positive curving left; turned to the vocabulary's "
                     f"(positive curving right, agreeing with the side spin)")
        return
    for field in ("spin_axis", "side_spin"):
        flags[(field, "inconsistent")] = disagree
    notes.append(f"side spin and spin axis disagree in sign in {int(disagree.sum())} of {int(clear.sum())} row(s) "
                 f"with clear spin: those rows' spin axis and side spin are flagged inconsistent and left out")


def _flag_all_zero(layout, values: dict, flags: dict, notes: list) -> None:
    """Rows where every field of ``layout.no_data_when_all_zero`` reads exactly 0: the monitor's "no club data"
    marker (no club is delivered with zero loft, path, face and attack angle at once); read as missing, flagged."""
    fields = [field for field in layout.no_data_when_all_zero if np.isfinite(values[field]).any()]
    if not fields:
        return
    zero = np.ones(len(values[fields[0]]), bool)
    for field in fields:
        zero &= values[field] == 0.0
    if not zero.any():
        return
    for field in fields:
        values[field] = np.where(zero, np.nan, values[field])
        flags[(field, "no data")] = flags.get((field, "no data"), np.zeros_like(zero)) | zero
    notes.append(f"{int(zero.sum())} row(s) give {', '.join(fields)} all exactly 0 (the {layout.name}'s no-data "
                 f"marker): read as missing")


def _flag_without(layout, values: dict, flags: dict, notes: list) -> None:
    """Values written where a field they are made from is missing (``layout.no_data_without``): placeholders, read
    as missing and flagged ``no data``, each rule said once with its count."""
    for rule in layout.no_data_without:
        value = values[rule["field"]]
        lacking = np.zeros(value.shape, bool)
        for field in rule["without"]:
            lacking |= np.isnan(values[field])
        placeholder = lacking & np.isfinite(value)
        if rule["only_zero"]:  # an exact 0 (0 in every unit)
            placeholder &= value == 0.0
        if not placeholder.any():
            continue
        values[rule["field"]] = np.where(placeholder, np.nan, value)
        flags[(rule["field"], "no data")] = flags.get((rule["field"], "no data"), np.zeros_like(placeholder)) | \
            placeholder
        written = "exactly 0" if rule["only_zero"] else "a value"
        notes.append(f"{int(placeholder.sum())} row(s) give {rule['field']} {written} with no "
                     f"{' or no '.join(rule['without'])}: read as missing" + (f" ({rule['why']})" if rule['why']
                                                                               else ""))


def _club_names(layout, names: tuple, notes: list) -> tuple:
    """Club names with the layout's words turned into the catalogue's (``Eisen 7`` -> ``Iron 7``), word by word;
    said once with an example."""
    if not layout.club_words:
        return names
    turned = {}
    for name in set(names):
        words = [layout.club_words.get(_norm(word), word) for word in name.split()]
        if " ".join(words) != " ".join(name.split()):
            turned[name] = " ".join(words)
    if turned:
        example = next(iter(sorted(turned.items())))
        notes.append(f"club names in the layout's words read as the catalogue's: {len(turned)} name(s), e.g. "
                     f"{example[0]!r} as {example[1]!r}")
    return tuple(turned.get(name, name) for name in names)


def _inherit(flags: dict, field: str, sources) -> None:
    for (name, kind), rows in list(flags.items()):
        if name in sources and kind in ("estimated", "clamped"):
            flags[(field, kind)] = flags.get((field, kind), np.zeros_like(rows)) | rows
