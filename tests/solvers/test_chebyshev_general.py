"""method="chebyshev" beyond the separable form: the clock path, the adaptive march, a constant hardness.

References, none of them the engine:
- B2 = kappa V'(zeta) s(V), B1 = mu B2 with s(V) = 1 + a V / V_max is Brownian motion with drift absorbed at 0 in
  the clock T = kappa (V + a V^2 / (2 V_max)) (closed form): the image solution with drift (Cox & Miller 1965);
  the adaptive march is checked on it by forcing it (``march="magnus"``);
- the Ornstein--Uhlenbeck case of ``test_chebyshev_honesty`` (drift and diffusion that do not commute; Gaussian
  mean and variance from their ODEs) for the march on a genuinely non-separable problem;
- the strip series :func:`persson_fp.exact` for the homogenised problem with a constant hardness, and the load
  balance F_el + sigma_Y A_pl = p_bar (the plastic area comes from the wall flux, not from that balance);
- a fine ``fv`` run with its own estimate for B2 = (1 + p / p_bar f(zeta)) dV/dzeta (slow).
"""

import math

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.special import ndtr

import persson_fp as pf
from persson_fp.solvers.chebyshev import magnus

from .test_chebyshev_honesty import _ou_case, poly_cell_masses

REF = pf.ContactProblem.reference()
PSD, PB, VMAX = REF.psd, float(REF.p_bar[0]), float(REF.V_max)


def _clock_problem(kappa, a, mu, p_bar):
    def B2(p, z):
        return np.full(np.shape(p), kappa * float(PSD.dV_dzeta(z)) * (1.0 + a * float(PSD.V(z)) / VMAX))

    B1 = None if mu == 0 else (lambda p, z: mu * B2(p, z))
    return pf.FokkerPlanckProblem(PSD, p_bar=p_bar, B1=B1, B2=B2)


def _clock_exact(kappa, a, mu, p_bar, z, edges):
    V = float(PSD.V(z))
    T = kappa * (V + 0.5 * a * V * V / VMAX)

    def cells(c):
        return np.diff(ndtr((edges - c - mu * T) / math.sqrt(T)))

    mass = cells(p_bar) - math.exp(-2.0 * mu * p_bar) * cells(-p_bar)
    s = math.sqrt(T)
    area = ndtr((p_bar + mu * T) / s) - math.exp(-2.0 * mu * p_bar) * ndtr((-p_bar + mu * T) / s)
    return mass, area


def _errors(sol, exact):
    """(true L1, true A error, L1 estimate, area estimate) at the last station."""
    edges = np.linspace(0.0, float(np.atleast_2d(sol.p)[-1][-1]), 3001)
    mass, area = exact(edges)
    L1 = float(np.sum(np.abs(poly_cell_masses(sol, -1, edges) - mass)))
    est = sol.info["error_estimate"]
    dA = abs(float(sol.contact_area_all[-1, 0]) - area)
    return L1, dA, float(est["L1"][-1, 0]), float(est["elastic_area"][-1, 0])


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("march", [None, "magnus"])
def test_clock_and_march_against_the_image_solution(seed, march):
    rng = np.random.default_rng(seed)
    kappa, a = float(rng.uniform(0.5, 2.0)), float(rng.uniform(0.3, 1.5))
    mu = float(rng.uniform(-1.0, 1.0)) / math.sqrt(kappa * VMAX)
    p_bar = float(rng.uniform(0.5, 2.0)) * math.sqrt(kappa * VMAX)
    tol = float(10.0 ** rng.uniform(-9, -5)) if march is None else float(10.0 ** rng.uniform(-7, -5))
    sol = pf.solve(_clock_problem(kappa, a, mu, p_bar), method="chebyshev", tol=tol, march=march)
    assert sol.info["path"] == ("clock" if march is None else "magnus")
    L1, dA, eL1, eA = _errors(sol, lambda e: _clock_exact(kappa, a, mu, p_bar, PSD.zeta_max, e))
    assert eL1 <= tol and eA <= tol
    assert L1 <= max(eL1, 1e-12) and dA <= max(eA, 1e-12), (L1, eL1, dA, eA)
    if march:
        m = sol.info["march"]
        assert m["steps"] >= 1 and m["expm"] >= 8 * m["steps"] - 2 and m["tol"] <= tol


@pytest.mark.parametrize("seed", range(2))
def test_march_on_a_non_separable_problem_against_its_gaussian(seed):
    rng = np.random.default_rng(40 + seed)
    pr, exact, label, _ = _ou_case(rng)
    tol = 1e-5
    sol = pf.solve(pr, method="chebyshev", tol=tol)
    assert sol.info["path"] == "magnus"
    L1, dA, eL1, eA = _errors(sol, lambda e: exact(e, PSD.zeta_max))
    assert eL1 <= tol and L1 <= eL1 and dA <= eA, (label, L1, eL1, dA, eA)


def test_commutator_free_step_is_fourth_order():
    # a small non-commuting system y' = A(t) y against DOP853 at 1e-13: the error of the fixed-step march falls
    # as h^4 (log-log fit)
    rng = np.random.default_rng(0)
    A0, A1, A2 = (rng.normal(size=(1, 4, 4)) for _ in range(3))

    def A_of(t):
        return A0 + np.sin(t) * A1 + t * t * A2

    y0 = np.ones((1, 4))
    ref = solve_ivp(lambda t, y: A_of(t)[0] @ y, (0.0, 1.0), y0[0], method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
    ns = np.array([8, 16, 32, 64])
    errs = []
    for n in ns:
        y = y0
        for k in range(n):
            y = magnus.cf4_step(A_of, k / n, 1.0 / n, y)
        errs.append(float(np.max(np.abs(y[0] - ref))))
    slope = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert slope >= 3.9, (errs, slope)
    # and exact for a constant operator (the separable case), to round-off
    y = magnus.cf4_step(lambda t: A0, 0.0, 0.7, y0)
    assert np.allclose(y, y0 @ sla.expm(0.7 * A0[0]).T, rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize("H", [0.04, 0.075, 0.2])
@pytest.mark.parametrize("tol", [1e-6, 1e-9])
def test_constant_hardness_against_the_strip_series(H, tol):
    pr = pf.ContactProblem.reference(hardness=H)
    sol = pf.solve(pr, method="chebyshev", tol=tol, zeta_out=[8.0, 40.0, PSD.zeta_max])
    c = sol.compare()
    est = sol.error_estimate
    for q in ("elastic_area", "plastic_area", "noncontact_area"):
        true = getattr(c, f"{q}_error")
        assert np.all(true <= np.maximum(est[q], 1e-12)), (q, true, est[q])
        assert np.all(est[q] <= tol)
    assert np.all(c.L1 <= np.maximum(est["L1"], 1e-12))
    # the areas balance, and A_pl from the wall flux meets the load balance F_el + sigma_Y A_pl = p_bar
    total = sol.elastic_area_all + sol.plastic_area_all + (1.0 - sol.contact_area_all)
    assert np.allclose(total, 1.0, rtol=0, atol=1e-15)
    balance = np.abs(sol.load_all - PB) / PB  # int p P0 dp + sigma_Y A_pl
    assert np.all(balance <= 10 * tol + 1e-11), balance
    assert sol.info["mass_balance_residual"] <= tol


@pytest.mark.filterwarnings("ignore:chebyshev. P0 has negative values")
def test_hardness_observed_order_is_spectral():
    pr = pf.ContactProblem.reference(hardness=0.075)
    ns = np.array([16, 20, 24, 28, 32])
    errs = [float(pf.solve(pr, method="chebyshev", n_p=int(n), V0_fraction=1e-2).compare().L1[0, 0]) for n in ns]
    slope = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert errs[-1] < 1e-5 and slope >= 4.0, (errs, slope)


@pytest.mark.slow
def test_non_separable_against_a_fine_finite_volume_run():
    # B2 = (1 + p / p_bar f(zeta)) dV/dzeta: no closed form; fv at its own estimate is the (stated) reference
    def B2(p, z):
        return PSD.dV_dzeta(z) * (1.0 + p / PB * 0.5 * (1.0 + math.sin(math.log(z))))

    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=B2)
    sol = pf.solve(fp, method="chebyshev", tol=1e-6)
    ref = pf.solve(fp, method="fv", n_p=1600, n_steps=1600)
    assert sol.info["path"] == "magnus"
    e_ref = float(ref.error_estimate["contact_area"][-1, 0])
    e = float(sol.error_estimate["contact_area"][-1, 0])
    assert e_ref < 1e-4
    assert abs(float(sol.contact_area_all[-1, 0]) - float(ref.contact_area_all[-1, 0])) <= e + e_ref


def test_march_option_and_refusals():
    with pytest.raises(ValueError, match="march"):
        pf.solve(REF, method="chebyshev", march="rk4")
    sol = pf.solve(REF, method="chebyshev", tol=1e-6, march="magnus")  # constant operator: one step suffices
    assert sol.info["path"] == "magnus" and float(np.max(sol.compare().L1)) <= 1e-6


def _zeta_dependent():
    def B2(p, z):
        return PSD.dV_dzeta(z) * (1.0 + p / PB * 0.2 * math.log(z))

    return pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=B2)


def _general_strip():
    def B2(p, z):
        return np.full(np.shape(p), 1.5 * float(PSD.dV_dzeta(z)) * (1.0 + 0.5 * float(PSD.V(z)) / VMAX))

    return pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=B2, B1=lambda p, z: -0.3 / PB * B2(p, z), hardness=3.0 * PB)


@pytest.mark.parametrize(
    "make, path",
    [(_zeta_dependent, "magnus"), (_general_strip, "clock"), (lambda: _clock_problem(1, 0.5, 0, PB), "clock")],
)
def test_auto_routes_the_new_classes_to_chebyshev(make, path):
    sol = pf.solve(make(), method="auto", tol=1e-6)
    a = sol.info["auto"]
    assert a["method"] == "chebyshev" and sol.info["path"] == path and path in a["why"]
    est = sol.error_estimate
    assert max(float(np.max(est[q])) for q in ("L1", "contact_area")) <= 1e-6


def test_auto_falls_through_to_fv_where_chebyshev_declines():
    # a moving wall is not chebyshev's: the front-fixed engine
    pr = pf.FokkerPlanckProblem(PSD, p_bar=PB, hardness=pf.hardness.PowerLaw(3.0 * PB, 0.2))
    sol = pf.solve(pr, method="auto", tol=1e-3)
    assert sol.info["auto"]["method"] == "fv"
