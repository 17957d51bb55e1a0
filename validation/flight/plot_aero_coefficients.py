"""Lift and drag coefficients against the spin ratio: the measurements measured_fit is fitted to, and the models.

Draws docs/figures/aero_coefficients.png from impactlab/data/validation/aero_coefficients.yaml (every row a
measurement, marker per ball group, filled above the ball's drag crisis, open in it) and the coefficient models of
impactlab.physics.aerodynamics at three Reynolds numbers (docs/flight.md).

Run from the project root: ``.venv/bin/python -m validation.flight.plot_aero_coefficients`` (a few seconds).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from validation.flight.aero_fit import GROUPS, measurements  # noqa: E402
from impactlab.physics.aerodynamics import aero_coefficients  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
LABELS = {"modern": "modern balls (Lyu 2018/2020, Bridgestone)", "usga_1998": "USGA ITR ball (c. 1998)",
          "bh_1976": "Bearman & Harvey 1976", "naruo_2004": "Naruo et al. 2004 (Skyway, wind tunnel)",
          "acushnet_invention": "Acushnet US 6,729,976 ball", "acushnet_prior_art": "Acushnet's prior-art ball"}
MARKERS = {"modern": "o", "usga_1998": "s", "bh_1976": "^", "naruo_2004": "D", "acushnet_invention": "v",
           "acushnet_prior_art": "<"}
#: Re -> (colour, line style, marker): the Re 1e5 and 2e5 lift curves nearly coincide, the markers keep both visible
CURVES = {6.0e4: ("tab:red", "-", None), 1.0e5: ("tab:green", "-.", "x"), 2.0e5: ("tab:blue", ":", "+")}


def main() -> Path:
    m = measurements()
    s_grid = np.linspace(0.0, 1.15, 231)
    fig, axes = plt.subplots(1, 2, figsize=(11, 5.6))
    for index, group in enumerate(GROUPS):
        rows = m["group"] == index
        for above, fill in ((True, None), (False, "none")):
            sel = rows & (m["supercritical"] == above)
            label = LABELS[group] + ("" if above else ", in its drag crisis")
            for ax, key in zip(axes, ("cl", "cd")):
                ok = sel & np.isfinite(m[key])
                if ok.any():
                    ax.scatter(m["s"][ok], m[key][ok], marker=MARKERS[group], s=16, facecolors=fill,
                               edgecolors="0.3" if above else "0.55", c=None if fill else "0.3", linewidths=0.7,
                               label=label if key == "cl" else None)
    lifts = {}
    for re, (colour, style, marker) in CURVES.items():
        cd, cl = aero_coefficients(s_grid, re, model="measured_fit")
        kwargs = {"color": colour, "linestyle": style, "marker": marker, "markevery": 20, "linewidth": 1.6}
        # a lift curve that lies on an earlier one says so (above the crisis the lift does not depend on Re)
        on = next((f"{other:.0e}" for other, lift in lifts.items() if np.allclose(lift, cl, atol=2e-3)), None)
        lifts[re] = cl
        axes[0].plot(s_grid, cl, label=f"measured_fit, Re {re:.0e}" + (f" (lift on Re {on}'s)" if on else ""),
                     **kwargs)
        axes[1].plot(s_grid, cd, **kwargs)
    cd, cl = aero_coefficients(s_grid, 1.5e5, model="smits_smith_1994")
    axes[0].plot(s_grid, cl, "k--", label="smits_smith_1994, Re 1.5e5")
    axes[1].plot(s_grid, cd, "k--")
    axes[0].set_ylabel("lift coefficient C_L")
    axes[1].set_ylabel("drag coefficient C_D")
    for ax in axes:
        ax.set_xlabel("spin ratio S = R omega / v")
        ax.set_xlim(0, 1.15)
        ax.grid(alpha=0.3)
    axes[1].text(0.72, 0.12, "above S 0.4 measured_fit's drag at the three Re coincides:\nthe crisis has moved "
                 "below Re 6e4 there", fontsize=7.5, ha="center")
    axes[0].set_ylim(-0.2, 0.6)
    axes[1].set_ylim(0.1, 0.6)
    fig.legend(*axes[0].get_legend_handles_labels(), fontsize=7.5, loc="lower center", ncol=3, frameon=False)
    fig.suptitle("Measured golf-ball lift and drag (aero_coefficients.yaml) and the coefficient models\n"
                 "measured_fit's drag is the modern balls' (the other balls' fitted offsets are 0.00-0.04 higher)",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    out = ROOT / "docs" / "figures" / "aero_coefficients.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


if __name__ == "__main__":
    print(main())
