"""Compiled annular-strip time loop with its small LU solver (:mod:`impactlab.physics.annuli`'s kernel)."""

from __future__ import annotations

import numpy as np

from ._numba import HAVE_NUMBA, compiled as _compiled


def _lu_factor(matrix, size, pivots):
    """In-place LU factorisation with partial pivoting of matrix[:size, :size]."""
    for k in range(size):
        best, row = abs(matrix[k, k]), k
        for i in range(k + 1, size):
            if abs(matrix[i, k]) > best:
                best, row = abs(matrix[i, k]), i
        pivots[k] = row
        if row != k:
            for j in range(size):
                matrix[k, j], matrix[row, j] = matrix[row, j], matrix[k, j]
        diagonal = matrix[k, k]
        for i in range(k + 1, size):
            factor = matrix[i, k] / diagonal
            matrix[i, k] = factor
            if factor != 0.0:
                for j in range(k + 1, size):
                    matrix[i, j] -= factor * matrix[k, j]


def _lu_solve(matrix, size, pivots, vector):
    for k in range(size):
        row = pivots[k]
        if row != k:
            vector[k], vector[row] = vector[row], vector[k]
    for i in range(size):
        for j in range(i):
            vector[i] -= matrix[i, j] * vector[j]
    for i in range(size - 1, -1, -1):
        for j in range(i + 1, size):
            vector[i] -= matrix[i, j] * vector[j]
        vector[i] /= matrix[i, i]


def _annuli_cases(chi, psi1, tau, inside, caps, displacement, load, gamma, gain_factor, max_iterations, record,
                  history, stick, h_nodes):
    """Annular-strip time loop per case, factorising the mixed system only when the stick/slip set changes.

    The system's rows depend on which annuli stick, slip or are out of contact, not on time, so one LU
    factorisation serves every step until an annulus enters, leaves, sticks or slips. Annuli outside the
    contact force their distributions to zero (the load matrix is upper triangular), so only the
    inside x inside block is solved. Returns (slip change, dissipation, failures).
    """
    cases = chi.size
    rings = gamma.size
    nodes = tau.size
    velocity_out = np.zeros(cases)
    dissipation_out = np.zeros(cases)
    failures = 0
    lu = np.zeros((rings, rings))
    pivots = np.zeros(rings, dtype=np.int64)
    rhs = np.zeros(rings)
    for case in range(cases):
        mode = np.zeros(rings, dtype=np.int64)  # 0 out, 1 stick, 2 slip
        direction = np.zeros(rings)
        offset = np.zeros(rings)
        strength = np.zeros(rings)
        u = np.zeros(rings)
        q = np.zeros(rings)
        position = 0.0
        velocity_change = 0.0
        acceleration = 0.0
        dissipation = 0.0
        previous_total = 0.0
        gain = gain_factor * chi[case]
        p1 = psi1[case]
        factored = -1  # size of the factorised block, -1: none valid
        for k in range(1, nodes):
            dt = tau[k] - tau[k - 1]
            half = velocity_change + 0.5 * dt * acceleration
            previous_position = position
            position = position + dt * (p1 + half)
            size = inside[k]
            for i in range(rings):
                if i < size and mode[i] == 0:  # entering: stuck where it already was
                    displaced = 0.0
                    for j in range(rings):
                        displaced += displacement[i, j] * strength[j]
                    offset[i] = previous_position - displaced
                    mode[i] = 1
                    factored = -1
                elif i >= size and mode[i] != 0:
                    mode[i] = 0
                    factored = -1
            if size != factored and factored != -1:
                factored = -1
            settled = False
            for _ in range(max_iterations):
                if factored == -1:
                    for i in range(size):
                        for j in range(size):
                            lu[i, j] = displacement[i, j] if mode[i] == 1 else load[i, j]
                    _lu_factor(lu, size, pivots)
                    factored = size
                for i in range(size):
                    rhs[i] = position - offset[i] if mode[i] == 1 else 2.0 * direction[i] * caps[k, i]
                _lu_solve(lu, size, pivots, rhs)
                for j in range(rings):
                    strength[j] = rhs[j] if j < size else 0.0
                changed = False
                for i in range(size):
                    # a stuck annulus's displacement and a slipping one's load are what was imposed:
                    # only the other quantity needs the sum (and the load matrix is upper triangular)
                    if mode[i] == 1:
                        load_i = 0.0
                        for j in range(i, size):
                            load_i += load[i, j] * strength[j]
                        q[i] = 0.5 * load_i
                        u[i] = position - offset[i]
                        if abs(q[i]) > caps[k, i] * (1 + 1e-10) + 1e-14:
                            mode[i] = 2
                            direction[i] = 1.0 if q[i] > 0 else -1.0
                            changed = True
                    else:
                        moved = 0.0
                        for j in range(size):
                            moved += displacement[i, j] * strength[j]
                        u[i] = moved
                        q[i] = direction[i] * caps[k, i]
                        if direction[i] * (position - u[i] - offset[i]) < -1e-12:
                            mode[i] = 1
                            changed = True
                if not changed:
                    settled = True
                    break
                factored = -1
            if not settled:
                failures += 1
            for i in range(size):
                if mode[i] == 2:
                    offset[i] = position - u[i]
            total = 0.0
            for j in range(size):
                total += strength[j] * gamma[j]
            dissipation += 0.5 * (previous_total + total) * (position - previous_position)
            previous_total = total
            acceleration = -gain * total
            velocity_change = half + 0.5 * dt * acceleration
            if record:
                history[case, k] = 1.5 * total
                first_slip = rings
                for i in range(size):
                    if mode[i] == 2:
                        first_slip = i
                        break
                root = np.sqrt(h_nodes[k]) if h_nodes[k] > 0.0 else 0.0
                stick[case, k] = root if first_slip >= size else first_slip / rings
        velocity_out[case] = velocity_change
        dissipation_out[case] = dissipation
    return velocity_out, dissipation_out, failures


if HAVE_NUMBA:
    # the helpers are looked up as globals when the kernel compiles: compile them first
    _lu_factor = _compiled(_lu_factor)
    _lu_solve = _compiled(_lu_solve)
annuli_cases = _compiled(_annuli_cases)
