"""maw's MDR resolution rule against a converged reference: does it keep its bound, and at what cost.

Run:  python benchmarks/resolution_rule.py           (about 10 minutes on one core; --quick: 3 values of chi)

The rule (impactlab.physics.mdr.resolution) promises |d psi2| <= tol * min(4 chi, psi1). This measures the
ratio |d psi2| / (tol * min(4 chi, psi1)) of the springs it chooses (STEPS_PER_SPRING steps each) over

- chi 0.3-15: real balls (K^2 0.08-0.4, nu 0.3-0.5 on a rigid face give chi 1.17-5.56) and the light-core
  ball of the former xfail (K^2 0.08, nu 0.45: chi 4.79), with its psi1 at 0.2 and 0.3 deg of loft, mu 0.6;
- psi1 from 1e-3 (SMALLEST_SCALE) to 6 chi, log-spaced, 12 points below 0.05;
- 33 tolerances log-spaced over 1e-5 .. 1e-3 (a tolerance is a continuous input: the ladder's rounding
  leaves a different margin at each);

for the rule and for the previous one (until 2026-11), and the cost of each, springs x steps summed over
the grid and over a golf batch (benchmarks/bench_maw.py's: chi 1.24, loft 2-60 deg, mu 0.1-0.5), and maw's
time per impact under each on that batch and on a grazing one (loft 0.1-2 deg).

Reference: the same solver at 24 steps per spring, Richardson-extrapolated from 4000 and 8000 springs; its
uncertainty (the change from the 2000/4000 extrapolation) is printed, and a few points are checked against
the independent MDR of tests/test_mutation_oracles.py (no event alignment, RK4 Hertz shape).
"""

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from impactlab.physics import mdr

HERE = Path(__file__).resolve().parent
KAPPA = 2 * (1 - 0.45) / (2 - 0.45)  # nu = 0.45 on a rigid face
LIGHT_CORE = KAPPA / 2 * (1 + 1 / 0.08)  # K^2 = 0.08: 4.79
GRAZING = KAPPA * np.tan(np.radians([0.2, 0.3])) / 0.6  # the former xfail's psi1 (mu 0.6)
CHIS = (0.3, 0.5, 0.7, 1.0, 1.17, 1.24, 1.44, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, LIGHT_CORE, 5.2, 5.56, 7.0, 10.0, 15.0)
QUICK_CHIS = (1.24, LIGHT_CORE, 15.0)
TOLERANCES = np.geomspace(1e-5, 1e-3, 33)
REPORTED = (1e-3, 1e-4, 1e-5)


def previous_rule(tolerance, chi, psi1):
    """The rule until 2026-11: 1.2 max(1, chi/4)^1.15 / sqrt(s) / springs^2, the same ladder."""
    scale = np.maximum(np.minimum(psi1, 4.0 * chi), mdr.SMALLEST_SCALE)
    wanted = np.maximum(12.0, np.sqrt(1.2 * max(1.0, chi / 4.0) ** 1.15 / (tolerance * np.sqrt(scale))))
    springs = np.ceil(12.0 * 2.0 ** (np.ceil(4.0 * np.log2(wanted / 12.0) - 1e-9) / 4.0)).astype(np.int64)
    return np.minimum(springs, mdr.MAX_SPRINGS), springs > mdr.MAX_SPRINGS


RULES = {"previous": previous_rule, "current": mdr.resolution}


def psi1_grid(chi):
    grid = np.concatenate([np.geomspace(1e-3, 0.05, 12), np.geomspace(0.05, 6 * chi, 11)[1:]])
    if chi == LIGHT_CORE:
        grid = np.concatenate([grid, GRAZING])
    return np.unique(grid)


def solve(chi, psi1, springs, steps_per_spring):
    chis = np.full(psi1.size, chi)
    return mdr.solve_scaled(chis, psi1, springs=int(springs), steps=int(steps_per_spring * springs)).slip_change


def reference(chi, psi1):
    """Richardson from 4000/8000 springs at 24 steps per spring, and its change from the 2000/4000 one."""
    coarse, middle, fine = (solve(chi, psi1, n, 24) for n in (2000, 4000, 8000))
    best = (4 * fine - middle) / 3
    return best, np.abs(best - (4 * middle - coarse) / 3)


def measure(chis):
    """{rule: [(ratio, chi, psi1, tol, springs)]} over the grid (capped cases left out), costs, reference error."""
    rows = {name: [] for name in RULES}
    cost = {name: {tol: 0.0 for tol in REPORTED} | {"all": 0.0} for name in RULES}
    capped = {name: 0 for name in RULES}
    reference_error = 0.0
    for chi in chis:
        start = time.perf_counter()
        psi1 = psi1_grid(chi)
        scale = np.minimum(psi1, 4 * chi)
        exact, uncertainty = reference(chi, psi1)
        reference_error = max(reference_error, float(np.max(uncertainty / scale)))
        solved = {}  # springs -> psi2 - psi1 of every psi1 of this chi
        for name, rule in RULES.items():
            for tol in sorted(set(TOLERANCES) | set(REPORTED)):
                springs, over = rule(tol, chi, psi1)
                capped[name] += int(np.sum(over))
                for count in np.unique(springs):
                    if count not in solved:
                        solved[count] = solve(chi, psi1, count, mdr.STEPS_PER_SPRING)
                got = np.array([solved[count][i] for i, count in enumerate(springs)])
                ratio = np.where(over, 0.0, np.abs(got - exact) / (tol * scale))
                rows[name] += [(float(ratio[i]), chi, float(psi1[i]), float(tol), int(springs[i]))
                               for i in range(psi1.size)]
                work = float(np.sum(springs.astype(float) * mdr.STEPS_PER_SPRING * springs))
                cost[name]["all"] += work
                for reported in REPORTED:
                    if np.isclose(tol, reported, rtol=1e-9):
                        cost[name][reported] += work
        print(f"   chi {chi:.3g}: {time.perf_counter() - start:.0f} s", file=sys.stderr, flush=True)
    return rows, cost, capped, reference_error


def golf_cost(rule, tolerance=1e-4, n=2000, seed=0):
    """Mean springs x steps per impact of bench_maw.py's golf batch (chi 1.24)."""
    rng = np.random.default_rng(seed)
    friction = rng.uniform(0.1, 0.5, n)
    angle = np.radians(rng.uniform(2.0, 60.0, n))
    psi1 = KAPPA * np.tan(angle) / friction
    springs, _ = rule(tolerance, KAPPA / 2 * (1 + 1 / 0.4), psi1)
    return float(np.mean(springs.astype(float) ** 2 * mdr.STEPS_PER_SPRING))


def cross_check():
    """The reference against the independent MDR of the tests at springs=800 (Richardson; its own error ~1e-5)."""
    sys.path.insert(0, str(HERE.parent / "tests"))
    from test_mutation_oracles import reference_mdr_psi2

    chi = np.array([LIGHT_CORE, LIGHT_CORE, LIGHT_CORE, 1.24, 15.0])
    psi1 = np.array([1e-3, GRAZING[0], GRAZING[1], 1e-3, 1e-3])
    independent = reference_mdr_psi2(chi, psi1, springs=800)
    ours = np.array([reference(c, np.array([p]))[0][0] + p for c, p in zip(chi, psi1)])
    return float(np.max(np.abs(independent - ours) / np.minimum(psi1, 4 * chi)))


def timing(tolerance=1e-4, n=2000, repeats=3):
    """Time per impact of maw at a tolerance under either rule: bench_maw.py's golf batch and a grazing one."""
    sys.path.insert(0, str(HERE))
    from bench_maw import OUTPUTS, golf_batch

    from impactlab.model.registry import get_model

    grazing = golf_batch(n, seed=1)
    grazing["angle"] = np.radians(np.random.default_rng(2).uniform(0.1, 2.0, n))
    grazing["friction"] = np.full(n, 0.6)
    current = mdr.resolution

    def seconds(inputs, rule):
        mdr.resolution = rule  # maw asks mdr.resolution for its springs
        try:
            model = get_model("maw")(tolerance=tolerance)
            start = time.perf_counter()
            model.compute(inputs, OUTPUTS)
            return time.perf_counter() - start
        finally:
            mdr.resolution = current

    for name, inputs in (("golf batch (loft 2-60 deg, mu 0.1-0.5)", golf_batch(n)),
                         ("grazing batch (loft 0.1-2 deg, mu 0.6)", grazing)):
        seconds(inputs, previous_rule), seconds(inputs, current)  # warm: compilation, grids
        times = {"previous": [], "current": []}
        for _ in range(repeats):  # in turn, so that a shared machine's load meets both alike
            times["previous"].append(seconds(inputs, previous_rule))
            times["current"].append(seconds(inputs, current))
        print(f"   {name}, tol {tolerance:g}: " + ", ".join(
            f"{key} {1e6 * np.median(value) / n:.1f} us" for key, value in times.items()) + " per impact")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--quick", action="store_true", help="chi 1.24, 4.79 and 15 only")
    args = parser.parse_args()
    chis = QUICK_CHIS if args.quick else CHIS
    print(f"grid: {len(chis)} values of chi in {min(chis):g}-{max(chis):g}, psi1 1e-3 .. 6 chi (23-25 points), "
          f"{TOLERANCES.size} tolerances 1e-5 .. 1e-3; {mdr.STEPS_PER_SPRING} steps per spring")
    rows, cost, capped, reference_error = measure(chis)
    print(f"reference: Richardson 4000/8000 springs, 24 steps per spring; it moves by at most {reference_error:.1e} "
          f"of min(4 chi, psi1) from the 2000/4000 one")
    print(f"           against the independent MDR of the tests (5 points, 800 springs): {cross_check():.1e} "
          "of min(4 chi, psi1)\n")
    print("worst |d psi2| / (tol min(4 chi, psi1))  (over the grid; <= 1 keeps the promise)")
    for name in RULES:
        worst = max(rows[name])
        print(f"   {name:<9} all tolerances: {worst[0]:.2f} at chi {worst[1]:.3g}, psi1 {worst[2]:.3g}, "
              f"tol {worst[3]:.3g} ({worst[4]} springs); capped cases {capped[name]}")
        for tol in REPORTED:
            worst = max(row for row in rows[name] if np.isclose(row[3], tol, rtol=1e-9))
            print(f"             tol {tol:g}: {worst[0]:.2f} at chi {worst[1]:.3g}, psi1 {worst[2]:.3g}")
        above = [row for row in rows[name] if row[0] > 1.0]
        if above:
            print(f"             {len(above)} of {len(rows[name])} (case, tolerance) pairs above 1, psi1 up to "
                  f"{max(row[2] for row in above):.3g}, chi {min(row[1] for row in above):.3g}-"
                  f"{max(row[1] for row in above):.3g}")
    print("\ncost, springs x steps, current over previous")
    print("   grid, all tolerances: " + f"{cost['current']['all'] / cost['previous']['all']:.2f}x; " + ", ".join(
        f"tol {tol:g}: {cost['current'][tol] / cost['previous'][tol]:.2f}x" for tol in REPORTED))
    print("   golf batch (bench_maw.py, chi 1.24, loft 2-60 deg, mu 0.1-0.5): " + ", ".join(
        f"tol {tol:g}: {golf_cost(mdr.resolution, tol) / golf_cost(previous_rule, tol):.2f}x" for tol in REPORTED))
    for chi in (1.24, LIGHT_CORE):
        line = []
        for psi1 in (1e-3, 1e-2, 0.1, 1.0):
            new, old = (rule(1e-4, chi, np.array([psi1]))[0][0] for rule in (mdr.resolution, previous_rule))
            line.append(f"psi1 {psi1:g}: {old} -> {new} springs ({(new / old) ** 2:.2f}x)")
        print(f"   chi {chi:.3g}, tol 1e-4: " + "; ".join(line))
    print("\ntime per impact, maw, one core, 2000 cases (median of 3 warm runs)")
    timing()


if __name__ == "__main__":
    main()
