"""Load and spectrum sweeps (:func:`persson_fp.sweep`): the runner, the quantity registry and the tidy result table."""
