"""The ball's core turning behind its shell: the rotatory (torsional) modes of an elastic core in a rigid shell.

Every other law in impactlab treats the ball as one rigid rotor. A multi-layer ball is a soft rubber core of
radius b (most of the mass) bonded inside a thin, stiffer shell (mantle and cover). The contact's tangential
force acts on the shell; the core follows through its own shear elasticity, a torsional wave at
c_s = sqrt(G / rho). This module gives the shell's rotation under a torque on it, as a rigid rotation of the
whole ball plus the core's n = 1 rotatory modes (derived here; the free-sphere limit is Lamb's).

Derivation (derived here, following the classical torsional ("toroidal") solution of Lamb 1882, section on
vibrations of the first class, and Love, *A Treatise on the Mathematical Theory of Elasticity*, 4th ed. (1927),
ch. XII). A rotation of the core about a diameter (axis z) that varies with the radius is the displacement
u_phi = f(r, t) sin(theta), which is divergence-free and satisfies Navier's equation when

    rho f_tt = G (f'' + 2 f' / r - 2 f / r^2),

solved by f = A j1(k r) e^{i omega t}, k = omega / c_s (j_n: spherical Bessel functions); f = r is the rigid
rotation. The shear stress on a sphere of radius r is tau_r_phi = G (f' - f / r) sin(theta), and its moment
about z over the sphere is M = (8 pi / 3) r^3 G (f' - f / r); with j1'(x) - j1(x) / x = -j2(x),
f' - f / r = -k A j2(k r). The rigid shell (inertia I_s about a diameter) is bonded to the core, so its angle is
alpha = f(b) / b, and it obeys I_s alpha'' = M_ext - (8 pi / 3) b^3 G (f'(b) - f(b) / b). A free vibration
(M_ext = 0) with x = k b and I_c = (8 pi / 15) rho b^5 the core's inertia gives the frequency equation

    5 I_c j2(x) + x I_s j1(x) = 0.                                                       (1)

Its roots x_1 < x_2 < ... give the modes omega_k = x_k c_s / b. Limits: I_s = 0 (a free sphere) gives
j2(x) = 0, x_1 = 5.7635 (Lamb's first torsional mode of the first class with n = 1); I_s -> inf (a clamped
surface) gives j1(x) = 0, x_1 = 4.4934; x -> 0 is the rigid rotation with inertia I_c + I_s.

Modal inertia. The kinetic energy of a mode is (1/2) q'^2 M_k with the generalised mass
M_k = (8 pi / 3) rho int_0^b f_k^2 r^2 dr + I_s alpha_k^2, and int_0^b j1(k r)^2 r^2 dr =
(b^3 / 2) (j1(x)^2 - j0(x) j2(x)). A torque M on the shell drives mode k with the force alpha_k M, and moves
the shell by alpha_k q_k. Normalised per unit shell rotation, each mode is an oscillator of inertia
I_k = M_k / alpha_k^2 at the shell:

    1 / I_k = j1(x)^2 / (m_c b^2 (j1(x)^2 - j0(x) j2(x)) + I_s j1(x)^2),   m_c the core's mass,     (2)

and the shell's angular velocity under a torque history M(t) is

    Omega_s = Omega_0 + sum_k omega_s,k,   I_tot Omega_0' = M,   omega_s,k' = M / I_k - omega_k^2 theta_k,

with I_tot = I_c + I_s (the rigid mode: (2) tends to 1 / I_tot as x -> 0). Since the core does not move at
the first instant, the mobilities add up to the shell's own: 1 / I_tot + sum_k 1 / I_k = 1 / I_s (checked in the
tests, the sum converging as x_k^-4). A few modes carry a contact's slow torque: the modes left out respond to
it quasi-statically (their displacement M / (I_k omega_k^2) is what is lost, again falling as x_k^-6).

Angular momentum. The total angular momentum is I_tot Omega_0 (the modes carry none: each is orthogonal to
the rigid mode), so after the contact the ball's spin, once the core's vibration has died, is L / I_tot: the
rigid mode's rate. That is the spin this law reports. Material damping of the core (loss factor eta) damps
mode k at the rate eta omega_k (damping ratio eta / 2); it changes what happens during contact, never the
conservation of L.

References
----------
H. Lamb, On the vibrations of an elastic sphere, Proc. London Math. Soc. 13 (1882) 189-212 (the frequency
equation of the first class; n = 1 torsional: j2(x) = 0 for a free sphere).
A. E. H. Love, A Treatise on the Mathematical Theory of Elasticity, 4th ed., Cambridge (1927), ch. XII.
D. B. Murray, L. Saviot, Phys. Rev. B 69 (2004) 094305 (tabulated free-sphere frequencies; torsional n = 1:
omega R / c_s = 5.763).
"""

from __future__ import annotations

import functools

import attrs
import numpy as np
from scipy import optimize, special

#: the root x_1 of j2 (a free sphere's first n = 1 torsional mode, omega R / c_s; Lamb 1882)
FREE_SPHERE_ROOT = 5.763459196
#: the ball law keeps by default the modes up to this frequency [Hz] (period 0.05 ms, an eighth of a golf impact's
#: 0.4 ms), and at least MIN_MODES: measured (benchmarks/measure_core_torsion.py) the spin is then within about
#: 0.1 % of 16-64 modes for G >= 2 MPa; with a fixed 4 modes it was 0.9 % low at 2 MPa and 14 % low at 0.1 MPa
CUTOFF_FREQUENCY = 20e3
MIN_MODES, MAX_MODES = 4, 64
DEFAULT_MODES = MIN_MODES


def frequency_function(x, shell_ratio):
    """5 j2(x) + x (I_s / I_c) j1(x), whose positive roots are the core's modes (module docstring, eq. 1)."""
    x = np.asarray(x, float)
    return 5.0 * special.spherical_jn(2, x) + x * shell_ratio * special.spherical_jn(1, x)


def roots(shell_ratio: float, count: int) -> np.ndarray:
    """The first ``count`` positive roots x_k = omega_k b / c_s of eq. (1) for I_s / I_c = ``shell_ratio`` >= 0.

    Bracketed on a grid of pi / 40 (root k lies between the k-th roots of j1, I_s -> inf, and of j2, I_s = 0,
    about pi apart) and refined by Brent's method to 1e-13; cached per (ratio, count).
    """
    if shell_ratio < 0.0 or not np.isfinite(shell_ratio):
        raise ValueError(f"the shell's inertia over the core's must be >= 0 and finite, not {shell_ratio}")
    return _roots(float(shell_ratio), int(count)).copy()


@functools.lru_cache(maxsize=256)
def _roots(shell_ratio: float, count: int) -> np.ndarray:
    # the first elastic root is above 4.49 and root k below (k + 1.5) pi: one grid over all of them
    grid = np.arange(1.0, (count + 2.0) * np.pi, np.pi / 40.0)
    values = frequency_function(grid, shell_ratio)
    change = np.flatnonzero(np.sign(values[:-1]) * np.sign(values[1:]) <= 0.0)[:count]
    return np.array([optimize.brentq(frequency_function, grid[i], grid[i + 1], args=(shell_ratio,), xtol=1e-13)
                     if values[i] != 0.0 else grid[i] for i in change])


def modal_inverse_inertia(x, core_mass, core_radius, shell_inertia):
    """1 / I_k of the modes at roots ``x`` (module docstring, eq. 2) [1/(kg m^2)]."""
    x = np.asarray(x, float)
    j0, j1, j2 = (special.spherical_jn(n, x) for n in (0, 1, 2))
    return j1**2 / (core_mass * core_radius**2 * (j1**2 - j0 * j2) + shell_inertia * j1**2)


@attrs.frozen
class CoreModes:
    """The rigid rotation and the core's rotatory modes of a ball, SI.

    Attributes
    ----------
    total_inertia : float
        I_tot = I_c + I_s about a diameter [kg m^2] (the rigid mode).
    shell_inertia, core_inertia : float
        I_s, I_c [kg m^2].
    frequency : ndarray (modes,)
        omega_k [rad/s].
    inverse_inertia : ndarray (modes,)
        1 / I_k, the mode's mobility at the shell [1/(kg m^2)].
    damping : ndarray (modes,)
        eta omega_k [1/s]: the modal equation is theta'' + eta omega theta' + omega^2 theta = M / I_k.
    """

    total_inertia: float
    shell_inertia: float
    core_inertia: float
    frequency: np.ndarray
    inverse_inertia: np.ndarray
    damping: np.ndarray


def core_modes(*, total_inertia, core_radius, core_density, shear_modulus, loss=0.0,
               modes: int = DEFAULT_MODES) -> CoreModes:
    """The core's rotatory modes in a ball of total inertia ``total_inertia`` (the shell holds the rest).

    Parameters
    ----------
    total_inertia : float
        The ball's moment of inertia about a diameter, K^2 m R^2 [kg m^2].
    core_radius : float
        b [m].
    core_density : float
        rho [kg/m^3] (a uniform core: I_c = (8 pi / 15) rho b^5).
    shear_modulus : float
        G of the core [Pa].
    loss : float
        The core's loss factor in shear, eta [1] (0: elastic).
    modes : int
        How many elastic modes to keep.

    Raises
    ------
    ValueError
        The core alone would hold more inertia than the ball (I_s < 0).
    """
    core_mass = 4.0 / 3.0 * np.pi * core_density * core_radius**3
    core_inertia = 0.4 * core_mass * core_radius**2
    shell_inertia = total_inertia - core_inertia
    if shell_inertia < 0.0:
        raise ValueError(f"a core of radius {core_radius * 1e3:.2f} mm and density {core_density:.0f} kg/m^3 "
                         f"has inertia {core_inertia * 1e7:.2f} g cm^2, more than the ball's "
                         f"{total_inertia * 1e7:.2f} g cm^2")
    x = roots(shell_inertia / core_inertia, modes)
    speed = np.sqrt(shear_modulus / core_density)
    frequency = x * speed / core_radius
    return CoreModes(total_inertia, shell_inertia, core_inertia, frequency,
                     modal_inverse_inertia(x, core_mass, core_radius, shell_inertia), loss * frequency)


def modes_below(cutoff, *, total_inertia, core_radius, core_density, shear_modulus) -> int:
    """How many modes lie at or below ``cutoff`` [Hz], clipped to [MIN_MODES, MAX_MODES]."""
    core_inertia = 0.4 * (4.0 / 3.0 * np.pi * core_density * core_radius**3) * core_radius**2
    ratio = max(total_inertia - core_inertia, 0.0) / core_inertia
    limit = 2.0 * np.pi * cutoff * core_radius / np.sqrt(shear_modulus / core_density)  # x at the cut-off
    # root k lies below (k + 1.5) pi: this many cover the cut-off
    wanted = int(min(max(limit / np.pi, MIN_MODES), MAX_MODES))
    count = int(np.sum(roots(ratio, wanted + 2) <= limit))
    return int(min(max(count, MIN_MODES), MAX_MODES))


def shell_response(modes: CoreModes, torque, dt: float):
    """The shell's angular velocity under a torque history on the shell, integrated mode by mode.

    Velocity Verlet on a uniform grid (the torque sampled at the nodes, ``torque[i]`` at t = i dt) with the
    damping on the half-step rate. A reference for the tests and a plain tool; the contact kernel carries the
    same modes in its own scaled variables.

    Parameters
    ----------
    modes : CoreModes
    torque : array_like (steps + 1,)
        M(t) on the shell [N m].
    dt : float
        Time step [s].

    Returns
    -------
    shell_rate : ndarray (steps + 1,)
        Omega_s [rad/s].
    momentum : ndarray (steps + 1,)
        The ball's angular momentum I_tot Omega_0 [N m s] (the modes carry none).
    energy : ndarray (steps + 1,)
        Kinetic and strain energy of the rigid rotation and the modes [J].
    """
    torque = np.asarray(torque, float)
    growth = verlet_growth(modes.frequency, modes.damping, dt)
    if np.any(growth > 1.0 + 1e-12):
        worst = int(np.argmax(growth))
        raise ValueError(f"time step dt = {dt:.3g} s is too long for the core's mode {worst + 1} (omega "
                         f"{modes.frequency[worst]:.4g} rad/s, damping {modes.damping[worst]:.4g} 1/s): velocity "
                         f"Verlet grows it by {growth[worst]:.4g} per step; take dt below about "
                         f"{0.95 * verlet_step_limit(modes.frequency, modes.damping).min():.3g} s (stable while "
                         "(omega dt)^2 + 2 c dt < 4 for every mode)")
    w0 = 0.0
    rate = np.zeros(modes.frequency.size)
    angle = np.zeros_like(rate)
    accel = torque[0] * modes.inverse_inertia
    shell, momentum, energy = (np.zeros(torque.size) for _ in range(3))
    inertia = 1.0 / modes.inverse_inertia
    for i in range(1, torque.size):
        w0 += 0.5 * dt * (torque[i - 1] + torque[i]) / modes.total_inertia
        half = rate + 0.5 * dt * accel
        angle = angle + dt * half
        accel = torque[i] * modes.inverse_inertia - modes.frequency**2 * angle - modes.damping * half
        rate = half + 0.5 * dt * accel
        shell[i] = w0 + rate.sum()
        momentum[i] = modes.total_inertia * w0
        energy[i] = 0.5 * modes.total_inertia * w0**2 + 0.5 * np.sum(inertia * (rate**2 + (modes.frequency
                                                                                             * angle) ** 2))
    return shell, momentum, energy


def verlet_growth(frequency, damping, dt: float) -> np.ndarray:
    """Largest factor by which :func:`shell_response`'s scheme multiplies a free mode per step (stable: <= 1).

    The free step maps (theta, theta') linearly, theta' being the full-step rate: with
    a = (-omega^2 theta - c theta') / (1 - c dt / 2), half = theta' + a dt / 2, theta_new = theta + dt half,
    a_new = -omega^2 theta_new - c half, theta'_new = half + a_new dt / 2. The spectral radius of that 2x2 map is
    computed, not a bound guessed from it (undamped, it is 1 for omega dt <= 2 and grows beyond; Hairer, Lubich &
    Wanner 2003, section I.1.4).

    Parameters
    ----------
    frequency, damping : array_like (modes,)
        omega_k [rad/s] and c_k = eta omega_k [1/s].
    dt : float
        Time step [s].

    Returns
    -------
    ndarray (modes,)
        The spectral radius of each mode's step map [-].
    """
    omega2 = np.asarray(frequency, float) ** 2
    c = np.asarray(damping, float) + 0.0 * omega2
    maps = np.empty(omega2.shape + (2, 2))
    for column, (theta, rate) in enumerate(((1.0, 0.0), (0.0, 1.0))):
        accel = (-omega2 * theta - c * rate) / (1.0 - 0.5 * c * dt)
        half = rate + 0.5 * dt * accel
        new_theta = theta + dt * half
        maps[..., 0, column] = new_theta
        maps[..., 1, column] = half + 0.5 * dt * (-omega2 * new_theta - c * half)
    growth = np.abs(np.linalg.eigvals(maps)).max(axis=-1)
    # at c dt / 2 >= 1 the full-step rate no longer fixes the acceleration (the division above); the map of
    # (theta, half-step rate), similar to it elsewhere, is defined there: its determinant 1 - c dt <= -1 grows it
    half = np.empty(omega2.shape + (2, 2))
    half[..., 0, 0], half[..., 0, 1] = 1.0, dt
    half[..., 1, 0], half[..., 1, 1] = -dt * omega2, 1.0 - c * dt - dt * dt * omega2
    return np.where(0.5 * c * dt < 1.0, growth, np.abs(np.linalg.eigvals(half)).max(axis=-1))


def verlet_step_limit(frequency, damping) -> np.ndarray:
    """The longest step :func:`shell_response`'s scheme is stable at, per mode [s].

    The free step's characteristic polynomial z^2 - (2 - c dt - h^2) z + (1 - c dt), h = omega dt, has both roots
    in the unit disc (Jury's conditions) while c dt < 2 and h^2 + 2 c dt < 4; the second binds first:
    dt < 4 / (c + sqrt(c^2 + 4 omega^2)), 2 / omega undamped, below it with damping (1.81 / omega at eta = 0.2).

    Parameters
    ----------
    frequency, damping : array_like (modes,)
        omega_k [rad/s] and c_k = eta omega_k [1/s].

    Returns
    -------
    ndarray (modes,)
        The stability limit of dt per mode [s] (inf for a mode with neither stiffness nor damping).
    """
    omega = np.asarray(frequency, float)
    c = np.asarray(damping, float) + 0.0 * omega
    with np.errstate(divide="ignore"):
        return 4.0 / (c + np.sqrt(c * c + 4.0 * omega * omega))


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["FREE_SPHERE_ROOT", "CUTOFF_FREQUENCY", "DEFAULT_MODES", "frequency_function", "roots",
           "modal_inverse_inertia", "CoreModes", "core_modes", "modes_below", "shell_response", "verlet_growth",
           "verlet_step_limit"]
