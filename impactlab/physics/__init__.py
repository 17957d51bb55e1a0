"""Physics as plain array functions of SI values.

Nothing here knows about studies, models or xarray: every function takes
numpy arrays (or floats) and returns arrays, broadcasting over cases.
"""

from __future__ import annotations

import numpy as np

#: what a physics function takes and gives: one value, or an array of values one per case (SI)
Values = float | np.ndarray

__all__ = ["Values"]
