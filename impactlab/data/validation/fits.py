"""A calibration written by ``impactlab fit TRAIN --json fit.json`` and applied to other shots.

``impactlab validate --dataset TEST --fit fit.json`` (and ``scorecard(table, fit=load_fits("fit.json"))``)
predicts TEST's held-out shots with each fitted model's parameters, so a calibration is judged on shots it never
saw. The file holds, per model, the fitted parameter values with their bounds (:data:`impactlab.data.fit.calibration.
PARAMETERS`) and provenance (the training file, its SHA-256 and row count, impactlab's version): a fit applied to
the file it was made on is said to be in-sample.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from pathlib import Path

import attrs

from impactlab.data.fit.calibration import PARAMETERS, apply, model_with
from impactlab.data.sessions.shots import ShotTable, predict
from impactlab._version import __version__
from impactlab.errors import StudyError
from impactlab.model.registry import available, get_model
from impactlab.study.scene_blocks import build_ball


def file_digest(path: str | os.PathLike[str]) -> str:
    """The SHA-256 of a file's bytes (hex)."""
    digest = hashlib.sha256()
    with open(path, "rb") as handle:
        for chunk in iter(lambda: handle.read(1 << 20), b""):
            digest.update(chunk)
    return digest.hexdigest()


def provenance(path: str | os.PathLike[str] | None, table: ShotTable) -> dict:
    """Where a fit comes from: the training file, its SHA-256, the rows fitted and impactlab's version."""
    out = {"table": table.name, "rows": table.size, "impactlab": __version__}
    if path is not None and Path(path).is_file():
        out.update(file=str(path), sha256=file_digest(path))
    return out


@attrs.frozen
class FittedModel:
    """One model's fitted parameters (SI) read from a fit file, ready to predict other shots."""

    model: str
    parameters: tuple[str, ...]
    values: tuple[float, ...]
    bounds: dict = attrs.field(eq=False, factory=dict)
    provenance: dict = attrs.field(eq=False, factory=dict)
    file: str = ""

    @property
    def label(self) -> str:
        """The fit's name in a scorecard: ``model (fit on TRAIN)``."""
        where = self.provenance.get("file") or self.provenance.get("table") or self.file
        return f"{self.model} (fit on {Path(str(where)).name})"

    def predict(self, table: ShotTable, inputs: dict) -> dict:
        """``table``'s outputs (SI arrays) with the fitted values; ``inputs`` are
        :func:`impactlab.data.sessions.shots.table_inputs` of ``table``."""
        ball = build_ball(table.ball or {"preset": "urethane_tour"})
        return predict(model_with(get_model(self.model)(), self.parameters, self.values),
                       apply(inputs, self.parameters, self.values, ball))


def _refuse(path, why: str):
    raise StudyError(f"{path}: expected a fit file written by impactlab fit --json (a list of fits, each with "
                     f"model, parameters and values); {why}")


def load_fits(path: str | os.PathLike[str]) -> list[FittedModel]:
    """The fits of a file written by ``impactlab fit SHOTS --json`` (every model in it).

    A file that is not one, a model not registered, a parameter the calibration does not know or a value outside
    its bounds is refused with one message (:class:`~impactlab.errors.StudyError`, exit 2), never half-applied.
    """
    path = Path(path)
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise StudyError(f"{path}: no such fit file (write one with impactlab fit SHOTS --json {path.name})") from None
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        _refuse(path, f"it cannot be read as JSON ({exc})")
    if isinstance(document, dict):
        document = [document]
    if not isinstance(document, list) or not document:
        _refuse(path, "it holds no fit")
    known = set(available())
    out = []
    for index, entry in enumerate(document):
        if not isinstance(entry, dict) or not {"model", "parameters", "values"} <= set(entry):
            _refuse(path, f"entry {index} lacks model, parameters or values")
        names, values = entry["parameters"], entry["values"]
        if (not isinstance(names, list) or not isinstance(values, list) or len(names) != len(values)
                or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)):
            _refuse(path, f"entry {index}: parameters and values must be lists of equal length, values numbers")
        if entry["model"] not in known:
            _refuse(path, f"entry {index}: model {entry['model']!r} is not registered here "
                          f"({', '.join(sorted(known))})")
        for name, value in zip(names, values):
            if name not in PARAMETERS:
                _refuse(path, f"entry {index}: {name!r} is not a calibration parameter ({', '.join(PARAMETERS)})")
            low, high = PARAMETERS[name][0]
            if not (math.isfinite(value) and low <= value <= high):
                _refuse(path, f"entry {index}: {name} = {value!r} is outside its bounds [{low:g}, {high:g}]")
        out.append(FittedModel(model=str(entry["model"]), parameters=tuple(names),
                               values=tuple(float(v) for v in values), bounds=dict(entry.get("bounds", {})),
                               provenance=dict(entry.get("provenance", {})), file=str(path)))
    return out


def in_sample(fits: list[FittedModel], path: str | os.PathLike[str]) -> list[str]:
    """Labels of the fits made on the very file ``path`` (same SHA-256): their errors there are in-sample."""
    if not Path(path).is_file():
        return []
    digest = file_digest(path)
    return [fit.label for fit in fits if fit.provenance.get("sha256") == digest]


def bounds_of(names) -> dict:
    """``{parameter: [lower, upper]}`` of the calibration's parameters (a fit file's ``bounds``)."""
    return {name: list(PARAMETERS[name][0]) for name in names}


__all__ = ["FittedModel", "bounds_of", "file_digest", "in_sample", "load_fits", "provenance"]
