"""The driver's carry against air density: the PGA TOUR radar's measured dose-response beside the flight models.

Draws docs/figures/flight_altitude.png (docs/flight.md, "Carry against air density"):

- left: carry gain (per cent, against the seasons' density 0.992) at the seasons' mean driver launch, against the air
  density ratio (of dry air at 25 degC and 101 325 Pa), the density changed by the pressure at 25 degC; the measured
  lines (raw and launch-adjusted, over the 40 events' range, dashed beyond it) and the altitude venues (raw filled,
  launch-adjusted open); models as flown, and with their coefficients held at the seasons' Re (dotted: a diagnostic).
- right: the plane of c0 and lift scale within their measured bounds: the density slope (colour; the measured bracket
  0.38-0.52 is reached nowhere in it), where the seasons' mean hang time is met (black: 0 and +0.2 s) and where their
  mean carry is (white), and two fits of the table in docs/flight.md.

Run from the project root: ``.venv/bin/python -m validation.flight.plot_flight_altitude`` (about half a minute).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from validation.flight import flight_altitude as fa  # noqa: E402
from validation.flight import flight_fit  # noqa: E402
from impactlab.data.carry import TABLES, carry_table, validate_carry  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


def main() -> Path:
    doc = fa.evidence()
    season = doc["season_density_ratio"]
    carry_2023 = carry_table(flight_fit.SOURCES[0]).carry[-1] / 0.9144
    ratios = np.linspace(0.76, 1.07, 14)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.4))
    ax = axes[0]
    for key, style, label in (("raw", "-", "measured, raw (40 events)"),
                              ("launch_adjusted", "-", "measured, launch-adjusted (40 events)")):
        line = doc["dose_response"][key]
        colour = "k" if key == "raw" else "0.45"
        inside = np.linspace(*doc["dose_response"]["density_range"], 5)
        beyond = np.linspace(0.76, doc["dose_response"]["density_range"][0], 5)
        for x, ls in ((inside, style), (beyond, "--")):
            ax.plot(x, 100 * (line["intercept"] + line["slope"] * x) / carry_2023, color=colour, linestyle=ls,
                    linewidth=2.0, label=label if ls == style else None)
    for event in doc["events"]:
        x = event["density_ratio"]
        ax.plot([x, x], [event["adjusted_percent"], event["carry_percent"]], color="tab:red", linewidth=1.0)
        ax.plot(x, event["carry_percent"], "o", color="tab:red", markersize=5)
        ax.plot(x, event["adjusted_percent"], "o", mfc="white", color="tab:red", markersize=5)
        if "Chapultepec" not in event["venue"] or event["event"].endswith("2017"):
            name = {"Club de Golf Chapultepec": "Chapultepec\n(4 years)", "Castle Pines Golf Club": "Castle Pines",
                    "Old Greenwood": "Old\nGreenwood"}.get(event["venue"], event["venue"])
            if name.startswith("Chapultepec"):  # at the plot's left edge: below the cluster, with an arrow
                ax.annotate(name, (x, event["adjusted_percent"]), xytext=(0.79, 1.0), textcoords="data", fontsize=8,
                            color="tab:red", arrowprops={"arrowstyle": "-", "color": "tab:red", "linewidth": 0.6})
                continue
            offset = {"Castle Pines": (-28, 8), "Old\nGreenwood": (7, -4)}[name]
            ax.annotate(name, (x, event["carry_percent"]), textcoords="offset points", xytext=offset, fontsize=8,
                        color="tab:red")
    ax.plot([], [], "o", color="tab:red", label="altitude venues (raw; open: launch-adjusted)")
    ax.plot([], [], "k--", linewidth=2.0, label="measured lines extrapolated below the 40 events' densities")
    models = (("measured_fit", "measured_fit", "tab:blue"),
              (f"fitted: c0 {fa.FITTED['c0']:.3f}, lift x {fa.FITTED['lift_scale']:.3f}",
               fa.coefficients(**fa.FITTED), "tab:purple"),
              ("smits_smith_1994", "smits_smith_1994", "tab:green"),
              ("usga_patent_2001", "usga_patent_2001", "tab:olive"))
    for label, model, colour in models:
        for frozen, ls in ((False, "-"), (True, ":")):
            r = fa.density_response(model, ratios=ratios, freeze_re=frozen)
            ax.plot(ratios, 100 * r["gains"], color=colour, linestyle=ls, linewidth=1.6,
                    label=label + (" (Re frozen)" if frozen and colour in ("tab:blue", "tab:purple") else "")
                    if not frozen or colour in ("tab:blue", "tab:purple") else None)
    ax.axvline(season, color="0.6", linewidth=0.8)
    ax.axhline(0.0, color="0.6", linewidth=0.8)
    ax.set_xlabel("air density / dry air at 25 degC, 101 325 Pa")
    ax.set_ylabel("driver carry gain against the seasons' air, %")
    ax.set_title("Carry against density at the seasons' mean driver launch")
    ax.legend(fontsize=7, loc="upper right")
    ax.set_xlim(0.76, 1.07)

    ax = axes[1]
    c0s = np.linspace(*fa.BOUNDS["c0"], 7)
    scales = np.linspace(*fa.BOUNDS["lift_scale"], 7)
    slope = np.empty((len(scales), len(c0s)))
    hang = np.empty_like(slope)
    rms = np.empty_like(slope)
    table = carry_table(flight_fit.SOURCES[0])
    for i, scale in enumerate(scales):
        for j, c0 in enumerate(c0s):
            model = fa.coefficients(c0, scale)
            slope[i, j] = fa.density_response(model, ratios=())["relative"]
            check = validate_carry(model, table)
            hang[i, j] = np.nanmean(check["flight_time"] - table.flight_time)
            rms[i, j] = np.mean(check["carry_error"])
    low, high = fa.bracket()["relative"]
    filled = ax.contourf(c0s, scales, slope, levels=np.linspace(0.1, 0.55, 10), cmap="viridis")
    fig.colorbar(filled, ax=ax, label="% carry per % density (model)")
    assert slope.max() < low, "the bracket is reached: draw its contour"  # it is not, anywhere in the bounds
    hangs = ax.contour(c0s, scales, hang, levels=[0.0, 0.2], colors="k", linewidths=1.2)
    ax.clabel(hangs, fmt={0.0: "hang 0 s", 0.2: "+0.2 s"}, fontsize=7)
    met = ax.contour(c0s, scales, rms, levels=[0.0], colors="white", linestyles="--", linewidths=1.5)
    ax.clabel(met, fmt={0.0: "seasons' carry met"}, fontsize=7)
    def held(params) -> str:  # the three tour tables' carry RMS, flown with params (nothing of them fitted)
        scores = fa.held_out({"crisis_shift": 1.0, "lift_loss_shift": 1.0, **params})
        return " / ".join(f"{100 * scores[name]['rms']:.1f}" for name in TABLES)

    ax.plot(fa.FITTED["c0"], fa.FITTED["lift_scale"], "r*", markersize=12,
            label=f"fitted with the density slope (held out {held(fa.FITTED)} %)")
    ax.plot(flight_fit.FITTED["c0"], 1.0, "ws", markersize=7, mec="k", label="flight_fit: c0 on carry only "
            f"(held out {held({'c0': flight_fit.FITTED['c0'], 'lift_scale': 1.0})} %)")
    ax.set_xlabel("c0 (bounds: measured balls' drag offsets)")
    ax.set_ylabel("lift scale (bounds: measured CL rows, S <= 0.2)")
    ax.set_title(f"Density slope over the bounded parameters: at most {slope.max():.2f}, "
                 f"measured {low:.2f}-{high:.2f}\n(black: seasons' hang time met, +0.2 s; white: their carry met)",
                 fontsize=10)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    out = ROOT / "docs" / "figures" / "flight_altitude.png"
    fig.savefig(out, dpi=110)
    return out


if __name__ == "__main__":
    print(main())
