"""The ball's drag level c0: what the measured radar flights want, and what the held-out tour tables then show.

Draws docs/figures/flight_fit_c0.png (docs/flight.md, "Settling the drag level on measured flights"):

- left: carry RMS against c0 (measured_fit with every other coefficient as fitted to measured CD and CL) on the PGA
  TOUR radar seasons (the fit) and on each of TrackMan's three tour tables without their driver rows (held out); the
  band is the range of the measured balls' drag offsets, the lines the modern balls', the fitted and the 1998 USGA
  ball's c0. The tables' curves are drawn after the fit, as a diagnostic: nothing was chosen on them.
- right: each held-out table row's carry error at the fitted c0 against its launch spin ratio S = R omega / v.

Run from the project root: ``.venv/bin/python -m validation.flight.plot_flight_fit_c0`` (about ten seconds).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from validation.flight import flight_fit  # noqa: E402
from impactlab.data.carry import TABLES, carry_table, validate_carry  # noqa: E402
from impactlab.physics.aerodynamics import BALL_RADIUS, MEASURED_FIT_OFFSETS  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
STYLE = {"trackman_carry": ("tab:blue", "s", "classic PGA table"),
         "trackman_carry_pga_2023": ("tab:orange", "^", "PGA 2023 table"),
         "trackman_carry_lpga_2023": ("tab:green", "D", "LPGA 2023 table")}


def main() -> Path:
    grid = np.linspace(flight_fit.C0_BOUNDS[0] - 0.003, flight_fit.C0_BOUNDS[1] + 0.003, 46)
    source = carry_table(flight_fit.SOURCES[0])
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.2))
    ax = axes[0]
    lo, hi = flight_fit.C0_BOUNDS
    ax.axvspan(lo, hi, color="0.92", label="measured balls' drag offsets (bounds)")
    fit_rms = [validate_carry(flight_fit.coefficients(c0), source)["rms_carry_error"] for c0 in grid]
    ax.plot(grid, 100 * np.array(fit_rms), "k-", linewidth=2.2, label="PGA TOUR radar seasons (fitted)")
    for name in TABLES:
        colour, marker, label = STYLE[name]
        table = carry_table(name)
        other = np.array([club != "Driver" for club in table.clubs])
        rms = [np.sqrt(np.mean(validate_carry(flight_fit.coefficients(c0), table)["carry_error"][other] ** 2))
               for c0 in grid]
        ax.plot(grid, 100 * np.array(rms), color=colour, marker=marker, markevery=6, linestyle="--",
                label=f"{label} without driver (held out)")
    modern, usga = MEASURED_FIT_OFFSETS["modern"], MEASURED_FIT_OFFSETS["usga_1998"]
    for c0, text, style, side in ((modern, f"modern balls {modern:.4f}", ":", "right"),
                                  (flight_fit.FITTED["c0"], f"fitted {flight_fit.FITTED['c0']:.4f}", "-", "left"),
                                  (usga, f"USGA 1998 ball {usga:.4f}", "-.", "left")):
        ax.axvline(c0, color="0.3", linestyle=style, linewidth=1.0)
        ax.text(c0, 5.6, text, rotation=90, va="bottom", ha=side, fontsize=8, color="0.25")
    ax.axhline(3.0, color="tab:red", linewidth=1.0)
    ax.text(grid[-1], 3.1, "3 % target", color="tab:red", ha="right", va="bottom", fontsize=8)
    ax.set_xlim(grid[0], grid[-1])
    ax.set_ylim(0, 11)
    ax.set_xlabel("supercritical drag level c0")
    ax.set_ylabel("carry RMS error, %")
    ax.set_title("carry RMS against the ball's drag level")
    ax.legend(fontsize=8, loc="lower right")
    ax = axes[1]
    for name, check in flight_fit.held_out(flight_fit.FITTED["c0"]).items():
        colour, marker, label = STYLE[name]
        table = check["table"]
        s0 = BALL_RADIUS * table.spin_rate / table.ball_speed
        ax.plot(s0, 100 * check["carry_error"], marker=marker, color=colour, linestyle="none", markersize=7,
                label=f"{label}: RMS {100 * check['rms_carry_error']:.1f} %")
        for i, club in enumerate(table.clubs):
            if name == "trackman_carry" and club in ("Driver", "3-wood", "5-wood", "Hybrid", "5-iron", "7-iron",
                                                     "PW"):
                ax.annotate(club, (s0[i], 100 * check["carry_error"][i]), textcoords="offset points",
                            xytext=(4, -10), fontsize=7, color="0.3")
    ax.axhspan(-3, 3, color="0.92", label="+-3 %")
    ax.axhline(0, color="0.4", linewidth=0.8)
    ax.set_xlabel("launch spin ratio S = R omega / v")
    ax.set_ylabel("carry error at the fitted c0 (model / TrackMan - 1), %")
    ax.set_title(f"held out: TrackMan's tour tables at c0 {flight_fit.FITTED['c0']:.4f}")
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(alpha=0.3)
    fig.suptitle("The drag level fitted to measured radar flights (PGA TOUR tee-shot seasons), tour tables held out",
                 fontsize=11)
    fig.tight_layout()
    path = ROOT / "docs" / "figures" / "flight_fit_c0.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


if __name__ == "__main__":
    print(main())
