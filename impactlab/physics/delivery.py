"""Golf delivery geometry in 3-D (the D-plane): from club path, face and loft to the impact plane and back.

Ground frame: ``x`` along the target line, ``y`` to the right of it (seen from
behind the golfer), ``z`` up. Delivery angles are given as a golfer describes
them, and outputs are absolute:

- ``path``: horizontal direction of the club-head velocity, positive in-to-out
  (to the right for a right-handed golfer, to the left for a left-handed one);
- ``attack_angle``: vertical direction of the club-head velocity, positive upwards;
- ``face_angle``: horizontal direction of the face normal, positive open
  (right for a right-handed golfer, left for a left-handed one);
- ``dynamic_loft``: elevation of the face normal above the horizontal;
- ``handedness``: +1 right-handed, -1 left-handed.

Outputs: ``horizontal_launch_angle`` and ``spin_axis`` are absolute, positive
to the right of the target line whoever swings (a left-handed golfer's open
face sends the ball left, negative). The impact happens in the plane spanned
by the face normal n and the club velocity v; the spin loft is the angle
between them, and the 2-D solution in that plane gives the ball's velocity and
a spin axis normal to the plane (the D-plane model, e.g. Jorgensen, *The
Physics of Golf*, 1999).
"""

from __future__ import annotations

import numpy as np


def _unit(horizontal, vertical, sign):
    """Unit vectors from a horizontal angle (right positive after ``sign``) and an elevation [rad]."""
    return np.stack([np.cos(vertical) * np.cos(horizontal), sign * np.cos(vertical) * np.sin(horizontal),
                     np.sin(vertical)], axis=-1)


def club_directions(path, face_angle, attack_angle, dynamic_loft, handedness=1.0):
    """Club velocity direction v and face normal n as (..., 3) arrays in the ground frame."""
    sign = np.sign(np.asarray(handedness, dtype=float))
    return _unit(path, attack_angle, sign), _unit(face_angle, dynamic_loft, sign)


def spin_loft(path, face_angle, attack_angle, dynamic_loft, handedness=1.0):
    """Angle between face normal and club velocity [rad]: the alpha of the 2-D impact."""
    velocity, normal = club_directions(path, face_angle, attack_angle, dynamic_loft, handedness)
    return np.arccos(np.clip(np.sum(velocity * normal, axis=-1), -1.0, 1.0))


def contact_face(dynamic_loft, face_angle, strike_toe, strike_high, bulge_radius, roll_radius):
    """Dynamic loft and face angle of the face at the strike point, from those at the face centre [rad].

    The face is the osculating paraboloid of its bulge and roll (:mod:`impactlab.physics.contact`): at a strike
    ``toe`` towards the toe and ``high`` up the face its outward normal is, in the face-centre axes (normal,
    toe, up), the unit vector along (1, a, b) with a = toe/R_bulge and b = high/R_roll. The face's heel-toe line
    at its centre is horizontal (the lie is not turned into the impact), so with the face-centre loft L_c and
    face angle f_c the contact normal has the elevation and the horizontal direction (open positive)

        sin L = (sin L_c + b cos L_c) / sqrt(1 + a^2 + b^2),
        f = f_c + atan2(a, cos L_c - b sin L_c).

    Parameters
    ----------
    dynamic_loft, face_angle : array_like
        Loft and face angle of the face at its centre [rad] (face angle counted open, towards the golfer's
        trail side, as :class:`impactlab.scene.core.Delivery` counts it).
    strike_toe, strike_high : array_like
        Strike point from the face centre towards the toe and up the face [m].
    bulge_radius, roll_radius : array_like
        Face radii heel to toe and sole to crown [m] (``inf``: flat).

    Returns
    -------
    (ndarray, ndarray)
        Dynamic loft and face angle of the face at the strike point [rad].

    See Also
    --------
    centre_face : the inverse.
    """
    loft = np.asarray(dynamic_loft, dtype=float)
    a = np.asarray(strike_toe, dtype=float) / np.asarray(bulge_radius, dtype=float)
    b = np.asarray(strike_high, dtype=float) / np.asarray(roll_radius, dtype=float)
    norm = np.sqrt(1.0 + a * a + b * b)
    contact_loft = np.arcsin(np.clip((np.sin(loft) + b * np.cos(loft)) / norm, -1.0, 1.0))
    return contact_loft, np.asarray(face_angle, dtype=float) + np.arctan2(a, np.cos(loft) - b * np.sin(loft))


def centre_face(dynamic_loft, face_angle, strike_toe, strike_high, bulge_radius, roll_radius):
    """Dynamic loft and face angle at the face centre whose face at the strike point has the given ones [rad].

    The inverse of :func:`contact_face`: a launch monitor reports the loft and face angle "at the center-point
    of contact between the club and ball" (TrackMan, Data Parameter Definitions,
    https://support.trackmangolf.com/hc/en-us/articles/5089892383515), the face-centre orientation is what
    turns the head. With b = high/R_roll, a = toe/R_bulge and N = sqrt(1 + a^2 + b^2):

        L_c = asin(N sin L / sqrt(1 + b^2)) - atan(b),
        f_c = f - atan2(a, cos L_c - b sin L_c).

    Parameters and units as :func:`contact_face`, with the contact-point loft and face angle given.
    """
    loft = np.asarray(dynamic_loft, dtype=float)
    a = np.asarray(strike_toe, dtype=float) / np.asarray(bulge_radius, dtype=float)
    b = np.asarray(strike_high, dtype=float) / np.asarray(roll_radius, dtype=float)
    norm = np.sqrt(1.0 + a * a + b * b)
    centre_loft = np.arcsin(np.clip(norm * np.sin(loft) / np.sqrt(1.0 + b * b), -1.0, 1.0)) - np.arctan(b)
    centre = np.asarray(face_angle, dtype=float) - np.arctan2(a, np.cos(centre_loft) - b * np.sin(centre_loft))
    return centre_loft, centre


def cg_projection(cg_toe, cg_high, cg_depth, bulge_radius, roll_radius, iterations: int = 4):
    """The point of the face whose normal passes through the head's centre of mass: its "CG projection" [m].

    Club designers call this point the CG projection (or the balance point): a strike there drives the normal
    impulse through the centre of mass, so the normal force turns the head neither about its toe axis (no vertical
    gear effect from it) nor about its up axis; a strike above it lowers the spin, below it raises it. On the face
    of :mod:`impactlab.physics.contact` (the osculating paraboloid of bulge R_b and roll R_r: the point
    (toe s_t, high s_h) lies a sag z = (s_t^2/R_b + s_h^2/R_r)/2 behind the face-centre plane, its normal is
    along (1, s_t/R_b, s_h/R_r) in the face-centre axes (normal, toe, up)), the normal through a point meets the
    centre of mass (toe c_t, high c_h, depth c_d behind the face centre) where

        s_t = c_t / (1 - (c_d - z)/R_b),    s_h = c_h / (1 - (c_d - z)/R_r),

    solved by fixed-point iteration on the sag z (z is of order s^2/R: two iterations reach round-off for a
    driver). A flat face (R = inf) projects the centre of mass straight along its normal: (c_t, c_h).

    Parameters
    ----------
    cg_toe, cg_high, cg_depth : array_like
        Centre of mass from the face centre towards the toe, up the face and behind it [m] (the face-centre axes of
        :class:`impactlab.scene.clubs.ClubHead`).
    bulge_radius, roll_radius : array_like
        Face radii heel to toe and sole to crown [m] (``inf``: flat); each larger than the depth.
    iterations : int
        Fixed-point iterations on the sag.

    Returns
    -------
    (ndarray, ndarray)
        The strike point towards the toe and up the face [m], in the coordinates of a study's ``strike:``.
    """
    c_t, c_h, c_d = (np.asarray(v, dtype=float) for v in (cg_toe, cg_high, cg_depth))
    bulge, roll = np.asarray(bulge_radius, dtype=float), np.asarray(roll_radius, dtype=float)
    s_t, s_h = c_t, c_h
    for _ in range(iterations):
        sag = 0.5 * (s_t * s_t / bulge + s_h * s_h / roll)
        s_t, s_h = c_t / (1.0 - (c_d - sag) / bulge), c_h / (1.0 - (c_d - sag) / roll)
    return s_t, s_h


def loft_for_spin_loft(spin_loft_angle, path, face_angle, attack_angle):
    """The dynamic loft whose face makes the 3-D spin loft ``spin_loft_angle`` with the club velocity [rad].

    With the club velocity v = (cos A cos p, cos A sin p, sin A) and the face normal
    n = (cos L cos f, cos L sin f, sin L) (attack A, path p, face f, loft L), cos S = v . n =
    c cos(L - phi) with c = sqrt((cos A cos(f - p))^2 + sin^2 A) and phi = atan2(sin A, cos A cos(f - p)); the
    loft above the club's direction is L = phi + acos(cos S / c). TrackMan defines spin loft as this 3-D angle
    ("the angle between the direction of the club head's movement and the club face's orientation at the time
    of maximum compression", Data Parameter Definitions), not dynamic loft minus attack angle.

    Returns
    -------
    ndarray
        The dynamic loft [rad]; NaN where no loft gives that spin loft (a spin loft below the horizontal angle
        between face and path, which it can never be smaller than).
    """
    s = np.asarray(spin_loft_angle, dtype=float)
    attack = np.asarray(attack_angle, dtype=float)
    horizontal = np.cos(attack) * np.cos(np.asarray(face_angle, dtype=float) - np.asarray(path, dtype=float))
    reach = np.hypot(horizontal, np.sin(attack))
    ratio = np.cos(s) / reach
    with np.errstate(invalid="ignore"):
        return np.where(ratio <= 1.0 + 1e-15, np.arctan2(np.sin(attack), horizontal)
                        + np.arccos(np.clip(ratio, -1.0, 1.0)), np.nan)


DELIVERY_INPUTS = ("path", "face_angle", "attack_angle", "dynamic_loft", "handedness")


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["club_directions", "spin_loft", "contact_face", "centre_face", "cg_projection", "loft_for_spin_loft",
           "DELIVERY_INPUTS"]
