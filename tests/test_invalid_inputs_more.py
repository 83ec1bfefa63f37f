"""More invalid inputs of the public API, each checked value by value (no sampling): a ValueError whose message
names the parameter, never a NaN, an inf, a TypeError or a silent number; and the finite numbers that extreme but
valid inputs must still give, against closed forms written here."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

import persson_fp as pf

PSD = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 1e3)
PR = pf.ContactProblem(PSD, 1.0, 0.05)
NAN = float("nan")
NOT_REAL = [NAN, float("inf"), None, "x", True, 1 + 1j, [1.0, NAN]]
FUDGES = [pf.fudge.NoFudge(), pf.fudge.YangPersson(), pf.fudge.WangMuser(), pf.fudge.Xu24()]


def _cases():
    for f in FUDGES:
        yield f"{f.name}.S A", lambda b, f=f: f.S(b), "A", NOT_REAL
        ev = pf.EffectiveVariance(f)
        yield f"{f.name} tau p_bar", lambda b, ev=ev: ev.tau(b, 1.0), "p_bar", NOT_REAL + [0.0, -1.0]
        yield f"{f.name} tau V", lambda b, ev=ev: ev.tau(1.0, b), "V", NOT_REAL + [-1.0, [1.0, -1.0]]
        yield f"{f.name} V_of_tau p_bar", lambda b, ev=ev: ev.V_of_tau(b, 1.0), "p_bar", NOT_REAL + [0.0, -1.0]
        yield f"{f.name} V_of_tau tau", lambda b, ev=ev: ev.V_of_tau(1.0, b), "tau", NOT_REAL + [-1.0]
    xu = pf.fudge.Xu24()
    yield "Xu24.area p_bar", lambda b: xu.area(b, 1.0), "p_bar", NOT_REAL + [0.0, -1.0]
    yield "Xu24.area V", lambda b: xu.area(0.1, b), "V", NOT_REAL + [-1.0]
    yield "SelfAffinePSD.C q", PSD.C, "q", NOT_REAL + [-1.0, -1e-300, [2.0, -2.0]]
    yield "zeta_of_V V", lambda b: PSD.zeta_of_V(b, 1.0), "V", NOT_REAL + [-1.0, [1.0, -1e-3]]
    yield "zeta_of_V E_star", lambda b: PSD.zeta_of_V(1.0, b), "E_star", [1e308, 1e200]
    yield "PSD.V E_star", lambda b: PSD.V(E_star=b), "E_star", [1e308, 1e200]
    yield "MeanSeparation decades", lambda b: pf.MeanSeparation(PSD, 1.0, decades=b), "decades", [1e308, 101.0, 3.0]
    yield "MagnificationResolved E_star", lambda b: pf.MagnificationResolved(PSD, b), "E_star", [1e308, 1e200]
    yield (
        "GapDistribution p_bar",
        lambda b: pf.GapDistribution(pf.MagnificationResolved(PSD), b),
        "p_bar",
        [1e308, 1e151, [0.1, 1e200]],
    )
    h = np.random.default_rng(0).normal(size=(16, 16))
    yield "psd_from_heightmap size", lambda b: pf.psd_from_heightmap(h, size=b), "size", ["x", 1 + 1j, True, None]
    prof = np.random.default_rng(0).normal(size=(4, 64))
    yield "psd_from_profiles H", lambda b: pf.psd_from_profiles(prof, 1.0, H=b), "H", [[0.5], np.array([0.5]), 0.5j]
    yield "sweep models", lambda b: pf.sweep(PSD, [0.1], models=b, progress=False), "models", [1.0, 3]
    yield "calibrate data", lambda b: pf.calibrate(PSD, b), "data", [1.0, 3]
    yield "pastewka_robbins rho", lambda b: pf.adhesion.pastewka_robbins(PSD, 1.0, 1e-3, b), "rho", [1e308]
    yield (
        "separation_from_areas E_star",
        lambda b: pf.separation_from_areas(PSD, b, [0.1, 0.2, 0.3], [1.0, 2.0], np.full((2, 3), 0.1)),
        "E_star",
        [1e308, 1e200],
    )


CASES = [(label, call, name, bad) for label, call, name, values in _cases() for bad in values]


@pytest.mark.parametrize(("call", "name", "bad"), [c[1:] for c in CASES], ids=[f"{c[0]}={c[3]!r}"[:60] for c in CASES])
def test_bad_input_is_a_value_error_naming_the_parameter(call, name, bad):
    """One ValueError naming the parameter (warnings as errors: no overflow on the way to it)."""
    with np.errstate(all="raise"), pytest.raises(ValueError, match=re.escape(name)):
        call(bad)


def test_fudge_factor_at_the_ends_of_its_range_is_the_closed_form():
    """S(0) = gamma and S(1) = 1 for YP08 and WM17 (S = gamma + (1 - gamma) A^2 and gamma - 2/9 A^2 +
    (11/9 - gamma) A^4): the range check lets both ends through."""
    for f in (pf.fudge.YangPersson(0.3), pf.fudge.WangMuser(0.5)):
        assert np.allclose(f.S(np.array([0.0, 1.0])), [f.gamma, 1.0], rtol=1e-15, atol=0)


def test_pastewka_robbins_at_a_huge_range_is_the_closed_form():
    """Pi = h' E* rho / (2 w) (h'^2 / (h'' rho))^(2/3) evaluated in logarithms (no overflow), for rho = 1e300."""
    E_star, w, rho = 1.0, 1e-3, 1e300
    out = pf.adhesion.pastewka_robbins(PSD, E_star, w, rho)
    h1, h2 = out["rms_slope"], out["rms_curvature"]
    log_pi = math.log(h1 * E_star / (2 * w)) + math.log(rho) + (2.0 / 3.0) * (2 * math.log(h1) - math.log(h2 * rho))
    assert math.isclose(out["number"], math.exp(log_pi), rel_tol=1e-12)
    assert out["sticky"] is False and math.isfinite(out["range_ratio"])


def test_leak_rate_is_linear_in_the_pressure_drop_up_to_the_float_limit():
    """Q = u^3 dp / (12 eta) (Persson's critical-junction estimate): Q(1e308) / Q(1) = 1e308 for an open seal,
    and a sealed interface (contact percolates before zeta_max) leaks 0 at any pressure drop."""
    open_ = pf.ContactProblem(PSD, 1.0, 0.001)
    q1, q_huge = pf.leak_rate(open_, 1.0, 1.0), pf.leak_rate(open_, 1.0, 1e308)
    assert q1 > 0 and math.isclose(q_huge / q1, 1e308, rel_tol=1e-12)
    sealed = pf.leak_rate(PR, 1.0, 1.0, full_output=True)
    assert sealed["sealed"] and sealed["flow_rate"] == 0.0 and pf.leak_rate(PR, 1.0, 1e308) == 0.0
