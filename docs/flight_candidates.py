"""The drag crisis' position: what it does to the tour tables' held-out carries, and what the measured drag says.

Draws docs/figures/flight_candidates.png (docs/flight.md, "Which change removes the spin-ratio residual"):

- left: each tour-table row's carry error (model over TrackMan minus 1, held out: nothing of the tables fitted)
  against its launch spin ratio, with the drag level fitted on the PGA TOUR radar seasons (impactlab.data.flight_fit,
  open markers) and with ``measured_fit_late_crisis`` (filled);
- middle: carry RMS against the drag-crisis midpoint Re_d, c0 fitted on the radar seasons at each (seasons: black;
  the three tables: colours); grey beyond the measured positions' upper edge;
- right: CD against Re of measured_fit, of the late crisis and of the crisis advanced by spin (refitted on the same
  rows, :func:`impactlab.data.aero_fit.fit_spin_advance`) at 2250 rpm and without spin, beside the measured rows:
  three modern balls at 2250 rpm (Lyu, Kensrud & Smith 2020, Fig. 3) and the 13-ball non-spinning mean (Lyu et al.
  2018, Fig. 3a).

Run from the project root: ``.venv/bin/python docs/flight_candidates.py`` (about half a minute).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from impactlab.data import aero_fit, flight_candidates, flight_fit  # noqa: E402
from impactlab.data.carry import TABLES, carry_table, validate_carry  # noqa: E402
from impactlab.physics.aerodynamics import BALL_RADIUS, MEASURED_FIT, aero_coefficients  # noqa: E402
from impactlab.physics.atmosphere import air_density, air_viscosity  # noqa: E402

from flight_fit_c0 import STYLE  # noqa: E402  (docs/: each table's colour, marker and name, as in that figure)

ROOT = Path(__file__).resolve().parent.parent


def main() -> Path:
    fig, axes = plt.subplots(1, 3, figsize=(17, 6.0))
    ax = axes[0]
    for name in TABLES:
        colour, marker, label = STYLE[name]
        table = carry_table(name)
        s = BALL_RADIUS * table.spin_rate / table.ball_speed
        before = validate_carry(flight_fit.coefficients(flight_fit.FITTED["c0"]), table)
        after = validate_carry("measured_fit_late_crisis", table)
        ax.plot(s, 100 * before["carry_error"], marker=marker, color=colour, linestyle="none", markerfacecolor="none",
                label=f"{label}: drag level only ({100 * before['rms_carry_error']:.1f} % RMS)")
        ax.plot(s, 100 * after["carry_error"], marker=marker, color=colour, linestyle="none",
                label=f"{label}: late crisis ({100 * after['rms_carry_error']:.1f} % RMS)")
    ax.axhspan(-3, 3, color="0.93", zorder=0, label="within 3 % (the target's RMS)")
    ax.axhline(0, color="0.5", linewidth=0.8)
    ax.set_xlabel("launch spin ratio S = R omega / v")
    ax.set_ylabel("carry error, model / TrackMan - 1 (%)")
    ax.set_title("Held-out tour tables, c0 fitted on the radar seasons")
    # the legend under the axes: above the points it hid some of them
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2)

    ax = axes[1]
    scan = flight_candidates.crisis_scan(tuple(np.round(np.arange(0.95, 1.351, 0.05), 2)))
    re_d = np.array([row["crisis_shift"] for row in scan]) * MEASURED_FIT["re_d"]
    ax.plot(re_d, [100 * row["score"][flight_candidates.RADAR]["rms"] for row in scan], "k-o", linewidth=2,
            label="PGA TOUR radar seasons (c0 fitted here)")
    for name in TABLES:
        colour, marker, label = STYLE[name]
        ax.plot(re_d, [100 * row["score"][name]["rms"] for row in scan], color=colour, marker=marker,
                linestyle="--", label=f"{label} (held out)")
    high = flight_candidates.PARAMETERS["crisis_shift"][0][1] * MEASURED_FIT["re_d"]
    ax.axvspan(high, re_d[-1] + 1000, color="0.9", label="beyond the measured crisis positions")
    ax.axvline(MEASURED_FIT["re_d"], color="0.4", linestyle=":", label="measured_fit (three spinning balls)")
    ax.axhline(3, color="0.5", linewidth=0.8)
    ax.set_xlabel("drag-crisis midpoint Re_d")
    ax.set_ylabel("carry RMS (%)")
    ax.set_title("Within the measured positions only the tables place the crisis")
    ax.legend(fontsize=7, loc="upper right")

    ax = axes[2]
    rho, mu = air_density(293.15, 101325.0, 0.5), air_viscosity(293.15)
    re = np.linspace(4.0e4, 1.3e5, 400)
    speed = re * mu / (rho * 2 * BALL_RADIUS)
    spin = 2250 * np.pi / 30 * BALL_RADIUS / speed
    for model, style in (("measured_fit", "-"), ("measured_fit_late_crisis", "--")):
        ax.plot(re, aero_coefficients(spin, re, model)[0], color="tab:red", linestyle=style,
                label=f"{model}, 2250 rpm")
        ax.plot(re, aero_coefficients(0.0 * re, re, model)[0], color="0.3", linestyle=style,
                label=f"{model}, no spin")
    # the crisis refitted on the same rows with its midpoint moving with spin (aero_fit.fit_spin_advance)
    advance = flight_candidates.CANDIDATES["crisis advanced by spin (measured)"][1]["crisis_spin_advance"]
    advanced = flight_candidates.coefficients(crisis_spin_advance=advance)
    for s, style, label in ((spin, "-", "2250 rpm"), (0.0 * re, "--", "no spin"),
                            (0.35 + 0.0 * re, ":", "S 0.35 (a long iron's descent)")):
        ax.plot(re, advanced(s, re)[0], color="tab:blue", linestyle=style, linewidth=1.2,
                label=f"crisis advanced by spin (fitted on these rows), {label}")
    m = aero_fit.measurements()
    spinning = np.isin(m["block"], ["lyu_2020_fig3_prov1", "lyu_2020_fig3_chromesoft", "lyu_2020_fig3_b330rx"])
    ax.plot(m["re"][spinning], m["cd"][spinning], "o", color="tab:red", markerfacecolor="none",
            label="measured, 3 modern balls at 2250 rpm (Lyu 2020)")
    still = m["block"] == "lyu_2018_fig3a"
    ax.plot(m["re"][still], m["cd"][still], "s", color="0.3", markerfacecolor="none",
            label="measured, 13-ball mean, no spin (Lyu 2018)")
    ax.set_xlim(re[0], re[-1])
    ax.set_xticks(np.arange(4.0e4, 1.31e5, 2.0e4))
    ax.set_ylim(0.15, 0.55)
    ax.set_xlabel("Reynolds number")
    ax.set_ylabel("C_D")
    ax.set_title("The crisis models against the measured drag:\nspin moves the crisis to lower Re\n"
                 "(2250 rpm: its spin ratio at each Re in air at 20 degC)", fontsize=10)
    ax.legend(fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.17), ncol=1)
    fig.tight_layout()
    out = ROOT / "docs" / "figures" / "flight_candidates.png"
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


if __name__ == "__main__":
    print(main())
