r"""The method of lines on the front-fixed fluxes of :mod:`persson_fp.solvers.engine.moving_wall` (``"mol"``).

The same semi-discrete system as ``"fv"``'s moving wall and general coefficients (the engine's conservative fluxes,
the wall masses as extra unknowns), integrated in V by ``scipy.integrate.solve_ivp`` with a banded Jacobian.
"""

from __future__ import annotations

import numpy as np

from persson_fp.results.solution import SolverError
from persson_fp.solvers.engine import fluxes as engine
from persson_fp.solvers.engine.estimate import finish, run_pair
from persson_fp.solvers.engine.moving_wall import MovingWall

__all__ = ["solve_lines", "solve_lines_cells"]


def solve_lines(
    mw: MovingWall, V_st, rtol: float, atol: float, integrator: str, tau0_fraction: float, V0=None, y0=None, source=None
):
    """The method of lines on the same fluxes: ``solve_ivp`` in V on y = (w, A_pl, A_non) per load, with S at
    the current total contact area and a banded Jacobian (S frozen: exact for the linear part).  Returns the
    per-station dict of :meth:`MovingWall.solve`."""
    import scipy.sparse as sp
    from scipy.integrate import solve_ivp

    pr = mw.problem
    S = pr.fudge.S
    m, n, h = pr.n_loads, mw.n, mw.h
    V_st = np.asarray(V_st, dtype=float)
    if V0 is None:
        V0 = mw.choose_V0(float(V_st[0]), tau0_fraction)
    if y0 is None:
        y0w, A_non0, A_pl0 = mw.start(V0)
    else:  # a given start, e.g. a manufactured solution
        y0w, A_non0, A_pl0 = np.array(y0, dtype=float), np.zeros(m), np.asarray(y0, dtype=float)[:, -1]
    k = n + 3  # unknowns per load: w (n), A_pl, A_non, the drift's load int int b1 P dp dV (first-moment law)

    def split(y):
        Y = y.reshape(m, k)
        return Y[:, : n + 1], Y[:, n + 1]

    def total_area(wa):
        return np.clip(wa[:, :n].sum(axis=1) * h + wa[:, n], 0.0, 1.0)

    calls = [0]

    def fun(V, y):
        calls[0] += 1
        if calls[0] % 64 == 0:
            mw.check_deadline(V)
        wa, _ = split(y)
        S_now = np.ones(m) if mw.no_fudge else S(total_area(wa))
        c = mw.coefficients(V, S_now)
        out = np.empty((m, k))
        out[:, : n + 1] = engine.apply(engine.assemble(c, h), wa)
        if source is not None:
            out[:, : n + 1] += source(V)
        out[:, n + 1] = engine.outflux_low(c, wa, h)
        out[:, n + 2] = mw.drift_rate(V, wa)
        return out.ravel()

    def jac(V, y):
        wa, _ = split(y)
        S_now = np.ones(m) if mw.no_fudge else S(total_area(wa))
        c = mw.coefficients(V, S_now)
        ab = engine.assemble(c, h)
        blocks = []
        for j in range(m):
            Lj = sp.diags(
                [ab[j, 3, :-2], ab[j, 2, :-1], ab[j, 1], ab[j, 0, 1:]], [-2, -1, 0, 1], shape=(n + 1, n + 1)
            ).tolil()
            J = sp.lil_matrix((k, k))
            J[: n + 1, : n + 1] = Lj
            D_wall = np.atleast_2d(c.D if c.D_cells is None else c.D_cells)[j, 0]
            J[n + 1, 0] = -engine.AbsorbingWall.flux_coefficient(float(D_wall), h)
            if mw.general:
                J[n + 2, :n] = mw.drift_cells(V) * h
            blocks.append(J.tocsr())
        return sp.block_diag(blocks, format="csr")

    load0 = mw.load(V0, y0w)
    y0 = np.concatenate([y0w, A_non0[:, None], np.zeros((m, 1))], axis=1).ravel()
    res = solve_ivp(
        fun,
        (V0, float(V_st[-1])),
        y0,
        method=integrator,
        t_eval=V_st,
        rtol=rtol,
        atol=atol,
        jac=jac if integrator in ("BDF", "Radau") else None,
    )
    if not res.success:
        raise SolverError(f"mol (moving wall): solve_ivp failed ({res.message})")
    Y = res.y.T.reshape(V_st.size, m, k)
    s_st = mw.wall_many(V_st)[0]
    W = Y[:, :, :n]
    return {
        "W": W,
        "s": s_st,
        "elastic_area": W.sum(axis=-1) * h,
        "plastic_area": Y[:, :, n],
        "noncontact_area": Y[:, :, n + 1],
        "elastic_load": s_st[:, None] * (W @ mw.x) * h,
        "plastic_load": s_st[:, None] * Y[:, :, n],
        "V0": V0,
        "zeta0": float(mw.zeta(V0)[0]),
        "start_plastic_area": float(np.max(A_pl0)),
        "start_load": load0,
        "drift_load": Y[:, :, n + 2],
        "steps": int(res.t.size),
        "nfev": int(res.nfev),
        "njev": int(res.njev),
        "max_cell_peclet": float("nan"),
    }


def solve_lines_cells(
    solver,
    n: int,
    rtol: float,
    atol: float,
    integrator: str,
    tau0_fraction: float,
    tol,
    zeta0=None,
    k_domain: float = 10.0,
):
    """The moving-wall run of ``"mol"``: n cells and its partner at n/2 (time by ``rtol``)."""
    fine, coarse = run_pair(
        solver,
        n,
        zeta0,
        k_domain,
        lambda mw, V_st, V0, _: solve_lines(mw, V_st, rtol, atol, integrator, tau0_fraction, V0),
    )
    what = f"|Q(n_p) - Q(n_p/2)|, n_p = {n}, rtol = {rtol:g} (conservative in p; time by rtol)"
    info = {"steps": fine["steps"], "integrator": integrator, "nfev": fine["nfev"], "njev": fine["njev"]}
    return finish(solver, n, fine, coarse, what, tol, info)
