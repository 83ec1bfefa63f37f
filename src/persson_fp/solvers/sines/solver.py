r"""Persson's original solution form: a sum of sines on [0, p_max] (``eq:P0_solution``).

With absorbing walls at p = 0 and p = L = p_max the diffusion equation
``E:diffusion_equ`` / ``eq:new_B2``, written in the effective variance
:math:`\tau = \int S\,dV`, is the plain heat equation, whose solution from
:math:`\delta(p - \bar p)` is

.. math::

    P_0(p, \tau) = \sum_{n\ge1} \frac{2}{L}\,\sin(k_n \bar p)\,\sin(k_n p)\,
                   e^{-\frac12 k_n^2 \tau}, \qquad k_n = n\pi/L .

The delta initial condition is represented exactly (no start-up zeta0), and
the error is the truncation of the series alone: it falls faster than any
power of the mode count (like :math:`e^{-\frac12 k_N^2\tau}`).  The far wall
adds an error of order :math:`e^{-(L-\bar p)^2/2\tau}` (< 1e-21 for the
default domain).

Contact area and load are exact integrals of the series,

.. math::

    A^* = \sum_n \frac{2}{L}\sin(k_n\bar p)\,\frac{1-\cos n\pi}{k_n}\,e^{-\frac12 k_n^2\tau},
    \qquad \int_0^L p\,\sin(k_n p)\,dp = -\frac{L\cos n\pi}{k_n},

so neither is limited by an output grid.  P0 is returned on Gauss--Legendre
nodes of [0, L] with their weights, spectrally accurate for the load and
variance integrals that :class:`~persson_fp.Solution` forms from the weights.

**Fudge factors** (``eq:new_B2``).  tau(zeta) must come from the *numerical* area of the series,
:math:`d\tau/dV = S(A_h(\tau))`, where :math:`A_h` is :func:`~persson_fp.solvers.sines.series_area` with the solve's
N modes
for :math:`\tau \ge \max(\tau_N, \tau_{sw})` (:math:`\tau_N`: where they are converged to ``tol``) and the
infinite series below, summed as its exact Poisson dual :func:`~persson_fp.solvers.sines.image_area` (both clipped to
[0, 1]; below
:math:`\tau_{sw}` that is 1 to round-off, see *Tiny tau*; with ``tol`` near its 1e-2 limit, where
:math:`\tau_N < \tau_{sw}`, the N-mode series would differ from it there by up to ``tol``, which moves
tau by at most ``tol`` max|S'| S_max / S_min^2 relative).  :math:`A_h` depends on tau alone, so the ODE is
separable: the tau of a station with complete-contact variance :math:`V_{out}` is the root of

.. math::  F(\tau) = V_{sw} + \int_{\tau_{sw}}^{\tau} \frac{dt}{S(A_h(t))} - V_{out},
           \qquad \frac{dF}{d\ln\tau} = \frac{\tau}{S(A_h(\tau))}

(V, tau and F in pressure^2; :math:`V_{sw} = \tau_{sw}/S(1)`, see *Tiny tau*).  It is found for every
(station, load) at once by Newton's method in :math:`x = \ln\tau`, started from the continuum map
(:meth:`~persson_fp.ContactProblem.tau_of_V`, only a guess), until :math:`|F| \le` ``rtol``
:math:`V_{out}`: F is evaluated at each iterate, and a step (:math:`|\Delta x| \le 10^{-3}`) is accepted
when Taylor's theorem bounds the residual at its end by ``rtol`` -- with
:math:`|d^2F/dx^2| \le \tau\,(1/S_{min} + \max|d(1/S)/dA|)` that takes one step from the continuum
guess (a ``RuntimeError`` after 50).  The integral is split about the continuum area
:math:`A_c = \mathrm{erf}(\bar p/\sqrt{2t})`, which differs from :math:`A_h` only by the modes beyond N
(for :math:`t \ge \tau_N`) and by the far wall:

* :math:`\int_{\tau_{sw}}^{\tau} dt/S(A_c) = \tau\,J(y)`, :math:`y = \ln(\tau/\bar p^2)`, is free of the
  load: :math:`J(y) = e^{-y}\int_{y_{sw}}^{y} e^{y'}/S(\mathrm{erf}(e^{-y'/2}/\sqrt2))\,dy'` is tabulated
  once per fudge factor at panel edges in y (composite Gauss--Legendre, width 1/4; each panel's 6-point
  value is checked against two 16-point halves to 1e-15 and halved where it fails), and a call adds the
  6-point rule over the last, partial panel: 8 evaluations of S per (station, load).
* the correction :math:`\int [1/S(A_h) - 1/S(A_c)]\,dt` is non-zero only for :math:`t \ge \tau_N`, where
  :math:`A_c - A_h = \sum_{n>N\ \mathrm{odd}} \frac{4}{L}\frac{\sin k_n\bar p}{k_n} e^{-k_n^2 t/2}` (Poisson
  summation) decays like :math:`e^{-\lambda t}`, :math:`\lambda = k_{N+1}^2/2`.  It is bounded by
  :math:`\max|d(1/S)/dA| \sum_n \frac{4}{L k_n}\frac{2}{k_n^2}e^{-k_n^2\tau_N/2}` (below 1e-3 of ``rtol``
  at the default ``tol``): left out (and ``rtol`` tightened by it) while that bound is below ``rtol``/10,
  else summed by 12-point Gauss--Laguerre in :math:`\lambda(t - a)` from :math:`a = \max(\tau_N, \tau_{sw})`
  and from tau.  (Only with ``tol`` near its 1e-2 limit can the clipped area have kinks there, which
  limits that correction to ~1e-8 of tau.)
* where the far wall reaches the area (:math:`\mathrm{erfc}((L-\bar p)/\sqrt{2\tau}) > 10^{-20}`, i.e.
  ``k_domain`` below about 9.2) the whole integral is taken directly on :math:`A_h` instead, by
  composite 16-point Gauss--Legendre in x (panels <= 0.5, split at :math:`\tau_N`).

Every rule is at round-off (~1e-16 relative) for the built-in models.  ``info`` reports the evaluations
of the area per call (``tau_map_nodes``), the Newton steps (``tau_map_iterations``), the final residual
max :math:`|F|/V_{out}` (its Taylor bound; ``tau_map_residual``) and whether the direct rule was used
(``tau_map_direct``).  With ``NoFudge``, tau = V.

*Tiny tau.*  For :math:`\tau \le \tau_{sw} = \bar p^2/72` the series area is 1 to round-off:
the infinite series equals the image sum on [0, L] (Poisson summation), whose mass defect is
:math:`\mathrm{erfc}(\bar p/\sqrt{2\tau}) < 2\cdot10^{-17}` there, so :math:`\tau = S(1)\,V` exactly.
On the direct path (far wall not negligible) :math:`\tau_{sw} = \min(\bar p, L - \bar p)^2/72`, so that
the far wall's share is below the same bound.
Between :math:`\tau_{sw}` and :math:`\tau_N` (where the chosen N modes are converged to ``tol``)
the same infinite series is summed in that dual form (:func:`~persson_fp.solvers.sines.image_area`, images ``|k| <= 1``,
the rest below e^-200), so the mode count only has to serve the output stations: the default
is the one that makes the truncation below ``tol`` at the first station.  (Before, N was sized
for :math:`\bar p^2/72`, and a load of 1e-4 sqrt(V) with a fudge factor needed 1.4 million modes.)
"""

from __future__ import annotations

import math

import numpy as np

from persson_fp.solvers.base import Solver, SolverOutput, check_float, check_int, check_k_domain
from persson_fp.solvers.sines.series import (
    _MAX_MODES,
    _modes_needed_scalar,
    _output_rule,
    _sine_basis,
    image_area,
    modes_needed,
    series_area,
    series_pdf,
)
from persson_fp.solvers.sines.taumap import _FAR_WALL_Z, _RTOL_FLOOR, _scaled_integral, _TauMap
from persson_fp.theory.fudge import NoFudge

__all__ = ["SineSeriesSolver", "series_area", "image_area", "series_pdf", "modes_needed"]

# -- the tau map with a fudge factor -------------------------------------------------------------------


class SineSeriesSolver(Solver):
    r"""Sum of sines on [0, p_max] (``eq:P0_solution``), exact in zeta once tau(zeta) is known.

    Options
    -------
    n_p : int or None
        Number of sine modes N; ``None`` chooses it so that the truncation is
        below ``tol`` at the smallest tau that matters (module docstring).
    n_eval : int or None
        Gauss--Legendre output nodes on [0, p_max]; ``None``: enough for the
        load integral to round-off at the first output station.
    tol : float
        Truncation target of the automatic mode count (L1 of P0, dimensionless).
    rtol : float
        Relative accuracy of the tau(V) map with a fudge factor: Newton's method stops at
        |F| <= rtol V_out (module docstring; at least 8 ulps); unused without one.
    k_domain : float
        p_max = max(p_bar) + k_domain sqrt(tau(zeta_max)).
    """

    name = "sines"
    SUPPORTS = frozenset({"hardness"})
    OPTIONS = {"n_p": None, "n_eval": None, "tol": 1e-13, "rtol": 1e-14, "k_domain": 10.0}
    SMALL_BATCH = 1  # (one load at one station: a vector-matrix product, below OpenBLAS's threading thresholds)

    def validate(self) -> None:
        o = self.opts
        given = self.given  # (an option left at its default in OPTIONS is valid: only those passed are checked)
        if o["n_p"] is not None:
            o["n_p"] = check_int(o["n_p"], "n_p", 1, 10_000_000)
        if o["n_eval"] is not None:
            o["n_eval"] = check_int(o["n_eval"], "n_eval", 2, 10_000_000)
        if "tol" in given:
            o["tol"] = check_float(o["tol"], "tol", 0.0, 1e-2)
        if "rtol" in given:
            o["rtol"] = check_float(o["rtol"], "rtol", 0.0, 1e-3)
        if "k_domain" in given:
            o["k_domain"] = check_k_domain(o["k_domain"], 1e3)

    # -- tau(V) from the series area -------------------------------------------------------------
    def _tau_map(self, tab, L, N, V_out, guess):
        """tau at the complete-contact variances ``V_out`` (n_zeta,) for every load, shape (n_zeta, n_loads).

        ``tab``: the fudge factor's :class:`_ScaledIntegral`; ``guess`` (n_zeta, n_loads): the continuum
        map's tau, Newton's starting point.
        """
        pr = self.problem
        pb = pr.p_bar
        o = self.opts
        rtol = max(o["rtol"], _RTOL_FLOOR)
        # the far wall: negligible while (L - p_bar) / sqrt(2 tau) >= _FAR_WALL_Z at the last station; p_max makes
        # L - p_bar >= k_domain sqrt(tau(zeta_max)) for every load, and the guess is at most that tau
        far = np.sqrt(2.0) * _FAR_WALL_Z
        direct = o["k_domain"] < far and not bool((L - pb >= far * np.sqrt(guess[-1])).all())
        tm = _TauMap(tab, L, N, o["tol"], pr, direct)
        tau, it, res, moved = tm.solve(V_out, guess, rtol)
        if not direct and moved > 1e-6 and not bool((L - pb >= far * np.sqrt(tau[-1])).all()):  # pragma: no cover
            tm = _TauMap(tab, L, N, o["tol"], pr, True)  # (a poor guess, and the answer is near the far wall)
            tau, it, res, _ = tm.solve(V_out, tau, rtol)
        info = {
            "tau_map_nodes": tm.nodes,
            "tau_map_iterations": it,
            "tau_map_residual": res,
            "tau_map_direct": direct,
            "tau_switch": tm.tau_sw,
        }
        return tau, info

    # -- the solve --------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        pr = self.problem
        o = self.opts
        pb = pr.p_bar
        fudge = pr.fudge
        L = pr.p_max(o["k_domain"])
        V_out = self.V_out  # (cached: the default station costs nothing)
        tol = o["tol"]
        tab = None if isinstance(fudge, NoFudge) else _scaled_integral(fudge)
        if o["n_p"] is not None:
            N = o["n_p"]
        else:
            # smallest tau that matters: the first station (tau >= min(S) V there); below it the
            # fudge factor's tau map evaluates the series area through its image dual (_tau_map)
            N = _modes_needed_scalar(L, (1.0 if tab is None else tab.S_min) * float(V_out[0]), tol)
            if N > _MAX_MODES:
                sigma = math.sqrt(float(np.min(self.tau_out[0])))
                raise ValueError(
                    f"sines: the first station zeta = {self.zeta_out[0]:.6g} needs {N} modes (> {_MAX_MODES}): "
                    f"its PDF is too narrow for the domain [0, {L:.3g}] (sqrt(tau) = {sigma:.3g}); start zeta_out "
                    "later, use fewer/closer loads, or use pf.exact / method='fv'"
                )
        if tab is None:  # tau = V (one load: a read-only view of V_out, broadcast like the repeat)
            tau = V_out[:, None] if pb.size == 1 else np.repeat(V_out[:, None], pb.size, axis=1)
            tinfo = {"tau_map_nodes": 0, "tau_map_iterations": 0, "tau_map_residual": 0.0}
        elif pr.hardness is not None:  # the strip's exact map tau' = S(A_el + A_pl): the infinite series' own area
            tau = np.asarray(self.tau_out, dtype=float)
            tinfo = {"tau_map": "exact strip map (persson_fp.theory.strip)"}
        else:
            tau, tinfo = self._tau_map(tab, L, N, V_out, self.tau_out)  # (n_zeta, n_loads)

        # output modes: those above tol / 1e3 at the first station, at most N
        tau_first = float(tau[0, 0]) if pb.size == 1 else float(np.min(tau[0]))
        N_out = min(N, _modes_needed_scalar(L, tau_first, tol * 1e-3))
        if N_out > _MAX_MODES:  # (n_p given): the output alone would take ~ N_out^2 numbers
            raise ValueError(
                f"sines: the first station zeta = {self.zeta_out[0]:.6g} needs {N_out} output modes (> {_MAX_MODES}); "
                "start zeta_out later, use fewer/closer loads, or use pf.exact / method='fv'"
            )
        n_eval = o["n_eval"] or max(64, math.ceil(1.2 * N_out + 40))
        p, w, k, mhk2, two_over_k_odd = _output_rule(L, N_out, n_eval)  # (cached per domain and size)
        with np.errstate(under="ignore"):
            coef = (2.0 / L) * np.sin(np.outer(pb, k)) * np.exp(tau[..., None] * mhk2)  # (n_z, n_l, N_out)
        P0 = coef @ _sine_basis(L, N_out, n_eval)  # (n_zeta, n_loads, n_eval)
        # odd modes carry the area (summed as before: a matmul is a little faster but moves the last bits, and
        # the notebooks quote round-off-level errors of the committed runs)
        A = (coef[..., ::2] * two_over_k_odd).sum(axis=-1)  # the odd modes n = 1, 3, 5, ...
        # the mass absorbed at the far wall, summed in closed form: with a hardness (L = sigma_Y) the plastic area
        # (the strip's A_pl sine series); without one a loss below tol, which the wall does not report as an area
        n = np.arange(1, N_out + 1, dtype=float)
        sgn = np.where(n % 2 == 1, 1.0, -1.0)
        plastic = pr.upper_wall.plastic_area(pb / L - (coef * (sgn * L / (n * np.pi))).sum(axis=-1))
        info = {
            "grid": "Gauss-Legendre",
            "p_max": L,
            "n_modes": N,
            "n_modes_out": N_out,
            "n_eval": n_eval,
            "tau": tau,
            "zeta0": 1.0,
            "steps": 0,
            **tinfo,
        }
        return SolverOutput(p=p, P0=P0, weights=w, kind="point", info=info, contact_area=A, plastic_area=plastic)
