"""Issue 21: does a driver's flexing face (the trampoline) make drivers under-roll while irons stay as they are?

Measures the face law (impactlab.physics.face_flex; options face_frequency, face_modal_mass, face_loss of the
one-spring models; it acts on spring-like faces only, club_restitution_gain > 0, and there takes the ball's own e)
on the TrackMan tour rows and a wedge shot, nothing fitted to them:

1. the face as a clamped titanium plate (model output): first-mode frequency, modal mass and stiffness over the
   plausible face thicknesses, on the driver preset's 110 x 60 mm face (an estimate in the catalogue);
2. the pair's coefficient of restitution of the Rules' test (ball fired at 48.8 m/s head-on at the driver preset's
   free head, the tour ball's own e) over the face's frequency and modal mass: the USGA and R&A state that the CT
   limit "very closely correlates" with the COR limit 0.830 (their 2003 proposal of the pendulum test), so a face
   at the CT limit is one whose COR is 0.830;
3. spin per unit of club speed x sin(spin loft) [rpm/mph] of the PGA and LPGA driver and 6-iron rows and the
   wedge shot, law off and on, under both of hertz_mindlin's inelastic laws, with and without the rolling law;
   the iron/driver ratio (measured 1.75), the PGA/LPGA driver spin ratio (measured 1.02), the drivers' ball speed
   against the law off (the fitted gain 0.083);
4. the face frequency fitted on one tour (spin RMS), the other tour reported;
5. the cost per impact against the elastic law (maw, as bench_ball_laws.py), CPU time, best of 7.

Run: .venv/bin/python benchmarks/measure_face_flex.py  (a few minutes)
"""

from __future__ import annotations

import sys
from pathlib import Path

import attrs
import numpy as np
from scipy import optimize

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "docs"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from ball_laws import (measured_cells, model_cells, scene_inputs,  # noqa: E402  (docs/ball_laws.py: the tour rows)
                       tour_and_wedge_inputs)
from bench_ball_laws import per_impact  # noqa: E402

from impactlab.data.shot_report import shot_table  # noqa: E402
from impactlab.data.sessions.shots import predict, shot_errors, table_inputs  # noqa: E402
from impactlab.model.registry import get_model  # noqa: E402
from impactlab.physics import face_flex  # noqa: E402
from impactlab.physics.contact import contact_state  # noqa: E402
from impactlab.scene.materials import MATERIAL_PRESETS  # noqa: E402
from impactlab.testing import _complete, _with, reference_inputs, reference_inputs_3d  # noqa: E402

#: Ti-6Al-4V: E, nu of the titanium preset (ASM handbook); density 4430 kg/m^3 (ASM handbook, annealed grade 5)
TITANIUM = (MATERIAL_PRESETS["titanium"].youngs_modulus, MATERIAL_PRESETS["titanium"].poisson_ratio, 4430.0)
#: the driver preset's face, 110 x 60 mm (catalogue FACE_SIZES, an estimate): the disc of equal area
FACE_RADIUS = np.sqrt(0.055 * 0.030)
FREQUENCIES = (3e3, 4e3, 5e3, 6e3, 8e3, 12e3, 20e3)
MASSES = (0.005, 0.010, 0.015)


def plate_table():
    print("The face as a clamped circular Ti-6Al-4V plate of the driver face's area (radius "
          f"{FACE_RADIUS * 1e3:.1f} mm; model output; modal mass ratio {face_flex.clamped_modal_mass_ratio():.4f})")
    print("| thickness mm | f_1 kHz | modal mass g | k_f MN/m | static 16 pi D / a^2 MN/m |")
    print("|---|---|---|---|---|")
    for h in (2.3, 2.6, 3.0, 3.3):
        f, m, k = face_flex.clamped_plate_mode(FACE_RADIUS, h * 1e-3, *TITANIUM)
        d = TITANIUM[0] * (h * 1e-3) ** 3 / (12 * (1 - TITANIUM[1] ** 2))
        static = 16 * np.pi * d / FACE_RADIUS**2
        print(f"| {h:.1f} | {f / 1e3:.2f} | {m * 1e3:.1f} | {k / 1e6:.2f} | {static / 1e6:.2f} |")


def pair_cor(options, speed=48.8):
    """The pair's COR of the Rules' test: the tour ball head-on at ``speed`` on the driver preset's free head."""
    rows = [("urethane_tour", "driver", speed / 0.44704, 0.0, 0.0)]
    inputs = scene_inputs(rows)
    inputs["speed"] = np.array([speed])
    out = get_model("hertz_mindlin")(**options).compute(inputs, ["normal_impulse"])
    m_star = 1.0 / contact_state(inputs)["mobility"][:, 2, 2]
    return float(out["normal_impulse"].values[0] / (m_star[0] * speed) - 1.0), float(inputs["restitution"][0])


def cor_table():
    print("\nThe Rules' COR test simulated (ball head-on at 48.8 m/s on the driver preset's free head): the pair's e "
          "[1] (law off: the ball's e + the fitted gain 0.083)")
    for inelastic in ("adjusted_speed", "hysteretic"):
        base, with_gain = pair_cor({"inelastic": inelastic})
        print(f"\n{inelastic}: law off {base:.3f} (ball's e + gain: {with_gain:.3f}; ball's own e "
              f"{with_gain - 0.083:.3f})")
        print("| face f kHz | " + " | ".join(f"m_f {m * 1e3:.0f} g" for m in MASSES) + " |")
        print("|---|" + "---|" * len(MASSES))
        for f in FREQUENCIES:
            values = [pair_cor({"inelastic": inelastic, "face_frequency": 2 * np.pi * f, "face_modal_mass": m})[0]
                      for m in MASSES]
            print(f"| {f / 1e3:g} | " + " | ".join(f"{v:.3f}" for v in values) + " |")


def cor_limit_faces():
    """The face frequency whose simulated COR is the Rules' limit 0.830 (hysteretic law) at the plate's modal
    masses of a 2.6 and a 3.0 mm face: the faces 'at the CT limit', sized without the TrackMan rows."""
    print("\nFaces at the COR limit 0.830 (hysteretic; the frequency solved at the plate's modal mass)")
    for h in (2.6, 3.0):
        _, modal, _ = face_flex.clamped_plate_mode(FACE_RADIUS, h * 1e-3, *TITANIUM)
        f = optimize.brentq(lambda f: pair_cor({"inelastic": "hysteretic", "face_frequency": 2 * np.pi * f,
                                                 "face_modal_mass": modal})[0] - 0.830, 4e3, 20e3, xtol=1.0)
        print(f"  {h:.1f} mm plate's modal mass {modal * 1e3:.1f} g: f = {f / 1e3:.2f} kHz")


#: faces sized without the TrackMan rows: the clamped plates of 2.6 and 3.0 mm (model outputs) and the faces of
#: those modal masses whose simulated COR is the Rules' limit 0.830 (cor_limit_faces, hysteretic law)
NAMED_FACES = (("plate 2.6 mm: 3.99 kHz, 10.9 g", 3.99e3, 0.0109), ("plate 3.0 mm: 4.60 kHz, 12.6 g", 4.60e3, 0.0126),
               ("COR 0.830: 6.88 kHz, 10.9 g", 6.88e3, 0.0109), ("COR 0.830: 6.47 kHz, 12.6 g", 6.47e3, 0.0126))


def pendulum_check():
    """The pendulum's mass at which each named face reads the CT limit 239 us in the simulated CT test, for two
    assumed tip radii and speeds (the USGA's Technical Description, which gives them, was not found): a check a
    reader with that document can make of the COR-limit sizing."""
    print("\nPendulum mass [g] at which a face reads CT = 239 us (steel tip on Ti-6Al-4V; tip radius and speed "
          "ASSUMED)")
    print("| face | tip 6.35 mm, 0.2 m/s | tip 6.35 mm, 0.5 m/s | tip 12.7 mm, 0.2 m/s | tip 12.7 mm, 0.5 m/s |")
    print("|---|---|---|---|---|")
    for name, f, m in NAMED_FACES:
        k = m * (2 * np.pi * f) ** 2
        masses = []
        for radius in (0.00635, 0.0127):
            tip = face_flex.hertz_constant(radius, 196e9, 0.272, TITANIUM[0], TITANIUM[1])
            for speed in (0.2, 0.5):
                masses.append(optimize.brentq(lambda mp: face_flex.pendulum_contact_time(k, m, mp, speed, tip)
                                              - 239e-6, 0.005, 2.0, xtol=1e-5))
        print(f"| {name} | " + " | ".join(f"{1e3 * mp:.0f}" for mp in masses) + " |")


def forms():
    yield "off (rigid face, gain 0.083)", {}
    for name, f, m in NAMED_FACES:
        yield f"**{name}**", {"face_frequency": 2 * np.pi * f, "face_modal_mass": m}
    for m in MASSES:
        for f in FREQUENCIES:
            yield f"{f / 1e3:g} kHz, {m * 1e3:.0f} g", {"face_frequency": 2 * np.pi * f, "face_modal_mass": m}
    yield "4 kHz, 10 g, face loss 0.05", {"face_frequency": 2 * np.pi * 4e3, "face_modal_mass": 0.010,
                                          "face_loss": 0.05}


def spin_table(inelastic, rolling):
    inputs, speeds = tour_and_wedge_inputs()
    label = f"hertz_mindlin, inelastic {inelastic}{' + rolling_hysteresis 1 - e_ball^2' if rolling else ''}"
    print(f"\n#### {label}: spin per unit [rpm/mph]\n")
    print("| face | PGA driver | LPGA driver | PGA 6-iron | LPGA 6-iron | wedge (assumed delivery) | iron/driver | "
          "PGA/LPGA driver spin | driver ball speed vs off % (PGA, LPGA) | PGA driver t_c us |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    print(measured_cells() + " | |")
    names = ["spin_rate", "spin_loft", "contact_time", "ball_speed"]
    reference = None
    for name, options in forms():
        options = dict(options, inelastic=inelastic)
        if rolling:
            options["rolling_hysteresis"] = "restitution"
        out = get_model("hertz_mindlin")(**options).compute(inputs, names)
        speed = out["ball_speed"].values
        reference = speed if reference is None else reference
        gain = 100 * (speed[:2] / reference[:2] - 1)
        print(f"| {name} | {model_cells(out['spin_rate'].values, out['spin_loft'].values, speeds)}"
              f" | {gain[0]:+.1f}, {gain[1]:+.1f} | {out['contact_time'].values[0] * 1e6:.0f} |")


def held_out_fit(modal=0.010):
    """The face frequency fitted on one tour's two rows (spin RMS, a grid 3-40 kHz, modal mass fixed), the other
    tour's errors reported: hertz_mindlin hysteretic, loft at contact, nothing else fitted."""
    table = attrs.evolve(shot_table("trackman_tour"), loft_at="contact")
    inputs = table_inputs(table)
    grid = np.geomspace(3e3, 40e3, 12)

    def errors(frequency, rolling):
        options = {"inelastic": "hysteretic"}
        if rolling:
            options["rolling_hysteresis"] = "restitution"
        if frequency is not None:
            options.update(face_frequency=2 * np.pi * float(frequency), face_modal_mass=modal)
        return shot_errors(predict(get_model("hertz_mindlin")(**options), inputs), table)

    sources = np.array(table.row_sources)
    for rolling in (False, True):
        print(f"\nThe face frequency fitted on one tour (spin RMS of its driver and 6-iron; modal mass {modal * 1e3:g} "
              f"g), the other tour's errors (hertz_mindlin hysteretic, loft at contact"
              f"{', rolling 1 - e_ball^2' if rolling else ''})")
        print("| fitted on | f fitted kHz | row | spin % | launch deg | ball speed % |")
        print("|---|---|---|---|---|---|")
        rows = {f: errors(f, rolling) for f in grid}
        without = errors(None, rolling)
        for index, label in enumerate(table.labels):
            print(f"| (rigid face) | - | {label} | {without['spin [%]'][index]:+.1f} | "
                  f"{without['launch angle [deg]'][index]:+.2f} | {without['ball_speed [%]'][index]:+.2f} |")
        for source in dict.fromkeys(table.row_sources):
            fit = sources == source
            best = min(grid, key=lambda f: float(np.sqrt(np.mean(rows[f]["spin [%]"][fit] ** 2))))
            for index in list(np.flatnonzero(~fit)) + list(np.flatnonzero(fit)):
                e = rows[best]
                tag = "held out" if not fit[index] else "fitted"
                print(f"| {source} | {best / 1e3:.2f} | {table.labels[index]} ({tag}) | {e['spin [%]'][index]:+.1f} | "
                      f"{e['launch angle [deg]'][index]:+.2f} | {e['ball_speed [%]'][index]:+.2f} |")


def cost():
    print("\nCost per impact (CPU time, best of 7) against the elastic law (maw), and against the model without the "
          "face (every case with a spring-like face, club_restitution_gain 0.05)")
    batches = {"3-D (48 driver cases)": _complete(reference_inputs_3d()), "1-D (126 plate cases)": reference_inputs()}
    face = {"face_frequency": "4 kHz", "face_modal_mass": "10 g"}
    for label, inputs in batches.items():
        inputs = _with(inputs, club_restitution_gain=0.05)
        elastic = per_impact(get_model("maw")(), inputs)
        print(f"  {label}: maw elastic {elastic * 1e3:.3f} ms")
        for options in ({}, {"inelastic": "hysteretic"}, {"rolling_hysteresis": "restitution"}):
            without = per_impact(get_model("hertz_mindlin")(**options), inputs)
            with_face = per_impact(get_model("hertz_mindlin")(**options, **face), inputs)
            print(f"    hertz_mindlin {options or ''} + face: {with_face * 1e3:.3f} ms, {with_face / elastic:.2f} x "
                  f"elastic, {with_face / without:.2f} x without the face")


def main():
    plate_table()
    cor_table()
    cor_limit_faces()
    pendulum_check()
    for inelastic in ("adjusted_speed", "hysteretic"):
        for rolling in (False, True):
            spin_table(inelastic, rolling)
    held_out_fit()
    cost()


if __name__ == "__main__":
    main()
