r"""Loads that share one grid: the transition density of a separable problem from one eigendecomposition.

Where b and c per unit V do not depend on V (``"exponential"`` path of :mod:`persson_fp.solvers.chebyshev`) or do
so through a common factor only (``"clock"`` path, in the clock tau), every load p_bar evolves under the same
operator :math:`\mathcal L P = \tfrac12 (bP)'' - (cP)'` with absorbing walls; only the start
:math:`\delta(p - \bar p)` differs.  The transition density is the biorthogonal eigenfunction expansion

.. math::  K(p, s \mid \bar p) = \sum_k \frac{\varphi_k(p)\,\psi_k(\bar p)}{N_k}\,e^{\lambda_k s}, \qquad
           N_k = \int \varphi_k \psi_k\,dp,

with :math:`\varphi_k` the eigenfunctions of :math:`\mathcal L` (forward) and :math:`\psi_k` those of its adjoint
:math:`\mathcal G u = \tfrac12 b u'' + c u'` (backward), both with Dirichlet walls and the same eigenvalues
:math:`\lambda_k < 0`.  The operator is symmetric in the speed measure, so that :math:`\varphi_k = m\,\psi_k` with
:math:`m = e^{\int_0^p 2c/b} / b` (up to a constant): one eigendecomposition, of the Chebyshev collocation matrix of
:math:`\mathcal G` on one plain Chebyshev grid of [0, p_max] (its right eigenvectors: spectrally accurate for the
modes the grid resolves; m by the Chebyshev derivative's inverse), N_k by Clenshaw--Curtis, :math:`\psi_k(\bar p)`
by barycentric interpolation (spectral in p_bar: the eigenfunctions are smooth).  The modes the grid does not
resolve are damped by :math:`e^{\lambda_k s}` at every station the grid is fit for (the degree is raised until
the estimate below meets tol).  No start expansion at a small V0 is
needed: the delta is exact at s = 0.  (Feeding the delta to the forward collocation alone, as the nodal vector
:math:`\ell_i(\bar p)/w_i`, converges only algebraically, ~n^-3: the collocation matrix is not self-adjoint in the
quadrature's inner product, so its left eigenvectors are not the adjoint eigenfunctions.)

Everything per load is a matrix product with the shared modes: P at the nodes (loads x modes times modes x nodes),
the areas and loads (quadratures), the mass out through the far wall (A_pl with a hardness) as the exit
probability :math:`h(\bar p, s) = h_\infty(\bar p) - \int K h_\infty\,dp` with :math:`\mathcal G h_\infty = 0`,
:math:`h_\infty(0) = 0, h_\infty(p_{max}) = 1`, and the drift's moment of the first-moment law likewise with
:math:`\mathcal G g_\infty = -c` (both collocation solves, shared).  Memory per load is its P at the stations and a
few vectors of the degree's size; the operator's work is done once.

Error estimate: the difference from a partner run at a lower degree, the last degree tried (1/1.3 of this one)
or 3/4 of it (per station and load; interpolated onto this grid, one matrix for all loads), plus twice the
far-wall mass (no hardness) and the round-off floor of ``collocation.roundoff_floor``
(:mod:`persson_fp.solvers.chebyshev.collocation`).  Used by method ``"chebyshev"``
(:mod:`persson_fp.solvers.chebyshev.solver`) for any number of loads where the degree the common grid needs is
within reach (``N_SHARED_MAX``); otherwise the per-load path runs.
"""

from __future__ import annotations

import math
import time

import numpy as np

from persson_fp.solvers.base import SolverOutput
from persson_fp.solvers.chebyshev import collocation

__all__ = ["solve_shared", "shared_memory", "SharedModes", "lagrange_rows"]

CHUNK = 256
"""Loads whose temporaries (the partner's P at a station, differences) are held at once."""
N_SHARED_MAX = 300
"""Largest degree of the common grid (two dense eigendecompositions of that size: ~0.2 s); beyond it the per-load
path (grids clustered at each load) runs instead."""


def estimate_entry(est: dict, method: str, parts: dict) -> dict:
    """The solver output's ``error_estimate`` from the per-quantity estimates ``est`` (the contact area is the
    elastic area of a problem with walls), with the words of ``method`` and the estimate's ``parts``."""
    return {
        "L1": est["L1"],
        "elastic_area": est["contact_area"],
        "plastic_area": est["plastic_area"],
        "noncontact_area": est["noncontact_area"],
        "load": est["load"],
        "method": method,
        "parts": parts,
    }


def shared_memory(n: int, n_loads: int, n_stations: int) -> float:
    """Bytes a shared run at degree ``n`` holds at its peak: per load and station its P (8 (n + 1)) and ~25
    scalars (areas, loads, estimates of the run and its partner: 200), the temporaries of one chunk of
    :data:`CHUNK` loads (the partner's P at a station, its difference: 16 (n + 1) a load), and the operators'
    dense matrices (~ 10 x 16 (n + 1)^2: eigenvectors of both operators, their products).  Measured
    (tracemalloc): 1.23 / 1.54 MB for 512 / 1024 loads at n = 65 (1 station), here 1.66 / 2.04 MB."""
    per_load = (8.0 * (n + 1) + 200.0) * n_stations
    return per_load * n_loads + 16.0 * (n + 1) * min(n_loads, CHUNK) * n_stations + 160.0 * (n + 1) ** 2 + 3e5


def lagrange_rows(x_nodes: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The Chebyshev--Lobatto cardinal functions at points ``x`` (barycentric; rows sum to 1): (len(x), n + 1)."""
    n = x_nodes.size - 1
    wb = np.ones(n + 1)
    wb[0] = wb[-1] = 0.5
    wb *= (-1.0) ** np.arange(n + 1)
    d = x[:, None] - x_nodes[None, :]
    exact = d == 0.0
    d[exact] = 1.0
    t = wb / d
    rows = t / t.sum(axis=1, keepdims=True)
    hit = exact.any(axis=1)
    if np.any(hit):
        rows[hit] = exact[hit].astype(float)
    return rows


class SharedModes:
    """The biorthogonal modes of the collocated forward and backward operators on one plain Chebyshev grid.

    Parameters
    ----------
    n : int
        Degree.
    p_max : float, pressure
        The far wall (sigma_Y with a hardness).
    cf : Coefficients
        b, c per unit V (:mod:`persson_fp.solvers.chebyshev.coefficients`), taken at V_max.

    Attributes
    ----------
    ok : bool
        False where the modes cannot be paired (an eigenvalue with a positive real part, or forward and backward
        eigenvalues that disagree on a mode the stations keep): the caller then uses the per-load path.
    """

    def __init__(self, n: int, p_max: float, cf):
        g = self.grid = collocation.chebyshev_grid(n, p_max, np.array([0.5 * p_max]), np.array([1e6 * p_max]))
        self.n, self.p_max = n, p_max
        p = g.p[0]
        b, c = cf.at(g.p)
        D1, D2 = g.D1[0], g.D2[0]
        self.L = collocation.generator(g, b, c)[0]  # (the forward operator: its round-off floor)
        Gfull = 0.5 * b[0][:, None] * D2 + (0.0 if c is None else c[0][:, None] * D1)
        Gb = Gfull[1:-1, 1:-1]
        lam, U = np.linalg.eig(Gb)
        order = np.argsort(-lam.real, kind="stable")
        lam, U = lam[order], U[:, order]
        # the speed density m = exp(int_0^p 2 c / b) / b (up to a constant): phi_k = m psi_k
        with np.errstate(all="ignore"):
            m = 1.0 / b[0]
            if c is not None:  # int_0^p 2 c / b by the Chebyshev derivative with I(0) = 0 (spectral)
                expo = np.zeros(n + 1)
                expo[1:] = np.linalg.solve(D1[1:, 1:], (2.0 * c[0] / b[0])[1:])
                m = m * np.exp(expo - np.max(expo[1:-1]))
        m = m[1:-1]
        w = g.w[0, 1:-1]
        N = np.sum((w * m)[:, None] * U * U, axis=0)
        self.real = not np.any(lam.imag != 0.0)
        if self.real:
            U, N, lam = U.real, N.real, lam.real
        self.lam, self.U, self.N, self.m = lam, U, N, m
        self.w_int, self.p_int = w, p[1:-1]
        # exit at the far wall, eventually (G h = 0, h(0) = 0, h(p_max) = 1), and the drift's moment (G g = -c)
        h = np.zeros(n + 1)
        h[-1] = 1.0
        h[1:-1] = np.linalg.solve(Gb, -Gfull[1:-1, -1])
        self.h_inf = h
        self.g_inf = None
        if c is not None:
            gi = np.zeros(n + 1)
            gi[1:-1] = np.linalg.solve(Gb, -c[0][1:-1])
            self.g_inf = gi
        scale = np.sum((w * m)[:, None] * np.abs(U) ** 2, axis=0)
        self.ok = bool(
            np.all(np.isfinite(m)) and np.all(m > 0) and np.all(np.isfinite(N)) and np.all(lam.real < 0)
        ) and bool(np.all(np.abs(N) >= 1e-10 * scale))

    def coefficients_of(self, p_bar: np.ndarray) -> np.ndarray:
        """psi_k(p_bar) / N_k, (n_loads, modes): the start's weight on each mode."""
        x = self.grid.x_of_p(np.broadcast_to(p_bar, (1, p_bar.size)))[0]
        rows = lagrange_rows(self.grid.x, np.clip(x, -1.0, 1.0))[:, 1:-1]  # (psi = 0 on the walls)
        return (rows @ self.U) / self.N

    def density(self, C: np.ndarray, s: float) -> np.ndarray:
        """P at the interior nodes after the span ``s`` (pressure^2, a clock increment on the clock path), per
        load: (n_loads, n - 1)."""
        with np.errstate(under="ignore"):
            e = np.exp(self.lam * s)
        P = ((C * e) @ self.U.T) * self.m
        return P.real if not self.real else P


def _run(modes: SharedModes, p_bar, spans, out=None):
    """(A, F, far-wall mass, drift moment), each (stations, loads), of one grid; P at the nodes (wall zeros
    included) written into ``out`` (stations, loads, n + 1) if given.  A drift-free problem has no moment (0)."""
    C = modes.coefficients_of(p_bar)
    x = modes.grid.x_of_p(np.broadcast_to(p_bar, (1, p_bar.size)))[0]
    rows = lagrange_rows(modes.grid.x, np.clip(x, -1.0, 1.0))
    h_at, g_at = rows @ modes.h_inf, (None if modes.g_inf is None else rows @ modes.g_inf)
    w, p = modes.w_int, modes.p_int
    h_in = w * modes.h_inf[1:-1]
    shape = (len(spans), p_bar.size)
    A, F, far, moment = np.zeros(shape), np.zeros(shape), np.zeros(shape), np.zeros(shape)
    for k, s in enumerate(spans):
        Pk = modes.density(C, s)
        if out is not None:
            out[k, :, 1:-1] = Pk
        A[k], F[k] = Pk @ w, Pk @ (w * p)
        far[k] = h_at - Pk @ h_in
        if g_at is not None:
            moment[k] = g_at - Pk @ (w * modes.g_inf[1:-1])
    return A, F, far, moment


def _l1_difference(main: SharedModes, part: SharedModes, P, p_bar, spans):
    """int |P - P_partner| dp per station and load, the partner's polynomial at this grid's nodes (one
    interpolation matrix for every station and load: the two grids share p_max)."""
    interp = lagrange_rows(part.grid.x, main.grid.x)[1:-1, 1:-1]  # (the walls: 0 in both)
    C2 = part.coefficients_of(p_bar)
    L1 = np.zeros((len(spans), p_bar.size))
    for k, s in enumerate(spans):
        L1[k] = np.abs(P[k, :, 1:-1] - part.density(C2, s) @ interp.T) @ main.w_int
    return L1


def solve_shared(solver, tol: float) -> SolverOutput | None:
    """The loads of ``solver`` (a :class:`~persson_fp.solvers.chebyshev.ChebyshevSolver` on its ``"exponential"``
    or ``"clock"`` path) on one common grid (module docstring); None where that grid would need more than
    :data:`N_SHARED_MAX` or its modes do not pair (the caller then runs the per-load path)."""
    pr, cf, sigma = solver.problem, solver._cf, solver._sigma
    pb = pr.p_bar.astype(float)
    V_out = np.asarray(solver.V_out, dtype=float)
    p_max, k_dom = solver._domain(tol, float(V_out[-1]))
    spans = V_out if solver.path == "exponential" else np.array([cf.tau(0.0, float(V)) for V in V_out])
    if not (np.all(cf.at(pb)[0] > 0) and np.all(spans > 0)):
        return None  # (the per-load path names the cause)
    # the first degree: the geometric mean of p_max in kernel widths sqrt(b s) at the loads and of the Lamperti
    # length of [0, p_max] in widths sqrt(s), at the first station (the plain grid's spacing is uniform in arccos,
    # neither in p nor in the Lamperti distance).  The degrees the estimate settles at (homogenised, and B2 =
    # (1 + p / (2 p0)) V' with loads 1e-3..3 sqrt(V)) are 2.5-2.7x that mean at tol 1e-4, 3.2-3.5x at 1e-6
    s_min = float(np.min(spans))
    widths = p_max / math.sqrt(float(np.min(cf.at(pb)[0])) * s_min)
    y_len = float(collocation.lamperti_distance(lambda q: cf.at(q)[0], np.array(0.0), np.array(p_max)))
    n = max(24, int(math.ceil((1.2 + 0.3 * math.log10(1.0 / tol)) * math.sqrt(widths * y_len / math.sqrt(s_min)))))
    deadline = time.perf_counter() + solver.max_time
    runs, prev = 0, None
    while True:
        if n > N_SHARED_MAX:
            return None
        n2 = max(16, int(round(0.75 * n)))  # (the first partner's degree)
        need = shared_memory(n, pb.size, spans.size)
        if need > solver.max_memory:
            raise ValueError(
                f"chebyshev: {pb.size} loads on a common grid of degree {n} would need about {need / 2**20:.3g} MiB "
                f"of memory (estimate), more than max_memory = {solver.max_memory / 2**20:.3g} MiB; use fewer loads "
                "per call or pass a larger max_memory (bytes)"
            )
        main = SharedModes(n, p_max, cf)
        # the partner: the last degree's modes (n / 1.3) where there is one, else a run at 3/4 of the degree
        part = prev if prev is not None else SharedModes(n2, p_max, cf)
        if not (main.ok and part.ok):
            return None
        # in chunks of loads: the temporaries (the partner's P, differences) stay within CHUNK loads
        P = A = F = far = moment = A2 = F2 = far2 = L1 = est = None  # (the last degree's: released first)
        P = np.zeros((spans.size, pb.size, n + 1))
        A, F, far, moment = (np.zeros((spans.size, pb.size)) for _ in range(4))
        A2, F2, far2, L1 = (np.zeros((spans.size, pb.size)) for _ in range(4))
        for lo in range(0, pb.size, CHUNK):
            ch = slice(lo, lo + CHUNK)
            A[:, ch], F[:, ch], far[:, ch], moment[:, ch] = _run(main, pb[ch], spans, P[:, ch])
            A2[:, ch], F2[:, ch], far2[:, ch], _ = _run(part, pb[ch], spans)
            L1[:, ch] = _l1_difference(main, part, P[:, ch], pb[ch], spans)
        runs += 1 if part is prev else 2
        hard = sigma is not None
        floor = np.maximum(
            4.0 * np.finfo(float).eps * n * n, collocation.roundoff_floor(main.L[None], float(spans[-1]), n)[0]
        )
        # (in place, the partner's arrays released as they are used: the peak is the run's P and a few scalars a
        # load and station)
        common = (0.0 if hard else 2.0 * np.maximum(far, 0.0)) + floor
        A_pl = far if hard else None
        est = {"L1": L1}
        L1 += common
        dA = np.abs(A - A2)
        dA += common
        est["contact_area"] = np.maximum(dA, L1, out=dA)
        A2 += far2 if hard else 0.0
        A2 -= A
        if hard:
            A2 -= far
            far2 -= far
            np.abs(far2, out=far2)
            far2 += floor
        est["plastic_area"] = far2 if hard else np.zeros_like(A)
        np.abs(A2, out=A2)
        A2 += common
        est["noncontact_area"] = A2
        F2 -= F
        np.abs(F2, out=F2)
        F2 /= pb
        F2 += common * np.maximum(1.0, 0.1 * p_max / pb)
        est["load"] = F2
        del common
        np.maximum(est["noncontact_area"], est["L1"] + est["plastic_area"], out=est["noncontact_area"])
        worst = max(float(np.max(est[q])) for q in ("L1", "contact_area", "plastic_area", "noncontact_area"))
        if worst <= tol:
            break
        if float(np.max(floor)) >= 0.3 * worst or time.perf_counter() > deadline:
            return None  # (the per-load path refuses it with its own reasons, or reaches it)
        n, prev = int(math.ceil(1.3 * n)), main
    law = pb + moment - (0.0 if hard else p_max * far)
    info = {
        "path": solver.path,
        "loads": "shared: one eigendecomposition of the collocated operator and of its adjoint for every load",
        "grid": {
            "n_p": n,
            "p_max": np.full(V_out.size, p_max),
            "k_domain": None if hard else k_dom,
            "mapping": "plain Chebyshev on [0, p_max], common to every load and station",
            "centre": np.array([0.5 * p_max]),
            "eps": np.array([1e6 * p_max]),
            "modes": int(np.count_nonzero(main.lam.real * float(np.min(spans)) > -37.0)),
        },
        "V0_fraction": 0.0,
        "zeta0": np.ones(V_out.size),
        "runs": runs,
        "error_estimate": estimate_entry(
            est,
            "|run - run at the last degree tried (or 3/4 degree)| + 2 x far-wall mass "
            "+ max(4 eps n^2, eps ||L dV||_1 (n/400)^2)",
            {"time": np.zeros_like(A), "roundoff": np.broadcast_to(floor, A.shape).copy()},
        ),
        "far_wall_mass": np.zeros_like(far) if hard else far,
        "load_law": law,
        "load_law_tolerance": est["load"] * pb,
        "mass_balance_residual": 0.0,  # (the mass out at p = 0 is 1 - A - far by construction: G (1 - h_inf) = 0)
    }
    # the polynomial's ripple where P is ~0 (tails, next to the walls), within the estimate: set to 0 in place
    info["ripple_zeroed"] = 0
    for Pk in P:  # (a station at a time: no full-size temporaries)
        ripple = (Pk < 0) & (Pk > -1e-6 * np.max(Pk, axis=-1, keepdims=True))
        Pk[ripple] = 0.0
        info["ripple_zeroed"] += int(np.count_nonzero(ripple))
    return SolverOutput(
        p=main.grid.p[0],
        P0=P,
        weights=main.grid.w[0],
        kind="point",
        info=info,
        contact_area=A,
        load=F,
        plastic_area=A_pl,
    )
