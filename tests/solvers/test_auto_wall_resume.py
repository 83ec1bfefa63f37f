"""method="auto" on a moving wall at 3e-7 <= tol <= 1e-4: fv first under its work cap; where its next attempt would
exceed the cap, "chebyshev"; where that declines, fv resumes at the resolution the cap stopped it at.  The declines
are forced (a chebyshev budget of 1 ms; a clock that says chebyshev spent the caller's max_time), the work is
counted (the fv runs and their resolutions), the result checked against chebyshev at a tight tol."""

import time

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.results.invariants import SolverError
from persson_fp.solvers import auto
from persson_fp.solvers.registry import get_solver

ZETA = [8.0]
AREAS = ("elastic_area", "plastic_area", "noncontact_area")
TOL = 1e-4


def scene_w():
    """The moving-wall scene W (sigma_Y = 0.035 zeta^0.2, p_bar = 0.03, sqrt(V) = 0.05), stopped at zeta = 8: fv's
    first attempt (50 cells and steps) misses 1e-4, its next (258) is over the work cap auto puts on it."""
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


@pytest.fixture
def fv_runs(monkeypatch):
    """The (n_p, n_steps) of every fv run, in order."""
    runs = []
    cls = get_solver("fv")
    real = cls.run

    def counted(self, *args, **kwargs):
        runs.append((self.opts["n_p"], self.opts["n_steps"]))
        return real(self, *args, **kwargs)

    monkeypatch.setattr(cls, "run", counted)
    return runs


@pytest.fixture
def capped(monkeypatch):
    """The work-capped fv attempts (what the cap stopped, and the attempts before it), as auto saw them."""
    seen = {}
    real = auto.solve_to_tol

    def spy(*args, **kwargs):
        try:
            return real(*args, **kwargs)
        except auto._TooMuchWork as stop:
            seen.update(options=dict(stop.options), attempts=list(stop.attempts))
            raise

    monkeypatch.setattr(auto, "solve_to_tol", spy)
    return seen


def test_fv_resumes_where_the_work_cap_stopped_it_when_chebyshev_declines(monkeypatch, fv_runs, capped):
    monkeypatch.setattr(auto, "_CHEB_WALL_TIME", 1e-3)  # (chebyshev's attempt: 1 ms, which it cannot meet)
    sol = pf.solve(scene_w(), "auto", tol=TOL, zeta_out=ZETA)
    info = sol.info["auto"]
    assert info["method"] == "fv" and sol.method == "fv"
    assert "method 'chebyshev' declined: chebyshev: max_time = 0.001 s exceeded" in info["why"]
    assert "fv resumed" in info["why"]
    # resumed, not restarted: each resolution ran once, the first after the cap the one the cap stopped
    stopped = (capped["options"]["n_p"], capped["options"]["n_steps"])
    before = [(a["options"]["n_p"], a["options"]["n_steps"]) for a in capped["attempts"]]
    assert before and stopped[0] * stopped[1] > auto._FV_WALL_WORK
    assert fv_runs[: len(before)] == before and fv_runs[len(before)] == stopped
    assert len(set(fv_runs)) == len(fv_runs), fv_runs
    assert info["attempts"][0]["options"] == capped["options"]
    assert [a["options"] for a in info["fv_attempts"]] == [a["options"] for a in capped["attempts"]]
    # tol met, against chebyshev at 1e-6 (spectral in p, a Radau march in V: no part of fv's discretisation)
    ref = pf.solve(scene_w(), "chebyshev", tol=1e-6, zeta_out=ZETA, max_time=120.0)
    for q in AREAS:
        true = abs(float(np.ravel(getattr(sol, q))[-1]) - float(np.ravel(getattr(ref, q))[-1]))
        assert true <= TOL - float(np.max(ref.info["error_estimate"][q])), (q, true)
        assert true <= float(np.max(sol.info["error_estimate"][q])), (q, true)  # (its own estimate is honest too)


class _Clock:
    """A perf_counter for auto that chebyshev's attempt can advance (the rest of the library keeps the real one)."""

    def __init__(self):
        self.offset = 0.0

    def perf_counter(self):
        return time.perf_counter() + self.offset


def test_a_max_time_spent_by_chebyshev_is_refused_naming_both_causes(monkeypatch, fv_runs, capped):
    clock, given = _Clock(), {}
    monkeypatch.setattr(auto, "time", clock)

    def spends_it_all(problem, zeta_out, tol, budget):  # declines after (the clock says) all but 1 ms of its budget
        given.update(budget)
        clock.offset += budget["max_time"] - 1e-3
        raise SolverError("chebyshev: forced decline after its budget")

    monkeypatch.setattr(auto, "_solve_chebyshev", spends_it_all)
    max_time = 15.0
    with pytest.raises(SolverError) as err:
        pf.solve(scene_w(), "auto", tol=TOL, zeta_out=ZETA, max_time=max_time)
    msg = str(err.value)
    assert f"not met within max_time = {max_time:g} s" in msg
    assert "the chebyshev attempt took" in msg and "declined (chebyshev: forced decline after its budget)" in msg
    assert "fv then ran out of the rest" in msg and "work-capped attempt(s)" in msg
    # chebyshev was given what fv's capped attempts left of max_time, and fv ran nothing after it (the 1 ms left is
    # below its forecast of the resumed attempt, 9 ms)
    spent = sum(a["wall_time"] for a in capped["attempts"])
    assert given["max_time"] <= max_time - spent
    assert len(fv_runs) == len(capped["attempts"]), fv_runs
