r"""Spectral solver for general Fokker--Planck coefficients and a constant hardness: method ``"chebyshev"``.

Solves the Fokker--Planck form of Persson's equation (Xu et al. tutorial, Eq. 'E:Fokker_Planck_Forward') for
:class:`~persson_fp.FokkerPlanckProblem` coefficients B2(p, zeta) > 0, B1(p, zeta) (and the homogenised
:class:`~persson_fp.ContactProblem`) with absorbing walls at p = 0 and p_max -- or, with a constant hardness, at
p = 0 and the yield stress sigma_Y, where the mass absorbed is the plastic area A_pl (Persson, Phys. Rev. Lett. 87
(2001) 116101).  In the variable V the equation is :math:`\partial_V P = \tfrac12\partial_p^2(bP) -
\partial_p(cP)` with b = B2 / V', c = B1 / V' (:mod:`persson_fp.solvers.chebyshev.coefficients`), discretised by
mapped Chebyshev collocation in p (:mod:`persson_fp.solvers.chebyshev.collocation`: spectral, faster than any power of
n_p where P is smooth).  Two paths, named in ``info["path"]``:

* ``"exponential"`` -- b and c independent of V (B2 = b(p) dV/dzeta, B1 = c(p) dV/dzeta: the homogenised theory,
  any pressure-dependent diffusion of that form): one matrix exponential per output station, exact in V.
* ``"clock"`` -- b and c change with V by a common factor s(V) only (B2 = b(p) g(zeta), B1 = c(p) g(zeta), any
  g): the separable form in the clock tau = int s dV (quadrature), one exponential over its increment, exact.
* ``"radau"`` -- anything else (a zeta-dependent b(p, zeta), a drift c(p, zeta) that does not scale with it):
  adaptive Radau IIA steps in V (order 5, L-stable; one real and one complex LU of the small dense operator a step,
  no matrix exponential), step doubling for the local error, whose signed estimates are propagated through the
  march for its estimate of the global error (:mod:`persson_fp.solvers.chebyshev.radau`); the partner runs replay
  its steps.  The march stops at the spectrum's roll-off, where dV/dzeta has a kink (a step across it is first
  order and its step-doubling estimate blind).  Every part of the estimate over a third of tol is refined at once,
  at its measured rate (the degree's first refinement at an assumed one, ``GRID_RATE_0``).  The march forecasts its
  cost after a few steps, and the loop the next try's before it runs, and either is refused at once if the solve
  would exceed its budget (``max_time``; by default ``MARCH_TIME_BUDGET`` = 10 s on this path), naming the tol that
  would fit and the time it would take.  ``march="magnus"`` takes the older fourth-order commutator-free
  exponential steps instead (:mod:`persson_fp.solvers.chebyshev.magnus`; not stopped at the roll-off);
  ``info["march"]`` counts the steps, rejected steps and solves, and lists the tries (``"tries"``: degree, start
  fraction, march tol, seconds, the forecast of those seconds, the estimate and its grid, start and time parts).
* On the first two paths the loads share one plain Chebyshev grid and the modes of its operator (one
  eigendecomposition of the adjoint for every load and station; :mod:`persson_fp.solvers.chebyshev.shared`,
  ``info["loads"]``), with no start at V0, where that grid's degree stays within reach; else the per-load grids below.
* ``"moving-wall"`` -- a scale-dependent hardness (no fudge factor): front-fixed in x = p / sigma_Y, the wall value
  beta A_pl lifted, the same kind of march (:mod:`persson_fp.solvers.chebyshev.wall`, which has its own estimate).

Every station starts afresh from the small-time expansion at V0 = V0_fraction x V (with the coefficients at V0/2
on a march path, the midpoint of [0, V0]; images across both walls).  With a hardness, what the yield wall
absorbed before V0 (the start's image across it: all of the load for a p_bar at sigma_Y) is part of A_pl.

Error estimate (``info["error_estimate"]``, per station and load; an area's is never below the L1 estimate,
which bounds it): the differences from a partner run at 3/4 of the degree (the grid) and from one started at 4 V0
divided by 4 (the start; its error scales as V0^2, so the true ratio is 15), plus twice the mass lost at the far
wall (not with a hardness: there it is A_pl), a round-off floor eps ||L dV||_1 (n / 400)^2, not below 4 eps n^2
(``collocation.roundoff_floor``: the dense exponential's backward error on the
clustered grid, whose closest nodes make ||L|| ~ n^4 / dp_min^2; measured 0.004-0.31 of eps ||L dV||_1 at
n = 100-400, 1.6e-9 to 4e-8 at n = 400, where the partners alone had fallen 1.0-1.6x below the true error) and, on
the march paths, the march's own estimate.  With ``tol`` the
degree is raised, V0 lowered or the march tightened -- whichever part dominates -- until the estimate meets it.  A
tol below the floor is refused before any run (the floor is computed from the operators alone), and again before a
run whose floor would exceed tol or once a higher degree raised an estimate the floor dominates: a
:class:`~persson_fp.SolverError` naming the best reachable accuracy (tol = 1e-12 in ~0.1 s; it took seconds up
to degree 400 before).  A march forecast to exceed its step limit is refused within ~1 s
(``radau.MarchTooLong``, naming the tol that fits).  Negative ripples of the
polynomial below 1e-6 of the peak (in the tails and next to the walls, within the estimate) are set to 0 in P0;
A*, A_pl and the load are the quadratures and wall fluxes of the polynomial itself.
"""

from __future__ import annotations

import math
import time

import numpy as np
from scipy.special import ndtr

from persson_fp.solvers.base import TIME_BUDGET, Solver, SolverOutput, check_float, check_int
from persson_fp.solvers.chebyshev import collocation
from persson_fp.solvers.chebyshev.budget import check_degree_memory, out_of_time
from persson_fp.solvers.chebyshev.coefficients import Coefficients
from persson_fp.solvers.chebyshev.magnus import magnus_march
from persson_fp.solvers.chebyshev.radau import FORECAST_AFTER_BREAK, MarchTooLong, one_sided, radau_march
from persson_fp.solvers.chebyshev.shared import estimate_entry, solve_shared
from persson_fp.solvers.chebyshev.wall import check_wall_problem, solve_moving_wall

__all__ = ["ChebyshevSolver"]

N_MAX = 400
"""Largest polynomial degree the adaptive loop reaches (a dense 400 x 400 exponential: ~50 ms)."""
TIME_SHARE = 3.0
"""The march's first tolerance, as a multiple of ``tol`` (lowered at its measured rate when the march's part of the
estimate exceeds a third of tol): the march's own estimate -- its local estimates propagated -- lands at 0.03-0.25 of
its tolerance on the families of ``benchmarks/honesty.py --method chebyshev`` (the local targets are met with room,
and the evolution damps early errors), so at 1x the march over-delivered and the result's true error sat ~70x below
tol."""
GRID_RATE_0 = 0.12
"""The march's first degree refinement assumes the grid part falls as exp(-GRID_RATE_0 n) (later ones use the rate
measured between the last two degrees): measured 0.08-0.11 a node between tries at n = 60-180 on the shifted
squared-Bessel and Ornstein--Uhlenbeck families of ``benchmarks/honesty.py --method chebyshev``, faster on the
smoother benchmark scenes A and B.  The old first step, 1.3x the degree, left most of those solves a third try."""
MARCHES = ("radau", "magnus")
"""The marches of V-dependent operators: Radau IIA (the default, :mod:`.radau`), exponential steps (:mod:`.magnus`)."""
MARCH_TIME_BUDGET = 10.0
"""Seconds a ``"radau"`` solve may take when ``max_time`` is not passed (its forecast refuses a longer one)."""
SHARED_MIN_LOADS = 1
"""Loads from which the exact paths put every load on one shared grid (:mod:`.shared`); 1: always, where it can."""
_GL96 = np.polynomial.legendre.leggauss(96)


class ChebyshevSolver(Solver):
    """Mapped Chebyshev collocation in p; exact exponentials or adaptive Magnus steps in V (module docstring).

    Options
    -------
    tol : float or None, default None
        Asked accuracy: the estimated L1 error of P0 and the error of every area at every station (as for ``tol``
        of :func:`persson_fp.solve`); degree, start and march are refined until the estimate meets it
        (:class:`~persson_fp.SolverError` if it cannot, at degree ``N_MAX``).  None: 1e-8 where the exponentials
        are exact and on a moving wall, 1e-6 on the march of a non-separable coefficient
        (``benchmarks/results/general_nonseparable.md`` for its cost against hand-written Crank--Nicolsons).
    n_p : int or None
        A fixed polynomial degree in [8, 1000] (no adaptation; the estimate is still reported).  With an explicit
        ``tol`` as well, a run whose estimate exceeds it is a :class:`~persson_fp.SolverError` (on a moving wall
        too, where ``tol`` also sets the march and the start).
    V0_fraction : float or None
        Start V0 / V(station) in (0, 0.1] (every station starts afresh from the delta); default from ``tol``.
    k_domain : float or None
        Far wall at k_domain unit-diffusion widths sqrt(V_max) beyond the largest load (in the Lamperti
        distance int dp / sqrt(b)); default from ``tol`` (8 to 12).  Not used with a hardness (the wall is sigma_Y).
    march : None, "radau" or "magnus"
        Force that adaptive march even where an exact exponential applies (to check it against one); "magnus" also
        replaces the Radau march of a non-separable problem by exponential steps.

    Notes
    -----
    Time budget: on the ``"radau"`` path a solve without ``max_time`` is held to ``MARCH_TIME_BUDGET`` = 10 s
    (its forecast refuses a longer one within about a second, naming what it would need); other paths use the
    global default ``max_time``.
    """

    name = "chebyshev"
    SUPPORTS = frozenset({"general", "hardness", "moving_wall"})
    SUPPORT_NOTES = {f: "without a fudge factor" for f in ("hardness", "moving_wall")}
    OPTIONS = {"tol": None, "n_p": None, "V0_fraction": None, "k_domain": None, "march": None}
    DEFAULT_TOL, MARCH_DEFAULT_TOL = 1e-8, {"radau": 1e-6, "magnus": 1e-6}

    def validate(self) -> None:
        o, pr = self.opts, self.problem
        tol_given = self._tol_given = o["tol"] is not None  # (a fixed n_p must then meet it, or is refused)
        o["tol"] = check_float(o["tol"], "tol", 1e-13, 1e-1) if tol_given else self.DEFAULT_TOL
        if o["n_p"] is not None:
            o["n_p"] = check_int(o["n_p"], "n_p", 8, 1000)
        if o["V0_fraction"] is not None:
            o["V0_fraction"] = check_float(o["V0_fraction"], "V0_fraction", 0.0, 0.1)
        if o["k_domain"] is not None:
            o["k_domain"] = check_float(o["k_domain"], "k_domain", 0.0, 100.0)
            if o["k_domain"] < 5.0:
                raise ValueError(
                    f"k_domain must lie in [5, 100], got {o['k_domain']!r}: the far wall would absorb load"
                )
        if pr.moving_wall:  # front-fixed, on the Magnus march (persson_fp.solvers.chebyshev.wall)
            check_wall_problem(pr, o)
            self.path = "moving-wall"
            return
        if pr.fudge.name != "none":
            raise ValueError(
                f"method 'chebyshev' solves fudge-free problems (B2 = b(p) dV/dzeta), got fudge={pr.fudge.name!r}; "
                "use method='sines', 'fv' or 'mol'"
            )
        self._sigma = pr.upper_wall.strip_sigma()  # (the fixed yield wall's sigma_Y; None without one)
        self._cf = cf = Coefficients(self.problem)
        if o["march"] not in (None, *MARCHES):
            raise ValueError(f"march must be None (choose), 'radau' or 'magnus' (force that march), got {o['march']!r}")
        self.path = o["march"] or ("exponential" if cf.separable else "clock" if cf.clock else "radau")
        if self.path in MARCHES and not tol_given:
            o["tol"] = self.MARCH_DEFAULT_TOL[self.path]

    # -- the solve ------------------------------------------------------------------------------------
    def _domain(self, tol, V):
        """(p_max, k) for the PDF at V: k widths sqrt(V) beyond the largest load in the Lamperti distance
        (of the largest b over zeta); sigma_Y with a hardness."""
        pr = self.problem
        k = self.opts["k_domain"] or float(np.clip(math.sqrt(2.0 * math.log(1.0 / (1e-3 * tol))) + 1.0, 8.0, 12.0))
        if self._sigma is not None:
            return self._sigma, k

        def b(p):
            return self._cf.envelope(p)[0]

        pbar = float(np.max(pr.p_bar))
        need = k * math.sqrt(V)
        push = 0.0  # the drift's push outwards, in the Lamperti distance
        if self._cf.drift:  # a drift moves the PDF by about c V: widen by the largest push outwards
            probe = np.linspace(0.0, pr.p_max(2.0 * k), 65)
            bb, cc = self._cf.envelope(probe)
            with np.errstate(over="ignore", invalid="ignore"):
                push = max(0.0, float(np.max(cc / np.sqrt(np.maximum(bb, 1e-300))))) * V
            need += push
        b_at = b(np.asarray(pr.p_bar, dtype=float))
        if not np.all(b_at > 1e-300):  # (no spreading from the load: the domain rule below would only run away)
            raise ValueError(
                "method 'chebyshev': B2 vanishes at the load p_bar (the start cannot spread); use method='fv' or 'mol'"
            )
        width = math.sqrt(float(np.min(b_at)) * V)
        if width < 1e-8 * float(np.min(pr.p_bar)):
            raise ValueError(
                f"method 'chebyshev': B2 is so small at the load that the PDF stays a spike of width sqrt(B2 V / "
                f"(dV/dzeta)) = {width:.3g} (below 1e-8 p_bar): no polynomial grid resolves it, and the contact area "
                "is 1 to within its tails; check the units of B2 (pressure^2 per unit zeta)"
            )
        hi = pbar + math.sqrt(float(b(np.array([pbar]))[0]) * V) * k
        for _ in range(80):
            if float(collocation.lamperti_distance(b, np.array(pbar), np.array(hi))) >= need:
                return hi, k
            hi = pbar + 1.5 * (hi - pbar)
        if not push <= k * math.sqrt(V):  # the drift, not the diffusion, sets the far wall (NaN and inf included)
            raise ValueError(
                "method 'chebyshev': B1 (the drift) is so large that it pushes the pressure outwards by about "
                f"max(B1 / sqrt(B2 dV/dzeta)) V = {push:.3g} in the Lamperti distance int dp / sqrt(B2 / "
                f"(dV/dzeta)) by V = {V:.3g}, beyond any far wall the domain rule reaches (the diffusion's own "
                f"width is {k:.3g} sqrt(V) = {k * math.sqrt(V):.3g}); the answer depends on the far wall -- check "
                "the size and units of B1 (pressure per unit zeta)"
            )
        raise ValueError(
            "method 'chebyshev': B2 grows so fast in p (faster than p^2) that the pressure reaches any far wall in "
            f"finite V: int dp / sqrt(B2 / (dV/dzeta)) from p_bar to infinity is below {need:.3g} (k_domain = "
            f"{k:.3g} widths sqrt(V)); the answer depends on the far wall -- bound B2 at large p"
        )

    def _run(self, n, frac, p_max, tol_t):
        """P at the stations: (grids, one per station, P (n_zeta, n_loads, n + 1)).

        Every station k starts afresh from the delta: the small-time start at V0_k = frac x V_k on a grid whose
        nodes cluster for that start (within a few widths sqrt(b V0_k) of p_bar), then one exponential (or a
        Magnus march) to V_k.  An early station does not make a later one start narrow: the nodes crowded for a
        narrow start would carry its stiff operator's round-off to the far stations (measured: 5e-10 at zeta_max
        after a station at zeta = 2), and passing a state between grids carries the start's undamped high modes.
        Also sets ``_far`` (mass out at p_max: A_pl with a hardness), ``_balance``, ``_time_err`` and ``_stats``.
        """
        cf, pb = self._cf, self.problem.p_bar.astype(float)
        grids, out = [], None
        shape = (self.V_out.size, pb.size)
        far, balance, t_err, law = np.zeros(shape), np.zeros(shape), np.zeros(shape), np.zeros(shape)
        unresolved, roundoff = np.zeros(shape), np.zeros(shape)
        stats = {"steps": 0, "rejected": 0, "expm": 0}
        floor = 4.0 * np.finfo(float).eps * n * n
        path = self.path
        for k, V in enumerate(self.V_out):
            V0, V_start, t0, b_at, grid = self._start_grid(n, frac, float(p_max[k]), float(V))
            if np.any(b_at <= 0):
                raise ValueError("method 'chebyshev': B2 vanishes at the load p_bar (the start cannot spread)")
            wall = None if self._sigma is None else np.full(pb.shape, self._sigma)
            P = collocation.start_density(lambda q, Vs=V_start: cf.at(q, Vs), grid.p, pb, t0, p_wall=wall)
            P[:, 0] = P[:, -1] = 0.0
            mass0 = np.sum(P * grid.w, axis=-1)
            load0 = np.sum(P * grid.w * grid.p, axis=-1)
            # does the grid resolve the start?  Its quadrature against 96-point Gauss--Legendre over +-12 widths
            lo = np.maximum(pb - 12.0 * np.sqrt(b_at * t0), 0.0)
            hi = np.minimum(pb + 12.0 * np.sqrt(b_at * t0), p_max[k])
            q = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * _GL96[0]
            Pq = collocation.start_density(lambda x, Vs=V_start: cf.at(x, Vs), q, pb, t0, p_wall=wall)
            mass_ref = 0.5 * (hi - lo) * (Pq @ _GL96[1])
            unresolved[k] = np.abs(mass0 - mass_ref)
            # and is the start itself sound?  Its mass against the drift-free images' (exact for constant b, c = 0)
            s0 = np.sqrt(b_at * t0)
            m_img = ndtr(pb / s0) - ndtr(-pb / s0)  # in [0, inf): the delta less its image across p = 0
            if wall is not None:  # in [0, sigma_Y]: less the mass above the wall and the image across it there
                d = wall - pb
                m_img = m_img - (ndtr((wall + pb) / s0) - ndtr(d / s0)) - (ndtr(-d / s0) - ndtr(-(wall + d) / s0))
            if not np.all(np.abs(mass_ref - m_img) <= 0.05):
                raise ValueError(
                    "method 'chebyshev': the small-time start at V0 is not valid here (its mass "
                    f"{float(np.min(mass_ref)):.3g} where about {float(np.min(m_img)):.3g} is due: the drift per unit "
                    "V is too strong across the start's width, or overflows); use method='fv' or 'mol'"
                )
            if path not in MARCHES:
                b_n, c_n = cf.at(grid.p)
                L = collocation.generator(grid, b_n, c_n)
                span = float(V) - V0 if path == "exponential" else cf.tau(V0, float(V))
                P[:, 1:-1], I = collocation.propagate_with_integral(L, P[:, 1:-1], span)
                roundoff[k] = collocation.roundoff_floor(L, span, n)
                out0, out_far = collocation.wall_losses(grid, b_n, c_n, I)
                moment = 0.0 if c_n is None else np.sum((grid.w * c_n)[:, 1:-1] * I, axis=-1)
            else:
                m = n - 1

                ops = collocation.WallRowOperators(grid)

                def A_of(Vq, grid=grid, ops=ops):
                    return ops([cf.at(grid.p, Vq)])[0]

                def many(Vs, grid=grid, ops=ops):  # (the Radau march's stages: one inversion zeta(V) for all)
                    return ops(cf.at_many(grid.p, Vs))

                A_of.many = many

                def norm(d, w=grid.w[:, 1:-1], m=m):
                    return np.sum(np.abs(d[:, :m]) * w, axis=-1) + np.abs(d[:, m]) + np.abs(d[:, m + 1])

                y0 = np.concatenate([P[:, 1:-1], np.zeros((pb.size, 3))], axis=1)
                try:
                    if path == "radau":  # (the general march and its forecast: chebyshev/radau.py)
                        y, t_err[k], st = self._radau(k, A_of, y0, V0, float(V), tol_t, norm, floor, n)
                    else:
                        y, t_err[k], st = magnus_march(
                            A_of, y0, V0, float(V), tol_t, norm, floor, deadline=self._deadline
                        )
                except TimeoutError as err:
                    self._out_of_time(str(err))
                except RuntimeError as err:
                    from persson_fp.results.invariants import SolverError

                    reach = getattr(err, "reachable", None)  # (the march's tol that fits in its steps)
                    hint = "" if reach is None else f" to about {reach * self.opts['tol'] / tol_t:.1e}"
                    raise SolverError(
                        f"chebyshev: {err} at degree {n}; loosen tol{hint}, pass a larger max_time or use method='fv'"
                    ) from None
                for key in st:
                    stats[key] = stats.get(key, 0) + st[key]
                roundoff[k] = collocation.roundoff_floor(
                    np.maximum(np.abs(A_of(V0)), np.abs(A_of(float(V)))), V - V0, n
                )
                P[:, 1:-1], out0, out_far, moment = y[:, :m], y[:, m], y[:, m + 1], y[:, m + 2]
            far[k] = np.maximum(out_far, 0.0)
            # the first-moment law: the load the solution must carry (with a hardness: elastic + sigma_Y A_pl)
            law[k] = load0 + moment - (0.0 if self._sigma is not None else p_max[k] * out_far)
            if wall is not None:  # what the wall absorbed before V0 (the start lacks it: all of it for a load at
                # the wall), from the start's image across it: 2 Phi(-y_w / sqrt(t0)), y_w the Lamperti distance
                y_w = collocation.lamperti_distance(lambda q, Vs=V_start: cf.at(q, Vs)[0], pb, wall)
                early = 2.0 * ndtr(-y_w / math.sqrt(t0))
                far[k] += early
                law[k] += self._sigma * early
            balance[k] = mass0 - np.sum(P * grid.w, axis=-1) - out0 - out_far  # what left = what crossed a wall
            if out is None:
                out = np.zeros((self.V_out.size,) + P.shape)
            out[k] = P
            grids.append(grid)
        self._far, self._balance, self._time_err, self._stats, self._law = far, balance, t_err, stats, law
        self._unresolved, self._roundoff = unresolved, roundoff
        return grids, out

    def _stats_of(self, grids, P, far):
        """(A_el, load F_el, A_pl) per station and load (A_pl = mass out at sigma_Y with a hardness, else 0)."""
        A = np.stack([np.sum(P[k] * g.w, axis=-1) for k, g in enumerate(grids)])
        F = np.stack([np.sum(P[k] * g.w * g.p, axis=-1) for k, g in enumerate(grids)])
        return A, F, (far if self._sigma is not None else np.zeros_like(A))

    def _compare(self, main, other):
        """(L1 of the difference, |dA_el|, |dF| / p_bar, |dA_pl|, |dA_non|) per station and load."""
        (g, P, far), (g2, P2, far2) = main, other
        L1 = np.stack(
            [
                np.sum(np.abs(P[k] - collocation.interpolate(g2[k], P2[k], g[k].p)) * g[k].w, axis=-1)
                for k in range(len(g))
            ]
        )
        A, F, Apl = self._stats_of(g, P, far)
        A2, F2, Apl2 = self._stats_of(g2, P2, far2)
        return L1, np.abs(A - A2), np.abs(F - F2) / self.problem.p_bar, np.abs(Apl - Apl2), np.abs(A + Apl - A2 - Apl2)

    def _three_runs(self, n, frac, p_max, tol_t):
        """The run and its two partners (3/4 degree, start at 4 V0); ``_stats`` of the run, ``_all`` of the three."""
        self._replay, self._nodes = None, {}
        main = (*self._run(n, frac, p_max, tol_t), self._far)
        self._replay = self._nodes  # (the partners replay the main run's Radau steps)
        far, balance, t_err, stats, law = self._far, self._balance, self._time_err, self._stats, self._law
        unresolved, roundoff = self._unresolved, self._roundoff
        all_stats = dict(stats)
        grid_part = (*self._run(max(8, int(round(0.75 * n))), frac, p_max, tol_t), self._far)
        all_stats = {key: all_stats[key] + self._stats.get(key, 0) for key in all_stats}
        start_part = (*self._run(n, 4.0 * frac, p_max, tol_t), self._far)
        self._replay = None
        self._all = {key: all_stats[key] + self._stats.get(key, 0) for key in all_stats}
        self._law_spread = np.abs(law - self._law)
        self._far, self._balance, self._time_err, self._stats, self._law = far, balance, t_err, stats, law
        self._unresolved, self._roundoff = unresolved, roundoff
        return main, grid_part, start_part

    def _start_grid(self, n, frac, p_max, V):
        """(V0, V_start, t0, b at the loads, grid) of the station at V: the start at V0 = frac V -- in V (separable),
        in the clock tau(V0) (clock), with the coefficients of mid-[0, V0] (Magnus) -- and the grid whose nodes
        cluster within a few of its widths sqrt(b t0) of each load (None where b vanishes at a load)."""
        cf, pb = self._cf, self.problem.p_bar.astype(float)
        V0 = frac * V
        V_start, t0 = (None, V0) if self.path == "exponential" else (0.5 * V0, V0)
        if self.path == "clock":
            V_start, t0 = None, cf.tau(0.0, V0)
        b_at = cf.at(pb, V_start)[0]
        if not np.all(b_at > 0):
            return V0, V_start, t0, b_at, None
        eps = 3.0 * np.sqrt(b_at * t0)
        # the cluster no closer to a wall than its width: a load within a few start widths of a wall (a hardness
        # just above p_bar) starts as the images' difference, smooth on that width, and a cluster on the wall,
        # on top of the Chebyshev ends' own, would shrink the closest spacing ~n-fold (and blow up ||L||)
        centre = np.clip(pb, np.minimum(eps, 0.5 * p_max), np.maximum(p_max - eps, 0.5 * p_max))
        grid = collocation.chebyshev_grid(n, p_max, centre, eps)
        return V0, V_start, t0, b_at, grid

    def _floor_at(self, n, frac, p_max):
        """The largest round-off floor (:func:`collocation.roundoff_floor`, not below 4 eps n^2) a run at degree n and
        start fraction ``frac`` would report, over stations and loads -- from the operators alone, before any run
        (milliseconds: the grids and generators of :meth:`_run` without their exponentials or march)."""
        cf, worst = self._cf, 4.0 * np.finfo(float).eps * n * n
        for k, V in enumerate(self.V_out):
            V0, _, _, b_at, grid = self._start_grid(n, frac, float(p_max[k]), float(V))
            if np.any(b_at <= 0):
                return worst  # (the run names it)
            if self.path not in MARCHES:
                span = float(V) - V0 if self.path == "exponential" else cf.tau(V0, float(V))
                L = collocation.generator(grid, *cf.at(grid.p))
            else:
                span = float(V) - V0
                L = np.maximum(*(np.abs(collocation.generator(grid, *cf.at(grid.p, Vq))) for Vq in (V0, float(V))))
            worst = max(worst, float(np.max(collocation.roundoff_floor(L, span, n))))
        return worst

    def _start_of(self, tol):
        """(first degree, start fraction) of the adaptive loop for ``tol``."""
        frac = self.opts["V0_fraction"] or float(np.clip(0.3 * math.sqrt(tol), 3e-5, 1e-2))
        return int(np.clip(8 + 8 * math.log10(1.0 / tol), 24, N_MAX)), frac

    def _unreachable(self, tol, n, floor, best, p_max):
        """The SolverError of a tol below the round-off floor, naming the floor and the best reachable accuracy: the
        smallest tol (half-decade steps) whose floor at 1.5x its first degree is below half of it -- the loop
        typically ends at 1.2-1.7x its first degree (measured on the drift, clock and homogenised cases)."""
        from persson_fp.results.invariants import SolverError

        reach = tol
        while reach < 0.1:
            reach *= math.sqrt(10.0)
            n1, frac1 = self._start_of(reach)
            if self._floor_at(min(int(1.5 * n1), N_MAX), frac1, p_max) <= 0.5 * reach:
                break
        done = "" if best is None else f"; the best estimate reached is {best:.2e}"
        raise SolverError(
            f"chebyshev: tol = {tol:.3g} is below what the dense exponential can reach here: its round-off floor at "
            f"degree {n} is {floor:.2e} (it grows ~n^6 with the degree; a coarser degree leaves a larger "
            f"discretisation error){done}; the best reachable accuracy is about {reach:.1e} -- loosen tol to it or "
            "use method='fv'"
        ) from None

    @staticmethod
    def _refuse_fixed_degree(n: int, tol: float, worst: float) -> None:
        """The :class:`~persson_fp.SolverError` of a fixed ``n_p`` whose error estimate ``worst`` exceeds ``tol``."""
        if worst > tol:
            from persson_fp.results.invariants import SolverError

            raise SolverError(
                f"chebyshev: n_p = {n} cannot meet tol = {tol:.3g}: the error estimate at that fixed degree "
                f"is {worst:.2e}; leave n_p out (the degree then adapts to tol), raise it, or leave tol out"
            )

    def check_degree_memory(self, n: int) -> None:
        """A ``ValueError`` if a run at degree ``n`` would exceed ``max_memory`` (``budget.check_degree_memory``)."""
        check_degree_memory(n, self.problem.n_loads, self.max_memory, self.path)

    def _out_of_time(self, where: str):
        out_of_time(getattr(self, "_budget", self.max_time), where)

    def _forecast_try(self, tries, now, worst: float, tol: float, runs: int) -> float:
        """Refuse before a refinement forecast over the time left, naming the forecast: the last try took
        ``tries[-1]["seconds"]`` at its (degree, march tol, start fraction); the next, at ``now``, costs that times
        the degree's growth squared (the operators, their LUs and the sweeps: between n^2 and n^3 at n = 40-120),
        the steps of the tighter march (tol^(-1/5): order 5) and of the longer span ln(1 / V0_fraction).  The
        forecast is kept in the next try's entry (``info["march"]["tries"]``), beside the seconds it took.  The
        refinement sizes each part of the estimate to its share of tol, but the degree's rate is a guess until two
        tries are in: such solves often take a third try, which this forecast does not see until the second is done.
        Returns the forecast (seconds)."""
        from persson_fp.results.invariants import SolverError

        last = tries[-1]
        n0, t0, f0 = last["n_p"], last["march_tol"], last["V0_fraction"]
        n1, t1, f1 = now
        steps = (t0 / t1) ** 0.2 * math.log(1.0 / f1) / math.log(1.0 / f0)
        need, left = last["seconds"] * (n1 / n0) ** 2 * steps, self._deadline - time.perf_counter()
        if need <= left:
            return need
        given = "max_time" if self._budget == self.max_time else f"the default budget of this path, {self._budget:g} s"
        reach = self._reach_in(last, now, left, steps, worst, tol)
        fits = f"a tol of about {reach:.1e} is forecast to fit -- loosen tol to it, " if reach < 0.1 else ""
        raise SolverError(
            f"chebyshev: after {runs} runs ({sum(t['seconds'] for t in tries):.3g} s) the error estimate is "
            f"{worst:.2e} over tol = {tol:.3g}; the next refinement (degree {n1}, march tol {t1:.2g}, V0 fraction "
            f"{f1:.2g}) is forecast to take ~{need:.3g} s, over the {max(left, 0.0):.3g} s left of {given} "
            f"({self._budget:.3g} s in all); {fits}pass a larger max_time (seconds) or use method='fv'"
        )

    def _reach_in(self, last, now, left: float, other: float, worst: float, tol: float) -> float:
        """The tol a refusal names: 1.5x the estimate forecast for the largest degree the time left affords (the
        last try's seconds times the degree's growth squared and ``other``, the growth of its steps), its grid part
        falling at the rate ``_refine`` used, the start and march parts as refined (V0^2 and the march tol);
        1.5x the estimate reached where no larger degree is affordable.  Never below 1.5 tol.  ``now``: the next try's
        (degree, march tol, start fraction)."""
        n0, parts = last["n_p"], last["parts"]
        n_aff = n0 * math.sqrt(max(left, 0.0) / max(last["seconds"] * other, 1e-9))
        if n_aff <= n0:
            return 1.5 * worst
        _, t1, f1 = now
        f0, t0 = last["V0_fraction"], last["march_tol"]
        forecast = (
            parts["grid"] * math.exp(-self._grid_rate * (n_aff - n0))
            + parts["start"] * (f1 / f0) ** 2
            + parts["time"] * t1 / t0
        )
        return 1.5 * min(max(forecast, tol), worst)

    def _refine(self, n, frac, tol_t, tol, grid, start, time_part):
        """The next (degree, start fraction, march tol) of the Radau path: every part of the estimate over its share
        of tol (a third each) is refined at once, by the rate it was measured to fall at -- the start's error as
        V0^2 (the fraction cut by sqrt(share / part), 4x to 16x), the degree's geometrically (at the rate between the
        last two degrees, else ``GRID_RATE_0``; 1.15x to 2x the degree), the march's as its tol -- instead of one
        part a try."""
        share = tol / 3.0
        prev = getattr(self, "_grid_seen", None)
        self._grid_seen = (n, grid)
        n_next = n
        rate = math.log(prev[1] / grid) / (n - prev[0]) if prev and prev[1] > grid and n > prev[0] else 0.0
        self._grid_rate = rate if rate > 0 else GRID_RATE_0
        if grid > share:
            need = n + math.log(grid / share) / self._grid_rate
            n_next = int(math.ceil(min(max(need, 1.15 * n), 2.0 * n)))
        if start > share and frac > 1e-6:
            frac *= float(np.clip(math.sqrt(share / start), 1.0 / 16.0, 0.25))
            n_next = max(n_next, int(math.ceil(1.15 * n)))  # (a narrower start needs a few more nodes)
        if time_part > share and tol_t > 1e-3 * tol:
            tol_t *= float(np.clip(share / time_part, 1.0 / 16.0, 0.25))
        if n_next == n and not (start > share or time_part > share):
            n_next = int(math.ceil(1.3 * n))  # (no part over its share but the sum over tol: the largest is the grid's)
        return n_next, frac, tol_t

    def _kinks(self) -> list:
        """The V where the spectrum's dV/dzeta has a kink (its roll-off zeta_r, where the derivative of dV/dzeta
        jumps): coefficients evaluated at zeta(V) are not smooth there, and a Radau step across it is first order
        while its step-doubling estimate stays blind -- measured on a shifted squared-Bessel problem (B2 =
        4 kappa V'(p + a(zeta))): a step over zeta_r = 2 left a true L1 of 3e-6 that the march never saw, 5e-7 at
        zeta_max against an estimate of 3e-8; stopping there, 5e-9."""
        if not hasattr(self, "_kink_V"):
            pr = self.problem
            zr = getattr(pr.psd, "zeta_r", None)
            self._kink_V = [float(pr.V(zr))] if zr is not None and 1.0 < zr < float(pr.zeta_max) else []
        return self._kink_V

    def _radau(self, k, A_of, y0, V0, V, tol_t, norm, floor, n):
        """The Radau march of station k (:func:`radau.radau_march`), stopping at the spectrum's kinks
        (:meth:`_kinks`; each piece held to its share of ``tol_t`` in ln V, a stage on a kink taking the operator of
        its own piece's side): a partner run replays the main run's steps; the main run's march is held to its share
        of the time left -- the stations still to go (each about as long: the same span ln(1 / V0_fraction) in ln V)
        and the two partners' replays (2 of the 3 solves of a step each) -- and refused at once if forecast over
        it."""
        points = [V0, *[b for b in self._kinks() if V0 * (1.0 + 1e-9) < b < V * (1.0 - 1e-9)], V]
        replaying = self._replay is not None
        nodes, record = (self._replay[k], None) if replaying else (None, [])
        runs = (self.V_out.size - k) * (1.0 + 4.0 / 3.0)  # (this march's cost is shared by ~this many)
        log_span = math.log(V / V0)
        y, est, stats = y0, 0.0, {}
        for a, b in zip(points[:-1], points[1:]):
            piece = (
                A_of if len(points) == 2 else one_sided(A_of, a if a != V0 else -math.inf, b if b != V else math.inf)
            )
            tol_piece = tol_t * math.log(b / a) / log_span
            # (past a kink the solution stays smooth -- only the coefficients' derivative jumps -- so the march
            # goes on at the step it had reached before it)
            h0 = None if a == V0 or not record or len(record) < 2 else record[-1] - record[-2]
            if replaying:
                replay = [v for v in nodes if a * (1.0 + 1e-12) < v <= b * (1.0 + 1e-12)]
                y, e, st = radau_march(piece, y, a, b, tol_piece, norm, floor, h0, self._deadline, nodes=replay)
            else:
                if record and record[-1] == a:  # (the march records its start again)
                    record.pop()
                share = (self._deadline - time.perf_counter()) / runs * math.log(b / a) / math.log(V / a)
                forecast_from = 0.0 if a == V0 else a * max(FORECAST_AFTER_BREAK, (b / a) ** 0.1)
                try:
                    y, e, st = radau_march(
                        piece, y, a, b, tol_piece, norm, floor, h0, self._deadline, record=record, time_budget=share,
                        forecast_from=forecast_from,
                    )  # fmt: skip
                except MarchTooLong as err:
                    reach = err.reachable * tol_t / tol_piece  # (in the units of the whole march's tol)
                    if not math.isfinite(err.needed):
                        raise MarchTooLong(str(err), reach, err.needed) from None
                    given = (
                        "max_time"
                        if self._budget == self.max_time
                        else f"the default budget of this path, {self._budget:g} s"
                    )
                    raise MarchTooLong(
                        f"{err}: the solve at tol = {self.opts['tol']:.3g} would take about {err.needed * runs:.3g} s "
                        f"more, over its budget ({given}: {self._budget:.3g} s in all)",
                        reach,
                        err.needed,
                    ) from None
            est = est + e
            for key, val in st.items():
                stats[key] = stats.get(key, 0) + val
        if record is not None:
            self._nodes[k] = record
        return y, est, stats

    def _solve(self) -> SolverOutput:
        o, pr = self.opts, self.problem
        if self.path == "moving-wall":  # (chosen in validate)
            budget, whose = self.max_time, "max_time"
            if self.max_time == TIME_BUDGET and o["march"] != "magnus":  # (the march's default budget)
                budget, whose = MARCH_TIME_BUDGET, f"the default budget of this path, {MARCH_TIME_BUDGET:g} s"
            out = solve_moving_wall(pr, o, self.zeta_out, self.V_out, budget, self.max_memory, whose)
            if o["n_p"] is not None and self._tol_given:  # a fixed degree is not raised: refused over tol
                est = out.info["error_estimate"]
                worst = max(float(np.max(est[q])) for q in ("L1", "elastic_area", "plastic_area", "noncontact_area"))
                self._refuse_fixed_degree(o["n_p"], o["tol"], worst)
            return out
        tol = o["tol"]
        shareable = self.path not in MARCHES and o["n_p"] is None and o["V0_fraction"] is None
        if shareable and pr.n_loads >= SHARED_MIN_LOADS:
            out = solve_shared(self, tol)  # loads on one grid share its modes (None: the grid cannot serve them)
            if out is not None:
                return out
        doms = []
        for V in self.V_out:  # a far wall per station (a loop, not a comprehension: one frame less below it)
            doms.append(self._domain(tol, float(V)))
        p_max, k = np.array([d[0] for d in doms]), doms[0][1]
        n, frac = self._start_of(tol)
        if self.path == "radau":  # (a march costs more than a degree: start where the loop usually ends)
            n = min(int(math.ceil(1.3 * n)), N_MAX)
        n = o["n_p"] or n
        tol_t = TIME_SHARE * tol
        runs, hard = 0, self._sigma is not None
        total = {"steps": 0, "rejected": 0, "expm": 0}
        self._budget = self.max_time  # (the general march's default budget: MARCH_TIME_BUDGET)
        if self.path == "radau" and self.max_time == TIME_BUDGET:
            self._budget = MARCH_TIME_BUDGET
        self._deadline = time.perf_counter() + self._budget
        self._grid_seen = None
        best = None  # the smallest worst estimate so far (tol runs)
        tries, forecast = [], None  # (what each try of the loop ran and took; on a march, its forecast)
        if o["n_p"] is None and (f0 := self._floor_at(n, frac, p_max)) > tol:  # refused before any run
            self._unreachable(tol, n, f0, None, p_max)
        while True:
            if time.perf_counter() > self._deadline:
                self._out_of_time(f"{runs} runs done, degree {n}")
            self.check_degree_memory(n)
            t_try = time.perf_counter()
            main, grid_part, start_part = self._three_runs(n, frac, p_max, tol_t)
            took = time.perf_counter() - t_try
            tries.append({"n_p": n, "V0_fraction": frac, "march_tol": tol_t, "seconds": took, "forecast_s": forecast})
            runs += 3
            far, balance, t_err = self._far, self._balance, self._time_err
            for key in self._all:
                total[key] = total.get(key, 0) + self._all[key]
            L1_g, dA_g, dF_g, dP_g, dN_g = self._compare(main, grid_part)
            L1_s, dA_s, dF_s, dP_s, dN_s = self._compare(main, start_part)
            A, F, A_pl = self._stats_of(*main)
            far_err = np.zeros_like(far) if hard else 2.0 * far
            # round-off of the dense exponential: its backward error eps ||L dV|| (collocation.roundoff_floor), not
            # below 4 eps n^2 (the quadrature of P at a small degree)
            floor = np.maximum(4.0 * np.finfo(float).eps * n * n, self._roundoff)
            common = far_err + floor + t_err + self._unresolved  # (the start's quadrature error: an L1 contraction
            # carries it to every station; partners that all miss a spike agree with each other)
            est = {
                "L1": L1_g + L1_s / 4.0 + common,
                "contact_area": dA_g + dA_s / 4.0 + common,
                "plastic_area": (dP_g + dP_s / 4.0 + floor + t_err) if hard else np.zeros_like(A),
                "noncontact_area": dN_g + dN_s / 4.0 + common,
                # (relative to p_bar; the round-off of P far out is weighted by p there: measured 1.5e-10 at
                # p_max = 160 p_bar, n = 157)
                "load": dF_g + dF_s / 4.0 + (common + floor * np.maximum(1.0, 0.1 * p_max[:, None] / pr.p_bar)),
            }
            # |A_el - A_el_ref| <= int |P - P_ref| dp: the L1 estimate bounds the area's error as well (the partners'
            # area differences alone missed it 6x at a coarse fixed degree: n_p = 24 with a strong drift)
            est["contact_area"] = np.maximum(est["contact_area"], est["L1"])
            est["noncontact_area"] = np.maximum(est["noncontact_area"], est["L1"] + est["plastic_area"])
            worst = max(float(np.max(est[q])) for q in ("L1", "contact_area", "plastic_area", "noncontact_area"))
            # (more nodes resolve the start: its quadrature error counts as the grid's)
            grid_worst = max(float(np.max(v)) for v in (L1_g, dA_g, dP_g, dN_g, self._unresolved))
            start_worst = max(float(np.max(v)) for v in (L1_s, dA_s, dP_s, dN_s)) / 4.0
            time_worst = float(np.max(t_err))
            tries[-1].update(estimate=worst, parts={"grid": grid_worst, "start": start_worst, "time": time_worst})
            if o["n_p"] is not None or worst <= tol:
                if o["n_p"] is not None and self._tol_given:  # a fixed degree is not raised
                    self._refuse_fixed_degree(n, tol, worst)
                break
            if best is not None and worst > best and float(np.max(floor)) >= 0.3 * worst:
                self._unreachable(tol, n, float(np.max(floor)), best, p_max)  # a higher degree raised the error
            best = worst if best is None else min(best, worst)
            if self.path == "radau":  # (each try is a march: refine every part that is over, by its measured rate)
                n, frac, tol_t = self._refine(n, frac, tol_t, tol, grid_worst, start_worst, time_worst)
                forecast = self._forecast_try(tries, (n, tol_t, frac), worst, tol, runs)
            elif time_worst > max(grid_worst, start_worst) and tol_t > 1e-3 * tol:
                tol_t /= 4.0
            elif start_worst > grid_worst and frac > 1e-6:
                frac /= 4.0
                n = int(math.ceil(1.15 * n))  # a narrower start needs a few more nodes
            else:
                n = int(math.ceil(1.3 * n))
            if n > N_MAX:
                from persson_fp.results.invariants import SolverError

                raise SolverError(
                    f"chebyshev: the error estimate {worst:.3e} exceeds tol = {tol:.3g} at degree {N_MAX}; "
                    f"the best reachable accuracy is about {best:.1e}: loosen tol or use method='fv'"
                )
            if (f_next := self._floor_at(n, frac, p_max)) > tol:  # the next run cannot meet tol: refuse now
                self._unreachable(tol, n, f_next, best, p_max)
        grids, P, _ = main
        info = {
            "path": self.path,
            "grid": {
                "n_p": n,
                "p_max": p_max,
                "k_domain": None if hard else k,
                "mapping": "p = centre + eps sinh(a1 + h (x + 1)), x Chebyshev, per load",
            },
            "V0_fraction": frac,
            "zeta0": self.zeta_from_V(frac * self.V_out),
            "runs": runs,
            "error_estimate": estimate_entry(
                est,
                "|run - run at 3/4 degree| + |run - run from 4 V0| / 4 + 2 x far-wall mass "
                "+ max(4 eps n^2, eps ||L dV||_1 (n/400)^2) "
                "+ the start's quadrature error on the grid"
                + (" + |march - companion march at double steps|" if self.path == "magnus" else "")
                + (" + the Radau march's propagated local estimates (step doubling)" if self.path == "radau" else ""),
                {"time": t_err, "roundoff": floor},
            ),
            "far_wall_mass": np.zeros_like(far) if hard else far,
            # d/dV int p P dp = int c P dp - p_max J(p_max), integrated alongside (checked by the invariants): the
            # catch for a result whose partners agree on something wrong (e.g. a PDF the grid cannot follow)
            "load_law": self._law,
            "load_law_tolerance": est["load"] * pr.p_bar + self._law_spread,
            "mass_balance_residual": float(np.max(np.abs(balance))),
        }
        if self.path in MARCHES:
            info["march"] = {**self._stats, "tol": tol_t, "all_runs": total, "tries": tries}
        Pout, p, w, extra = self._output(grids, P, p_max, n)
        info["grid"].update(extra)
        # the polynomial's ripple where P is ~0 (tails, next to the walls) is within the estimate: set to 0
        Pout, info["ripple_zeroed"] = collocation.zero_ripple(Pout)
        return SolverOutput(
            p=p,
            P0=Pout,
            weights=w,
            kind="point",
            info=info,
            contact_area=A,
            load=F,
            plastic_area=A_pl if hard else None,
        )

    def _output(self, grids, P, p_max, n):
        """P0 on one output grid: (P0 (n_zeta, n_loads, m), p, weights, grid info)."""
        pr = self.problem
        if pr.n_loads == 1:  # the last station's grid (the widest domain), earlier stations' polynomials on it
            # (at the nodes: spectrally accurate values, 0 beyond their far wall; A* and the load come from each
            # station's own grid)
            g0 = grids[-1]
            Pout = np.stack([P[k] if g is g0 else collocation.interpolate(g, P[k], g0.p) for k, g in enumerate(grids)])
            return Pout, g0.p[0], g0.w[0], {"centre": g0._map[2], "eps": g0._map[3]}
        # a common output grid: plain Chebyshev of twice the degree (areas and loads from the own grids)
        pm = float(p_max[-1])
        common = collocation.chebyshev_grid(2 * n, pm, np.array([0.5 * pm]), np.array([1e6 * pm]))
        p, w = common.p[0], common.w[0]
        q = np.broadcast_to(p, (pr.n_loads, p.size))
        Pout = np.stack([collocation.interpolate(grids[kk], P[kk], q) for kk in range(P.shape[0])])
        return Pout, p, w, {}
