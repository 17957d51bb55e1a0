"""Which maw method is right under the hysteretic (damped) normal law: MDR or the annular strips?

Measured (docs/models.md, "The hysteretic law and the two methods"):

1. beta from MDR (200 and 800 springs) and from the annular-strip method (80 and 160 rings, extrapolated to
   infinitely many with its measured second order, checked at 320 rings for two cases) for a urethane ball on
   a rigid face (chi = 1.24) over psi1 = 0.25-4 and e = 1, 0.8, 0.6, 0.4;
2. along each MDR solution, whether a spring slips inside a stuck one (a slip zone that is not an annulus at
   the edge) and by how much the 3-D traction the springs represent (inverse MDR transform) exceeds the
   3-D Coulomb limit mu p(r) anywhere.

Run: .venv/bin/python benchmarks/bench_hysteretic.py (about a minute on one core).
"""

import time

import numpy as np

from impactlab.physics import annuli, hertz, mdr

CHI = 1.24
PSI1 = np.array([0.25, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 4.0])


def beta(solution, psi1):
    return -(psi1 + solution.slip_change) / psi1


def coulomb_excess(chi, psi1, normal, springs=100):
    """Largest 3-D excess max(|tau|/(mu p)) - 1 of the MDR state over the impact, and whether a spring ever slipped
    inside a stuck one, per case."""
    excess = np.zeros(psi1.size)
    interior = np.zeros(psi1.size, dtype=bool)

    def observe(_, u, cap):
        m = int(np.count_nonzero(cap > 0.0))
        if m < 6:
            return
        traction = mdr.traction_3d(u[:, :m])
        pressure = mdr.traction_3d(cap[:m])
        # the last two cells sit on the edge, where both vanish: their ratio is noise
        ratio = np.abs(traction[:, : m - 2]) / pressure[None, : m - 2]
        excess[:] = np.maximum(excess, ratio.max(axis=1) - 1.0)
        interior[:] |= mdr.slip_inside_stick(u[:, :m], cap[:m])

    mdr.solve_scaled(np.full(psi1.size, chi), psi1, springs=springs, steps=6 * springs, normal=normal,
                     observe=observe)
    return excess, interior


def main():
    start = time.time()
    chi = np.full(PSI1.size, CHI)
    print(f"chi = {CHI}; beta of MDR (200 springs), annuli extrapolated from 80 and 160 rings, their gap;")
    print("interior: a spring slipped inside a stuck one; excess: largest 3-D |tau|/(mu p) - 1 of the MDR state\n")
    print(f"{'e':>4} {'psi1':>5} {'mdr200':>9} {'mdr800':>9} {'ann80':>9} {'ann160':>9} {'ann_inf':>9} "
          f"{'gap':>9} {'interior':>9} {'excess':>8}")
    worst = {True: 0.0, False: 0.0}
    for e in (1.0, 0.8, 0.6, 0.4):
        normal = hertz.ELASTIC if e == 1.0 else hertz.DampedNormal(hertz.damping_for_restitution(e))
        m200 = beta(mdr.solve_scaled(chi, PSI1, springs=200, steps=1200, normal=normal), PSI1)
        m800 = beta(mdr.solve_scaled(chi, PSI1, springs=800, steps=4800, normal=normal), PSI1)
        a80 = beta(annuli.solve_scaled(chi, PSI1, rings=80, steps=800, normal=normal), PSI1)
        a160 = beta(annuli.solve_scaled(chi, PSI1, rings=160, steps=1600, normal=normal), PSI1)
        extrapolated = a160 + (a160 - a80) / 3.0  # second order, measured below
        excess, interior = coulomb_excess(CHI, PSI1, normal)
        for i, psi1 in enumerate(PSI1):
            gap = m800[i] - extrapolated[i]
            worst[bool(interior[i])] = max(worst[bool(interior[i])], abs(gap))
            print(f"{e:4.1f} {psi1:5.2f} {m200[i]:9.5f} {m800[i]:9.5f} {a80[i]:9.5f} {a160[i]:9.5f} "
                  f"{extrapolated[i]:9.5f} {gap:9.1e} {'yes' if interior[i] else 'no':>9} {excess[i]:8.3f}")
    print(f"\nlargest |gap|: {worst[False]:.1e} where MDR's slip zone stays at the edge, "
          f"{worst[True]:.1e} where a spring slips inside a stuck one")
    # the annular method's order, from 80, 160, 320 rings at e = 0.6
    normal = hertz.DampedNormal(hertz.damping_for_restitution(0.6))
    two = np.array([1.0, 2.0])
    runs = [beta(annuli.solve_scaled(np.full(2, CHI), two, rings=n, steps=10 * n, normal=normal), two)
            for n in (80, 160, 320)]
    order = np.log2(np.abs(runs[1] - runs[0]) / np.abs(runs[2] - runs[1]))
    print(f"annuli at e = 0.6, psi1 = 1, 2: beta at 80/160/320 rings {np.round(runs, 5).tolist()}, "
          f"observed order {np.round(order, 2).tolist()}")
    print(f"({time.time() - start:.0f} s)")


if __name__ == "__main__":
    main()
