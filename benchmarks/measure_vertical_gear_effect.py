"""The Clydebank Post (2014) driver observation, 15 mm higher on the face: -800 rpm, +4 deg (one golfer, TrackMan),
against every model, with the loft held at the face centre (one swing struck higher: the observation's definition)
and at the contact point (the roll's extra loft taken out), with and without the cover's rolling hysteresis.

    .venv/bin/python benchmarks/measure_vertical_gear_effect.py

Prints markdown (docs/validation.md, "Vertical gear effect"). The delivery is ASSUMED (observations.yaml).
"""

from __future__ import annotations

from impactlab.data.validation.observations import load_observations, vertical_gear_effect
from impactlab.model.registry import get_model

MODELS = ("rigid_coulomb", "restitution", "hertz_mindlin", "maw", "dem_linear")


def main() -> None:
    observation = load_observations()["vertical_gear_effect"][0]
    print("| model | loft held at | lower / upper spin [rpm] | spin change (ratio to -800) | lower / upper launch "
          "[deg] | launch change (ratio to +4) |")
    print("|---|---|---|---|---|---|")
    for name in MODELS:
        for rolling in (False, True):
            if rolling and name in ("restitution",):
                continue
            model = get_model(name)(**({"rolling_hysteresis": "restitution"} if rolling else {}))
            for loft_at in ("centre", "contact"):
                r = vertical_gear_effect(model, observation, loft_at)
                label = name + (" + rolling 1 - e^2" if rolling else "")
                print(f"| {label} | {loft_at} | {r['spin'][0]:.0f} / {r['spin'][1]:.0f} | "
                      f"{r['spin_change']:+.0f} ({r['ratio']:.2f}) | {r['launch'][0]:.1f} / {r['launch'][1]:.1f} | "
                      f"{r['launch_change']:+.2f} ({r['ratio_launch']:.2f}) |")


if __name__ == "__main__":
    main()
