"""Swept model options (``sweep: {model_option.ENTRY.OPTION: [...]}``): one run per value, one dataset.

A model option is no input of the cases (a model's options are fixed when it is made), so the study runs once
per value with the entry's model made with that value (:class:`impactlab.study.core.OptionAxis`), and the results
are joined along a dimension named after the option, after the sweep's own. A model the option does not belong to
is the same along it.
"""

from __future__ import annotations

import shutil
from collections.abc import Callable
from pathlib import Path
from typing import Any

import attrs
import numpy as np
import pandas as pd
import xarray as xr

from impactlab.io.results import write_results
from impactlab.study.core import OptionAxis, Study
from impactlab.vocabulary import MODEL_DIM


def run_option_sweep(study: Study, run: Callable[..., xr.Dataset], *, output: str | Path | None = None,
                     progress_folder: str | Path | None = None, **options: Any) -> xr.Dataset:
    """Run ``study`` once per combination of its swept model options and join the results.

    Parameters
    ----------
    study : Study
        A study with ``option_sweep``.
    run : callable
        :func:`impactlab.run.runner.run_study` (passed in: this module sits below the runner).
    output : path, optional
        Write the joined result file here.
    progress_folder : path, optional
        Each run keeps its finished chunks in a subfolder of its own.
    **options
        The other keywords of ``run``.

    Returns
    -------
    xarray.Dataset
        Dimensions ``model``, the sweep's, then one per swept option (coordinate: the values as written).
    """
    base = attrs.evolve(study, option_sweep=())
    dataset = _joined(base, study.option_sweep, run, progress_folder, options, ())
    dims = [MODEL_DIM] + [axis.dim for axis in study.sweep] + [axis.dim for axis in study.option_sweep]
    dataset = dataset.transpose(*dims, ...)
    if output is not None:
        write_results(dataset, output)
        if progress_folder is not None:  # every run's chunks are in the file now (a killed sweep resumes from them)
            shutil.rmtree(progress_folder, ignore_errors=True)
    return dataset


def _joined(study: Study, axes: tuple[OptionAxis, ...], run, folder, options, path) -> xr.Dataset:
    if not axes:
        sub = None if folder is None else Path(folder).joinpath(*path)
        return run(study, progress_folder=sub, **options)
    axis, rest = axes[0], axes[1:]
    parts = []
    for index, model in enumerate(axis.models):
        entries = tuple(attrs.evolve(entry, model=model) if entry.id == axis.entry else entry
                        for entry in study.models)
        parts.append(_joined(attrs.evolve(study, models=entries), rest, run, folder, options,
                             path + (f"{axis.dim}_{index}",)))
    values = list(axis.values)
    coordinate = pd.Index(np.asarray(values) if all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                    for v in values) else [str(v) for v in values], name=axis.dim)
    joined = xr.concat(parts, dim=coordinate, combine_attrs="override")
    joined[axis.dim].attrs.update({"long_name": f"option {axis.option} of model {axis.entry}",
                                   "study_path": f"sweep.model_option.{axis.entry}.{axis.option}"})
    return joined
