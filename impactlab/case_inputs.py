"""Public path kept for plugins: :class:`CaseInputs` lives in :mod:`impactlab.model.case_inputs`."""

from impactlab.model.case_inputs import CaseInputs

__all__ = ["CaseInputs"]
