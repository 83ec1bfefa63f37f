"""The front-fixed engine's fluxes on general Fokker-Planck coefficients: a manufactured solution (orders in p and V).

Manufactured solution in the complete-contact variance V (the solvers' time variable) on p in [0, L], with
absorbing walls at both ends:

    P*(p, V) = exp(-V / T) sin(pi p / L) (1 + p / (2L)),
    B1 = c (p / L) V'(zeta),  B2 = d (1 + eps p / L) V'(zeta)   (so b1 = B1 / V', b2 = B2 / V' are V-independent),

and the source f = dP*/dV + d(b1 P*)/dp - 1/2 d^2(b2 P*)/dp^2, written out below by hand.  The wall fluxes are
known in closed form too, so the absorbed masses are checked as well.
"""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.front_fixed.moving_wall import MovingWall
from persson_fp.solvers.mol.lines import solve_lines

C, D, EPS = 0.3, 0.8, 0.5  # drift, diffusion and its slope (dimensionless, times V')
PSD = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=64.0)
P_BAR = 0.02
_GL = np.polynomial.legendre.leggauss(4)


def _problem():
    dV = lambda z: float(PSD.dV_dzeta(z))  # noqa: E731
    L = _problem.L
    return pf.FokkerPlanckProblem(
        PSD, p_bar=P_BAR, B1=lambda p, z: C * (p / L) * dV(z), B2=lambda p, z: D * (1 + EPS * p / L) * dV(z)
    )


def _domain():
    pr = pf.ContactProblem(PSD, p_bar=P_BAR)
    return pr.p_max(10.0), pr.V_max


_problem.L, V_MAX = _domain()
T = V_MAX  # decay scale of the manufactured solution


def _g(p, L):
    k = np.pi / L
    g = np.sin(k * p) * (1 + p / (2 * L))
    g1 = k * np.cos(k * p) * (1 + p / (2 * L)) + np.sin(k * p) / (2 * L)
    g2 = -(k**2) * np.sin(k * p) * (1 + p / (2 * L)) + k * np.cos(k * p) / L
    return g, g1, g2


def _P(p, V, L):
    return np.exp(-V / T) * _g(p, L)[0]


def _f(p, V, L):
    """dP/dV + d(b1 P)/dp - 1/2 d^2(b2 P)/dp^2 for P = exp(-V/T) g(p)."""
    g, g1, g2 = _g(p, L)
    b1, b1p = C * p / L, C / L
    b2, b2p = D * (1 + EPS * p / L), D * EPS / L
    return np.exp(-V / T) * (-g / T + b1p * g + b1 * g1 - 0.5 * (2 * b2p * g1 + b2 * g2))


def _cell_avg(fun, n, L):
    """Cell averages on n cells of [0, L] by 4-point Gauss-Legendre (error ~h^8)."""
    x, w = _GL
    edges = np.linspace(0, L, n + 1)
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    pts = mid[:, None] + half[:, None] * x[None, :]
    return (fun(pts) * w).sum(axis=1) / 2.0


def _run(n, steps=None, rtol=None):
    """Error (max over cells of the cell averages of P) at V_end, and the absorbed mass at p = 0."""
    pr = _problem()
    L = _problem.L
    mw = MovingWall(pr, n, 10.0, p_end=L)  # the manufactured solution lives on [0, L]
    V0, V1 = 0.1 * T, 0.6 * T
    y0 = np.zeros((1, n + 1))
    y0[0, :n] = L * _cell_avg(lambda p: _P(p, V0, L), n, L)  # w = L P
    src_cache = {}

    def source(V):
        if V not in src_cache:
            out = np.zeros((1, n + 1))
            out[0, :n] = L * _cell_avg(lambda p: _f(p, V, L), n, L)
            src_cache[V] = out
        return src_cache[V]

    if steps is not None:
        r = mw.solve(np.array([V1]), steps, V0=V0, y0=y0, source=source, damped=0)
    else:
        r = solve_lines(mw, np.array([V1]), rtol, rtol * 1e-3, "BDF", 0.05, V0=V0, y0=y0, source=source)
    P_num = r["W"][-1, 0] / L
    P_ex = _cell_avg(lambda p: _P(p, V1, L), n, L)
    # absorbed at p = 0: int 1/2 d(b2 P)/dp at 0 dV = 1/2 b2(0) g'(0) int exp(-V/T) dV
    k = np.pi / L
    A_non = 0.5 * D * k * T * (np.exp(-V0 / T) - np.exp(-V1 / T))
    return np.max(np.abs(P_num - P_ex)) * L, abs(r["noncontact_area"][-1, 0] - A_non), P_num * L


def _slope(ns, errs):
    return -np.polyfit(np.log(ns), np.log(errs), 1)[0]


@pytest.mark.slow
def test_fv_manufactured_solution_second_order_in_p_and_in_V():
    """Observed orders of the finite-volume fluxes with p-dependent B2 and a drift B1, fitted within 0.1 of 2:
    in p against the manufactured solution (measured 1.95; the absorbed mass 1.99), in V by self-convergence
    against a 640-step run at the same grid (the time error is far below the space error here)."""
    ns = np.array([40, 80, 160])
    space = [_run(n, steps=100) for n in ns]
    assert abs(_slope(ns, [e[0] for e in space]) - 2.0) < 0.1
    assert abs(_slope(ns, [e[1] for e in space]) - 2.0) < 0.1  # the wall flux, time-integrated
    steps = np.array([5, 10, 20, 40])
    ref = _run(40, steps=640)[2]
    time_ = [np.max(np.abs(_run(40, steps=k)[2] - ref)) for k in steps]
    assert abs(_slope(steps, time_) - 2.0) < 0.1


def test_mol_manufactured_solution_second_order_in_p():
    """The method of lines on the same fluxes (time to rtol 1e-10): second order in p (measured 1.95)."""
    ns = np.array([40, 80, 160])
    errs = [_run(n, rtol=1e-10)[0] for n in ns]
    assert abs(_slope(ns, errs) - 2.0) < 0.1
