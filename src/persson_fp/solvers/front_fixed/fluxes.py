r"""The general finite-volume engine: conservative fluxes on a cell grid, wall objects, time integrators.

The DST fast path of ``"fv"`` (``persson_fp.solvers.fv.spectral``) is exact only for the constant-coefficient
heat equation between two fixed absorbing walls.  Everything else -- a moving yield wall, and (in time)
p-dependent coefficients -- is solved here, in conservative form on ``n`` uniform cells of a coordinate
:math:`x \in [0, 1]`:

.. math::  \partial_t w = -\partial_x G, \qquad G = -D\,\partial_x w - v\,w ,

with the cell averages :math:`w_i` as unknowns, face fluxes
:math:`G_{i+1/2} = -D_{i+1/2}(w_{i+1}-w_i)/h - v_{i+1/2}(w_i + w_{i+1})/2` (second order), and one extra unknown
per wall that keeps what the wall absorbs.  The walls are small objects that supply their face flux as a linear
function of the neighbouring unknowns (cf. py-pde's boundary classes: the operator never asks which wall it is):

- ``AbsorbingWall`` at x = 0 (:math:`w = 0`; the odd ghost cell :math:`-w_0`, exact for the image solution's
  odd symmetry, so the wall costs no order).  What leaves through it is the non-contact area :math:`A_{non}`.
- ``YieldWall`` at x = 1 with the Dirichlet value :math:`w_b = \beta\,a`, where a is the wall's own unknown
  (the plastic area :math:`A_{pl}`) and :math:`da/dt = G_{n-1/2}`; the derivative at the wall by the one-sided
  second-order formula :math:`(8w_b - 9w_{n-1} + w_{n-2})/(3h)`.  :math:`\beta = 0` is a fixed absorbing yield wall.

The state is :math:`y = (w_0, \dots, w_{n-1}, a)` and :math:`\dot y = L(t)\,y` with L banded (2 sub-, 1
super-diagonal).  Because every face flux appears once with each sign, :math:`\sum_i w_i h + a + A_{non}` is
conserved to round-off by any linear time integrator; ``step`` advances it with TR-BDF2 (L-stable, second
order; Bank et al. 1985) or a θ-scheme, with the operator re-assembled at each stage time, and accumulates the
flux through x = 0 with the same stage weights so that the balance closes exactly (``step``).

This module knows nothing of contact mechanics: :mod:`~persson_fp.solvers.front_fixed.moving_wall` maps the moving
yield wall onto it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import get_lapack_funcs

from persson_fp.solvers.schemes import TRBDF2_A, TRBDF2_B, TRBDF2_GAMMA, TRBDF2_W

_gbsv = get_lapack_funcs("gbsv", dtype=np.float64)

__all__ = ["AbsorbingWall", "YieldWall", "Coefficients", "assemble", "apply", "step", "outflux_low"]

LOWER, UPPER = 2, 1
"""Bandwidths of L in ``solve_banded`` form."""


class AbsorbingWall:
    """w = 0 at x = 0 (odd ghost cell); its face flux is :math:`G_{-1/2} = -2 D_{-1/2} w_0 / h`."""

    @staticmethod
    def flux_coefficient(D_face: float, h: float) -> float:
        """d G_{-1/2} / d w_0."""
        return -2.0 * D_face / h


class YieldWall:
    r"""Dirichlet :math:`w_b = \beta a` at x = 1, a = the wall's absorbed mass (plastic area).

    :math:`G_{n-1/2} = -D (8\beta a - 9 w_{n-1} + w_{n-2})/(3h) - v\,\beta a`; returns the coefficients of
    :math:`(w_{n-2}, w_{n-1}, a)`.
    """

    @staticmethod
    def flux_coefficients(D_face: float, v_face: float, beta, h: float):
        return -D_face / (3.0 * h), 3.0 * D_face / h, -(8.0 * D_face / (3.0 * h) + v_face) * beta


@dataclass
class Coefficients:
    r"""Face data at one time: diffusivity D and drift v at the n + 1 faces, and the yield wall's beta.

    ``D`` and ``v`` have shape (n + 1,) or (m, n + 1) (m problems, e.g. loads, advanced together);
    ``beta`` a scalar or shape (m,).  With ``D_cells`` (shape (n,) or (m, n)) the diffusive flux is taken in
    the form :math:`-\partial_x(D w)` (the Fokker--Planck/Ito form of the tutorial's Eq.
    'E:Fokker_Planck_Forward'): :math:`-(D_{i+1}w_{i+1} - D_i w_i)/h` at interior faces, and at the walls the
    odd extension of :math:`u = Dw` (which, unlike w, stays regular where D vanishes at the wall: a degenerate
    diffusion still absorbs).  Second order as long as u is odd-smooth at p = 0, i.e. B1(0) = 0 or P'(0) = 0.
    """

    D: np.ndarray
    v: np.ndarray
    beta: np.ndarray
    D_cells: np.ndarray | None = None


def assemble(c: Coefficients, h: float) -> np.ndarray:
    """L in ``solve_banded`` (2, 1) form, shape (m, 4, n + 1): rows 0..n-1 the cells, row n the wall mass."""
    D = np.atleast_2d(c.D)
    v = np.atleast_2d(c.v)
    m, nf = D.shape
    n = nf - 1
    beta = np.broadcast_to(np.asarray(c.beta, dtype=float), (m,))
    ab = np.zeros((m, 4, n + 1))
    # interior face i+1/2 (i = 0..n-2): G = a_i w_i + b_i w_{i+1}
    vi = v[:, 1:-1]
    if c.D_cells is None:
        DL = DR = D[:, 1:-1]
        D0, Dn1, Dn2 = D[:, 0], D[:, -1], D[:, -1]
    else:
        Dc = np.broadcast_to(np.atleast_2d(c.D_cells), (m, n))
        DL, DR = Dc[:, :-1], Dc[:, 1:]
        D0, Dn1, Dn2 = Dc[:, 0], Dc[:, -1], Dc[:, -2]
    a = DL / h - 0.5 * vi
    b = -DR / h - 0.5 * vi
    # cell i gets -(G_{i+1/2} - G_{i-1/2})/h.  Band layout: ab[u + i - j, j] = L[i, j] (u = 1).
    diag = np.zeros((m, n + 1))
    sup = np.zeros((m, n + 1))  # L[i, i+1] stored at ab[0, i+1]
    sub = np.zeros((m, n + 1))  # L[i+1, i] stored at ab[2, i]
    sub2 = np.zeros((m, n + 1))  # L[i+2, i] stored at ab[3, i]
    # face i+1/2 between cells i and i+1: cell i loses G, cell i+1 gains G
    diag[:, : n - 1] -= a / h
    sup[:, 1:n] -= b / h  # L[i, i+1]
    sub[:, : n - 1] += a / h  # L[i+1, i]
    diag[:, 1:n] += b / h
    # x = 0: absorbing wall, G_{-1/2} = g0 w_0 leaves cell 0 through its lower face
    g0 = AbsorbingWall.flux_coefficient(D0, h)
    diag[:, 0] += g0 / h
    # x = 1: yield wall, G_{n-1/2} = c2 w_{n-2} + c1 w_{n-1} + ca a: out of cell n-1, into the wall mass
    c2, c1, ca = YieldWall.flux_coefficients(D[:, -1], v[:, -1], beta, h)
    if c.D_cells is not None:  # -d(Dw)/dx at the wall from (D w) at the wall and in the last two cells
        c2, c1 = -Dn2 / (3.0 * h), 3.0 * Dn1 / h
    sub[:, n - 2] -= c2 / h  # L[n-1, n-2]
    diag[:, n - 1] -= c1 / h
    sup[:, n] -= ca / h  # L[n-1, n]
    sub2[:, n - 2] += c2  # L[n, n-2]
    sub[:, n - 1] += c1  # L[n, n-1]
    diag[:, n] += ca
    ab[:, 0] = sup
    ab[:, 1] = diag
    ab[:, 2] = sub
    ab[:, 3] = sub2
    return ab


def apply(ab: np.ndarray, y: np.ndarray) -> np.ndarray:
    """L @ y for the banded ``ab`` (m, 4, n + 1) and ``y`` (m, n + 1)."""
    out = ab[:, 1] * y
    out[:, :-1] += ab[:, 0, 1:] * y[:, 1:]
    out[:, 1:] += ab[:, 2, :-1] * y[:, :-1]
    out[:, 2:] += ab[:, 3, :-2] * y[:, :-2]
    return out


def outflux_low(c: Coefficients, y: np.ndarray, h: float) -> np.ndarray:
    """Rate of mass leaving through x = 0, -G_{-1/2} = 2 D w_0 / h (m,)."""
    D0 = np.atleast_2d(c.D)[:, 0] if c.D_cells is None else np.atleast_2d(c.D_cells)[:, 0]
    return -AbsorbingWall.flux_coefficient(D0, h) * y[:, 0]


def _solve(ab: np.ndarray, c: float, rhs: np.ndarray) -> np.ndarray:
    """(I - c L) y = rhs for each of the m systems (LAPACK ``gbsv``, partial pivoting)."""
    m, _, N = ab.shape
    out = np.empty_like(rhs)
    work = np.zeros((2 * LOWER + UPPER + 1, N))  # gbsv's layout: LOWER extra rows on top for the fill-in
    for k in range(m):
        work[:LOWER] = 0.0
        np.multiply(ab[k], -c, out=work[LOWER:])
        work[LOWER + UPPER] += 1.0
        _, _, x, info = _gbsv(LOWER, UPPER, work, rhs[k], overwrite_ab=1, overwrite_b=0)
        if info != 0:  # pragma: no cover - I - cL is an M-matrix for c > 0
            raise np.linalg.LinAlgError(f"banded solve failed (LAPACK info {info})")
        out[k] = x
    return out


def step(coef_at, t: float, dt: float, y: np.ndarray, h: float, scheme: str = "tr-bdf2", source=None):
    r"""One step of :math:`\dot y = L(t) y + f(t)` from t to t + dt; returns (y_new, mass through x = 0).

    ``coef_at(t)`` gives the :class:`Coefficients` at time t; ``source(t)`` (optional, for manufactured solutions)
    the cell averages of f, shape (m, n + 1) (last column: the wall mass's source, usually 0).  Schemes:
    "tr-bdf2" (trapezoidal stage to t + γdt, then BDF2), "crank-nicolson", "implicit" (backward Euler),
    "be-halves" (two backward-Euler half steps, a damped start).  The absorbed mass uses the stage weights of the
    scheme, so that sum(w) h + a + absorbed is conserved to round-off (without a source).
    """
    f = (lambda _t: 0.0) if source is None else source
    if scheme == "be-halves":
        y1, j1 = step(coef_at, t, 0.5 * dt, y, h, "implicit", source)
        y2, j2 = step(coef_at, t + 0.5 * dt, 0.5 * dt, y1, h, "implicit", source)
        return y2, j1 + j2
    c0 = coef_at(t)
    if scheme == "implicit":
        c1 = coef_at(t + dt)
        y1 = _solve(assemble(c1, h), dt, y + dt * f(t + dt))
        return y1, dt * outflux_low(c1, y1, h)
    if scheme == "crank-nicolson":
        c1 = coef_at(t + dt)
        L0 = assemble(c0, h)
        y1 = _solve(assemble(c1, h), 0.5 * dt, y + 0.5 * dt * (apply(L0, y) + f(t) + f(t + dt)))
        return y1, 0.5 * dt * (outflux_low(c0, y, h) + outflux_low(c1, y1, h))
    if scheme != "tr-bdf2":
        raise ValueError(f"scheme must be 'tr-bdf2', 'crank-nicolson', 'implicit' or 'be-halves', got {scheme!r}")
    tg = t + TRBDF2_GAMMA * dt
    cg = coef_at(tg)
    c1 = coef_at(t + dt)
    L0 = assemble(c0, h)
    ys = _solve(assemble(cg, h), 0.5 * TRBDF2_GAMMA * dt, y + 0.5 * TRBDF2_GAMMA * dt * (apply(L0, y) + f(t) + f(tg)))
    js = 0.5 * TRBDF2_GAMMA * dt * (outflux_low(c0, y, h) + outflux_low(cg, ys, h))
    y1 = _solve(assemble(c1, h), TRBDF2_W * dt, TRBDF2_A * ys - TRBDF2_B * y + TRBDF2_W * dt * f(t + dt))
    j1 = TRBDF2_A * js + TRBDF2_W * dt * outflux_low(c1, y1, h)
    return y1, j1
