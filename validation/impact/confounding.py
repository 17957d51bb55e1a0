"""Issue 33, round 2: is the measured fall of driver spin with club speed a property of the ball or of the players?

    .venv/bin/python -u -m validation.impact.confounding           (section 1 in seconds; section 2 a few minutes)
    .venv/bin/python -u -m validation.impact.confounding --quick   (section 2 on training subsamples of 200 rows)
    .venv/bin/python -u -m validation.impact.confounding --part 1  (section 1 only)
    .venv/bin/python -u -m validation.impact.confounding --part 3  (the face at the COR limit on every kept row)
    .venv/bin/python -u -m validation.impact.confounding --part 4  (the same, fitted on the whole file, predicting
                                                                    the tour tables and the wedge test)

The shared TrackMan file (validation/impact/shots.py; no player column) gives spin ~ V^0.34 sin(spin loft)^0.70 when
all its shots are pooled (issue 33). Pooling mixes two things: how one player's spin changes when he swings faster
(what a ball law at a fixed delivery must reproduce) and how fast players differ from slow ones (strike, shaft,
driver head, ball setting: what no ball law should reproduce).

1. Within and across sessions. The file is the concatenation of sessions (its rows are in session order: the 50-row
   block means of club speed jump between 78 and 112 mph). A session proxy is a block of B contiguous rows of the
   file, cut again wherever TrackMan's ball setting (column ``Ball``) changes. Three estimates of
   log spin = a + k log V + m log sin(spin loft) [+ c h]:
   - pooled: one intercept for every shot (the issue's 0.34 / 0.70);
   - within (block fixed effects): each block's own intercept, so k is measured from speed changes inside blocks;
   - across (between): the same law fitted to the blocks' means (weighted by rows), k from differences between blocks.
   Spin loft is dynamic loft minus attack angle (the file has no spin-loft column); V the club speed; h the strike
   height (``Impact Height``, mm, on about 1,750 of the kept rows) as a linear covariate where given. Fits are
   ordinary least squares on the logs and, beside them, a Huber fit (scipy.optimize.least_squares, loss "huber",
   f_scale 0.15: mishits are in the data); 95 % intervals from a bootstrap over blocks (blocks resampled with
   replacement, 400 draws, seeded). B in {10, 25, 50, 100}: a block straddling two sessions mixes across-session
   variation into the within estimate, so a shorter block is the cleaner within estimate (and the noisier).
2. The package's mechanisms with a time or length scale, each alone, fitted on one speed band and tested on the other
   (validation/impact/rate_laws.py's protocol and fit): the flexing face (face_frequency, face_modal_mass; the plate
   model's face under the default law, and the face sized at the COR limit under the hysteretic law beside its rigid
   face), the 3-D head with the measured strike height (vertical gear effect) and the round-1 compression lever,
   beside the regression spin = k V sin(spin loft) and gradient boosting fitted on the same training rows; each
   form's spin-speed exponent at a fixed delivery (the TrackMan tour drivers' deliveries, 96 -> 115 mph).
"""

from __future__ import annotations

import argparse
import csv
import math
import time
import warnings

import numpy as np
from scipy import optimize

from validation.impact.shots import DATA, filtered_lines

BLOCKS = (10, 25, 50, 100)
DRAWS = 400


def read_rows(path=DATA):
    """The kept rows (validation.impact.shots' filter) as arrays, in file order, with their 0-based file position."""
    kept, _, _ = filtered_lines(path)
    out = {"position": [], "ball": [], "speed": [], "loft": [], "attack": [], "spin": [], "height": []}
    with open(path, newline="", encoding="utf-8") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        next(reader)
        col = {name: i for i, name in enumerate(header)}
        for line, row in enumerate(reader, start=3):
            if line not in kept:
                continue

            def num(name, row=row):
                try:
                    return float(row[col[name]])
                except (ValueError, IndexError):
                    return np.nan

            out["position"].append(line - 3)
            out["ball"].append(row[col["Ball"]])
            out["speed"].append(num("Club Speed"))
            out["loft"].append(num("Dyn. Loft"))
            out["attack"].append(num("Attack Angle"))
            out["spin"].append(num("Spin Rate"))
            out["height"].append(num("Impact Height"))
    rows = {k: np.asarray(v) if k == "ball" else np.asarray(v, float) for k, v in out.items()}
    rows["spin_loft"] = rows["loft"] - rows["attack"]
    return rows


def blocks_of(rows, size):
    """Block label of each row: B contiguous file rows, cut again where the ball setting changes."""
    chunk = (rows["position"] // size).astype(int)
    change = np.r_[True, (rows["ball"][1:] != rows["ball"][:-1]) | (chunk[1:] != chunk[:-1])]
    return np.cumsum(change) - 1


def design(rows, with_height):
    """(y, X, mask): log spin, [log V, log sin(spin loft), (h mm)], the rows where they are defined."""
    with np.errstate(invalid="ignore", divide="ignore"):
        y = np.log(rows["spin"])
        cols = [np.log(rows["speed"]), np.log(np.sin(np.radians(rows["spin_loft"])))]
    if with_height:
        cols.append(rows["height"])
    x = np.stack(cols, -1)
    mask = np.isfinite(y) & np.all(np.isfinite(x), -1) & (rows["spin"] > 0) & (rows["spin_loft"] > 0)
    return y, x, mask


def _demean(values, labels, weights=None):
    """values minus their block means (labels 0..n-1)."""
    n = labels.max() + 1
    count = np.bincount(labels, minlength=n)
    if values.ndim == 1:
        return values - (np.bincount(labels, values, n) / np.maximum(count, 1))[labels]
    return np.stack([_demean(values[:, j], labels) for j in range(values.shape[1])], -1)


def _means(values, labels):
    n = labels.max() + 1
    count = np.bincount(labels, minlength=n)
    if values.ndim == 1:
        return np.bincount(labels, values, n) / np.maximum(count, 1), count
    return np.stack([_means(values[:, j], labels)[0] for j in range(values.shape[1])], -1), count


def _solve(y, x, weights=None, robust=False):
    """Slopes of y on x (x already centred or with a constant column appended by the caller)."""
    w = np.ones_like(y) if weights is None else weights
    sw = np.sqrt(w)
    beta, *_ = np.linalg.lstsq(x * sw[:, None], y * sw, rcond=None)
    if robust:
        fit = optimize.least_squares(lambda b: (y - x @ b) * sw, beta, loss="huber", f_scale=0.15)
        beta = fit.x
    return beta


def estimates(y, x, labels, robust=False):
    """{pooled, within, across}: the slopes (k, m[, c]) of each estimator."""
    ones = np.ones((y.size, 1))
    pooled = _solve(y, np.hstack([x, ones]), robust=robust)[:-1]
    within = _solve(_demean(y, labels), _demean(x, labels), robust=robust)
    my, count = _means(y, labels)
    mx, _ = _means(x, labels)
    keep = count > 0
    across = _solve(my[keep], np.hstack([mx[keep], np.ones((keep.sum(), 1))]), weights=count[keep].astype(float),
                    robust=robust)[:-1]
    return {"pooled": pooled, "within": within, "across": across}


def bootstrap(y, x, labels, robust, draws=DRAWS, seed=33):
    """2.5 and 97.5 percentiles of each estimator's slopes, blocks resampled with replacement."""
    rng = np.random.default_rng(seed)
    n = labels.max() + 1
    members = np.split(np.argsort(labels, kind="stable"), np.cumsum(np.bincount(labels, minlength=n))[:-1])
    samples = {"pooled": [], "within": [], "across": []}
    for _ in range(draws):
        pick = rng.integers(0, n, n)
        index = np.concatenate([members[b] for b in pick])
        relabel = np.repeat(np.arange(n), [members[b].size for b in pick])
        for name, value in estimates(y[index], x[index], relabel, robust).items():
            samples[name].append(value)
    return {name: np.percentile(np.array(v), [2.5, 97.5], axis=0) for name, v in samples.items()}


def variance_share(values, labels):
    """Share of the variance of values between blocks (1 - within variance / total variance)."""
    return 1.0 - np.var(_demean(values, labels)) / np.var(values)


def part1(draws=DRAWS):
    rows = read_rows()
    print("### 1. The spin-speed exponent within sessions and across them (the shared TrackMan file)\n")
    print(f"- kept rows (validation.impact.shots' filter): {rows['spin'].size}; ball settings: "
          + ", ".join(f"{b} {c}" for b, c in zip(*np.unique(rows['ball'], return_counts=True))))
    print("- log spin = a + k log V + m log sin(spin loft) [+ c h]; V club speed, spin loft = dynamic loft - attack "
          "angle, h strike height [mm]; 95 % intervals: bootstrap over blocks, "
          f"{draws} draws\n")
    print("| inputs | block B (rows) | blocks | rows | club speed variance between blocks | fit | k pooled | "
          "k within blocks [95 %] | k across blocks [95 %] | m within | c within [1/mm] |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    results = {}
    for with_height in (False, True):
        y, x, mask = design(rows, with_height)
        sub = {k: v[mask] for k, v in rows.items()}
        for size in BLOCKS:
            labels = np.unique(blocks_of(sub, size), return_inverse=True)[1]
            share = variance_share(np.log(sub["speed"]), labels)
            for robust in (False, True):
                est = estimates(y[mask], x[mask], labels, robust)
                ci = bootstrap(y[mask], x[mask], labels, robust, draws=draws if not robust else draws // 4)
                results[(with_height, size, robust)] = (est, ci, labels)
                c = f"{est['within'][2]:+.4f}" if with_height else "-"
                print(f"| {'V, spin loft, h' if with_height else 'V, spin loft'} | {size} | {labels.max() + 1} | "
                      f"{mask.sum()} | {100 * share:.0f} % | {'Huber' if robust else 'OLS'} | "
                      f"{est['pooled'][0]:.2f} [{ci['pooled'][0][0]:.2f}, {ci['pooled'][1][0]:.2f}] | "
                      f"{est['within'][0]:.2f} [{ci['within'][0][0]:.2f}, {ci['within'][1][0]:.2f}] | "
                      f"{est['across'][0]:.2f} [{ci['across'][0][0]:.2f}, {ci['across'][1][0]:.2f}] | "
                      f"{est['within'][1]:.2f} | {c} |")
    y, x, mask = design(rows, False)
    sub = {k: v[mask] for k, v in rows.items()}
    print("\nThe same fits (OLS) with the spin-loft exponent held at 1 (every model's law: spin ~ sin(spin loft) at a "
          "fixed speed), and split by club speed (blocks kept, the rows of each band alone):\n")
    print("| rows | block B | k pooled | k within [95 %] | k across [95 %] |")
    print("|---|---|---|---|---|")
    for size in (10, 25, 50):
        labels = np.unique(blocks_of(sub, size), return_inverse=True)[1]
        for name, keep, fixed in (("all, m = 1", np.ones(labels.size, bool), True),
                                  ("< 95 mph, m fitted", sub["speed"] < 95.0, False),
                                  (">= 95 mph, m fitted", sub["speed"] >= 95.0, False)):
            lab = np.unique(labels[keep], return_inverse=True)[1]
            yy = y[mask][keep] - (x[mask][keep][:, 1] if fixed else 0.0)
            xx = x[mask][keep][:, :1] if fixed else x[mask][keep]
            est = estimates(yy, xx, lab)
            ci = bootstrap(yy, xx, lab, False, draws=draws // 2)
            print(f"| {name} ({keep.sum()}) | {size} | {est['pooled'][0]:.2f} | {est['within'][0]:.2f} "
                  f"[{ci['within'][0][0]:.2f}, {ci['within'][1][0]:.2f}] | {est['across'][0]:.2f} "
                  f"[{ci['across'][0][0]:.2f}, {ci['across'][1][0]:.2f}] |")
    labels = np.unique(blocks_of(sub, 25), return_inverse=True)[1]
    spread = np.std(_demean(x[mask], labels), axis=0)
    print(f"\n- spread within blocks of 25 (standard deviation): log V {spread[0]:.3f} (about "
          f"{100 * spread[0]:.1f} % of club speed), log sin(spin loft) {spread[1]:.3f}. A club-speed reading error "
          "of 1 % (an assumption, not a TrackMan figure) would lower the within slope by "
          f"{100 * 0.01**2 / spread[0]**2:.0f} % (attenuation var(error) / var(within)); errors in the spin loft "
          "(dynamic loft and attack angle are each read to about a degree on a 13-degree spin loft) attenuate m "
          "and, through its correlation with V, move k.")
    return results


#: the flexing face, held at the middle of the plate model's range (docs/models.md, "The face flexing behind the
#: contact": a clamped plate's first mode 3.5-5.1 kHz, modal mass 9.7-13.9 g; a model output, not a measurement)
#: face_frequency is an angular frequency [rad/s] when bare (models._common.face_frequency_field): 2 pi f
FACE = {"face_frequency": 2.0 * math.pi * 4300.0, "face_modal_mass": 0.0118}
#: the face sized by the Rules' COR limit (docs/models.md: 6.88 kHz at 10.9 g, a model output), with the hysteretic
#: normal law, the one under which a yielding face can return energy (under adjusted_speed it only takes energy)
FACE_COR = {"face_frequency": 2.0 * math.pi * 6880.0, "face_modal_mass": 0.0109, "inelastic": "hysteretic"}


def part2_forms():
    from validation.impact.rate_laws import Form

    fitted = ("e_ball", "friction")
    return [
        (Form("hertz_mindlin, strike at the face centre", "hertz_mindlin", {}, fitted), False),
        (Form("hertz_mindlin, 3-D head, measured strike (gear effect)", "hertz_mindlin", {}, fitted), True),
        (Form("hertz_mindlin + flexing face 4.3 kHz, 11.8 g (adjusted_speed law), measured strike", "hertz_mindlin",
              FACE, fitted), True),
        (Form("hertz_mindlin, hysteretic law, rigid face, measured strike", "hertz_mindlin",
              {"inelastic": "hysteretic"}, fitted), True),
        (Form("hertz_mindlin, hysteretic law + flexing face at the COR limit 6.88 kHz, 10.9 g, measured strike",
              "hertz_mindlin", FACE_COR, fitted), True),
        (Form("hertz_mindlin_lever (compression lever), measured strike", "hertz_mindlin", {},
              fitted + ("compression_lever",)), True),
    ]


def part2(sample):
    """Section 2: each mechanism alone, fitted on one speed band and tested on the other (rows with a location)."""
    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.shots import bands, load

    table, _ = load()
    rows = read_rows()
    located = {int(p) + 3 for p, h in zip(rows["position"], rows["height"]) if np.isfinite(h)}
    lines = np.array([int(label.split()[-1]) for label in table.labels])
    table = table.subset(np.flatnonzero([line in located for line in lines]))
    slow, fast = bands(table)
    inputs = table_inputs(table)
    centred_table = attrs_evolve_strike(table)
    centred = table_inputs(centred_table)
    bounds = dict(rl.BOUNDS)
    lam = rl.lever_bound()
    bounds["compression_lever"] = (0.0, lam, min(0.05, lam / 2), rl.BOUNDS["compression_lever"][3])
    rng = np.random.default_rng(33)
    print("\n### 2. Mechanisms with a time or length scale, each alone: fitted on one band, tested on the other\n")
    print(f"- rows with the impact location: {table.size}; < 95 mph {slow.sum()}, > 100 mph {fast.sum()}; training: "
          f"a seeded subsample of {sample} rows of the training band (validation.impact.rate_laws.fit: e_ball and "
          f"friction bounded as there, lever <= {lam:.3f}); testing: every located row of the other band\n")
    print("| form | fitted on -> tested on | fitted parameters (at bound) | spin median abs err % | spin median err % "
          "| ball speed median abs err % | regression k V sin(spin loft), same training rows: spin median abs err % |"
          " form minus regression [points] |")
    print("|---|---|---|---|---|---|---|---|")
    summary = {}
    for label, train_rows, test_rows, train, test in rl.band_folds(table, slow, fast, sample, rng):
        predicted, k = rl.regression(train, test)
        base = rl.spin_error(predicted, test)
        summary.setdefault("regression", []).append(base)
        boosted = rl.boosting(train, test)
        if boosted is not None:
            boost = rl.spin_error(boosted, test)
            summary.setdefault("boosting", []).append(boost)
        for form, strike in part2_forms():
            source = inputs if strike else centred
            train_in, test_in = rl.take(source, train_rows, table.size), rl.take(source, test_rows, table.size)
            values, at_bound = rl.fit(form, train_in, train.measured, bounds)
            e = rl.errors(rl.run(form, values, test_in), test.measured)
            med = 100 * np.nanmedian(np.abs(e["spin"]))
            summary.setdefault(form.name, []).append(med)
            summary.setdefault((form.name, "values"), values)
            cells = ", ".join(f"{n} {v:.4g}" for n, v in values.items())
            flag = f" (at bound: {', '.join(at_bound)})" if at_bound else ""
            print(f"| {form.name} | {label} | {cells}{flag} | {med:.1f} | {100 * np.nanmedian(e['spin']):+.1f} | "
                  f"{100 * np.nanmedian(np.abs(e['speed'])):.2f} | {base:.1f} (k = {k * rl.RPM / (1 / 0.44704):.1f} "
                  f"rpm/mph) | {med - base:+.1f} |")
    print("\n| form | held-out spin median abs err %, < 95 -> > 100 and > 100 -> < 95 | beats the regression on both? "
          "| spin-speed exponent k at the PGA / LPGA driver delivery (fitted on < 95 mph; strike at the centre) |")
    print("|---|---|---|---|")
    base = summary["regression"]
    for form, _ in part2_forms():
        med = summary[form.name]
        ks = rl.exponent(form, summary[(form.name, "values")])
        both = "yes" if all(m < b for m, b in zip(med, base)) else "no"
        print(f"| {form.name} | {med[0]:.1f} / {med[1]:.1f} | {both} | {ks[0]:.3f} / {ks[1]:.3f} |")
    print(f"| regression k V sin(spin loft) | {base[0]:.1f} / {base[1]:.1f} | - | 1.000 / 1.000 |")
    if "boosting" in summary:
        boost = summary["boosting"]
        print("| gradient boosting (scikit-learn, 7 delivery and strike inputs), same training rows | "
              f"{boost[0]:.1f} / {boost[1]:.1f} | - | n/a |")
    gear_and_face(rl)
    return summary


def gear_and_face(rl):
    """The model's vertical gear effect and flexing face at the PGA driver delivery (one row; model outputs)."""
    import attrs

    from impactlab.data.sessions.shots import table_inputs

    table = rl.tour().subset([0])
    plain = rl.Form("hertz_mindlin", "hertz_mindlin", {}, ())
    values = {"e_ball": 0.742}
    spins = []
    for high in (-0.010, 0.0, 0.010):
        delivery = dict(table.delivery, strike_high=np.full(1, high), strike_toe=np.zeros(1))
        spins.append(float(rl.run(plain, values, table_inputs(attrs.evolve(table, delivery=delivery)))["spin_rate"][0]))
    slope = (math.log(spins[2]) - math.log(spins[0])) / 20.0
    print(f"\n- the model's vertical gear effect (hertz_mindlin, e_ball 0.742, the PGA driver delivery, the measured "
          f"dynamic loft held at the contact point): spin {spins[0] * rl.RPM:.0f} / {spins[1] * rl.RPM:.0f} / "
          f"{spins[2] * rl.RPM:.0f} rpm at strike height -10 / 0 / +10 mm, d log spin / dh = {slope:+.4f} per mm; "
          "the file's within-block slope c at fixed measured loft is -0.0001 to -0.0024 per mm (section 1).")
    print("\n| flexing face (hertz_mindlin, e_ball 0.742, PGA driver delivery; 3.5-5.1 kHz the plate model, "
          "6.88 / 6.47 kHz the faces at the COR limit: model outputs, docs/models.md) | ball speed [m/s] | "
          "spin [rpm] |")
    print("|---|---|---|")
    inputs = table_inputs(table)
    for law in ("adjusted_speed", "hysteretic"):
        out = rl.run(rl.Form("rigid", "hertz_mindlin", {"inelastic": law}, ()), values, inputs)
        print(f"| rigid face, gain 0.083, {law} law | {out['ball_speed'][0]:.2f} | "
              f"{out['spin_rate'][0] * rl.RPM:.0f} |")
        for frequency, mass in ((3500.0, 0.0097), (3500.0, 0.0139), (5100.0, 0.0097), (5100.0, 0.0139),
                                (6880.0, 0.0109), (6470.0, 0.0126)):
            options = {"face_frequency": 2.0 * math.pi * frequency, "face_modal_mass": mass, "inelastic": law}
            out = rl.run(rl.Form("flex", "hertz_mindlin", options, ()), values, inputs)
            print(f"| {frequency / 1000:.2f} kHz, {mass * 1000:.1f} g, {law} law | {out['ball_speed'][0]:.2f} | "
                  f"{out['spin_rate'][0] * rl.RPM:.0f} |")
    print(f"| measured (TrackMan PGA driver row) | {table.measured['ball_speed'][0]:.2f} | "
          f"{table.measured['spin_rate'][0] * rl.RPM:.0f} |")


def part3(sample):
    """Section 3: the face at the COR limit on every kept row (round 1's protocol; strike at the centre where the row
    has no location), beside its rigid face, the plain model and the regression fitted on the same rows."""
    from impactlab.data.sessions.shots import table_inputs
    from validation.impact import rate_laws as rl
    from validation.impact.shots import bands, load

    table, _ = load()
    slow, fast = bands(table)
    inputs = table_inputs(table)
    fitted = ("e_ball", "friction")
    forms = [rl.Form("hertz_mindlin (today's)", "hertz_mindlin", {}, fitted),
             rl.Form("hertz_mindlin, hysteretic law, rigid face", "hertz_mindlin", {"inelastic": "hysteretic"}, fitted),
             rl.Form("hertz_mindlin, hysteretic law + face at the COR limit", "hertz_mindlin", FACE_COR, fitted)]
    rng = np.random.default_rng(33)
    print("\n### 3. The face at the COR limit on every kept row (round 1's protocol, training subsample "
          f"{sample})\n")
    print("| form | fitted on -> tested on | fitted parameters (at bound) | spin median abs err % | spin median err % "
          "| "
          "ball speed median abs err % | regression, same rows: spin median abs err % |")
    print("|---|---|---|---|---|---|---|")
    for label, train_rows, test_rows, train, test in rl.band_folds(table, slow, fast, sample, rng):
        predicted, _ = rl.regression(train, test)
        base = rl.spin_error(predicted, test)
        for form in forms:
            values, at_bound = rl.fit(form, rl.take(inputs, train_rows, table.size), train.measured, rl_bounds(rl))
            e = rl.errors(rl.run(form, values, rl.take(inputs, test_rows, table.size)), test.measured)
            cells = ", ".join(f"{n} {v:.4g}" for n, v in values.items())
            flag = f" (at bound: {', '.join(at_bound)})" if at_bound else ""
            print(f"| {form.name} | {label} | {cells}{flag} | {100 * np.nanmedian(np.abs(e['spin'])):.1f} | "
                  f"{100 * np.nanmedian(e['spin']):+.1f} | {100 * np.nanmedian(np.abs(e['speed'])):.2f} | "
                  f"{base:.1f} |")


def part4(sample):
    """Section 4: the face at the COR limit fitted on the whole file, predicting TrackMan's tour tables and the wedge
    ball-type test without refitting (validation.impact.rate_laws, section 5's protocol), beside hertz_mindlin."""
    from impactlab.data.sessions.shots import table_inputs
    from impactlab.data.validation.observations import cover_effect
    from validation.impact import rate_laws as rl
    from validation.impact.shots import load

    table, _ = load()
    inputs = table_inputs(table)
    rows = rl.whole_file_rows(table.size, sample)
    table_t = rl.tour()
    inputs_t = table_inputs(table_t)
    wedge = rl.wedge_test()
    print(f"\n### 4. Fitted on {sample} rows of the whole file, predicting the tour tables and the wedge test (not "
          "refitted)\n")
    print("| form | fitted | " + " | ".join(f"{label}: spin %, ball speed %, launch deg" for label in table_t.labels)
          + " | exponent k (PGA / LPGA driver delivery) | wedge urethane/ionomer - 1 (measured +48 %) |")
    print("|---|---|" + "---|" * table_t.size + "---|---|")
    fitted = ("e_ball", "friction")
    for form in (rl.Form("hertz_mindlin", "hertz_mindlin", {}, fitted),
                 rl.Form("hertz_mindlin_face (hysteretic, face at the COR limit)", "hertz_mindlin", FACE_COR, fitted)):
        values, at_bound = rl.fit(form, rl.take(inputs, rows, table.size), table.subset(rows).measured, rl_bounds(rl))
        e = rl.errors(rl.run(form, values, inputs_t), table_t.measured)
        cells = [f"{100 * e['spin'][i]:+.1f}, {100 * e['speed'][i]:+.2f}, {e['launch'][i]:+.2f}"
                 for i in range(table_t.size)]
        ks = rl.exponent(form, values)
        cover = cover_effect(rl.model_of(form, values), wedge,
                             inputs_hook=lambda i, v=values, f=form: rl.apply(i, v, f))
        fit_cells = ", ".join(f"{n} {v:.4g}" for n, v in values.items())
        flag = f" (at bound: {', '.join(at_bound)})" if at_bound else ""
        print(f"| {form.name} | {fit_cells}{flag} | " + " | ".join(cells) + f" | {ks[0]:.3f} / {ks[1]:.3f} | "
              f"{100 * cover['predicted']:+.1f} % |")


def rl_bounds(rl):
    return dict(rl.BOUNDS)


def attrs_evolve_strike(table):
    """The table with every strike moved to the face centre (the 1-D-like reference of the gear effect)."""
    import attrs

    delivery = dict(table.delivery, strike_toe=np.zeros(table.size), strike_high=np.zeros(table.size))
    return attrs.evolve(table, delivery=delivery)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="section 2 on training subsamples of 200 rows")
    parser.add_argument("--part", type=int, choices=(1, 2, 3, 4),
                        help="one section only (3 and 4: only when asked)")
    args = parser.parse_args(argv)
    started = time.time()
    # the file's rows hold strikes and speeds beyond a study's plausible range: measured data, computed as given
    warnings.filterwarnings("ignore", message=".*is unusual for golf.*")
    warnings.filterwarnings("ignore", category=RuntimeWarning)
    if args.part in (None, 1):
        part1()
    if args.part in (None, 2):
        part2(200 if args.quick else 400)
    if args.part == 3:
        part3(200 if args.quick else 400)
    if args.part == 4:
        part4(200 if args.quick else 400)
    print(f"\n(elapsed {time.time() - started:.0f} s)")


if __name__ == "__main__":
    main()
