"""What a solver gives: numerical solutions (:class:`~persson_fp.Solution`), the solver output they are built from,
their comparison with the exact solution (:mod:`persson_fp.analysis`) and the invariant checks."""
