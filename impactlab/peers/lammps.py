"""LAMMPS (GRANULAR package) as a peer: run one ball-on-wall impact and map its settings onto impactlab's.

A golf impact in LAMMPS is one sphere (``atom_style sphere``, solid, I = 0.4 m R^2)
hitting ``fix wall/gran granular hertz/material E 0 nu tangential MODEL KT 0 MU``.
The wall is not rigid: it takes the particle's E and nu. What the 2021-2022
releases (Debian's ``lammps`` 20220106) compute, established in
tests/test_lammps.py by contact time, peak force and rebound:

1. Normal stiffness: ``fix wall/gran`` sets E_eff = E / (2 (1 - nu)), not the
   documented same-material E / (2 (1 - nu^2)) of ``pair granular``. Contact time
   and peak force match Hertz with that E_eff to 1e-4.
2. Tangential stiffness with ``KT = NULL``: the code computes
   k_t = E/4 * (2 - nu) * (1 + nu) (operator precedence; Mindlin's would be
   4 G / (2 - nu) = 2 E / ((1 + nu)(2 - nu)) for the same material), and the force is
   F_t = k_t a xi. For nu = 0.45 that is k_t/k_n = 0.31 instead of Mindlin's 0.71:
   a spring 2.3 times softer than the documentation leads one to expect.
3. History rules: ``mindlin`` stores the displacement (F_t = k_t a xi),
   ``mindlin/force`` the force (dF_t = k_t a dxi), ``_rescale`` shrinks the
   stored value by a/a_old on unloading; all reset to the Coulomb cap when
   sliding. ``linear_history`` is a constant k_t: F_t = k_t xi.
4. Integration: velocity Verlet with a first-order history update; at the
   time step used here (2e-8 s, ~26 000 steps per contact) it is converged to 1e-5.

With 1 and 2 mapped (:func:`equivalent_scene` and :func:`equivalent_options`),
``hertz_mindlin`` and ``dem_linear`` reproduce every variant to ~1e-5; the
direct reading of the documentation misses the rebound spin by a factor of 2-4.
"""

from __future__ import annotations

import shutil
import subprocess
import tempfile
from pathlib import Path

import attrs
import numpy as np

from impactlab.physics import hertz

#: LAMMPS tangential model -> impactlab model and options (before the stiffness mapping)
VARIANTS = {
    "mindlin": ("hertz_mindlin", {"history": "displacement", "rescale": False}),
    "mindlin_rescale": ("hertz_mindlin", {"history": "displacement", "rescale": True}),
    "mindlin/force": ("hertz_mindlin", {"history": "force", "rescale": False}),
    "mindlin_rescale/force": ("hertz_mindlin", {"history": "force", "rescale": True}),
    "linear_history": ("dem_linear", {}),
}

SCRIPT = """units si
atom_style sphere
atom_modify map array
boundary f f f
region box block -1 1 -1 1 -0.01 1
create_box 1 box
create_atoms 1 single 0.0 0.0 {start}
set atom 1 diameter {diameter}
set atom 1 mass {mass}
velocity all set {vx} 0.0 {vz}
comm_modify vel yes
neighbor {skin} bin
fix wall all wall/gran granular hertz/material {E} 0.0 {nu} tangential {model} {kt} 0.0 {mu} damping velocity zplane 0.0 NULL
fix move all nve/sphere
timestep {dt}
variable vx equal vx[1]
variable vz equal vz[1]
variable fz equal fz[1]
compute spin all property/atom omegay
compute total all reduce sum c_spin
variable wy equal c_total
thermo_style custom step v_vx v_vz v_wy v_fz
thermo_modify format float %.14g
thermo {every}
run {steps}
"""


@attrs.frozen
class LammpsImpact:
    """One sphere striking the wall z = 0 at ``speed`` and ``angle`` from the wall normal (SI, radians)."""

    youngs_modulus: float
    poisson_ratio: float
    radius: float
    mass: float
    friction: float
    speed: float
    angle: float
    model: str = "mindlin"
    kt: float | None = None  # None: LAMMPS's NULL (its own default from E and nu)


def available() -> bool:
    """Whether the LAMMPS executable ``lmp`` is on the PATH (the peer-code tests skip without it)."""
    return shutil.which("lmp") is not None


def run(impact: LammpsImpact, dt: float = 2e-8, every: int = 10) -> dict:
    """Run LAMMPS; return the rebound velocity (m/s), spin about y (rad/s), contact time (s), peak force (N)."""
    vx, vz = impact.speed * np.sin(impact.angle), impact.speed * np.cos(impact.angle)
    effective = impact.youngs_modulus / (2.0 * (1.0 - impact.poisson_ratio))  # what fix wall/gran uses (rule 1)
    contact = hertz.contact_time(impact.mass, impact.radius, effective, vz)
    steps = int(1.3 * contact / dt)
    script = SCRIPT.format(start=impact.radius * (1 + 1e-6), diameter=2 * impact.radius, mass=impact.mass, vx=vx,
                           vz=-vz, skin=0.1 * impact.radius, E=impact.youngs_modulus, nu=impact.poisson_ratio,
                           model=impact.model, kt="NULL" if impact.kt is None else impact.kt, mu=impact.friction,
                           dt=dt, every=every, steps=steps)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "in.impact"
        path.write_text(script)
        done = subprocess.run(["lmp", "-in", str(path), "-log", "none", "-echo", "none"], capture_output=True,
                              text=True, cwd=folder, timeout=300)
    if done.returncode != 0 or "ERROR" in done.stdout:
        raise RuntimeError(f"LAMMPS failed: {done.stdout[-2000:]}{done.stderr[-2000:]}")
    table = _thermo_table(done.stdout)
    force = table[:, 4]
    return {"vx": table[-1, 1], "vz": table[-1, 2], "spin": table[-1, 3],
            "contact_time": np.count_nonzero(force > 0.0) * every * dt, "peak_force": force.max()}


def _thermo_table(text: str) -> np.ndarray:
    lines = text.splitlines()
    start = next(i for i, line in enumerate(lines) if line.split()[:1] == ["Step"])
    rows = []
    for line in lines[start + 1:]:
        try:
            rows.append([float(value) for value in line.split()])
        except ValueError:
            break
    return np.array(rows)


def null_tangential_stiffness(youngs_modulus: float, poisson_ratio: float) -> float:
    """k_t that ``fix wall/gran`` uses for KT = NULL (rule 2), in Pa: F_t = k_t a xi."""
    return youngs_modulus / 4.0 * (2.0 - poisson_ratio) * (1.0 + poisson_ratio)


def equivalent_scene(impact: LammpsImpact) -> dict:
    """impactlab inputs (SI arrays of one case) for the LAMMPS impact: a rigid face and E* as LAMMPS has it."""
    nu = impact.poisson_ratio
    effective = impact.youngs_modulus / (2.0 * (1.0 - nu))
    values = dict(ball_radius=impact.radius, ball_mass=impact.mass, ball_inertia_factor=0.4,
                  ball_youngs_modulus=effective * (1.0 - nu**2), ball_poisson_ratio=nu,
                  face_youngs_modulus=np.inf, face_poisson_ratio=0.0, restitution=1.0, spin=0.0,
                  friction=impact.friction, speed=impact.speed, angle=impact.angle)
    return {key: np.array([float(value)]) for key, value in values.items()}


def equivalent_options(impact: LammpsImpact) -> tuple[str, dict]:
    """(impactlab model, options) that claim to reproduce ``impact.model`` with LAMMPS's stiffness semantics."""
    name, options = VARIANTS[impact.model]
    nu = impact.poisson_ratio
    effective = impact.youngs_modulus / (2.0 * (1.0 - nu))
    if name == "dem_linear":  # constant k_t [N/m]; impactlab's ratio is to k_n = 2 E* a_max
        if impact.kt is None:
            raise ValueError("linear_history needs an explicit KT")
        vz = impact.speed * np.cos(impact.angle)
        a_max = np.sqrt(impact.radius * hertz.max_approach(impact.mass, impact.radius, effective, vz))
        return name, dict(options, stiffness_ratio=float(impact.kt / (2.0 * effective * a_max)))
    kt = null_tangential_stiffness(impact.youngs_modulus, nu) if impact.kt is None else impact.kt
    return name, dict(options, stiffness_ratio=float(kt / (2.0 * effective)))


def documented_options(impact: LammpsImpact) -> tuple[str, dict, dict]:
    """What a direct reading of the documentation gives: a same-material wall and Mindlin's own stiffness."""
    name, options = VARIANTS[impact.model]
    scene = equivalent_scene(impact)
    nu = impact.poisson_ratio
    scene["ball_youngs_modulus"] = np.array([impact.youngs_modulus / 2.0])  # E* = E / (2 (1 - nu^2))
    return name, dict(options), scene | {"ball_poisson_ratio": np.array([nu])}
