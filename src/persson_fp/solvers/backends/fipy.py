r"""Persson's diffusion equation driven through FiPy [1]_ (the generic finite-volume tool).

The method
----------
``E:diffusion_equ`` with ``eq:new_B2`` is set up the way a FiPy user would: a ``Grid1D`` of
``n_p`` cells on [0, p_max] (``p_max = problem.p_max(k_domain)``), a ``CellVariable`` P0 with
``constrain(0, facesLeft/facesRight)`` (absorbing walls; FiPy's face value 0 is the odd image
extension, so the wall costs no order), and

.. math::  \texttt{TransientTerm()} == \texttt{DiffusionTerm(coeff=D)}, \qquad
           D = \tfrac12 S(A^*)

with D a FiPy ``Variable`` set before every solve.  As in :mod:`persson_fp.solvers.backends.pypde` the
"time" is the complete-contact variance V (exact change of variable, dV = dV/dzeta dzeta), so D
holds only the fudge factor; the steps are placed uniformly in the exact effective variance tau
(``stepping="tau"``) or in V, and every output station is a step node.

``scheme``: "explicit" (``ExplicitDiffusionTerm``, D from A*_n; stable for S dV/dp^2 <= 1),
"implicit" (backward Euler, D from A*_{n+1}) or "crank-nicolson" (0.5 ``DiffusionTerm`` + 0.5
``ExplicitDiffusionTerm``, D from (S(A*_n) + S(A*_{n+1}))/2, i.e. the trapezoidal rule for
tau = int S dV).  The implicit schemes *sweep* the nonlinear fudge factor: solve with the A*_{n+1}
guessed, recompute A*_{n+1} = sum P dp from the result, repeat until the A* used and the A*
produced agree to ``sweep_tol`` (at most ``max_sweeps``; the first guess is extrapolated from the
last two steps, so one or two sweeps are typical).  Without a fudge factor one solve per step.
``linear_solver``: "lu" (``LinearLUSolver``, scipy splu) or "pcg" (``LinearPCGSolver``).

Accuracy guidance
-----------------
FiPy costs about 6-18 ms of Python per solve whatever the grid, so the step count sets the run
time.  Space error is 2nd order (L1 ~ dp^2), Crank--Nicolson time error 2nd order in the step.
The defaults (``scheme="crank-nicolson"``, ``n_p=800``, ``n_steps=200``, start from the exact
solution at tau0 = 0.05 tau_max) reach L1 ~ 6e-5 (fudge "YP08") and ~3e-5 (None) on
``ContactProblem.reference()`` at zeta = 4, 32, 128 (promised: L1 <= 1e-3) in about 3 s (None, one
solve per step) to 7-10 s (a fudge factor: ~3 solves per step with the sweeps) per load on a
2-core machine.  For L1 ~ 1e-5 take ``n_p=1600, n_steps=400``; each doubling of both costs 2x
time for ~4x accuracy (the first station, where tau is smallest, needs the most).  "explicit"
needs n_steps ~ 3 tau_range/dp^2 (thousands of steps: minutes) and is refused above its
stability limit unless ``allow_unstable=True``; FiPy itself would return a growing, oscillating field without a
warning (persson-fp raises :class:`~persson_fp.InstabilityError`).  "implicit" is 1st
order (needs ~10x the steps of "crank-nicolson").  ``initial="delta"`` (one cell at p_bar,
zeta = 1) makes Crank--Nicolson ring (negative P0, reported in ``info["checks"]``).

References
----------
.. [1] J.E. Guyer, D. Wheeler, J.A. Warren, "FiPy: Partial Differential Equations with Python",
       Comput. Sci. Eng. 11 (2009) 6.
"""

from __future__ import annotations

import time

import numpy as np

from persson_fp.results.solution import InstabilityError
from persson_fp.solvers.backends._stepping import r_per_step, step_nodes
from persson_fp.solvers.base import Solver, SolverOutput, StationRecorder, check_float, check_int
from persson_fp.theory.fudge import NoFudge

__all__ = ["FiPySolver", "SCHEMES", "LINEAR_SOLVERS"]

SCHEMES = ("explicit", "implicit", "crank-nicolson")
LINEAR_SOLVERS = ("lu", "pcg")


class FiPySolver(Solver):
    r"""Persson's equation through FiPy (see the module docstring).

    Options
    -------
    n_p : int, default 800
        Cells on [0, p_max] (cell width dp, pressure).
    n_steps : int or None, default None
        Steps from the start to the last station (shared over the stations' segments); None:
        200 for the implicit schemes, ``cfl`` of the stability limit for "explicit".
    cfl : float, default 1/3
        "explicit" with ``n_steps=None``: S dV / dp^2 per step (1 = stability limit).
    scheme : str, default "crank-nicolson"
        "explicit" | "implicit" | "crank-nicolson".
    stepping : str, default "tau"
        Step nodes uniform in the exact effective variance tau ("tau") or in V ("V").
    linear_solver : str, default "lu"
        "lu" (direct) or "pcg" (preconditioned conjugate gradients, tolerance ``pcg_tol``).
    pcg_tol : float, default 1e-12
        Relative residual of "pcg".
    sweep_tol : float, default 1e-8
        Sweeps of the fudge factor stop when ``|A*_used - A*_produced| <= sweep_tol`` (about 2 linear
        solves per step; the A* error left, <= sweep_tol per step, is far below the truncation error).
    max_sweeps : int, default 10
        Cap on sweeps per step (hitting it is counted in ``info["sweeps_capped"]``).
    initial, zeta0, tau0_fraction, k_domain, allow_unstable
        As for "py-pde" (:class:`~persson_fp.solvers.backends.pypde.PyPDESolver`).
    """

    name = "fipy"
    OPTIONS = {
        "n_p": 800,
        "n_steps": None,
        "cfl": 1.0 / 3.0,
        "scheme": "crank-nicolson",
        "stepping": "tau",
        "linear_solver": "lu",
        "pcg_tol": 1e-12,
        "sweep_tol": 1e-8,
        "max_sweeps": 10,
        "initial": "exact",
        "zeta0": None,
        "tau0_fraction": 0.05,
        "k_domain": 8.0,
        "allow_unstable": False,
    }
    DEFAULT_STEPS = 200
    """n_steps of the implicit schemes when ``n_steps=None``."""

    def validate(self) -> None:
        o = self.opts
        o["n_p"] = check_int(o["n_p"], "n_p", 4)
        if o["n_steps"] is not None:
            o["n_steps"] = check_int(o["n_steps"], "n_steps", 1)
        o["cfl"] = check_float(o["cfl"], "cfl", 0.0, 10.0)
        for key, allowed in (
            ("scheme", SCHEMES),
            ("stepping", ("tau", "V")),
            ("linear_solver", LINEAR_SOLVERS),
            ("initial", ("exact", "delta")),
        ):
            if o[key] not in allowed:
                raise ValueError(f"{key} must be one of {list(allowed)}, got {o[key]!r}")
        o["pcg_tol"] = check_float(o["pcg_tol"], "pcg_tol", 0.0, 1.0)
        o["sweep_tol"] = check_float(o["sweep_tol"], "sweep_tol", 0.0, 1.0)
        o["max_sweeps"] = check_int(o["max_sweeps"], "max_sweeps", 1)
        self.validate_start_options()

    def _solve(self) -> SolverOutput:
        import fipy

        o, pr = self.opts, self.problem
        N = o["n_p"]
        edges, dp = self.cell_grid(N)
        p_max = edges[-1]
        z0, V0, P_init, A_init = self.initial_cell_averages(edges)
        V_st = np.concatenate(([V0], self.V_out))
        explicit = o["scheme"] == "explicit"
        n_steps = o["n_steps"]
        if n_steps is None and not explicit:
            n_steps = self.DEFAULT_STEPS
        V_nodes, st_idx = step_nodes(pr, V_st, dp, n_steps, o["cfl"], o["stepping"])
        r = r_per_step(pr, V_nodes, dp)
        r_max = float(np.max(r))
        if explicit and r_max > 1.0 + 1e-12 and not o["allow_unstable"]:
            raise ValueError(
                f"fipy/explicit: n_steps = {V_nodes.size - 1} gives S dV / dp^2 up to {r_max:.3g} > 1, above the "
                f"explicit stability limit; use n_steps >= {int(np.ceil((V_nodes.size - 1) * r_max))}, "
                "n_steps=None, another scheme, or allow_unstable=True"
            )
        dV = np.diff(V_nodes)
        fudge = pr.fudge
        no_fudge = isinstance(fudge, NoFudge)

        def S(A):
            return float(fudge.S(np.array(A)))

        t_c = time.perf_counter()
        mesh = fipy.Grid1D(nx=N, dx=dp)
        phi = fipy.CellVariable(mesh=mesh, value=P_init[0], hasOld=True)
        phi.constrain(0.0, mesh.facesLeft)
        phi.constrain(0.0, mesh.facesRight)
        D = fipy.Variable(value=0.5)
        # FiPy 4.0's ExplicitDiffusionTerm builds its operator from var.old, which carries no
        # constraints, so it ignores the fixed face values (a no-flux wall; checked: a constant field
        # does not move), and applies it to var.value (not var.old), so it is explicit only on the
        # first solve after updateOld() -- sweeps below reset var to var.old first.  The absorbing walls' flux of the
        # explicit part is therefore added as an explicit source, -D P_wall^n / (dp/2) / dp.
        wall_mask = np.zeros(N)
        wall_mask[0] = wall_mask[-1] = 2.0 / dp**2
        wall_sink = -D * fipy.CellVariable(mesh=mesh, value=wall_mask) * phi.old
        if explicit:
            eq = fipy.TransientTerm() == fipy.ExplicitDiffusionTerm(coeff=D) + wall_sink
        elif o["scheme"] == "implicit":
            eq = fipy.TransientTerm() == fipy.DiffusionTerm(coeff=D)
        else:
            eq = fipy.TransientTerm() == (
                0.5 * fipy.DiffusionTerm(coeff=D) + 0.5 * fipy.ExplicitDiffusionTerm(coeff=D) + 0.5 * wall_sink
            )
        if o["linear_solver"] == "lu":
            lin = fipy.LinearLUSolver()
        else:
            lin = fipy.LinearPCGSolver(tolerance=o["pcg_tol"])
        setup_time = time.perf_counter() - t_c

        m = pr.n_loads
        rec = StationRecorder(st_idx[1:], P0=(m, N))
        remedy = "raise n_steps (or n_steps=None)" if explicit else "raise n_steps"
        name = f"fipy/{o['scheme']}"
        sweeps_total = 0
        sweeps_capped = 0
        solves = 0
        t_s = time.perf_counter()
        for j in range(m):
            phi.setValue(P_init[j])
            phi.updateOld()
            A_n = float(A_init[j])
            A_prev = A_n
            l1_0 = A_n
            for n in range(dV.size):
                dt = float(dV[n])
                if explicit or no_fudge:
                    D.setValue(0.5 * S(A_n))
                    with np.errstate(all="ignore"):
                        eq.solve(var=phi, dt=dt, solver=lin)
                    solves += 1
                    A_new = float(np.sum(phi.value) * dp)
                else:
                    # guess A*_{n+1} by extrapolation, then sweep until the A* used is the A* produced
                    ratio = dt / float(dV[n - 1]) if n > 0 else 0.0
                    A_guess = max(A_n + (A_n - A_prev) * ratio, 0.0)
                    for sweep in range(o["max_sweeps"]):
                        S_eff = S(A_guess) if o["scheme"] == "implicit" else 0.5 * (S(A_n) + S(A_guess))
                        D.setValue(0.5 * S_eff)
                        if sweep > 0:  # ExplicitDiffusionTerm applies its operator to var.value: reset it
                            phi.setValue(phi.old.value)
                        with np.errstate(all="ignore"):
                            eq.solve(var=phi, dt=dt, solver=lin)
                        solves += 1
                        A_new = float(np.sum(phi.value) * dp)
                        if abs(A_new - A_guess) <= o["sweep_tol"]:
                            break
                        A_guess = A_new
                    else:
                        sweeps_capped += 1
                    sweeps_total += sweep + 1
                P = phi.value
                if (n + 1) % 20 == 0 or (n + 1) in rec or n + 1 == dV.size:
                    z_now = float(self.zeta_from_V(V_nodes[n + 1])[0])
                    self.check_state(P, np.array([A_new]), np.array([A_n]), z_now, name, remedy)
                    if np.sum(np.abs(P)) * dp > l1_0 * (1.0 + 1e-3) + 1e-12:
                        raise InstabilityError(
                            f"{name}: int |P0| dp grew to {np.sum(np.abs(P)) * dp:.3e} (> {l1_0:.3e}) by zeta = "
                            f"{z_now:.6g} -- the discrete evolution is unstable; {remedy}"
                        )
                elif not (A_new <= A_n * (1 + 1e-8) + 1e-12) or not np.isfinite(A_new):
                    z_now = float(self.zeta_from_V(V_nodes[n + 1])[0])
                    self.check_state(P, np.array([A_new]), np.array([A_n]), z_now, name, remedy)
                A_prev, A_n = A_n, A_new
                phi.updateOld()
                rec.record(n + 1, load=j, P0=P)
        solve_time = time.perf_counter() - t_s

        ex_end = self.exact_at(self.zeta_out[-1])
        A_ex = np.asarray(ex_end.contact_area, float).reshape(m)
        tail = A_ex - np.asarray(ex_end.cdf_contact(np.array([p_max])), float).reshape(m)
        info = {
            "grid": {"n_p": N, "p_max": p_max, "dp": dp},
            "edges": edges,
            "zeta0": z0,
            "initial": o["initial"],
            "time_variable": "V",
            "scheme": o["scheme"],
            "stepping": o["stepping"],
            "linear_solver": o["linear_solver"],
            "steps": int(dV.size),
            "linear_solves": solves,
            "sweeps": sweeps_total,
            "sweeps_capped": sweeps_capped,
            "r_max": r_max,
            "compile_time": setup_time,
            "solve_time": solve_time,
            "far_wall_mass": float(np.max(tail)),
            "fipy_version": fipy.__version__,
            "fipy_solver_suite": getattr(fipy.solvers, "solver_suite", None),
        }
        return SolverOutput(
            p=np.asarray(mesh.cellCenters[0].value, float).copy(),
            P0=rec["P0"],
            weights=np.full(N, dp),
            kind="cell",
            info=info,
        )
