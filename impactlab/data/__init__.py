"""Measured data: shot tables, calibration and fitting, validation datasets, sensitivity, convergence."""
