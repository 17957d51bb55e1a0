"""Spin per unit of club speed x sin(spin loft) against club speed: the shared file's shots (measured) beside the
plain models and the lever forms (model output), each predicted on the same shots.

    .venv/bin/python -m validation.impact.plot_spin_per_unit   (about a minute)

writes docs/figures/rate_laws_spin_per_unit.png.

The model forms carry the whole-file fits of validation/impact/rate_laws.py (section 4: e_ball 0.742, friction 0.6,
lever 0.054 rigid / 0.0877 Hertz-Mindlin). Medians per 5 mph bin of club speed (bins with at least 40 shots), the
measured interquartile range shaded.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impactlab.data.sessions.shots import predict, table_inputs  # noqa: E402
from impactlab.model.registry import get_model  # noqa: E402
from validation.impact.rate_laws import RPM, apply, spin_loft  # noqa: E402
from validation.impact.shots import MPH, load  # noqa: E402

OUT = Path(__file__).resolve().parents[2] / "docs" / "figures" / "rate_laws_spin_per_unit.png"
VALUES = {"e_ball": 0.742, "friction": 0.6}
FORMS = [("rigid_coulomb (today)", "rigid_coulomb", {}), ("rigid_coulomb + lever 0.054", "rigid_coulomb",
                                                          {"compression_lever": 0.054}),
         ("hertz_mindlin (today)", "hertz_mindlin", {}), ("hertz_mindlin + lever 0.0877", "hertz_mindlin",
                                                           {"compression_lever": 0.0877})]


def main() -> None:
    table, _ = load()
    inputs = apply(table_inputs(table), VALUES, None)
    speed = np.asarray(table.delivery["club_speed"]) / MPH
    unit = speed * np.sin(spin_loft(table))
    edges = np.arange(60.0, 126.0, 5.0)
    centre = 0.5 * (edges[1:] + edges[:-1])
    which = np.digitize(speed, edges) - 1

    def binned(values):
        rows = [values[which == i] for i in range(centre.size)]
        keep = np.array([r.size >= 40 for r in rows])
        return keep, np.array([np.median(r) if r.size else np.nan for r in rows]), np.array(
            [np.percentile(r, [25, 75]) if r.size else [np.nan, np.nan] for r in rows])

    fig, ax = plt.subplots(figsize=(7.5, 4.8))
    keep, median, quartiles = binned(table.measured["spin_rate"] * RPM / unit)
    ax.fill_between(centre[keep], quartiles[keep, 0], quartiles[keep, 1], color="0.85", label="measured, quartiles")
    ax.plot(centre[keep], median[keep], "ko-", label=f"measured (TrackMan file, {table.size} drivers), median")
    curves = {}
    for label, name, options in FORMS:
        out = predict(get_model(name)(**options), inputs)
        _, model_median, _ = binned(out["spin_rate"] * RPM / unit)
        curves[label] = model_median[keep]
        ax.plot(centre[keep], model_median[keep], "--" if "today" in label else "-", marker=".", label=label)
    # say where one curve lies under another (within 1 rpm/mph over three bins or more), so none is hidden unsaid
    notes = []
    labels = list(curves)
    for i, first in enumerate(labels):
        for second in labels[i + 1:]:
            close = np.abs(curves[first] - curves[second]) <= 1.0
            if close.sum() >= 3:
                speeds = centre[keep][close]
                notes.append(f"{first} and {second} within 1 rpm/mph at {speeds.min():.1f}-{speeds.max():.1f} mph "
                             f"({close.sum()} bins): one lies under the other there")
    if notes:
        import textwrap

        ax.text(0.01, 0.01, "\n".join(textwrap.fill(note, 70) for note in notes), transform=ax.transAxes, fontsize=7,
                va="bottom", bbox={"facecolor": "white", "alpha": 0.8, "edgecolor": "none"})
    ax.set_xlabel("club speed [mph] (5 mph bins, >= 40 shots)")
    ax.set_ylabel("spin / (club speed x sin spin loft) [rpm/mph]")
    ax.set_title("Driver spin per unit of V sin(spin loft): measured beside the models\n"
                 "(whole-file fits: e_ball 0.742, head COR 0.825; models predicted on the same shots)", fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT, dpi=110)
    print(f"wrote {OUT}")


if __name__ == "__main__":
    main()
