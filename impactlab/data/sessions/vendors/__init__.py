"""Launch-monitor export layouts as data: one YAML column map per vendor (read by impactlab.data.sessions.reader)."""
