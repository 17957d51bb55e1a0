"""Cost of the laws with a scale (impactlab.physics.rate_laws, issue 33) per impact against the same model's
elastic law, measured in one run (goal: within 3x on the 1-D and 3-D batches of impactlab.testing's conformance suite).

The batches: :func:`impactlab.testing.reference_inputs` (plate cases, 1-D) and
:func:`impactlab.testing.reference_inputs_3d` (golf deliveries on free heads, 3-D). "Elastic law" is the same model
with every law off. Time: the process's CPU time (the models run on one thread), best of 5 repeats, after a warm-up
run that compiles the kernels and builds the SLS table (cached per relaxed fraction, as in use).

A second table measures a restitution per case, as a ball whose e falls with the normal speed gives (every case's e
distinct, so the models tabulate the damped law per case): its cost against one e for the whole batch, on the 3-D
batch, for the spring model with the face at the COR limit (``hertz_mindlin_face``) and for ``maw``. Before
2026-11-29 the spring models solved a damped law per distinct e for a 3-D limit correction they do not make
(about 0.07 s each; this table read 160x for hertz_mindlin_face before, 0.99x after, measured 2026-11-29).

Run: .venv/bin/python benchmarks/bench_rate_laws.py  (about a minute on one core)
"""

import time

import numpy as np

from impactlab.model.registry import get_model
from impactlab.testing import _complete, reference_inputs, reference_inputs_3d

LAWS = [
    ("SLS normal (a)", {"relaxation_time": 43e-6, "relaxed_fraction": 0.376}),
    ("pressure friction (b)", {"friction_pressure_exponent": 0.3}),
    ("slip-speed friction (b)", {"friction_slip_exponent": 0.9}),
    ("tangential dashpot time (b)", {"tangential_relaxation_time": 20e-6}),
    ("compression lever (c)", {"compression_lever": 0.05}),
    ("all of them", {"relaxation_time": 43e-6, "relaxed_fraction": 0.376, "friction_pressure_exponent": 0.3,
                     "friction_slip_exponent": 0.9, "compression_lever": 0.05}),
]
MODELS = ("rigid_coulomb", "hertz_mindlin", "maw")
OUTPUTS = ["spin_rate", "ball_speed"]


def cost(model, inputs, repeats=5):
    model.compute_arrays(inputs, OUTPUTS)  # warm-up: kernels, tables
    best = float("inf")
    for _ in range(repeats):
        start = time.process_time()
        model.compute_arrays(inputs, OUTPUTS)
        best = min(best, time.process_time() - start)
    return best / inputs["speed"].size


def main():
    batches = {"1-D": _complete(reference_inputs()), "3-D": _complete(reference_inputs_3d())}
    print("| model | law | batch | cases | elastic law [us/impact] | with the law [us/impact] | ratio (goal <= 3) |")
    print("|---|---|---|---|---|---|---|")
    for name in MODELS:
        for batch, inputs in batches.items():
            base = cost(get_model(name)(), inputs)
            for law, options in LAWS:
                if name == "rigid_coulomb" and "tangential_relaxation_time" in options:
                    continue
                with_law = cost(get_model(name)(**options), inputs)
                print(f"| {name} | {law} | {batch} | {inputs['speed'].size} | {base * 1e6:.1f} | "
                      f"{with_law * 1e6:.1f} | {with_law / base:.2f} |", flush=True)
    per_case(batches["3-D"])


def per_case(inputs):
    """The cost of a distinct restitution per case against one restitution for the batch (3-D batch)."""
    # four copies of the batch: 192 distinct e, more than the 64 damped laws a model keeps (as in a session's file)
    inputs = {k: (np.tile(v, (4,) + (1,) * (np.ndim(v) - 1)) if np.ndim(v) else v) for k, v in inputs.items()}
    count = inputs["speed"].size
    one = dict(inputs, restitution=np.full(count, 0.80))
    distinct = dict(inputs, restitution=np.linspace(0.76, 0.84, count))
    print("\n| model | batch | cases | one e [us/impact] | an e per case [us/impact] | ratio |")
    print("|---|---|---|---|---|---|")
    for name in ("hertz_mindlin_face", "maw"):
        base, each = cost(get_model(name)(), one), cost(get_model(name)(), distinct)
        print(f"| {name} | 3-D | {count} | {base * 1e6:.1f} | {each * 1e6:.1f} | {each / base:.2f} |", flush=True)


if __name__ == "__main__":
    main()
