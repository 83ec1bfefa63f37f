"""ContactProblem: an immutable value whose zeta_max quantities are cached (problem.py)."""

import numpy as np
import pytest

import persson_fp as pf


def test_problem_and_spectrum_are_immutable():
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.array([0.2, 1.0]))
    with pytest.raises(AttributeError, match="immutable"):
        pr.p_bar = np.array([1.0, 2.0])
    with pytest.raises(AttributeError, match="immutable"):
        pr.fudge = None
    with pytest.raises(ValueError):  # read-only array: an in-place edit cannot make the caches stale
        pr.p_bar[0] = 3.0
    with pytest.raises(AttributeError, match="immutable"):
        pr.psd.H = 0.5
    tab = pf.TabulatedPSD([1.0, 2.0, 4.0], [1.0, 0.5, 0.1])
    with pytest.raises(ValueError):
        tab.q[0] = 0.5


@pytest.mark.parametrize("fudge", [None, "YP08", "Xu24"])
def test_cached_zeta_max_quantities_match_fresh_ones(fudge):
    """V_max, tau_max and p_max against the uncached closed forms (V from the spectrum's moment,
    tau from tau_of_V at that V): equal to round-off, so caching changes nothing."""
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=np.array([0.01, 0.5, 3.0]))
    V_fresh = float(pr.psd.V(pr.zeta_max, pr.E_star))
    assert pr.V_max == pytest.approx(V_fresh, rel=1e-14)
    assert float(pr.V()) == pr.V_max
    tau_fresh = pr.tau_of_V(np.array([V_fresh]))[0]
    np.testing.assert_allclose(pr.tau_max, tau_fresh, rtol=1e-14)
    np.testing.assert_allclose(pr.tau(), tau_fresh, rtol=1e-14)
    assert pr.p_max(8.0) == pytest.approx(float(np.max(pr.p_bar + 8.0 * np.sqrt(tau_fresh))), rel=1e-14)


def test_tau_of_V_each_is_the_diagonal_of_tau_of_V():
    pr = pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=np.array([0.1, 0.5, 2.0]))
    V = pr.V_max * np.array([[0.1, 0.5, 0.9], [0.2, 0.3, 1.0]])  # one V per load, two rows
    each = pr.tau_of_V_each(V)
    for i in range(2):
        for j in range(3):
            assert each[i, j] == pytest.approx(pr.tau_of_V(V[i, j])[j], rel=1e-14)


@pytest.mark.parametrize("fudge", ["YP08", "WM17", "Xu24", None])
def test_V_of_tau_inverts_tau_of_V(fudge):
    """Round trip V -> tau -> V over 12 decades of V / p_bar^2 (both table branches, the linear ends):
    the Hermite tables of w(s) and s(w) are each ~1e-12 accurate, so 1e-10 relative leaves a margin."""
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=np.array([1e-4, 0.05, 0.5, 3.0]))
    V = pr.V_max * np.geomspace(1e-8, 1.0, 60)[:, None] * np.ones(pr.n_loads)
    tau = pr.tau_of_V_each(V)
    np.testing.assert_allclose(pr.V_of_tau_each(tau), V, rtol=1e-10)
    assert np.all(pr.V_of_tau_each(np.zeros(pr.n_loads)) == 0.0)


@pytest.mark.parametrize("fudge", ["YP08", "WM17"])
def test_huge_loads_small_V_do_not_underflow(fudge):
    """p_bar = 5e148 (allowed) and V / p_bar^2 below the smallest double: A* = 1, so tau = S(1) V exactly
    (V / p_bar^2 once underflowed to 0 and tau came back 0)."""
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=1e150)
    V = pr.V_max * np.array([1e-30, 1e-25, 1e-20])
    S1 = float(pr.fudge.S(np.array(1.0)))
    np.testing.assert_allclose(pr.tau_of_V(V)[:, 0], S1 * V, rtol=1e-14)
    np.testing.assert_allclose(pr.V_of_tau_each(S1 * V[:, None])[:, 0], V, rtol=1e-14)


def test_immutability_survives_pickle_and_deepcopy():
    import copy
    import pickle

    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.array([0.2, 1.0]))
    tau = pr.tau_max.copy()
    for clone in (pickle.loads(pickle.dumps(pr)), copy.deepcopy(pr)):
        np.testing.assert_array_equal(clone.tau_max, tau)
        with pytest.raises(ValueError):
            clone.p_bar[0] = 1e-3
        with pytest.raises(ValueError):
            clone.tau_max[0] = 1.0
        with pytest.raises(AttributeError, match="immutable"):
            del clone.p_bar
        with pytest.raises(AttributeError, match="immutable"):
            clone.psd.H = 0.3
    tab = copy.deepcopy(pf.TabulatedPSD([1.0, 2.0, 4.0], [1.0, 0.5, 0.1]))
    with pytest.raises(ValueError):
        tab.values[0] = 2.0


@pytest.mark.parametrize("bad", [-1e-6, np.nan])
def test_tau_maps_refuse_negative_or_nan(bad):
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.array([0.1, 1.0]))
    with pytest.raises(ValueError, match="V must be >= 0"):
        pr.tau_of_V(bad)
    with pytest.raises(ValueError, match="tau must be >= 0"):
        pr.V_of_tau_each(np.array([0.01, bad]))


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"B2": lambda p, z: -p}, "B2 must be finite and >= 0"),
        ({"B1": lambda p, z: np.nan * p}, "B1 must be finite"),
        ({"B2": lambda p, z: np.ones(3)}, "vectorised"),
        ({"B2": 3.0}, "B2 must be None or a callable"),
        ({"fudge": "YP08"}, "fudge must be None"),
    ],
)
def test_bad_coefficients(kw, match):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=64.0)
    with pytest.raises(ValueError, match=match):
        pf.FokkerPlanckProblem(psd, p_bar=0.02, **kw)


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"B2": lambda p, z: p + 1j}, r"B2 must be real: B2\(p = 0, zeta = 1\)"),
        ({"B1": lambda p, z: 1 / 0}, r"B1\(p, zeta\) could not be evaluated at p in \[0, .*ZeroDivisionError"),
        ({"B1": lambda p, z: np.ones((2, 3))}, "B1.*vectorised"),
        ({"B1": lambda p, z: "x"}, "B1.*real numbers"),
        ({"B2": lambda p, z: np.where(p > 0.1, np.inf, 1e-3)}, r"B2 must be finite and >= 0: B2\(p = 0.1"),
        ({"B2": lambda p, z: np.full(p.shape, -1e-3 if z > 50 else 1e-3)}, r"B2 must be .*zeta = (6|1)"),
    ],
)
def test_bad_coefficients_name_the_coefficient_and_where(kw, match):
    ref = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match=match):
        pf.FokkerPlanckProblem(ref.psd, p_bar=float(ref.p_bar[0]), **kw)


def test_load_above_the_modulus_warns_in_terms_of_p_over_E():
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 128.0)
    with pytest.warns(UserWarning, match=r"p_bar / E_star = 1e\+06 > 1.*same unit"):  # E* in GPa, p_bar in Pa
        pf.ContactProblem(psd, E_star=1.0, p_bar=1e6)
