r"""Spectral solver for general coefficients of the form b(p) dV/dzeta: method ``"chebyshev"``.

Solves the Fokker--Planck form of Persson's equation (Xu et al. tutorial, Eq. 'E:Fokker_Planck_Forward') for
:class:`~persson_fp.FokkerPlanckProblem` coefficients :math:`B_2 = b(p)\,dV/d\zeta`,
:math:`B_1 = c(p)\,dV/d\zeta` -- the homogenised theory (b = 1), any pressure-dependent diffusion
``b(p) * dV/dzeta`` and a drift of the same form -- with absorbing walls at p = 0 and p_max.  In V the problem
is autonomous, and :mod:`persson_fp.solvers.engine.collocation` propagates a mapped-Chebyshev discretisation
exactly (one matrix exponential per output station, stacked over loads): the error is that of the grid in p
(spectral: faster than any power of n_p where P is smooth) and of the small-time start at V0 (O(V0^2)).

The form is detected by sampling B2 / (dV/dzeta) and B1 / (dV/dzeta) on a probe grid in p and zeta; other
coefficients are refused (use "fv" or "mol").

Error estimate (``info["error_estimate"]``, per station and load): the differences from a partner run at
3/4 of the degree (the grid) and from one started at 4 V0 divided by 4 (the start; its error scales as V0^2,
so the true ratio is 15), plus twice the mass lost at the far wall and a round-off floor 4 eps n^2 (the error of
the dense exponential grows with the degree; measured ~1e-11 at n = 250).  With ``tol`` the degree is raised
and V0 lowered until the estimate meets it.  Negative ripples of the polynomial below 1e-6 of the peak (in the
tails and next to the walls, within the estimate) are set to 0 in P0; A* and the load are the quadratures of the
polynomial itself (Clenshaw--Curtis, exact for it).
"""

from __future__ import annotations

import math

import numpy as np

from persson_fp.solvers.base import Solver, SolverOutput, check_float, check_int
from persson_fp.solvers.engine import collocation as co

__all__ = ["ChebyshevSolver"]

N_MAX = 400
"""Largest polynomial degree the adaptive loop reaches (a dense 400 x 400 exponential: ~50 ms)."""


class ChebyshevSolver(Solver):
    """Mapped Chebyshev collocation in p, exact propagation in V (see the module docstring).

    Options
    -------
    tol : float, default 1e-8
        Asked accuracy: the estimated L1 error of P0 and the error of A* at every station (as for ``tol``
        of :func:`persson_fp.solve`); the degree and the start are refined until the estimate meets it
        (:class:`~persson_fp.SolverError` if it cannot, at degree ``N_MAX``).
    n_p : int or None
        A fixed polynomial degree in [8, 1000] (no adaptation; the estimate is still reported).
    V0_fraction : float or None
        Start V0 / V(station) in (0, 0.1] (every station starts afresh from the delta); default from ``tol``.
    k_domain : float or None
        Far wall at k_domain unit-diffusion widths sqrt(V_max) beyond the largest load (in the Lamperti
        distance int dp / sqrt(b)); default from ``tol`` (8 to 12).
    """

    name = "chebyshev"
    SUPPORTS = frozenset({"general"})
    OPTIONS = {"tol": 1e-8, "n_p": None, "V0_fraction": None, "k_domain": None}

    def validate(self) -> None:
        o, pr = self.opts, self.problem
        o["tol"] = check_float(o["tol"], "tol", 1e-13, 1e-1)
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
        if pr.fudge.name != "none":
            raise ValueError(
                f"method 'chebyshev' solves fudge-free problems (B2 = b(p) dV/dzeta), got fudge={pr.fudge.name!r}; "
                "use method='sines', 'fv' or 'mol'"
            )
        self._b_ref, self._c_ref = self._separable_form()

    # -- coefficients ---------------------------------------------------------------------------------
    def _raw(self, p, zeta):
        pr = self.problem
        if pr.general:
            return pr.coefficients(p, zeta)
        return None, np.full(np.shape(p), float(pr.dV_dzeta(zeta)))

    def _separable_form(self):
        """(b, c) callables per unit V, after checking B2 = b(p) g(zeta), B1 = c(p) g(zeta) on a probe grid."""
        pr = self.problem
        z_ref = float(pr.zeta_max)
        g_ref = float(pr.dV_dzeta(z_ref))
        if not g_ref > 0:
            raise ValueError("method 'chebyshev' needs dV/dzeta > 0 at zeta_max")
        probe = np.linspace(0.0, pr.p_max(8.0), 33)
        _, b0 = self._raw(probe, z_ref)
        c0 = self._raw(probe, z_ref)[0]
        for z in np.geomspace(1.0 + 1e-9, z_ref, 9):
            g = float(pr.dV_dzeta(z))
            if not g > 0:
                continue
            B1, B2 = self._raw(probe, z)
            bad_b = np.max(np.abs(B2 / g - b0 / g_ref)) > 1e-9 * max(np.max(np.abs(b0 / g_ref)), 1e-300)
            bad_c = B1 is not None and np.max(np.abs(B1 / g - c0 / g_ref)) > 1e-9 * max(
                np.max(np.abs(c0 / g_ref)), np.max(np.abs(b0 / g_ref)) / max(probe[-1], 1e-300), 1e-300
            )
            if bad_b or bad_c:
                which = "B2" if bad_b else "B1"
                raise ValueError(
                    f"method 'chebyshev' needs {which} = (a function of p) x dV/dzeta; {which}(p, zeta) / (dV/dzeta) "
                    f"changes with zeta (at zeta = {z:.6g}); use method='fv' or 'mol'"
                )

        drift = c0 is not None and bool(np.any(c0 != 0.0))

        def coef(p):  # (b, c or None) per unit V, one evaluation of the coefficients
            B1, B2 = self._raw(p, z_ref)
            return B2 / g_ref, (B1 / g_ref if drift else None)

        self._coef = coef

        def b(p):
            return coef(p)[0]

        return b, ((lambda p: coef(p)[1]) if drift else None)

    # -- the solve ------------------------------------------------------------------------------------
    def _domain(self, tol, V):
        """(p_max, k) for the PDF at V: k widths sqrt(V) beyond the largest load in the Lamperti distance."""
        pr, b = self.problem, self._b_ref
        k = self.opts["k_domain"] or float(np.clip(math.sqrt(2.0 * math.log(1.0 / (1e-3 * tol))) + 1.0, 8.0, 12.0))
        pbar = float(np.max(pr.p_bar))
        need = k * math.sqrt(V)
        if self._c_ref is not None:  # a drift moves the PDF by about c V: widen by the largest push outwards
            probe = np.linspace(0.0, pr.p_max(2.0 * k), 65)
            need += max(0.0, float(np.max(self._c_ref(probe) / np.sqrt(np.maximum(b(probe), 1e-300))))) * V
        hi = pbar + math.sqrt(float(b(np.array([pbar]))[0]) * V) * k
        for _ in range(80):
            if float(co.lamperti_distance(b, np.array(pbar), np.array(hi))) >= need:
                return hi, k
            hi = pbar + 1.5 * (hi - pbar)
        raise ValueError(
            "method 'chebyshev': B2 grows so fast in p (faster than p^2) that the pressure reaches any far wall in "
            f"finite V: int dp / sqrt(B2 / (dV/dzeta)) from p_bar to infinity is below {need:.3g} (k_domain = "
            f"{k:.3g} widths sqrt(V)); the answer depends on the far wall -- bound B2 at large p"
        )

    def _run(self, n, frac, p_max):
        """P at the stations: (grids, one per station, P (n_zeta, n_loads, n + 1)).

        Every station k starts afresh from the delta: the small-time start at V0_k = frac x V_k on a grid whose
        nodes cluster for that start (within a few widths sqrt(b V0_k) of p_bar), then one exponential to V_k.
        An early station does not make a later one start narrow: the nodes crowded for a narrow start would
        carry its stiff operator's round-off to the far stations (measured: 5e-10 at zeta_max after a station
        at zeta = 2), and passing a state between grids carries the start's undamped high modes with it.
        """
        pr, b = self.problem, self._b_ref
        pb = pr.p_bar.astype(float)
        b_at = b(pb)
        if np.any(b_at <= 0):
            raise ValueError("method 'chebyshev': B2 vanishes at the load p_bar (the start cannot spread)")
        grids, out = [], None
        far = np.zeros((self.V_out.size, pb.size))
        balance = np.zeros_like(far)
        for k, V in enumerate(self.V_out):
            V0 = frac * float(V)
            grid = co.chebyshev_grid(n, p_max[k], pb, 3.0 * np.sqrt(b_at * V0))
            P = co.start_density(self._coef, grid.p, pb, V0)
            P[:, 0] = P[:, -1] = 0.0
            b_n, c_n = self._coef(grid.p)
            L = co.generator(grid, b_n, c_n)
            mass0 = np.sum(P * grid.w, axis=-1)
            P[:, 1:-1], I = co.propagate_with_integral(L, P[:, 1:-1], float(V) - V0)
            out0, out_far = co.wall_losses(grid, b_n, c_n, I)
            far[k] = np.maximum(out_far, 0.0)
            balance[k] = mass0 - np.sum(P * grid.w, axis=-1) - out0 - out_far  # what left = what crossed a wall
            if out is None:
                out = np.zeros((self.V_out.size,) + P.shape)
            out[k] = P
            grids.append(grid)
        self._far, self._balance = far, balance
        return grids, out

    @staticmethod
    def _stats(grids, P):
        A = np.stack([np.sum(P[k] * g.w, axis=-1) for k, g in enumerate(grids)])
        F = np.stack([np.sum(P[k] * g.w * g.p, axis=-1) for k, g in enumerate(grids)])
        return A, F

    def _compare(self, main, other):
        """(L1 of the difference, |dA|, |dF| / p_bar) per station and load, the other run interpolated."""
        g, P = main
        g2, P2 = other
        L1 = np.stack(
            [np.sum(np.abs(P[k] - co.interpolate(g2[k], P2[k], g[k].p)) * g[k].w, axis=-1) for k in range(len(g))]
        )
        A, F = self._stats(g, P)
        A2, F2 = self._stats(g2, P2)
        return L1, np.abs(A - A2), np.abs(F - F2) / self.problem.p_bar

    def _solve(self) -> SolverOutput:
        o, pr = self.opts, self.problem
        tol = o["tol"]
        doms = [self._domain(tol, float(V)) for V in self.V_out]  # a far wall per station
        p_max, k = np.array([d[0] for d in doms]), doms[0][1]
        frac = o["V0_fraction"] or float(np.clip(0.3 * math.sqrt(tol), 3e-5, 1e-2))
        n = o["n_p"] or int(np.clip(8 + 8 * math.log10(1.0 / tol), 24, N_MAX))
        runs = 0
        while True:
            main = self._run(n, frac, p_max)
            far, balance = self._far, self._balance  # mass out at p_max (from V0 on), mass-balance residual
            grid_part = self._run(max(8, int(round(0.75 * n))), frac, p_max)
            start_part = self._run(n, 4.0 * frac, p_max)
            runs += 3
            L1_g, dA_g, dF_g = self._compare(main, grid_part)
            L1_s, dA_s, dF_s = self._compare(main, start_part)
            A, F = self._stats(*main)
            far_err = 2.0 * far
            floor = 4.0 * np.finfo(float).eps * n * n  # round-off of the dense exponential
            est = {
                "L1": L1_g + L1_s / 4.0 + far_err + floor,
                "contact_area": dA_g + dA_s / 4.0 + far_err + floor,
                # (relative to p_bar; the round-off of P far out is weighted by p there: measured 1.5e-10 at
                # p_max = 160 p_bar, n = 157)
                "load": dF_g + dF_s / 4.0 + (far_err + floor * np.maximum(1.0, 0.1 * p_max[:, None] / pr.p_bar)),
            }
            worst = max(float(np.max(est[q])) for q in ("L1", "contact_area"))
            if o["n_p"] is not None or worst <= tol:
                break
            grid_worst = max(float(np.max(v)) for v in (L1_g, dA_g))
            start_worst = max(float(np.max(v)) for v in (L1_s, dA_s)) / 4.0
            if start_worst > grid_worst and frac > 1e-6:
                frac /= 4.0
                n = int(math.ceil(1.15 * n))  # a narrower start needs a few more nodes
            else:
                n = int(math.ceil(1.3 * n))
            if n > N_MAX:
                from persson_fp.results.invariants import SolverError

                raise SolverError(
                    f"chebyshev: the error estimate {worst:.3e} exceeds tol = {tol:.3g} at degree {N_MAX}; "
                    "loosen tol or use method='fv'"
                )
        grids, P = main
        info = {
            "grid": {
                "n_p": n,
                "p_max": p_max,
                "k_domain": k,
                "mapping": "p = centre + eps sinh(a1 + h (x + 1)), x Chebyshev, per load",
            },
            "V0_fraction": frac,
            "zeta0": self.zeta_from_V(frac * self.V_out),
            "runs": runs,
            "error_estimate": {
                "L1": est["L1"],
                "elastic_area": est["contact_area"],
                "plastic_area": np.zeros_like(A),
                "noncontact_area": est["contact_area"],
                "load": est["load"],
                "method": "|run - run at 3/4 degree| + |run - run from 4 V0| / 4 + 2 x far-wall mass + 4 eps n^2",
            },
            "far_wall_mass": far,
            "mass_balance_residual": float(np.max(np.abs(balance))),
        }
        if pr.n_loads == 1:  # the last station's grid (the widest domain), earlier stations' polynomials on it
            # (at the nodes: spectrally accurate values, 0 beyond their far wall; A* and the load come from each
            # station's own grid)
            g0 = grids[-1]
            p, w = g0.p[0], g0.w[0]
            Pout = np.stack([P[k] if g is g0 else co.interpolate(g, P[k], g0.p) for k, g in enumerate(grids)])
        else:  # a common output grid: plain Chebyshev of twice the degree (areas and loads from the own grids)
            m = 2 * n
            pm = float(p_max[-1])
            common = co.chebyshev_grid(m, pm, np.array([0.5 * pm]), np.array([1e6 * pm]))
            p, w = common.p[0], common.w[0]
            q = np.broadcast_to(p, (pr.n_loads, p.size))
            Pout = np.stack([co.interpolate(grids[kk], P[kk], q) for kk in range(P.shape[0])])
        if pr.n_loads == 1:  # the output grid's map
            info["grid"].update(centre=g0._map[2], eps=g0._map[3])
        # the polynomial's ripple where P is ~0 (tails, next to the walls) is within the estimate: set to 0
        peak = np.max(Pout, axis=-1, keepdims=True)
        ripple = (Pout < 0) & (Pout > -1e-6 * peak)
        Pout = np.where(ripple, 0.0, Pout)
        info["ripple_zeroed"] = int(np.count_nonzero(ripple))
        return SolverOutput(p=p, P0=Pout, weights=w, kind="point", info=info, contact_area=A, load=F)
