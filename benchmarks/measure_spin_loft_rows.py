"""Issue 21 items 1 and 6: the tour rows read with TrackMan's published 3-D spin lofts, not only dynamic loft minus
attack angle, and what that does to the models' errors (nothing fitted).

    .venv/bin/python benchmarks/measure_spin_loft_rows.py

TrackMan publishes, beside the tour averages' dynamic loft and attack angle, their spin loft, the 3-D angle between
the club's velocity and the face normal at maximum compression (physics brief, section 12, TrackMan's blog pages;
measurements): PGA driver 14.7 deg, 6-iron 24.3; LPGA driver 15.0, 6-iron 25.9. Dynamic loft minus attack angle
of the same rows is 13.7, 23.9, 12.7 and 25.9. An average of shots has a 3-D spin loft above its 2-D one because
each shot's face-to-path adds to it; the only angle of the definition left to carry the difference is the face to
path, so the second reading gives each row the face to path whose 3-D angle, with the row's own dynamic loft and
attack angle, is the published spin loft (its sign is not published: taken open, which moves neither the spin rate
nor the launch angle of a centred strike by more than the head's small heel-toe asymmetry). The rows' measured
spin, launch and ball speed are unchanged; the predictions are compared with them as in ``impactlab validate``.

Prints markdown: per configuration and reading, each row's errors (ball speed %, launch deg, spin %).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import attrs
import numpy as np
from scipy import optimize

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "docs"))

from ball_laws import ROWS  # noqa: E402  (docs/ball_laws.py: the tour rows with TrackMan's spin lofts)

from impactlab.data.shot_report import shot_table  # noqa: E402
from impactlab.data.sessions.shots import predict, shot_errors, table_inputs  # noqa: E402
from impactlab.model.registry import get_model  # noqa: E402
from impactlab.physics.delivery import spin_loft  # noqa: E402

#: TrackMan's published spin lofts of the four tour rows by label (deg; measurements)
PUBLISHED_SPIN_LOFT = {row[0]: row[6] for row in ROWS}
FACE = {"face_frequency": "6.88 kHz", "face_modal_mass": "10.9 g"}
CONFIGURATIONS = [
    ("defaults", {}),
    ("rolling 1 - e_ball^2", {"rolling_hysteresis": "restitution"}),
    ("hysteretic + rolling", {"inelastic": "hysteretic", "rolling_hysteresis": "restitution"}),
    ("hysteretic + rolling + face at the COR limit", {"inelastic": "hysteretic", "rolling_hysteresis": "restitution",
                                                       **FACE}),
    ("hysteretic + face at the COR limit", {"inelastic": "hysteretic", **FACE}),
]


def face_to_path_for(published, attack, loft):
    """The face to path (open, rad) whose 3-D spin loft with ``attack`` and ``loft`` is ``published``; 0 where the
    2-D angle already reaches it."""
    if spin_loft(0.0, 0.0, attack, loft) >= published:
        return 0.0
    return optimize.brentq(lambda face: spin_loft(0.0, face, attack, loft) - published, 0.0, 0.5, xtol=1e-12)


def three_d_table(table):
    delivery = dict(table.delivery)
    face = np.array([face_to_path_for(math.radians(PUBLISHED_SPIN_LOFT[label]), attack, loft)
                     for label, attack, loft in zip(table.labels, delivery["attack_angle"], delivery["dynamic_loft"])])
    delivery.update(path=np.zeros_like(face), face_angle=face)
    return attrs.evolve(table, delivery=delivery), face


def main() -> None:
    table = attrs.evolve(shot_table("trackman_tour"), loft_at="contact")
    spun, face = three_d_table(table)
    print("Face to path implied by the published spin loft (deg, open): "
          + ", ".join(f"{label} {math.degrees(f):.2f}" for label, f in zip(table.labels, face)))
    print("\n| configuration (`hertz_mindlin`, loft at contact, not fitted) | rows read with | "
          + " | ".join(f"{label}: ball speed %, launch deg, spin %" for label in table.labels) + " |")
    print("|---|---|" + "---|" * len(table.labels))
    for name, options in CONFIGURATIONS:
        model = get_model("hertz_mindlin")(**options)
        for reading, rows in (("dynamic loft - attack", table), ("published 3-D spin loft", spun)):
            errors = shot_errors(predict(model, table_inputs(rows)), rows)
            cells = [f"{errors['ball_speed [%]'][i]:+.2f}, {errors['launch angle [deg]'][i]:+.2f}, "
                     f"{errors['spin [%]'][i]:+.1f}" for i in range(len(table.labels))]
            print(f"| {name} | {reading} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
