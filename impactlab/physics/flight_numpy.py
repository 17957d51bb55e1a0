"""The numpy integrator of :func:`impactlab.physics.flight.fly`: classical RK4 at a fixed step on all shots at once,
the landing on the cubic Hermite interpolant refined by partial RK4 steps, the apex on the Hermite interpolant of vz.

It was the flight's only integrator before the compiled kernel (:mod:`impactlab.physics.kernels.flight`); it flies a
model given as a Python function and every model where numba is off (``IMPACTLAB_KERNELS=numpy``), and
tests/test_flight_kernel.py checks the two against each other on the docs' shots and the tour tables' launches.
State (7, n): x y z vx vy vz omega, internal frame (y LEFT); ``p`` the shots' air as
:func:`impactlab.physics.flight._launch` gives it, with ``coef`` the coefficient function.
"""

from __future__ import annotations

import numpy as np

__all__ = ["integrate_numpy"]


def _derivs(state, p):
    """Time derivative of the state, shape (7, N): x y z vx vy vz omega (y LEFT)."""
    vx, vy, vz, omega = state[3], state[4], state[5], state[6]
    wind, axis = p["wind"], p["axis"]
    rx, ry, rz = vx - wind[0], vy - wind[1], vz - wind[2]
    speed = np.sqrt(rx * rx + ry * ry + rz * rz)
    speed = np.maximum(speed, 1e-9)
    inv = 1.0 / speed
    # omega_hat x v_hat; its norm is sin(angle between axis and relative
    # velocity): only the perpendicular spin component makes lift.
    ax, ay, az = axis[0], axis[1], axis[2]
    cx = (ay * rz - az * ry) * inv
    cy = (az * rx - ax * rz) * inv
    cz = (ax * ry - ay * rx) * inv
    sin_ax = np.sqrt(cx * cx + cy * cy + cz * cz)
    rad = p["radius"]
    s = rad * omega * sin_ax * inv
    re = p["re_per_speed"] * speed
    cd, cl = p["coef"](s, re)
    k = p["k"]  # rho A / (2 m)
    fd = k * cd * speed
    fl = k * cl * speed * speed / np.maximum(sin_ax, 1e-12)
    out = np.empty_like(state)
    out[0] = vx
    out[1] = vy
    out[2] = vz
    out[3] = -fd * rx + fl * cx
    out[4] = -fd * ry + fl * cy
    out[5] = -fd * rz + fl * cz - p["g"]
    out[6] = -p["lam"] * speed * omega / rad
    return out


def _rk4(state, dt, p, k1=None):
    if k1 is None:
        k1 = _derivs(state, p)
    k2 = _derivs(state + 0.5 * dt * k1, p)
    k3 = _derivs(state + 0.5 * dt * k2, p)
    k4 = _derivs(state + dt * k3, p)
    return state + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)


def _subset(p, idx):
    q = dict(p)
    for key in ("wind", "axis"):
        q[key] = p[key][:, idx]
    for key in ("re_per_speed", "radius", "k", "lam"):
        q[key] = p[key][idx]
    return q


def _hermite_root(z0, z1, dz0, dz1, h):
    """Fraction s in [0, 1] where the cubic Hermite through (z0,dz0),(z1,dz1) is 0."""
    s = z0 / np.where(z0 - z1 == 0, 1e-300, z0 - z1)  # linear guess
    s = np.clip(s, 0.0, 1.0)
    for _ in range(6):  # Newton on the cubic
        h00 = 2 * s**3 - 3 * s**2 + 1
        h10 = s**3 - 2 * s**2 + s
        h01 = -2 * s**3 + 3 * s**2
        h11 = s**3 - s**2
        f = h00 * z0 + h10 * h * dz0 + h01 * z1 + h11 * h * dz1
        d00 = 6 * s**2 - 6 * s
        d10 = 3 * s**2 - 4 * s + 1
        d01 = -6 * s**2 + 6 * s
        d11 = 3 * s**2 - 2 * s
        df = d00 * z0 + d10 * h * dz0 + d01 * z1 + d11 * h * dz1
        s = np.clip(s - f / np.where(df == 0, -1e-300, df), 0.0, 1.0)
    return s


def integrate_numpy(state, p, dt, t_max, return_trajectories):
    """Fly every shot with the numpy RK4 integrator (fixed step ``dt``, all shots at once): results and paths as
    :func:`impactlab.physics.flight._integrate_kernel`'s, paths trimmed to the step the last shot landed in."""
    n = state.shape[1]
    results = np.full((n, 9), np.nan)
    results[:, 8] = np.where(state[5] <= 0, 0.0, np.nan)  # launched flat/down: apex at tee
    # launched below the horizontal from the ground: it meets the ground at once (carry 0, its landing the launch),
    # as the kernel says, where a fixed step of 0.02 s let lift turn a shot launched at -0.1 deg up first
    down = state[5] < 0.0
    results[down, :7] = state[:, down].T
    results[down, 7] = 0.0
    active = np.flatnonzero(~down)
    s0 = state[:, active]
    p = _subset(p, active)
    t = 0.0
    n_steps = int(np.ceil(t_max / dt))
    traj = np.full((n, 6, n_steps + 1), np.nan) if return_trajectories else np.full((n, 6, 1), np.nan)
    traj[:, :, 0] = state[0:6].T
    last_step = 0
    for step in range(n_steps):
        if active.size == 0:
            break
        last_step = step
        k1 = _derivs(s0, p)
        s1 = _rk4(s0, dt, p, k1)
        t += dt
        _numpy_apex(s0, s1, k1, p, dt, active, results)
        down = (s1[2] <= 0.0) & (s1[5] < 0.0)
        if np.any(down):
            idx = np.nonzero(down)[0]
            landing, tau = _numpy_landing(s0[:, idx], s1[:, idx], _subset(p, idx), dt)
            results[active[idx], :7] = landing.T
            results[active[idx], 7] = t - dt + tau
            s1[:, idx] = landing
        if return_trajectories:
            traj[active, :, step + 1] = s1[0:6].T
        if np.any(down):
            keep = ~down
            active = active[keep]
            s0 = s1[:, keep]
            p = _subset(p, keep)  # boolean mask works as an index too
        else:
            s0 = s1
    # Shots that land while still rising (not physical for golf, but possible for wind-blown lobs) would have no
    # apex; use the launch height (0).
    results[:, 8] = np.where(np.isnan(results[:, 8]), 0.0, results[:, 8])
    results[np.isnan(results[:, 7]), 8] = np.nan
    traj = traj[:, :, : last_step + 2] if return_trajectories else traj
    landed = ~np.isnan(results[:, 7])
    for c in range(6):  # freeze landed shots at their landing point
        comp = traj[:, c]
        bad = np.isnan(comp) & landed[:, None]
        fill = np.zeros((len(landed), 1)) if c == 2 else results[:, c, None]  # z: on the ground
        comp[bad] = np.broadcast_to(fill, comp.shape)[bad]
    return results, traj


def _numpy_apex(s0, s1, k1, p, dt, active, results):
    """The apex of the shots whose vz changes sign in this step: z on the Hermite interpolant at the root of vz."""
    up = (s0[5] > 0) & (s1[5] <= 0)
    if not np.any(up):
        return
    iu = np.nonzero(up)[0]
    d1 = _derivs(s1[:, iu], _subset(p, iu))
    z0, z1 = s0[2, iu], s1[2, iu]
    vz0, vz1 = s0[5, iu], s1[5, iu]
    # root of vz on its Hermite interpolant, then z there.
    sf = _hermite_root(vz0, vz1, k1[5, iu], d1[5], dt)
    h00 = 2 * sf**3 - 3 * sf**2 + 1
    h10 = sf**3 - 2 * sf**2 + sf
    h01 = -2 * sf**3 + 3 * sf**2
    h11 = sf**3 - sf**2
    zap = h00 * z0 + h10 * dt * vz0 + h01 * z1 + h11 * dt * vz1
    results[active[iu], 8] = np.maximum(zap, np.maximum(z0, z1))


def _numpy_landing(sd, s1, p, dt):
    """The landing state (7, m) and its time inside the step (m,) of the shots whose z crosses 0 going down: the
    root on the cubic Hermite interpolant, refined by Newton on partial RK4 steps."""
    sf = _hermite_root(sd[2], s1[2], sd[5], s1[5], dt)
    tau = sf * dt
    sl = _rk4(sd, tau, p)
    for _ in range(2):  # Newton refine on the exact RK4 sub-step
        tau = tau - sl[2] / np.where(sl[5] == 0, -1e-12, sl[5])
        tau = np.clip(tau, 0.0, dt)
        sl = _rk4(sd, tau, p)
    # a flight shorter than one step starts this step on the tee, rising: the root found at tau = 0 is the
    # launch, not the landing (it gave carry 0 and the launch's velocity as the landing's). The landing is
    # the interpolant's other root; bisection on the RK4 sub-step finds it (z > 0 just after launch, <= 0
    # at the step's end).
    early = (tau <= 1e-12 * dt) & (sd[5] > 0.0)
    if np.any(early):
        ie = np.nonzero(early)[0]
        pe, se = _subset(p, ie), sd[:, ie]
        lo, hi = np.zeros(ie.size), np.full(ie.size, dt)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            above = _rk4(se, mid, pe)[2] > 0.0
            lo, hi = np.where(above, mid, lo), np.where(above, hi, mid)
        tau[ie] = hi
        sl[:, ie] = _rk4(se, hi, pe)
    return sl, tau
