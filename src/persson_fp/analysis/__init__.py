"""The analytic front ends of a problem: functions that take a :class:`~persson_fp.ContactProblem` first and return
its closed-form result -- the exact solution (:func:`persson_fp.exact`), elastic energy and pressure spectrum, mean
separation and stiffness, gaps, leakage, conductance and adhesion -- built on :mod:`persson_fp.theory`."""
