"""Issue 33, round 4: how low a spin error the file's inputs allow at all, band by band.

    .venv/bin/python -u -m validation.impact.attainable      (about a minute; output: attainable_output.md)

The issue's first goal asks for a held-out median |spin error| <= 15 % on each club-speed band when a model is
fitted on the other band. Before reading a model's score against that number, this measures what the rows of each
band allow when nothing has to be extrapolated: every learner below is trained on rows *of the band it is tested
on* (interpolation, the easy case), by 5-fold cross-validation in contiguous blocks of the file (its sessions lie in
file order and the file has no session column; contiguous folds keep most of a session's rows on one side).

- gradient boosting (scikit-learn's HistGradientBoostingRegressor on log spin) of the seven delivery and strike
  inputs the models take (club speed, attack angle, dynamic loft, path, face angle, strike toe and height; NaN where
  the file has no location), trained on every other fold of the band;
- the one-parameter regression spin = k V sin(spin loft) of the protocol, k fitted on the other folds;
- a free power law log spin = a + b log V + c log sin(spin loft), fitted on the other folds (the shape the issue's
  exponents come from).

The in-band score is a floor for what a model of the same inputs can reach on that band held out: a model fitted
on the other band cannot know the band better than learners trained on the band's own rows, unless it brings
physics the learners lack (which is the point of the issue, so the floor is a reference, not a proof). Reported
beside: the spin's scatter within runs of consecutive shots at nearly the same delivery (the repeatability the
instrument and the golfer leave), the median |log ratio| of spin between consecutive shots whose delivery differs
by little.

Section 2 regresses the models' predictions the same way. The issue's exponent goal compares a model's d log spin /
d log V at a fixed delivery with exponents of regressions on the file, which absorb whatever else changes with the
club speed across the rows (path, face angle, strike, attack) and, on the data side only, the reading errors of the
spin loft (which attenuate c and, through its correlation with V, move b). The same power law fitted to a model's
predictions on the same rows (its inputs the same measured deliveries, so no reading error enters its side) is the
like-for-like comparison: the remaining gap is the model's.
"""

from __future__ import annotations

import argparse
import math
import time
import warnings

import numpy as np

FOLDS = 5


def contiguous_folds(count: int, folds: int = FOLDS):
    """(training, testing) index arrays of ``folds`` contiguous blocks of ``count`` rows in file order."""
    edges = np.linspace(0, count, folds + 1).astype(int)
    every = np.arange(count)
    for start, stop in zip(edges[:-1], edges[1:]):
        test = every[start:stop]
        yield np.concatenate([every[:start], every[stop:]]), test


def features(table):
    """The seven delivery and strike inputs of the learners (SI; strike NaN where the file has none)."""
    from validation.impact import rate_laws as rl

    return np.stack([np.asarray(table.delivery[name], float) for name in rl.FEATURES], -1)


def power_law(train, test):
    """log spin = a + b log V + c log sin(spin loft), least squares on ``train``: (predictions on ``test``, b, c)."""
    from validation.impact import rate_laws as rl

    def design(table):
        speed = np.asarray(table.delivery["club_speed"], float)
        return np.stack([np.ones_like(speed), np.log(speed), np.log(np.sin(rl.spin_loft(table)))], -1)

    with np.errstate(invalid="ignore", divide="ignore"):  # a negative spin loft has no log: that row is left out
        x, y, x_test = design(train), np.log(np.asarray(train.measured["spin_rate"], float)), design(test)
    good = np.all(np.isfinite(x), -1) & np.isfinite(y)
    coefficients, *_ = np.linalg.lstsq(x[good], y[good], rcond=None)
    return np.exp(x_test @ coefficients), float(coefficients[1]), float(coefficients[2])


def in_band(table, mask):
    """Median |spin error| % of the three learners by contiguous 5-fold CV within the rows of ``mask``, and the
    power law's exponents (mean over folds)."""
    from sklearn.ensemble import HistGradientBoostingRegressor

    from validation.impact import rate_laws as rl

    band = table.subset(np.flatnonzero(mask))
    x = features(band)
    spin = np.asarray(band.measured["spin_rate"], float)
    predicted = {name: np.full(band.size, np.nan) for name in ("boosting", "regression", "power law")}
    exponents = []
    for train_rows, test_rows in contiguous_folds(band.size):
        train, test = band.subset(train_rows), band.subset(test_rows)
        learner = HistGradientBoostingRegressor(max_iter=300, learning_rate=0.05, random_state=0)
        learner.fit(x[train_rows], np.log(spin[train_rows]))
        predicted["boosting"][test_rows] = np.exp(learner.predict(x[test_rows]))
        predicted["regression"][test_rows] = rl.regression(train, test)[0]
        predicted["power law"][test_rows], b, c = power_law(train, test)
        exponents.append((b, c))
    scores = {name: float(100 * np.nanmedian(np.abs(p / spin - 1.0))) for name, p in predicted.items()}
    return scores, np.mean(exponents, 0), band.size


def repeatability(table, mask, speed_tolerance=0.02, loft_tolerance=np.radians(1.0)):
    """Median |spin ratio - 1| % between consecutive rows of the band whose club speed differs by < 2 % and spin
    loft by < 1 deg (and strike, where both have one, by < 5 mm): the scatter of two nearly identical deliveries,
    and the number of such pairs. Half of the pairs' log spread is each shot's; the median |error| of a perfect model
    is about the pair value over sqrt(2)."""
    from validation.impact import rate_laws as rl

    band = table.subset(np.flatnonzero(mask))
    speed = np.asarray(band.delivery["club_speed"], float)
    loft = rl.spin_loft(band)
    spin = np.asarray(band.measured["spin_rate"], float)
    strike = np.stack([np.asarray(band.delivery[n], float) for n in ("strike_toe", "strike_high")], -1)
    near = (np.abs(np.diff(speed)) < speed_tolerance * speed[1:]) & (np.abs(np.diff(loft)) < loft_tolerance)
    apart = np.any(np.abs(np.diff(strike, axis=0)) > 0.005, -1)  # NaN compares False: kept without a location
    pairs = near & ~apart
    ratio = np.abs(np.log(spin[1:][pairs] / spin[:-1][pairs]))
    return float(100 * (np.exp(np.median(ratio)) - 1.0)), int(pairs.sum())


#: the models of section 2 at their whole-file fits (rate_laws_output.md section 4: hertz_mindlin e_ball 0.742,
#: friction 0.6; face_bounds_output.md section 3: hertz_mindlin_face e_ball 0.786, friction 0.50;
#: slip_friction_output.md section 2: hertz_mindlin_slip e_ball 0.787, friction 0.339, m 1.0 at its bound)
APPARENT_FORMS = (("hertz_mindlin (today's law)", "plain", {"e_ball": 0.742, "friction": 0.6}),
                  ("hertz_mindlin_face (face at the COR limit)", "face", {"e_ball": 0.786, "friction": 0.50}),
                  ("hertz_mindlin_slip (the face, friction rising with the slip speed)", "slip",
                   {"e_ball": 0.787, "friction": 0.339}))


def options_of(kind: str) -> dict:
    """hertz_mindlin's options of an APPARENT_FORMS entry: plain, the face at the COR limit, or the face with the
    slip-speed friction at its fitted exponent (hertz_mindlin_slip's defaults)."""
    from impactlab_models.dem import FITTED_SLIP_EXPONENT
    from validation.impact.face_bounds import FACE_COR

    return {"plain": {}, "face": FACE_COR, "slip": {**FACE_COR, "friction_slip_exponent": FITTED_SLIP_EXPONENT}}[kind]


def apparent_exponents(table, masks):
    """The power law's (b, c) fitted to the measured spin and to each model's predicted spin on the same rows."""
    import types

    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl

    inputs = table_inputs(table)
    rows_of = {label: np.flatnonzero(mask) for label, mask in masks}
    out = {"measured": {label: power_law(table.subset(rows), table.subset(rows))[1:]
                        for label, rows in rows_of.items()}}
    for name, options, values in APPARENT_FORMS:
        form = rl.Form(name, "hertz_mindlin", options_of(options), ())
        spin = rl.run(form, values, inputs)["spin_rate"]
        out[name] = {}
        for label, rows in rows_of.items():
            rows = rows[np.isfinite(spin[rows])]
            sub = table.subset(rows)
            predicted = types.SimpleNamespace(delivery=sub.delivery, measured={"spin_rate": spin[rows]})
            out[name][label] = power_law(predicted, sub)[1:]
    return out


#: reading errors of the dynamic loft and of the attack angle tried in section 3 [deg] (each; the spin loft, their
#: difference, carries sqrt(2) times it). TrackMan publishes no per-parameter accuracy (lit33, section 5): a range.
READING_ERRORS = (0.5, 1.0, 1.5)


def reading_error_shift(table, mask, form_index: int = 1, draws: int = 20, seed: int = 33):
    """(sigma, b, c) of a model's predictions (APPARENT_FORMS[form_index], the face model by default) regressed on
    the spin loft read with an error: the model's spin is computed from the rows' deliveries as if they were exact,
    then regressed on those deliveries with Gaussian noise of sigma added to the dynamic loft and to the attack angle
    (the spin loft's reading); b and c are the means over ``draws`` seeded draws. sigma 0 is section 2's value; the
    shift is what reading errors alone do to the regression the issue's exponents come from."""
    import types

    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl

    rows = np.flatnonzero(mask)
    sub = table.subset(rows)
    name, options, values = APPARENT_FORMS[form_index]
    spin = rl.run(rl.Form(name, "hertz_mindlin", options_of(options), ()), values, table_inputs(sub))["spin_rate"]
    rng = np.random.default_rng(seed)
    out = []
    for sigma in (0.0, *READING_ERRORS):
        fitted = []
        for _ in range(draws if sigma else 1):
            noise = np.radians(sigma) * math.sqrt(2.0) * rng.standard_normal(sub.size)
            delivery = dict(sub.delivery, spin_loft=rl.spin_loft(sub) + noise)
            read = types.SimpleNamespace(delivery=delivery, measured={"spin_rate": spin})
            fitted.append(power_law(read, read)[1:])
        out.append((sigma, *np.mean(fitted, 0)))
    return out


def tour_from_the_file(table):
    """The TrackMan tour rows predicted by learners trained on the file's drivers (no physics): spin, ball speed and
    launch relative errors on each tour row. What the file itself says of the tour rows, beside the goal that a model
    fitted to the file must meet them within 7 % (spin), 1 % (ball speed) and 0.7 deg (launch)."""
    from sklearn.ensemble import HistGradientBoostingRegressor

    from validation.impact import rate_laws as rl

    tour = rl.tour()
    x_file, x_tour = features(table), features(tour)
    out = {}
    for name, transform, inverse in (("spin_rate", np.log, np.exp), ("ball_speed", np.log, np.exp),
                                     ("vertical_launch_angle", np.degrees, np.radians)):
        y = np.asarray(table.measured[name], float)
        keep = np.isfinite(y)
        learner = HistGradientBoostingRegressor(max_iter=300, learning_rate=0.05, random_state=0)
        learner.fit(x_file[keep], transform(y[keep]))
        out[name] = inverse(learner.predict(x_tour))
    regression, _ = rl.regression(table, tour)
    smash = float(np.nanmedian(np.asarray(table.measured["ball_speed"]) / np.asarray(table.delivery["club_speed"])))
    return tour, out, {"spin_rate": regression, "ball_speed": smash * np.asarray(tour.delivery["club_speed"])}


def main(argv=None) -> None:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args(argv)
    warnings.filterwarnings("ignore", message=".*is unusual for golf.*")
    from validation.impact.shots import bands, load

    started = time.time()
    table, _ = load()
    slow, fast = bands(table)
    print("### What the inputs allow within each band (contiguous 5-fold CV, trained on the band's own rows)\n")
    print("| band | rows | gradient boosting % | regression k V sin(spin loft) % | power law % (b on V, c on sin "
          "spin loft) | consecutive near-identical deliveries: spin differs by (median) %, pairs |")
    print("|---|---|---|---|---|---|")
    for label, mask in (("< 95 mph", slow), ("> 100 mph", fast), ("every kept row", np.ones(table.size, bool))):
        scores, (b, c), rows = in_band(table, mask)
        pair, count = repeatability(table, mask)
        print(f"| {label} | {rows} | {scores['boosting']:.1f} | {scores['regression']:.1f} | "
              f"{scores['power law']:.1f} (b {b:.2f}, c {c:.2f}) | {pair:.1f}, {count} |")
    masks = (("< 95 mph", slow), ("> 100 mph", fast), ("every kept row", np.ones(table.size, bool)))
    print("\n### The same power law, log spin = a + b log V + c log sin(spin loft), fitted to the measured spin and to "
          "the models' predictions on the same rows\n")
    print("| spin | " + " | ".join(f"{label}: b, c" for label, _ in masks) + " |")
    print("|---|" + "---|" * len(masks))
    for name, fitted in apparent_exponents(table, masks).items():
        print(f"| {name} | " + " | ".join(f"{b:.2f}, {c:.2f}" for b, c in fitted.values()) + " |")
    print("\n### The models' predictions regressed on a spin loft read with an error (the deliveries taken as exact "
          "for the model; Gaussian reading error sigma on the dynamic loft and on the attack angle; means of 20 "
          "draws)\n")
    print("| model | sigma [deg] | " + " | ".join(f"{label}: b, c" for label, _ in masks) + " |")
    print("|---|---|" + "---|" * len(masks))
    for index in (1, 2):
        shifts = [reading_error_shift(table, mask, index) for _, mask in masks]
        for row, sigma in enumerate((0.0, *READING_ERRORS)):
            print(f"| {APPARENT_FORMS[index][0]} | {sigma:g} | "
                  + " | ".join(f"{s[row][1]:.2f}, {s[row][2]:.2f}" for s in shifts) + " |")
    tour, learned, simple = tour_from_the_file(table)
    print("\n### The tour rows predicted from the file's drivers by learners without physics (every kept row; the "
          "issue's goal for a model fitted to the file: spin within 7 %, ball speed within 1 %, launch within 0.7 deg)"
          "\n")
    print("| learner | " + " | ".join(f"{label}: spin %, ball speed %, launch deg" for label in tour.labels) + " |")
    print("|---|" + "---|" * tour.size)
    measured = tour.measured
    cells = [f"{100 * (learned['spin_rate'][i] / measured['spin_rate'][i] - 1):+.1f}, "
             f"{100 * (learned['ball_speed'][i] / measured['ball_speed'][i] - 1):+.2f}, "
             f"{np.degrees(learned['vertical_launch_angle'][i] - measured['vertical_launch_angle'][i]):+.2f}"
             for i in range(tour.size)]
    print("| gradient boosting (seven delivery and strike inputs) | " + " | ".join(cells) + " |")
    cells = [f"{100 * (simple['spin_rate'][i] / measured['spin_rate'][i] - 1):+.1f}, "
             f"{100 * (simple['ball_speed'][i] / measured['ball_speed'][i] - 1):+.2f}, -" for i in range(tour.size)]
    print("| regression k V sin(spin loft); ball speed = median smash x V | " + " | ".join(cells) + " |")
    print(f"\n(elapsed {time.time() - started:.0f} s)")


if __name__ == "__main__":
    main()
