"""The shared TrackMan file, shipped as the dataset ``trackman_driver_sessions``, goes through every command that
reads shots (shots, fly, validate, fit, export) with exit 0, and the rows each skips, per reason, are those a hand
count of the file gives (issue 32, items 1, 2, 6).

The hand count is written here with the csv module from the published bytes, not with the reader: blank cells,
TrackMan's -2^31 marker (times a power of ten), rows repeated cell for cell, and the rule values typed from their
sources (the Rules' COR limit 0.830 + 0.008, the 45.93 g ball, the catalogue driver's 204 g head and its face).
"""

from __future__ import annotations

import csv
import gzip
import hashlib
import io
import json
import math
import re
from collections import Counter

import pytest

from impactlab.cli import main
from impactlab.data.sessions import DATASETS, dataset_path, read_session
from impactlab.scene.catalogue import club_preset

NAME = "trackman_driver_sessions"
#: the published file (tim-blackmore/launch-monitor-regression data.csv @ fd8869f; the shared README)
SHA256 = "fae80d325e69c928debcbbbacd908c1e4a8b0d44d5cd5290a2bbad95b83cae04"
#: the largest smash factor of the catalogue driver: (1 + 0.838) x 204 g / (204 g + 45.93 g), + 2 % for measurement
SMASH_LIMIT = 1.838 * 0.204 / (0.204 + 0.04593) * 1.02
SMASH_REASON = ("a smash factor no driver gives (above 1.530: the Rules' COR limit, the head's mass, 2 % for "
                "measurement)")
STRIKE_REASON = "strike off the driver's face (Impact Height beyond 30 mm of its centre)"
LAUNCH = ("Ball Speed", "Launch Angle", "Launch Direction", "Spin Rate", "Spin Axis")


def _published_rows() -> tuple[list[str], list[list[str]]]:
    text = gzip.decompress(dataset_path(NAME).read_bytes()).decode("utf-8")
    rows = list(csv.reader(io.StringIO(text)))
    return rows[0], rows[2:]  # the header, then the units row, then one shot per line (file line = index + 3)


def _number(cell: str) -> float | None:
    """A cell's number, None for a blank, TrackMan's 'NaN' or its -2^31 marker (times 10^k)."""
    if cell.strip() in ("", "NaN"):
        return None
    value = float(cell)
    if value < 0 and abs(value / -2.0 ** 31 / 10 ** round(math.log10(value / -2.0 ** 31)) - 1) < 1e-5:
        return None
    return value


def hand_count(header: list[str], rows: list[list[str]]) -> tuple[Counter, Counter, Counter, int]:
    """(rows not read as shots, rows the impact models skip, rows fly skips: each reason -> count; shots read)."""
    column = {name: index for index, name in enumerate(header)}
    face = club_preset("driver")
    half_width, half_height = face.face_width * 500, face.face_height * 500  # mm
    seen, kept = set(), []
    not_read = Counter()
    for cells in rows:
        if tuple(cells) in seen:
            not_read["repeats"] += 1
            continue
        seen.add(tuple(cells))
        kept.append(cells)
    models, flown = Counter(), Counter()
    for cells in kept:
        get = {name: _number(cells[index]) for name, index in column.items() if name not in ("Club", "Ball")}
        bad = []
        smash = get["Smash Factor"] if get["Smash Factor"] is not None else (
            get["Ball Speed"] / get["Club Speed"] if get["Ball Speed"] and get["Club Speed"] else None)
        if smash is not None and smash > SMASH_LIMIT:
            bad.append(SMASH_REASON)
        if get["Impact Height"] is not None and abs(get["Impact Height"]) > half_height:
            bad.append(STRIKE_REASON)
        assert get["Impact Offset"] is None or abs(get["Impact Offset"]) <= half_width  # no such row in the file
        for name, words in (("Club Speed", "no club speed"), ("Attack Angle", "no attack angle"),
                            ("Dyn. Loft", "no dynamic loft")):
            if get[name] is None:
                models[words] += 1
        if all(get[name] is None for name in LAUNCH):
            models["no measured launch quantity"] += 1
        for reason in bad:
            models[reason] += 1
            flown[reason] += 1
        for name, words in (("Ball Speed", "no ball speed"), ("Launch Angle", "no launch angle"),
                            ("Spin Rate", "no spin rate")):
            if get[name] is None:
                marker = cells[column[name]].strip() not in ("", "NaN")
                flown[words + (" (a no-value marker in the file)" if marker else "")] += 1
        if get["Launch Angle"] is not None and get["Launch Angle"] < 0:
            flown["launched below the horizontal (it meets the ground at once: no carry to predict)"] += 1
    return not_read, models, flown, len(kept)


def _said(text: str) -> Counter:
    """reason -> count of every summary line a command printed (unusual values aside)."""
    found = Counter()
    for line in text.splitlines():
        match = re.match(r"^\s+(.*): (\d+) row\(s\) \((?:first line|line\(s\))", line)
        if match and "unusual, used as given" not in line:
            found[match.group(1)] += int(match.group(2))
    return found


def _subset(tmp_path, lines: list[int]):
    """A file of the published header, units row and the rows at these file lines, as published."""
    header, rows = _published_rows()
    text = gzip.decompress(dataset_path(NAME).read_bytes()).decode("utf-8").splitlines(keepends=True)
    path = tmp_path / "subset.csv"
    path.write_text("".join(text[:2] + [text[line - 1] for line in lines]))
    return path, header, [rows[line - 3] for line in lines]


def test_the_shipped_dataset_is_the_published_file_with_its_licence():
    raw = gzip.decompress(dataset_path(NAME).read_bytes())
    assert len(raw) == 3_117_201 and hashlib.sha256(raw).hexdigest() == SHA256
    licence = dataset_path(NAME).with_name(f"{NAME}.LICENSE").read_text()
    assert "MIT License" in licence and "Tim Blackmore" in licence
    assert NAME in DATASETS and "fd8869f" in dataset_path(NAME).with_name("README.md").read_text()


#: file lines of the quick subset: the first 40 shots (flown indoors: TrackMan's model output), four flights the radar
#: tracked for their whole hang time (2034-2036, 2038), and each kind of bad row (a smash factor of 1.59 at line 75,
#: the empty row 145 and its repeats at 171 and 452, a launch below the horizontal at 2043, the -2^31 x 10 rpm spin
#: at 4490, a strike 31 mm up the face at 5892)
SUBSET = list(range(3, 43)) + [75, 145, 171, 452, 2034, 2035, 2036, 2038, 2043, 4490, 5892]


def test_a_subset_is_read_and_exported_with_exit_0_and_its_skips_match_the_hand_count(tmp_path, capsys):
    path, header, rows = _subset(tmp_path, SUBSET)
    not_read, models, flown, kept = hand_count(header, rows)
    assert not_read["repeats"] == 2 and models[SMASH_REASON] >= 1 and models[STRIKE_REASON] == 1  # the subset's
    assert main(["shots", str(path)]) == 0
    said = _said(capsys.readouterr().out)
    first = 2 + SUBSET.index(145) + 1  # the empty row's line in the subset file; its two repeats follow it
    assert said == Counter({**{k: v for k, v in models.items() if v}, f"repeats line {first} cell for cell (the same "
                            "shot twice: a session exported or appended twice, a message sent again)": 2})
    out = tmp_path / "shots.json"
    assert main(["export", str(path), "-o", str(out)]) == 0
    assert _said(capsys.readouterr().err) == +flown
    distinct = list(dict.fromkeys(map(tuple, rows)))
    assert len(json.loads(out.read_text())) == kept - sum(1 for cells in distinct if _flown_not(header, list(cells)))
    assert main(["validate", "--dataset", str(path), "--model", "rigid_coulomb", "--strict"]) == 2
    err = capsys.readouterr().err
    strike = 2 + SUBSET.index(5892) + 1
    assert "--strict: 2 bad row(s)" in err and f"subset.csv:{strike}: strike off the driver's face" in err


@pytest.mark.slow
def test_a_subset_is_flown_validated_and_fitted_with_exit_0_and_its_skips_match_the_hand_count(tmp_path, capsys):
    path, header, rows = _subset(tmp_path, SUBSET)
    _, models, flown, _ = hand_count(header, rows)
    assert main(["fly", str(path)]) == 0
    printed = capsys.readouterr().out
    assert _said(printed) == +flown
    assert "model against the monitor's carry, 4 shot(s)" in printed  # the four tracked flights, no other
    assert "over the flights the monitor measured (4 of " in printed
    assert main(["validate", "--dataset", str(path), "--model", "rigid_coulomb"]) == 0
    assert _said(capsys.readouterr().out) == +models
    assert main(["fit", str(path), "--model", "rigid_coulomb", "--parameter", "friction"]) == 0
    assert _said(capsys.readouterr().out) == +models


def _flown_not(header, cells) -> bool:
    """Whether a (distinct) row is not flown, by the hand count's rules."""
    _, _, flown, _ = hand_count(header, [cells])
    return bool(+flown)


@pytest.mark.slow
def test_the_published_file_goes_through_every_command_with_exit_0_and_its_skips_match_the_hand_count(tmp_path,
                                                                                                      capsys):
    header, rows = _published_rows()
    not_read, models, flown, kept = hand_count(header, rows)
    assert kept == 10_166 and not_read["repeats"] == 3
    session = read_session(NAME)
    assert session.size == kept and session.vendor.id == "trackman_tps_legacy"
    # the README's counts of tracked flights: 1,113 tracked for at least 90 % of their hang time
    modelled = session.flags[("carry_distance", "modelled")]
    import numpy as np
    assert int((np.isfinite(session.values["carry_distance"]) & ~modelled).sum()) == 1113
    assert main(["shots", NAME]) == 0
    said = _said(capsys.readouterr().out)
    assert {reason: said[reason] for reason in models} == dict(models)
    assert main(["fly", NAME]) == 0
    assert _said(capsys.readouterr().out) == +flown
    assert main(["export", NAME, "-o", str(tmp_path / "shots.json")]) == 0
    assert _said(capsys.readouterr().err) == +flown
    assert main(["validate", "--dataset", NAME, "--model", "rigid_coulomb"]) == 0
    assert _said(capsys.readouterr().out) == +models
    assert main(["fit", NAME, "--model", "rigid_coulomb", "--parameter", "friction"]) == 0
    assert _said(capsys.readouterr().out) == +models
