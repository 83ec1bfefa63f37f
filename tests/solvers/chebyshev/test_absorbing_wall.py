"""method="chebyshev" at the wall p = 0: coefficients defined only for p >= 0, and a diffusion that vanishes there.

References written here, none of them the engine:
- the image solution of Brownian motion with drift absorbed at 0;
- for B2 = kappa p^a dV/dzeta (0 <= a < 2), the Lamperti variable Y = p^(1 - a/2) / (sqrt(kappa) (1 - a/2)) is a
  Bessel process in V of index nu = -1 / (2 - a), absorbed at 0, whose hitting time of 0 from Y0 is Y0^2 / (2G) with
  G ~ Gamma(|nu|) (Revuz & Yor, Continuous Martingales and Brownian Motion, Ch. XI): A*(V) = P(|nu|, Y0^2 / 2V),
  the regularised lower incomplete gamma function; a = 1 (the squared Bessel process of dimension 0) gives
  A* = 1 - exp(-2 p_bar / (kappa V)).
"""

import numpy as np
import pytest
from scipy.special import gammainc, ndtr

import persson_fp as pf
from persson_fp.solvers.chebyshev import ChebyshevSolver

REF = pf.ContactProblem.reference()
PSD, PB, VMAX = REF.psd, float(REF.p_bar[0]), float(REF.V_max)


def _power_diffusion(p_bar, kappa, a, psd=PSD):
    """B2 = kappa p^a dV/dzeta: a diffusion vanishing at the wall p = 0 like p^a."""
    return pf.FokkerPlanckProblem(psd, p_bar=p_bar, B2=lambda p, z: kappa * np.maximum(p, 0.0) ** a * psd.dV_dzeta(z))


def _bessel_area(p_bar, kappa, a, V):
    """A*(V) for B2 = kappa p^a dV/dzeta (module docstring)."""
    Y0 = p_bar ** (1.0 - 0.5 * a) / (np.sqrt(kappa) * (1.0 - 0.5 * a))
    return float(gammainc(1.0 / (2.0 - a), Y0**2 / (2.0 * V)))


def test_bessel_area_reference_is_the_squared_bessel_one_at_a_equal_1():
    kappa = 2.0 * PB / VMAX
    assert _bessel_area(PB, kappa, 1.0, VMAX) == pytest.approx(1.0 - np.exp(-2.0 * PB / (kappa * VMAX)), rel=1e-14)


def test_coefficients_undefined_below_the_wall_are_never_evaluated_there():
    """B1, B2 that are NaN for p < 0 (a natural way to write (p / p_bar)^a) are never evaluated there: the start's
    finite-difference stencils once reached p < 0 and the solve was refused as "B2 must be finite"; the result is the
    image solution."""
    b, c = 1.7, -0.4 * PB / VMAX

    def B2(p, z):
        return np.where(np.asarray(p) >= 0, b * float(PSD.dV_dzeta(z)), np.nan)

    def B1(p, z):
        return np.where(np.asarray(p) >= 0, c * float(PSD.dV_dzeta(z)), np.nan)

    for tol in (1e-3, 1e-6):  # (both refused before)
        sol = pf.solve(pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=B1, B2=B2), method="chebyshev", tol=tol)
        s, m = np.sqrt(b * VMAX), PB + c * VMAX
        # A* of the image solution phi(p - m) - exp(-2 c p_bar / b) phi(p + p_bar - cV), integrated over p > 0
        A_exact = ndtr(m / s) - np.exp(-2 * c * PB / b) * ndtr((c * VMAX - PB) / s)
        est = float(np.max(sol.error_estimate["contact_area"]))
        assert abs(float(sol.contact_area[-1]) - A_exact) <= est <= tol


def test_diffusion_vanishing_linearly_at_the_wall_is_declined_at_once_and_auto_meets_the_closed_form():
    kappa = 2.0 * PB / VMAX  # A* = 1 - e^-1
    fp = _power_diffusion(PB, kappa, 1.0)
    with pytest.raises(ValueError, match=r"vanishes at the wall p = 0 \(like p\^1"):
        pf.solve(fp, method="chebyshev", tol=1e-3)
    # declined while the options are checked, before any degree is tried (it used to run to degree 400 and end in
    # "loosen tol"): the solver cannot even be built
    with pytest.raises(ValueError, match=r"vanishes at the wall p = 0 \(like p\^1"):
        ChebyshevSolver(fp, tol=1e-3)
    sol = pf.solve(fp, method="auto", tol=1e-3)
    assert sol.info["auto"]["method"] == "fv"
    err = abs(float(sol.contact_area[-1]) - _bessel_area(PB, kappa, 1.0, VMAX))
    assert err <= float(np.max(sol.error_estimate["contact_area"])) <= 1e-3


@pytest.mark.parametrize("p_bar", [0.05, 0.07])
def test_diffusion_like_p_to_the_0_9_is_declined(p_bar):
    # B2 = 0.1 p^0.9 V' at p_bar = 0.05 once measured its exponent a hair below 0.9 (round-off of log2 of two
    # samples) and was not declined: it ran to degree 400 and ended in 'loosen tol'
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, H=0.8, q_l=1.0, q_r=1.0, q_s=100.0)
    with pytest.raises(ValueError, match="vanishes at the wall"):
        pf.solve(_power_diffusion(p_bar, 0.1, 0.9, psd), "chebyshev", tol=1e-6)


@pytest.mark.parametrize("a", [0.3, 0.5])
def test_diffusion_vanishing_slower_than_linearly_meets_the_bessel_closed_form(a):
    """B2 ~ p^a, a < 0.9: P ~ p^(1 - a) vanishes at the wall, so the spectral wall holds (algebraic convergence
    there): A* within its estimate of the closed form, and the estimate within tol."""
    kappa = PB**-a  # B2 = (p / p_bar)^a dV/dzeta: A* ~ 0.37
    for tol in (1e-3, 1e-4):
        sol = pf.solve(_power_diffusion(PB, kappa, a), method="chebyshev", tol=tol)
        err = abs(float(sol.contact_area[-1]) - _bessel_area(PB, kappa, a, VMAX))
        assert err <= float(np.max(sol.error_estimate["contact_area"])) <= tol


def test_diffusion_like_p_to_the_0_85_is_refused_or_right():
    """Just below the decline threshold (P ~ p^0.15 at the wall) chebyshev may not converge: it refuses openly, and
    never returns an area outside its estimate of the closed form."""
    kappa = PB**-0.85
    try:
        sol = pf.solve(_power_diffusion(PB, kappa, 0.85), method="chebyshev", tol=1e-3)
    except pf.SolverError as err:
        assert "exceeds tol" in str(err)
    else:
        err = abs(float(sol.contact_area[-1]) - _bessel_area(PB, kappa, 0.85, VMAX))
        assert err <= float(np.max(sol.error_estimate["contact_area"]))
