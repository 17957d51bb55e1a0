"""Execution: run_study, plans, executors, the progress store, assembly and fault handling."""
