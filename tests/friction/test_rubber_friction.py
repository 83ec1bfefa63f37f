"""pf.rubber_friction against references written here: closed-form angular integrals and scipy quadratures in q,
the elastic limit, the symmetries and conventions of Persson's friction theory."""

import math
import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf
from tests.friction.conftest import prony_model

ve = pf.viscoelastic


def zener_phi(w, Er, Eg, tau):
    """int_0^{2 pi} |E(w cos phi)|^2 dphi of a Zener solid (closed form)."""
    x = w * tau
    return 2 * np.pi * (Eg**2 - (Eg**2 - Er**2) / np.sqrt(1 + x * x))


def zener_psi(w, Er, Eg, tau):
    """int_0^{2 pi} cos phi Im E(w cos phi) dphi of a Zener solid (closed form)."""
    x = w * tau
    r = np.sqrt(1 + x * x)
    return 2 * np.pi * (Eg - Er) * x / (r * (1 + r))  # (1 - 1/r) / x without cancellation at small x


def reference_mu(psd, Er, Eg, tau, nu, s0, v, q1, gamma=0.45):
    """mu and P(q1) by scipy quad in ln q with the closed-form angular integrals (Persson 2001)."""
    lo = math.log(psd.q_l)
    brk = [math.log(psd.q_r)] if psd.q_r > psd.q_l else None

    def G(q):
        f = lambda lq: math.exp(4 * lq) * float(psd.C(math.exp(lq))) * zener_phi(math.exp(lq) * v, Er, Eg, tau)
        pts = [b for b in (brk or []) if b < math.log(q)] or None
        if math.log(q) - lo < 1e-7:  # G grows linearly from q0: the trapezoid is exact to 1e-14 there
            val = 0.5 * (f(lo) + f(math.log(q))) * (math.log(q) - lo)
        else:
            val = quad(f, lo, math.log(q), points=pts, limit=400, epsabs=0, epsrel=1e-11)[0]
        return val / (8 * (1 - nu**2) ** 2 * s0**2)

    def integrand(t):  # ln q = ln q0 + t^2: P ~ 1/sqrt(ln(q/q0)) where G grows fast near q0 becomes smooth
        q = psd.q_l * math.exp(t * t)
        Gq = G(q)
        P = erf(0.5 / math.sqrt(Gq)) if Gq > 0 else 1.0
        return (
            2
            * t
            * 0.5
            * q**4
            * float(psd.C(q))
            * P
            * (gamma + (1 - gamma) * P * P)
            * zener_psi(q * v, Er, Eg, tau)
            / ((1 - nu**2) * s0)
        )

    # sub-intervals growing geometrically from q0, the roll-off among the ends (one quad over the whole range can
    # miss the steep part near q0 while reporting a small error)
    t_end = math.sqrt(math.log(q1) - lo)
    ends = set(np.geomspace(1e-6, t_end, 9)) | {0.0} | {math.sqrt(b - lo) for b in (brk or []) if b < math.log(q1)}
    ends = sorted(ends)
    mu = sum(quad(integrand, a, b, limit=200, epsrel=1e-11)[0] for a, b in zip(ends[:-1], ends[1:]))
    return mu, erf(0.5 / math.sqrt(G(q1)))


@pytest.mark.parametrize("v", [1e-4, 1e-2, 1.0])
def test_zener_on_a_power_law_against_quadrature(road, zener, v):
    res = pf.rubber_friction(road, zener, 2e5, v)
    mu, A = reference_mu(road, 3e6, 3e9, 1e-4, 0.5, 2e5, v, road.q_s)
    assert float(res.mu) == pytest.approx(mu, rel=1e-6)
    assert float(res.contact_area) == pytest.approx(A, rel=1e-6)
    # the estimate is an upper bound of the true error here and within the stated 1e-4
    assert abs(float(res.mu) - mu) <= max(float(res.mu_error), 1e-9 * mu)
    assert float(res.mu_error) <= 1e-4 * mu


def test_cut_off_q1_against_quadrature(road, zener):
    res = pf.rubber_friction(road, zener, 2e5, 0.01, q1=1e6)
    mu, A = reference_mu(road, 3e6, 3e9, 1e-4, 0.5, 2e5, 0.01, 1e6)
    assert float(res.mu) == pytest.approx(mu, rel=1e-6)
    assert float(res.contact_area) == pytest.approx(A, rel=1e-6)
    assert res.q[-1] == 1e6 and res.q[0] == road.q_l


def test_elastic_limit_has_no_friction_and_the_elastic_contact_area(road):
    E = 3e6
    el = ve.Zener(E, E, 1e-3, nu=0.5)
    res = pf.rubber_friction(road, el, 2e5, np.logspace(-3, 1, 5))
    assert np.all(res.mu == 0.0) and np.all(res.mu_error == 0.0)
    E_star = E / (1 - 0.5**2)
    # P(q) = erf(sigma0 / sqrt(2 V(zeta))), the elastic contact area of the tutorial, at every node
    zeta = np.clip(res.q[1:] / road.q_l, 1.0, road.zeta_max)
    expect = erf(2e5 / np.sqrt(2 * road.V(zeta, E_star)))
    assert res.P[0, 0] == 1.0 and res.G[0, 0] == 0.0
    # inside a panel G comes from the panel's interpolating polynomial (1e-7 relative, stated); at q1, a panel's end,
    # from its full Gauss rule (round-off)
    np.testing.assert_allclose(res.P[0, 1:], expect, rtol=1e-7)
    np.testing.assert_allclose(res.G[0, -1], road.V(road.zeta_max, E_star) / (2 * 2e5**2), rtol=1e-12)
    ex = pf.exact(pf.ContactProblem(road, E_star, 2e5))
    np.testing.assert_allclose(res.contact_area, float(np.ravel(ex.contact_area)[-1]), rtol=1e-10)


def test_full_circle_is_four_quarter_circles(zener):
    from persson_fp.theory.sliding import AngularIntegrals

    ang = AngularIntegrals(zener)
    for w0 in (1e2, 1e4, 1e6):
        E = lambda phi: zener.modulus(abs(w0 * math.cos(phi)))
        full_phi = quad(lambda p: abs(zener.modulus_ref(w0 * math.cos(p))) ** 2, 0, 2 * math.pi, limit=500,
                        points=[math.pi / 2, 3 * math.pi / 2], epsrel=1e-11)[0]  # fmt: skip
        # Im E is odd in omega: E(-w) = conj(E(w)) for a real response function
        full_psi = quad(
            lambda p: math.cos(p) * math.copysign(1, math.cos(p)) * E(p).imag, 0, 2 * math.pi, limit=500,
            points=[math.pi / 2, 3 * math.pi / 2], epsrel=1e-11,
        )[0]  # fmt: skip
        P1, P2, Psi = ang.direct(np.array([w0]))[:, 0]
        assert P1 + P2 == pytest.approx(full_phi, rel=1e-9)
        assert Psi == pytest.approx(full_psi, rel=1e-7)


def test_temperature_shift_is_a_change_of_speed(road):
    law = ve.WLF(8.86, 101.6)
    warm = ve.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=law)
    cold = ve.Zener(3e6, 3e9, 1e-4)
    v = np.array([1e-3, 1e-1])
    res = pf.rubber_friction(road, warm, 2e5, v, temperature=60.0)
    aT = 10 ** float(law.log10_aT(60.0, 20.0))
    ref = pf.rubber_friction(road, cold, 2e5, v * aT)
    np.testing.assert_allclose(res.mu, ref.mu, rtol=1e-6)
    np.testing.assert_allclose(res.contact_area, ref.contact_area, rtol=1e-6)


def test_friction_map_shape_and_one_by_one(road, zener):
    law = ve.WLF(8.86, 101.6)
    mat = ve.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=law)
    T = np.array([[0.0], [20.0], [50.0]])
    v = np.logspace(-4, 0, 4)
    res = pf.rubber_friction(road, mat, 2e5, v, temperature=T)
    assert res.mu.shape == (3, 4) and res.G.shape == (3, 4, res.q.size) and res.P.shape == res.G.shape
    one = pf.rubber_friction(road, mat, 2e5, v[2], temperature=50.0)
    assert float(one.mu) == pytest.approx(res.mu[2, 2], rel=1e-12)
    assert np.shape(one.mu) == ()


def test_fudge_weights_mu_only(road, zener):
    v = np.array([1e-3, 1e-1])
    yp = pf.rubber_friction(road, zener, 2e5, v, fudge="YP08")
    none = pf.rubber_friction(road, zener, 2e5, v, fudge=None)
    np.testing.assert_array_equal(yp.contact_area, none.contact_area)
    np.testing.assert_array_equal(yp.G, none.G)
    # S = 0.45 + 0.55 P^2 <= 1: the YP08 weight lowers mu; with P -> 0 at small areas by about 0.45
    assert np.all(yp.mu < none.mu) and np.all(yp.mu > 0.45 * none.mu)


def test_modulus_in_G_plain_scales_G(road, zener):
    red = pf.rubber_friction(road, zener, 2e5, 0.01)
    plain = pf.rubber_friction(road, zener, 2e5, 0.01, modulus_in_G="plain")
    np.testing.assert_allclose(plain.G, red.G * (1 - 0.5**2) ** 2, rtol=1e-13)
    assert plain.conventions["modulus_in_G"] == "plain" and "modulus_in_G='plain'" not in repr(red)


def test_psd_convention_does_not_change_mu(zener):
    q = np.logspace(3, 7, 81)
    C = 1e-20 * (q / 1e3) ** (-2 * 1.8)
    persson = pf.TabulatedPSD(q, C)
    iso = pf.TabulatedPSD(q, C * (2 * np.pi) ** 2, convention="iso2d")
    a = pf.rubber_friction(persson, zener, 1e5, [1e-3, 1.0])
    b = pf.rubber_friction(iso, zener, 1e5, [1e-3, 1.0])
    np.testing.assert_allclose(a.mu, b.mu, rtol=1e-12)
    assert "iso2d" in b.conventions["psd_convention"]


def test_frequency_unit_does_not_change_mu(road):
    p = prony_model()
    f = np.logspace(-4, 11, 76)
    E = p.modulus(2 * np.pi * f)
    hz = ve.MasterCurve(f, E.real, E.imag, frequency_unit="Hz")
    rad = ve.MasterCurve(2 * np.pi * f, E.real, E.imag, frequency_unit="rad/s")
    v = [1e-4, 1e-2]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # both curves miss the same frequencies
        np.testing.assert_allclose(pf.rubber_friction(road, hz, 2e5, v).mu, pf.rubber_friction(road, rad, 2e5, v).mu,
                                   rtol=1e-12)  # fmt: skip


def test_tabulated_master_curve_matches_its_model(road):
    p = prony_model()
    f = np.logspace(-5, 12, 171)  # 10 points per decade, covering q v for v <= 1e-2
    E = p.modulus(2 * np.pi * f)
    mc = ve.MasterCurve(f, E.real, E.imag)
    v = np.array([1e-5, 1e-3])
    a = pf.rubber_friction(road, mc, 2e5, v)
    b = pf.rubber_friction(road, p, 2e5, v)
    # the spline's 3e-5 error in the moduli (measured in the material tests) is what separates them
    np.testing.assert_allclose(a.mu, b.mu, rtol=2e-4)
    np.testing.assert_allclose(a.contact_area, b.contact_area, rtol=2e-4)


def test_master_curve_that_does_not_cover_warns_or_raises(road):
    f = np.logspace(0, 4, 9)
    E1, E2 = 1e6 * (1 + 0.1 * np.log10(f)), 1e5 * np.ones(9)
    mc = ve.MasterCurve(f, E1, E2, check_kk=False)
    with pytest.warns(UserWarning, match=r"rad/s.*the curve gives"):
        pf.rubber_friction(road, mc, 2e5, 1.0)
    strict = ve.MasterCurve(f, E1, E2, check_kk=False, extrapolation="raise")
    with pytest.raises(ValueError, match="cover"):
        pf.rubber_friction(road, strict, 2e5, 1.0)


def test_strain_softening_scales_the_moduli(road, zener):
    ones = ve.StrainSoftening([1e-3, 1.0], [1.0, 1.0], [1.0, 1.0])
    a = pf.rubber_friction(road, zener, 2e5, 0.01, strain_softening=ones)
    b = pf.rubber_friction(road, zener, 2e5, 0.01)
    # with softening the tables of E'^2 and E''^2 are interpolated apart, without it their sum: 1e-10 apart
    np.testing.assert_allclose(a.mu, b.mu, rtol=1e-8)
    # f = g = c at every strain is the same material with E -> c E: compare with the scaled Zener
    c = 0.5
    soft = ve.StrainSoftening([1e-3, 1.0], [c, c], [c, c])
    s = pf.rubber_friction(road, zener, 2e5, 0.01, strain_softening=soft)
    ref = pf.rubber_friction(road, ve.Zener(c * 3e6, c * 3e9, 1e-4), 2e5, 0.01)
    np.testing.assert_allclose(s.mu, ref.mu, rtol=1e-8)
    np.testing.assert_allclose(s.contact_area, ref.contact_area, rtol=1e-8)


def test_repr_states_scope_and_conventions(road, zener):
    r = repr(pf.rubber_friction(road, zener, 2e5, [0.01, 0.1]))
    assert "flash temperature" in r and "modulus_in_G=reduced" in r and "fudge=YP08" in r and "q1=" in r


def test_table_and_plot(road, zener):
    import matplotlib

    matplotlib.use("Agg")
    res = pf.rubber_friction(road, zener, 2e5, np.logspace(-4, 0, 5))
    tab = res.table
    cols = list(tab.keys()) if isinstance(tab, dict) else list(tab.columns)
    assert cols[0] == "velocity [length/s]" and "mu [-]" in cols
    np.testing.assert_array_equal(np.asarray(tab["mu [-]"]), res.mu)
    fig = res.plot()
    assert len(fig.axes) == 2 and "mu" in fig.axes[0].get_ylabel()


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(sigma0=0.0), "sigma0"),
        (dict(sigma0=np.nan), "sigma0"),
        (dict(velocity=0.0), "velocity"),
        (dict(velocity=[1.0, -1.0]), "velocity"),
        (dict(velocity="fast"), "velocity"),
        (dict(q1=1e9), "q1"),
        (dict(q1=1e3), "q1"),
        (dict(q1=1e3 * (1 + 1e-13)), "q1"),
        (dict(fudge="nope"), "fudge"),
        (dict(modulus_in_G="reduce"), "modulus_in_G"),
        (dict(strain_softening=0.5), "strain_softening"),
        (dict(material=3e6), "material"),
        (dict(temperature=-300.0), "temperature"),
    ],
)
def test_bad_input_is_refused_by_name(road, zener, kwargs, name):
    args = dict(psd=road, material=zener, sigma0=2e5, velocity=0.01)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        pf.rubber_friction(**args)


def test_temperature_required_with_a_shift_and_outside_the_wlf_pole(road):
    mat = ve.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=ve.WLF(8.86, 101.6))
    with pytest.raises(ValueError, match="temperature"):
        pf.rubber_friction(road, mat, 2e5, 0.01)
    with pytest.raises(ValueError, match="temperature"):
        pf.rubber_friction(road, mat, 2e5, 0.01, temperature=-90.0)
