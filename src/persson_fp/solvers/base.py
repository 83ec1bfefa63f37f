"""Base class of the numerical solvers: options, output stations, timing, checks.

A method subclasses :class:`Solver`, declares its own options with defaults in
``OPTIONS`` and writes only :meth:`Solver._solve`, which returns a
:class:`SolverOutput`.  :meth:`Solver.run` owns validation, timing and the
assembly of the :class:`~persson_fp.results.solution.Solution` (where the invariants
are checked once).  Cf. scipy's ``OdeSolver.step``/``_step_impl``.

Shared resolution knobs: ``n_p``, ``n_steps``, ``rtol``, ``atol``,
``scheme``, ``zeta_out``; a shared knob a method does not use draws a warning,
a misspelt one a ``TypeError``, an out-of-range value a ``ValueError``.
"""

from __future__ import annotations

import difflib
import functools
import math
import time
import warnings

import numpy as np

from persson_fp._validate import as_float_array
from persson_fp.analysis.exact import exact
from persson_fp.problems.contact import ContactProblem
from persson_fp.results.output import SolverOutput
from persson_fp.results.solution import DEFAULT_TOLERANCES, InstabilityError, Solution
from persson_fp.solvers.options import K_DOMAIN_MIN, check_bool, check_float, check_int, check_k_domain

__all__ = [
    "Solver",
    "SolverOutput",
    "StationRecorder",
    "zeta_of",
    "SHARED_KNOBS",
    "check_int",
    "check_float",
    "check_bool",
    "check_k_domain",
    "MIN_SIGMA_CELLS",
    "K_DOMAIN_MIN",
    "LOAD_RATIO_RANGE",
    "MEMORY_BUDGET",
    "MEMORY_MODELS",
    "TIME_BUDGET",
    "TIME_MODELS",
]

SHARED_KNOBS = ("n_p", "n_steps", "rtol", "atol", "scheme", "zeta_out")
"""Resolution knobs every method accepts (and warns about when it ignores one)."""


LOAD_RATIO_RANGE = {
    "fv": (1e-10, np.inf),
    "chapman-kolmogorov": (1e-10, np.inf),
}
"""Loads p_bar / sqrt(tau(zeta_max)) where a method keeps its relative accuracy (others are refused).

Below 1e-10 the cell averages of the finite-volume and Chapman--Kolmogorov methods lose the load to
round-off (measured: 7e-4 relative A* error at 1e-14, 93 % at 1e-20); 'sines' and pf.exact are exact
there.  Large loads are refused by the grid-resolution checks with the same hint."""

FEATURES = {
    "hardness": "a hardness wall",
    "moving_wall": "a scale-dependent hardness (moving yield wall)",
    "general": "general Fokker-Planck coefficients",
}
"""What a problem may need beyond the homogenised elastic one (``ContactProblem.features``), in words: a method
lists those it solves in its ``SUPPORTS``."""

_SUPPORTERS: list = []
"""The hint-maker set by the registry of methods (``persson_fp.solvers.registry``): feature -> method names."""


def supporters_hint(feature: str) -> str:
    """'use method=...' naming the methods of the registry (quoted, each with its condition) whose ``SUPPORTS`` hold
    ``feature``."""
    names = _SUPPORTERS[0](feature) if _SUPPORTERS else []
    if not names:
        return "no method solves it"
    return "use method=" + (names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1])


def load_handlers(problem) -> str:
    """Which methods handle a load that another method refuses: the closed forms where the problem has one,
    else chebyshev (the spectral method, accurate at any load)."""
    return _LOAD_HANDLERS_OF[problem.features - {"hardness"}]  # (keyed by what the closed forms do not cover)


LOAD_HANDLERS = "method 'sines' (p_bar / sqrt(tau) up to about 2e3) or the closed form pf.exact (any load) handle it"
_LOAD_HANDLERS_OF = {
    frozenset(): LOAD_HANDLERS,
    frozenset({"moving_wall"}): "method 'chebyshev' handles it without a fudge factor",
    frozenset({"general"}): "method 'chebyshev' handles it (general coefficients)",
    frozenset({"general", "moving_wall"}): "method 'chebyshev' handles it (general coefficients)",
}
"""The hint of a refused load, by what the problem needs beyond the closed forms (``features`` less a constant
hardness)."""

MEMORY_BUDGET = 4 * 2**30
"""Default ``max_memory`` (bytes) of a solve: 4 GiB.  Override per call, ``pf.solve(..., max_memory=...)``."""


def _larger_plus_half(a, b):
    return max(a, b) + 0.5 * min(a, b)


MEMORY_MODELS = {
    # (options, n_loads, n_stations, with_fudge) -> bytes, fitted to tracemalloc peaks (reference problem)
    # fv: 85 MB at n_p = 2e4, 100 steps; 1.67 GB at 2000 steps (the trajectory of one load is kept); 83 / 134 MB
    # at (n_p, n_steps) = (2000, 1000) / (8000, 400), 1 and 10 loads -- the model 1.2-1.5x those.  The front-fixed
    # engine (a moving wall or general coefficients, no trajectory; whole pf.solve calls, benchmarks/
    # memory_estimates.py): cells ~600 B a load, steps ~950 B whatever the loads, and on general coefficients a
    # ~1 MB set-up (sizing the domain from B1, B2).  Moving wall: 0.42 / 1.61 / 6.36 MB at n_p = n_steps = 400 /
    # 1600 / 6400, 3.10 / 2.05 / 4.08 / 8.13 MB at (400, 3200) / (3200, 400) / (6400, 800) / (12800, 400); 10 loads
    # 2.31 / 1.58 / 9.12 MB at (400, 400) / (200, 1600) / (1600, 200).  General: 1.15 MB at (200, 100), 1.16 / 2.49 /
    # 10.8 MB and 3.75 / 2.64 / 5.23 / 9.48 MB at the same; 10 loads 2.31 / 1.96 MB at (400, 400) / (200, 1600).
    # The model 1.1-1.9x those.  General: a sum of the parts.  Moving wall: the larger part plus half the smaller
    # (the cells' and the steps' peaks partly coincide: the sum was 1.7x at n_p = n_steps and its traced peak
    # moved by ~20 % between runs at 400 x 400, to 2.1x)
    "fv": lambda o, nl, nz, f: (
        (300.0 + 500.0 * nl) * o["n_p"] + 1000.0 * o["n_steps"] + 1e6
        if o.get("front_fixed") and o.get("general")
        else _larger_plus_half((60.0 + 650.0 * nl) * o["n_p"], 1000.0 * o["n_steps"]) + 5e4
        if o.get("front_fixed")
        else 48.0 * o["n_p"] * (o["n_steps"] + 10) + 160.0 * o["n_p"] * nl
    ),
    # mol: ~600 B per point and load of a chunk (<= 250 loads), + dense blocks in zeta (benchmarks/mol_memory.py)
    "mol": lambda o, nl, nz, f: (
        600.0 * o["n_p"] * min(nl, 250) + 65536.0 + 24.0 * o["n_p"] ** 2 * nl * (f and o.get("variable") == "zeta")
    ),
    # Chapman--Kolmogorov: 22 MB at n_p = 2e4 (banded kernel)
    "chapman-kolmogorov": lambda o, nl, nz, f: 1e3 * o["n_p"] * nl + 8.0 * o["n_p"] * nl * nz,
    # Monte Carlo: histograms (4 arrays per station and load), one chunk of temporaries, all walkers with S(A*)
    "monte-carlo": lambda o, nl, nz, f: (
        32.0 * o["n_p"] * nl * nz
        + 64.0 * min(o["chunk_size"], o["n_walkers"] * nl)
        + (16.0 * o["n_walkers"] * nl if f else 0.0)
    ),
}
"""Peak-memory estimates (bytes) per method, checked before anything is allocated (:meth:`Solver.check_memory`)."""

TIME_BUDGET = 3600.0
"""Default ``max_time`` (seconds) of a solve.  Override per call, ``pf.solve(..., max_time=...)``."""

TIME_MODELS = {
    # seconds, from single-core timings of the reference problem (order of magnitude: they bound runaway
    # requests such as n_walkers = 1e9, not the ordinary ones)
    "fv": lambda o, nl, nz, f: 1.2e-7 * o["n_p"] * (o["n_steps"] + 10) * (1.0 + nl / 8.0),
    "chapman-kolmogorov": lambda o, nl, nz, f: 3.5e-6 * o["n_p"] * (o["n_steps"] + nz) * nl,
    "monte-carlo": lambda o, nl, nz, f: 1.6e-7 * o["n_walkers"] * nl * (o["n_steps"] + nz),
}
"""Run-time estimates (seconds) per method, checked with the memory (:meth:`Solver.check_memory`)."""

MIN_SIGMA_CELLS = 1.0
"""A cell method refuses a first station with sqrt(tau) < MIN_SIGMA_CELLS * dp (the PDF would be narrower
than a cell); the start-up is placed at sqrt(tau0) >= 2 dp where the first station allows it."""


_IGNORED_RANGES = {
    "rtol": lambda v, k: check_float(v, k, 0.0, 1.0),
    "atol": lambda v, k: check_float(v, k, 0.0, lo_open=False),
    "n_p": lambda v, k: check_int(v, k, 1),
    "n_steps": lambda v, k: check_int(v, k, 1),
}
"""The ranges of the shared knobs, checked even where a method ignores the knob (``atol=-1`` is wrong anywhere)."""


def zeta_of(problem, V) -> np.ndarray:
    """Magnifications where V(zeta) = ``V`` (pressure^2, finite: a solver's own values), as a 1-D array: 1 where
    V <= 0, zeta_max beyond V(zeta_max).  The spectrum's closed-form inverse, unchecked
    (:meth:`persson_fp.PSD.zeta_of_V_unchecked`)."""
    return np.atleast_1d(problem.V_kernels.zeta_of_V(np.atleast_1d(np.asarray(V, dtype=float))))


class StationRecorder:
    """What a march holds as it passes the output stations: one recorder for every stepping method.

    ``steps[i]`` is the step after which station i is reached (non-decreasing; stations may share a step);
    ``shapes`` names each recorded quantity and its shape at one station (e.g. ``P0=(n_loads, n_p)``).
    :meth:`record` after step n stores the given values at every station reached then; ``recorder[name]`` is the
    array (n_stations, *shape).

    Examples
    --------
    >>> rec = StationRecorder([2, 5, 5], area=(1,))
    >>> for n in range(1, 6):
    ...     rec.record(n, area=[float(n)])
    >>> rec["area"][:, 0].tolist()
    [2.0, 5.0, 5.0]
    """

    def __init__(self, steps, **shapes):
        self.steps = np.asarray(steps, dtype=int)
        self._at: dict[int, list[int]] = {}
        for i, n in enumerate(self.steps.tolist()):
            self._at.setdefault(n, []).append(i)
        self.values = {name: np.empty((self.steps.size, *shape)) for name, shape in shapes.items()}

    def __contains__(self, n: int) -> bool:
        """Whether a station is reached after step ``n``."""
        return n in self._at

    def record(self, n: int, load: int | None = None, **values) -> None:
        """After step ``n``: store each value at every station reached then (nothing where none is).  ``load``
        indexes the first axis of the shape (a method that marches one load at a time passes its index)."""
        for i in self._at.get(n, ()):
            at = i if load is None else (i, load)
            for name, v in values.items():
                self.values[name][at] = v

    def __getitem__(self, name: str) -> np.ndarray:
        return self.values[name]


class Solver:
    """A numerical method for ``E:diffusion_equ`` / ``eq:new_B2`` with absorbing walls.

    Parameters
    ----------
    problem : ContactProblem
    zeta_out : float or array, optional
        Output stations in (1, zeta_max], sorted; default ``[zeta_max]``.
    **options
        The method's own options (see its ``OPTIONS``) and the shared knobs.
    """

    name: str = "base"
    SUPPORTS: frozenset = frozenset()
    """Which problems beyond the homogenised elastic one the method solves: "hardness" (a constant yield wall),
    "moving_wall" (a scale-dependent hardness), "general" (Fokker-Planck coefficients B1, B2)."""
    OPTIONS: dict = {}
    """Options of the method with their defaults (shared knobs it uses included)."""

    def __init__(
        self, problem: ContactProblem, zeta_out=None, *, check=True, max_memory=None, max_time=None, **options
    ):
        if not isinstance(problem, ContactProblem):
            raise ValueError(f"problem must be a ContactProblem, got {type(problem).__name__}")
        self.problem = problem
        missing = problem.features - self.SUPPORTS
        if missing:
            need = min(missing)
            raise ValueError(f"method {self.name!r} does not solve {FEATURES[need]}; {supporters_hint(need)}")
        self.check = check if check is True or check is False else check_bool(check, "check")
        self.max_memory, self.max_time = check_budgets(max_memory, max_time)
        known = self.OPTIONS.keys()
        for key in list(options):  # (none given: nothing to look up)
            if key in known:
                continue
            if key in SHARED_KNOBS:
                _IGNORED_RANGES.get(key, lambda v, k: v)(options[key], key)  # out of range: an error all the same
                warnings.warn(f"method {self.name!r} ignores the option {key!r}", UserWarning, stacklevel=3)
                options.pop(key)
                continue
            close = difflib.get_close_matches(key, sorted(known | set(SHARED_KNOBS)), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise TypeError(f"method {self.name!r} got an unknown option {key!r}{hint}; it takes {sorted(known)}")
        self.opts = {**self.OPTIONS, **options}
        self.given = frozenset(options)
        """The options passed to this call (the others are the class defaults of ``OPTIONS``, valid as they are)."""
        self.zeta_out = self._check_zeta_out(zeta_out)
        self.validate()
        self.check_load_range()
        self.check_memory()

    # -- to be written by a method ------------------------------------------------------------
    def validate(self) -> None:
        """Check ``self.opts`` (raise ``ValueError`` naming the option and its range)."""

    def memory_options(self) -> dict:
        """What the method's memory model needs beyond its options (e.g. which engine runs); none by default."""
        return {}

    def _solve(self) -> SolverOutput:  # pragma: no cover - abstract
        raise NotImplementedError

    def invariant_tolerances(self) -> dict:
        """Tolerances of the invariant check (:func:`persson_fp.results.solution.check_invariants`) for this run.

        Tied to the requested accuracy: the defaults (``persson_fp.results.solution.DEFAULT_TOLERANCES``:
        load drift 1e-2, A* growth 1e-6 relative), loosened to 100 x ``rtol`` (load) and 10 x ``rtol``
        (A*) for a method run at a looser tolerance than that.
        """
        o = self.opts
        r = max(float(o.get("rtol") or 0.0), float(o.get("tol") or 0.0))
        start = getattr(self, "_start_load_error", None)
        if start is None and 100.0 * r <= DEFAULT_TOLERANCES["load"] and 10.0 * r <= DEFAULT_TOLERANCES["area"]:
            return DEFAULT_TOLERANCES  # the defaults themselves (check_invariants reads them, never writes)
        tol = dict(DEFAULT_TOLERANCES)
        tol["load"] = max(tol["load"], 100.0 * r)
        tol["area"] = max(tol["area"], 10.0 * r)
        if start is not None:  # a one-cell delta carries the load of its cell centre from the start
            tol["load"] = tol["load"] + start
        return tol

    def check_load_range(self, range_of: str | None = None) -> None:
        """Refuse loads outside the method's range of relative accuracy (:data:`LOAD_RATIO_RANGE`; ``range_of``:
        another method's range, e.g. ``"fv"``'s for mol on the engine, whose start is fv's cell averages).

        The ratio is p_bar / sqrt(tau(zeta_max)) (tau = V without a fudge factor); the message names
        the methods that handle the load.
        """
        lo, hi = LOAD_RATIO_RANGE.get(range_of or self.name, (0.0, np.inf))
        if lo <= 0.0 and hi == np.inf:  # no range: every positive load is in it (and nothing to compute)
            return
        pr = self.problem
        scale = pr.upper_wall.tau_scale(pr)  # (V_max for a moving wall: no exact tau there with S)
        ratio = pr.p_bar / np.sqrt(scale)
        for bad, side in ((ratio < lo, f"below {lo:g}"), (ratio > hi, f"above {hi:g}")):
            if np.any(bad):
                r = float(ratio[bad][0])
                raise ValueError(
                    f"{self.name}: the load p_bar / sqrt(tau(zeta_max)) = {r:.3g} is {side}, where this method "
                    f"loses its relative accuracy; {load_handlers(pr)}"
                )

    def check_memory(self, n_p=None) -> None:
        """Refuse a run whose estimated peak memory (:data:`MEMORY_MODELS`) exceeds ``max_memory``
        (default :data:`MEMORY_BUDGET`), with a ``ValueError`` that states the estimate.

        ``n_p``: the grid size where the method fixes it only later (mol's automatic grid).
        """
        args = self._model_args(n_p)
        if args is None:  # (a method without a memory model, or a grid not fixed yet: nothing to estimate)
            return
        need = float(MEMORY_MODELS[self.name](*args))
        secs = float(TIME_MODELS[self.name](*args)) if self.name in TIME_MODELS else 0.0
        if secs > self.max_time:
            raise ValueError(
                f"{self.name}: this run would take about {secs:.3g} s (estimate), more than max_time = "
                f"{self.max_time:.3g} s; use a coarser grid (n_p, n_steps), fewer loads or walkers (n_walkers), "
                "or pass a larger max_time (seconds)"
            )
        if need > self.max_memory:
            raise ValueError(
                f"{self.name}: this run would need about {need / 2**30:.3g} GiB of memory (estimate), more than "
                f"max_memory = {self.max_memory / 2**30:.3g} GiB; use a coarser grid (n_p, n_steps), fewer loads or "
                "walkers (n_walkers), or pass a larger max_memory (bytes) if the machine has it"
            )

    def _model_args(self, n_p=None):
        """The arguments (options, n_loads, n_stations, with_fudge) of this method's :data:`MEMORY_MODELS` entry, or
        None where it has none or the grid is not fixed yet (``n_p``: as in :meth:`check_memory`)."""
        if self.name not in MEMORY_MODELS:
            return None
        o = dict(self.opts)
        if n_p is not None:
            o["n_p"] = n_p
        if o.get("n_p", 0) is None:
            return None
        o.update(self.memory_options())
        return o, self.problem.n_loads, self.zeta_out.size, self.problem.fudge.name != "none"

    def memory_estimate(self, n_p=None) -> float | None:
        """The estimated peak memory (bytes) that :meth:`check_memory` holds against ``max_memory``; None where
        the method has no model or its grid is not fixed yet."""
        args = self._model_args(n_p)
        return None if args is None else float(MEMORY_MODELS[self.name](*args))

    # -- shared machinery ------------------------------------------------------------------------
    @functools.cached_property
    def V_out(self) -> np.ndarray:
        """V at the output stations (pressure^2), shape (n_zeta_out,), computed once."""
        pr = self.problem
        if self.zeta_out.size == 1 and self.zeta_out[0] == pr.zeta_max:
            V = np.array([pr.V_max])  # the cached value (the default station)
        else:
            V = np.atleast_1d(pr.V(self.zeta_out)).astype(float)
        V.setflags(write=False)
        return V

    @functools.cached_property
    def tau_out(self) -> np.ndarray:
        """Exact tau at the output stations (pressure^2), shape (n_zeta_out, n_loads), computed once."""
        pr = self.problem
        if self.zeta_out.size == 1 and self.zeta_out[0] == pr.zeta_max:
            t = pr.tau_max[None, :].copy()
        else:
            t = np.asarray(pr.tau_of_V(self.V_out), dtype=float)
        t.setflags(write=False)
        return t

    def validate_start_options(self) -> None:
        """Check the start-up and domain options a cell method shares (present ones only):
        ``tau0_fraction`` in (0, 1], ``k_domain`` in (0, 100], ``zeta0`` in [1, first station],
        ``allow_unstable`` a real bool.  ``k_domain`` below :data:`K_DOMAIN_MIN` is refused: the far wall
        would absorb a visible part of the load (82 % of it at k_domain = 1)."""
        o = self.opts
        if o.get("tau0_fraction") is not None:
            o["tau0_fraction"] = check_float(o["tau0_fraction"], "tau0_fraction", 0.0, 1.0)
        if "k_domain" in o:
            o["k_domain"] = check_k_domain(o["k_domain"])
        if "allow_unstable" in o:
            o["allow_unstable"] = check_bool(o["allow_unstable"], "allow_unstable")
        if o.get("zeta0") is not None:
            check_float(o["zeta0"], "zeta0", 1.0, float(self.zeta_out[0]))

    def cell_grid(self, n_p: int):
        """Uniform cells on [0, p_max], p_max = ``problem.p_max(opts["k_domain"])``: (edges (n_p + 1,), dp)."""
        p_max = self.problem.p_max(self.opts["k_domain"])
        return np.linspace(0.0, p_max, n_p + 1), p_max / n_p

    def uniform_V_nodes(self, V_start: float, n_steps: int):
        """Step ends uniform in V within each station interval (every station a node), and station indices.

        Steps per interval are proportional to its V length (at least one).
        """
        bounds = np.concatenate(([V_start], self.V_out))
        total = bounds[-1] - bounds[0]
        nodes, stations = [V_start], []
        for a, c in zip(bounds[:-1], bounds[1:]):
            m = max(1, int(round(n_steps * (c - a) / total)))
            seg = a + (c - a) * np.arange(1, m + 1) / m
            seg[-1] = c
            nodes.extend(seg.tolist())
            stations.append(len(nodes) - 1)
        return np.array(nodes), stations

    def _check_zeta_out(self, zeta_out) -> np.ndarray:
        return check_zeta_out(self.problem, zeta_out)

    def zeta_from_V(self, V_target) -> np.ndarray:
        """Magnification at which V reaches ``V_target`` (1 where V <= 0, zeta_max beyond V(zeta_max)).

        The spectrum's closed-form inverse (:meth:`persson_fp.surfaces.psd.PSD.zeta_of_V`), vectorised.
        """
        return zeta_of(self.problem, V_target)

    def start_zeta(self, zeta0=None, tau0_fraction=None, dp=None) -> float:
        """Start-up magnification zeta0 of an ``initial="exact"`` run.

        ``zeta0`` if given (in [1, first station]); else where tau is ``tau0_fraction`` x tau(zeta_max)
        for the load with the largest tau -- but at most half of that load's tau at the first output
        station, so that the start always lies before it, and, on a grid of spacing ``dp``, not below
        tau = 2 dp^2 where that station allows it (an unresolved start would spoil every later station).
        tau(V) is inverted by :meth:`~persson_fp.ContactProblem.V_of_tau_each` (to ~1e-12).
        """
        pr = self.problem
        if zeta0 is not None:
            return check_float(zeta0, "zeta0", 1.0, float(self.zeta_out[0]))
        frac = check_float(tau0_fraction, "tau0_fraction", 0.0, 1.0)
        V_max = pr.V_max
        tt = np.stack([pr.tau_max, self.tau_out[0]])  # (2, n_loads)
        j = int(np.argmax(tt[0]))
        target = min(frac * float(tt[0, j]), 0.5 * float(tt[1, j]))
        if dp is not None:
            target = max(target, min(2.0 * dp**2, 0.5 * float(tt[1, j])))
        V0 = float(pr.V_of_tau_each(np.full(pr.n_loads, target))[j])  # the exact inverse (tau = V without S)
        return float(self.zeta_from_V(min(max(V0, 0.0), V_max))[0])

    def check_resolved(self, dp: float, what: str = "n_p") -> None:
        """Raise ``ValueError`` unless the first output station is resolved on a grid of spacing ``dp``.

        sqrt(tau(first station)) must be >= MIN_SIGMA_CELLS * dp for the smallest-tau load; the
        message names the ``n_p`` that would resolve it (or suggests a later first station).
        """
        tau_first = float(np.min(self.tau_out[0]))
        need = MIN_SIGMA_CELLS * dp
        if np.sqrt(tau_first) < need:
            grow = need / np.sqrt(tau_first)
            raise ValueError(
                f"{self.name}: the first output station zeta = {self.zeta_out[0]:.6g} is not resolved by the grid "
                f"(sqrt(tau) = {np.sqrt(tau_first):.3e} < {MIN_SIGMA_CELLS:g} cells of {dp:.3e}); "
                f"raise {what} by a factor >= {grow:.3g} or start zeta_out later; {LOAD_HANDLERS}"
            )

    def initial_cell_averages(self, edges):
        """Start of a cell-average method on the grid ``edges``: ``(zeta0, V0, P, A)``.

        ``initial="exact"`` (``self.opts``): the exact cell averages at :meth:`start_zeta`
        (P shape ``(n_loads, n_p)``, A* per load).  ``initial="delta"``: one cell of mass 1 at
        p_bar at zeta = 1 (the discrete delta of the stability study).
        """
        o, pr = self.opts, self.problem
        edges = np.asarray(edges, dtype=float)
        dp = np.diff(edges)
        n_p = dp.size
        if o["initial"] == "delta":
            P = np.zeros((pr.n_loads, n_p))
            idx = np.minimum(np.searchsorted(edges, pr.p_bar, side="right") - 1, n_p - 1)
            P[np.arange(pr.n_loads), idx] = 1.0 / dp[idx]
            centre = 0.5 * (edges[idx] + edges[idx + 1])
            self._start_load_error = np.abs(centre - pr.p_bar) / pr.p_bar  # the cell's load, not p_bar
            return 1.0, 0.0, P, np.ones(pr.n_loads)
        self.check_resolved(float(np.max(dp)))
        z0 = self.start_zeta(o["zeta0"], o["tau0_fraction"], dp=float(np.max(dp)))
        ex = exact(self.problem, np.atleast_1d(z0))
        F = np.asarray(ex.cdf_contact(edges)).reshape(pr.n_loads, -1)
        P = np.ascontiguousarray(np.diff(F, axis=-1) / dp)
        A = np.asarray(ex.contact_area, dtype=float).reshape(pr.n_loads)
        return z0, float(np.ravel(ex.V)[0]), P, A

    def exact_at(self, zeta):
        """The exact solution of the problem at ``zeta`` (for start-up data and references)."""
        return exact(self.problem, np.atleast_1d(zeta))

    @staticmethod
    def check_state(P, mass, mass_prev, zeta, name, remedy="reduce the step or use an implicit scheme"):
        """Raise :class:`InstabilityError` on NaN, negative mass or mass growth (per load).

        Growth is judged with the invariant checks' area tolerance (``DEFAULT_TOLERANCES["area"]``, relative): an
        unstable march grows far past it at once; a load with ~1 cell per sqrt(tau) can gain 1e-8 without being so."""
        if not np.all(np.isfinite(P)):
            raise InstabilityError(f"{name}: non-finite values at zeta = {zeta:.6g}; {remedy}")
        if np.any(mass < -1e-12):
            raise InstabilityError(f"{name}: negative contact area {mass.min():.3e} at zeta = {zeta:.6g}; {remedy}")
        if mass_prev is not None and np.any(mass > mass_prev * (1 + DEFAULT_TOLERANCES["area"]) + 1e-12):
            raise InstabilityError(
                f"{name}: contact area grows ({np.max(mass - mass_prev):.3e}) at zeta = {zeta:.6g} -- "
                "the discrete evolution is unstable, or oscillates so that a negative wall cell returns mass "
                f"(contact can only be lost, eq:Area); {remedy}"
            )

    def run(self) -> Solution:
        """Solve, time it, and return a :class:`Solution` whose invariants are checked
        (:class:`~persson_fp.SolverError` on a breach, a warning with ``check=False``)."""
        t0 = time.perf_counter()
        out = self._solve()
        wall = time.perf_counter() - t0
        out.info = {"method": self.name, "options": dict(self.opts), **out.info}
        wall = out.info.pop("solve_time", wall)
        return Solution.from_output(
            self.problem,
            out,
            method=self.name,
            zeta=self.zeta_out,
            wall_time=wall,
            check=self.check,
            tolerances=self.invariant_tolerances(),
        )


def check_zeta_out(problem, zeta_out) -> np.ndarray:
    """The output stations as a strictly increasing 1-D array in (1, zeta_max] (default: [zeta_max]), or a
    ``ValueError`` naming ``zeta_out`` and the range."""
    zmax = problem.zeta_max
    if zeta_out is None:
        return np.array([zmax])
    z = as_float_array(zeta_out, "zeta_out")
    if z.ndim > 1:
        raise ValueError(f"zeta_out must be a scalar or a 1-D array, got shape {z.shape}")
    z = np.atleast_1d(z)
    if z.size == 0:
        raise ValueError("zeta_out must hold at least one station")
    if np.any(z <= 1.0) or np.any(z > zmax * (1 + 1e-12)):
        raise ValueError(f"zeta_out must lie in (1, zeta_max] = (1, {zmax:.6g}], got {z.min():.6g}..{z.max():.6g}")
    if np.any(np.diff(z) <= 0):
        raise ValueError("zeta_out must be strictly increasing")
    return np.minimum(z, zmax)


def check_budgets(max_memory, max_time) -> tuple[float, float]:
    """(max_memory in bytes, max_time in seconds): the defaults for None, ``inf`` for no limit, else a positive
    float -- or a ``ValueError`` naming the budget and its range (0, inf]."""
    out = []
    for value, name, default in ((max_memory, "max_memory", MEMORY_BUDGET), (max_time, "max_time", TIME_BUDGET)):
        if value is None:
            out.append(default)
        elif _is_inf(value):
            out.append(math.inf)
        else:
            out.append(check_float(value, name, 0.0))
    return out[0], out[1]


def _is_inf(value) -> bool:
    try:
        return not isinstance(value, (bool, np.bool_, str)) and float(value) == math.inf
    except (TypeError, ValueError):
        return False
