"""The memory estimates that refuse a run (``max_memory``) against tracemalloc's peak of the whole call.

Reference: ``tracemalloc``'s peak over ``pf.solve`` (numpy reports its array buffers to it).  The target of every
estimate is 1 <= estimate / peak <= 2: below the peak a run may exhaust the machine, far above it a run that fits is
refused.  The benchmark ``benchmarks/memory_estimates.py`` measures the same over larger grids.
"""

from __future__ import annotations

import csv
import os
import sys
import tracemalloc
import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers import get_solver
from persson_fp.solvers.chebyshev.budget import degree_memory

BENCH = os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "benchmarks")


def _moving_wall():  # (scene W of the benchmarks)
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


def _separable():  # (scene S: B2 = dV/dzeta (1 + p / (2 p_bar)), the exponential path)
    pr = pf.ContactProblem.reference()
    psd, pb = pr.psd, float(pr.p_bar[0])
    return pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + p / (2 * pb)))


def _nonseparable():  # (scene A: B2 = dV/dzeta (1 + 0.2 (p / p_bar) ln zeta), the general march)
    pr = pf.ContactProblem.reference()
    psd, pb = pr.psd, float(pr.p_bar[0])
    return pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + 0.2 * (p / pb) * np.log(z)))


def _peak(pr, method, **opts) -> float:
    """tracemalloc's peak (bytes) of the whole call, after an untraced call of the same (first-use costs apart)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pf.solve(pr, method, **opts)
        tracemalloc.start()
        try:
            pf.solve(pr, method, **opts)
            return float(tracemalloc.get_traced_memory()[1])
        finally:
            tracemalloc.stop()


@pytest.mark.parametrize(
    "name, problem, method, opts",
    [
        ("fv, reference (trajectory kept)", pf.ContactProblem.reference, "fv", {"n_p": 400, "n_steps": 400}),
        ("fv, moving wall (front-fixed)", _moving_wall, "fv", {"n_p": 3200, "n_steps": 400}),
        ("chebyshev, exponential path", _separable, "chebyshev", {"n_p": 60}),
    ],
)
def test_estimate_within_1x_to_2x_of_the_traced_peak(name, problem, method, opts):
    pr = problem()
    if method == "chebyshev":  # (the degree is n_p when it is fixed)
        est = degree_memory(opts["n_p"], pr.n_loads, get_solver(method)(pr, **opts).path)
    else:
        est = get_solver(method)(pr, **opts).memory_estimate()
    peak = _peak(pr, method, **opts)
    assert 1.0 <= est / peak <= 2.0, (name, est, peak)


@pytest.mark.slow
def test_quick_benchmark_every_estimate_within_1x_to_2x(tmp_path):
    sys.path.insert(0, BENCH)
    try:
        import memory_estimates
    finally:
        sys.path.remove(BENCH)
    memory_estimates.main(["--quick", "--output", str(tmp_path)])
    with open(tmp_path / "memory_estimates.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert {r["group"] for r in rows} == set(memory_estimates.GROUPS)
    for r in rows:
        assert 1.0 <= float(r["ratio"]) <= 2.0, r


@pytest.mark.parametrize(
    "problem, method, opts",
    [
        (_moving_wall, "fv", {"n_p": 12800, "n_steps": 12800}),
        (_moving_wall, "chebyshev", {"n_p": 200}),
        (_nonseparable, "chebyshev", {"n_p": 200}),
    ],
)
def test_a_run_over_max_memory_is_refused_naming_it(problem, method, opts):
    # the estimates above 1 MB: refused before the run (no march started: fast)
    with pytest.raises(ValueError, match="max_memory"):
        pf.solve(problem(), method, max_memory=1e6, **opts)
