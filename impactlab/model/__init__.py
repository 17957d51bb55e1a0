"""The plugin contract: ImpactModel and its result, the registry, planning, case inputs, derivation, diagnostics.

``impactlab.model`` is the public path for plugin authors (docs/writing-a-model.md); its modules are the
implementation.
"""

from impactlab.model.base import HISTORY_LENGTH, ImpactModel, ModelResult, NoOptions
from impactlab.model.case_inputs import CaseInputs
from impactlab.model.diagnostics import LARGE_CONTACT_RATIO, ValidityWarning

__all__ = ["HISTORY_LENGTH", "CaseInputs", "ImpactModel", "ModelResult", "NoOptions", "LARGE_CONTACT_RATIO",
           "ValidityWarning"]
