r"""The spectral fast path of the ``"fv"`` solver: its operators are diagonal in the DST-II basis.

*The spectral fast path* (``linalg="dst"``, the default through "auto").  With odd ghost cells at
*both* walls, L and M are diagonalised exactly by the orthonormal DST-II basis (cell-centred sines
:math:`\phi_j(i) \propto \sin(\pi j (i+\tfrac12)/n_p)`, j = 1..n_p, odd about both wall faces, so
the ghost rules hold for every j; the compact end rows (9, 1)/12 are exactly M's odd-ghost rows):

.. math::  L\phi_j = \mu_j\phi_j,\quad \mu_j = -\frac{2}{\Delta p^2}\sin^2\frac{\pi j}{2n_p}, \qquad
           M\phi_j = m_j\phi_j,\quad m_j = m_d + 2m_o\cos\frac{\pi j}{n_p}
           \;\big(\text{compact4: } (10 + 2\cos(\pi j/n_p))/12\big)

(:func:`dst_eigenvalues`; checked against the dense matrices to 1e-15 in the tests).  So every
step above multiplies coefficient j by a rational amplification factor of
:math:`x_j = \Delta\tau\,\lambda_j`, :math:`\lambda_j = \mu_j/m_j` (``_amplification``):
θ-step :math:`R = (1+(1-\theta)x)/(1-\theta x)`; Rannacher start :math:`(1-x/2)^{-2}`; TR-BDF2,
whose two stages share :math:`1-h`, :math:`h = \gamma x/2`: :math:`R = (1+(A+B)h)/(1-h)^2` with
the BDF2 weights A, B (A - B = 1).  Without a fudge factor a whole run is
:math:`P_N = S^{-1}\,\mathrm{diag}(\prod_k R_k)\,S P_0` (one ``scipy.fft.dst`` and one ``idst`` for
all stations and loads).  With one, :math:`\Delta\tau_k` depends on the numerical
:math:`A^* = \sum_i\bar P_i\Delta p` and (predictor) on the wall flux, both linear functionals
of the coefficients (:math:`\langle v, P\rangle = \langle Sv, SP\rangle`, S orthogonal), so the
march stays in coefficient space: O(n_p n_loads) array operations a step, no solve and no
transform; P is transformed back only at the output stations.  For the lagged and predictor couplings
(whose :math:`\Delta\tau_n` depends on the state before step n only) the whole sequence of steps is
found at once, as the fixed point of a causal map solved by 3-8 Newton sweeps over the trajectory
(``FiniteVolumeSolver._fudge_trajectory``: each sweep one cumulative product over steps x modes, the
Jacobian approximated by the wall outflux), then the run is the closed form above.  This is done for up to
three loads (``_fudge_trajectory_max_loads``, ``_TRAJECTORY_SIZE`` numbers at most); larger batches march step by
step, vectorised over the loads, which is faster from about five loads on (``benchmarks/fv_timing.py``, last
table), as do runs with fewer than 16 steps and ``"picard"``.  Either way it is the banded path's
discrete solution to ~1e-13.  The wall fluxes are functionals too, accumulated with the scheme's stage
weights (per-mode weight F(x)), so ``contact_area_flux`` and ``far_wall_mass`` are the banded path's to
round-off.  The stability checks run on coefficients: non-finite values, negative or growing A* (as the
conserved sum(M P) dp), and growth of :math:`\|P\|_2 = \|c\|_2` (which :math:`|R_j| \le 1` makes
non-increasing) instead of max ``|P|``; an explicit step past its limit (:math:`|R_j| > 1` for the top
modes) still raises :class:`~persson_fp.InstabilityError`.  The fast path is
exact for every option of this solver, so "auto" always picks it; ``linalg="banded"`` keeps the
tridiagonal solves below as the readable reference (the two agree to ~1e-14 of max P0).  It would
stop being exact with a wall that is not odd (a reflecting far wall, another basis) or a
non-uniform grid in p.  Coefficients below 1e-200 of :math:`\|P_0\|_2` are set to zero (the top
modes would otherwise decay into subnormal numbers, ~100x slower arithmetic).  Measured
(``benchmarks/fv_timing.py``): 1.9-13x faster than the banded path for one load without a fudge
factor and 3.8-7.9x with YP08 (the trajectory sweeps), where the set-up (start-up data and nodes, ~1 ms)
is a large part of the time, and 6.4-7.3x for 1000 loads with YP08 (step by step, vectorised over the
loads).
"""

from __future__ import annotations

import numpy as np

from persson_fp.results.solution import DEFAULT_TOLERANCES, InstabilityError
from persson_fp.solvers.base import Solver, StationRecorder, zeta_of
from persson_fp.solvers.fv.dst import _amplification, _growth, _Spectral, dst_eigenvalues
from persson_fp.solvers.fv.operators import march_result
from persson_fp.solvers.fv.stepping import damped_steps, step_kind
from persson_fp.theory.fudge import NoFudge

__all__ = ["dst_eigenvalues", "DSTMarch"]

_FLUSH = 1e-200
"""DST path: coefficients (relative to ||P0||_2) below this are set to 0.  The top modes decay by
|R| << 1 a step into the subnormal range, where arithmetic is ~100x slower (measured: 10 ms instead
of 1.3 ms a step for 1000 loads); 1e-200 of the data is far below round-off."""
_TRAJECTORY_SIZE = 2_000_000
"""DST path with a fudge factor: runs of at most ``_fudge_trajectory_max_loads`` loads with n_loads x n_steps x n_p
up to this many numbers solve the coupling for the whole trajectory at once (FiniteVolumeSolver._fudge_trajectory);
others march step by step (vectorised over the loads, which amortises the per-step overhead there)."""
_fudge_trajectory_max_loads = 3
"""Most loads solved by the whole-trajectory coupling; larger batches march step by step, vectorised over
the loads (benchmarks/fv_timing.py times both for 1-10 loads: break-even near 5 loads)."""
_TRAJECTORY_MIN_STEPS = 16
"""Below this many steps the step-by-step march is as cheap as the 4-8 sweeps of the trajectory."""
_TRAJECTORY_SWEEPS = 30
_TRAJECTORY_TOL = 1e-14
"""Converged when every step's residual is below this fraction of the load's largest step."""


class DSTMarch:
    """The DST-II march of ``"fv"`` (module docstring): built from the problem, the method's options, the output
    stations, the cell width and the start's plastic area; :meth:`march` runs it.

    Parameters
    ----------
    problem : ContactProblem
    opts : dict
        ``"fv"``'s options (scheme, initial, rannacher_steps, check_every ...).
    zeta_out : ndarray
        Output stations (dimensionless).
    dp : float
        Cell width (pressure).
    A_pl0 : ndarray
        Plastic area at the start per load (zeros without a hardness).
    """

    def __init__(self, problem, opts, zeta_out, dp: float, A_pl0):
        self.problem, self.opts, self.zeta_out, self.dp = problem, opts, zeta_out, dp
        self._hard, self._A_pl0 = problem.hardness is not None, A_pl0

    def _check_dst(self, C, mass, mass_prev, norm, norm0, V_now, r_max):
        """The stability checks of the banded path, on coefficients (the l2 norm of P0 is ||c||_2)."""
        name = "fv/" + self.opts["scheme"]
        remedy = "raise n_steps or use scheme='tr-bdf2'"
        try:
            Solver.check_state(C, mass, mass_prev, np.nan, name, remedy)
        except InstabilityError:  # say where (the root find costs only when it fails)
            Solver.check_state(C, mass, mass_prev, float(zeta_of(self.problem, V_now)[0]), name, remedy)
        if np.any(norm > 2.0 * norm0 + 1e-300):
            z_now = float(zeta_of(self.problem, V_now)[0])
            raise InstabilityError(
                f"{name}: the l2 norm of P0 grew by a factor {np.max(norm / norm0):.3g} by zeta = "
                f"{z_now:.6g} (the heat equation cannot do that; r = {r_max:.3g}); {remedy}"
            )

    def _amplify_all(self, X, theta):
        """R and F of every step at once: X (n_steps, ..., n_p); the damped first steps are BE halves."""
        n_steps = X.shape[0]
        R, F = _amplification(step_kind(self.opts, n_steps), theta, X)
        r0 = min(damped_steps(self.opts), n_steps)
        if r0 > 0:
            R[:r0], F[:r0] = _amplification("be-halves", theta, X[:r0])
        return R, F

    def _fudge_trajectory(self, sp, C0, V_nodes, theta, coupling):
        r"""Steps :math:`\Delta\tau_n` of the lagged/predictor coupling for the whole run at once.

        The coupled march defines :math:`\Delta\tau_n = \Phi(A^*_n, b_n, \Delta V_n)` from the state
        before step n, and that state is :math:`C_0\prod_{k<n}R(\Delta\tau_k\lambda)`: a causal
        (Volterra) fixed point in the step sizes.  It is solved by Newton sweeps over the whole
        trajectory, each one vectorised over steps and modes (a cumulative product), starting from the
        exact continuum steps tau(V_{n+1}) - tau(V_n).  The Jacobian is approximated by what dominates
        it: a step of size d moves every later A* by -b d (b: the current outflux density), so the
        correction solves :math:`\delta_n = r_n - \Phi'_n b_n\sum_{k<n}\delta_k` (a scalar
        recurrence).  The fixed point is the per-step march's (to 1e-14 of the steps); 3-6 sweeps
        instead of n_steps Python-level steps.  Returns (dts (n_steps, n_loads), sweeps), or
        (None, sweeps) when it does not converge in ``_TRAJECTORY_SWEEPS`` (the caller then marches
        step by step, which also reports any instability).
        """
        pr = self.problem
        S = pr.fudge.S
        fun = sp.functionals
        m = C0.shape[0]
        dV = np.diff(V_nodes, axis=0)  # (n_steps, m)
        tau_nodes = pr.tau_of_V_each(V_nodes)  # the continuum's steps: the starting guess
        if self.opts["initial"] == "delta":
            tau_nodes[0] = 0.0
        dts = np.diff(tau_nodes, axis=0)
        W = np.stack([C0 * fun[:, 0], C0 * (fun[:, 1] + fun[:, 2])])  # (2, m, N): A* and the outflux
        # only modes that carry A* or the outflux: the even ones carry neither (both functionals are
        # symmetric about the middle), nor do the top modes of a smooth start (dropped below 1e-18 of
        # the largest term: with |R| <= 1 the sums move by < n_p 1e-18 of themselves)
        big = np.max(np.abs(W), axis=(1, 2), keepdims=True)
        keep = np.any(np.abs(W) > 1e-18 * big, axis=(0, 1))
        W = np.ascontiguousarray(W[:, :, keep])
        lam = sp.lam[keep]
        mass0, b0 = W[0].sum(axis=-1), W[1].sum(axis=-1)  # at the start (node 0)
        WT = np.ascontiguousarray(W[:, 0, :].T) if m == 1 else None  # one load: a matmul, not an einsum
        r0 = min(damped_steps(self.opts), dts.shape[0])
        kind = step_kind(self.opts, dts.shape[0])
        chord = None  # the correction's recurrence, set up once (a chord method: the Jacobian is approximate anyway)
        with np.errstate(over="ignore", invalid="ignore", under="ignore"):
            for sweep in range(1, _TRAJECTORY_SWEEPS + 1):
                X = dts[:-1, :, None] * lam  # the last step's factor is not needed here
                R = _growth(kind, theta, X)
                if r0 > 0:
                    R[:r0] = _growth("be-halves", theta, X[:r0])
                G = np.cumprod(R, axis=0)  # amplification up to the start of steps 1..n-1
                if WT is not None:
                    Q = (G[:, 0, :] @ WT).T[:, :, None]  # (2, n_steps - 1, 1)
                else:  # several loads
                    Q = np.einsum("cjn,kjn->ckj", W, G)  # (2, n_steps - 1, m)
                if not np.all(np.isfinite(Q)):
                    return None, sweep
                mass = np.concatenate([mass0[None], Q[0]])
                b = np.concatenate([b0[None], Q[1]])
                Sn = S(mass)
                if coupling == "lagged":
                    new = Sn * dV
                else:
                    A_pred = np.minimum(np.maximum(mass - dV * Sn * b, 0.0), 1.0)
                    new = 0.5 * dV * (Sn + S(A_pred))
                res = new - dts
                if np.all(np.abs(res) <= _TRAJECTORY_TOL * np.max(dts, axis=0)):
                    return new, sweep
                if chord is None:  # c_n = dPhi/dA * b_n (docstring), from the first sweep's trajectory
                    A_c = np.minimum(np.maximum(mass, 1e-6), 1.0 - 1e-6)
                    c = dV * (S(A_c + 1e-6) - S(A_c - 1e-6)) / 2e-6 * b
                    alpha = 1.0 - c
                    P = np.cumprod(alpha, axis=0) if np.all((alpha > 0.25) & (alpha < 4.0)) else None
                    chord = (c, alpha, P)
                c, alpha, P = chord
                if P is not None:  # D_{n+1} = alpha_n D_n + r_n in closed form
                    D = np.concatenate([np.zeros((1, m)), P[:-1] * np.cumsum(res / P, axis=0)[:-1]])
                else:
                    D = np.zeros_like(res)
                    for n in range(1, res.shape[0]):
                        D[n] = alpha[n - 1] * D[n - 1] + res[n - 1]
                dts = dts + res - c * D
        return None, _TRAJECTORY_SWEEPS

    def _dst_closed(self, sp, C0, P_edge0, A0, dts, V_nodes, station_idx, theta, r_limit, w_edge, sweeps=0):
        """The whole march from given steps dts (n_steps, 1 or n_loads), all steps at once (see march)."""
        o = self.opts
        fun = sp.functionals
        m, N = C0.shape
        dp = self.dp
        n_steps, mm = dts.shape

        def contract(Wt, A):  # sum_j Wt[l, j] A[k, l or 0, j] -> (k, l): a matmul when loads share steps
            return (Wt @ A[:, 0, :].T).T if mm == 1 else np.einsum("lj,klj->kl", Wt, A)

        X = dts[:, :, None] * sp.lam
        R, F = self._amplify_all(X, theta)
        with np.errstate(over="ignore", invalid="ignore"):
            G = np.cumprod(R, axis=0)  # G[k]: amplification through step k
            np.copyto(G, 0.0, where=np.abs(G) < _FLUSH)  # no subnormals (see _FLUSH)
            F *= dts[:, :, None]
            F[1:] *= G[:-1]
            H = np.cumsum(F, axis=0)  # H[k]: wall-flux weight through step k
        r_max = 0.5 * float(np.max(dts)) / dp**2
        if theta == 0.0 and r_max > r_limit and not o["allow_unstable"]:
            raise ValueError(
                f"explicit scheme: r = dtau/(2 dp^2) = {r_max:.4g} exceeds the stability limit {r_limit:.4g} "
                "(the fudge factor enlarged dtau); raise n_steps or use an implicit scheme"
            )
        norm0 = np.sqrt(np.einsum("ij,ij->i", C0, C0))
        ks = np.array([k for k in range(n_steps) if (k + 1) % o["check_every"] == 0 or k + 1 == n_steps])
        with np.errstate(over="ignore", invalid="ignore"):
            Gk = G[ks]
            w_cons = fun[:, 0] - w_edge * dp**2 * (fun[:, 1] + fun[:, 2])  # the conserved sum(M P) dp
            mass_k = contract(C0 * w_cons, Gk).T  # (m, n_checks)
            norm_k = np.sqrt(contract(C0 * C0, Gk * Gk)).T
            mass_prev = np.concatenate([(C0 @ w_cons)[:, None], mass_k[:, :-1]], axis=1)
            bad = (
                ~(np.isfinite(Gk).all(axis=(1, 2)) & np.isfinite(mass_k).all(axis=0) & np.isfinite(norm_k).all(axis=0))
                | (mass_k < -1e-12).any(axis=0)
                | (mass_k > mass_prev * (1 + DEFAULT_TOLERANCES["area"]) + 1e-12).any(axis=0)
                | (norm_k > 2.0 * norm0[:, None] + 1e-300).any(axis=0)
            )
        if bad.any():
            i = int(np.argmax(bad))
            k = ks[i]
            with np.errstate(over="ignore", invalid="ignore"):
                Ck = C0 * G[k]
            self._check_dst(Ck, mass_k[:, i], mass_prev[:, i], norm_k[:, i], norm0, V_nodes[k + 1, 0], r_max)
            raise AssertionError("unreachable: a failed check raises")  # pragma: no cover
        K = station_idx - 1
        C_st = C0[None, :, :] * G[K]  # (n_st, m, N)
        P_out = sp.inverse(C_st)
        A_out = C_st @ fun[:, 0]
        J0 = contract(C0 * fun[:, 1], H[K])  # (n_st, m)
        Af_out = A0 - J0 + w_edge * dp * (P_out[:, :, 0] - P_edge0)
        JN_out = contract(C0 * fun[:, 2], H[K])  # (n_st, m): the plastic area gained (with a hardness wall)
        JN = contract(C0 * fun[:, 2], H[-1:])[0]
        return march_result(
            {"P_out": P_out, "A_out": A_out, "Af_out": Af_out, "JN_out": JN_out},
            JN,
            r_max,
            np.broadcast_to(dts.sum(axis=0), (m,)).copy(),
            {
                "linalg": "dst",
                "transforms": sp.transforms,
                "tridiagonal_solves": 0,
                "factorizations": 0,
                "picard_iterations": 0,
                "trajectory_sweeps": sweeps,
            },
        )

    def march(self, P, A0, V_nodes, station_idx, scheme, coupling, space, r_limit, w_edge) -> dict:
        r"""The time loop of the banded march in DST-II coefficient space (module docstring).

        Every step multiplies coefficient j by :math:`R(\Delta\tau\lambda_j)` (``_amplification``);
        A* and the wall fluxes are linear functionals of the coefficients, so the coupling of the
        fudge factor needs no transform; P is transformed back only at the output stations.
        """
        o, pr = self.opts, self.problem
        no_fudge = isinstance(pr.fudge, NoFudge)
        m, N = P.shape
        dp = self.dp
        sp = _Spectral(N, dp, space)
        fun = sp.functionals
        n_steps = V_nodes.shape[0] - 1
        theta = scheme.theta
        C0 = sp.forward(P)
        P_edge0 = P[:, 0].copy()
        norm0 = np.sqrt(np.einsum("ij,ij->i", C0, C0))
        rec = StationRecorder(station_idx, P_out=(m, N), A_out=(m,), Af_out=(m,), JN_out=(m,))
        hard, A_pl0 = self._hard, self._A_pl0
        too_big = (
            "explicit scheme: r = dtau/(2 dp^2) = {:.4g} exceeds the stability limit {:.4g} "
            "(the fudge factor enlarged dtau); raise n_steps or use an implicit scheme"
        )
        check_every = o["check_every"]

        if no_fudge and np.all(V_nodes == V_nodes[:, :1]):
            # one linear map per station: P_N = S^-1 diag(prod_k R_k) S P_0, all steps at once
            dV = np.diff(V_nodes[:, 0])
            dts = np.empty(n_steps)
            prev = None
            for n in range(n_steps):  # the banded path's rule for re-using a factorisation
                d = dV[n]
                if prev is not None and abs(d - prev) <= 1e-12 * d:
                    d = prev
                dts[n] = prev = d
            return self._dst_closed(sp, C0, P_edge0, A0, dts[:, None], V_nodes, station_idx, theta, r_limit, w_edge)
        if (
            not no_fudge
            and not hard
            and coupling != "picard"
            and n_steps >= _TRAJECTORY_MIN_STEPS
            and m <= _fudge_trajectory_max_loads
            and m * n_steps * N <= _TRAJECTORY_SIZE
        ):
            dts, sweeps = self._fudge_trajectory(sp, C0, V_nodes, theta, coupling)
            if dts is not None:
                return self._dst_closed(
                    sp, C0, P_edge0, A0, dts, V_nodes, station_idx, theta, r_limit, w_edge, sweeps=sweeps
                )

        # per-step march in coefficient space: dtau depends on the numerical A* (a functional)
        S = pr.fudge.S
        lam = sp.lam
        fun_w = np.ascontiguousarray(fun[:, [1, 2, 2, 3]])  # 4 columns again (see _Spectral)

        X = np.empty((m, N))
        work = (np.empty((m, N)), np.empty((m, N)), np.empty((m, N)))
        bufs = [np.empty((m, N)), np.empty((m, N))]  # the state and the next state, swapped every step

        kinds = [step_kind(self.opts, n) for n in range(n_steps)]
        dV_all = np.diff(V_nodes, axis=0)

        def step(C, dtau, n):
            np.multiply(dtau[:, None], lam, out=X)
            R, F, T = work
            _amplification(kinds[n], theta, X, work)
            np.multiply(C, F, out=T)
            fl = T @ fun_w
            Cn = bufs[1] if C is bufs[0] else bufs[0]
            np.multiply(C, R, out=Cn)
            return Cn, dtau * fl[:, 0], dtau * fl[:, 1]

        C = bufs[0]
        C[:] = C0
        flush = _FLUSH * float(np.max(norm0, initial=0.0))
        mass, b0, bN, _ = (C @ fun).T
        mass_prev = mass - w_edge * dp**2 * (b0 + bN)  # the checks' conserved sum(M P) dp (b = P_wall / dp)
        J0 = np.zeros(m)
        JN = np.zeros(m)
        picard_iters = 0
        dtau_max = r_max = 0.0
        dtau_total = np.zeros(m)
        dtau_prev = None
        for n in range(n_steps):
            dV = dV_all[n]
            if no_fudge:
                dtau = dV.copy()
                if dtau_prev is not None and np.all(np.abs(dtau - dtau_prev) <= 1e-12 * dtau):
                    dtau = dtau_prev
            else:  # S at the contact area: A_el (+ A_pl with a hardness wall, which keeps what it absorbs)
                total = mass + (A_pl0 + JN if hard else 0.0)
                loss = b0 if hard else b0 + bN
                Sn = S(np.minimum(total, 1.0))
                if coupling == "lagged":
                    dtau = Sn * dV
                else:
                    A_pred = np.minimum(np.maximum(total - dV * Sn * loss, 0.0), 1.0)
                    dtau = 0.5 * dV * (Sn + S(A_pred))
            Cn, dJ0, dJN = step(C, dtau, n)
            if coupling == "picard" and not no_fudge:
                for _ in range(o["picard_maxiter"]):
                    picard_iters += 1
                    dtau_new = 0.5 * dV * (Sn + S(np.clip(total - dJ0 - (0.0 if hard else dJN), 0.0, 1.0)))
                    if np.max(np.abs(dtau_new - dtau)) <= o["picard_tol"] * np.max(dtau):
                        dtau = dtau_new
                        break
                    dtau = dtau_new
                    Cn, dJ0, dJN = step(C, dtau, n)
            dtau_max = max(dtau_max, float(dtau.max()))
            r_max = 0.5 * dtau_max / dp**2
            if theta == 0.0 and r_max > r_limit and not o["allow_unstable"]:
                raise ValueError(too_big.format(r_max, r_limit))
            dtau_prev = dtau
            C = Cn
            if n % 8 == 7:
                np.copyto(C, 0.0, where=np.abs(C) < flush)  # no subnormals (see _FLUSH)
            J0 += dJ0
            JN += dJN
            dtau_total += dtau
            mass, b0, bN, _ = (C @ fun).T
            if (n + 1) % check_every == 0 or n + 1 == n_steps:
                norm = np.sqrt(np.einsum("ij,ij->i", C, C))
                cons = mass - w_edge * dp**2 * (b0 + bN)
                self._check_dst(C, cons, mass_prev, norm, norm0, V_nodes[n + 1, 0], r_max)
                mass_prev = cons
            if n + 1 in rec:
                Pst = sp.inverse(C)
                Af = A0 - J0 + w_edge * dp * (Pst[:, 0] - P_edge0)
                rec.record(n + 1, P_out=Pst, A_out=mass, Af_out=Af, JN_out=JN)
        return march_result(
            rec,
            JN,
            r_max,
            dtau_total,
            {
                "linalg": "dst",
                "transforms": sp.transforms,
                "tridiagonal_solves": 0,
                "factorizations": 0,
                "picard_iterations": picard_iters,
                "trajectory_sweeps": 0,
            },
        )
