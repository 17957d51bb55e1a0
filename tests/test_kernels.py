"""The compiled kernels give the numpy reference's results to round-off."""

import numpy as np
import pytest

from impactlab.physics import hertz, mdr
from impactlab.physics import kernels as _kernels

pytestmark = pytest.mark.skipif(not _kernels.HAVE_NUMBA, reason="numba is not installed")


def assert_same_solution(fast, slow, rtol=1e-12):
    np.testing.assert_allclose(fast.slip_change, slow.slip_change, rtol=rtol, atol=1e-12)
    np.testing.assert_allclose(fast.dissipation, slow.dissipation, rtol=rtol, atol=1e-12)
    np.testing.assert_allclose(fast.force, slow.force, rtol=rtol, atol=1e-12)
    np.testing.assert_array_equal(fast.stick_radius, slow.stick_radius)


@pytest.mark.parametrize("normal", [None, hertz.DampedNormal(0.4)], ids=["elastic", "damped"])
def test_mdr_kernel_matches_numpy(normal):
    rng = np.random.default_rng(7)
    chi, psi1 = rng.uniform(0.3, 10.0, 40), np.concatenate([rng.uniform(0.0, 3.0, 20), rng.uniform(3.0, 60.0, 20)])
    fast = mdr.solve_scaled(chi, psi1, springs=60, steps=240, record=True, normal=normal)
    slow = mdr.solve_scaled(chi, psi1, springs=60, steps=240, record=True, normal=normal, _force_numpy=True)
    assert_same_solution(fast, slow)
    # without histories the kernel takes its vectorised (reassociated) loop: the same to round-off
    quick = mdr.solve_scaled(chi, psi1, springs=60, steps=240, normal=normal)
    np.testing.assert_allclose(quick.slip_change, slow.slip_change, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(quick.dissipation, slow.dissipation, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("normal", [None, hertz.DampedNormal(0.4)], ids=["elastic", "damped"])
def test_annuli_kernel_matches_the_dense_solve(normal):
    from impactlab.physics import annuli

    chi = np.concatenate([np.full(6, 1.44), np.full(6, 6.0)])
    psi1 = np.tile(np.linspace(0.2, 12.0, 6), 2)
    fast = annuli.solve_scaled(chi, psi1, rings=16, steps=160, record=True, normal=normal)
    dense = annuli.solve_scaled(chi, psi1, rings=16, steps=160, record=True, normal=normal, dense=True)
    assert_same_solution(fast, dense, rtol=1e-11)


def test_annuli_kernel_updates_of_the_inverse_keep_to_the_dense_solve_over_many_changes():
    # 60 annuli under a damped law: hundreds of annuli entering, leaving and turning between stick and slip, each
    # an O(n^2) update of the kernel's inverse, with refreshes between; the dense path solves every system afresh
    from impactlab.physics import annuli

    normal = hertz.DampedNormal(hertz.damping_for_restitution(0.6))
    chi, psi1 = np.array([0.9, 1.24, 5.0]), np.array([0.4, 2.0, 6.0])
    fast = annuli.solve_scaled(chi, psi1, rings=60, steps=300, normal=normal)
    dense = annuli.solve_scaled(chi, psi1, rings=60, steps=300, normal=normal, dense=True)
    np.testing.assert_allclose(fast.slip_change, dense.slip_change, rtol=1e-10, atol=0)
    np.testing.assert_allclose(fast.dissipation, dense.dissipation, rtol=1e-10, atol=0)


@pytest.mark.slow
def test_a_freshly_compiled_kernel_and_one_loaded_from_the_cache_give_the_same_bits(tmp_path):
    # every process of an executor must run the same machine code: workers load numba's cache that the
    # first process wrote, so a kernel whose code differs between the two would make results depend on
    # where a chunk ran (it did once, through a fastmath helper linked into a plain kernel)
    import os
    import subprocess
    import sys

    script = ("import hashlib, numpy as np\n"
              "from impactlab.physics import compliant3d, hertz, mdr\n"
              "r = mdr.solve_scaled(np.full(64, 1.3), np.geomspace(0.05, 9.0, 64), springs=60, steps=360)\n"
              "w = np.tile(np.array([[80.0, 5.0, 9.0], [5.0, 70.0, -4.0], [9.0, -4.0, 30.0]]), (16, 1, 1))\n"
              "s = compliant3d.solve(w, np.full(16, 40.0), np.linspace(0.0, 30.0, 16), friction=np.full(16, 0.4),\n"
              "                      kappa=np.full(16, 0.7), modulus=np.full(16, 1.5e8), radius=np.full(16, 0.02),\n"
              "                      normal=hertz.ELASTIC, springs=40, steps=200)\n"
              "print(hashlib.sha256(r.slip_change.tobytes() + r.dissipation.tobytes() + s.impulse.tobytes())"
              ".hexdigest())\n")
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path))
    fresh = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    cached = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True)
    assert any(tmp_path.rglob("*.nbc")), "the first run should have written the cache"
    assert fresh.stdout == cached.stdout


# -- the 3-D kernel's cases on one line (kernels/line.py) ----------------------------------------------------------

def _line_arguments(n, law, springs, normal, *, core=False, face=False, rolling=False, loss=0.0):
    """Cases on one line (a sphere on a point-mass head: W diagonal), every feature the 3-D kernel carries."""
    from impactlab.physics import core_torsion, face_flex

    mass, radius, total = 0.04593, 0.021335, 0.4 * 0.04593 * 0.021335**2
    mobility = np.broadcast_to(np.diag([1 / mass + radius**2 / total] * 2 + [1 / mass + 1 / 0.2]), (n, 3, 3)).copy()
    arguments = dict(friction=np.linspace(0.2, 0.6, n), kappa=np.full(n, 0.7), modulus=np.full(n, 1.5e8),
                     radius=np.full(n, radius), normal=normal, springs=springs, steps=400, law=law,
                     tangential_loss=np.full(n, loss))
    if core:
        modes = core_torsion.core_modes(total_inertia=total, core_radius=0.019, core_density=1150.0,
                                        shear_modulus=1e7, loss=0.2, modes=3)
        arguments["core"] = (np.tile(modes.inverse_inertia, (n, 1)), np.tile(modes.frequency, (n, 1)),
                             np.tile(modes.damping, (n, 1)), np.full(n, radius))
    if face:
        arguments["face"] = face_flex.modal_inputs(np.full(n, 6e6), np.linspace(0.006, 0.012, n), 0.1)
    if rolling:  # a sphere's couple mobility on a fixed face: B_sl = -B_ls = R / I, D = 1 / I (couple_mobility)
        coupling = np.zeros((n, 3, 2))
        coupling[:, 0, 1], coupling[:, 1, 0] = -radius / total, radius / total
        arguments["rolling"] = (coupling, np.broadcast_to(np.eye(2) / total, (n, 2, 2)).copy(),
                                np.stack([np.zeros(n), np.linspace(-50.0, 50.0, n)], -1), np.full(n, 0.05))
    return mobility, np.full(n, 40.0), np.linspace(-10.0, 30.0, n), arguments


LINE_FORMS = [
    ("mdr", 24, 0.3, dict(core=True, rolling=True, loss=0.1)),
    ("mdr", 24, 0.0, dict(face=True)),
    ("mindlin", 1, 0.3, dict(face=True, rolling=True)),
    ("mindlin", 1, 0.0, dict(core=True, rolling=True, face=True)),
    ("linear", 1, 0.2, dict(core=True, loss=0.2)),
]


@pytest.mark.parametrize("law, springs, damping, features", LINE_FORMS)
def test_line_kernel_equals_the_3d_kernel_on_cases_on_the_line(law, springs, damping, features):
    """kernels/line.py is the 3-D kernel's arithmetic on the line's components: on cases on one line (W diagonal, a
    planar couple) every output of compliant3d.solve_once, the histories included, equals the 3-D kernel's (line=False)
    to round-off; a dropped term (the couple's push on the slip, a mode's damping, the face's loss) moves them by
    1e-3 or more."""
    from impactlab.physics import compliant3d

    mobility, speeds, slips, arguments = _line_arguments(7, law, springs, hertz.DampedNormal(damping)
                                                         if damping else hertz.ELASTIC, **features)
    if law == "mindlin":
        arguments.update(store_force=damping > 0.0, rescale=True, tangential_damping=0.1)
    line = compliant3d.solve_once(mobility, speeds, slips, record=True, **arguments)
    plain = compliant3d.solve_once(mobility, speeds, slips, record=True, line=False, **arguments)
    np.testing.assert_array_equal(line.steps, plain.steps)
    scale = np.abs(plain.impulse).max()
    for name in ("impulse", "impulse_time", "contact_time", "work", "moment", "core_energy", "face_energy"):
        ours, theirs = getattr(line, name), getattr(plain, name)
        np.testing.assert_allclose(ours, theirs, rtol=1e-10, atol=1e-12 * np.abs(theirs).max(), err_msg=name)
    for name in ("normal_force", "tangential_force", "stick_radius"):
        ours, theirs = getattr(line, name), getattr(plain, name)
        np.testing.assert_allclose(ours, theirs, rtol=1e-9, atol=1e-11 * np.nanmax(np.abs(theirs)), err_msg=name)
    assert np.all(plain.impulse[:, 1] == 0.0) and scale > 0.0
    if "rolling" in features:
        assert np.all(np.abs(plain.moment[:, 1]) > 0.0)


def test_line_kernel_numpy_path_equals_the_compiled_one(monkeypatch):
    from impactlab.physics import compliant3d

    if not _kernels.HAVE_NUMBA:
        pytest.skip("numba is off: the numpy path is the only one")
    mobility, speeds, slips, arguments = _line_arguments(2, "mdr", 8, hertz.DampedNormal(0.3), core=True,
                                                         rolling=True, face=True, loss=0.1)
    arguments["steps"] = 120
    compiled = compliant3d.solve_once(mobility, speeds, slips, **arguments)
    monkeypatch.setattr(_kernels, "HAVE_NUMBA", False)
    reference = compliant3d.solve_once(mobility, speeds, slips, **arguments)
    for name in ("impulse", "work", "moment", "core_energy", "face_energy", "contact_time"):
        np.testing.assert_allclose(getattr(compiled, name), getattr(reference, name), rtol=1e-10, atol=1e-14)


def test_only_cases_on_one_line_take_the_line_kernel():
    """compliant3d.on_line: the 1-D path's tolerance (1e-12 of W_nn) on a, b; a couple kept planar."""
    from impactlab.physics import compliant3d

    n = 6
    ratio = np.broadcast_to(np.diag([3.5, 3.5]), (n, 2, 2)).copy()
    coupling = np.zeros((n, 2))
    coupling[1, 0] = 1e-14  # round-off of a centred strike: on the line
    coupling[2, 1] = 1e-6  # a strike off centre: not
    ratio[3, 0, 1] = ratio[3, 1, 0] = 1e-3
    couple_n, couple_t, couple_rr = np.zeros((n, 2)), np.zeros((n, 2, 2)), np.broadcast_to(np.eye(2), (n, 2, 2)).copy()
    couple_t[:, 0, 1], couple_t[:, 1, 0] = -1.0, 1.0
    couple_t[4, 1, 1] = 1e-3  # a couple about l that pushes the lateral slip
    rolling0 = np.zeros((n, 2))
    rolling0[5, 0] = 0.1  # rolling about s before impact
    arm = np.full(n, 0.05)
    assert list(compliant3d.on_line(ratio, coupling, arm, couple_n, couple_t, couple_rr, rolling0)) == [
        True, True, False, False, False, False]
    assert list(compliant3d.on_line(ratio, coupling, np.zeros(n), couple_n, couple_t, couple_rr, rolling0)) == [
        True, True, False, False, True, True]
