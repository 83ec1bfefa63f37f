"""Drive one of scipy's ``OdeSolver`` classes to output stations, keeping memory linear in the unknowns.

``solve_ivp(..., dense_output=True)`` keeps every step's interpolant (BDF: (order + 1) x n numbers per
step) and ``sol(t)`` evaluates *all* n unknowns at every requested t.  For a batch of loads that each
have their own station times (mol with a fudge factor: load j reaches V(zeta_k) at its own tau) that
is memory O(steps x n) and work O(loads x stations x n), i.e. quadratic in the number of loads.  Here
the solver is stepped by hand; only the current step's interpolant is alive, and a station inside a
step is evaluated on that load's own rows only (:func:`restrict`).

Stiff solvers with a sparse Jacobian factor ``I - c J`` with SuperLU in its natural column order
(:func:`natural_order_lu`): mol's Jacobian is banded per load with one extra row per load, which the
natural order factors without fill beyond those rows, while SuperLU's default COLAMD order made each
factorization ~7x and each solve ~25x slower (measured, 100 loads, 22800 unknowns).
"""

from __future__ import annotations

import copy
import time
import weakref

import numpy as np
import scipy.integrate as si
from scipy.sparse import issparse
from scipy.sparse.linalg import splu

__all__ = ["make_solver", "restrict", "march_shared", "march_own"]


def make_solver(method: str, fun, t0: float, y0, t_bound: float, blocks=None, **kw):
    """A scipy ``OdeSolver`` (``method`` as in ``solve_ivp``) with a structure-aware LU for a sparse Jacobian.

    ``blocks = (n_loads, m)``: the Jacobian is ``[[diag(K, ..., K), 0], [R, 0]]`` -- one m x m block K shared
    by the n_loads loads, then ``n_extra`` rows R (``y0.size - n_loads m``, 0 or n_loads) -- and
    :func:`shared_block_lu` factors only K.  Otherwise SuperLU in natural order (:func:`natural_order_lu`).
    """
    solver = getattr(si, method)(fun, t0, y0, t_bound, **kw)
    if method == "BDF":  # scipy allocates the difference table with np.empty and reads rows it has not written yet
        solver.D[2:] = 0.0  # (harmless garbage, but inf - inf under np.seterr(invalid="raise")); zero them
    if method in ("BDF", "Radau") and issparse(getattr(solver, "J", None)):
        if blocks is not None:
            shared_block_lu(solver, *blocks)
        else:
            natural_order_lu(solver)
    return solver


def shared_block_lu(solver, n_loads: int, m: int) -> None:
    """LU of ``a I - c J`` for ``J = [[diag(K, ..., K), 0], [R, 0]]``: factor the m x m block once.

    The matrix is ``[[diag(M, ..., M), 0], [B, E]]`` with M = a I - c K and E diagonal, so
    ``x_P = M^-1 b_P`` for all loads at once (one sparse LU, n_loads right-hand sides) and
    ``x_V = (b_V - B x_P) / E``.  Work and memory O(n_loads m) per factorization and per solve.
    """
    n = n_loads * m

    owner = weakref.ref(solver)  # no reference cycle: the solver's arrays go as soon as it does

    def lu(A):
        owner().nlu += 1
        A = A.tocsr()
        M = splu(A[:m, :m].tocsc(), permc_spec="NATURAL")
        if A.shape[0] == n:
            return M, None, None
        return M, A[n:, :n], A.diagonal()[n:]

    def solve_lu(LU, b):
        M, B, E = LU
        xP = M.solve(np.ascontiguousarray(b[:n].reshape(n_loads, m).T)).T.ravel()
        if B is None:
            return xP
        return np.concatenate([xP, (b[n:] - B @ xP) / E])

    solver.lu = lu
    solver.solve_lu = solve_lu


def natural_order_lu(solver) -> None:
    """Replace the solver's sparse LU (``solver.lu``, counted in ``nlu``) by SuperLU with natural ordering."""

    owner = weakref.ref(solver)  # no reference cycle: the solver's arrays go as soon as it does

    def lu(A):
        owner().nlu += 1
        return splu(A.tocsc(), permc_spec="NATURAL")

    solver.lu = lu


def restrict(interp, rows):
    """The step interpolant ``interp`` (a scipy ``DenseOutput``) for the unknowns ``rows`` only.

    The BDF, Radau, RK23/RK45, DOP853 and LSODA interpolants are polynomials whose coefficient arrays have
    one row (or column) per unknown: slicing them gives the same numbers as ``interp(t)[rows]`` at the cost
    of ``rows`` alone.  Any other interpolant is called whole and sliced.
    """
    out = copy.copy(interp)
    if hasattr(out, "D"):  # BDF: D (order + 1, n)
        out.D = out.D[:, rows]
    elif hasattr(out, "Q") and hasattr(out, "y_old"):  # Radau, RK23, RK45: Q (n, k), y_old (n,)
        out.Q, out.y_old = out.Q[rows], out.y_old[rows]
    elif hasattr(out, "F") and hasattr(out, "y_old"):  # DOP853: F (k, n)
        out.F, out.y_old = out.F[:, rows], out.y_old[rows]
    elif hasattr(out, "yh"):  # LSODA: yh (n, order + 1)
        out.yh = out.yh[rows]
    else:
        return lambda t: np.asarray(interp(t))[rows]
    return out


class BudgetExceeded(RuntimeError):
    """The march ran past its deadline (the solver's ``max_time``)."""


def _step(solver, name, deadline=None):
    msg = solver.step()
    if solver.status == "failed":
        raise RuntimeError(f"{name}: the integrator failed ({msg})")
    if deadline is not None and time.perf_counter() > deadline:
        raise BudgetExceeded(f"{name}: max_time exceeded at t = {solver.t:.6g}")


def march_shared(solver, t_out, name: str = "solve_ivp", deadline=None):
    """Step to the end and return y at the shared stations ``t_out`` (increasing; the last = t_bound).

    Returns (Y of shape (n, len(t_out)), number of steps).  The last station is the step point itself.
    """
    t_out = np.asarray(t_out, float)
    Y = np.empty((solver.n, t_out.size))
    k, steps = 0, 0
    while k < t_out.size:
        if solver.status == "finished":
            raise RuntimeError(f"{name}: reached {solver.t:.6g} before the station {t_out[k]:.6g}")
        _step(solver, name, deadline)
        steps += 1
        j = k
        while j < t_out.size and t_out[j] <= solver.t:
            j += 1
        if j > k:
            inside = t_out[k:j]
            at_end = inside >= solver.t
            if np.any(~at_end):
                Y[:, k:j][:, ~at_end] = solver.dense_output()(inside[~at_end]).reshape(solver.n, -1)
            Y[:, k:j][:, at_end] = solver.y[:, None]
            k = j
    return Y, steps


def march_own(solver, V_rows, P_rows, V_out, S_of, name: str = "solve_ivp", newton_max: int = 20, deadline=None):
    """Step until every load j has passed ``V_out[-1]`` in its own unknown ``y[V_rows[j]]`` (increasing in t).

    At each crossing of a station ``V_out[k]`` by load j, the time is refined by Newton's method on the step
    interpolant restricted to that load's rows: dV_j/dt = 1 / S(P_j) is known (``S_of(P, j)``, P of shape
    (..., len(P_rows[j]))).  Returns (t_st (n_stations, n_loads), P_st (n_stations, n_loads, m), steps).
    """
    V_rows = np.asarray(V_rows)
    nl, n_z, m = V_rows.size, len(V_out), P_rows.shape[1]
    V_out = np.asarray(V_out, float)
    t_st = np.empty((n_z, nl))
    P_st = np.empty((n_z, nl, m))
    nxt = np.zeros(nl, dtype=int)  # next station of each load
    steps = 0
    V_old = solver.y[V_rows].copy()
    while np.any(nxt < n_z):
        if solver.status == "finished":
            raise RuntimeError(f"{name}: reached t = {solver.t:.6g} before every load's last station")
        t_old = solver.t
        _step(solver, name, deadline)
        steps += 1
        V_new = solver.y[V_rows]
        crossed = np.flatnonzero((nxt < n_z) & (V_new >= V_out[np.minimum(nxt, n_z - 1)]))
        if crossed.size:
            interp = solver.dense_output()
            for j in crossed:
                k1 = int(np.searchsorted(V_out, V_new[j], side="right"))
                ks = np.arange(nxt[j], k1)
                rows = np.concatenate([P_rows[j], [V_rows[j]]])
                f = restrict(interp, rows)
                # start: linear in the step, then Newton on V_j(t) = V_out[k]
                frac = (V_out[ks] - V_old[j]) / max(V_new[j] - V_old[j], 1e-300)
                t = t_old + np.clip(frac, 0.0, 1.0) * (solver.t - t_old)
                lo, hi = min(t_old, solver.t), max(t_old, solver.t)
                for _ in range(newton_max):
                    Y = np.asarray(f(t)).reshape(m + 1, -1)
                    dt = (Y[m] - V_out[ks]) * S_of(Y[:m].T, j)
                    t = np.clip(t - dt, lo, hi)
                    if np.all(np.abs(dt) <= 1e-15 * np.abs(t)):
                        break
                Y = np.asarray(f(t)).reshape(m + 1, -1)
                t_st[ks, j] = t
                P_st[ks, j] = Y[:m].T
                nxt[j] = k1
        V_old = V_new.copy()
    return t_st, P_st, steps
