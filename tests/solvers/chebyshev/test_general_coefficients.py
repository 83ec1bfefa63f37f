"""method="chebyshev" beyond the separable form: the clock path, the adaptive march on non-separable problems, and
auto's routing of these classes.

References, none of them the engine:
- B2 = kappa V'(zeta) s(V), B1 = mu B2 with s(V) = 1 + a V / V_max is Brownian motion with drift absorbed at 0 in
  the clock T = kappa (V + a V^2 / (2 V_max)) (closed form): the image solution with drift (Cox & Miller 1965);
  the adaptive marches are checked on it by forcing them (``march="radau"``, ``march="magnus"``);
- the Ornstein--Uhlenbeck case of ``test_error_estimates`` (drift and diffusion that do not commute; Gaussian
  mean and variance from their ODEs) for the march on a genuinely non-separable problem;
- a fine ``fv`` run with its own estimate for B2 = (1 + p / p_bar f(zeta)) dV/dzeta (slow).
"""

import math

import numpy as np
import pytest
from scipy.special import ndtr

import persson_fp as pf

from .test_error_estimates import _ou_case, poly_cell_masses

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


@pytest.mark.parametrize(
    "seed, march", [(s, None) for s in range(4)] + [(s, m) for s in range(2) for m in ("radau", "magnus")]
)
def test_clock_and_march_against_the_image_solution(seed, march):
    from persson_fp.solvers.chebyshev.solver import TIME_SHARE  # (the march's first tol, a multiple of tol)

    rng = np.random.default_rng(seed)
    kappa, a = float(rng.uniform(0.5, 2.0)), float(rng.uniform(0.3, 1.5))
    mu = float(rng.uniform(-1.0, 1.0)) / math.sqrt(kappa * VMAX)
    p_bar = float(rng.uniform(0.5, 2.0)) * math.sqrt(kappa * VMAX)
    tol = float(10.0 ** rng.uniform(-9, -5)) if march is None else float(10.0 ** rng.uniform(-7, -5))
    sol = pf.solve(_clock_problem(kappa, a, mu, p_bar), method="chebyshev", tol=tol, march=march, max_time=600)
    assert sol.info["path"] == (march or "clock")
    L1, dA, eL1, eA = _errors(sol, lambda e: _clock_exact(kappa, a, mu, p_bar, PSD.zeta_max, e))
    assert eL1 <= tol and eA <= tol
    assert L1 <= max(eL1, 1e-12) and dA <= max(eA, 1e-12), (L1, eL1, dA, eA)
    if march == "magnus":
        m = sol.info["march"]
        assert m["steps"] >= 1 and m["expm"] >= 8 * m["steps"] - 2 and m["tol"] <= TIME_SHARE * tol
    elif march == "radau":
        m = sol.info["march"]
        assert m["steps"] >= 1 and m["solves"] >= 3 * m["steps"] and m["tol"] <= TIME_SHARE * tol


@pytest.mark.parametrize("seed", range(2))
def test_march_on_a_non_separable_problem_against_its_gaussian(seed):
    rng = np.random.default_rng(40 + seed)
    pr, exact, label, _ = _ou_case(rng)
    tol = 1e-5
    sol = pf.solve(pr, method="chebyshev", tol=tol, max_time=600)  # (not the default budget: machines differ)
    assert sol.info["path"] == "radau"
    L1, dA, eL1, eA = _errors(sol, lambda e: exact(e, PSD.zeta_max))
    assert eL1 <= tol and L1 <= eL1 and dA <= eA, (label, L1, eL1, dA, eA)


@pytest.mark.slow
def test_non_separable_against_a_fine_finite_volume_run():
    # B2 = (1 + p / p_bar f(zeta)) dV/dzeta: no closed form; fv at its own estimate is the (stated) reference
    def B2(p, z):
        return PSD.dV_dzeta(z) * (1.0 + p / PB * 0.5 * (1.0 + math.sin(math.log(z))))

    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=B2)
    sol = pf.solve(fp, method="chebyshev", tol=1e-6)
    ref = pf.solve(fp, method="fv", n_p=1600, n_steps=1600)
    assert sol.info["path"] == "radau"
    e_ref = float(ref.error_estimate["contact_area"][-1, 0])
    e = float(sol.error_estimate["contact_area"][-1, 0])
    assert e_ref < 1e-4
    assert abs(float(sol.contact_area_all[-1, 0]) - float(ref.contact_area_all[-1, 0])) <= e + e_ref


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
    [(_zeta_dependent, "radau"), (_general_strip, "clock"), (lambda: _clock_problem(1, 0.5, 0, PB), "clock")],
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
