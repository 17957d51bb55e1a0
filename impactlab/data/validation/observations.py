"""Published observations that are differences between shots: a heel or toe strike's spin-axis change, a higher
strike's change of spin and launch, and the cover's effect on a wedge's spin (``observations.yaml``).

Each observation carries its source, whether it is a measurement, exactly what the source publishes, and the
delivery impactlab must assume to reproduce it (the sources give none); the assumption is said in the data file
and by :func:`describe`. A model is compared by the ratio of its predicted difference to the published one: 1 is
agreement; the issue's target is 0.5-1.5.
"""

from __future__ import annotations

import math
from importlib import resources

import attrs
import numpy as np

from impactlab.data.sessions.shots import DELIVERY_FIELDS, MEASURED_FIELDS, ShotTable, predict, table_inputs
from impactlab.units import to_si


@attrs.frozen
class Observation:
    """One published difference between shots.

    Attributes
    ----------
    name, source, kind : str
        ``kind`` is ``measurement`` or ``model output``.
    club : str
        Club preset the shots are hit with.
    delivery : dict
        The assumed delivery (SI: ``club_speed`` m/s, angles rad); the source gives none.
    assumption : str
        What was assumed, in words.
    published : float
        The published difference: a spin-axis change [rad] for ``gear_effect``, a spin change [rad/s] for
        ``vertical_gear_effect``, the relative spin difference spin(urethane)/spin(ionomer) - 1 for ``cover``.
    offsets : tuple of float
        Gear effect: the inner and outer strike offsets from the face centre [m] (towards the toe and the heel);
        vertical gear effect: the lower and the upper strike, up the face [m].
    balls : dict
        Cover: ``urethane`` and ``ionomer`` ball presets.
    published_launch : float
        Vertical gear effect: the published change of launch angle [rad] (NaN elsewhere).
    loft_at : str or None
        The delivery's definition the observation needs (``centre``: the same swing struck elsewhere), or None
        (the caller's, ``contact`` by default).
    """

    name: str
    kind: str
    source: str
    club: str
    delivery: dict
    assumption: str
    published: float
    offsets: tuple = ()
    balls: dict = attrs.field(factory=dict)
    published_launch: float = math.nan
    loft_at: str | None = None


def load_observations() -> dict[str, list[Observation]]:
    """The shipped observations by family (``gear_effect``, ``cover``), units converted to SI."""
    import yaml

    document = yaml.safe_load(resources.files(__package__).joinpath("observations.yaml").read_text())
    out: dict[str, list[Observation]] = {"gear_effect": [], "vertical_gear_effect": [], "cover": []}
    for item in document["gear_effect"]:
        delivery = {key: to_si(value, DELIVERY_FIELDS[key], f"{item['name']}.{key}")
                    for key, value in item["assumed_delivery"].items()}
        out["gear_effect"].append(Observation(
            item["name"], item["kind"], " ".join(item["source"].split()), item["club"], delivery,
            " ".join(item["assumption"].split()), to_si(item["spin_axis_change"], "angle", item["name"]),
            (to_si(item["inner_offset"], "length", item["name"]), to_si(item["outer_offset"], "length", item["name"]))))
    for item in document["vertical_gear_effect"]:
        name = item["name"]
        delivery = {key: to_si(value, DELIVERY_FIELDS[key], f"{name}.{key}")
                    for key, value in item["assumed_delivery"].items()}
        out["vertical_gear_effect"].append(Observation(
            name, item["kind"], " ".join(item["source"].split()), item["club"], delivery,
            " ".join(item["assumption"].split()), to_si(item["spin_change"], "angular_speed", name),
            (to_si(item["lower_high"], "length", name), to_si(item["upper_high"], "length", name)),
            published_launch=to_si(item["launch_change"], "angle", name), loft_at=item["loft_at"]))
    for item in document["cover"]:
        delivery = {key: to_si(value, DELIVERY_FIELDS[key], f"{item['name']}.{key}")
                    for key, value in item["assumed_delivery"].items()}
        spin = {ball: to_si(value, "angular_speed", item["name"]) for ball, value in item["spin"].items()}
        out["cover"].append(Observation(
            item["name"], item["kind"], " ".join(item["source"].split()), item["club"], delivery,
            " ".join(item["assumption"].split()), spin["urethane"] / spin["ionomer"] - 1.0,
            balls=dict(item["balls"])))
    return out


def strike_table(observation: Observation, strikes_toe, loft_at: str = "contact", strikes_high=None) -> ShotTable:
    """Shots of the observation's assumed delivery at the strike offsets ``strikes_toe`` [m] (+ toe) and
    ``strikes_high`` [m] (+ up the face; default 0), nothing measured (a table to predict, not to compare)."""
    strikes_toe = np.asarray(strikes_toe, dtype=float)
    n = strikes_toe.size
    delivery = {key: np.full(n, observation.delivery.get(key, 0.0)) for key in DELIVERY_FIELDS}
    delivery["strike_toe"] = strikes_toe
    delivery["strike_high"] = np.zeros(n) if strikes_high is None else np.asarray(strikes_high, dtype=float)
    delivery["spin_loft"] = np.full(n, math.nan)
    delivery["face_to_path"] = np.full(n, math.nan)
    nothing = {key: np.full(n, math.nan) for key in MEASURED_FIELDS}
    return ShotTable(name=observation.name, source=observation.source,
                     labels=tuple(f"toe {x * 1e3:+.1f} mm, high {y * 1e3:+.1f} mm"
                                  for x, y in zip(strikes_toe, delivery["strike_high"])), clubs=(observation.club,) * n,
                     handedness=("right",) * n, delivery=delivery, measured=nothing,
                     sigma={key: np.ones(n) for key in MEASURED_FIELDS}, loft_at=loft_at)


def gear_effect(model, observation: Observation, loft_at: str = "contact", club_reference: str = "centre_of_mass",
                inputs_hook=None) -> dict:
    """The model's spin-axis change between the inner and outer strike offsets, toe and heel, against the
    published change.

    Returns
    -------
    dict
        ``toe`` and ``heel``: the change of the spin axis [deg] (outer minus inner offset, its magnitude);
        ``predicted``: their mean [deg]; ``published`` [deg]; ``ratio`` predicted / published.
    ``inputs_hook(inputs) -> inputs`` may change the model inputs (a calibration's values).
    """
    inner, outer = observation.offsets
    table = strike_table(observation, [inner, outer, -inner, -outer], loft_at)
    inputs = table_inputs(table, club_reference=club_reference)
    if inputs_hook is not None:
        inputs = inputs_hook(inputs)
    axis = np.degrees(predict(model, inputs)["spin_axis"])
    toe, heel = abs(axis[1] - axis[0]), abs(axis[3] - axis[2])
    predicted = 0.5 * (toe + heel)
    published = math.degrees(observation.published)
    return {"toe": float(toe), "heel": float(heel), "predicted": float(predicted), "published": published,
            "ratio": float(predicted / published)}


def vertical_gear_effect(model, observation: Observation, loft_at: str | None = None,
                         club_reference: str = "centre_of_mass", inputs_hook=None) -> dict:
    """The model's change of spin and launch angle from the lower to the upper strike against the published ones.

    ``loft_at`` defaults to the observation's own definition (``centre`` for one swing struck at two heights:
    the head's delivery is the same, the roll changes the loft at the contact point).

    Returns
    -------
    dict
        ``spin`` [rpm] and ``launch`` [deg] at the lower and upper strike; ``spin_change`` [rpm] and
        ``launch_change`` [deg], upper minus lower; ``published_spin`` [rpm], ``published_launch`` [deg];
        ``ratio`` (spin) and ``ratio_launch``, predicted / published.
    """
    lower, upper = observation.offsets
    table = strike_table(observation, [0.0, 0.0], loft_at or observation.loft_at or "contact", [lower, upper])
    inputs = table_inputs(table, club_reference=club_reference)
    if inputs_hook is not None:
        inputs = inputs_hook(inputs)
    out = predict(model, inputs)
    spin = out["spin_rate"] * 60.0 / (2.0 * math.pi)
    launch = np.degrees(out["vertical_launch_angle"])
    published_spin = observation.published * 60.0 / (2.0 * math.pi)
    published_launch = math.degrees(observation.published_launch)
    spin_change, launch_change = float(spin[1] - spin[0]), float(launch[1] - launch[0])
    return {"spin": (float(spin[0]), float(spin[1])), "launch": (float(launch[0]), float(launch[1])),
            "spin_change": spin_change, "launch_change": launch_change, "published_spin": published_spin,
            "published_launch": published_launch, "ratio": spin_change / published_spin,
            "ratio_launch": launch_change / published_launch}


def cover_effect(model, observation: Observation, loft_at: str = "contact", club_reference: str = "centre_of_mass",
                 inputs_hook=None) -> dict:
    """The model's relative wedge-spin difference spin(urethane)/spin(ionomer) - 1 against the published one.

    Returns
    -------
    dict
        ``spin`` [rpm] per ball; ``predicted`` and ``published`` relative differences; ``ratio`` of the two.
    """
    table = strike_table(observation, [0.0], loft_at)
    spin = {}
    for ball, preset in observation.balls.items():
        inputs = table_inputs(table, {"preset": preset}, club_reference=club_reference)
        if inputs_hook is not None:
            inputs = inputs_hook(inputs)
        spin[ball] = float(predict(model, inputs)["spin_rate"][0] * 60 / (2 * math.pi))
    predicted = spin["urethane"] / spin["ionomer"] - 1.0
    return {"spin": spin, "predicted": predicted, "published": observation.published,
            "ratio": predicted / observation.published}


def describe(observation: Observation) -> str:
    """The observation's source, kind and the assumption made to reproduce it, in one line."""
    return f"{observation.name} ({observation.kind}): {observation.source}. ASSUMED: {observation.assumption}"
