"""Outputs the framework derives from a model's impulses (rule 6 of the model contract).

The impulse on the ball, in the contact frame of :mod:`impactlab.physics.contact`,
fixes everything after impact: ball velocity and spin, the head's velocity and
angular velocity, the contact point's restitution and the energy lost
(:func:`impactlab.physics.contact.after_impact`); with a golf delivery, also the
launch in golf terms (:func:`impactlab.physics.contact.ground_outputs`). One
code path serves a fixed face, a point-mass club and a free 3-D head.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from impactlab.model.case_inputs import CaseInputs
from impactlab.physics import hertz
from impactlab.physics.contact import (GEOMETRY_INPUTS, INERTIA_INPUTS, LAUNCH_PLANE_OUTPUTS, after_impact,
                                       ground_outputs, impulse_vector)
from impactlab.physics.delivery import DELIVERY_INPUTS
from impactlab.physics.flight import fly
from impactlab.physics.mechanics import AFTER_IMPACT_INPUTS
from impactlab.vocabulary import FLIGHT_OUTPUTS
from impactlab.scene.flight import air_arrays

IMPULSES = frozenset({"normal_impulse", "tangential_impulse"})
FROM_IMPULSES = frozenset({
    "launch_angle", "launch_ratio", "rebound_angle", "total_angle", "ball_speed", "spin_rate", "normal_velocity",
    "tangential_velocity", "tangential_restitution", "energy_loss", "smash_factor", "club_speed_after",
    "club_angular_velocity",
})
FROM_DELIVERY = frozenset({
    "spin_loft", "vertical_launch_angle", "horizontal_launch_angle", "vertical_launch_ratio",
    "horizontal_launch_ratio", "spin_axis", "back_spin", "side_spin",
})
#: the ball flight after the launch (impactlab.physics.flight), computed only when asked for by name
FROM_FLIGHT = frozenset(FLIGHT_OUTPUTS)
#: the air of a study's conditions block (absent: the standard air of impactlab.scene.flight)
FLIGHT_INPUTS = ("air_temperature", "air_pressure", "relative_humidity", "altitude", "headwind", "crosswind")
#: Maw-Barber-Fawcett's normalised incidence and rebound, from the materials and friction of the scene
FROM_MATERIALS = frozenset({"normalised_incidence", "normalised_rebound"})
MATERIAL_INPUTS = ("ball_youngs_modulus", "ball_poisson_ratio", "face_youngs_modulus", "face_poisson_ratio",
                   "friction")
#: inputs each family needs (the optional ones default: no spin, a fixed face, a centred strike)
NEEDS = {
    "impulses": frozenset(AFTER_IMPACT_INPUTS) - {"spin"},
    "delivery": frozenset(DELIVERY_INPUTS),
    "flight": frozenset(DELIVERY_INPUTS),
    "materials": frozenset(MATERIAL_INPUTS),
}
#: inputs the derivation uses when given
DERIVATION_OPTIONAL = frozenset({"spin", "club_mass"} | set(GEOMETRY_INPUTS) | set(DELIVERY_INPUTS))
NO_DELIVERY = "needs a golf delivery (a delivery block: path, face angle, attack angle, dynamic loft)"
NO_MATERIALS = "needs the ball's and face's elastic constants and the friction (kappa = G*/E*, mu)"
NO_LATERAL = ("the model gives impulses on one line (no lateral_impulse), and the scene has a free club head "
              "whose impact may turn the slip")


def derivable(name: str, provides: Iterable[str],
              given_inputs: Iterable[str] | None = None) -> tuple[bool, str | None]:
    """Whether ``name`` can be derived for a model that provides ``provides``; if not, why (None: not derivable)."""
    if not IMPULSES <= set(provides) or name not in FROM_IMPULSES | FROM_DELIVERY | FROM_MATERIALS | FROM_FLIGHT:
        return False, None
    if given_inputs is not None and "lateral_impulse" not in provides and set(INERTIA_INPUTS) <= set(given_inputs):
        return False, NO_LATERAL
    if name in FROM_DELIVERY | FROM_FLIGHT and given_inputs is not None and not NEEDS["delivery"] <= set(given_inputs):
        return False, NO_DELIVERY
    if name in FROM_MATERIALS and given_inputs is not None and not NEEDS["materials"] <= set(given_inputs):
        return False, NO_MATERIALS
    return True, None


def derive(names: Iterable[str], raw: dict[str, Any], inputs: Mapping[str, Any]) -> dict:
    """Compute the derived outputs ``names`` from the impulses in ``raw`` and the case ``inputs`` (SI)."""
    names = set(names)
    out: dict[str, np.ndarray] = {}
    if not names:
        return out
    inputs = inputs if isinstance(inputs, CaseInputs) else CaseInputs(inputs)
    state = inputs.contact_state()  # the model's hook has usually computed it already
    impulse = impulse_vector(state, raw["normal_impulse"], raw["tangential_impulse"], raw.get("lateral_impulse"))
    needed = set(names & FROM_IMPULSES)
    if names & FROM_MATERIALS:
        needed |= {"tangential_restitution", "normal_velocity"}  # what normalised_slip reads
    if names & FROM_FLIGHT:
        needed |= {"ball_speed"}
    moment = None
    # a rolling-resistance couple on the ball (a model without a rolling law gives zeros: after_impact ignores them)
    if any((np.asarray(raw[name]) != 0.0).any() for name in ("rolling_moment_slip", "rolling_moment") if name in raw):
        zero = np.zeros_like(impulse[:, 0])
        moment = np.stack([np.asarray(raw.get("rolling_moment_slip", zero), float),
                           np.asarray(raw.get("rolling_moment", zero), float)], -1)
    plane = inputs.launch_plane() if needed & LAUNCH_PLANE_OUTPUTS else None  # one per batch, for every model
    basics = after_impact(state, impulse, names=needed, moment=moment, plane=plane, **inputs)
    out.update({name: basics[name] for name in names & FROM_IMPULSES})
    if names & (FROM_DELIVERY | FROM_FLIGHT):
        golf = ground_outputs(state, basics, **{name: inputs[name] for name in DELIVERY_INPUTS})
        out.update({name: golf[name] for name in names & FROM_DELIVERY})
        if names & FROM_FLIGHT:
            flown = fly_launch(basics["ball_speed"], golf, inputs)
            out.update({name: flown[name] for name in names & FROM_FLIGHT})
    if names & FROM_MATERIALS:
        out.update({name: value for name, value in normalised_slip(state, basics, inputs).items() if name in names})
    return out


def normalised_slip(state: Mapping[str, Any], basics: dict, inputs: Mapping[str, Any]) -> dict:
    """psi1 = kappa V_x/(mu V_z) and psi2 = kappa V_x'/(mu V_z') of Maw, Barber & Fawcett (NaN without friction).

    V_x, V_x' are the contact point's slip velocities before and after (V_x' = -beta V_x), V_z, V_z' the
    normal approach and rebound speeds, kappa = G*/E* of the ball-face pair. Every Coulomb model gives
    psi2 = psi1 - 4 chi in gross slip; the rigid ones give psi2 = 0 below it.
    """
    moduli = [inputs[name] for name in MATERIAL_INPUTS[:4]]
    kappa = hertz.tangential_modulus(*moduli) / hertz.effective_modulus(*moduli)
    normal_speed, slip = state["normal_speed"], state["slip_speed"]
    friction = np.where(inputs["friction"] > 0.0, inputs["friction"], np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        incidence = kappa * np.abs(slip) / (friction * normal_speed)
        rebound = -basics["tangential_restitution"] * incidence * normal_speed / basics["normal_velocity"]
    return {"normalised_incidence": incidence, "normalised_rebound": rebound}


def fly_launch(ball_speed, golf: dict, inputs) -> dict:
    """The ball flight of a launch in golf terms (:func:`impactlab.physics.flight.fly`; SI arrays).

    The spin flown is the spin across the flight, ``hypot(back_spin, side_spin)``, about the axis tilted by
    ``spin_axis``; spin along the flight (rifle spin) makes no lift in the model and is left out. The ball's mass
    and radius are the scene's; the air is the study's ``conditions`` (absent: the standard air of
    :mod:`impactlab.scene.flight`). The same numbers as :func:`impactlab.fly` with those arguments.
    """
    spin = np.hypot(golf["back_spin"], golf["side_spin"])
    return fly(ball_speed, golf["vertical_launch_angle"], spin, golf["spin_axis"], golf["horizontal_launch_angle"],
               ball_mass=inputs["ball_mass"], ball_radius=inputs["ball_radius"],
               **air_arrays({name: inputs[name] for name in FLIGHT_INPUTS if name in inputs}))


#: the public names of this module (a plugin reaches them through impactlab.model: docs/writing-a-model.md)
__all__ = ["IMPULSES", "FROM_IMPULSES", "FROM_DELIVERY", "FROM_FLIGHT", "FLIGHT_INPUTS", "FROM_MATERIALS",
           "MATERIAL_INPUTS", "NEEDS", "DERIVATION_OPTIONAL", "NO_DELIVERY", "NO_MATERIALS", "NO_LATERAL",
           "derivable", "derive", "normalised_slip", "fly_launch"]
