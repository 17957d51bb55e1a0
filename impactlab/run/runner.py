"""Run a study: check every model can run, build the case inputs, call the models, assemble one dataset.

Planning (what runs, what is derived, what is missing and why) happens
before any model runs, so a study that cannot run fails at once and says why.
"""

from __future__ import annotations

import contextlib
import os
import warnings
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import attrs
import numpy as np
import xarray as xr

from impactlab.errors import PlausibilityWarning
from impactlab.run.assemble import assemble
from impactlab.run.options import run_option_sweep
from impactlab.model.diagnostics import warn as warn_validity
from impactlab.model.planning import OutputPlan, require_inputs
from impactlab.run.sensitivity import run_sensitivity
from impactlab.study.arrays import ball_law_applies, case_inputs
from impactlab.study.core import Study, load_study
from impactlab.physics.contact import contact_state
from impactlab.physics.delivery import DELIVERY_INPUTS
from impactlab.study.limits import check
from impactlab.run.execution import ProgressStore, fingerprint, run_chunks
from impactlab.io.results import write_results


@attrs.frozen
class StudyPlan:
    """The work a study will do: one output plan per model entry, and the case count.

    The model plans are made once per study, for the names of its case inputs (``inputs``), and are the ones
    every chunk runs with; the sentence on the solver paths needs the contact state of every case, so it is
    built only when the plan is described (``impactlab run --plan``), never on the way to a run.
    """

    study: str
    n_cases: int
    models: tuple[tuple[str, OutputPlan], ...]
    #: the resources it will take (impactlab.study.limits.Estimate.describe)
    resources: str = ""
    #: the names of the case inputs the models were planned for (:func:`case_input_names`)
    inputs: frozenset[str] = frozenset()
    source: Study | None = attrs.field(default=None, eq=False, repr=False)
    #: cases on one line (1-D solvers), counted by the run from the chunks' contact states; None before a run
    one_line: int | None = None

    @property
    def paths(self) -> str:
        """Which solver path the cases take, and why (one paragraph; empty without a club head).

        After a run, from the count its chunks made of their own contact states; before (``--plan``), from a
        contact state of every case built here for the purpose."""
        return describe_paths(self.source, self.one_line) if self.source is not None else ""

    def describe(self) -> str:
        """The plan in words: cases x models, the resource estimate, per model what is computed, derived and missing."""
        lines = [f"study {self.study!r}: {self.n_cases} case(s) x {len(self.models)} model(s)"]
        if self.resources:
            lines.append(f"  {self.resources}")
        lines += [f"  [{entry_id}] {plan.describe()}" for entry_id, plan in self.models]
        paths = self.paths
        if paths:
            lines.append(f"  contact: {paths}")
        return "\n".join(lines)


def describe_paths(study: Study, one_line: int | None = None) -> str:
    """How many cases lie on one line (the 1-D solvers) and how many need the 3-D ones, and why.

    ``one_line``: that count if known (a run counts it chunk by chunk); else it is computed from the contact
    state of every case."""
    if study.scene.club is None:
        return ""
    if one_line is None:
        one_line = int(np.sum(contact_state(case_inputs(study))["one_dimensional"]))
    coupled = study.n_cases - one_line
    text = (f"{one_line} case(s) on one line (the mobility matrix is diagonal in the contact frame: a strike on the "
            f"centre-of-mass line of a flat face) take the closed forms and the scaled 1-D solvers; {coupled} case(s) "
            "are coupled (off the centre-of-mass line or on a curved face: the slip may turn) and take Stronge's "
            "integration (rigid_coulomb) and the 3-D kernel (compliant models); restitution solves both with the "
            "full mobility")
    if "face_rotation" in study.outputs:
        text += "; face_rotation is asked for, so the compliant models take the 3-D kernel for every case"
    return text


def plan_study(study: Study) -> StudyPlan:
    """Plan every model of the study; refuse a model that lacks a required input, naming model and input.

    A study that would need more cases or memory than :mod:`impactlab.study.limits` allows is refused here,
    before its inputs are built (the one place the limits are checked on the way to a run).
    """
    resources = check(study).describe()
    given = case_input_names(study)
    plans = []
    for entry in study.models:
        plan = entry.model.plan(study.all_outputs, given)
        require_inputs(f"{study.file or study.name}: model {entry.id!r}", entry.model.requires, given, "the study")
        plans.append((entry.id, plan))
    return StudyPlan(study.name, study.n_cases, tuple(plans), resources, frozenset(given), study)


def case_input_names(study: Study) -> set[str]:
    """The names of :func:`case_inputs` of ``study``, without building its arrays."""
    names = (set(study.scene.inputs()) | {field.input for axis in study.sweep for field in axis.fields}
             | {name for name, _ in study.plugin_inputs})
    if all(name in names for name in DELIVERY_INPUTS):
        names.add("angle")
    if ball_law_applies(study):
        names.add("restitution")
    return names


def run_study(source: str | os.PathLike[str] | Mapping[str, Any] | Study, *,
              progress: Callable[[str], None] | None = None, executor: str = "auto",
              workers: int | None = None, scheduler: str | None = None, chunk_size: int | None = None,
              progress_folder: str | Path | None = None, show_progress: bool = False,
              output: str | Path | None = None, plan: StudyPlan | None = None) -> xr.Dataset:
    """Run a study (path, YAML text, mapping or Study) and return its results as one dataset.

    Parameters
    ----------
    executor : str
        ``"auto"`` (serial for small studies, every core for large ones),
        ``"serial"``, ``"processes"`` or ``"dask"``; the results are identical.
    workers : int, optional
        Worker processes (default: every core).
    scheduler : str, optional
        Address of a dask.distributed scheduler (with ``executor="dask"``;
        without it a LocalCluster is started).
    chunk_size : int, optional
        Cases per unit of work.
    progress_folder : path, optional
        Where finished chunks are saved; a run interrupted at any point and
        started again with the same folder computes only what is missing.
    show_progress : bool
        Draw a progress bar on stderr.
    output : path, optional
        Also write the result file here (atomically); with a progress folder, the folder stays locked
        against another run until the file is written and the folder removed.
    plan : StudyPlan, optional
        The study's plan if the caller has made it (:func:`plan_study`: limits checked, models planned),
        so that neither is done twice.
    """
    study = load_study(source)
    if study.option_sweep:  # swept model options: one run per value, joined (impactlab.run.options)
        return run_option_sweep(study, run_study, output=output, progress_folder=progress_folder, progress=progress,
                                executor=executor, workers=workers, scheduler=scheduler, chunk_size=chunk_size,
                                show_progress=show_progress)
    if plan is None or plan.source is not study:
        plan = plan_study(study)
    if study.sensitivity is not None:  # a sensitivity and model-form study (impactlab.run.sensitivity)
        dataset = run_sensitivity(study, progress=progress)
        if output is not None:
            write_results(dataset, output)
        return dataset
    inputs = case_inputs(study)
    if set(inputs) != plan.inputs:  # the plans every chunk runs with were made for these very names
        raise RuntimeError(f"case inputs {sorted(set(inputs) ^ plan.inputs)} differ from the plan's "
                           "(case_input_names and case_inputs disagree)")
    outputs = study.all_outputs
    say = progress or (lambda text: None)
    with contextlib.ExitStack() as stack:
        store = None
        if progress_folder is not None:
            store = stack.enter_context(ProgressStore(Path(progress_folder), fingerprint(study, outputs), say,
                                                      output=output))
        say(f"running {len(study.models)} model(s) on {study.n_cases} case(s)")
        results = run_chunks(study, inputs, outputs, executor=executor, workers=workers, scheduler=scheduler,
                             chunk_size=chunk_size, store=store, show_progress=show_progress,
                             plans=[model_plan for _, model_plan in plan.models])
        if results and "one_line" in results[0]:  # counted from the chunks' own contact states
            plan = attrs.evolve(plan, one_line=results[0]["one_line"])
        dataset = assemble(study, plan, results)
        if output is not None:
            write_results(dataset, output)
            if store is not None:
                store.clear()
    warn_validity(dataset)
    if dataset.attrs.get("head_cor"):  # a result from a head beyond the Rules' COR limit says so (rules_test)
        warnings.warn(str(dataset.attrs["head_cor"]), PlausibilityWarning, stacklevel=2)
    return dataset
