"""The 3-D kernel's Richardson step on cases on one line: its time error against the 2N run alone.

compliant3d.solve extrapolates 2 J(2N) - J(N), which removes a first-order time error (a turning slip). On the 126
1-D plate cases of the conformance suite (W diagonal: the slip stays on one line), for the forms that send them to
the 3-D kernel, this prints the largest time error of J_t of (a) the extrapolated pair and (b) the 2N run alone,
against the same springs at 16 times the steps (extrapolated), in units of the allowed error
min(mu J_n, m_t |V_x|) (the tolerance is 1e-4), and their difference. Nothing is changed by it; see
docs/performance.md, "Cases on one line through the 3-D kernel".

Run: .venv/bin/python benchmarks/measure_line_extrapolation.py
"""

import numpy as np

from impactlab.model import case_inputs
from impactlab.model.registry import get_model
from impactlab.physics import compliant3d
from impactlab.testing import _with, reference_inputs

FACE = {"face_frequency": "4 kHz", "face_modal_mass": "10 g"}
CORE = {"core_radius": 0.01905, "core_shear_modulus": 10e6, "core_specific_gravity": 1.15}
FORMS = [("hertz_mindlin", FACE), ("dem_linear", FACE), ("maw", FACE), ("maw", CORE),
         ("maw", {"rolling_hysteresis": "restitution"}),
         ("hertz_mindlin", {**CORE, "rolling_hysteresis": "restitution"}),
         ("hertz_mindlin", {**FACE, "rolling_hysteresis": "restitution"}), ("maw", {**CORE, "inelastic": "hysteretic"})]


def impulses(name, options, inputs, how):
    original = compliant3d.solve
    if how == "2N alone":
        compliant3d.solve = lambda *a, **k: original(*a, **dict(k, extrapolate=False))
    elif how == "reference":
        compliant3d.solve = lambda *a, **k: original(*a, **dict(k, steps=k["steps"] * 16))
    try:
        result = get_model(name)(**options).compute(inputs, ["tangential_impulse", "normal_impulse"])
    finally:
        compliant3d.solve = original
    return result["tangential_impulse"].values, result["normal_impulse"].values


def main():
    inputs = _with(reference_inputs(), club_restitution_gain=0.05)
    state = case_inputs.CaseInputs(inputs).contact_state()
    m_t, slip = 1.0 / state["mobility"][:, 0, 0], np.abs(state["slip_speed"])
    print("time error of J_t / min(mu J_n, m_t |V_x|), 126 plate cases (largest)")
    for name, options in FORMS:
        reference, normal = impulses(name, options, inputs, "reference")
        allowed = np.minimum(inputs["friction"] * normal, m_t * slip)
        allowed = np.where(allowed > 0.0, allowed, np.inf)
        pair, _ = impulses(name, options, inputs, "extrapolated")
        alone, _ = impulses(name, options, inputs, "2N alone")
        print(f"  {name} {sorted(options)}: extrapolated {np.max(np.abs(pair - reference) / allowed):.2e}, "
              f"2N alone {np.max(np.abs(alone - reference) / allowed):.2e}, "
              f"apart {np.max(np.abs(alone - pair) / allowed):.2e}")


if __name__ == "__main__":
    main()
