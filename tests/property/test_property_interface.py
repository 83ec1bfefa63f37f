"""Property tests of what happens in the gaps: traction laws against their work of adhesion by quadrature, the
stickiness criteria against their published formulas (Persson & Tosatti 2001; Pastewka & Robbins, PNAS 111 (2014)
3298, Eq. 10) with the spectral moments by quadrature, the DMT pull-off against a brute-force minimum of the
applied load, the leak rate's exact scaling with viscosity and pressure drop, and Barber's relation between
conductance and stiffness (Proc. R. Soc. A 459 (2003) 53)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.special import erfcx

import persson_fp as pf

from .strategies import log_uniform, moment_quad, problems, self_affine, slow_scale


def _work(law, rho):
    cuts = [0.0, rho, 10 * rho, 100 * rho, 1e4 * rho]
    return math.fsum(
        quad(lambda u: float(law.sigma(np.array([u]))[0]), a, b, epsabs=0, epsrel=1e-11, limit=200)[0]
        for a, b in zip(cuts, cuts[1:])
    )


@given(log_uniform(1e-6, 1e2), log_uniform(1e-9, 1e-3), st.floats(-3.0, 3.0), log_uniform(1e-3, 1e2))
def test_property_traction_laws_carry_their_work_of_adhesion(w, rho, c, h):
    """Each traction law is >= 0 and integrates to its work of adhesion w (quadrature here, 1e-7; the Lennard-Jones
    tail beyond 1e4 rho carries < 1e-8 w); a callable law's w is its integral; resolve_interaction keeps a law
    and wraps a callable; the exponential law's folded mean is E[sigma(|X|)] for X ~ N(c rho, (h rho)^2) (1e-7)."""
    laws = [
        pf.adhesion.Exponential(w, rho),
        pf.adhesion.MaugisDugdale(w, w / rho),
        pf.adhesion.LennardJones93(w, rho),
        pf.adhesion.CallableInteraction(lambda u: (w / rho) * np.exp(-np.asarray(u) / rho), rho),
    ]
    for law in laws:
        assert isinstance(law, pf.adhesion.Interaction)
        assert pf.adhesion.resolve_interaction(law) is law
        u = rho * np.geomspace(1e-3, 1e3, 50)
        assert np.all(law.sigma(u) >= 0)
        assert _work(law, rho) == pytest.approx(w, rel=1e-7)
        assert law.w == pytest.approx(w, rel=1e-7)
    wrapped = pf.adhesion.resolve_interaction(lambda u: (w / rho) * np.exp(-np.asarray(u) / rho), rho)
    assert isinstance(wrapped, pf.adhesion.CallableInteraction) and wrapped.w == pytest.approx(w, rel=1e-7)
    ex = laws[0]
    mu, s = c * rho, h * rho

    def f(x):
        return (
            float(ex.sigma(np.array([abs(x)]))[0])
            * math.exp(-((x - mu) ** 2) / (2 * s * s))
            / (s * math.sqrt(2 * math.pi))
        )

    pts = sorted({mu - 12 * s, 0.0, mu + 12 * s})
    pts = [x for x in pts if mu - 12 * s <= x <= mu + 12 * s]
    ref = math.fsum(quad(f, a, b, epsabs=0, epsrel=1e-11, limit=200)[0] for a, b in zip(pts, pts[1:]))
    assert float(np.asarray(ex.folded_mean(np.array([mu]), np.array([s])))[0]) == pytest.approx(
        ref, rel=1e-7, abs=1e-14 * w / rho
    )


@given(self_affine(max_zeta=1e4), log_uniform(1e-3, 1e3), log_uniform(1e-6, 1e2), log_uniform(1e-9, 1e-3))
def test_property_stickiness_criteria_are_their_formulas(psd, E, w, rho):
    """Persson--Tosatti: w_eff = w A_true/A_0 - (pi/2) E* int q^2 C dq with A_true/A_0 = 1 + 1/2 sqrt(pi/lambda)
    erfcx(sqrt(lambda)), lambda = 1/<|grad h|^2>; Pastewka--Robbins: Pi = h' E* rho / (2 w) (h'^2 / (h'' rho))^(2/3)
    with h'' = 1/2 <(lap h)^2>^(1/2); Tabor mu = (1/h'')^(1/3) (w/E*)^(2/3) / rho; moments by quadrature (1e-8)."""
    m2 = moment_quad(psd, 2.0)
    m4 = moment_quad(psd, 4.0)
    U_el = 0.25 * E * moment_quad(psd, 1.0)  # (pi/2) E int q^2 C dq = E/4 * 2 pi int q^2 C dq
    lam = 1.0 / m2
    ratio = 1.0 + 0.5 * math.sqrt(math.pi / lam) * erfcx(math.sqrt(lam))
    pt = pf.adhesion.persson_tosatti(psd, E, w)
    assert pt["U_el"] == pytest.approx(U_el, rel=1e-8)
    assert pt["area_ratio"] == pytest.approx(ratio, rel=1e-10)
    assert pt["w_eff"] == pytest.approx(w * ratio - U_el, rel=1e-8, abs=1e-8 * (w * ratio + U_el))
    assert pt["sticky"] == (pt["w_eff"] > 0)
    h1, h2 = math.sqrt(m2), 0.5 * math.sqrt(m4)
    pr = pf.adhesion.pastewka_robbins(psd, E, w, rho)
    assert pr["number"] == pytest.approx(h1 * E * rho / (2 * w) * (h1 * h1 / (h2 * rho)) ** (2 / 3), rel=1e-8)
    assert pr["sticky"] == (pr["number"] < 1)
    tabor = pf.adhesion.tabor_parameter(psd, E, w, rho)
    assert tabor == pytest.approx((1 / h2) ** (1 / 3) * (w / E) ** (2 / 3) / rho, rel=1e-8)


@slow_scale(0.3)
@given(problems(lo=1e-2, hi=2.0, n_max=2, max_zeta=1e3, fudge="WM17"), st.floats(0.02, 2.0), st.floats(0.01, 1.0))
def test_property_pull_off_is_the_least_applied_load(pr, w_scale, rho_scale):
    """The DMT pull-off is minus the least applied load p_rep - p_att: no load of a dense brute-force grid over
    [1e-6, 3] sqrt(V) (adhesive_contact of those loads) pulls harder than the reported pull-off by more than the
    stated resolution (1e-6 relative in p_rep, so ~1e-5 relative in the pull-off, and 1e-12 sqrt(V) absolute)."""
    sv = math.sqrt(float(pr.psd.V(E_star=pr.E_star)))
    h = pr.psd.rms_height
    law = pf.adhesion.Exponential(w_scale * sv * h, rho_scale * h)
    ad = pf.adhesive_contact(pr, law)
    assert isinstance(ad, pf.AdhesiveContact)
    grid = pf.ContactProblem(pr.psd, pr.E_star, np.geomspace(1e-6, 3.0, 61) * sv, pr.fudge)
    brute = pf.adhesive_contact(grid, law)
    least = float(np.min(brute.p_applied))
    assert ad.pull_off >= -least - 1e-5 * abs(least) - 1e-12 * sv
    np.testing.assert_allclose(
        np.atleast_1d(ad.p_applied),
        np.atleast_1d(ad.p_repulsive) - np.atleast_1d(ad.p_attractive),
        rtol=1e-12,
        atol=1e-15 * sv,
    )


@slow_scale(0.5)
@given(problems(lo=0.05, hi=2.0, n_max=2, max_zeta=1e3, fudge="YP08"), log_uniform(1e-4, 1e2), log_uniform(1e-3, 1e3))
def test_property_leak_rate_and_conductance_scale_and_follow_barber(pr, eta, dp):
    """The leak rate is linear in the pressure drop and inverse in the viscosity (exactly: 1e-12); the electrical
    and thermal conductances are Barber's 2K/(E* (rho_1 + rho_2)) and 2K/(E* (1/k_1 + 1/k_2)) with the stiffness
    of contact_stiffness (1e-12)."""
    Q = np.atleast_1d(pf.leak_rate(pr, eta, dp))
    np.testing.assert_allclose(np.atleast_1d(pf.leak_rate(pr, 2 * eta, 3 * dp)), 1.5 * Q, rtol=1e-12, atol=0)
    assert np.all(Q >= 0)
    K = np.atleast_1d(pf.contact_stiffness(pr))
    G = np.atleast_1d(pf.contact_conductance(pr, resistivity=(eta, dp)))
    np.testing.assert_allclose(G, 2 * K / (pr.E_star * (eta + dp)), rtol=1e-12)
    Gt = np.atleast_1d(pf.contact_conductance(pr, thermal_conductivity=(eta, dp)))
    np.testing.assert_allclose(Gt, 2 * K / (pr.E_star * (1 / eta + 1 / dp)), rtol=1e-12)


def test_regression_callable_interaction_of_short_range_has_its_work():
    """Found by the traction-law property: one quadrature over [0, inf) missed a law of range 1e-9 (w = 6e-91
    instead of 1, or 0 and a refusal naming w)."""
    rho = 1e-9
    law = pf.adhesion.CallableInteraction(lambda u: (1.0 / rho) * np.exp(-np.asarray(u) / rho), rho)
    assert law.w == pytest.approx(1.0, rel=1e-9)


def test_regression_exponential_folded_mean_below_minus_rho_with_a_narrow_width_is_finite():
    """Found by the traction-law property: c = -rho, h = 0.01 rho gave NaN (0 * inf in the erfcx form); the
    reference is the Gaussian mean of sigma(|x|), whose mass sits near x = -rho: (w/rho) e^{-1} to 1e-3."""
    law = pf.adhesion.Exponential(1.0, 1e-3)
    val = float(law.folded_mean(np.array([-1e-3]), np.array([1e-5]))[0])
    assert val == pytest.approx(1e3 * math.exp(-1.0) * math.exp(0.5 * 1e-4), rel=1e-6)
