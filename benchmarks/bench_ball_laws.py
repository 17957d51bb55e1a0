"""Cost of the ball laws per impact against the elastic law (issue 21: each within 3x of it).

The batch: the conformance suite's golf deliveries on free heads (driver preset and a symmetric head, struck across
the face; 48 cases, 3-D) and its plate cases (126, 1-D), each model at its default tolerance. "Elastic law" is the
model as the paper has it (maw elastic, adjusted speed); each form's time per impact is divided by it, and, for the
rigid forms, by rigid_coulomb without the law too (the integrator over the normal impulse costs what Stronge's
3-D integration does, far more than the closed forms of the 1-D cases).

The friction law's forms run on the same cases with a wet, grooved face and a melting cover (every part of the law
computed); their "x without" is the same model with the constant mu.
Each form's time is also divided by its own model without the law ("x without"): the cost of the law itself.
The 1-D batch's elastic law takes 4-5 ms for all its cases, so on a shared machine wall-clock ratios moved by
+-50 % from run to run: the time is the process's CPU time (the models run on one thread), best of 7 repeats.

Run: .venv/bin/python benchmarks/bench_ball_laws.py  (about a minute on one core)
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
FRICTION_BASES = {"maw + friction law": "maw (elastic law)", "hertz_mindlin + friction law": "hertz_mindlin",
             "rigid_coulomb + friction law": "rigid_coulomb",
             "restitution + friction law": "restitution (energy cap)"}
#: the surface and cover every case gets, so that the law's squeeze film and flash temperature are computed
WET_GROOVED = {"face_roughness_slope": 0.2, "face_roughness": 5.7e-6, "face_groove_land": 1.35e-3,
               "face_water_film": 10e-6, "face_effusivity": 8030.0, "ball_cover_melt_rise": 66.0,
               "ball_cover_effusivity": 718.0}
OUTPUTS = ["spin_rate", "launch_angle", "ball_speed"]


#: the form without its law, for the "x without" column
WITHOUT = {"maw + rolling": "maw (elastic law)", "maw hysteretic + rolling": "maw hysteretic",
           "hertz_mindlin + rolling": "hertz_mindlin", "rigid_coulomb + rolling": "rigid_coulomb", **FRICTION_BASES}


def per_impact(model, inputs, repeats=7):
    model.compute(inputs, OUTPUTS)  # compile and warm caches
    best = np.inf
    for _ in range(repeats):
        start = time.process_time()
        model.compute(inputs, OUTPUTS)
        best = min(best, time.process_time() - start)
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
            without = f"   {seconds / times[WITHOUT[form]]:6.2f} x without" if form in WITHOUT else ""
            print(f"  {form:28s} {seconds * 1e3:9.3f} ms   {seconds / elastic:6.2f} x elastic{without}")


if __name__ == "__main__":
    main()
