"""Under the hysteretic (damped) normal law, which maw method is right: MDR or the annular strips?

Theory: MDR's row of springs represents a 3-D contact (the inverse MDR transform) and its Coulomb caps the 3-D
limit mu p(r) only while the pressure is an elastic one (Popov & Hess 2015; Jaeger's superposition of Hertz
pressures). A damped law scales the pressure by a load factor that falls fastest where it is largest, and the
springs' 3-D traction then exceeds mu p(r): the MDR state is no solution of the 3-D problem, which the annular
strips solve directly. Measured in benchmarks/bench_hysteretic.py and docs/models.md.
"""

import math

import numpy as np
from impactlab.physics import annuli, hertz, mdr
from impactlab.model.registry import get_model
from impactlab.data.validation.benchmarks import Sphere, plate_inputs

CHI = 1.24  # urethane ball (nu 0.45) on a rigid face


def test_inverse_mdr_transform_gives_the_hertz_pressure():
    # oracle: the line load E* (a^2 - x^2)/R of a sphere maps to p(r) = (2 E*/(pi R)) sqrt(a^2 - r^2)
    # (the jumps at the cell edges sample an integrable 1/sqrt singularity: the error falls as cells^-1/2)
    errors = []
    for cells in (400, 1600):
        x = (np.arange(cells) + 0.5) / cells
        pressure = mdr.traction_3d(1.0 - x**2) * cells  # the transform counts lengths in cell widths
        expected = 2.0 / np.pi * np.sqrt(1.0 - x**2)
        errors.append(np.max(np.abs(pressure / expected - 1.0)[x < 0.8]))
    assert errors[1] < 0.6 * errors[0] and errors[1] < 0.02


def _largest_excess(psi1, normal, springs=60):
    worst = np.zeros(len(psi1))

    def observe(_, u, cap):
        worst[:] = np.maximum(worst, mdr.coulomb_excess(u, cap))

    mdr.solve_scaled(np.full(len(psi1), CHI), np.asarray(psi1, float), springs=springs, steps=6 * springs,
                     normal=normal, observe=observe)
    return worst


def test_mdr_springs_respect_the_3d_coulomb_limit_for_an_elastic_pressure_only():
    psi1 = [0.5, 1.0, 2.0, 3.0]
    assert np.all(_largest_excess(psi1, hertz.ELASTIC) < 1e-9)
    damped = _largest_excess(psi1, hertz.DampedNormal(hertz.damping_for_restitution(0.6)))
    assert damped[0] < 1e-9  # low incidence: the slip zone stays where MDR can represent it
    assert damped[2] > 0.05  # psi1 = 2: the springs carry a 3-D traction 5 % and more beyond mu p(r)


def test_annuli_converge_to_mdr_where_mdr_is_a_3d_solution_and_away_from_it_where_it_is_not():
    normal = hertz.DampedNormal(hertz.damping_for_restitution(0.6))
    psi1 = np.array([1.0, 2.0])
    chi = np.full(2, CHI)
    plain = -(psi1 + mdr.solve_scaled(chi, psi1, springs=200, steps=1200, normal=normal).slip_change) / psi1
    ring40, ring80 = (-(psi1 + annuli.solve_scaled(chi, psi1, rings=n, steps=10 * n, normal=normal).slip_change)
                      / psi1 for n in (40, 80))
    # psi1 = 1: the gap halves as the rings double, as for an elastic impact
    assert abs(ring80[0] - plain[0]) < 0.6 * abs(ring40[0] - plain[0]) and abs(ring80[0] - plain[0]) < 2e-3
    # psi1 = 2: the rings have settled to 6e-4 while MDR stays 9e-3 away
    assert abs(ring80[1] - ring40[1]) < 1e-3 and abs(ring80[1] - plain[1]) > 8e-3


def test_maw_solves_by_annular_strips_where_its_springs_break_the_3d_limit():
    ball = Sphere("urethane-like", 0.021335, 1128.0, 5.0e7, 0.45, "a golf-ball-like sphere for the test")
    angles = np.radians([10.0, 35.0, 45.0])  # psi1 0.31, 1.24, 1.7: the last two break the limit under e = 0.6
    inputs = plate_inputs(ball, speed=35.0, angle=angles, friction=0.4, restitution=0.6)
    outputs = ["tangential_restitution", "validity"]
    springs = get_model("maw")(inelastic="hysteretic", rings=40).compute(inputs, outputs)
    strips = get_model("maw")(inelastic="hysteretic", method="annuli", rings=40).compute(inputs, outputs)
    beta, reference = springs.tangential_restitution.values, strips.tangential_restitution.values
    np.testing.assert_allclose(beta[1:], reference[1:], rtol=0, atol=1e-12)
    assert abs(beta[0] - reference[0]) > 1e-4  # left to MDR, the finer engine, where it is exact
    # the adjusted-speed law is elastic: no case leaves MDR, none misses the default tolerance
    assert not np.any(get_model("maw")().compute(inputs, ["validity"]).validity.values.astype(int) & 4)
    # at the default tolerance, 160 rings cannot reach MDR's 1e-4: said in the validity flags
    flags = get_model("maw")(inelastic="hysteretic").compute(inputs, ["validity"]).validity.values.astype(int)
    assert [bool(flag & 4) for flag in flags] == [False, True, True]
    assert math.isfinite(beta.sum())


def test_laws_with_a_constant_load_factor_are_not_checked():
    # an elastic law, and a hysteretic law without damping (e = 1): the pressure is Hertz's, MDR is exact
    for normal in (hertz.ELASTIC, hertz.DampedNormal(0.0)):
        solved = mdr.solve_scaled(np.full(2, CHI), np.array([0.5, 2.0]), springs=40, steps=240, normal=normal)
        assert solved.breaks_3d_limit is None


def test_compiled_limit_check_flags_the_cases_the_numpy_reference_flags():
    # oracle: the numpy path checks the full inverse transform (mdr.coulomb_excess) of every case at the same steps;
    # the kernel sums only inside the outermost jump of the springs' forces that exceeds the caps' and reuses the
    # grid's pressure, which must flag exactly the same cases
    normal = hertz.DampedNormal(hertz.damping_for_restitution(0.7))
    psi1 = np.linspace(0.2, 4.0, 24)
    chi = np.repeat([0.9, CHI, 3.0], 8)
    compiled = mdr.solve_scaled(chi, psi1, springs=60, steps=360, normal=normal)
    reference = mdr.solve_scaled(chi, psi1, springs=60, steps=360, normal=normal, _force_numpy=True)
    assert 0 < np.count_nonzero(reference.breaks_3d_limit) < psi1.size  # both kinds of case are in the batch
    np.testing.assert_array_equal(compiled.breaks_3d_limit, reference.breaks_3d_limit)


def test_compiled_limit_check_flags_tractions_beyond_the_limit_of_either_sign():
    # oracle: mdr.coulomb_excess (numpy, the full transform of every case) at the same steps. In restitution a heavy
    # ball's springs reverse (chi 2-5, low e): the 3-D traction beyond the limit is then negative, and a kernel that
    # screened its rows by the signed force jumps instead of their size missed 75 of 1920 such cases (review7); the
    # batch above (e 0.7, chi <= 3) has none of them
    chi = np.repeat([2.0, 5.0], 12)
    psi1 = np.tile(np.geomspace(0.2, 1.2, 12), 2)
    for e in (0.5, 0.9):
        normal = hertz.DampedNormal(hertz.damping_for_restitution(e))
        compiled = mdr.solve_scaled(chi, psi1, springs=60, steps=360, normal=normal)
        reference = mdr.solve_scaled(chi, psi1, springs=60, steps=360, normal=normal, _force_numpy=True)
        assert 0 < np.count_nonzero(reference.breaks_3d_limit) < psi1.size
        np.testing.assert_array_equal(compiled.breaks_3d_limit, reference.breaks_3d_limit)


def test_compiled_limit_check_keeps_one_pressure_transform_per_grid():
    # the kernel's 3-D pressures at the steps checked are cached per (law, springs, steps): one law solved on several
    # grids in a row (a study with two resolutions) must give each grid's own flags, as the numpy reference does; a
    # cache keyed without the steps reused the first grid's pressures (review7)
    normal = hertz.DampedNormal(hertz.damping_for_restitution(0.6))
    chi = np.repeat([0.9, 2.0, 5.0], 8)
    psi1 = np.tile(np.geomspace(0.2, 3.0, 8), 3)
    for springs, steps in ((48, 480), (48, 200), (48, 96), (30, 200)):
        compiled = mdr.solve_scaled(chi, psi1, springs=springs, steps=steps, normal=normal)
        reference = mdr.solve_scaled(chi, psi1, springs=springs, steps=steps, normal=normal, _force_numpy=True)
        np.testing.assert_array_equal(compiled.breaks_3d_limit, reference.breaks_3d_limit, err_msg=f"{springs, steps}")


def test_many_laws_limit_checks_leave_their_grids_in_the_cache(monkeypatch):
    # a batch of many restitutions holds one damped law each. The check's arrays (a transform that depends on the
    # springs alone, held once per law, and the law's pressures) shared the grids' cache and pushed the laws' own
    # grids out (FIFO over a working set beyond the budget), and every call rebuilt every grid: 20 restitutions at the
    # default tolerance ran 10 s instead of 3.4 (review7). Here 4 laws under a 2 MB budget: their grids fit (about
    # 0.1 MB a law), with the check's arrays (1 MB a law) they would not
    from impactlab.physics import hertz

    monkeypatch.setattr(hertz, "_GRIDS", {})
    monkeypatch.setattr(hertz, "_GRIDS_BYTES", 2 * 2**20)
    built = []
    real = mdr._spring_grid
    monkeypatch.setattr(mdr, "_spring_grid", lambda normal, springs, steps: built.append(springs) or real(
        normal, springs, steps))
    laws = [hertz.DampedNormal(hertz.damping_for_restitution(e)) for e in (0.55, 0.65, 0.75, 0.85)]
    for _ in range(2):
        for law in laws:
            solved = mdr.solve_scaled(np.array([CHI]), np.array([0.5]), springs=300, steps=1800, normal=law)
            assert solved.breaks_3d_limit is not None
    assert len(built) == len(laws)  # each law's grid built once, then found
    held = [a for entry in hertz._GRIDS.values() for a in entry[1] if isinstance(a, np.ndarray)]
    assert not any(a.shape == (300, 300) for a in held)
