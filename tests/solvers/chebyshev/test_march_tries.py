"""The refinement loop of the general march (``method="chebyshev"`` on coefficients that do not separate): what each
try ran is reported (``info["march"]["tries"]``), and a refinement forecast over the time left is refused after the
try that forecast it, naming the forecast and a tol that fits.  Work (the tries run) is counted, not wall-clock time:
the clock the loop reads is advanced by a fixed amount per try."""

import re

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.chebyshev import solver as cs


def scene_b():
    """B2 = dV/dzeta (1 + p zeta / (zeta_max p_bar)): does not separate (the benchmark's scene B)."""
    pr = pf.ContactProblem.reference()
    psd, pb, zm = pr.psd, 0.5 * float(np.sqrt(pr.V_max)), float(pr.zeta_max)
    return pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1.0 + p * z / (zm * pb)))


def test_each_try_is_reported_with_what_it_ran():
    sol = pf.solve(scene_b(), "chebyshev", tol=1e-5)
    info = sol.info
    tries = info["march"]["tries"]
    assert info["path"] == "radau" and info["runs"] == 3 * len(tries) >= 3
    last = tries[-1]
    assert last["n_p"] == info["grid"]["n_p"] and last["V0_fraction"] == info["V0_fraction"]
    assert last["march_tol"] == info["march"]["tol"] and last["seconds"] > 0
    assert tries[0]["forecast_s"] is None  # (the first try has nothing to forecast from)
    quantities = ("L1", "elastic_area", "plastic_area", "noncontact_area")
    assert last["estimate"] == max(float(np.max(info["error_estimate"][q])) for q in quantities) <= 1e-5
    assert max(last["parts"].values()) <= last["estimate"]  # (the parts of the sum it reports)


def test_a_refinement_forecast_over_the_time_left_is_refused_after_the_try(monkeypatch):
    # tol 1e-8 on scene B takes two tries; each try is made to look 4 s long on the loop's clock (max_time 10 s):
    # the second is forecast at >= 4 s x (degree growth)^2 > the 6 s left, and refused before it runs
    clock = {"offset": 0.0}
    real = cs.time.perf_counter

    class FakeTime:
        @staticmethod
        def perf_counter():
            return real() + clock["offset"]

    three_runs = cs.ChebyshevSolver._three_runs
    calls = []

    def slow_three_runs(self, *args):
        out = three_runs(self, *args)
        calls.append(args[0])
        clock["offset"] += 4.0
        return out

    monkeypatch.setattr(cs, "time", FakeTime)
    monkeypatch.setattr(cs.ChebyshevSolver, "_three_runs", slow_three_runs)
    with pytest.raises(pf.SolverError, match=r"the next refinement \(degree \d+.*is forecast to take") as err:
        pf.solve(scene_b(), "chebyshev", tol=1e-8, max_time=10.0)
    msg = str(err.value)
    assert len(calls) == 1, msg  # (refused after the first try, before the second ran)
    assert "after 3 runs" in msg and "max_time" in msg
    reached = float(re.search(r"the error estimate is ([0-9.e+-]+)", msg).group(1))
    fits = float(re.search(r"a tol of about ([0-9.e+-]+) is forecast to fit", msg).group(1))
    assert 1.5e-8 <= fits <= 1.6 * reached and reached > 1e-8  # (printed to 2 digits; 1.5x at most)
    need = float(re.search(r"forecast to take ~([0-9.e+-]+) s", msg).group(1))
    left = float(re.search(r"over the ([0-9.e+-]+) s left", msg).group(1))
    assert need > left and need >= 4.0


@pytest.mark.parametrize(
    "n, grid, tol, expect", [(80, 1e-3, 3e-7, 157), (100, 1e-6, 3e-7, 120), (60, 1e-4, 3e-6, 99), (80, 1e-2, 3e-9, 160),
                             (100, 3e-7, 3e-7, 115)]
)  # fmt: skip
def test_the_first_degree_refinement_follows_the_assumed_rate(n, grid, tol, expect):
    # the grid part e^(-r n) brought to a third of tol at r = GRID_RATE_0: n + ln(grid / (tol / 3)) / r, between
    # 1.15x and 2x the degree (80 + ln(1e4) / 0.12 = 156.8 -> 157; 100 + ln(3) / 0.12 = 109.2 -> 1.15 x 100)
    solver = object.__new__(cs.ChebyshevSolver)
    assert cs.GRID_RATE_0 == 0.12  # (the rate the expected degrees above were worked out with)
    n_next, _, _ = solver._refine(n, 1e-3, tol, tol, grid, 0.0, 0.0)
    assert n_next == expect
