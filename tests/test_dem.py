"""DEM-style tangential laws (physics brief 6): exact limits, their relation to Maw, numerics."""

import numpy as np
import pytest

from impactlab.physics import dem, mdr
from impactlab.physics import kernels as _kernels
from impactlab.model.registry import get_model
from impactlab.testing import check_model

VARIANTS = [
    ("dem_linear", {}),
    ("dem_linear", {"stiffness_ratio": 1.0, "damping": 0.2}),
    ("hertz_mindlin", {}),
    ("hertz_mindlin", {"rescale": False}),
    ("hertz_mindlin", {"history": "displacement", "rescale": False}),
    ("hertz_mindlin", {"history": "displacement", "rescale": True}),
]
IDS = [f"{name}-{options}" for name, options in VARIANTS]


def mbf(nu=0.45, k2=0.4):
    return 2 * (1 - nu) / (2 - nu), (1 - nu) / (2 - nu) * (1 + 1 / k2)


@pytest.mark.parametrize(("name", "options"), VARIANTS, ids=IDS)
def test_every_variant_passes_the_conformance_suite(name, options):
    check_model(get_model(name)(**options))


@pytest.mark.parametrize(("name", "options"), VARIANTS, ids=IDS)
def test_gross_slip_follows_the_coulomb_line_like_every_model(golf_inputs, name, options):
    # sliding throughout, every Coulomb law gives psi2 = psi1 - 4 chi: the DEM laws agree with rigid Coulomb
    inputs = golf_inputs(friction=0.05, angle=np.radians([40.0, 55.0, 70.0]))
    names = ["tangential_impulse", "launch_angle", "spin_rate"]
    dem_result = get_model(name)(**options).compute(inputs, names)
    rigid = get_model("rigid_coulomb")().compute(inputs, names)
    for key in names:
        np.testing.assert_allclose(dem_result[key], rigid[key], rtol=1e-6)


@pytest.mark.parametrize(("law", "history", "rescale"), [("linear", "force", False), ("mindlin", "force", True),
                                                         ("mindlin", "displacement", False)])
def test_compiled_kernel_equals_the_numpy_reference(law, history, rescale):
    if not _kernels.HAVE_NUMBA:
        pytest.skip("numba kernels are off (IMPACTLAB_KERNELS=numpy or numba missing)")
    chi, psi1 = np.full(40, 1.24), np.geomspace(0.02, 12.0, 40)
    kwargs = dict(law=law, history=history, rescale=rescale, stiffness_factor=0.4, damping=0.1, steps=700,
                  record=True)
    fast, slow = dem.solve_scaled(chi, psi1, **kwargs), dem.solve_scaled(chi, psi1, _force_numpy=True, **kwargs)
    np.testing.assert_allclose(fast.slip_change, slow.slip_change, rtol=1e-13, atol=1e-14)
    np.testing.assert_allclose(fast.force, slow.force, rtol=1e-13, atol=1e-14)
    # with a rolling couple on the line (every other case, rolling forwards or backwards before impact)
    rng = np.random.default_rng(3)
    rolling = (rng.uniform(-2.0, -0.5, 40), rng.uniform(-0.6, -0.1, 40), rng.uniform(0.5, 2.0, 40),
               rng.uniform(-0.3, 0.3, 40), np.where(np.arange(40) % 2 == 0, 0.07, 0.0))
    fast, slow = (dem.solve_scaled(chi, psi1, rolling=rolling, **kwargs),
                  dem.solve_scaled(chi, psi1, rolling=rolling, _force_numpy=True, **kwargs))
    assert np.all(fast.moment[::2] != 0.0) and np.all(fast.moment[1::2] == 0.0)
    for name in ("slip_change", "force", "moment", "rolling_work", "dissipation"):
        np.testing.assert_allclose(getattr(fast, name), getattr(slow, name), rtol=1e-13, atol=1e-14, err_msg=name)


@pytest.mark.parametrize(("law", "history", "rescale"), [("linear", "force", False), ("mindlin", "force", True),
                                                         ("mindlin", "force", False),
                                                         ("mindlin", "displacement", True)])
def test_default_steps_meet_the_tolerance_against_both_scales(law, history, rescale):
    chi, psi1 = np.full(30, 1.24), np.geomspace(0.01, 8.0, 30)
    kwargs = dict(law=law, history=history, rescale=rescale, stiffness_factor=0.4)
    converged = dem.solve_scaled(chi, psi1, steps=100_000, **kwargs).slip_change
    for tolerance in (1e-3, 1e-4):
        steps, capped = dem.steps_for(tolerance)
        result = dem.solve_scaled(chi, psi1, steps=steps, **kwargs).slip_change
        assert not capped
        assert np.all(np.abs(result - converged) <= tolerance * np.minimum(4 * chi, psi1))


def test_energy_balance_closes_in_scaled_variables():
    chi, psi1 = np.full(20, 1.24), np.geomspace(0.05, 8.0, 20)
    solved = dem.solve_scaled(chi, psi1, steps=4000)
    assert np.max(np.abs(solved.energy_residual(chi, psi1))) < 1e-6 * np.max(psi1**2)


@pytest.mark.parametrize(("history", "onset"), [("force", 1.0), ("displacement", 1.5)])
def test_first_touch_ratio_is_maws_for_the_incremental_law_and_half_more_for_the_total_law(golf_inputs, history,
                                                                                          onset):
    # at first touch xi = V_x t and a^2 ~ t: the total law k_t(a) xi gives F_t/(mu F_n) = 1.5 psi1 (slip from
    # psi1 = 2/3); the incremental law integrates k_t(a) dxi to psi1, Maw's value (slip from psi1 = 1)
    kappa, _ = mbf()
    mu = 0.4
    targets = np.array([0.3, 0.5, 0.8, 1.5])
    inputs = golf_inputs(friction=mu, angle=np.arctan(targets * mu / kappa))
    model = get_model("hertz_mindlin")(history=history, rescale=False, history_points=2001, steps=8000)
    result = model.compute(inputs, ["normal_force", "tangential_force", "contact_time"])
    early = np.argmin(np.abs(result["time"].values - 0.02 * result["contact_time"].values.min()))
    ratio = (result["tangential_force"] / (mu * result["normal_force"])).isel(time=early).values
    np.testing.assert_allclose(ratio, np.minimum(onset * targets, 1.0), rtol=0.03)


def test_incremental_mindlin_without_slip_is_mdr_during_loading():
    # with no Coulomb cap reached, MDR's springs entering the growing contact at u = 0 add dF = k_t(a) dxi:
    # exactly the incremental Hertz-Mindlin law, as long as the contact grows
    chi, psi1 = np.array([1.24]), np.array([1e-4])
    spring = dem.solve_scaled(chi, psi1, law="mindlin", history="force", rescale=False, steps=6000, record=True)
    springs = mdr.solve_scaled(chi, psi1, springs=800, steps=6000, record=True)
    peak = np.searchsorted(spring.tau, 0.5 * spring.tau[-1]) - 1  # the contact grows until half its duration
    on_mdr_grid = np.interp(spring.tau[:peak], springs.tau, springs.force[0])
    np.testing.assert_allclose(spring.force[0, :peak], on_mdr_grid, rtol=0, atol=5e-3 * np.abs(on_mdr_grid).max())


def test_dem_laws_depart_from_maw_at_golf_lofts_in_opposite_directions(golf_inputs):
    # the comparison the approaches study draws: same inputs, 10-25 deg of loft, mu 0.4
    inputs = golf_inputs(angle=np.radians([10.0, 15.0, 20.0, 25.0]), restitution=0.8)
    beta = {name: get_model(name)().compute(inputs, ["tangential_restitution"])["tangential_restitution"].values
            for name in ("maw", "dem_linear", "hertz_mindlin", "rigid_coulomb")}
    assert np.all(beta["hertz_mindlin"] < beta["maw"] - 0.1)  # no microslip: the whole contact lets go at once
    assert np.all(beta["dem_linear"] > beta["maw"] + 0.3)     # stiff constant spring returns its energy
    np.testing.assert_allclose(beta["rigid_coulomb"], 0.0, atol=1e-12)


def test_bad_options_name_the_field_and_the_choices():
    from impactlab.errors import FieldError

    with pytest.raises(FieldError, match="history.*displacement, force"):
        get_model("hertz_mindlin")(history="forces")
    with pytest.raises(FieldError, match="stiffness_ratio"):
        get_model("dem_linear")(stiffness_ratio=-1.0)


def test_tangential_damping_dissipates_in_stick_and_changes_nothing_in_gross_slip(golf_inputs):
    # the ball keeps less tangential energy (|beta| falls), whichever way beta pointed without damping
    sticking = golf_inputs(angle=np.radians([8.0, 15.0]))
    sliding = golf_inputs(friction=0.05, angle=np.radians([50.0, 65.0]))
    names = ["tangential_restitution", "energy_loss"]
    for name in ("hertz_mindlin", "dem_linear"):
        plain, damped = get_model(name)(), get_model(name)(damping=0.5)
        a, b = plain.compute(sticking, names), damped.compute(sticking, names)
        assert np.all(np.abs(b["tangential_restitution"].values) < np.abs(a["tangential_restitution"].values))
        assert np.all(b["energy_loss"].values > a["energy_loss"].values)
        np.testing.assert_allclose(damped.compute(sliding, ["tangential_impulse"])["tangential_impulse"],
                                   plain.compute(sliding, ["tangential_impulse"])["tangential_impulse"], rtol=1e-6)


@pytest.mark.parametrize("name", ["hertz_mindlin", "dem_linear"])
def test_force_history_integrates_to_the_impulse_and_never_exceeds_coulomb(golf_inputs, name):
    inputs = golf_inputs(angle=np.radians([10.0, 30.0]))
    result = get_model(name)(history_points=4001).compute(
        inputs, ["tangential_force", "normal_force", "tangential_impulse", "stick_radius"])
    time = result["time"].values
    for case in range(2):
        force = np.nan_to_num(result["tangential_force"].values[case])
        normal = np.nan_to_num(result["normal_force"].values[case])
        assert np.trapezoid(force, time) == pytest.approx(result["tangential_impulse"].values[case], rel=2e-3)
        # (the histories are interpolated onto the output axis; the normal force is exact there)
        assert np.all(np.abs(force) <= 0.4 * normal + 0.01 * 0.4 * normal.max())
    stick = result["stick_radius"].values
    assert np.nanmax(stick) > 0 and np.nanmin(stick) == 0.0  # the whole contact sticks, or none of it
