"""Ball laws beyond the paper's elastic sphere: the rolling resistance of a viscoelastic cover, as plain functions.

Rolling resistance (a centre-of-pressure offset). A viscoelastic body rolling over
a contact is loaded at the leading edge and unloaded at the trailing edge; the
material gives back less on unloading than it took on loading, so the pressure
is higher ahead of the contact centre than behind it. The resultant normal force
then acts a distance d ahead of the centre, and its moment about the ball's
centre opposes the rolling: a couple of size d F_n that resists the relative
rolling rate Omega of ball and face. Greenwood & Tabor's hysteresis argument
(Tabor 1955; Greenwood, Minshall & Tabor 1961; Johnson, *Contact Mechanics*,
1985, section 8.? "rolling of viscoelastic bodies", the hysteresis estimate)
gives, for a sphere whose material loses the fraction alpha of the elastic
energy of a loading-unloading cycle,

    d = (3 / 16) alpha a,

with a the Hertz contact radius (for a cylinder the factor is 2 / (3 pi)). The
offset grows and shrinks with the contact (a ~ F_n^(1/3)), so it is a law, not
a constant: its angular impulse over an impact is (3/16) alpha int a F_n dt.

The hysteresis fraction alpha of a golf ball's cover under the contact is not
published; the loading-unloading cycle of the same material under the same
contact is the normal impact itself, which loses the fraction 1 - e^2 of its
energy (e: normal restitution). ``alpha = 1 - e^2`` is therefore the choice
that adds no free parameter (option value ``"restitution"`` in the models); a
number may be given instead. The couple only dissipates: it always opposes the
relative rolling rate and, when the rolling stops, holds it at zero with a
couple no larger than d F_n (the rolling analogue of Coulomb's static friction),
so the work it does on the relative rolling is never positive.

Energy bookkeeping. The couple C on the ball (the head takes -C) joins the
contact impulse J as two more generalised coordinates with the symmetric
mobility of :func:`impactlab.physics.contact.couple_mobility`; the rigid-body
integrator below works on that 5 x 5 mobility with Stronge's energetic
restitution, so rolling resistance never changes the normal work that sets e.

References
----------
D. Tabor, The mechanism of rolling friction II, Proc. R. Soc. A 229 (1955) 198-220.
J. A. Greenwood, H. Minshall, D. Tabor, Hysteresis losses in rolling and sliding friction, Proc. R. Soc. A 259
(1961) 480-507.
K. L. Johnson, *Contact Mechanics*, Cambridge University Press (1985), ch. 8 (rolling contact of viscoelastic
bodies; the hysteresis estimate d = (3/16) alpha a for a sphere).
W. J. Stronge, *Impact Mechanics*, Cambridge University Press (2000), ch. 5.
Proceedings 49 (2020) 47 (Waterloo and Ping): a rigid-body driver model fitted a 0.5 mm shift of the normal
force's line below the ball's centre (a fitted parameter, not a measurement), the same couple with a constant d.
"""

from __future__ import annotations

import functools

import numpy as np

from . import hertz
from . import kernels as _kernels

#: d / (alpha a) for a sphere (Greenwood-Tabor hysteresis estimate; Johnson 1985, ch. 8)
SPHERE_FACTOR = 3.0 / 16.0
#: default steps over the normal impulse of :func:`rolling_impulses` (run at N and 2N and extrapolated)
ROLLING_STEPS = 200
#: most sweeps of the projected block Gauss-Seidel that splits each step's impulse between friction and the couple:
#: warm-started from the previous step, the kernel's sweeps stop once the split no longer changes (usually after
#: two); 6 left some off-centre cases 1e-5 short of the converged split (tests/test_ball_laws.py)
SWEEPS = 30


def hysteresis_fraction(value, restitution, face_gain=0.0):
    """alpha per case: a number in [0, 1], or ``"restitution"`` for 1 - e_ball^2 (module docstring) [1].

    e_ball = e - face_gain is the ball's own restitution against a rigid face: a thin wood face's spring-like
    rise of e (input ``club_restitution_gain``) returns energy the face stored, not energy the cover kept, so
    it does not enter the cover's hysteresis.
    """
    e = np.asarray(restitution, float)
    if isinstance(value, str):
        ball = e - np.asarray(face_gain, float)
        return np.clip(1.0 - ball**2, 0.0, 1.0)
    return np.broadcast_to(np.asarray(value, float), e.shape).copy()


def rolling_arm(alpha, contact_radius):
    """Offset d = (3/16) alpha a of the normal force ahead of the contact centre [m] (Johnson 1985, ch. 8).

    Parameters
    ----------
    alpha : array_like
        Fraction of the elastic energy of a loading-unloading cycle lost to hysteresis [1].
    contact_radius : array_like
        Hertz contact radius a [m].
    """
    return SPHERE_FACTOR * np.asarray(alpha, float) * np.asarray(contact_radius, float)


@functools.lru_cache(maxsize=1)
def mean_radius_ratio() -> float:
    """The impulse-weighted mean contact radius of an elastic Hertz impact over its largest, int a F dt / (a_max J).

    With h = delta / delta_max, a = a_max h^(1/2) and F ~ h^(3/2): int h^2 dtau / int h^(3/2) dtau over the
    contact (0.896, computed here on the exact Hertz history, :func:`impactlab.physics.hertz.scaled_approach`).
    """
    tau = np.linspace(0.0, hertz.TAU_CONTACT, 20001)
    h = np.clip(hertz.scaled_approach(tau), 0.0, None)
    return float(np.trapezoid(h**2, tau) / np.trapezoid(h**1.5, tau))


def mean_rolling_arm(alpha, contact_radius, effective_mass, modulus, normal_speed):
    """The impulse-weighted mean offset d_bar = (3/16) alpha a_bar of an elastic Hertz impact [m].

    a_bar = 0.896 a_max with a_max = sqrt(R delta_max) (:func:`mean_radius_ratio`): the offset a rigid-body model
    applies per unit normal impulse, so that its couple's angular impulse is that of the Hertz history,
    (3/16) alpha int a F dt.

    Parameters
    ----------
    alpha : array_like
        Hysteresis fraction [1].
    contact_radius : array_like
        Relative radius of curvature R of ball and face [m] (Hertz's R, not the contact radius).
    effective_mass, modulus, normal_speed : array_like
        m* [kg], E* [Pa], V_n [m/s].
    """
    approach = hertz.max_approach(effective_mass, contact_radius, modulus, normal_speed)
    return rolling_arm(alpha, mean_radius_ratio() * np.sqrt(np.asarray(contact_radius, float) * approach))


def _project(vector, limit):
    """Vectors (n, 2) put inside discs of radius ``limit`` (n,) along themselves."""
    size = np.hypot(vector[:, 0], vector[:, 1])
    scale = np.where(size > limit, limit / np.where(size > 0.0, size, 1.0), 1.0)
    return vector * scale[:, None]


def rolling_impulses(initial, mobility, coupling, rotation, rolling, friction, restitution, arm,
                     steps: int = ROLLING_STEPS, extrapolate: bool = True):
    """The rolling impact of each case (:func:`rolling_impulses_numpy` has the method and the parameters).

    Runs the compiled kernel (``_kernels.rolling_cases``; numpy where numba is off, to round-off the same) at
    ``steps`` and ``2 steps`` and extrapolates, 2 J(2N) - J(N): measured on the conformance suite's driver
    cases against 32000 steps, the plain error falls as 0.1 / steps of mu J_n (the slip direction is frozen
    within a step); extrapolated at 200 it is 1.3e-5 on the driver cases and 5e-5 on the plate cases (where
    the compression ends inside a step; benchmarks/bench_ball_laws.py). Returns
    (impulse (n, 3), moment (n, 2), flags (n,)).
    """
    arguments = (initial, mobility, coupling, rotation, rolling, friction, restitution, arm)
    if extrapolate:  # Richardson: the error is first order in 1/steps where the slip turns
        coarse, fine = rolling_impulses(*arguments, steps, False), rolling_impulses(*arguments, 2 * steps, False)
        return 2.0 * fine[0] - coarse[0], 2.0 * fine[1] - coarse[1], fine[2] | coarse[2]
    if not _kernels.HAVE_NUMBA:
        return rolling_impulses_numpy(*arguments, steps)
    n = initial.shape[0]
    impulse, moment, flags = np.zeros((n, 3)), np.zeros((n, 2)), np.zeros(n, dtype=np.int64)

    def column(value):
        return np.broadcast_to(np.asarray(value, float), (n,)).copy()

    _kernels.rolling_cases(np.ascontiguousarray(initial, float), np.ascontiguousarray(mobility, float),
                           np.ascontiguousarray(coupling, float), np.ascontiguousarray(rotation, float),
                           np.ascontiguousarray(rolling, float), column(friction), column(restitution), column(arm),
                           int(steps), SWEEPS, impulse, moment, flags)
    return impulse, moment, flags


def rolling_impulses_numpy(initial, mobility, coupling, rotation, rolling, friction, restitution, arm,
                           steps: int = ROLLING_STEPS):
    """Rigid impact with Coulomb friction, a rolling-resistance couple and Stronge's energetic restitution.

    Integrates over the normal impulse P in ``steps`` equal steps of (1 + e) V_n / W_nn (more if the contact
    lasts longer; at most 4x). Each step's tangential impulse dJ_t and couple dC minimise the kinetic energy
    after the step inside their cones, |dJ_t| <= mu dP and |dC| <= d dP (maximal dissipation: where the slip or
    the rolling can stop within the step they stop, else they slide against it), found by a projected block
    Gauss-Seidel over the two blocks; the normal impulse grows until the normal force's work in restitution
    is e^2 times (minus) its work in compression. With d = 0 the couple vanishes and this is the 3-D Coulomb
    impact of :func:`impactlab.physics.rigid.stronge_impulses` (to the step's error).

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
        mu, the energetic e and the offset d [m] (the couple's limit per unit normal impulse).
    steps : int
        Nominal steps over the normal impulse.

    Returns
    -------
    impulse : ndarray (n, 3)
        Impulse on the ball in (s, l, n) [N s].
    moment : ndarray (n, 2)
        Angular impulse of the couple on the ball along (s, l) [N m s].
    flags : ndarray (n,) of int
        Bit 1: the step limit came before the impact ended.
    """
    n = initial.shape[0]
    mu = np.broadcast_to(np.asarray(friction, float), (n,))
    e = np.broadcast_to(np.asarray(restitution, float), (n,))
    d = np.broadcast_to(np.asarray(arm, float), (n,))
    w_tt, w_tn = mobility[:, :2, :2], mobility[:, :2, 2]
    w_nn = mobility[:, 2, 2]
    b_t, b_n = coupling[:, :2, :], coupling[:, 2, :]
    dp = (1.0 + e) * (-initial[:, 2]) / w_nn / steps
    inverse_tt = np.linalg.inv(w_tt)
    inverse_rr = np.linalg.inv(rotation)
    velocity = initial.copy()
    omega = rolling.copy()
    impulse = np.zeros((n, 3))
    moment = np.zeros((n, 2))
    compression = np.zeros(n)   # work of the normal force while approaching (<= 0)
    restoring = np.zeros(n)     # and while separating (>= 0)
    active = np.ones(n, dtype=bool)
    separating = np.zeros(n, dtype=bool)
    # each step's sweeps start from the previous step's split (the minimum is unique; the kernel does the same)
    jt = np.zeros((n, 2))
    couple = np.zeros((n, 2))
    for _ in range(4 * steps):
        if not np.any(active):
            break
        step = np.where(active, dp, 0.0)
        # the normal increment's own effect, then the tangential impulse and couple that minimise the energy
        base_t = velocity[:, :2] + w_tn * step[:, None]
        base_r = omega + b_n * step[:, None]
        for _sweep in range(SWEEPS):
            wanted_t = -np.einsum("nij,nj->ni", inverse_tt, base_t + np.einsum("nij,nj->ni", b_t, couple))
            jt = _project(wanted_t, mu * step)
            wanted_r = -np.einsum("nij,nj->ni", inverse_rr, base_r + np.einsum("nji,nj->ni", b_t, jt))
            couple = _project(wanted_r, d * step)
        increment = np.concatenate([jt, step[:, None]], -1)
        old_normal = velocity[:, 2]
        new_normal = old_normal + np.einsum("nj,nj->n", mobility[:, 2, :], increment) + np.einsum(
            "nj,nj->n", coupling[:, 2, :], couple)
        # a separating case whose restitution ends inside this step takes the fraction f of it that ends it
        # (the normal velocity is linear over the step): v0 f + (v1 - v0) f^2 / 2 = remaining work / dP
        remaining = -(e**2) * compression - restoring
        full = 0.5 * (old_normal + new_normal) * step
        ending = active & separating & (full >= remaining)
        fraction = np.ones(n)
        if np.any(ending):
            v0, dv = old_normal[ending], (new_normal - old_normal)[ending]
            target = np.maximum(remaining[ending], 0.0) / step[ending]
            with np.errstate(divide="ignore", invalid="ignore"):
                root = np.where(np.abs(dv) > 1e-300, (-v0 + np.sqrt(np.maximum(v0**2 + 2.0 * dv * target, 0.0)))
                                / dv, target / np.where(v0 > 0.0, v0, 1.0))
            fraction[ending] = np.clip(np.where(np.isfinite(root), root, 1.0), 0.0, 1.0)
        increment *= fraction[:, None]
        couple = couple * fraction[:, None]
        velocity = velocity + np.einsum("nij,nj->ni", mobility, increment) + np.einsum("nij,nj->ni", coupling, couple)
        omega = omega + np.einsum("nji,nj->ni", coupling, increment) + np.einsum("nij,nj->ni", rotation, couple)
        impulse += increment
        moment += couple
        work = 0.5 * (old_normal + velocity[:, 2]) * increment[:, 2]
        compression += np.where(active & ~separating, work, 0.0)
        restoring += np.where(active & separating, work, 0.0)
        separating |= active & (velocity[:, 2] >= 0.0)
        active &= ~ending
    return impulse, moment, active.astype(np.int64)


def layered_kappa(kappa, tangential_modulus, ball_shear_modulus, contact_radius, thickness, cover_shear_modulus):
    """Tangential-to-normal stiffness ratio of a ball with a thin cover of its own shear modulus over its core [1].

    The ball's equivalent material (its E and nu) sets the Hertz and Mindlin stiffnesses k_n = 2 a E* and
    k_t = 2 a G* (:mod:`.hertz`). A cover of thickness t << a and shear modulus G_c replaces a layer t of that
    material under the contact; in shear the layer is a spring of stiffness G pi a^2 / t in series, so

        1 / k_t,eff = 1 / (2 a G*) + (t / (pi a^2)) (1 / G_c - 1 / G_b),

    (G_b the ball's shear modulus: a cover of the ball's own modulus changes nothing). Its normal counterpart uses
    the confined modulus E (1 - nu) / ((1 + nu)(1 - 2 nu)), 3.8 E at nu = 0.45, and is 40-80 times smaller for
    covers within 4x of the ball's modulus, so the normal (Hertz) law is kept. The cover therefore enters MBF's
    problem through kappa_eff = k_t,eff / k_n (evaluated at the Hertz impulse-weighted mean contact radius).

    Parameters
    ----------
    kappa : array_like
        G*/E* of the ball's equivalent material against the face [1].
    tangential_modulus : array_like
        G* [Pa] (:func:`impactlab.physics.hertz.tangential_modulus`).
    ball_shear_modulus : array_like
        G_b = E_b / (2 (1 + nu_b)) [Pa].
    contact_radius : array_like
        a [m].
    thickness : array_like
        Cover thickness t [m] (0: no cover).
    cover_shear_modulus : array_like
        G_c [Pa].

    Returns
    -------
    ndarray
        kappa_eff [1], positive (a cover stiffer than the core cannot remove more than the layer it replaces: the
        series compliance is floored at 5 % of Mindlin's).

    References
    ----------
    K. L. Johnson, *Contact Mechanics* (1985), sections 5.8 (layered solids; the thin-layer limit) and 7.2
    (Mindlin's tangential stiffness).
    """
    a = np.asarray(contact_radius, float)
    base = 1.0 / (2.0 * a * np.asarray(tangential_modulus, float))
    layer = np.asarray(thickness, float) / (np.pi * a**2) * (1.0 / np.asarray(cover_shear_modulus, float)
                                                            - 1.0 / np.asarray(ball_shear_modulus, float))
    return np.asarray(kappa, float) * base / np.maximum(base + layer, 0.05 * base)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["SPHERE_FACTOR", "ROLLING_STEPS", "SWEEPS", "hysteresis_fraction", "rolling_arm", "mean_radius_ratio",
           "mean_rolling_arm", "rolling_impulses", "rolling_impulses_numpy", "layered_kappa"]
