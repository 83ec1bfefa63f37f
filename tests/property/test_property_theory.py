"""Property tests of the theory building blocks against formulas written here from the papers: the fudge factors
(Yang & Persson 2008, Wang & Müser 2017, the global model of Xu et al. 2024), the hardness laws, the effective
variance tau = int S dV (Xu, Li, Chen, Zhou tutorial, Eq. 'eq:new_B2') and the image solution
(Eqs. 'eq:P0_solution', 'eq:Area_Persson', 'eq:variance_p_form1')."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.optimize import brentq
from scipy.special import erf

import persson_fp as pf

from .strategies import log_uniform, slow_scale

areas = st.floats(0.0, 1.0)


def _S_closed(model, gamma, A):
    """S(A*) of each model, from the papers."""
    if model == "none":
        return 1.0
    if model == "YP08":
        return gamma + (1.0 - gamma) * A * A
    if model == "WM17":
        return gamma - 2.0 / 9.0 * A**2 + (11.0 / 9.0 - gamma) * A**4
    raise AssertionError(model)


@given(st.sampled_from(["none", "YP08", "WM17"]), st.floats(0.45, 1.0), st.lists(areas, min_size=1, max_size=5))
def test_property_fudge_factor_formulas_derivatives_and_resolution(model, gamma, A):
    """S(A) is the published polynomial to round-off; dS/dA is its derivative (central difference of the closed
    form, step 1e-5: truncation below 1e-9); resolve() maps names, instances and callables to the same S."""
    cls = pf.fudge.MODELS[model]
    f = cls() if model == "none" else cls(gamma)
    assert isinstance(f, pf.fudge.FudgeFactor)
    g = {"none": None, "YP08": pf.fudge.YangPersson, "WM17": pf.fudge.WangMuser}[model]
    assert g is None or isinstance(f, g)
    A = np.asarray(A)
    ref = np.array([_S_closed(model, gamma, a) for a in A])
    np.testing.assert_allclose(f.S(A), ref, rtol=1e-14, atol=0)
    np.testing.assert_allclose(f(A), ref, rtol=1e-14, atol=0)  # __call__ == S
    h = 1e-5
    fd = np.array([(_S_closed(model, gamma, a + h) - _S_closed(model, gamma, a - h)) / (2 * h) for a in A])
    np.testing.assert_allclose(f.dS_dA(A), fd, rtol=1e-8, atol=1e-9)
    if model == "none":
        assert isinstance(f, pf.fudge.NoFudge) and isinstance(pf.fudge.resolve(None), pf.fudge.NoFudge)
    by_name = pf.fudge.resolve(model.lower())
    np.testing.assert_allclose(
        by_name.S(A), [_S_closed(model, _default_gamma(model), a) for a in A], rtol=1e-14, atol=0
    )
    assert pf.fudge.resolve(f) is f
    user = pf.fudge.resolve(lambda a: _S_closed(model, gamma, a))  # scalar callable: evaluated point by point
    assert isinstance(user, pf.fudge.CallableFudge)
    np.testing.assert_allclose(user.S(A), ref, rtol=1e-14, atol=0)
    np.testing.assert_allclose(pf.fudge.CallableFudge(f.S).S(A), ref, rtol=1e-14, atol=0)


def _default_gamma(model):
    return {"none": 1.0, "YP08": pf.fudge.GAMMA_YP08, "WM17": pf.fudge.GAMMA_WM17}[model]


@given(st.floats(0.05, 1.0), log_uniform(1e-6, 1e3), log_uniform(1e-3, 1e3))
def test_property_global_model_area_and_its_B2_form(gamma, ratio, scale):
    """Xu24.area solves A = erf(p_bar / sqrt(2 g(A) V)), g = gamma + (1 - gamma) A (own root by brentq, to 1e-12
    absolute: the docstring states round-off); its S is d tau/dV along tau = g(A(V)) V (central difference in V,
    relative step 1e-5: agreement to 1e-6)."""
    m = pf.fudge.Xu24(gamma)
    p = ratio * scale
    V = scale**2

    def root(V):
        x = p / math.sqrt(2.0 * V)
        if x > 30:
            return 1.0
        return brentq(lambda A: A - erf(x / math.sqrt(gamma + (1 - gamma) * A)), 0.0, 1.0, xtol=1e-15, rtol=1e-15)

    A = float(m.area(p, V))
    assert A == pytest.approx(root(V), abs=1e-12)
    np.testing.assert_allclose(m.g(A), gamma + (1 - gamma) * A, rtol=1e-15)
    if 1e-6 < A < 1 - 1e-6:
        h = 1e-5 * V
        tau = [(gamma + (1 - gamma) * root(v)) * v for v in (V - h, V + h)]
        np.testing.assert_allclose(m.S(A), (tau[1] - tau[0]) / (2 * h), rtol=1e-6)
    np.testing.assert_allclose(m.area(np.array([p, p]), np.array([V, V])), [A, A], rtol=0, atol=0)


@given(log_uniform(1e-2, 1e3), st.floats(0.0, 2.0), st.lists(log_uniform(1.0, 1e6), min_size=1, max_size=6))
def test_property_hardness_laws_and_resolution(sigma, n, zeta):
    """sigma_Y of each law is its formula; its derivative the derivative of the formula (central differences of a
    CallableHardness within 1e-7 relative, its docstring's ~1e-11 for a smooth law plus round-off of sigma
    itself); resolve() turns a number into a ConstantHardness and a callable into a CallableHardness; check()
    refuses a load at or above sigma_Y(1), naming p_bar."""
    z = np.asarray(zeta)
    const = pf.hardness.ConstantHardness(sigma)
    assert isinstance(const, pf.hardness.Hardness)
    np.testing.assert_array_equal(const.sigma(z), np.full(z.shape, sigma))
    np.testing.assert_array_equal(const.dsigma_dzeta(z), 0.0)
    law = pf.hardness.PowerLaw(sigma, n)
    np.testing.assert_allclose(law.sigma(z), sigma * z**n, rtol=1e-14)
    np.testing.assert_allclose(law.dsigma_dzeta(z), n * sigma * z ** (n - 1), rtol=1e-14)
    user = pf.hardness.CallableHardness(lambda x: sigma * np.asarray(x) ** n)
    np.testing.assert_allclose(user.sigma(z), sigma * z**n, rtol=1e-14)
    np.testing.assert_allclose(user.dsigma_dzeta(z), n * sigma * z ** (n - 1), rtol=1e-7, atol=1e-9 * sigma)
    with_d = pf.hardness.CallableHardness(lambda x: sigma * np.asarray(x) ** n, lambda x: n * sigma * x ** (n - 1))
    np.testing.assert_allclose(with_d.dsigma_dzeta(z), n * sigma * z ** (n - 1), rtol=1e-14)
    resolved = pf.hardness.resolve(sigma)
    assert isinstance(resolved, pf.hardness.ConstantHardness) and resolved.value == sigma
    assert pf.hardness.resolve(law) is law and pf.hardness.resolve(None) is None
    assert isinstance(pf.hardness.resolve(lambda x: sigma + 0 * x), pf.hardness.CallableHardness)
    law.check(float(z.max()), 0.5 * sigma)  # a load below sigma_Y(1) passes
    with pytest.raises(ValueError, match="p_bar"):
        law.check(float(z.max()), sigma)


@given(st.sampled_from(sorted(pf.fudge.MODELS)), st.floats(0.4, 1.0), log_uniform(1e-3, 1e3), log_uniform(1e-6, 1e12))
def test_property_effective_variance_solves_its_ode(name, gamma, p_bar, v):
    """tau(p_bar, V) solves d tau/dV = S(erf(p_bar / sqrt(2 tau))), tau(0) = 0 (Eq. 'eq:new_B2'): central difference
    in V (relative step 1e-4, truncation ~1e-8) matches S to 1e-6; V_of_tau inverts tau (1e-9 relative);
    tau(c p, c^2 V) = c^2 tau(p, V) (the load-free form u(v), to 1e-12); vectorised == one by one; the cached
    map is the class's; the global model's tau is g(A) V with its own A (to 1e-9)."""
    f = pf.fudge.MODELS[name]() if name == "none" else pf.fudge.MODELS[name](round(gamma, 1))  # a few solves
    ev = pf.effective_variance(f)
    assert isinstance(ev, pf.EffectiveVariance) and pf.effective_variance(f) is ev
    V = v * p_bar**2
    tau = float(ev.tau(p_bar, V))
    assert tau > 0
    h = 1e-4 * V
    slope = (float(ev.tau(p_bar, V + h)) - float(ev.tau(p_bar, V - h))) / (2 * h)
    S = float(f.S(erf(p_bar / math.sqrt(2 * tau))))
    assert slope == pytest.approx(S, rel=1e-6)
    assert float(ev.V_of_tau(p_bar, tau)) == pytest.approx(V, rel=1e-9)
    c = 7.3
    assert float(ev.tau(c * p_bar, c * c * V)) == pytest.approx(c * c * tau, rel=1e-12)
    Vs = V * np.array([0.5, 1.0, 2.0])
    np.testing.assert_array_equal(ev.tau(p_bar, Vs), [float(ev.tau(p_bar, x)) for x in Vs])
    if gamma < 0.41:  # the class itself, solved afresh (~10 ms each, so only sometimes)
        assert float(pf.EffectiveVariance(f).tau(p_bar, V)) == pytest.approx(tau, rel=1e-12)
    if isinstance(f, pf.fudge.Xu24):
        A = float(f.area(p_bar, V))
        assert tau == pytest.approx(float(f.g(A)) * V, rel=1e-9)


@slow_scale(0.5)
@given(log_uniform(1e-6, 1e6), log_uniform(1e-8, 1e3))
def test_property_image_solution_mass_load_and_variance(p_bar, r):
    """The image solution is a density of mass A* = erf(p_bar/sqrt(2 tau)) whose mean over the interface is p_bar
    (load conservation: the atom at p = 0 carries no load) and whose variance is variance_closed_form, which is
    int_0^tau A*(t) dt; all by quadrature here (epsrel 1e-12; asserted to 1e-8).  image_pdf equals the
    difference of Gaussians where that is not cancelling, and is vectorised."""
    tau = (p_bar / r) ** 2
    s = math.sqrt(tau)
    cuts = np.unique([0.0, p_bar, p_bar + s, p_bar + 10 * s, p_bar + 60 * s])

    def P(p):
        return float(pf.image_pdf(p, p_bar, tau))

    def integral(f):
        return math.fsum(quad(f, a, b, epsabs=0.0, epsrel=1e-13, limit=400)[0] for a, b in zip(cuts[:-1], cuts[1:]))

    mass = integral(P)
    A = float(pf.area_from_tau(p_bar, tau))
    assert A == pytest.approx(erf(p_bar / math.sqrt(2 * tau)), rel=1e-15)
    assert mass == pytest.approx(A, rel=1e-8)
    load = integral(lambda p: p * P(p))
    assert load == pytest.approx(p_bar, rel=1e-8)
    second = integral(lambda p: p * p * P(p))
    var = float(pf.variance_closed_form(p_bar, tau))
    assert var == pytest.approx(second - p_bar**2, rel=1e-7, abs=1e-9 * p_bar**2)
    t_cuts = np.concatenate(([0.0], p_bar**2 * np.geomspace(1e-3, 1e20, 24)))
    t_cuts = np.unique(np.append(t_cuts[t_cuts < tau], tau))
    by_t = math.fsum(
        quad(lambda t: erf(p_bar / math.sqrt(2 * t)) if t > 0 else 1.0, a, b, epsabs=0.0, epsrel=1e-13)[0]
        for a, b in zip(t_cuts[:-1], t_cuts[1:])
    )
    assert var == pytest.approx(by_t, rel=1e-8)
    p = np.array([0.5, 1.0, 2.0]) * p_bar
    if 0.2 < p_bar**2 / tau < 50:  # no cancellation in the plain difference of Gaussians
        g = np.exp(-((p - p_bar) ** 2) / (2 * tau)) - np.exp(-((p + p_bar) ** 2) / (2 * tau))
        np.testing.assert_allclose(pf.image_pdf(p, p_bar, tau), g / math.sqrt(2 * math.pi * tau), rtol=1e-9)
    np.testing.assert_array_equal(pf.image_pdf(p, p_bar, tau), [P(x) for x in p])
    assert float(pf.image_pdf(-p_bar, p_bar, tau)) == 0.0
