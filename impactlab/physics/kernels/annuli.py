"""Compiled annular-strip time loop: a small LU solver and O(n^2) updates of the inverse (:mod:`.annuli`'s kernel)."""

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


def _fresh_inverse(displacement, load, mode, size, inverse, lu, pivots, rhs):
    """inverse[:size, :size] = the mixed system's inverse, from an LU factorisation with partial pivoting."""
    for i in range(size):
        source = displacement if mode[i] == 1 else load
        for j in range(size):
            lu[i, j] = source[i, j]
    _lu_factor(lu, size, pivots)
    for column in range(size):
        for i in range(size):
            rhs[i] = 1.0 if i == column else 0.0
        _lu_solve(lu, size, pivots, rhs)
        for i in range(size):
            inverse[i, column] = rhs[i]


def _change_row(displacement, load, mode, row_mode, i, size, inverse, column, product):
    """Sherman-Morrison: the inverse after row i of the system changes from row_mode[i]'s to mode[i]'s.

    Returns False (inverse untouched) when the update's pivot is too small to trust: refactorise instead.
    """
    for j in range(size):
        product[j] = 0.0
    new_row = displacement if mode[i] == 1 else load
    old_row = displacement if row_mode[i] == 1 else load
    for m in range(size):
        change = new_row[i, m] - old_row[i, m]
        if change != 0.0:
            for j in range(size):
                product[j] += change * inverse[m, j]
    pivot = 1.0 + product[i]
    if abs(pivot) < PIVOT_FLOOR:
        return False
    for m in range(size):
        column[m] = inverse[m, i] / pivot
    for m in range(size):
        if column[m] != 0.0:
            for j in range(size):
                inverse[m, j] -= column[m] * product[j]
    row_mode[i] = mode[i]
    return True


def _grow(displacement, load, mode, row_mode, size, inverse, column, product, work):
    """The bordered inverse: annulus ``size`` (stuck) joins the system of the first ``size``. False: refactorise."""
    # y = N c (c the new column of the old rows), z = r N (r the new row), s = d - r y
    for j in range(size):
        work[j] = displacement[j, size] if row_mode[j] == 1 else load[j, size]
    for m in range(size):
        total = 0.0
        for j in range(size):
            total += inverse[m, j] * work[j]
        column[m] = total
    new_row = displacement if mode[size] == 1 else load
    for j in range(size):
        product[j] = 0.0
    pivot = new_row[size, size]
    for m in range(size):
        entry = new_row[size, m]
        pivot -= entry * column[m]
        if entry != 0.0:
            for j in range(size):
                product[j] += entry * inverse[m, j]
    if abs(pivot) < PIVOT_FLOOR:
        return False
    for j in range(size):
        product[j] /= pivot
    for m in range(size):
        scale = column[m]
        if scale != 0.0:
            for j in range(size):
                inverse[m, j] += scale * product[j]
    for m in range(size):
        inverse[m, size] = -column[m] / pivot
    for j in range(size):
        inverse[size, j] = -product[j]
    inverse[size, size] = 1.0 / pivot
    row_mode[size] = mode[size]
    return True


def _shrink(size, inverse):
    """The inverse of the leading block once the last of ``size`` annuli leaves the system. False: refactorise."""
    last = size - 1
    corner = inverse[last, last]
    if abs(corner) < PIVOT_FLOOR:  # the leading block is (nearly) singular: the update cannot be trusted
        return False
    for m in range(last):
        factor = inverse[m, last] / corner
        if factor != 0.0:
            for j in range(last):
                inverse[m, j] -= factor * inverse[last, j]
    return True


def _annuli_cases(chi, psi1, tau, inside, caps, displacement, load, gamma, gain_factor, max_iterations, record,
                  history, stick, h_nodes):
    """Annular-strip time loop per case, keeping the inverse of the mixed system up to date as it changes.

    The system's rows depend on which annuli stick, slip or are out of contact, not on time. Its inverse is
    carried from step to step and updated in O(n^2) when an annulus enters (a bordered inverse), leaves (the
    leading block's inverse) or changes between stick and slip (a rank-one row change, Sherman-Morrison), instead
    of an O(n^3) factorisation at each change; it is computed afresh (LU with partial pivoting) after REFRESH
    updates per annulus in contact, or when an update's pivot is too small, which bounds the round-off they
    accumulate (results agree with a factorisation at every change to 1e-12 of mu J_n). Annuli outside the
    contact force their distributions to zero (the load matrix is upper triangular), so only the inside x inside
    block is solved. Returns (slip change, dissipation, failures).
    """
    cases = chi.size
    rings = gamma.size
    nodes = tau.size
    velocity_out = np.zeros(cases)
    dissipation_out = np.zeros(cases)
    failures = 0
    lu = np.zeros((rings, rings))
    inverse = np.zeros((rings, rings))
    pivots = np.zeros(rings, dtype=np.int64)
    rhs = np.zeros(rings)
    column = np.zeros(rings)
    product = np.zeros(rings)
    work = np.zeros(rings)
    for case in range(cases):
        mode = np.zeros(rings, dtype=np.int64)  # 0 out, 1 stick, 2 slip
        row_mode = np.zeros(rings, dtype=np.int64)  # the modes the inverse is of
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
        held = -1  # size of the system the inverse is of, -1: none valid
        updates = 0  # updates since it was last computed afresh
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
                elif i >= size and mode[i] != 0:
                    mode[i] = 0
            settled = False
            for _ in range(max_iterations):
                # bring the inverse to this step's system: annuli leaving, rows that changed, annuli entering
                if held != -1 and updates <= REFRESH * size:
                    while held > size:
                        if not _shrink(held, inverse):
                            held = -1
                            break
                        held -= 1
                        updates += 1
                    for i in range(max(held, 0)):
                        if row_mode[i] != mode[i]:
                            if not _change_row(displacement, load, mode, row_mode, i, held, inverse, column,
                                               product):
                                held = -1
                                break
                            updates += 1
                    while held != -1 and held < size:
                        if not _grow(displacement, load, mode, row_mode, held, inverse, column, product, work):
                            held = -1
                            break
                        held += 1
                        updates += 1
                if held == -1 or updates > REFRESH * size:
                    _fresh_inverse(displacement, load, mode, size, inverse, lu, pivots, rhs)
                    for i in range(size):
                        row_mode[i] = mode[i]
                    held = size
                    updates = 0
                for i in range(size):
                    rhs[i] = position - offset[i] if mode[i] == 1 else 2.0 * direction[i] * caps[k, i]
                for i in range(size):
                    total = 0.0
                    for j in range(size):
                        total += inverse[i, j] * rhs[j]
                    strength[i] = total
                for j in range(size, rings):
                    strength[j] = 0.0
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


#: smallest pivot of an O(n^2) update of the inverse that is trusted (the system's entries are O(1)); below it the
#: system is factorised afresh
PIVOT_FLOOR = 1e-8
#: updates of the inverse, per annulus in contact, after which it is computed afresh (bounds their round-off)
REFRESH = 4


if HAVE_NUMBA:
    # the helpers are looked up as globals when the kernel compiles: compile them first
    _lu_factor = _compiled(_lu_factor)
    _lu_solve = _compiled(_lu_solve)
    _fresh_inverse = _compiled(_fresh_inverse)
    _change_row = _compiled(_change_row)
    _grow = _compiled(_grow)
    _shrink = _compiled(_shrink)
annuli_cases = _compiled(_annuli_cases)
