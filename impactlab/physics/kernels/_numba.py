"""numba switch and compile helper shared by the kernel modules.

numba caches a compiled function by the file it is defined in, so each kernel family has its own module
(:mod:`.mdr`, :mod:`.annuli`, :mod:`.dem`, :mod:`.rigid`, :mod:`.contact3d`, :mod:`.line`): editing one recompiles
only that family. Set IMPACTLAB_KERNELS=numpy to force the numpy path.
"""

from __future__ import annotations

import os

try:  # numba is a dependency, but impactlab stays usable (slower) where it cannot be installed
    import numba

    HAVE_NUMBA = os.environ.get("IMPACTLAB_KERNELS", "numba") != "numpy"
except ImportError:  # pragma: no cover - depends on the platform
    numba = None  # type: ignore[assignment]
    HAVE_NUMBA = False


def compiled(function, fastmath=False):
    """The numba-compiled kernel (cached on disk), or None where numba is off."""
    return numba.njit(cache=True, nogil=True, fastmath=fastmath)(function) if HAVE_NUMBA else None
