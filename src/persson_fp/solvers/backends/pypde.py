r"""Persson's diffusion equation driven through py-pde [1]_ (the generic tool a user might pick).

The method
----------
``E:diffusion_equ`` with the corrected coefficient ``eq:new_B2``,

.. math::  \frac{\partial P_0}{\partial\zeta} = \tfrac12 B_2\,\frac{\partial^2 P_0}{\partial p^2},
           \qquad B_2 = S(A^*)\,\frac{dV}{d\zeta}, \qquad A^* = \int_0^{p_{max}} P_0\,dp ,

is written as a py-pde ``PDEBase`` on a ``CartesianGrid`` of ``n_p`` cells on [0, p_max]
(``p_max = problem.p_max(k_domain)``) with ``bc={"value": 0}`` at both ends (absorbing walls; py-pde
sets the ghost cell to minus the edge cell, which is exactly the odd image extension, so the
wall costs no order) and py-pde's 2nd-order ``laplace`` operator.

*Time variable.*  The equation is integrated in the complete-contact variance V, not in zeta:
:math:`dP_0/dV = \tfrac12 S(A^*)\,\partial_p^2 P_0` is the same equation (chain rule, exact), its
right-hand side is autonomous (no tabulated dV/dzeta, whose kink at zeta = q_r/q_l an interpolant
would smear), the explicit stability limit :math:`\Delta V \le \Delta p^2/S` is uniform along the
run, and every output station zeta_k maps to an exact V_k = V(zeta_k).  To *hit* the stations
with py-pde's fixed-step steppers (which take ``round((t_end - t_start)/dt)`` steps of one compiled
``dt``), py-pde's time is a pseudo time s with ``dt = 1``: segment k of ``n_k`` steps covers
s in [s_{k-1}, s_k] with integer knots, and V(s) is the monotone C1 cubic (PCHIP) through
(s_k, V_k).  The rhs is then :math:`\tfrac12\,V'(s)\,S(A^*)\,\partial_p^2 P_0`; V'(s) is continuous
and a polynomial inside every step, so every one-step method sees a smooth ODE and lands on the
stations exactly.

*Fudge factor.*  A* is the current numerical :math:`\sum_i P_i\,\Delta p`, computed inside the
compiled rhs from its ``(data, t)`` arguments (py-pde freezes captured arrays at compile time, so
nothing may be updated from outside).  With the numba backend S must be compiled: None, "YP08" and
"WM17" are compiled closed-form polynomials; "Xu24" (needs erfinv) and user callables are
tabulated on ~4600 points of [0, 1] (uniform plus a geometric cluster at A* -> 1) and linearly
interpolated (``np.interp`` in numba; the relative interpolation error, measured at the
midpoints and reported in ``info["S_table_error"]``, is ~2e-8 for a smooth S and ~1e-6 for
Xu24).  The numpy backend calls ``fudge.S`` exactly (about 500x slower).

*Solvers* (option ``solver``): py-pde's "euler" (explicit, fixed step), "runge-kutta" (adaptive
Runge--Kutta--Fehlberg, ``tolerance = rtol * max P0``), "implicit" and "crank-nicolson" (py-pde's
*fixed-point* iterations, which converge only for :math:`\Delta V\,S\,2/\Delta p^2 < 1`, i.e. about the
explicit limit -- they buy no stiffness), and "scipy" (``scipy.integrate.solve_ivp``, default BDF;
``jac_sparsity`` tridiagonal for S = 1, a dense finite-difference Jacobian with a fudge factor,
because the tridiagonal pattern misses the rank-1 part dS/dA* and BDF's Newton then stalls).

Accuracy guidance
-----------------
The space error is that of 2nd-order finite volumes, :math:`\propto \Delta p^2`.  The defaults
(``solver="euler"``, ``n_p=800``, steps uniform in the exact effective variance tau with
:math:`S\,\Delta V/\Delta p^2 = 1/3` -- the classical r = 1/6 at which explicit Euler's leading
time error cancels the leading space error -- and a start from the exact solution at
tau0 = 0.05 tau_max) give on ``ContactProblem.reference()`` at zeta = 4, 32, 128 (measured, 2-core
machine): L1 = 6e-8 without a fudge factor (the cancellation is exact for S = 1) and L1 = 5.7e-6,
``|dA*|`` = 2.9e-6 with "YP08" (the explicit coupling of S(A*) is 1st order: L1 ~ dp^2), in 0.03 s
of stepping **plus the numba compilation** of a stepper in which py-pde freezes the grid, the
time map V(s) and S: 1.5-3 s when numba is warm, 7-20 s in a fresh process (``info["compile_time"]``,
kept out of ``Solution.wall_time``).  The compiled stepper is cached in the process (the 16 most
recent, keyed by exactly what it freezes; ``info["stepper_cached"]``), so repeating a call costs no
compile, while a new grid, new stations or new loads whose time map differs compile anew.
Promised: L1 <= 1e-4.  Halving dp costs 4x the steps and buys 4x
accuracy (n_p=1600: ~1.4e-6 for YP08, 0.3 s).  "scipy" (BDF) is 100x slower here (a Python
rhs call per evaluation; a dense finite-difference Jacobian with a fudge factor, see
``jac_sparsity``) and "runge-kutta" is limited by the space error of its grid.
``initial="delta"`` (one cell at p_bar, zeta = 1) costs accuracy (L1 ~ 4e-3) and is there to
show it.  An explicit run with ``n_steps`` above the stability limit is refused unless
``allow_unstable=True``; py-pde itself returns a silently huge field there (persson-fp raises
:class:`~persson_fp.InstabilityError`), and py-pde's "implicit"/"crank-nicolson" raise
``ConvergenceError`` (here an InstabilityError) once the step passes about the explicit limit.

References
----------
.. [1] D. Zwicker, "py-pde: A Python package for solving partial differential equations",
       J. Open Source Softw. 5 (2020) 2158.
"""

from __future__ import annotations

import time
from collections import OrderedDict

import numpy as np

from persson_fp.results.solution import InstabilityError, SolverError
from persson_fp.solvers.backends._stepping import _pchip_map, r_per_step, step_nodes
from persson_fp.solvers.base import Solver, SolverOutput, check_float, check_int
from persson_fp.theory.fudge import NoFudge, WangMuser, YangPersson

__all__ = ["PyPDESolver", "SOLVERS", "BACKENDS"]

SOLVERS = ("euler", "runge-kutta", "implicit", "crank-nicolson", "scipy")
"""py-pde solvers selectable through the option ``solver``."""
BACKENDS = ("numba", "numpy")
_FIXED = ("euler", "implicit", "crank-nicolson")
_S_TABLE = 4097
_STEPPERS = OrderedDict()
"""Compiled py-pde steppers of this process, least recently used first: key -> (grid, solver, stepper, S info)."""
_STEPPER_CACHE_SIZE = 16


def _fudge_key(fudge):
    """What the compiled S depends on: the closed form's parameter, or the tabulated values."""
    if type(fudge) in (NoFudge, YangPersson, WangMuser):
        return (type(fudge).__name__, float(getattr(fudge, "gamma", 0.0)))
    A_tab = np.unique(np.concatenate((np.linspace(0.0, 1.0, _S_TABLE), 1.0 - np.logspace(-14, -2.5, 512))))
    return ("table", np.asarray(fudge.S(A_tab), dtype=float).tobytes())


# -- compiled pieces -------------------------------------------------------------------------------
def _compiled_S(fudge):
    """(njit S(A) for numba, description, measured interpolation error or 0)."""
    import numba as nb

    kind = type(fudge)
    if kind is NoFudge:

        @nb.njit
        def S(A):
            return 1.0

        return S, "S = 1 (compiled)", 0.0
    if kind is YangPersson:
        g = float(fudge.gamma)

        @nb.njit
        def S(A):
            return g + (1.0 - g) * A * A

        return S, "YP08 closed form (compiled)", 0.0
    if kind is WangMuser:
        g = float(fudge.gamma)

        @nb.njit
        def S(A):
            A2 = A * A
            return g - (2.0 / 9.0) * A2 + (11.0 / 9.0 - g) * A2 * A2

        return S, "WM17 closed form (compiled)", 0.0
    # uniform on [0, 1] plus a geometric cluster at A* -> 1 (Xu24's S has an erfinv singularity there)
    A_tab = np.unique(np.concatenate((np.linspace(0.0, 1.0, _S_TABLE), 1.0 - np.logspace(-14, -2.5, 512))))
    S_tab = np.asarray(fudge.S(A_tab), dtype=float)
    mid = 0.5 * (A_tab[1:] + A_tab[:-1])
    S_mid = np.asarray(fudge.S(mid), dtype=float)
    err = float(np.max(np.abs(np.interp(mid, A_tab, S_tab) - S_mid) / S_mid))

    @nb.njit
    def S(A):
        return np.interp(min(max(A, 0.0), 1.0), A_tab, S_tab)

    return S, f"{fudge.name}: table of {A_tab.size} points on [0, 1], linear interpolation (compiled)", err


def _make_pde(fudge, knots, coef, dp, backend_name):
    """The py-pde PDE dP/ds = 1/2 V'(s) S(A*) P_pp with Dirichlet 0 at both ends."""
    from pde import PDEBase

    S_info = {"S": "fudge.S (numpy, exact)", "S_table_error": 0.0}
    if backend_name == "numba":
        S_nb, desc, err = _compiled_S(fudge)
        S_info = {"S": desc, "S_table_error": err}
    n_seg = knots.size - 1

    def g_np(t):
        k = min(max(int(np.searchsorted(knots, t, side="right")) - 1, 0), n_seg - 1)
        x = t - knots[k]
        return (coef[0, k] * x + coef[1, k]) * x + coef[2, k]

    class PerssonPDE(PDEBase):
        """dP0/ds = 1/2 V'(s) S(A*) d^2P0/dp^2 (``E:diffusion_equ``, ``eq:new_B2``), absorbing walls."""

        check_implementation = False
        explicit_time_dependence = True

        def __init__(self):
            super().__init__()
            self.bc = {"value": 0.0}

        def evolution_rate(self, state, t=0.0):  # numpy backend
            A = float(np.sum(state.data) * dp)
            return state.laplace(bc=self.bc) * (0.5 * g_np(t) * float(fudge.S(np.array(A))))

        def make_evolution_rate(self, state, backend):  # numba backend
            if backend.name != "numba":
                raise NotImplementedError
            lap = state.grid.make_operator("laplace", bc=self.bc, backend=backend)
            S = S_nb
            kn, c = knots, coef

            def rhs(data, t=0.0):
                A = np.sum(data) * dp
                k = np.searchsorted(kn, t, side="right") - 1
                k = min(max(k, 0), n_seg - 1)
                x = t - kn[k]
                g = (c[0, k] * x + c[1, k]) * x + c[2, k]
                return (0.5 * g * S(A)) * lap(data)

            return rhs

    return PerssonPDE(), S_info


class PyPDESolver(Solver):
    r"""Persson's equation as a py-pde PDE (see the module docstring).

    Options
    -------
    n_p : int, default 800
        Cells on [0, p_max] (cell width dp, pressure).
    n_steps : int or None, default None
        Steps (in V) from the start to the last station for the fixed-step solvers ("euler",
        "implicit", "crank-nicolson"); None: from ``cfl``.  For "runge-kutta" it only sets the
        first trial step; "scipy" ignores it.
    cfl : float, default 1/3
        With ``n_steps=None`` (fixed-step solvers): S dV / dp^2 per step, 1 being the explicit
        stability limit (py-pde's fixed-point "crank-nicolson" also converges only below 1 and
        "implicit" below 1/2).
    stepping : str, default "tau"
        Fixed-step node placement: uniform in the exact effective variance tau of the load with
        the largest tau ("tau", so that S dV stays at cfl dp^2) or uniform in V ("V").
    solver : str, default "euler"
        One of ``SOLVERS``.
    backend : str, default "numba"
        "numba" (compiled; compile time in ``info["compile_time"]``) or "numpy".
    rtol, atol : float
        "scipy": passed to ``solve_ivp`` (atol default ``rtol * 1e-3 * max P0``); "runge-kutta":
        tolerance = rtol * max P0 (py-pde's error is absolute); "implicit"/"crank-nicolson":
        fixed-point tolerance = rtol * max P0 (rms change).
    scipy_method : str, default "BDF"
        ``solve_ivp`` method of ``solver="scipy"`` ("BDF", "Radau", "LSODA", "RK45", ...).
    jac_sparsity : str, default "auto"
        "scipy" with BDF/Radau: "tridiagonal" (finite-difference Jacobian from 3 rhs calls) or
        "dense" (n_p calls).  "auto": tridiagonal for S = 1, dense with a fudge factor -- the
        tridiagonal pattern misses the dense rank-1 part d(rhs)/dA* dA*/dP, and BDF's Newton then
        stalls (measured: WM17, n_p=100, 3e5 rhs calls and 180 s instead of < 1 s).
    picard_maxiter : int, default 100
        Iteration cap of py-pde's fixed-point "implicit"/"crank-nicolson".
    initial : str, default "exact"
        "exact": exact cell averages at zeta0; "delta": one cell of mass 1 at p_bar at zeta = 1.
    zeta0, tau0_fraction : float
        Start of "exact": zeta0 given, else where tau = ``tau0_fraction`` tau(zeta_max) (largest
        load; lowered to half the first station's tau if needed).
    k_domain : float, default 8
        p_max = max(p_bar) + k_domain sqrt(tau(zeta_max)) (pressure).
    allow_unstable : bool, default False
        Let "euler" run with a step above the explicit limit (an InstabilityError is expected).
    """

    name = "py-pde"
    OPTIONS = {
        "n_p": 800,
        "n_steps": None,
        "cfl": 1.0 / 3.0,
        "stepping": "tau",
        "solver": "euler",
        "backend": "numba",
        "rtol": 1e-6,
        "atol": None,
        "scipy_method": "BDF",
        "jac_sparsity": "auto",
        "picard_maxiter": 100,
        "initial": "exact",
        "zeta0": None,
        "tau0_fraction": 0.05,
        "k_domain": 8.0,
        "allow_unstable": False,
    }

    def validate(self) -> None:
        o = self.opts
        o["n_p"] = check_int(o["n_p"], "n_p", 8)
        if o["n_steps"] is not None:
            o["n_steps"] = check_int(o["n_steps"], "n_steps", 1)
        o["cfl"] = check_float(o["cfl"], "cfl", 0.0, 10.0)
        for key, allowed in (
            ("solver", SOLVERS),
            ("backend", BACKENDS),
            ("initial", ("exact", "delta")),
            ("stepping", ("tau", "V")),
            ("jac_sparsity", ("auto", "tridiagonal", "dense")),
        ):
            if o[key] not in allowed:
                raise ValueError(f"{key} must be one of {list(allowed)}, got {o[key]!r}")
        o["rtol"] = check_float(o["rtol"], "rtol", 0.0, 1.0)
        if o["atol"] is not None:
            o["atol"] = check_float(o["atol"], "atol", 0.0)
        if not isinstance(o["scipy_method"], str):
            raise ValueError(f"scipy_method must be a solve_ivp method name, got {o['scipy_method']!r}")
        o["picard_maxiter"] = check_int(o["picard_maxiter"], "picard_maxiter", 1)
        self.validate_start_options()

    # -- the run -------------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        import pde

        o, pr = self.opts, self.problem
        N = o["n_p"]
        edges, dp = self.cell_grid(N)
        p_max = edges[-1]
        z0, V0, P_init, A_init = self.initial_cell_averages(edges)
        V_st = np.concatenate(([V0], self.V_out))
        S_max = float(np.max(pr.fudge.S(np.linspace(0.0, 1.0, 2001))))
        fixed = o["solver"] in _FIXED
        peak = float(np.max(P_init))

        # -- the pseudo-time map V(s): integer knots (fixed steps) or s = (V - V0) / (V_end - V0)
        if fixed:
            V_nodes, st_idx = self._nodes(V_st, dp)
            knots = np.arange(V_nodes.size, dtype=float)
            if o["solver"] == "euler":
                # Euler evaluates the rhs only at step starts: a piecewise-constant V'(s) = the
                # secant makes every step exactly dV_i (exact station hits, no O(dV) drift)
                coef = np.zeros((3, V_nodes.size - 1))
                coef[2] = np.diff(V_nodes)
            else:  # t and t + dt are evaluated: V'(s) must be continuous (PCHIP)
                knots, coef, _ = _pchip_map(knots, V_nodes)
            st_knots = knots[st_idx]
            r_max = self._r_max(V_nodes, dp)
            if o["solver"] == "euler" and r_max > 1.0 + 1e-12 and not o["allow_unstable"]:
                raise ValueError(
                    f"py-pde/euler: n_steps = {V_nodes.size - 1} gives S dV / dp^2 up to {r_max:.3g} > 1, above the "
                    f"explicit stability limit; use n_steps >= {int(np.ceil((V_nodes.size - 1) * r_max))}, "
                    "n_steps=None, another solver, or allow_unstable=True"
                )
            n_total = V_nodes.size - 1
            dt = 1.0
        else:
            knots = (V_st - V0) / (V_st[-1] - V0)
            knots, coef, _ = _pchip_map(knots, V_st)
            st_knots = knots
            n_total = None
            r_max = None
            dt = None
            if o["solver"] == "runge-kutta":
                n0 = o["n_steps"] or int(np.ceil((V_st[-1] - V0) / (dp**2 / S_max)))
                dt = 1.0 / n0

        remedy = (
            "raise n_steps (or n_steps=None)"
            if o["solver"] == "euler"
            else "use solver='scipy' or a smaller step (py-pde's implicit schemes are fixed-point iterations)"
        )
        # -- compile (make_stepper + one warm-up step on a copy), timed apart from the solve; py-pde freezes
        # the grid, the time map and S into the compiled stepper, so it is cached under exactly those
        t_c = time.perf_counter()
        key = self._stepper_key(N, p_max, dt, knots, coef, peak)
        hit = _STEPPERS.get(key)
        if hit is None:
            eq, S_info = _make_pde(pr.fudge, knots, coef, dp, o["backend"])
            grid = pde.CartesianGrid([[0.0, p_max]], N)
            state = pde.ScalarField(grid, P_init[0].copy())
            solver = self._make_pde_solver(pde, eq, peak)
            stepper = solver.make_stepper(state, dt=dt)
            warm = state.copy()
            self._advance(stepper, warm, float(knots[0]), float(knots[0]) + (1.0 if fixed else 1e-9), remedy)
            _STEPPERS[key] = (grid, solver, stepper, S_info)
            while len(_STEPPERS) > _STEPPER_CACHE_SIZE:
                _STEPPERS.pop(next(iter(_STEPPERS)))
        else:
            _STEPPERS.move_to_end(key)
            grid, solver, stepper, S_info = hit
            state = pde.ScalarField(grid, P_init[0].copy())
        compile_time = time.perf_counter() - t_c
        solver.info["steps"] = 0
        if dt is not None and "dt" in solver.info:
            solver.info["dt"] = dt

        # -- the stepping: every load, station by station (chunks of <= 2000 steps for checks)
        m = pr.n_loads
        P_out = np.empty((self.zeta_out.size, m, N))
        t_s = time.perf_counter()
        for j in range(m):
            state.data[:] = P_init[j]
            mass_prev = float(A_init[j])
            l1_0 = float(A_init[j])
            for k in range(1, st_knots.size):
                bounds = [st_knots[k - 1], st_knots[k]]
                if fixed and bounds[1] - bounds[0] > 2000:
                    bounds = list(np.arange(bounds[0], bounds[1], 2000.0)) + [bounds[1]]
                for a, b in zip(bounds[:-1], bounds[1:]):
                    self._advance(stepper, state, float(a), float(b), remedy)
                    P = state.data
                    mass = float(np.sum(P) * dp)
                    z_now = self._zeta_at(V_st, st_knots, k, b)
                    self.check_state(P, np.array([mass]), np.array([mass_prev]), z_now, f"py-pde/{o['solver']}", remedy)
                    if np.sum(np.abs(P)) * dp > l1_0 * (1.0 + 1e-3) + 1e-12:
                        raise InstabilityError(
                            f"py-pde/{o['solver']}: int |P0| dp grew to {np.sum(np.abs(P)) * dp:.3e} "
                            f"(> {l1_0:.3e}) by zeta = {z_now:.6g} -- the discrete evolution is unstable; {remedy}"
                        )
                    mass_prev = mass
                P_out[k - 1, j] = state.data
        solve_time = time.perf_counter() - t_s

        info = {
            "grid": {"n_p": N, "p_max": p_max, "dp": dp},
            "edges": edges,
            "zeta0": z0,
            "initial": o["initial"],
            "time_variable": "V (pseudo time s, V(s) monotone C1 cubic through the stations)",
            "solver": o["solver"],
            "backend": o["backend"],
            "steps": int(solver.info.get("steps", 0)),
            "compile_time": compile_time,
            "stepper_cached": hit is not None,
            "solve_time": solve_time,
            "pypde_version": pde.__version__,
            **S_info,
        }
        if fixed:
            info["stepping"] = o["stepping"]
            info["r_max"] = r_max
            info["steps_requested"] = n_total
        if o["solver"] == "scipy":
            info["rhs_evaluations"] = info.pop("steps")
        ex_end = self.exact_at(self.zeta_out[-1])
        A_ex = np.asarray(ex_end.contact_area, float).reshape(m)
        info["far_wall_mass"] = float(
            np.max(A_ex - np.asarray(ex_end.cdf_contact(np.array([p_max])), float).reshape(m))
        )
        return SolverOutput(p=grid.axes_coords[0].copy(), P0=P_out, weights=np.full(N, dp), kind="cell", info=info)

    def _stepper_key(self, N, p_max, dt, knots, coef, peak):
        """Everything a compiled stepper freezes: grid, solver and its settings, time map, S."""
        o = self.opts
        settings = tuple(o[k] for k in ("solver", "backend", "rtol", "atol", "scipy_method", "jac_sparsity"))
        return (
            settings + (o["picard_maxiter"], N, float(p_max), dt, float(peak)),
            np.asarray(knots, float).tobytes(),
            np.asarray(coef, float).tobytes(),
            _fudge_key(self.problem.fudge),
        )

    def _nodes(self, V_st, dp):
        """V at every step node (stations included) and the stations' node indices."""
        o = self.opts
        return step_nodes(self.problem, V_st, dp, o["n_steps"], o["cfl"], o["stepping"])

    def _r_max(self, V_nodes, dp):
        """max over steps and loads of S(A*_exact) dV / dp^2 (1 = explicit stability limit)."""
        return float(np.max(r_per_step(self.problem, V_nodes, dp)))

    def _make_pde_solver(self, pde, eq, peak):
        o = self.opts
        be = o["backend"]
        if o["solver"] == "euler":
            return pde.solvers.EulerSolver(eq, backend=be, adaptive=False)
        if o["solver"] == "runge-kutta":
            return pde.solvers.RungeKuttaSolver(eq, backend=be, adaptive=True, tolerance=o["rtol"] * peak)
        if o["solver"] == "implicit":
            return pde.solvers.ImplicitSolver(eq, backend=be, maxiter=o["picard_maxiter"], maxerror=o["rtol"] * peak)
        if o["solver"] == "crank-nicolson":
            return pde.solvers.CrankNicolsonSolver(
                eq, backend=be, maxiter=o["picard_maxiter"], maxerror=o["rtol"] * peak
            )
        import scipy.sparse as sps

        N = o["n_p"]
        atol = o["atol"] if o["atol"] is not None else o["rtol"] * 1e-3 * peak
        kw = {"method": o["scipy_method"], "rtol": o["rtol"], "atol": atol}
        sparsity = o["jac_sparsity"]
        if sparsity == "auto":
            sparsity = "tridiagonal" if isinstance(self.problem.fudge, NoFudge) else "dense"
        if o["scipy_method"] in ("BDF", "Radau") and sparsity == "tridiagonal":
            kw["jac_sparsity"] = sps.diags([1.0, 1.0, 1.0], [-1, 0, 1], shape=(N, N), format="csc")
        return pde.solvers.ScipySolver(eq, backend=be, **kw)

    def _advance(self, stepper, state, a, b, remedy):
        from pde.solvers.base import ConvergenceError

        name = f"py-pde/{self.opts['solver']}"
        try:
            with np.errstate(all="ignore"):
                stepper(state, a, b)
        except ConvergenceError as err:
            raise InstabilityError(
                f"{name}: py-pde's fixed-point iteration did not converge ({err}); it converges only below "
                f"about the explicit step limit; {remedy}"
            ) from err
        except RuntimeError as err:
            if "Not-A-Number" in str(err) or "NaN" in str(err):
                raise InstabilityError(f"{name}: {err}; {remedy}") from err
            raise SolverError(f"{name}: {err}") from err

    def _zeta_at(self, V_st, knots, k, s):
        """Magnification at pseudo time s inside segment k (for messages; exact at the knots)."""
        if s == knots[k]:
            return float(self.zeta_out[k - 1])
        frac = (s - knots[k - 1]) / (knots[k] - knots[k - 1])
        V = V_st[k - 1] + frac * (V_st[k] - V_st[k - 1])
        return float(self.zeta_from_V(V)[0]) if V > 0 else 1.0
