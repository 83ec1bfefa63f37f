r"""The moving yield wall on the spectral engine: method ``"chebyshev"`` for a scale-dependent hardness.

The physics (Persson, Phys. Rev. Lett. 87 (2001) 116101; Surf. Sci. Rep. 61 (2006) 201, Sec. 3) and the front
fixing are those of :mod:`persson_fp.solvers.front_fixed.moving_wall`: with :math:`s(V) = \sigma_Y(\zeta(V))`,
:math:`x = p/s \in [0, 1]` and the mass density :math:`w(x, V) = s\,P(sx, V)`, the diffusion equation of the Xu et al.
tutorial (Eq. 'E:diffusion_equ', no fudge factor: S = 1, so V is the effective variance) becomes

.. math::  \partial_V w = \partial_x\big(D\,\partial_x w + v\,w\big), \qquad D = \frac{1}{2s^2}, \quad
           v = \frac{s_V}{s}\,x, \qquad w(0) = 0, \quad w(1) = \beta A_{pl}, \quad \beta = 2 s s_V,

with :math:`dA_{pl}/dV = -(D\,\partial_x w + v w)(1)` (the flux out through the wall; the load balance
:math:`F_{el} + \sigma_Y A_{pl} = \bar p` is what fixes the wall value) and :math:`dA_{non}/dV = D\,\partial_x w(0)`.
:math:`s_V = \sigma_Y'(\zeta) / V'(\zeta)` (1 / pressure).

*Discretisation.*  Chebyshev collocation in x on the sinh-mapped grid of :mod:`persson_fp.solvers.chebyshev.collocation`
(clustered around the start p_bar / s and at both walls).  The wall value is lifted, :math:`w = u + \beta A_{pl}\,x`
with u = 0 at both walls (``_operator``), so the state :math:`y = [u(x_1 \dots x_{n-1}), A_{pl}, A_{non}]` obeys a
*linear* system :math:`dy/dV = A(V)\,y` whose operator depends on V through s, s_V and :math:`\beta'` only (linear
because S = 1; a fudge factor S(A) would make it nonlinear and is declined).  It is marched by the adaptive Radau
IIA steps of :mod:`persson_fp.solvers.chebyshev.radau` (order 5, L-stable, one real and one complex LU a step; the
march's estimate the propagated sum of its step-doubling local estimates), the partner runs replaying the main run's
steps (``nodes=``).  Where the spectrum rolls off (zeta_r = q_r / q_l) V'(zeta) has a kink, so d beta / dV and the
operator jump there: the march stops at V(zeta_r) and restarts from it (``_Wall.breaks``), each piece's stages taking
the operator's limit from within it -- a step across the jump is first order and its step-doubling estimate blind
(measured on the moving-wall scene W: A_pl 8e-5 off at a march estimate of 4e-7; with the break, 1e-8 off).  The
march forecasts its cost a tenth of the way through each piece and is refused at once if it would exceed its share of
the time left (``max_time``; by default the chebyshev march budget, ``MARCH_TIME_BUDGET`` = 10 s), naming the tol
that would fit; so is a refinement forecast over the time left.  ``march="magnus"`` takes the older commutator-free
fourth-order exponential steps (:mod:`persson_fp.solvers.chebyshev.magnus`, 8 dense exponentials a step, order 2
where beta changes fast; on the moving-wall scene W 11 s for tol = 1e-6 where Radau takes 0.9 s, though faster at
1e-4: ``benchmarks/results/wall_marches.md``).  A constant
hardness gives beta = 0: the absorbing strip.

*Start.*  Every station starts afresh at V0 = V0_fraction x V from the heat kernel in p with its images across p = 0
and the wall s(V0) (the strip's small-time solution; the wall, many widths away, is felt only through the images)
and the strip's areas at (s(V0), V0) (:func:`persson_fp.theory.strip.strip_quantities`).

*Error estimate* (``info["error_estimate"]``; per station and load), as for the other paths of
:mod:`persson_fp.solvers.chebyshev`: the difference from a partner run at 3/4 of the degree, the difference from one
started at 4 V0 divided by 4, the march's own estimate, the start's
quadrature error on the grid, a round-off floor (that of the general path, ``collocation.roundoff_floor``, not
below 4 eps n^2) and the residual of the area balance A_el + A_pl + A_non
= 1 (exact in the continuum; the collocated wall fluxes meet it to the discretisation error).  With ``tol`` the
degree is raised, V0 lowered or the march tightened, whichever part dominates, until the estimate meets it.  The
round-off floor is computed from the operators alone (``_floor_at``, milliseconds) and grows along every step of that
loop, so a tol below it is refused before any march, and again before a pass whose floor would exceed tol: a
:class:`~persson_fp.SolverError` naming tol, the floor, the degree and a tol within reach.  A tol close to the floor
is refused before any march too if the floor at the degree where the loop then ends, 1.3x its first, exceeds it
(a first pass near the floor has not met tol; a fixed ``n_p`` runs anyway).
"""

from __future__ import annotations

import math
import time

import numpy as np

from persson_fp.results.invariants import SolverError
from persson_fp.solvers.base import SolverOutput, zeta_of
from persson_fp.solvers.chebyshev import collocation
from persson_fp.solvers.chebyshev.budget import check_degree_memory, out_of_time
from persson_fp.solvers.chebyshev.magnus import magnus_march
from persson_fp.solvers.chebyshev.radau import (
    EST_DIV_WALL,
    FORECAST_AFTER_BREAK,
    MarchTooLong,
    one_sided,
    radau_march,
)
from persson_fp.theory.strip import strip_quantities

__all__ = ["check_wall_problem", "solve_moving_wall", "N_MAX_WALL"]

N_MAX_WALL = 160
"""Largest degree the adaptive loop reaches on the moving wall."""


def check_wall_problem(problem, opts) -> None:
    """``ValueError`` unless the moving wall is one this path solves: the homogenised problem, no fudge factor
    (``opts``: chebyshev's options)."""
    pr = problem
    if opts["march"] not in (None, "radau", "magnus"):
        got = opts["march"]
        raise ValueError(
            f"march must be None, 'radau' or 'magnus' (a moving wall is always marched; None: 'radau'), got {got!r}"
        )
    if pr.general:
        raise ValueError(
            "method 'chebyshev' solves a scale-dependent hardness (moving yield wall) for the homogenised "
            "ContactProblem only, not with general Fokker-Planck coefficients; use method='fv' or 'mol'"
        )
    if pr.fudge.name != "none":
        raise ValueError(
            "method 'chebyshev' solves a scale-dependent hardness (moving yield wall) only without a fudge factor "
            f"(S = 1, where the front-fixed equation is linear), got fudge={pr.fudge.name!r}; use method='fv' or 'mol'"
        )
    if not float(pr.dV_dzeta(float(pr.zeta_max))) > 0:
        raise ValueError("method 'chebyshev' marches in V and needs dV/dzeta > 0 at zeta_max; use method='fv'")


_DU = 1e-3
"""The step in ln zeta of the 5-point differences that give d beta / dV (truncation ~ _DU^4, round-off ~ eps / _DU)."""
_ONE_SIDED = np.array([-25.0, 48.0, -36.0, 16.0, -3.0]) / 12.0
_STENCILS = {  # (offsets in _DU, weights): central, and one-sided where the stencil would straddle the roll-off kink
    0: (np.array([-2.0, -1.0, 1.0, 2.0]), np.array([1.0, -8.0, 8.0, -1.0]) / 12.0),
    1: (np.arange(5.0), _ONE_SIDED),
    -1: (-np.arange(5.0), -_ONE_SIDED),
}


class _Wall:
    """s(V) = sigma_Y(zeta(V)) (pressure), s_V = d sigma_Y / dV (1 / pressure) and d beta / dV, cached per V
    (beta = 2 s s_V; its derivative by 5-point differences in ln zeta, one-sided next to the spectrum's roll-off
    zeta_r, where dV/dzeta has a kink)."""

    def __init__(self, problem):
        self.problem = problem
        self._cache: dict = {}
        zr = getattr(problem.psd, "zeta_r", None)
        self.zeta_kink = float(zr) if zr is not None and 1.0 < zr < problem.zeta_max else None

    def _beta(self, z):
        pr = self.problem
        return 2.0 * pr.hardness.sigma(z) * pr.hardness.dsigma_dzeta(z) / pr.V_kernels.dV_dzeta(z)

    def breaks(self, V_a: float, V_b: float) -> list:
        """The V in (V_a, V_b) where the operator jumps: the roll-off's kink, where d beta / dV does (beta has
        1 / V'(zeta), whose derivative jumps there)."""
        if self.zeta_kink is None:
            return []
        Vk = self._V_kink = getattr(self, "_V_kink", None) or float(self.problem.V(self.zeta_kink))
        return [Vk] if V_a < Vk < V_b else []

    def many(self, Vs) -> np.ndarray:
        """(len(Vs), 3): (s, s_V, d beta / dV) at the points ``Vs`` in one vectorised pass (one inversion zeta(V)
        for all; the stencils chosen point by point as in ``__call__``)."""
        pr = self.problem
        Vs = np.asarray(Vs, dtype=float)
        z = zeta_of(pr, Vs)
        dV = pr.V_kernels.dV_dzeta(z)
        if not np.all(dV > 0):
            return np.array([self(float(v)) for v in Vs])  # (the point-wise path names the zeta)
        u = np.log(z)
        side = np.where(u < 2.5 * _DU, 1, np.where(u > math.log(pr.zeta_max) - 2.5 * _DU, -1, 0))
        if self.zeta_kink is not None:
            uk = math.log(self.zeta_kink)
            side = np.where(np.abs(u - uk) < 2.5 * _DU, np.where(u >= uk, 1, -1), side)
        dbeta_du = np.empty(u.size)
        for sd in np.unique(side):
            pick = side == sd
            off, wt = _STENCILS[int(sd)]
            dbeta_du[pick] = self._beta(np.exp(u[pick, None] + off * _DU).ravel()).reshape(-1, off.size) @ wt / _DU
        return np.stack([pr.hardness.sigma(z), pr.hardness.dsigma_dzeta(z) / dV, dbeta_du / (z * dV)], axis=1)

    def __call__(self, V: float):
        hit = self._cache.get(V)
        if hit is None:
            pr = self.problem
            z = zeta_of(pr, float(V))
            dV = float(pr.V_kernels.dV_dzeta(z)[0])
            if not dV > 0:
                raise ValueError(
                    f"method 'chebyshev': dV/dzeta vanishes at zeta = {float(z[0]):.6g} (V is no clock there for "
                    "the moving wall); use method='fv'"
                )
            s = float(pr.hardness.sigma(z)[0])
            u = math.log(float(z[0]))
            side = 1 if u < 2.5 * _DU else (-1 if u > math.log(pr.zeta_max) - 2.5 * _DU else 0)
            if self.zeta_kink is not None and abs(u - math.log(self.zeta_kink)) < 2.5 * _DU:
                side = 1 if u >= math.log(self.zeta_kink) else -1
            off, wt = _STENCILS[side]
            dbeta_du = float(wt @ self._beta(np.exp(u + off * _DU))) / _DU
            hit = self._cache[V] = (s, float(pr.hardness.dsigma_dzeta(z)[0]) / dV, dbeta_du / (float(z[0]) * dV))
        return hit


def _operator(grid, s: float, sV: float, dbeta: float):
    r"""A(V) of the state [u at the interior nodes, A_pl, A_non] (n_loads, n + 1, n + 1), the wall value lifted:
    :math:`w = u + \beta A_{pl}\,x` with u = 0 at both walls, so that no V-dependent factor multiplies a stiff
    wall row (with the wall node :math:`\beta A_{pl}` in the collocated rows the march stalled at steps of 1e-5 V
    where beta changes fast):

    .. math::  \partial_V u = \mathcal L u + (2a\beta - \beta' + \beta^2 (D + a))\,x A_{pl}
               + \beta x\,D\,\partial_x u(1), \qquad \dot A_{pl} = -D\,\partial_x u(1) - \beta (D + a) A_{pl},
               \qquad \dot A_{non} = D\,\partial_x u(0) + D\beta A_{pl},

    :math:`\mathcal L u = D u_{xx} + a (u + x u_x)`, D = 1 / (2 s^2), a = s_V / s (so that L x = 2 a x)."""
    return _Operators(grid).at(np.array([[s, sV, dbeta]]))[0]


class _Operators:
    """The operator of ``_operator`` as a sum of five fixed matrices of the grid with scalar factors of V
    (D, a, beta D, the lift's source, A_pl's loss): ``at(rows)`` builds it at many V at once."""

    def __init__(self, grid):
        x = grid.p  # (the grid is in x)
        nl, m = x.shape[0], x.shape[1] - 2
        xi = x[:, 1:-1]
        d1 = grid.D1[:, -1, 1:-1]  # u_x(1)
        B = np.zeros((5, nl, m + 2, m + 2))
        B[0, :, :m, :m] = grid.D2[:, 1:-1, 1:-1]
        B[0, :, m, :m] = -d1
        B[0, :, m + 1, :m] = grid.D1[:, 0, 1:-1]
        B[1, :, :m, :m] = (np.eye(m + 2)[None] + x[:, :, None] * grid.D1)[:, 1:-1, 1:-1]
        B[2, :, :m, :m] = xi[:, :, None] * d1[:, None, :]
        B[2, :, m + 1, m] = 1.0
        B[3, :, :m, m] = xi
        B[4, :, m, m] = 1.0
        self.basis = B.reshape(5, -1)
        self.shape = (nl, m + 2, m + 2)

    def at(self, rows) -> np.ndarray:
        """(len(rows), n_loads, m + 2, m + 2) at the rows (s, s_V, d beta / dV) of :meth:`_Wall.many`."""
        s, sV, dbeta = np.asarray(rows, dtype=float).T
        D, a, beta = 0.5 / (s * s), sV / s, 2.0 * s * sV
        f = np.stack([D, a, beta * D, 2.0 * a * beta - dbeta + beta * beta * (D + a), -beta * (D + a)], axis=1)
        return (f @ self.basis).reshape((f.shape[0],) + self.shape)


def _run(pr, V_out, wall, n: int, frac: float, tol_t: float, budget, nodes=None, march="magnus"):
    """One run at degree n and start fraction ``frac`` to the stations ``V_out`` (on the steps ``nodes[k]`` per
    station if given; ``budget`` = (deadline, max_time)): a dict of per-station arrays, the grids and the accepted
    steps."""
    pb = pr.p_bar.astype(float)
    n_st, nl = V_out.size, pb.size
    shape = (n_st, nl)
    out = {key: np.zeros(shape) for key in ("A_el", "A_pl", "A_non", "F_el", "t_err", "unresolved", "beta", "roundoff")}
    out["W"], out["grids"], out["s"], out["nodes"] = np.zeros((n_st, nl, n + 1)), [], np.zeros(n_st), []
    stats = {"steps": 0, "rejected": 0, "expm" if march == "magnus" else "solves": 0}
    floor = 4.0 * np.finfo(float).eps * n * n
    for k, V in enumerate(V_out):
        V = float(V)
        V0, s0, grid = _station_grid(pr, wall, n, frac, V)
        wall_p = np.full(nl, s0)
        w0 = s0 * collocation.start_density(lambda q: (np.ones(np.shape(q)), None), s0 * grid.p, pb, V0, p_wall=wall_p)
        w0[:, 0] = w0[:, -1] = 0.0
        q = strip_quantities(pb, s0, V0)
        # the start's quadrature on the grid against the strip's exact elastic area
        out["unresolved"][k] = np.abs(np.sum(w0 * grid.w, axis=-1) - q["elastic_area"])
        m = n - 1
        wts = grid.w[:, 1:-1]

        A_of = _operator_of(grid, wall)

        s_end, sV_end, _ = wall(V)
        lift = 1.0 + s_end * sV_end  # |A_pl| and the lift beta A_pl x (its L1: beta |A_pl| / 2) at the station

        def norm(d, wts=wts, m=m, lift=lift):
            return np.sum(np.abs(d[:, :m]) * wts, axis=-1) + np.abs(d[:, m]) * lift

        y0 = np.concatenate([w0[:, 1:-1], q["plastic_area"][:, None] * np.ones((nl, 1)), np.zeros((nl, 1))], axis=1)
        used: list = []  # (the accepted steps: the partners replay them)
        try:
            y, t_err, st = _march(
                march, A_of, y0, V0, V, wall.breaks(V0, V), tol_t, norm, floor, budget,
                None if nodes is None else nodes[k], used, (V_out.size - k) * (1.0 + 4.0 / 3.0),
            )  # fmt: skip
        except TimeoutError as err:
            out_of_time(budget[1], f"moving wall: {err}")
        except MarchTooLong as err:
            where = (float(zeta_of(pr, V)[0]), math.sqrt(V) / s_end)
            raise SolverError(_too_long(err, tol_t, budget, where)) from None
        except RuntimeError as err:
            raise SolverError(f"chebyshev (moving wall): {err}; loosen tol or use method='fv'") from None
        for key in stats:
            stats[key] += st[key]
        s, sV, _ = wall(V)
        beta = 2.0 * s * sV
        w = np.zeros((nl, n + 1))
        w[:, 1:-1], w[:, -1] = y[:, :m] + beta * y[:, m : m + 1] * grid.p[:, 1:-1], beta * y[:, m]
        out["W"][k], out["s"][k], out["beta"][k] = w, s, beta
        out["A_el"][k] = np.sum(w * grid.w, axis=-1)
        out["F_el"][k] = s * np.sum(w * grid.w * grid.p, axis=-1)
        out["A_pl"][k] = y[:, m]
        out["A_non"][k] = q["noncontact_area"] + y[:, m + 1]
        out["t_err"][k] = t_err
        out["roundoff"][k] = _roundoff(A_of, V0, V, n)
        out["grids"].append(grid)
        out["nodes"].append(used if nodes is None else nodes[k])
    out["stats"] = stats
    return out


def _station_grid(pr, wall, n: int, frac: float, V: float):
    """(V0, s0 = sigma_Y at V0, the grid in x) of the station at V started at V0 = frac V: the Chebyshev points
    sinh-mapped around p_bar / s0, clustered within 3 start widths sqrt(V0) / s0."""
    V0 = frac * V
    s0 = wall(V0)[0]
    nl = pr.p_bar.size
    grid = collocation.chebyshev_grid(n, 1.0, pr.p_bar.astype(float) / s0, np.full(nl, 3.0 * math.sqrt(V0) / s0))
    return V0, s0, grid


def _operator_of(grid, wall):
    """``A_of(V)``: the operator of :func:`_operator` on ``grid`` at V, with ``A_of.many(Vs)`` stacking it over
    many V in one pass (:func:`~persson_fp.solvers.chebyshev.radau.operators`)."""
    ops = _Operators(grid)

    def A_of(Vq):
        return ops.at(np.array([wall(Vq)]))[0]

    A_of.many = lambda Vs: ops.at(wall.many(Vs))
    return A_of


def _roundoff(A_of, V0: float, V: float, n: int):
    """The round-off floor of a station (per load): :func:`collocation.roundoff_floor` of the larger of the operators
    at its ends, |A(V0)| and |A(V)| entrywise, over the span V - V0 -- the backward error of the stiff operator's
    solves and exponentials, as on the general paths of :mod:`persson_fp.solvers.chebyshev`."""
    return collocation.roundoff_floor(np.maximum(np.abs(A_of(V0)), np.abs(A_of(V))), V - V0, n)


def _floor_at(pr, V_out, wall, n: int, frac: float) -> float:
    """The largest round-off floor a pass at degree n and start fraction ``frac`` would report (max(4 eps n^2,
    :func:`_roundoff`) over stations and loads, the ``"roundoff"`` part of its estimate, which every part of it
    includes) -- from the operators alone, before any march (milliseconds: the grids and two operators a station).
    It grows along the refinement loop's steps -- the degree 1.3x, or the start fraction 4x lower with the degree
    1.15x -- (~n^6: ||A|| ~ n^4 on the clustered grid, times (n / 400)^2; a narrower start alone can lower it a
    little, the walls' nodes spreading; measured at least 1.32x a step over the moving-wall scenes, n = 24-140,
    fractions 1e-2 to 1e-6), so once a pass's floor exceeds tol no later pass meets it."""
    worst = 4.0 * np.finfo(float).eps * n * n
    for V in V_out:
        V0, _, grid = _station_grid(pr, wall, n, frac, float(V))
        worst = max(worst, float(np.max(_roundoff(_operator_of(grid, wall), V0, float(V), n))))
    return worst


def _start_of(pr, V_out, tol: float, opts) -> tuple:
    """(first degree, start fraction) of the refinement loop for ``tol`` (``opts``: chebyshev's options)."""
    frac = opts["V0_fraction"] or min(float(np.clip(0.3 * math.sqrt(tol), 3e-5, 1e-2)), _wall_fraction(pr, V_out, tol))
    return opts["n_p"] or int(np.clip(8 + 8 * math.log10(1.0 / tol), 24, N_MAX_WALL)), frac


def _reachable(pr, V_out, wall, tol: float, opts) -> float:
    """The smallest tol above ``tol`` (in half-decade steps) whose round-off floor at the degree the loop usually
    ends at -- 1.3x its first degree (measured on the moving-wall scenes: 72 -> 94 at tol 1e-8, 80 -> 104 at 1e-9)
    -- stays below half of it (the other half for the discretisation and the march); 0.1 at most."""
    reach = tol
    while reach < 0.1:
        reach = min(reach * math.sqrt(10.0), 0.1)
        n1, frac1 = _start_of(pr, V_out, reach, opts)
        if _floor_at(pr, V_out, wall, min(int(math.ceil(1.3 * n1)), N_MAX_WALL), frac1) <= 0.5 * reach:
            break
    return reach


def _unreachable(pr, V_out, wall, tol: float, n: int, floor: float, opts, done: str = "") -> None:
    """Raise the :class:`~persson_fp.SolverError` of a tol below the round-off floor of the next pass (``floor``
    at degree ``n``; ``done``: what the passes so far reached), naming the floor and a tol within reach."""
    reach = _reachable(pr, V_out, wall, tol, opts)
    raise SolverError(
        f"chebyshev (moving wall): tol = {tol:.3g} is below the round-off floor of the stiff collocated operator: "
        f"{floor:.2e} at degree {n} (it grows ~n^6 with the degree, and a coarser degree leaves a larger "
        f"discretisation error){done}; the best reachable accuracy is about {reach:.1e} -- loosen tol to it or use "
        "method='fv'"
    )


def _march(march, A_of, y0, V0, V, breaks, tol_t, norm, floor, budget, nodes, record, runs):
    """March y0 from V0 to V, stopping at every point of ``breaks`` (where the operator jumps: no step straddles
    a jump, across which a step is first order and its step-doubling estimate blind), each piece held to its share
    of ``tol_t`` in ln V.  A main run's Radau march (``nodes`` None) is held to its share of the time left,
    ``(deadline - now) / runs`` (``runs``: the marches still to come, the partners' replays counted), and refused
    at once if forecast over it (:class:`~persson_fp.solvers.chebyshev.radau.MarchTooLong`).  (y, estimate,
    statistics)."""
    points = [V0, *[b for b in breaks if V0 * (1.0 + 1e-9) < b < V * (1.0 - 1e-9)], V]
    A_full = A_of
    log_span = math.log(V / V0)
    est, stats = 0.0, {}
    y = y0
    for a, b in zip(points[:-1], points[1:]):
        tol_piece = tol_t * math.log(b / a) / log_span
        if len(points) > 2:  # (a stage on the break takes the operator of this piece's side: one-sided limits)
            A_of = one_sided(A_full, a if a != V0 else -math.inf, b if b != V else math.inf)
        replay = None if nodes is None else [v for v in nodes if a * (1.0 + 1e-12) < v <= b * (1.0 + 1e-12)]
        if record and record[-1] == a:  # (the march records its start again)
            record.pop()
        if march == "magnus":
            y, e, st = magnus_march(
                A_of, y, a, b, tol_piece, norm, floor, None, budget[0], nodes=replay, record=record,
                refusal="pace",
            )  # fmt: skip
        else:
            share = None
            if replay is None and budget[0] is not None:
                share = (budget[0] - time.perf_counter()) / runs * math.log(b / a) / math.log(V / a)
            try:
                y, e, st = radau_march(
                    A_of, y, a, b, tol_piece, norm, floor, None if a == V0 else 1e-5 * a, budget[0], nodes=replay,
                    record=record, time_budget=share, est_div=EST_DIV_WALL,
                    forecast_from=a * max(FORECAST_AFTER_BREAK if a != V0 else 1.0, (b / a) ** 0.1),
                )  # fmt: skip
            except MarchTooLong as err:
                err.reachable *= tol_t / tol_piece  # (in the units of the whole march's tol)
                raise
        est = est + e
        for key, val in st.items():
            stats[key] = stats.get(key, 0) + val
    return y, est, stats


def _too_long(err, tol_t, budget, where) -> str:
    """The message of a march forecast over its budget, naming the forecast, the station (``where`` = (zeta, the
    PDF's width sqrt(V) / sigma_Y there)) and the tol that would fit -- or, where the PDF is a sliver of the domain,
    the remedy: a later first station."""
    fits = ""
    if math.isfinite(getattr(err, "reachable", math.nan)) and len(budget) > 3:
        fits = f"; tol = {budget[3]:.3g} is forecast to need too many steps, a tol of about "
        fits += f"{min(err.reachable * budget[3] / tol_t, 0.1):.1e} would fit"
    remedy = "loosen tol, pass a larger max_time (seconds) or use method='fv'"
    if where[1] < 1e-2:  # (the PDF a tiny fraction of the domain wide: no tol makes it cheap)
        remedy = f"the PDF there is {where[1]:.1e} of sigma_Y wide: start zeta_out later (or use method='fv')"
    return f"chebyshev (moving wall): {err} (budget: {_whose(budget)}){fits} (worst at zeta = {where[0]:.6g}); {remedy}"


def _compare(main, other, p_bar):
    """(L1 of w, i.e. of P in p; |dA_el|; |dA_pl|; |dA_non|; |dF| / p_bar) per station and load."""
    L1 = np.stack(
        [
            np.sum(np.abs(main["W"][k] - collocation.interpolate(g2, other["W"][k], g.p)) * g.w, axis=-1)
            for k, (g, g2) in enumerate(zip(main["grids"], other["grids"]))
        ]
    )
    d = {q: np.abs(main[q] - other[q]) for q in ("A_el", "A_pl", "A_non")}
    return L1, d["A_el"], d["A_pl"], d["A_non"], np.abs(main["F_el"] - other["F_el"]) / p_bar


def _forecast_pass(took: float, was, now, budget, worst: float, tol: float, runs: int, where) -> None:
    """Refuse before a refinement forecast over the time left: the last pass took ``took`` seconds at (degree,
    march tol, start fraction) ``was``; the next, at ``now``, costs that times the degree's growth squared (the
    operators and their LUs; measured between n^2 and n^3 at n = 40-100), the steps of the tighter march (order 5:
    tol^(-1/5)) and of the longer span ln(1 / frac)."""
    if budget[0] is None:
        return
    (n0, t0, f0), (n1, t1, f1) = was, now
    grow = (n1 / n0) ** 2 * (t0 / t1) ** 0.2 * math.log(1.0 / f1) / math.log(1.0 / f0)
    need, left = took * grow, budget[0] - time.perf_counter()
    if need > left:
        remedy = where[1] or (
            (f"a tol of about {1.5 * worst:.1e} fits -- loosen tol to it, " if 1.5 * worst < 0.1 else "")
            + "pass a larger max_time (seconds) or use method='fv'"
        )
        raise SolverError(
            f"chebyshev (moving wall): after {runs} runs the error estimate is {worst:.2e} over tol = {tol:.3g} "
            f"(worst at zeta = {where[0]:.6g}); the next refinement (degree {n1}) is forecast to take ~{need:.3g} s, "
            f"over the {max(left, 0.0):.3g} s left of {_whose(budget)}; {remedy}"
        )


def _whose(budget) -> str:
    return budget[2] if len(budget) > 2 and budget[2] != "max_time" else f"max_time = {budget[1]:.3g} s"


def _wall_fraction(pr, V_out, tol: float) -> float:
    """The largest V0 / V(zeta_max) at which the start, and its partner at 4 V0, are k widths sqrt(V0) below the
    wall with exp(-k^2 / 2) < 1e-3 tol at the partner (the image start knows nothing of the wall's motion and of the
    plastic area it has taken before V0)."""
    gap = float(np.min(pr.sigma_Y(1.0) - pr.p_bar))  # the wall only moves out: sigma_Y(1) is its closest
    k = 2.0 * math.sqrt(2.0 * math.log(1e3 / tol))
    return max((gap / k) ** 2 / float(np.max(V_out)), 1e-12)


def solve_moving_wall(
    problem, opts, zeta_out, V_out, max_time: float, max_memory: float, budget_name: str = "max_time"
) -> SolverOutput:
    """Solve ``problem`` (a moving wall, no fudge factor) to ``opts["tol"]`` at the stations (zeta_out, V_out) within
    ``max_time`` seconds (``budget_name`` says whose budget it is, in refusals) and ``max_memory`` bytes (module
    docstring; ``opts``: chebyshev's options).

    The cost is forecast twice: each main march after its first steps (its share of the time left, against its
    pace so far; :func:`~persson_fp.solvers.chebyshev.radau.radau_march`), and before every refinement (the last
    pass's time scaled by the new degree squared and the steps the tighter march and earlier start need); a solve
    forecast over the budget is refused at once, naming the forecast and the accuracy that fits."""
    o, pr = opts, problem
    tol = o["tol"]
    wall = _Wall(pr)
    n, frac = _start_of(pr, V_out, tol, o)
    if o["n_p"] is None:  # refused before any march: the floor at the first degree, and at the degree the loop
        # ends at where tol is close to the floor (1.3x the first: a first pass there never met it, measured on
        # scene W and the nearly constant wall, tol 9e-11 ... 3e-9; a fixed n_p skips this forecast)
        n_end = min(int(math.ceil(1.3 * n)), N_MAX_WALL)
        if (f0 := _floor_at(pr, V_out, wall, n, frac)) > tol:
            _unreachable(pr, V_out, wall, tol, n, f0, o)
        if (f_end := _floor_at(pr, V_out, wall, n_end, frac)) > tol:
            _unreachable(pr, V_out, wall, tol, n_end, f_end, o, f" (where the refinement ends near the floor; a fixed "
                         f"n_p = {n} runs anyway)")  # fmt: skip
    tol_t = tol / 4.0
    budget = (time.perf_counter() + max_time, max_time, budget_name, tol)  # (deadline, max_time, whose, tol)
    march = o["march"] or "radau"
    total = {"steps": 0, "rejected": 0, "expm" if march == "magnus" else "solves": 0}
    runs = 0
    last_time = math.inf  # the march's part of the last estimate where it was tightened after it
    while True:
        check_degree_memory(n, pr.n_loads, max_memory, "moving-wall")
        t_pass = time.perf_counter()
        main = _run(pr, V_out, wall, n, frac, tol_t, budget, march=march)
        grid_part = _run(pr, V_out, wall, max(8, int(round(0.75 * n))), frac, tol_t, budget, main["nodes"], march)
        start_part = _run(pr, V_out, wall, n, 4.0 * frac, tol_t, budget, main["nodes"], march)
        runs += 3
        for r in (main, grid_part, start_part):
            for key in total:
                total[key] += r["stats"][key]
        L1_g, dA_g, dP_g, dN_g, dF_g = _compare(main, grid_part, pr.p_bar)
        L1_s, dA_s, dP_s, dN_s, dF_s = _compare(main, start_part, pr.p_bar)
        floor = np.maximum(4.0 * np.finfo(float).eps * n * n, main["roundoff"])
        balance = np.abs(main["A_el"] + main["A_pl"] + main["A_non"] - 1.0)
        t_err, unresolved = main["t_err"], main["unresolved"]
        common = floor + t_err + unresolved + balance
        est = {
            "L1": L1_g + L1_s / 4.0 + common,
            "elastic_area": dA_g + dA_s / 4.0 + common,
            "plastic_area": dP_g + dP_s / 4.0 + common,
            "noncontact_area": dN_g + dN_s / 4.0 + common,
            "load": dF_g + dF_s / 4.0 + common,
        }
        est["elastic_area"] = np.maximum(est["elastic_area"], est["L1"])  # |dA_el| <= int |dP| dp
        worst = max(float(np.max(est[q])) for q in ("L1", "elastic_area", "plastic_area", "noncontact_area"))
        if o["n_p"] is not None or worst <= tol:
            break
        # refine every part above a third of tol at once: the march (its estimate ~ 2 x its tol, measured), the
        # start (earlier V0, a few more nodes for the narrower start) and the degree
        grid_worst = max(float(np.max(v)) for v in (L1_g, dA_g, dP_g, dN_g, unresolved))
        start_worst = max(float(np.max(v)) for v in (L1_s, dA_s, dP_s, dN_s)) / 4.0
        time_worst = float(np.max(t_err + balance))  # (the area balance is broken by the march, mostly)
        share = tol / 3.0
        # (the partners march on the main run's steps: their differences measure the degree and the start alone)
        refined = False
        was = (n, tol_t, frac)
        if time_worst > share and time_worst > 0.5 * last_time:  # a tighter march did not lower it: round-off
            reach = max(3.0 * time_worst, _reachable(pr, V_out, wall, tol, o))
            raise SolverError(
                f"chebyshev (moving wall): the march's error estimate stays at {time_worst:.2e} (tol = {tol:.3g}) "
                f"however small its steps (the round-off of the stiff operator at degree {n}); loosen tol (about "
                f"{reach:.1e} is within reach) or use method='fv'"
            )
        last_time = time_worst if time_worst > share else math.inf
        if time_worst > share and tol_t > 1e-3 * tol:
            tol_t *= float(np.clip(0.5 * share / time_worst, 1.0 / 16.0, 0.5))
            refined = True
        if start_worst > share and frac > 1e-6:
            frac /= 4.0
            n = int(math.ceil(1.15 * n))
            refined = True
        if not refined and time_worst >= grid_worst and tol_t > 1e-3 * tol:  # no part alone exceeds its share
            tol_t /= 4.0
        elif grid_worst > share or not refined:
            n = int(math.ceil(1.3 * n))
        k = int(np.argmax(np.max(est["L1"], axis=1)))  # the station that fails
        z_k, width = float(zeta_out[k]), math.sqrt(float(V_out[k])) / float(main["s"][k])
        hint = "loosen tol or use method='fv'"
        if width < 1e-2:  # (the PDF a tiny fraction of the domain wide: no degree resolves it)
            hint = f"the PDF there is {width:.1e} of sigma_Y wide: start zeta_out later (or use method='fv')"
        if n > N_MAX_WALL:
            raise SolverError(
                f"chebyshev (moving wall): the error estimate {worst:.3e} exceeds tol = {tol:.3g} at degree "
                f"{N_MAX_WALL} (worst at zeta = {z_k:.6g}); {hint}"
            )
        if (f_next := _floor_at(pr, V_out, wall, n, frac)) > tol:  # the next pass cannot meet tol: refuse now
            _unreachable(pr, V_out, wall, tol, n, f_next, o, f"; after {runs} runs the error estimate is {worst:.2e}")
        where = (z_k, None if width >= 1e-2 else hint)
        _forecast_pass(time.perf_counter() - t_pass, was, (n, tol_t, frac), budget, worst, tol, runs, where)
        if time.perf_counter() > budget[0]:
            out_of_time(max_time, f"moving wall: {runs} runs done, degree {n}")
    load = main["F_el"] + main["s"][:, None] * main["A_pl"]
    info = {
        "path": "moving-wall",
        "moving_wall": True,
        "grid": {
            "n_p": n,
            "p_max": main["s"],
            "mapping": "x = p / sigma_Y(zeta), Chebyshev points sinh-mapped around p_bar / sigma_Y(zeta0)",
        },
        "V0_fraction": frac,
        "zeta0": zeta_of(pr, frac * V_out),
        "runs": runs,
        "error_estimate": {
            **est,
            "method": "|run - run at 3/4 degree| + |run - run from 4 V0| / 4 + |march - companion march at double "
            "steps| x 2 + the start's quadrature error + max(4 eps n^2, eps ||L dV||_1 (n/400)^2) "
            "+ |A_el + A_pl + A_non - 1|",
            "parts": {"time": t_err, "area_balance": balance, "start": unresolved, "roundoff": floor},
        },
        "area_residual": float(np.max(balance)),
        "load_residual": float(np.max(np.abs(load - pr.p_bar) / pr.p_bar)),
        "march": {**main["stats"], "tol": tol_t, "all_runs": total},
        "wall_value": main["beta"] * main["A_pl"],
    }
    p, P0, weights = _output(pr, main, n)
    P0, info["ripple_zeroed"] = collocation.zero_ripple(P0)
    return SolverOutput(
        p=p,
        P0=P0,
        weights=weights,
        kind="point",
        info=info,
        contact_area=main["A_el"],
        load=main["F_el"],
        plastic_area=main["A_pl"],
    )


def _output(pr, main, n):
    """(p (n_zeta, m), P0 (n_zeta, n_loads, m), weights (n_zeta, m)): the grid stretches with sigma_Y (P = w / s)."""
    s = main["s"]
    if pr.n_loads == 1:  # each station's own nodes
        x = np.stack([g.p[0] for g in main["grids"]])
        wx = np.stack([g.w[0] for g in main["grids"]])
        W = main["W"]
    else:  # a common plain Chebyshev grid of twice the degree in x
        common = collocation.chebyshev_grid(2 * n, 1.0, np.array([0.5]), np.array([1e6]))
        x = np.broadcast_to(common.p[0], (s.size, common.p.shape[1]))
        wx = np.broadcast_to(common.w[0], x.shape)
        q = np.broadcast_to(common.p[0], (pr.n_loads, common.p.shape[1]))
        W = np.stack([collocation.interpolate(g, main["W"][k], q) for k, g in enumerate(main["grids"])])
    return s[:, None] * x, W / s[:, None, None], s[:, None] * wx
