"""The club face flexing behind the contact: one modal oscillator of the face in series with the Hertz contact.

A driver's thin titanium face is a spring ("trampoline" or spring-like effect). Its first mode is taken as one
oscillator along the contact normal, of modal mass m_f and angular frequency omega_f = 2 pi f_f (stiffness
k_f = m_f omega_f^2) and loss factor eta, driven by the contact force F and attached to the rigid head:

    m_f y'' + eta m_f omega_f y' + k_f y = F,      F = (4/3) E* sqrt(R) delta^1.5,   delta = r - y,

with r the approach of the rigid bodies (ball and head, through the head's mobility as before) and y the face's
deflection into the head. In modal coordinates of the free head the rigid modes take the whole force, so the
rigid bodies' impulse balance is unchanged; the face adds a compliance in series with the ball's, along the
normal only: the ball's tangential compliance is not changed. Ball + head + face conserve energy on an elastic
ball (eta = 0); the face's vibration left at separation is energy the ball does not get. On a lossy ball the face
lowers the ball's own loss (the ball is compressed less and more slowly): that is the trampoline gain, which the
fitted ``club_restitution_gain`` stands for when the face is rigid.

Where the numbers come from:

- the first mode of a clamped circular plate (Leissa 1969, Table 2.1: lambda^2 = 10.2158 for the fundamental
  mode; the mode shape J0(lambda r/a) - J0(lambda)/I0(lambda) I0(lambda r/a)); its modal mass at the centre,
  (integral rho h W^2 dA) / W(0)^2, is computed here (:func:`clamped_plate_mode`, 0.1828 of the plate's mass):
  a model output, not a measurement of a driver face;
- the characteristic time (CT) of the Rules (Equipment Rules, Part 2, 4c / Appendix II; USGA-TPX3004, Procedure
  for Measuring the Flexibility of a Golf Clubhead, rev. 1.0.0, 2008): a small steel pendulum strikes the face
  centre at low speed and the contact time is its CT; the limit is 239 us with a test tolerance of 18 us.
  :func:`pendulum_contact_time` simulates that test for a face oscillator. The pendulum's mass and tip radius
  are in the USGA's "Technical Description of the Pendulum Test", which is not in the corpora searched here:
  they are arguments, never defaults.

References
----------
A. W. Leissa, *Vibration of Plates*, NASA SP-160 (1969), ch. 2 (clamped circular plate).
S. Timoshenko, S. Woinowsky-Krieger, *Theory of Plates and Shells*, 2nd ed., McGraw-Hill (1959), sec. 19
(centre deflection of a clamped circular plate under a central load: F a^2 / (16 pi D)).
USGA, Procedure for Measuring the Flexibility of a Golf Clubhead, USGA-TPX3004 rev. 1.0.0 (2008).
N. Maw, J. R. Barber, J. N. Fawcett, Wear 38 (1976) 101-114 (the tangential oscillation at separation).
"""

from __future__ import annotations

import functools

import numpy as np
from scipy import integrate, optimize, special

#: the fundamental root of a clamped circular plate, lambda (lambda^2 = 10.2158; Leissa 1969, Table 2.1)
CLAMPED_ROOT = 3.196220616582


@functools.lru_cache(maxsize=1)
def clamped_modal_mass_ratio() -> float:
    """Modal mass at the centre of a clamped circular plate's first mode over the plate's mass [1].

    m_f / (rho h pi a^2) = 2 int_0^1 W(s)^2 s ds / W(0)^2 with W(s) = J0(lambda s) - J0(lambda)/I0(lambda)
    I0(lambda s) (Leissa 1969, ch. 2), by Gauss-Legendre quadrature: 0.1828.
    """
    lam = CLAMPED_ROOT
    nodes, weights = np.polynomial.legendre.leggauss(64)
    s = 0.5 * (nodes + 1.0)
    shape = special.j0(lam * s) - special.j0(lam) / special.i0(lam) * special.i0(lam * s)
    centre = 1.0 - special.j0(lam) / special.i0(lam)
    return float(2.0 * np.sum(0.5 * weights * shape**2 * s) / centre**2)


def clamped_plate_mode(radius, thickness, youngs_modulus, poisson_ratio, density):
    """First mode of a clamped circular plate as the face's oscillator: (f [Hz], m_f [kg], k_f [N/m]).

    f = lambda^2 / (2 pi a^2) sqrt(D / (rho h)), D = E h^3 / (12 (1 - nu^2)) (Leissa 1969); m_f the modal mass at
    the centre (:func:`clamped_modal_mass_ratio` times rho h pi a^2); k_f = m_f (2 pi f)^2, which is 1.19 times
    the static centre stiffness 16 pi D / a^2 (Timoshenko & Woinowsky-Krieger 1959). A model output: a real face
    is elliptic, thicker at its centre than at its edge, and its edge (crown, sole, skirt) is not clamped.

    Parameters
    ----------
    radius : array_like
        Plate radius a [m] (an elliptic face: the radius of equal area, sqrt(a b)).
    thickness : array_like
        Plate thickness h [m].
    youngs_modulus, poisson_ratio, density : array_like
        E [Pa], nu [1] and rho [kg/m^3] of the face's alloy.
    """
    a, h = np.asarray(radius, float), np.asarray(thickness, float)
    rigidity = youngs_modulus * h**3 / (12.0 * (1.0 - np.asarray(poisson_ratio, float) ** 2))
    frequency = CLAMPED_ROOT**2 / (2.0 * np.pi * a**2) * np.sqrt(rigidity / (density * h))
    mass = clamped_modal_mass_ratio() * density * h * np.pi * a**2
    return frequency, mass, mass * (2.0 * np.pi * frequency) ** 2


def hertz_constant(radius, youngs_1, poisson_1, youngs_2, poisson_2) -> float:
    """K of F = K delta^1.5 for a sphere of radius R on a flat [N/m^1.5]: (4/3) E* sqrt(R) (Johnson 1985, ch. 4)."""
    modulus = 1.0 / ((1.0 - poisson_1**2) / youngs_1 + (1.0 - poisson_2**2) / youngs_2)
    return 4.0 / 3.0 * modulus * np.sqrt(radius)


def pendulum_contact_time(stiffness: float, modal_mass: float, pendulum_mass: float, speed: float,
                          contact_constant: float, loss: float = 0.0) -> float:
    """Contact time [s] of a mass striking the face oscillator through a Hertz contact: the CT test simulated.

    A pendulum mass m_p (a free mass during the microseconds of contact) strikes at ``speed`` the face's modal
    mass m_f on its spring k_f (the head held still: its mass is hundreds of times the face's): Hertz's
    F = K delta^1.5 between them, delta = x_p - y, m_p x_p'' = -F, m_f y'' + eta sqrt(k_f m_f) y' + k_f y = F.
    Integrated with scipy's DOP853 over 8 times the longest of the contact's time scales; the CT is the last
    instant the force ends (the pendulum may bounce on the light modal mass several times: the CT is when its
    velocity has reached its final, largest rebound, as the USGA's pendulum patent EP 1 450 151 defines the time
    it reads). For m_f << m_p and a stiff contact it tends to pi sqrt(m_p / k_f); on a rigid face to Hertz's
    2.943 delta_max / V with delta_max = (5 m_p V^2 / (4 K))^(2/5).

    Parameters
    ----------
    stiffness, modal_mass : float
        k_f [N/m] and m_f [kg] of the face.
    pendulum_mass : float
        m_p [kg] (the USGA's is in its Technical Description of the Pendulum Test, not stored here).
    speed : float
        Impact speed [m/s].
    contact_constant : float
        K [N/m^1.5] of the pendulum tip on the face (:func:`hertz_constant`).
    loss : float
        Loss factor of the face's mode [1].
    """
    omega = np.sqrt(stiffness / modal_mass)
    hertz_time = 2.943 * (1.25 * pendulum_mass * speed**2 / contact_constant) ** 0.4 / speed
    span = 8.0 * max(hertz_time, np.pi / omega, np.pi * np.sqrt(pendulum_mass / stiffness))

    def rates(_, state):
        xp, vp, y, vy = state
        delta = xp - y
        force = contact_constant * delta**1.5 if delta > 0.0 else 0.0
        return [vp, -force / pendulum_mass, vy, (force - loss * modal_mass * omega * vy - stiffness * y) / modal_mass]

    def parted(t, state):
        return state[0] - state[2] if t > 1e-3 * hertz_time else 1.0

    parted.direction = -1  # type: ignore[attr-defined]  # (solve_ivp reads it off the event function)
    solved = integrate.solve_ivp(rates, (0.0, span), [0.0, speed, 0.0, 0.0], method="DOP853", events=parted,
                                 rtol=1e-10, atol=1e-14 * speed * span, max_step=hertz_time / 50.0)
    xp, vp, y, vy = solved.y[:, -1]
    reach = np.hypot(y, vy / omega)
    if not solved.t_events[0].size or vp >= 0.0 or xp + reach > 0.0:
        raise ValueError("pendulum_contact_time: the pendulum did not leave the face within the simulated time")
    return float(solved.t_events[0][-1])


def stiffness_for_contact_time(contact_time: float, modal_mass: float, pendulum_mass: float, speed: float,
                               contact_constant: float) -> float:
    """The face stiffness k_f [N/m] whose simulated CT (:func:`pendulum_contact_time`) is ``contact_time`` [s].

    Brent's method between a face 100 times stiffer and 100 times softer than pi^2 m_p / CT^2; raises ValueError
    when the rigid face alone (the Hertz contact) already lasts longer than ``contact_time``.
    """
    guess = np.pi**2 * pendulum_mass / contact_time**2

    def excess(log_k):
        return pendulum_contact_time(np.exp(log_k), modal_mass, pendulum_mass, speed, contact_constant) \
            - contact_time

    low, high = np.log(guess) - np.log(100.0), np.log(guess) + np.log(100.0)
    if excess(high) > 0.0:
        raise ValueError(f"stiffness_for_contact_time: the contact alone lasts longer than {contact_time:.3g} s")
    return float(np.exp(optimize.brentq(excess, low, high, xtol=1e-9)))


def modal_inputs(stiffness, modal_mass, loss=0.0):
    """The 3-D kernel's ``face`` tuple (:func:`impactlab.physics.compliant3d.solve`) of a face oscillator.

    Returns (1 / m_f [1/kg], omega_f [rad/s], eta omega_f [1/s]); a modal mass of 0 (or inf stiffness) is a
    rigid face, 1 / m_f = 0.
    """
    k, m = np.asarray(stiffness, float), np.asarray(modal_mass, float)
    rigid = (m <= 0.0) | ~np.isfinite(k)
    with np.errstate(divide="ignore", invalid="ignore"):
        omega = np.where(rigid, 0.0, np.sqrt(k / np.where(rigid, 1.0, m)))
        inverse = np.where(rigid, 0.0, 1.0 / np.where(rigid, 1.0, m))
    return inverse, omega, np.asarray(loss, float) * omega


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["CLAMPED_ROOT", "clamped_modal_mass_ratio", "clamped_plate_mode", "hertz_constant",
           "pendulum_contact_time", "stiffness_for_contact_time", "modal_inputs"]
