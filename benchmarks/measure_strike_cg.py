"""Issue 21: where the tour rows are struck and where the driver's centre of mass projects onto its face, measured
as a sensitivity of the held-out errors (docs/validation.md, "Strike height and the driver's CG projection").

    .venv/bin/python benchmarks/measure_strike_cg.py [--models hertz_mindlin rigid_coulomb]     (about 30 s)

No published tour-average strike location and no published CG projection of a modern driver were found (the
searches are listed in docs/validation.md), so nothing here changes a shipped row or preset: every value below is a
point of a sensitivity sweep over the ranges the sources name, never a value chosen by looking at the errors.

- Strike height up the face [mm]: -12.7 to +12.7, the +-0.5 in of Hot Stix Golf's driver chart (quoted by T. J.
  Tomasi, "Maxing Out Driver Distance", Keiser University College of Golf; measurement, delivery not given), which
  also spans the Clydebank Post's 15 mm between a low and a high group (2014; measurement, one golfer).
- The driver's CG up the face [mm]: the preset's reading of Proceedings 49 (2020) 47 Table 1 (2.9 mm along the
  face; docs/clubs.md), the same 2.9 mm read as vertical in the address frame (10.06 mm up the face), and the
  preset +- 2.54 mm: "0.1 in is a fairly large movement of CG" (J. Summitt, Hireko's chief technical officer,
  quoted by D. Tutelman, "Placement of Center of Gravity for Best Spin and Launch Angle", 2013, page 3; a
  designer's statement).
- The 6-iron's strike height [mm]: -5 to +5 (no published tour value; the range is this script's choice).

Configurations: "contact + rolling" (loft at the contact point, TrackMan's definition; the cover's rolling
hysteresis alpha = 1 - e^2; no fit) and "AFTER" (the same plus the leave-one-source-out calibration of friction,
tangential loss, restitution and face gain, fitted on the other tour: the Goal's AFTER row). The strike applies to
both tours' rows alike (a tour average is assumed the same on both tours: no source separates them).

Then the model's vertical gear effect against Hot Stix's chart: spin at +-0.25 in and +-0.5 in from the face
centre (2971 / 2098 and 3165 / 1862 rpm, centre 2564), with the PGA delivery ASSUMED (the source gives none) and
the loft held at the face centre (one swing struck higher).
"""

from __future__ import annotations

import argparse
import contextlib
import math

import attrs
import numpy as np

import impactlab.scene.catalogue as catalogue
from impactlab.data.fit.calibration import DEFAULT_PARAMETERS, calibrate, cross_validate
from impactlab.data.shot_report import shot_table
from impactlab.data.sessions.shots import errors_by_source, predict, shot_errors, table_inputs
from impactlab.data.validation.observations import load_observations, strike_table
from impactlab.model.registry import get_model

MM = 1e-3
INCH = 25.4
STRIKES_MM = (-12.7, -7.5, -5.0, -2.5, 0.0, 2.5, 5.0, 7.5, 12.7)
PRESET_CG_HIGH = 2.9
ADDRESS_CG_HIGH = 42.3 * math.sin(math.radians(9.8)) + 2.9 * math.cos(math.radians(9.8))  # 10.06 mm
CG_HIGHS_MM = {"preset - 0.1 in": PRESET_CG_HIGH - 2.54, "preset (face frame)": PRESET_CG_HIGH,
               "preset + 0.1 in": PRESET_CG_HIGH + 2.54, "address-frame reading": ADDRESS_CG_HIGH}
IRON_STRIKES_MM = (-5.0, -2.5, 0.0, 2.5, 5.0)
#: Hot Stix Golf's driver chart (spin [rpm] at the strike height up the face [in]), quoted by Tomasi (Keiser
#: University College of Golf): a fitter's measurement; club speed, loft and ball not given
HOT_STIX = {-0.5: 3165.0, -0.25: 2971.0, 0.0: 2564.0, 0.25: 2098.0, 0.5: 1862.0}
KEYS = ("ball_speed [%]", "launch angle [deg]", "spin [%]")
RPM = 60.0 / (2.0 * math.pi)


@contextlib.contextmanager
def driver_cg_high(high_mm: float | None):
    """The ``driver`` preset with its centre of mass ``high_mm`` up the face (toe and depth kept), for the sweep."""
    old = catalogue.CLUB_PRESETS["driver"]
    if high_mm is not None:
        toe, _, depth = old.center_of_mass
        catalogue.CLUB_PRESETS["driver"] = attrs.evolve(old, center_of_mass=(toe, high_mm * MM, depth))
    try:
        yield
    finally:
        catalogue.CLUB_PRESETS["driver"] = old


def tour_table(driver_high_mm: float, iron_high_mm: float):
    """TrackMan's tour rows (loft at the contact point), every driver row struck ``driver_high_mm`` up the face and
    every iron row ``iron_high_mm``, centred heel to toe."""
    table = attrs.evolve(shot_table("trackman_tour"), loft_at="contact")
    driver = np.array([club == "driver" for club in table.clubs])
    delivery = dict(table.delivery, strike_high=np.where(driver, driver_high_mm, iron_high_mm) * MM,
                    strike_toe=np.zeros(table.size))
    return attrs.evolve(table, delivery=delivery)


def measure(model_name: str, fitted: bool, driver_high=0.0, iron_high=0.0, cg_high=None) -> dict:
    """Per source the RMS errors, and per row the signed spin error [%] and launch error [deg], on rows not fitted."""
    model = get_model(model_name)(rolling_hysteresis="restitution")
    table = tour_table(driver_high, iron_high)
    with driver_cg_high(cg_high):
        if fitted:
            names = [p for p in DEFAULT_PARAMETERS
                     if p != "tangential_loss" or "tangential_loss" in model.optional_inputs]
            full = calibrate(model, table, names)
            held = cross_validate(model, table, names, by="source", start=dict(zip(full.parameters, full.values)))
            by_source, errors = held["by_source"], held["errors"]
        else:
            errors = shot_errors(predict(model, table_inputs(table)), table)
            by_source = errors_by_source(errors, table)
    return {"by_source": by_source, "rows": dict(zip(table.labels, zip(errors["spin [%]"],
                                                                         errors["launch angle [deg]"],
                                                                         errors["ball_speed [%]"])))}


def _cells(result: dict) -> str:
    sources = " | ".join(" / ".join(f"{rms[k]:.2f}" for k in KEYS) for rms in result["by_source"].values())
    rows = " | ".join(f"{result['rows'][label][0]:+.1f}" for label in ("PGA driver", "LPGA driver"))
    return f"{sources} | {rows} |"


def strike_sweep(model_name: str) -> None:
    print(f"\n#### {model_name}: driver strike height (preset CG, 2.9 mm up the face)\n")
    print("| configuration | driver strike up the face [mm] | PGA: ball speed % / launch deg / spin % | LPGA: ball "
          "speed % / launch deg / spin % | PGA driver spin error % | LPGA driver spin error % |")
    print("|---|---|---|---|---|---|")
    for fitted, name in ((False, "contact + rolling"), (True, "AFTER (+ LOSO calibration)")):
        for index, high in enumerate(STRIKES_MM):
            print(f"| {name if index == 0 else ''} | {high:+.1f} | " + _cells(measure(model_name, fitted, high)))


def cg_sweep(model_name: str) -> None:
    print(f"\n#### {model_name}: the driver's CG up the face x strike height (AFTER)\n")
    print("| driver CG up the face [mm] | driver strike [mm] | PGA: ball speed % / launch deg / spin % | LPGA: ball "
          "speed % / launch deg / spin % | PGA driver spin error % | LPGA driver spin error % |")
    print("|---|---|---|---|---|---|")
    for name, cg in CG_HIGHS_MM.items():
        for index, high in enumerate((-7.5, 0.0, 7.5)):
            label = f"{cg:.2f} ({name})" if index == 0 else ""
            print(f"| {label} | {high:+.1f} | " + _cells(measure(model_name, True, high, cg_high=cg)))


def iron_sweep(model_name: str) -> None:
    print(f"\n#### {model_name}: 6-iron strike height (driver centred, preset CG; AFTER)\n")
    print("| 6-iron strike [mm] | PGA: ball speed % / launch deg / spin % | LPGA: ball speed % / launch deg / "
          "spin % | PGA 6-iron spin error % | LPGA 6-iron spin error % |")
    print("|---|---|---|---|---|")
    for high in IRON_STRIKES_MM:
        result = measure(model_name, True, 0.0, high)
        sources = " | ".join(" / ".join(f"{rms[k]:.2f}" for k in KEYS) for rms in result["by_source"].values())
        irons = " | ".join(f"{result['rows'][label][0]:+.1f}" for label in ("PGA 6-iron", "LPGA 6-iron"))
        print(f"| {high:+.1f} | {sources} | {irons} |")


def per_mm(model_name: str) -> None:
    """Each mechanism alone (contact + rolling, no fit): d(error)/d(mm) by central difference over +-1 mm."""
    print(f"\n#### {model_name}: each mechanism alone, per mm (contact + rolling, no fit; central difference)\n")
    print("| mechanism (+1 mm) | row | spin [% of measured] | launch [deg] | ball speed [%] |")
    print("|---|---|---|---|---|")
    cases = {"driver strike up the face": lambda s: dict(driver_high=s),
             "driver CG up the face": lambda s: dict(cg_high=PRESET_CG_HIGH + s),
             "6-iron strike up the face": lambda s: dict(iron_high=s)}
    for name, case in cases.items():
        up, down = measure(model_name, False, **case(1.0)), measure(model_name, False, **case(-1.0))
        rows = ("PGA driver", "LPGA driver") if "driver" in name else ("PGA 6-iron", "LPGA 6-iron")
        for label in rows:
            d = [(u - w) / 2.0 for u, w in zip(up["rows"][label], down["rows"][label])]
            print(f"| {name} | {label} | {d[0]:+.2f} | {d[1]:+.3f} | {d[2]:+.3f} |")


def hot_stix(model_name: str) -> None:
    """The model's spin change between Hot Stix's strike heights (delivery ASSUMED: the PGA tour driver average,
    loft held at the face centre as Clydebank's), as a ratio to the chart's."""
    observation = load_observations()["vertical_gear_effect"][0]  # Clydebank: its assumed delivery and club
    heights = sorted(HOT_STIX)
    table = strike_table(observation, [0.0] * len(heights), "centre", [h * INCH * MM for h in heights])
    for rolling in (False, True):
        model = get_model(model_name)(**({"rolling_hysteresis": "restitution"} if rolling else {}))
        spin = predict(model, table_inputs(table))["spin_rate"] * RPM
        ratios = [(spin[-1 - i] - spin[i]) / (HOT_STIX[heights[-1 - i]] - HOT_STIX[heights[i]]) for i in (0, 1)]
        print(f"| {model_name}{' + rolling 1 - e^2' if rolling else ''} | "
              + " / ".join(f"{s:.0f}" for s in spin) + f" | {ratios[1]:.2f} | {ratios[0]:.2f} |")


def fitted_strike(model_name: str) -> None:
    """A diagnostic, not a shipped value: the mean strike height fitted as a fifth calibration parameter on one tour
    (every row of it, bounds +-15 mm), then the other tour predicted with it. Does a strike fitted on one tour carry
    over to the other?"""
    model = get_model(model_name)(rolling_hysteresis="restitution")
    table = tour_table(0.0, 0.0)
    names = [p for p in DEFAULT_PARAMETERS if p != "tangential_loss" or "tangential_loss" in model.optional_inputs]
    names.append("strike_high")
    full = calibrate(model, table, names)
    held = cross_validate(model, table, names, by="source", start=dict(zip(full.parameters, full.values)))
    for (source, rms), fit, calibration in zip(held["by_source"].items(), held["fits"], held["calibrations"]):
        at = calibration.at_bound or (False,) * len(names)
        near = calibration.near_bound or (False,) * len(names)
        flags = ", ".join(f"{name} {'at' if a else 'near'} its bound" for name, a, b in zip(names, at, near)
                          if a or b) or "-"
        print(f"| {model_name} | {source} | {fit['strike_high'] / MM:+.2f} | "
              + " / ".join(f"{rms[k]:.2f}" for k in KEYS) + f" | {flags} |")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--models", nargs="+", default=["hertz_mindlin", "rigid_coulomb"])
    args = parser.parse_args()
    for name in args.models:
        per_mm(name)
        strike_sweep(name)
        cg_sweep(name)
        iron_sweep(name)
    print("\n#### Diagnostic: the strike height fitted on the other tour (AFTER + strike_high; not shipped)\n")
    print("| model | held-out source | strike fitted on the other tour [mm] | held out: ball speed % / launch deg / "
          "spin % | fit flags at or near a bound |")
    print("|---|---|---|---|---|")
    for name in args.models:
        fitted_strike(name)
    print("\n#### Hot Stix's driver chart against the models (delivery assumed: PGA driver average, loft at the "
          "face centre)\n")
    print("| model | spin at -0.5 / -0.25 / 0 / +0.25 / +0.5 in [rpm] (chart: " + " / ".join(
        f"{v:.0f}" for v in HOT_STIX.values()) + ") | ratio of the +-0.25 in change (chart -873) | ratio of the "
        "+-0.5 in change (chart -1303) |")
    print("|---|---|---|---|")
    for name in args.models:
        hot_stix(name)


if __name__ == "__main__":
    main()
