r"""Compounded Chapman--Kolmogorov solver: iterate Dapp's transition density over zeta steps.

The Xu et al. tutorial's ``E:Compounded_CK`` propagates the pressure PDF from scale to scale
with the exact transition density of ``eq:transition_probability``
(Dapp et al.), an absorbing kernel with no re-entry (``eq:No_reentry``):

.. math::

    P(p,\zeta+\Delta\zeta\,|\,p',\zeta) = \delta(p)\,\big[1-\mathrm{erf}(p'/\sqrt{2\Delta\tau})\big]
        + \theta(p)\,\big[\rho(p;p',\Delta\tau) - \rho(p;-p',\Delta\tau)\big],

with :math:`\Delta\tau = \Delta V` in the original theory and
:math:`\Delta\tau = \int S(A^*)\,dV` over the step with a fudge factor
(``eq:new_B2``).  ``eq:CK_P0`` gives the continuous part and ``eq:Area`` the
contact area after the step.

Discretisation (what is exact, what is not)
-------------------------------------------
* **Grid.** n_p uniform cells on ``[0, p_max]``, ``p_max = max(p_bar) + k_domain
  sqrt(tau(zeta_max))`` (:meth:`~persson_fp.ContactProblem.p_max`, used for sizing only);
  the unknowns are cell averages (``kind = "cell"``).
* **Cell-exact kernel.** With P0 piecewise constant on the source cells the
  double integral of the Gaussian over (target cell) x (source cell) is exact
  in closed form (second differences of :math:`H(x) = \sigma^2\rho(x) -
  |x|\,\Phi_c(|x|/\sigma)`, written with ``erfcx`` so the tails neither cancel
  nor overflow).  The image term makes the matrix Toeplitz minus Hankel,
  :math:`M_{ij} = D(i-j) - D(i+j+1)`: only 3 n_p kernel values per step.  The
  jump to the atom, :math:`\int_{\rm cell} \mathrm{erfc}(p'/\sqrt{2\Delta\tau})dp'`,
  is exact as well, so atom + continuous part + the mass that left through
  ``p_max`` is one to round-off, for any step size (tiny steps included): the
  matrix is non-negative and sub-stochastic.
* **Variance correction** (``variance_correction=True``, the default).  The
  piecewise-constant reconstruction and the cell average are two box filters:
  a step with the cell-exact kernel acts on smooth data like the exact
  kernel with the extra variance :math:`h^2/6` (symbol
  :math:`\mathrm{sinc}^2(kh/2) \approx e^{-k^2 h^2/12}`).  Subtracting it, i.e.
  applying the kernel with :math:`\Delta\tau - h^2/6`, leaves a per-step error
  :math:`O(k^4h^4/1440)` plus aliasing :math:`O(e^{-2\pi^2(\Delta\tau-h^2/6)/h^2})`:
  fourth order in h, and the result becomes independent of the number of
  steps to that order -- the discrete form of the semigroup property of the
  exact kernel.  It needs every step to resolve the cells,
  :math:`S_{\min}\Delta V - h^2/6 \ge h^2` (checked; a ``ValueError`` says what to
  change).  Without it any step size works, but each step adds :math:`h^2/6`
  of numerical variance, an error growing linearly with ``n_steps``.
* **Initial condition.** ``initial="delta"``: the first step from
  :math:`\delta(p-\bar p)` at zeta = 1 is done exactly -- the compounded kernel
  from a delta is the image solution, so its cell averages are computed from
  erf differences.  One step to ``zeta_max`` is therefore exact, and many
  steps agree with it to the discretisation error above.  ``initial="exact"``:
  start at ``zeta0`` (or where tau = ``tau0_fraction`` tau(zeta_max)) from the
  exact cell averages there.
* **Fudge-factor coupling.** Within step k the effective variance obeys
  :math:`dV/d\tau = 1/S(A^*(\tau))`.  :math:`A^*(\tau)` along the step is taken
  from the *numerical* solution: by ``eq:Area``,
  :math:`A^*(\tau) = \int \mathrm{erf}(p'/\sqrt{2(\tau-\tau_s)})\,P_0(p',\tau_s)\,dp'`
  is exact for any earlier state s under the exact kernel.  We take s = the
  state at the start of the *previous* step (so that :math:`\tau-\tau_s` is at
  least one step wide and the cell-exact formula is resolved; for the first two
  steps s is the delta at zeta = 1, whose A* is erf in closed form), integrate
  :math:`1/S` over the step by composite 3-point Gauss--Legendre in tau (panels
  of at most 1/128 of the V range; sixth order, ~1e-13 relative in tau on the
  reference problem) and solve
  :math:`\int_0^{\Delta\tau} d t/S = \Delta V` for :math:`\Delta\tau` by a safeguarded
  Newton iteration (vectorised over loads).  No exact tau is used after the
  start.

Batched loads share the grid; without a fudge factor they share the matrix
(one BLAS product per step), with one they are propagated by batched FFT
convolution of the odd extension (Toeplitz + Hankel), with no Python loop over
loads either way.
"""

from __future__ import annotations

import numpy as np
from scipy.signal import fftconvolve
from scipy.special import erf, erfc, erfcx

from persson_fp.results.solution import SolverError
from persson_fp.solvers.base import Solver, SolverOutput, StationRecorder, check_float, check_int
from persson_fp.theory import fudge as _fudge

__all__ = ["ChapmanKolmogorovSolver"]

_SQRT2PI = np.sqrt(2.0 * np.pi)
_SQRTPI = np.sqrt(np.pi)
_GL3_X = 0.5 + 0.5 * np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
_GL3_W = np.array([5.0, 8.0, 5.0]) / 18.0
_MIN_RESOLVED = 1.0
"""Smallest corrected step variance in units of h^2 (aliasing below ~exp(-2 pi^2) = 3e-9)."""


# -- closed-form cell integrals ------------------------------------------------------------------
def _kernel_lags(t, h, n):
    r"""Cell-to-cell kernel D(m), m = -(n-1) .. 2n-1, for variance(s) ``t`` (shape (L,)) -> (L, 3n-1).

    :math:`D(m) = h^{-1}\int_{\rm cell\ i}\int_{\rm cell\ j}\rho(p-p';t)\,dp'\,dp` for i - j = m,
    written as :math:`\delta_{m0} + (\sigma/h)\,\Delta^2\psi(mh/\sigma)` with
    :math:`\psi(z) = \varphi(z) - |z|\Phi_c(|z|)` (even, decaying).
    """
    sigma = np.sqrt(np.asarray(t, float))[:, None]
    ell = np.arange(-n, 2 * n + 1)
    z = np.abs(ell)[None, :] * h / sigma
    with np.errstate(under="ignore"):
        psi = np.exp(-0.5 * z * z) * (1.0 / _SQRT2PI - 0.5 * z * erfcx(z / np.sqrt(2.0)))
    H = sigma * psi
    D = (H[:, 2:] - 2.0 * H[:, 1:-1] + H[:, :-2]) / h
    D[:, n - 1] += 1.0  # m = 0
    return np.maximum(D, 0.0)


def _cell_erfc(edges, t):
    r"""Cell averages of :math:`\mathrm{erfc}(p/\sqrt{2t})` (the jump weight to the atom), shape (L, n).

    Antiderivative :math:`x\,\mathrm{erfc}(x/s) - s e^{-x^2/s^2}/\sqrt\pi`
    = :math:`s e^{-z^2}(z\,\mathrm{erfcx}(z) - 1/\sqrt\pi)`, z = x/s, which decays, so the
    far cells keep their (tiny) values without cancellation against 1.
    """
    s = np.sqrt(2.0 * np.asarray(t, float))[..., None]
    with np.errstate(under="ignore", over="ignore"):  # t -> 0: z -> inf, exp(-z^2) -> 0, z erfcx(z) -> 1/sqrt(pi)
        z = edges / s
        Ec = s * np.exp(-z * z) * (z * erfcx(z) - 1.0 / _SQRTPI)
    return np.diff(Ec, axis=-1) / np.diff(edges)


def _erf_diff(x1, x2):
    """erf(x2) - erf(x1) without cancellation in the tails (x2 >= x1)."""
    both_pos = x1 >= 0
    both_neg = x2 <= 0
    out = erf(x2) - erf(x1)
    out = np.where(both_pos, erfc(x1) - erfc(x2), out)
    return np.where(both_neg, erfc(-x2) - erfc(-x1), out)


def _image_cell_averages(edges, p_bar, tau):
    """Exact cell averages of the image solution (``eq:P0_solution``) at tau, shape (L, n)."""
    s = np.sqrt(2.0 * tau)[:, None]
    pb = p_bar[:, None]
    a, b = edges[None, :-1], edges[None, 1:]
    direct = 0.5 * _erf_diff((a - pb) / s, (b - pb) / s)
    image = 0.5 * _erf_diff((a + pb) / s, (b + pb) / s)
    return np.maximum(direct - image, 0.0) / np.diff(edges)


class ChapmanKolmogorovSolver(Solver):
    r"""Compounded Chapman--Kolmogorov equation (``E:Compounded_CK``) with Dapp's exact kernel.

    See the module docstring for the discretisation and the fudge-factor
    coupling.  Units: pressures as in the problem; P0 in 1/pressure.

    Options
    -------
    n_p : int, default 400
        Cells on ``[0, p_max]`` (>= 8).
    n_steps : int, default 50
        Steps in zeta, uniform in V(zeta) and split so that every output
        station is a step end (the count actually taken is ``info["steps"]``).
    k_domain : float, default 10
        ``p_max = max(p_bar) + k_domain sqrt(tau(zeta_max))`` (>= 3).
    initial : {"delta", "exact"}, default "delta"
        Exact first step from delta(p - p_bar) at zeta = 1, or exact cell averages at ``zeta0``.
    zeta0 : float, optional
        Start magnification for ``initial="exact"``.
    tau0_fraction : float, default 0.01
        For ``initial="exact"`` without ``zeta0``: start where tau = this fraction of tau(zeta_max).
    variance_correction : bool, default True
        Apply the cell-exact kernel with ``dtau - h^2/6`` (fourth-order in h);
        ``False`` gives the plain cell-exact scheme (second order, any step size).
    tol : None
        Not supported: the accuracy is set by ``n_p`` and ``n_steps`` (a ``ValueError`` says so).

    ``info`` holds ``edges``, ``grid`` (n_p, p_max, h), ``steps``, ``matrix``
    (its shape and how it is applied), ``tau`` (the numerical effective
    variance at each station), ``atom``, ``far_loss`` and ``min_step_ratio``
    (smallest kernel variance of a grid step in units of h^2).
    """

    name = "chapman-kolmogorov"
    OPTIONS = {
        "n_p": 400,
        "n_steps": 50,
        "k_domain": 10.0,
        "initial": "delta",
        "zeta0": None,
        "tau0_fraction": 0.01,
        "variance_correction": True,
        "tol": None,
    }

    def validate(self) -> None:
        o = self.opts
        if o["tol"] is not None:
            raise ValueError(
                f"chapman-kolmogorov has no tolerance control (tol = {o['tol']!r}): its accuracy is set by n_p and "
                "n_steps (double them to see how far the result moves); set those, or use method='auto' (or 'fv' / "
                "'mol') with tol"
            )
        o["n_p"] = check_int(o["n_p"], "n_p", 8, 200_000)
        o["n_steps"] = check_int(o["n_steps"], "n_steps", 1)
        o["k_domain"] = check_float(o["k_domain"], "k_domain", 3.0, 100.0, lo_open=False)
        if o["initial"] not in ("delta", "exact"):
            raise ValueError(f"initial must be 'delta' or 'exact', got {o['initial']!r}")
        if not isinstance(o["variance_correction"], (bool, np.bool_)):
            raise ValueError(f"variance_correction must be True or False, got {o['variance_correction']!r}")
        if o["initial"] == "delta" and o["zeta0"] is not None:
            raise ValueError("zeta0 is only used with initial='exact'")
        self.validate_start_options()

    # -- step plan ------------------------------------------------------------------------------------
    def _step_nodes(self, V_start):
        """V at the step ends (uniform in V within each station interval) and the station indices."""
        return self.uniform_V_nodes(V_start, self.opts["n_steps"])

    # -- fudge coupling -------------------------------------------------------------------------------
    @staticmethod
    def _solve_dtau(dV, tau_k, area, S, S_lo, S_hi, panels):
        r"""Solve :math:`\int_0^{\Delta\tau} dt / S(A(\tau_k + t)) = \Delta V` per load.

        ``area(tau)`` (tau shape (..., L)) returns A* there.  Composite 3-point
        Gauss--Legendre with ``panels`` panels; safeguarded Newton in the
        bracket [dV S_lo, dV S_hi] (the integrand lies in [1/S_hi, 1/S_lo]).
        """
        L = tau_k.size
        lo = np.full(L, dV * S_lo * (1 - 1e-12))
        hi = np.full(L, dV * S_hi * (1 + 1e-12))
        x = np.minimum(np.maximum(dV * S(area(tau_k[None, :]))[0], lo), hi)
        frac = (np.arange(panels)[:, None] + _GL3_X[None, :]).ravel() / panels
        w = np.tile(_GL3_W, panels) / panels
        for _ in range(60):
            nodes = tau_k[None, :] + frac[:, None] * x[None, :]
            f = x * (w @ (1.0 / S(area(nodes)))) - dV
            lo = np.where(f < 0, x, lo)
            hi = np.where(f >= 0, x, hi)
            df = 1.0 / S(area((tau_k + x)[None, :]))[0]
            xn = x - f / df
            bad = ~((xn > lo) & (xn < hi))
            xn = np.where(bad, 0.5 * (lo + hi), xn)
            done = np.abs(xn - x) <= 1e-15 * np.abs(x)
            x = xn
            if np.all(done | (hi - lo <= 4e-16 * hi)):
                break
        return x

    # -- kernel application ---------------------------------------------------------------------------
    def _apply(self, P, t, h, idx):
        """One cell-exact CK step of P (L, n) with kernel variance(s) t (L,); returns (P_new, how).

        A matrix shared by many loads is built densely (``M_ij = D(i-j) - D(i+j+1)``)
        and applied by one BLAS product; otherwise the odd extension of P is
        convolved with D by FFT, batched over loads (equal to the matrix
        product to ~1e-15 relative; round-off negatives are clipped).
        """
        L, n = P.shape
        shared = bool(np.all(t == t[0]))
        if shared and L >= 32 and n <= 1024:
            D = _kernel_lags(t[:1], h, n)[0]
            M = np.maximum(D[idx[:, None] - idx[None, :] + (n - 1)] - D[idx[:, None] + idx[None, :] + n], 0.0)
            return P @ M.T, "dense matrix shared by the loads (BLAS)"
        D = _kernel_lags(t[:1] if shared else t, h, n)
        Q = np.concatenate([-P[:, ::-1], P], axis=1)  # odd extension, cell indices -n .. n-1
        c = fftconvolve(Q, D, axes=-1)
        return np.maximum(c[:, 2 * n - 1 : 3 * n - 1], 0.0), "FFT convolution of the odd extension, batched over loads"

    # -- main -----------------------------------------------------------------------------------------
    def _solve(self) -> SolverOutput:
        o = self.opts
        pr = self.problem
        pb = pr.p_bar
        L = pb.size
        n = o["n_p"]
        fud = pr.fudge
        const_S = isinstance(fud, _fudge.NoFudge)
        edges, h = self.cell_grid(n)
        p_max = edges[-1]
        centres = edges[:-1] + 0.5 * h
        c_var = h * h / 6.0 if o["variance_correction"] else 0.0
        self.check_resolved(h)

        A_grid = np.linspace(0.0, 1.0, 2001)
        S_vals = np.asarray(fud.S(A_grid), float)
        S_lo, S_hi = float(S_vals.min()), float(S_vals.max())

        if o["initial"] == "delta":
            V_start, zeta0 = 0.0, 1.0
            tau = np.zeros(L)
            P = None
        else:
            zeta0 = self.start_zeta(o["zeta0"], o["tau0_fraction"], dp=h)
            V_start = float(pr.V(zeta0))
            tau = np.asarray(pr.tau_of_V(V_start), float).reshape(L)
            P = _image_cell_averages(edges, pb, tau)
        nodes, stations = self._step_nodes(V_start)
        dVs = np.diff(nodes)

        # grid steps must resolve the cells when the variance correction is on
        first_grid = 1 if P is None else 0
        if o["variance_correction"] and dVs.size > first_grid:
            worst = float(S_lo * dVs[first_grid:].min() - c_var) / h**2
            if worst < _MIN_RESOLVED:
                need = (_MIN_RESOLVED + 1 / 6) * h**2 / S_lo
                n_ok = int((nodes[-1] - V_start) / need)
                raise ValueError(
                    f"n_steps = {o['n_steps']} is too many for n_p = {n}: a step's variance increment "
                    f"S_min*dV = {S_lo * dVs[first_grid:].min():.3e} must exceed (1 + 1/6) h^2 = "
                    f"{(_MIN_RESOLVED + 1 / 6) * h**2:.3e} for the cell-exact kernel with variance correction "
                    f"(the kernel must resolve the cells); use n_steps <= ~{max(n_ok, 1)}, a larger n_p, "
                    "or variance_correction=False"
                )

        atom = np.zeros(L) if P is None else erfc(pb / np.sqrt(2.0 * tau))
        far = np.zeros(L) if P is None else 1.0 - atom - P.sum(-1) * h
        idx = np.arange(n)
        V_span = nodes[-1] - V_start

        # source of A*(tau) for the coupling: state at the start of the previous step (delta at first)
        src = None  # None: the delta at tau = 0
        rec = StationRecorder(stations, P=(L, n), tau=(L,), atom=(L,), far=(L,))
        how = "exact image solution (single step from the delta)"
        min_ratio = np.inf

        def area_from(source):
            if source is None:

                def area(tt):
                    with np.errstate(divide="ignore"):
                        return erf(np.divide(pb, np.sqrt(2.0 * tt), out=np.full(tt.shape, np.inf), where=tt > 0))

                return area
            P_s, tau_s = source

            def area(tt):
                t_eff = tt - tau_s - c_var
                if np.any(t_eff <= 0):  # pragma: no cover - excluded by the step check
                    raise SolverError("chapman-kolmogorov: coupling evaluated below the cell resolution")
                loss = _cell_erfc(edges, t_eff)  # (..., L, n)
                return h * np.sum(P_s * (1.0 - loss), axis=-1)

            return area

        for k, dV in enumerate(dVs, start=1):
            if const_S:
                dtau = np.full(L, dV)
            else:
                panels = int(np.ceil(128 * dV / V_span))  # each Gauss panel spans <= 1/128 of the V range
                dtau = self._solve_dtau(dV, tau, area_from(src), fud.S, S_lo, S_hi, panels)
            if P is None:  # exact first step from the delta
                tau_new = tau + dtau
                P_new = _image_cell_averages(edges, pb, tau_new)
                atom = erfc(pb / np.sqrt(2.0 * tau_new))
                far = 1.0 - atom - P_new.sum(-1) * h
            else:
                t_eff = dtau - c_var
                min_ratio = min(min_ratio, float(np.min(t_eff)) / h**2)
                if np.any(t_eff <= 0):
                    raise SolverError(
                        f"chapman-kolmogorov: step {k} has kernel variance {t_eff.min():.3e} <= 0 after the "
                        "variance correction; use fewer steps or more cells"
                    )
                P_new, how = self._apply(P, t_eff, h, idx)
                loss = _cell_erfc(edges, t_eff)
                absorbed = h * np.sum(P * loss, axis=-1)
                kept = h * np.sum(P * (1.0 - loss), axis=-1)
                atom = atom + absorbed
                far = far + kept - h * P_new.sum(-1)
                tau_new = tau + dtau
            src = None if P is None else (P, tau)  # the start of this step serves the next one
            P, tau = P_new, tau_new
            rec.record(k, P=P, tau=tau, atom=atom, far=far)
        out_P, out_tau, out_atom, out_far = rec["P"], rec["tau"], rec["atom"], rec["far"]
        self.check_state(out_P, out_P.sum(-1) * h, None, float(self.zeta_out[-1]), self.name)
        info = {
            "edges": edges,
            "grid": {"n_p": n, "p_max": p_max, "h": h},
            "steps": int(dVs.size),
            "matrix": {"shape": (n, n), "application": how},
            "zeta0": zeta0,
            "tau": out_tau,
            "atom": out_atom,
            "far_loss": out_far,
            "min_step_ratio": min_ratio,
            "coupling": "none (S = 1)"
            if const_S
            else "dV/dtau = 1/S(A*(tau)), A* from eq:Area on the previous step's state, 3-pt Gauss, Newton",
        }
        return SolverOutput(
            p=centres,
            P0=out_P,
            weights=np.full(n, h),
            kind="cell",
            info=info,
            contact_area_flux=1.0 - out_atom,
        )
