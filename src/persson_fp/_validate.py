"""Input validation helpers shared by the physics modules.

Every check raises a :class:`ValueError` that names the parameter and the
allowed range, so that bad input never turns into a NaN, an overflow warning
or a silently wrong number downstream.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "as_positive_scalar",
    "as_float_array",
    "check_in_range",
]


def as_positive_scalar(value, name: str, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a finite float > 0 (or >= 0), else raise ``ValueError``."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not np.isfinite(x):
        raise ValueError(f"{name} must be finite, got {x!r}")
    if allow_zero:
        if x < 0:
            raise ValueError(f"{name} must be >= 0, got {x!r}")
    elif x <= 0:
        raise ValueError(f"{name} must be > 0, got {x!r}")
    return x


def as_float_array(value, name: str) -> np.ndarray:
    """Return ``value`` as a finite float array, else raise ``ValueError``."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be numeric, got {value!r}") from None
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite everywhere (got NaN or inf)")
    return a


def check_in_range(a, name: str, lo: float, hi: float, *, rtol: float = 1e-12) -> np.ndarray:
    """Check that every element of ``a`` lies in ``[lo, hi]``.

    Values outside by no more than ``rtol`` relative (round-off from a caller's
    arithmetic, e.g. ``q_s / q_l``) are clipped onto the interval.
    """
    a = as_float_array(a, name)
    slack_lo = rtol * max(abs(lo), 1.0)
    slack_hi = rtol * max(abs(hi), 1.0)
    if np.any(a < lo - slack_lo) or np.any(a > hi + slack_hi):
        bad = a[(a < lo - slack_lo) | (a > hi + slack_hi)].ravel()[0]
        raise ValueError(f"{name} must lie in [{lo:.17g}, {hi:.17g}], got {float(bad)!r}")
    return np.clip(a, lo, hi)
