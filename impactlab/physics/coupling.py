"""The normal-tangential coupling every model here neglects: Dundurs' second constant and an estimate of its effect.

Every compliant model of impactlab solves the normal (Hertz) and tangential (Mindlin, DEM springs) problems
separately, which is exact only when the two bodies have the same second Dundurs constant, i.e. when

    beta_D = [(1 - 2 nu1)/G1 - (1 - 2 nu2)/G2] / (2 [(1 - nu1)/G1 + (1 - nu2)/G2])

vanishes (Dundurs, J. Appl. Mech. 36 (1969) 650; Johnson, Contact Mechanics, 1985, section 5.5, for what it does
to a Hertz contact with friction; Spence, J. Elasticity 5 (1975) 297 for the normal loading of dissimilar
spheres with finite friction). A compliant ball (nu 0.45) on a steel or rigid face has beta_D = +0.09.

What beta_D does (derived here, not taken from a coupled solution):

1. **The normal pressure slides the surfaces radially.** Under a Hertz pressure each surface moves towards the
   axis by u_r = -(1 - 2 nu)/(6 G) (a^2/r) [1 - (1 - r^2/a^2)^(3/2)] p0 (Johnson 1985, eq. 3.41a); the two
   surfaces differ at the contact edge by |du_r(a)| = (2 |beta_D| / (3 E*)) a p0 = (4 / (3 pi)) |beta_D| delta,
   using (1 - nu1)/G1 + (1 - nu2)/G2 = 2/E* and p0 = 2 E* a / (pi R). Friction resists that mismatch with a
   radial traction that uses part of the Coulomb limit mu p the tangential (x) problem needs.
2. **The scale it is measured against** is the tangential displacement at which Mindlin's contact reaches gross
   slip, delta_x = (3/2) mu P / k_t = mu delta / kappa (k_t = 8 G*_J a, kappa = 4 G*_J / E* as in
   impactlab.physics.hertz). Their ratio is the coupling parameter

       r_c = |du_r(a)| / delta_x = (4 / (3 pi)) |beta_D| kappa / mu

   (0.068 for the urethane ball on steel at mu = 0.4: the coupling asks for 7 % of the slip the friction allows).
3. **The first-order effect on the tangential impulse vanishes.** In half-space theory the contact sees the two
   bodies only through their composite gap and their materials; turning the whole configuration by 180 deg about
   the axis across the slip swaps the bodies (beta_D -> -beta_D) and leaves the relative slip, the relative
   approach, the mobility and the tangential force on the ball unchanged. So J_t is an even function of beta_D.
4. **Second order.** Where the contact slips, the traction is mu p along the slip, which now has a radial part
   of relative size up to r_c; its x-component falls by 1 - cos(theta) ~ theta^2 / 2 with theta <= r_c. Hence the
   estimate

       |dJ_t| ~ (r_c^2 / 2) mu J_n       (capped at mu J_n)

   2.3e-3 of mu J_n for the ball above at mu = 0.4 (4.2e-3 at mu = 0.3). It is an order-of-magnitude estimate
   (the pressure redistribution that the tangential traction causes through beta_D is of the same order and is
   not counted separately), not a bound: a coupled solution (e.g. in the annular method) would settle it and is
   not in impactlab.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike


def dundurs_beta(youngs_1: ArrayLike, poisson_1: ArrayLike, youngs_2: ArrayLike, poisson_2: ArrayLike) -> np.ndarray:
    """Dundurs' second constant beta_D of body 1 (the ball) against body 2 (the face).

    Parameters
    ----------
    youngs_1, poisson_1 : array_like
        Young's modulus [Pa] and Poisson's ratio [1] of body 1.
    youngs_2, poisson_2 : array_like
        The same of body 2; an infinite modulus is a rigid body (its terms drop).

    Returns
    -------
    ndarray
        beta_D [1], in [-1/2, 1/2]: positive when body 1 is the more compressible-shear-compliant one, 0 for
        identical materials or two incompressible ones. A rigid body 2 gives (1 - 2 nu1) / (2 (1 - nu1)).

    References
    ----------
    J. Dundurs, J. Appl. Mech. 36 (1969) 650-652; K. L. Johnson, Contact Mechanics (1985), section 5.5.
    """
    e1, n1, e2, n2 = (np.asarray(v, dtype=float) for v in (youngs_1, poisson_1, youngs_2, poisson_2))
    compliance_1 = 2.0 * (1.0 + n1) / e1  # 1/G
    with np.errstate(divide="ignore", invalid="ignore"):
        compliance_2 = np.where(np.isinf(e2), 0.0, 2.0 * (1.0 + n2) / e2)
    numerator = (1.0 - 2.0 * n1) * compliance_1 - (1.0 - 2.0 * n2) * compliance_2
    denominator = 2.0 * ((1.0 - n1) * compliance_1 + (1.0 - n2) * compliance_2)
    return numerator / denominator


def coupling_ratio(beta: ArrayLike, kappa: ArrayLike, friction: ArrayLike) -> np.ndarray:
    """r_c = (4 / (3 pi)) |beta_D| kappa / mu: the radial mismatch at the contact edge over the gross-slip
    tangential displacement [1] (module docstring, step 2); inf for mu = 0 and beta_D != 0."""
    beta, kappa, friction = (np.asarray(v, dtype=float) for v in (beta, kappa, friction))
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = 4.0 / (3.0 * math.pi) * np.abs(beta) * kappa / friction
    return np.where(np.abs(beta) == 0.0, 0.0, ratio)


def coupling_estimate(beta: ArrayLike, kappa: ArrayLike, friction: ArrayLike) -> np.ndarray:
    """Estimated change of the tangential impulse from the neglected coupling, relative to mu J_n [1].

    min(r_c^2 / 2, 1) (module docstring, step 4): 0 for identical materials; 2.3e-3 for a urethane ball
    (nu 0.45) on steel at mu = 0.4.
    """
    ratio = coupling_ratio(beta, kappa, friction)
    return np.minimum(0.5 * ratio**2, 1.0)


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["dundurs_beta", "coupling_ratio", "coupling_estimate"]
