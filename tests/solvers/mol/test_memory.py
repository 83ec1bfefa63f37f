"""mol's memory: its model against the measured peak, the automatic grid within the budget for a thousand loads, and
max_memory kept on the front-fixed engine's path.  References: tracemalloc's peak, and the image solution."""

import tracemalloc

import numpy as np
import pytest
from scipy.special import erf

import persson_fp as pf
from persson_fp.solvers import get_solver

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, float(REF.p_bar[0])


@pytest.mark.slow
def test_mol_memory_estimate_within_2x_of_the_measured_peak():
    """The estimate (base.MEMORY_MODELS['mol']) against tracemalloc's peak, two shapes (before: ~40-340x over)."""
    from persson_fp.solvers.base import MEMORY_MODELS

    for pr, n_p in ((REF, 2000), (pf.ContactProblem.reference(p_bar_ratio=np.linspace(0.2, 2, 10)), 600)):
        solver = get_solver("mol")(pr, n_p=n_p)
        tracemalloc.start()
        solver.run()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        est = MEMORY_MODELS["mol"](solver.opts, pr.n_loads, 1, False)
        assert 0.5 <= est / peak <= 2.0, (est, peak)


def test_mol_does_not_refuse_a_thousand_loads():
    pr = pf.ContactProblem.reference(p_bar_ratio=np.linspace(0.2, 2.0, 1000), fudge="YP08")
    solver = get_solver("mol")(pr)
    p, _ = solver._grid()  # the automatic grid and its memory check (4 GiB default): no ValueError
    assert p.size > 100


@pytest.mark.parametrize(
    "problem",
    [
        lambda: pf.FokkerPlanckProblem(PSD, p_bar=PB),
        lambda: pf.ContactProblem(
            pf.SelfAffinePSD.from_rms_slope(4.0, H=0.8, q_l=1.0, q_r=1.0, q_s=10.0),
            p_bar=0.3,
            hardness=pf.hardness.PowerLaw(1.0, 0.2),
        ),
    ],
    ids=["general", "moving wall"],
)
def test_mol_engine_path_keeps_max_memory(problem):
    with pytest.raises(ValueError, match=r"mol: this run would need about .* more than max_memory"):
        pf.solve(problem(), method="mol", max_memory=1000)
    # a budget that suffices changes nothing: the same areas as without one
    sol = pf.solve(problem(), method="mol", max_memory=2**30)
    assert np.array_equal(sol.contact_area_all, pf.solve(problem(), method="mol").contact_area_all)
    if problem().general:  # B2 = dV/dzeta, no drift: the image solution A* = erf(p_bar / sqrt(2V)) (eq:Area_Persson)
        exact = erf(PB / np.sqrt(2.0 * REF.V_max))
        assert abs(float(sol.contact_area_all[-1, 0]) - exact) <= float(sol.error_estimate["contact_area"][-1, 0])
