"""The hand-stepped solve_ivp driver of mol (``mol/ivp_march.py``) against scipy's own machinery.

References are independent of the driver: scipy's full dense output (``interp(t)``), ``spsolve`` of the
assembled matrix, and ``solve_ivp(dense_output=True)`` of the same system.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.integrate import solve_ivp
from scipy.sparse.linalg import spsolve

from persson_fp.solvers.mol import ivp_march as _ivp_march
from persson_fp.solvers.mol import laplacian


def _system(nl=3, m=12, coupled=True):
    """dP_j/dt = K P_j / 2 with a shared Laplacian block K; with ``coupled`` dV_j/dt = 1 + (w . P_j)^2."""
    K = laplacian(m, 1.0 / (m + 1), 2).tocsr()
    n = nl * m
    w = np.full(m, 1.0 / (m + 1))
    Kb = sp.kron(sp.identity(nl), K, format="csr")

    def fun(t, y):
        out = np.empty_like(y)
        out[:n] = 0.5 * (Kb @ y[:n])
        if coupled:
            out[n:] = 1.0 + (y[:n].reshape(nl, m) @ w) ** 2
        return out

    def jac(t, y):
        top = sp.hstack([0.5 * Kb, sp.csr_matrix((n, nl if coupled else 0))])
        if not coupled:
            return top.tocsr()
        A = y[:n].reshape(nl, m) @ w
        rows = np.repeat(np.arange(nl), m)
        bot = sp.csr_matrix(((2 * A[:, None] * w[None, :]).ravel(), (rows, np.arange(n))), shape=(nl, n + nl))
        return sp.vstack([top, bot], format="csr")

    x = (np.arange(1, m + 1) / (m + 1))[None, :]
    P0 = np.sin(np.pi * x) * np.array([1.0, 2.0, 0.5][:nl])[:, None]
    y0 = np.concatenate([P0.ravel(), np.zeros(nl)]) if coupled else P0.ravel()
    return fun, jac, y0, n


@pytest.mark.parametrize("method", ["BDF", "Radau", "RK45", "RK23", "DOP853", "LSODA"])
def test_restricted_interpolant_equals_the_full_one(method):
    fun, jac, y0, n = _system()
    kw = {"jac": jac} if method in ("BDF", "Radau", "LSODA") else {}
    s = _ivp_march.make_solver(method, fun, 0.0, y0, 1.0, **kw)
    for _ in range(3):
        s.step()
    interp = s.dense_output()
    rows = np.array([2, 5, n + 1])
    t = np.linspace(s.t_old, s.t, 4)
    np.testing.assert_allclose(_ivp_march.restrict(interp, rows)(t), interp(t)[rows], rtol=1e-14, atol=1e-300)


@pytest.mark.parametrize("coupled", [True, False])
@pytest.mark.parametrize("a", [1.0, 3.7 + 1.2j])
def test_shared_block_lu_solves_the_assembled_matrix(coupled, a):
    fun, jac, y0, n = _system(coupled=coupled)
    s = _ivp_march.make_solver("BDF", fun, 0.0, y0, 1.0, jac=jac, blocks=(3, 12))
    J = jac(0.0, y0 + 0.3)
    A = (a * sp.identity(J.shape[0]) - 0.05 * J).tocsc()
    b = np.cos(np.arange(J.shape[0]) + 0.5)
    # spsolve of the assembled matrix: an independent direct solve; both are backward stable (~1e-15)
    np.testing.assert_allclose(s.solve_lu(s.lu(A), b), spsolve(A, b.astype(A.dtype)), rtol=1e-12, atol=1e-14)


@pytest.mark.parametrize("method", ["BDF", "Radau", "LSODA"])
def test_march_own_hits_each_loads_stations(method):
    """V_j(t) reaches V_out at the station the driver reports, and P_j there equals solve_ivp's dense output."""
    fun, jac, y0, n = _system()
    nl, m = 3, 12
    V_out = np.array([0.2, 0.5, 0.9])
    w = np.full(m, 1.0 / (m + 1))
    S_of = lambda P, j: 1.0 / (1.0 + (P @ w) ** 2)  # dt/dV_j = 1 / (dV_j/dt)
    kw = dict(rtol=1e-10, atol=1e-12, jac=jac)
    s = _ivp_march.make_solver(method, fun, 0.0, y0, 5.0, blocks=(nl, m), **kw)
    t_st, P_st, steps = _ivp_march.march_own(s, n + np.arange(nl), np.arange(n).reshape(nl, m), V_out, S_of)
    ref = solve_ivp(fun, (0.0, float(t_st.max())), y0, method=method, dense_output=True, **kw)
    for j in range(nl):
        Y = ref.sol(t_st[:, j])
        # the station is where V_j = V_out (to the integrators' tolerance, 1e-10 relative)
        np.testing.assert_allclose(Y[n + j], V_out, rtol=1e-8)
        np.testing.assert_allclose(P_st[:, j], Y[j * m : (j + 1) * m].T, rtol=1e-7, atol=1e-9)
    assert steps > 3


def test_march_shared_returns_the_stations():
    fun, jac, y0, n = _system(coupled=False)
    t_out = np.array([0.01, 0.05, 0.2])
    s = _ivp_march.make_solver("BDF", fun, 0.0, y0, 0.2, jac=jac, blocks=(3, 12), rtol=1e-10, atol=1e-13)
    Y, steps = _ivp_march.march_shared(s, t_out)
    ref = solve_ivp(fun, (0.0, 0.2), y0, method="BDF", t_eval=t_out, jac=jac, rtol=1e-10, atol=1e-13)
    np.testing.assert_allclose(Y, ref.y, rtol=1e-7, atol=1e-10)
