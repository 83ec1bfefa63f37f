r"""Finite volumes in p, θ-schemes (and TR-BDF2) in the effective variance.

The method
----------
Persson's equation (``E:diffusion_equ`` with ``eq:new_B2``)

.. math::  \frac{\partial P_0}{\partial\zeta} = \tfrac12 B_2(\zeta)\,\frac{\partial^2 P_0}{\partial p^2},
           \qquad B_2 = S(A^*)\,\frac{dV}{d\zeta}, \qquad A^* = \int_0^{p_{max}} P_0\,dp \quad (\texttt{eq:Area})

is written in the effective variance :math:`d\tau = S(A^*)\,dV`: every step is a step
:math:`\Delta\tau` of the plain heat equation :math:`\partial_\tau P_0 = \tfrac12\partial_p^2 P_0`,
and the fudge factor only decides how large :math:`\Delta\tau` is for a given :math:`\Delta V`
(the *coupling*, below).

*Space.*  ``n_p`` cells of width :math:`\Delta p = p_{max}/n_p` on :math:`[0, p_{max}]`, unknowns the
cell averages :math:`\bar P_i`.  The flux through face :math:`i+\tfrac12` is
:math:`F_{i+1/2} = -\tfrac12(\bar P_{i+1}-\bar P_i)/\Delta p` and
:math:`d\bar P_i/d\tau = -(F_{i+1/2}-F_{i-1/2})/\Delta p` (:func:`rhs`).  Both walls absorb
(:math:`P_0 = 0` at the face): ghost values :math:`\bar P_{-1} = -\bar P_0`,
:math:`\bar P_{n_p} = -\bar P_{n_p-1}`.  Because the exact solution is odd about p = 0
(image solution, ``eq:P0_solution``), the ghost cell *is* the cell average of the odd extension,
so the wall costs no order: the scheme is 2nd order in p everywhere.  The wall fluxes
:math:`\bar P_0/\Delta p` and :math:`\bar P_{n_p-1}/\Delta p` are integrated with the same
time-stepping weights as the cells, so :math:`\sum_i \bar P_i\,\Delta p + J_0 + J_{max}` is conserved
to round-off and :math:`A^*(\zeta_0) - J_0` is reported as ``contact_area_flux``; the far-wall
loss :math:`J_{max}` is reported in ``info["far_wall_mass"]``.  The load ``eq:Load_equilibrium``
is conserved by the p = 0 wall exactly, so its drift measures the far-wall and truncation error.

*Time.*  A θ-step with the tridiagonal operator :math:`L` (:func:`banded_operator`),

.. math::  (I - \theta\,\Delta\tau\,L)\,P^{n+1} = (I + (1-\theta)\,\Delta\tau\,L)\,P^n ,

with θ = 0 ("explicit", stable for :math:`r = \tfrac12\Delta\tau/\Delta p^2 \le \tfrac12`),
θ = 1/2 ("crank-nicolson"), θ = 1 ("implicit", backward Euler), "rannacher" (θ = 1/2 after
``rannacher_steps`` steps each done as two backward-Euler half steps) and "tr-bdf2" (an L-stable
2nd-order one-step method: a trapezoidal stage over :math:`\gamma\Delta\tau` then BDF2, with
:math:`\gamma = 2-\sqrt2` so that both stages share one matrix; from ``initial="delta"`` its first
``rannacher_steps`` steps are backward-Euler half steps, because L-stability does not make it positive:
its amplification factor is negative for :math:`\Delta\tau|\lambda| \gtrsim 2.4`, and no 2nd-order
one-step scheme is positive for every step size).  All loads are advanced together
(``P`` has shape ``(n_loads, n_p)``) on one grid sized by the largest load: when all loads share
:math:`\Delta\tau` (S = 1) one factorisation (LAPACK ``pttrf``; the matrix is symmetric positive
definite) serves all of them and is re-used while :math:`\Delta\tau` repeats (uniform steps);
otherwise the per-load systems are stacked into one block-tridiagonal solve (``ptsv``),
O(n_p n_loads) per step.  This is the ``linalg="banded"`` path; the default is the spectral one below.

*Space, 4th order* (``space="compact4"``, the default).  The same fluxes with the compact mass
matrix :math:`M = \mathrm{tridiag}(1, 10, 1)/12` (``M dP/dtau = L P``, odd ghosts again), which is
the 4th-order reconstruction of the face derivative from cell averages; ``space="fv2"`` is
M = I (2nd order).  Every θ-step above reads :math:`(M - \theta\Delta\tau L)P^{n+1} =
(M + (1-\theta)\Delta\tau L)P^n`.  Here :math:`\sum_i (MP)_i\Delta p + J_0 + J_{max}` is the
conserved quantity, and ``contact_area_flux`` adds the known edge term
:math:`\tfrac16\Delta p\,(\bar P_0 - \bar P_0^{\,start})`, so the mass balance still closes to round-off.

*The spectral fast path* (``linalg="dst"``, the default through "auto").  With odd ghost cells at
*both* walls, L and M are diagonalised exactly by the orthonormal DST-II basis (cell-centred sines
:math:`\phi_j(i) \propto \sin(\pi j (i+\tfrac12)/n_p)`, j = 1..n_p, odd about both wall faces, so
the ghost rules hold for every j; the compact end rows (9, 1)/12 are exactly M's odd-ghost rows):

.. math::  L\phi_j = \mu_j\phi_j,\quad \mu_j = -\frac{2}{\Delta p^2}\sin^2\frac{\pi j}{2n_p}, \qquad
           M\phi_j = m_j\phi_j,\quad m_j = m_d + 2m_o\cos\frac{\pi j}{n_p}
           \;\big(\text{compact4: } (10 + 2\cos(\pi j/n_p))/12\big)

(:func:`dst_eigenvalues`; checked against the dense matrices to 1e-15 in the tests).  So every
step above multiplies coefficient j by a rational amplification factor of
:math:`x_j = \Delta\tau\,\lambda_j`, :math:`\lambda_j = \mu_j/m_j` (:func:`_amplification`):
θ-step :math:`R = (1+(1-\theta)x)/(1-\theta x)`; Rannacher start :math:`(1-x/2)^{-2}`; TR-BDF2,
whose two stages share :math:`1-h`, :math:`h = \gamma x/2`: :math:`R = (1+(A+B)h)/(1-h)^2` with
the BDF2 weights A, B (A - B = 1).  Without a fudge factor a whole run is
:math:`P_N = S^{-1}\,\mathrm{diag}(\prod_k R_k)\,S P_0` (one ``scipy.fft.dst`` and one ``idst`` for
all stations and loads).  With one, :math:`\Delta\tau_k` depends on the numerical
:math:`A^* = \sum_i\bar P_i\Delta p` and (predictor) on the wall flux, both linear functionals
of the coefficients (:math:`\langle v, P\rangle = \langle Sv, SP\rangle`, S orthogonal), so the
march stays in coefficient space: O(n_p n_loads) array operations a step, no solve and no
transform; P is transformed back only at the output stations.  For the lagged and predictor couplings
(whose :math:`\Delta\tau_n` depends on the state before step n only) the whole sequence of steps is
found at once, as the fixed point of a causal map solved by 3-8 Newton sweeps over the trajectory
(``FiniteVolumeSolver._fudge_trajectory``: each sweep one cumulative product over steps x modes, the
Jacobian approximated by the wall outflux), then the run is the closed form above.  This is done for up to
three loads (``_fudge_trajectory_max_loads``, ``_TRAJECTORY_SIZE`` numbers at most); larger batches march step by
step, vectorised over the loads, which is faster from about five loads on (``benchmarks/fv_timing.py``, last
table), as do runs with fewer than 16 steps and ``"picard"``.  Either way it is the banded path's
discrete solution to ~1e-13.  The wall fluxes are functionals too, accumulated with the scheme's stage
weights (per-mode weight F(x)), so ``contact_area_flux`` and ``far_wall_mass`` are the banded path's to
round-off.  The stability checks run on coefficients: non-finite values, negative or growing A* (as the
conserved sum(M P) dp), and growth of :math:`\|P\|_2 = \|c\|_2` (which :math:`|R_j| \le 1` makes
non-increasing) instead of max |P|; an explicit step past its limit (:math:`|R_j| > 1` for the top
modes) still raises :class:`InstabilityError`.  The fast path is
exact for every option of this solver, so "auto" always picks it; ``linalg="banded"`` keeps the
tridiagonal solves below as the readable reference (the two agree to ~1e-14 of max P0).  It would
stop being exact with a wall that is not odd (a reflecting far wall, another basis) or a
non-uniform grid in p.  Coefficients below 1e-200 of :math:`\|P_0\|_2` are set to zero (the top
modes would otherwise decay into subnormal numbers, ~100x slower arithmetic).  Measured
(``benchmarks/fv_timing.py``): 1.9-13x faster than the banded path for one load without a fudge
factor and 3.8-7.9x with YP08 (the trajectory sweeps), where the set-up (start-up data and nodes, ~1 ms)
is a large part of the time, and 6.4-7.3x for 1000 loads with YP08 (step by step, vectorised over the
loads).

*Stepping* (measured on the reference problem, ``benchmarks/fv_timing.py``): nodes uniform in the
effective variance ("tau") beat geometric and uniform-in-zeta nodes by 3-4x in error at equal
cost at zeta_max, because the error made early is damped by the later diffusion, but they starve
early output stations; the default "graded" is uniform in tau + 0.05 tau_max ln tau: within 4 %
of "tau" at zeta_max and 30x better at the worst of 24 stations.

*Coupling of the fudge factor* (``eq:new_B2``), with :math:`A^*` always the numerical
:math:`\sum\bar P_i\Delta p`:

``"lagged"``     :math:`\Delta\tau = S(A^*_n)\,\Delta V` (1st order; default of "explicit" and "implicit").
``"predictor"``  Heun: :math:`A^p = A^*_n - \Delta V\,S(A^*_n)\,b_n` from the current wall flux
                 :math:`b_n`, then :math:`\Delta\tau = \tfrac12\Delta V\,(S(A^*_n)+S(A^p))` (2nd order,
                 one solve per step; default of "crank-nicolson", "rannacher" and "tr-bdf2").
``"picard"``     the trapezoidal rule :math:`\Delta\tau = \tfrac12\Delta V\,(S(A^*_n)+S(A^*_{n+1}))`
                 iterated to ``picard_tol`` (starting from the predictor; 2nd order).

Without a fudge factor :math:`\Delta\tau = \Delta V` exactly and the coupling does nothing.

References
----------
.. [1] B.N.J. Persson, J. Chem. Phys. 115 (2001) 3840 (``E:diffusion_equ``).
.. [2] R.E. Bank et al., "Transient simulation of silicon devices and circuits", IEEE Trans.
       CAD 4 (1985) 436 (TR-BDF2).
.. [3] R. Rannacher, "Finite element solution of diffusion problems with irregular data",
       Numer. Math. 43 (1984) 309.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import fft as _fft
from scipy.linalg import lapack

from ..exact import tail_mass
from ..fudge import NoFudge
from ..solution import InstabilityError
from .base import Solver, SolverOutput, check_float, check_int

__all__ = ["FiniteVolumeSolver", "SCHEMES", "rhs", "banded_operator", "apply_operator", "dst_eigenvalues"]


# -- the scheme table: a scheme is data -----------------------------------------------------------
@dataclass(frozen=True)
class _Scheme:
    theta: float
    """Implicitness θ of the θ-step (TR-BDF2: θ of its first stage)."""
    order: int
    """Order in τ."""
    l_stable: bool
    coupling: str
    """Default coupling of the fudge factor (see the module docstring)."""


SCHEMES = {
    "explicit": _Scheme(theta=0.0, order=1, l_stable=False, coupling="lagged"),
    "implicit": _Scheme(theta=1.0, order=1, l_stable=True, coupling="lagged"),
    "crank-nicolson": _Scheme(theta=0.5, order=2, l_stable=False, coupling="predictor"),
    "rannacher": _Scheme(theta=0.5, order=2, l_stable=False, coupling="predictor"),
    "tr-bdf2": _Scheme(theta=0.5, order=2, l_stable=True, coupling="predictor"),
}
"""Scheme name -> θ, order in τ, L-stability and default coupling."""

_GAMMA = 2.0 - np.sqrt(2.0)
"""TR-BDF2 stage fraction; makes the trapezoidal and BDF2 matrices equal."""
_BDF2_A = 1.0 / (_GAMMA * (2.0 - _GAMMA))
_BDF2_B = (1.0 - _GAMMA) ** 2 / (_GAMMA * (2.0 - _GAMMA))
_BDF2_W = (1.0 - _GAMMA) / (2.0 - _GAMMA)  # = GAMMA / 2

STEPPINGS = ("geometric", "zeta", "tau", "graded")
_GRADE = 0.05
"""'graded' stepping: uniform in s = tau + _GRADE tau_max ln(tau) (geometric below _GRADE tau_max, uniform above)."""
COUPLINGS = ("auto", "lagged", "predictor", "picard")
LINALGS = ("auto", "dst", "banded")
_FLUSH = 1e-200
"""DST path: coefficients (relative to ||P0||_2) below this are set to 0.  The top modes decay by
|R| << 1 a step into the subnormal range, where arithmetic is ~100x slower (measured: 10 ms instead
of 1.3 ms a step for 1000 loads); 1e-200 of the data is far below round-off."""
_TRAJECTORY_SIZE = 2_000_000
"""DST path with a fudge factor: runs of at most ``_fudge_trajectory_max_loads`` loads with n_loads x n_steps x n_p
up to this many numbers solve the coupling for the whole trajectory at once (FiniteVolumeSolver._fudge_trajectory);
others march step by step (vectorised over the loads, which amortises the per-step overhead there)."""
_fudge_trajectory_max_loads = 3
"""Most loads solved by the whole-trajectory coupling; larger batches march step by step, vectorised over
the loads (benchmarks/fv_timing.py times both for 1-10 loads: break-even near 5 loads)."""
_TRAJECTORY_MIN_STEPS = 16
"""Below this many steps the step-by-step march is as cheap as the 4-8 sweeps of the trajectory."""
_TRAJECTORY_SWEEPS = 30
_TRAJECTORY_TOL = 1e-14
"""Converged when every step's residual is below this fraction of the load's largest step."""


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


# -- the spectral fast path: L and M are diagonal in the DST-II basis ------------------------------
def dst_eigenvalues(n_p: int, dp: float, space: str = "fv2"):
    r"""Eigenvalues of L (:func:`banded_operator`) and of M (:func:`apply_mass`) in the DST-II basis.

    Both are diagonalised *exactly* by the orthonormal cell-centred sines
    :math:`\phi_j(i) \propto \sin(\pi j (i+\tfrac12)/n_p)`, j = 1..n_p (odd about both walls, so the
    odd ghost cells hold for every j):
    :math:`\mu_j = -\frac{2}{\Delta p^2}\sin^2\frac{\pi j}{2 n_p}` and
    :math:`m_j = m_d + 2 m_o \cos\frac{\pi j}{n_p}` (compact4: :math:`(10 + 2\cos(\pi j/n_p))/12`).

    Returns
    -------
    mu : ndarray (n_p,), 1/pressure^2
    m : ndarray (n_p,)
    """
    j = np.arange(1, n_p + 1)
    s2 = np.sin(0.5 * np.pi * j / n_p) ** 2
    md, mo = SPACES[space]
    return -(2.0 / dp**2) * s2, md + 2.0 * mo * (1.0 - 2.0 * s2)


class _Spectral:
    """The DST-II pair of the fast path and the linear functionals it needs in coefficient space."""

    def __init__(self, n_p: int, dp: float, space: str):
        mu, m_eig = dst_eigenvalues(n_p, dp, space)
        self.lam = mu / m_eig  # eigenvalues of M^-1 L
        self.transforms = 0
        unit = np.zeros((3, n_p))
        unit[0] = 1.0  # sum_i P_i
        unit[1, 0] = 1.0  # P_0 (wall p = 0)
        unit[2, -1] = 1.0  # P_{n-1} (wall p = p_max)
        E = self.forward(unit)  # <v, P> = <S v, S P> (S orthogonal)
        # a 4th (zero) column: with 3, numpy's matmul of (1000, 250) @ (250, 3) is ~20x slower than with 4
        self.functionals = np.ascontiguousarray(np.stack([E[0] * dp, E[1] / dp, E[2] / dp, 0.0 * E[0]], axis=1))
        """(n_p, 4): coefficients -> (sum P dp, wall flux at 0, wall flux at p_max, 0)."""
        self.transforms = 0  # count the run's transforms only

    def forward(self, P):
        self.transforms += 1
        return _fft.dst(P, type=2, norm="ortho", axis=-1)

    def inverse(self, C):
        self.transforms += 1
        return _fft.idst(C, type=2, norm="ortho", axis=-1)


def _amplification(kind: str, theta: float, x, work=None):
    r"""Per-mode amplification R and wall-flux weight F of one step, with x = dtau lambda_j.

    One step maps the DST coefficient :math:`c_j` to :math:`R_j c_j`; the outflow through a wall
    over the step is :math:`\Delta\tau\sum_j F_j c_j \phi_j(\text{wall})/\Delta p`, F being the
    scheme's stage weights applied to the wall flux (exactly what the banded path accumulates).
    ``kind``: "theta" (θ-step), "be-halves" (two backward-Euler half steps, the Rannacher start)
    or "tr-bdf2".  ``work``: optional three arrays of x's shape (R, F, scratch) written in place
    (no temporaries: for 1000 loads allocating them costs more than the arithmetic).
    """
    R, F, T = work if work is not None else (np.empty_like(x), np.empty_like(x), np.empty_like(x))
    if kind == "tr-bdf2":
        # both stages share 1 - h, h = gamma x / 2 = W x: the trapezoidal stage is Rs = (1 + h)/(1 - h),
        # then R = (A Rs - B)/(1 - h) = (1 + (A + B) h)/(1 - h)^2 (A - B = 1) and the wall-flux weight
        # F = (A gamma / 2)(Rs + 1) + W R = A gamma/(1 - h) + W R
        np.multiply(x, -_BDF2_W, out=T)
        T += 1.0
        np.divide(1.0, T, out=T)  # 1/(1 - h)
        np.multiply(x, (_BDF2_A + _BDF2_B) * _BDF2_W, out=R)
        R += 1.0
        R *= T
        R *= T
        np.multiply(R, _BDF2_W, out=F)
        T *= _BDF2_A * _GAMMA
        F += T
    elif kind == "be-halves":
        np.multiply(x, -0.5, out=T)
        T += 1.0
        np.divide(1.0, T, out=T)  # Rh
        np.multiply(T, T, out=R)
        np.add(T, R, out=F)
        F *= 0.5
    else:
        np.multiply(x, -theta, out=T)
        T += 1.0  # 1 - theta x
        np.multiply(x, 1.0 - theta, out=R)
        R += 1.0
        R /= T
        np.multiply(R, theta, out=F)
        F += 1.0 - theta
    return R, F


def _growth(kind: str, theta: float, x):
    """The amplification factor R of :func:`_amplification` alone (no wall-flux weight): the trajectory
    sweeps of the fudge coupling need only R."""
    if kind == "tr-bdf2":
        T = 1.0 / (1.0 - _BDF2_W * x)
        return (1.0 + ((_BDF2_A + _BDF2_B) * _BDF2_W) * x) * (T * T)
    if kind == "be-halves":
        T = 1.0 / (1.0 - 0.5 * x)
        return T * T
    return (1.0 + (1.0 - theta) * x) / (1.0 - theta * x)


class FiniteVolumeSolver(Solver):
    r"""Cell-centred finite volumes with θ-schemes / TR-BDF2 (see the module docstring).

    Options
    -------
    n_p : int, default 200
        Cells on [0, p_max].
    n_steps : int, default 100
        Steps from zeta0 to the last output station (shared over the stations' segments).
    scheme : str, default "tr-bdf2"
        "explicit" | "implicit" | "crank-nicolson" | "rannacher" | "tr-bdf2".
    stepping : str, default "graded"
        Node placement, by the closed-form tau(V) of each load (the coupling still uses the
        numerical A*): "graded" (uniform in s = tau + 0.05 tau_max ln tau: geometric while tau is
        small, uniform in tau later), "tau" (uniform in the effective variance), "geometric"
        (uniform in ln V) or "zeta" (uniform in zeta).  Measured on the reference problem with
        the default 100 steps, ``benchmarks/fv_stepping.py`` (L1 at zeta_max / worst over the
        stations): one station 5.8e-6 ("graded") vs 5.6e-6 ("tau"); 24 stations from zeta = 1.5:
        8.2e-6 / 7.4e-4 vs 6.7e-6 / 2.1e-2 ("tau") and 5.7e-5 / 1.3e-3 ("geometric").
        Uniform-in-tau steps are the cheapest for zeta_max alone (early errors are damped by the
        later diffusion) but starve early stations; the grading keeps the relative step dtau/tau
        bounded near the start.
    space : str, default "compact4"
        "compact4" (4th order in p) or "fv2" (2nd order in p, M = I).
    coupling : str, default "auto"
        "lagged" | "predictor" | "picard"; "auto" is the scheme's own (``SCHEMES``).
    picard_tol, picard_maxiter : float, int
        Relative tolerance on dtau and iteration cap of ``coupling="picard"``.
    initial : str, default "exact"
        "exact": exact cell averages at zeta0; "delta": one cell of mass 1 at p_bar at zeta = 1.
    zeta0, tau0_fraction : float
        Start of "exact": zeta0 given, else where tau = ``tau0_fraction`` tau(zeta_max) (largest
        load; lowered to half the first station's tau if needed).  The start is exact, so zeta0
        enters the error only through the steps spent after it.
    k_domain : float, default 8
        p_max = max(p_bar) + k_domain sqrt(tau(zeta_max)) (``ContactProblem.p_max``).
    rannacher_steps : int, default 2
        Steps of "rannacher", and of "tr-bdf2" from ``initial="delta"``, done as two backward-Euler
        half steps (damps the rough start; TR-BDF2's amplification factor is negative for large
        steps, so from a one-cell delta it would ring: -0.41 of the peak at r >= 36 without it).
    allow_unstable : bool, default False
        Let "explicit" run past r = 1/2 (then an :class:`InstabilityError` is expected).
    check_every : int, default 10
        Steps between stability checks (NaN, mass growth, max |P0| growth; the l2 norm of P0 on the
        "dst" path).
    linalg : str, default "auto"
        "dst": the spectral fast path (the same discrete solution to round-off, see the module
        docstring); "banded": the tridiagonal solves (readable reference); "auto": "dst" whenever
        it is exact for the chosen options, which is every combination this solver offers.
    """

    name = "fv"
    OPTIONS = {
        "n_p": 200,
        "n_steps": 100,
        "scheme": "tr-bdf2",
        "stepping": "graded",
        "coupling": "auto",
        "picard_tol": 1e-12,
        "picard_maxiter": 20,
        "initial": "exact",
        "zeta0": None,
        "tau0_fraction": 0.05,
        "k_domain": 8.0,
        "space": "compact4",
        "rannacher_steps": 2,
        "allow_unstable": False,
        "check_every": 10,
        "linalg": "auto",
    }

    def validate(self) -> None:
        o = self.opts
        o["n_p"] = check_int(o["n_p"], "n_p", 4)
        o["n_steps"] = check_int(o["n_steps"], "n_steps", 1)
        for key, allowed in (
            ("scheme", tuple(SCHEMES)),
            ("stepping", STEPPINGS),
            ("coupling", COUPLINGS),
            ("initial", ("exact", "delta")),
            ("space", tuple(SPACES)),
            ("linalg", LINALGS),
        ):
            if o[key] not in allowed:
                raise ValueError(f"{key} must be one of {list(allowed)}, got {o[key]!r}")
        o["picard_tol"] = check_float(o["picard_tol"], "picard_tol", 0.0, 1.0)
        o["picard_maxiter"] = check_int(o["picard_maxiter"], "picard_maxiter", 1)
        o["rannacher_steps"] = check_int(o["rannacher_steps"], "rannacher_steps", 0)
        o["check_every"] = check_int(o["check_every"], "check_every", 1)
        self.validate_start_options()

    # -- set-up --------------------------------------------------------------------------------
    def _start(self):
        """(zeta0, V0, P_init (n_loads, n_p), A_init (n_loads,)) on the grid ``self.edges``."""
        pr = self.problem
        z0, V0, P, A = self.initial_cell_averages(self.edges)
        self._tau0 = np.asarray(pr.tau_of_V(V0), dtype=float).reshape(pr.n_loads)
        self._hard = pr.hardness is not None
        self._A_pl0 = np.zeros(pr.n_loads)
        if self._hard and self.opts["initial"] == "exact":  # the yield wall may have absorbed a little already
            self._A_pl0 = np.asarray(self.exact_at(z0).plastic_area, dtype=float).reshape(pr.n_loads)
        return z0, V0, P, A

    def _zeta_of_V(self, V) -> float:
        """Magnification where V(zeta) = V (1 for V <= 0)."""
        return float(self.zeta_from_V(V)[0])

    def _nodes(self, V0):
        """V at the step nodes, shape (n_nodes, n_loads); every station is a node."""
        o, pr = self.opts, self.problem
        V_st = np.concatenate(([V0], self.V_out))
        z_st = np.concatenate(([self.zeta0], self.zeta_out))
        m = pr.n_loads
        if o["stepping"] == "zeta":
            s = z_st
        elif o["stepping"] == "geometric":
            s = np.log(np.maximum(V_st, 1e-3 * V_st[1]))
        else:  # tau of the largest-tau load decides the split; nodes per load below
            s = np.max(pr.tau_of_V(V_st), axis=-1)
            if o["stepping"] == "graded":  # (the offset 1e-3 g keeps a delta start, tau = 0, finite)
                tau_st, g = s, _GRADE * s[-1]
                s = tau_st + g * np.log(tau_st + 1e-3 * g)
        lengths = np.diff(s)
        n_seg = len(lengths)
        counts = np.maximum(1, np.round(o["n_steps"] * lengths / max(s[-1] - s[0], 1e-300)).astype(int))
        while counts.sum() > max(o["n_steps"], n_seg):
            counts[np.argmax(counts)] -= 1
        while counts.sum() < o["n_steps"]:
            counts[np.argmax(lengths / counts)] += 1
        pieces = [np.full((1, m), V_st[0])]
        for i in range(n_seg):
            t = np.linspace(0.0, 1.0, counts[i] + 1)[1:]
            Va, Vb = V_st[i], V_st[i + 1]
            if o["stepping"] == "zeta":
                V = np.atleast_1d(pr.V(z_st[i] + t * (z_st[i + 1] - z_st[i])))[:, None] * np.ones(m)
            elif o["stepping"] == "geometric":
                lo = max(Va, 1e-3 * V_st[1])
                V = np.exp(np.log(lo) + t * (np.log(Vb) - np.log(lo)))[:, None] * np.ones(m)
            elif o["stepping"] == "graded":  # uniform in s within the segment, mapped to tau fractions
                ta, tb = tau_st[i], tau_st[i + 1]
                tt = ta + np.geomspace(1e-3 * g, tb - ta + 1e-3 * g, 513) - 1e-3 * g
                ss = tt + g * np.log(tt + 1e-3 * g)
                tau_t = np.interp(s[i] + t * (s[i + 1] - s[i]), ss, tt)
                V = self._uniform_tau_nodes(Va, Vb, (tau_t - ta) / max(tb - ta, 1e-300))
            else:
                V = self._uniform_tau_nodes(Va, Vb, t)
            V[-1] = Vb  # land on the station exactly
            pieces.append(V)
        return np.concatenate(pieces, axis=0), np.cumsum(counts)

    def _uniform_tau_nodes(self, Va, Vb, t):
        """V nodes at the tau fractions ``t`` between tau(Va) and tau(Vb), per load, shape (len(t), n_loads).

        The closed-form tau of each load, inverted exactly (:meth:`~persson_fp.ContactProblem.V_of_tau_each`).
        """
        pr = self.problem
        if Vb <= Va:
            return np.full((t.size, pr.n_loads), Vb)
        if isinstance(pr.fudge, NoFudge):
            return (Va + t * (Vb - Va))[:, None] * np.ones(pr.n_loads)
        ta, tb = pr.tau_of_V(np.array([Va, Vb]))  # (n_loads,) each
        V = pr.V_of_tau_each(ta + t[:, None] * (tb - ta))
        return np.minimum(np.maximum(V, Va), Vb)  # (round-off of the inverse table kept inside the segment)

    # -- the run ---------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        o, pr = self.opts, self.problem
        scheme = SCHEMES[o["scheme"]]
        coupling = scheme.coupling if o["coupling"] == "auto" else o["coupling"]
        no_fudge = isinstance(pr.fudge, NoFudge)
        S = pr.fudge.S

        self.n_p = N = o["n_p"]
        self.edges, self.dp = self.cell_grid(N)
        dp, p_max = self.dp, self.edges[-1]
        p = 0.5 * (self.edges[1:] + self.edges[:-1])

        linalg = "banded" if o["linalg"] == "banded" else "dst"  # dst is exact for every option here
        self.zeta0, V0, P, A0 = self._start()
        V_nodes, station_idx = self._nodes(V0)
        n_steps = V_nodes.shape[0] - 1

        space = o["space"]
        compact = space != "fv2"
        r_limit = 1.0 / 3.0 if compact else 0.5  # explicit: dtau max|eig(M^-1 L)| <= 2
        w_edge = 1.0 - SPACES[space][0]  # sum(M P) = sum(P) - w_edge (P_0 + P_-1)
        # explicit-scheme limit, checked up front with the largest possible dtau
        if scheme.theta == 0.0:
            S_hi = 1.0 if no_fudge else float(np.max(S(np.linspace(0.0, 1.0, 201))))
            r_pred = 0.5 * S_hi * float(np.max(np.diff(V_nodes, axis=0))) / dp**2
            if r_pred > r_limit and not o["allow_unstable"]:
                raise ValueError(
                    f"explicit scheme: r = dtau/(2 dp^2) = {r_pred:.4g} exceeds the stability limit "
                    f"{r_limit:.4g} ({space}); raise n_steps to >= {int(np.ceil(n_steps * r_pred / r_limit))}, "
                    "lower n_p, or use "
                    "scheme='tr-bdf2' / 'implicit' (or pass allow_unstable=True)"
                )

        P_far0 = P[:, -1].copy()
        if linalg == "dst":
            res = self._march_dst(P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge)
        else:
            res = self._march_banded(P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge)
        P_out, A_out, Af_out = res["P_out"], res["A_out"], res["Af_out"]
        JN, r_max, dtau_total = res["JN"], res["r_max"], res["dtau_total"]

        if pr.hardness is None:
            tail = tail_mass(p_max, pr.p_bar, self.tau_out[-1])
        else:  # the far wall is the yield wall: what it absorbs is the plastic area, not a loss
            tail = np.zeros(1)
        info = {
            "grid": {"n_p": N, "p_max": p_max, "dp": dp},
            "edges": self.edges,
            "steps": n_steps,
            "zeta0": self.zeta0,
            "scheme": o["scheme"],
            "stepping": o["stepping"],
            "coupling": "exact (S = 1)" if no_fudge else coupling,
            "order_tau": scheme.order,
            **res["counters"],
            "r_max": r_max,
            "far_wall_mass": 0.0 if pr.hardness is not None else float(np.max(JN)),
            "tail_mass_exact": float(np.max(np.abs(tail))),
            "tau_numerical": dtau_total + (0.0 if o["initial"] == "delta" else self._tau0),
            "k_domain": o["k_domain"],
            "space": space,
            "order_p": 4 if compact else 2,
        }
        return SolverOutput(
            p=p,
            P0=P_out,
            weights=np.full(N, dp),
            kind="cell",
            info=info,
            contact_area=A_out,
            contact_area_flux=Af_out,
            # A_pl: the flux absorbed at the yield wall plus the compact scheme's edge term of that wall (so that
            # A_el + A_pl + A_non is conserved to round-off; 0 for fv2)
            plastic_area=None
            if pr.hardness is None
            else self._A_pl0 + res["JN_out"] - w_edge * dp * (P_out[:, :, -1] - P_far0),
        )

    # -- the reference march: tridiagonal solves in p -------------------------------------------
    def _march_banded(self, P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge) -> dict:
        """The time loop with LAPACK tridiagonal solves (the readable reference of :meth:`_march_dst`)."""
        o, pr = self.opts, self.problem
        no_fudge = isinstance(pr.fudge, NoFudge)
        S = pr.fudge.S
        m, N = P.shape
        dp = self.dp
        k = 0.5 / dp**2
        compact = space != "fv2"
        n_steps = V_nodes.shape[0] - 1
        solver = _Tridiag(N, m, k, space)
        m_d, m_o = SPACES[space]
        MP = np.empty_like(P)
        P_edge0 = P[:, 0].copy()
        mass = P.sum(axis=-1) * dp
        J0 = np.zeros(m)  # absorbed through p = 0 since zeta0
        JN = np.zeros(m)  # lost through p = p_max
        P_out = np.empty((self.zeta_out.size, m, N))
        A_out = np.empty((self.zeta_out.size, m))
        Af_out = np.empty((self.zeta_out.size, m))
        JN_out = np.empty((self.zeta_out.size, m))
        hard, A_pl0 = self._hard, self._A_pl0
        sup0 = np.max(np.abs(P), axis=-1)
        # the checks watch the conserved sum(M P) dp (= A* - w_edge dp (P_0 + P_-1)): with the compact mass
        # matrix A* itself may rise a little while the wall cells change fast (a delta start), stably
        mass_prev = mass - w_edge * dp * (P[:, 0] + P[:, -1])
        picard_iters = 0
        r_max = 0.0
        dtau_total = np.zeros(m)

        def theta_step(P, dtau, theta):
            """One θ-step of size dtau (per load); returns (P_new, dJ0, dJN)."""
            b0, bN = wall_flux(P, dp)
            ck = ((1.0 - theta) * k) * (dtau if m > 1 else dtau[0])
            if m > 1:
                ck = ck[:, None]
            # (M + (1 - theta) dtau L) P in one stencil pass
            Bv = _tri_matvec(P, m_o + ck, m_d - 2.0 * ck, m_d - m_o - 3.0 * ck, np.empty_like(P))
            Pn = solver.solve(theta * dtau, Bv) if (theta > 0.0 or compact) else Bv
            c0, cN = wall_flux(Pn, dp)
            return (
                Pn,
                dtau * (theta * c0 + (1.0 - theta) * b0),
                dtau * (theta * cN + (1.0 - theta) * bN),
            )

        def step(P, dtau, n):
            """One step of the chosen scheme: (P_new, dJ0, dJN)."""
            kind = self._step_kind(n)
            if kind == "tr-bdf2":
                Ps, j0s, jNs = theta_step(P, _GAMMA * dtau, 0.5)
                apply_mass(_BDF2_A * Ps - _BDF2_B * P, space, out=MP)
                Pn = np.ascontiguousarray(solver.solve(_BDF2_W * dtau, MP))
                c0, cN = wall_flux(Pn, dp)
                return Pn, _BDF2_A * j0s + _BDF2_W * dtau * c0, _BDF2_A * jNs + _BDF2_W * dtau * cN
            if kind == "be-halves":
                Ph, a0, aN = theta_step(P, 0.5 * dtau, 1.0)
                Pn, b0_, bN_ = theta_step(np.ascontiguousarray(Ph), 0.5 * dtau, 1.0)
                return Pn, a0 + b0_, aN + bN_
            return theta_step(P, dtau, scheme.theta)

        st = 0
        dtau_prev = None
        for n in range(n_steps):
            dV = V_nodes[n + 1] - V_nodes[n]
            if no_fudge:
                dtau = dV.copy()
                if dtau_prev is not None and np.all(np.abs(dtau - dtau_prev) <= 1e-12 * dtau):
                    dtau = dtau_prev  # uniform steps: keep the factorisation (a 1e-12 relative shift)
            else:  # S at the contact area: A_el (+ A_pl with a hardness wall)
                total = mass + (A_pl0 + JN if hard else 0.0)
                Sn = S(np.minimum(total, 1.0))
                if coupling == "lagged":
                    dtau = Sn * dV
                else:
                    b = (P[:, 0] + (0.0 if hard else P[:, -1])) / dp
                    A_pred = np.clip(total - dV * Sn * b, 0.0, 1.0)
                    dtau = 0.5 * dV * (Sn + S(A_pred))
            Pn, dJ0, dJN = step(P, dtau, n)
            if coupling == "picard" and not no_fudge:
                for _ in range(o["picard_maxiter"]):
                    picard_iters += 1
                    new_mass = np.clip(total - dJ0 - (0.0 if hard else dJN), 0.0, 1.0)
                    dtau_new = 0.5 * dV * (Sn + S(new_mass))
                    if np.max(np.abs(dtau_new - dtau)) <= o["picard_tol"] * np.max(dtau):
                        dtau = dtau_new
                        break
                    dtau = dtau_new
                    Pn, dJ0, dJN = step(P, dtau, n)
            r_max = max(r_max, 0.5 * float(np.max(dtau)) / dp**2)
            if scheme.theta == 0.0 and r_max > r_limit and not o["allow_unstable"]:
                raise ValueError(
                    f"explicit scheme: r = dtau/(2 dp^2) = {r_max:.4g} exceeds the stability limit {r_limit:.4g} "
                    "(the fudge factor enlarged dtau); raise n_steps or use an implicit scheme"
                )
            dtau_prev = dtau
            P = np.ascontiguousarray(Pn)
            J0 += dJ0
            JN += dJN
            dtau_total += dtau
            mass = P.sum(axis=-1) * dp
            if (n + 1) % o["check_every"] == 0 or n + 1 == n_steps:
                remedy = "raise n_steps or use scheme='tr-bdf2'"
                cons = mass - w_edge * dp * (P[:, 0] + P[:, -1])
                try:
                    self.check_state(P, cons, mass_prev, np.nan, "fv/" + o["scheme"], remedy)
                except InstabilityError:  # say where (the root find costs only when it fails)
                    z_now = self._zeta_of_V(float(V_nodes[n + 1, 0]))
                    self.check_state(P, cons, mass_prev, z_now, "fv/" + o["scheme"], remedy)
                sup = np.max(np.abs(P), axis=-1)
                if np.any(sup > 2.0 * sup0 + 1e-300):
                    z_now = self._zeta_of_V(float(V_nodes[n + 1, 0]))
                    raise InstabilityError(
                        f"fv/{o['scheme']}: max |P0| grew by a factor {np.max(sup / sup0):.3g} by zeta = "
                        f"{z_now:.6g} (the heat equation cannot do that; r = {r_max:.3g}); {remedy}"
                    )
                mass_prev = cons
            while st < station_idx.size and n + 1 == station_idx[st]:
                P_out[st] = P
                A_out[st] = mass
                Af_out[st] = A0 - J0 + w_edge * dp * (P[:, 0] - P_edge0)
                JN_out[st] = JN
                st += 1
        return {
            "P_out": P_out,
            "A_out": A_out,
            "Af_out": Af_out,
            "JN_out": JN_out,
            "JN": JN,
            "r_max": r_max,
            "dtau_total": dtau_total,
            "counters": {
                "linalg": "banded",
                "tridiagonal_solves": solver.solves,
                "factorizations": solver.factorizations,
                "picard_iterations": picard_iters,
                "trajectory_sweeps": 0,
            },
        }

    # -- the fast march: the same steps in DST-II coefficient space --------------------------------
    def _damped_steps(self) -> int:
        """Leading steps done as two backward-Euler half steps: Rannacher's start-up, and TR-BDF2's
        from a delta (its amplification factor is negative for dtau |lambda| > ~2.4: one-step
        2nd-order schemes cannot be positive for every step size, so rough data would ring)."""
        o = self.opts
        if o["scheme"] == "rannacher" or (o["scheme"] == "tr-bdf2" and o["initial"] == "delta"):
            return o["rannacher_steps"]
        return 0

    def _step_kind(self, n: int) -> str:
        if n < self._damped_steps():
            return "be-halves"
        return "tr-bdf2" if self.opts["scheme"] == "tr-bdf2" else "theta"

    def _check_dst(self, C, mass, mass_prev, norm, norm0, V_now, r_max):
        """The stability checks of the banded path, on coefficients (the l2 norm of P0 is ||c||_2)."""
        name = "fv/" + self.opts["scheme"]
        remedy = "raise n_steps or use scheme='tr-bdf2'"
        try:
            self.check_state(C, mass, mass_prev, np.nan, name, remedy)
        except InstabilityError:  # say where (the root find costs only when it fails)
            self.check_state(C, mass, mass_prev, self._zeta_of_V(V_now), name, remedy)
        if np.any(norm > 2.0 * norm0 + 1e-300):
            raise InstabilityError(
                f"{name}: the l2 norm of P0 grew by a factor {np.max(norm / norm0):.3g} by zeta = "
                f"{self._zeta_of_V(V_now):.6g} (the heat equation cannot do that; r = {r_max:.3g}); {remedy}"
            )

    def _amplify_all(self, X, theta):
        """R and F of every step at once: X (n_steps, ..., n_p); the damped first steps are BE halves."""
        n_steps = X.shape[0]
        R, F = _amplification(self._step_kind(n_steps), theta, X)
        r0 = min(self._damped_steps(), n_steps)
        if r0 > 0:
            R[:r0], F[:r0] = _amplification("be-halves", theta, X[:r0])
        return R, F

    def _fudge_trajectory(self, sp, C0, V_nodes, theta, coupling):
        r"""Steps :math:`\Delta\tau_n` of the lagged/predictor coupling for the whole run at once.

        The coupled march defines :math:`\Delta\tau_n = \Phi(A^*_n, b_n, \Delta V_n)` from the state
        before step n, and that state is :math:`C_0\prod_{k<n}R(\Delta\tau_k\lambda)`: a causal
        (Volterra) fixed point in the step sizes.  It is solved by Newton sweeps over the whole
        trajectory, each one vectorised over steps and modes (a cumulative product), starting from the
        exact continuum steps tau(V_{n+1}) - tau(V_n).  The Jacobian is approximated by what dominates
        it: a step of size d moves every later A* by -b d (b: the current outflux density), so the
        correction solves :math:`\delta_n = r_n - \Phi'_n b_n\sum_{k<n}\delta_k` (a scalar
        recurrence).  The fixed point is the per-step march's (to 1e-14 of the steps); 3-6 sweeps
        instead of n_steps Python-level steps.  Returns (dts (n_steps, n_loads), sweeps), or
        (None, sweeps) when it does not converge in ``_TRAJECTORY_SWEEPS`` (the caller then marches
        step by step, which also reports any instability).
        """
        pr = self.problem
        S = pr.fudge.S
        fun = sp.functionals
        m = C0.shape[0]
        dV = np.diff(V_nodes, axis=0)  # (n_steps, m)
        tau_nodes = pr.tau_of_V_each(V_nodes)  # the continuum's steps: the starting guess
        if self.opts["initial"] == "delta":
            tau_nodes[0] = 0.0
        dts = np.diff(tau_nodes, axis=0)
        W = np.stack([C0 * fun[:, 0], C0 * (fun[:, 1] + fun[:, 2])])  # (2, m, N): A* and the outflux
        # only modes that carry A* or the outflux: the even ones carry neither (both functionals are
        # symmetric about the middle), nor do the top modes of a smooth start (dropped below 1e-18 of
        # the largest term: with |R| <= 1 the sums move by < n_p 1e-18 of themselves)
        big = np.max(np.abs(W), axis=(1, 2), keepdims=True)
        keep = np.any(np.abs(W) > 1e-18 * big, axis=(0, 1))
        W = np.ascontiguousarray(W[:, :, keep])
        lam = sp.lam[keep]
        mass0, b0 = W[0].sum(axis=-1), W[1].sum(axis=-1)  # at the start (node 0)
        WT = np.ascontiguousarray(W[:, 0, :].T) if m == 1 else None  # one load: a matmul, not an einsum
        r0 = min(self._damped_steps(), dts.shape[0])
        kind = self._step_kind(dts.shape[0])
        chord = None  # the correction's recurrence, set up once (a chord method: the Jacobian is approximate anyway)
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            for sweep in range(1, _TRAJECTORY_SWEEPS + 1):
                X = dts[:-1, :, None] * lam  # the last step's factor is not needed here
                R = _growth(kind, theta, X)
                if r0 > 0:
                    R[:r0] = _growth("be-halves", theta, X[:r0])
                G = np.cumprod(R, axis=0)  # amplification up to the start of steps 1..n-1
                if WT is not None:
                    Q = (G[:, 0, :] @ WT).T[:, :, None]  # (2, n_steps - 1, 1)
                else:  # several loads
                    Q = np.einsum("cjn,kjn->ckj", W, G)  # (2, n_steps - 1, m)
                if not np.all(np.isfinite(Q)):
                    return None, sweep
                mass = np.concatenate([mass0[None], Q[0]])
                b = np.concatenate([b0[None], Q[1]])
                Sn = S(mass)
                if coupling == "lagged":
                    new = Sn * dV
                else:
                    A_pred = np.minimum(np.maximum(mass - dV * Sn * b, 0.0), 1.0)
                    new = 0.5 * dV * (Sn + S(A_pred))
                res = new - dts
                if np.all(np.abs(res) <= _TRAJECTORY_TOL * np.max(dts, axis=0)):
                    return new, sweep
                if chord is None:  # c_n = dPhi/dA * b_n (docstring), from the first sweep's trajectory
                    A_c = np.minimum(np.maximum(mass, 1e-6), 1.0 - 1e-6)
                    c = dV * (S(A_c + 1e-6) - S(A_c - 1e-6)) / 2e-6 * b
                    alpha = 1.0 - c
                    P = np.cumprod(alpha, axis=0) if np.all((alpha > 0.25) & (alpha < 4.0)) else None
                    chord = (c, alpha, P)
                c, alpha, P = chord
                if P is not None:  # D_{n+1} = alpha_n D_n + r_n in closed form
                    D = np.concatenate([np.zeros((1, m)), P[:-1] * np.cumsum(res / P, axis=0)[:-1]])
                else:
                    D = np.zeros_like(res)
                    for n in range(1, res.shape[0]):
                        D[n] = alpha[n - 1] * D[n - 1] + res[n - 1]
                dts = dts + res - c * D
        return None, _TRAJECTORY_SWEEPS

    def _dst_closed(self, sp, C0, P_edge0, A0, dts, V_nodes, station_idx, theta, r_limit, w_edge, sweeps=0):
        """The whole march from given steps dts (n_steps, 1 or n_loads), all steps at once (see _march_dst)."""
        o = self.opts
        fun = sp.functionals
        m, N = C0.shape
        dp = self.dp
        n_steps, mm = dts.shape

        def contract(Wt, A):  # sum_j Wt[l, j] A[k, l or 0, j] -> (k, l): a matmul when loads share steps
            return (Wt @ A[:, 0, :].T).T if mm == 1 else np.einsum("lj,klj->kl", Wt, A)

        X = dts[:, :, None] * sp.lam
        R, F = self._amplify_all(X, theta)
        with np.errstate(over="ignore", invalid="ignore"):
            G = np.cumprod(R, axis=0)  # G[k]: amplification through step k
            np.copyto(G, 0.0, where=np.abs(G) < _FLUSH)  # no subnormals (see _FLUSH)
            F *= dts[:, :, None]
            F[1:] *= G[:-1]
            H = np.cumsum(F, axis=0)  # H[k]: wall-flux weight through step k
        r_max = 0.5 * float(np.max(dts)) / dp**2
        if theta == 0.0 and r_max > r_limit and not o["allow_unstable"]:
            raise ValueError(
                f"explicit scheme: r = dtau/(2 dp^2) = {r_max:.4g} exceeds the stability limit {r_limit:.4g} "
                "(the fudge factor enlarged dtau); raise n_steps or use an implicit scheme"
            )
        norm0 = np.sqrt(np.einsum("ij,ij->i", C0, C0))
        ks = np.array([k for k in range(n_steps) if (k + 1) % o["check_every"] == 0 or k + 1 == n_steps])
        with np.errstate(over="ignore", invalid="ignore"):
            Gk = G[ks]
            w_cons = fun[:, 0] - w_edge * dp**2 * (fun[:, 1] + fun[:, 2])  # the conserved sum(M P) dp
            mass_k = contract(C0 * w_cons, Gk).T  # (m, n_checks)
            norm_k = np.sqrt(contract(C0 * C0, Gk * Gk)).T
            mass_prev = np.concatenate([(C0 @ w_cons)[:, None], mass_k[:, :-1]], axis=1)
            bad = (
                ~(np.isfinite(Gk).all(axis=(1, 2)) & np.isfinite(mass_k).all(axis=0) & np.isfinite(norm_k).all(axis=0))
                | (mass_k < -1e-12).any(axis=0)
                | (mass_k > mass_prev * (1 + 1e-8) + 1e-12).any(axis=0)
                | (norm_k > 2.0 * norm0[:, None] + 1e-300).any(axis=0)
            )
        if bad.any():
            i = int(np.argmax(bad))
            k = ks[i]
            with np.errstate(over="ignore", invalid="ignore"):
                Ck = C0 * G[k]
            self._check_dst(Ck, mass_k[:, i], mass_prev[:, i], norm_k[:, i], norm0, V_nodes[k + 1, 0], r_max)
            raise AssertionError("unreachable: a failed check raises")  # pragma: no cover
        K = station_idx - 1
        C_st = C0[None, :, :] * G[K]  # (n_st, m, N)
        P_out = sp.inverse(C_st)
        A_out = C_st @ fun[:, 0]
        J0 = contract(C0 * fun[:, 1], H[K])  # (n_st, m)
        Af_out = A0 - J0 + w_edge * dp * (P_out[:, :, 0] - P_edge0)
        JN_out = contract(C0 * fun[:, 2], H[K])  # (n_st, m): the plastic area gained (with a hardness wall)
        JN = contract(C0 * fun[:, 2], H[-1:])[0]
        return {
            "P_out": P_out,
            "A_out": A_out,
            "Af_out": Af_out,
            "JN_out": JN_out,
            "JN": JN,
            "r_max": r_max,
            "dtau_total": np.broadcast_to(dts.sum(axis=0), (m,)).copy(),
            "counters": {
                "linalg": "dst",
                "transforms": sp.transforms,
                "tridiagonal_solves": 0,
                "factorizations": 0,
                "picard_iterations": 0,
                "trajectory_sweeps": sweeps,
            },
        }

    def _march_dst(self, P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge) -> dict:
        r"""The time loop of :meth:`_march_banded` in DST-II coefficient space (module docstring).

        Every step multiplies coefficient j by :math:`R(\Delta\tau\lambda_j)` (:func:`_amplification`);
        A* and the wall fluxes are linear functionals of the coefficients, so the coupling of the
        fudge factor needs no transform; P is transformed back only at the output stations.
        """
        o, pr = self.opts, self.problem
        no_fudge = isinstance(pr.fudge, NoFudge)
        m, N = P.shape
        dp = self.dp
        sp = _Spectral(N, dp, space)
        fun = sp.functionals
        n_steps = V_nodes.shape[0] - 1
        theta = scheme.theta
        C0 = sp.forward(P)
        P_edge0 = P[:, 0].copy()
        norm0 = np.sqrt(np.einsum("ij,ij->i", C0, C0))
        P_out = np.empty((self.zeta_out.size, m, N))
        A_out = np.empty((self.zeta_out.size, m))
        Af_out = np.empty((self.zeta_out.size, m))
        JN_out = np.empty((self.zeta_out.size, m))
        hard, A_pl0 = self._hard, self._A_pl0
        too_big = (
            "explicit scheme: r = dtau/(2 dp^2) = {:.4g} exceeds the stability limit {:.4g} "
            "(the fudge factor enlarged dtau); raise n_steps or use an implicit scheme"
        )
        check_every = o["check_every"]

        if no_fudge and np.all(V_nodes == V_nodes[:, :1]):
            # one linear map per station: P_N = S^-1 diag(prod_k R_k) S P_0, all steps at once
            dV = np.diff(V_nodes[:, 0])
            dts = np.empty(n_steps)
            prev = None
            for n in range(n_steps):  # the banded path's rule for re-using a factorisation
                d = dV[n]
                if prev is not None and abs(d - prev) <= 1e-12 * d:
                    d = prev
                dts[n] = prev = d
            return self._dst_closed(sp, C0, P_edge0, A0, dts[:, None], V_nodes, station_idx, theta, r_limit, w_edge)
        if (
            not no_fudge
            and not hard
            and coupling != "picard"
            and n_steps >= _TRAJECTORY_MIN_STEPS
            and m <= _fudge_trajectory_max_loads
            and m * n_steps * N <= _TRAJECTORY_SIZE
        ):
            dts, sweeps = self._fudge_trajectory(sp, C0, V_nodes, theta, coupling)
            if dts is not None:
                return self._dst_closed(
                    sp, C0, P_edge0, A0, dts, V_nodes, station_idx, theta, r_limit, w_edge, sweeps=sweeps
                )

        # per-step march in coefficient space: dtau depends on the numerical A* (a functional)
        S = pr.fudge.S
        lam = sp.lam
        fun_w = np.ascontiguousarray(fun[:, [1, 2, 2, 3]])  # 4 columns again (see _Spectral)

        X = np.empty((m, N))
        work = (np.empty((m, N)), np.empty((m, N)), np.empty((m, N)))
        bufs = [np.empty((m, N)), np.empty((m, N))]  # the state and the next state, swapped every step

        kinds = [self._step_kind(n) for n in range(n_steps)]
        dV_all = np.diff(V_nodes, axis=0)
        stations = [int(i) for i in station_idx]

        def step(C, dtau, n):
            np.multiply(dtau[:, None], lam, out=X)
            R, F, T = work
            _amplification(kinds[n], theta, X, work)
            np.multiply(C, F, out=T)
            fl = T @ fun_w
            Cn = bufs[1] if C is bufs[0] else bufs[0]
            np.multiply(C, R, out=Cn)
            return Cn, dtau * fl[:, 0], dtau * fl[:, 1]

        C = bufs[0]
        C[:] = C0
        flush = _FLUSH * float(np.max(norm0, initial=0.0))
        mass, b0, bN, _ = (C @ fun).T
        mass_prev = mass - w_edge * dp**2 * (b0 + bN)  # the checks' conserved sum(M P) dp (b = P_wall / dp)
        J0 = np.zeros(m)
        JN = np.zeros(m)
        picard_iters = 0
        dtau_max = r_max = 0.0
        dtau_total = np.zeros(m)
        dtau_prev = None
        st = 0
        for n in range(n_steps):
            dV = dV_all[n]
            if no_fudge:
                dtau = dV.copy()
                if dtau_prev is not None and np.all(np.abs(dtau - dtau_prev) <= 1e-12 * dtau):
                    dtau = dtau_prev
            else:  # S at the contact area: A_el (+ A_pl with a hardness wall, which keeps what it absorbs)
                total = mass + (A_pl0 + JN if hard else 0.0)
                loss = b0 if hard else b0 + bN
                Sn = S(np.minimum(total, 1.0))
                if coupling == "lagged":
                    dtau = Sn * dV
                else:
                    A_pred = np.minimum(np.maximum(total - dV * Sn * loss, 0.0), 1.0)
                    dtau = 0.5 * dV * (Sn + S(A_pred))
            Cn, dJ0, dJN = step(C, dtau, n)
            if coupling == "picard" and not no_fudge:
                for _ in range(o["picard_maxiter"]):
                    picard_iters += 1
                    dtau_new = 0.5 * dV * (Sn + S(np.clip(total - dJ0 - (0.0 if hard else dJN), 0.0, 1.0)))
                    if np.max(np.abs(dtau_new - dtau)) <= o["picard_tol"] * np.max(dtau):
                        dtau = dtau_new
                        break
                    dtau = dtau_new
                    Cn, dJ0, dJN = step(C, dtau, n)
            dtau_max = max(dtau_max, float(dtau.max()))
            r_max = 0.5 * dtau_max / dp**2
            if theta == 0.0 and r_max > r_limit and not o["allow_unstable"]:
                raise ValueError(too_big.format(r_max, r_limit))
            dtau_prev = dtau
            C = Cn
            if n % 8 == 7:
                np.copyto(C, 0.0, where=np.abs(C) < flush)  # no subnormals (see _FLUSH)
            J0 += dJ0
            JN += dJN
            dtau_total += dtau
            mass, b0, bN, _ = (C @ fun).T
            if (n + 1) % check_every == 0 or n + 1 == n_steps:
                norm = np.sqrt(np.einsum("ij,ij->i", C, C))
                cons = mass - w_edge * dp**2 * (b0 + bN)
                self._check_dst(C, cons, mass_prev, norm, norm0, V_nodes[n + 1, 0], r_max)
                mass_prev = cons
            if st < len(stations) and n + 1 == stations[st]:
                Pst = sp.inverse(C)
                while st < len(stations) and n + 1 == stations[st]:
                    P_out[st] = Pst
                    A_out[st] = mass
                    Af_out[st] = A0 - J0 + w_edge * dp * (Pst[:, 0] - P_edge0)
                    JN_out[st] = JN
                    st += 1
        return {
            "P_out": P_out,
            "A_out": A_out,
            "Af_out": Af_out,
            "JN_out": JN_out,
            "JN": JN,
            "r_max": r_max,
            "dtau_total": dtau_total,
            "counters": {
                "linalg": "dst",
                "transforms": sp.transforms,
                "tridiagonal_solves": 0,
                "factorizations": 0,
                "picard_iterations": picard_iters,
                "trajectory_sweeps": 0,
            },
        }
