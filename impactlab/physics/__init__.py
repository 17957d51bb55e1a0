"""Physics as plain array functions of SI values.

Nothing here knows about studies, models or xarray: every function takes
numpy arrays (or floats) and returns arrays, broadcasting over cases.
"""
