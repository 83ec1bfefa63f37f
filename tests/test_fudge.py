"""Fudge factors (eq:new_B2) and the effective-variance map (persson_fp.theory.effective)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.special import erf

import persson_fp as pf
from persson_fp.theory import fudge as F


def test_models_and_defaults_stated_once():
    assert F.YangPersson().gamma == F.GAMMA_YP08 == 0.45
    assert F.WangMuser().gamma == pytest.approx(5 / 9)
    assert F.Xu24().gamma == F.GAMMA_XU24
    A = np.linspace(0, 1, 11)
    np.testing.assert_allclose(F.YangPersson(0.42).S(A), 0.42 + 0.58 * A**2)
    np.testing.assert_allclose(F.WangMuser().S(A), 5 / 9 - 2 / 9 * A**2 + (11 / 9 - 5 / 9) * A**4)
    # every model tends to 1 at full contact
    for m in ("YP08", "WM17", "Xu24"):
        assert F.resolve(m).S(np.array(1.0)) == pytest.approx(1.0, abs=1e-15)
    assert isinstance(F.resolve(None), F.NoFudge)
    assert F.resolve("yp08") == F.YangPersson()


def test_derivatives_match_finite_differences():
    A = np.linspace(0.05, 0.95, 7)
    for m in (F.YangPersson(0.48), F.WangMuser()):
        fd = (m.S(A + 1e-6) - m.S(A - 1e-6)) / 2e-6
        np.testing.assert_allclose(m.dS_dA(A), fd, rtol=1e-7)


@pytest.mark.parametrize("bad", [lambda A: 1 - 2 * A, lambda A: np.where(A > 0.5, np.nan, 1.0), lambda A: 0 * A])
def test_user_callable_must_be_positive(bad):
    with pytest.raises(ValueError, match="must be finite, > 0"):
        F.resolve(bad)


def test_bad_names_and_gammas():
    with pytest.raises(ValueError, match="fudge must be None, one of"):
        F.resolve("YP09")
    with pytest.raises(ValueError, match="gamma of YP08"):
        F.YangPersson(gamma=0.0)
    with pytest.raises(ValueError, match="gamma of WM17"):
        F.WangMuser(gamma=2.0)


def test_scalar_only_user_callable_is_vectorised():
    def S(a):
        return 0.5 + 0.5 * float(a) ** 2

    f = F.resolve(S)
    np.testing.assert_allclose(f.S(np.array([0.0, 1.0])), [0.5, 1.0])


def reference_tau(S, p_bar, V_end):
    """Independent reference: dtau/dV = S(erf(p_bar / sqrt(2 tau))) integrated directly."""
    V0 = 1e-6 * p_bar**2  # A* = 1 to round-off up to here, so tau = S(1) V0
    sol = solve_ivp(
        lambda V, t: S(erf(p_bar / np.sqrt(2 * t))),
        (V0, V_end),
        [float(S(np.array(1.0))) * V0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-14 * p_bar**2,
    )
    return sol.y[0, -1]


@pytest.mark.parametrize(
    "model", [F.YangPersson(), F.YangPersson(0.42), F.WangMuser(), F.CallableFudge(lambda A: 0.7 + 0.1 * A)]
)
@pytest.mark.parametrize("ratio", [0.05, 0.5, 2.0])
def test_effective_variance_vs_direct_ode(model, ratio):
    ev = pf.effective_variance(model)
    p_bar = 0.03
    V_end = (p_bar / ratio) ** 2
    tau = ev.tau(p_bar, V_end)
    assert tau == pytest.approx(reference_tau(model.S, p_bar, V_end), rel=1e-9)


def test_effective_variance_is_load_scale_free():
    ev = pf.effective_variance(F.YangPersson())
    v = np.geomspace(1e-4, 1e8, 50)
    for p in (1e-3, 1.0, 1e4):
        np.testing.assert_allclose(ev.tau(p, v * p**2) / p**2, ev.u_of_v(v), rtol=1e-14)


def test_xu24_equivalent_S_reproduces_closed_form():
    """The B2 form S = dtau/dV of Xu24, integrated, gives the closed-form root find (two routes)."""
    m = F.Xu24()
    ev = pf.EffectiveVariance(m)  # the ODE route (uncached instance)
    p_bar = 1.0
    V = np.geomspace(1e-2, 1e6, 40)
    tau_ode = ev.tau(p_bar, V)
    A_closed = m.area(p_bar, V)
    np.testing.assert_allclose(A_closed, erf(p_bar / np.sqrt(2 * m.g(A_closed) * V)), rtol=1e-14)
    np.testing.assert_allclose(tau_ode, m.g(A_closed) * V, rtol=1e-9)


@pytest.mark.parametrize("model", [F.YangPersson(), F.WangMuser(), F.Xu24()])
def test_effective_variance_table_matches_dense_output(model):
    """The Hermite table behind u_of_v against the ODE solver's dense output it was built from.

    The table step in s = ln v is ~5e-3; cubic Hermite error h^4/384 max|w''''| is ~1e-12 for these
    smooth maps, so 1e-11 relative in u has a margin of ~5 and still catches any indexing slip (which
    would give errors of order h ~ 1e-3)."""
    ev = pf.EffectiveVariance(model)
    rng = np.random.default_rng(3)
    s = rng.uniform(np.log(ev.v0) + 1e-9, np.log(1e16) - 1e-9, 20_000)
    u_tab = ev.u_of_v(np.exp(s))
    u_ref = np.exp(ev.w_dense(s))
    np.testing.assert_allclose(u_tab, u_ref, rtol=1e-11)


@pytest.mark.parametrize("model", [F.YangPersson(), F.WangMuser(), F.CallableFudge(lambda A: 0.7 + 0.1 * A)])
def test_effective_variance_inverse_round_trip(model):
    """V_of_tau(tau(V)) = V from v = 1e-6 (A* = 1, linear branch) through the table to v = 1e20 (beyond
    V_MAX = 1e16, the linear continuation): each table is ~1e-12 accurate, 1e-10 leaves a margin."""
    ev = pf.EffectiveVariance(model)
    p_bar = 0.3
    V = p_bar**2 * np.geomspace(1e-6, 1e20, 200)
    np.testing.assert_allclose(ev.V_of_tau(p_bar, ev.tau(p_bar, V)), V, rtol=1e-10)
