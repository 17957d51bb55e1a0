"""Issue 33, round 5: fitted on the TrackMan driver file, predicting a real iron session it never saw.

    .venv/bin/python -u -m validation.impact.real_irons            (training subsample of 400 driver rows)
    .venv/bin/python -u -m validation.impact.real_irons --quick    (200 rows)

The issue asks for one set of ball parameters serving drivers and irons. Until now the irons were checked on tour
averages only (two 6-iron rows). This is the first real iron session with its club delivery in the project: a
FlightScope Mevo+ range session of 36 8-iron shots (russosanti/golf-metrics, MIT; shipped whole as
``tests/data/vendors/flightscope_fsgolf_mevo.csv``, read by the package's FS Golf layout). One golfer, outdoors,
ball not stated, a consumer radar (its club data and spin are the monitor's readings, not a laboratory's). The
reader leaves out 7 rows whose Smash disagrees with Ball / Club by 2-5 % (each with its line) and keeps 29.

Protocol: nothing is fitted on the iron rows. Each model form either runs as registered (the presets and the
registered constants) or is fitted on a seeded 400-row subsample of the driver file (the same rows, bounds and
face as ``validation.impact.face_mechanisms`` section 2, so the head COR stays within the Rules); then it predicts
each iron shot from its delivery (club speed, attack angle, dynamic loft, path, face angle; strike at the centre,
the export's impact location being unread). Baselines fitted on the same driver rows: the one-parameter regression
spin = k V sin(spin loft) and gradient boosting on the delivery (``validation.impact.rate_laws``). For scale, two
in-session baselines fitted on the iron rows themselves by leave-one-out: the other rows' median spin, and the same
regression with k from the other rows. Section 2 refits the driver baselines on 20 training samples and on the whole
file: gradient boosting's score moves with its sample (trees do not extrapolate beyond the drivers' spin lofts), so
its one number in section 1 is not a ranking; section 1's square brackets give each median's bootstrap interval.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

SESSION = Path(__file__).resolve().parents[2] / "tests" / "data" / "vendors" / "flightscope_fsgolf_mevo.csv"
RPM = 60.0 / (2.0 * np.pi)
MPH = 0.44704


def session_table():
    """(the iron session's shot table, report lines): the rows the package's reader keeps for the models."""
    from impactlab.data.sessions.reader import read_session

    session = read_session(SESSION)
    table = session.shot_table()
    _, skipped = session.usable()
    report = [f"shots read: {session.size}; used: {table.size}",
              *(f"skipped, line {line}: {why}" for line, why in session.skipped),
              *(f"left out of the models, line {line}: {why}" for line, why in skipped)]
    return table, report


def registered_forms():
    """(name, model) of the registered models as shipped: presets and registered constants, nothing fitted here."""
    from impactlab.model.registry import get_model

    return [(name, get_model(name)()) for name in ("rigid_coulomb", "maw", "hertz_mindlin", "hertz_mindlin_face",
                                                   "hertz_mindlin_slip")]


def fitted_forms():
    """The driver-file forms refitted here (e_ball and the friction scale on 400 driver rows)."""
    from validation.impact.slip_friction import forms

    chosen = forms()
    return [chosen[0], chosen[3]]  # hertz_mindlin_face (Coulomb) and hertz_mindlin_slip as registered (m = 1)


def interval(predicted, test, draws: int = 2000, seed: int = 33) -> tuple[float, float]:
    """95 % bootstrap interval of the median |spin error| [%] over the iron rows (rows resampled with replacement)."""
    error = np.abs(np.asarray(predicted) / test.measured["spin_rate"] - 1.0)
    rng = np.random.default_rng(seed)
    medians = np.median(error[rng.integers(0, error.size, size=(draws, error.size))], axis=1)
    return tuple(100 * np.percentile(medians, [2.5, 97.5]))


def paired_difference(one, other, test, draws: int = 2000, seed: int = 33) -> tuple[float, float, float]:
    """(difference of the median |spin error| of ``one`` and ``other`` [points], its 95 % bootstrap interval), both
    predictors scored on the same resamples of the rows."""
    measured = test.measured["spin_rate"]
    first = np.abs(np.asarray(one) / measured - 1.0)
    second = np.abs(np.asarray(other) / measured - 1.0)
    draw = np.random.default_rng(seed).integers(0, first.size, size=(draws, first.size))
    differences = 100 * (np.median(first[draw], axis=1) - np.median(second[draw], axis=1))
    low, high = np.percentile(differences, [2.5, 97.5])
    return 100 * (np.median(first) - np.median(second)), float(low), float(high)


def spin_cells(predicted, test) -> str:
    """'median |error| % [95 % interval] (bias %)' of the spin over the iron rows."""
    from validation.impact import rate_laws as rl

    low, high = interval(predicted, test)
    bias = 100 * np.median(np.asarray(predicted) / test.measured["spin_rate"] - 1)
    return f"{rl.spin_error(predicted, test):.1f} [{low:.0f}-{high:.0f}] ({bias:+.1f})"


def row(name, fitted, out, test) -> str:
    """One table row: spin median |error| % [interval] (bias), ball speed and launch errors on the iron rows."""
    from validation.impact import rate_laws as rl

    e = rl.errors(out, test.measured)
    return (f"| {name} | {fitted} | {spin_cells(out['spin_rate'], test)} "
            f"| {100 * np.median(np.abs(e['speed'])):.2f} ({100 * np.median(e['speed']):+.2f}) "
            f"| {np.median(np.abs(e['launch'])):.2f} ({np.median(e['launch']):+.2f}) |")


def baseline_spread(table, test, sizes=(100, 200, 400, 600), seeds=(1, 2, 3, 4, 5)):
    """The driver-fitted baselines' spin error on the iron rows over training subsamples and seeds, and on the whole
    file: {name: (errors over the subsamples, error on the whole file)}."""
    from validation.impact import rate_laws as rl

    out = {"regression": ([], None), "gradient boosting": ([], None)}
    for size in sizes:
        for seed in seeds:
            train = table.subset(np.sort(np.random.default_rng(seed).choice(table.size, size=size, replace=False)))
            out["regression"][0].append(rl.spin_error(rl.regression(train, test)[0], test))
            boosted = rl.boosting(train, test)
            if boosted is not None:
                out["gradient boosting"][0].append(rl.spin_error(boosted, test))
    whole = {"regression": rl.spin_error(rl.regression(table, test)[0], test)}
    boosted = rl.boosting(table, test)
    if boosted is not None:
        whole["gradient boosting"] = rl.spin_error(boosted, test)
    return {name: (errors, whole.get(name)) for name, (errors, _) in out.items() if errors}


def leave_one_out_constant(test) -> np.ndarray:
    """Each iron row's spin predicted as the median spin of the *other* iron rows (no delivery at all)."""
    spin = np.asarray(test.measured["spin_rate"], float)
    return np.array([np.median(np.delete(spin, i)) for i in range(spin.size)])


def leave_one_out_regression(test) -> np.ndarray:
    """spin = k V sin(spin loft) with k the median ratio of the *other* iron rows (an in-session baseline)."""
    from validation.impact import rate_laws as rl

    x = np.asarray(test.delivery["club_speed"]) * np.sin(rl.spin_loft(test))
    ratio = test.measured["spin_rate"] / x
    k = np.array([np.median(np.delete(ratio, i)) for i in range(ratio.size)])
    return k * x


def main(argv=None) -> None:
    from impactlab.data.sessions.shots import predict, table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.face_bounds import head_cor
    from validation.impact.face_mechanisms import bounds, command_line, describe
    from validation.impact.shots import load

    args = command_line(argv, __doc__.splitlines()[0])
    started, sample = args.started, args.sample

    test, report = session_table()
    inputs = table_inputs(test)
    speed = np.asarray(test.delivery["club_speed"]) / MPH
    loft = np.degrees(rl.spin_loft(test))
    spin = test.measured["spin_rate"] * RPM
    print("### 0. The iron session (FlightScope Mevo+, 8-iron, one golfer; read by the package's FS Golf layout)\n")
    print("\n".join(f"- {line}" for line in report))
    print(f"- club speed {speed.min():.1f}-{speed.max():.1f} mph (median {np.median(speed):.1f}); spin loft "
          f"{loft.min():.1f}-{loft.max():.1f} deg (median {np.median(loft):.1f}); spin {spin.min():.0f}-"
          f"{spin.max():.0f} rpm (median {np.median(spin):.0f})")
    per_unit = spin / (speed * np.sin(np.radians(loft)))
    print(f"- spin per mph of V sin(spin loft): median {np.median(per_unit):.0f} rpm (tour irons and wedges, "
          "TrackMan averages: 160-179; physics brief section 13); the driver file's drivers: 122-145")
    from scipy.stats import spearmanr

    rho_loft = spearmanr(spin, loft).statistic
    rho_launch = spearmanr(np.degrees(test.measured["vertical_launch_angle"]),
                           np.degrees(np.asarray(test.delivery["dynamic_loft"]))).statistic
    print(f"- rank correlation of spin with spin loft: {rho_loft:+.2f} (every ball law and the regression make spin "
          f"rise with it); of launch with dynamic loft: {rho_launch:+.2f}\n")

    table, _ = load()
    rows = rl.whole_file_rows(table.size, sample)
    train = table.subset(rows)
    train_inputs = rl.take(table_inputs(table), rows, table.size)

    print(f"### 1. Predicted, not fitted on these rows ({test.size} iron shots; median |error|, its 95 % bootstrap "
          "interval over the rows in square brackets, bias in round brackets)\n")
    print("| form | fitted on | spin % [interval] (bias) | ball speed % (bias) | launch deg (bias) |")
    print("|---|---|---|---|---|")
    spins = {}
    for name, model in registered_forms():
        out = predict(model, inputs)
        spins[f"`{name}` as registered"] = out["spin_rate"]
        print(row(f"`{name}` as registered", "nothing here (presets, registered constants)", out, test), flush=True)
    for form in fitted_forms():
        values, at_bound = rl.fit(form, train_inputs, train.measured, bounds(), rigid_face_head=False)
        out = rl.run(form, values, inputs)
        spins[f"{form.name}, fitted on drivers"] = out["spin_rate"]
        print(row(form.name, f"{sample} driver rows: {describe(values, at_bound, head_cor(values['e_ball']))}",
                  out, test), flush=True)
    predicted, k = rl.regression(train, test)
    print(f"| regression spin = k V sin(spin loft) | {sample} driver rows: k {k * RPM / (1 / MPH):.1f} rpm/mph | "
          f"{spin_cells(predicted, test)} | - | - |")
    spins["regression, fitted on drivers"] = predicted
    boosted = rl.boosting(train, test)
    if boosted is not None:
        spins["gradient boosting, fitted on drivers"] = boosted
        print(f"| gradient boosting on the delivery | {sample} driver rows | {spin_cells(boosted, test)} | - | - |")
    spins["in-session median (leave-one-out)"] = leave_one_out_constant(test)
    spins["in-session regression (leave-one-out)"] = leave_one_out_regression(test)
    print(f"| in-session baseline: each row's spin as the median of the other iron rows (no delivery) | the iron "
          f"rows | {spin_cells(spins['in-session median (leave-one-out)'], test)} | - | - |")
    print(f"| in-session baseline: the regression with k from the other iron rows (leave-one-out) | the iron rows "
          f"| {spin_cells(spins['in-session regression (leave-one-out)'], test)} | - | - |")

    reference = next(name for name in spins if name.startswith("hertz_mindlin_slip"))
    print(f"\nPaired on the same bootstrap resamples of the 29 shots: the median |spin error| of {reference} minus "
          "each other predictor's [points; 95 % interval]\n")
    print("| predictor | difference | interval |")
    print("|---|---|---|")
    for name, other in spins.items():
        if name != reference:
            difference, low, high = paired_difference(spins[reference], other, test)
            print(f"| {name} | {difference:+.1f} | {low:+.1f} to {high:+.1f} |")

    print("\n### 2. The driver-fitted baselines over training samples (100, 200, 400, 600 rows x seeds 1-5) and on the "
          f"whole file ({table.size} rows): spin median |error| on the iron rows\n")
    print("| baseline | over the 20 subsamples: min / median / max % | whole file % |")
    print("|---|---|---|")
    for name, (spread, whole) in baseline_spread(table, test).items():
        print(f"| {name} | {min(spread):.1f} / {np.median(spread):.1f} / {max(spread):.1f} | "
              f"{'-' if whole is None else f'{whole:.1f}'} |", flush=True)
    print(f"\n(elapsed {time.time() - started:.0f} s)")


if __name__ == "__main__":
    main()
