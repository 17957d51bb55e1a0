"""Issue 33, round 6: what the measured data allow for the three goals no model form has met.

    .venv/bin/python -u -m validation.impact.goal_limits            (about 30 s; output: goal_limits_output.md)

Five rounds tried model forms against the issue's goals (docs/validation.md). Three goals stay unmet: held-out spin
within 15 % on both speed bands, the tour tables within 7 % / 1 % / 0.7 deg from a fit to the shared file, and a
16-50 % wedge spin difference between urethane and ionomer covers. This script asks the data, not a model, how far
each goal is reachable. Nothing in it is fitted to a tour row or to the wedge row, and no package model runs in it:
every number is either a measurement (the file, the tables, the wedge test), a learner without physics, or a rigid-
body closed form written out here (Goldsmith's impulse relations for a sphere and a translating face), so the limits
do not depend on the laws they judge.

1. **Held-out spin (goal 1).** Learners of the delivery without physics, fitted on one club-speed band and tested on
   the other as the models were, and the same power law with its level set on the tested rows themselves (an
   oracle no model has): how low a prediction of the file's inputs goes on each band.
2. **The tour tables (goal 3).** (a) The ball speed the Rules' COR limit allows a free driver head at each row's spin
   loft, against the table's ball speed, and the head mass the table's smash factor would need. (b) The file's own
   shots nearest each tour driver's delivery: what a model that fits the file must predict there. (c) The spin-
   speed exponents with which the two tours' driver rows can both lie within 7 %, under one level.
3. **The wedge (goal 4).** The rigid-body friction at which a ball stops sliding on the test's assumed delivery, and
   the ionomer cover friction each end of the goal needs, beside the frictions measured or fitted for the covers.
"""

from __future__ import annotations

import math
import time

import numpy as np

RPM = 60.0 / (2.0 * np.pi)
#: the issue's goals: held-out spin (median |error|), tour spin, tour ball speed, wedge difference
SPIN_GOAL, TOUR_SPIN, TOUR_BALL_SPEED, WEDGE_GOAL = 0.15, 0.07, 0.01, (0.16, 0.50)
#: tracked for at least this fraction of the hang time: the flight measured, outdoors (README beside the file)
TRACKED = 0.9
#: the neighbourhood of a tour row's delivery among the file's rows: club speed [mph], spin loft and attack [deg]
NEAR = {"club_speed": 4.0, "spin_loft": 1.5, "attack_angle": 3.0}
#: face to path within this [deg]: the tour rows' square face
SQUARE = 1.5
#: allowances towards the tour tables' ball speed (section 2a): the shaft's added mass [kg] (rate_laws.BOUNDS: under
#: 3 g, McNally et al. 2020) and a ball lighter than the Rules' 45.93 g maximum [kg] (an allowance, not a measurement)
LENIENT = {"added_mass": 0.003, "ball_mass": 0.0455}
#: the speed of the USGA/R&A COR test [m/s] (Equipment Rules, Part 2, 5a; impactlab.scene.clubs)
COR_TEST_SPEED = 48.8


# -- closed forms (rigid bodies; Goldsmith, Impact, 1960, ch. 2; Stronge, Impact Mechanics, 2000, ch. 2-3) ---------

def free_head_speed_ratio(spin_loft, restitution, ball_mass, head_mass, inertia_factor=0.4):
    """Ball speed over club speed after a rigid sphere is struck by a translating flat face, centred, no face rotation.

    The face (mass ``head_mass`` [kg], no rotation: the centred strike whose normal passes through the head's centre
    of mass) meets the ball at rest at ``spin_loft`` [rad] between its velocity and the face normal. Normal: the
    relative speed is reversed to ``restitution`` times itself; tangential: friction enough to stop the sliding
    (rolling at separation, the largest tangential speed a Coulomb contact gives). Returns |v_ball| / V.

    With the reduced masses 1/m_n = 1/m + 1/M and 1/m_t = 1/m + 1/M + 1/(K m) (K the ball's inertia factor),
    v_n = (1 + e) V cos(a) m_n / m and v_t = V sin(a) m_t / m.
    """
    a = np.asarray(spin_loft, float)
    normal = (1.0 + restitution) * np.cos(a) / (1.0 + ball_mass / head_mass)
    tangential = np.sin(a) / (1.0 + ball_mass / head_mass + 1.0 / inertia_factor)
    return np.hypot(normal, tangential)


def head_mass_for(speed_ratio, spin_loft, restitution, ball_mass, inertia_factor=0.4):
    """The head mass [kg] at which :func:`free_head_speed_ratio` equals ``speed_ratio`` (np.inf if even an immovable
    head falls short: the table's smash factor is then beyond the restitution at any mass)."""
    from scipy.optimize import brentq

    def gap(log_mass):
        ratio = free_head_speed_ratio(spin_loft, restitution, ball_mass, math.exp(log_mass), inertia_factor)
        return ratio - speed_ratio

    if gap(math.log(1e6)) < 0.0:
        return math.inf
    return math.exp(brentq(gap, math.log(1e-3), math.log(1e6), xtol=1e-12))


def rolling_friction(spin_loft, restitution, ball_mass, head_mass, inertia_factor=0.4):
    """The friction coefficient at which the ball stops sliding exactly at separation (the same rigid impact).

    Below it the ball slides throughout and its spin is proportional to mu (spin = mu J_n R / I); at or above it the
    ball leaves rolling and its spin no longer depends on mu. mu_c = J_t* / J_n = tan(a) (1/m + 1/M) /
    ((1 + e) (1/m + 1/M + 1/(K m))).
    """
    inverse_normal = 1.0 / ball_mass + 1.0 / head_mass
    inverse_tangential = inverse_normal + 1.0 / (inertia_factor * ball_mass)
    return np.tan(spin_loft) * inverse_normal / ((1.0 + restitution) * inverse_tangential)


def instantaneous_slip_fraction(friction, spin_loft, restitution, ball_mass, head_mass, speed, inertia_factor=0.4,
                                reference_slip=10.0):
    """The tangential impulse over the rolling one when friction follows the instantaneous slip speed, the rigid
    impact of :func:`free_head_speed_ratio` under Arakawa's friction stress proportional to the sliding speed
    (mu = mu_0 u / u_ref, the law's m = 1 applied at each instant, not once per impact).

    dJ_t = mu(u) dJ_n and du = -dJ_t / m_t give u = u_0 exp(-mu_0 J_n / (m_t u_ref)): the ball never quite rolls,
    and J_t / J_t* = 1 - exp(-mu_0 J_n / (m_t u_ref)) with J_n = (1 + e) m_n V cos(a) at separation. ``speed`` is
    the club speed V [m/s], ``reference_slip`` u_ref [m/s] (impactlab.physics.rate_laws.REFERENCE_SLIP_SPEED)."""
    inverse_normal = 1.0 / ball_mass + 1.0 / head_mass
    inverse_tangential = inverse_normal + 1.0 / (inertia_factor * ball_mass)
    normal_impulse = (1.0 + restitution) * speed * np.cos(spin_loft) / inverse_normal
    return 1.0 - np.exp(-friction * normal_impulse * inverse_tangential / reference_slip)


def exponent_window(speed_ratio, loft_ratio, spin_ratio, loft_exponent, tolerance=TOUR_SPIN):
    """The spin-speed exponents k for which spin = A V^k sin(spin loft)^c can put two rows within ``tolerance``
    (relative) of their measured spins under one level A: (k_min, k_max).

    Two rows fit under one A iff the predicted ratio over the measured one lies within [(1 - t)/(1 + t),
    (1 + t)/(1 - t)]: speed_ratio^k loft_ratio^c / spin_ratio in that interval."""
    low, high = (1.0 - tolerance) / (1.0 + tolerance), (1.0 + tolerance) / (1.0 - tolerance)
    base = loft_exponent * math.log(loft_ratio) - math.log(spin_ratio)
    return ((math.log(low) - base) / math.log(speed_ratio), (math.log(high) - base) / math.log(speed_ratio))


def allowed_restitution(normal_speed, limit: float, slope: float, test_speed: float = 48.8):
    """The head-ball e the Rules allow at ``normal_speed`` [m/s], an upper estimate: ``limit`` at and above the COR
    test's ``test_speed``, raised below it by the ball's COR slope (``slope`` [1/(m/s)], negative: e falls with
    speed), the head's share of the loss held fixed."""
    v = np.asarray(normal_speed, float)
    return limit + slope * np.minimum(v - test_speed, 0.0)


def ball_cor_slope() -> float:
    """de/dv [1/(m/s)] of the ball's COR against a rigid barrier through Chou & Yang's two measured points (1994:
    0.85 at 20 m/s, 0.78 at 45 m/s; rate_laws.CHOU_YANG): negative, the ball is less lively at a faster impact."""
    from validation.impact import rate_laws as rl

    (v1, e1), (v2, e2) = rl.CHOU_YANG
    return (e2 - e1) / (v2 - v1)


def spin_loft_of(delivery: dict) -> float:
    """The 2-D spin loft [rad] of a delivery in SI: dynamic loft less attack angle."""
    return float(delivery["dynamic_loft"] - delivery["attack_angle"])


def oracle_error(predicted, measured) -> float:
    """Median |error| % once the predictions' level is set on the measured rows themselves (their median log
    ratio): the error left by the predictions' shape alone."""
    predicted, measured = np.asarray(predicted, float), np.asarray(measured, float)
    return median_error(predicted * np.exp(np.median(np.log(measured / predicted))), measured)


# -- the file --------------------------------------------------------------------------------------------------------

def tracked_fraction(table, path=None) -> np.ndarray:
    """The fraction of each row's hang time the radar tracked: ``Last data Point - Time`` over ``Carry Flat - Time``
    (NaN where either is missing); at least 0.9 is a measured flight, below 0.1 an indoor or netted shot."""
    from validation.impact.shots import file_columns

    times = file_columns(table, ("Last data Point - Time", "Carry Flat - Time"), float, path)
    with np.errstate(invalid="ignore", divide="ignore"):
        return times["Last data Point - Time"] / times["Carry Flat - Time"]


def neighbours(table, delivery: dict, near: dict = NEAR) -> np.ndarray:
    """Boolean mask of the rows of ``table`` within ``near`` of ``delivery`` (club speed [mph], spin loft and attack
    angle [deg], each a half-width)."""
    from validation.impact import rate_laws as rl
    from validation.impact.shots import MPH

    speed = np.asarray(table.delivery["club_speed"], float) / MPH
    loft = np.degrees(rl.spin_loft(table))
    attack = np.degrees(np.asarray(table.delivery["attack_angle"], float))
    edge = 1e-9  # the half-widths are inclusive, to the rounding of the unit conversions
    return ((np.abs(speed - delivery["club_speed"]) <= near["club_speed"] + edge)
            & (np.abs(loft - delivery["spin_loft"]) <= near["spin_loft"] + edge)
            & (np.abs(attack - delivery["attack_angle"]) <= near["attack_angle"] + edge))


def session_blocks(lines, gap: int = 100) -> np.ndarray:
    """Block labels of rows given their file ``lines`` (ascending): a jump of more than ``gap`` lines starts a new
    block. The file names no session; rows far apart in it are taken as other sessions (a proxy)."""
    lines = np.asarray(lines)
    return np.concatenate([[0], np.cumsum(np.diff(lines) > gap)]) if lines.size else np.zeros(0, int)


def median_interval(values, blocks=None, draws: int = 2000, seed: int = 33) -> tuple[float, float, float]:
    """(median, 2.5 %, 97.5 % of the bootstrap medians), resampling whole ``blocks`` (labels per value) when given:
    shots of one session are not independent draws."""
    values = np.asarray(values, float)
    rng = np.random.default_rng(seed)
    if blocks is None:
        boot = np.median(rng.choice(values, (draws, values.size)), axis=1)
    else:
        members = [values[np.asarray(blocks) == b] for b in np.unique(blocks)]
        boot = np.array([np.median(np.concatenate([members[i] for i in rng.integers(0, len(members), len(members))]))
                         for _ in range(draws)])
    return float(np.median(values)), float(np.percentile(boot, 2.5)), float(np.percentile(boot, 97.5))


def median_error(predicted, measured) -> float:
    return float(100 * np.median(np.abs(np.asarray(predicted) / np.asarray(measured) - 1.0)))


# -- sections ----------------------------------------------------------------------------------------------------------

def held_out_section(table) -> None:
    from validation.impact import attainable as at
    from validation.impact import rate_laws as rl
    from validation.impact.shots import bands

    slow, fast = bands(table)
    loft_ok = rl.spin_loft(table) > 0  # a power law has no log of a negative spin loft
    print("### 1. Held-out spin (goal 1): learners of the delivery without physics, by the models' protocol\n")
    print("Trained on every row of one band, tested on every row of the other (median |spin error| %, bias in "
          "brackets). The last column sets the power law's level on the tested rows themselves, keeping the shape "
          "(b, c) fitted on the training band: an oracle no model has, the error left by that shape alone.\n")
    print("| trained on -> tested on | rows tested | regression k V sin(spin loft) | power law a V^b sin^c (b, c) | "
          "the same power law, level set on the tested rows (oracle) |")
    print("|---|---|---|---|---|")
    for train_mask, test_mask, label in ((slow, fast, "< 95 -> > 100 mph"), (fast, slow, "> 100 -> < 95 mph")):
        train = table.subset(np.flatnonzero(train_mask & loft_ok))
        test = table.subset(np.flatnonzero(test_mask & loft_ok))
        measured = np.asarray(test.measured["spin_rate"], float)
        regression, _ = rl.regression(train, test)
        power, b, c = at.power_law(train, test)
        cells = [f"{median_error(p, measured):.1f} ({100 * np.median(p / measured - 1):+.1f})"
                 for p in (regression, power)]
        print(f"| {label} | {test.size} | {cells[0]} | {cells[1]} (b {b:.2f}, c {c:.2f}) | "
              f"{oracle_error(power, measured):.1f} |")
    print("\nFor comparison (committed outputs, not recomputed here): learners trained on the tested band's own rows "
          "(contiguous 5-fold, attainable_output.md) reach 17.2 % (< 95 mph, gradient boosting) and 13.2 % (> 100 "
          "mph, power law); the best physical forms held out reach 16.0 % and 17.3 % (docs/validation.md, round 4); "
          "consecutive near-identical deliveries differ in spin by 9-10 % (median of pairs), about 6.5 % per shot. "
          "These are empirical figures, not a bound: a better learner, or more of the file's columns, may lower them "
          "by a point or so; what they show is that most of the slow band's spread is not carried by its inputs.\n")


def tour_section(table) -> None:
    from scipy.optimize import brentq

    from impactlab.scene.catalogue import CLUB_CATALOGUE
    from impactlab.scene.materials import BALL_PRESETS
    from validation.impact import rate_laws as rl
    from validation.impact.ball_groups import per_unit
    from validation.impact.shots import MPH

    ball = BALL_PRESETS["urethane_tour"]
    limit, head_mass = rl.HEAD_COR_LIMIT, CLUB_CATALOGUE["driver"].mass
    slope = ball_cor_slope()
    tour = rl.tour()
    rows = {label: i for i, label in enumerate(tour.labels)}
    speed = np.asarray(tour.delivery["club_speed"]) / MPH
    loft = rl.spin_loft(tour)
    smash = np.asarray(tour.measured["ball_speed"]) / np.asarray(tour.delivery["club_speed"])
    spin = np.asarray(tour.measured["spin_rate"]) * RPM

    print("### 2. The tour tables (goal 3)\n")
    light_ball, heavy_head = LENIENT["ball_mass"], head_mass + LENIENT["added_mass"]
    print(f"**(a) Ball speed against the Rules' COR limit.** A rigid ball struck by a free, translating face at the "
          f"row's spin loft, friction enough to roll (the largest tangential speed of a Coulomb contact; a "
          f"tangential rebound would add under 0.3 %), K = {ball.inertia_factor:.2f} (closed form, "
          "free_head_speed_ratio; a head turning about its centre of mass only lowers it). Every choice leans towards "
          f"the table: e = {limit:.3f} (the USGA/R&A limit with its tolerance, at the COR test's {COR_TEST_SPEED} m/s) "
          f"held above that speed and raised below it by the ball's measured COR slope (Chou & Yang 1994: 0.85 at "
          f"20 m/s, 0.78 at 45 m/s; allowed_restitution); the package's measured {head_mass * 1e3:.0f} g driver head "
          f"(Proceedings 49 (2020) 47, Table 1) plus the {LENIENT['added_mass'] * 1e3:.0f} g a shaft can add "
          f"(McNally et al. 2020), {heavy_head * 1e3:.0f} g; a {light_ball * 1e3:.1f} g ball, lighter than the "
          f"Rules' {ball.mass * 1e3:.2f} g maximum (an allowance, not a measurement). The 6-irons' e is not bounded by "
          "the Rules and they are left out.\n")
    print(f"| row | club speed [mph] | spin loft [deg] | normal speed [m/s] | e allowed | measured smash factor | "
          f"smash bound ({heavy_head * 1e3:.0f} g head, {light_ball * 1e3:.1f} g ball) | bound vs the table "
          "(goal: within 1 %) | e the table needs (same masses) | head mass the table needs at the e allowed |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for label in ("PGA driver", "LPGA driver"):
        i = rows[label]
        normal = float(tour.delivery["club_speed"][i]) * math.cos(loft[i])
        e = float(allowed_restitution(normal, limit, slope, COR_TEST_SPEED))
        bound = float(free_head_speed_ratio(loft[i], e, light_ball, heavy_head, ball.inertia_factor))
        gap = 100 * (bound / smash[i] - 1)
        verdict = "within reach" if gap >= -100 * TOUR_BALL_SPEED else "out of reach"
        need_e = brentq(lambda x: float(free_head_speed_ratio(loft[i], x, light_ball, heavy_head,
                                                              ball.inertia_factor)) - smash[i], 0.0, 1.0)
        need = head_mass_for(smash[i], loft[i], e, light_ball, ball.inertia_factor)
        print(f"| {label} | {speed[i]:.0f} | {np.degrees(loft[i]):.1f} | {normal:.1f} | {e:.3f} | {smash[i]:.3f} | "
              f"{bound:.3f} | {gap:+.1f} %: {verdict} | {need_e:.3f} | {need * 1e3:.0f} g |")

    kept = np.isfinite(rl.spin_loft(table))
    fraction = tracked_fraction(table)
    settings = np.asarray(table.ball_settings)
    square = np.abs(np.degrees(np.asarray(table.delivery["face_to_path"], float))) <= SQUARE
    premium = kept & (settings == "Premium")
    groups = (("every kept row", kept), ("Premium ball setting", premium),
              (f"Premium, face to path within {SQUARE:g} deg", premium & square),
              (f"flight tracked >= {TRACKED:.0%} (outdoors, measured)", kept & (fraction >= TRACKED)),
              ("flight tracked < 10 % (indoors or netted)", kept & (fraction < 0.1)))
    lines = np.array([int(label.split()[-1]) for label in table.labels])
    print(f"\n**(b) The file's own shots at each tour driver's delivery.** The rows within {NEAR['club_speed']:g} mph "
          f"of club speed, {NEAR['spin_loft']:g} deg of spin loft (dynamic loft less attack: the file has no spin "
          f"loft column) and {NEAR['attack_angle']:g} deg of attack angle of the row (strike unconstrained, as the "
          "table gives none): their median spin and smash factor against the table's. The interval is the 95 % "
          "bootstrap interval of the median resampling blocks of the file (a jump of more than 100 lines starts a "
          "block: shots of one session are not independent). This is not a bound: a model fitted to the whole file "
          "need not be unbiased at one delivery. It says how far below the file's own shots there a model must "
          "predict to meet the row.\n")
    print("| row (table spin, smash) | rows of the file | n (blocks) | spin: median [interval] rpm | spin vs the "
          "table | smash: median | smash vs the table |")
    print("|---|---|---|---|---|---|---|")
    for label in ("PGA driver", "LPGA driver"):
        i = rows[label]
        delivery = {"club_speed": speed[i], "spin_loft": np.degrees(loft[i]),
                    "attack_angle": np.degrees(tour.delivery["attack_angle"][i])}
        near = neighbours(table, delivery)
        for name, group in groups:
            chosen = near & group
            n = int(chosen.sum())
            if n < 10:
                print(f"| {label} ({spin[i]:.0f} rpm, {smash[i]:.3f}) | {name} | {n} | too few | - | - | - |")
                continue
            file_spin = np.asarray(table.measured["spin_rate"])[chosen] * RPM
            file_smash = (np.asarray(table.measured["ball_speed"]) / np.asarray(table.delivery["club_speed"]))[chosen]
            blocks = session_blocks(lines[chosen])
            m, lo, hi = median_interval(file_spin, blocks)
            s = float(np.median(file_smash))
            print(f"| {label} ({spin[i]:.0f} rpm, {smash[i]:.3f}) | {name} | {n} ({blocks.max() + 1}) | "
                  f"{m:.0f} [{lo:.0f}-{hi:.0f}] | "
                  f"{100 * (m / spin[i] - 1):+.1f} % [{100 * (lo / spin[i] - 1):+.0f} to "
                  f"{100 * (hi / spin[i] - 1):+.0f}] | "
                  f"{s:.3f} | {100 * (s / smash[i] - 1):+.1f} % |")
    unit = per_unit(table)
    print("\nSpin per mph of V sin(spin loft), medians: " + "; ".join(
        f"{name} {np.nanmedian(unit[group]):.0f} rpm ({int(group.sum())} rows)" for name, group in groups)
        + "; the tables: " + "; ".join(
        f"{label} {spin[rows[label]] / (speed[rows[label]] * np.sin(loft[rows[label]])):.0f}"
        for label in ("PGA driver", "LPGA driver")) + ".\n")

    p, q = rows["PGA driver"], rows["LPGA driver"]
    speed_ratio, loft_ratio = speed[p] / speed[q], np.sin(loft[p]) / np.sin(loft[q])
    spin_ratio = spin[p] / spin[q]
    print(f"**(c) The two tours' drivers under one law (information, not a limit).** Measured: club speed ratio "
          f"{speed_ratio:.3f}, sin(spin loft) ratio {loft_ratio:.3f}, spin ratio {spin_ratio:.3f}. A law spin = A V^k "
          "sin(spin loft)^c puts both rows within 7 % under one level A only for k in the window below "
          "(exponent_window). The windows overlap the issue's 0.5-0.8 at its low end: the two tours alone do not "
          "rule the exponent goal out.\n")
    print("| c | k window |")
    print("|---|---|")
    for c in (0.5, 0.6, 0.7, 0.85, 1.0):
        k_min, k_max = exponent_window(speed_ratio, loft_ratio, spin_ratio, c)
        print(f"| {c:.2f} | {k_min:+.2f} to {k_max:+.2f} |")
    print()


def wedge_section() -> None:
    from impactlab.scene.catalogue import CLUB_CATALOGUE
    from impactlab.scene.materials import BALL_PRESETS
    from validation.impact import rate_laws as rl
    from validation.impact.shots import MPH

    wedge = rl.wedge_test()
    delivery = wedge.delivery  # SI: club speed m/s, angles rad
    loft = spin_loft_of(delivery)
    normal_speed = float(delivery["club_speed"]) * math.cos(loft)
    ball = BALL_PRESETS[wedge.balls["urethane"]]
    head = CLUB_CATALOGUE[wedge.club]
    urethane, ionomer = (BALL_PRESETS[wedge.balls[k]].friction for k in ("urethane", "ionomer"))
    print("### 3. The wedge ball-type test (goal 4)\n")
    print(f"The test's assumed delivery (observations.yaml, {wedge.name}: {delivery['club_speed'] / MPH:.0f} mph, "
          f"attack {math.degrees(delivery['attack_angle']):+.0f} deg, dynamic loft "
          f"{math.degrees(delivery['dynamic_loft']):.0f} deg; not measured): spin loft {math.degrees(loft):.0f} deg, "
          f"normal speed {normal_speed:.1f} m/s. The rigid impact of section 2 with the {head.mass * 1e3:.0f} g head "
          f"of the package's {wedge.club}: below mu_c the ball slides and its spin is mu / mu_c of the rolling spin, "
          "so a urethane ball that rolls and an ionomer ball of friction mu_i differ by "
          "mu_c / mu_i - 1. The goal's 16-50 % (measured +48 %) then needs mu_i in the interval below.\n")
    print("| pair restitution e | mu_c (stops sliding) | mu_i for +50 % | mu_i for +16 % | mu_i for the measured "
          "+48 % |")
    print("|---|---|---|---|---|")
    for e in (0.70, 0.75, 0.787, 0.82):
        mu_c = float(rolling_friction(loft, e, ball.mass, head.mass, ball.inertia_factor))
        print(f"| {e:.3f} | {mu_c:.3f} | {mu_c / (1 + WEDGE_GOAL[1]):.3f} | {mu_c / (1 + WEDGE_GOAL[0]):.3f} | "
              f"{mu_c / (1 + wedge.published):.3f} |")
    tour = rl.tour()
    driver = [float(instantaneous_slip_fraction(urethane, rl.spin_loft(tour)[i], 0.83, ball.mass,
                                                CLUB_CATALOGUE["driver"].mass,
                                                float(tour.delivery["club_speed"][i]), ball.inertia_factor))
              for i, label in enumerate(tour.labels) if "driver" in label]
    fractions = [float(instantaneous_slip_fraction(mu, loft, 0.787, ball.mass, head.mass, float(delivery["club_speed"]),
                                                   ball.inertia_factor)) for mu in (urethane, ionomer)]
    print(f"\nFriction following the instantaneous slip (Arakawa's F = lambda A u applied at each instant, mu = mu_0 u "
          f"/ 10 m/s; instantaneous_slip_fraction; the package's law reads one slip per impact): in this rigid impact "
          f"the ball never quite rolls, the urethane ball ({urethane:.2f}) reaching {fractions[0]:.4f} of the rolling "
          f"spin and the ionomer ({ionomer:.2f}) {fractions[1]:.4f}: a difference of "
          f"{100 * (fractions[0] / fractions[1] - 1):+.1f} %. The form does not separate the covers either. On the "
          f"PGA and LPGA driver deliveries (section 2) the urethane ball reaches {driver[0]:.6f} and {driver[1]:.6f}: "
          "rolling, so its spin there grows as the club speed (exponent 1), the exponent goal unmet by this form in "
          "a rigid impact.\n")
    print(f"The covers' frictions the package has: sled measurements {urethane:.2f} (urethane) and {ionomer:.2f} "
          "(ionomer; Henrikson et al. 2020, at loads far below an impact's). With them both balls roll in every form "
          "and the difference is 0 to -3 %. The compliant models slide at higher friction than the rigid one "
          "(model outputs, committed): `hertz_mindlin_face` gives +18.3 % at an ionomer mu_0 of 0.175 and +42.2 % "
          "at 0.14 (slip_friction_output.md, section 4), so it needs about 0.13-0.18; `hertz_mindlin_slip` reaches "
          "+39 % only at 0.07. The driver file's range-ball rows, fitted (ball_groups_output.md, a model fit on "
          "drivers, not on the wedge), give 0.22-0.24 with the face and +4.3 / +7.5 % on the wedge. So the goal "
          "needs an ionomer friction at impact of about 0.09-0.18 (a quarter to a half of the sled's value, by "
          "model), 0.04-0.15 below anything measured or fitted for an ionomer-like cover. No source found in three "
          "searches measures it (docs/validation.md, rounds 4-5).\n")


def main(argv=None) -> None:
    from validation.impact.face_mechanisms import command_line
    from validation.impact.shots import load

    args = command_line(argv, __doc__.splitlines()[0])
    table, _ = load()
    held_out_section(table)
    tour_section(table)
    wedge_section()
    print(f"(elapsed {time.time() - args.started:.0f} s)")


if __name__ == "__main__":
    main()
