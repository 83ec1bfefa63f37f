"""The package's own exceptions, below every folder so that any may raise them (re-exported as ``pf.SolverError``,
``pf.InstabilityError``)."""

from __future__ import annotations

__all__ = ["SolverError", "InstabilityError"]


class SolverError(RuntimeError):
    """A solver could not produce a trustworthy result: it failed, or its result breaks an invariant
    (:func:`~persson_fp.results.solution.check_invariants`); the message names the invariant and the remedy."""


class InstabilityError(SolverError):
    """The discrete evolution went unstable (NaN, negative or growing mass, blow-up)."""
