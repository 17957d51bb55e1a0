"""Cost of the ball laws per impact against the elastic law (issue 21: each within 3x of it).

The batch: the conformance suite's golf deliveries on free heads (driver preset and a symmetric head, struck across
the face; 48 cases, 3-D) and its plate cases (126, 1-D), each model at its default tolerance. "Elastic law" is the
model as the paper has it (maw elastic, adjusted speed); each form's time per impact is divided by it, and, for the
rigid forms, by rigid_coulomb without the law too (the integrator over the normal impulse costs what Stronge's
3-D integration does, far more than the closed forms of the 1-D cases).

Run: .venv/bin/python benchmarks/bench_ball_laws.py  (about a minute on one core; best of 3 repeats)
"""

import time

import numpy as np

from impactlab.model.registry import get_model
from impactlab.testing import _complete, reference_inputs, reference_inputs_3d

FORMS = [
    ("maw (elastic law)", "maw", {}),
    ("maw + rolling", "maw", {"rolling_hysteresis": "restitution"}),
    ("maw hysteretic", "maw", {"inelastic": "hysteretic"}),
    ("maw hysteretic + rolling", "maw", {"inelastic": "hysteretic", "rolling_hysteresis": "restitution"}),
    ("hertz_mindlin", "hertz_mindlin", {}),
    ("hertz_mindlin + rolling", "hertz_mindlin", {"rolling_hysteresis": "restitution"}),
    ("rigid_coulomb", "rigid_coulomb", {}),
    ("rigid_coulomb + rolling", "rigid_coulomb", {"rolling_hysteresis": "restitution"}),
    ("restitution (energy cap)", "restitution", {"tangential_restitution": 0.3}),
]
OUTPUTS = ["spin_rate", "launch_angle", "ball_speed"]


def per_impact(model, inputs, repeats=3):
    model.compute(inputs, OUTPUTS)  # compile and warm caches
    best = np.inf
    for _ in range(repeats):
        start = time.perf_counter()
        model.compute(inputs, OUTPUTS)
        best = min(best, time.perf_counter() - start)
    return best / inputs["speed"].size


def main():
    batches = {"3-D (48 driver cases)": _complete(reference_inputs_3d()), "1-D (126 plate cases)": reference_inputs()}
    for label, inputs in batches.items():
        times = {form: per_impact(get_model(name)(**options), inputs) for form, name, options in FORMS}
        elastic = times["maw (elastic law)"]
        print(f"\n{label}: time per impact and ratio to the elastic law (maw)")
        for form, seconds in times.items():
            print(f"  {form:28s} {seconds * 1e3:9.3f} ms   {seconds / elastic:6.2f} x elastic")
        ratio = times["rigid_coulomb + rolling"] / times["rigid_coulomb"]
        print(f"  rigid_coulomb + rolling / rigid_coulomb: {ratio:.1f} x")


if __name__ == "__main__":
    main()
