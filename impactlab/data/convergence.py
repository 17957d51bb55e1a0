"""Error against run time: a work-precision study of every model in a study.

For each model entry that declares ``has_tolerance`` (rule 8 of
:class:`~impactlab.model.base.ImpactModel`: its ``tolerance`` option sets the
numerical error), the study's cases
are run along a ladder of tolerances. Each output's error is measured against
a converged reference: the same physics at a tolerance far below the ladder,
run twice (reference tolerance and a quarter of it, i.e. twice the
resolution) and extrapolated assuming the error falls in proportion to the
tolerance (Richardson). Models declare how their reference is computed
(:meth:`ImpactModel.reference_options`); ``maw`` uses its MDR engine for
both methods, since both solve the same problem. Wall time per impact is the
median of repeated runs after a warm-up run (caches and imports excluded).
Closed-form models (no declared tolerance) are timed once and have no error to
report beyond round-off.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable, Iterable

import attrs
import numpy as np
import xarray as xr

from impactlab._version import __version__
from impactlab.io.results import RESULT_FORMAT
from impactlab.study.arrays import case_inputs
from impactlab.study.core import Study
from impactlab.vocabulary import OUTPUTS, is_scalar

LADDER = (1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6)


def _timed(model, inputs, outputs, repeats: int) -> tuple[xr.Dataset, float]:
    result = model.compute(inputs, outputs)  # warm-up: imports, caches, calibrations
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        model.compute(inputs, outputs)
        times.append(time.perf_counter() - start)
    return result, float(np.median(times))


def work_precision(study: Study, tolerances: Iterable[float] | np.ndarray = LADDER, repeats: int = 3,
                   progress: Callable[[str], None] | None = None) -> xr.Dataset:
    """Error and wall time per impact for every model entry of ``study`` along a ladder of tolerances."""
    inputs = case_inputs(study)
    n_cases = study.n_cases
    outputs = [name for name in study.outputs if is_scalar(name)]
    tolerances = np.asarray(sorted(tolerances, reverse=True), dtype=float)
    ids = [entry.id for entry in study.models]
    error = np.full((len(ids), tolerances.size, len(outputs)), np.nan)
    abs_error = np.full_like(error, np.nan)
    wall = np.full((len(ids), tolerances.size), np.nan)
    resolution = np.full((len(ids), tolerances.size), np.nan)
    notes = {}
    for m, entry in enumerate(study.models):
        model = entry.model
        say = progress or (lambda text: None)
        if not model.has_tolerance:
            _, seconds = _timed(model, inputs, outputs, repeats)
            wall[m, :] = seconds / n_cases
            error[m, :, :] = 0.0
            abs_error[m, :, :] = 0.0
            notes[entry.id] = "closed form: exact to round-off at any tolerance"
            say(f"{entry.id}: closed form, {1e6 * seconds / n_cases:.2f} us per impact")
            continue
        finest = float(tolerances.min()) / 30.0
        reference_model = type(model)(model.reference_options(finest))
        fine = reference_model.compute(inputs, outputs)
        finer = type(model)(model.reference_options(finest / 4.0)).compute(inputs, outputs)
        reference = {name: finer[name].values + (finer[name].values - fine[name].values) / 3.0 for name in outputs}
        notes[entry.id] = (f"reference: {type(model).__name__} options "
                           f"{json.dumps(attrs.asdict(model.reference_options(finest / 4.0)))} extrapolated")
        for t, tolerance in enumerate(tolerances):
            configured = type(model)(attrs.evolve(model.options, tolerance=float(tolerance)))
            if not configured.can_reach(float(tolerance)):
                continue
            result, seconds = _timed(configured, inputs, outputs, repeats)
            wall[m, t] = seconds / n_cases
            if "steps" in configured.provides:
                resolution[m, t] = float(np.max(configured.compute(inputs, ["steps"])["steps"].values))
            for o, name in enumerate(outputs):
                difference = np.abs(result[name].values - reference[name])
                scale = max(float(np.nanmax(np.abs(reference[name]))), 1e-300)
                abs_error[m, t, o] = float(np.nanmax(difference))
                error[m, t, o] = abs_error[m, t, o] / scale
            say(f"{entry.id}: tolerance {tolerance:g}: error {np.nanmax(error[m, t]):.2e}, "
                f"{1e6 * wall[m, t]:.1f} us per impact")
    return xr.Dataset(
        {
            "error": (("model", "tolerance", "output"), error,
                      {"units": "1", "long_name": "largest error over the cases, relative to the output's largest "
                                                  "magnitude"}),
            "abs_error": (("model", "tolerance", "output"), abs_error,
                          {"long_name": "largest absolute error over the cases, in the output's units"}),
            "wall_time": (("model", "tolerance"), wall, {"units": "s", "long_name": "wall time per impact "
                                                         "(median of repeats, warm)"}),
            "steps": (("model", "tolerance"), resolution, {"units": "1", "long_name": "largest number of time "
                                                           "steps of a case"}),
        },
        coords={"model": ids, "tolerance": ("tolerance", tolerances, {"units": "1", "long_name": "requested "
                                                                      "tolerance"}),
                "output": outputs,
                "output_units": ("output", [OUTPUTS[name].units for name in outputs])},
        attrs={"title": f"work-precision of study {study.name}", "study_name": study.name,
               "study_source": study.source, "cases": n_cases, "repeats": repeats,
               "reference": json.dumps(notes), "impactlab_version": __version__, "impactlab_format": RESULT_FORMAT,
               "method": __doc__.strip().split("\n\n")[1].replace("\n", " ")},
    )
