"""Spectrum moments against independent quadrature (scipy.integrate.quad)."""

import numpy as np
import pytest
from scipy.integrate import quad

import persson_fp as pf


def quad_moment(psd, k, zeta):
    """Independent reference: adaptive quadrature of q^k C(q), split at the roll-off."""
    q_hi = zeta * psd.q_l
    pts = sorted({psd.q_l, min(max(getattr(psd, "q_r", psd.q_l), psd.q_l), q_hi), q_hi})
    total = 0.0
    for a, b in zip(pts[:-1], pts[1:]):
        if b > a:
            total += quad(lambda q: q**k * psd.C(q), a, b, epsabs=0, epsrel=1e-13, limit=200)[0]
    return total


@pytest.mark.parametrize("H", [0.0, 0.3, 0.5, 0.8, 1.0])
@pytest.mark.parametrize("q_r", [1.0, 2.0, 10.0])
@pytest.mark.parametrize("zeta", [1.5, 3.0, 64.0])
def test_moments_closed_form_vs_quad(H, q_r, zeta):
    psd = pf.SelfAffinePSD(C0=2.5e-4, H=H, q_l=1.0, q_r=q_r, q_s=64.0)
    for k in (1, 2, 3):
        ref = quad_moment(psd, k, zeta)
        assert psd.moment(k, zeta) == pytest.approx(ref, rel=1e-10)
    # V and dV/dzeta from their definitions (eq:V_equ, eq:dVdxi)
    E = 2.0
    assert psd.V(zeta, E) == pytest.approx(np.pi / 2 * E**2 * quad_moment(psd, 3, zeta), rel=1e-10)
    h = 1e-5 * zeta
    if zeta + h <= psd.zeta_max and abs(zeta * psd.q_l - q_r) > 1e-3:
        fd = (psd.V(zeta + h, E) - psd.V(zeta - h, E)) / (2 * h)
        assert psd.dV_dzeta(zeta, E) == pytest.approx(fd, rel=1e-7)


def test_tutorial_closed_forms():
    """eq:Vh_closed_form and eq:Vp_closed_form as printed in the Xu et al. tutorial, 0 < H < 1."""
    C0, H, ql, qr, qs, E = 3e-4, 0.7, 2.0, 8.0, 256.0, 1.7
    psd = pf.SelfAffinePSD(C0, H, ql, qr, qs)
    for z in (2.0, 4.0, 100.0):  # below and above the roll-off (zeta_r = 4)
        if z * ql < qr:
            h2 = np.pi * C0 * qr ** (-2 * H - 2) * ql**2 * (z**2 - 1)
            V = np.pi / 8 * E**2 * C0 * qr ** (-2 * H - 2) * ql**4 * (z**4 - 1)
        else:
            h2 = (
                np.pi
                * C0
                * (qr ** (-2 * H - 2) * (qr**2 - ql**2) + (qr ** (-2 * H) - z ** (-2 * H) * ql ** (-2 * H)) / H)
            )
            V = (
                np.pi
                / 8
                * E**2
                * C0
                * (
                    qr ** (-2 * H - 2) * (qr**4 - ql**4)
                    + 2 / (1 - H) * (z ** (2 - 2 * H) * ql ** (2 - 2 * H) - qr ** (2 - 2 * H))
                )
            )
        assert psd.h2(z) == pytest.approx(h2, rel=1e-12)
        assert psd.V(z, E) == pytest.approx(V, rel=1e-12)


@pytest.mark.parametrize("H_limit", [0.0, 1.0])
def test_continuity_at_log_limits(H_limit):
    """The closed forms are continuous at H = 0 and H = 1 (logarithmic limits)."""
    base = pf.SelfAffinePSD(1e-4, H_limit, 1.0, 3.0, 500.0)
    for eps in (1e-6, 1e-9):
        H = H_limit + eps if H_limit == 0 else H_limit - eps
        near = pf.SelfAffinePSD(1e-4, H, 1.0, 3.0, 500.0)
        for k in (1, 2, 3):
            assert near.moment(k, 400.0) == pytest.approx(base.moment(k, 400.0), rel=20 * eps * np.log(500) ** 2)
    # the H = 1 tail of V is (pi/8) E^2 C0 * 4 ln(zeta q_l / q_r) (the H -> 1 limit of eq:Vp_closed_form)
    if H_limit == 1.0:
        plateau = np.pi / 8 * base.C0 * 3.0**-4 * (3.0**4 - 1.0)
        assert base.V(400.0) == pytest.approx(plateau + np.pi / 8 * base.C0 * 4 * np.log(400 / 3), rel=1e-13)


def test_no_rolloff_and_vectorised():
    psd = pf.SelfAffinePSD(1e-4, 0.8, 1.0, 1.0, 100.0)
    z = np.array([1.0, 2.0, 50.0, 100.0])
    V = psd.V(z)
    assert V.shape == (4,) and V[0] == 0.0
    assert np.all(np.diff(V) > 0)
    ref = [np.pi / 2 * quad_moment(psd, 3, zz) for zz in z]
    np.testing.assert_allclose(V, ref, rtol=1e-10)


def test_constructors_from_slope_and_height():
    s = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    assert s.rms_slope == pytest.approx(0.1, rel=1e-14)
    assert s.V(E_star=1.0) == pytest.approx(0.25 * 0.01, rel=1e-14)  # eq:VV_relation
    h = pf.SelfAffinePSD.from_rms_height(2e-3, H=0.3, q_l=1.0, q_r=4.0, q_s=64.0)
    assert h.rms_height == pytest.approx(2e-3, rel=1e-14)
    assert 2 * np.pi * quad_moment(h, 1, 64.0) == pytest.approx(4e-6, rel=1e-10)


@pytest.mark.parametrize("H", [0.0, 0.8, 1.0])
def test_tabulated_reproduces_self_affine(H):
    """Log-log interpolation is exact for a piecewise power law, so moments agree to round-off."""
    psd = pf.SelfAffinePSD(1e-4, H, 1.0, 4.0, 256.0)
    q = np.unique(np.concatenate((np.geomspace(1.0, 256.0, 60), [4.0])))
    tab = pf.TabulatedPSD(q, psd.C(q))
    z = np.array([1.0, 2.5, 4.0, 17.3, 256.0])
    for k in (1, 2, 3):
        np.testing.assert_allclose(tab.moment(k, z), psd.moment(k, z), rtol=1e-11, atol=0)
    np.testing.assert_allclose(tab.dV_dzeta(z), psd.dV_dzeta(z), rtol=1e-11)


def test_tabulated_moments_vs_quad_for_a_measured_shape():
    q = np.geomspace(1, 100, 25)
    C = 1e-3 * q**-3.1 * (1 + 0.3 * np.sin(q))
    tab = pf.TabulatedPSD(q, C)
    for z in (3.3, 100.0):
        ref = 0.0
        for a, b in zip(q[:-1], q[1:]):
            if a < z:
                ref += quad(lambda x: x**3 * tab.C(x), a, min(b, z), epsrel=1e-13, epsabs=0)[0]
        assert tab.moment(3, z) == pytest.approx(ref, rel=1e-10)


def test_tabulated_csv_roundtrip_and_bad_rows(tmp_path):
    good = tmp_path / "psd.csv"
    good.write_text("q,C\n1,1e-4\n2,2e-5\n4,3e-6\n")
    tab = pf.TabulatedPSD.from_csv(good)
    assert tab.zeta_max == 4.0
    bad = tmp_path / "bad.csv"
    bad.write_text("q,C\n1,1e-4\n2,-2e-5\n4,3e-6\n")
    with pytest.raises(ValueError, match="line 3"):
        pf.TabulatedPSD.from_csv(bad)
    bad.write_text("q,C\n1,1e-4\n2,abc\n")
    with pytest.raises(ValueError, match="line 3"):
        pf.TabulatedPSD.from_csv(bad)
    bad.write_text("wavenumber,C\n1,1e-4\n")
    with pytest.raises(ValueError, match="header"):
        pf.TabulatedPSD.from_csv(bad)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(C0=1e-4, H=1.2, q_l=1, q_r=2, q_s=10), "H must lie in"),
        (dict(C0=1e-4, H=-0.1, q_l=1, q_r=2, q_s=10), "H must lie in"),
        (dict(C0=1e-4, H=float("nan"), q_l=1, q_r=2, q_s=10), "H must be finite"),
        (dict(C0=0.0, H=0.8, q_l=1, q_r=2, q_s=10), "C0 must be > 0"),
        (dict(C0=float("inf"), H=0.8, q_l=1, q_r=2, q_s=10), "C0 must be finite"),
        (dict(C0=1e-4, H=0.8, q_l=3, q_r=2, q_s=10), "q_r must lie in"),
        (dict(C0=1e-4, H=0.8, q_l=1, q_r=20, q_s=10), "q_s must be >= q_r"),
        (dict(C0=1e-4, H=0.8, q_l=-1, q_r=2, q_s=10), "q_l must be > 0"),
        (dict(C0=1e-4, H=0.8, q_l=1, q_r=1, q_s=1), "q_s must be > q_l"),
    ],
)
def test_bad_spectrum_input(kwargs, match):
    with pytest.raises(ValueError, match=match):
        pf.SelfAffinePSD(**kwargs)


def test_bad_zeta_and_tabulated_input():
    psd = pf.SelfAffinePSD(1e-4, 0.8, 1.0, 2.0, 10.0)
    for z in (0.5, 11.0, np.nan):
        with pytest.raises(ValueError, match="zeta"):
            psd.V(z)
    with pytest.raises(ValueError, match="strictly increasing"):
        pf.TabulatedPSD([1, 3, 2], [1, 1, 1])
    with pytest.raises(ValueError, match="C must be > 0"):
        pf.TabulatedPSD([1, 2, 3], [1, 0, 1])
    with pytest.raises(ValueError, match="E_star"):
        psd.V(2.0, E_star=-1.0)


@pytest.mark.parametrize("H", [0.0, 0.5, 1.0])
@pytest.mark.parametrize("q_r", [1.0, 3.0])
def test_zeta_of_V_inverts_V(H, q_r):
    """The closed-form inverse against a bracketing root find (scipy brentq) of V(zeta) = V."""
    from scipy.optimize import brentq

    psd = pf.SelfAffinePSD(2e-4, H, 1.0, q_r, 300.0)
    E = 3.0
    V_max = float(psd.V(E_star=E))
    targets = np.array([0.0, 1e-9 * V_max, 0.01 * V_max, float(psd.V(q_r, E)), 0.5 * V_max, V_max, 2 * V_max])
    z = psd.zeta_of_V(targets, E)
    assert z[0] == 1.0 and z[-1] == psd.zeta_max
    for t, zz in zip(targets[1:-1], z[1:-1]):
        ref = brentq(lambda x, t=t: float(psd.V(x, E)) - t, 1.0, psd.zeta_max, xtol=1e-15, rtol=1e-15)
        assert zz == pytest.approx(ref, rel=1e-12)


def test_zeta_of_V_tabulated():
    q = np.geomspace(1, 100, 25)
    tab = pf.TabulatedPSD(q, 1e-3 * q**-3.1 * (1 + 0.3 * np.sin(q)))
    z = np.geomspace(1, 100, 200)
    np.testing.assert_allclose(tab.zeta_of_V(tab.V(z)), z, rtol=1e-12)


def test_tabulated_band_limits_must_be_numbers():
    with pytest.raises(ValueError, match="q_l must be a real number"):  # was TypeError
        pf.TabulatedPSD([1.0, 2.0, 4.0], [1.0, 0.5, 0.1], q_l=[1, 2])
