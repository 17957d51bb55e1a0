"""The building blocks the built-in models share, at a public path for plugin authors.

A plugin that wants what ``maw`` or ``dem_linear`` build on imports it from here (``from impactlab_models.shared
import HertzTangentialModel, CompliantOptions``), never from the private modules that hold it (``_common``,
``_compliant``: they may move). The built-in models import these names from here too, so that the example a
plugin author copies uses only public paths (docs/writing-a-model.md, "Public paths"; checked by
tests/test_public_api.py).
"""

from ._common import (CLOSED_FORM_DIAGNOSTICS, CORE_TORSION_DOC, FACE_FLEX_DOC, FRICTION_INPUTS, FRICTION_LAW,
                      FRICTION_LAW_DOC, IMPULSES_3D, MATERIAL_OPTIONAL, RIGID_BODY_INPUTS, RIGID_BODY_OPTIONAL,
                      RIGID_NOT_PROVIDED, ROLLING_HYSTERESIS, ROLLING_OUTPUTS, STRONGE, BallLawOptions,
                      closed_form_diagnostics, cover_modulus_field, cover_thickness_field, impulse_outputs,
                      law_friction, rolling_on, PLAIN_BALL, RATE_LAWS_DOC, lever_field, pressure_exponent_field,
                      slip_exponent_field, characteristic_slip,
                      rate_law_state, reference_speed_field, relaxation_time_field, relaxed_fraction_field,
                      face_frequency_field, face_modal_mass_field)
from ._compliant import INELASTIC, CompliantOptions, HertzTangentialModel, int_at_least, optional_int

__all__ = [
    # the compliant models' base class and the protocol of their options (docs/writing-a-model.md)
    "HertzTangentialModel", "CompliantOptions", "INELASTIC", "int_at_least", "optional_int",
    # the ball laws' options (rolling resistance, friction law, core, flexing face) shared by every model
    "BallLawOptions", "cover_modulus_field", "cover_thickness_field", "ROLLING_HYSTERESIS", "rolling_on",
    "FRICTION_LAW", "law_friction", "CORE_TORSION_DOC", "FACE_FLEX_DOC", "FRICTION_LAW_DOC",
    # declarations of inputs and outputs several models make alike
    "RIGID_BODY_INPUTS", "RIGID_BODY_OPTIONAL", "MATERIAL_OPTIONAL", "FRICTION_INPUTS", "IMPULSES_3D",
    "ROLLING_OUTPUTS", "CLOSED_FORM_DIAGNOSTICS", "closed_form_diagnostics", "impulse_outputs",
    "RIGID_NOT_PROVIDED", "STRONGE",
    # the laws with a scale of their own (impactlab.physics.rate_laws): their options and the state they set
    "PLAIN_BALL", "RATE_LAWS_DOC", "lever_field", "pressure_exponent_field",
    "slip_exponent_field", "characteristic_slip", "rate_law_state", "reference_speed_field",
    "relaxation_time_field", "relaxed_fraction_field",
    # the flexing face's options (a registered model may default them on: hertz_mindlin_face)
    "face_frequency_field", "face_modal_mass_field",
]
