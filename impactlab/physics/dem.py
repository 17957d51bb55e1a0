"""DEM-style tangential laws: one spring per contact, capped by Coulomb friction, in MBF's scaled variables.

Discrete-element codes (LAMMPS, LIGGGHTS, YADE, MercuryDPM) replace the
microslip of the Mindlin contact by a single tangential spring on the contact
point, F_t = k_t xi with xi the accumulated slip displacement, truncated at
mu F_n and reset to the truncation when it slides (Cundall & Strack 1979).
The contact either sticks as a whole or slips as a whole; there is no annulus
of microslip.

In the scaled variables of :mod:`.mdr` (tau = t V_z/delta_max, h = delta/delta_max,
slip velocity psi = kappa V_x/(mu V_z), tangential force f = F_t/(mu F_max)),
the slip obeys psi' = -(5/2) chi f (the MDR equation with f = 1.5 * integral of u),
the Coulomb cap is |f| <= h^(3/2) (times the load factor of a damped normal law),
and the spring laws read, with s = integral psi dtau:

- ``linear``   f = 1.5 q s: a constant k_t = r k_n with k_n = 2 E* a_max,
  the normal contact's tangent stiffness at maximum compression, q = r/kappa;
- ``mindlin``, history ``displacement``  f = 1.5 q sqrt(h) s  (k_t = 8 G* a q, "total");
- ``mindlin``, history ``force``  df = 1.5 q sqrt(h) ds  (incremental);

q = 1 for Mindlin's no-slip stiffness (kappa = k_t/k_n = G*/E* as in :mod:`.mdr`).

``rescale`` multiplies the stored displacement or force by a_new/a_old
whenever the contact shrinks (Walton; Thornton et al. 2013, eq. 18b), so that a
shrinking contact cannot keep a load it can no longer support.

Optional tangential damping adds f_d = c psi with c set by a damping ratio
zeta of the spring-mass oscillator at the current stiffness; the cap applies to
the sum, as in LAMMPS.

Numerics: a uniform time grid, velocity Verlet for the slip and a return map
for the spring (exact for a monotonic slip within a step).

References
----------
P. A. Cundall, O. D. L. Strack, A discrete numerical model for granular
assemblies, Geotechnique 29 (1979) 47-65.
C. Thornton, S. J. Cummins, P. W. Cleary, An investigation of the comparative
behaviour of alternative contact force models during inelastic collisions,
Powder Technology 233 (2013) 30-46.
"""

from __future__ import annotations

import numpy as np

from . import kernels as _kernels
from .compliant3d import CORE_STEP
from .hertz import ELASTIC, NormalLaw, cached_grid
from .mdr import TANGENTIAL_GAIN, TangentialSolution

#: psi' = -SLIP_GAIN * chi * f
SLIP_GAIN = 2.5
LAWS = ("linear", "mindlin")
HISTORIES = ("displacement", "force")


def stiffness_shape(law: str, h: np.ndarray, stiffness_factor: float) -> np.ndarray:
    """Scaled stiffness df/ds at approach h: 1.5 q (linear) or 1.5 q sqrt(h) (Mindlin), q = stiffness_factor."""
    if law == "linear":
        return np.full_like(h, 1.5 * stiffness_factor)
    return 1.5 * stiffness_factor * np.sqrt(np.maximum(h, 0.0))


def solve_scaled(chi, psi1, *, law: str = "mindlin", stiffness_factor: float = 1.0, history: str = "force",
                 rescale: bool = True, damping: float = 0.0, steps: int = 2000, record: bool = False,
                 normal: NormalLaw | None = None, rolling=None, core=None,
                 _force_numpy: bool = False) -> TangentialSolution:
    """Solve the scaled tangential impact under a DEM spring law for each (chi, psi1) pair.

    Parameters
    ----------
    chi, psi1 : array_like (cases,)
        MBF parameter and normalised incidence (see :mod:`.mdr`).
    law : {"linear", "mindlin"}
    stiffness_factor : float
        q = r/kappa: the spring's stiffness ratio r = k_t/k_n over Mindlin's kappa. For ``linear``,
        k_n is the normal tangent stiffness at maximum compression; for ``mindlin``, the current one
        (q = 1 is Mindlin's no-slip stiffness 8 G* a).
    history : {"displacement", "force"}
        What the spring stores between steps (the same for ``linear``).
    rescale : bool
        Scale the stored history by a_new/a_old when the contact shrinks.
    damping : float
        Tangential damping ratio zeta >= 0 (0: none).
    steps : int
        Uniform time steps over the contact.
    rolling : tuple of array_like (cases,), optional
        A rolling-resistance couple on the line (:mod:`.ball_laws`; the planar case of
        :func:`impactlab.physics.compliant3d.solve`, whose scaled couple c = C / (F_max a_max) and rolling rate
        w = Omega a_max / V_z it uses): (slip gain (5/4)(kappa/mu) b, rolling gain mu b, rotation r, rolling rate
        before impact w_0, arm factor d / a), with b = m* a_max B_sl and r = m* a_max^2 D_ll from
        :func:`impactlab.physics.contact.couple_mobility`, so that

            psi' = -(5/2) chi f + (5/4)(kappa/mu) b c,    w' = (5/4)(-mu b f + r c),    |c| <= (d/a) h^0.5 f_n.

        Each step takes the couple that stops the rolling by the step's end, put on its limit. None: no couple.
    core : tuple of array_like (cases, modes), optional
        The core turning behind the shell (:mod:`.core_torsion`), scaled: ((5/4) kappa g_k, Omega_k^2, d_k) with
        g_k = m* R^2 / I_k, Omega_k = omega_k delta_max / V_z, d_k = eta Omega_k; each mode adds its rate Z_k to
        the slip, Z_k' = -(5/4) kappa g_k f - Omega_k^2 Y_k - d_k Z_k (the 3-D kernel's modes on one line).
        ``dissipation`` then counts what the modes took as well (the rigid bodies' loss). Not with ``rolling``.
        Refused (ValueError) when the stiffest mode has Omega_k dt above
        :data:`impactlab.physics.compliant3d.CORE_STEP`: the modes' leapfrog would diverge.

    Returns
    -------
    TangentialSolution
        With ``moment`` (the couple's angular impulse, integral c d tau) and ``rolling_work`` (its work on the
        rolling, integral c w d tau [F_max delta_max]) when ``rolling`` is given; ``slip_change`` is then the
        change of psi from the friction and the couple together.
    """
    if law not in LAWS or history not in HISTORIES:
        raise ValueError(f"law must be one of {LAWS} and history one of {HISTORIES}")
    normal = normal or ELASTIC
    chi = np.atleast_1d(np.asarray(chi, dtype=float))
    psi1 = np.atleast_1d(np.asarray(psi1, dtype=float))

    def grid():
        nodes = np.linspace(0.0, normal.tau_end, steps + 1)
        return nodes, np.maximum(normal.approach(nodes), 0.0), normal.load_factor(nodes)

    tau, h, load = cached_grid(normal, ("dem", steps), grid)
    n = chi.size
    # (slip gain, rolling gain, rotation, rolling rate, arm factor) per case; no couple: arm 0
    parts = (0.0, 0.0, 1.0, 0.0, 0.0) if rolling is None else rolling
    couple = [np.ascontiguousarray(np.broadcast_to(np.asarray(part, float), (n,))) for part in parts]
    cap = h**1.5 * load
    stiffness = stiffness_shape(law, h, stiffness_factor)
    # a_new / a_old when the contact shrinks, 1 otherwise
    # (applied half before and half after the step's increment: Strang splitting keeps second order)
    shrink = np.ones_like(h)
    if rescale:
        ratio = np.sqrt(np.divide(h[1:], h[:-1], out=np.zeros(h.size - 1), where=h[:-1] > 0.0))
        shrink[1:] = np.sqrt(np.where(h[1:] < h[:-1], ratio, 1.0))
    # an incremental spring takes the step's mean stiffness (trapezoid), the end-point one would be first order
    mean_stiffness = np.concatenate([[0.0], 0.5 * (stiffness[1:] + stiffness[:-1])])
    store_force = history == "force" or law == "linear"
    args = (chi, psi1, tau, cap, stiffness, mean_stiffness, shrink, store_force, float(damping), SLIP_GAIN, record)
    root = np.sqrt(h)
    if core is not None and rolling is not None:
        raise ValueError("the core's modes and a rolling couple on the line are not combined (the 3-D kernel is)")
    modes = [np.zeros((n, 0))] * 3 if core is None else [
        np.ascontiguousarray(np.broadcast_to(np.asarray(part, float), (n, np.shape(core[0])[-1]))) for part in core]
    fastest = float(np.sqrt(np.max(modes[1], initial=0.0))) * normal.tau_end / steps  # Omega_k dt
    if fastest > CORE_STEP:  # the modes' leapfrog diverges beyond 2: a wrong number, not a slow one
        raise ValueError(f"the core's stiffest mode has Omega dt = {fastest:.3g} at {steps} steps, above "
                         f"{CORE_STEP}: give at least {int(np.ceil(fastest * steps / CORE_STEP))} steps or fewer modes")
    if _kernels.HAVE_NUMBA and not _force_numpy:
        force = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
        stuck = np.zeros((chi.size, tau.size)) if record else np.zeros((1, 1))
        change, work, moment, rolling_work = _kernels.dem_cases(*args, force, stuck, root, *couple, *modes)
    else:
        change, work, force, stuck, moment, rolling_work = _numpy_cases(*args, root, *couple, *modes)
    stick_radius = root[None, :] * stuck if record else None
    # the work of f on the slip, in the units of TangentialSolution.dissipation (f = 1.5 * integral u)
    dissipation = work * SLIP_GAIN / TANGENTIAL_GAIN
    return TangentialSolution(change, tau if record else None, force if record else None, stick_radius,
                              steps, dissipation, moment=None if rolling is None else moment,
                              rolling_work=None if rolling is None else rolling_work)


def _numpy_cases(chi, psi1, tau, cap, stiffness, mean_stiffness, shrink, store_force, damping, gain, record, root,
                 couple_slip, couple_roll, rotation, rolling0, arm, mode_force, mode_frequency2, mode_damping):
    """Reference implementation, vectorised over cases; same arithmetic as ``_kernels.dem_cases``."""
    n = chi.size
    modes = mode_force.shape[1]
    zm, ym, am, hm = (np.zeros((n, modes)) for _ in range(4))
    core_taken = np.zeros(n)
    spring = np.zeros(n)  # stored force (force history) or displacement (displacement history)
    change, acceleration, work, previous = np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n)
    rolls = arm > 0.0
    rate, rate_change, couple, previous_couple = rolling0.copy(), np.zeros(n), np.zeros(n), np.zeros(n)
    moment, rolling_work = np.zeros(n), np.zeros(n)
    force = np.zeros((n, tau.size)) if record else None
    stuck = np.zeros((n, tau.size)) if record else None
    for k in range(1, tau.size):
        dt = tau[k] - tau[k - 1]
        half = change + 0.5 * dt * acceleration
        velocity = psi1 + half
        if modes:  # leapfrog, as the kernel
            hm = hm + (0.5 if k == 1 else 1.0) * dt * am
            ym = ym + dt * hm
            for j in range(modes):  # in the kernel's order
                velocity = velocity + hm[:, j]
        stiff = stiffness[k]
        spring *= shrink[k]
        spring += (mean_stiffness[k] if store_force else 1.0) * dt * velocity
        spring *= shrink[k]
        elastic = spring if store_force else stiff * spring
        viscous = 2.0 * damping * np.sqrt(stiff / (gain * chi)) * velocity if damping > 0.0 else 0.0
        total = elastic + viscous
        over = np.abs(total) > cap[k]
        total = np.where(over, np.sign(total) * cap[k], total)
        reset = total - viscous
        if store_force:
            spring = np.where(over, reset, spring)
        else:
            spring = np.where(over, reset / stiff if stiff > 0.0 else 0.0, spring)
        work += 0.5 * (previous + total) * dt * velocity
        previous = total
        acceleration = -gain * chi * total
        if modes:
            am = -mode_force * total[:, None] - mode_frequency2 * ym - mode_damping * hm
            for j in range(modes):  # (a mode of gain 0 pads a case with fewer modes: inert, takes nothing)
                core_taken = core_taken + dt * np.divide(mode_damping[:, j] * hm[:, j] * hm[:, j], mode_force[:, j],
                                                         out=np.zeros(n), where=mode_force[:, j] > 0.0)
        if np.any(rolls):  # the couple that stops the rolling by the step's end, on its limit (the kernel's rule)
            middle = rate + 0.5 * dt * rate_change
            drive = -couple_roll * total
            wanted = -(middle / (0.625 * dt) + drive) / rotation
            limit = arm * root[k] * cap[k]
            couple = np.where(rolls, np.where(np.abs(wanted) > limit, np.sign(wanted) * limit, wanted), 0.0)
            acceleration = acceleration + np.where(rolls, couple_slip * couple, 0.0)
            rate_change = np.where(rolls, 1.25 * (drive + rotation * couple), 0.0)
            rate = np.where(rolls, middle + 0.5 * dt * rate_change, rate)
            rolling_work += np.where(rolls, dt * 0.5 * (previous_couple + couple) * middle, 0.0)
            moment += np.where(rolls, 0.5 * dt * (previous_couple + couple), 0.0)
            previous_couple = couple
        change = half + 0.5 * dt * acceleration
        if record:
            force[:, k] = total
            stuck[:, k] = np.where(over, 0.0, 1.0)
    if modes:
        zm = hm + 0.5 * (tau[-1] - tau[-2]) * am  # the rates at the last step's end
        for j in range(modes):
            core_taken = core_taken + np.divide(zm[:, j] * zm[:, j] + mode_frequency2[:, j] * ym[:, j] * ym[:, j],
                                                2.0 * mode_force[:, j], out=np.zeros(n), where=mode_force[:, j] > 0.0)
        work = work + core_taken
    return change, work, force, stuck, moment, rolling_work


#: most uniform steps the rule may choose; a tolerance needing more is flagged tolerance_not_met
MAX_STEPS = 200_000


def steps_for(tolerance: float) -> tuple[int, bool]:
    """Uniform steps so that |dJ_t| <= tolerance * min(mu J_n, m_t |V_x|), and whether capped.

    The same bound as MDR's (beta, spin and launch ratio accurate to the tolerance). Measured
    (chi 0.5-10, psi1 1e-3 to 6 chi, every law and history): |d psi2| / min(4 chi, psi1) <=
    91 steps^-1.5; the incremental laws converge at order 1.5 (stiffness ~ sqrt(t) from first touch),
    the others faster. The rule uses 100.
    """
    wanted = int(np.ceil((100.0 / tolerance) ** (2.0 / 3.0)))
    return min(MAX_STEPS, max(200, wanted)), wanted > MAX_STEPS


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["SLIP_GAIN", "LAWS", "HISTORIES", "stiffness_shape", "solve_scaled", "MAX_STEPS", "steps_for"]
