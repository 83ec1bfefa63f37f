"""Rough surfaces: power spectra (models and tables), spectrum conventions, height-map and profile analysis, file
readers.  Imports nothing else of persson_fp."""
