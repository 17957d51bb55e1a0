"""Files: result files, atomic writes, simulator interchange."""
