"""Validators of the solvers' options (cf. ``scipy.integrate._ivp.common``): a bad value is a ``ValueError`` that
names the option and its allowed range -- never ``bool("False")``, a NaN or an overflow further down."""

from __future__ import annotations

import numpy as np


def _is_real_scalar(value) -> bool:
    """A real number that is not a bool (bools, complex, strings, lists, arrays of size != 1 are not)."""
    if isinstance(value, (bool, np.bool_)):
        return False
    if isinstance(value, np.ndarray):
        return value.ndim == 0 and value.dtype.kind in "iuf"
    return isinstance(value, (int, float, np.integer, np.floating))


MAX_INT = 10**9
"""Upper bound of an integer option given without its own (grid sizes, steps, iterations, walkers)."""


def check_int(value, name: str, lo: int, hi: int | None = None) -> int:
    """An integer in [lo, hi] (hi default :data:`MAX_INT`) or a ``ValueError`` naming ``name`` and the range.

    Bools, complex numbers, strings, lists, NaN and inf are refused (never an ``OverflowError``);
    integral floats such as ``1e3`` are accepted.
    """
    if hi is None:  # no option is meant to be astronomically large: 1e300 iterations is a hang
        hi = MAX_INT
    rng = f"[{lo}, {hi}]"
    if not _is_real_scalar(value):
        raise ValueError(f"{name} must be an integer {rng}, got {value!r}")
    if isinstance(value, (float, np.floating, np.ndarray)):
        x = float(value)
        if not np.isfinite(x) or x != np.floor(x):
            raise ValueError(f"{name} must be an integer {rng}, got {x!r}")
    iv = int(value)
    if iv < lo or (hi is not None and iv > hi):
        raise ValueError(f"{name} must be an integer {rng}, got {iv!r}")
    return iv


def check_float(value, name: str, lo: float, hi: float = np.inf, *, lo_open: bool = True) -> float:
    """A finite float in (lo, hi] (or [lo, hi]) or a ``ValueError`` naming ``name`` and the range.

    Bools, complex numbers, strings and lists are refused.
    """
    br = "(" if lo_open else "["
    if not _is_real_scalar(value):
        raise ValueError(f"{name} must be a real number in {br}{lo:g}, {hi:g}], got {value!r}")
    x = float(value)
    ok = np.isfinite(x) and (x > lo if lo_open else x >= lo) and x <= hi
    if not ok:
        raise ValueError(f"{name} must lie in {br}{lo:g}, {hi:g}], got {x!r}")
    return x


def check_bool(value, name: str) -> bool:
    """``True``/``False`` (numpy bools too) or a ``ValueError`` naming ``name`` -- never ``bool("False")``."""
    if not isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be True or False, got {value!r}")
    return bool(value)


K_DOMAIN_MIN = 5.0
"""Smallest ``k_domain`` (far wall at max(p_bar) + k_domain sqrt(tau(zeta_max))) a grid method accepts:
the far wall then takes less than erfc(5/sqrt(2)) / 2 ~ 3e-7 of the mass, below the methods' default
accuracy; at k_domain = 1 it takes most of the load."""


def check_k_domain(value, hi: float = 100.0) -> float:
    """``k_domain`` in [K_DOMAIN_MIN, hi] or a ``ValueError`` naming it, the range and the reason."""
    k = check_float(value, "k_domain", 0.0, hi)
    if k < K_DOMAIN_MIN:
        raise ValueError(
            f"k_domain must lie in [{K_DOMAIN_MIN:g}, {hi:g}], got {k!r}: the far wall at p_bar + k_domain sqrt(tau) "
            "would absorb part of the load (the closed form has no far wall)"
        )
    return k
