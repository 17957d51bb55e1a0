"""impactlab's built-in impact models, installed as ``impactlab_models``.

They register through the ``impactlab.models`` entry-point group, exactly as
a third-party plugin would; nothing in :mod:`impactlab` imports them directly.
"""
