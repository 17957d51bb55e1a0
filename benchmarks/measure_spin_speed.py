"""Issue 21: driver spin against club speed, the structural obstacle of the Goal (docs/validation.md, "Driver spin
against club speed: what controlled data say").

    .venv/bin/python benchmarks/measure_spin_speed.py     (about 10 s once numba has compiled the kernels)

Measured (TrackMan 2023 tour averages, trackman_tour.yaml; TrackMan's published spin lofts, docs/ball_laws.py ROWS),
the two tours' drivers spin alike (PGA 2545 rpm at 115 mph, LPGA 2506 rpm at 96 mph) at nearly the same spin loft
(14.7 and 15.0 deg). Written as spin ~ v^k sin(spin loft), the two rows say k = 0.19 for drivers and k = 0.68 for the
6-irons (94 and 80 mph); read with dynamic loft minus attack angle (13.7 and 12.7 deg), k = -0.33 and 0.77. That k is
APPARENT: the two tours differ in more than club speed (strike, head rotation,
shaft, ball fitting), so it is not a measurement of how one delivery's spin depends on its speed. No controlled
measurement of that (one club, one strike, one spin loft, several speeds) with its delivery was found in the stored
corpora (docs/validation.md lists what was searched).

What this script measures, nothing fitted (every number is a model output):

1. Each model form's exponent k at a fixed delivery: the row's attack angle, dynamic loft and strike held, the club
   speed moved from the LPGA row's to the PGA row's (96 -> 115 mph drivers, 80 -> 94 mph 6-irons), so k =
   ln(spin ratio) / ln(speed ratio); and the model's PGA/LPGA driver spin ratio on the rows as shipped (measured
   2545 / 2506 = 1.016).
2. What a missing mechanism would have to do on the scale-free forms (k = 1 exactly: a Hertz-Mindlin-Coulomb impact
   with a constant e has no speed scale, Maw, Barber & Fawcett 1976): the share x = 1 - measured / predicted of each
   row's spin it must remove, and how that share must grow with the club speed (x ~ v^p) between the tours.
3. Question A (the deliveries): how far apart the tours' strike heights, or their head rotations before impact, must
   be for the model to give the measured PGA/LPGA driver ratio, the LPGA driver held centred and unrotated.
4. Question B (a speed-dependent ball): a linear restitution law e(v_n) = 0.787 + s (v_n - 40 m/s) feeding the
   cover's rolling law (alpha = 1 - e_ball^2, so alpha grows with the impact speed); s swept over the calibration's
   bounds [-0.01, 0] s/m. The e at 40 m/s stays the preset's (fitted on these rows, as shipped). What the slope does
   to the driver ratio, to each row's ball speed and spin, and to the smash factors, which the rows also measure
   (PGA 171/115 = 1.487, LPGA 143/96 = 1.490): a held-out check of any slope, since smash factor is not what is
   being fixed.
5. The same slope as a fifth parameter of the Goal's AFTER calibration, fitted on one tour and tested on the other.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import attrs
import numpy as np
from scipy import optimize

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "docs"))

from ball_laws import ROWS, per_unit  # noqa: E402  (the tour rows with TrackMan's spin lofts, measured)

from impactlab.data.fit.calibration import DEFAULT_PARAMETERS, calibrate, cross_validate  # noqa: E402
from impactlab.data.shot_report import shot_table  # noqa: E402
from impactlab.data.sessions.shots import errors_by_source, predict, shot_errors, table_inputs  # noqa: E402
from impactlab.model.registry import get_model  # noqa: E402

MM = 1e-3
MPH = 0.44704
RPM = 60.0 / (2.0 * math.pi)
FACE = {"face_frequency": "6.88 kHz", "face_modal_mass": "10.9 g"}
CORE = {"core_radius": "19.05 mm", "core_shear_modulus": "10 MPa", "core_specific_gravity": 1.15}
ROLL = {"rolling_hysteresis": "restitution"}
#: the model forms of issue 21 (docs/models.md), each as the Goal tables use it
CONFIGURATIONS = [
    ("rigid_coulomb", "rigid_coulomb", {}),
    ("rigid_coulomb + rolling", "rigid_coulomb", ROLL),
    ("rigid_coulomb + friction_law adhesion", "rigid_coulomb", {"friction_law": "adhesion"}),
    ("hertz_mindlin", "hertz_mindlin", {}),
    ("hertz_mindlin + rolling", "hertz_mindlin", ROLL),
    ("hertz_mindlin hysteretic", "hertz_mindlin", {"inelastic": "hysteretic"}),
    ("hertz_mindlin + friction_law adhesion", "hertz_mindlin", {"friction_law": "adhesion"}),
    ("hertz_mindlin + core (G 10 MPa)", "hertz_mindlin", CORE),
    ("hertz_mindlin hysteretic + face (COR limit)", "hertz_mindlin", {"inelastic": "hysteretic", **FACE}),
    ("hertz_mindlin hysteretic + rolling + face", "hertz_mindlin", {"inelastic": "hysteretic", **ROLL, **FACE}),
    ("maw", "maw", {}),
    ("maw + rolling", "maw", ROLL),
]
#: the configurations of questions A and B (the Goal's uncalibrated forms)
SHORT = ("rigid_coulomb", "rigid_coulomb + rolling", "hertz_mindlin", "hertz_mindlin + rolling",
         "hertz_mindlin hysteretic + rolling + face")
SLOPES = (0.0, -0.001, -0.002, -0.004, -0.006, -0.01)  # de/dv [s/m]; the calibration's bounds are [-0.01, 0]
DEPTH = 0.0423  # the driver preset's CG behind the face [m]: a toe-axis rate w turns the face up by atan(w d / v)


def tour_table():
    """TrackMan's tour rows, loft at the contact point (TrackMan's definition)."""
    return attrs.evolve(shot_table("trackman_tour"), loft_at="contact")


def with_delivery(table, **changes):
    """The table with some delivery columns replaced (SI arrays)."""
    return attrs.evolve(table, delivery=dict(table.delivery, **{k: np.asarray(v, float) for k, v in changes.items()}))


def rows(table, name):
    return [i for i, label in enumerate(table.labels) if label.startswith(name)]


def spins(model, table, ball=None, hook=None):
    """Predicted spin [rpm] and ball speed [m/s] of every row."""
    inputs = table_inputs(table, ball)
    if hook is not None:
        inputs = hook(inputs)
    out = predict(model, inputs)
    return np.asarray(out["spin_rate"]) * RPM, np.asarray(out["ball_speed"])


def apparent_exponents(reading="3-D"):
    """k of spin ~ v^k sin(spin loft) between the tours, from the measured rows (not controlled): with TrackMan's
    published 3-D spin lofts (``"3-D"``) or with dynamic loft minus attack angle (``"2-D"``, the shipped rows)."""
    by = {row[0]: row for row in ROWS}
    out = {}
    for club in ("driver", "6-iron"):
        p, lp = by[f"PGA {club}"], by[f"LPGA {club}"]
        loft_p, loft_l = (p[6], lp[6]) if reading == "3-D" else (p[4] - p[3], lp[4] - lp[3])
        unit_ratio = per_unit(p[5], p[2], loft_p) / per_unit(lp[5], lp[2], loft_l)
        out[club] = 1.0 + math.log(unit_ratio) / math.log(p[2] / lp[2])
    return out


def exponent_table(table):
    """Per configuration: k at each row's delivery (speed moved from the LPGA to the PGA row's), and the model's
    PGA/LPGA driver spin ratio on the rows as shipped."""
    pga, lpga = rows(table, "PGA"), rows(table, "LPGA")
    speed = table.delivery["club_speed"]
    slow = speed.copy()
    fast = speed.copy()
    for p, lp in zip(pga, lpga):  # PGA and LPGA rows of the same club, in the same order
        slow[p], fast[lp] = speed[lp], speed[p]
    slow_table, fast_table = with_delivery(table, club_speed=slow), with_delivery(table, club_speed=fast)
    print("\n### 1. The exponent k of spin ~ v^k at a fixed delivery (model output; nothing fitted)\n")
    for reading, what in (("3-D", "TrackMan's published spin lofts"), ("2-D", "dynamic loft minus attack angle")):
        apparent = apparent_exponents(reading)
        print(f"Apparent k between the tours (measured rows, deliveries differ; {what}): drivers "
              f"{apparent['driver']:.2f}, 6-irons {apparent['6-iron']:.2f}.")
    print()
    print("| configuration | " + " | ".join(f"k at the {label} delivery" for label in table.labels)
          + " | PGA/LPGA driver spin (rows as shipped; measured 1.016) |")
    print("|---|" + "---|" * (table.size + 1))
    results = {}
    for name, model_name, options in CONFIGURATIONS:
        model = get_model(model_name)(**options)
        s_slow, _ = spins(model, slow_table)
        s_fast, _ = spins(model, fast_table)
        s_rows, _ = spins(model, table)
        k = np.log(s_fast / s_slow) / np.log(fast / slow)
        d_p, d_l = rows(table, "PGA driver")[0], rows(table, "LPGA driver")[0]
        ratio = s_rows[d_p] / s_rows[d_l]
        results[name] = (k, ratio)
        print(f"| {name} | " + " | ".join(f"{v:.3f}" for v in k) + f" | {ratio:.3f} |")
    return results


def ratio_with(model, table, hook=None, **delivery):
    s, _ = spins(model, with_delivery(table, **delivery) if delivery else table, hook=hook)
    return s[rows(table, "PGA driver")[0]] / s[rows(table, "LPGA driver")[0]], s


def deliveries(table):
    """Question A: the strike or head-rotation difference between the tours that gives the measured ratio."""
    measured = ROWS[0][5] / ROWS[1][5]
    d_p, d_l = rows(table, "PGA driver")[0], rows(table, "LPGA driver")[0]
    target = {d_p: ROWS[0][5], d_l: ROWS[1][5]}
    print("\n### 3. Question A: the delivery difference the model needs (LPGA driver centred, no rotation)\n")
    print("| configuration | PGA driver strike up the face for the measured ratio [mm] | each driver's own strike "
          "for its measured spin, PGA / LPGA [mm] | driver launch error PGA / LPGA [deg]: centred -> at those "
          "strikes | PGA driver's toe-axis head rotation for the measured ratio [deg of face-centre over CG "
          "attack] |")
    print("|---|---|---|---|---|")
    for name, model_name, options in CONFIGURATIONS:
        if name not in SHORT:
            continue
        model = get_model(model_name)(**options)

        def strike_gap(mm, index=None):
            high = np.zeros(table.size)
            high[d_p if index is None else index] = mm * MM
            ratio, s = ratio_with(model, table, strike_high=high)
            return ratio - measured if index is None else s[index] / target[index] - 1.0

        def root(f, lo, hi):
            try:
                return optimize.brentq(f, lo, hi, xtol=1e-3)
            except ValueError:
                return None

        def solve(f, lo, hi):
            value = root(f, lo, hi)
            return f"none in [{lo:+.0f}, {hi:+.0f}]" if value is None else f"{value:+.1f}"

        strike = solve(strike_gap, -20.0, 25.0)
        highs = [root(lambda mm, i=i: strike_gap(mm, i), -20.0, 25.0) for i in (d_p, d_l)]
        own = " / ".join("none" if h is None else f"{h:+.1f}" for h in highs)
        launch = "n/a"
        if None not in highs:
            high = np.zeros(table.size)
            high[[d_p, d_l]] = np.asarray(highs) * MM

            def launches(t):
                return shot_errors(predict(model, table_inputs(t)), t)["launch angle [deg]"][[d_p, d_l]]
            before, after = launches(table), launches(with_delivery(table, strike_high=high))
            launch = f"{before[0]:+.2f} / {before[1]:+.2f} -> {after[0]:+.2f} / {after[1]:+.2f}"

        def rotation_gap(deg):
            def hook(inputs):
                inputs = dict(inputs)
                w = np.zeros(table.size)
                w[d_p] = math.tan(math.radians(deg)) / DEPTH * inputs["speed"][d_p]
                inputs["head_rotation_toe"] = w
                return inputs
            return ratio_with(model, table, hook=hook)[0] - measured

        rotation = solve(rotation_gap, -6.0, 10.0)
        print(f"| {name} | {strike} | {own} | {launch} | {rotation} |")


def restitution_slopes(table):
    """Question B: a speed-dependent ball restitution feeding the rolling law, not fitted."""
    measured_ratio = ROWS[0][5] / ROWS[1][5]
    m = table.measured
    smash_measured = m["ball_speed"] / table.delivery["club_speed"]
    d_p, d_l = rows(table, "PGA driver")[0], rows(table, "LPGA driver")[0]
    print("\n### 4. Question B: a ball restitution falling with the impact speed, feeding the rolling law "
          "(alpha = 1 - e_ball^2; e(40 m/s) = 0.787 kept; nothing fitted)\n")
    print(f"Measured smash factors: PGA driver {smash_measured[d_p]:.3f}, LPGA driver {smash_measured[d_l]:.3f} "
          f"(PGA/LPGA {smash_measured[d_p] / smash_measured[d_l]:.3f}); driver spin PGA/LPGA {measured_ratio:.3f}.\n")
    print("| configuration | de/dv [s/m] | e_ball PGA / LPGA driver | PGA/LPGA driver spin | PGA/LPGA driver smash "
          "| " + " | ".join(f"{label}: ball speed %, spin %" for label in table.labels)
          + " | spin RMS PGA / LPGA % | ball speed RMS PGA / LPGA % |")
    print("|---|---|---|---|---|" + "---|" * table.size + "---|---|")
    for name, model_name, options in CONFIGURATIONS:
        if name not in ("rigid_coulomb + rolling", "hertz_mindlin + rolling",
                        "hertz_mindlin hysteretic + rolling + face"):
            continue
        model = get_model(model_name)(**options)
        for slope in SLOPES:
            ball = {"preset": "urethane_tour", "restitution": {"law": "linear", "value": 0.787,
                                                                 "reference_speed": "40 m/s",
                                                                 "slope": f"{slope} s/m"}}
            inputs = table_inputs(table, ball)
            e_ball = inputs["restitution"] - inputs.get("club_restitution_gain", 0.0)
            predicted = predict(model, inputs)
            errors = shot_errors(predicted, table)
            by_source = errors_by_source(errors, table)
            s = np.asarray(predicted["spin_rate"])
            smash = np.asarray(predicted["ball_speed"]) / table.delivery["club_speed"]
            cells = [f"{errors['ball_speed [%]'][i]:+.2f}, {errors['spin [%]'][i]:+.1f}" for i in range(table.size)]
            pga, lpga = by_source["TrackMan PGA Tour"], by_source["TrackMan LPGA Tour"]
            print(f"| {name} | {slope:g} | {e_ball[d_p]:.3f} / {e_ball[d_l]:.3f} | {s[d_p] / s[d_l]:.3f} | "
                  f"{smash[d_p] / smash[d_l]:.3f} | " + " | ".join(cells)
                  + f" | {pga['spin [%]']:.1f} / {lpga['spin [%]']:.1f} | {pga['ball_speed [%]']:.2f} / "
                  f"{lpga['ball_speed [%]']:.2f} |")


def fitted_slope(table):
    """Question B, calibrated: the Goal's AFTER configuration (loft at contact, rolling, the leave-one-source-out
    calibration of friction, tangential loss, restitution and face gain), with and without the restitution slope
    as a fifth parameter; each tour's errors from the fit on the other tour only."""
    print("\n### 5. Question B, calibrated: AFTER with the restitution slope fitted (leave one source out)\n")
    print("| configuration | fitted on | de/dv [s/m] | e(40 m/s) | held-out source | ball speed % | launch deg "
          "| spin % |")
    print("|---|---|---|---|---|---|---|---|")
    for name, model_name, options in CONFIGURATIONS:
        if name not in ("rigid_coulomb + rolling", "hertz_mindlin + rolling"):
            continue
        model = get_model(model_name)(**options)
        base = [p for p in DEFAULT_PARAMETERS if p != "tangential_loss" or "tangential_loss" in model.optional_inputs]
        for names in (base, [*base, "restitution_slope"]):
            full = calibrate(model, table, names)
            held = cross_validate(model, table, names, by="source", start=dict(zip(full.parameters, full.values)))
            sources = list(table.sources)
            for rows_out, calibration in zip(held["folds"], held["calibrations"]):
                values = dict(zip(calibration.parameters, calibration.values))
                source = sources[int(np.asarray(rows_out)[0])]
                trained = " + ".join(dict.fromkeys(s for s in sources if s != source))
                rms = held["by_source"][source]
                bound = ", ".join(p for p, b in zip(calibration.parameters, calibration.at_bound) if b)
                print(f"| {name}{' + slope' if len(names) > len(base) else ''} | {trained} | "
                      f"{values.get('restitution_slope', 0.0):+.4f} | {values['restitution']:.3f} | {source} | "
                      f"{rms['ball_speed [%]']:.2f} | {rms['launch angle [deg]']:.2f} | {rms['spin [%]']:.1f}"
                      f"{' (at bound: ' + bound + ')' if bound else ''} |")


def required_share(table):
    """What a missing mechanism would have to do, on the scale-free forms (k = 1): the share x = 1 - measured /
    predicted of each row's predicted spin it must remove, and the exponent p of x ~ v^p between the tours (the
    deliveries taken as the rows give them). A mechanism whose share grows as v^p moves k by -p x / (1 - x)."""
    print("\n### 2. What a missing mechanism would have to remove (scale-free forms, rows as shipped)\n")
    print("| configuration | share x of the predicted spin to remove: " + " / ".join(table.labels)
          + " | p of x ~ v^p, drivers | p, 6-irons |")
    print("|---|---|---|---|")
    measured = table.measured["spin_rate"]
    speed = table.delivery["club_speed"]
    for name, model_name, options in CONFIGURATIONS:
        if options:
            continue
        predicted, _ = spins(get_model(model_name)(**options), table)
        x = 1.0 - measured * RPM / predicted
        p = {}
        for club in ("driver", "6-iron"):
            i, j = rows(table, f"PGA {club}")[0], rows(table, f"LPGA {club}")[0]
            p[club] = math.log(x[i] / x[j]) / math.log(speed[i] / speed[j]) if x[i] * x[j] > 0 else float("nan")
        print(f"| {name} | " + " / ".join(f"{v:+.3f}" for v in x) + f" | {p['driver']:.1f} | {p['6-iron']:.1f} |")


def main() -> None:
    table = tour_table()
    exponent_table(table)
    required_share(table)
    deliveries(table)
    restitution_slopes(table)
    fitted_slope(table)


if __name__ == "__main__":
    main()
