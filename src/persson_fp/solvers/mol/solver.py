r"""Method of lines: finite differences in p, ``scipy.integrate.solve_ivp`` in tau or zeta.

Point values :math:`P_i \approx P_0(p_i)` on the uniform nodes
:math:`p_i = i h`, :math:`i = 0..n_p-1`, :math:`h = p_{max}/(n_p-1)`, with the
absorbing walls :math:`P_0 = P_{n_p-1} = 0` (``E:diffusion_equ``).  The
unknowns are the :math:`m = n_p - 2` interior values.

**Space.**  ``order=2``: the three-point Laplacian.  ``order=4``: the
five-point one, :math:`(-P_{i-2} + 16P_{i-1} - 30P_i + 16P_{i+1} - P_{i+2})/12h^2`,
whose ghost values next to a wall come from the odd extension
:math:`P_0(-p) = -P_0(p)` (and likewise about p_max).  That extension is exact
for the image solution (``eq:P0_solution``): with :math:`P_0(0) = 0` the heat
equation forces every even derivative to vanish at the wall, so the odd
extension is as smooth as P0 and the stencil keeps fourth order up to the
wall.  Quadrature (contact area, and A* inside the fudge factor): the
trapezoid rule for ``order=2`` and Gregory's fourth-order end-corrected rule
(weights h [3/8, 7/6, 23/24, 1, ..., 1, 23/24, 7/6, 3/8]) for ``order=4`` --
the trapezoid rule alone would cap A* at O(h^2) because P0'(0) != 0.

**Time.**  ``variable="tau"`` (default) integrates in the effective variance
:math:`\tau = \int S\,dV` (``eq:new_B2``), where the semi-discrete system is
linear with a constant banded matrix, :math:`dP/d\tau = \tfrac12 L P`.
Without a fudge factor tau = V and that is all.  With one, each load carries
its complete-contact variance :math:`V_j` as an extra unknown,

.. math::  \frac{dP_j}{d\tau} = \tfrac12 L P_j, \qquad
           \frac{dV_j}{d\tau} = \frac{1}{S(A_j)}, \quad A_j = w\cdot P_j ,

so the nonlocal coupling sits in one extra Jacobian row per load,
:math:`\partial \dot V_j/\partial P_j = -S'(A_j)/S(A_j)^2\, w^T` (m entries):
the Jacobian stays sparse, its LU has no fill beyond that row, and it is
exact.  All loads share tau; each load's stations are the taus where
:math:`V_j = V(\zeta_{out})`, found by Newton's method on the dense output
(:math:`dV_j/d\tau = 1/S` is known), and the run stops when the slowest load
reaches V(zeta_max).  ``variable="zeta"`` integrates
:math:`dP_j/d\zeta = c_j L P_j`, :math:`c_j = \tfrac12 S(A_j)\,dV/d\zeta`,
whose exact Jacobian :math:`c_j L + (L P_j)(c_j'\,w)^T` is a rank-one update
of a banded block -- dense per load (m^2 entries, dense LU): kept for the
comparison, not as the default.

**Start.**  ``initial="exact"``: the image solution at a small start-up tau0
(``tau0_fraction`` of the largest final tau, default automatic: tau0 = 2 h^2,
enough that the sampled Gaussian is resolved; measured: the final error does
not depend on tau0 once tau0 >~ h^2, and is O(1) below, where the sampled
Gaussian loses its mass), converted to zeta0 per load
through the exact effective-variance map and reported in ``info["zeta0"]``.
The exact start is part of the reference, so it adds no error of its own;
the error is then space (O(h^order)) plus time (``rtol``/``atol``).
``initial="delta"``: the discrete delta (mass and first moment of
:math:`\delta(p-\bar p)` split between the two neighbouring nodes) at
zeta = 1: an O(h^2/tau) start-up error that never fully heals.

**Integrators.**  Stiff ("BDF", "Radau", "LSODA") get the sparse Jacobian
(LSODA a dense one: it cannot take sparse matrices); explicit ones ("RK45",
"RK23", "DOP853") must resolve the stiffest mode, step ~ h^2/S: their cost
grows like n_p^2 (the stability study).
"""

from __future__ import annotations

import functools
import gc
import time

import numpy as np
import scipy.sparse as sp
from scipy.special import erf

from persson_fp.results.solution import SolverError
from persson_fp.solvers.base import LOAD_HANDLERS, Solver, SolverOutput, check_float, check_int, check_k_domain
from persson_fp.solvers.front_fixed.estimate import finish, run_pair
from persson_fp.solvers.front_fixed.start import general_start
from persson_fp.solvers.mol import ivp_march
from persson_fp.solvers.mol.grid import MOLSystem, laplacian, laplacian_readable, quadrature_weights, start_pdf, start_V
from persson_fp.solvers.mol.lines import solve_lines
from persson_fp.theory.fudge import NoFudge

__all__ = ["MethodOfLinesSolver", "laplacian", "quadrature_weights", "MOLSystem"]

_STIFF = ("BDF", "Radau", "LSODA")
_LOADS_PER_CHUNK = 250
"""Batches above this many loads are solved in chunks (memory of one chunk, time linear in the loads);
250: ~35 MB at the default grid, and no slower than 1000 loads at once (measured)."""
_EXPLICIT = ("RK45", "RK23", "DOP853")
_H_OVER_SIGMA = {2: 0.0085, 4: 0.085}
"""Automatic spacing h / sqrt(tau_first): L1 ~ 5e-6 at the first station on the reference problem."""
_N_P_AUTO_MAX = 20001


class MethodOfLinesSolver(Solver):
    r"""Method of lines for ``E:diffusion_equ`` / ``eq:new_B2`` (module docstring).

    Options
    -------
    n_p : int or None
        Grid nodes on [0, p_max], walls included (>= 8).  ``None``: the spacing
        h = c sqrt(tau) at the first output station (smallest tau over loads),
        c = 0.085 for order 4 and 0.0085 for order 2, measured to give
        L1 ~ 5e-6 there (the error scales like (h/sqrt(tau))^order, so a uniform
        grid sized for zeta_max alone is too coarse for early stations).
    order : {2, 4}
        Order of the finite differences in p.
    integrator : str
        ``solve_ivp`` method: "BDF", "Radau", "LSODA", "RK45", "RK23", "DOP853".
    rtol, atol : float
        ``solve_ivp`` tolerances (atol in 1/pressure, scaled by 1/sqrt(tau_max) if None; on the engine's path, None:
        rtol x 1e-3 of each load's mass at the start, so that a tiny load keeps its relative accuracy).
    variable : {"tau", "zeta"}
        Independent variable (module docstring).
    initial : {"exact", "delta"}
        Start from the exact solution at zeta0 or from the discrete delta at zeta = 1.
    zeta0, tau0_fraction : float or None
        Start-up magnification, or tau0 as a fraction of the largest final tau
        (``initial="exact"``); both None: tau0 = 2 h^2.
    k_domain : float
        p_max = max(p_bar) + k_domain sqrt(tau(zeta_max)).
    tol : float or None
        Moving yield wall only: raise :class:`~persson_fp.SolverError` when the error estimate of the areas
        or the load residual exceeds it.

    A constant hardness: the domain is [0, sigma_Y] (absorbing yield wall) and A_pl = (p_bar - F_el)/sigma_Y
    (the strip's load balance); with a fudge factor S sees A_el + A_pl.  A scale-dependent hardness (moving
    wall): the front-fixed finite-volume fluxes of :mod:`persson_fp.solvers.front_fixed.moving_wall` on ``n_p`` cells
    (default 200), integrated in V by ``solve_ivp`` with a banded Jacobian, and the error estimated from a
    partner run on n_p / 2 cells.  General coefficients: a drift the cells next to a wall do not resolve is refused
    (:func:`~persson_fp.solvers.front_fixed.start.check_wall_peclet`), and a
    march whose PDF has drained into a wall stops.
    """

    name = "mol"
    SUPPORTS = frozenset({"hardness", "moving_wall", "general"})
    OPTIONS = {
        "n_p": None,
        "order": 4,
        "integrator": "BDF",
        "rtol": 1e-5,
        "atol": None,
        "variable": "tau",
        "initial": "exact",
        "zeta0": None,
        "tau0_fraction": None,
        "k_domain": 10.0,
        "tol": None,
    }

    def validate(self) -> None:
        o = self.opts
        if o["n_p"] is not None:
            o["n_p"] = check_int(o["n_p"], "n_p", 8, 10_000_000)
        if not (
            isinstance(o["order"], (int, np.integer)) and not isinstance(o["order"], bool) and o["order"] in (2, 4)
        ):
            shown = o["order"].item() if isinstance(o["order"], np.generic) else o["order"]
            raise ValueError(f"order must be 2 or 4, got {shown!r}")
        o["order"] = int(o["order"])
        if o["tau0_fraction"] is not None:
            o["tau0_fraction"] = check_float(o["tau0_fraction"], "tau0_fraction", 0.0, 1.0)
        if o["zeta0"] is not None:
            o["zeta0"] = check_float(o["zeta0"], "zeta0", 1.0, float(self.zeta_out[0]), lo_open=False)
        if o["integrator"] not in _STIFF + _EXPLICIT:
            raise ValueError(f"integrator must be one of {list(_STIFF + _EXPLICIT)}, got {o['integrator']!r}")
        o["rtol"] = check_float(o["rtol"], "rtol", 0.0, 1.0)
        if o["atol"] is not None:
            o["atol"] = check_float(o["atol"], "atol", 0.0, np.inf)
        if o["variable"] not in ("tau", "zeta"):
            raise ValueError(f"variable must be 'tau' or 'zeta', got {o['variable']!r}")
        if o["initial"] not in ("exact", "delta"):
            raise ValueError(f"initial must be 'exact' or 'delta', got {o['initial']!r}")
        if o["tol"] is not None:
            o["tol"] = check_float(o["tol"], "tol", 1e-15, 1.0, lo_open=False)
        if o["initial"] == "delta" and (o["zeta0"] is not None or o["tau0_fraction"] is not None):
            raise ValueError("zeta0 / tau0_fraction apply to initial='exact' only")
        o["k_domain"] = check_k_domain(o["k_domain"], 1e3)

    def check_load_range(self) -> None:
        """Any load on the homogenised path; on the engine's (moving wall, general coefficients) the range of
        ``"fv"``: its start is fv's cell averages, which lose a load below it to round-off (p_bar = 1e-300 started
        with no mass and reported A* = 0 with an estimate of exactly 0)."""
        super().check_load_range()
        if self.problem.moving_wall or self.problem.general:
            super().check_load_range(range_of="fv")

    # -- grid and start ---------------------------------------------------------------------------
    def _grid(self):
        o = self.opts
        L = getattr(self, "_p_max_shared", None) or self.problem.p_max(o["k_domain"])
        if o["n_p"] is None:
            tau_first = float(np.min(self.problem.tau(self.zeta_out[0])))
            h = _H_OVER_SIGMA[o["order"]] * np.sqrt(tau_first)
            need = np.ceil(L / h) + 1
            if need > _N_P_AUTO_MAX:  # a PDF too narrow for the domain: refuse rather than under-resolve
                raise ValueError(
                    f"mol: the first station zeta = {self.zeta_out[0]:.6g} needs n_p = {need:.3g} grid points "
                    f"(> {_N_P_AUTO_MAX}) to resolve sqrt(tau) = {np.sqrt(tau_first):.3e} on [0, {L:.3e}]; "
                    f"start zeta_out later, use closer loads, or {LOAD_HANDLERS}"
                )
            o["n_p"] = int(max(need, 16))
        self.check_memory(o["n_p"])
        p = np.linspace(0.0, L, o["n_p"])
        self.check_resolved(p[1] - p[0])
        return p, p[1] - p[0]

    def _start(self, h):
        """Start-up (zeta0 per load, tau0 per load, V0 per load) for ``initial="exact"``."""
        pr = self.problem
        o = self.opts
        tau_max = pr.tau(pr.zeta_max)
        if o["zeta0"] is not None:
            z0 = self.start_zeta(zeta0=o["zeta0"])
        else:
            frac = o["tau0_fraction"]
            if frac is None:
                tau_first = float(np.max(pr.tau(self.zeta_out[0])))
                frac = min(2.0 * h * h, 0.25 * tau_first) / float(np.max(tau_max))
            z0 = self.start_zeta(tau0_fraction=frac)
        V0 = float(pr.V(z0))
        tau0 = pr.tau_of_V(V0)  # per load
        return z0, V0, tau0

    # -- the semi-discrete system -----------------------------------------------------------------
    def system(self) -> MOLSystem:
        """Build the ODE system, its readable twin, the exact Jacobian and the start (see module docstring)."""
        pr = self.problem
        o = self.opts
        p, h = self._grid()
        n_p, order = o["n_p"], o["order"]
        m = n_p - 2
        nl = pr.n_loads
        pi = p[1:-1]
        w = quadrature_weights(n_p, h, order)[1:-1]
        Lm = laplacian(m, h, order)
        Lb = sp.kron(sp.identity(nl, format="csr"), Lm, format="csr") if nl > 1 else Lm
        fudge = pr.fudge
        nofudge = isinstance(fudge, NoFudge)
        self._grid_cache = (p, h, w)
        # the contact area that S sees, A = wA . P + a0: A_el, plus (constant hardness) A_pl = (p_bar - F_el)/sigma
        wA, a0 = pr.upper_wall.fudge_area_weights(w, pi, pr.p_bar)
        info = {}

        # initial data
        if o["initial"] == "exact":
            z0, V0, tau0_l = self._start(h)
            if o["variable"] == "tau":
                tau0 = float(np.max(tau0_l))  # common tau0; each load's V_j0 from the exact map
                V0_l = start_V(self.problem, tau0)
                P0 = start_pdf(self.problem, pi[None, :], pr.p_bar[:, None], tau0)
                info["zeta0"] = self.zeta_from_V(V0_l) if not nofudge else np.full(nl, z0)
            else:
                tau0 = None
                P0 = start_pdf(self.problem, pi[None, :], pr.p_bar[:, None], tau0_l[:, None])
                V0_l = np.full(nl, V0)
                info["zeta0"] = np.full(nl, z0)
        else:
            P0 = np.zeros((nl, m))
            for j, pb in enumerate(pr.p_bar):
                i = min(int(np.floor(pb / h)), n_p - 2)  # p_i <= pb < p_{i+1}
                a = (p[i + 1] - pb) / h
                if i >= 1:
                    P0[j, i - 1] += a / w[i - 1]
                if i + 1 <= m:
                    P0[j, i] += (1.0 - a) / w[i]
            tau0, V0_l = 0.0, np.zeros(nl)
            info["zeta0"] = np.ones(nl)
        self._info0 = info
        self._V0_l = V0_l

        if o["variable"] == "zeta":
            dVdz = pr.dV_dzeta
            t0 = float(np.min(info["zeta0"]))
            t1 = float(self.zeta_out[-1])

            def fun_readable(t, y):
                P = y.reshape(nl, m)
                A = P @ wA + a0
                c = 0.5 * fudge.S(A) * float(dVdz(t))
                return (c[:, None] * laplacian_readable(P, h, order)).ravel()

            def fun(t, y):
                P = y.reshape(nl, m)
                c = 0.5 * fudge.S(P @ wA + a0) * float(dVdz(t))
                return (Lb @ y).reshape(nl, m).__imul__(c[:, None]).ravel()

            def jac(t, y):
                P = y.reshape(nl, m)
                A = P @ wA + a0
                d = 0.5 * float(dVdz(t))
                c = d * fudge.S(A)
                if nofudge:
                    return Lb * c[0]
                cp = d * fudge.dS_dA(A)
                LP = (Lb @ y).reshape(nl, m)
                blocks = [c[j] * Lm + sp.csr_matrix(np.outer(LP[j], cp[j] * wA)) for j in range(nl)]
                return sp.block_diag(blocks, format="csr")

            return MOLSystem(fun, fun_readable, jac, P0.ravel(), t0, t1, nl, m, False)

        # variable == "tau"
        t0 = float(tau0)
        if nofudge:
            half_L = (0.5 * Lb).tocsr()

            def fun_readable(t, y):
                return 0.5 * laplacian_readable(y.reshape(nl, m), h, order).ravel()

            def fun(t, y):
                return half_L @ y

            t1 = float(pr.V(self.zeta_out[-1]))
            return MOLSystem(fun, fun_readable, half_L, P0.ravel(), t0, t1, nl, m, False)

        n = nl * m
        S_max = float(np.max(fudge.S(np.linspace(0.0, 1.0, 2001))))
        V_end = float(pr.V(self.zeta_out[-1]))
        t1 = t0 + (V_end - float(np.min(V0_l))) * S_max * (1.0 + 1e-6) * 1.01
        # Jacobian structure: [[L/2 blocks, 0], [rows -S'/S^2 w on own block, 0]]
        top = sp.hstack([0.5 * Lb, sp.csr_matrix((n, nl))], format="csr")
        rows = np.repeat(np.arange(nl), m)
        cols = np.arange(n)
        bot_pattern = sp.csr_matrix((np.ones(n), (rows, cols)), shape=(nl, n + nl))
        J = sp.vstack([top, bot_pattern], format="csr")
        J.sort_indices()
        bot_start = J.indptr[n]

        def fun_readable(t, y):
            P = y[:n].reshape(nl, m)
            A = P @ wA + a0
            return np.concatenate([0.5 * laplacian_readable(P, h, order).ravel(), 1.0 / fudge.S(A)])

        half_top = (0.5 * Lb).tocsr()

        def fun(t, y):
            out = np.empty_like(y)
            out[:n] = half_top @ y[:n]
            out[n:] = 1.0 / fudge.S(y[:n].reshape(nl, m) @ wA + a0)
            return out

        def jac(t, y):
            A = y[:n].reshape(nl, m) @ wA + a0
            S = fudge.S(A)
            r = -fudge.dS_dA(A) / (S * S)
            data = J.data.copy()
            data[bot_start:] = (r[:, None] * wA[None, :]).ravel()
            return sp.csr_matrix((data, J.indices, J.indptr), shape=J.shape)

        y0 = np.concatenate([P0.ravel(), V0_l])
        return MOLSystem(fun, fun_readable, jac, y0, t0, t1, nl, m, True)

    def _solve_on_engine(self, n: int, rtol: float, atol, integrator: str, frac: float) -> SolverOutput:
        """A moving wall or general coefficients: the front-fixed engine's fluxes on n cells, integrated in V by
        :func:`~persson_fp.solvers.mol.lines.solve_lines`, and its partner at n/2 (time by ``rtol``).  ``atol`` None:
        rtol x 1e-3 of each load's mass in play at the start (``solve_lines``'s ``per_mass``)."""
        pr, o = self.problem, self.opts
        stations = (self.zeta_out, self.V_out)
        zeta0 = general_start(pr, stations, n, o["zeta0"], o["k_domain"], frac, self.name)
        per_mass = atol is None
        atol = rtol * 1e-3 if per_mass else atol
        run = functools.partial(
            solve_lines, rtol=rtol, atol=atol, integrator=integrator, tau0_fraction=frac, per_mass=per_mass
        )
        fine, coarse = run_pair(pr, self.V_out, self.zeta_out, n, zeta0, o["k_domain"], run, self.max_time)
        what = f"|Q(n_p) - Q(n_p/2)|, n_p = {n}, rtol = {rtol:g} (conservative in p; time by rtol)"
        info = {"steps": fine["steps"], "integrator": integrator, "nfev": fine["nfev"], "njev": fine["njev"]}
        return SolverOutput(**finish(pr, n, fine, coarse, what, o["tol"], info, self.name))

    # -- the solve --------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        pr = self.problem
        o = self.opts
        if pr.moving_wall or pr.general:
            if o["integrator"] not in ("BDF", "Radau", "LSODA"):
                raise ValueError("a moving yield wall needs a stiff integrator: 'BDF', 'Radau' or 'LSODA'")
            n = 200 if o["n_p"] is None else o["n_p"]
            self.check_memory(n)  # (Solver.__init__ skips it while n_p is None, the automatic grid)
            atol = o["atol"]  # None: rtol x 1e-3 of each load's mass at the start (solve_lines)
            frac = 0.05 if o["tau0_fraction"] is None else o["tau0_fraction"]
            return self._solve_on_engine(n, o["rtol"], atol, o["integrator"], frac)
        if pr.n_loads > _LOADS_PER_CHUNK and o["variable"] == "tau":
            return self._solve_in_chunks()
        sysm = self.system()
        p, h, w = self._grid_cache
        nl, m = sysm.n_loads, sysm.m
        integ = o["integrator"]
        tau_scale = float(np.max(pr.tau(pr.zeta_max)))
        # default atol ~ rtol x the size of P0 ~ A* / sqrt(tau), per load: a tiny load (A* ~ p_bar / sqrt(tau))
        # keeps its relative accuracy (an atol fixed at 1/sqrt(tau) cost it 5 % at p_bar / sqrt(V) = 1e-8)
        A_min = np.minimum(erf(pr.p_bar / np.sqrt(2.0 * pr.tau_max)), 1.0)
        atol_l = o["rtol"] * 1e-2 * A_min / np.sqrt(tau_scale)
        atol = o["atol"] if o["atol"] is not None else np.repeat(atol_l, m)
        kw = {"method": integ, "rtol": o["rtol"], "atol": atol}
        if integ in _STIFF:
            jac = sysm.jac
            if integ == "LSODA":
                if sp.issparse(jac):
                    dense = jac.toarray()

                    def jac(t, y, d=dense):
                        return d

                else:

                    def jac(t, y, f=jac):
                        return f(t, y).toarray()

            kw["jac"] = jac
        if sysm.augmented:
            atol_v = np.full(sysm.y0.size, 0.0)
            atol_v[: nl * m] = atol
            atol_v[nl * m :] = o["rtol"] * tau_scale * 1e-2
            kw["atol"] = atol_v
        zeta_out = self.zeta_out
        n_z = zeta_out.size

        if o["variable"] == "zeta":
            t_eval = zeta_out
        elif not sysm.augmented:
            t_eval = np.atleast_1d(pr.V(zeta_out)).astype(float)
        else:
            t_eval = None
        if t_eval is not None and t_eval[0] < sysm.t0:
            raise ValueError(f"the start-up ({sysm.t0:.6g}) lies beyond the first output station; lower tau0_fraction")

        # stepped by hand (_ivp_march): no dense output kept, each load's stations on its own rows only
        method = kw.pop("method")
        n = nl * m
        t_end = sysm.t1 if sysm.augmented else float(t_eval[-1])
        # in tau the Jacobian's P part is one Laplacian block per load, shared: factor it once per step
        blocks = (nl, m) if o["variable"] == "tau" else None
        solver = ivp_march.make_solver(method, sysm.fun, sysm.t0, sysm.y0, t_end, blocks=blocks, **kw)
        deadline = time.perf_counter() + self.max_time
        try:
            if sysm.augmented:
                V_out = np.atleast_1d(pr.V(zeta_out)).astype(float)
                pi = p[1:-1]
                wall = pr.upper_wall

                def S_of(P, j):  # S at the area of load j's P (..., m), A_pl from the load balance with a hardness
                    return pr.fudge.S(wall.contact_for_fudge(P, w, pi, pr.p_bar[j]))

                tau_st, P, steps = ivp_march.march_own(
                    solver, n + np.arange(nl), np.arange(n).reshape(nl, m), V_out, S_of, "mol", deadline=deadline
                )
                tau_info = tau_st
            else:
                Y, steps = ivp_march.march_shared(solver, t_eval, "mol", deadline=deadline)
                P = Y.T.reshape(n_z, nl, m)
                tau_info = t_eval if o["variable"] == "tau" else None
        except ivp_march.BudgetExceeded as err:
            raise SolverError(
                f"{err} (max_time = {self.max_time:.3g} s); use a coarser grid or a looser rtol, or pass a "
                "larger max_time (seconds)"
            ) from err
        except RuntimeError as err:
            raise SolverError(f"mol: solve_ivp failed ({err})") from err

        P_full = np.zeros((n_z, nl, o["n_p"]))
        P_full[..., 1:-1] = P
        info = {
            **self._info0,
            "grid": p,
            "h": h,
            "p_max": p[-1],
            "order": o["order"],
            "integrator": integ,
            "variable": o["variable"],
            "nfev": int(solver.nfev),
            "njev": int(solver.njev),
            "nlu": int(solver.nlu),
            "steps": int(steps),
            "t_span": (sysm.t0, float(solver.t)),
            "tau_out": tau_info,
        }
        wq = quadrature_weights(o["n_p"], h, o["order"])
        # a constant hardness: the strip's load balance F_el + sigma A_pl = p_bar gives A_pl (clipped at 0: the
        # quadrature error of F_el may push a vanishing A_pl a little below, -5e-8 measured); None without a wall
        plastic = pr.upper_wall.plastic_from_load(pr.p_bar, P_full @ (wq * p))
        return SolverOutput(p=p, P0=P_full, weights=wq, kind="point", info=info, plastic_area=plastic)

    def _solve_in_chunks(self) -> SolverOutput:
        """Large batches: the loads in chunks of ``_LOADS_PER_CHUNK`` on the grid of the whole batch.

        Memory stays that of one chunk (~35 MB for 250 loads at the default grid) and time linear in the
        number of loads; each chunk meets the tolerances on its own.
        """
        pr, o = self.problem, self.opts
        p, _ = self._grid()  # n_p (automatic: from the whole batch) and p_max of the whole batch
        outs = []
        for a in range(0, pr.n_loads, _LOADS_PER_CHUNK):
            sub = type(self)(pr.with_loads(pr.p_bar[a : a + _LOADS_PER_CHUNK]), zeta_out=self.zeta_out, **o)
            sub._p_max_shared = float(p[-1])
            outs.append(sub._solve())
            del sub
            gc.collect()  # scipy's OdeSolver holds itself in a cycle (its wrapped fun): free the chunk's arrays now
        first = outs[0]
        info = dict(first.info)
        for key in ("nfev", "njev", "nlu", "steps"):
            info[key] = int(sum(out.info[key] for out in outs))
        info["zeta0"] = np.concatenate([np.atleast_1d(out.info["zeta0"]) for out in outs])
        tau = [out.info["tau_out"] for out in outs]
        info["tau_out"] = np.concatenate(tau, axis=1) if np.ndim(tau[0]) == 2 else tau[0]
        info["chunks"] = len(outs)
        plastic = None if first.plastic_area is None else np.concatenate([out.plastic_area for out in outs], axis=1)
        P0 = np.concatenate([out.P0 for out in outs], axis=1)
        return SolverOutput(p=first.p, P0=P0, weights=first.weights, kind="point", info=info, plastic_area=plastic)
