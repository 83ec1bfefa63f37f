r"""The start-up of a general-coefficient run of the front-fixed engine and its refusals (``"fv"``, ``"mol"``).

A start-up Gaussian cleared of the walls (``clear_start_V``), the drift's cell Peclet number at a wall
(``check_wall_peclet``) and the error that names a drift too strong for the implicit step
(``singular_step_error``).
"""

from __future__ import annotations

import numpy as np

from persson_fp.solvers.base import zeta_of
from persson_fp.solvers.front_fixed.moving_wall import MovingWall, check_resolved, domain_end

__all__ = [
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


def clear_start_V(mw: MovingWall, V0: float, k: float = START_CLEARANCE, tries: int = 40) -> float:
    r"""The start-up V0, lowered (by 4x at a time) until the start is meaningful for general coefficients.

    The start is a Gaussian N(c, tau0) along the mean path :math:`c = \bar p + \int_1^{\zeta_0} B_1 d\zeta`
    (:meth:`MovingWall.start_moments`) with images about the walls.  Where the drift moved it by less than its width
    sqrt(tau0) that is as good as without a drift; where it moved it further the centre must be ``k`` widths inside
    [0, p_end] (or [0, sigma_Y]): a strong drift toward a wall (B1 = -1 with p_bar = 0.025 reaches p = 0 at
    zeta ~ 1.025) otherwise gives a centre beyond the wall, where the image start is no PDF at all (cell masses
    summing to -1, or to 0 with nothing absorbed: "the areas do not sum to 1").  Checked at V0 and 2 V0 (the start
    partner of :func:`~persson_fp.solvers.front_fixed.estimate.run_pair`)."""
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


def general_start(problem, stations, n: int, zeta0, k_domain: float, tau0_fraction: float, name: str):
    """The start-up zeta0 of a general-coefficient run of the engine on ``n`` cells, checked (``"fv"``, ``"mol"``).

    The resolution of the stations (:func:`~persson_fp.solvers.front_fixed.moving_wall.check_resolved`), the
    engine's own
    start-up (``MovingWall.choose_V0``) lowered by :func:`clear_start_V`, and the drift at the walls
    (:func:`check_wall_peclet`).  Returns ``zeta0`` unchanged where it is given, or where the problem has no general
    coefficients; else the cleared start-up (None where it is the engine's own choice).  ``stations``: (zeta, V) of
    the output stations; ``name``: the method's, for the messages."""
    pr = problem
    if not pr.general:
        return zeta0
    p_end = None if pr.hardness is not None else domain_end(pr, k_domain)[0]
    zeta_st, V_st = stations
    V_st = np.asarray(V_st, dtype=float)
    check_resolved(pr, V_st, n, zeta_st, k_domain, p_end)
    mw = MovingWall(pr, n, k_domain, p_end)
    if zeta0 is not None:
        V0 = float(pr.V(zeta0))
        out = zeta0
    else:
        V_own = mw.choose_V0(float(V_st[0]), tau0_fraction)
        V0 = clear_start_V(mw, V_own)
        out = None if V0 == V_own else float(zeta_of(pr, V0)[0])
    if V0 > 0.0:
        check_wall_peclet(mw, V0, name)
    return out
