"""fv on a moving yield wall (the front-fixed engine): its memory estimate against the measured peak, and the grids
the default budget used to refuse.  Reference: tracemalloc's peak of the whole run."""

import tracemalloc

import pytest

import persson_fp as pf
from persson_fp.solvers import get_solver


def _moving_wall():
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, E_star=1.0, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


def test_fine_grids_on_a_moving_wall_fit_the_default_budget():
    # 12 800 cells and steps were refused as 7.3 GiB (the fixed-wall march's trajectory model) where the
    # front-fixed engine keeps no trajectory: ~20 MB
    solver = get_solver("fv")(_moving_wall(), n_p=12800, n_steps=12800)
    solver.check_memory()  # (no ValueError)
    with pytest.raises(ValueError, match="max_memory"):
        get_solver("fv")(_moving_wall(), n_p=12800, n_steps=12800, max_memory=1e6).check_memory()


@pytest.mark.slow
def test_fv_moving_wall_memory_estimate_within_2x_of_the_measured_peak():
    from persson_fp.solvers.base import MEMORY_MODELS

    pr = _moving_wall()
    pf.solve(pr, "fv", n_p=100, n_steps=100)  # (first-call caches outside the measure)
    for n_p, n_steps in ((400, 400), (1600, 400), (400, 1600)):
        solver = get_solver("fv")(pr, n_p=n_p, n_steps=n_steps)
        tracemalloc.start()
        solver.run()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        o = dict(solver.opts, front_fixed=True)
        est = MEMORY_MODELS["fv"](o, pr.n_loads, 1, False)
        assert 0.5 <= est / peak <= 2.0, (n_p, n_steps, est, peak)
