r"""The method of lines on the front-fixed fluxes of :mod:`persson_fp.solvers.front_fixed.moving_wall` (``"mol"``).

The same semi-discrete system as ``"fv"``'s moving wall and general coefficients (the engine's conservative fluxes,
the wall masses as extra unknowns), integrated in V by ``scipy.integrate.solve_ivp`` with a banded Jacobian.
"""

from __future__ import annotations

import numpy as np

from persson_fp.results.solution import SolverError
from persson_fp.solvers.front_fixed import fluxes
from persson_fp.solvers.front_fixed.moving_wall import MovingWall

__all__ = ["solve_lines", "DRAINED"]

DRAINED = 1e-12
"""mol on the engine: a run stops once the mass that can still reach a station (the elastic cells, plus a moving
yield wall's plastic area) is below this fraction of its start for every load (:func:`solve_lines`)."""


def solve_lines(
    mw: MovingWall,
    V_st,
    rtol: float,
    atol: float,
    integrator: str,
    tau0_fraction: float,
    V0=None,
    y0=None,
    source=None,
    drained: float = DRAINED,
    per_mass: bool = False,
    level: int = 0,
):
    """The method of lines on the same fluxes: ``solve_ivp`` in V on y = (w, A_pl, A_non) per load, with S at
    the current total contact area and a banded Jacobian (S frozen: exact for the linear part).  Returns the
    per-station dict of :meth:`MovingWall.solve`.

    ``per_mass``: ``atol`` is relative to each load's mass in play at the start (its elastic and wall cells, ~A* at
    V0): a tiny load (A* ~ p_bar / sqrt(V)) keeps the relative accuracy of a large one (an absolute atol of 1e-8 left
    p_bar = 1e-9 with 1.6 % error against an estimate of 1.2 %).  ``drained`` (relative to that mass, 0: never):
    the march stops once every load's mass in play is below it (a drift that has carried the PDF into a wall; the
    centred fluxes then ring at the tolerance and BDF resolved the ringing in steps of ~1e-7 in V, > 100 s); each
    later station holds what was left as absorbed at p = 0 (mass only leaves, so every later area is below it).
    ``level`` (the partner's, :func:`~persson_fp.solvers.front_fixed.estimate.run_pair`) changes nothing: time is
    controlled by ``rtol`` at every level."""
    import scipy.sparse as sp
    from scipy.integrate import solve_ivp

    pr = mw.problem
    S = pr.fudge.S
    m, n, h = pr.n_loads, mw.n, mw.h
    V_st = np.asarray(V_st, dtype=float)
    if V0 is None:
        V0 = mw.model.clear_start_V(mw, mw.choose_V0(float(V_st[0]), tau0_fraction))  # (as general_start)
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
        out[:, : n + 1] = fluxes.apply(fluxes.assemble(c, h), wa)
        if source is not None:
            out[:, : n + 1] += source(V)
        out[:, n + 1] = fluxes.outflux_low(c, wa, h)
        out[:, n + 2] = mw.drift_rate(V, wa)
        return out.ravel()

    def jac(V, y):
        wa, _ = split(y)
        S_now = np.ones(m) if mw.no_fudge else S(total_area(wa))
        c = mw.coefficients(V, S_now)
        ab = fluxes.assemble(c, h)
        blocks = []
        for j in range(m):
            Lj = sp.diags(
                [ab[j, 3, :-2], ab[j, 2, :-1], ab[j, 1], ab[j, 0, 1:]], [-2, -1, 0, 1], shape=(n + 1, n + 1)
            ).tolil()
            J = sp.lil_matrix((k, k))
            J[: n + 1, : n + 1] = Lj
            D_wall = np.atleast_2d(c.D if c.D_cells is None else c.D_cells)[j, 0]
            J[n + 1, 0] = -fluxes.AbsorbingWall.flux_coefficient(float(D_wall), h)
            mw.model.add_drift_jacobian(J, mw, V, n, h)
            blocks.append(J.tocsr())
        return sp.block_diag(blocks, format="csr")

    load0 = mw.load(V0, y0w)
    y0 = np.concatenate([y0w, A_non0[:, None], np.zeros((m, 1))], axis=1).ravel()
    back = pr.upper_wall.mass_back  # a moving yield wall hands its plastic area back (1); elsewhere it stays (0)
    mass0 = np.maximum(y0w[:, :n].sum(axis=1) * h + y0w[:, n], np.finfo(float).tiny)  # in play at V0, per load
    if per_mass:
        atol = np.repeat(atol * mass0, k)

    def remaining(V, y):  # the mass that can still reach a station, relative, above the drained level (an event)
        Y = y.reshape(m, k)
        M = Y[:, :n].sum(axis=1) * h + back * Y[:, n]
        return float(np.max(M / mass0)) - drained

    remaining.terminal, remaining.direction = True, -1.0
    try:
        res = solve_ivp(
            fun,
            (V0, float(V_st[-1])),
            y0,
            method=integrator,
            t_eval=V_st,
            rtol=rtol,
            atol=atol,
            jac=jac if integrator in ("BDF", "Radau") else None,
            events=remaining if drained > 0.0 and source is None else None,
        )
    except (RuntimeError, np.linalg.LinAlgError) as err:  # SuperLU: "Factor is exactly singular"
        mw.model.singular_step(err, "mol", pr, mw.p_end, needs="singular")
    if not res.success:
        raise SolverError(f"mol (moving wall): solve_ivp failed ({res.message})")
    Y = np.empty((V_st.size, m, k))
    got = len(res.t)  # (a list where the event ended the run before the first station)
    if got:
        Y[:got] = np.asarray(res.y).T.reshape(got, m, k)
    if got < V_st.size:  # drained (the event): every later area is below drained x mass0 (mass only leaves)
        y_end = res.y_events[0][-1].reshape(m, k).copy()
        y_end[:, n + 1] += y_end[:, :n].sum(axis=1) * h + back * y_end[:, n]  # to the wall p = 0
        y_end[:, :n] = 0.0
        y_end[:, n] *= 1.0 - back  # (what the wall hands back went to p = 0 too)
        Y[got:] = y_end
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
        "steps": got,
        "nfev": int(res.nfev),
        "njev": int(res.njev),
        "max_cell_peclet": float("nan"),
    }
