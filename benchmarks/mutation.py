"""Mutation testing over impactlab/physics and models: does the test suite notice a small realistic bug?

Each mutant below is one small edit a person could make by mistake (a flipped sign, a dropped factor,
an off-by-one, a wrong variable, a wrong constant). The script copies the project once into a temporary
folder (the working tree is never edited), applies one mutant at a time to the copy, runs the tests that
cover the mutated code with a timeout, restores the file (try/finally) and reports which mutants the tests
killed and which survived. A kill is confirmed: the first test that failed with the mutant is run again on the
unmutated copy, and the mutant counts as killed only if that test passes there (a test that fails without the
mutant too says nothing about it). A timeout is no kill: a loaded machine's slowness would count as tests
noticing the bug; it is reported as undecided, as is a kill the unmutated tree does not confirm.

    .venv/bin/python benchmarks/mutation.py                 # every mutant
    .venv/bin/python benchmarks/mutation.py -k hertz dem    # mutants whose id contains a word
    .venv/bin/python benchmarks/mutation.py --list          # what would run
    .venv/bin/python benchmarks/mutation.py --tests tests/test_mutation_oracles.py   # the oracles alone

The copy's modules shadow the installed ones (the copy goes first on PYTHONPATH, and ``impactlab_models``
is a link to its ``models``); numba's on-disk cache is copied with the sources, so only a mutated kernel
compiles. A mutant whose ``old`` text is not found exactly once is reported as stale (the source moved on),
not silently skipped. Results are written to ``benchmarks/mutation_results.json`` (committed: docs/testing.md
quotes the last full run's counts from it, with the commit it ran on).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# the tests that cover each area (the whole suite per mutant would take hours on 2 cores)
T_MAW = ["tests/test_maw.py", "tests/test_mutation_oracles.py"]
T_DEM = ["tests/test_dem.py", "tests/test_approaches.py", "tests/test_mutation_oracles.py"]
T_RIGID = ["tests/test_rigid_models.py", "tests/test_clubs.py", "tests/test_mutation_oracles.py"]
T_CORE = ["tests/test_maw.py", "tests/test_rigid_models.py", "tests/test_units_and_physics.py",
          "tests/test_mutation_oracles.py", "tests/test_properties.py"]
T_GSPRO = ["tests/test_gspro.py", "tests/test_interchange.py"]
T_CLUB = ["tests/test_clubs.py", "tests/test_delivery.py", "tests/test_mutation_oracles.py"]
#: the 3-D contact, club data, the 3-D kernel, derivation and deliveries (issue 23): with the oracles written
#: independently of that code (tests/test_oracles_3d.py)
T_3D = T_CLUB + ["tests/test_oracles_3d.py"]
#: the friction law of the ball-face pair (issue 21 item 3b)
T_FRICTION = ["tests/test_friction_laws.py"]
#: the JSON shot records (session_json) and the measured aerodynamic fit (aero_fit, measured_fit)
T_JSON = ["tests/test_vendors.py", "tests/test_shots.py"]
T_AERO = ["tests/test_flight.py", "tests/test_pinned_values.py"]
#: the measured aerodynamic fit (a reproduction, moved out of the package with its tests: validation/flight)
T_AERO_FIT = ["validation/flight/tests/test_aero_fit.py"]
#: the core turning behind the shell (impactlab.physics.core_torsion and its modes in the kernels)
T_FACE_FLEX = ["tests/test_face_flex.py"]
T_CORE_TORSION = ["tests/test_core_torsion.py"]
#: the drag level settled on measured radar flights, the tour tables held out (validation.flight.flight_fit, carry)
T_FLIGHT_FIT = ["validation/flight/tests/test_flight_fit.py"]
#: the values pinned in issue 31 (least squares, calibration, session rows, simulator units, club inertias)
T_FIT = ["tests/test_pinned_values.py", "tests/test_least_squares.py"]
T_ROWS = ["tests/test_pinned_values.py", "tests/test_vendors.py"]
T_SIM = ["tests/test_pinned_values.py", "tests/test_interchange.py", "tests/test_gspro.py"]
T_CAT = ["tests/test_pinned_values.py", "tests/test_club_catalogue.py", "tests/test_clubs.py"]

# (id, file, old, new, tests, what the bug is). ``old`` must occur exactly once in the file.
MUTANTS = [
    # --- physics/contact.py after_impact (the 1-D mechanics.after_impact it generalised was only tests' code and
    # is gone; its three mutants moved here, to the function every model's derived outputs come from)
    ("contact-club-recoil", "impactlab/physics/contact.py",
     "np.isinf(club), 0.0, 1.0 / club)[:, None] * impulse_ground", "np.isinf(club), 0.0, 0.0 * club)[:, None] * impulse_ground",
     T_CORE, "club's recoil dropped from the head's velocity after impact"),
    ("contact-spin-sign", "impactlab/physics/contact.py",
     'ball_spin = state["ball_spin"] + (radius / inertia)[:, None] * torque_arm',
     'ball_spin = state["ball_spin"] - (radius / inertia)[:, None] * torque_arm',
     T_CORE, "spin change with the wrong sign"),
    ("contact-energy-mean-velocity", "impactlab/physics/contact.py",
     'state["initial_velocity"] + 0.5 * (relative_after - state["initial_velocity"])',
     'state["initial_velocity"] + 1.0 * (relative_after - state["initial_velocity"])',
     T_CORE, "energy loss from the work on the final relative velocity, not the mean one (no 1/2)"),
    # --- physics/mechanics.py (the helpers plugins use, docs/writing-a-model.md)
    ("mechanics-tangential-mass-k2", "impactlab/physics/mechanics.py",
     "return 1.0 / ((1.0 + 1.0 / inertia_factor) / ball_mass + 1.0 / club_mass)",
     "return 1.0 / ((1.0 + inertia_factor) / ball_mass + 1.0 / club_mass)",
     T_CORE, "K^2 instead of 1/K^2 in the tangential mass"),
    ("mechanics-approach-spin-sign", "impactlab/physics/mechanics.py",
     "speed * np.sin(angle) - radius * spin", "speed * np.sin(angle) + radius * spin",
     T_CORE, "incoming spin adds to the slip instead of reducing it"),
    # --- physics/hertz.py
    ("hertz-modulus-nu", "impactlab/physics/hertz.py",
     "return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)", "return 1.0 / ((1.0 - nu1) / e1 + (1.0 - nu2**2) / e2)",
     T_MAW, "nu instead of nu^2 in the contact modulus"),
    ("hertz-tangential-modulus", "impactlab/physics/hertz.py",
     "return 1.0 / ((2.0 - nu1) / (4.0 * g1) + (2.0 - nu2) / (4.0 * g2))",
     "return 1.0 / ((2.0 - nu1) / (4.0 * g1) + (2.0 - nu2) / (2.0 * g2))",
     T_MAW + ["tests/test_approaches.py"], "face term of G* with 2 G instead of 4 G"),
    ("hertz-max-approach-constant", "impactlab/physics/hertz.py",
     "(15.0 * effective_mass * normal_speed**2 / (16.0 * modulus", "(16.0 * effective_mass * normal_speed**2 / (15.0 * modulus",
     T_MAW, "15/16 inverted in delta_max"),
    ("hertz-damped-load-factor-one", "impactlab/physics/hertz.py",
     "return np.maximum(1.0 + self.damping * self._solution(tau)[1], 0.0)", "return np.ones_like(tau)",
     T_MAW + ["tests/test_balls.py"], "damped (Hunt-Crossley) load factor replaced by 1"),
    ("hertz-damped-rhs-sign", "impactlab/physics/hertz.py",
     "return [v, -1.25 * max(h, 0.0) ** 1.5 * (1.0 + c * v)]", "return [v, -1.25 * max(h, 0.0) ** 1.5 * (1.0 - c * v)]",
     T_MAW + ["tests/test_balls.py"], "Hunt-Crossley damping with the wrong sign"),
    ("hertz-grid-cache-key-steps", "impactlab/physics/mdr.py",
     'cached_grid(normal, ("mdr", springs, steps),', 'cached_grid(normal, ("mdr", springs),',
     T_MAW + ["tests/test_work.py"], "MDR grid cache keyed without the step count"),
    # --- physics/mdr.py
    ("mdr-midpoints", "impactlab/physics/mdr.py",
     "xi = (np.arange(springs) + 0.5) / springs", "xi = (np.arange(springs) + 1.0) / springs",
     T_MAW, "springs at the cell ends instead of the mid-points"),
    ("mdr-gain", "impactlab/physics/mdr.py", "TANGENTIAL_GAIN = 15.0 / 4.0", "TANGENTIAL_GAIN = 5.0 / 2.0",
     T_MAW, "wrong constant in the slip equation"),
    ("mdr-ladder-floor", "impactlab/physics/mdr.py",
     "np.ceil(4.0 * np.log2(wanted / 12.0) - 1e-9)", "np.floor(4.0 * np.log2(wanted / 12.0) - 1e-9)",
     T_MAW, "resolution ladder rounded down"),
    ("mdr-steps-per-spring", "impactlab/physics/mdr.py", "STEPS_PER_SPRING = 6", "STEPS_PER_SPRING = 4",
     T_MAW, "4 time steps per spring instead of 6"),
    ("mdr-error-constant", "impactlab/physics/mdr.py", "ERROR_CONSTANT = 1.0", "ERROR_CONSTANT = 0.25",
     T_MAW, "springs term of the resolution rule's error model 4x too small"),
    ("mdr-floor-constant", "impactlab/physics/mdr.py", "PREVIOUS_CONSTANT = 1.2", "PREVIOUS_CONSTANT = 0.3",
     T_MAW + ["tests/test_benchmarks.py"], "the resolution rule's floor (the previous rule) 4x too small: gross-slip "
     "cases lose springs"),
    ("mdr-time-error-term", "impactlab/physics/mdr.py", "TIME_ERROR_CONSTANT = 0.15", "TIME_ERROR_CONSTANT = 0.0",
     T_MAW, "the time steps' term of the resolution rule's error model dropped (the rule until 2026-11)"),
    ("mdr-stick-radius-off-by-one", "impactlab/physics/kernels/mdr.py",
     "for i in range(reach):\n                    limit = max((h - xi2[i]) * load, 0.0)",
     "for i in range(reach - 1):\n                    limit = max((h - xi2[i]) * load, 0.0)",
     T_MAW, "kernel loop skips the outermost spring in contact (off by one)"),
    # --- data/least_squares.py (the one least-squares core of fit and calibrate)
    ("least-squares-variances", "impactlab/data/fit/least_squares.py",
     "sigma[depends] = np.sqrt(np.maximum(np.diag(inner), 0.0))", "sigma[depends] = np.maximum(np.diag(inner), 0.0)",
     ["tests/test_least_squares.py"], "uncertainties reported as variances, not standard deviations"),
    ("least-squares-no-rescale", "impactlab/data/fit/least_squares.py",
     "inner = inner * (float(residuals @ residuals) / (n - depends.sum()))", "inner = inner",
     ["tests/test_least_squares.py"], "unit-weight fits not rescaled by the reduced chi-square"),
    ("least-squares-near-bound-half-sigma", "impactlab/data/fit/least_squares.py",
     "(distance <= uncertainties)", "(distance <= 0.5 * uncertainties)",
     ["tests/test_least_squares.py"], "'near its bound' only within half a sigma"),
    # --- physics/kernels/contact3d.py (the 3-D kernel's one MDR spring update, and its callers)
    ("contact3d-spring-cap-doubled", "impactlab/physics/kernels/contact3d.py",
     "if squared > cap * cap:", "if squared > 4.0 * cap * cap:",
     T_CLUB + ["tests/test_kernels.py", "tests/test_coupling.py"],
     "3-D MDR springs return to a Coulomb circle twice too large (friction limit doubled)"),
    ("contact3d-spring-relaxation", "impactlab/physics/kernels/contact3d.py",
     "u[i, 0] = (u[i, 0] + ratio * x0) / (1.0 + ratio)", "u[i, 0] = (u[i, 0] + x0) / (1.0 + ratio)",
     T_CLUB + ["tests/test_kernels.py", "tests/test_coupling.py"],
     "a sliding spring-dashpot relaxes towards the cap without the step's ratio (one component)"),
    # --- physics/dem.py
    ("dem-first-order-stiffness", "impactlab/physics/dem.py",
     "mean_stiffness = np.concatenate([[0.0], 0.5 * (stiffness[1:] + stiffness[:-1])])",
     "mean_stiffness = np.concatenate([[0.0], stiffness[1:]])",
     T_DEM, "end-point (first-order) stiffness in the incremental laws"),
    ("dem-slip-gain", "impactlab/physics/dem.py", "SLIP_GAIN = 2.5", "SLIP_GAIN = 3.75",
     T_DEM, "wrong constant in the slip equation"),
    ("dem-rescale-direction", "impactlab/physics/dem.py",
     "np.where(h[1:] < h[:-1], ratio, 1.0)", "np.where(h[1:] > h[:-1], ratio, 1.0)",
     T_DEM, "history rescaled while the contact grows instead of shrinks"),
    ("dem-mindlin-sqrt", "impactlab/physics/dem.py",
     "return 1.5 * stiffness_factor * np.sqrt(np.maximum(h, 0.0))", "return 1.5 * stiffness_factor * np.maximum(h, 0.0)",
     T_DEM, "Mindlin stiffness ~ h instead of sqrt(h) (a instead of a^2 confusion)"),
    ("dem-steps-rule", "impactlab/physics/dem.py",
     "wanted = int(np.ceil((100.0 / tolerance) ** (2.0 / 3.0)))", "wanted = int(np.ceil((100.0 / tolerance) ** 0.5))",
     T_DEM, "step rule with order 2 where the incremental laws are order 1.5"),
    # --- the rolling couple on the one-spring models' 1-D solver (kernels/dem.py, models/_compliant.py)
    ("dem-couple-off-the-slip", "impactlab/physics/kernels/dem.py",
     "acceleration += slip_gain * couple", "acceleration += 0.0 * slip_gain * couple",
     T_DEM + ["tests/test_ball_laws.py"], "the couple on the line does not move the slip"),
    ("dem-couple-limit-radius", "impactlab/physics/kernels/dem.py",
     "limit = rho * root[k] * cap[k]", "limit = rho * cap[k]",
     T_DEM + ["tests/test_ball_laws.py"], "the couple's limit without the contact radius (d = arm a_max, not arm a)"),
    ("compliant-planar-rolling-sign", "models/_compliant.py",
     "start = np.where(planar, np.sign(slip) * rate[:, 1]", "start = np.where(planar, rate[:, 1]",
     T_DEM + ["tests/test_ball_laws.py"], "the rolling rate not mirrored with a negative slip on the line"),
    ("compliant-planar-energy-couple-work", "models/_compliant.py",
     "work = friction_work + unit * rolling_work", "work = friction_work",
     T_DEM + ["tests/test_ball_laws.py"], "the couple's work left out of the 1-D energy residual"),
    # --- physics/annuli.py
    ("annuli-outside-halved", "impactlab/physics/annuli.py",
     "np.where(inside, 1.0, 2.0 / np.pi * np.arcsin(", "np.where(inside, 1.0, 1.0 / np.pi * np.arcsin(",
     ["tests/test_maw.py", "tests/test_mutation_oracles.py"], "annuli: outside influence coefficient halved"),
    ("annuli-sliver-dropped", "impactlab/physics/annuli.py",
     "cap[last] += cap[last + 1]", "cap[last] += 0.0",
     ["tests/test_maw.py", "tests/test_mutation_oracles.py"], "annuli: contact beyond the last mid-radius loses its load"),
    # --- physics/rigid.py
    ("rigid-sliding-test", "impactlab/physics/rigid.py",
     "sliding = stop_slip >= cap", "sliding = stop_slip <= cap",
     T_RIGID, "rigid Coulomb: sliding and rolling branches swapped"),
    ("rigid-restitution-one-plus-e", "impactlab/physics/rigid.py",
     "jn = (1.0 + restitution) * m_normal * normal_speed", "jn = restitution * m_normal * normal_speed",
     T_RIGID, "normal impulse e m* V instead of (1+e) m* V"),
    ("restitution-beta-target-sign", "impactlab/physics/rigid.py",
     "target = np.stack([-beta * initial[:, 0]", "target = np.stack([beta * initial[:, 0]",
     T_RIGID, "tangential restitution with the wrong sign"),
    # --- physics/contact.py
    ("contact-ball-mobility-k2", "impactlab/physics/contact.py",
     "(eye + (eye - normal[:, :, None] * normal[:, None, :]) / k2[:, None, None])",
     "(eye + (eye - normal[:, :, None] * normal[:, None, :]) * k2[:, None, None])",
     T_CLUB + ["tests/test_maw.py"], "ball mobility with K^2 instead of 1/K^2"),
    ("contact-bulge-tilt-sign", "impactlab/physics/contact.py",
     "normal = _unit(flat_normal + tilt_toe[:, None] * toe", "normal = _unit(flat_normal - tilt_toe[:, None] * toe",
     T_CLUB, "convex face normal tilted the wrong way"),
    # --- models/_compliant.py
    ("compliant-chi-ball-mass", "models/_compliant.py",
     "c.chi = chi = 0.5 * c.kappa * c.m_normal / c.m_tangential",
     "c.chi = chi = 0.5 * c.kappa * c.ball_mass / c.m_tangential",
     T_MAW + ["tests/test_clubs.py"], "chi with the ball mass instead of the effective mass"),
    ("compliant-history-sign", "models/_compliant.py",
     '"tangential_force": peak * c.friction * np.sign(c.slip)', '"tangential_force": peak * c.friction',
     T_MAW + ["tests/test_paper.py"], "tangential-force history's sign dropped for negative slip"),
    ("compliant-adjusted-speed", "models/_compliant.py",
     "c.scale_speed = 0.5 * (1.0 + c.normal_restitution) * c.normal_speed",
     "c.scale_speed = c.normal_restitution * c.normal_speed",
     T_MAW, "adjusted speed e V instead of (1+e) V / 2"),
    ("compliant-impulse-sign", "models/_compliant.py",
     '"tangential_impulse": -np.sign(slip) * m_tangential * c.slip_change',
     '"tangential_impulse": np.sign(slip) * m_tangential * c.slip_change',
     T_MAW, "tangential impulse along the slip instead of against it"),
    # --- models/maw.py, models/dem.py
    ("maw-block-slice", "models/maw.py",
     "parts = [solve(chi[i:i + BLOCK], psi1[i:i + BLOCK])", "parts = [solve(chi[i:i + BLOCK], psi1[i:i + BLOCK - 1])",
     T_MAW, "off-by-one in the block slicing (crashes or shifts beyond 2047 cases)"),
    ("maw-annuli-steps", "models/maw.py",
     "return max(annuli.ANNULI_MIN_STEPS, annuli.STEPS_PER_ANNULUS * count)", "return annuli.ANNULI_MIN_STEPS",
     T_MAW, "annuli steps not scaled with the ring count"),
    ("dem-linear-ratio-inverted", "models/dem.py",
     '"stiffness_factor": self.options.stiffness_ratio / float(kappa)}', '"stiffness_factor": float(kappa) / self.options.stiffness_ratio}',
     T_DEM, "dem_linear stiffness factor r/kappa inverted"),
    # --- issue 23: new mutants over the 3-D contact, club data, the 3-D kernel, derivation and deliveries
    ("contact-path-ignores-vertical-coupling", "impactlab/physics/contact.py",
     "off = np.abs(matrix[:, [0, 0, 1], [1, 2, 2]]).max(axis=1)",
     "off = np.abs(matrix[:, [0, 1], [1, 2]]).max(axis=1)",
     T_3D, "1-D/3-D path test ignores the normal-slip (vertical) coupling: a high strike loses its gear effect"),
    ("contact-cg-in-front", "impactlab/physics/contact.py",
     '- value("club_cg_depth", 0.0)[:, None] * flat_normal)', '+ value("club_cg_depth", 0.0)[:, None] * flat_normal)',
     T_3D, "centre of mass put in front of the face instead of behind it"),
    ("contact-roll-uses-bulge", "impactlab/physics/contact.py",
     "tilt_toe, tilt_high = strike_toe / bulge, strike_high / roll",
     "tilt_toe, tilt_high = strike_toe / bulge, strike_high / bulge",
     T_3D, "the face's roll tilt computed with the bulge radius"),
    ("contact-static-loft-sign", "impactlab/physics/contact.py",
     "target = np.cos(static) * normal - np.sin(static) * up", "target = np.cos(static) * normal + np.sin(static) * up",
     T_3D, "head frame turned the wrong way by the static loft (inertia tensor misplaced)"),
    ("contact-curved-radius-sign", "impactlab/physics/contact.py",
     "contact_radius = np.sqrt(1.0 / ((1.0 / radius + 1.0 / bulge) * (1.0 / radius + 1.0 / roll)))",
     "contact_radius = np.sqrt(1.0 / ((1.0 / radius - 1.0 / bulge) * (1.0 / radius - 1.0 / roll)))",
     T_3D, "a convex face's curvature subtracted from the ball's (a concave face)"),
    ("contact-incoming-spin-sign", "impactlab/physics/contact.py",
     "ball_spin = spin[:, None] * lateral_direction", "ball_spin = -spin[:, None] * lateral_direction",
     T_3D, "incoming ball spin counted the other way in 3-D"),
    ("contact-handedness-launch-direction", "impactlab/physics/contact.py",
     "horizontal, side_spin = sign * horizontal_rh, sign * side_spin_rh",
     "horizontal, side_spin = horizontal_rh, sign * side_spin_rh",
     T_3D, "handedness sign dropped from the launch direction"),
    ("compliant3d-lateral-force-factor", "impactlab/physics/kernels/contact3d.py",
     "f1 *= 1.5 * weight", "f1 *= weight",
     T_3D, "3-D kernel: the lateral spring force without its factor 1.5"),
    ("compliant3d-loss-time-pi2", "impactlab/physics/compliant3d.py",
     "normal.tau_end / np.pi", "normal.tau_end / np.pi**3",
     T_3D + ["tests/test_balls.py"], "tangential-loss relaxation time off by pi^2"),
    ("compliant3d-coupling-sign", "impactlab/physics/compliant3d.py",
     "coupling = np.ascontiguousarray(mobility[:, :2, 2] / mobility[:, 2, 2, None])",
     "coupling = np.ascontiguousarray(-mobility[:, :2, 2] / mobility[:, 2, 2, None])",
     T_3D, "3-D kernel: the normal-tangential coupling b = W_tn/W_nn with the wrong sign"),
    ("compliant3d-lateral-impulse-sign", "impactlab/physics/compliant3d.py",
     "impulse = np.stack([-friction * out[:, 1], -friction * out[:, 2], out[:, 0]], -1)",
     "impulse = np.stack([-friction * out[:, 1], friction * out[:, 2], out[:, 0]], -1)",
     T_3D, "3-D kernel: lateral impulse returned with the wrong sign"),
    ("clubs-driver-cg-toe-high-swapped", "impactlab/scene/catalogue.py",
     'center_of_mass=tuple(c * MM for c in DRIVER_2020["center"])',
     'center_of_mass=tuple(c * MM for c in (2.9, 1.0, 42.3))',
     T_3D, "the measured driver's centre-of-mass toe and height offsets swapped"),
    ("clubs-iron-loft-lie-swapped", "impactlab/scene/catalogue.py",
     "loft=math.radians(loft), lie=math.radians(lie)", "loft=math.radians(lie), lie=math.radians(loft)",
     T_3D, "iron presets built with loft and lie swapped"),
    ("clubs-driver-axes-not-mapped", "impactlab/scene/catalogue.py", "order = [2, 1, 0]", "order = [0, 1, 2]",
     T_3D, "the published tensor's x, y, z taken as toe, up, target without remapping"),
    ("clubs-driver-gain-dropped", "impactlab/scene/catalogue.py",
     'restitution_gain=0.083, **_face("driver")', 'restitution_gain=0.0, **_face("driver")',
     T_3D + ["tests/test_validation.py"], "the driver's fitted face restitution gain dropped"),
    ("clubs-iron-depth-inch-as-cm", "impactlab/scene/catalogue.py",
     "return ((depth[2] + fraction * (depth[9] - depth[2])) * INCH,",
     "return ((depth[2] + fraction * (depth[9] - depth[2])) * 10.0,",
     ["tests/test_club_catalogue.py", "tests/test_oracles_3d.py"], "the patent's CG depths in inches read as cm"),
    ("clubs-iron-set-reversed", "impactlab/scene/catalogue.py", "fraction = (number - 2) / 7.0",
     "fraction = (9 - number) / 7.0", ["tests/test_club_catalogue.py", "tests/test_oracles_3d.py"],
     "the patent's 2-iron values given to the 9-iron (deeper CG with more loft)"),
    ("gear-effect-vertical-loft-at-contact", "impactlab/data/validation/observations.py",
     'loft_at or observation.loft_at or "contact"', 'loft_at or "contact"',
     ["tests/test_validation_sources.py"], "the higher-strike observation compared with the loft held at the contact"),
    ("derive-lateral-impulse-ignored", "impactlab/model/derive.py",
     'raw["tangential_impulse"], raw.get("lateral_impulse"))', 'raw["tangential_impulse"], None)',
     T_3D, "derived launch and spin ignore the lateral impulse (the slip that turns)"),
    ("delivery-handedness-path", "impactlab/physics/delivery.py",
     "return _unit(path, attack_angle, sign), _unit(face_angle, dynamic_loft, sign)",
     "return _unit(path, attack_angle, 1.0), _unit(face_angle, dynamic_loft, sign)",
     T_3D + ["tests/test_delivery_definitions.py"], "a left-hander's club path not mirrored"),
    # --- glue outside physics/models that the issue names
    ("study-poisson-override", "impactlab/study/scene_blocks.py",
     "ratio = base.poisson_ratio if ratio is None else ratio", "ratio = base.poisson_ratio",
     ["tests/test_study.py", "tests/test_mutation_oracles.py"], "a preset's Poisson ratio override ignored"),
    ("gspro-knots", "impactlab/units.py", "MPH = 0.44704", "MPH = 0.514444",
     T_GSPRO, "mph taken as knots in the GSPro export"),
    ("gspro-side-spin-sign", "impactlab/io/interchange.py",
     '"SideSpin": round(values["spin_rate"] * math.sin(axis), 1)',
     '"SideSpin": round(-values["spin_rate"] * math.sin(axis), 1)',
     T_GSPRO, "GSPro SideSpin with the sign opposite to SpinAxis (Garmin's CSV convention)"),
    ("gspro-handedness-dropped", "impactlab/io/interchange.py",
     'degrees = degrees * np.sign(inputs["handedness"])', "degrees = degrees",
     T_GSPRO, "a left-hander's path and face sent in golfer's words, not right-positive"),
    ("gspro-carry-in-metres", "impactlab/io/interchange.py",
     "* metres / YARD", "* metres", T_GSPRO, "CarryDistance sent in metres under Units Yards"),
    ("json-stream-refuses-cut", "impactlab/io/json_stream.py",
     'if error.pos >= len(text) or error.msg.startswith("Unterminated string"):',
     'if error.pos >= len(text):',
     T_GSPRO + ["tests/test_json_stream.py"], "a reply cut inside a string by a read refused as not JSON"),
    # --- physics/friction_laws.py: the friction law of the ball-face pair
    ("friction-cover-plane-strain", "impactlab/physics/friction_laws.py",
     "stiffness = column(cover_modulus) / (1.0 - column(cover_poisson) ** 2)",
     "stiffness = column(cover_modulus)",
     T_FRICTION, "the cover's E used for Persson's E* (the plane-strain 1 - nu^2 dropped)"),
    ("friction-peak-not-mean-pressure", "impactlab/physics/friction_laws.py",
     "mu = column(shear_strength) * 1.5 / p0 * area / force_integral",
     "mu = column(shear_strength) * 1.0 / p0 * area / force_integral",
     T_FRICTION, "adhesion over the peak pressure p0 instead of the mean pressure (2/3) p0"),
    ("friction-disc-drain-radius", "impactlab/physics/friction_laws.py",
     "drain = np.maximum(2.0 / (3.0 * a_max**2) / root, root / (4.0 * land**2))",
     "drain = np.maximum(2.0 / (3.0 * a_max**2), root / (4.0 * land**2))",
     T_FRICTION, "the squeeze film drained over the largest contact, not the growing one"),
    ("friction-flash-heat-partition", "impactlab/physics/friction_laws.py",
     "np.sqrt(np.pi) * (np.asarray(cover_effusivity, float) + np.asarray(face_effusivity, float)))\n    with",
     "np.sqrt(np.pi) * np.asarray(face_effusivity, float))\n    with",
     T_FRICTION, "the frictional heat all taken by the face (the cover's effusivity dropped)"),
    ("friction-law-ignored", "models/_common.py",
     "    if law == \"coulomb\":\n        return np.broadcast_to",
     "    if True:\n        return np.broadcast_to",
     T_FRICTION, "the models' friction_law option read but never applied"),
    ("friction-flash-slip-signed", "impactlab/physics/friction_laws.py",
     "heating = 2.0 * np.asarray(mean_pressure, float) * 0.5 * np.abs(slip_speed)",
     "heating = 2.0 * np.asarray(mean_pressure, float) * 0.5 * np.asarray(slip_speed)",
     T_FRICTION, "the flash temperature heated by the signed slip: a mirrored strike cools its cover"),
    ("friction-strip-drain-width", "impactlab/physics/friction_laws.py",
     "root / (4.0 * land**2))", "root / (2.0 * land**2))",
     T_FRICTION, "the strips between grooves drained as if the land, not half of it, were the drainage length"),
    ("friction-half-contact-time", "impactlab/physics/friction_laws.py",
     "hertz.TAU_CONTACT * approach / normal_speed", "hertz.TAU_MAX_COMPRESSION * approach / normal_speed",
     T_FRICTION, "the flash temperature over the compression only, not the whole contact"),
    ("friction-peak-pressure-heats", "impactlab/physics/friction_laws.py",
     "(2.0 / 3.0) * p0 * weighted", "p0 * weighted",
     T_FRICTION, "the flash temperature from the central pressure p0, not the mean pressure (2/3) p0"),
    ("friction-tangential-mass", "impactlab/physics/friction_laws.py",
     'mass = 1.0 / state["mobility"][:, 2, 2]', 'mass = 1.0 / state["mobility"][:, 0, 0]',
     T_FRICTION, "the Hertz history of the law driven by the tangential effective mass, not the normal one"),
    ("friction-ploughing-face-gain", "impactlab/physics/friction_laws.py",
     "ploughing_friction(slope, e - gain)", "ploughing_friction(slope, e)",
     T_FRICTION, "the ploughing loss from e with a wood face's spring-like gain, not the ball's own e"),
    ("json-escaped-quote", "impactlab/data/sessions/json_records.py",
     "skip = offset + 1", "skip = -1",
     T_JSON, "an escaped quote inside a JSON string ends the string: later shots get the wrong line"),
    ("json-case-fold", "impactlab/data/sessions/json_records.py",
     "folded = [{key.lower(): value for", "folded = [{key: value for",
     T_JSON, "keys spelled BackSpin in one message and Backspin in another land in different columns"),
    ("json-session-prefix", "impactlab/data/sessions/json_records.py",
     'if key != lists[0]}, "../")', 'if key != lists[0]}, "")',
     T_JSON, "a session's own keys (its club) not prefixed: they collide with the shots' keys"),
    ("json-line-off-by-one", "impactlab/data/sessions/json_records.py",
     "lines += [bisect.bisect_left(breaks, offset) + 1 for", "lines += [bisect.bisect_left(breaks, offset) for",
     T_JSON, "shot lines counted from 0: every message names the line above the shot"),
    ("aero-crisis-width", "impactlab/physics/aerodynamics.py",
     "return 0.5 * (1.0 - np.tanh(0.5 * (re - midpoint) / w_d))",
     "return 0.5 * (1.0 - np.tanh((re - midpoint) / w_d))",
     T_AERO, "the drag crisis half as wide as fitted (tanh without its 1/2)"),
    ("aero-crisis-spin-advance-sign", "impactlab/physics/aerodynamics.py",
     "midpoint = re_d * np.exp(-m * s)",
     "midpoint = re_d * np.exp(m * s)",
     T_AERO, "the crisis moved to a higher Re with spin instead of a lower one"),
    ("aero-fit-crisis-spin-advance", "validation/flight/aero_fit.py",
     "midpoint = re_d * np.exp(-spin_advance * s)", "midpoint = re_d * np.exp(-spin_advance * 0.0 * s)",
     T_AERO_FIT, "the fit's crisis midpoint not moving with spin (m fitted to nothing)"),
    ("aero-fit-drag-groups", "validation/flight/aero_fit.py",
     "return p[slot[group[rows]]] + p[n] * re[rows] / 1e5", "return p[slot[0 * group[rows]]] + p[n] * re[rows] / 1e5",
     T_AERO_FIT, "one drag offset for every ball instead of one per ball group"),
    ("candidates-m0-refit", "validation/flight/flight_candidates.py",
     'if p["crisis_spin_advance"] == 0.0:', 'if False:',
     ["validation/flight/tests/test_flight_candidates.py"], "the crisis without the spin advance flown with the advanced crisis' "
     "constants instead of its own refit"),
    ("aero-lift-loss-spin", "impactlab/physics/aerodynamics.py",
     "** 2 - s / s_l)", "** 2 + s / s_l)",
     T_AERO, "the reverse-Magnus lift loss growing with spin instead of fading"),
    ("aero-fit-supercritical-rows", "validation/flight/aero_fit.py",
     "data[:, 0] >= limit)", "data[:, 0] >= 0.5 * limit)",
     T_AERO_FIT, "rows inside the drag crisis fitted as supercritical"),
    ("aero-fit-model-group", "validation/flight/aero_fit.py",
     'MODEL_GROUP = "modern"', 'MODEL_GROUP = "usga_1998"',
     T_AERO_FIT, "the model's drag level taken from the 1998 ball, not the modern balls"),
    ("gspro-201-answers", "impactlab/io/gspro_connect.py",
     "if reply.code in UNSOLICITED:\n                    self._note(reply)\n                    continue",
     "if False:\n                    continue",
     T_GSPRO, "an unsolicited 201 player-information message taken as the answer to a shot"),
    # --- the core turning behind the shell (physics/core_torsion.py, the modes in both kernels, the options)
    ("core-frequency-factor", "impactlab/physics/core_torsion.py",
     "return 5.0 * special.spherical_jn(2, x) + x * shell_ratio", "return 3.0 * special.spherical_jn(2, x) + x * shell_ratio",
     T_CORE_TORSION, "frequency equation with 3 I_c for 5 I_c"),
    ("core-modal-mass-sign", "impactlab/physics/core_torsion.py",
     "(j1**2 - j0 * j2)", "(j1**2 + j0 * j2)",
     T_CORE_TORSION, "the core's modal mass integral with the wrong sign"),
    ("core-kernel3d-couple-sign", "impactlab/physics/kernels/contact3d.py",
     "am[j, 0] = -coef[j, 0] * f0 - coef[j, 3] * c1", "am[j, 0] = -coef[j, 0] * f0 + coef[j, 3] * c1",
     T_CORE_TORSION, "3-D kernel: the rolling couple drives the core's modes with the wrong sign"),
    ("core-kernel3d-slip", "impactlab/physics/kernels/contact3d.py",
     "                    v0 += hm[j, 0]\n", "                    v0 += 0.5 * hm[j, 0]\n",
     T_CORE_TORSION, "3-D kernel: half the mode's rate in the slip"),
    ("core-kernel1d-slip", "impactlab/physics/kernels/dem.py",
     "velocity += hm[j]", "velocity -= hm[j]",
     T_CORE_TORSION, "1-D solver: the mode's rate taken out of the slip"),
    ("core-line-gain", "models/_compliant.py",
     "1.25 * c.kappa[:, None] * (c.m_normal * core[3] ** 2)[:, None] * core[0]",
     "2.5 * c.kappa[:, None] * (c.m_normal * core[3] ** 2)[:, None] * core[0]",
     T_CORE_TORSION, "1-D solver: the modes' gain doubled"),
    ("core-default-density", "models/_common.py",
     "mass / (4.0 / 3.0 * np.pi * ball_radius**3)", "mass / (np.pi * ball_radius**3)",
     T_CORE_TORSION, "the default core density without the 4/3"),
    ("core-modal-damping", "impactlab/physics/core_torsion.py",
     "modal_inverse_inertia(x, core_mass, core_radius, shell_inertia), loss * frequency)",
     "modal_inverse_inertia(x, core_mass, core_radius, shell_inertia), 0.0 * frequency)",
     T_CORE_TORSION, "the core's loss factor dropped"),
    ("core-stable-steps", "impactlab/physics/compliant3d.py",
     "wanted = np.ceil(fastest * tau_end / CORE_STEP).astype(int)", "wanted = np.ceil(0.0 * fastest).astype(int)",
     T_CORE_TORSION, "3-D kernel: a stiff core's modes integrated on the given steps (their leapfrog diverges)"),
    ("core-stable-line", "models/_compliant.py",
     "three_d |= (fastest * tau_end > compliant3d.CORE_STEP", "three_d |= (fastest * tau_end > 1e9 * compliant3d.CORE_STEP",
     T_CORE_TORSION, "1-D solver: a stiff core kept on a line whose steps cannot carry its modes"),
    # --- the drag level fitted on measured flights (impactlab/data/flight_fit.py, carry.py; review5)
    ("flightfit-drag-sign", "validation/flight/flight_fit.py",
     'return cd + (c0 - MEASURED_FIT["c0"]), cl * lift_scale', 'return cd - (c0 - MEASURED_FIT["c0"]), cl * lift_scale',
     T_FLIGHT_FIT, "more c0 taken as less drag"),
    ("flightfit-fold-not-left-out", "validation/flight/flight_fit.py",
     "params = fit(sources, exclude=(group,), **shape, **options)", "params = fit(sources, **shape, **options)",
     T_FLIGHT_FIT, "leave-one-out fits every row: the 'held-out' season was fitted"),
    ("flightfit-fold-wrong-rows", "validation/flight/flight_fit.py",
     "held = np.array([group in (name, label) for", "held = np.array([group not in (name, label) for",
     T_FLIGHT_FIT, "leave-one-out reports the fitted rows' errors as the held-out one's"),
    ("flightfit-lift-rows", "validation/flight/flight_fit.py",
     '(m["s"] <= DRIVER_S) & (m["s"] > 0)', '(m["s"] >= DRIVER_S) & (m["s"] > 0)',
     T_FLIGHT_FIT, "the lift scale's bounds read from the high-spin rows, not the drivers'"),
    ("flightfit-apex-ratio", "validation/flight/flight_fit.py",
     'c["apex_height"] / c["table"].max_height - 1.0', 'c["table"].max_height / c["apex_height"] - 1.0',
     T_FLIGHT_FIT, "the apex residual inverted (measured over model)"),
    ("flightfit-height-sign", "validation/flight/flight_fit.py",
     '"height_error": check["apex_height"] - check["table"].max_height',
     '"height_error": check["table"].max_height - check["apex_height"]',
     T_FLIGHT_FIT, "held-out height error as table minus model, against the documented model minus table"),
    ("carry-air-precedence", "impactlab/data/carry.py",
     "model=model, **{**table.air, **options})", "model=model, **{**options, **table.air})",
     T_FLIGHT_FIT, "a table's stated air overrides the caller's explicit air (a sensitivity silently not run)"),
    ("carry-air-kelvin", "impactlab/data/carry.py",
     '"temperature_degC": ("temperature", 1.0, 273.15)', '"temperature_degC": ("temperature", 1.0, 0.0)',
     T_FLIGHT_FIT, "a table's temperature in degC taken as kelvin"),
    # --- the face flexing behind the contact (physics/face_flex.py, the face's mode in the 3-D kernel, the options)
    ("face-kernel-push", "impactlab/physics/kernels/contact3d.py",
     "        face_push = 1.25 * gf\n", "        face_push = 2.5 * gf\n",
     T_FACE_FLEX, "3-D kernel: the contact force drives the face's mode twice as hard"),
    ("face-kernel-compression", "impactlab/physics/kernels/contact3d.py",
     "                h = rigid - fy\n", "                h = rigid + fy\n",
     T_FACE_FLEX, "3-D kernel: the face's deflection added to the ball's compression"),
    ("face-kernel-rate", "impactlab/physics/kernels/contact3d.py",
     "load = 1.0 + c * (h_half + 0.5 * dt * ah - fz - 0.5 * dt * fa)", "load = 1.0 + c * (h_half + 0.5 * dt * ah)",
     T_FACE_FLEX, "3-D kernel: the ball's loss from the bodies' approach rate, not its compression rate"),
    ("face-kernel-reach", "impactlab/physics/kernels/contact3d.py",
     "rigid + np.sqrt(fy * fy + fz * fz / face_w2) > 0.0", "rigid > 0.0",
     T_FACE_FLEX, "3-D kernel: the contact ends before the face's swing can no longer reach the ball"),
    ("face-own-restitution", "models/_common.py",
     "np.where(face[1], np.minimum(restitution - gain, 1.0), restitution)",
     "np.where(face[1], restitution, restitution)",
     T_FACE_FLEX, "the fitted gain kept with the flexing face: ball speed counted twice"),
    ("face-modal-mass-ratio", "impactlab/physics/face_flex.py",
     "return float(2.0 * np.sum(0.5 * weights * shape**2 * s) / centre**2)",
     "return float(np.sum(0.5 * weights * shape**2 * s) / centre**2)",
     T_FACE_FLEX, "the plate's modal mass without the factor 2 of the area integral"),
    ("face-pendulum-last", "impactlab/physics/face_flex.py",
     "return float(solved.t_events[0][-1])", "return float(solved.t_events[0][0])",
     T_FACE_FLEX, "the CT taken at the pendulum's first parting, not its last"),
    # review6: the face's energy bookkeeping, the refusals of a gain above e and of a gain swept through 0
    ("face-energy-held", "impactlab/physics/kernels/contact3d.py",
     "out[case, 12] = face_taken + 0.4 * (fz * fz", "out[case, 12] = face_taken + 0.2 * (fz * fz",
     T_FACE_FLEX, "3-D kernel: the face's vibration at separation counted at half its energy"),
    ("face-energy-loss", "impactlab/physics/kernels/contact3d.py",
     "face_taken += dt * face_loss * fz * fz", "face_taken += 0.0 * face_loss * fz * fz",
     T_FACE_FLEX, "3-D kernel: what the face's loss took left out of the face's energy"),
    ("face-gain-above-e", "models/_common.py",
     "below = face[1] & (restitution < gain)", "below = face[1] & (restitution < 0.0)",
     T_FACE_FLEX, "a pair's e below the club's gain clipped to a plastic ball without a word"),
    ("face-gain-through-zero", "impactlab/study/core.py",
     "np.any(values == 0.0) and np.any(values > 0.0)):", "np.any(values < 0.0) and np.any(values > 0.0)):",
     T_FACE_FLEX, "a study sweeping the face's marker gain through 0 runs, drawing the face switching on as a jump"),
    # perf7: the 3-D kernel's arithmetic on one line (kernels/line.py), which the centred plate cases now take
    ("line-face-push", "impactlab/physics/kernels/line.py",
     "        face_push = 1.25 * gf\n", "        face_push = 2.5 * gf\n",
     T_FACE_FLEX + ["tests/test_kernels.py"], "line kernel: the contact force drives the face's mode twice as hard"),
    ("line-face-compression", "impactlab/physics/kernels/line.py",
     "                h = rigid - fy\n", "                h = rigid + fy\n",
     T_FACE_FLEX + ["tests/test_kernels.py"], "line kernel: the face's deflection added to the ball's compression"),
    ("line-face-reach", "impactlab/physics/kernels/line.py",
     "rigid + np.sqrt(fy * fy + fz * fz / face_w2) > 0.0", "rigid > 0.0",
     T_FACE_FLEX + ["tests/test_kernels.py"], "line kernel: the contact ends before the face's swing is out of reach"),
    ("line-face-energy-held", "impactlab/physics/kernels/line.py",
     "out[case, 12] = face_taken + 0.4 * (fz * fz", "out[case, 12] = face_taken + 0.2 * (fz * fz",
     T_FACE_FLEX + ["tests/test_kernels.py"], "line kernel: the face's vibration at separation at half its energy"),
    ("line-face-energy-loss", "impactlab/physics/kernels/line.py",
     "face_taken += dt * face_loss * fz * fz", "face_taken += 0.0 * face_loss * fz * fz",
     T_FACE_FLEX + ["tests/test_kernels.py"], "line kernel: what the face's loss took left out of the face's energy"),
    ("line-core-couple-sign", "impactlab/physics/kernels/line.py",
     "am[j] = -coef[j, 0] * f0 - coef[j, 3] * c1", "am[j] = -coef[j, 0] * f0 + coef[j, 3] * c1",
     T_CORE_TORSION + ["tests/test_kernels.py"], "line kernel: the rolling couple drives the core's modes backwards"),
    ("line-spring-cap", "impactlab/physics/kernels/line.py",
     "                    x0 = u[i] + d0 + lag * v0\n", "                    x0 = u[i] + d0\n",
     T_MAW + ["tests/test_kernels.py"], "line kernel: an MDR spring's dashpot left out of its trial extension"),
    ("line-couple-slip", "impactlab/physics/kernels/line.py",
     "as0 = -1.25 * k * a00 * f0 + (1.25 * k / mu) * ct01 * c1", "as0 = -1.25 * k * a00 * f0",
     T_CORE_TORSION + T_FACE_FLEX + ["tests/test_kernels.py"], "line kernel: the couple no longer moves the slip"),
    ("line-on-line-lateral", "impactlab/physics/compliant3d.py",
     "& np.all(np.abs(coupling) <= small, axis=1))", ")",
     T_FACE_FLEX + ["tests/test_kernels.py"], "a strike off centre (b != 0) given to the line kernel"),
    ("face-stable-steps", "impactlab/physics/compliant3d.py",
     "steps = face_steps(mobility, normal_speed, modulus, radius, normal, face, steps)", "pass",
     T_FACE_FLEX, "3-D kernel: a stiff face's mode integrated on the model's coarse steps (leapfrog diverges)"),
    ("face-limit-correction", "models/_compliant.py",
     "correct = c.three_d & c.sliding & (c.loss == 0.0)  #",
     "correct = c.three_d & c.sliding & (c.loss == 0.0) & (c.face is None)  #",
     T_FACE_FLEX, "maw hysteretic: the annular strips' correction and flag 64 dropped on flexing-face cases"),
    ("face-calibration-gain", "impactlab/data/fit/calibration.py",
     'if "face_restitution_gain" in names and float(', 'if False and float(',
     T_FACE_FLEX, "the calibration fits the gain the flexing face replaces (flat, and at 0 the face off)"),
    ("face-bare-unit", "impactlab/study/core.py",
     "to_si(value, dimension, f\"{where}.{key}\")", "to_si(value, dimension, f\"{where}.{key}\", bare=\"si\")",
     T_FACE_FLEX, "a study's bare face_frequency: 4000 read as rad/s (a guessed unit)"),
    # --- values pinned by tests/test_pinned_values.py (issue 31 item 7: bugs that had survived the suite)
    ('pinned-identified-range', 'impactlab/data/fit/least_squares.py',
     'identified = depends & (sigma < IDENTIFIED_SIGMA * span)',
     'identified = depends & (sigma < IDENTIFIED_SIGMA)',
     T_FIT, 'identified: sigma below 0.5 (a unit) instead of half the allowed range'),
    ('pinned-at-bound-range', 'impactlab/data/fit/least_squares.py',
     'at_bound = distance <= AT_BOUND * span',
     'at_bound = distance <= AT_BOUND',
     T_FIT, 'at its bound: within 1e-3 (a unit) instead of 1e-3 of the range'),
    ('pinned-at-bound-far-side', 'impactlab/data/fit/least_squares.py',
     'distance = np.minimum(values - lower, upper - values)',
     'distance = np.maximum(values - lower, upper - values)',
     T_FIT, 'at its bound: the distance to the far bound'),
    ('pinned-dof-all-parameters', 'impactlab/data/fit/least_squares.py',
     'inner = inner * (float(residuals @ residuals) / (n - depends.sum()))',
     'inner = inner * (float(residuals @ residuals) / (n - p))',
     T_FIT, 'unit weights: n - p degrees of freedom counting a parameter not identified'),
    ('pinned-rescale-weighted', 'impactlab/data/fit/least_squares.py',
     'if not weighted and n > depends.sum():',
     'if n > depends.sum():',
     T_FIT, 'stated sigmas: the covariance rescaled as if none were stated'),
    ('pinned-near-bound-sigma', 'impactlab/data/fit/least_squares.py',
     'near_bound = ~at_bound & identified & (distance <= uncertainties)',
     'near_bound = ~at_bound & identified',
     T_FIT, 'near its bound without the one-sigma condition'),
    ('pinned-offset-replaces', 'impactlab/data/fit/calibration.py',
     'out["strike_high"] = out["strike_high"] + given["strike_high"]',
     'out["strike_high"] = np.full(n, given["strike_high"])',
     T_FIT, "a fitted strike offset replaces each row's measured strike instead of adding to it"),
    ('pinned-gain-to-irons', 'impactlab/data/fit/calibration.py',
     'out["club_restitution_gain"] = np.where(wood, given["face_restitution_gain"], 0.0)',
     'out["club_restitution_gain"] = np.full(n, given["face_restitution_gain"])',
     T_FIT, "the face's spring-like gain given to irons (flat faces)"),
    ('pinned-flags-by-position', 'impactlab/data/sessions/reader.py',
     'values[self.flagged(key)[index]] = np.nan',
     'values[self.flagged(key)[:index.size]] = np.nan',
     T_ROWS, 'estimated values blanked by position among the kept rows, not by row'),
    ('pinned-handedness-by-position', 'impactlab/data/sessions/reader.py',
     'handedness=tuple(self.text["handedness"][i] or "right" for i in index)',
     'handedness=tuple(self.text["handedness"][i] or "right" for i in range(index.size))',
     T_ROWS, 'handedness taken by position among the kept rows, not by row'),
    ('pinned-rh-as-left', 'impactlab/data/sessions/reader.py',
     '{"r": "right", "rh": "right", "l": "left", "lh": "left"}',
     '{"r": "right", "rh": "left", "l": "left", "lh": "left"}',
     T_ROWS, 'RH read as a left-hander'),
    ('pinned-mph-as-knots', 'impactlab/io/interchange.py',
     '"Speed": round(values["ball_speed"] / MPH, 2)',
     '"Speed": round(values["ball_speed"] / 0.514444, 2)',
     T_SIM, 'ball speed sent in knots instead of mph'),
    ('pinned-units-attribute-ignored', 'impactlab/io/interchange.py',
     'return output_unit_factor(str(values.name), values.attrs.get("units"))',
     'return 1.0',
     T_SIM, "a result's units attribute ignored (an edited file's mph sent as m/s)"),
    ('pinned-carry-metres-as-yards', 'impactlab/io/interchange.py',
     'return _flat(carry, reference).astype(float) * metres / YARD',
     'return _flat(carry, reference).astype(float) * metres',
     T_SIM, 'carry sent in metres labelled yards'),
    ('pinned-backspin-sin', 'impactlab/io/interchange.py',
     '"BackSpin": round(values["spin_rate"] * math.cos(axis), 1)',
     '"BackSpin": round(values["spin_rate"] * math.sin(axis), 1)',
     T_SIM, 'back spin from the sine of the axis (back and side swapped)'),
    ('pinned-driver-axes', 'impactlab/scene/catalogue.py',
     'order = [2, 1, 0]  # toe <- z, up <- y, target <- x',
     'order = [1, 2, 0]',
     T_CAT, "the measured driver's axes mapped in another order"),
    ('pinned-wood-unscaled', 'impactlab/scene/catalogue.py',
     'moments = tuple(m * mass / 212.0 for m in (1800.0, 3300.0, 1700.0))',
     'moments = (1800.0, 3300.0, 1700.0)',
     T_CAT, "the fairway woods' moments not scaled by their mass"),
    ('pinned-iron-target-plus', 'impactlab/scene/catalogue.py',
     'return toe, up, up + toe - 200.0',
     'return toe, up, up + toe + 200.0',
     T_CAT, "the iron estimate's target moment up + toe + 200 instead of - 200"),
    ('pinned-hybrid-scale-inverted', 'impactlab/scene/catalogue.py',
     'moments = tuple(m * mass / 228.0 for m in (1300.0, 2900.0, 2200.0))',
     'moments = tuple(m * 228.0 / mass for m in (1300.0, 2900.0, 2200.0))',
     T_CAT, "the hybrids' moments scaled by the inverse mass ratio"),
]

#: mutants that change no result beyond the contract's tolerance, with the reason; the kill rate leaves them out
EQUIVALENT: dict[str, str] = {
    "maw-annuli-steps": "equivalent to the contract: the annular method's error is set by its ring count; 200 "
                        "steps instead of 10 per annulus stay within its tolerance (measured against an "
                        "independent MDR: 0.83 of the bound at 40 and 85 annuli, against 0.82 unmutated)",
}
# Not equivalent, a survivor: ``mdr-error-constant`` (the springs term of the MDR resolution rule 4x smaller)
# takes the worst ratio to the documented bound over benchmarks/resolution_rule.py's grid to 1.03 (chi 10, psi1
# 1e-3, tol 2e-5), against 0.85 unmutated: it breaks the accuracy contract, and no test sees it yet.


def _copy_tree(destination: Path) -> Path:
    ignore = shutil.ignore_patterns(".venv", ".git", "results", "*.egg-info", ".pytest_cache")
    target = destination / "impactlab-mutation"
    shutil.copytree(ROOT, target, ignore=ignore, copy_function=shutil.copy2)  # copy2 keeps mtimes: numba's cache
    (target / "impactlab_models").symlink_to(target / "models", target_is_directory=True)
    return target


def _pytest(python: str, tree: Path, env: dict, tests: list[str], timeout: float):
    """pytest on ``tests`` in the copy: (return code, stdout), or None when it ran out of time."""
    try:
        done = subprocess.run([python, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *tests],
                              cwd=tree, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return None
    return done.returncode, done.stdout


def _first_failure(stdout: str) -> str | None:
    """The node id of the first failed or erroring test in pytest's short summary (``FAILED tests/a.py::t - ...``;
    a parametrised id may hold spaces: ``t[driver 3-D]``)."""
    for line in stdout.splitlines():
        if line.startswith(("FAILED ", "ERROR ")):
            return line.split(" ", 1)[1].split(" - ", 1)[0].strip()
    return None


def _verdict(python, tree, env, tests, timeout) -> tuple[str, str]:
    """Run the mutant's tests (the mutant in place), then confirm a kill on the unmutated tree (see the module
    docstring): (status, detail); a failure is "pending" with the node id of the test to confirm."""
    ran = _pytest(python, tree, env, tests, timeout)
    if ran is None:
        return "undecided", f"timeout after {timeout:.0f} s (a timeout is no kill)"
    code, stdout = ran
    if code == 0:
        return "survived", stdout.strip().splitlines()[-1] if stdout.strip() else ""
    # the first failing test, or (nothing named: the files did not even import, pytest exit 2 or 4) the files
    node = _first_failure(stdout)
    return "pending", node if node else "\n".join(tests)


def run(selected, timeout: float, python: str, on_result=None) -> list[dict]:
    """Each mutant's verdict; ``on_result(results)`` after each (a long run's record kept as it goes)."""
    results = []
    confirmed: dict[str, tuple[int, str] | None] = {}  # node id -> its run on the unmutated tree
    with tempfile.TemporaryDirectory(prefix="impactlab-mutation-") as folder:
        tree = _copy_tree(Path(folder))
        env = {**os.environ, "PYTHONPATH": str(tree), "PYTHONDONTWRITEBYTECODE": "1"}
        for ident, file, old, new, tests, what in selected:
            path = tree / file
            original = path.read_text() if path.exists() else ""
            if original.count(old) != 1:
                results.append({"id": ident, "file": file, "what": what, "status": "stale",
                                "detail": f"the original text occurs {original.count(old)} times"})
                print(f"{ident:34s} STALE", flush=True)
                continue
            start = time.perf_counter()
            existing = [test for test in tests if (tree / test).exists()]
            try:
                path.write_text(original.replace(old, new))
                status, detail = _verdict(python, tree, env, existing, timeout)
            finally:
                path.write_text(original)  # the next mutant starts from the original source
                os.utime(path, (path.stat().st_atime, (ROOT / file).stat().st_mtime))
            if status == "pending":  # the failing test, on the unmutated tree: a kill only if it passes there
                node = detail
                if node not in confirmed:
                    confirmed[node] = _pytest(python, tree, env, node.split("\n"), timeout)
                clean = confirmed[node]
                node = node.replace("\n", " ")
                if clean is not None and clean[0] == 0:
                    status, detail = "killed", f"{node} (passes unmutated)"
                else:
                    status = "undecided"
                    detail = f"{node} fails without the mutant too" if clean else f"{node} timed out unmutated"
            if ident in EQUIVALENT:
                status = "equivalent"
            seconds = time.perf_counter() - start
            results.append({"id": ident, "file": file, "what": what, "status": status, "detail": detail,
                            "seconds": round(seconds, 1)})
            print(f"{ident:34s} {status.upper():9s} {seconds:6.1f} s  {detail[:110]}", flush=True)
            if on_result is not None:
                on_result(results)
    return results


def _area(file: str) -> str:
    return "physics" if file.startswith("impactlab/physics/") else "models" if file.startswith("models/") else "other"


def counts(results: list[dict]) -> dict:
    """Killed, survived, undecided, equivalent and stale mutants, over all and by area (physics, models, other)."""
    def tally(rows):
        return {status: sum(r["status"] == status for r in rows)
                for status in ("killed", "survived", "undecided", "equivalent", "stale")}
    return {"all": tally(results),
            **{area: tally([r for r in results if _area(r["file"]) == area]) for area in ("physics", "models", "other")}}


def describe(record: dict, name: str) -> str:
    """The sentence of docs/testing.md quoting a result file (``name``): tests/test_mutation_record.py checks it."""
    tally = record["counts"]
    areas = ", ".join(f"{area} {t['killed']}/{t['killed'] + t['survived']}" for area, t in tally.items()
                      if area != "all" and t["killed"] + t["survived"])
    everything = tally["all"]
    commits = ", ".join(record.get("commits") or [record.get("commit", "")])
    run = record.get("run") or f"{len(record['mutants'])} mutants"
    return (f"`{name}` (commit {commits}; {run}, {'complete' if record.get('complete') else 'incomplete'}): "
            f"**{everything['killed']} of {everything['killed'] + everything['survived']} decided mutants killed** "
            f"({areas}); {everything['undecided']} undecided, {everything['equivalent']} equivalent, "
            f"{everything['stale']} stale")


def summary(results: list[dict]) -> str:
    """The counts in words: the kill rate is over the mutants decided (killed or survived); undecided ones are
    listed apart, never counted as kills."""
    lines = []
    for area, tally in counts(results).items():
        decided = tally["killed"] + tally["survived"]
        if decided or tally["undecided"]:
            rate = f" ({100 * tally['killed'] / decided:.0f} %)" if decided else ""
            lines.append(f"{area}: {tally['killed']}/{decided} killed{rate}, {tally['undecided']} undecided, "
                         f"{tally['equivalent']} equivalent, {tally['stale']} stale")
    for r in results:
        if r["status"] != "killed":
            lines.append(f"  {r['status']}: {r['id']} ({r['file']}): {r['what']}")
    return "\n".join(lines)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-k", nargs="*", default=[], help="run only mutants whose id contains one of these words")
    parser.add_argument("--timeout", type=float, default=240.0,
                        help="seconds per test run before the mutant counts as undecided (never as killed)")
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    parser.add_argument("--tests", nargs="*", help="run these test files for every mutant instead of the mapped ones "
                        "(e.g. tests/test_mutation_oracles.py: does the oracle alone kill it?)")
    parser.add_argument("--output", default=str(ROOT / "benchmarks" / "mutation_results.json"))
    parser.add_argument("--reverse", action="store_true",
                        help="run the list from its end (a second run beside a first one shares the work; merge "
                             "their records with --merge)")
    parser.add_argument("--merge", nargs=2, metavar=("FIRST", "SECOND"),
                        help="write to --output the record of two runs of the same list that met (the second run "
                             "--reverse), each mutant's verdict from the run that decided it, then exit")
    parser.add_argument("--update", action="store_true",
                        help="replace the selected mutants' entries in the output file (run again, e.g. the "
                             "undecided ones) and recount, keeping the rest of its run")
    args = parser.parse_args(argv)
    if args.merge:
        first, second = (json.loads(Path(name).read_text()) for name in args.merge)
        by_id = {r["id"]: r for r in second["mutants"]}
        by_id.update({r["id"]: r for r in first["mutants"]})
        results = [by_id[m[0]] for m in MUTANTS if m[0] in by_id]
        record = {"commits": sorted({first["commit"], second["commit"]}), "command": "benchmarks/mutation.py and "
                  "benchmarks/mutation.py --reverse beside it, merged", "complete": len(results) == len(MUTANTS),
                  "run": f"{len(results)} of {len(MUTANTS)} mutants", "date": time.strftime("%Y-%m-%d", time.gmtime()),
                  "counts": counts(results), "mutants": results}
        Path(args.output).write_text(json.dumps(record, indent=1) + "\n")
        print(summary(results))
        return 0
    selected = [m for m in MUTANTS if not args.k or any(word in m[0] for word in args.k)]
    if args.reverse:
        selected = selected[::-1]
    if args.tests:
        selected = [(ident, file, old, new, list(args.tests), what) for ident, file, old, new, _, what in selected]
    if args.list:
        for ident, file, _, _, _tests, what in selected:
            print(f"{ident:34s} {file:32s} {what}")
        return 0
    started = time.perf_counter()
    # the tree the mutants run on is copied now: its commit, and whether the sources differ from it
    commit = subprocess.run(["git", "rev-parse", "HEAD"], cwd=ROOT, capture_output=True, text=True).stdout.strip()
    dirty = bool(subprocess.run(["git", "status", "--porcelain", "--", "impactlab", "models", "tests"], cwd=ROOT,
                                capture_output=True, text=True).stdout.strip())
    command = " ".join(["benchmarks/mutation.py", *(argv if argv is not None else sys.argv[1:])])

    def partial(results):  # the record so far, so that a run stopped early still says what it decided
        if not args.update:
            Path(args.output).write_text(json.dumps(
                {"commit": commit, "uncommitted_changes": dirty, "command": command, "complete": False,
                 "run": f"{len(results)} of {len(selected)} mutants", "counts": counts(results),
                 "mutants": results}, indent=1) + "\n")

    results = run(selected, args.timeout, sys.executable, partial)
    record = {"commit": commit, "uncommitted_changes": dirty, "date": time.strftime("%Y-%m-%d", time.gmtime()),
              "command": command, "complete": True,
              "full_run": not args.k and not args.tests, "minutes": round((time.perf_counter() - started) / 60, 1),
              "counts": counts(results), "mutants": results}
    if args.update:  # the earlier run's record, with these mutants' entries replaced and the runs listed
        earlier = json.loads(Path(args.output).read_text())
        again = {r["id"]: r for r in results}
        results = [again.pop(r["id"], r) for r in earlier["mutants"]] + list(again.values())
        earlier.setdefault("updates", []).append({key: record[key] for key in ("commit", "date", "command")})
        record = {**earlier, "counts": counts(results), "mutants": results}
    Path(args.output).write_text(json.dumps(record, indent=1) + "\n")
    print(summary(results))
    return 1 if any(r["status"] in ("survived", "stale", "undecided") for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
