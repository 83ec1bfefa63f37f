"""Input validation helpers shared by the physics modules.

Every check raises a :class:`ValueError` that names the parameter and the
allowed range, so that bad input never turns into a NaN, an overflow warning
or a silently wrong number downstream.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "as_positive_scalar",
    "as_float_array",
    "check_in_range",
    "as_nonnegative_array",
    "as_file_path",
]


def _short(value) -> str:
    """A value for an error message: an array by its shape and first element, never printed whole."""
    if np.ndim(value) == 0:
        return repr(value)
    a = np.asarray(value)
    return f"(an array of shape {a.shape}, first element {a.flat[0]!r})" if a.size else f"(an empty array {a.shape})"


def _refuse_non_real(value, name: str) -> None:
    """Raise ``ValueError`` for bools, complex numbers and strings (``float()`` would take them silently)."""
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    if np.iscomplexobj(value):
        raise ValueError(f"{name} must be real, got a complex value {_short(value)}")
    dtype = getattr(value, "dtype", None)
    if dtype is not None and dtype.kind in "bOSU":
        raise ValueError(f"{name} must be a real number (or an array of them), got dtype {dtype}")


def as_positive_scalar(value, name: str, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a finite float > 0 (or >= 0), else raise ``ValueError``.

    Bools, complex numbers, strings, lists and arrays of size != 1 are refused.
    """
    if type(value) is float and math.isfinite(value) and (value > 0.0 or (allow_zero and value == 0.0)):
        return value  # a plain finite float in range (the common case): nothing to convert
    _refuse_non_real(value, name)
    if np.ndim(value) != 0:
        raise ValueError(f"{name} must be a real number, got {value!r}")
    try:
        x = float(value)
    except (TypeError, ValueError, OverflowError):
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
    """Return ``value`` as a finite float array, else raise ``ValueError`` (complex, bool and string
    values are refused rather than cast)."""
    kind = type(value)
    if (kind is np.ndarray and value.dtype == np.float64) or kind is float or kind is np.float64:
        a = np.asarray(value, dtype=float)  # the common case: nothing to refuse (the same array for a float64 one)
        if not np.all(np.isfinite(a)):
            raise ValueError(f"{name} must be finite everywhere (got NaN or inf)")
        return a
    _refuse_non_real(value, name)
    if isinstance(value, (list, tuple)):
        try:
            items = np.asarray(value, dtype=object).ravel()
        except ValueError:
            raise ValueError(f"{name} must be a rectangular array of real numbers, got {value!r}") from None
        if any(isinstance(v, (bool, np.bool_, str, bytes, complex, np.complexfloating)) for v in items):
            raise ValueError(f"{name} must hold real numbers only, got {value!r}")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be numeric, got {value!r}") from None
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name} must be finite everywhere (got NaN or inf)")
    return a


def check_in_range(a, name: str, lo: float, hi: float, *, rtol: float = 1e-12) -> np.ndarray:
    """Check that every element of ``a`` lies in ``[lo, hi]``.

    Values outside by no more than ``rtol`` relative (round-off from a caller's
    arithmetic, e.g. ``q_s / q_l``) are clipped onto the interval.
    """
    if not (type(a) is np.ndarray and a.dtype == np.float64 and np.all(np.isfinite(a))):  # else: as it is
        a = as_float_array(a, name)
    slack_lo = rtol * max(abs(lo), 1.0)
    slack_hi = rtol * max(abs(hi), 1.0)
    if np.any(a < lo - slack_lo) or np.any(a > hi + slack_hi):
        bad = a[(a < lo - slack_lo) | (a > hi + slack_hi)].ravel()[0]
        raise ValueError(f"{name} must lie in [{lo:.17g}, {hi:.17g}], got {float(bad)!r}")
    return np.clip(a, lo, hi)


def as_nonnegative_array(value, name: str, *, allow_zero: bool = True) -> np.ndarray:
    """``value`` as a finite float array whose elements are all >= 0 (or > 0), else a ``ValueError``."""
    a = as_float_array(value, name)
    bad = a < 0.0 if allow_zero else a <= 0.0
    if np.any(bad):
        rel = ">=" if allow_zero else ">"
        raise ValueError(f"{name} must be {rel} 0 everywhere, got {float(a[bad].ravel()[0])!r}")
    return a


def as_file_path(path, name: str = "path") -> str:
    """``path`` as the name of an existing regular file (str); a ValueError otherwise.

    An int is refused rather than taken as a file descriptor (``open`` would then close the caller's file), and
    a folder is named as such.
    """
    import os

    if isinstance(path, (bool, int, np.integer)) or not isinstance(path, (str, bytes, os.PathLike)):
        raise ValueError(f"{name} must be a file name (str or path-like), got {type(path).__name__} {path!r}")
    path = os.fsdecode(os.fspath(path))
    if os.path.isdir(path):
        raise ValueError(f"{name}: {path!r} is a folder, expected a file")
    if not os.path.exists(path):
        raise ValueError(f"{name}: no such file {path!r}")
    return path
