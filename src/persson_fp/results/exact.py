"""Old path of :func:`~persson_fp.exact` and :class:`~persson_fp.ExactSolution` (moved to
:mod:`persson_fp.analysis.exact`).

Kept for one release so that existing imports keep working; import from :mod:`persson_fp.analysis.exact` (or
``persson_fp``).
"""

from persson_fp.analysis.exact import FULL_CONTACT, ExactSolution, exact

__all__ = ["ExactSolution", "exact", "FULL_CONTACT"]
