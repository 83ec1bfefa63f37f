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
so the true ratio is 15), plus twice the mass lost at the far wall.  With ``tol`` the degree and V0 are raised
until the estimate meets it.  Negative ripples of the polynomial below 1e-6 of the peak (in the tails and next
to the walls, within the estimate) are set to 0 in P0; A* and the load are the quadratures of the polynomial
itself (Clenshaw--Curtis, exact for it).
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
        Asked accuracy: the estimated L1 error of P0 and the area and load errors (relative to p_bar) at
        every station; the degree and the start are raised until the estimate meets it
        (:class:`~persson_fp.SolverError` if it cannot, at degree ``N_MAX``).
    n_p : int or None
        A fixed polynomial degree in [8, 1000] (no adaptation; the estimate is still reported).
    V0_fraction : float or None
        Start V0 / V(first station) in (0, 0.5]; default from ``tol``.
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
            o["V0_fraction"] = check_float(o["V0_fraction"], "V0_fraction", 0.0, 0.5)
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

        def b(p):
            return self._raw(p, z_ref)[1] / g_ref

        c = None
        if c0 is not None and np.any(c0 != 0.0):

            def c(p):
                return self._raw(p, z_ref)[0] / g_ref

        return b, c

    # -- the solve ------------------------------------------------------------------------------------
    def _domain(self, tol):
        pr, b = self.problem, self._b_ref
        k = self.opts["k_domain"] or float(np.clip(math.sqrt(2.0 * math.log(1.0 / (1e-3 * tol))) + 1.0, 8.0, 12.0))
        pbar = float(np.max(pr.p_bar))
        need = k * math.sqrt(pr.V_max)
        if self._c_ref is not None:  # a drift moves the PDF by about c V: widen by the largest push outwards
            probe = np.linspace(0.0, pr.p_max(2.0 * k), 65)
            need += max(0.0, float(np.max(self._c_ref(probe) / np.sqrt(np.maximum(b(probe), 1e-300))))) * pr.V_max
        hi = pbar + math.sqrt(float(b(np.array([pbar]))[0]) * pr.V_max) * k
        for _ in range(80):
            if float(co.lamperti_distance(b, np.array(pbar), np.array(hi))) >= need:
                return hi, k
            hi = pbar + 1.5 * (hi - pbar)
        raise ValueError("method 'chebyshev': B2 grows too fast in p to bound the domain (no far wall found)")

    def _run(self, n, V0, p_max):
        """P at the stations on one grid: (grid, P (n_zeta, n_loads, n + 1))."""
        pr, b = self.problem, self._b_ref
        pb = pr.p_bar.astype(float)
        b_at = b(pb)
        if np.any(b_at <= 0):
            raise ValueError("method 'chebyshev': B2 vanishes at the load p_bar (the start cannot spread)")
        grid = co.chebyshev_grid(n, p_max, pb, 3.0 * np.sqrt(b_at * V0))
        P0 = co.start_density(b, self._c_ref, grid.p, pb, V0, float(np.max(pb)))
        L = co.generator(grid, b(grid.p), None if self._c_ref is None else self._c_ref(grid.p))
        dV = np.diff(np.concatenate(([V0], self.V_out)))
        inner = co.propagate(L, P0[:, 1:-1], dV)
        P = np.zeros((dV.size,) + grid.p.shape)
        P[:, :, 1:-1] = inner
        return grid, P

    def _stats(self, grid, P):
        A = np.einsum("zln,ln->zl", P, grid.w)
        F = np.einsum("zln,ln->zl", P, grid.w * grid.p)
        return A, F

    def _compare(self, main, other):
        """(L1 of the difference, |dA|, |dF| / p_bar) per station and load, the other run interpolated."""
        g, P = main
        g2, P2 = other
        Q = np.stack([co.interpolate(g2, P2[k], g.p) for k in range(P.shape[0])])
        L1 = np.einsum("zln,ln->zl", np.abs(P - Q), g.w)
        A, F = self._stats(g, P)
        A2, F2 = self._stats(g2, P2)
        return L1, np.abs(A - A2), np.abs(F - F2) / self.problem.p_bar

    def _solve(self) -> SolverOutput:
        o, pr = self.opts, self.problem
        tol = o["tol"]
        p_max, k = self._domain(tol)
        V_first = float(self.V_out[0])
        frac = o["V0_fraction"] or float(np.clip(0.3 * math.sqrt(tol), 3e-5, 1e-2))
        n = o["n_p"] or int(np.clip(12 + 9 * math.log10(1.0 / tol), 24, N_MAX))
        runs = 0
        while True:
            V0 = frac * V_first
            main = self._run(n, V0, p_max)
            grid_part = self._run(max(8, int(round(0.75 * n))), V0, p_max)
            start_part = self._run(n, 4.0 * V0, p_max)
            runs += 3
            L1_g, dA_g, dF_g = self._compare(main, grid_part)
            L1_s, dA_s, dF_s = self._compare(main, start_part)
            A, F = self._stats(*main)
            far = np.maximum((pr.p_bar - F) / p_max, 0.0) if self._c_ref is None else np.full(A.shape, np.nan)
            far_err = 2.0 * np.nan_to_num(far)
            est = {
                "L1": L1_g + L1_s / 4.0 + far_err,
                "contact_area": dA_g + dA_s / 4.0 + far_err,
                "load": dF_g + dF_s / 4.0 + far_err * p_max / pr.p_bar,
            }
            worst = max(float(np.max(v)) for v in est.values())
            if o["n_p"] is not None or worst <= tol:
                break
            grid_worst = max(float(np.max(v)) for v in (L1_g, dA_g, dF_g))
            start_worst = max(float(np.max(v)) for v in (L1_s, dA_s, dF_s)) / 4.0
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
        grid, P = main
        # the polynomial's ripple where P is ~0 (tails, next to the walls) is within the estimate: set to 0
        peak = np.max(P, axis=-1, keepdims=True)
        ripple = (P < 0) & (P > -1e-6 * peak)
        P = np.where(ripple, 0.0, P)
        info = {
            "grid": {
                "n_p": n,
                "p_max": p_max,
                "k_domain": k,
                "mapping": "p = centre + eps sinh(a1 + h (x + 1)), x Chebyshev, per load",
                "centre": grid._map[2],
                "eps": grid._map[3],
            },
            "V0": V0,
            "zeta0": float(self.zeta_from_V(V0)[0]),
            "runs": runs,
            "error_estimate": {
                "L1": est["L1"],
                "elastic_area": est["contact_area"],
                "plastic_area": np.zeros_like(A),
                "noncontact_area": est["contact_area"],
                "load": est["load"],
                "method": "|run - run at 3/4 degree| + |run - run from 4 V0| / 4 + 2 x far-wall mass",
            },
            "far_wall_mass": far,
            "ripple_zeroed": int(np.count_nonzero(ripple)),
        }
        if pr.n_loads == 1:
            p, w, Pout = grid.p[0], grid.w[0], P
        else:  # a common output grid: plain Chebyshev of twice the degree (areas and loads from the own grids)
            m = 2 * n
            common = co.chebyshev_grid(m, p_max, np.array([0.5 * p_max]), np.array([1e6 * p_max]))
            p, w = common.p[0], common.w[0]
            q = np.broadcast_to(p, (pr.n_loads, p.size))
            Pout = np.stack([co.interpolate(grid, P[kk], q) for kk in range(P.shape[0])])
        return SolverOutput(p=p, P0=Pout, weights=w, kind="point", info=info, contact_area=A, load=F)
