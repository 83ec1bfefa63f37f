r"""What the front-fixed engine asks of a problem's coefficients: the homogenised ones or general B1, B2.

The engine (:mod:`~persson_fp.solvers.front_fixed.moving_wall`) marches the same conservative fluxes for both; it
asks the problem's coefficient model for what differs, never which model it has:

- :class:`Homogenised` -- Persson's B1 = 0, B2 = S(A) dV/dzeta (Xu et al. tutorial, Eq. 'eq:new_B2'): the face
  coefficients in closed form, a start on the image/strip solution that is exact, no drift, the domain cut at
  max(p_bar) + k sqrt(tau(zeta_max)).
- :class:`General` -- the Fokker--Planck coefficients B1(p, zeta), B2(p, zeta) of a
  :class:`~persson_fp.FokkerPlanckProblem` (Eq. 'E:Fokker_Planck_Forward'): the coefficients sampled at the faces and
  cells, a start-up Gaussian along the mean path (cleared of the walls, its error measured by a third run), the drift's
  load, the cell Peclet number at the walls, and a domain sized from B1 and B2
  (:func:`~persson_fp.solvers.front_fixed.domain.coefficient_domain`).

:func:`model_of` picks the model once per engine grid.
"""

from __future__ import annotations

import numpy as np

from persson_fp.solvers.front_fixed import fluxes
from persson_fp.solvers.front_fixed.domain import coefficient_domain

__all__ = ["Homogenised", "General", "model_of", "START_CLEARANCE", "PECLET_MAX", "N_P_LIMIT", "COEF_CACHE"]

COEF_CACHE = 8
"""General coefficients: how many variances V keep their sampled coefficients (the most recent; a step of the
march asks for a few V, the next step starts at the last one).  Unbounded, the cache held every stage time of the
march: ~40 n_p bytes a stage, 18 MB at n_p = n_steps = 400 (tracemalloc) and O(n_p n_steps) beyond."""

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


class Homogenised:
    """B1 = 0, B2 = S(A) dV/dzeta: nothing to sample, clear or measure beyond the Richardson pair."""

    def domain_end(self, problem, k_domain: float):
        """(p_end, info) of the far cut without a hardness: max(p_bar) + k sqrt(tau(zeta_max))."""
        p_end = float(problem.p_max(k_domain))
        return p_end, {"p_end": p_end, "rule": "max(p_bar) + k_domain sqrt(tau(zeta_max))"}

    def face_coefficients(self, mw, V, S_bar):
        """Engine coefficients at V with the fudge factor frozen at ``S_bar`` (m,): D = S/(2 s^2), v = (s_V/s) x,
        beta = 2 s s_V / S (:mod:`~persson_fp.solvers.front_fixed.moving_wall`)."""
        hit = mw._cache.get(V)  # (mw.wall(V), one call less: this runs at every right-hand side)
        if hit is None:
            s_, sV_ = mw.problem.upper_wall.front(mw.problem, np.array([V]), mw.p_end)  # (mw.wall_many's)
            hit = mw._cache[V] = (float(s_[0]), float(sV_[0]))
        s, sV = hit
        m = mw.problem.n_loads
        S_bar = np.broadcast_to(np.asarray(S_bar, dtype=float), (m,))
        D = (S_bar / (2.0 * s * s))[:, None] * np.ones(mw.n + 1)
        v = np.broadcast_to((sV / s) * mw.x_faces, (m, mw.n + 1))
        return fluxes.Coefficients(D=D, v=v, beta=2.0 * s * sV / S_bar)

    def drift_cells(self, mw, V) -> np.ndarray:
        """b1 at the cell centres: zeros."""
        return np.zeros(mw.n)

    def drift_rate(self, mw, V, y) -> np.ndarray:
        """d/dV of the load the drift carries: none."""
        return np.zeros(y.shape[0])

    def add_drift_jacobian(self, J, mw, V, n: int, h: float) -> None:
        """The drift's load row of mol's Jacobian: none."""

    def start_moments(self, mw, V0, tau0):
        """Centre and variance (m,) of the start at V0: the loads and the elastic effective variance (exact)."""
        return mw.problem.p_bar, tau0

    def clear_start_V(self, mw, V0: float) -> float:
        """The start is exact: V0 as it is."""
        return V0

    def check_wall_peclet(self, mw, V0: float, name: str) -> None:
        """No drift: nothing to resolve at the walls."""

    def start_partner(self, run, grid, n: int, V_st, fine: dict, coarse: dict) -> None:
        """The start is exact: no third run."""

    def floor_stations(self, est: dict) -> dict:
        """The Richardson estimates as they are."""
        return est

    def start_load(self, fine: dict, problem):
        """The load at the start of the first-moment law: p_bar (the drift carries none)."""
        return problem.p_bar

    def law_error(self, fine: dict, coarse: dict, law_total, total):
        """Discretisation error of the first-moment law: none (it holds exactly without a drift)."""
        return np.zeros_like(total)

    def singular_step(self, err, name: str, pr, p_end=None, needs: str | None = None):
        """A singular implicit step cannot come from the homogenised coefficients: the original error."""
        raise err


class General(Homogenised):
    """General Fokker--Planck coefficients B1(p, zeta), B2(p, zeta) (:class:`~persson_fp.FokkerPlanckProblem`)."""

    def domain_end(self, problem, k_domain: float):
        """(p_end, info) of the far cut without a hardness, sized from B1 and B2 themselves
        (:func:`~persson_fp.solvers.front_fixed.domain.coefficient_domain`)."""
        return coefficient_domain(problem, k_domain)

    def face_coefficients(self, mw, V, S_bar):
        r"""Front-fixed form of :math:`\partial_V P = -\partial_p(b_1P) + \tfrac12\partial_p^2(b_2P)`, b = B / V'(zeta):
        the diffusive flux :math:`-\partial_x(D w)` with :math:`D = b_2/(2s^2)` at the cells (``D_cells``, the
        Fokker--Planck form), the drift :math:`v = (s_V/s)x - b_1/s` at the faces, :math:`\beta = 2 s s_V / b_2(s)`.
        Cached per V."""
        hit = mw._coef_cache.get(V)
        if hit is not None:
            return hit
        pr = mw.problem
        s, sV = mw.wall(V)
        z = float(mw.zeta(V)[0])  # (from the spectrum's inverse: in [1, zeta_max])
        dVdz = float(pr.V_kernels.dV_dzeta(z))
        B1f, B2f = pr.coefficients(s * mw.x_faces, z)
        B1c, B2c = pr.coefficients(s * mw.x, z)
        b1f, b2f, b2c = B1f / dVdz, B2f / dVdz, B2c / dVdz
        for cache in (mw._coef_cache, mw._drift_cache):  # (the oldest out: memory independent of n_steps)
            while len(cache) >= COEF_CACHE:
                del cache[next(iter(cache))]
        mw._drift_cache[V] = B1c / dVdz
        v = (sV / s) * mw.x_faces - b1f / s
        if sV > 0 and not b2f[-1] > 0:
            raise ValueError(f"B2 must be > 0 at a moving yield wall (p = {s:.6g}, zeta = {z:.6g}), got {B2f[-1]!r}")
        beta = 2.0 * s * sV / b2f[-1] if sV > 0 else 0.0
        m = pr.n_loads
        c = fluxes.Coefficients(
            D=np.broadcast_to(b2f / (2.0 * s * s), (m, mw.n + 1)),
            v=np.broadcast_to(v, (m, mw.n + 1)),
            beta=np.full(m, beta),
            D_cells=np.broadcast_to(b2c / (2.0 * s * s), (m, mw.n)),
        )
        mw._coef_cache[V] = c
        return c

    def drift_cells(self, mw, V) -> np.ndarray:
        """b1 = B1 / V'(zeta) at the cell centres at V (pressure per unit V)."""
        if V not in mw._drift_cache:
            self.face_coefficients(mw, V, None)
        return mw._drift_cache[V]

    def drift_rate(self, mw, V, y) -> np.ndarray:
        r"""d/dV of the load carried by the drift, :math:`\int b_1 P\,dp = \sum_i b_1(p_i) w_i h` (m,)."""
        return (y[:, : mw.n] @ self.drift_cells(mw, V)) * mw.h

    def add_drift_jacobian(self, J, mw, V, n: int, h: float) -> None:
        """The row of the drift's load (mol's extra unknown): d/dy of int b1 P dp."""
        J[n + 2, :n] = self.drift_cells(mw, V) * h

    def start_moments(self, mw, V0, tau0):
        """A Gaussian along the mean path (:meth:`MovingWall.start_moments`): exact for coefficients that do not
        depend on p."""
        return mw.start_moments(float(mw.zeta(V0)[0]))

    def start_partner(self, run, grid, n: int, V_st, fine: dict, coarse: dict) -> None:
        """The start (a frozen-coefficient Gaussian) is not exact, and a partner that shares it cannot see its
        error: a third run at n/2 from twice the start-up variance measures it, ``fine["start_error"] =
        |Q(n/2, 2 V0) - Q(n/2, V0)|`` (an upper bound for a start error of order >= 1 in V0; the two coarse runs
        share their grid, so their difference is the start alone)."""
        V1 = 2.0 * fine["V0"]
        if V1 >= 0.5 * V_st[0]:  # no room before the first station: start earlier instead
            V1 = 0.5 * fine["V0"]
        other = run(grid(max(n // 2, 4)), V_st, V0=V1, level=1)
        quantities = ("elastic_area", "plastic_area", "noncontact_area", "elastic_load", "plastic_load")
        fine["start_error"] = {q: np.abs(other[q] - coarse[q]) for q in quantities}
        fine["start_error"]["L1"] = np.abs(other["W"] - coarse["W"]).sum(axis=-1) / coarse["W"].shape[-1]
        fine["start_V"] = (fine["V0"], V1)

    def floor_stations(self, est: dict) -> dict:
        """A difference that changes sign between stations passes through 0 where the error need not: no station's
        estimate is below STATION_FLOOR x its neighbours' (per load)."""
        for q in est:
            e = est[q]
            if np.all(np.isnan(e)) or e.shape[0] < 2:
                continue
            nb = np.maximum(np.vstack([e[1:2], e[:-1]]), np.vstack([e[1:], e[-2:-1]]))
            est[q] = np.maximum(e, STATION_FLOOR * nb)
        return est

    def start_load(self, fine: dict, problem):
        """The load of the start-up Gaussian (its centre moved with the drift)."""
        return fine["start_load"]

    def law_error(self, fine: dict, coarse: dict, law_total, total):
        """The law and the load are both discrete: each carries its own discretisation error (Richardson)."""
        law_c = coarse["start_load"][None, :] + coarse["drift_load"]
        return np.abs(law_total - law_c) + np.abs(total - coarse["elastic_load"] - coarse["plastic_load"])

    def singular_step(self, err, name: str, pr, p_end=None, needs: str | None = None):
        """A singular implicit step (LAPACK's banded solve, SuperLU's "singular" factor) named as a drift too strong;
        ``needs``: a text the error must contain (else the original error)."""
        if needs is not None and needs not in str(err):
            raise err
        raise self.singular_step_error(name, pr, f"{type(err).__name__}: {err}", p_end) from err

    def clear_start_V(self, mw, V0: float, k: float = START_CLEARANCE, tries: int = 40) -> float:
        r"""The start-up V0, lowered (by 4x at a time) until the start is meaningful for general coefficients.

        The start is a Gaussian N(c, tau0) along the mean path :math:`c = \bar p + \int_1^{\zeta_0} B_1 d\zeta`
        (:meth:`MovingWall.start_moments`) with images about the walls.  Where the drift moved it by less than its width
        sqrt(tau0) that is as good as without a drift; where it moved it further the centre must be ``k`` widths inside
        [0, p_end] (or [0, sigma_Y]): a strong drift toward a wall (B1 = -1 with p_bar = 0.025 reaches p = 0 at
        zeta ~ 1.025) otherwise gives a centre beyond the wall, where the image start is no PDF at all (cell masses
        summing to -1, or to 0 with nothing absorbed: "the areas do not sum to 1").  Checked at V0 and 2 V0 (the start
        partner of :func:`~persson_fp.solvers.front_fixed.estimate.run_pair`)."""
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

    def check_wall_peclet(self, mw, V0: float, name: str, k: float = START_CLEARANCE, nodes: int = 256) -> None:
        r"""``ValueError`` where the drift B1 is not resolved by the cells next to a wall while the PDF is there.

        The engine's fluxes are centred; next to an absorbing wall a drift B1 toward (or away from) it makes a layer of
        width B2 / (2 |B1|), which the cells resolve while the cell Peclet number :math:`2|B1|\,\Delta p/B2` is modest.
        Far beyond :data:`PECLET_MAX` the discrete solution rings with cell masses of either sign (negative mass at the
        far wall, an A* that grows) and the stiff integrator of ``"mol"`` crawls through the ringing.  Checked along the
        mean path from the start ``V0`` (Heun in zeta, as :meth:`MovingWall.start_moments`), at the cell next to each
        wall, wherever the band c +- k sqrt(tau) reaches it.
        """
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
            detail = (
                f"a cell Peclet number 2 |B1| dp / B2 = {pe:.3g} on n_p = {mw.n} cells, which needs n_p >= {need:.3g}"
            )
            # the drift's entry of L (per unit V) times a step of 1 % of V there, against the identity of I - dV L
            entry = abs(float(pr.coefficients(np.array([p]), zw)[0][0])) / float(pr.dV_dzeta(zw)) / dp
            if entry * 0.01 * float(pr.V(zw)) * np.finfo(float).eps > 1.0:
                raise self.singular_step_error(name, pr, detail)
            if need > N_P_LIMIT:
                raise ValueError(
                    f"{name}: the drift B1 is too large for any grid where the PDF meets the wall (p = {p:.3g}, zeta = "
                    f"{zw:.5g}): {detail}; weaken B1 there"
                )
            need = int(np.ceil(need))
            raise ValueError(
                f"{name}: the drift B1 is not resolved where the PDF meets the wall: at p = {p:.3g}, "
                f"zeta = {zw:.5g} the cell Peclet number 2 |B1| dp / B2 = {pe:.3g} exceeds {PECLET_MAX:g} on "
                f"n_p = {mw.n} cells (dp = {dp:.3g}), and the centred fluxes would ring (cell masses of either "
                f"sign); raise n_p to >= {need}, or weaken B1 there"
            )

    def singular_step_error(self, name: str, pr, detail: str, p_end: float | None = None) -> ValueError:
        """The ``ValueError`` for a drift B1 so large that the implicit step ``I - dV L`` is singular to round-off
        (LAPACK's banded solve, SuperLU's "Factor is exactly singular"): names B1, its largest magnitude relative to B2
        on a probe grid (where), and the remedy."""
        hi = p_end
        if hi is None:
            hi = pr.upper_wall.probe_end(pr.zeta_max, lambda: self.domain_end(pr, 10.0)[0])
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


STATION_FLOOR = 0.1
"""General coefficients: no station's error estimate is below this fraction of its neighbours'
(:meth:`General.floor_stations`)."""


def model_of(problem):
    """The engine's model of ``problem``'s coefficients (the one place that tells them apart)."""
    return General() if problem.general else Homogenised()
