"""Research reproductions beside the package: each module is one command that prints a table of the docs.

Not installed with impactlab. Run from the project root, e.g. ``python -m validation.flight.aero_fit``.
"""
