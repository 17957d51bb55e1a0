"""Results of the ball laws' forms before and after a change of the solvers: the largest differences per form.

Runs every form of bench_ball_laws.py on its two batches (the conformance suite's 48 3-D driver cases and 126 1-D
plate cases, the same wet grooved face, here also spring-like: club_restitution_gain 0.05), and the core and face
laws, at each model's default tolerance, and saves spin, beta (the contact point's tangential restitution), ball
speed and launch angle; given a saved file from another version of the code, prints the largest absolute difference
of each per form and batch.

Measured 2026-11-24 (perf6: MDR's limit check and the annular-strip kernel made faster), against the tree before:
every form identical except maw hysteretic (1-D; and with the face, 3-D), which moved by round-off: at most
3e-9 rpm of spin, 4e-13 in beta, 1e-12 m/s of ball speed, 5e-12 deg of launch.
Measured 2026-11-24 (perf7: the 3-D kernel's cases on one line run kernels/line.py), against the tree before
(840006f): every 3-D form identical; the 1-D forms that reach the 3-D kernel (the face, maw's core and rolling, the
core with rolling, maw hysteretic with core, face or rolling) moved by round-off: at most 1.2e-10 rpm of spin,
2.4e-13 in beta, 1.6e-13 m/s of ball speed, 1.4e-13 deg of launch; every other form identical.

Run: .venv/bin/python benchmarks/compare_ball_laws.py save before.npz   (on the old code)
     .venv/bin/python benchmarks/compare_ball_laws.py compare before.npz (on the new code)
"""

import sys

import numpy as np

from bench_ball_laws import FORMS, WET_GROOVED
from impactlab.model.registry import get_model
from impactlab.testing import _complete, reference_inputs, reference_inputs_3d

#: the core and face laws (measure_core_torsion.py, measure_face_flex.py) under maw's hysteretic law, whose 3-D cases
#: carry the annular strips' correction; the face acts on spring-like faces (club_restitution_gain 0.05 here)
CORE = {"core_radius": 0.01905, "core_shear_modulus": 10e6, "core_specific_gravity": 1.15}
FACE = {"face_frequency": 2 * 3.141592653589793 * 4e3, "face_modal_mass": 0.010}
EXTRA = [("maw hysteretic + core", "maw", {"inelastic": "hysteretic", **CORE}),
         ("maw hysteretic + face", "maw", {"inelastic": "hysteretic", **FACE}),
         ("hertz_mindlin + face", "hertz_mindlin", FACE), ("hertz_mindlin + core", "hertz_mindlin", CORE),
         ("maw + core", "maw", CORE), ("hertz_mindlin + face + rolling", "hertz_mindlin",
                                       {"rolling_hysteresis": "restitution", **FACE}),
         ("hertz_mindlin + core + rolling", "hertz_mindlin", {"rolling_hysteresis": "restitution", **CORE}),
         ("dem_linear hysteretic + face", "dem_linear", {"inelastic": "hysteretic", **FACE})]
OUTPUTS = {"spin_rate": "spin [rpm]", "tangential_restitution": "beta", "ball_speed": "ball speed [m/s]",
           "launch_angle": "launch [deg]"}


def results() -> dict[str, np.ndarray]:
    batches = {"3-D": _complete(reference_inputs_3d()), "1-D": reference_inputs()}
    out = {}
    for batch, inputs in batches.items():
        n = inputs["speed"].size
        inputs = dict(inputs, **{key: np.full(n, value) for key, value in WET_GROOVED.items()},
                      club_restitution_gain=np.full(n, 0.05))
        for form, name, options in FORMS + EXTRA:
            data = get_model(name)(**options).compute(inputs, list(OUTPUTS))
            for output in OUTPUTS:
                out[f"{batch}|{form}|{output}"] = np.asarray(data[output], dtype=float)
    return out


def main():
    action, path = sys.argv[1], sys.argv[2]
    now = results()
    if action == "save":
        np.savez(path, **now)
        return
    before = np.load(path)
    print(f"{'batch':4s} {'form':32s} " + " ".join(f"{label:>17s}" for label in OUTPUTS.values()))
    for key in sorted({k.rsplit('|', 1)[0] for k in now}):
        diffs = []
        for output in OUTPUTS:
            old, new = before[f"{key}|{output}"], now[f"{key}|{output}"]
            both = np.isfinite(old) & np.isfinite(new)
            same_nan = np.array_equal(np.isnan(old), np.isnan(new))
            diffs.append(f"{np.max(np.abs(new - old)[both], initial=0.0):17.3g}" + ("" if same_nan else " (NaN moved)"))
        batch, form = key.split("|")
        print(f"{batch:4s} {form:32s} " + " ".join(diffs))


if __name__ == "__main__":
    main()
