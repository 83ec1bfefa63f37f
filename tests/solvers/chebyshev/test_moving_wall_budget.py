"""method="chebyshev" on the moving-wall scene W (sigma_Y = 0.035 zeta^0.2, p_bar = 0.03, a spectrum with its
roll-off at zeta = 2): the Radau march stops at the roll-off's kink (where d sigma_Y / dV jumps), forecasts its cost
and either returns a result within tol -- checked against fv's Richardson-extrapolated areas -- or is refused at once,
naming the forecast (no wall-clock assertion: the refusal is asked for by a budget far below the solve's cost)."""

import numpy as np
import pytest

import persson_fp as pf


def cheaper_scene():
    """The moving-wall scene W; the tests stop at zeta = 8 (the kink at 2 inside the span)."""
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


ZETA = [8.0]
AREAS = ("elastic_area", "plastic_area", "noncontact_area")


def _areas(sol):
    return {q: float(np.ravel(getattr(sol, q))[-1]) for q in AREAS}


@pytest.fixture(scope="module")
def fv_ref():
    """fv at 400 and 800 cells and steps, Richardson-extrapolated (second order: the 200 -> 400 -> 800 differences of
    A_pl fall 3.5x and 3.8x, measured), uncertainty |extrapolated - finer|."""
    coarse, fine = (_areas(pf.solve(cheaper_scene(), "fv", n_p=n, n_steps=n, zeta_out=ZETA)) for n in (400, 800))
    ref = {q: fine[q] + (fine[q] - coarse[q]) / 3.0 for q in AREAS}
    unc = {q: abs(fine[q] - coarse[q]) / 3.0 for q in AREAS}
    return ref, unc


def test_the_march_stops_at_the_kink_and_meets_tol(fv_ref):
    ref, unc = fv_ref
    tol = 1e-5
    sol = pf.solve(cheaper_scene(), "chebyshev", tol=tol, zeta_out=ZETA)
    assert sol.info["path"] == "moving-wall"
    est = sol.info["error_estimate"]
    got = _areas(sol)
    for q in AREAS:
        true = abs(got[q] - ref[q])
        assert true <= tol + unc[q], (q, true, unc[q])
        assert true <= float(np.max(est[q])) + unc[q], (q, true, float(np.max(est[q])))
    # no step straddles the kink: the march takes a step ending on V(zeta = 2) (the operator jumps there) -- its
    # replayed steps, the partners' nodes, are not exposed, so the check is the march's own step count staying
    # small where, straddling it, the step control had crawled towards the kink in ever smaller steps
    assert sol.info["march"]["rejected"] <= 0.2 * sol.info["march"]["steps"]


def test_the_radau_pieces_meet_at_the_kink():
    """The march's break points: V(zeta_r) of the roll-off, strictly inside the span, nowhere else."""
    from persson_fp.solvers.chebyshev.wall import _Wall

    pr = cheaper_scene()
    wall = _Wall(pr)
    Vk = float(pr.V(2.0))
    assert wall.breaks(1e-3 * Vk, 10.0 * Vk) == [pytest.approx(Vk, rel=1e-14)]
    assert wall.breaks(1.001 * Vk, 10.0 * Vk) == [] and wall.breaks(1e-3 * Vk, 0.999 * Vk) == []
    # d beta / dV jumps there: the one-sided limits of the wall's third entry differ, while s and s_V are continuous
    left, right = wall.many([Vk * (1.0 - 1e-12)])[0], wall.many([Vk * (1.0 + 1e-12)])[0]
    np.testing.assert_allclose(left[:2], right[:2], rtol=1e-9)
    assert abs(left[2] - right[2]) > 1e3 * abs(right[2])


def test_a_solve_forecast_over_its_budget_is_refused_naming_the_forecast():
    # tol = 1e-9 needs several times the 0.5 s given; the march forecasts its cost a tenth of the way in ln V and
    # refuses (1e-10 is refused before any march: below the round-off floor where the refinement would end)
    # (a refusal by the deadline instead would say "exceeded", not "forecast")
    pr = cheaper_scene()
    with pytest.raises(pf.SolverError, match=r"forecast to (need|take).*max_time = 0.5 s") as err:
        pf.solve(pr, "chebyshev", tol=1e-9, zeta_out=ZETA, max_time=0.5)
    assert "exceeded" not in str(err.value) and "use method='fv'" in str(err.value)


def test_the_default_budget_is_named_when_no_max_time_is_given(monkeypatch):
    """Without max_time the march is held to the path's default budget (MARCH_TIME_BUDGET; here lowered to 0.5 s, far
    below what tol = 1e-9 needs), named in the refusal with a tol that would fit."""
    from persson_fp.solvers.chebyshev import solver

    monkeypatch.setattr(solver, "MARCH_TIME_BUDGET", 0.5)
    with pytest.raises(pf.SolverError, match=r"default budget of this path, 0.5 s.*a tol of about") as err:
        pf.solve(cheaper_scene(), "chebyshev", tol=1e-9, zeta_out=ZETA)
    fits = float(str(err.value).split("a tol of about ")[1].split()[0])
    assert 1e-9 < fits <= 0.1


def test_auto_goes_to_chebyshev_where_fv_would_need_too_many_cells(fv_ref):
    """auto at 1e-5 on this wall: fv first, whose next attempt would exceed the work cap (n_p x n_steps), then
    chebyshev -- whose result meets tol against the reference; on a wall far from the load fv meets it alone."""
    from persson_fp.solvers import auto

    ref, unc = fv_ref
    sol = pf.solve(cheaper_scene(), "auto", tol=1e-5, zeta_out=ZETA)
    info = sol.info["auto"]
    assert info["method"] == "chebyshev"
    assert f"> {auto._FV_WALL_WORK:.3g}" in info["why"] and len(info["fv_attempts"]) >= 1
    got = _areas(sol)
    for q in AREAS:
        assert abs(got[q] - ref[q]) <= 1e-5 + unc[q], q
    psd = pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0)  # (benchmarks/plasticity.py, B)
    far = pf.ContactProblem(psd, p_bar=0.3, hardness=pf.hardness.PowerLaw(1.0, 0.2))
    assert pf.solve(far, "auto", tol=1e-5).info["auto"]["method"] == "fv"
