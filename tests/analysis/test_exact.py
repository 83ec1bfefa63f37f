"""Exact solutions against quadrature and independent computations."""

import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad, solve_ivp
from scipy.special import erf

import persson_fp as pf


@pytest.fixture(scope="module")
def ref():
    return pf.ContactProblem.reference(p_bar_ratio=np.array([0.05, 0.5, 2.0]))


@pytest.mark.parametrize("fudge", [None, "YP08", "WM17", "Xu24"])
def test_mass_and_load_by_quadrature(ref, fudge):
    pr = pf.ContactProblem(ref.psd, 1.0, ref.p_bar, fudge)
    ex = pf.exact(pr, np.array([1.5, 20.0, 128.0]))
    for i in range(3):
        for j, pb in enumerate(pr.p_bar):
            tau = ex.tau[i, j]
            f = lambda p: float(pf.image_pdf(p, pb, tau))  # noqa: E731
            hi = pb + 40 * np.sqrt(tau)
            pts = [pb]
            mass = quad(f, 0, hi, points=pts, epsabs=0, epsrel=1e-13, limit=200)[0]
            load = quad(lambda p: p * f(p), 0, hi, points=pts, epsabs=0, epsrel=1e-13, limit=200)[0]
            second = quad(lambda p: p * p * f(p), 0, hi, points=pts, epsabs=0, epsrel=1e-13, limit=200)[0]
            assert mass == pytest.approx(ex.contact_area[i, j], rel=1e-10)
            assert load == pytest.approx(pb, rel=1e-10)
            assert second - pb**2 == pytest.approx(ex.variance[i, j], rel=1e-9, abs=1e-12 * pb**2)
            # Var = int_0^tau A*(t) dt (eq:variance_p_form1 in tau)
            v2 = quad(lambda t: erf(pb / np.sqrt(2 * t)) if t > 0 else 1.0, 0, tau, epsrel=1e-13, epsabs=0)[0]
            assert v2 == pytest.approx(ex.variance[i, j], rel=1e-9)


def test_pdf_is_accurate_near_zero_and_for_tiny_tau():
    # near p = 0: P0 ~ (2 p_bar p / tau) rho(0; p_bar, tau), no cancellation
    p = np.array([1e-300, 1e-12, 1e-8])
    val = pf.image_pdf(p, 1.0, 0.5)
    slope = 2 * 1.0 / 0.5 * np.exp(-1.0 / (2 * 0.5)) / np.sqrt(2 * np.pi * 0.5)
    np.testing.assert_allclose(val / p, slope, rtol=1e-7)
    # tiny tau: a narrow Gaussian, finite, no overflow warning (np.seterr raises in tests)
    v = pf.image_pdf(np.array([0.0, 1.0, 1.0 + 1e-9, 2.0]), 1.0, 1e-20)
    assert np.all(np.isfinite(v)) and v[0] == 0 and v[3] == 0
    assert v[1] == pytest.approx(1 / np.sqrt(2 * np.pi * 1e-20))
    # cdf_contact agrees with the pdf's integral
    pr = pf.ContactProblem.reference()
    ex = pf.exact(pr, 50.0)
    tau = float(ex.tau)
    assert ex.cdf_contact(10.0) == pytest.approx(ex.contact_area, rel=1e-14)
    F = ex.cdf_contact(0.02)
    I = quad(lambda p: float(pf.image_pdf(p, pr.p_bar[0], tau)), 0, 0.02, epsrel=1e-13)[0]
    assert F == pytest.approx(I, rel=1e-11)


def _independent_area(H, ratio, fudge):
    """V by adaptive quadrature of the PSD, tau by solve_ivp, A* = erf: no package numerics."""
    C0, ql, qr, qs, E = 1.0, 1.0, 2.0, 128.0, 1.0
    psd = pf.SelfAffinePSD(C0, H, ql, qr, qs)
    Cq = lambda q: C0 * (qr if q < qr else q) ** (-2 * (1 + H))  # noqa: E731
    V = (
        np.pi
        / 2
        * E**2
        * (
            quad(lambda q: q**3 * Cq(q), ql, qr, epsrel=1e-14)[0]
            + quad(lambda q: q**3 * Cq(q), qr, qs, epsrel=1e-14, limit=200)[0]
        )
    )
    pb = ratio * np.sqrt(V)
    if fudge is None:
        tau = V
    else:
        S = pf.fudge.resolve(fudge).S
        V0 = 1e-6 * pb**2
        tau = solve_ivp(
            lambda v, t: S(erf(pb / np.sqrt(2 * t))), (V0, V), [V0], method="DOP853", rtol=1e-12, atol=1e-16 * pb**2
        ).y[0, -1]
    return psd, pb, erf(pb / np.sqrt(2 * tau))


@pytest.mark.parametrize("H", [0.0, 0.3, 0.8, 1.0])
@pytest.mark.parametrize("fudge", [None, "YP08", "WM17"])
def test_contact_area_agrees_with_independent_computation(H, fudge):
    """1e-8 relative against an independent computation, H in {0, .3, .8, 1}, 3 loads, 3 fudges."""
    for ratio in (0.01, 0.5, 3.0):
        psd, pb, A_ref = _independent_area(H, ratio, fudge)
        A = pf.exact(pf.ContactProblem(psd, 1.0, pb, fudge)).contact_area
        assert A == pytest.approx(A_ref, rel=1e-8)


def test_vectorised_shapes_and_asymptote(ref):
    z = np.array([2.0, 128.0])
    ex = pf.exact(ref, z)
    assert ex.contact_area.shape == (2, 3)
    assert ex.pdf(np.linspace(0, 0.1, 7)).shape == (2, 3, 7)
    assert np.shape(pf.exact(ref).contact_area) == (3,)
    one = pf.exact(pf.ContactProblem.reference(), 128.0)
    assert isinstance(one.contact_area, float)
    # eq:Asymptote_1 : A* ~ sqrt(2/pi) p_bar / sqrt(V) for small loads
    small = pf.exact(pf.ContactProblem.reference(p_bar_ratio=1e-4))
    assert small.contact_area == pytest.approx(np.sqrt(2 / np.pi) * 1e-4, rel=1e-7)
    assert small.area_asymptote == pytest.approx(np.sqrt(2 / np.pi) * 1e-4, rel=1e-14)
    # the atom keeps its digits where A* ~ 1
    big = pf.exact(pf.ContactProblem.reference(p_bar_ratio=8.0))
    from scipy.special import erfc

    assert big.atom == pytest.approx(erfc(8 / np.sqrt(2)), rel=1e-12)  # 1.2e-15: 1 - A* would lose it all
    assert 0 < big.atom < 1e-14


def test_elastic_energy_and_pressure_spectrum():
    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([0.1, 1.0, 50.0]))
    U = pf.elastic_energy(pr)
    # independent quadrature for the middle load
    pb = pr.p_bar[1]
    psd = pr.psd
    f = lambda q: q**2 * float(psd.C(q)) * erf(pb / np.sqrt(2 * float(psd.V(q / psd.q_l))))  # noqa: E731
    ref = np.pi / 2 * (quad(f, 1, 2, epsrel=1e-12)[0] + quad(f, 2, 128, epsrel=1e-12, limit=200)[0])
    assert U[1] == pytest.approx(ref, rel=1e-9)
    # a very large load is complete contact: eq:Uel_complete_2
    assert U[2] == pytest.approx(psd.elastic_energy_complete(), rel=1e-9)
    assert U[0] < U[1] < U[2]
    # eq:variance_p_form2 with eq:Pf_prime: Var = (2 pi)^3 / A_n int q |p(q)|^2 dq
    for fudge in (None, "YP08"):
        p2 = pf.ContactProblem(psd, 1.0, pb, fudge)
        g = lambda q: q * float(pf.pressure_spectrum(p2, q, A_n=2.0))  # noqa: E731
        var = (2 * np.pi) ** 3 / 2.0 * (quad(g, 1, 2, epsrel=1e-12)[0] + quad(g, 2, 128, epsrel=1e-12, limit=200)[0])
        assert var == pytest.approx(pf.exact(p2).variance, rel=1e-7)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(p_bar=0.0), "p_bar must be > 0"),
        (dict(p_bar=-1.0), "p_bar must be > 0"),
        (dict(p_bar=np.nan), "p_bar must be finite"),
        (dict(p_bar=[[1.0]]), "1-D"),
        (dict(p_bar=0.1, E_star=0.0), "E_star must be > 0"),
        (dict(p_bar=0.1, E_star=np.inf), "E_star must be finite"),
        (dict(p_bar=0.1, fudge=lambda A: A - 0.5), "must be finite, > 0"),
        (dict(p_bar=0.1, fudge="foo"), "fudge must be"),
    ],
)
def test_bad_problem_input(kwargs, match):
    psd = pf.SelfAffinePSD(1e-4, 0.8, 1.0, 2.0, 100.0)
    with pytest.raises(ValueError, match=match):
        pf.ContactProblem(psd, **kwargs)


def test_bad_arguments_of_energy_and_spectrum():
    pr = pf.ContactProblem.reference()
    for bad in (-1.0, np.nan, "a"):
        with pytest.raises(ValueError, match="epsrel"):
            pf.elastic_energy(pr, epsrel=bad)
    with pytest.raises(ValueError, match="scalar"):
        pf.elastic_energy(pr, zeta=[2.0, 3.0])
    with pytest.raises(ValueError, match="ContactProblem"):
        pf.exact(pr.psd)
    with pytest.raises(ValueError, match="ContactProblem"):
        pf.elastic_energy(pr.psd)
    # q = q_l is valid input: tau = 0 there, A* = 1, no division by zero (np.seterr raises in tests)
    assert pf.pressure_spectrum(pr, 1.0) == pytest.approx((1 / (4 * np.pi)) ** 2 * float(pr.psd.C(1.0)))


def test_extreme_loads_stay_finite_and_right():
    """p_bar down to 1e-300 sqrt(V) with a fudge factor: A* -> sqrt(2/pi) p_bar / sqrt(S(0) V), no overflow."""
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.array([1e-300, 1e-160, 1e-9]))
    A = pf.exact(pr).contact_area
    np.testing.assert_allclose(A, np.sqrt(2 / np.pi) * np.array([1e-300, 1e-160, 1e-9]) / np.sqrt(0.45), rtol=1e-8)


def test_bad_zeta_for_exact():
    pr = pf.ContactProblem.reference()
    for z in (0.99, 129.0, np.inf):
        with pytest.raises(ValueError, match="zeta"):
            pf.exact(pr, z)
    with pytest.raises(ValueError, match="delta"):
        pf.exact(pr, 1.0).pdf(0.1)


@settings(max_examples=40, deadline=None)
@given(
    H=st.floats(0.0, 1.0),
    zr=st.floats(1.0, 10.0),
    zmax=st.floats(10.0, 1e4),
    ratio=st.floats(1e-3, 5.0),
    fudge=st.sampled_from([None, "YP08", "WM17", "Xu24"]),
)
def test_invariants_property(H, zr, zmax, ratio, fudge):
    psd = pf.SelfAffinePSD.from_rms_slope(0.2, H, 1.0, zr, zmax)
    pr = pf.ContactProblem(psd, 2.0, ratio * np.sqrt(psd.V(E_star=2.0)), fudge)
    z = np.geomspace(1.0, zmax, 30)
    ex = pf.exact(pr, z)
    A = ex.contact_area
    assert np.all((A >= 0) & (A <= 1))
    assert np.all(np.diff(A) <= 1e-15)
    assert np.all(pf.exact(pr, z[1:]).pdf(np.linspace(0, pr.p_max(), 50)) >= 0)
    assert np.all(np.diff(ex.variance) >= -1e-15)


@pytest.mark.parametrize(
    "make, match",
    [
        (lambda pr: pf.fudge.YangPersson(gamma="a"), "gamma of YP08"),
        (lambda pr: pf.fudge.YangPersson(gamma=None), "gamma of YP08"),
        (lambda pr: pf.SelfAffinePSD(1e-4, [0.5, 0.6], 1, 2, 10), "H must be a scalar"),
        (lambda pr: pf.ContactProblem(pr.psd, 1, 0.1, lambda A: "x"), "must return numbers"),
        (lambda pr: pf.ContactProblem(pr.psd, 1, 0.1, lambda A: 1e300 + 0 * A), "<= 1e"),
        (lambda pr: pf.TabulatedPSD([[1, 2], [3, 4]], [[1, 1], [1, 1]]), "1-D"),
        (lambda pr: pf.SelfAffinePSD.from_rms_slope(1e200, 0.8, 1, 2, 10), "rms_slope"),
        (lambda pr: pf.ContactProblem(pr.psd, 1, 1e300), "p_bar must be <= 1e150"),
        (lambda pr: pf.solve(pr, "fv", zeta_out=[[2, 3]]), "zeta_out must be a scalar or a 1-D"),
    ],
)
def test_more_bad_input_names_the_parameter(make, match):
    with pytest.raises(ValueError, match=match):
        make(pf.ContactProblem.reference())


def test_tail_mass_is_the_complement_of_the_cdf():
    """tail_mass(p) = A* - cdf_contact(p) (two closed forms), and it matches a quadrature of the pdf."""
    from persson_fp.theory.image import tail_mass

    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([0.1, 0.5, 2.0]))
    ex = pf.exact(pr, 40.0)
    tau = np.asarray(ex.tau)
    for p in (0.01, 0.05, 0.2):
        got = tail_mass(p, pr.p_bar, tau)
        np.testing.assert_allclose(got, ex.contact_area - ex.cdf_contact(p), rtol=1e-12, atol=1e-16)
        for j in range(3):
            ref = quad(lambda x: float(ex.pdf(x)[j]), p, np.inf, epsabs=1e-15, epsrel=1e-12)[0]
            assert got[j] == pytest.approx(ref, rel=1e-8, abs=1e-15)


def test_exact_full_contact_at_every_load_names_the_cause():
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 128.0)
    pr = pf.ContactProblem(psd, E_star=1.0, p_bar=[0.5, 0.9])  # sqrt(V) = 0.05: p_bar / sqrt(V) >= 10
    with pytest.warns(UserWarning, match=r"full contact at every load.*p_bar / sqrt\(V\).*different units"):
        ex = pf.exact(pr)
    np.testing.assert_allclose(ex.contact_area, 1.0, rtol=0, atol=1e-15)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an ordinary load is quiet
        pf.exact(pf.ContactProblem.reference(p_bar_ratio=[0.5, 3.0]))


@pytest.mark.parametrize(
    "p, p_bar, tau, name",
    [(np.nan, 1.0, 1.0, "p"), (1.0, -1.0, 1.0, "p_bar"), (1.0, 1.0, 0.0, "tau"), (1.0, 1.0, np.inf, "tau")],
)
def test_tail_mass_refuses_bad_input_by_name(p, p_bar, tau, name):
    """A NaN p, a non-positive load or a zero / infinite variance is a ValueError naming it, never a NaN."""
    from persson_fp.theory.image import tail_mass

    with pytest.raises(ValueError, match=rf"^{name}\b"):
        tail_mass(p, p_bar, tau)
