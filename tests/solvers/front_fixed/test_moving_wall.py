"""The moving yield wall (scale-dependent hardness) on the front-fixed engine: no closed form, so orders of
convergence, conservation, the strip as its constant-hardness limit, fv against mol, and the error estimate against a
finer run."""

import numpy as np
import pytest

import persson_fp as pf

SIGMA = 1.5 * np.sqrt(0.0025)  # 1.5 sqrt(V(zeta_max)) of the reference problem


def _moving(fudge=None, p_bar=0.3):
    """sigma_Y = zeta^0.2, p_bar = 0.3 sigma_1, zeta to 10, rms slope 4: A_pl ~ 0.167 at zeta = 10."""
    psd = pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0)
    return pf.ContactProblem(psd, E_star=1.0, p_bar=p_bar, fudge=fudge, hardness=pf.hardness.PowerLaw(1.0, 0.2))


def _order(values):
    """Observed order from successive differences of a sequence refined by 2 each time (log2 ratio, fitted)."""
    d = np.abs(np.diff(values))
    return -np.polyfit(np.arange(d.size), np.log2(d), 1)[0]


@pytest.mark.slow
def test_moving_wall_is_second_order_in_p_and_in_zeta():
    """Front fixing keeps second order: with the start fixed and the other resolution fine, the differences
    of A_pl fall 4x per refinement (measured 4.05/4.01 in p, 4.0/4.0 in zeta), fitted order within 0.1 of 2."""
    from persson_fp.solvers.front_fixed.moving_wall import MovingWall

    pr = _moving()
    V = pr.V(np.array([10.0]))
    V0 = 1e-4 * float(V[0])
    space = [MovingWall(pr, n).solve(V, 3000, V0=V0)["plastic_area"][-1, 0] for n in (50, 100, 200, 400)]
    time_ = [MovingWall(pr, 200).solve(V, k, V0=V0)["plastic_area"][-1, 0] for k in (50, 100, 200, 400)]
    assert abs(_order(space) - 2.0) < 0.1
    assert abs(_order(time_) - 2.0) < 0.1


def test_moving_wall_conserves_area_and_load_and_reports_its_error():
    """Areas balance to round-off; the load balance F_el + sigma_Y A_pl = p_bar (which the scheme does not
    impose) to its discretisation error; the error estimate bounds the error against a 4x finer run."""
    pr = _moving(p_bar=np.array([0.1, 0.3]))
    sol = pf.solve(pr, method="fv", n_p=100, n_steps=100, zeta_out=[3.0, 10.0])
    ref = pf.solve(pr, method="fv", n_p=400, n_steps=400, zeta_out=[3.0, 10.0])
    # the areas from the cells and the wall mass against 1 - the mass absorbed at p = 0, accumulated apart
    assert np.max(np.abs(sol.contact_area - sol.contact_area_flux)) < 1e-12
    assert sol.info["area_residual"] < 1e-12
    assert sol.info["load_residual"] < 1e-5  # measured 5.5e-6 (2nd order: 1.5e-6 at 200 cells and steps)
    assert np.allclose(sol.load, pr.p_bar, rtol=1e-5)
    est = sol.info["error_estimate"]
    true = np.abs(sol.plastic_area - ref.plastic_area)
    assert np.all(true <= est["plastic_area"] + 1e-9)
    assert est["max_area"] < 1e-4  # measured 5.3e-5 (the zeta = 3 station of the lighter load)
    with pytest.raises(ValueError, match="no exact solution"):
        sol.compare()


def test_moving_wall_with_fudge_factor_and_tolerance(monkeypatch):
    from persson_fp.solvers import auto
    from persson_fp.solvers.fv import FiniteVolumeSolver

    pr = _moving(fudge="YP08")
    sol = pf.solve(pr, method="fv", n_p=100, n_steps=100)
    assert 0.0 < float(sol.plastic_area[-1]) < 0.3
    assert sol.info["error_estimate"]["max_area"] < 1e-4
    with pytest.raises(pf.SolverError, match="exceeds tol"):  # the solver's own check, given a resolution
        FiniteVolumeSolver(pr, n_p=20, n_steps=20, tol=1e-9).run()
    monkeypatch.setattr(auto, "MAX_REFINE", 0)  # pf.solve(tol=) refines first; without refinements it reports
    with pytest.raises(pf.SolverError, match="not met after 0 refinements"):
        pf.solve(pr, method="fv", n_p=20, n_steps=20, tol=1e-9)


def test_moving_wall_engine_reproduces_the_strip_for_a_constant_hardness():
    """The general engine with beta = 0 (a fixed yield wall) against the exact strip series: 2nd order
    (measured errors 4.9e-5, 1.3e-5, 3.3e-6 at n = n_steps = 100, 200, 400)."""
    from persson_fp.solvers.front_fixed.moving_wall import MovingWall

    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 1.0]), hardness=SIGMA)
    z = np.array([4.0, 32.0, 128.0])
    ex = pf.exact(pr, zeta=z)
    errs = []
    for n in (100, 200, 400):
        r = MovingWall(pr, n).solve(pr.V(z), n)
        errs.append(np.max(np.abs(r["plastic_area"] - ex.plastic_area)))
        assert np.allclose(r["elastic_area"] + r["plastic_area"] + r["noncontact_area"], 1.0, atol=1e-12)
    slope = -np.polyfit(np.log([100, 200, 400]), np.log(errs), 1)[0]
    assert abs(slope - 2.0) < 0.1 and errs[-1] < 5e-6


def test_moving_wall_refuses_an_unresolved_grid():
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, H=0.8, q_l=1.0, q_r=1.0, q_s=1e16)
    pr = pf.ContactProblem(psd, p_bar=0.3, hardness=pf.hardness.PowerLaw(1.0, 0.2))
    with pytest.raises(ValueError, match="raise n_p to"):
        pf.solve(pr, method="fv", n_p=50, zeta_out=np.geomspace(10, 1e16, 4))


def test_mol_moving_wall_agrees_with_fv():
    """Two methods, one physics: mol (BDF on the engine's fluxes) and fv (TR-BDF2) to within their own
    error estimates (measured difference 2e-7 in A_pl at 200 cells)."""
    pr = _moving(fudge="YP08", p_bar=np.array([0.1, 0.3]))
    a = pf.solve(pr, method="mol", rtol=1e-8, zeta_out=[3.0, 10.0])
    b = pf.solve(pr, method="fv", n_p=200, n_steps=400, zeta_out=[3.0, 10.0])
    bound = a.info["error_estimate"]["plastic_area"] + b.info["error_estimate"]["plastic_area"]
    assert np.all(np.abs(a.plastic_area - b.plastic_area) <= bound)
    assert np.max(np.abs(a.plastic_area - b.plastic_area)) < 1e-6
    assert a.info["area_residual"] < 1e-12
