"""The analytic front ends of a problem: functions that take a :class:`~persson_fp.ContactProblem` first and return
its closed-form result -- the exact solution (:func:`persson_fp.exact`), the elastic energy and pressure spectrum,
the mean separation and stiffness, gaps, leak rate, conductance and adhesion -- built on the closed forms of
``persson_fp.theory``."""
