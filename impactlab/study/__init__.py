"""Study loading: the YAML schema, blocks, sweeps, limits and line numbers."""
