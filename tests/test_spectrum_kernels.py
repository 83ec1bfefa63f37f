"""The spectrum's unchecked kernels (what solvers call in their inner loops) against the physics and against the
checked public methods they sit behind.

For random self-affine and tabulated spectra, magnifications in [1, zeta_max] and moduli E*:
``moment_unchecked(3, .)`` gives V = (pi/2) E*^2 int q^3 C dq (``eq:Vp_closed_form``, by adaptive quadrature to 1e-9),
``dV_dzeta_unchecked`` is (pi/2) E*^2 q_l q^3 C(q) at q = zeta q_l (``eq:dVdxi``) evaluated here from C, and
``zeta_of_V_unchecked`` inverts V (the round trip to 1e-9); each equals its checked method bit for bit on valid
input.  The checked methods refuse bad input with a ValueError naming the parameter; the kernels check nothing
(deliberately: their callers have checked).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import persson_fp as pf

SETTINGS = settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])


def _log_uniform(lo, hi):
    return st.floats(np.log10(lo), np.log10(hi)).map(lambda x: 10.0**x)


@st.composite
def spectra(draw):
    H = draw(st.floats(0.0, 1.0))
    zeta_max = draw(_log_uniform(2.0, 1e5))
    zeta_r = min(draw(_log_uniform(1.0, 10.0)), zeta_max)
    q_l = draw(_log_uniform(1e-3, 1e3))
    slope = draw(_log_uniform(1e-3, 1.0))
    psd = pf.SelfAffinePSD.from_rms_slope(slope, H, q_l, zeta_r * q_l, zeta_max * q_l)
    if draw(st.booleans()):  # a table of the same shape, log-log interpolated (its own exact moments)
        q = np.geomspace(psd.q_l, psd.q_s, draw(st.integers(3, 40)))
        psd = pf.TabulatedPSD(q, psd.C(q))
    return psd


def _V_quad(psd, zeta, E):
    """(pi/2) E^2 int_{q_l}^{zeta q_l} q^3 C(q) dq by adaptive quadrature in ln q, split at every knot of C."""
    hi = np.log(zeta * psd.q_l)
    inner = psd.q if isinstance(psd, pf.TabulatedPSD) else [psd.q_r]
    knots = np.log(np.concatenate(([psd.q_l], inner, [psd.q_s])))
    cuts = np.unique(np.clip(knots, np.log(psd.q_l), hi))
    total = sum(
        quad(lambda x: np.exp(4.0 * x) * float(psd.C(np.exp(x))), a, b, epsabs=0.0, epsrel=1e-11, limit=200)[0]
        for a, b in zip(cuts[:-1], cuts[1:])
    )
    return 0.5 * np.pi * E**2 * total


@SETTINGS
@given(spectra(), st.lists(st.floats(0.0, 1.0), min_size=1, max_size=6), _log_uniform(1e-3, 1e3))
@example(pf.SelfAffinePSD(C0=3.2e-05, H=0.0, q_l=10.0, q_r=10.0, q_s=100.0), [1e-8], 1.0)  # z - 1 = 2.3e-8
def test_kernels_are_the_physics_and_the_checked_methods(psd, fractions, E):
    z = np.clip(np.exp(np.asarray(fractions) * np.log(psd.zeta_max)), 1.0, psd.zeta_max)  # as callers must
    V = 0.5 * np.pi * E**2 * psd.moment_unchecked(3, z)
    ref = np.array([_V_quad(psd, zi, E) for zi in z])
    # quadrature to 1e-11; the closed form's (b^e - a^e)/e cancels as z -> 1: a few eps of its terms, whose size is
    # that of the moment over the first octave of the band
    eps = np.finfo(float).eps
    octave = 0.5 * np.pi * E**2 * psd.moment_unchecked(3, min(2.0, psd.zeta_max))
    assert np.all(np.abs(V - ref) <= 1e-9 * np.abs(ref) + 64.0 * eps * octave)
    q = z * psd.q_l
    np.testing.assert_allclose(psd.dV_dzeta_unchecked(z, E), 0.5 * np.pi * E**2 * psd.q_l * q**3 * psd.C(q), rtol=1e-14)
    z_off = np.array([1.0 - 1e-13, psd.zeta_max * (1.0 + 1e-13)])  # round-off beyond the ends: clipped, as checked
    assert np.array_equal(psd.dV_dzeta_unchecked(z_off, E), psd.dV_dzeta(z_off, E))
    back = psd.zeta_of_V_unchecked(V, E)
    grows = psd.dV_dzeta_unchecked(z, E) > 0  # (where V is flat in zeta, the inverse is not unique)
    np.testing.assert_allclose(back[grows], z[grows], rtol=1e-9)
    for k in (1, 3):
        assert np.array_equal(psd.moment_unchecked(k, z), psd.moment(k, z))
    np.testing.assert_allclose(psd.V(z, E), V, rtol=1e-15)
    assert np.array_equal(psd.dV_dzeta_unchecked(z, E), psd.dV_dzeta(z, E))
    assert np.array_equal(back, psd.zeta_of_V(V, E))
    assert np.array_equal(psd.zeta_of_V_unchecked(V, E), psd.zeta_of_V(V, E))


BAD = [
    ("V", {"zeta": 0.5}, "zeta"),
    ("V", {"zeta": np.nan}, "zeta"),
    ("V", {"E_star": -1.0}, "E_star"),
    ("dV_dzeta", {"zeta": 1e9}, "zeta"),
    ("dV_dzeta", {"E_star": 0.0}, "E_star"),
    ("zeta_of_V", {"V": np.inf}, "V"),
    ("zeta_of_V", {"V": "1"}, "V"),
    ("zeta_of_V", {"E_star": np.nan}, "E_star"),
]


@pytest.mark.parametrize(("method", "kwargs", "name"), BAD)
def test_checked_methods_refuse_what_the_kernels_trust(method, kwargs, name):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    args = {"V": 1e-3} if method == "zeta_of_V" else {"zeta": 2.0}
    with pytest.raises(ValueError, match=name):
        getattr(psd, method)(**{**args, **kwargs})
