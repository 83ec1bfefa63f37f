"""Base class of the numerical solvers: options, output stations, timing, checks.

A method subclasses :class:`Solver`, declares its own options with defaults in
``OPTIONS`` and writes only :meth:`Solver._solve`, which returns a
:class:`SolverOutput`.  :meth:`Solver.run` owns validation, timing and the
assembly of the :class:`~persson_fp.solution.Solution` (where the invariants
are checked once).  Cf. scipy's ``OdeSolver.step``/``_step_impl``.

Shared resolution knobs (DESIGN §3): ``n_p``, ``n_steps``, ``rtol``, ``atol``,
``scheme``, ``zeta_out``; a shared knob a method does not use draws a warning,
a misspelt one a ``TypeError``, an out-of-range value a ``ValueError``.
"""

from __future__ import annotations

import difflib
import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from .._validate import as_float_array
from ..exact import exact
from ..problem import ContactProblem
from ..solution import InstabilityError, Solution

__all__ = ["Solver", "SolverOutput", "SHARED_KNOBS", "check_int", "check_float"]

SHARED_KNOBS = ("n_p", "n_steps", "rtol", "atol", "scheme", "zeta_out")
"""Resolution knobs every method accepts (and warns about when it ignores one)."""


def check_int(value, name: str, lo: int, hi: int | None = None) -> int:
    """An integer in [lo, hi] or a ``ValueError`` naming ``name`` and the range."""
    try:
        iv = int(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be an integer >= {lo}, got {value!r}") from None
    if iv != value or iv < lo or (hi is not None and iv > hi):
        rng = f"[{lo}, {hi}]" if hi is not None else f">= {lo}"
        raise ValueError(f"{name} must be an integer {rng}, got {value!r}")
    return iv


def check_float(value, name: str, lo: float, hi: float = np.inf, *, lo_open: bool = True) -> float:
    """A finite float in (lo, hi] (or [lo, hi]) or a ``ValueError`` naming ``name`` and the range."""
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    ok = np.isfinite(x) and (x > lo if lo_open else x >= lo) and x <= hi
    if not ok:
        br = "(" if lo_open else "["
        raise ValueError(f"{name} must lie in {br}{lo}, {hi}], got {value!r}")
    return x


@dataclass
class SolverOutput:
    """What a method's ``_solve`` hands back to :meth:`Solver.run`.

    P0 has shape ``(n_zeta_out, n_loads, n_p)``.  ``kind`` is "cell" for cell
    averages (give ``edges``) or "point" for point values.
    """

    p: np.ndarray
    P0: np.ndarray
    weights: np.ndarray
    kind: str
    info: dict = field(default_factory=dict)
    contact_area: np.ndarray | None = None
    contact_area_flux: np.ndarray | None = None
    stderr_area: np.ndarray | None = None


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
    OPTIONS: dict = {}
    """Options of the method with their defaults (shared knobs it uses included)."""

    def __init__(self, problem: ContactProblem, zeta_out=None, **options):
        if not isinstance(problem, ContactProblem):
            raise ValueError(f"problem must be a ContactProblem, got {type(problem).__name__}")
        self.problem = problem
        known = set(self.OPTIONS)
        for key in list(options):
            if key in known:
                continue
            if key in SHARED_KNOBS:
                warnings.warn(f"method {self.name!r} ignores the option {key!r}", UserWarning, stacklevel=3)
                options.pop(key)
                continue
            close = difflib.get_close_matches(key, sorted(known | set(SHARED_KNOBS)), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise TypeError(f"method {self.name!r} got an unknown option {key!r}{hint}; it takes {sorted(known)}")
        self.opts = {**self.OPTIONS, **options}
        self.zeta_out = self._check_zeta_out(zeta_out)
        self.validate()

    # -- to be written by a method ------------------------------------------------------------
    def validate(self) -> None:
        """Check ``self.opts`` (raise ``ValueError`` naming the option and its range)."""

    def _solve(self) -> SolverOutput:  # pragma: no cover - abstract
        raise NotImplementedError

    # -- shared machinery ------------------------------------------------------------------------
    def _check_zeta_out(self, zeta_out) -> np.ndarray:
        zmax = self.problem.zeta_max
        if zeta_out is None:
            return np.array([zmax])
        z = np.atleast_1d(as_float_array(zeta_out, "zeta_out")).ravel()
        if z.size == 0:
            raise ValueError("zeta_out must hold at least one station")
        if np.any(z <= 1.0) or np.any(z > zmax * (1 + 1e-12)):
            raise ValueError(f"zeta_out must lie in (1, zeta_max] = (1, {zmax:.6g}], got {z.min():.6g}..{z.max():.6g}")
        if np.any(np.diff(z) <= 0):
            raise ValueError("zeta_out must be strictly increasing")
        return np.minimum(z, zmax)

    def zeta_from_V(self, V_target) -> np.ndarray:
        """Magnification at which V reaches ``V_target`` (monotone root find on the spectrum)."""
        from scipy.optimize import brentq

        V_target = np.atleast_1d(np.asarray(V_target, float))
        out = np.empty_like(V_target)
        zmax = self.problem.zeta_max
        for i, vt in enumerate(V_target):
            out[i] = brentq(lambda z, vt=vt: float(self.problem.V(z)) - vt, 1.0, zmax, xtol=1e-14, rtol=1e-15)
        return out

    def start_zeta(self, zeta0=None, tau0_fraction=None) -> float:
        """Start-up magnification zeta0: given, or where tau = ``tau0_fraction`` * tau(zeta_max) (largest load)."""
        if zeta0 is not None:
            z0 = check_float(zeta0, "zeta0", 1.0, float(self.zeta_out[0]))
            return z0
        frac = check_float(tau0_fraction, "tau0_fraction", 0.0, 1.0)
        # tau is monotone in V; find V0 with tau(V0) = frac * tau(V_max) for the load with the largest tau
        V_max = float(self.problem.V())
        tau_max = self.problem.tau_of_V(V_max)
        j = int(np.argmax(tau_max))
        target = frac * tau_max[j]
        from scipy.optimize import brentq

        V0 = brentq(lambda v: float(self.problem.tau_of_V(v)[j]) - target, 0.0, V_max, xtol=1e-300, rtol=1e-15)
        z0 = float(self.zeta_from_V(V0)[0])
        if z0 >= self.zeta_out[0]:
            raise ValueError(
                f"the start-up zeta0 = {z0:.6g} (tau0_fraction = {frac}) is not below the first output station "
                f"{self.zeta_out[0]:.6g}; lower tau0_fraction"
            )
        return z0

    def exact_at(self, zeta):
        """The exact solution of the problem at ``zeta`` (for start-up data and references)."""
        return exact(self.problem, np.atleast_1d(zeta))

    @staticmethod
    def check_state(P, mass, mass_prev, zeta, name, remedy="reduce the step or use an implicit scheme"):
        """Raise :class:`InstabilityError` on NaN, negative mass or mass growth (per load)."""
        if not np.all(np.isfinite(P)):
            raise InstabilityError(f"{name}: non-finite values at zeta = {zeta:.6g}; {remedy}")
        if np.any(mass < -1e-12):
            raise InstabilityError(f"{name}: negative contact area {mass.min():.3e} at zeta = {zeta:.6g}; {remedy}")
        if mass_prev is not None and np.any(mass > mass_prev * (1 + 1e-8) + 1e-12):
            raise InstabilityError(
                f"{name}: contact area grows ({np.max(mass - mass_prev):.3e}) at zeta = {zeta:.6g} -- "
                f"the discrete evolution is unstable; {remedy}"
            )

    def run(self) -> Solution:
        """Solve, time it, and return a checked :class:`Solution`."""
        t0 = time.perf_counter()
        out = self._solve()
        wall = time.perf_counter() - t0
        info = {"method": self.name, "options": dict(self.opts), **out.info}
        wall = info.pop("solve_time", wall)
        return Solution.build(
            self.name,
            self.problem,
            self.zeta_out,
            out.p,
            out.P0,
            out.weights,
            out.kind,
            wall,
            info=info,
            contact_area=out.contact_area,
            contact_area_flux=out.contact_area_flux,
            stderr_area=out.stderr_area,
        )
