"""Loads beyond the separation theory's range (p_bar >= E*, full contact) are named in a warning, and the value is
still the theory's (an independent quadrature of Persson 2007's integral, plain theory)."""

import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import exp1

import persson_fp as pf
from persson_fp.theory.separation import FULL_CONTACT

E = 1.0
SLOPE, H, Q_L, Q_R, Q_S = 0.1, 0.8, 2 * np.pi, 8 * np.pi, 128 * np.pi
PSD = pf.SelfAffinePSD.from_rms_slope(SLOPE, H, Q_L, Q_R, Q_S)
SIGMA_MAX = E * SLOPE / 2  # sqrt(V(zeta_max)), V = E*^2 <|grad h|^2> / 4


def _u_plain(p_bar):
    """u = (2/E*) int_{q_l}^{q_s} g(p_bar / sigma(q)) / q  dsigma/dq dq, g(y) = E1(y^2/2) / sqrt(2 pi) (Persson 2007),
    sigma^2 = V(q) = (pi/2) E*^2 int_{q_l}^q k^3 C(k) dk: the spectrum integrated here in closed form."""
    C0 = float(PSD.C(Q_L))

    def V(q):
        flat = 0.25 * (min(q, Q_R) ** 4 - Q_L**4)
        tail = 0.0 if q <= Q_R else Q_R ** (2 + 2 * H) * (q ** (2 - 2 * H) - Q_R ** (2 - 2 * H)) / (2 - 2 * H)
        return 0.5 * np.pi * E**2 * C0 * (flat + tail)

    def f(q):
        s = np.sqrt(V(q))
        dV = 0.5 * np.pi * E**2 * q**3 * float(PSD.C(q))
        return exp1((p_bar / s) ** 2 / 2) / np.sqrt(2 * np.pi) / q * dV / (2 * s)

    # the integrand is significant only near q_s (sigma near sigma_max) at these loads
    return 2 / E * quad(f, Q_L * 1.0001, Q_S, points=[Q_R], limit=400, epsabs=0, epsrel=1e-10)[0]


def test_full_contact_and_a_load_above_the_modulus_are_named_and_the_value_still_returned():
    ms = pf.MeanSeparation(PSD, E)
    assert float(np.sqrt(PSD.V(E_star=E))) == pytest.approx(SIGMA_MAX, rel=1e-9)
    fine = pf.MeanSeparation(PSD, E, n_per_unit=200)
    # p_bar / sqrt(V): the last load inside the range, then full contact (u ~ 1e-40, 1e-96 of the band's scale);
    # the default rule (2 panels per unit of ln sigma) resolves the tail to 7.5e-9 at 8, 1.5e-3 at 12, 25 % at 20
    # (it decays over 1 / y^2 in ln sigma), a fine one to 1e-9 (measured)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert float(ms.mean_separation(7 * SIGMA_MAX)) == pytest.approx(_u_plain(7 * SIGMA_MAX), rel=1e-9, abs=0)
    for ratio, rel in ((12.0, 3e-3), (20.0, 0.3)):
        p = ratio * SIGMA_MAX
        with pytest.warns(UserWarning, match=r"full contact .*exponentially small") as rec:
            u = float(ms.mean_separation(p))
        assert len(rec) == 1 and f"= {ratio:.3g} > {FULL_CONTACT:g}" in str(rec[0].message)
        ref = _u_plain(p)
        assert u == pytest.approx(ref, rel=rel, abs=0)
        with pytest.warns(UserWarning, match="full contact"):
            assert float(fine.mean_separation(p)) == pytest.approx(ref, rel=1e-8, abs=0)
    with pytest.warns(UserWarning, match=r"p_bar = 2 >= E\* = 1: .*beyond the linear elasticity") as rec:
        u = ms.mean_separation(2 * E)  # p_bar / sqrt(V) = 40: below the floating-point range
    assert u == 0.0 and "below the floating-point range" in str(rec[0].message)
    with pytest.warns(UserWarning, match=r"full contact .*exponentially large"):
        K = ms.stiffness(10 * SIGMA_MAX)
    assert np.isfinite(K) and K > 1e20


def test_loads_inside_the_range_are_silent_and_the_neighbourhood_is_monotone():
    ratios = np.geomspace(0.1, 10.0, 41)  # p_bar / E* (p_bar / sqrt(V) from 2 to 200)
    for fudge in (None, "YP08", "WM17", "Xu24"):
        ms = pf.MeanSeparation(PSD, E, fudge)
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            u_in = ms.mean_separation(np.array([1e-3, 0.1, 1.0, FULL_CONTACT * 0.999]) * SIGMA_MAX)
        assert np.all(np.diff(u_in) < 0)
        with pytest.warns(UserWarning):
            u = ms.mean_separation(ratios * E)
        assert np.all(np.isfinite(u)) and np.all(u >= 0) and np.all(np.diff(u) <= 0)  # no NaN, no rise
    steep = pf.MeanSeparation(pf.SelfAffinePSD.from_rms_slope(4.0, H, Q_L, Q_R, Q_S), E)  # sqrt(V) = 2 E*
    with pytest.warns(UserWarning, match=r"E\* = 1: .*linear elasticity") as rec:
        steep.mean_separation(1.5 * E)  # p_bar / sqrt(V) = 0.75: not full contact, but p_bar > E*
    assert "full contact" not in str(rec[0].message)
