"""Issue 33, round 4: the flexing face at the COR limit together with the lever and with pressure-dependent friction.

    .venv/bin/python -u -m validation.impact.face_mechanisms            (training subsamples of 400 rows; ~10 minutes)
    .venv/bin/python -u -m validation.impact.face_mechanisms --quick    (200 rows)

Round 1 measured the compression lever alone (the normal force's line moved off the ball's centre in proportion to
the ball's compression, d = lambda delta: McNally, McPhee & Henrikson 2020 fitted about 0.5 mm on a driver, a model
fit) and round 2 the face at the Rules' COR limit alone. Each lowered the spin-speed exponent at a fixed delivery
(0.90-0.92 and 0.89), neither to the 0.5-0.8 the file's sessions show. The two act through different scales (the
face through its mode's frequency against the contact time, the lever through the ball's compression, which grows
as V^(4/5)), so they are measured here together, with round 3's protocol and bounds:

- e_ball (the ball's own restitution on the flexing face) in [0.70, 0.787]: 0.787 (solved) is where the simulated
  Rules' COR test on this face reads 0.830 (face_bounds.e_ball_at_limit), so every fit is within the Rules; 0.70 is
  Penner's line at 55 m/s, below any driver impact of the file;
- friction 0.20-0.60 (round 1);
- lambda in [0, 0.186]: the mean offset at most 1.0 mm at the PGA driver delivery, twice McNally et al.'s fitted
  0.5 mm (rate_laws.lever_bound).

Fitted (log spin and 3 x log ball speed, robust, as every round) on one club-speed band and tested on the other,
beside the face without the lever refitted on the same rows, the regression and gradient boosting on the same rows;
then fitted on the whole file's subsample: the exponent at a fixed delivery, the tour tables and the wedge test, not
refitted. The lever moves the launch as well as the spin, and launch is not in the fit's objective, so its held-out
launch error is the check the lever must pass.

The same protocol carries friction that falls with the contact pressure, mu = mu_0 (p_mean / 10 MPa)^(-n)
(impactlab.physics.rate_laws.pressure_friction): n = 1 is the adhesive regime of elastomer friction (a constant
shear strength: friction force = tau A), n = 1/3 Hertzian multi-asperity contact (Popov et al. 2018, measurements of
elastomers falling with load as a power law), and n fitted in [0, 1]. The driver file barely identifies n (a driver
contact grips whatever the friction above about 0.04), while the wedge ball-type test depends on it (round 1,
rate_laws section 6: a sensitivity). Here n is set by the two physical regimes, or fitted on the driver rows, never
chosen from the wedge's result, and the wedge is predicted.
"""

from __future__ import annotations

import argparse
import time
import warnings

import numpy as np

#: e_ball's lower bound on the face at the COR limit: Penner's line at 55 m/s (the upper: face_bounds.e_ball_at_limit)
E_BALL_LOW = 0.70


def forms():
    from validation.impact import rate_laws as rl
    from validation.impact.face_bounds import FACE_COR

    fitted = ("e_ball", "friction")
    return (rl.Form("hertz_mindlin_face (face at the COR limit)", "hertz_mindlin", FACE_COR, fitted),
            rl.Form("hertz_mindlin_face + compression lever", "hertz_mindlin", FACE_COR,
                    (*fitted, "compression_lever")),
            rl.Form("hertz_mindlin_face + adhesive friction (n = 1)", "hertz_mindlin",
                    dict(FACE_COR, friction_pressure_exponent=1.0), fitted),
            rl.Form("hertz_mindlin_face + multi-asperity friction (n = 1/3)", "hertz_mindlin",
                    dict(FACE_COR, friction_pressure_exponent=1.0 / 3.0), fitted),
            rl.Form("hertz_mindlin_face + pressure friction, n fitted", "hertz_mindlin", FACE_COR,
                    (*fitted, "friction_pressure_exponent")))


def bounds():
    from validation.impact import rate_laws as rl

    from validation.impact.face_bounds import e_ball_at_limit

    out = dict(rl.BOUNDS)
    # less the root's tolerance (1e-4 in e), so that a fit at the cap reads at most 0.830, not just over it
    out["e_ball"] = (E_BALL_LOW, e_ball_at_limit() - 1e-4, 0.76,
                     "head COR <= 0.830 on the face (simulated test); Penner at 55 m/s")
    out["compression_lever"] = (0.0, rl.lever_bound(), 0.05, "mean offset <= 1.0 mm at the PGA driver delivery")
    return out


def describe(values, at_bound, cor):
    from validation.impact.face_bounds import HEAD_COR_LIMIT

    text = ", ".join(f"{name} {value:.4g}" for name, value in values.items())
    text += f" (at bound: {', '.join(at_bound)})" if at_bound else ""
    return f"{text}; head COR {cor:.3f}{'' if cor <= HEAD_COR_LIMIT + 1e-9 else ' BEYOND THE RULES'}"


def lever_section():
    """Section 0: the lever forced on the face (not fitted): the exponent and the tour rows' spin against lambda, at
    the face's whole-file fit (e_ball 0.786, friction 0.50; face_bounds_output.md section 3)."""
    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.face_bounds import FACE_COR

    tour = rl.tour()
    values = {"e_ball": 0.786, "friction": 0.50}
    print("### 0. The lever forced on the face (not fitted): what it would do\n")
    print("| lambda | mean offset at the PGA driver delivery [mm] | exponent k (PGA / LPGA driver) | tour rows' spin "
          "% (" + ", ".join(tour.labels) + ") | launch deg |")
    print("|---|---|---|---|---|")
    bound = rl.lever_bound()
    for lever in (0.0, 0.05, 0.1, bound):
        form = rl.Form("face + lever", "hertz_mindlin", dict(FACE_COR, compression_lever=lever), ())
        e = rl.errors(rl.run(form, values, table_inputs(tour)), tour.measured)
        ks = rl.exponent(form, values)
        print(f"| {lever:.3f} | {1.0 * lever / bound:.2f} | {ks[0]:.3f} / {ks[1]:.3f} | "
              + ", ".join(f"{100 * x:+.1f}" for x in e["spin"]) + " | "
              + ", ".join(f"{x:+.2f}" for x in e["launch"]) + " |")
    print()


def bands_section(sample, chosen=None):
    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.face_bounds import head_cor
    from validation.impact.shots import bands, load

    table, _ = load()
    slow, fast = bands(table)
    inputs = table_inputs(table)
    limits = bounds()
    print(f"### 1. Held out by club-speed band (training: a seeded subsample of {sample} rows of one band; every row "
          "of the other tested)\n")
    print("| form | fitted on -> tested on | fitted | spin median abs err % (bias) | ball speed median abs err % | "
          "launch median abs err deg (bias) | regression / boosting, same rows % |")
    print("|---|---|---|---|---|---|---|")
    rng = np.random.default_rng(33)
    slow_fits = {}
    for label, train_rows, test_rows, train, test in rl.band_folds(table, slow, fast, sample, rng):
        regression = rl.spin_error(rl.regression(train, test)[0], test)
        boosted = rl.boosting(train, test)
        boosting = rl.spin_error(boosted, test) if boosted is not None else float("nan")
        for form in chosen or forms():
            values, at_bound = rl.fit(form, rl.take(inputs, train_rows, table.size), train.measured, limits,
                                      rigid_face_head=False)
            slow_fits.setdefault(form.name, values)
            e = rl.errors(rl.run(form, values, rl.take(inputs, test_rows, table.size)), test.measured)
            print(f"| {form.name} | {label} | {describe(values, at_bound, head_cor(values['e_ball']))} | "
                  f"{100 * np.nanmedian(np.abs(e['spin'])):.1f} ({100 * np.nanmedian(e['spin']):+.1f}) | "
                  f"{100 * np.nanmedian(np.abs(e['speed'])):.2f} | {np.nanmedian(np.abs(e['launch'])):.2f} "
                  f"({np.nanmedian(e['launch']):+.2f}) | {regression:.1f} / {boosting:.1f} |")
    print("\n| form | exponent k at the PGA / LPGA driver delivery (the < 95 mph fit) |")
    print("|---|---|")
    for form in chosen or forms():
        ks = rl.exponent(form, slow_fits[form.name])
        print(f"| {form.name} | {ks[0]:.3f} / {ks[1]:.3f} |")


def tour_section(sample, chosen=None):
    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.face_bounds import head_cor
    from validation.impact.shots import load

    table, _ = load()
    inputs = table_inputs(table)
    rows = rl.whole_file_rows(table.size, sample)
    tour = rl.tour()
    wedge = rl.wedge_test()
    print(f"\n### 2. Fitted on {sample} rows of the whole file; the tour tables and the wedge test, not refitted "
          "(goals: spin within 7 %, ball speed within 1 %, launch within 0.7 deg; exponent 0.5-0.8; wedge +16 to "
          "+50 %)\n")
    rl.print_tour_table_head("fitted", tour)
    for form in chosen or forms():
        values, at_bound = rl.fit(form, rl.take(inputs, rows, table.size), table.subset(rows).measured, bounds(),
                                  rigid_face_head=False)
        print(f"| {form.name} | {describe(values, at_bound, head_cor(values['e_ball']))} | "
              f"{rl.tour_row_cells(form, values, tour, wedge)} |")


def command_line(argv, description: str, parts: bool | tuple[int, ...] = False,
                 part_help: str = "one section only") -> argparse.Namespace:
    """The research scripts' shared command line: ``--quick`` (training subsamples of 200 rows, else 400) and, with
    ``parts``, ``--part`` (one section only: sections 0-3, or the numbers ``parts`` gives). Silences the warnings
    the file's mishits raise by the thousand (unusual deliveries, flown as given). Returns the arguments with
    ``sample`` and ``started`` (time.time()) added."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--quick", action="store_true", help="training subsamples of 200 rows")
    if parts:
        choices = (0, 1, 2, 3) if parts is True else tuple(parts)
        parser.add_argument("--part", type=int, choices=choices, help=part_help)
    args = parser.parse_args(argv)
    warnings.filterwarnings("ignore", message=".*is unusual for golf.*")
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    args.sample = 200 if args.quick else 400
    args.started = time.time()
    return args


def run(argv, description: str, first, chosen=None, last=None) -> None:
    """The command line of this protocol: section 0 (``first``), then the bands and the tour tables of ``chosen``
    (default: this module's forms), then section 3 (``last``) if given; slip_friction runs its own forms through
    it."""
    args = command_line(argv, description, parts=True)
    started, sample = args.started, args.sample
    if args.part in (None, 0):
        first()
    if args.part in (None, 1):
        bands_section(sample, chosen)
    if args.part in (None, 2):
        tour_section(sample, chosen)
    if last is not None and args.part in (None, 3):
        last()
    print(f"\n(elapsed {time.time() - started:.0f} s)")


def main(argv=None) -> None:
    run(argv, __doc__.splitlines()[0], lever_section)


if __name__ == "__main__":
    main()
