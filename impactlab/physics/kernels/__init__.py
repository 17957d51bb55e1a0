"""Compiled inner loops (numba), with the numpy implementations as the reference and the fallback.

The kernels run one case at a time, which lets them skip the springs outside
the contact and keep a case's springs in cache; the numpy versions in
:mod:`impactlab.physics.mdr` run all cases at once. Both do the same arithmetic in the same
order per spring, so results agree to round-off (tests/test_kernels.py).
Set IMPACTLAB_KERNELS=numpy to force the numpy path.

One module per kernel family, because numba's on-disk cache is keyed by the file a function is defined in:
editing one family recompiles only it. ``HAVE_NUMBA`` here is the switch the physics modules read (tests turn
it off to run the numpy references).
"""

from ._numba import HAVE_NUMBA
from .annuli import _annuli_cases, annuli_cases
from .contact3d import _contact3d_cases, contact3d_cases
from .dem import _dem_cases, dem_cases
from .line import _line_cases, line_cases
from .mdr import _mdr_cases, _mdr_pressures, mdr_cases, mdr_pressures
from .rigid import _stronge_cases, stronge_cases
from .rolling import _rolling_cases, rolling_cases

__all__ = ["HAVE_NUMBA", "annuli_cases", "contact3d_cases", "dem_cases", "line_cases", "mdr_cases", "mdr_pressures",
           "stronge_cases", "rolling_cases",
           "_annuli_cases", "_contact3d_cases", "_dem_cases", "_line_cases", "_mdr_cases", "_mdr_pressures",
           "_stronge_cases", "_rolling_cases"]
