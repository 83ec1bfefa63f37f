r"""Persson's equation with general Fokker--Planck coefficients.

The Xu et al. tutorial derives Persson's diffusion equation as the forward Kolmogorov (Fokker--Planck) equation
of the pressure process, Eq. 'E:Fokker_Planck_Forward':

.. math::  \frac{\partial P}{\partial\zeta} = -\frac{\partial}{\partial p}\big[B_1(p,\zeta)P\big]
           + \frac12\frac{\partial^2}{\partial p^2}\big[B_2(p,\zeta)P\big],

and the homogenised theory is its special case :math:`B_1 = 0`, :math:`B_2 = dV/d\zeta` (the tutorial's
Eq. 'eq:B2_xi_1').  :class:`FokkerPlanckProblem` lets a user model more than that -- a pressure-dependent diffusion
(e.g. :math:`B_2 = (p/\bar p)^\alpha dV/d\zeta`) or a drift -- with the same walls: absorbing at p = 0 and, with a
hardness, the yield wall of :mod:`persson_fp.theory.hardness`.  No closed form exists: ``"fv"`` and ``"mol"``
solve it in conservative flux form, :math:`F = B_1P - \tfrac12\partial_p(B_2P)`, and report an error estimate with every
result.

This module imports no solver.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from persson_fp.problems.contact import ContactProblem

__all__ = ["FokkerPlanckProblem"]


class FokkerPlanckProblem(ContactProblem):
    r"""A contact problem with general drift B1(p, zeta) and diffusion B2(p, zeta).

    Parameters
    ----------
    psd, E_star, p_bar, hardness
        As for :class:`~persson_fp.ContactProblem` (the spectrum sets V(zeta), the magnification range and the
        default diffusion).
    B1 : callable or None, pressure per unit zeta
        Drift ``B1(p, zeta)``, vectorised in p (an array of pressures and a scalar zeta in, an array out).
        ``None``: 0.
    B2 : callable or None, pressure^2 per unit zeta
        Diffusion ``B2(p, zeta) >= 0``, vectorised in p.  ``None``: the homogenised dV/dzeta.
    fudge : None
        Must be None (B2 says everything about the diffusion; multiply a fudge factor into B2 if wanted).

    Raises
    ------
    ValueError
        A coefficient that is not callable, not vectorised, non-finite or (B2) negative on the probe grid (33
        pressures on [0, p_max] at 9 magnifications), naming the coefficient and where; a fudge factor (B2
        already says everything about the diffusion; put S into B2 if wanted).

    Notes
    -----
    The coefficients are checked again on every grid a solver evaluates them on (the same ``ValueError``).
    A solver sees the coefficients only where it samples them: ``fv`` and ``mol`` at their cells and steps,
    ``chebyshev`` at its nodes in p and at its probe magnifications and quadrature nodes in zeta.  A feature
    narrower than that sampling -- a spike of B2 in p thinner than a cell, a bump or step in zeta between two
    steps -- is not seen, and a run and its partner at another resolution can miss it alike, so that the error
    estimate does not contain it either (measured: a bump of relative width 0.3 % at zeta = 100 changed A* by
    1e-3 with estimates of 1e-8).  Keep the coefficients smooth on the scale of the grid, or check such a feature
    by hand with runs fine enough to resolve it (``n_p``, ``n_steps``).
    ``pf.exact`` has no closed form for this problem; ``Solution.compare`` is replaced by the solver's error
    estimate (``info["error_estimate"]``).
    """

    def __init__(
        self,
        psd,
        E_star: float = 1.0,
        p_bar=None,
        B1: Callable | None = None,
        B2: Callable | None = None,
        hardness=None,
        fudge=None,
    ):
        if fudge is not None:
            raise ValueError(
                "fudge must be None for a FokkerPlanckProblem: B2 defines the diffusion completely "
                "(multiply a fudge factor into B2 if wanted)"
            )
        for name, f in (("B1", B1), ("B2", B2)):
            if f is not None and not callable(f):
                raise ValueError(f"{name} must be None or a callable {name}(p, zeta), got {f!r}")
        object.__setattr__(self, "B1_fun", B1)
        object.__setattr__(self, "B2_fun", B2)
        super().__init__(psd, E_star=E_star, p_bar=p_bar, fudge=None, hardness=hardness)
        zeta = np.geomspace(1.0, self.zeta_max, 9)
        for z in zeta:
            hi = self.upper_wall.probe_end(float(z), lambda: self.p_max(8.0))
            self.coefficients(np.linspace(0.0, hi, 33), z)

    @property
    def general(self) -> bool:
        return True

    @property
    def features(self) -> frozenset:
        return super().features | {"general"}

    @property
    def conserved_load(self):
        return None

    def require_closed_form(
        self, remedy: str = "solve the problem numerically: pf.solve(problem, method='fv') (or 'mol')"
    ):
        raise ValueError(f"general Fokker-Planck coefficients (B1, B2) have no closed form; {remedy}")

    def require_elastic(self, what: str, remedy: str = "; use a ContactProblem") -> None:
        super().require_elastic(what, remedy)
        raise ValueError(
            f"{what} is the elastic theory's: a FokkerPlanckProblem with general coefficients (B1, B2) is not "
            f"covered{remedy}"
        )

    def with_loads(self, p_bar) -> FokkerPlanckProblem:
        """The same surface, coefficients and hardness with other load(s).

        Parameters
        ----------
        p_bar : float or 1-D array, pressure
            The new nominal pressure(s).

        Returns
        -------
        FokkerPlanckProblem
        """
        new = FokkerPlanckProblem(self.psd, self.E_star, p_bar, self.B1_fun, self.B2_fun, self.hardness)
        return new if new.response == self.response else new.with_response(self.response)

    def coefficients(self, p, zeta: float):
        """The coefficients at pressures ``p`` and magnification ``zeta``, checked.

        Parameters
        ----------
        p : array, pressure
            Pressures (any shape).
        zeta : float
            Magnification.

        Returns
        -------
        (ndarray, ndarray)
            B1 (pressure per unit zeta) and B2 (pressure^2 per unit zeta), the shape of ``p``.

        Raises
        ------
        ValueError
            A non-finite, complex or (B2) negative value, a coefficient that is not vectorised (wrong shape) or
            that raises, naming the coefficient and the (p, zeta) where.
        """
        p = np.asarray(p, dtype=float)
        z = float(zeta)
        out = []
        for name, f, default in (
            ("B1", self.B1_fun, lambda: np.zeros(p.shape)),
            ("B2", self.B2_fun, lambda: np.full(p.shape, float(self.dV_dzeta(z)))),
        ):
            if f is None:
                val = default()
            else:
                val = _evaluate(name, f, p, z)
            bad = ~np.isfinite(val)
            if name == "B2":
                bad |= val < 0
            if np.any(bad):
                i = int(np.argmax(bad))
                what = "finite and >= 0" if name == "B2" else "finite"
                raise ValueError(
                    f"{name} must be {what}: {name}(p = {p.flat[i]:.6g}, zeta = {z:.6g}) = {val.flat[i]!r}"
                )
            out.append(val)
        return out[0], out[1]

    def __repr__(self):
        names = [
            f"{k}={getattr(f, '__name__', 'callable')}" for k, f in (("B1", self.B1_fun), ("B2", self.B2_fun)) if f
        ]
        base = super().__repr__()
        return base.replace("ContactProblem(", "FokkerPlanckProblem(", 1)[:-1] + ", " + ", ".join(names) + ")"


def _where(p: np.ndarray, z: float) -> str:
    """The place of an evaluation, in words (for an error message)."""
    lo, hi = (float(np.min(p)), float(np.max(p))) if p.size else (0.0, 0.0)
    return f"p in [{lo:.6g}, {hi:.6g}], zeta = {z:.6g}"


def _evaluate(name: str, f, p: np.ndarray, z: float) -> np.ndarray:
    """``f(p, z)`` as a real float array of the shape of ``p``, or a ``ValueError`` naming ``name`` and where."""
    try:
        raw = f(p, z)
    except Exception as err:  # any failure of a user callable is bad input, reported with where it happened
        raise ValueError(
            f"{name}(p, zeta) could not be evaluated at {_where(p, z)}: {type(err).__name__}: {err}"
        ) from None
    if type(raw) is np.ndarray and raw.dtype == np.float64 and raw.shape == p.shape:
        return raw.copy()  # (the common case: no conversion, no check of the form)
    where = _where(p, z)
    try:
        arr = np.asarray(raw)
    except Exception as err:
        raise ValueError(f"{name}(p, zeta) returned {type(raw).__name__}, not an array of numbers ({where})") from err
    if arr.dtype.kind == "c":
        imag = np.abs(np.imag(arr))
        i = int(np.argmax(imag)) if imag.size else 0
        at = f"p = {float(p.flat[i]):.6g}, zeta = {z:.6g}" if arr.shape == p.shape and p.size else where
        value = arr.flat[i] if arr.size else "an empty array"
        raise ValueError(f"{name} must be real: {name}({at}) = {value!r} is complex")
    if arr.dtype.kind not in "biuf":
        raise ValueError(f"{name}(p, zeta) must return real numbers, got dtype {arr.dtype} at {where}")
    arr = arr.astype(float)
    if arr.shape != p.shape:
        try:
            if arr.ndim > p.ndim:
                raise ValueError
            arr = np.broadcast_to(arr, p.shape).astype(float)
        except ValueError:
            raise ValueError(
                f"{name}(p, zeta) must be vectorised in p (shape {p.shape}), got shape {arr.shape} at {where}"
            ) from None
    return arr
