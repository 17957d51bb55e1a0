"""What the friction law of the ball-face pair does to spin (issue 21 item 3b), mechanism by mechanism.

Prints four tables, every parameter fixed beforehand from its own source (impactlab/scene/materials.py: tau from
Henrikson et al.'s sled friction, cover moduli and melting point from datasheets, the face's grooves from the
Rules, its slope assumed), none fitted to the rows compared with:

1. the coefficient the law gives on the TrackMan tour rows (driver, 6-iron) and on the Titleist wedge observation
   (impactlab/data/validation/observations.yaml, its assumed delivery), urethane and ionomer;
2. the Titleist wedge cover difference, mechanism by mechanism (the sled's constant mu; + the load dependence of
   adhesion on the real area, cold; + the flash temperature), for rigid_coulomb, maw and hertz_mindlin;
3. its sensitivity to the unpublished numbers: the face's r.m.s. slope s (tau re-derived from the sled at each s)
   and whether the urethane cover softens (cast thermoset: never; a thermoplastic urethane: from its Vicat point,
   104 degC, 84 K above 20 degC);
4. a wet face: the wedge's spin loss against the water film on the face, grooved and without grooves, for the
   Rules' roughness limit (R_q 5.7 um, the preset) and smoother faces, against the published wet-wedge losses
   (measurements of sprayed faces, film thickness not stated).

Run: .venv/bin/python benchmarks/measure_friction_law.py  (about 20 s)
"""

from __future__ import annotations

import math
import sys
import warnings
from pathlib import Path

import numpy as np

from impactlab.data.sessions.shots import predict, table_inputs
from impactlab.data.validation.observations import load_observations, strike_table
from impactlab.model.case_inputs import CaseInputs
from impactlab.model.registry import get_model
from impactlab.physics import friction_laws
from impactlab.scene.materials import FITTED_RESTITUTION, ball_preset

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "docs"))
import ball_laws  # noqa: E402  (the tour rows and their inputs)

RPM = 60.0 / (2.0 * math.pi)
MODELS = [("rigid_coulomb", {}), ("maw", {}), ("hertz_mindlin", {})]
#: published wet-wedge spin losses (measurements; sprayed or wet faces, film thickness not stated)
WET_MEASURED = [("tablehopping.com (SkyTrak, lob wedge, face sprayed; 25/50/89 yd)", (0.13, 0.175, 0.11)),
                ("exactgolf.com (55 m wedge, wet face)", (0.42,)),
                ("windmillleisure.co.uk (56 deg, 50-60 yd, wet)", (0.47,)),
                ("peterfieldgolf.co.uk citing a study (average; best, worst)", (0.35, 0.10, 0.60))]


def wedge_inputs(ball: str, **changes):
    observation = load_observations()["cover"][0]
    inputs = dict(table_inputs(strike_table(observation, [0.0]), {"preset": ball}))
    for key, value in changes.items():
        inputs[key] = np.full(inputs["speed"].shape, value, dtype=float)
    return inputs


def spin(model, inputs) -> float:
    return float(predict(model, inputs)["spin_rate"][0] * RPM)


def law_mu(inputs) -> np.ndarray:
    batch = CaseInputs(inputs)
    return friction_laws.effective_friction("adhesion", dict(batch), batch.contact_state(), inputs["restitution"])


def cover_ratio(name, options, urethane_changes=None, ionomer_changes=None, published=0.482) -> tuple:
    model = get_model(name)(**options)
    u = spin(model, wedge_inputs("urethane_tour", **(urethane_changes or {})))
    i = spin(model, wedge_inputs("two_piece_ionomer", **(ionomer_changes or {})))
    return u, i, (u / i - 1.0) / published


def resloped(ball: str, slope: float) -> dict:
    """The ball's tau re-derived from its sled friction on a plate of slope s, and the face given that slope."""
    b = ball_preset(ball)
    tau = friction_laws.shear_strength_from_sled(b.friction, b.cover_modulus, b.material.poisson_ratio, slope,
                                                 FITTED_RESTITUTION.value)
    return {"ball_shear_strength": tau, "face_roughness_slope": slope}


def main():
    warnings.simplefilter("ignore")
    observation = load_observations()["cover"][0]
    print("1. The law's coefficient (sled: urethane 0.40, ionomer 0.35 on a grooved, blasted plate)")
    tour = ball_laws.scene_inputs([("urethane_tour", *row[1:5]) for row in ball_laws.ROWS])
    ionomer_tour = ball_laws.scene_inputs([("two_piece_ionomer", *row[1:5]) for row in ball_laws.ROWS])
    for label, inputs in (("urethane", tour), ("ionomer", ionomer_tour)):
        mu = law_mu(inputs)
        print(f"  {label:9s}" + "".join(f"  {row[0]} {value:.3f}" for row, value in zip(ball_laws.ROWS, mu)))
    for ball in ("urethane_tour", "two_piece_ionomer"):
        inputs = wedge_inputs(ball)
        cold = law_mu(dict(inputs, ball_cover_melt_rise=np.full(1, np.inf)))
        print(f"  wedge ({observation.name}) {ball}: cold {cold[0]:.3f}, with the flash temperature "
              f"{law_mu(inputs)[0]:.3f}")

    print(f"\n2. Wedge cover difference, mechanism by mechanism ({observation.name}, published relative difference "
          f"{observation.published:.3f}; ratio predicted/published, target 0.5-1.5)")
    steps = [("sled mu, constant (today)", {}, {}, {}),
             ("+ adhesion on the real area, cold", {"friction_law": "adhesion"}, {},
              {"ball_cover_melt_rise": np.inf}),
             ("+ flash temperature (the presets)", {"friction_law": "adhesion"}, {}, {})]
    for name, options in MODELS:
        for label, law, u_changes, i_changes in steps:
            u, i, ratio = cover_ratio(name, {**options, **law}, u_changes, i_changes)
            print(f"  {name:14s} {label:36s} urethane {u:6.0f}  ionomer {i:6.0f} rpm  ratio {ratio:6.2f}")

    print("\n3. Sensitivity to the unpublished numbers (tau from the sled at each slope; ratio to the published)")
    for name, options in MODELS[:2]:
        for slope in (0.1, 0.2, 0.4):
            for melt, words in ((np.inf, "urethane never melts"), (84.0, "urethane softens, 84 K")):
                u_changes = {**resloped("urethane_tour", slope), "ball_cover_melt_rise": melt}
                u, i, ratio = cover_ratio(name, {**options, "friction_law": "adhesion"}, u_changes,
                                          resloped("two_piece_ionomer", slope))
                print(f"  {name:14s} s = {slope:.1f}, {words:22s} urethane {u:6.0f}  ionomer {i:6.0f}  "
                      f"ratio {ratio:5.2f}")

    print("\n4. Wet face, urethane ball, the wedge observation's delivery: spin loss against the dry face")
    for label, values in WET_MEASURED:
        print(f"  measured: {label}: " + ", ".join(f"{v:.0%}" for v in values))
    for name, options in MODELS[:2]:
        model = get_model(name)(friction_law="adhesion", **options)
        dry = spin(model, wedge_inputs("urethane_tour"))
        for roughness in (5.7e-6, 2e-6, 1e-6):
            for grooves, land in (("grooved", 1.35e-3), ("no grooves", math.inf)):
                losses = []
                for film in (10e-6, 20e-6, 50e-6, 100e-6):
                    wet = spin(model, wedge_inputs("urethane_tour", face_water_film=film, face_groove_land=land,
                                                   face_roughness=roughness))
                    losses.append(f"{film * 1e6:3.0f} um {1.0 - wet / dry:4.0%}")
                print(f"  {name:14s} dry {dry:5.0f} rpm, R_q {roughness * 1e6:3.1f} um, {grooves:10s} "
                      + "  ".join(losses))


if __name__ == "__main__":
    main()
