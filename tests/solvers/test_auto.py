"""method="auto" and tol=: the choice, and the tolerance met (true error where a closed form exists)."""

import numpy as np
import pytest

import persson_fp as pf


def _moving():
    psd = pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0)
    return pf.ContactProblem(psd, p_bar=0.3, hardness=pf.hardness.PowerLaw(1.0, 0.2))


def _general():
    ref = pf.ContactProblem.reference()
    dV = lambda z: float(ref.psd.dV_dzeta(z))  # noqa: E731
    return pf.FokkerPlanckProblem(
        ref.psd, p_bar=0.025, B1=lambda p, z: -0.1 * p * dV(z), B2=lambda p, z: (1 + p / 0.05) * dV(z)
    )


SCENES = {
    "A* only": (lambda: pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 1.0])), "sines"),
    "P0 with a fudge factor": (lambda: pf.ContactProblem.reference(fudge="YP08"), "sines"),
    "constant hardness": (lambda: pf.ContactProblem.reference(hardness=0.075, fudge="YP08"), "sines"),
    "moving hardness": (_moving, "fv"),
    "general coefficients": (_general, "chebyshev"),  # B2, B1 = functions of p x dV/dzeta: the spectral engine
}


@pytest.mark.parametrize("scene", list(SCENES))
def test_auto_choice_and_tolerance(scene):
    make, expected = SCENES[scene]
    pr = make()
    tol = 1e-3 if scene == "general coefficients" else 1e-6  # (the general path is second order: see the note)
    sol = pf.solve(pr, method="auto", tol=tol)
    a = sol.info["auto"]
    assert a["method"] == expected and a["why"]
    est = sol.error_estimate
    assert np.max(est["L1"]) <= tol and np.max(est["contact_area"]) <= tol
    if pr.has_closed_form:  # the true error, not an estimate
        assert est["kind"].startswith("true error")
        c = sol.compare()
        assert c.max_L1 <= tol and c.max_area_error <= tol
    else:
        assert est["kind"].startswith("estimate")
        # auto's own record names the estimate the method formed (chebyshev's partners are not "half resolution")
        assert a["kind"] == "estimate (" + sol.info["error_estimate"]["method"] + ")"


def test_auto_moving_wall_true_error_below_tol():
    """The moving wall's estimate is honest: against a 4x finer extrapolated run the error is below tol."""
    pr = _moving()
    sol = pf.solve(pr, method="auto", tol=1e-5)
    fine = pf.solve(pr, method="fv", n_p=800, n_steps=800)
    half = pf.solve(pr, method="fv", n_p=400, n_steps=400)
    ref = fine.plastic_area + (fine.plastic_area - half.plastic_area) / 3
    assert abs(float(sol.plastic_area[-1] - ref[-1])) <= 1e-5


@pytest.mark.parametrize("method", ["fv", "mol"])
def test_tol_chooses_the_resolution_of_a_named_method(method):
    pr = pf.ContactProblem.reference(fudge="YP08")
    for tol in (1e-4, 1e-6):
        sol = pf.solve(pr, method=method, tol=tol)
        c = sol.compare()
        assert c.max_L1 <= tol and c.max_area_error <= tol
        assert sol.info["auto"]["method"] == method


def test_error_estimate_on_every_solution():
    sol = pf.solve(pf.ContactProblem.reference(), method="fv")
    est = sol.error_estimate
    assert est["L1"].shape == (1, 1) and est["kind"].startswith("true error")
    mc = pf.solve(pf.ContactProblem.reference(), method="monte-carlo", n_walkers=2000, seed=1)
    assert "stderr_area" in mc.error_estimate


def test_auto_refuses_knobs_and_bad_tol():
    pr = pf.ContactProblem.reference()
    with pytest.raises(TypeError, match="chooses the resolution itself"):
        pf.solve(pr, method="auto", n_p=10)
    with pytest.raises(ValueError, match="tol must lie in"):
        pf.solve(pr, method="auto", tol=0.0)


def test_unreachable_tol_raises(monkeypatch):
    from persson_fp.solvers import auto

    monkeypatch.setattr(auto, "MAX_REFINE", 0)
    with pytest.raises(pf.SolverError, match="not met after"):
        pf.solve(_general(), method="fv", tol=1e-9, n_p=40, n_steps=20)
    monkeypatch.setattr(auto, "MAX_REFINE", 4)
    monkeypatch.setattr(auto, "MAX_CELLS", 100)
    with pytest.raises(pf.SolverError, match="would need more than 100"):
        pf.solve(_general(), method="fv", tol=1e-9, n_p=40, n_steps=20)


def test_auto_picks_a_resolution_the_engine_accepts():
    """The moving-wall scene W: the engine demands n_p >= 53; auto's first attempt must be above that
    (before: n_p = 50 and a ValueError)."""
    from persson_fp.solvers.auto import _first_options
    from persson_fp.solvers.front_fixed.moving_wall import min_cells

    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    pr = pf.ContactProblem(psd, p_bar=0.3, hardness=pf.hardness.PowerLaw(sigma_1=1.0, n=0.2))
    need = min_cells(pr, np.array([pr.V_max]))
    assert need == 53
    for tol in (1e-3, 1e-4, 1e-5):
        for method in ("fv", "mol"):
            assert _first_options(pr, method, tol)["n_p"] >= need
