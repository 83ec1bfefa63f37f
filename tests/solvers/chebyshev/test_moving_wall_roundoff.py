"""method="chebyshev" on a moving wall refuses a tol below the round-off floor of its stiff collocated operator before
any march: the floor is computed from the operators alone (the grids and the operator at the ends of each station's
span), the same quantity each pass adds to every part of its error estimate, so a pass whose floor exceeds tol cannot
meet it.  Work, not wall-clock time, is what the tests count (the marches run)."""

import re

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.results.invariants import SolverError
from persson_fp.solvers.chebyshev import wall as cw


def scene_w():
    """The moving-wall scene W: sqrt(V) = 0.05, p_bar = 0.03, sigma_Y = 0.035 zeta^0.2 to zeta = 128."""
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


def nearly_constant_wall():
    """sigma_Y = zeta^1e-12 to zeta = 10, p_bar = 0.3: the wall moves by < 3e-12 sigma_1, so the areas are the exact
    strip's at sigma_Y = 1 to ~1e-11 (dA / dsigma ~ 1 / sigma)."""
    psd = pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0)
    return pf.ContactProblem(psd, p_bar=0.3, hardness=pf.hardness.PowerLaw(1.0, 1e-12))


@pytest.fixture
def marches(monkeypatch):
    """Counts the marches the moving-wall path runs (Radau and exponential alike)."""
    calls = []
    for name in ("radau_march", "magnus_march"):
        real = getattr(cw, name)

        def counted(*args, _real=real, **kwargs):
            calls.append(1)
            return _real(*args, **kwargs)

        monkeypatch.setattr(cw, name, counted)
    return calls


def _named(message: str, what: str) -> float:
    return float(re.search(what + r" ([0-9.e+-]+)", message).group(1))


@pytest.mark.parametrize("tol", [1e-12, 1e-10])
def test_a_tol_below_the_floor_is_refused_before_any_march(marches, tol):
    # (tol 1e-10 and 1e-12 had run two and one passes of three marches, ~5 s, before their refusals)
    with pytest.raises(SolverError, match=rf"tol = {tol:.3g} is below the round-off floor") as err:
        pf.solve(scene_w(), "chebyshev", tol=tol)
    msg = str(err.value)
    assert not marches, msg
    floor, degree = _named(msg, "operator:"), int(_named(msg, "at degree"))
    reach = _named(msg, "accuracy is about")
    assert tol < floor < reach and 24 <= degree <= cw.N_MAX_WALL, msg


def test_the_floor_forecast_is_the_floor_a_pass_reports():
    # the forecast is the "roundoff" part of the estimate of a pass at that degree and start (fixed n_p: one pass)
    pr, zeta_out = scene_w(), [8.0, 128.0]
    sol = pf.solve(pr, "chebyshev", n_p=40, tol=1e-3, zeta_out=zeta_out)
    reported = float(np.max(sol.info["error_estimate"]["parts"]["roundoff"]))
    V_out = np.asarray(pr.V(np.array(zeta_out)), dtype=float)
    forecast = cw._floor_at(pr, V_out, cw._Wall(pr), 40, sol.info["V0_fraction"])
    assert forecast == pytest.approx(reported, rel=1e-12)


def test_the_floor_grows_along_the_refinement_loop():
    # what the refusal relies on: each refinement raises the degree 1.3x, or lowers the start fraction 4x with the
    # degree 1.15x (a narrower start alone can lower the floor: the walls' nodes spread), and either raises the floor
    pr = scene_w()
    V_out = np.asarray(pr.V(np.array([2.0, 128.0])), dtype=float)
    wall = cw._Wall(pr)
    for n in (24, 60, 120):
        for frac in (1e-2, 1e-4, 1e-6):
            f0 = cw._floor_at(pr, V_out, wall, n, frac)
            assert cw._floor_at(pr, V_out, wall, int(np.ceil(1.3 * n)), frac) > f0, (n, frac)
            assert cw._floor_at(pr, V_out, wall, int(np.ceil(1.15 * n)), frac / 4.0) > f0, (n, frac)


@pytest.mark.slow
def test_the_named_accuracy_is_met_against_the_strip(marches):
    """The refusal's reachable tol is met, against the exact strip (the wall barely moves)."""
    pr = nearly_constant_wall()
    with pytest.raises(SolverError, match="round-off floor") as err:
        pf.solve(pr, "chebyshev", tol=1e-12)
    assert not marches
    reach = _named(str(err.value), "accuracy is about")
    sol = pf.solve(pr, "chebyshev", tol=reach, max_time=120.0)
    ex = pf.exact(pf.ContactProblem(pr.psd, p_bar=0.3, hardness=1.0))
    for q in ("elastic_area", "plastic_area", "noncontact_area"):
        true = abs(float(np.ravel(getattr(sol, q))[-1]) - float(np.ravel(getattr(ex, q))[-1]))
        assert true <= reach, (q, true, reach)
        assert true <= float(np.max(sol.info["error_estimate"][q])) + 1e-11, q


def test_a_tol_between_the_first_and_the_last_degree_floors_is_refused_before_any_march(marches):
    # tol 5e-10 on scene W: above the floor at the first degree, below the floor at the degree the loop ends at near
    # the floor (1.3x the first); it ran a pass of three marches (~2.5 s) before its refusal
    pr, tol = scene_w(), 5e-10
    V_out = np.asarray(pr.V(np.array([float(pr.zeta_max)])), dtype=float)
    n1, frac = cw._start_of(pr, V_out, tol, {"V0_fraction": None, "n_p": None})
    assert cw._floor_at(pr, V_out, cw._Wall(pr), n1, frac) < tol
    with pytest.raises(SolverError, match="below the round-off floor") as err:
        pf.solve(pr, "chebyshev", tol=tol)
    msg = str(err.value)
    assert not marches, msg
    assert int(_named(msg, "at degree")) == int(np.ceil(1.3 * n1)) and _named(msg, "operator:") > tol, msg
    assert f"a fixed n_p = {n1} runs anyway" in msg
