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
