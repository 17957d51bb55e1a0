"""Ball laws against launch data: spin per unit of club speed x sin(spin loft), and the wedge cover difference.

Runs studies/ball_laws.yaml (spin loft swept for the driver, 6-iron and pitching-wedge presets), the four TrackMan
tour rows of the physics brief (section 12: PGA and LPGA driver and 6-iron; club speed, attack angle, dynamic loft,
measured spin; their spin lofts 14.7, 15.0, 24.3, 25.9 deg from TrackMan's spin-loft pages) and the Titleist
WedgeCraft wedge test (physics_lit.md section 4: 58 deg wedge, 75 yd, Pro V1 8,300 rpm against a two-piece Surlyn
ball 5,600 rpm, measured by the manufacturer; club speed and loft not stated, so 62 mph, dynamic loft 48 deg and
attack -4 deg are assumed here), for each combination of forms; prints the tables and draws
docs/figures/ball_laws_spin_per_unit.png.

Run from the project root: ``.venv/bin/python docs/ball_laws.py`` (about 30 s).
"""

from __future__ import annotations

import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import impactlab  # noqa: E402
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
WEDGE_MEASURED = {"tour_urethane": 8300.0, "two_piece_ionomer": 5600.0}
WEDGE_DELIVERY = (62.0, 48.0, -4.0)  # mph, dynamic loft deg, attack deg: assumed (the test does not state them)
FORMS = [("rigid_coulomb", "rigid_coulomb", {}),
         ("rigid_rolling", "rigid_coulomb", {"rolling_hysteresis": "restitution"}),
         ("maw", "maw", {}),
         ("maw_rolling", "maw", {"rolling_hysteresis": "restitution"}),
         ("maw_rolling_bound", "maw", {"rolling_hysteresis": 1.0}),
         ("maw_hysteretic_rolling", "maw", {"inelastic": "hysteretic", "rolling_hysteresis": "restitution"})]


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


def main(out=ROOT / "docs" / "figures" / "ball_laws_spin_per_unit.png"):
    result = impactlab.run_study(impactlab.load_study(ROOT / "studies" / "ball_laws.yaml"))
    speeds = result["club_speed"].values / MPH
    sweep = per_unit(result["spin_rate"], speeds[None, :, None], result["spin_loft"])

    measured = np.array([per_unit(row[5], row[2], row[6]) for row in ROWS])
    tour = scene_inputs([("tour_urethane", *row[1:5]) for row in ROWS])
    print("TrackMan tour rows: spin per (club speed mph x sin spin loft), rpm/mph (measured: physics brief s12)")
    print(f"  {'form':24s}" + "".join(f"{row[0]:>13s}" for row in ROWS))
    print(f"  {'measured':24s}" + "".join(f"{value:13.1f}" for value in measured))
    rows_model = {}
    for form, name, options in FORMS:
        out_ = get_model(name)(**options).compute(tour, ["spin_rate", "spin_loft"])
        values = per_unit(out_["spin_rate"].values, np.array([row[2] for row in ROWS]), out_["spin_loft"].values)
        rows_model[form] = values
        print(f"  {form:24s}" + "".join(f"{value:13.1f}" for value in values))

    speed, loft, attack = WEDGE_DELIVERY
    wedge = scene_inputs([(ball, "pitching_wedge", speed, attack, loft) for ball in WEDGE_MEASURED])
    ratio_measured = WEDGE_MEASURED["tour_urethane"] / WEDGE_MEASURED["two_piece_ionomer"]
    print(f"\nWedge cover test (Titleist WedgeCraft, measured urethane/ionomer spin {ratio_measured:.2f}; "
          f"delivery assumed {speed:.0f} mph, loft {loft:.0f}, attack {attack:.0f} deg)")
    wedge_ratio = {}
    for form, name, options in FORMS:
        spin = get_model(name)(**options).compute(wedge, ["spin_rate"])["spin_rate"].values
        wedge_ratio[form] = spin[0] / spin[1]
        print(f"  {form:24s} urethane {spin[0]:7.0f}  ionomer {spin[1]:7.0f}  ratio {spin[0] / spin[1]:.3f}")

    fig, (left, right) = plt.subplots(1, 2, figsize=(13, 5.2), gridspec_kw={"width_ratios": [2.2, 1]})
    colors = dict(zip([form for form, _, _ in FORMS], plt.cm.tab10.colors))
    markers = {"driver": "o", "6_iron": "s", "pitching_wedge": "^"}
    for form in result["model"].values:
        for club in result["club"].values:
            left.plot(result["spin_loft"].sel(model=form, club=club), sweep.sel(model=form, club=club),
                      marker=markers[club], markersize=3.5, lw=1.2, color=colors[form],
                      label=form if club == "driver" else None)
    for (label, (low, high)), (x0, x1) in zip(BANDS.items(), [(12, 17), (20, 50)]):
        left.fill_between([x0, x1], low, high, color="0.8", alpha=0.6, zorder=0)
        left.text(x0 + 0.3, high + 2, f"measured band, {label}", fontsize=8, color="0.3")
    left.scatter([row[6] for row in ROWS], measured, color="k", marker="*", s=110, zorder=5,
                 label="TrackMan tour rows (measured)")
    left.axhline(134.0, color="0.5", ls=":", lw=1)
    left.text(42, 136, "rigid rolling, 200 g head: 134", fontsize=8, color="0.4")
    left.set_xlabel("spin loft [deg]")
    left.set_ylabel("spin / (club speed x sin spin loft) [rpm/mph]")
    left.set_title("Driver (o), 6-iron (s), PW (^) presets, tour urethane ball; alpha = 1 - e^2 unless 'bound'",
                   fontsize=9)
    left.legend(fontsize=7.5, loc="lower right")
    left.set_ylim(0, 260)
    forms = [form for form, _, _ in FORMS]
    right.barh(range(len(forms)), [wedge_ratio[form] for form in forms], color=[colors[form] for form in forms])
    right.axvline(ratio_measured, color="k", lw=2)
    right.axvspan(0.5 * (ratio_measured - 1) + 1, 1.5 * (ratio_measured - 1) + 1, color="0.85", zorder=0)
    right.text(ratio_measured + 0.01, len(forms) - 0.6, f"measured {ratio_measured:.2f}", fontsize=8)
    right.set_yticks(range(len(forms)), forms, fontsize=8)
    right.set_xlabel("wedge spin, urethane / two-piece ionomer")
    right.set_xlim(0.9, 1.7)
    right.set_title("Wedge cover difference (58 deg, 75 yd; band: 0.5-1.5x the\nmeasured difference)", fontsize=9)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"\nwrote {out}")
    return rows_model, wedge_ratio


if __name__ == "__main__":
    main(*sys.argv[1:2])
