"""Fitting a model to measured launches: the one bounded least-squares core (:mod:`.least_squares`), calibration to
shot tables (:mod:`.calibration`) and to measured-data files (:mod:`.fitting`)."""
