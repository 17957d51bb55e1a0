"""How the flight model's constants were found: fits to measured lift, drag and radar flights, tables held out.

Each module is a ``__main__`` that prints a table of docs/flight.md; each ``plot_*.py`` redraws a figure of it.
The constants they produced live in :mod:`impactlab.physics.aerodynamics` with their citations.
Run from the project root: ``python -m validation.flight.<module>``; their tests: ``python -m pytest validation``.
"""
