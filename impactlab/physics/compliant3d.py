"""The compliant contact in 3-D: Hertz normal contact and a tangential law whose slip may turn, on a coupled mobility.

The 1-D solvers (:mod:`.mdr`, :mod:`.dem`) rest on two facts of a centred
impact: the normal problem does not depend on the tangential one, and the slip
stays on one line. A free club head struck off its centre-of-mass line breaks
both: the mobility matrix W (:mod:`.contact`) couples the normal and tangential
directions, and a tangential force turns the slip. This module integrates the
contact with the full W, in the scaled variables of Maw, Barber & Fawcett with
the normal scales of the uncoupled impact (m* = 1/W_nn):

    tau = t V_z / delta_max,  h = delta / delta_max,  S = kappa v_t / (mu V_z)  (2-vector),
    f = F_t / (mu F_max) (2-vector, along the slip),  a = W_tt / W_nn,  b = W_tn / W_nn,

    h'' = -(5/4) (h^1.5 L - mu b.f),     S' = -(5/4) kappa a f + (5/4) (kappa/mu) b h^1.5 L.

With b = 0 and a = (m*/m_t) 1 this is the 1-D problem (S' = -(5/2) chi f), which
the tests check to 1e-6. The tangential law is that of the model: MDR springs
(Popov & Hess) whose displacements are 2-vectors capped on the Coulomb circle
|G* u| <= mu E* w, or one DEM spring (linear or Mindlin) capped on the circle
|F_t| <= mu F_n. For a slip that turns, MDR with circular caps is an
approximation of the 3-D Mindlin contact (it is exact for a slip along one line;
Popov & Hess 2015, ch. 5): the local traction directions of a real contact
differ across it.

A case that stays on one line (:func:`on_line`: W diagonal, a planar couple), sent
here by a law the scaled 1-D solvers do not carry (a flexing face, a core with a
couple, ...), runs :mod:`.kernels.line`: the same arithmetic on the line's
components only, the same results to round-off, 2-3x cheaper per step.

References
----------
V. L. Popov, M. Hess, *Method of Dimensionality Reduction in Contact Mechanics
and Friction*, Springer (2015), ch. 5.
N. Maw, J. R. Barber, J. N. Fawcett, Wear 38 (1976) 101-114.
"""

from __future__ import annotations

import attrs
import numpy as np

from . import hertz
from . import kernels as _kernels

LAWS = {"mdr": 0, "linear": 1, "mindlin": 2}
#: measured error constants of the 3-D kernel against min(mu J_n, m_t |V_x|) (benchmarks/bench_clubs.py and
#: docs/clubs.md; driver deliveries struck across the face): springs C_s / springs^2; time, after Richardson
#: extrapolation of the runs at N and 2N steps, C_t / N^2. Where the slip turns the plain time error is first order
#: (0.09 / N; it is second order on one line), which the extrapolation removes.
SPRING_ERROR, TIME_ERROR = 0.25, 3.0
MAX_STEPS = 200_000
#: the largest Omega_k dt the core's modes are integrated at (scaled time). Their leapfrog, damped on the half-step
#: rate, has the amplification lambda^2 - (2 - eta a - a^2) lambda + 1 - eta a = 0 (a = Omega dt) and diverges for
#: a > sqrt(eta^2 + 4) - eta: 2 undamped, 0.83 at the largest loss factor, eta = 2 (derived here). A case whose
#: stiffest mode is faster gets more steps (core_steps)
CORE_STEP = 0.5


def resolution(tolerance: float, springs_needed: bool = True) -> tuple[int, int, bool]:
    """(springs, steps of the coarse run, capped) for a 3-D case at ``tolerance``, half the budget to each error."""
    springs = max(int(np.ceil(np.sqrt(SPRING_ERROR / (0.5 * tolerance)))), 16) if springs_needed else 1
    steps = max(int(np.ceil(np.sqrt(TIME_ERROR / (0.5 * tolerance)))), 2 * springs, 100)
    capped = steps > MAX_STEPS
    return springs, min(steps, MAX_STEPS), capped
#: the kernel may run this many times its nominal steps (a coupled contact lasts longer or shorter)
STEP_ALLOWANCE = 4


@attrs.frozen
class Contact3DSolution:
    """Result of :func:`solve`, SI unless stated.

    Attributes
    ----------
    impulse : ndarray (n, 3)
        Impulse on the ball in the contact frame (s, l, n) [N s].
    impulse_time : ndarray (n, 3)
        Time integral of the running impulse over the contact [N s^2] (the head's rotation follows from it).
    contact_time : ndarray (n,) [s]
    moment : ndarray (n, 2)
        Angular impulse on the ball of the rolling-resistance couple along (s, l) [N m s] (zeros without one).
    work : ndarray (n,)
        Work of the contact forces on the relative motion of the rigid bodies [J] (with a core, less what its
        modes took: ``core_energy``).
    core_energy : ndarray (n,)
        Energy the core's modes took from the contact, held as vibration at separation or damped [J] (zeros
        without a core).
    face_energy : ndarray (n,)
        Energy the flexing face took from the contact, held as its vibration at separation or lost in it [J]
        (zeros on a rigid face); it is part of what the rigid bodies lost, ``-work`` on an elastic ball.
    steps : ndarray (n,)
    unfinished : ndarray (n,) of bool
        The step limit came before the bodies separated.
    tau, normal_force, tangential_force, stick_radius : ndarray or None
        Histories on each case's own uniform grid (tau [s] per case (n, nodes); forces [N]; radius [m]).
    """

    impulse: np.ndarray
    impulse_time: np.ndarray
    contact_time: np.ndarray
    work: np.ndarray
    steps: np.ndarray
    unfinished: np.ndarray
    moment: np.ndarray
    core_energy: np.ndarray
    face_energy: np.ndarray
    time: np.ndarray | None = None
    normal_force: np.ndarray | None = None
    tangential_force: np.ndarray | None = None
    stick_radius: np.ndarray | None = None


def solve(mobility, normal_speed, slip_speed, *, friction, kappa, modulus, radius, normal, springs: int,
          steps: int, law: str = "mdr", stiffness_factor: float = 1.0, store_force: bool = True,
          rescale: bool = False, tangential_damping: float = 0.0, tangential_loss=0.0, record: bool = False,
          extrapolate: bool = True, rolling=None, core=None, face=None, line: bool = True) -> Contact3DSolution:
    """Integrate the coupled compliant contact of each case; by default at ``steps`` and ``2 steps``, extrapolated.

    Richardson extrapolation 2 J(2N) - J(N) of the impulses, their time integrals and the work removes the
    first-order time error of a turning slip (measured order after it: about 2). Contact time and histories are
    those of the 2N run; ``steps`` reports 3N. See :func:`solve_once` for the parameters.
    """
    arguments = dict(friction=friction, kappa=kappa, modulus=modulus, radius=radius, normal=normal, springs=springs,
                     law=law, stiffness_factor=stiffness_factor, store_force=store_force, rescale=rescale,
                     tangential_damping=tangential_damping, tangential_loss=tangential_loss, rolling=rolling,
                     core=core, face=face, line=line)
    if core is not None:  # the coarse run's steps stable for the core's modes (per case; see solve_once)
        steps = core_steps(mobility, normal_speed, modulus, radius, normal, core, steps)
    if face is not None:  # and for the face's mode on the contact's stiffness (face_steps)
        steps = face_steps(mobility, normal_speed, modulus, radius, normal, face, steps)
    fine = solve_once(mobility, normal_speed, slip_speed, steps=2 * steps, record=record, **arguments)
    if not extrapolate:
        return fine
    coarse = solve_once(mobility, normal_speed, slip_speed, steps=steps, record=False, **arguments)
    return attrs.evolve(fine, impulse=2.0 * fine.impulse - coarse.impulse,
                        moment=2.0 * fine.moment - coarse.moment,
                        impulse_time=2.0 * fine.impulse_time - coarse.impulse_time,
                        work=2.0 * fine.work - coarse.work, steps=fine.steps + coarse.steps,
                        core_energy=2.0 * fine.core_energy - coarse.core_energy,
                        face_energy=2.0 * fine.face_energy - coarse.face_energy,
                        unfinished=fine.unfinished | coarse.unfinished)


def core_steps(mobility, normal_speed, modulus, radius, normal, core, steps):
    """Steps per case (n,) of at least ``steps`` at which the core's stiffest mode has Omega_k dt <= CORE_STEP.

    The modes ride on the kernel's leapfrog, which diverges for Omega_k dt > 2: a stiff core (a few GPa) on the
    3-D kernel's default steps turned a ball's spin into twice the rigid ball's, or into nonsense, with no flag.
    Cases whose modes the given steps carry keep them (their results unchanged).
    """
    n = normal_speed.size
    approach = hertz.max_approach(1.0 / mobility[:, 2, 2], radius, modulus, normal_speed)
    fastest = np.max(np.asarray(core[1], float), axis=1, initial=0.0) * approach / normal_speed  # scaled Omega
    tau_end = np.broadcast_to(np.asarray(normal.tau_end, float), (n,))
    wanted = np.ceil(fastest * tau_end / CORE_STEP).astype(int)
    return np.maximum(np.broadcast_to(np.asarray(steps, int), (n,)), wanted)


def face_steps(mobility, normal_speed, modulus, radius, normal, face, steps):
    """Steps per case (n,) of at least ``steps`` at which the face's mode has Omega_eff dt <= CORE_STEP.

    The face's mode rides on the kernel's leapfrog (as the core's modes) and feels the contact's stiffness as well
    as its own: in the scaled variables of :func:`solve_once`, y'' = (5/4) g h^1.5 - Omega^2 y with h = r - y, so
    Omega_eff^2 = Omega^2 + (15/8) g h^0.5, taken at h = 1 (the compression never exceeds the elastic approach of
    the scaled problem). A stiff face (100 kHz - 1 MHz, inside the option's range) or a light one on the default
    steps diverged to NaN or 1e280 impulses, unflagged in maw. Cases the given steps carry keep them.
    """
    n = normal_speed.size
    m_normal = 1.0 / mobility[:, 2, 2]
    inverse_mass, omega_f = (np.broadcast_to(np.asarray(part, float), (n,)) for part in face[:2])
    approach = hertz.max_approach(m_normal, radius, modulus, normal_speed)
    gain = m_normal * inverse_mass
    scaled = np.sqrt((omega_f * approach / normal_speed) ** 2 + 1.875 * gain)
    tau_end = np.broadcast_to(np.asarray(normal.tau_end, float), (n,))
    wanted = np.where(gain > 0.0, np.ceil(scaled * tau_end / CORE_STEP), 0).astype(int)
    return np.maximum(np.broadcast_to(np.asarray(steps, int), (n,)), wanted)


def on_line(ratio_tt, coupling, arm, couple_n, couple_t, couple_rr, rolling0, tolerance: float = 1e-12):
    """Whether each case stays on one line in the 3-D kernel's scaled variables (n,) bool.

    The slip along s stays there when the mobility ratios couple nothing to it (a_sl = a_ls = 0, b = 0, under
    ``tolerance``: the 1-D path's test, off-diagonal mobilities under DIAGONAL_TOLERANCE W_nn,
    :mod:`impactlab.physics.contact`). A couple (arm > 0) keeps to the lateral axis when it moves neither the
    normal nor the slip through its own axis (B_n = 0, B_ss = B_ll = 0; B_ls acts only on a couple about s, which
    stays 0), D_sl = D_ls = 0 and nothing rolls about s before impact (each under ``tolerance`` of the largest
    entry of B, of D and of the rolling rate, as :func:`impactlab.physics.rolling_line.planar_couple`). Such a case's
    components off the line stay 0 in :func:`impactlab.physics.kernels.contact3d._contact3d_cases` (to that
    tolerance), and :mod:`impactlab.physics.kernels.line` skips them.

    Parameters
    ----------
    ratio_tt : ndarray (n, 2, 2)
        a = W_tt / W_nn [1].
    coupling : ndarray (n, 2)
        b = W_tn / W_nn [1].
    arm : ndarray (n,)
        The couple's arm factor d / a [1] (0: no couple).
    couple_n, couple_t, couple_rr : ndarray (n, 2), (n, 2, 2), (n, 2, 2)
        The couple's scaled mobilities m* a_max B_n, m* a_max B_t and m* a_max^2 D [1] (:func:`solve_once`).
    rolling0 : ndarray (n, 2)
        The scaled relative rolling rate before impact, Omega a_max / V_z [1].
    tolerance : float
        Relative size under which a coupling counts as zero.

    Returns
    -------
    ndarray (n,) of bool
    """
    small = tolerance
    plain = ((np.abs(ratio_tt[:, 0, 1]) <= small) & (np.abs(ratio_tt[:, 1, 0]) <= small)
             & np.all(np.abs(coupling) <= small, axis=1))
    scale_b = small * np.maximum(np.abs(couple_n).max(axis=1), np.abs(couple_t).max(axis=(1, 2)))
    scale_d = small * np.abs(couple_rr).max(axis=(1, 2))
    planar = (np.all(np.abs(couple_n) <= scale_b[:, None], axis=1)
              & (np.abs(couple_t[:, 0, 0]) <= scale_b) & (np.abs(couple_t[:, 1, 1]) <= scale_b)
              & (np.abs(couple_rr[:, 0, 1]) <= scale_d) & (np.abs(couple_rr[:, 1, 0]) <= scale_d)
              & (np.abs(rolling0[:, 0]) <= small * np.maximum(np.abs(rolling0[:, 1]), 1.0))
              & (couple_rr[:, 1, 1] != 0.0))
    return plain & ((arm == 0.0) | planar)


def solve_once(mobility, normal_speed, slip_speed, *, friction, kappa, modulus, radius, normal, springs: int,
               steps, law: str = "mdr", stiffness_factor: float = 1.0, store_force: bool = True,
               rescale: bool = False, tangential_damping: float = 0.0, tangential_loss=0.0,
               record: bool = False, rolling=None, core=None, face=None, line: bool = True) -> Contact3DSolution:
    """Integrate the coupled compliant contact of each case.

    Parameters
    ----------
    mobility : ndarray (n, 3, 3)
        W in the contact frame (s, l, n) [1/kg].
    normal_speed : ndarray (n,)
        The normal approach speed that scales the problem [m/s] (the adjusted speed for that option).
    slip_speed : ndarray (n,)
        The contact point's slip along s [m/s] (the lateral slip is 0 by the frame's choice).
    friction, kappa, modulus, radius : ndarray (n,)
        mu, kappa = G*/E*, E* [Pa] and the Hertz radius [m].
    normal : NormalLaw or CaseNormals
        The normal law (its damping, and its duration for the step size): one for all cases, or one per case.
    springs : int
        MDR springs on the half-contact (1 for a DEM law).
    steps : int or ndarray (n,)
        Uniform steps over the uncoupled contact (with a core, raised per case where its stiffest mode needs
        more: :func:`core_steps`).
    law, stiffness_factor, store_force, rescale, tangential_damping
        The tangential law (see :mod:`.dem`; ``"mdr"`` for Maw's).
    tangential_loss : array_like
        Loss factor eta (tan delta) of the ball's cover in shear, per case: a dashpot beside each tangential
        spring with relaxation time eta / omega, omega = pi / t_c the frequency of the contact's half-sine
        pulse (a Kelvin-Voigt solid whose loss factor at omega is eta). 0: elastic springs.
    rolling : tuple, optional
        Rolling resistance (:mod:`.ball_laws`): (coupling B (n, 3, 2), rotation D (n, 2, 2), relative rolling rate
        (n, 2), arm factor (n,)) with B, D and the rate of :func:`impactlab.physics.contact.couple_mobility` and the
        arm factor d / a = (3/16) alpha; None (default): no couple.
    core : tuple, optional
        The core turning behind the shell (:mod:`.core_torsion`): (1 / I_k (n, K) [1/(kg m^2)], omega_k (n, K)
        [rad/s], modal damping eta omega_k (n, K) [1/s], the ball's radius R (n,) [m]); the rigid rotation of
        the whole ball is already in ``mobility``. None (default): a rigid ball.
    face : tuple, optional
        The face flexing behind the contact (:mod:`.face_flex`): (1 / m_f (n,) [1/kg], omega_f (n,) [rad/s],
        modal damping eta omega_f (n,) [1/s]), one modal oscillator of the face along the contact normal in
        series with the Hertz contact; 1 / m_f = 0 is a rigid face. None (default): every face rigid.
    line : bool
        Give the cases exactly on one line (:func:`on_line`) to the kernel that carries only the line's components
        (:mod:`impactlab.physics.kernels.line`: the same arithmetic, the same results to round-off, 2-3x faster);
        False: every case through the 3-D kernel (the reference).
    """
    n = normal_speed.size
    m_normal = 1.0 / mobility[:, 2, 2]
    ratio_tt = np.ascontiguousarray(mobility[:, :2, :2] / mobility[:, 2, 2, None, None])
    coupling = np.ascontiguousarray(mobility[:, :2, 2] / mobility[:, 2, 2, None])
    friction = np.broadcast_to(np.asarray(friction, float), (n,)).copy()
    with np.errstate(divide="ignore", invalid="ignore"):
        psi = np.where(friction > 0.0, kappa * slip_speed / np.where(friction > 0.0, friction * normal_speed, 1.0),
                       0.0)
    psi = np.stack([psi, np.zeros(n)], -1)
    if core is not None:
        steps = core_steps(mobility, normal_speed, modulus, radius, normal, core, steps)
    dtau = np.broadcast_to(np.asarray(normal.tau_end, float), (n,)) / steps
    max_steps = STEP_ALLOWANCE * int(np.max(steps))
    xi2 = ((np.arange(springs) + 0.5) / springs) ** 2
    shape = (n, max_steps + 1) if record else (1, 1)
    history_normal, history_tangential, history_stick = (np.zeros(shape) for _ in range(3))
    kernel = _kernels.contact3d_cases if _kernels.HAVE_NUMBA else _kernels._contact3d_cases
    approach = hertz.max_approach(m_normal, radius, modulus, normal_speed)
    reach = np.sqrt(radius * approach)  # a_max
    couple_n, couple_t, couple_rr, rolling0, arm = _scaled_rolling(rolling, n, m_normal, reach, normal_speed)
    gain, frequency, damping_modes, arm_ratio, face_gain, face_frequency, face_damping = _scaled_modes(
        core, face, n, m_normal, approach, reach, normal_speed)
    out = np.zeros((n, 13))
    # Kelvin-Voigt relaxation eta / omega with omega = pi / t_c, in the scaled time of the uncoupled contact
    relaxation = np.broadcast_to(np.asarray(tangential_loss, float), (n,)) * normal.tau_end / np.pi
    damping = np.ascontiguousarray(np.broadcast_to(np.asarray(normal.damping, float), (n,)))
    arguments = (ratio_tt, coupling, np.asarray(kappa, float).copy(), friction, psi, damping,
                 np.ascontiguousarray(dtau), max_steps, LAWS[law], float(stiffness_factor), bool(store_force),
                 bool(rescale), float(tangential_damping), np.ascontiguousarray(relaxation), xi2, 1.0 / springs,
                 bool(record), history_normal, history_tangential, history_stick, out, couple_n, couple_t, couple_rr,
                 rolling0, arm, gain, frequency, damping_modes, arm_ratio, face_gain, face_frequency, face_damping)
    straight = on_line(ratio_tt, coupling, arm, couple_n, couple_t, couple_rr, rolling0) & line
    if np.any(straight):
        (_kernels.line_cases if _kernels.HAVE_NUMBA else _kernels._line_cases)(*arguments, np.flatnonzero(straight))
    if not np.all(straight):
        kernel(*arguments, np.flatnonzero(~straight))

    solution = _solution(out, friction, modulus, radius, approach, reach, normal_speed, max_steps)
    if record:
        nodes = np.arange(max_steps + 1)
        time_unit = approach / normal_speed
        peak = 4.0 / 3.0 * modulus * np.sqrt(radius) * approach**1.5
        solution.update(
            time=nodes[None, :] * (dtau * time_unit)[:, None],
            normal_force=history_normal * peak[:, None],
            tangential_force=history_tangential * (friction * peak)[:, None],
            stick_radius=history_stick * np.sqrt(radius * approach)[:, None])
        beyond = nodes[None, :] > out[:, 8:9]
        for name in ("normal_force", "tangential_force", "stick_radius"):
            solution[name][beyond] = np.nan
    return Contact3DSolution(**solution)


def _scaled_rolling(rolling, n: int, m_normal, reach, normal_speed) -> tuple:
    """The rolling couple's mobilities and rolling rate in the kernel's scaled units (none: zeros, identity)."""
    if rolling is None:
        couple_n, couple_t = np.zeros((n, 2)), np.zeros((n, 2, 2))
        couple_rr, rolling0, arm = np.broadcast_to(np.eye(2), (n, 2, 2)).copy(), np.zeros((n, 2)), np.zeros(n)
    else:
        b, d, rate, factor = rolling
        couple_n = np.ascontiguousarray(b[:, 2, :] * (m_normal * reach)[:, None])
        couple_t = np.ascontiguousarray(b[:, :2, :] * (m_normal * reach)[:, None, None])
        couple_rr = np.ascontiguousarray(d * (m_normal * reach**2)[:, None, None])
        rolling0 = np.ascontiguousarray(rate * (reach / normal_speed)[:, None])
        arm = np.broadcast_to(np.asarray(factor, float), (n,)).copy()
    return couple_n, couple_t, couple_rr, rolling0, arm


def _scaled_modes(core, face, n: int, m_normal, approach, reach, normal_speed) -> tuple:
    """The core's modes and the face's mode in the kernel's scaled units (none: empty, zeros)."""
    if core is None:
        gain, frequency, damping_modes, arm_ratio = np.zeros((n, 0)), np.zeros((n, 0)), np.zeros((n, 0)), np.zeros(n)
    else:  # scaled: g_k = m* R^2 / I_k, Omega_k = omega_k delta_max / V_z, d_k likewise, a_max / R
        inverse, omega, eta_omega, ball_radius = core
        time_scale = (approach / normal_speed)[:, None]
        gain = np.ascontiguousarray((m_normal * ball_radius**2)[:, None] * inverse)
        frequency = np.ascontiguousarray(omega * time_scale)
        damping_modes = np.ascontiguousarray(eta_omega * time_scale)
        arm_ratio = np.ascontiguousarray(reach / ball_radius)
    if face is None:
        face_gain, face_frequency, face_damping = np.zeros(n), np.zeros(n), np.zeros(n)
    else:  # scaled: g = m* / m_f, Omega = omega_f delta_max / V_z, d likewise
        inverse_mass, omega_f, eta_omega_f = (np.broadcast_to(np.asarray(part, float), (n,)) for part in face)
        time_scale = approach / normal_speed
        face_gain = np.ascontiguousarray(m_normal * inverse_mass)
        face_frequency = np.ascontiguousarray(np.where(face_gain > 0.0, omega_f * time_scale, 1.0))
        face_damping = np.ascontiguousarray(eta_omega_f * time_scale)
    return gain, frequency, damping_modes, arm_ratio, face_gain, face_frequency, face_damping


def _solution(out, friction, modulus, radius, approach, reach, normal_speed, max_steps: int) -> dict:
    """The kernel's scaled results back in SI (impulses, times, work, moments, energies)."""
    peak = 4.0 / 3.0 * modulus * np.sqrt(radius) * approach**1.5
    time_unit = approach / normal_speed
    impulse_unit = peak * time_unit
    impulse = np.stack([-friction * out[:, 1], -friction * out[:, 2], out[:, 0]], -1) * impulse_unit[:, None]
    impulse_time = np.stack([-friction * out[:, 5], -friction * out[:, 6], out[:, 4]], -1) \
        * (impulse_unit * time_unit)[:, None]
    solution = dict(impulse=impulse, impulse_time=impulse_time, contact_time=out[:, 3] * time_unit,
                    work=out[:, 7] * peak * approach, steps=out[:, 8], unfinished=out[:, 8] >= max_steps,
                    moment=out[:, 9:11] * (peak * reach * time_unit)[:, None], core_energy=out[:, 11] * peak * approach,
                    face_energy=out[:, 12] * peak * approach)
    return solution


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["LAWS", "MAX_STEPS", "CORE_STEP", "resolution", "STEP_ALLOWANCE", "Contact3DSolution", "solve",
           "core_steps", "face_steps", "on_line", "solve_once"]
