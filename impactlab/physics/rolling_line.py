"""The rigid impact with Coulomb friction and a rolling couple on one line, in closed form (event-driven, exact).

:func:`impactlab.physics.ball_laws.rolling_impulses` integrates the rigid impact with a rolling-resistance couple
over the normal impulse P for any case. On a case whose problem stays on one line it has an exact solution, which
this module computes event by event: the cost of a few array operations per case instead of two runs of some
hundreds of steps.

Derivation
----------
Generalised coordinates, impulse J = (J_s, J_l, J_n) on the ball [N s] and couple C = (C_s, C_l) on the ball
[N m s] (the head takes the opposite), with the symmetric mobility of
:func:`impactlab.physics.contact.couple_mobility` (Stronge 2000, ch. 5, extended by the couple):

    d(v, Omega) = [[W, B], [B^T, D]] d(J, C),

v the relative contact velocity in the contact frame (s, l, n) [m/s], Omega the relative rolling rate along
(s, l) [rad/s]. **The line.** A case is on one line when (i) W is diagonal (the slip along s and the normal
uncoupled, ``contact_state``'s ``one_dimensional``), (ii) the couple moves neither the normal (B_ns = B_nl = 0)
nor the slip through its own axis (B_ss = B_ll = 0), (iii) D_sl = 0, and (iv) nothing moves along the lateral
line before impact (v_l = 0, Omega_s = 0): the test of :func:`planar_couple` with the
mobility and the lateral slip added (:func:`on_line`). Then v_l and Omega_s receive nothing from J_s, J_n, C_l,
stay zero, and maximal dissipation keeps J_l = C_s = 0; what remains is

    normal:  dv_n = W_nn dP,
    line:    ds = a dJ + c dC,   dr = c dJ + b dC,

with s = v_s the slip [m/s], r = Omega_l the relative rolling [rad/s], J = J_s, C = C_l, a = W_ss [1/kg],
b = D_ll [1/(kg m^2)], c = B_sl [1/(kg m)]; the 2 x 2 matrix M = [[a, c], [c, b]] is positive definite
(Delta = a b - c^2 > 0; for a sphere on a fixed face Delta = 1 / (m I_b)).

**Normal impulse.** v_n does not depend on J or C, so compression ends at P_c = V_n / W_nn and the normal
force's work while separating is e^2 times its work while approaching at P_f = (1 + e) P_c: J_n = (1 + e) m_n V_n
with m_n = 1 / W_nn, Stronge's energetic e equal to Newton's kinematic e (Stronge 2000, ch. 5).

**Tangential path.** The integrator's step takes the dJ, dC that minimise the kinetic energy after the step
inside |dJ| <= mu dP, |dC| <= d dP (maximal dissipation; ``rolling_impulses_numpy``). As dP -> 0 the energy's
change s dJ + r dC is first order, so with sigma = dJ/dP, tau = dC/dP:

1. s != 0, r != 0 (both slide): sigma = -mu sgn s, tau = -d sgn r;
2. s = 0, r != 0: tau = -d sgn r, and friction holds the slip (ds/dP = 0) with sigma = -c tau / a if
   |c| d <= a mu; else the slip leaves zero with sgn(c tau) and sigma = -mu sgn(c tau) (case 1);
3. r = 0, s != 0: sigma = -mu sgn s, and the couple holds the rolling with tau = -c sigma / b if
   |c| mu <= b d; else the rolling leaves zero with sgn(c sigma) and tau = -d sgn(c sigma) (case 1);
4. s = 0, r = 0: sigma = tau = 0 holds both (M y = 0 has y = 0 only), and they stay held.

Within each regime the rates are constant, so s(P), r(P), J(P), C(P) are piecewise linear; the events are s or r
reaching zero. Held slip (2) has dr/dP = -d sgn(r) Delta / a, held rolling (3) ds/dP = -mu sgn(s) Delta / b:
both run to zero, into (4). In (1) a coordinate passing through zero keeps going only where the other's rate
drives it (|c| d > a mu for s, |c| mu > b d for r); both at once would need c^2 > a b, so at most one crossing
occurs and a case has at most three events (e.g. r crosses, s is held, r is held). The kinetic energy of the
line, x^T M^-1 x / 2 with x = (s, r), changes at s sigma + r tau = -mu |s| - d |r| <= 0: it never rises.

The result is the integrator's limit of infinitely many steps; the integrator's own error is first order in
1 / steps where a regime changes inside a step (``rolling_impulses``; Richardson extrapolation takes most of
it). With d = 0 it is the closed form of :func:`impactlab.physics.rigid.coulomb_impulses_1d`.

References
----------
W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 5 (rigid-body impact with friction
integrated over the normal impulse, energetic restitution; the slip's stick and reversal).
:mod:`impactlab.physics.ball_laws` (the rolling-resistance couple d F_n, d = (3/16) alpha a; Johnson,
*Contact Mechanics*, 1985, ch. 8) and docs/models.md, "Ball laws".
"""

from __future__ import annotations

import numpy as np

from .contact import DIAGONAL_TOLERANCE

#: regime bits of :func:`rolling_line_impulses` (``regimes=True``): slip sliding or held x rolling moving or held
BOTH_SLIDE, SLIP_HELD, ROLLING_HELD, BOTH_HELD, CROSSING = 1, 2, 4, 8, 16
#: events per case the loop allows (three at most occur, derivation in the module docstring)
MAX_EVENTS = 8


def on_line(initial, mobility, coupling, rotation, rolling, tolerance: float = DIAGONAL_TOLERANCE):
    """Whether each case's rolling impact stays on one line (module docstring, conditions i-iv).

    Parameters
    ----------
    initial : ndarray (n, 3)
        Relative contact velocity before impact in (s, l, n) [m/s].
    mobility : ndarray (n, 3, 3)
        W [1/kg].
    coupling, rotation, rolling : ndarray
        B (n, 3, 2) [1/(kg m)], D (n, 2, 2) [1/(kg m^2)] and the relative rolling rate (n, 2) [rad/s] of
        :func:`impactlab.physics.contact.couple_mobility`.
    tolerance : float
        Zero to this fraction of the largest entry of W (as ``contact_state``'s ``one_dimensional``), of B and D
        and of the rolling rate (as :func:`planar_couple`), and of the speed for the lateral slip [1].

    Returns
    -------
    ndarray (n,) of bool
    """
    off = np.abs(mobility[:, [0, 0, 1], [1, 2, 2]]).max(axis=1)
    speed = np.abs(initial).max(axis=1)
    return ((off <= tolerance * mobility[:, 2, 2]) & planar_couple(coupling, rotation, rolling, tolerance)
            & (np.abs(initial[:, 1]) <= tolerance * speed))


def planar_couple(coupling, rotation, rate, tolerance: float = DIAGONAL_TOLERANCE):
    """Whether a rolling couple stays on the line of a 1-D case: couple and rolling about the lateral axis alone.

    On a case whose mobility is diagonal (the slip along s, the normal uncoupled), the couple of
    :func:`impactlab.physics.contact.couple_mobility` keeps to the line when it moves neither the normal
    (B_n = 0) nor the slip through its own axis (B_ss = B_ll = 0), a couple along l turns nothing along s
    (D_sl = 0) and nothing rolls along s before impact: then the friction along s drives the rolling along l
    only, and the couple along l the slip along s only (a sphere on a fixed face or a point-mass head; a head
    struck on its centre-of-mass line with principal axes along the face). Zero to ``tolerance`` of the
    largest entry of B, D and the rolling rate. The compliant models keep such cases on their 1-D solver;
    :func:`on_line` adds the mobility and the lateral slip for the rigid impact's closed form.

    Parameters
    ----------
    coupling, rotation, rate : ndarray
        B (n, 3, 2) [1/(kg m)], D (n, 2, 2) [1/(kg m^2)] and the relative rolling rate (n, 2) [rad/s] of
        :func:`impactlab.physics.contact.couple_mobility`.
    tolerance : float
        Zero to this fraction of the largest entry [1].

    Returns
    -------
    ndarray (n,) of bool
    """
    scale_b = np.abs(coupling).max(axis=(1, 2))
    scale_d = np.abs(rotation).max(axis=(1, 2))
    return ((np.abs(coupling[:, 2, :]).max(axis=1) <= tolerance * scale_b)
            & (np.abs(coupling[:, 0, 0]) <= tolerance * scale_b) & (np.abs(coupling[:, 1, 1]) <= tolerance * scale_b)
            & (np.abs(rotation[:, 0, 1]) <= tolerance * scale_d)
            & (np.abs(rate[:, 0]) <= tolerance * np.maximum(np.abs(rate[:, 1]), 1.0)))


def _rates(slip, roll, mu, d, a, b, c):
    """sigma = dJ/dP, tau = dC/dP and whether the slip and the rolling are held (regimes 1-4 of the docstring)."""
    sigma, tau = -mu * np.sign(slip), -d * np.sign(roll)
    slip_zero, roll_zero = slip == 0.0, roll == 0.0
    only_slip = slip_zero & ~roll_zero
    hold = -c * tau / a
    slip_held = only_slip & (np.abs(hold) <= mu)
    sigma = np.where(only_slip, np.where(slip_held, hold, -mu * np.sign(c * tau)), sigma)
    only_roll = roll_zero & ~slip_zero
    hold = -c * sigma / b
    roll_held = only_roll & (np.abs(hold) <= d)
    tau = np.where(only_roll, np.where(roll_held, hold, -d * np.sign(c * sigma)), tau)
    both = slip_zero & roll_zero
    return sigma, tau, slip_held | both, roll_held | both


def rolling_line_impulses(initial, mobility, coupling, rotation, rolling, friction, restitution, arm,
                          regimes: bool = False):
    """The rigid rolling impact of cases on one line, exactly (derivation in the module docstring).

    Same arguments and results as :func:`impactlab.physics.ball_laws.rolling_impulses`; every case must be on
    one line (:func:`on_line`), which is not checked here.

    Parameters
    ----------
    initial : ndarray (n, 3)
        Relative contact velocity before impact in (s, l, n) [m/s] (v_n < 0).
    mobility : ndarray (n, 3, 3)
        W [1/kg].
    coupling, rotation, rolling : ndarray
        B (n, 3, 2), D (n, 2, 2) and the relative rolling rate (n, 2) of
        :func:`impactlab.physics.contact.couple_mobility`.
    friction, restitution, arm : array_like (n,)
        mu [1], the energetic (here also kinematic) e [1] and the offset d [m].
    regimes : bool
        Also return which regimes each case went through.

    Returns
    -------
    impulse : ndarray (n, 3)
        Impulse on the ball in (s, l, n) [N s] (J_l = 0).
    moment : ndarray (n, 2)
        Angular impulse of the couple on the ball along (s, l) [N m s] (C_s = 0).
    flags : ndarray (n,) of int
        Bit 1: more than :data:`MAX_EVENTS` events (never, by the derivation; kept as the integrator's flag).
    visited : ndarray (n,) of int
        Only with ``regimes``: the bits :data:`BOTH_SLIDE`, :data:`SLIP_HELD`, :data:`ROLLING_HELD`,
        :data:`BOTH_HELD` of the regimes met (over a positive range of P, or at its end), :data:`CROSSING` if
        the slip or the rolling passed through zero.
    """
    n = initial.shape[0]
    mu = np.broadcast_to(np.asarray(friction, float), (n,))
    e = np.broadcast_to(np.asarray(restitution, float), (n,))
    d = np.broadcast_to(np.asarray(arm, float), (n,))
    a, b, c = mobility[:, 0, 0], rotation[:, 1, 1], coupling[:, 0, 1]
    p_end = (1.0 + e) * (-initial[:, 2]) / mobility[:, 2, 2]
    slip, roll = initial[:, 0].astype(float), rolling[:, 1].astype(float)
    p, jt, couple = np.zeros(n), np.zeros(n), np.zeros(n)
    visited = np.zeros(n, dtype=np.int64)
    done = p_end <= 0.0
    for _ in range(MAX_EVENTS):
        if np.all(done):
            break
        sigma, tau, slip_held, roll_held = _rates(slip, roll, mu, d, a, b, c)
        ds = np.where(slip_held, 0.0, a * sigma + c * tau)
        dr = np.where(roll_held, 0.0, c * sigma + b * tau)
        regime = np.where(slip_held, np.where(roll_held, BOTH_HELD, SLIP_HELD),
                          np.where(roll_held, ROLLING_HELD, BOTH_SLIDE))
        visited |= np.where(done, 0, regime)
        crossing = ((slip == 0.0) & ~slip_held) | ((roll == 0.0) & ~roll_held)
        visited |= np.where(~done & crossing & (p > 0.0), CROSSING, 0)
        with np.errstate(divide="ignore", invalid="ignore"):
            to_slip = np.where((slip != 0.0) & (slip * ds < 0.0), -slip / ds, np.inf)
            to_roll = np.where((roll != 0.0) & (roll * dr < 0.0), -roll / dr, np.inf)
        left = p_end - p
        step = np.where(done, 0.0, np.minimum(np.minimum(to_slip, to_roll), left))
        jt += sigma * step
        couple += tau * step
        slip = np.where(to_slip <= step, 0.0, slip + ds * step)
        roll = np.where(to_roll <= step, 0.0, roll + dr * step)
        ending = ~done & (left <= step)
        p = np.where(ending, p_end, p + step)
        done |= ending
    impulse = np.stack([jt, np.zeros(n), np.where(p_end > 0.0, p_end, 0.0)], -1)
    moment = np.stack([np.zeros(n), couple], -1)
    flags = (~done).astype(np.int64)
    return (impulse, moment, flags, visited) if regimes else (impulse, moment, flags)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["MAX_EVENTS", "on_line", "planar_couple", "rolling_line_impulses"]
