"""Benchmarks of the free 3-D club head against the real-clubs issue's targets, ratios measured in one run.

Run:  python benchmarks/bench_clubs.py            (a few minutes; --quick for a smoke run)

Prints, measured in this run on this machine:
1. per-impact cost of 3-D maw (off-centre driver strikes, default tolerance) against today's 1-D solver
   (centred strikes on a point-mass head, same deliveries), kernel and public API, and their ratio
   (target: 3-D within 3x of 1-D);
2. the 3-D error at the default tolerance against a resolution study (tolerance 1e-7 reference), in beta,
   spin (relative) and launch angles;
3. the same for hertz_mindlin, dem_linear and rigid_coulomb's Stronge integration;
4. 10^6 3-D scenes on every core through the CLI (target: under 5 minutes).
"""

import argparse
import time

import numpy as np

import impactlab
from impactlab.model.case_inputs import CaseInputs
from impactlab.scene.catalogue import CLUB_PRESETS
from impactlab.model.registry import get_model

from bench_maw import run_on_every_core  # the same timing of a large study through `impactlab run`

OUTPUTS = ["tangential_restitution", "spin_rate", "vertical_launch_angle", "horizontal_launch_angle", "spin_axis"]


def driver_batch(n, seed=0, centred=False):
    """Driver deliveries (club speed 35-52 m/s, loft 9-16 deg, mu 0.3-0.5, e 0.75-0.85) at strikes over the face."""
    rng = np.random.default_rng(seed)
    head = CLUB_PRESETS["driver"]
    scene_inputs = {
        "ball_radius": 0.021335, "ball_mass": 0.04593, "ball_inertia_factor": 0.4, "ball_youngs_modulus": 136e6,
        "ball_poisson_ratio": 0.45, "face_youngs_modulus": head.material.youngs_modulus,
        "face_poisson_ratio": head.material.poisson_ratio, "club_mass": head.mass, "spin": 0.0, "handedness": 1.0,
    }
    if not centred:
        scene_inputs.update({f"club_inertia_{k}": v for k, v in head.inertia_components().items()})
        scene_inputs.update(club_cg_toe=head.center_of_mass[0], club_cg_high=head.center_of_mass[1],
                            club_cg_depth=head.center_of_mass[2], club_loft=head.loft,
                            face_bulge_radius=head.bulge_radius, face_roll_radius=head.roll_radius)
    inputs = {key: np.full(n, float(value)) for key, value in scene_inputs.items()}
    inputs["speed"] = rng.uniform(35.0, 52.0, n)
    inputs["dynamic_loft"] = np.radians(rng.uniform(9.0, 16.0, n))
    inputs["attack_angle"] = np.radians(rng.uniform(-3.0, 4.0, n))
    inputs["path"] = np.radians(rng.uniform(-3.0, 3.0, n))
    inputs["face_angle"] = np.radians(rng.uniform(-3.0, 3.0, n))
    inputs["friction"] = rng.uniform(0.3, 0.5, n)
    inputs["restitution"] = rng.uniform(0.75, 0.85, n)
    if not centred:
        inputs["strike_toe"] = rng.uniform(-0.02, 0.02, n)
        inputs["strike_high"] = rng.uniform(-0.01, 0.01, n)
    return impactlab.scene.core.complete_inputs(inputs)


def timed(function, repeats=3):
    function()
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def errors(result, reference):
    spin = np.abs(reference["spin_rate"].values)
    return {
        "beta": float(np.max(np.abs(result["tangential_restitution"].values
                                    - reference["tangential_restitution"].values))),
        "spin (rel.)": float(np.max(np.abs(result["spin_rate"].values - reference["spin_rate"].values)
                                    / np.maximum(spin, 1.0))),
        "launch angles [deg]": float(max(np.max(np.abs(result[name].values - reference[name].values))
                                         for name in ("vertical_launch_angle", "horizontal_launch_angle"))),
        "spin axis [deg]": float(np.max(np.abs(result["spin_axis"].values - reference["spin_axis"].values))),
    }


def frame_following_estimate(strikes=(-0.02, -0.01, 0.01, 0.02)):
    """The head turns during contact; impactlab keeps the contact frame of first contact. Estimate what following
    the face would change: solve again with the face turned by half the contact's rotation, and print the change
    of launch and spin. Half is an upper estimate: the head's angular speed grows with the impulse, so the
    force-weighted mean orientation lies nearer the start."""
    from impactlab.physics import compliant3d, hertz
    from impactlab.physics.contact import contact_state

    maw = get_model("maw")()
    names = ["ball_speed", "vertical_launch_angle", "horizontal_launch_angle", "spin_rate", "spin_axis"]
    base = driver_batch(len(strikes), centred=False)
    for key, value in dict(speed=51.4, dynamic_loft=np.radians(12.8), attack_angle=np.radians(-0.9), path=0.0,
                           face_angle=0.0, friction=0.4, restitution=0.8, strike_high=0.0).items():
        base[key] = np.full(len(strikes), value)
    base["strike_toe"] = np.asarray(strikes, dtype=float)
    base = impactlab.scene.core.complete_inputs(base)
    state = contact_state(base)
    moduli = [base[k] for k in ("ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus",
                                "face_poisson_ratio")]
    modulus = hertz.effective_modulus(*moduli)
    kappa = hertz.tangential_modulus(*moduli) / modulus
    springs, steps, _ = compliant3d.resolution(1e-4)
    solved = compliant3d.solve(state["mobility"], 0.5 * (1 + base["restitution"]) * state["normal_speed"],
                               state["slip_speed"], friction=base["friction"], kappa=kappa, modulus=modulus,
                               radius=state["contact_radius"], normal=hertz.ELASTIC, springs=springs, steps=steps)
    moment = np.einsum("nij,nj->ni", state["frame"], solved.impulse_time)
    # the head takes -J: its rotation over the contact is -I^-1 (r x integral J dt)
    turn = -np.einsum("nij,nj->ni", state["head_inverse_inertia"], np.cross(state["lever"], moment))
    turned = dict(base)
    # ground frame X target, Y left, Z up: a turn about +Z closes the face, about +Y delofts it
    turned["face_angle"] = base["face_angle"] - 0.5 * turn[:, 2]
    turned["dynamic_loft"] = base["dynamic_loft"] - 0.5 * turn[:, 1]
    turned = impactlab.scene.core.complete_inputs(turned)
    fixed, following = maw.compute(base, names), maw.compute(turned, names)
    for index, toe in enumerate(strikes):
        changes = ", ".join(f"{name} {float(following[name][index] - fixed[name][index]):+.3g}" for name in names)
        print(f"   strike toe {1e3 * toe:+.0f} mm: head turn {np.degrees(np.linalg.norm(turn[index])):.2f} deg; "
              f"following the face at mid-contact changes {changes} (units of the vocabulary)")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true")
    args = parser.parse_args()
    n = 200 if args.quick else 2000

    print(f"1. Cost per impact, {n} driver deliveries (maw, default tolerance), public API (compute) end to end")
    off_centre, centred = driver_batch(n), driver_batch(n, centred=True)
    maw = get_model("maw")()
    seconds_3d = timed(lambda: maw.compute(off_centre, OUTPUTS))
    seconds_1d = timed(lambda: maw.compute(centred, OUTPUTS))
    ratio = seconds_3d / seconds_1d
    print(f"   3-D (off-centre, free head): {1e6 * seconds_3d / n:.0f} us; 1-D (centred, point-mass head): "
          f"{1e6 * seconds_1d / n:.0f} us; ratio {ratio:.2f} (target <= 3): {'MET' if ratio <= 3 else 'NOT MET'}")
    print("   Kernels alone (the same cases through the hook, no derivation):")
    impulses = frozenset({"normal_impulse", "tangential_impulse"})
    hook_3d = timed(lambda: maw._compute(CaseInputs(off_centre), impulses))  # a fresh batch: its contact state
    hook_1d = timed(lambda: maw._compute(CaseInputs(centred), impulses))  # is the hook's work, timed with it
    print(f"   3-D {1e6 * hook_3d / n:.0f} us, 1-D {1e6 * hook_1d / n:.0f} us, ratio {hook_3d / hook_1d:.2f}")

    print("\n2./3. Error at the default against a resolution study (the same model at tolerance 1e-7 / 50x steps)")
    subset = {key: value[: max(50, n // 10)] for key, value in off_centre.items()}
    for name, reference_options in (("maw", {"tolerance": 1e-7}), ("hertz_mindlin", {"tolerance": 1e-7}),
                                    ("dem_linear", {"tolerance": 1e-7}), ("rigid_coulomb", {"steps": 100_000})):
        model = get_model(name)()
        reference = get_model(name)(**reference_options).compute(subset, OUTPUTS)
        seconds = timed(lambda model=model: model.compute(subset, OUTPUTS), repeats=1)
        found = errors(model.compute(subset, OUTPUTS), reference)
        print(f"   {name:14s} default {model.options_dict()}: {1e6 * seconds / len(subset['speed']):.0f} us/impact; "
              + ", ".join(f"{key} {value:.2g}" for key, value in found.items()))

    print("\n5. Contact frame fixed at first contact vs following the face: driver heel and toe strikes (maw)")
    frame_following_estimate()

    print("\n4. 10^6 3-D scenes on every core (maw, default tolerance) through `impactlab run`")
    size = 10_000 if args.quick else 1_000_000
    toes = 100
    text = f"""name: million3d
ball: {{preset: urethane_tour}}
club: {{preset: driver}}
contact: {{friction: 0.4, restitution: 0.8}}
delivery: {{club_speed: 105 mph, attack_angle: 1 deg, dynamic_loft: 13 deg}}
sweep:
  strike.toe: {{start: -20 mm, stop: 20 mm, num: {toes}}}
  strike.high: {{start: -10 mm, stop: 10 mm, num: {size // toes // 10}}}
  delivery.face_angle: {{start: -3 deg, stop: 3 deg, num: 10}}
models: [maw]
outputs: [ball_speed, vertical_launch_angle, horizontal_launch_angle, spin_rate, spin_axis]
"""
    seconds, peak = run_on_every_core(text)
    print(f"   {size} scenes in {seconds:.1f} s including start-up and writing (target <= 300 s): "
          f"{'MET' if seconds <= 300 else 'NOT MET'}; largest process {peak:.0f} MB")


if __name__ == "__main__":
    main()
