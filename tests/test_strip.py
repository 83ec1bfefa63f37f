"""The elastoplastic strip (constant hardness): closed forms against quadrature and an independent ODE."""

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

import persson_fp as pf
from persson_fp.theory.hardness import CallableHardness, ConstantHardness, PowerLaw, resolve
from persson_fp.theory.strip import strip_cdf, strip_pdf, strip_quantities

SIG = 1.0
# tau below and above the image/sine switch at tau = sigma^2, and right at it
TAUS = [1e-3, 0.05, 0.4, 1.0, 2.5, 20.0]


@pytest.mark.parametrize("tau", TAUS)
@pytest.mark.parametrize("p_bar", [0.05, 0.3, 0.8])
def test_invariants_of_the_series_against_quadrature(p_bar, tau):
    """A_el, F_el, <p^2>_el against adaptive quadrature of the pdf; the two balances to round-off."""
    q = strip_quantities(p_bar, SIG, tau)
    kw = {"epsabs": 1e-14, "epsrel": 1e-12, "limit": 200, "points": [p_bar]}
    for k, key in enumerate(("elastic_area", "elastic_load", "elastic_second_moment")):
        ref = quad(lambda p, k=k: p**k * strip_pdf(p, p_bar, SIG, tau), 0.0, SIG, **kw)[0]
        assert q[key] == pytest.approx(ref, abs=1e-12)
    total = q["elastic_area"] + q["plastic_area"] + q["noncontact_area"]
    assert total == pytest.approx(1.0, abs=1e-14)
    assert q["elastic_load"] + q["plastic_load"] == pytest.approx(p_bar, rel=1e-13)
    assert strip_cdf(0.5 * SIG, p_bar, SIG, tau) == pytest.approx(
        quad(lambda p: strip_pdf(p, p_bar, SIG, tau), 0.0, 0.5 * SIG, **kw)[0], abs=1e-12
    )


@pytest.mark.parametrize("p_bar", [0.2, 0.7])
def test_absorbed_masses_are_time_integrals_of_the_wall_fluxes(p_bar):
    """A_non(tau) = int 1/2 dP/dp(0) dtau' and A_pl = int -1/2 dP/dp(sigma) dtau', the derivative by a
    4th-order difference of the closed-form pdf (h = 1e-4: error ~1e-12) and the time integral by quad."""
    h = 1e-4

    def dPdp(p, t):
        f = lambda x: strip_pdf(x, p_bar, SIG, t)  # noqa: E731
        if p == 0.0:  # one-sided with the odd extension (P is odd about the wall)
            return (8 * (f(h)) - (f(2 * h))) / (6 * h)
        return -(8 * f(p - h) - f(p - 2 * h)) / (6 * h)

    tau = 1.7
    A_non = quad(lambda t: 0.5 * dPdp(0.0, t), 1e-9, tau, epsabs=1e-12, limit=200)[0]
    A_pl = quad(lambda t: -0.5 * dPdp(SIG, t), 1e-9, tau, epsabs=1e-12, limit=200)[0]
    q = strip_quantities(p_bar, SIG, tau)
    assert q["noncontact_area"] == pytest.approx(A_non, abs=1e-8)
    assert q["plastic_area"] == pytest.approx(A_pl, abs=1e-8)


def test_limits_of_the_strip():
    """sigma -> infinity: the elastic image solution; tau -> infinity: A_el -> 0, A_pl -> p_bar / sigma."""
    q = strip_quantities(0.3, 50.0, 0.7)
    assert q["elastic_area"] == pytest.approx(float(pf.area_from_tau(0.3, 0.7)), abs=1e-14)
    q = strip_quantities(0.3, 1.0, 400.0)
    assert q["elastic_area"] < 1e-200 and q["plastic_area"] == pytest.approx(0.3, abs=1e-15)


def test_exact_with_a_fudge_factor_follows_the_effective_variance_ode():
    """tau(V) of YP08 with a hardness wall against an independent integration of dtau/dV = S(A_el + A_pl)."""
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.array([0.2, 1.0]), hardness=0.08)
    sig = 0.08
    S = pr.fudge.S

    def rhs(V, t):
        q = strip_quantities(pr.p_bar, sig, np.maximum(t, 1e-300))
        return S(q["elastic_area"] + q["plastic_area"])

    V_end = pr.V_max
    ref = solve_ivp(rhs, (1e-12, V_end), S(1.0) * 1e-12 * np.ones(2), method="Radau", rtol=1e-11, atol=1e-16)
    ex = pf.exact(pr)
    assert np.allclose(ex.tau, ref.y[:, -1], rtol=1e-8)
    # pf.exact derives A_el and F_el from the balances; the PDF's own moments must agree with them
    q = strip_quantities(pr.p_bar, sig, ex.tau)
    assert np.allclose(ex.elastic_area, q["elastic_area"], atol=1e-14)
    assert np.allclose(ex.elastic_load, q["elastic_load"], rtol=1e-13)
    # the inverse map used to place nodes
    assert np.allclose(pr.V_of_tau_each(ex.tau), V_end, rtol=1e-7)


def test_exact_variance_with_hardness_counts_the_yield_atom():
    pr = pf.ContactProblem.reference(p_bar_ratio=0.5, hardness=0.07)
    ex = pf.exact(pr)
    grid = np.linspace(0.0, 0.07, 20001)
    m2 = np.trapezoid(grid**2 * ex.pdf(grid), grid) + 0.07**2 * ex.plastic_area
    assert ex.variance == pytest.approx(m2 - pr.p_bar[0] ** 2, rel=1e-7)


def test_hardness_models():
    pl = PowerLaw(2.0, 0.25)
    z = np.array([1.0, 16.0])
    assert np.allclose(pl.sigma(z), [2.0, 4.0])
    assert np.allclose(pl.dsigma_dzeta(z), 0.25 * 2.0 * z**-0.75)
    c = CallableHardness(lambda z: 2.0 * z**0.25)
    assert np.allclose(c.dsigma_dzeta(z), pl.dsigma_dzeta(z), rtol=1e-8)
    assert isinstance(resolve(0.3), ConstantHardness) and resolve(None) is None
    assert PowerLaw(1.0, 0.0).is_constant


@pytest.mark.parametrize(
    "hardness, match",
    [
        (-1.0, "hardness (sigma )?must be > 0"),
        (True, "hardness must be None"),
        ("hard", "hardness must be None"),
        (lambda z: 1.0 / z, "non-decreasing"),
        (lambda z: np.nan * z, "finite"),
        (1e-4, "p_bar must be < sigma_Y"),
    ],
)
def test_bad_hardness_is_a_value_error(hardness, match):
    with pytest.raises(ValueError, match=match):
        pf.ContactProblem.reference(hardness=hardness)


def test_bad_power_law_exponent():
    with pytest.raises(ValueError, match=r"n \(hardness exponent\) must lie in \[0, 2\]"):
        PowerLaw(1.0, -0.1)


def test_exact_refuses_a_moving_wall():
    pr = pf.ContactProblem.reference(hardness=PowerLaw(0.1, 0.2))
    with pytest.raises(ValueError, match="no closed form"):
        pf.exact(pr)


@pytest.mark.parametrize("tau", TAUS)
def test_strip_areas_are_the_absorbed_masses_of_strip_quantities(tau):
    from persson_fp.theory.strip import strip_areas

    q = strip_quantities(0.3, SIG, tau)
    A_non, A_pl = strip_areas(0.3, SIG, tau)
    assert A_non == pytest.approx(q["noncontact_area"], abs=1e-15) and A_pl == pytest.approx(
        q["plastic_area"], abs=1e-15
    )
    assert 1.0 - A_non - A_pl == pytest.approx(q["elastic_area"], abs=1e-14)  # the balance ExactSolution uses
