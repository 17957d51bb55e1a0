"""Cost of the ball laws per impact against the elastic law (issue 21: each within 3x of it).

The batch: the conformance suite's golf deliveries on free heads (driver preset and a symmetric head, struck across
the face; 48 cases, 3-D) and its plate cases (126, 1-D), each model at its default tolerance. "Elastic law" is the
model as the paper has it (maw elastic, adjusted speed); each form's time per impact is divided by it, and, for the
rigid forms, by rigid_coulomb without the law too (the integrator over the normal impulse costs what Stronge's
3-D integration does, far more than the closed forms of the 1-D cases).

The friction law's forms run on the same cases with a wet, grooved face and a melting cover (every part of the law
computed), and are divided by the same model with the constant mu.

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
    # the friction law (impactlab.physics.friction_laws): every part on (a wet, grooved face; a melting cover)
    ("maw + friction law", "maw", {"friction_law": "adhesion"}),
    ("hertz_mindlin + friction law", "hertz_mindlin", {"friction_law": "adhesion"}),
    ("rigid_coulomb + friction law", "rigid_coulomb", {"friction_law": "adhesion"}),
    ("restitution + friction law", "restitution", {"tangential_restitution": 0.3, "friction_law": "adhesion"}),
]
#: each friction-law form against the same model with the constant mu (issue 21: within 3x per impact)
LAW_BASES = {"maw + friction law": "maw (elastic law)", "hertz_mindlin + friction law": "hertz_mindlin",
             "rigid_coulomb + friction law": "rigid_coulomb",
             "restitution + friction law": "restitution (energy cap)"}
#: the surface and cover every case gets, so that the law's squeeze film and flash temperature are computed
WET_GROOVED = {"face_roughness_slope": 0.2, "face_roughness": 5.7e-6, "face_groove_land": 1.35e-3,
               "face_water_film": 10e-6, "face_effusivity": 8030.0, "ball_cover_melt_rise": 66.0,
               "ball_cover_effusivity": 718.0}
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
        n = inputs["speed"].size
        inputs = dict(inputs, **{key: np.full(n, value) for key, value in WET_GROOVED.items()})
        times = {form: per_impact(get_model(name)(**options), inputs) for form, name, options in FORMS}
        elastic = times["maw (elastic law)"]
        print(f"\n{label}: time per impact and ratio to the elastic law (maw)")
        for form, seconds in times.items():
            print(f"  {form:28s} {seconds * 1e3:9.3f} ms   {seconds / elastic:6.2f} x elastic")
        ratio = times["rigid_coulomb + rolling"] / times["rigid_coulomb"]
        print(f"  rigid_coulomb + rolling / rigid_coulomb: {ratio:.1f} x")
        for form, base in LAW_BASES.items():
            print(f"  {form} / {base} (constant mu): {times[form] / times[base]:.2f} x")


if __name__ == "__main__":
    main()
