"""What a problem gives: the exact solution (:func:`persson_fp.exact`) and its energy, numerical solutions
(:class:`~persson_fp.Solution`), their comparison with the exact one and the invariant checks."""
