"""Issue 33, round 5: the driver file held out by TrackMan's ball setting, and what the range balls' fit says.

    .venv/bin/python -u -m validation.impact.ball_groups            (training subsamples of 400 rows)
    .venv/bin/python -u -m validation.impact.ball_groups --quick    (200 rows)

The shared TrackMan file names a ball on every row (its ``Ball`` column: TrackMan's ball setting, README beside the
file). Among the rows this study keeps, 7,652 say Premium and 435 Limited Distance Soft (a range ball with limited
flight), 175 Medium. At the same delivery the Limited Distance rows spin about a quarter more per mph of V sin(spin
loft) than the Premium rows (163 against 128 rpm, section 0) with a slightly lower smash factor (1.407 against
1.423). That is a group the models can be held out on (the guide's "hold out by group"), and a second ball in the
one file: if a fit on the range-ball rows alone asks for other ball parameters than a fit on the Premium rows, those
parameters are the data's own estimate of how the two balls differ at impact.

Caveats, stated once: the setting is what the monitor was set to, not a measurement of the ball; the range-ball rows
come from some sessions only (file lines 2477-8383), so they differ in golfers too; what the range ball's cover is,
the file does not say (range balls are commonly two-piece balls with ionomer covers: an assumption, not a source).

Sections: 0, the groups; 1, fitted on 400 Premium rows, held out on the other groups and on other Premium rows,
beside the regression and gradient boosting fitted on the same rows; 2, each group's own fit (e_ball and the
friction's level) on two disjoint halves of its rows; 3, the wedge ball-type test with the urethane ball at the
Premium fit and the ionomer ball at each group's fit (a hypothesis test on a row no fit saw, not a fit to it); 4, the
ionomer's wedge spin against its friction, to read where it slides and where its spin peaks.
"""

from __future__ import annotations

import time

import numpy as np

RPM = 60.0 / (2.0 * np.pi)
GROUPS = ("Premium", "Limited Distance Soft", "Medium")


def ball_settings(table, path=None) -> np.ndarray:
    """The file's ``Ball`` setting of each row of ``table`` (rows labelled by their file line; '' for a line the file
    does not hold). ``path``: the file (default: the shared TrackMan file)."""
    from validation.impact.shots import file_column

    return file_column(table, "Ball", str, path)


def forms():
    """``hertz_mindlin_face`` (Coulomb) and ``hertz_mindlin_slip`` as registered (m = 1): e_ball and friction fitted."""
    from validation.impact.slip_friction import forms as slip_forms

    chosen = slip_forms()
    return [chosen[0], chosen[3]]


def per_unit(table) -> np.ndarray:
    """Spin per mph of V sin(spin loft) [rpm / mph] of each row."""
    from validation.impact import rate_laws as rl
    from validation.impact.shots import MPH

    speed = np.asarray(table.delivery["club_speed"]) / MPH
    return table.measured["spin_rate"] * RPM / (speed * np.sin(rl.spin_loft(table)))


def spin_cell(predicted, test) -> str:
    from validation.impact import rate_laws as rl

    bias = 100 * np.median(np.asarray(predicted) / test.measured["spin_rate"] - 1)
    return f"{rl.spin_error(predicted, test):.1f} ({bias:+.1f})"


def wedge_ratio(form, urethane: dict, ionomer: dict) -> tuple[float, dict]:
    """The wedge test's urethane/ionomer - 1 with each ball at its own fitted values (e_ball, friction as mu_0).

    The ionomer ball's inputs are told from the urethane's by the presets' sled friction (0.35 against 0.40); exactly
    one of the two balls must match, or the comparison would silently be of one ball with itself."""
    from impactlab.data.validation.observations import cover_effect
    from impactlab.scene.materials import BALL_PRESETS
    from validation.impact import rate_laws as rl

    wedge = rl.wedge_test()
    ionomer_friction = BALL_PRESETS[wedge.balls["ionomer"]].friction
    assert BALL_PRESETS[wedge.balls["urethane"]].friction != ionomer_friction, "the two presets are not told apart"
    matched = []

    def hook(inputs):
        is_ionomer = bool(np.allclose(inputs["friction"], ionomer_friction))
        matched.append(is_ionomer)
        out = dict(inputs, friction=np.full_like(np.asarray(inputs["friction"], float), rl.URETHANE_FRICTION))
        return rl.apply(out, ionomer if is_ionomer else urethane, form)

    result = cover_effect(rl.model_of(form, urethane), wedge, inputs_hook=hook)
    if sorted(matched) != [False, True]:
        raise RuntimeError(f"the wedge test's balls were not told apart (ionomer matched: {matched})")
    return result["predicted"], result["spin"]


def friction_sweep(form, values, frictions=(0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5)) -> list[float]:
    """The ionomer ball's wedge spin [rpm] against its friction mu_0, e_ball and everything else at ``values``."""
    return [wedge_ratio(form, values, {**values, "friction": mu})[1]["ionomer"] for mu in frictions]


def main(argv=None) -> None:
    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.face_bounds import head_cor
    from validation.impact.face_mechanisms import bounds, command_line, describe
    from validation.impact.shots import load

    args = command_line(argv, __doc__.splitlines()[0])
    started, sample = args.started, args.sample

    table, _ = load()
    inputs = table_inputs(table)
    setting = ball_settings(table)
    ratio = per_unit(table)
    smash = table.measured["ball_speed"] / np.asarray(table.delivery["club_speed"])
    print("### 0. The file's rows by TrackMan's ball setting (rows kept by validation.impact.shots)\n")
    print("| ball setting | rows | club speed median [mph] | smash factor median | spin per mph of V sin(spin loft), "
          "median [rpm] |")
    print("|---|---|---|---|---|")
    for group in GROUPS:
        mask = setting == group
        print(f"| {group} | {mask.sum()} | {np.median(table.delivery['club_speed'][mask]) / 0.44704:.1f} | "
              f"{np.median(smash[mask]):.3f} | {np.nanmedian(ratio[mask]):.0f} |")

    premium = np.flatnonzero(setting == "Premium")
    rng = np.random.default_rng(33)
    train_rows = np.sort(rng.choice(premium, size=min(sample, premium.size), replace=False))
    control_rows = np.sort(rng.choice(np.setdiff1d(premium, train_rows), size=min(sample, premium.size - sample),
                                      replace=False))
    train = table.subset(train_rows)
    tests = {"other Premium rows": control_rows,
             "Limited Distance Soft": np.flatnonzero(setting == "Limited Distance Soft"),
             "Medium": np.flatnonzero(setting == "Medium")}
    print(f"\n### 1. Fitted on {train_rows.size} Premium rows, tested on each group (spin median |error| %, bias in "
          "brackets)\n")
    print("| form | fitted | " + " | ".join(f"{name} ({rows.size})" for name, rows in tests.items()) + " |")
    print("|---|---|" + "---|" * len(tests))
    premium_fits = {}
    for form in forms():
        values, at_bound = rl.fit(form, rl.take(inputs, train_rows, table.size), train.measured, bounds(),
                                  rigid_face_head=False)
        premium_fits[form.name] = values
        cells = [spin_cell(rl.run(form, values, rl.take(inputs, rows, table.size))["spin_rate"], table.subset(rows))
                 for rows in tests.values()]
        print(f"| {form.name} | {describe(values, at_bound, head_cor(values['e_ball']))} | {' | '.join(cells)} |",
              flush=True)
    cells = [spin_cell(rl.regression(train, table.subset(rows))[0], table.subset(rows)) for rows in tests.values()]
    print(f"| regression | k on the same rows | {' | '.join(cells)} |")
    boosted = [rl.boosting(train, table.subset(rows)) for rows in tests.values()]
    if boosted[0] is not None:
        cells = [spin_cell(b, table.subset(rows)) for b, rows in zip(boosted, tests.values())]
        print(f"| gradient boosting | the same rows | {' | '.join(cells)} |")

    print("\n### 2. Each group's own fit (e_ball and friction mu_0) on two disjoint halves of its rows (at most "
          f"{sample} each; in-sample spin error)\n")
    print("| form | group | half | rows | fitted | in-sample spin % (bias) |")
    print("|---|---|---|---|---|---|")
    group_fits: dict = {}
    for form in forms():
        for group in GROUPS:
            index = np.random.default_rng(33).permutation(np.flatnonzero(setting == group))
            for half, part in enumerate((index[: index.size // 2], index[index.size // 2:]), start=1):
                rows = np.sort(part[:sample])
                values, at_bound = rl.fit(form, rl.take(inputs, rows, table.size), table.subset(rows).measured,
                                          bounds(), rigid_face_head=False)
                group_fits.setdefault((form.name, group), []).append(values)
                out = rl.run(form, values, rl.take(inputs, rows, table.size))
                print(f"| {form.name} | {group} | {half} | {rows.size} | "
                      f"{describe(values, at_bound, head_cor(values['e_ball']))} | "
                      f"{spin_cell(out['spin_rate'], table.subset(rows))} |", flush=True)

    print("\n### 3. The wedge ball-type test with each ball at a group's fit (measured +48 %, goal +16 to +50 %; "
          "not fitted to it)\n")
    print("| form | urethane ball | ionomer ball | spin urethane / ionomer [rpm] | urethane/ionomer - 1 |")
    print("|---|---|---|---|---|")
    for form in forms():
        premium_values = group_fits[(form.name, "Premium")][0]
        for group in GROUPS:
            for values in group_fits[(form.name, group)]:
                predicted, spin = wedge_ratio(form, premium_values, values)
                fitted = ", ".join(f"{k} {v:.3f}" for k, v in values.items())
                print(f"| {form.name} | Premium fit (half 1) | {group} fit ({fitted}) | {spin['urethane']:.0f} / "
                      f"{spin['ionomer']:.0f} | {100 * predicted:+.1f} % |", flush=True)
    frictions = (0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5)
    print("\n### 4. The ionomer ball's wedge spin against its friction mu_0 (e_ball and the rest at the Premium fit, "
          "half 1; rpm): where it slides and where its spin peaks\n")
    print("| form | urethane ball (Premium fit) | " + " | ".join(f"ionomer mu_0 {mu:g}" for mu in frictions) + " |")
    print("|---|---|" + "---|" * len(frictions))
    for form in forms():
        values = group_fits[(form.name, "Premium")][0]
        urethane = wedge_ratio(form, values, values)[1]["urethane"]
        print(f"| {form.name} | {urethane:.0f} | " + " | ".join(f"{x:.0f}" for x in friction_sweep(form, values,
                                                                                                  frictions)) + " |",
              flush=True)
    print(f"\n(elapsed {time.time() - started:.0f} s)")


if __name__ == "__main__":
    main()
