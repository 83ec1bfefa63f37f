r"""Finite volumes in p, θ-schemes (and TR-BDF2) in the effective variance.

The method
----------
Persson's equation (``E:diffusion_equ`` with ``eq:new_B2``; Persson 2001 [1]_)

.. math::  \frac{\partial P_0}{\partial\zeta} = \tfrac12 B_2(\zeta)\,\frac{\partial^2 P_0}{\partial p^2},
           \qquad B_2 = S(A^*)\,\frac{dV}{d\zeta}, \qquad A^* = \int_0^{p_{max}} P_0\,dp \quad (\texttt{eq:Area})

is written in the effective variance :math:`d\tau = S(A^*)\,dV`: every step is a step
:math:`\Delta\tau` of the plain heat equation :math:`\partial_\tau P_0 = \tfrac12\partial_p^2 P_0`,
and the fudge factor only decides how large :math:`\Delta\tau` is for a given :math:`\Delta V`
(the *coupling*, below).

*Space.*  ``n_p`` cells of width :math:`\Delta p = p_{max}/n_p` on :math:`[0, p_{max}]`, unknowns the
cell averages :math:`\bar P_i`.  The flux through face :math:`i+\tfrac12` is
:math:`F_{i+1/2} = -\tfrac12(\bar P_{i+1}-\bar P_i)/\Delta p` and
:math:`d\bar P_i/d\tau = -(F_{i+1/2}-F_{i-1/2})/\Delta p` (:func:`~persson_fp.solvers.fv.rhs`).  Both walls absorb
(:math:`P_0 = 0` at the face): ghost values :math:`\bar P_{-1} = -\bar P_0`,
:math:`\bar P_{n_p} = -\bar P_{n_p-1}`.  Because the exact solution is odd about p = 0
(image solution, ``eq:P0_solution``), the ghost cell *is* the cell average of the odd extension,
so the wall costs no order: the scheme is 2nd order in p everywhere.  The wall fluxes
:math:`\bar P_0/\Delta p` and :math:`\bar P_{n_p-1}/\Delta p` are integrated with the same
time-stepping weights as the cells, so :math:`\sum_i \bar P_i\,\Delta p + J_0 + J_{max}` is conserved
to round-off and :math:`A^*(\zeta_0) - J_0` is reported as ``contact_area_flux``; the far-wall
loss :math:`J_{max}` is reported in ``info["far_wall_mass"]``.  The load ``eq:Load_equilibrium``
is conserved by the p = 0 wall exactly, so its drift measures the far-wall and truncation error.

*Time.*  A θ-step with the tridiagonal operator :math:`L` (:func:`~persson_fp.solvers.fv.banded_operator`),

.. math::  (I - \theta\,\Delta\tau\,L)\,P^{n+1} = (I + (1-\theta)\,\Delta\tau\,L)\,P^n ,

with θ = 0 ("explicit", stable for :math:`r = \tfrac12\Delta\tau/\Delta p^2 \le \tfrac12`),
θ = 1/2 ("crank-nicolson"), θ = 1 ("implicit", backward Euler), "rannacher" [3]_ (θ = 1/2 after
``rannacher_steps`` steps each done as two backward-Euler half steps) and "tr-bdf2" (an L-stable
2nd-order one-step method [2]_: a trapezoidal stage over :math:`\gamma\Delta\tau` then BDF2, with
:math:`\gamma = 2-\sqrt2` so that both stages share one matrix; from ``initial="delta"`` its first
``rannacher_steps`` steps are backward-Euler half steps, because L-stability does not make it positive:
its amplification factor is negative for :math:`\Delta\tau|\lambda| \gtrsim 2.4`, and no 2nd-order
one-step scheme is positive for every step size).  All loads are advanced together
(``P`` has shape ``(n_loads, n_p)``) on one grid sized by the largest load: when all loads share
:math:`\Delta\tau` (S = 1) one factorisation (LAPACK ``pttrf``; the matrix is symmetric positive
definite) serves all of them and is re-used while :math:`\Delta\tau` repeats (uniform steps);
otherwise the per-load systems are stacked into one block-tridiagonal solve (``ptsv``),
O(n_p n_loads) per step.  This is the ``linalg="banded"`` path; the default is the spectral one below.

*Space, 4th order* (``space="compact4"``, the default).  The same fluxes with the compact mass
matrix :math:`M = \mathrm{tridiag}(1, 10, 1)/12` (``M dP/dtau = L P``, odd ghosts again), which is
the 4th-order reconstruction of the face derivative from cell averages; ``space="fv2"`` is
M = I (2nd order).  Every θ-step above reads :math:`(M - \theta\Delta\tau L)P^{n+1} =
(M + (1-\theta)\Delta\tau L)P^n`.  Here :math:`\sum_i (MP)_i\Delta p + J_0 + J_{max}` is the
conserved quantity, and ``contact_area_flux`` adds the known edge term
:math:`\tfrac16\Delta p\,(\bar P_0 - \bar P_0^{\,start})`, so the mass balance still closes to round-off.
*Stepping* (measured on the reference problem, ``benchmarks/fv_timing.py``): nodes uniform in the
effective variance ("tau") beat geometric and uniform-in-zeta nodes by 3-4x in error at equal
cost at zeta_max, because the error made early is damped by the later diffusion, but they starve
early output stations; the default "graded" is uniform in tau + 0.05 tau_max ln tau: within 4 %
of "tau" at zeta_max and 30x better at the worst of 24 stations.

*Coupling of the fudge factor* (``eq:new_B2``), with :math:`A^*` always the numerical
:math:`\sum\bar P_i\Delta p`:

- ``"lagged"``: :math:`\Delta\tau = S(A^*_n)\,\Delta V` (1st order; default of "explicit" and "implicit").
- ``"predictor"``: Heun, :math:`A^p = A^*_n - \Delta V\,S(A^*_n)\,b_n` from the current wall flux
  :math:`b_n`, then :math:`\Delta\tau = \tfrac12\Delta V\,(S(A^*_n)+S(A^p))` (2nd order,
  one solve per step; default of "crank-nicolson", "rannacher" and "tr-bdf2").
- ``"picard"``: the trapezoidal rule :math:`\Delta\tau = \tfrac12\Delta V\,(S(A^*_n)+S(A^*_{n+1}))`
  iterated to ``picard_tol`` (starting from the predictor; 2nd order).

Without a fudge factor :math:`\Delta\tau = \Delta V` exactly and the coupling does nothing.

References
----------
.. [1] B.N.J. Persson, J. Chem. Phys. 115 (2001) 3840 (``E:diffusion_equ``).
.. [2] R.E. Bank et al., "Transient simulation of silicon devices and circuits", IEEE Trans.
       CAD 4 (1985) 436 (TR-BDF2).
.. [3] R. Rannacher, "Finite element solution of diffusion problems with irregular data",
       Numer. Math. 43 (1984) 309.
"""

from __future__ import annotations

import numpy as np

from persson_fp.results.solution import InstabilityError
from persson_fp.solvers.base import Solver, SolverOutput, StationRecorder, check_float, check_int, zeta_of
from persson_fp.solvers.front_fixed.estimate import finish, run_pair
from persson_fp.solvers.front_fixed.models import model_of
from persson_fp.solvers.front_fixed.start import general_start
from persson_fp.solvers.fv.dst import dst_eigenvalues  # noqa: F401
from persson_fp.solvers.fv.operators import (  # noqa: F401  (re-exported: the operators are part of the fv API)
    COUPLINGS,
    LINALGS,
    SPACES,
    _tri_matvec,
    _Tridiag,
    apply_mass,
    apply_operator,
    banded_operator,
    march_result,
    rhs,
    wall_flux,
)
from persson_fp.solvers.fv.spectral import DSTMarch
from persson_fp.solvers.fv.stepping import STEPPINGS, step_kind, step_nodes
from persson_fp.solvers.schemes import SCHEMES, TRBDF2_A, TRBDF2_B, TRBDF2_GAMMA, TRBDF2_W
from persson_fp.theory.fudge import NoFudge
from persson_fp.theory.image import tail_mass

__all__ = ["FiniteVolumeSolver", "SCHEMES", "rhs", "banded_operator", "apply_operator", "dst_eigenvalues"]


class FiniteVolumeSolver(Solver):
    r"""Cell-centred finite volumes with θ-schemes / TR-BDF2 (see the module docstring).

    Options
    -------
    n_p : int, default 200
        Cells on [0, p_max].
    n_steps : int, default 100
        Steps from zeta0 to the last output station (shared over the stations' segments).
    scheme : str, default "tr-bdf2"
        "explicit" | "implicit" | "crank-nicolson" | "rannacher" | "tr-bdf2".
    stepping : str, default "graded"
        Node placement, by the closed-form tau(V) of each load (the coupling still uses the
        numerical A*): "graded" (uniform in s = tau + 0.05 tau_max ln tau: geometric while tau is
        small, uniform in tau later), "tau" (uniform in the effective variance), "geometric"
        (uniform in ln V) or "zeta" (uniform in zeta).  Measured on the reference problem with
        the default 100 steps, ``benchmarks/fv_stepping.py`` (L1 at zeta_max / worst over the
        stations): one station 5.8e-6 ("graded") vs 5.6e-6 ("tau"); 24 stations from zeta = 1.5:
        8.2e-6 / 7.4e-4 vs 6.7e-6 / 2.1e-2 ("tau") and 5.7e-5 / 1.3e-3 ("geometric").
        Uniform-in-tau steps are the cheapest for zeta_max alone (early errors are damped by the
        later diffusion) but starve early stations; the grading keeps the relative step dtau/tau
        bounded near the start.
    space : str, default "compact4"
        "compact4" (4th order in p) or "fv2" (2nd order in p, M = I).
    coupling : str, default "auto"
        "lagged" | "predictor" | "picard"; "auto" is the scheme's own (``SCHEMES``).
    picard_tol, picard_maxiter : float, int
        Relative tolerance on dtau and iteration cap of ``coupling="picard"``.
    initial : str, default "exact"
        "exact": exact cell averages at zeta0; "delta": one cell of mass 1 at p_bar at zeta = 1.
    zeta0, tau0_fraction : float
        Start of "exact": zeta0 given, else where tau = ``tau0_fraction`` tau(zeta_max) (largest
        load; lowered to half the first station's tau if needed).  The start is exact, so zeta0
        enters the error only through the steps spent after it.
    k_domain : float, default 8
        p_max = max(p_bar) + k_domain sqrt(tau(zeta_max)) (``ContactProblem.p_max``).
    rannacher_steps : int, default 2
        Steps of "rannacher", and of "tr-bdf2" from ``initial="delta"``, done as two backward-Euler
        half steps (damps the rough start; TR-BDF2's amplification factor is negative for large
        steps, so from a one-cell delta it would ring: -0.41 of the peak at r >= 36 without it).
    allow_unstable : bool, default False
        Let "explicit" run past r = 1/2 (then an :class:`~persson_fp.InstabilityError` is expected).
    check_every : int, default 10
        Steps between stability checks (NaN, mass growth, max ``|P0|`` growth; the l2 norm of P0 on the
        "dst" path).
    tol : float, optional
        Moving yield wall and general coefficients only: raise :class:`~persson_fp.SolverError` when the error
        estimate of the areas (Richardson, plus the start-up and far-wall parts for general coefficients) or the
        load residual beyond its estimate exceeds ``tol`` (the estimate is always in ``info["error_estimate"]``).
    linalg : str, default "auto"
        "dst": the spectral fast path (the same discrete solution to round-off, see the module
        docstring); "banded": the tridiagonal solves (readable reference); "auto": "dst" whenever
        it is exact for the chosen options, which is every combination this solver offers.
    """

    name = "fv"
    SUPPORTS = frozenset({"hardness", "moving_wall", "general"})
    OPTIONS = {
        "n_p": 200,
        "n_steps": 100,
        "scheme": "tr-bdf2",
        "stepping": "graded",
        "coupling": "auto",
        "picard_tol": 1e-12,
        "picard_maxiter": 20,
        "initial": "exact",
        "zeta0": None,
        "tau0_fraction": 0.05,
        "k_domain": 8.0,
        "space": "compact4",
        "rannacher_steps": 2,
        "allow_unstable": False,
        "check_every": 10,
        "linalg": "auto",
        "tol": None,
    }

    def validate(self) -> None:
        o = self.opts
        o["n_p"] = check_int(o["n_p"], "n_p", 4)
        o["n_steps"] = check_int(o["n_steps"], "n_steps", 1)
        for key, allowed in (
            ("scheme", tuple(SCHEMES)),
            ("stepping", STEPPINGS),
            ("coupling", COUPLINGS),
            ("initial", ("exact", "delta")),
            ("space", tuple(SPACES)),
            ("linalg", LINALGS),
        ):
            if o[key] not in allowed:
                raise ValueError(f"{key} must be one of {list(allowed)}, got {o[key]!r}")
        o["picard_tol"] = check_float(o["picard_tol"], "picard_tol", 0.0, 1.0)
        o["picard_maxiter"] = check_int(o["picard_maxiter"], "picard_maxiter", 1)
        o["rannacher_steps"] = check_int(o["rannacher_steps"], "rannacher_steps", 0)
        o["check_every"] = check_int(o["check_every"], "check_every", 1)
        if o["tol"] is not None:
            o["tol"] = check_float(o["tol"], "tol", 1e-15, 1.0, lo_open=False)
        self.validate_start_options()
        # the engine, chosen once: the general one (persson_fp.solvers.front_fixed.moving_wall, .engine) or the march
        pr = self.problem
        self._engine = "front-fixed" if pr.moving_wall or pr.general else "march"

    def memory_options(self) -> dict:
        """The engine's memory model (no trajectory kept on the front-fixed engine, general coefficients sampled on
        its grid; :data:`MEMORY_MODELS`)."""
        return {"front_fixed": self._engine == "front-fixed", "general": bool(self.problem.general)}

    # -- set-up --------------------------------------------------------------------------------
    def _start(self):
        """(zeta0, V0, P_init (n_loads, n_p), A_init (n_loads,)) on the grid ``self.edges``."""
        pr = self.problem
        z0, V0, P, A = self.initial_cell_averages(self.edges)
        self._tau0 = np.asarray(pr.tau_of_V(V0), dtype=float).reshape(pr.n_loads)
        self._hard = pr.hardness is not None
        self._A_pl0 = np.zeros(pr.n_loads)
        if self._hard and self.opts["initial"] == "exact":  # the yield wall may have absorbed a little already
            self._A_pl0 = np.asarray(self.exact_at(z0).plastic_area, dtype=float).reshape(pr.n_loads)
        return z0, V0, P, A

    # -- the run ---------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        o, pr = self.opts, self.problem
        if self._engine == "front-fixed":  # (chosen in validate)
            return self._solve_moving_wall()
        scheme = SCHEMES[o["scheme"]]
        coupling = scheme.coupling if o["coupling"] == "auto" else o["coupling"]
        no_fudge = isinstance(pr.fudge, NoFudge)
        S = pr.fudge.S

        self.n_p = N = o["n_p"]
        self.edges, self.dp = self.cell_grid(N)
        dp, p_max = self.dp, self.edges[-1]
        p = 0.5 * (self.edges[1:] + self.edges[:-1])

        linalg = "banded" if o["linalg"] == "banded" else "dst"  # dst is exact for every option here
        self.zeta0, V0, P, A0 = self._start()
        V_nodes, station_idx = step_nodes(pr, o, self.zeta0, V0, self.zeta_out, self.V_out)
        n_steps = V_nodes.shape[0] - 1

        space = o["space"]
        compact = space != "fv2"
        r_limit = 1.0 / 3.0 if compact else 0.5  # explicit: dtau max|eig(M^-1 L)| <= 2
        w_edge = 1.0 - SPACES[space][0]  # sum(M P) = sum(P) - w_edge (P_0 + P_-1)
        # explicit-scheme limit, checked up front with the largest possible dtau
        if scheme.theta == 0.0:
            S_hi = 1.0 if no_fudge else float(np.max(S(np.linspace(0.0, 1.0, 201))))
            r_pred = 0.5 * S_hi * float(np.max(np.diff(V_nodes, axis=0))) / dp**2
            if r_pred > r_limit and not o["allow_unstable"]:
                raise ValueError(
                    f"explicit scheme: r = dtau/(2 dp^2) = {r_pred:.4g} exceeds the stability limit "
                    f"{r_limit:.4g} ({space}); raise n_steps to >= {int(np.ceil(n_steps * r_pred / r_limit))}, "
                    "lower n_p, or use "
                    "scheme='tr-bdf2' / 'implicit' (or pass allow_unstable=True)"
                )

        P_far0 = P[:, -1].copy()
        if linalg == "dst":
            march = DSTMarch(pr, o, self.zeta_out, self.dp, self._A_pl0)
            res = march.march(P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge)
        else:
            res = self._march_banded(P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge)
        P_out, A_out, Af_out = res["P_out"], res["A_out"], res["Af_out"]
        JN, r_max, dtau_total = res["JN"], res["r_max"], res["dtau_total"]

        # the mass the exact solution has beyond the far cut (none at a yield wall: what it absorbs is plastic area)
        tail = pr.upper_wall.lost_mass(tail_mass(p_max, pr.p_bar, self.tau_out[-1]))
        info = {
            "grid": {"n_p": N, "p_max": p_max, "dp": dp},
            "edges": self.edges,
            "steps": n_steps,
            "zeta0": self.zeta0,
            "scheme": o["scheme"],
            "stepping": o["stepping"],
            "coupling": "exact (S = 1)" if no_fudge else coupling,
            "order_tau": scheme.order,
            **res["counters"],
            "r_max": r_max,
            "far_wall_mass": float(np.max(pr.upper_wall.lost_mass(JN))),
            "tail_mass_exact": float(np.max(np.abs(tail))),
            "tau_numerical": dtau_total + (0.0 if o["initial"] == "delta" else self._tau0),
            "k_domain": o["k_domain"],
            "space": space,
            "order_p": 4 if compact else 2,
        }
        return SolverOutput(
            p=p,
            P0=P_out,
            weights=np.full(N, dp),
            kind="cell",
            info=info,
            contact_area=A_out,
            contact_area_flux=Af_out,
            # A_pl: the flux absorbed at the yield wall plus the compact scheme's edge term of that wall (so that
            # A_el + A_pl + A_non is conserved to round-off; 0 for fv2)
            plastic_area=pr.upper_wall.plastic_area(
                self._A_pl0 + res["JN_out"] - w_edge * dp * (P_out[:, :, -1] - P_far0)
            ),
        )

    # -- the reference march: tridiagonal solves in p -------------------------------------------
    def _march_banded(self, P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge) -> dict:
        """The time loop with LAPACK tridiagonal solves (the readable reference of the DST march, ``DSTMarch``)."""
        o, pr = self.opts, self.problem
        no_fudge = isinstance(pr.fudge, NoFudge)
        S = pr.fudge.S
        m, N = P.shape
        dp = self.dp
        k = 0.5 / dp**2
        compact = space != "fv2"
        n_steps = V_nodes.shape[0] - 1
        solver = _Tridiag(N, m, k, space)
        m_d, m_o = SPACES[space]
        MP = np.empty_like(P)
        P_edge0 = P[:, 0].copy()
        mass = P.sum(axis=-1) * dp
        J0 = np.zeros(m)  # absorbed through p = 0 since zeta0
        JN = np.zeros(m)  # lost through p = p_max
        rec = StationRecorder(station_idx, P_out=(m, N), A_out=(m,), Af_out=(m,), JN_out=(m,))
        hard, A_pl0 = self._hard, self._A_pl0
        sup0 = np.max(np.abs(P), axis=-1)
        # the checks watch the conserved sum(M P) dp (= A* - w_edge dp (P_0 + P_-1)): with the compact mass
        # matrix A* itself may rise a little while the wall cells change fast (a delta start), stably
        mass_prev = mass - w_edge * dp * (P[:, 0] + P[:, -1])
        picard_iters = 0
        r_max = 0.0
        dtau_total = np.zeros(m)

        def theta_step(P, dtau, theta):
            """One θ-step of size dtau (per load); returns (P_new, dJ0, dJN)."""
            b0, bN = wall_flux(P, dp)
            ck = ((1.0 - theta) * k) * (dtau if m > 1 else dtau[0])
            if m > 1:
                ck = ck[:, None]
            # (M + (1 - theta) dtau L) P in one stencil pass
            Bv = _tri_matvec(P, m_o + ck, m_d - 2.0 * ck, m_d - m_o - 3.0 * ck, np.empty_like(P))
            Pn = solver.solve(theta * dtau, Bv) if (theta > 0.0 or compact) else Bv
            c0, cN = wall_flux(Pn, dp)
            return (
                Pn,
                dtau * (theta * c0 + (1.0 - theta) * b0),
                dtau * (theta * cN + (1.0 - theta) * bN),
            )

        def step(P, dtau, n):
            """One step of the chosen scheme: (P_new, dJ0, dJN)."""
            kind = step_kind(o, n)
            if kind == "tr-bdf2":
                Ps, j0s, jNs = theta_step(P, TRBDF2_GAMMA * dtau, 0.5)
                apply_mass(TRBDF2_A * Ps - TRBDF2_B * P, space, out=MP)
                Pn = np.ascontiguousarray(solver.solve(TRBDF2_W * dtau, MP))
                c0, cN = wall_flux(Pn, dp)
                return Pn, TRBDF2_A * j0s + TRBDF2_W * dtau * c0, TRBDF2_A * jNs + TRBDF2_W * dtau * cN
            if kind == "be-halves":
                Ph, a0, aN = theta_step(P, 0.5 * dtau, 1.0)
                Pn, b0_, bN_ = theta_step(np.ascontiguousarray(Ph), 0.5 * dtau, 1.0)
                return Pn, a0 + b0_, aN + bN_
            return theta_step(P, dtau, scheme.theta)

        dtau_prev = None
        for n in range(n_steps):
            dV = V_nodes[n + 1] - V_nodes[n]
            if no_fudge:
                dtau = dV.copy()
                if dtau_prev is not None and np.all(np.abs(dtau - dtau_prev) <= 1e-12 * dtau):
                    dtau = dtau_prev  # uniform steps: keep the factorisation (a 1e-12 relative shift)
            else:  # S at the contact area: A_el (+ A_pl with a hardness wall)
                total = mass + (A_pl0 + JN if hard else 0.0)
                Sn = S(np.minimum(total, 1.0))
                if coupling == "lagged":
                    dtau = Sn * dV
                else:
                    b = (P[:, 0] + (0.0 if hard else P[:, -1])) / dp
                    A_pred = np.clip(total - dV * Sn * b, 0.0, 1.0)
                    dtau = 0.5 * dV * (Sn + S(A_pred))
            Pn, dJ0, dJN = step(P, dtau, n)
            if coupling == "picard" and not no_fudge:
                for _ in range(o["picard_maxiter"]):
                    picard_iters += 1
                    new_mass = np.clip(total - dJ0 - (0.0 if hard else dJN), 0.0, 1.0)
                    dtau_new = 0.5 * dV * (Sn + S(new_mass))
                    if np.max(np.abs(dtau_new - dtau)) <= o["picard_tol"] * np.max(dtau):
                        dtau = dtau_new
                        break
                    dtau = dtau_new
                    Pn, dJ0, dJN = step(P, dtau, n)
            r_max = max(r_max, 0.5 * float(np.max(dtau)) / dp**2)
            if scheme.theta == 0.0 and r_max > r_limit and not o["allow_unstable"]:
                raise ValueError(
                    f"explicit scheme: r = dtau/(2 dp^2) = {r_max:.4g} exceeds the stability limit {r_limit:.4g} "
                    "(the fudge factor enlarged dtau); raise n_steps or use an implicit scheme"
                )
            dtau_prev = dtau
            P = np.ascontiguousarray(Pn)
            J0 += dJ0
            JN += dJN
            dtau_total += dtau
            mass = P.sum(axis=-1) * dp
            if (n + 1) % o["check_every"] == 0 or n + 1 == n_steps:
                remedy = "raise n_steps or use scheme='tr-bdf2'"
                cons = mass - w_edge * dp * (P[:, 0] + P[:, -1])
                try:
                    self.check_state(P, cons, mass_prev, np.nan, "fv/" + o["scheme"], remedy)
                except InstabilityError:  # say where (the root find costs only when it fails)
                    z_now = float(zeta_of(pr, float(V_nodes[n + 1, 0]))[0])
                    self.check_state(P, cons, mass_prev, z_now, "fv/" + o["scheme"], remedy)
                sup = np.max(np.abs(P), axis=-1)
                if np.any(sup > 2.0 * sup0 + 1e-300):
                    z_now = float(zeta_of(pr, float(V_nodes[n + 1, 0]))[0])
                    raise InstabilityError(
                        f"fv/{o['scheme']}: max |P0| grew by a factor {np.max(sup / sup0):.3g} by zeta = "
                        f"{z_now:.6g} (the heat equation cannot do that; r = {r_max:.3g}); {remedy}"
                    )
                mass_prev = cons
            if n + 1 in rec:
                Af = A0 - J0 + w_edge * dp * (P[:, 0] - P_edge0)
                rec.record(n + 1, P_out=P, A_out=mass, Af_out=Af, JN_out=JN)
        return march_result(
            rec,
            JN,
            r_max,
            dtau_total,
            {
                "linalg": "banded",
                "tridiagonal_solves": solver.solves,
                "factorizations": solver.factorizations,
                "picard_iterations": picard_iters,
                "trajectory_sweeps": 0,
            },
        )

    def _solve_moving_wall(self) -> SolverOutput:
        o = self.opts
        if o["scheme"] == "explicit":
            raise ValueError("scheme='explicit' is not offered for a moving yield wall; use 'tr-bdf2' (default)")
        scheme = "crank-nicolson" if o["scheme"] == "rannacher" else o["scheme"]
        coupling = "predictor" if o["coupling"] in ("auto", "picard") else o["coupling"]
        damped = o["rannacher_steps"] if o["scheme"] in ("rannacher", "tr-bdf2") else 0
        # general coefficients: a start the drift has not carried beyond a wall, and a drift the cells resolve there
        pr = self.problem
        zeta0 = general_start(
            pr, (self.zeta_out, self.V_out), o["n_p"], o["zeta0"], o["k_domain"], o["tau0_fraction"], self.name
        )
        n, n_steps, frac = o["n_p"], o["n_steps"], o["tau0_fraction"]

        def run(mw, V_st, V0, level):  # the pair: (n, n_steps) and (n/2, n_steps/2)
            return mw.solve(V_st, max(n_steps // 2**level, 2), scheme, coupling, damped, frac, V0)

        try:
            fine, coarse = run_pair(pr, self.V_out, self.zeta_out, n, zeta0, o["k_domain"], run, self.max_time)
        except np.linalg.LinAlgError as err:  # LAPACK's banded solve of I - c L (the engine's implicit step)
            model_of(pr).singular_step(err, self.name, pr)
        what = f"|Q(n_p, n_steps) - Q(n_p/2, n_steps/2)|, n_p = {n}, n_steps = {n_steps} (conservative)"
        info = {
            "steps": fine["steps"],
            "scheme": scheme,
            "coupling": "exact (S = 1)" if isinstance(pr.fudge, NoFudge) else coupling,
        }
        return SolverOutput(**finish(pr, n, fine, coarse, what, o["tol"], info, self.name))
