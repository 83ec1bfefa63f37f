r"""The finite-volume operators of the ``"fv"`` solver on a uniform cell grid with absorbing walls.

Readable flux form (:func:`rhs`), its tridiagonal matrix (:func:`banded_operator`, :func:`apply_operator`), the
compact 4th-order mass matrix (:func:`apply_mass`, ``SPACES``), the batched tridiagonal solver (``_Tridiag``)
and the option values ``COUPLINGS``, ``LINALGS`` (the schemes themselves are data in ``solvers/schemes.py``).  The
scheme is described in ``fv/solver.py``; the spectral fast path that diagonalises these operators exactly is in
``fv/spectral.py`` and ``fv/dst.py``.
"""

from __future__ import annotations

import numpy as np
from scipy.linalg import lapack

__all__ = ["rhs", "wall_flux", "banded_operator", "apply_operator", "apply_mass", "SPACES"]


# -- the readable operator and the fast one ------------------------------------------------------
def rhs(P, dp):
    r"""dP/dτ of the semi-discrete heat equation, written as flux differences (readable path).

    Parameters
    ----------
    P : array, shape (..., n_p), 1/pressure
        Cell averages on a uniform grid of ``n_p`` cells on [0, p_max].
    dp : float, pressure
        Cell width.

    Returns
    -------
    ndarray, shape of ``P``, 1/(pressure^3)
        :math:`-(F_{i+1/2}-F_{i-1/2})/\Delta p` with :math:`F = -\tfrac12\partial_p P` and
        absorbing walls (ghost cells :math:`-\bar P_0`, :math:`-\bar P_{n_p-1}`).  Multiply by
        :math:`B_2 = S(A^*)\,dV/d\zeta` for dP0/dzeta (``E:diffusion_equ``, ``eq:new_B2``).
    """
    P = np.asarray(P, dtype=float)
    ghost_lo = -P[..., :1]  # P0 = 0 at the face p = 0
    ghost_hi = -P[..., -1:]  # P0 = 0 at the face p = p_max
    ext = np.concatenate([ghost_lo, P, ghost_hi], axis=-1)
    flux = -0.5 * np.diff(ext, axis=-1) / dp  # F at the n_p + 1 faces
    return -np.diff(flux, axis=-1) / dp


def wall_flux(P, dp):
    """Outflow rates (per unit τ) through p = 0 and p = p_max: ``(P[...,0]/dp, P[...,-1]/dp)``."""
    return P[..., 0] / dp, P[..., -1] / dp


def banded_operator(n_p: int, dp: float) -> np.ndarray:
    """The operator of :func:`rhs` in LAPACK/``solve_banded`` (1, 1) form, shape (3, n_p), 1/pressure^2."""
    k = 0.5 / dp**2
    ab = np.empty((3, n_p))
    ab[0] = k
    ab[2] = k
    ab[1] = -2.0 * k
    ab[1, 0] = ab[1, -1] = -3.0 * k
    ab[0, 0] = ab[2, -1] = 0.0
    return ab


def _tri_matvec(P, a, d, d_end, out):
    """out = T @ P along the last axis, T tridiagonal Toeplitz (a, d, a) with corner entries d_end.

    ``a``, ``d``, ``d_end`` are scalars or per-load columns of shape (n_loads, 1).
    """
    np.add(P[..., 2:], P[..., :-2], out=out[..., 1:-1])
    out[..., 1:-1] *= a
    out[..., 1:-1] += d * P[..., 1:-1]
    out[..., :1] = d_end * P[..., :1] + a * P[..., 1:2]
    out[..., -1:] = d_end * P[..., -1:] + a * P[..., -2:-1]
    return out


def apply_operator(P, k, out=None):
    """L @ P along the last axis (fast path of :func:`rhs`), ``k = 1/(2 dp^2)``."""
    if out is None:
        out = np.empty_like(P)
    out[..., 1:-1] = P[..., 2:] + P[..., :-2]
    out[..., 1:-1] -= 2.0 * P[..., 1:-1]
    out[..., 0] = P[..., 1] - 3.0 * P[..., 0]
    out[..., -1] = P[..., -2] - 3.0 * P[..., -1]
    out *= k
    return out


SPACES = {"fv2": (1.0, 0.0), "compact4": (10.0 / 12.0, 1.0 / 12.0)}
"""Space discretisation -> (diagonal, off-diagonal) of the mass matrix M of ``M dP/dtau = L P``."""


def apply_mass(P, space, out=None):
    """M @ P along the last axis (odd ghost cells at both walls); M = I for "fv2"."""
    md, mo = SPACES[space]
    if mo == 0.0:
        return P.copy() if out is None else np.copyto(out, P) or out
    if out is None:
        out = np.empty_like(P)
    out[..., 1:-1] = P[..., 2:] + P[..., :-2]
    out[..., 1:-1] *= mo
    out[..., 1:-1] += md * P[..., 1:-1]
    out[..., 0] = (md - mo) * P[..., 0] + mo * P[..., 1]
    out[..., -1] = (md - mo) * P[..., -1] + mo * P[..., -2]
    return out


class _Tridiag:
    """Solves (M - c_j L) X_j = B_j for every load j (c_j >= 0 per load, L from :func:`banded_operator`)."""

    def __init__(self, n_p: int, n_loads: int, k: float, space: str = "fv2"):
        self.n, self.m, self.k = n_p, n_loads, k
        self.md, self.mo = SPACES[space]
        self._cache_c = None
        self._lu = None
        self.solves = 0
        self.factorizations = 0

    def _diagonals(self, c):
        n, k = self.n, self.k
        d = np.empty(n)
        d[:] = self.md + 2.0 * c * k
        d[0] = d[-1] = self.md - self.mo + 3.0 * c * k
        off = np.full(n - 1, self.mo - c * k)
        return off, d

    def solve(self, c, B):
        """c : (n_loads,) ; B : (n_loads, n_p) C-contiguous.  Returns X of the same shape."""
        self.solves += 1
        if self.m == 1 or (c == c[0]).all():
            c0 = float(c[0])
            if self._cache_c is None or abs(c0 - self._cache_c) > 4e-16 * abs(c0):
                off, d = self._diagonals(c0)
                d, e, info = lapack.dpttrf(d, off)  # M - c L is symmetric positive definite: L D L^T
                self._lu = (d, e)
                self._cache_c = c0
                self.factorizations += 1
            X, info = lapack.dpttrs(*self._lu, B.T)
            return X.T
        # per-load steps: one stacked block-tridiagonal system of size n_loads * n_p
        n, k = self.n, self.k
        ck = (c * k)[:, None]
        d = np.empty((self.m, n))
        d[:] = self.md + 2.0 * ck
        d[:, 0] = d[:, -1] = (self.md - self.mo + 3.0 * ck)[:, 0]
        off = np.empty((self.m, n))
        off[:] = self.mo - ck
        off[:, -1] = 0.0  # no coupling between the blocks
        off = off.ravel()[:-1]
        self.factorizations += 1
        _, _, X, info = lapack.dptsv(d.ravel(), off, B.reshape(-1, 1))
        return X.reshape(self.m, n)


def march_result(stations, JN, r_max, dtau_total, counters: dict) -> dict:
    """What a march of ``"fv"`` hands back (every path: banded, DST stepping, DST exact in tau).

    ``stations``: a :class:`~persson_fp.solvers.base.StationRecorder` (or a dict) of ``P_out`` (n_st, m, n_p) and
    ``A_out``/``Af_out``/``JN_out`` (n_st, m): P0, the mass and the flux-accumulated area at each station and the
    plastic area gained; ``JN`` the last of these; ``r_max`` the largest diffusion number; ``dtau_total`` (m,) the
    effective variance marched; ``counters`` the work done (reported in ``info``).
    """
    return {
        **{key: stations[key] for key in ("P_out", "A_out", "Af_out", "JN_out")},
        "JN": JN,
        "r_max": r_max,
        "dtau_total": dtau_total,
        "counters": counters,
    }


COUPLINGS = ("auto", "lagged", "predictor", "picard")
LINALGS = ("auto", "dst", "banded")
