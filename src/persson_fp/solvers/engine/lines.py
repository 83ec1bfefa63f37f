r"""The method of lines on the front-fixed fluxes of :mod:`persson_fp.solvers.engine.moving_wall` (``"mol"``).

The same semi-discrete system as ``"fv"``'s moving wall and general coefficients (the engine's conservative fluxes,
the wall masses as extra unknowns), integrated in V by ``scipy.integrate.solve_ivp`` with a banded Jacobian.
"""

from __future__ import annotations

import numpy as np

from persson_fp.results.solution import SolverError
from persson_fp.solvers.engine import fluxes as engine
from persson_fp.solvers.engine.estimate import finish, run_pair
from persson_fp.solvers.engine.moving_wall import MovingWall, check_resolved, domain_end

__all__ = [
    "solve_lines",
    "solve_lines_cells",
    "clear_start_V",
    "check_wall_peclet",
    "general_start",
    "singular_step_error",
]

START_CLEARANCE = 6.0
"""General coefficients: a start-up Gaussian whose drift moved it by more than its width must lie at least this many
widths inside the domain (:func:`clear_start_V`; the image start then puts < 1e-9 of its mass beyond a wall)."""
PECLET_MAX = 50.0
"""General coefficients: the largest cell Peclet number 2 |B1| dp / B2 accepted where the PDF meets a wall
(:func:`check_wall_peclet`).  Measured with B1 = const < 0, p_bar = 0.025 on the reference spectrum, n_p = 200:
Peclet 23 (B1 = -0.1) and 88 (-0.3) give A* ~ 0 within the estimate (mol 0.8 s and 4-5 s); 150 (-0.5) an estimate
of 2e-2 and mol 8 s; 240 (-0.7) negative mass at the far wall (fv and mol); 340 (-1) a march that crawls (mol, > 100 s)
or cell masses of either sign (fv)."""
N_P_LIMIT = 1e7
"""Beyond this many cells the Peclet refusal names the drift as too large for any grid."""
DRAINED = 1e-12
"""mol on the engine: a run stops once the mass that can still reach a station (the elastic cells, plus a moving
yield wall's plastic area) is below this fraction of its start for every load (:func:`solve_lines`)."""


def clear_start_V(mw: MovingWall, V0: float, k: float = START_CLEARANCE, tries: int = 40) -> float:
    r"""The start-up V0, lowered (by 4x at a time) until the start is meaningful for general coefficients.

    The start is a Gaussian N(c, tau0) along the mean path :math:`c = \bar p + \int_1^{\zeta_0} B_1 d\zeta`
    (:meth:`MovingWall.start_moments`) with images about the walls.  Where the drift moved it by less than its width
    sqrt(tau0) that is as good as without a drift; where it moved it further the centre must be ``k`` widths inside
    [0, p_end] (or [0, sigma_Y]): a strong drift toward a wall (B1 = -1 with p_bar = 0.025 reaches p = 0 at
    zeta ~ 1.025) otherwise gives a centre beyond the wall, where the image start is no PDF at all (cell masses
    summing to -1, or to 0 with nothing absorbed: "the areas do not sum to 1").  Checked at V0 and 2 V0 (the start
    partner of :func:`~persson_fp.solvers.engine.estimate.run_pair`)."""
    if not mw.general:
        return V0
    pr = mw.problem
    for _ in range(tries):
        ok = True
        for V in (V0, 2.0 * V0):
            c, tau = mw.start_moments(float(mw.zeta(V)[0]))
            sd = np.sqrt(tau)
            s = float(mw.wall_many(np.array([V]))[0][0])
            moved = np.abs(c - pr.p_bar) > sd
            ok &= not np.any(moved & ((c < k * sd) | (c > s - k * sd)))
        if ok:
            return float(V0)
        V0 *= 0.25
    return float(V0)


def check_wall_peclet(mw: MovingWall, V0: float, name: str, k: float = START_CLEARANCE, nodes: int = 256) -> None:
    r"""``ValueError`` where the drift B1 is not resolved by the cells next to a wall while the PDF is there.

    The engine's fluxes are centred; next to an absorbing wall a drift B1 toward (or away from) it makes a layer of
    width B2 / (2 |B1|), which the cells resolve while the cell Peclet number :math:`2|B1|\,\Delta p/B2` is modest.
    Far beyond :data:`PECLET_MAX` the discrete solution rings with cell masses of either sign (negative mass at the
    far wall, an A* that grows) and the stiff integrator of ``"mol"`` crawls through the ringing.  Checked along the
    mean path from the start ``V0`` (Heun in zeta, as :meth:`MovingWall.start_moments`), at the cell next to each
    wall, wherever the band c +- k sqrt(tau) reaches it.
    """
    if not mw.general:
        return
    pr = mw.problem
    z = np.geomspace(float(mw.zeta(V0)[0]), float(pr.zeta_max), nodes)
    c, tau = mw.start_moments(float(z[0]))
    s_all = mw.wall_many(np.asarray(pr.V(z), dtype=float))[0]
    B1a, B2a = pr.coefficients(c, float(z[0]))
    worst = (0.0, 0.0, 1.0, 1.0)  # (Peclet, p, zeta, dp)
    lo_prev = hi_prev = None
    for i in range(nodes):
        if i:
            dz = z[i] - z[i - 1]
            B1b, _ = pr.coefficients(c + dz * B1a, float(z[i]))
            c = c + 0.5 * dz * (B1a + B1b)
            B1b, B2b = pr.coefficients(c, float(z[i]))
            tau = tau + 0.5 * dz * (B2a + B2b)
            B1a, B2a = B1b, B2b
        s = float(s_all[i])
        w = k * np.sqrt(tau)
        lo, hi = c - w, c + w  # the band of each load
        if lo_prev is not None:  # the band swept over [min, max] of the two nodes (a fast crossing included)
            a, b = np.minimum(lo, lo_prev), np.maximum(hi, hi_prev)
        else:
            a, b = lo, hi
        lo_prev, hi_prev = lo, hi
        dp = s / mw.n
        at_low, at_high = np.any((a < 0.0) & (b > 0.0)), np.any((a < s) & (b > s))
        for p in [q for q, hit in ((0.5 * dp, at_low), (s - 0.5 * dp, at_high)) if hit]:
            B1w, B2w = pr.coefficients(np.array([p]), float(z[i]))
            pe = float(2.0 * abs(B1w[0]) * dp / B2w[0]) if B2w[0] > 0 else (np.inf if B1w[0] != 0 else 0.0)
            if pe > worst[0]:
                worst = (pe, p, float(z[i]), dp)
        if np.all((hi < 0.0) | (lo > s)):  # every load's PDF has left through a wall
            break
    pe, p, zw, dp = worst
    if pe > PECLET_MAX:
        need = 1.1 * mw.n * pe / PECLET_MAX  # (10 % over: the path moves a little with the grid)
        detail = f"a cell Peclet number 2 |B1| dp / B2 = {pe:.3g} on n_p = {mw.n} cells, which needs n_p >= {need:.3g}"
        # the drift's entry of L (per unit V) times a step of 1 % of V there, against the identity of I - dV L
        entry = abs(float(pr.coefficients(np.array([p]), zw)[0][0])) / float(pr.dV_dzeta(zw)) / dp
        if entry * 0.01 * float(pr.V(zw)) * np.finfo(float).eps > 1.0:
            raise singular_step_error(name, pr, detail)
        if need > N_P_LIMIT:
            raise ValueError(
                f"{name}: the drift B1 is too large for any grid where the PDF meets the wall (p = {p:.3g}, zeta = "
                f"{zw:.5g}): {detail}; weaken B1 there"
            )
        need = int(np.ceil(need))
        raise ValueError(
            f"{name}: the drift B1 is not resolved where the PDF meets the wall: at p = {p:.3g}, zeta = {zw:.5g} the "
            f"cell Peclet number 2 |B1| dp / B2 = {pe:.3g} exceeds {PECLET_MAX:g} on n_p = {mw.n} cells "
            f"(dp = {dp:.3g}), and the centred fluxes would ring (cell masses of either sign); raise n_p to >= {need}, "
            "or weaken B1 there"
        )


def singular_step_error(name: str, pr, detail: str, p_end: float | None = None) -> ValueError:
    """The ``ValueError`` for a drift B1 so large that the implicit step ``I - dV L`` is singular to round-off
    (LAPACK's banded solve, SuperLU's "Factor is exactly singular"): names B1, its largest magnitude relative to B2
    on a probe grid (where), and the remedy."""
    hi = p_end
    if hi is None:
        hi = float(pr.hardness.sigma(pr.zeta_max)) if pr.hardness is not None else domain_end(pr, 10.0)[0]
    p = np.linspace(0.0, hi, 257)[1:]
    worst = (-1.0, 0.0, 1.0, 0.0, 0.0)
    for z in np.geomspace(1.0, float(pr.zeta_max), 17):
        B1, B2 = pr.coefficients(p, float(z))
        with np.errstate(divide="ignore", invalid="ignore"):
            r = np.where(B2 > 0, np.abs(B1) / np.where(B2 > 0, B2, 1.0), np.where(B1 != 0, np.inf, 0.0))
        i = int(np.argmax(r))
        if r[i] > worst[0]:
            worst = (float(r[i]), float(p[i]), float(z), float(B1[i]), float(B2[i]))
    _, pw, zw, b1, b2 = worst
    return ValueError(
        f"{name}: the drift B1 is too large for the implicit step: |B1| = {abs(b1):.3g} against B2 = {b2:.3g} at "
        f"p = {pw:.3g}, zeta = {zw:.4g} ({detail}); at this magnitude I - dV L loses its identity to round-off and "
        "the implicit step is singular; weaken B1 (the cells must resolve B2 / (2 |B1|), the width of the layer it "
        "makes at a wall)"
    )


def general_start(solver, n: int, zeta0, k_domain: float, tau0_fraction: float):
    """The start-up zeta0 of a general-coefficient run of the engine on ``n`` cells, checked (``"fv"``, ``"mol"``).

    The resolution of the stations (:func:`~persson_fp.solvers.engine.moving_wall.check_resolved`), the engine's own
    start-up (``MovingWall.choose_V0``) lowered by :func:`clear_start_V`, and the drift at the walls
    (:func:`check_wall_peclet`).  Returns ``zeta0`` unchanged where it is given, or where the problem has no general
    coefficients; else the cleared start-up (None where it is the engine's own choice)."""
    pr = solver.problem
    if not pr.general:
        return zeta0
    p_end = None if pr.hardness is not None else domain_end(pr, k_domain)[0]
    V_st = np.asarray(solver.V_out, dtype=float)
    check_resolved(pr, V_st, n, solver.zeta_out, k_domain, p_end)
    mw = MovingWall(pr, n, k_domain, p_end)
    if zeta0 is not None:
        V0 = float(pr.V(zeta0))
        out = zeta0
    else:
        V_own = mw.choose_V0(float(V_st[0]), tau0_fraction)
        V0 = clear_start_V(mw, V_own)
        out = None if V0 == V_own else float(solver.zeta_from_V(V0)[0])
    if V0 > 0.0:
        check_wall_peclet(mw, V0, solver.name)
    return out


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
):
    """The method of lines on the same fluxes: ``solve_ivp`` in V on y = (w, A_pl, A_non) per load, with S at
    the current total contact area and a banded Jacobian (S frozen: exact for the linear part).  Returns the
    per-station dict of :meth:`MovingWall.solve`.

    ``per_mass``: ``atol`` is relative to each load's mass in play at the start (its elastic and wall cells, ~A* at
    V0): a tiny load (A* ~ p_bar / sqrt(V)) keeps the relative accuracy of a large one (an absolute atol of 1e-8 left
    p_bar = 1e-9 with 1.6 % error against an estimate of 1.2 %).  ``drained`` (relative to that mass, 0: never):
    the march stops once every load's mass in play is below it (a drift that has carried the PDF into a wall; the
    centred fluxes then ring at the tolerance and BDF resolved the ringing in steps of ~1e-7 in V, > 100 s); each
    later station holds what was left as absorbed at p = 0 (mass only leaves, so every later area is below it)."""
    import scipy.sparse as sp
    from scipy.integrate import solve_ivp

    pr = mw.problem
    S = pr.fudge.S
    m, n, h = pr.n_loads, mw.n, mw.h
    V_st = np.asarray(V_st, dtype=float)
    if V0 is None:
        V0 = clear_start_V(mw, mw.choose_V0(float(V_st[0]), tau0_fraction))  # (as general_start)
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
    returns = pr.moving_wall  # a moving yield wall hands its plastic area back; elsewhere A_pl stays absorbed
    mass0 = np.maximum(y0w[:, :n].sum(axis=1) * h + y0w[:, n], np.finfo(float).tiny)  # in play at V0, per load
    if per_mass:
        atol = np.repeat(atol * mass0, k)

    def remaining(V, y):  # the mass that can still reach a station, relative, above the drained level (an event)
        Y = y.reshape(m, k)
        M = Y[:, :n].sum(axis=1) * h + (Y[:, n] if returns else 0.0)
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
        if not (mw.general and "singular" in str(err)):
            raise
        raise singular_step_error("mol", pr, f"{type(err).__name__}: {err}", mw.p_end) from err
    if not res.success:
        raise SolverError(f"mol (moving wall): solve_ivp failed ({res.message})")
    Y = np.empty((V_st.size, m, k))
    got = len(res.t)  # (a list where the event ended the run before the first station)
    if got:
        Y[:got] = np.asarray(res.y).T.reshape(got, m, k)
    if got < V_st.size:  # drained (the event): every later area is below drained x mass0 (mass only leaves)
        y_end = res.y_events[0][-1].reshape(m, k).copy()
        y_end[:, n + 1] += y_end[:, :n].sum(axis=1) * h + (y_end[:, n] if returns else 0.0)  # to the wall p = 0
        y_end[:, :n] = 0.0
        if returns:
            y_end[:, n] = 0.0
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


def solve_lines_cells(
    solver,
    n: int,
    rtol: float,
    atol,
    integrator: str,
    tau0_fraction: float,
    tol,
    zeta0=None,
    k_domain: float = 10.0,
):
    """The moving-wall run of ``"mol"``: n cells and its partner at n/2 (time by ``rtol``).  ``atol`` None: rtol x 1e-3
    of each load's mass in play at the start (``solve_lines``'s ``per_mass``)."""
    zeta0 = general_start(solver, n, zeta0, k_domain, tau0_fraction)
    per_mass = atol is None
    atol = rtol * 1e-3 if per_mass else atol
    fine, coarse = run_pair(
        solver,
        n,
        zeta0,
        k_domain,
        lambda mw, V_st, V0, _: solve_lines(mw, V_st, rtol, atol, integrator, tau0_fraction, V0, per_mass=per_mass),
    )
    what = f"|Q(n_p) - Q(n_p/2)|, n_p = {n}, rtol = {rtol:g} (conservative in p; time by rtol)"
    info = {"steps": fine["steps"], "integrator": integrator, "nfev": fine["nfev"], "njev": fine["njev"]}
    return finish(solver, n, fine, coarse, what, tol, info)
