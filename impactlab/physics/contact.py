"""The 3-D contact of a ball and a club head: contact frame, approach velocity and mobility (Delassus) matrix.

Every model solves the impact at the contact point: the relative velocity of
the ball's and the head's material points there, v = v_ball - v_head, changes
with the impulse J on the ball (the head takes -J) as

    dv = W dJ,    W = W_ball + W_head,

with the mobility (inverse-inertia, Delassus) matrix of each body at the
contact point (Stronge, *Impact Mechanics*, ch. 5; Cross & Nathan 2009 for the
off-centre effective mass):

    W_ball = (1/m) [1 + (1/K^2) (1 - n n^T)]          (a sphere, lever -R n)
    W_head = (1/M) 1 + [r]^T I_G^-1 [r]               (r: from the head's centre of mass to the contact)

A fixed face has W_head = 0; a point-mass club (no inertia given) has
W_head = 1/M. W is symmetric positive definite. Off the centre-of-mass line it
couples the normal and tangential directions, and a tangential impulse turns
the slip direction: this is the gear effect.

Frames. Computations use a right-handed ground frame for a right-handed
golfer: X towards the target, Y to the left, Z up (the toe points to -Y). A
left-handed golfer's impact is the mirror image (Y -> -Y) of the same numbers,
so it is computed as a right-handed one and its lateral outputs are mirrored
(:func:`ground_outputs`). The contact frame is (s, l, n): n the outward face
normal at the strike point (bulge and roll tilt it), s along the incoming slip
of the contact point (the club velocity's tangential part, reversed), and
l = n x s. The contact frame is fixed at first contact: the head turns by a
fraction of a degree during contact (output ``face_rotation``; docs/clubs.md
measures what following it would change).

A plate experiment (impact speed and angle, no delivery) is the delivery with
zero path, face angle and attack angle and a dynamic loft equal to the impact
angle; its contact frame is the face frame of :mod:`.mechanics`.
"""

from __future__ import annotations

import numpy as np

from impactlab.physics.delivery import centre_face

#: inputs of the club head's rigid body (SI); without them the club is a point mass (or fixed if M = inf)
INERTIA_INPUTS = tuple(f"club_inertia_{name}" for name in ("toe", "up", "target", "toe_up", "toe_target",
                                                              "up_target"))
CENTER_INPUTS = ("club_cg_toe", "club_cg_high", "club_cg_depth")
FACE_SHAPE_INPUTS = ("club_loft", "face_bulge_radius", "face_roll_radius")
STRIKE_INPUTS = ("strike_toe", "strike_high")
#: the head's angular velocity at first contact about its toe, up and target axes [rad/s]
HEAD_ROTATION_INPUTS = ("head_rotation_toe", "head_rotation_up", "head_rotation_target")
#: the point of the head whose velocity the delivery's club speed, path and attack angle give, by its code in
#: the input ``club_reference`` (it matters only when the head turns: a head that does not turn moves as a point)
CLUB_REFERENCES = ("centre_of_mass", "face_centre", "contact")
#: every input of the 3-D geometry beyond the ball, speed, angle and spin (and the striking body's spin)
GEOMETRY_INPUTS = (INERTIA_INPUTS + CENTER_INPUTS + FACE_SHAPE_INPUTS + STRIKE_INPUTS + ("club_spin",)
                   + HEAD_ROTATION_INPUTS + ("club_reference", "loft_at_contact"))
#: every input :func:`contact_state` reads (a batch without one of them takes its default)
CONTACT_STATE_INPUTS = frozenset({"speed", "angle", "spin", "ball_mass", "ball_radius", "ball_inertia_factor",
                                  "club_mass", "dynamic_loft", "face_angle", "path", "attack_angle"}
                                 | set(GEOMETRY_INPUTS))
#: relative tolerance under which off-diagonal mobilities count as zero (the 1-D path applies)
DIAGONAL_TOLERANCE = 1e-12


def _cross(a, b):
    """a x b for (n, 3) arrays: numpy's formula written out (np.cross costs 4x as much at golf batch sizes)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    out[..., 0] = a[..., 1] * b[..., 2] - a[..., 2] * b[..., 1]
    out[..., 1] = a[..., 2] * b[..., 0] - a[..., 0] * b[..., 2]
    out[..., 2] = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
    return out


def _unit(vectors):
    norm = np.linalg.norm(vectors, axis=-1, keepdims=True)
    return vectors / np.where(norm > 0.0, norm, 1.0)


def _skew(r):
    """[r] with [r] x = r cross x, for (..., 3) arrays."""
    zero = np.zeros_like(r[..., 0])
    return np.stack([np.stack([zero, -r[..., 2], r[..., 1]], -1),
                     np.stack([r[..., 2], zero, -r[..., 0]], -1),
                     np.stack([-r[..., 1], r[..., 0], zero], -1)], -2)


def _rotation_z(angle):
    c, s = np.cos(angle), np.sin(angle)
    one, zero = np.ones_like(c), np.zeros_like(c)
    return np.stack([np.stack([c, -s, zero], -1), np.stack([s, c, zero], -1), np.stack([zero, zero, one], -1)], -2)


def face_axes(dynamic_loft, face_angle):
    """Toe, up-the-face and normal unit vectors of the face at impact, (n, 3) each (right-handed golfer).

    The face normal is (cos L cos f, -cos L sin f, sin L) for dynamic loft L and face angle f (open to the
    right); the toe is horizontal, to the right of the normal.
    """
    loft, face = np.asarray(dynamic_loft, float), np.asarray(face_angle, float)
    zero = np.zeros_like(loft)
    normal = np.stack([np.cos(loft), zero, np.sin(loft)], -1)
    up = np.stack([-np.sin(loft), zero, np.cos(loft)], -1)
    toe = np.stack([zero, -np.ones_like(loft), zero], -1)
    turn = _rotation_z(-face)
    return tuple(np.einsum("nij,nj->ni", turn, v) for v in (toe, up, normal))


def _head_axes(inputs, n, toe, up, normal):
    """The head's toe, up and target axes at impact (columns, (n, 3, 3)), or None for a point mass."""
    if not all(name in inputs for name in INERTIA_INPUTS):
        return None
    # head-frame axes at impact: toe stays the face's toe; up and target are the face's up and normal turned
    # back by the static loft (the face normal is the target axis tilted up by the loft)
    static = np.broadcast_to(np.asarray(inputs.get("club_loft", 0.0), float), (n,))[:, None]
    target = np.cos(static) * normal - np.sin(static) * up
    vertical = np.sin(static) * normal + np.cos(static) * up
    return np.stack([toe, vertical, target], -1)  # columns: head axes in ground coordinates


def _head_inverse_inertia(inputs, n, axes):
    """Inverse inertia tensor of the head in the ground frame at impact (n, 3, 3), from its axes at impact."""
    c = {name: np.broadcast_to(np.asarray(inputs[name], float), (n,)) for name in INERTIA_INPUTS}
    tensor = np.stack([
        np.stack([c["club_inertia_toe"], c["club_inertia_toe_up"], c["club_inertia_toe_target"]], -1),
        np.stack([c["club_inertia_toe_up"], c["club_inertia_up"], c["club_inertia_up_target"]], -1),
        np.stack([c["club_inertia_toe_target"], c["club_inertia_up_target"], c["club_inertia_target"]], -1),
    ], -2)
    return np.linalg.inv(np.einsum("nia,nab,njb->nij", axes, tensor, axes))


def approach_state(inputs: dict) -> dict:
    """The contact frame and the approach velocities of each case, without the mobility (SI arrays).

    The part of :func:`contact_state` that a ball's restitution law needs (``normal_speed``), without the
    (n, 3, 3) mobility and head inertia that make up most of its cost; the same arithmetic, so the same bits.
    Returns ``normal_speed``, ``slip_speed``, ``initial_velocity``, ``frame`` and the directions of
    :func:`contact_state`.
    """
    return contact_state(inputs, mobility=False)


def contact_state(inputs: dict, mobility: bool = True) -> dict:
    """Contact frame, approach velocity and mobility of each case, from model inputs (SI arrays).

    Returns
    -------
    dict of arrays (n cases)
        ``slip_direction``, ``lateral_direction``, ``normal`` (n, 3): the contact frame in ground
        coordinates (right-handed golfer); ``club_direction`` (n, 3); ``normal_speed`` V_n > 0 and
        ``slip_speed`` V_s (signed, as the 1-D models count it: positive along the club's slip direction)
        [m/s]; ``mobility`` (n, 3, 3) [1/kg] in the contact frame (s, l, n); ``contact_radius`` R_e [m],
        the Hertz radius of ball and face curvature; ``lever`` (n, 3) from the head's centre of mass to the
        contact [m]; ``head_inverse_inertia`` (n, 3, 3) or None; ``ball_spin`` (n, 3) [rad/s] before impact;
        ``initial_velocity`` (n, 3) [m/s], the relative contact velocity in the contact frame;
        ``one_dimensional`` (n,) bool: mobility diagonal in the contact frame, so the slip stays on one
        line and the normal problem is uncoupled (the 1-D solvers apply); ``club_velocity`` (n, 3), the
        head's centre-of-mass velocity before impact, and ``contact_velocity`` (n, 3), that of its material
        point at the contact [m/s]; ``head_spin`` (n, 3), its angular velocity before impact [rad/s].

    Notes
    -----
    Inputs of a launch monitor's delivery (:class:`impactlab.scene.core.Delivery` supplies them):
    ``loft_at_contact`` 1 counts ``dynamic_loft`` and ``face_angle`` at the strike point (the head is turned
    by :func:`impactlab.physics.delivery.centre_face`), 0 or absent at the face centre;
    ``head_rotation_toe``, ``_up``, ``_target`` [rad/s] turn the head about its axes at impact (absent: 0);
    ``club_reference`` (0 centre of mass, absent; 1 face centre; 2 contact point) is the point whose
    velocity ``speed`` along the path and attack angle give, every other point moving by w x r from it.

    With ``mobility=False`` only the frame and the approach velocities (:func:`approach_state`).
    """
    speed = np.atleast_1d(np.asarray(inputs["speed"], float))
    n = speed.size
    value = _input_values(inputs, n)
    bulge, roll = value("face_bulge_radius", np.inf), value("face_roll_radius", np.inf)
    strike_toe, strike_high = value("strike_toe", 0.0), value("strike_high", 0.0)
    loft, face, path, attack = _face_and_path(inputs, value, n, strike_toe, strike_high, bulge, roll)
    toe, up, flat_normal = face_axes(loft, face)
    club_direction = np.stack([np.cos(attack) * np.cos(path), -np.cos(attack) * np.sin(path), np.sin(attack)], -1)

    ball_mass, radius = value("ball_mass", np.nan), value("ball_radius", np.nan)
    k2 = value("ball_inertia_factor", 0.4)
    # the face as the osculating paraboloid of its bulge and roll (exact to O(s^4/R^3) at offsets s)
    tilt_toe, tilt_high = strike_toe / bulge, strike_high / roll
    normal = _unit(flat_normal + tilt_toe[:, None] * toe + tilt_high[:, None] * up)
    sag = 0.5 * (strike_toe * tilt_toe + strike_high * tilt_high)
    point = strike_toe[:, None] * toe + strike_high[:, None] * up - sag[:, None] * flat_normal

    axes = _head_axes(inputs, n, toe, up, flat_normal)
    lever, club_velocity, rotation, contact_velocity = _head_motion(inputs, value, n, axes, (toe, up, flat_normal),
                                                                    point, speed, club_direction)
    turning = np.any(rotation != 0.0, axis=-1)
    slip_direction, lateral_direction, frame = _slip_frame(turning, contact_velocity, speed, club_direction, normal,
                                                           up)

    spin = value("spin", 0.0)
    ball_spin = spin[:, None] * lateral_direction  # backspin counted as in the 1-D models: about n x s
    ball_point_velocity = -radius[:, None] * _cross(ball_spin, normal)

    # the striking body's own spin (a sphere striker), about the same axis n x s as the ball's; it moves the
    # head's contact point by w x lever (nothing for a point mass or a fixed face, which have no lever)
    head_spin = value("club_spin", 0.0)[:, None] * lateral_direction + rotation
    head_point_velocity = _cross(head_spin, lever)
    initial = np.einsum("nia,ni->na", frame, ball_point_velocity - club_velocity - head_point_velocity)
    if not mobility:
        return {"slip_direction": slip_direction, "lateral_direction": lateral_direction, "normal": normal,
                "flat_normal": flat_normal, "club_direction": club_direction, "normal_speed": -initial[:, 2],
                "slip_speed": initial[:, 0], "initial_velocity": initial, "frame": frame}

    matrix, inverse_inertia = _contact_mobility(inputs, value, n, axes, normal, k2, ball_mass, lever, frame)
    off = np.abs(matrix[:, [0, 0, 1], [1, 2, 2]]).max(axis=1)
    one_dimensional = off <= DIAGONAL_TOLERANCE * matrix[:, 2, 2]

    # Hertz radius of the ball on the curved face: the geometric mean of the principal relative radii
    # (Johnson, Contact Mechanics, 1985, section 4.2: good to a few per cent of the contact radius for the
    # mild ellipticity of a bulged face)
    contact_radius = np.sqrt(1.0 / ((1.0 / radius + 1.0 / bulge) * (1.0 / radius + 1.0 / roll)))
    return {
        "slip_direction": slip_direction, "lateral_direction": lateral_direction, "normal": normal,
        "flat_normal": flat_normal, "club_direction": club_direction, "normal_speed": -initial[:, 2],
        "slip_speed": initial[:, 0], "initial_velocity": initial, "mobility": matrix,
        "contact_radius": contact_radius, "lever": lever, "head_inverse_inertia": inverse_inertia,
        "ball_spin": ball_spin, "head_spin": head_spin, "one_dimensional": one_dimensional, "frame": frame,
        "club_velocity": club_velocity, "contact_velocity": contact_velocity,
    }


def _input_values(inputs: dict, n: int):
    """``value(name, default)``: an input as n floats (its default where absent)."""
    def value(name, default):
        return np.broadcast_to(np.asarray(inputs.get(name, default), float), (n,))
    return value


def _face_and_path(inputs: dict, value, n: int, strike_toe, strike_high, bulge, roll) -> tuple:
    """Loft and face angle of the face centre, path and attack angle [rad] of each case."""
    if "dynamic_loft" in inputs:
        loft, face = value("dynamic_loft", 0.0), value("face_angle", 0.0)
        path, attack = value("path", 0.0), value("attack_angle", 0.0)
        at_contact = value("loft_at_contact", 0.0) > 0.5
        if np.any(at_contact):  # the loft and face angle of the face at the strike point: turn the head to them
            centre_loft, centre_angle = centre_face(loft, face, strike_toe, strike_high, bulge, roll)
            loft, face = np.where(at_contact, centre_loft, loft), np.where(at_contact, centre_angle, face)
    else:  # a plate experiment: the club moves along X, the face normal is tilted up by the impact angle
        loft, face = value("angle", 0.0), np.zeros(n)
        path, attack = np.zeros(n), np.zeros(n)
    return loft, face, path, attack


def _head_motion(inputs: dict, value, n: int, axes, face_frame: tuple, point, speed, club_direction) -> tuple:
    """The head's lever to the contact, its centre of mass's velocity, its angular velocity (n, 3 each) and the
    velocity of its material point at the contact, before impact."""
    toe, up, flat_normal = face_frame
    if axes is not None:
        center = (value("club_cg_toe", 0.0)[:, None] * toe + value("club_cg_high", 0.0)[:, None] * up
                  - value("club_cg_depth", 0.0)[:, None] * flat_normal)
        lever = point - center
    else:
        center, lever = np.zeros((n, 3)), np.zeros((n, 3))
    # the head turning at first contact (about its toe, up and target axes): the delivery's velocity is that of
    # one point of the head (club_reference), every other point moves by w x (its offset from that one)
    club_velocity = speed[:, None] * club_direction
    rotation = np.zeros((n, 3))
    if axes is not None and any(name in inputs for name in HEAD_ROTATION_INPUTS):
        rotation = np.einsum("nia,na->ni", axes, np.stack([value(name, 0.0) for name in HEAD_ROTATION_INPUTS], -1))
    turning = np.any(rotation != 0.0, axis=-1)
    if np.any(turning):
        reference = value("club_reference", 0.0)
        reference_point = np.where((reference == 1.0)[:, None], 0.0, np.where((reference == 2.0)[:, None], point,
                                                                               center))
        club_velocity = club_velocity + _cross(rotation, center - reference_point)
    # the velocity of the head's material point at the contact, before impact (the striking sphere's own spin,
    # club_spin, enters below, counted about the slip frame it defines)
    contact_velocity = club_velocity + _cross(rotation, lever)
    return lever, club_velocity, rotation, contact_velocity


def _slip_frame(turning, contact_velocity, speed, club_direction, normal, up) -> tuple:
    """The contact frame: slip and lateral directions (n, 3) and the frame (n, 3, 3), columns s, l, n."""
    # slip direction: the ball's contact point moves against the club's tangential velocity there
    relative = np.where(turning[:, None], -contact_velocity / speed[:, None], -club_direction)
    tangential = relative - np.sum(relative * normal, -1, keepdims=True) * normal
    fallback = up - np.sum(up * normal, -1, keepdims=True) * normal  # head-on: any tangent will do
    has_slip = np.linalg.norm(tangential, axis=-1) > 1e-12
    slip_direction = _unit(np.where(has_slip[:, None], tangential, fallback))
    # counted up the face, as the 1-D models count x: a slip down the face is a negative slip speed
    slip_direction *= np.where(np.sum(slip_direction * up, -1) < 0.0, -1.0, 1.0)[:, None]
    lateral_direction = _cross(normal, slip_direction)
    frame = np.stack([slip_direction, lateral_direction, normal], -1)  # columns s, l, n
    return slip_direction, lateral_direction, frame


def _contact_mobility(inputs: dict, value, n: int, axes, normal, k2, ball_mass, lever, frame) -> tuple:
    """The mobility (n, 3, 3) [1/kg] of ball and head at the contact in the contact frame, symmetrised, and the
    head's inverse inertia (None for a point mass or a fixed face)."""
    eye = np.eye(3)
    ball_mobility = (eye + (eye - normal[:, :, None] * normal[:, None, :]) / k2[:, None, None]) \
        / ball_mass[:, None, None]
    club_mass = value("club_mass", np.inf)
    head_mobility = np.zeros((n, 3, 3)) + eye / club_mass[:, None, None]
    inverse_inertia = _head_inverse_inertia(inputs, n, axes) if axes is not None else None
    if inverse_inertia is not None:
        skew = _skew(lever)
        head_mobility = head_mobility + np.einsum("nji,njk,nkl->nil", skew, inverse_inertia, skew)
    matrix = np.einsum("nia,nij,njb->nab", frame, ball_mobility + head_mobility, frame)
    return 0.5 * (matrix + np.swapaxes(matrix, 1, 2)), inverse_inertia


def impulse_vector(state, normal_impulse, tangential_impulse, lateral_impulse=None):
    """The impulse on the ball in the contact frame (s, l, n) from the models' components [N s].

    ``tangential_impulse`` is counted positive against the incoming slip (as every model reports it),
    ``lateral_impulse`` along l = n x s.
    """
    jn = np.asarray(normal_impulse, float)
    lateral = np.zeros_like(jn) if lateral_impulse is None else np.asarray(lateral_impulse, float)
    return np.stack([-np.asarray(tangential_impulse, float), lateral, jn], -1)


#: what :func:`after_impact` can give; the groups below are computed only when one of their names is asked for
AFTER_IMPACT_OUTPUTS = frozenset({
    "ball_velocity", "ball_spin_vector", "club_velocity", "club_spin", "normal_velocity", "tangential_velocity",
    "spin_rate", "tangential_restitution", "launch_angle", "launch_ratio", "rebound_angle", "total_angle",
    "ball_speed", "energy_loss", "smash_factor", "club_speed_after", "club_angular_velocity"})
_NEEDS_HEAD = frozenset({"club_velocity", "club_spin", "normal_velocity", "tangential_velocity", "rebound_angle",
                         "total_angle", "club_speed_after", "club_angular_velocity"})
#: what needs the plane of the club's path and the contact normal (:func:`launch_plane`)
LAUNCH_PLANE_OUTPUTS = frozenset({"launch_angle", "launch_ratio", "total_angle"})


def launch_plane(state):
    """The plane of the club's path and the contact normal (``state``: :func:`contact_state`), where the launch and
    the face are measured: ``across`` (n, 3), its unit vector normal to the path on the side of a normal tilted up
    the face, and ``angle`` (n,), the normal's angle from the path, positive up the face (the 1-D models' sign)
    [rad]. A function of the state alone: the models of one batch share it (``CaseInputs.launch_plane``).
    """
    direction = state["club_direction"]
    towards_normal = state["normal"] - np.sum(state["normal"] * direction, -1, keepdims=True) * direction
    orientation = np.where(np.sum(towards_normal * state["slip_direction"], -1) < 0.0, -1.0, 1.0)
    across_unit = orientation[:, None] * _unit(towards_normal)
    angle = np.arctan2(np.sum(state["normal"] * across_unit, -1), np.sum(state["normal"] * direction, -1))
    return {"across": across_unit, "angle": angle}


def couple_mobility(state, ball_mass, ball_radius, ball_inertia_factor):
    """How a couple on the ball (the opposite on the head) moves the contact, and the relative rolling rate.

    A couple C in the tangent plane (components along s and l, the head taking -C) turns the ball by C / I_b and
    the head by -I_c^-1 C; the contact points then move relative to each other, and the relative angular velocity
    Omega = omega_ball - omega_head changes. With the contact impulse J this is one symmetric generalised
    mobility (Stronge 2000, ch. 5, extended by the couple's two coordinates):

        d(v, Omega_t) = [[W, B], [B^T, D]] d(J, C),
        B = -[r_b]x / I_b - [r_c]x I_c^-1,   D = 1 / I_b + I_c^-1   (tangent-plane components),

    r_b = -R n the ball's lever, r_c the head's (from its centre of mass). A point-mass club or a fixed face
    takes no rotation (I_c^-1 = 0).

    Parameters
    ----------
    state : dict
        :func:`contact_state`.
    ball_mass, ball_radius, ball_inertia_factor : array_like
        m [kg], R [m], K^2 [1].

    Returns
    -------
    coupling : ndarray (n, 3, 2)
        B in the contact frame: rows (s, l, n), columns the couple along (s, l) [1/(kg m)].
    rotation : ndarray (n, 2, 2)
        D on (s, l) [1/(kg m^2)].
    rolling : ndarray (n, 2)
        The relative angular velocity before impact along (s, l) [rad/s].
    """
    n = state["normal"].shape[0]
    m = np.broadcast_to(np.asarray(ball_mass, float), (n,))
    radius = np.broadcast_to(np.asarray(ball_radius, float), (n,))
    inverse_ball = 1.0 / (np.broadcast_to(np.asarray(ball_inertia_factor, float), (n,)) * m * radius**2)
    eye = np.eye(3)
    inverse_head = state["head_inverse_inertia"]
    if inverse_head is None:
        inverse_head = np.zeros((n, 3, 3))
    lever_ball = -radius[:, None] * state["normal"]
    ground = -_skew(lever_ball) * inverse_ball[:, None, None] - np.einsum("nij,njk->nik", _skew(state["lever"]),
                                                                        inverse_head)
    rotation_ground = inverse_ball[:, None, None] * eye + inverse_head
    frame = state["frame"]
    tangent = frame[:, :, :2]  # columns s, l
    coupling = np.einsum("nia,nij,njb->nab", frame, ground, tangent)
    rotation = np.einsum("nia,nij,njb->nab", tangent, rotation_ground, tangent)
    rotation = 0.5 * (rotation + np.swapaxes(rotation, 1, 2))
    relative = state["ball_spin"] - state["head_spin"]
    rolling = np.einsum("nia,ni->na", tangent, relative)
    return coupling, rotation, rolling


def after_impact(state, impulse, *, ball_mass, ball_radius, ball_inertia_factor, speed, club_mass=np.inf,
                 names=None, moment=None, plane=None, **_):
    """Ball and head after an impact with contact-frame impulse ``impulse`` (n, 3) on the ball (SI).

    Returns the ground-frame vectors (right-handed golfer) and the face-frame quantities of the 1-D problem,
    generalised to a contact normal, a free head and a slip that may turn: ``normal_velocity`` and
    ``tangential_velocity`` (ball centre relative to the head's material point at the contact, along the normal
    and the incoming slip) [m/s], ``spin_rate`` [rad/s] (positive: the backspin friction gives a ball sliding up
    a lofted face), ``tangential_restitution`` beta (minus the contact point's slip after over before, NaN
    without incoming slip), ``launch_angle`` [rad] and ``launch_ratio`` (NaN at a zero angle) in the plane of
    the path and the normal, ``rebound_angle`` [rad], ``total_angle`` (incidence plus rebound, the plate
    experiment's measure) [rad], ``ball_speed`` [m/s] (ground frame), ``smash_factor`` and ``energy_loss``
    [J] (kinetic energy of ball and head lost; Stronge, *Impact Mechanics* (2000), ch. 5). ``names`` (default: all of
    :data:`AFTER_IMPACT_OUTPUTS`) limits the work to what is asked: the head's motion, the launch plane and
    the contact's relative velocity are computed only where an asked-for quantity needs them (the dict may
    hold more than asked, never less). ``moment`` (n, 2), optional: the angular impulse of a couple on the ball
    along (s, l) [N m s] (a rolling-resistance law), the head taking the opposite; see :func:`couple_mobility`.
    ``plane``, optional: :func:`launch_plane` of ``state`` where the caller has it (the models of one batch share it).
    """
    names = AFTER_IMPACT_OUTPUTS if names is None else frozenset(names)
    n = impulse.shape[0]
    frame = state["frame"]
    impulse_ground = np.einsum("nij,nj->ni", frame, impulse)
    # a batch's own arrays as they are (np.broadcast_to's Python code is cold after a kernel), else broadcast
    m, radius, factor, speed = (value if type(value) is np.ndarray and value.shape == (n,) and value.dtype == float
                                else np.broadcast_to(np.asarray(value, float), (n,))
                                for value in (ball_mass, ball_radius, ball_inertia_factor, speed))
    inertia = factor * m * radius**2

    ball_velocity = impulse_ground / m[:, None]
    # dw = I^-1 (-R n) x J = (R/I) J x n; in the contact frame J x n = (J_l, -J_s, 0) (exactly 0 for a normal J)
    torque_arm = impulse[:, 1:2] * state["slip_direction"] - impulse[:, 0:1] * state["lateral_direction"]
    ball_spin = state["ball_spin"] + (radius / inertia)[:, None] * torque_arm
    has_moment = moment is not None and np.any(moment != 0.0)
    if has_moment:
        moment = np.asarray(moment, float)
        moment_ground = moment[:, 0:1] * state["slip_direction"] + moment[:, 1:2] * state["lateral_direction"]
        ball_spin = ball_spin + moment_ground / inertia[:, None]
    out = {"ball_velocity": ball_velocity, "ball_spin_vector": ball_spin}
    if "spin_rate" in names:
        spin_sense = np.sign(np.sum(ball_spin * state["lateral_direction"], -1))
        out["spin_rate"] = np.where(spin_sense == 0.0, 1.0, spin_sense) * np.linalg.norm(ball_spin, axis=-1)
    if names & {"ball_speed", "smash_factor"}:
        out["ball_speed"] = np.linalg.norm(impulse, axis=-1) / m
        out["smash_factor"] = out["ball_speed"] / speed
    if names & {"tangential_restitution", "energy_loss"}:
        relative_after = state["initial_velocity"] + np.einsum("nij,nj->ni", state["mobility"], impulse)
        if has_moment:
            coupling, rotation, rolling = couple_mobility(state, ball_mass, ball_radius, ball_inertia_factor)
            relative_after = relative_after + np.einsum("nij,nj->ni", coupling, moment)
        slip = state["slip_speed"]
        if "tangential_restitution" in names:
            with np.errstate(divide="ignore", invalid="ignore"):
                out["tangential_restitution"] = np.where(
                    slip != 0.0, -relative_after[:, 0] / np.where(slip != 0.0, slip, 1.0), np.nan)
        if "energy_loss" in names:  # the work of the impulse on the mean relative velocity, -(J . (v0 + v1)/2)
            out["energy_loss"] = -np.sum(
                impulse * (state["initial_velocity"] + 0.5 * (relative_after - state["initial_velocity"])), -1)
            if has_moment:  # and the couple's work on the mean relative rolling rate
                rolling_after = rolling + np.einsum("nji,nj->ni", coupling, impulse) + np.einsum(
                    "nij,nj->ni", rotation, moment)
                out["energy_loss"] -= np.sum(moment * 0.5 * (rolling + rolling_after), -1)
    if names & _NEEDS_HEAD:
        out.update(_head_after(state, impulse_ground, ball_velocity, club_mass, speed, n,
                               moment_ground if has_moment else None))
    if names & LAUNCH_PLANE_OUTPUTS:  # angles in the plane of the path and the contact normal (launch_plane)
        plane = launch_plane(state) if plane is None else plane
        direction, across_unit, angle = state["club_direction"], plane["across"], plane["angle"]
        launch_angle = np.arctan2(np.sum(ball_velocity * across_unit, -1), np.sum(ball_velocity * direction, -1))
        if "launch_ratio" in names:
            with np.errstate(divide="ignore", invalid="ignore"):
                out["launch_ratio"] = np.where(angle != 0.0, launch_angle / np.where(angle != 0.0, angle, 1.0),
                                               np.nan)
        out["launch_angle"] = launch_angle
        if "rebound_angle" in out:
            out["total_angle"] = angle + out["rebound_angle"]
    return out


def _head_after(state: dict, impulse_ground, ball_velocity, club_mass, speed, n: int, moment_ground) -> dict:
    """The head after the impact (its velocity, spin and speed) and the ball's centre relative to the head's
    material point at the contact (normal and tangential velocity, rebound angle); ``moment_ground`` the couple
    on the ball in ground axes, or None."""
    club = np.broadcast_to(np.asarray(club_mass, float), (n,))
    club_velocity = state["club_velocity"] - np.where(
        np.isinf(club), 0.0, 1.0 / club)[:, None] * impulse_ground
    if state["head_inverse_inertia"] is not None:
        club_spin = state["head_spin"] - np.einsum("nij,nj->ni", state["head_inverse_inertia"],
                                                   _cross(state["lever"], impulse_ground))
        if moment_ground is not None:
            club_spin = club_spin - np.einsum("nij,nj->ni", state["head_inverse_inertia"], moment_ground)
    else:
        club_spin = np.zeros((n, 3))
    # the ball centre relative to the head's material point at the contact
    head_point = club_velocity + _cross(club_spin, state["lever"])
    centre_relative = ball_velocity - head_point
    normal_velocity = np.sum(centre_relative * state["normal"], -1)
    tangential_velocity = np.sum(centre_relative * state["slip_direction"], -1)
    return {
        "club_velocity": club_velocity, "club_spin": club_spin,
        "normal_velocity": normal_velocity, "tangential_velocity": tangential_velocity,
        "rebound_angle": np.arctan2(tangential_velocity, normal_velocity),
        "club_speed_after": np.linalg.norm(club_velocity, axis=-1) if np.all(np.isfinite(club)) else np.where(
            np.isinf(club), speed, np.linalg.norm(club_velocity, axis=-1)),
        "club_angular_velocity": np.linalg.norm(club_spin, axis=-1),
    }


def ground_outputs(state, after, *, dynamic_loft=None, attack_angle=None, path=None, face_angle=None,
                   handedness=None, angle=None, **_):
    """Launch direction and spin in golf terms; lateral quantities mirrored for a left-handed golfer (rad, rad/s).

    ``horizontal_launch_angle`` and ``spin_axis`` are positive to the right of the target line (spin axis:
    a ball that curves right), whoever swings; ``back_spin`` and ``side_spin`` split the spin about the
    horizontal axis across the flight and the axis across the flight perpendicular to it (side spin positive
    curving right); spin along the flight direction (rifle spin) enters neither.
    """
    velocity, spin = after["ball_velocity"], after["ball_spin_vector"]
    n = velocity.shape[0]
    sign = np.sign(np.broadcast_to(np.asarray(1.0 if handedness is None else handedness, float), (n,)))
    horizontal_rh = np.arctan2(-velocity[:, 1], velocity[:, 0])
    vertical = np.arctan2(velocity[:, 2], np.hypot(velocity[:, 0], velocity[:, 1]))
    flight = _unit(velocity)
    back_axis = _unit(_cross(velocity * np.array([1.0, 1.0, 0.0]), np.array([0.0, 0.0, 1.0])))
    up_axis = _cross(back_axis, flight)  # perpendicular to the flight and the back-spin axis, upwards
    back_spin = np.sum(spin * back_axis, -1)
    side_spin_rh = -np.sum(spin * up_axis, -1)  # a spin vector tilted down on the right curves right
    horizontal, side_spin = sign * horizontal_rh, sign * side_spin_rh
    out = {
        "vertical_launch_angle": vertical,
        "horizontal_launch_angle": horizontal,
        "back_spin": back_spin,
        "side_spin": side_spin,
        "spin_axis": np.arctan2(side_spin, back_spin),
        "spin_loft": np.arccos(np.clip(np.sum(state["normal"] * state["club_direction"], -1), -1.0, 1.0)),
    }
    if dynamic_loft is not None:
        path_abs, face_abs = sign * np.asarray(path, float), sign * np.asarray(face_angle, float)
        with np.errstate(invalid="ignore", divide="ignore"):
            vertical_ratio = (vertical - attack_angle) / (dynamic_loft - attack_angle)
            horizontal_ratio = (horizontal - path_abs) / (face_abs - path_abs)
        out["vertical_launch_ratio"] = np.where(np.abs(dynamic_loft - attack_angle) > 1e-12, vertical_ratio, np.nan)
        out["horizontal_launch_ratio"] = np.where(np.abs(face_abs - path_abs) > 1e-12, horizontal_ratio, np.nan)
    return out


#: the names a plugin may use (docs/writing-a-model.md, "Public paths")
__all__ = ["INERTIA_INPUTS", "CENTER_INPUTS", "FACE_SHAPE_INPUTS", "STRIKE_INPUTS", "HEAD_ROTATION_INPUTS",
           "CLUB_REFERENCES", "GEOMETRY_INPUTS", "CONTACT_STATE_INPUTS", "DIAGONAL_TOLERANCE", "face_axes",
           "approach_state", "contact_state", "impulse_vector", "AFTER_IMPACT_OUTPUTS", "LAUNCH_PLANE_OUTPUTS",
           "launch_plane", "couple_mobility", "after_impact", "ground_outputs"]
