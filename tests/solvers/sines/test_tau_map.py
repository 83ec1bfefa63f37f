"""The effective-variance map of the sine-series solver (``sines/taumap.py``) with a fudge factor: tau against an
independent ODE reference, its Newton iteration, its cost, and tiny loads summed through the image dual."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import persson_fp as pf
from persson_fp.solvers.sines import SineSeriesSolver, image_area, series_area
from persson_fp.solvers.sines import taumap as sines_taumap

ZETA_OUT = [1.5, 10.0, 128.0]


@pytest.mark.parametrize("fudge", ["YP08", "WM17"])
def test_tiny_loads_with_fudge_need_few_modes(fudge):
    """The tau map sums the series through its image dual below tau_N: no mode count ~ 1 / p_bar."""
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=np.array([1e-4, 1e-2, 3.0]))
    sol = pf.solve(pr, "sines")
    assert sol.info["n_modes"] < 2000  # was 1.4e6 for 1e-4 sqrt(V)
    err = sol.compare()
    assert err.max_L1 < 1e-10 and err.max_area_error < 1e-12


def _tau_reference(fudge, L, N, tol, p_bar, V_out):
    """tau(V_out) of dtau/dV = S(A_h(tau)) by DOP853, A_h = series_area (N modes) for tau >= max(tau_N, tau_sw),
    image_area (the infinite series) below.

    Started far below the solver's switch, at tau0 = min(p_bar, L - p_bar)^2 / 2000 (both walls >= 31 sigma away,
    A* = 1 to ~1e-200), so the solver's "tau = S(1) V below tau_sw" is checked, not assumed; the switch of A_h
    (a jump of up to tol) is an event, where the integration restarts.
    """
    tau_N = 2.0 * (np.log(2.0 / tol) + np.log(4.0)) * (L / (np.pi * (N + 1))) ** 2  # modes_needed's bound
    tau_switch = max(tau_N, p_bar**2 / 72.0)
    S1 = float(fudge.S(np.array(1.0)))
    tau0 = min(p_bar, L - p_bar) ** 2 / 2000.0
    V0, t0 = tau0 / S1, tau0
    out = S1 * np.asarray(V_out, dtype=float)
    todo = V_out > V0

    def rhs(area):
        return lambda V, y: [float(fudge.S(np.array(min(max(float(area(y[0])), 0.0), 1.0))))]

    opts = {"method": "DOP853", "rtol": 1e-13, "atol": 1e-300, "dense_output": True}

    def reach_switch(V, y):
        return y[0] - tau_switch

    reach_switch.terminal = True
    sol = solve_ivp(rhs(lambda t: image_area(L, p_bar, t)), (V0, V_out[-1]), [t0], events=reach_switch, **opts)
    now = todo & (V_out <= sol.t[-1])
    if now.any():
        out[now] = sol.sol(V_out[now])[0]
    todo &= V_out > sol.t[-1]
    V0, t0 = sol.t[-1], sol.y[0, -1]
    if todo.any():
        sol = solve_ivp(rhs(lambda t: series_area(L, p_bar, t, N)), (V0, V_out[-1]), [t0], **opts)
        out[todo] = sol.sol(V_out[todo])[0]
    return out


def _cubic(A):
    return 0.3 + 0.7 * A**3


@pytest.mark.filterwarnings("ignore:sines. P0 has negative values:RuntimeWarning")  # n_p=12: Gibbs
@pytest.mark.parametrize("fudge", ["YP08", "WM17", "Xu24", _cubic])
@pytest.mark.parametrize(
    "opts",
    [{}, {"n_p": 12, "check": False}, {"tol": 1e-6}, {"k_domain": 6.0}, {"k_domain": 5.0}],
    ids=[
        "default",
        "n_p=12",
        "tol=1e-6 (dropped-mode correction)",
        "k_domain=6 (far wall: direct rule)",
        "k_domain=5 (the smallest accepted)",
    ],
)
def test_tau_map_against_ode_reference(fudge, opts):
    """tau solves the series' own dtau/dV = S(A_h) for tiny to big loads and early to late stations.

    Tolerance 2e-13: the map is converged to rtol = 1e-14 (its quadratures are at round-off), while DOP853 at
    rtol = 1e-13 keeps each step's local error below 1e-13 tau, and over its few hundred steps (across 8 decades
    of V for the 1e-4 load) the global error stays of that order (observed <= 4e-14).
    """
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=[1e-4, 0.05, 0.5, 3.0])
    z = np.array([1.05, 1.5, 10.0, 128.0])  # 1.05: V below V_sw of the big load (tau = S(1) V)
    sol = pf.solve(pr, "sines", zeta_out=z, **opts)
    info = sol.info
    V = np.atleast_1d(pr.V(z)).astype(float)
    for j, pb in enumerate(pr.p_bar):
        ref = _tau_reference(pr.fudge, info["p_max"], info["n_modes"], opts.get("tol", 1e-13), pb, V)
        np.testing.assert_allclose(info["tau"][:, j], ref, rtol=2e-13, atol=0)
    assert info["tau_map_residual"] <= 1e-14
    # (with k_domain = 1 the wall takes area early: the continuum guess is further off, one more Newton step)
    assert 1 <= info["tau_map_iterations"] <= (6 if opts.get("k_domain", 10.0) < 2.0 else 3)
    assert info["tau_map_direct"] == ("k_domain" in opts)


@pytest.mark.parametrize("scale", [1.3, 0.8, np.nan])
def test_tau_map_guess_is_only_a_guess(monkeypatch, scale):
    """A poor (or NaN) continuum guess costs Newton steps, not accuracy."""
    pr = pf.ContactProblem.reference(fudge="WM17", p_bar_ratio=[1e-3, 0.5, 3.0])
    good = pf.solve(pr, "sines", zeta_out=ZETA_OUT)
    tau_map = SineSeriesSolver._tau_map
    monkeypatch.setattr(SineSeriesSolver, "_tau_map", lambda self, *a: tau_map(self, *a[:-1], scale * a[-1]))
    bad = pf.solve(pr, "sines", zeta_out=ZETA_OUT)
    assert bad.info["tau_map_iterations"] > good.info["tau_map_iterations"]
    np.testing.assert_allclose(bad.info["tau"], good.info["tau"], rtol=1e-14)
    assert bad.info["tau_map_residual"] <= 1e-14


def test_tau_map_reports_non_convergence(monkeypatch):
    monkeypatch.setattr(sines_taumap, "_MAX_NEWTON", 1)
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=0.3)
    with pytest.raises(RuntimeError, match="did not converge in 1 Newton steps"):
        pf.solve(pr, "sines", tol=1e-2)  # the loose truncation makes the first step's bound exceed rtol


def test_tau_map_is_cheap():
    """By default one evaluation of the load-free table (its partial-panel rule and both ends per station and
    load) and one Newton step: the dropped-mode correction is below rtol / 10 and left out."""
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.geomspace(0.01, 3.0, 7))
    sol = pf.solve(pr, "sines", zeta_out=ZETA_OUT)
    assert sol.info["tau_map_iterations"] == 1
    assert sol.info["tau_map_nodes"] == (sines_taumap._TABLE_Q + 2) * len(ZETA_OUT) * 7
