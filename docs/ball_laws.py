"""Ball laws against launch data: spin per unit of club speed x sin(spin loft), the wedge cover difference, a wet face.

Runs studies/ball_laws.yaml (spin loft swept for the driver, 6-iron and pitching-wedge presets), the four TrackMan
tour rows of the physics brief (section 12: PGA and LPGA driver and 6-iron; club speed, attack angle, dynamic loft,
measured spin; their spin lofts 14.7, 15.0, 24.3, 25.9 deg from TrackMan's spin-loft pages) and the Titleist
WedgeCraft observation (impactlab/data/validation/observations.yaml: 58 deg wedge, 75 yd, Pro V1 8,300 rpm against
a two-piece Surlyn ball 5,600 rpm, measured by the manufacturer; the delivery, 65 mph, loft 34 deg, attack -4 deg,
is that file's assumption), for each combination of forms; prints the tables and draws
docs/figures/ball_laws_spin_per_unit.png, whose third panel is the friction law's wet-face spin loss on that wedge
shot against the face's roughness, with and without grooves, beside the published wet-wedge losses.

Run from the project root: ``.venv/bin/python docs/ball_laws.py`` (about 40 s).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import impactlab  # noqa: E402
from impactlab.data.sessions.shots import predict, table_inputs  # noqa: E402
from impactlab.data.validation.observations import cover_effect, load_observations, strike_table  # noqa: E402
from impactlab.model.registry import get_model  # noqa: E402
from impactlab.scene.catalogue import CLUB_PRESETS  # noqa: E402
from impactlab.scene.core import Contact, Delivery, Scene, complete_inputs  # noqa: E402
from impactlab.scene.materials import ball_preset  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
MPH = 0.44704
#: (label, club preset, club speed mph, attack deg, dynamic loft deg, spin rpm, TrackMan spin loft deg): measured
ROWS = [("PGA driver", "driver", 115, -0.9, 12.8, 2545, 14.7), ("LPGA driver", "driver", 96, 2.8, 15.5, 2506, 15.0),
        ("PGA 6-iron", "6_iron", 94, -3.7, 20.2, 6204, 24.3), ("LPGA 6-iron", "6_iron", 80, -2.3, 23.6, 5904, 25.9)]
#: the measured bands of the physics brief, section 13 (rpm per mph)
BANDS = {"tour drivers": (87.0, 101.0), "irons and wedges": (160.0, 179.0)}
#: Titleist WedgeCraft (measured): urethane (Pro V1) and two-piece Surlyn spin on a 75-yd shot with a 58 deg wedge
#: published wet-wedge spin losses, measurements of sprayed or wet faces (film thickness not stated): tablehopping.com
#: (SkyTrak, lob wedge, 25/50/89 yd), exactgolf.com (55 m), windmillleisure.co.uk (56 deg, 50-60 yd),
#: peterfieldgolf.co.uk citing a study (average 35 %, best 10 %, worst 60 %)
WET_LOSSES = (0.13, 0.175, 0.11, 0.42, 0.47, 0.35, 0.10, 0.60)
FORMS = [("rigid_coulomb", "rigid_coulomb", {}),
         ("rigid_rolling", "rigid_coulomb", {"rolling_hysteresis": "restitution"}),
         ("maw", "maw", {}),
         ("maw_rolling", "maw", {"rolling_hysteresis": "restitution"}),
         ("maw_rolling_bound", "maw", {"rolling_hysteresis": 1.0}),
         ("maw_hysteretic_rolling", "maw", {"inelastic": "hysteretic", "rolling_hysteresis": "restitution"}),
         ("rigid_friction", "rigid_coulomb", {"friction_law": "adhesion"}),
         ("rigid_rolling_friction", "rigid_coulomb", {"rolling_hysteresis": "restitution", "friction_law": "adhesion"}),
         ("maw_friction", "maw", {"friction_law": "adhesion"}),
         ("maw_rolling_friction", "maw", {"rolling_hysteresis": "restitution", "friction_law": "adhesion"})]


def scene_inputs(rows):
    """Model inputs of (ball preset, club preset, club speed mph, attack deg, dynamic loft deg) rows."""
    scenes = []
    for ball_name, club_name, speed, attack, loft in rows:
        ball, club = ball_preset(ball_name), CLUB_PRESETS[club_name]
        delivery = Delivery(speed * MPH, path=0.0, face_angle=0.0, attack_angle=np.radians(attack),
                            dynamic_loft=np.radians(loft))
        scenes.append(Scene.from_delivery(ball, Scene.face_of(club), Contact(ball.friction, None), delivery, 0.0,
                                          club))
    keys = scenes[0].inputs().keys()
    return complete_inputs({key: np.array([scene.inputs()[key] for scene in scenes]) for key in keys})


def per_unit(spin_rpm, speed_mph, spin_loft_deg):
    return spin_rpm / (speed_mph * np.sin(np.radians(spin_loft_deg)))


#: the WedgeCraft shot (observations.yaml: titleist_wedgecraft_58; delivery assumed there): club preset, club speed
#: mph, attack deg, dynamic loft deg, and the urethane ball's measured 8300 rpm
WEDGE = ("lob_wedge", 65, -4.0, 34.0, 8300)


def tour_and_wedge_inputs():
    """Model inputs of the four tour rows and the WedgeCraft wedge shot, urethane ball, and their club speeds [mph]."""
    rows = [("urethane_tour", *row[1:5]) for row in ROWS] + [("urethane_tour", *WEDGE[:4])]
    return scene_inputs(rows), np.array([row[2] for row in ROWS] + [WEDGE[1]])


def measured_cells() -> str:
    """The measured row of a spin-per-unit table: the four tour rows (TrackMan's spin lofts), the wedge (loft minus
    attack: its spin loft is not published), the iron/driver ratio of the means and the PGA/LPGA driver spin."""
    measured = np.array([per_unit(row[5], row[2], row[6]) for row in ROWS])
    wedge = per_unit(WEDGE[4], WEDGE[1], WEDGE[3] - WEDGE[2])
    return ("| measured | " + " | ".join(f"{v:.1f}" for v in measured) + f" | {wedge:.1f} (loft minus attack)"
            f" | {measured[2:].mean() / measured[:2].mean():.2f} | {ROWS[0][5] / ROWS[1][5]:.2f} |")


def model_cells(spin_rpm, spin_loft_deg, speeds_mph) -> str:
    """A model's cells of a spin-per-unit table, beside :func:`measured_cells`: the four tour rows and the wedge
    (spin per unit at the model's own spin loft), the iron/driver ratio of the means and the PGA/LPGA driver spin."""
    values = per_unit(spin_rpm, speeds_mph, spin_loft_deg)
    return (" | ".join(f"{v:.1f}" for v in values) + f" | {values[2:4].mean() / values[:2].mean():.2f}"
            f" | {spin_rpm[0] / spin_rpm[1]:.2f}")


def wet_losses(roughness_values, lands, film=20e-6):
    """The friction law's spin loss on the wedge observation's shot (urethane ball, maw) with a film on the face."""
    observation = load_observations()["cover"][0]
    model = get_model("maw")(friction_law="adhesion")
    base = table_inputs(strike_table(observation, [0.0]), {"preset": "urethane_tour"})

    def spin(**changes):
        inputs = dict(base, **{key: np.full(1, value) for key, value in changes.items()})
        return float(predict(model, inputs)["spin_rate"][0])

    dry = spin()
    return {land: [1.0 - spin(face_water_film=film, face_roughness=rq, face_groove_land=land) / dry
                   for rq in roughness_values] for land in lands}


def main(out=ROOT / "docs" / "figures" / "ball_laws_spin_per_unit.png"):
    result = impactlab.run_study(impactlab.load_study(ROOT / "studies" / "ball_laws.yaml"))
    speeds = result["club_speed"].values / MPH
    sweep = per_unit(result["spin_rate"], speeds[None, :, None], result["spin_loft"])

    measured = np.array([per_unit(row[5], row[2], row[6]) for row in ROWS])
    tour = scene_inputs([("urethane_tour", *row[1:5]) for row in ROWS])
    print("TrackMan tour rows: spin per (club speed mph x sin spin loft), rpm/mph (measured: physics brief s12), and "
          "the iron/driver ratio of the means")
    print(f"  {'form':24s}" + "".join(f"{row[0]:>13s}" for row in ROWS) + f"{'iron/driver':>13s}")
    print(f"  {'measured':24s}" + "".join(f"{value:13.1f}" for value in measured)
          + f"{measured[2:].mean() / measured[:2].mean():13.2f}")
    rows_model = {}
    for form, name, options in FORMS:
        out_ = get_model(name)(**options).compute(tour, ["spin_rate", "spin_loft"])
        values = per_unit(out_["spin_rate"].values, np.array([row[2] for row in ROWS]), out_["spin_loft"].values)
        rows_model[form] = values
        print(f"  {form:24s}" + "".join(f"{value:13.1f}" for value in values)
              + f"{values[2:].mean() / values[:2].mean():13.2f}")

    observation = load_observations()["cover"][0]
    ratio_measured = observation.published + 1.0
    print(f"\nWedge cover test ({observation.name}: measured urethane/ionomer spin {ratio_measured:.2f}; delivery "
          f"assumed in observations.yaml)")
    wedge_ratio = {}
    for form, name, options in FORMS:
        effect = cover_effect(get_model(name)(**options), observation)
        wedge_ratio[form] = effect["predicted"] + 1.0
        print(f"  {form:24s} urethane {effect['spin']['urethane']:7.0f}  ionomer {effect['spin']['ionomer']:7.0f}  "
              f"ratio {wedge_ratio[form]:.3f}  (difference {effect['ratio']:.2f}x the published)")

    roughness = np.array([0.4, 0.7, 1.0, 1.5, 2.0, 3.0, 4.0, 5.7]) * 1e-6
    losses = wet_losses(roughness, (1.35e-3, np.inf))
    print("\nWet face (20 um of water), urethane ball, maw with the friction law: spin loss against the face's R_q")
    for land, values in losses.items():
        words = "grooved (half-land 1.35 mm)" if np.isfinite(land) else "no grooves"
        print(f"  {words:28s}" + "".join(f"  {rq * 1e6:.1f} um {v:4.0%}" for rq, v in zip(roughness, values)))

    fig, (left, middle, right) = plt.subplots(1, 3, figsize=(17, 6.6), gridspec_kw={"width_ratios": [2.2, 1.1, 1]})
    colors = dict(zip([form for form, _, _ in FORMS], plt.cm.tab10.colors + plt.cm.Dark2.colors))
    styles = {form: "--" if "friction" in form else "-" for form, _, _ in FORMS}
    markers = {"driver": "o", "6_iron": "s", "pitching_wedge": "^"}
    drawn = list(result["model"].values)
    # a form whose curves lie on an earlier form's (within 1 rpm/mph everywhere) is hidden under it: say so
    hidden_under = {form: next((other for other in drawn[:index]
                                if float(np.nanmax(np.abs(sweep.sel(model=form) - sweep.sel(model=other)))) < 1.0),
                               None) for index, form in enumerate(drawn)}
    for form in drawn:
        label = form if hidden_under[form] is None else f"{form} (under {hidden_under[form]})"
        for club in result["club"].values:
            left.plot(result["spin_loft"].sel(model=form, club=club), sweep.sel(model=form, club=club),
                      marker=markers[club], markersize=3.5, lw=1.2, color=colors[form], ls=styles[form],
                      label=label if club == "driver" else None)
    for (label, (low, high)), (x0, x1), above in zip(BANDS.items(), [(12, 17), (20, 50)], (False, True)):
        left.fill_between([x0, x1], low, high, color="0.8", alpha=0.6, zorder=0)
        left.text(x0 + 0.3, high + 2 if above else low - 8, f"measured band, {label}", fontsize=8, color="0.2",
                  bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8, "pad": 1})
    left.scatter([row[6] for row in ROWS], measured, color="k", marker="*", s=110, zorder=5,
                 label="TrackMan tour rows (measured)")
    left.axhline(134.0, color="0.5", ls=":", lw=1)
    left.text(42, 137, "rigid rolling, 200 g head: 134", fontsize=8, color="0.3",
              bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8, "pad": 1})
    left.set_xlabel("spin loft [deg]")
    left.set_ylabel("spin / (club speed x sin spin loft) [rpm/mph]")
    left.set_title("Driver (o), 6-iron (s), PW (^) presets, urethane tour ball; alpha = 1 - e^2 unless 'bound';\n"
                   "dashed: with the friction law (driver: smooth titanium face, irons: grooved, blasted steel)",
                   fontsize=9)
    left.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=4)
    left.set_ylim(0, 260)
    forms = [form for form, _, _ in FORMS]
    middle.barh(range(len(forms)), [wedge_ratio[form] for form in forms], color=[colors[form] for form in forms])
    middle.axvline(ratio_measured, color="k", lw=2)
    middle.axvspan(0.5 * (ratio_measured - 1) + 1, 1.5 * (ratio_measured - 1) + 1, color="0.85", zorder=0)
    middle.text(ratio_measured + 0.02, len(forms) - 0.6, f"measured {ratio_measured:.2f}", fontsize=8)
    middle.set_yticks(range(len(forms)), forms, fontsize=8)
    middle.set_xlabel("wedge spin, urethane / two-piece ionomer")
    middle.set_xlim(0.8, 2.6)
    for index, form in enumerate(forms):
        middle.text(wedge_ratio[form] + 0.02, index, f"{wedge_ratio[form]:.2f}", va="center", fontsize=7.5)
    middle.set_title(f"Wedge cover difference ({observation.name};\nshaded: 0.5-1.5x the measured difference)",
                     fontsize=9)
    for land, marker in ((1.35e-3, "s"), (np.inf, "o")):
        right.plot(roughness * 1e6, 100 * np.array(losses[land]), marker=marker, color="C0" if marker == "s" else "C3",
                   label="grooved (half-land 1.35 mm)" if np.isfinite(land) else "no grooves")
    right.axhspan(100 * min(WET_LOSSES), 100 * max(WET_LOSSES), color="0.85", zorder=0)
    right.text(0.45, 100 * max(WET_LOSSES) + 1.5, "published wet-wedge losses\n(measured, film not stated)",
               fontsize=7.5, color="0.3")
    right.axvline(5.7, color="0.5", ls=":", lw=1)
    right.text(5.55, 80, "Rules' limit\n(the preset)", fontsize=7.5, color="0.4", ha="right")
    right.set_xscale("log")
    right.set_xticks([0.4, 0.7, 1.0, 2.0, 4.0, 5.7], ["0.4", "0.7", "1", "2", "4", "5.7"])
    right.minorticks_off()
    right.set_xlabel("face roughness R_q [um]")
    right.set_ylabel("spin lost to a 20 um water film [%]")
    right.set_ylim(-2, 100)
    right.set_title("Wet face, urethane ball, maw + friction law\n(the wedge observation's delivery)", fontsize=9)
    right.legend(fontsize=8, loc="center right")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"\nwrote {out}")
    return rows_model, wedge_ratio


if __name__ == "__main__":
    main(*sys.argv[1:2])
