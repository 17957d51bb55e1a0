"""Why the 6-iron's heel/toe spin-axis change is a fraction of TrackMan's 5 deg: one mechanism at a time.

    .venv/bin/python benchmarks/measure_iron_gear_effect.py

Prints markdown (docs/validation.md, "Gear effect on irons"):

1. the TrackMan 2009 6-iron observation (0.14 in -> 1/2 in, square face to path, PGA 6-iron delivery ASSUMED) with
   the models on three heads: the estimate the catalogue had (CG 6 mm deep, 2600 g cm^2), Campau's patent head
   (the catalogue now) and the hand calculation (tests/test_gear_effect_oracle.py) on each;
2. the CG depth a rigid head would need for 5 deg (the hand calculation);
3. two things a rigid impulse leaves out, from a planar (top view) time integration of a Hertz contact with a
   Mindlin-Coulomb tangential spring between a ball and a free head: the face turning during the contact, and
   TrackMan's face angle read "at the time of maximum compression" (a face read square then was closed at first
   contact by the turn it had made by then), converted to a spin-axis change by the D-plane,
   atan(sin(turn) / tan(spin loft)).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import attrs
import numpy as np

from impactlab.data.validation.observations import gear_effect, load_observations
from impactlab.model.registry import get_model
from impactlab.scene import catalogue

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_gear_effect_oracle import hand_spin_axis  # noqa: E402  (the independent oracle, one definition)

G_CM2 = 1e-7
BALL_MASS, RADIUS = 0.04593, 0.021335
INNER, OUTER = 0.14 * 0.0254, 0.5 * 0.0254


def planar_impact(mass, moment, depth, x, speed, frozen, modulus=150e6, e=0.787, mu=0.4, steps=30000):
    """Top view of a ball hit by a free head at x [m] towards the toe, CG ``depth`` [m] behind the face: Hertz
    normal force (Hunt-Crossley damping for about e), a Mindlin spring capped by Coulomb friction tangentially.
    ``frozen``: the face normal and the lever stay as at first contact (a rigid impulse's geometry).
    Returns the ball's spin about the vertical [rad/s] and the head's turn [deg] at maximum compression and at
    separation."""
    inertia = 0.4 * BALL_MASS * RADIUS**2
    stiffness = 4 / 3 * modulus * math.sqrt(RADIUS)
    ratio = 2 * (1 - 0.48) / (2 - 0.48)  # k_t / k_n of a rubbery ball (nu 0.48) on a rigid face
    damping = 3 * (1 - e**2) / (4 * speed)
    head, head_velocity, angle, rate = np.array([-depth, -x]), np.array([speed, 0.0]), 0.0, 0.0
    ball, ball_velocity, spin = np.array([RADIUS, 0.0]), np.zeros(2), 0.0
    lever0, slip_store, dt, started = np.array([depth, x]), 0.0, 1.5e-3 / steps, False
    deepest, angle_at_deepest = 0.0, 0.0
    for _ in range(steps):
        turn = 0.0 if frozen else angle
        normal = np.array([math.cos(turn), math.sin(turn)])
        tangent = np.array([-normal[1], normal[0]])
        gap = (ball - head) @ normal - depth
        lever = lever0 if frozen else ball - gap * normal - head
        penetration = RADIUS - gap
        if penetration <= 0:
            if started:
                break
            force, arm = np.zeros(2), -RADIUS * normal
        else:
            started = True
            arm = -gap * normal
            relative = (ball_velocity + spin * np.array([-arm[1], arm[0]])
                        - head_velocity - rate * np.array([-lever[1], lever[0]]))
            normal_force = max(stiffness * penetration**1.5 * (1 - damping * (relative @ normal)), 0.0)
            k_t = ratio * 1.5 * stiffness * math.sqrt(penetration)
            slip_store += (relative @ tangent) * dt
            tangential = -k_t * slip_store
            if abs(tangential) > mu * normal_force:
                tangential = math.copysign(mu * normal_force, tangential)
                slip_store = -tangential / k_t
            force = normal_force * normal + tangential * tangent
            if penetration > deepest:
                deepest, angle_at_deepest = penetration, angle
        ball_velocity = ball_velocity + force / BALL_MASS * dt
        spin += (arm[0] * force[1] - arm[1] * force[0]) / inertia * dt
        head_velocity = head_velocity - force / mass * dt
        if penetration > 0:
            rate -= (lever[0] * force[1] - lever[1] * force[0]) / moment * dt
        ball, head, angle = ball + ball_velocity * dt, head + head_velocity * dt, angle + rate * dt
    return {"spin": spin, "turn_at_max_compression": math.degrees(angle_at_deepest), "turn": math.degrees(angle)}


def main() -> None:
    observation = next(o for o in load_observations()["gear_effect"] if o.name == "trackman2009_6_iron")
    d = observation.delivery
    speed, spin_loft = d["club_speed"], d["dynamic_loft"] - d["attack_angle"]
    preset = catalogue.CLUB_PRESETS["6_iron"]
    heads = {
        "estimate the catalogue had (CG 6 mm deep, 2600 g cm^2)": attrs.evolve(
            preset, inertia=(800 * G_CM2, 2600 * G_CM2, 3200 * G_CM2), center_of_mass=(-0.002, -0.002, 0.006)),
        "Campau's patent head (the catalogue now: 3.52 mm, 2784 g cm^2)": preset,
    }
    print("#### The TrackMan 2009 6-iron observation: 0.14 in -> 1/2 in, mean of toe and heel (published 5 deg)\n")
    print("| head | hand calculation | rigid_coulomb | hertz_mindlin | maw |")
    print("|---|---|---|---|---|")
    for label, head in heads.items():
        saved = catalogue.CLUB_PRESETS["6_iron"]
        catalogue.CLUB_PRESETS["6_iron"] = head
        try:
            cells = [gear_effect(get_model(m)(), observation)["predicted"]
                     for m in ("rigid_coulomb", "hertz_mindlin", "maw")]
        finally:
            catalogue.CLUB_PRESETS["6_iron"] = saved
        moments = head.inertia_components()
        hand = [hand_spin_axis(x, head.center_of_mass[2], moments["up"], moments["toe"], head.mass, speed, spin_loft)
                for x in (INNER, OUTER)]
        print(f"| {label} | {hand[0] - hand[1]:.2f} deg ({(hand[0] - hand[1]) / 5:.2f}x) | "
              + " | ".join(f"{c:.2f} deg ({c / 5:.2f}x)" for c in cells) + " |")
    print("\n(hand calculation: rigid, rolling at the end, Newton's e = 0.787, the CG straight behind the strike line; "
          "the models: the preset's CG 2 mm heel and low, the tour ball's restitution law)\n")

    moments = preset.inertia_components()
    for depth in (0.0035, 0.006, 0.010, 0.0175, 0.025):
        change = [hand_spin_axis(x, depth, moments["up"], moments["toe"], preset.mass, speed, spin_loft)
                  for x in (INNER, OUTER)]
        print(f"- CG {depth * 1e3:.1f} mm behind the face (2784 g cm^2): {change[0] - change[1]:.2f} deg")

    print("\n#### Beyond the rigid impulse (planar time integration, 6-iron 261 g, 2784 g cm^2, normal speed "
          f"{speed * math.cos(spin_loft):.1f} m/s)\n")
    print("| CG depth | strike | lateral spin, frozen geometry | lateral spin, face turning | turn at max compression "
          "| turn at separation |")
    print("|---|---|---|---|---|---|")
    normal_speed = speed * math.cos(spin_loft)
    turns = {}
    for depth in (0.0035, 0.006):
        for x in (INNER, OUTER):
            frozen = planar_impact(preset.mass, moments["up"], depth, x, normal_speed, True)
            turning = planar_impact(preset.mass, moments["up"], depth, x, normal_speed, False)
            turns[(depth, x)] = turning["turn_at_max_compression"]
            print(f"| {depth * 1e3:.1f} mm | {x / 0.0254:.2f} in | {frozen['spin'] * 30 / math.pi:.0f} rpm | "
                  f"{turning['spin'] * 30 / math.pi:.0f} rpm | {turning['turn_at_max_compression']:.3f} deg | "
                  f"{turning['turn']:.2f} deg |")
    dturn = turns[(0.0035, OUTER)] - turns[(0.0035, INNER)]
    axis = math.degrees(math.atan(math.sin(math.radians(dturn)) / math.tan(spin_loft)))
    print(f"\nA face read square at maximum compression (TrackMan) was closed at first contact by the turn it "
          f"had made by then: {dturn:.3f} deg more at 1/2 in than at 0.14 in, a draw of about {axis:.2f} deg more "
          f"spin axis (D-plane, spin loft {math.degrees(spin_loft):.1f} deg) on a toe strike, the gear effect's way.")


if __name__ == "__main__":
    main()
