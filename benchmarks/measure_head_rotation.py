"""Issue 21 item 2/3: what the head rotation TrackMan's club-data definitions imply does to the tour rows and to
the gear-effect observations, applied (not fitted) with TrackMan's definitions (loft and face at the contact point,
club speed and path of the head's centre of mass).

    .venv/bin/python benchmarks/measure_head_rotation.py [--models rigid_coulomb hertz_mindlin]

The rates (docs/clubs.md, "The head's rotation before impact"): C. Hahn (TrackMan, "Club Data Definitions"): for a
driver "the center of the face moves more upwards compared to CoG ... (typically 1 degree)" and its path is
"approximately 3 degrees" more outside-in; with the driver preset's CG 42.3 mm behind the face that is
w_toe = v tan(1 deg) / 42.3 mm and w_up = v tan(3 deg) / 42.3 mm (21.2 and 63.7 rad/s at 115 mph), taken in
proportion to each row's club speed. TrackMan gives no iron figure ("for non-drivers ... less sensitive"): the
irons take the driver's w / v, an ASSUMPTION, in the second variant only. Nothing is fitted: every row is held out.
Prints markdown: per row the spin error, per source the RMS, and the observations' ratios.
"""

from __future__ import annotations

import argparse
import math

import attrs
import numpy as np

from impactlab.data.shot_report import shot_table
from impactlab.data.sessions.shots import errors_by_source, predict, shot_errors, table_inputs
from impactlab.data.validation.observations import gear_effect, load_observations, vertical_gear_effect
from impactlab.model.registry import get_model

DEPTH = 0.0423  # the driver preset's CG behind the face [m] (Proceedings 49 (2020) 47)
PER_SPEED = {"toe": math.tan(math.radians(1.0)) / DEPTH, "up": math.tan(math.radians(3.0)) / DEPTH}  # [1/m]


def rotation_hook(clubs_turning, axes=("toe", "up")):
    """inputs -> inputs with the head rotation of each turning club at its row's speed."""
    def hook(inputs, clubs):
        inputs = dict(inputs)
        turning = np.isin(np.asarray(clubs), clubs_turning)
        for axis in axes:
            inputs[f"head_rotation_{axis}"] = np.where(turning, PER_SPEED[axis] * inputs["speed"], 0.0)
        return inputs
    return hook


VARIANTS = {
    "no rotation (default)": None,
    "driver rows: toe (TrackMan's 1 deg)": rotation_hook(("driver",), ("toe",)),
    "driver rows: toe and up (1 deg and 3 deg)": rotation_hook(("driver",)),
    "every row: toe and up, irons at the driver's w/v (ASSUMED)": rotation_hook(("driver", "6_iron")),
}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--models", nargs="+", default=["rigid_coulomb", "hertz_mindlin"])
    args = parser.parse_args()
    table = attrs.evolve(shot_table("trackman_tour"), loft_at="contact")
    observations = load_observations()
    for name in args.models:
        for rolling in (False, True):
            model = get_model(name)(**({"rolling_hysteresis": "restitution"} if rolling else {}))
            print(f"\n#### {name}{' + rolling_hysteresis 1 - e^2' if rolling else ''} (loft_at contact, "
                  "club_reference centre_of_mass)\n")
            print("| head rotation | " + " | ".join(f"{label} spin %" for label in table.labels)
                  + " | PGA RMS spin % | LPGA RMS spin % | launch RMS PGA / LPGA deg | driver axis ratio "
                  "| 6-iron axis ratio | driver higher strike: spin, launch |")
            print("|---|" + "---|" * (table.size + 6))
            for label, hook in VARIANTS.items():
                inputs = table_inputs(table)
                if hook is not None:
                    inputs = hook(inputs, table.clubs)
                errors = shot_errors(predict(model, inputs), table)
                by_source = errors_by_source(errors, table)
                pga, lpga = by_source["TrackMan PGA Tour"], by_source["TrackMan LPGA Tour"]

                def observed(club, hook=hook):  # the observation's shots are all of its one club
                    return None if hook is None else (lambda i: hook(i, (club,) * len(i["speed"])))
                axis = {o.name: gear_effect(model, o, inputs_hook=observed(o.club))["ratio"]
                        for o in observations["gear_effect"]}
                vertical = vertical_gear_effect(model, observations["vertical_gear_effect"][0],
                                                inputs_hook=observed("driver"))
                print(f"| {label} | " + " | ".join(f"{e:+.1f}" for e in errors["spin [%]"])
                      + f" | {pga['spin [%]']:.1f} | {lpga['spin [%]']:.1f} | {pga['launch angle [deg]']:.2f} / "
                      f"{lpga['launch angle [deg]']:.2f} | {axis['trackman2009_driver']:.2f} | "
                      f"{axis['trackman2009_6_iron']:.2f} | {vertical['ratio']:.2f}, {vertical['ratio_launch']:.2f} |")


if __name__ == "__main__":
    main()
