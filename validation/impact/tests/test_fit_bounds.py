"""The rate-law fit stays within physics (issue 33, "calibration within physics"): bounded parameters, the head COR
refused beyond the Rules, a parameter at its bound flagged."""

import numpy as np
import pytest

from impactlab.data.sessions.shots import table_inputs
from impactlab.physics import rate_laws
from validation.impact import rate_laws as research


def tour_drivers():
    table = research.tour()
    rows = [i for i, label in enumerate(table.labels) if "driver" in label]
    table = table.subset(rows)
    return table, table_inputs(table)


def test_the_bounds_hold_the_driver_pair_within_the_head_cor_limit():
    low, high = research.BOUNDS["e_ball"][:2]
    assert high + research.DRIVER_GAIN == pytest.approx(rate_laws.HEAD_COR_LIMIT)
    assert low < high


def test_a_fit_that_needs_a_head_beyond_0830_is_refused():
    """The tour drivers' smash factors need a pair e near 0.87 with this head: widen the bound and the fit goes there,
    and is refused, never returned."""
    table, inputs = tour_drivers()
    form = research.Form("rigid", "rigid_coulomb", {}, ("e_ball",))
    bounds = dict(research.BOUNDS, e_ball=(0.60, 0.95, 0.72, "widened for the test"))
    with pytest.raises(ValueError, match="beyond the Rules' limit"):
        research.fit(form, inputs, table.measured, bounds)


def test_a_fit_held_by_its_bound_says_so():
    table, inputs = tour_drivers()
    form = research.Form("rigid", "rigid_coulomb", {}, ("e_ball",))
    values, at_bound = research.fit(form, inputs, table.measured, research.BOUNDS)
    assert at_bound == ["e_ball"]
    assert values["e_ball"] + research.DRIVER_GAIN <= rate_laws.HEAD_COR_LIMIT + 1e-12
    assert np.isfinite(values["e_ball"])
