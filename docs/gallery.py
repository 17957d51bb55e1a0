"""Write docs/gallery.md: every figure in docs/figures with the title its study gives it.

Run from the project root: ``python docs/gallery.py``. tests/test_docs_site.py checks the page is up to date.
The figures themselves come from ``impactlab run STUDY --plot`` (file name: study name, underscore, plot name).
"""

from __future__ import annotations

import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent
FIGURES = ROOT / "docs" / "figures"
#: figures drawn by other commands than ``impactlab run --plot``
OTHER = {"work_precision": ("Work-precision diagram: error against run time per impact, every model",
                            "impactlab convergence studies/work_precision.yaml --plot"),
         "sensitivity_indices": ("Sobol total indices of every input for launch angle, spin, ball speed and beta, "
                                 "per model and delivery", "impactlab run studies/sensitivity.yaml --plot"),
         "flight_trajectories": ("Ball flight after each model's launch, side and top view: driver struck heel, "
                                 "centre and toe (studies/flight.yaml)",
                                 "impactlab run studies/flight.yaml --plot (or impactlab plot RESULT --trajectories)"),
         "aero_coefficients": ("Measured golf-ball lift and drag against spin ratio (every ball group, above and in "
                               "its drag crisis) beside measured_fit at Re 6e4, 1e5, 2e5 and smits_smith_1994",
                               "python -m validation.flight.plot_aero_coefficients"),
         "flight_fit_c0": ("Carry RMS against the ball's drag level c0 on the PGA TOUR radar seasons (fitted) and on "
                           "TrackMan's three tour tables without their drivers (held out), and the held-out rows' "
                           "carry errors against launch spin ratio", "python -m validation.flight.plot_flight_fit_c0"),
         "flight_altitude": ("Driver carry against air density at the PGA TOUR radar seasons' mean launch: the "
                             "measured dose-response (raw and launch-adjusted) and altitude venues beside the models, "
                             "as flown and with Re frozen; the density slope over c0 and lift scale within their "
                             "bounds", "python -m validation.flight.plot_flight_altitude"),
         "rate_laws_spin_per_unit": ("Driver spin per unit of club speed x sin(spin loft) against club speed: the "
                                     "shared TrackMan file's median and quartiles (8,324 drivers, 5 mph bins) beside "
                                     "rigid_coulomb and hertz_mindlin as today and with the compression lever, all "
                                     "fitted on the whole file and predicted on the same shots (in-sample)",
                                     "python -m validation.impact.plot_spin_per_unit"),
         "flight_candidates": ("The drag crisis' advance with spin: held-out tour-table carry errors against launch "
                               "spin ratio with measured_fit and with the crisis at one Re, carry RMS against the "
                               "spin advance (radar seasons and tables), and both crisis models against the measured "
                               "drag of spinning and non-spinning balls",
                               "python -m validation.flight.plot_flight_candidates"),
         "ball_laws_spin_per_unit": ("Spin per unit of club speed x sin(spin loft) against spin loft for each "
                                     "ball-law form (friction law dashed) beside TrackMan's tour rows and bands, "
                                     "the wedge cover difference, and a wet face's spin loss",
                                     "python docs/ball_laws.py (studies/ball_laws.yaml)"),
         "trackman_tour_validation": ("TrackMan tour averages (measured, +- the assumed 1 sigma) beside every model "
                                      "with the calibrated ball and club presets",
                                      "impactlab validate --dataset trackman_tour --plot FILE"),
         **{stem: (title, "impactlab.data.validation.benchmark_report.plot_figures (docs/benchmarks.md)")
            for stem, title in (
             ("benchmark_tests12_force", "Chung & Ooi tests 1-2: normal force history of elastic impacts against "
                                         "Hertz, every compliant model"),
             ("benchmark_test4_kharaz", "Chung & Ooi test 4 = Kharaz et al. (2001, measured): tangential "
                                        "restitution, spin and rebound angle against incidence, every model"),
             ("benchmark_test5_fem", "Chung & Ooi test 5: normalised rebound and spin against the FEM curve "
                                     "(a model output), every model"),
             ("benchmark_test6_spin", "Chung & Ooi test 6: a spinning sphere on a rigid plane against the DEM curve "
                                      "(a model output), every model"))}}


def _titles() -> dict[str, tuple[str, str]]:
    """Figure file stem -> (title, study file) for every declared plot of the shipped studies."""
    titles = {}
    for path in sorted([*ROOT.glob("studies/*.yaml"), *ROOT.glob("studies/paper/*.yaml")]):
        study = yaml.safe_load(path.read_text())
        name = study.get("name", path.stem)
        for plot in study.get("plots") or []:
            titles[f"{name}_{plot['name']}"] = (plot.get("title", plot["name"]), path.relative_to(ROOT).as_posix())
        titles.setdefault(name, (study.get("description", name).strip().split("\n")[0],
                                 path.relative_to(ROOT).as_posix()))
    return titles


def gallery() -> str:
    titles = {**_titles(), **OTHER}
    lines = ["# Gallery", "",
             "Every figure of the shipped studies, as `impactlab run STUDY --plot` draws it; the caption is the "
             "plot's title in its study, and the study file says the conditions in full. Regenerate the page "
             "with `python docs/gallery.py`.", ""]
    for png in sorted(FIGURES.glob("*.png")):
        title, study = titles.get(png.stem, (png.stem.replace("_", " "), "a study no longer shipped"))
        lines += [f"## {title}", "", f"![{title}](figures/{png.name})", "",
                  f"*`{png.name}`, from `{study}`.*", ""]
    return "\n".join(lines)


if __name__ == "__main__":
    target = ROOT / "docs" / "gallery.md"
    target.write_text(gallery())
    print(f"wrote {target.relative_to(ROOT)}", file=sys.stderr)
