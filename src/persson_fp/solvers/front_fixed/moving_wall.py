r"""A scale-dependent hardness: the moving yield wall, front-fixed onto the general fluxes.

The physics (Persson, Phys. Rev. Lett. 87 (2001) 116101; Surf. Sci. Rep. 61 (2006) 201, Sec. 3).  On
:math:`0 < p < \sigma_Y(\zeta)` the PDF obeys :math:`\partial_\tau P = \tfrac12\partial_p^2 P` in the effective
variance :math:`d\tau = S(A)\,dV` (A = A_el + A_pl, the total contact area), absorbing at p = 0.  Where the wall
moves (:math:`\sigma_Y' > 0`) the PDF does not vanish at it: area balance gives
:math:`dA_{pl}/d\tau = -\dot\sigma P(\sigma_Y) - \tfrac12\partial_pP(\sigma_Y)` and the load balance
:math:`F_{el} + \sigma_Y A_{pl} = \bar p` then requires :math:`P(\sigma_Y) = 2\dot\sigma A_{pl}`
(:math:`\dot\sigma = d\sigma_Y/d\tau`): the plastic area sits at the wall and is handed back into the elastic
domain as the wall moves out.  No closed form exists.

*Front fixing.*  With :math:`x = p/s`, :math:`s(\tau) = \sigma_Y(\zeta(\tau))` and the mass density in x,
:math:`w(x, \tau) = s\,P(sx, \tau)`, the domain is fixed, :math:`x \in [0, 1]`, and the equation is conservative:

.. math::  \partial_\tau w = \partial_x\Big(\frac{1}{2s^2}\partial_x w + \frac{\dot s}{s}\,x\,w\Big),
           \qquad w(0) = 0, \qquad w(1) = 2 s\dot s\,A_{pl}, \qquad \frac{dA_{pl}}{d\tau} = G(1),

G being the flux through x = 1: exactly the engine's yield wall (:mod:`persson_fp.solvers.front_fixed.fluxes`) with
:math:`\beta = 2s\dot s`.  The independent variable is V (known in closed form along the spectrum), so with
:math:`d\tau = S\,dV`: :math:`D = S/(2s^2)`, :math:`v = (s_V/s)\,x`, :math:`\beta = 2 s s_V / S`,
:math:`s_V = \sigma_Y'(\zeta)/V'(\zeta)`.  Second order in x and V on a fixed grid, no cut cells; the areas balance
to round-off; the load balance is met to the discretisation error (reported).

*Start.*  At a small :math:`\zeta_0` the PDF has not reached the wall; the start is the strip solution at
:math:`\sigma_Y(\zeta_0)` and the elastic effective variance (its plastic area, ~0, is reported as
``start_plastic_area``).

*Error estimate.*  No closed form, so each run is paired with one at half the cells and half the steps;
the Richardson estimate of the fine run's error for every area and load at every station
(``info["error_estimate"]``; :mod:`persson_fp.solvers.front_fixed.estimate`, which adds the start-up and far-wall parts
for general coefficients); the observed order is measured in the tests and in ``benchmarks/plasticity.py``.
"""

from __future__ import annotations

import time
from functools import partial

import numpy as np

from persson_fp.problems.contact import ContactProblem
from persson_fp.results.solution import SolverError
from persson_fp.solvers.base import StationRecorder, zeta_of
from persson_fp.solvers.front_fixed import fluxes
from persson_fp.solvers.front_fixed.models import model_of
from persson_fp.solvers.schemes import TRBDF2_GAMMA, graded
from persson_fp.theory.fudge import NoFudge
from persson_fp.theory.strip import strip_cdf, strip_quantities

__all__ = ["MovingWall", "min_cells", "check_resolved", "domain_end"]


class MovingWall:
    """The front-fixed moving-wall problem on ``n`` cells in x for every load of ``problem``.

    Parameters
    ----------
    problem : ContactProblem
        With a hardness (constant or not: a constant one gives beta = 0, the strip).
    n : int
        Cells in x = p / sigma_Y.
    """

    def __init__(self, problem: ContactProblem, n: int, k_domain: float = 10.0, p_end: float | None = None):
        self.problem = problem
        self.n = n
        self.h = 1.0 / n
        self.x_faces = np.linspace(0.0, 1.0, n + 1)
        self.x = 0.5 * (self.x_faces[1:] + self.x_faces[:-1])
        self.no_fudge = isinstance(problem.fudge, NoFudge)
        self.model = model_of(problem)
        """What the engine asks of the coefficients (:mod:`~persson_fp.solvers.front_fixed.models`)."""
        # the model's answers for this grid (bound once: no extra frame per right-hand side)
        self.coefficients = partial(self.model.face_coefficients, self)
        """``coefficients(V, S_bar)``: the engine coefficients at V with the fudge factor frozen at ``S_bar`` (m,)."""
        self.drift_cells = partial(self.model.drift_cells, self)
        """``drift_cells(V)``: b1 = B1 / V'(zeta) at the cell centres (pressure per unit V; zeros without a drift)."""
        self.drift_rate = partial(self.model.drift_rate, self)
        r"""``drift_rate(V, y)``: d/dV of the load the drift carries, :math:`\int b_1 P\,dp` (m,)."""
        self.elastic = problem.elastic_counterpart()
        # without a hardness the far wall is the end of the numerical domain (what it absorbs is reported as lost);
        # general coefficients: sized from B1 and B2 themselves (persson_fp.solvers.front_fixed.domain)
        given = None if p_end is None else (float(p_end), None)
        self.p_end = problem.upper_wall.grid_cut(lambda: given or self.model.domain_end(problem, k_domain))[0]
        self.wall_many = partial(problem.upper_wall.front, problem, p_end=self.p_end)
        """``wall_many(V)``: (s, s_V) arrays at complete-contact variances V, the far end of the grid and its rate
        d s / dV (pressure, 1/pressure): sigma_Y(zeta(V)) at a yield wall, the cut ``p_end`` without one."""
        self._cache = {}
        self._coef_cache = {}
        self._drift_cache = {}
        self.deadline = None
        """perf_counter() time by which a march must be done (the solver's max_time), or None."""

    # -- the wall along V --------------------------------------------------------------------------------
    def zeta(self, V):
        pr = self.problem
        return zeta_of(pr, V)

    def wall(self, V):
        """(s, s_V) at one V, from the cache that :meth:`prefill` fills (vectorised) for a march's stage times."""
        hit = self._cache.get(V)
        if hit is None:
            s, sV = self.wall_many(np.array([V]))
            hit = self._cache[V] = (float(s[0]), float(sV[0]))
        return hit

    def prefill(self, V_nodes):
        """Evaluate the wall at every stage time of a march over ``V_nodes`` at once (the engine's expressions)."""
        t, dt = V_nodes[:-1], np.diff(V_nodes)
        pts = np.concatenate([V_nodes, t + TRBDF2_GAMMA * dt, t + dt, t + 0.5 * dt, (t + 0.5 * dt) + 0.5 * dt])
        s, sV = self.wall_many(pts)
        self._cache.update(zip(pts.tolist(), zip(s.tolist(), sV.tolist())))

    def load(self, V, y) -> np.ndarray:
        """F_el + s a: the load of the state y (m, n + 1) at V (elastic, plus the wall's mass at the wall)."""
        s, _ = self.wall(V)
        return s * ((y[:, : self.n] @ self.x) * self.h + y[:, self.n])

    def check_deadline(self, V) -> None:
        """:class:`~persson_fp.SolverError` once the march has run past its ``deadline`` (max_time)."""
        if self.deadline is not None and time.perf_counter() > self.deadline:
            raise SolverError(
                f"moving wall / general engine: max_time exceeded at zeta = {float(self.zeta(V)[0]):.6g} (of "
                f"{float(self.problem.zeta_max):.6g}); use fewer cells or steps, or pass a larger max_time (seconds)"
            )

    # -- start, nodes -----------------------------------------------------------------------------------
    def start(self, V0):
        """The state y0 (m, n + 1) at V0: the strip's cell averages at sigma_Y(zeta(V0)) and the elastic tau."""
        pr = self.problem
        s0, _ = self.wall(V0)
        tau0 = np.asarray(self.elastic.tau_of_V(np.array([V0])), dtype=float).reshape(pr.n_loads)
        centre, tau0 = self.model.start_moments(self, V0, tau0)  # (general: a Gaussian along the mean path)
        edges = s0 * self.x_faces
        F = strip_cdf(edges[None, :], centre[:, None], s0, tau0[:, None])
        q = strip_quantities(centre, s0, tau0)
        y0 = np.empty((pr.n_loads, self.n + 1))
        y0[:, :-1] = np.diff(F, axis=-1) / self.h  # w = s P: its cell average in x is the p-cell mass / h
        y0[:, -1] = q["plastic_area"]
        return y0, q["noncontact_area"], q["plastic_area"]

    def start_moments(self, z0: float, n: int = 64):
        r"""Mean and variance (m,) of the start-up Gaussian at zeta0: the drift and the diffusion integrated in zeta
        along the mean path, :math:`c(\zeta) = \bar p + \int_1^\zeta B_1(c, \zeta')\,d\zeta'` and
        :math:`\tau_0 = \int_1^{\zeta_0} B_2(c, \zeta')\,d\zeta'` (trapezoid rule on ``n`` nodes in ln zeta, Heun
        for the path).  Exact when B1 and B2 do not depend on p (any dependence on zeta included); otherwise the
        error is that of freezing p over the start's width, measured by the start partner (:func:`run_pair`)."""
        pr = self.problem
        if z0 <= 1.0:
            return pr.p_bar.copy(), np.full(pr.n_loads, 1e-300)
        lz = np.linspace(0.0, np.log(z0), n + 1)
        z = np.exp(lz)
        c = pr.p_bar.astype(float).copy()
        tau = np.zeros(pr.n_loads)
        B1a, B2a = pr.coefficients(c, float(z[0]))
        for i in range(n):
            dz = z[i + 1] - z[i]
            c_pred = c + dz * B1a
            B1b, B2b = pr.coefficients(c_pred, float(z[i + 1]))
            c = c + 0.5 * dz * (B1a + B1b)
            B1b, B2b = pr.coefficients(c, float(z[i + 1]))
            tau += 0.5 * dz * (B2a + B2b)
            B1a, B2a = B1b, B2b
        return c, np.maximum(tau, 1e-300)

    def choose_V0(self, V_first: float, tau0_fraction: float):
        """Start where sqrt(tau) spans ~3 cells of the wall's grid, at most ``tau0_fraction`` of the first
        station's V (in V; tau ~ S(1) V there)."""
        s1, _ = self.wall(V_first)
        target = max(9.0 * (s1 * self.h) ** 2, 1e-6 * V_first)
        return float(min(target, tau0_fraction * V_first))

    @staticmethod
    def nodes(V0: float, V_st: np.ndarray, n_steps: int):
        """V nodes from V0 through every station (graded: :func:`persson_fp.solvers.schemes.graded`) and the station
        indices."""
        V_all = np.concatenate(([V0], V_st))
        u = graded(V_all, V_all[-1])
        counts = np.maximum(1, np.round(n_steps * np.diff(u) / (u[-1] - u[0])).astype(int))
        pieces, idx = [np.array([V0])], []
        for i in range(V_st.size):
            uu = np.linspace(u[i], u[i + 1], counts[i] + 1)[1:]
            Vg = np.geomspace(V_all[i], V_all[i + 1], 2049)
            ug = graded(Vg, V_all[-1])
            seg = np.interp(uu, ug, Vg)
            seg[-1] = V_all[i + 1]
            pieces.append(seg)
            idx.append(sum(len(p) for p in pieces) - 1)
        return np.concatenate(pieces), np.array(idx)

    # -- the march --------------------------------------------------------------------------------------
    def solve(
        self,
        V_st,
        n_steps: int,
        scheme: str = "tr-bdf2",
        coupling: str = "predictor",
        damped: int = 2,
        tau0_fraction: float = 0.05,
        V0: float | None = None,
        y0=None,
        source=None,
    ):
        """March from the start (at ``V0``, default :meth:`choose_V0`) through the stations ``V_st``;
        a dict of per-station arrays."""
        pr = self.problem
        S = pr.fudge.S
        m, h = pr.n_loads, self.h
        if V0 is None:
            V0 = self.choose_V0(float(V_st[0]), tau0_fraction)
        if y0 is None:
            y, A_non0, A_pl0 = self.start(V0)
        else:  # a given start (cell averages of w and the wall mass), e.g. a manufactured solution
            y, A_non0, A_pl0 = np.array(y0, dtype=float), np.zeros(m), np.asarray(y0, dtype=float)[:, -1]
        V_nodes, st_idx = self.nodes(V0, np.asarray(V_st, dtype=float), n_steps)
        self.prefill(V_nodes)
        rec = StationRecorder(st_idx, W=(m, self.n), A_pl=(m,), A_non=(m,), s=(), drift=(m,))
        absorbed = np.zeros(m)
        drift = np.zeros(m)  # int b1 P dp dV since V0 (the first-moment law, info["load_law"])
        load0 = self.load(V0, y)
        rate = self.drift_rate(V0, y)
        peclet = 0.0
        for k in range(V_nodes.size - 1):
            Va, Vb = V_nodes[k], V_nodes[k + 1]
            dV = Vb - Va
            if self.no_fudge:
                S_bar = np.ones(m)
            else:  # S at the total contact area A_el + A_pl = 1 - A_non
                A_now = np.clip(1.0 - A_non0 - absorbed, 0.0, 1.0)
                Sn = S(A_now)
                if coupling == "lagged":
                    S_bar = Sn
                else:
                    out_rate = fluxes.outflux_low(self.coefficients(Va, np.ones(m)), y, h)  # per unit tau
                    S_bar = 0.5 * (Sn + S(np.clip(A_now - dV * Sn * out_rate, 0.0, 1.0)))
            coef = lambda V, S_bar=S_bar: self.coefficients(V, S_bar)  # noqa: E731
            y, j = fluxes.step(coef, Va, dV, y, h, "be-halves" if k < damped else scheme, source)
            absorbed += j
            rate_b = self.drift_rate(Vb, y)
            drift += 0.5 * dV * (rate + rate_b)  # trapezoid in V: second order, like the march
            rate = rate_b
            c = coef(Vb)
            peclet = max(peclet, float(np.max(np.abs(c.v[:, -1]) * h / np.max(c.D))))
            if not np.all(np.isfinite(y)):
                raise SolverError(f"moving wall: non-finite values at V = {Vb:.6g}; raise n_steps")
            if self.deadline is not None and k % 16 == 15:
                self.check_deadline(Vb)
            if k + 1 in rec:
                rec.record(k + 1, W=y[:, :-1], A_pl=y[:, -1], A_non=A_non0 + absorbed, s=self.wall(Vb)[0], drift=drift)
        W, A_pl, A_non, s_st, drift_st = rec["W"], rec["A_pl"], rec["A_non"], rec["s"], rec["drift"]
        A_el = W.sum(axis=-1) * h
        F_el = s_st[:, None] * (W @ self.x) * h
        return {
            "W": W,
            "s": s_st,
            "elastic_area": A_el,
            "plastic_area": A_pl,
            "noncontact_area": A_non,
            "elastic_load": F_el,
            "plastic_load": s_st[:, None] * A_pl,
            "V0": V0,
            "zeta0": float(self.zeta(V0)[0]),
            "start_plastic_area": float(np.max(A_pl0)),
            "start_load": load0,
            "drift_load": drift_st,
            "steps": V_nodes.size - 1,
            "max_cell_peclet": peclet,
        }


def min_cells(problem, V_st, k_domain: float = 10.0, p_end=None) -> int:
    """The fewest cells n with which the PDF spans at least one cell at every station (:func:`check_resolved`)."""
    s = MovingWall(problem, 4, k_domain, p_end).wall_many(V_st)[0]
    S1 = float(problem.fudge.S(np.array(1.0)))
    return int(np.ceil(float(np.max(s / np.sqrt(S1 * np.asarray(V_st, dtype=float)))) * (1.0 + 1e-12)))


def check_resolved(problem, V_st, n: int, zeta_st, k_domain: float = 10.0, p_end=None) -> None:
    """``ValueError`` unless the PDF spans at least one cell of the stretched grid at every station:
    sqrt(tau) >= sigma_Y / n (or p_end / n without a hardness), tau taken as S(1) V (its largest value before
    contact is lost)."""
    mw = MovingWall(problem, n, k_domain, p_end)
    s, _ = mw.wall_many(V_st)
    S1 = float(problem.fudge.S(np.array(1.0)))
    need = s / n
    have = np.sqrt(S1 * V_st)
    bad = have < need
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(
            f"moving wall / general engine: the PDF at zeta = {zeta_st[i]:.6g} (width sqrt(tau) ~ {have[i]:.3e}) "
            f"is narrower than one cell of the grid on [0, {s[i]:.4g}] with n_p = {n}; raise n_p to >= "
            f"{int(np.ceil(n * float(np.max(need / have))))} or start zeta_out later"
        )


def domain_end(problem, k_domain: float):
    """(p_end, info) of the far wall without a hardness: from the coefficients for a general problem
    (:func:`~persson_fp.solvers.front_fixed.domain.coefficient_domain`), else max(p_bar) + k sqrt(tau)."""
    return model_of(problem).domain_end(problem, k_domain)
