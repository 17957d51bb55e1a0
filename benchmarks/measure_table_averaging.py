"""Do the tour tables' averages explain the spin-ratio residual? (docs/flight.md, "Which change removes the
spin-ratio residual": "What remains").

A tour table's carry is the mean of many shots' carries, flown in the weather of many events; the model flies the
mean launch in still air. Two averaging effects could make the table's carry shorter than the model's, and more for
some clubs than others:

1. **Launch spread** (Jensen's inequality): the mean carry of launches spread around the mean launch is not the
   carry of the mean launch where carry is curved in the launch. Spreads assumed (not published per club by
   TrackMan): ball speed +-4 and +-6 mph, launch angle +-1.5 and +-2.5 deg, spin +-12 and +-20 % (one sigma, normal).
2. **Wind** not normalised (TrackMan: "location and weather are not normalised"): a wind of 2, 3 and 4 m/s from
   twelve directions evenly spread; the carry of each is its total distance in the air (carry and offline
   combined), as a radar reports the landing point.

Run ``python benchmarks/measure_table_averaging.py`` (about 2 min): it prints each club's change in percent. The
default model, standard air; the classic PGA table's launches (impactlab/data/validation/trackman_carry.yaml).
"""

from __future__ import annotations

import warnings

import numpy as np

from impactlab import fly
from impactlab.data.carry import carry_table
from impactlab.errors import PlausibilityWarning

SPREADS = [(4.0, 1.5, 0.12), (6.0, 2.5, 0.20)]  # (mph, deg, fraction) one sigma
WINDS = [2.0, 3.0, 4.0]  # m/s
MPH = 0.44704


def main() -> None:
    table = carry_table("trackman_carry")
    rng = np.random.default_rng(20261124)
    print("| club | model carry yd | launch spread small | launch spread large | wind 2 m/s | 3 m/s | 4 m/s |")
    print("|---|---|---|---|---|---|---|")
    for index, club in enumerate(table.clubs):
        v, angle, spin = table.ball_speed[index], table.launch_angle[index], table.spin_rate[index]
        base = float(fly(v, angle, spin).carry_distance)
        cells = []
        for speed_sd, angle_sd, spin_sd in SPREADS:
            n = 4000
            with warnings.catch_warnings():
                # a 20 % spin spread about a 9,300 rpm wedge samples a few shots above 12,000 rpm: flown on purpose
                warnings.simplefilter("ignore", PlausibilityWarning)
                spread = fly(v + speed_sd * MPH * rng.standard_normal(n),
                             angle + np.radians(angle_sd) * rng.standard_normal(n),
                             spin * (1 + spin_sd * rng.standard_normal(n)))
            cells.append(f"{100 * (float(spread.carry_distance.mean()) / base - 1):+.2f} %")
        directions = np.linspace(0.0, 2 * np.pi, 12, endpoint=False)
        for wind in WINDS:
            flown = [fly(v, angle, spin, conditions={"headwind": f"{wind * np.cos(d)} m/s",
                                                     "crosswind": f"{wind * np.sin(d)} m/s"}) for d in directions]
            total = np.mean([np.hypot(float(f.carry_distance), float(f.offline_distance)) for f in flown])
            cells.append(f"{100 * (total / base - 1):+.2f} %")
        print(f"| {club} | {base / 0.9144:.1f} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
