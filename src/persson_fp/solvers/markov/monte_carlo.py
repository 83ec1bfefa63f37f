r"""Monte Carlo solver: random walks in p, absorbed at p = 0 with no re-entry.

Each walker is one location of the interface; its pressure performs the
Markov process behind ``E:CK_forward``.  Walkers start at p_bar at zeta = 1 and
take Gaussian steps of variance :math:`\Delta\tau = S(A^*)\,\Delta V` (i.e.
:math:`B_2\,\Delta\zeta`, ``eq:new_B2``); a walker that reaches p <= 0 is out of
contact for good (``eq:No_reentry``).  The contact area is the surviving
fraction, P0 a histogram.

Absorption
----------
With ``bridge=True`` (default) a walker that is positive at both ends of a
step is still absorbed with the probability that the Brownian bridge between
them crossed zero, :math:`\exp(-2 p_k p_{k+1}/\Delta\tau)`.  Without a fudge
factor the walk is then an *exact* sample of killed Brownian motion at the
step ends, for any step size: A* is unbiased even with one step.
``bridge=False`` only checks the end points and misses excursions below
zero inside a step: A* is biased high by :math:`O(\sqrt{\Delta\tau})` (the
0.5826 sqrt(dt) boundary shift of discretely monitored Brownian motion),
kept for the bias demonstration.

Fudge-factor coupling and chunking
----------------------------------
S depends on the surviving fraction of the *whole* population, so all
walkers are advanced in lock-step: in step k every chunk takes the same
:math:`\Delta\tau_k` (per load), computed from the whole population.  Within a
step, A*(tau) is replaced by its exact conditional expectation given the walkers' positions at
the start of the step, :math:`N^{-1}\sum_i \mathrm{erf}(p_i/\sqrt{2(\tau-\tau_k)})`
(survival of killed Brownian motion; positions binned into 2048 bins of
[0, p_max]; for the first step every walker is at p_bar), and
:math:`\int_0^{\Delta\tau} d\tau/S(A^*) = \Delta V_k` is solved as in the
Chapman--Kolmogorov solver (Gauss quadrature + Newton).  The coupling thus
adds no step-size error of its own -- only the statistical error of the
positions, O(1/sqrt(N)) -- so coarse steps are fine.  Memory is the state of
the surviving walkers (8 bytes each, plus 8 for the load index when there are
several loads) plus temporaries of one chunk (~40 bytes per walker of ``chunk_size``).  Without a fudge factor
:math:`\Delta\tau_k = \Delta V_k` is known in advance and each chunk is run
through all steps on its own (memory: one chunk).  No exact tau is used.

Statistics
----------
Standard errors are those of means of independent walkers:
:math:`\mathrm{se}(A^*) = \sqrt{A^*(1-A^*)/N}`, and for the load and the second
moment (atom included) the sample standard deviation of
:math:`p\,\mathbb 1_{\rm alive}` (resp. :math:`p^2 \mathbb 1_{\rm alive}`) over
:math:`\sqrt N`, given in ``info["moments"]``.  With a fudge factor the
walkers interact weakly through S(A*), which adds an :math:`O(1/N)` bias.
"""

from __future__ import annotations

import numpy as np

from persson_fp.solvers.base import Solver, SolverOutput, check_float, check_int
from persson_fp.solvers.markov.chapman_kolmogorov import ChapmanKolmogorovSolver, _cell_erfc
from persson_fp.theory import fudge as _fudge
from persson_fp.theory.image import area_from_tau

__all__ = ["MonteCarloSolver"]


def _area_from_delta(p_bar):
    """A*(tau) of walkers that all sit at p_bar at tau = 0: erf(p_bar / sqrt(2 tau))."""

    def area(tau):
        return area_from_tau(p_bar, tau)

    return area


_COUPLING_BINS = 2048
"""Bins of the walker-position histogram used by the fudge-factor coupling."""


def _area_from_walkers(occ, edges, tau_k):
    r"""Expected surviving fraction at tau > tau_k given the walkers at tau_k (binned, fraction per bin).

    :math:`E[A^*(\tau_k+t)\,|\,\{p_i\}] = N^{-1}\sum_i \mathrm{erf}(p_i/\sqrt{2t})` (the survival
    probability of killed Brownian motion), each walker spread uniformly over its bin
    of ``_COUPLING_BINS`` on [0, p_max] (those above p_max sit in the last bin, where
    erf = 1 anyway).
    """

    def area(tau):
        t = np.maximum(tau - tau_k, 1e-300)
        return np.sum(occ * (1.0 - _cell_erfc(edges, t)), axis=-1)

    return area


class MonteCarloSolver(Solver):
    r"""Random walks with absorption at p = 0 (see the module docstring).

    Options
    -------
    n_walkers : int, default 100_000
        Walkers per load (>= 1).
    n_steps : int, default 32
        Steps in zeta, uniform in V(zeta), split so that every output station
        is a step end (count taken: ``info["steps"]``).
    n_p : int, default 200
        Histogram bins on ``[0, p_max]`` (>= 1).
    k_domain : float, default 8
        ``p_max = max(p_bar) + k_domain sqrt(tau(zeta_max))`` (> 0); walkers
        above it count in A* and the moments but not in the histogram
        (``info["above_p_max"]``).
    seed : None, int, SeedSequence or numpy Generator
        Seed of the random streams (one child stream per chunk, spawned from
        it); the same seed, ``n_walkers``, ``chunk_size`` and ``n_steps`` give
        the same result.  ``info["seed_entropy"]`` records the entropy used
        when an int or None was given.
    tol : None
        Not supported: the error is statistical (a ``ValueError`` says so; set ``n_walkers``).
    bridge : bool, default True
        Brownian-bridge crossing correction (False: plain absorption, biased).
    chunk_size : int, default 2**20
        Walkers processed at a time (bounds the temporaries).

    Returns a cell-kind :class:`~persson_fp.Solution` whose ``contact_area`` is
    the surviving fraction, with ``stderr_area`` and ``info["stderr_P0"]``
    (1/pressure), ``info["moments"]`` (load, second moment and their standard
    errors, pressure and pressure^2), ``info["tau"]``.
    """

    name = "monte-carlo"
    OPTIONS = {
        "n_walkers": 100_000,
        "n_steps": 32,
        "n_p": 200,
        "k_domain": 8.0,
        "seed": None,
        "bridge": True,
        "chunk_size": 2**20,
        "tol": None,
    }

    def validate(self) -> None:
        o = self.opts
        o["n_walkers"] = check_int(o["n_walkers"], "n_walkers", 1)
        o["n_steps"] = check_int(o["n_steps"], "n_steps", 1)
        o["n_p"] = check_int(o["n_p"], "n_p", 1)
        o["k_domain"] = check_float(o["k_domain"], "k_domain", 0.0, 100.0)
        o["chunk_size"] = check_int(o["chunk_size"], "chunk_size", 1)
        if not isinstance(o["bridge"], (bool, np.bool_)):
            raise ValueError(f"bridge must be True or False, got {o['bridge']!r}")
        if o["tol"] is not None:
            raise ValueError(
                f"monte-carlo has no tolerance control (tol = {o['tol']!r}): its error is statistical, the standard "
                "error of the area falls as 1 / sqrt(n_walkers) (Solution.stderr_area); set n_walkers, or use "
                "method='auto' (or 'fv' / 'mol') with tol"
            )
        seed = o["seed"]
        ok = seed is None or isinstance(seed, (np.random.Generator, np.random.SeedSequence))
        if not ok and not isinstance(seed, (bool, np.bool_, str, bytes, float)):  # True is not a seed
            try:
                ok = int(seed) == seed and int(seed) >= 0
            except (TypeError, ValueError, OverflowError):
                ok = False
        if not ok:
            raise ValueError(f"seed must be None, an integer >= 0, a SeedSequence or a numpy Generator, got {seed!r}")
        self._load_tol = 1e-3  # _solve replaces it by 6 standard errors of the load

    def _step_nodes(self):
        """V at the step ends (uniform in V within each station interval, from V = 0) and the station indices."""
        return self.uniform_V_nodes(0.0, self.opts["n_steps"])

    @staticmethod
    def _advance(p, li, dtau, rng, bridge):
        """One step of the walkers (p, load index li) with per-load variance dtau; returns survivors."""
        var = dtau[0] if li is None else dtau[li]
        q = p + np.sqrt(var) * rng.standard_normal(p.size)
        alive = q > 0.0
        if bridge:
            u = rng.random(p.size)
            with np.errstate(under="ignore"):
                alive &= u >= np.exp(-2.0 * p * np.maximum(q, 0.0) / var)
        return q[alive], (None if li is None else li[alive])

    def _solve(self) -> SolverOutput:
        o = self.opts
        pr = self.problem
        pb = pr.p_bar
        L = pb.size
        N = o["n_walkers"]
        n_p = o["n_p"]
        fud = pr.fudge
        const_S = isinstance(fud, _fudge.NoFudge)
        edges, h = self.cell_grid(n_p)
        p_max = edges[-1]
        nodes, stations = self._step_nodes()
        dVs = np.diff(nodes)
        n_st = len(stations)
        st = dict(zip(stations, range(n_st)))
        S_vals = np.asarray(fud.S(np.linspace(0.0, 1.0, 2001)), float)
        S_lo, S_hi = float(S_vals.min()), float(S_vals.max())

        seed = o["seed"]
        info_seed = {}
        if seed is None or not isinstance(seed, (np.random.Generator, np.random.SeedSequence)):
            seed = np.random.SeedSequence(None if seed is None else int(seed))
            info_seed["seed_entropy"] = seed.entropy
        total = N * L
        C = o["chunk_size"]
        bounds = list(range(0, total, C)) + [total]
        n_chunks = len(bounds) - 1
        if isinstance(seed, np.random.Generator):
            rngs = seed.spawn(n_chunks)
        else:
            rngs = [np.random.default_rng(s) for s in seed.spawn(n_chunks)]

        # accumulators per station
        cnt = np.zeros((n_st, L))
        s1 = np.zeros((n_st, L))
        s2 = np.zeros((n_st, L))
        s4 = np.zeros((n_st, L))
        hist = np.zeros((n_st, L * n_p))
        above = np.zeros((n_st, L))

        def accumulate(i, p, li):
            if li is None:
                cnt[i, 0] += p.size
                s1[i, 0] += p.sum()
                p2 = p * p
                s2[i, 0] += p2.sum()
                s4[i, 0] += (p2 * p2).sum()
                b = np.minimum((p / h).astype(np.int64), n_p)
                hh = np.bincount(b, minlength=n_p + 1)
                hist[i] += hh[:n_p]
                above[i, 0] += hh[n_p]
                return
            p2 = p * p
            cnt[i] += np.bincount(li, minlength=L)
            s1[i] += np.bincount(li, weights=p, minlength=L)
            s2[i] += np.bincount(li, weights=p2, minlength=L)
            s4[i] += np.bincount(li, weights=p2 * p2, minlength=L)
            b = (p / h).astype(np.int64)
            inside = b < n_p
            above[i] += np.bincount(li[~inside], minlength=L)
            hist[i] += np.bincount(li[inside] * n_p + b[inside], minlength=L * n_p)

        def init(c):
            w = np.arange(bounds[c], bounds[c + 1])
            li = None if L == 1 else (w // N).astype(np.intp)
            p = np.full(w.size, pb[0]) if L == 1 else pb[li]
            return p, li

        tau = np.zeros(L)
        out_tau = np.empty((n_st, L))
        bridge = bool(o["bridge"])
        if const_S:
            dtaus = np.repeat(dVs[:, None], L, axis=1)
            for c in range(n_chunks):
                p, li = init(c)
                for k, dt in enumerate(dtaus, start=1):
                    p, li = self._advance(p, li, dt, rngs[c], bridge)
                    if k in st:
                        accumulate(st[k], p, li)
            out_tau[:] = np.cumsum(dtaus, axis=0)[np.array(stations) - 1]
        else:
            states = [init(c) for c in range(n_chunks)]
            nb = _COUPLING_BINS
            hb = p_max / nb
            cb_edges = hb * np.arange(nb + 1)
            V_span = nodes[-1]
            area = _area_from_delta(pb)  # step 1: every walker at p_bar
            for k, dV in enumerate(dVs, start=1):
                # Gauss panels of <= 1/16 of the V range (quadrature error ~1e-6, far below the noise)
                panels = 128 if k == 1 else int(np.ceil(16 * dV / V_span))
                dt = ChapmanKolmogorovSolver._solve_dtau(dV, tau, area, fud.S, S_lo, S_hi, panels)
                occ = np.zeros(L * nb)
                for c in range(n_chunks):
                    p, li = self._advance(*states[c], dt, rngs[c], bridge)
                    states[c] = (p, li)
                    b = np.minimum((p / hb).astype(np.int64), nb - 1)
                    occ += np.bincount(b if li is None else li * nb + b, minlength=L * nb)
                    if k in st:
                        accumulate(st[k], p, li)
                tau = tau + dt
                if k in st:
                    out_tau[st[k]] = tau
                area = _area_from_walkers(occ.reshape(L, nb) / N, cb_edges, tau.copy())
        A = cnt / N
        se_A = np.sqrt(A * (1.0 - A) / N)
        m1, m2, m4 = s1 / N, s2 / N, s4 / N
        denom = max(N - 1, 1)
        se_load = np.sqrt(np.maximum(m2 - m1**2, 0.0) / denom)
        self._load_tol = 6.0 * se_load / pb + 1e-12
        se_m2 = np.sqrt(np.maximum(m4 - m2**2, 0.0) / denom)
        counts = hist.reshape(n_st, L, n_p)
        P0 = counts / (N * h)
        se_P0 = np.sqrt(counts * np.maximum(1.0 - counts / N, 0.0)) / (N * h)
        info = {
            "edges": edges,
            "grid": {"n_p": n_p, "p_max": p_max, "h": h},
            "steps": int(dVs.size),
            "n_walkers": N,
            "chunks": n_chunks,
            "bridge": bridge,
            "tau": out_tau,
            "stderr_P0": se_P0,
            "above_p_max": above / N,
            "moments": {"load": m1, "stderr_load": se_load, "second_moment": m2, "stderr_second_moment": se_m2},
            "coupling": "none (S = 1): chunks run independently"
            if const_S
            else "lock-step over chunks; int dtau/S(E[A*|walkers]) = dV per step (Gauss + Newton)",
            **info_seed,
        }
        return SolverOutput(
            p=edges[:-1] + 0.5 * h,
            P0=P0,
            weights=np.full(n_p, h),
            kind="cell",
            info=info,
            contact_area=A,
            stderr_area=se_A,
            load=m1,
            stderr_load=se_load,
        )

    def invariant_tolerances(self) -> dict:
        """Statistical tolerances: the load (the walkers' mean pressure, unbiased: the killed walk is a
        martingale) within 6 standard errors; A* is a surviving fraction, in [0, 1] and non-increasing
        by construction; the histogram is non-negative."""
        return {**super().invariant_tolerances(), "load": self._load_tol}

    def check_load_range(self) -> None:
        """Refuse a load whose expected number of walkers in contact, n_walkers x A*(zeta_max), is below
        100: A* would have a relative standard error above 10 % (or be 0)."""
        pr = self.problem
        A = np.asarray(area_from_tau(pr.p_bar, pr.tau_max), dtype=float)
        N = self.opts["n_walkers"]
        j = int(np.argmin(A))
        if N * A[j] < 100.0 * (1.0 - A[j]):
            need = 100.0 * (1.0 - A[j]) / max(A[j], 1e-300)
            raise ValueError(
                f"monte-carlo: at p_bar = {pr.p_bar[j]:.6g} only n_walkers x A* = {N * A[j]:.3g} walkers are expected "
                f"to stay in contact (relative standard error of A* > 10 %); raise n_walkers to >= {need:.3g} or use "
                "method 'sines', 'fv' or the closed form pf.exact"
            )
