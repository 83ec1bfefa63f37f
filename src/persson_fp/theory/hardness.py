r"""Hardness models: the yield stress sigma_Y(zeta) that caps the contact pressure.

In Persson's elastoplastic theory the contact pressure cannot exceed the penetration hardness
:math:`\sigma_Y`; the pressure PDF lives on :math:`0 < p < \sigma_Y(\zeta)` and what reaches the wall
becomes plastic contact area (Persson, Phys. Rev. Lett. 87 (2001) 116101; Persson, Surf. Sci. Rep. 61
(2006) 201, Sec. 3; the Xu et al. tutorial, section "Zero contact area paradox").  With a
constant hardness the elastic contact area still vanishes as zeta grows, but the plastic area tends
to p_bar / sigma_Y: the tutorial's zero-contact-area paradox is resolved.

A hardness model is an object with ``sigma(zeta)`` and ``dsigma_dzeta(zeta)`` (pressure), vectorised,
positive and non-decreasing in zeta (a size-dependent hardness that grows at small scales, e.g. the
power law sigma_1 zeta^n).  :func:`resolve` turns the user's ``hardness=`` argument into one:

=====================================  ===================================================
``None``                               purely elastic (no wall)
a number                               :class:`ConstantHardness` (the strip problem)
:class:`PowerLaw` ``(sigma_1, n)``     sigma_Y = sigma_1 zeta^n (n = 0: constant)
any callable ``sigma_Y(zeta)``         :class:`CallableHardness` (derivative numerically)
=====================================  ===================================================

This module imports no solver.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from persson_fp._validate import as_positive_scalar

__all__ = ["Hardness", "ConstantHardness", "PowerLaw", "CallableHardness", "resolve"]


class Hardness:
    """Base class: a yield stress sigma_Y(zeta) > 0 (pressure), non-decreasing in zeta."""

    name: str = "hardness"
    is_constant: bool = False
    """True when sigma_Y does not depend on zeta (a fixed wall: the strip problem with a closed form)."""

    def sigma(self, zeta) -> np.ndarray:  # pragma: no cover - abstract
        """sigma_Y at magnification(s) ``zeta`` (pressure)."""
        raise NotImplementedError

    def dsigma_dzeta(self, zeta) -> np.ndarray:  # pragma: no cover - abstract
        """d sigma_Y / d zeta (pressure)."""
        raise NotImplementedError

    def check(self, zeta_max: float, p_bar_max: float) -> None:
        """Raise ``ValueError`` unless sigma_Y is finite, > 0 and non-decreasing on [1, zeta_max]
        (checked on 257 log-spaced magnifications) and every load lies below sigma_Y(1)."""
        z = np.unique(np.concatenate(([1.0], np.geomspace(1.0, max(zeta_max, 1.0), 257))))
        try:
            s = np.asarray(self.sigma(z), dtype=float)
            ds = np.asarray(self.dsigma_dzeta(z), dtype=float)
        except (TypeError, ValueError, ArithmeticError) as err:
            raise ValueError(f"hardness: sigma_Y(zeta) could not be evaluated on [1, zeta_max]: {err}") from None
        if s.shape != z.shape or ds.shape != z.shape:
            raise ValueError("hardness: sigma_Y(zeta) must be vectorised (an array of zeta in, the same shape out)")
        if not (np.all(np.isfinite(s)) and np.all(np.isfinite(ds))):
            raise ValueError("hardness: sigma_Y(zeta) must be finite on [1, zeta_max]")
        if np.any(s <= 0):
            bad = z[s <= 0][0]
            raise ValueError(
                f"hardness: sigma_Y must be > 0 on [1, zeta_max], got {s[s <= 0][0]!r} at zeta = {bad:.6g}"
            )
        if np.any(np.diff(s) < -1e-12 * s[:-1]) or np.any(ds < -1e-9 * s / z):
            i = int(np.argmax(np.diff(s) < -1e-12 * s[:-1]))
            raise ValueError(
                "hardness: sigma_Y(zeta) must be non-decreasing in zeta (a yield wall may only move outwards), "
                f"got a decrease near zeta = {z[i]:.6g}"
            )
        if p_bar_max >= s[0]:
            raise ValueError(
                f"p_bar must be < sigma_Y(1) = {s[0]:.6g} (the nominal pressure cannot exceed the hardness), "
                f"got {p_bar_max:.6g}"
            )


class ConstantHardness(Hardness):
    """sigma_Y = ``sigma`` (pressure) at every magnification: a fixed absorbing wall."""

    is_constant = True

    def __init__(self, sigma: float):
        self.value = as_positive_scalar(sigma, "hardness sigma")
        self.name = f"constant({self.value:.6g})"

    def sigma(self, zeta) -> np.ndarray:
        return np.full(np.shape(zeta), self.value)

    def dsigma_dzeta(self, zeta) -> np.ndarray:
        return np.zeros(np.shape(zeta))

    def __repr__(self):
        return f"ConstantHardness({self.value:.6g})"


class PowerLaw(Hardness):
    """Size-dependent hardness sigma_Y = sigma_1 zeta^n (pressure), n >= 0.

    Parameters
    ----------
    sigma_1 : float, pressure
        Hardness at the largest scale (zeta = 1), > 0.
    n : float
        Exponent in [0, 2]; n = 0 is a constant hardness.  Indentation size effects give n of
        order 0.1-0.5 (Persson, Surf. Sci. Rep. 61 (2006) 201, Sec. 3.5).
    """

    def __init__(self, sigma_1: float, n: float):
        self.sigma_1 = as_positive_scalar(sigma_1, "sigma_1")
        try:
            n = as_positive_scalar(n, "n (hardness exponent)", allow_zero=True)
        except ValueError:
            n = None
        if n is None or n > 2.0:
            raise ValueError(f"n (hardness exponent) must lie in [0, 2], got {n!r}")
        self.n = n
        self.is_constant = n == 0.0
        self.name = f"power law ({self.sigma_1:.6g} zeta^{self.n:g})"

    def sigma(self, zeta) -> np.ndarray:
        return self.sigma_1 * np.asarray(zeta, dtype=float) ** self.n

    def dsigma_dzeta(self, zeta) -> np.ndarray:
        z = np.asarray(zeta, dtype=float)
        return self.n * self.sigma_1 * z ** (self.n - 1.0)

    def __repr__(self):
        return f"PowerLaw(sigma_1={self.sigma_1:.6g}, n={self.n:g})"


class CallableHardness(Hardness):
    """A user's sigma_Y(zeta) (pressure, vectorised); the derivative by central differences
    (relative step 1e-6 in ln zeta, ~1e-11 relative error for a smooth law) unless ``derivative`` is given."""

    def __init__(self, fun: Callable, derivative: Callable | None = None):
        if not callable(fun):
            raise ValueError(f"hardness must be None, a number, a Hardness or a callable sigma_Y(zeta), got {fun!r}")
        if derivative is not None and not callable(derivative):
            raise ValueError(f"derivative must be None or a callable dsigma_Y/dzeta, got {derivative!r}")
        self.fun = fun
        self.derivative = derivative
        self.name = getattr(fun, "__name__", "callable")

    def sigma(self, zeta) -> np.ndarray:
        z = np.asarray(zeta, dtype=float)
        return np.broadcast_to(np.asarray(self.fun(z), dtype=float), z.shape).copy()

    def dsigma_dzeta(self, zeta) -> np.ndarray:
        z = np.asarray(zeta, dtype=float)
        if self.derivative is not None:
            return np.broadcast_to(np.asarray(self.derivative(z), dtype=float), z.shape).copy()
        h = 1e-6
        return (self.sigma(z * np.exp(h)) - self.sigma(z * np.exp(-h))) / (z * 2.0 * np.sinh(h))

    def __repr__(self):
        return f"CallableHardness({self.name})"


def resolve(hardness) -> Hardness | None:
    """The :class:`Hardness` of a user's ``hardness=`` argument (see the module docstring), or None."""
    if hardness is None or isinstance(hardness, Hardness):
        return hardness
    if isinstance(hardness, (bool, np.bool_)):
        raise ValueError(f"hardness must be None, a number > 0, a Hardness or a callable, got {hardness!r}")
    if isinstance(hardness, (int, float, np.integer, np.floating)) or (
        isinstance(hardness, np.ndarray) and hardness.ndim == 0
    ):
        return ConstantHardness(float(hardness))
    if callable(hardness):
        return CallableHardness(hardness)
    raise ValueError(f"hardness must be None, a number > 0, a Hardness or a callable sigma_Y(zeta), got {hardness!r}")
