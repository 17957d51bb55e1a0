"""Issue 21: does the ball's core lag its shell in rotation, and does that make drivers under-roll while irons do not?

Measures the core law (impactlab.physics.core_torsion; options core_radius & co. of the compliant models) on the
TrackMan tour rows and a wedge shot, nothing fitted:

1. the core's first modes against the contact time, over the plausible range of the core's shear modulus;
2. spin per unit of club speed x sin(spin loft) [rpm/mph] of the PGA and LPGA driver and 6-iron rows (the four rows
   of docs/ball_laws.py: TrackMan's deliveries and spin, measured; spin lofts 14.7, 15.0, 24.3, 25.9 deg) and of
   the Titleist WedgeCraft wedge shot (urethane ball, 8,300 rpm measured; the delivery 65 mph, loft 34 deg,
   attack -4 deg is impactlab/data/validation/observations.yaml's ASSUMPTION), law off and on, with and without
   the rolling law; the iron/driver ratio of the means (measured 1.75) and the PGA/LPGA driver spin ratio
   (measured 1.02);
3. the cost per impact against the elastic law (maw, as bench_ball_laws.py), CPU time, best of 7.

Core parameters and their sources: radius 19.05 mm (core diameter 1.50 in, the top of the range 1.10-1.50 in of
US 2025/0195958 claim 1, a five-piece ball; a patent claim range, not a measured ball) and 15 mm; specific gravity
1.15 (inside that claim's 1.10-1.40) or the ball's mean density (1.129); shear modulus 2-47 MPa: no measured core
shear modulus was found; 47 MPa is the ball preset's equivalent E / (2 (1 + nu)) = 136 MPa / 2.9 (chosen to give
the measured contact time, so an upper bound for the softest part of the ball), the lower end a soft rubber.

Run: .venv/bin/python benchmarks/measure_core_torsion.py  (about a minute)
"""

from __future__ import annotations

import sys
from pathlib import Path

import attrs
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "docs"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from ball_laws import (measured_cells, model_cells, per_unit,  # noqa: E402  (docs/ball_laws.py: the tour rows)
                       tour_and_wedge_inputs)
from bench_ball_laws import per_impact  # noqa: E402

from impactlab.data.shot_report import shot_table  # noqa: E402
from impactlab.data.sessions.shots import predict, shot_errors, table_inputs  # noqa: E402
from impactlab.model.registry import get_model  # noqa: E402
from impactlab.physics import core_torsion  # noqa: E402
from impactlab.testing import _complete, reference_inputs, reference_inputs_3d  # noqa: E402

MASS, RADIUS, FACTOR = 0.04593, 0.021335, 0.4
SHEARS = (2e6, 5e6, 10e6, 20e6, 47e6)
CORES = (0.01905, 0.015)


def modes_table():
    print("Core modes (uniform core, ball K^2 = 0.4, m = 45.93 g, R = 21.335 mm; first elastic mode f_1 and the "
          "share of the shell's instantaneous mobility 1/I_s - 1/I_tot it carries)")
    print("| core radius mm | SG | I_s / I_tot | G MPa | c_s m/s | f_1 kHz | period ms | I_tot/I_1 | f_2 kHz |")
    print("|---|---|---|---|---|---|---|---|---|")
    total = FACTOR * MASS * RADIUS**2
    for core in CORES:
        for gravity in (1.15, None):
            density = 1000.0 * gravity if gravity else MASS / (4 / 3 * np.pi * RADIUS**3)
            for shear in SHEARS:
                modes = core_torsion.core_modes(total_inertia=total, core_radius=core, core_density=density,
                                                shear_modulus=shear, modes=2)
                print(f"| {core * 1e3:.2f} | {density / 1000:.3f} | {modes.shell_inertia / total:.3f} | "
                      f"{shear / 1e6:.0f} | {np.sqrt(shear / density):.0f} | {modes.frequency[0] / 2e3 / np.pi:.2f} | "
                      f"{2 * np.pi / modes.frequency[0] * 1e3:.3f} | {total * modes.inverse_inertia[0]:.3f} | "
                      f"{modes.frequency[1] / 2e3 / np.pi:.2f} |")


def forms():
    yield "off (rigid ball)", {}
    for core in CORES:
        for shear in SHEARS:
            yield f"b {core * 1e3:.2f} mm, G {shear / 1e6:.0f} MPa", {"core_radius": core, "core_shear_modulus": shear,
                                                                     "core_specific_gravity": 1.15}
    yield "b 19.05 mm, G 10 MPa, loss 0.1", {"core_radius": 0.01905, "core_shear_modulus": 10e6,
                                            "core_specific_gravity": 1.15, "core_loss": 0.1}
    yield "b 19.05 mm, G the ball's (47 MPa), SG the ball's", {"core_radius": 0.01905}


def spin_table(model_name, rolling):
    inputs, speeds = tour_and_wedge_inputs()
    label = f"{model_name}{' + rolling_hysteresis 1 - e_ball^2' if rolling else ''}"
    print(f"\n#### {label}: spin per unit [rpm/mph] (contact time of the PGA driver row in brackets)\n")
    print("| form | PGA driver | LPGA driver | PGA 6-iron | LPGA 6-iron | wedge (assumed delivery) | iron/driver | "
          "PGA/LPGA driver spin | driver t_c ms |")
    print("|---|---|---|---|---|---|---|---|---|")
    print(measured_cells() + " |")
    for name, options in forms():
        if rolling:
            options = dict(options, rolling_hysteresis="restitution")
        out = get_model(model_name)(**options).compute(inputs, ["spin_rate", "spin_loft", "contact_time"])
        print(f"| {name} | {model_cells(out['spin_rate'].values, out['spin_loft'].values, speeds)}"
              f" | {out['contact_time'].values[0] * 1e3:.3f} |")


def soft_core_sweep():
    """From a core that cannot follow within the contact (G -> 0: the shell alone takes the impulse) to a rigid
    ball; the default modes (up to 20 kHz); hertz_mindlin, no rolling law; the tangential restitution beta of each
    row as well."""
    inputs, speeds = tour_and_wedge_inputs()
    print("\n#### From a free shell to a rigid ball (hertz_mindlin, b 19.05 mm, SG 1.15, modes up to 20 kHz): spin "
          "per unit [rpm/mph], and beta\n")
    print("| G MPa | PGA driver | LPGA driver | PGA 6-iron | LPGA 6-iron | wedge | iron/driver | beta: PGA driver, "
          "PGA 6-iron, wedge |")
    print("|---|---|---|---|---|---|---|---|")
    for shear in (None, 0.1e6, 0.2e6, 0.5e6, 1e6, 2e6, 3e6, 5e6, 10e6, 100e6):
        options = {} if shear is None else {"core_radius": 0.01905, "core_shear_modulus": shear,
                                            "core_specific_gravity": 1.15}
        out = get_model("hertz_mindlin")(**options).compute(inputs, ["spin_rate", "spin_loft",
                                                                     "tangential_restitution"])
        values = per_unit(out["spin_rate"].values, speeds, out["spin_loft"].values)
        beta = out["tangential_restitution"].values
        print(f"| {'off' if shear is None else f'{shear / 1e6:g}'} | " + " | ".join(f"{v:.1f}" for v in values)
              + f" | {values[2:4].mean() / values[:2].mean():.2f} | {beta[0]:+.2f}, {beta[2]:+.2f}, {beta[4]:+.2f} |")


def stiffer_contact():
    """Is the result a property of Mindlin's tangential stiffness? hertz_mindlin with k_t / k_n = 3 and 10 (about 4
    and 14 times Mindlin's kappa = 2 (1 - nu) / (2 - nu) = 0.71 of the ball on a near-rigid face): the core
    against the rigid ball."""
    inputs, speeds = tour_and_wedge_inputs()
    print("\nA stiffer tangential spring (hertz_mindlin stiffness_ratio), b 19.05 mm, SG 1.15: spin per unit "
          "(PGA driver, LPGA driver, PGA 6-iron, LPGA 6-iron, wedge) and iron/driver")
    for ratio in (3.0, 10.0):
        for shear in (None, 2e6, 5e6, 10e6, 20e6):
            options = {"stiffness_ratio": ratio}
            if shear is not None:
                options.update(core_radius=0.01905, core_shear_modulus=shear, core_specific_gravity=1.15)
            out = get_model("hertz_mindlin")(**options).compute(inputs, ["spin_rate", "spin_loft"])
            values = per_unit(out["spin_rate"].values, speeds, out["spin_loft"].values)
            ratio_iron = values[2:4].mean() / values[:2].mean()
            print(f"  k_t/k_n {ratio:g}, {'rigid ball' if shear is None else f'G {shear / 1e6:g} MPa'}: "
                  + ", ".join(f"{v:.1f}" for v in values) + f"; iron/driver {ratio_iron:.2f}")


def truncation():
    """The spin's change with the number of modes kept, against 32 (hertz_mindlin, b 19.05 mm, SG 1.15)."""
    inputs, _ = tour_and_wedge_inputs()
    print("\nModes kept: spin against 32 modes [%] (PGA driver, LPGA driver, PGA 6-iron, LPGA 6-iron, wedge)")
    total = FACTOR * MASS * RADIUS**2
    for shear in (0.1e6, 2e6, 10e6, 20e6, 47e6):
        spins = {count: get_model("hertz_mindlin")(core_radius=0.01905, core_shear_modulus=shear,
                                                   core_specific_gravity=1.15, core_modes=count).compute(
            inputs, ["spin_rate"])["spin_rate"].values for count in (32, 16, 8, 4, 2, 1, None)}
        automatic = core_torsion.modes_below(core_torsion.CUTOFF_FREQUENCY, total_inertia=total, core_radius=0.01905,
                                             core_density=1150.0, shear_modulus=shear)
        for count in (16, 8, 4, 2, 1, None):
            label = f"default ({automatic}, up to 20 kHz)" if count is None else f"{count}"
            print(f"  G {shear / 1e6:g} MPa, {label} modes against 32: "
                  + ", ".join(f"{100 * (a / b - 1):+.2f}" for a, b in zip(spins[count], spins[32])))


def held_out_fit():
    """The core's shear modulus fitted on one tour's two rows (spin RMS, a log grid 0.1-50 MPa), the other tour's
    errors reported: hertz_mindlin, loft at contact, rolling 1 - e_ball^2, b 19.05 mm, SG 1.15, nothing else
    fitted (the Goal's AFTER without its calibration)."""
    table = attrs.evolve(shot_table("trackman_tour"), loft_at="contact")
    inputs = table_inputs(table)
    grid = np.geomspace(0.1e6, 50e6, 25)

    def errors(shear):
        options = {"rolling_hysteresis": "restitution"}
        if shear is not None:
            options.update(core_radius=0.01905, core_shear_modulus=float(shear), core_specific_gravity=1.15)
        return shot_errors(predict(get_model("hertz_mindlin")(**options), inputs), table)

    print("\nThe core's shear modulus fitted on one tour (spin RMS of its driver and 6-iron), the other tour's errors "
          "(hertz_mindlin, loft at contact, rolling 1 - e_ball^2, b 19.05 mm, SG 1.15)")
    print("| fitted on | G fitted MPa | row | spin % | launch deg | ball speed % |")
    print("|---|---|---|---|---|---|")
    sources = np.array(table.row_sources)
    rows = {shear: errors(shear) for shear in grid}
    without = errors(None)
    for label in table.labels:
        index = table.labels.index(label)
        print(f"| (no core) | - | {label} | {without['spin [%]'][index]:+.1f} | "
              f"{without['launch angle [deg]'][index]:+.2f} | {without['ball_speed [%]'][index]:+.2f} |")
    for source in dict.fromkeys(table.row_sources):
        fit = sources == source
        best = min(grid, key=lambda g: float(np.sqrt(np.mean(rows[g]["spin [%]"][fit] ** 2))))
        for index in np.flatnonzero(~fit):
            e = rows[best]
            print(f"| {source} | {best / 1e6:.2f} | {table.labels[index]} (held out) | {e['spin [%]'][index]:+.1f} | "
                  f"{e['launch angle [deg]'][index]:+.2f} | {e['ball_speed [%]'][index]:+.2f} |")
        for index in np.flatnonzero(fit):
            e = rows[best]
            print(f"| {source} | {best / 1e6:.2f} | {table.labels[index]} (fitted) | {e['spin [%]'][index]:+.1f} | "
                  f"{e['launch angle [deg]'][index]:+.2f} | {e['ball_speed [%]'][index]:+.2f} |")


def cost():
    print("\nCost per impact (CPU time, best of 7) against the elastic law (maw), and against the model without the "
          "core")
    batches = {"3-D (48 driver cases)": _complete(reference_inputs_3d()), "1-D (126 plate cases)": reference_inputs()}
    core = {"core_radius": 0.01905, "core_shear_modulus": 10e6, "core_specific_gravity": 1.15}
    for label, inputs in batches.items():
        elastic = per_impact(get_model("maw")(), inputs)
        print(f"  {label}: maw elastic {elastic * 1e3:.3f} ms")
        for name, options in (("hertz_mindlin", {}), ("hertz_mindlin", {"rolling_hysteresis": "restitution"}),
                              ("maw", {})):
            without = per_impact(get_model(name)(**options), inputs)
            with_core = per_impact(get_model(name)(**options, **core), inputs)
            print(f"    {name}{' + rolling' if options else ''} + core (G 10 MPa: 7 modes): {with_core * 1e3:.3f} ms, "
                  f"{with_core / elastic:.2f} x elastic, {with_core / without:.2f} x without the core")


def main():
    modes_table()
    for model_name in ("hertz_mindlin", "maw"):
        for rolling in (False, True):
            spin_table(model_name, rolling)
    soft_core_sweep()
    stiffer_contact()
    truncation()
    held_out_fit()
    cost()


if __name__ == "__main__":
    main()
