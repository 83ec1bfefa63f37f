"""Property tests of the rubber-friction names: random materials, spectra, speeds and temperatures against oracles
written here from the physics (closed forms, scaling laws, one by one = vectorised), and random invalid inputs that
must be refused with a ValueError naming the parameter."""

import math
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf

FAST = settings(max_examples=8, deadline=None, database=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow])  # fmt: skip
SLOW = settings(max_examples=40, deadline=None, database=None, derandomize=True,
                suppress_health_check=[HealthCheck.too_slow])  # fmt: skip


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda x: float(10.0**x))


@st.composite
def spectra(draw, max_decades=5.0):
    H = draw(st.floats(0.3, 1.0))
    q_l = draw(log_uniform(1e2, 1e5))
    zeta_max = draw(log_uniform(10.0, 10**max_decades))
    zeta_r = min(draw(log_uniform(1.0, 10.0)), zeta_max)
    slope = draw(log_uniform(0.05, 2.0))
    return pf.SelfAffinePSD.from_rms_slope(slope, H, q_l, zeta_r * q_l, zeta_max * q_l)


@st.composite
def zeners(draw, elastic=False):
    Er = draw(log_uniform(1e5, 1e8))
    ratio = 1.0 if elastic else draw(log_uniform(1.5, 1e4))
    tau = draw(log_uniform(1e-8, 1e-1))
    nu = draw(st.floats(0.0, 0.5))
    return pf.viscoelastic.Zener(Er, Er * ratio, tau, nu=nu)


@st.composite
def pronys(draw):
    n = draw(st.integers(1, 6))
    tau = np.sort(np.array([draw(log_uniform(1e-9, 1e1)) for _ in range(n)]))
    E_i = np.array([draw(log_uniform(1e5, 1e9)) for _ in range(n)])
    return pf.viscoelastic.Prony(draw(log_uniform(1e5, 1e8)), E_i, tau, nu=draw(st.floats(0.0, 0.5)))


def zener_phi_psi(w, z):
    x = w * z.tau
    Er, Eg = z.E_rubbery, z.E_glassy
    r = np.sqrt(1 + x * x)
    # (1 - 1/r) / x written without cancellation at small x: x / (r (1 + r))
    return 2 * np.pi * (Eg**2 - (Eg**2 - Er**2) / r), 2 * np.pi * (Eg - Er) * x / (r * (1 + r))


# -- materials ----------------------------------------------------------------------------------------------------
@FAST
@given(z=zeners(), w=st.lists(log_uniform(1e-6, 1e12), min_size=1, max_size=5))
def test_zener_modulus_property(z, w):
    w = np.array(w)
    E = pf.viscoelastic.Zener(z.E_rubbery, z.E_glassy, z.tau, nu=z.nu).modulus(w)
    x = w * z.tau
    ref_real = z.E_rubbery + (z.E_glassy - z.E_rubbery) * x * x / (1 + x * x)
    ref_imag = (z.E_glassy - z.E_rubbery) * x / (1 + x * x)
    np.testing.assert_allclose(E.real, ref_real, rtol=1e-13)
    np.testing.assert_allclose(E.imag, ref_imag, rtol=1e-13, atol=1e-300)
    # E'' >= 0 (passive), E_r <= E' <= E_g
    assert np.all(E.imag >= 0) and np.all(E.real >= z.E_rubbery * (1 - 1e-14))
    assert np.all(E.real <= z.E_glassy * (1 + 1e-14))


@FAST
@given(p=pronys())
def test_prony_and_master_curve_property(p):
    """A Prony model tabulated at 10 points per decade: the master curve reproduces it between the points, and the
    Kramers-Kronig misfit of the causal table stays under the tolerance (no warning); with E'' doubled it warns."""
    E_i, tau_i = p.E_i, p.tau_i
    model = pf.viscoelastic.Prony(p.E_rubbery, E_i, tau_i, nu=p.nu)
    lo, hi = math.log10(1 / tau_i.max()) - 2, math.log10(1 / tau_i.min()) + 2
    w = np.logspace(lo, hi, int(10 * (hi - lo)) + 1)
    E = model.modulus(w)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mc = pf.viscoelastic.MasterCurve(w, E.real, E.imag, frequency_unit="rad/s")
    assert mc.kk_misfit < pf.viscoelastic.KK_TOLERANCE
    mid = np.sqrt(w[1:-1] * w[2:])
    ref = p.E_rubbery + (E_i * 1j * mid[:, None] * tau_i / (1 + 1j * mid[:, None] * tau_i)).sum(-1)
    got = mc.modulus(mid)
    np.testing.assert_allclose(got.real, ref.real, rtol=2e-3)
    np.testing.assert_allclose(got.imag, ref.imag, rtol=2e-3)
    if model.E_glassy >= 2 * model.E_rubbery:  # the stated power of the check: a factor 2 of dispersion
        assert pf.viscoelastic.kramers_kronig_misfit(w, E.real, 2 * E.imag) > pf.viscoelastic.KK_TOLERANCE


@FAST
@given(
    C1=st.floats(1.0, 30.0),
    C2=st.floats(20.0, 200.0),
    T_ref=st.floats(-50.0, 100.0),
    dT=st.lists(st.floats(-0.99, 3.0), min_size=1, max_size=4),
    E_a=log_uniform(1e4, 5e5),
)
def test_shift_laws_property(C1, C2, T_ref, dT, E_a):
    T = T_ref + np.array(dT) * C2  # above the WLF pole T_ref - C2
    wlf = pf.viscoelastic.WLF(C1, C2)
    np.testing.assert_allclose(wlf.log10_aT(T, T_ref), -C1 * (T - T_ref) / (C2 + T - T_ref), rtol=1e-12, atol=1e-12)
    assert wlf.log10_aT(T_ref, T_ref) == 0.0
    arr = pf.viscoelastic.Arrhenius(E_a)
    ref = E_a / (8.314462618 * math.log(10)) * (1 / (T + 273.15) - 1 / (T_ref + 273.15))
    np.testing.assert_allclose(arr.log10_aT(T, T_ref), ref, rtol=1e-12, atol=1e-12)
    table = pf.viscoelastic.ShiftTable([T_ref - 10, T_ref, T_ref + 10], [10.0, 1.0, 0.1])
    inside = np.clip(T, T_ref - 10, T_ref + 10)
    np.testing.assert_allclose(table.log10_aT(inside, T_ref), -(inside - T_ref) / 10, rtol=1e-12, atol=1e-12)
    with pytest.raises(ValueError, match="temperature"):
        wlf.log10_aT(T_ref - C2 * 1.01, T_ref)


@FAST
@given(eps=st.lists(log_uniform(1e-4, 10.0), min_size=1, max_size=6), n=st.integers(2, 6), data=st.data())
def test_strain_softening_property(eps, n, data):
    strain = np.logspace(-3, 0, n)
    f = np.array(data.draw(st.lists(st.floats(0.1, 1.0), min_size=n, max_size=n)))
    g = np.array(data.draw(st.lists(st.floats(0.1, 1.0), min_size=n, max_size=n)))
    soft = pf.viscoelastic.StrainSoftening(strain, f, g)
    fe, ge = soft.factors(np.array(eps))
    np.testing.assert_allclose(fe, np.interp(np.log(np.array(eps)), np.log(strain), f), rtol=1e-13)
    np.testing.assert_allclose(ge, np.interp(np.log(np.array(eps)), np.log(strain), g), rtol=1e-13)
    assert np.all(fe >= f.min() - 1e-15) and np.all(fe <= f.max() + 1e-15)


@FAST
@given(T=st.floats(-273.0, 500.0))
def test_check_temperature_property(T):
    assert float(pf.viscoelastic.check_temperature(T)) == T
    with pytest.raises(ValueError, match="temperature"):
        pf.viscoelastic.check_temperature(-273.15 - abs(T))


# -- the friction integrals ---------------------------------------------------------------------------------------
@FAST
@given(z=zeners(), w0=st.lists(log_uniform(1e-3, 1e14), min_size=1, max_size=8))
def test_angular_integrals_property(z, w0):
    from persson_fp.theory.sliding import AngularIntegrals

    w0 = np.array(w0)
    Phi, Psi = zener_phi_psi(w0, z)
    P1, P2, Ps = AngularIntegrals(z)(w0)
    np.testing.assert_allclose(P1 + P2, Phi, rtol=1e-5)
    np.testing.assert_allclose(Ps, Psi, rtol=1e-5, atol=1e-5 * Psi.max())


@FAST
@given(psd=spectra(), z=zeners(), s0=log_uniform(1e-3, 1.0), v=st.lists(log_uniform(1e-8, 1e2), min_size=1, max_size=4),
       c=log_uniform(1e-3, 1e3))  # fmt: skip
def test_rubber_friction_scaling_property(psd, z, s0, v, c):
    """mu and A are unchanged by E -> cE with sigma0 -> c sigma0 (G and Im E / sigma0 invariant) and by
    v -> c v with tau -> tau / c (the frequencies q v tau unchanged); one by one = vectorised."""
    sigma0 = s0 * z.E_rubbery
    v = np.array(v)
    base = pf.rubber_friction(psd, z, sigma0, v)
    scaled = pf.rubber_friction(
        psd, pf.viscoelastic.Zener(c * z.E_rubbery, c * z.E_glassy, z.tau, nu=z.nu), c * sigma0, v
    )
    faster = pf.rubber_friction(psd, pf.viscoelastic.Zener(z.E_rubbery, z.E_glassy, z.tau / c, nu=z.nu), sigma0, c * v)
    for other in (scaled, faster):
        np.testing.assert_allclose(other.mu, base.mu, rtol=1e-6, atol=1e-12)
        np.testing.assert_allclose(other.contact_area, base.contact_area, rtol=1e-6, atol=1e-300)
    one = pf.rubber_friction(psd, z, sigma0, float(v[-1]))
    assert float(one.mu) == pytest.approx(base.mu[-1], rel=1e-12, abs=1e-300)
    assert np.all(base.mu >= 0) and np.all((base.contact_area > 0) & (base.contact_area <= 1))
    assert np.all(np.diff(base.P, axis=-1) <= 1e-15)  # P(q) never grows with q
    r = repr(base)
    assert "flash temperature" in r


@FAST
@given(psd=spectra(), z=zeners(elastic=True), s0=log_uniform(1e-3, 1.0), v=log_uniform(1e-6, 10.0))
def test_elastic_limit_property(psd, z, s0, v):
    """Im E = 0: no friction at all, and P(q1) is the elastic half-space's erf(sigma0 / sqrt(2 V))."""
    sigma0 = s0 * z.E_rubbery
    res = pf.rubber_friction(psd, z, sigma0, v)
    assert float(res.mu) == 0.0
    E_star = z.E_rubbery / (1 - z.nu**2)
    A = erf(sigma0 / math.sqrt(2 * float(psd.V(psd.zeta_max, E_star))))
    assert float(res.contact_area) == pytest.approx(A, rel=1e-9, abs=1e-300)
    pr = pf.sliding_contact(psd, z, sigma0, v)
    zeta = np.geomspace(1.001, psd.zeta_max, 7)
    np.testing.assert_allclose(pr.V(zeta), psd.V(zeta, E_star), rtol=1e-12)


@pytest.mark.slow
@SLOW
@given(psd=spectra(max_decades=3.0), z=zeners(), s0=log_uniform(1e-2, 1.0), v=log_uniform(1e-6, 1e1))
def test_rubber_friction_against_quadrature_property(psd, z, s0, v):
    """A Zener rubber on a random self-affine road: mu and A against scipy quad in ln q with the closed-form angular
    integrals, within the result's own error estimate plus the reference's own accuracy."""
    sigma0 = s0 * z.E_rubbery
    nu2 = 1 - z.nu**2

    def G(q):
        pts = [math.log(psd.q_r)] if psd.q_l * (1 + 1e-6) < psd.q_r < q else None
        f = lambda x: math.exp(4 * x) * float(psd.C(math.exp(x))) * float(zener_phi_psi(math.exp(x) * v, z)[0])
        a, b = math.log(psd.q_l), math.log(q)
        if b - a < 1e-7:  # G grows linearly from q0: the trapezoid is exact to 1e-14 there
            return 0.5 * (f(a) + f(b)) * (b - a) / (8 * nu2**2 * sigma0**2)
        return quad(f, a, b, points=pts, limit=300, epsrel=1e-11)[0] / (8 * nu2**2 * sigma0**2)

    def integrand(t):  # in t with ln q = ln q0 + t^2: P ~ 1/sqrt(ln(q/q0)) near q0 becomes smooth
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
            * (0.45 + 0.55 * P * P)
            * float(zener_phi_psi(q * v, z)[1])
            / (nu2 * sigma0)
        )

    # quad over sub-intervals growing geometrically from q0 (one call over the whole range can miss the steep part
    # near q0 while reporting 1e-10), the roll-off among the ends
    t_end = math.sqrt(math.log(psd.zeta_max))
    ends = set(np.geomspace(1e-6, t_end, 9)) | {0.0}
    if psd.q_l * (1 + 1e-6) < psd.q_r < psd.q_s:
        ends.add(math.sqrt(math.log(psd.q_r / psd.q_l)))
    ends = sorted(ends)
    mu = sum(quad(integrand, a, b, limit=200, epsrel=1e-11)[0] for a, b in zip(ends[:-1], ends[1:]))
    A = erf(0.5 / math.sqrt(G(psd.q_s)))
    res = pf.rubber_friction(psd, z, sigma0, v)
    # the nested adaptive quadratures of this reference agree with their own refinements to ~1e-6 (the inner G is
    # a quad inside the outer quad's integrand): the allowance for the reference itself
    assert abs(float(res.mu) - mu) <= float(res.mu_error) + 2e-6 * mu + 1e-15
    assert abs(float(res.contact_area) - A) <= float(res.contact_area_error) + 1e-7 * A + 1e-300


# -- invalid input ------------------------------------------------------------------------------------------------
BAD_NUMBERS = st.sampled_from([float("nan"), float("inf"), -1.0, 0.0, True, "1", None, [1.0, 2.0], 1e400])


@FAST
@given(bad=BAD_NUMBERS, which=st.sampled_from(["sigma0", "velocity", "q1", "temperature"]))
def test_rubber_friction_invalid_property(bad, which):
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1e3, 1e4, 1e7)
    mat = pf.viscoelastic.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=pf.viscoelastic.WLF(8.86, 101.6))
    args = dict(sigma0=2e5, velocity=0.01, temperature=20.0)
    if bad is None and which in ("q1",):  # None is the default cut-off: valid
        return
    if which == "velocity" and isinstance(bad, list):  # a list of speeds is valid
        bad = [1.0, -2.0]
    if which == "temperature" and isinstance(bad, list):
        bad = [20.0, -400.0]
    if which == "temperature" and (bad in (-1.0, 0.0)):  # valid temperatures in degrees C
        bad = -500.0
    args[which] = bad
    with pytest.raises(ValueError, match=which):
        pf.rubber_friction(psd, mat, **args)


@FAST
@given(bad=BAD_NUMBERS, which=st.sampled_from(["E_rubbery", "E_glassy", "tau", "nu"]))
def test_zener_and_prony_invalid_property(bad, which):
    args = dict(E_rubbery=1e6, E_glassy=1e9, tau=1e-3, nu=0.5)
    if which == "nu" and bad == 0.0:
        bad = 0.7  # nu = 0 is valid
    args[which] = bad
    with pytest.raises(ValueError, match=which):
        pf.viscoelastic.Zener(**args)
    if which != "E_glassy":
        pargs = dict(E_rubbery=1e6, E_i=[1e8], tau_i=[1e-3], nu=0.5)
        key = {"tau": "tau_i"}.get(which, which)
        pargs[key] = bad if key != "tau_i" else [bad] if not isinstance(bad, list) else [1.0, -1.0]
        with pytest.raises(ValueError, match=key):
            pf.viscoelastic.Prony(**pargs)


@FAST
@given(
    which=st.sampled_from(["frequency", "E_storage", "E_loss"]),
    bad=st.sampled_from([float("nan"), float("inf"), -1.0, 0.0, "x", True]),
    i=st.integers(0, 3),
)
def test_master_curve_invalid_property(which, bad, i):
    cols = dict(frequency=[1.0, 10.0, 100.0, 1000.0], E_storage=[1e6, 2e6, 3e6, 4e6], E_loss=[1e5, 2e5, 2e5, 1e5])
    col = list(cols[which])
    col[i] = bad
    cols[which] = col
    with pytest.raises(ValueError, match=which):
        pf.viscoelastic.MasterCurve(**cols, check_kk=False)


@FAST
@given(
    which=st.sampled_from(["C1", "C2", "E_a", "T", "a_T", "strain", "f", "g"]),
    bad=st.sampled_from([float("nan"), float("inf"), -1.0, 0.0, "x", True]),
)
def test_shift_and_softening_invalid_property(which, bad):
    with pytest.raises(ValueError, match=which if which not in ("T",) else "T"):
        if which == "C1":
            pf.viscoelastic.WLF(bad, 100.0)
        elif which == "C2":
            pf.viscoelastic.WLF(8.0, bad)
        elif which == "E_a":
            pf.viscoelastic.Arrhenius(bad)
        elif which == "T":
            pf.viscoelastic.ShiftTable([0.0, bad if bad not in (-1.0, 0.0) else -500.0], [1.0, 0.1])
        elif which == "a_T":
            pf.viscoelastic.ShiftTable([0.0, 10.0], [1.0, bad])
        elif which == "strain":
            pf.viscoelastic.StrainSoftening([0.01, bad], [1.0, 0.5], [1.0, 0.5])
        elif which == "f":
            pf.viscoelastic.StrainSoftening([0.01, 0.1], [1.0, bad], [1.0, 0.5])
        else:
            pf.viscoelastic.StrainSoftening([0.01, 0.1], [1.0, 0.5], [bad, 0.5])


@FAST
@given(bad=BAD_NUMBERS, which=st.sampled_from(["sigma0", "velocity", "temperature"]))
def test_sliding_contact_invalid_property(bad, which):
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1e3, 1e4, 1e7)
    mat = pf.viscoelastic.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=pf.viscoelastic.WLF(8.86, 101.6))
    args = dict(sigma0=2e5, velocity=0.01, temperature=20.0)
    if which == "sigma0" and isinstance(bad, list):
        return  # several loads are valid
    if which == "temperature" and bad in (-1.0, 0.0):
        bad = -500.0
    args[which] = bad
    name = {"sigma0": "p_bar"}.get(which, which)
    with pytest.raises(ValueError, match=name):
        pf.sliding_contact(psd, mat, **args)


def test_friction_result_is_what_rubber_friction_returns():
    """FrictionResult: the class of every rubber_friction result, its fields fixed by name (scripts rely on them)."""
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1e3, 1e4, 1e6)
    res = pf.rubber_friction(psd, pf.viscoelastic.Zener(3e6, 3e9, 1e-4), 2e5, [0.01, 0.1])
    assert isinstance(res, pf.FrictionResult)
    for name in ("mu", "contact_area", "q", "G", "P", "mu_error", "contact_area_error", "conventions"):
        assert hasattr(res, name)


@FAST
@given(v=st.lists(log_uniform(1e-6, 10.0), min_size=1, max_size=3), T=st.lists(st.floats(-20, 80), min_size=1,
       max_size=3))  # fmt: skip
def test_friction_result_property(v, T):
    """The result's fields: shapes broadcast (temperature, velocity) with a trailing q axis; the table's rows are the
    broadcast pairs in C order; P = erf(1/(2 sqrt(G))) at every node."""
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1e3, 1e4, 1e6)
    mat = pf.viscoelastic.Zener(3e6, 3e9, 1e-4, T_ref=20.0, shift=pf.viscoelastic.WLF(8.86, 101.6))
    Tc = np.array(T)[:, None]
    res = pf.rubber_friction(psd, mat, 2e5, np.array(v), temperature=Tc)
    assert isinstance(res, pf.FrictionResult)
    assert res.mu.shape == (len(T), len(v)) and res.P.shape == (len(T), len(v), res.q.size)
    with np.errstate(divide="ignore"):
        np.testing.assert_allclose(res.P, erf(0.5 / np.sqrt(res.G)), rtol=1e-14)
    tab = res.table
    np.testing.assert_array_equal(np.asarray(tab["temperature [degC]"]), np.broadcast_to(Tc, res.mu.shape).ravel())
    np.testing.assert_array_equal(np.asarray(tab["mu [-]"]), res.mu.ravel())


@FAST
@given(z=zeners(), p=pronys(), T=st.floats(-50.0, 150.0))
def test_material_base_and_constants_property(z, p, T):
    """Every material is a ViscoelasticMaterial whose modulus at T is b_T E_ref(omega a_T); every shift law a
    ShiftLaw; the module's constants are the physical ones (R exact in SI since 2019, 0 degC = 273.15 K)."""
    law = pf.viscoelastic.WLF(8.86, 101.6)
    for m in (z, p):
        assert isinstance(m, pf.viscoelastic.ViscoelasticMaterial) and not m.needs_temperature
    shifted = pf.viscoelastic.Zener(z.E_rubbery, z.E_glassy, z.tau, nu=z.nu, T_ref=20.0, shift=law, vertical="kelvin")
    assert isinstance(law, pf.viscoelastic.ShiftLaw)
    w = np.logspace(-3, 9, 7)
    aT = 10.0 ** (-8.86 * (T - 20.0) / (101.6 + T - 20.0))
    bT = (T + pf.viscoelastic.KELVIN) / (20.0 + pf.viscoelastic.KELVIN)
    np.testing.assert_allclose(shifted.modulus(w, T), bT * z.modulus(w * aT), rtol=1e-12)
    np.testing.assert_allclose(shifted.storage_modulus(w, T), bT * z.modulus(w * aT).real, rtol=1e-12)
    np.testing.assert_allclose(shifted.loss_modulus(w, T), bT * z.modulus(w * aT).imag, rtol=1e-12, atol=1e-300)
    assert pf.viscoelastic.R_GAS == 8.314462618 and pf.viscoelastic.KELVIN == 273.15
    assert 0 < pf.viscoelastic.KK_TOLERANCE < 0.2


GARBAGE = st.sampled_from([float("nan"), 1.0, -1.0, True, "road", None, [1.0, 2.0], np.array([]), 1 + 2j, object()])


@FAST
@given(bad=GARBAGE, which=st.sampled_from(["rubber_friction", "sliding_contact"]))
def test_not_a_spectrum_is_refused_property(bad, which):
    """Anything but a spectrum as ``psd`` is one ValueError naming psd (it was an AttributeError)."""
    mat = pf.viscoelastic.Zener(3e6, 3e9, 1e-4)
    fn = pf.rubber_friction if which == "rubber_friction" else pf.sliding_contact
    with pytest.raises(ValueError, match="psd"):
        fn(bad, mat, 2e5, 0.01)


@FAST
@given(bad=GARBAGE, which=st.sampled_from(["omega", "E_storage", "E_loss"]))
def test_kramers_kronig_misfit_invalid_property(bad, which):
    """A table that is not three positive increasing columns of one length is refused naming the column (it was an
    IndexError or a TypeError)."""
    cols = dict(omega=[1.0, 10.0, 100.0], E_storage=[1e6, 2e6, 3e6], E_loss=[1e5, 2e5, 3e5])
    cols[which] = bad
    with pytest.raises(ValueError, match=which):
        pf.viscoelastic.kramers_kronig_misfit(**cols)


def test_extreme_scales_are_refused_not_infinite():
    """A subnormal sigma0 and a speed that overflows q v are refused by name (they gave NaN and an OverflowError)."""
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1e3, 1e4, 1e7)
    mat = pf.viscoelastic.Zener(3e6, 3e9, 1e-4)
    with pytest.raises(ValueError, match="sigma0"):
        pf.rubber_friction(psd, mat, 1e-320, 0.01)
    with pytest.raises(ValueError, match="velocity"):
        pf.sliding_contact(psd, mat, 2e5, 1e308)
    assert np.isfinite(pf.viscoelastic.WLF(8.86, 101.6).log10_aT(1e308, 20.0))
