"""Viscoelastic materials and shift laws against formulas written here (Zener, Prony, WLF, Arrhenius, tables)."""

import math
import warnings

import numpy as np
import pytest

import persson_fp as pf
from tests.friction.conftest import prony_model

ve = pf.viscoelastic


def test_zener_modulus_is_the_standard_linear_solid():
    z = ve.Zener(1e6, 1e9, 1e-3, nu=0.4)
    w = np.logspace(-2, 8, 21)
    ref = 1e6 + (1e9 - 1e6) * 1j * w * 1e-3 / (1 + 1j * w * 1e-3)
    np.testing.assert_allclose(z.modulus(w), ref, rtol=1e-14)
    assert z.nu == 0.4 and not z.needs_temperature


def test_prony_modulus_is_the_sum_of_maxwell_elements():
    p = prony_model()
    w = np.logspace(-3, 10, 27)
    ref = p.E_rubbery + sum(E * 1j * w * t / (1 + 1j * w * t) for E, t in zip(p.E_i, p.tau_i))
    np.testing.assert_allclose(p.modulus(w), ref, rtol=1e-13)
    assert p.E_glassy == pytest.approx(p.E_rubbery + p.E_i.sum(), rel=1e-15)


def test_elastic_zener_has_no_loss():
    z = ve.Zener(2e6, 2e6, 1e-3)
    E = z.modulus(np.logspace(-5, 12, 30))
    assert np.all(E.imag == 0.0) and np.all(E.real == 2e6)


def test_master_curve_reproduces_its_points_and_the_model_between_them():
    p = prony_model()
    f = np.logspace(-4, 10, 141)  # 10 points per decade
    E = p.modulus(2 * np.pi * f)
    mc = ve.MasterCurve(f, E.real, E.imag, frequency_unit="Hz")
    np.testing.assert_allclose(mc.modulus(2 * np.pi * f), E, rtol=1e-12)
    w = 2 * np.pi * np.logspace(-3.95, 9.95, 200)
    # cubic splines in log-log between points 0.1 decade apart: the model within 1e-4 (measured 3e-5)
    np.testing.assert_allclose(mc.modulus(w).real, p.modulus(w).real, rtol=1e-4)
    np.testing.assert_allclose(mc.modulus(w).imag, p.modulus(w).imag, rtol=1e-4)


def test_frequency_unit_hz_is_two_pi_rad_per_s():
    f = np.logspace(0, 6, 13)
    E1, E2 = 1e6 * (1 + np.log10(f)), 1e5 * (1 + 0.1 * np.log10(f))
    a = ve.MasterCurve(f, E1, E2, frequency_unit="Hz", check_kk=False)
    b = ve.MasterCurve(2 * np.pi * f, E1, E2, frequency_unit="rad/s", check_kk=False)
    w = np.logspace(0.5, 6.5, 40)
    np.testing.assert_allclose(a.modulus(w), b.modulus(w), rtol=1e-13)
    assert "Hz" in repr(a) and "rad/s" in repr(b)


def test_extrapolation_policies():
    f = np.array([1.0, 10.0, 100.0])
    E1, E2 = np.array([1e6, 2e6, 4e6]), np.array([1e5, 2e5, 4e5])
    clamp = ve.MasterCurve(f, E1, E2, frequency_unit="rad/s", check_kk=False)
    loglin = ve.MasterCurve(f, E1, E2, frequency_unit="rad/s", extrapolation="loglinear", check_kk=False)
    strict = ve.MasterCurve(f, E1, E2, frequency_unit="rad/s", extrapolation="raise", check_kk=False)
    assert clamp.modulus(1e4) == pytest.approx(4e6 + 4e5j, rel=1e-14)
    assert clamp.modulus(1e-3) == pytest.approx(1e6 + 1e5j, rel=1e-14)
    # log-log slope log10(2) per decade: two decades beyond 100 rad/s -> 4e6 * 4
    assert loglin.modulus(1e4) == pytest.approx(16e6 + 16e5j, rel=1e-12)
    with pytest.raises(ValueError, match="omega"):
        strict.modulus(1e3)
    assert strict.modulus(50.0).real > 0


def test_wlf_formula_and_pole():
    law = ve.WLF(8.86, 101.6)
    T = np.array([-20.0, 0.0, 20.0, 80.0])
    np.testing.assert_allclose(law.log10_aT(T, 20.0), -8.86 * (T - 20) / (101.6 + T - 20), rtol=1e-14)
    with pytest.raises(ValueError, match="temperature"):
        law.log10_aT(20.0 - 101.6, 20.0)


def test_arrhenius_in_kelvin():
    law = ve.Arrhenius(1e5)
    T, Tr = 60.0, 20.0
    ref = 1e5 / (8.314462618 * math.log(10)) * (1 / (T + 273.15) - 1 / (Tr + 273.15))
    assert law.log10_aT(T, Tr) == pytest.approx(ref, rel=1e-13)
    assert law.log10_aT(Tr, Tr) == 0.0


def test_shift_table_linear_in_log_a_and_warnings():
    table = ve.ShiftTable([0.0, 20.0, 40.0], [1e3, 1.0, 1e-2])
    assert table.log10_aT(10.0, 20.0) == pytest.approx(1.5, rel=1e-14)
    assert table.log10_aT(30.0, 20.0) == pytest.approx(-1.0, rel=1e-14)
    with pytest.warns(UserWarning, match="extrapolated"):
        assert table.log10_aT(50.0, 20.0) == pytest.approx(-3.0, rel=1e-14)
    with pytest.warns(UserWarning, match="a_T"):
        ve.Zener(1e6, 1e8, 1e-3, T_ref=10.0, shift=table)  # a_T(10) = 10^1.5: not the curve's reference


def test_time_temperature_superposition():
    z = ve.Zener(1e6, 1e9, 1e-3, T_ref=20.0, shift=ve.WLF(8.86, 101.6), vertical="kelvin")
    w = np.logspace(-2, 6, 9)
    aT = 10 ** (-8.86 * 30 / (101.6 + 30))
    bT = (50 + 273.15) / (20 + 273.15)
    ref = ve.Zener(1e6, 1e9, 1e-3).modulus(w * aT) * bT
    np.testing.assert_allclose(z.modulus(w, 50.0), ref, rtol=1e-13)
    with pytest.raises(ValueError, match="temperature"):
        z.modulus(w)


def test_strain_softening_interpolates_in_log_strain_and_holds_the_ends():
    s = ve.StrainSoftening([0.01, 0.1, 1.0], [1.0, 0.5, 0.25], [1.0, 0.8, 0.6])
    f, g = s.factors([0.001, math.sqrt(0.01 * 0.1), 0.1, 10.0])
    np.testing.assert_allclose(f, [1.0, 0.75, 0.5, 0.25], rtol=1e-14)
    np.testing.assert_allclose(g, [1.0, 0.9, 0.8, 0.6], rtol=1e-14)


def test_kramers_kronig_check_passes_a_causal_model_and_warns_a_doubled_loss():
    p = prony_model()
    f = np.logspace(-4, 10, 71)  # 5 points per decade
    E = p.modulus(2 * np.pi * f)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mc = ve.MasterCurve(f, E.real, E.imag)
    assert mc.kk_misfit < 0.01
    with pytest.warns(UserWarning, match="Kramers-Kronig"):
        bad = ve.MasterCurve(f, E.real, 2 * E.imag)
    assert bad.kk_misfit > 0.1


def test_from_csv(tmp_path):
    p = prony_model()
    f = np.logspace(-2, 8, 51)
    E = p.modulus(2 * np.pi * f)
    path = tmp_path / "mc.csv"
    np.savetxt(path, np.c_[f, E.real, E.imag], delimiter=",", header="frequency [Hz],E_storage [Pa],E_loss [Pa]",
               comments="")  # fmt: skip
    mc = ve.MasterCurve.from_csv(path)
    np.testing.assert_allclose(mc.modulus(2 * np.pi * f), E, rtol=1e-12)
    empty = tmp_path / "empty.csv"
    empty.write_text("")
    with pytest.raises(ValueError, match="frequency"):
        ve.MasterCurve.from_csv(empty)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(frequency=[1, 1, 2]), "frequency"),
        (dict(frequency=[1, 3, 2]), "frequency"),
        (dict(frequency=[-1, 2, 3]), "frequency"),
        (dict(E_storage=[1, -1, 1]), "E_storage"),
        (dict(E_loss=[1, -1, 1]), "E_loss"),
        (dict(E_loss=[1, np.nan, 1]), "E_loss"),
        (dict(nu=0.6), "nu"),
        (dict(nu=-0.1), "nu"),
        (dict(frequency_unit="kHz"), "frequency_unit"),
        (dict(extrapolation="linear"), "extrapolation"),
        (dict(shift=ve.WLF(8.86, 101.6)), "T_ref"),
        (dict(T_ref=-300.0), "T_ref"),
        (dict(shift="WLF"), "shift"),
    ],
)
def test_master_curve_refuses_bad_input(kwargs, name):
    base = dict(frequency=[1.0, 2.0, 3.0], E_storage=[1.0, 2.0, 3.0], E_loss=[0.1, 0.2, 0.3], check_kk=False)
    base.update(kwargs)
    with pytest.raises(ValueError, match=name):
        ve.MasterCurve(**base)


@pytest.mark.parametrize(
    "args, name",
    [
        ((-1.0, 2.0, 1.0), "E_rubbery"),
        ((1.0, 0.5, 1.0), "E_glassy"),
        ((1.0, 2.0, 0.0), "tau"),
        ((1.0, 2.0, np.inf), "tau"),
        ((True, 2.0, 1.0), "E_rubbery"),
    ],
)
def test_zener_refuses_bad_input(args, name):
    with pytest.raises(ValueError, match=name):
        ve.Zener(*args)
