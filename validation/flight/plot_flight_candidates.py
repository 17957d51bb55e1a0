"""The drag crisis and its advance with spin: what they do to the tour tables' held-out carries, and what the measured
drag says.

Draws docs/figures/flight_candidates.png (docs/flight.md, "Which change moves the spin-ratio residual"):

- left: each tour-table row's carry error (model over TrackMan minus 1, held out: nothing of the tables fitted)
  against its launch spin ratio, c0 fitted on the PGA TOUR radar seasons, with ``measured_fit``'s crisis advancing
  with spin (filled) and with the crisis refitted at one position for every spin (m = 0, open markers);
- middle: carry RMS against the spin advance m (Re_d exp(-m S)), c0 fitted on the radar seasons at each (seasons:
  black; the three tables: colours); the measured m +- 2 sigma shaded;
- right: CD against Re at 2250 rpm and without spin, measured_fit and the crisis without the advance, beside the
  measured rows: three modern balls at 2250 rpm (Lyu, Kensrud & Smith 2020, Fig. 3) and the 13-ball non-spinning
  mean (Lyu et al. 2018, Fig. 3a).

Run from the project root: ``.venv/bin/python -m validation.flight.plot_flight_candidates`` (about half a minute).
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from validation.flight import aero_fit, flight_candidates  # noqa: E402
from impactlab.data.carry import TABLES, carry_table  # noqa: E402
from impactlab.physics.aerodynamics import BALL_RADIUS, MEASURED_FIT  # noqa: E402
from impactlab.physics.atmosphere import air_density, air_viscosity  # noqa: E402

from flight_fit_c0 import STYLE  # noqa: E402  (docs/: each table's colour, marker and name, as in that figure)

ROOT = Path(__file__).resolve().parents[2]


def _radar_fit(**fixed) -> dict:
    return flight_candidates.fit((flight_candidates.RADAR,), ("c0",), fixed)


def main() -> Path:
    fig, axes = plt.subplots(1, 3, figsize=(17, 6.0))
    ax = axes[0]
    advanced, held = _radar_fit(), _radar_fit(crisis_spin_advance=0.0)
    for name in TABLES:
        colour, marker, label = STYLE[name]
        table = carry_table(name)
        s = BALL_RADIUS * table.spin_rate / table.ball_speed
        without = flight_candidates.flights(held, name)
        with_ = flight_candidates.flights(advanced, name)
        ax.plot(s, 100 * without["carry_error"], marker=marker, color=colour, linestyle="none",
                markerfacecolor="none", label=f"{label}: crisis at one Re, m = 0 "
                                              f"({100 * without['rms_carry_error']:.1f} % RMS)")
        ax.plot(s, 100 * with_["carry_error"], marker=marker, color=colour, linestyle="none",
                label=f"{label}: measured_fit, crisis advanced by spin ({100 * with_['rms_carry_error']:.1f} % RMS)")
    ax.axhspan(-3, 3, color="0.93", zorder=0, label="within 3 % (the target's RMS)")
    ax.axhline(0, color="0.5", linewidth=0.8)
    ax.set_xlabel("launch spin ratio S = R omega / v")
    ax.set_ylabel("carry error, model / TrackMan - 1 (%)")
    ax.set_title("Held-out tour tables, c0 fitted on the radar seasons")
    # the legend under the axes: above the points it hid some of them
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1)

    ax = axes[1]
    advances = np.array([0.0, 0.3, 0.6, 0.87, 1.0, 1.27, 1.5, 1.68, 2.0])
    fits = [_radar_fit(crisis_spin_advance=float(m)) for m in advances]
    scores = [flight_candidates.score(params) for params in fits]
    ax.plot(advances, [100 * s[flight_candidates.RADAR]["rms"] for s in scores], "k-o", linewidth=2,
            label="PGA TOUR radar seasons (c0 fitted here)")
    for name in TABLES:
        colour, marker, label = STYLE[name]
        ax.plot(advances, [100 * s[name]["rms"] for s in scores], color=colour, marker=marker, linestyle="--",
                label=f"{label} (held out)")
    low, high = flight_candidates.PARAMETERS["crisis_spin_advance"][0]
    ax.axvspan(low, high, color="0.9", label="measured m +- 2 sigma (Lyu 2018, 2020 rows)")
    ax.axvline(MEASURED_FIT["m"], color="0.4", linestyle=":", label=f"measured_fit, m = {MEASURED_FIT['m']:.2f}")
    ax.axhline(3, color="0.5", linewidth=0.8)
    ax.set_xlabel("spin advance m of the crisis midpoint Re_d exp(-m S)\n(Re_d, w_d, d: measured_fit's; at m = 0 the "
                  "crisis refitted without the advance)")
    ax.set_ylabel("carry RMS (%)")
    ax.set_title("Without the advance the tables miss 3 %; the seasons cannot place m")
    ax.legend(fontsize=7, loc="upper right")

    ax = axes[2]
    rho, mu = air_density(293.15, 101325.0, 0.5), air_viscosity(293.15)
    re = np.linspace(4.0e4, 1.3e5, 400)
    speed = re * mu / (rho * 2 * BALL_RADIUS)
    spin = 2250 * np.pi / 30 * BALL_RADIUS / speed
    models = (("measured_fit (crisis advanced by spin)", flight_candidates.coefficients(), "-"),
              ("crisis at one Re (m = 0, refitted)", flight_candidates.coefficients(crisis_spin_advance=0.0), "--"))
    for label, model, style in models:
        ax.plot(re, model(spin, re)[0], color="tab:red", linestyle=style, label=f"{label}, 2250 rpm")
        ax.plot(re, model(0.0 * re, re)[0], color="0.3", linestyle=style, label=f"{label}, no spin")
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
