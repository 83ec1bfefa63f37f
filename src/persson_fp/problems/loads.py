"""The loads of a problem: validation of ``p_bar`` (finite, > 0, representable when squared) and the warning for a
likely unit slip (p_bar above the contact modulus, deep in full contact)."""

from __future__ import annotations

import warnings

import numpy as np

from persson_fp._validate import as_float_array


def _check_loads(p_bar) -> np.ndarray:
    """``p_bar`` as a float array of shape () or (n,), every load finite, > 0 and <= 1e150 (pressure)."""
    if p_bar is None:
        raise ValueError("p_bar (nominal pressure, > 0) is required")
    pb = as_float_array(p_bar, "p_bar")
    if pb.ndim > 1:
        raise ValueError(f"p_bar must be a scalar or a 1-D array, got shape {pb.shape}")
    if pb.size == 0:
        raise ValueError("p_bar must hold at least one load")
    if np.any(pb <= 0):
        raise ValueError(f"p_bar must be > 0 (every load), got {float(pb[pb <= 0].ravel()[0])!r}")
    if np.any(pb > 1e150):
        raise ValueError(
            f"p_bar must be <= 1e150 (p_bar^2 must be representable; rescale units), got {float(pb.max())!r}"
        )
    return pb


def _warn_unit_slip(p_bar, E_star, V_max):
    """Warn when a load exceeds the contact modulus (p_bar / E_star > 1) deep in full contact (p_bar / sqrt(V) > 6,
    A* = 1 - 2e-9): usually E* and p_bar in other units (a steep test surface reaches p_bar > E* before that)."""
    ratio = float(np.max(p_bar)) / E_star
    if ratio > 1.0 and float(np.max(p_bar)) > 6.0 * V_max**0.5:
        warnings.warn(
            f"p_bar / E_star = {ratio:.3g} > 1 and p_bar / sqrt(V(zeta_max)) = {float(np.max(p_bar)) / V_max**0.5:.3g} "
            "(V = E_star^2 <|grad h|^2> / 4): the nominal pressure exceeds the contact modulus, where small-slope "
            "contact has p_bar << E_star and full contact already near p_bar = 3 sqrt(V); are p_bar and E_star in the "
            "same unit (e.g. E_star in GPa with p_bar in Pa)?",
            UserWarning,
            stacklevel=3,
        )
