"""BLAS threads during a solve (``solvers/_threads.py``): one by default, the pool restored afterwards, the option
validated."""

from __future__ import annotations

import numpy as np
import pytest

import persson_fp as pf


def _problem(fudge, hardness, loads):
    base = pf.ContactProblem.reference()
    sv = np.sqrt(base.V_max)
    hard = None if hardness is None else hardness * sv
    return pf.ContactProblem(base.psd, 1.0, np.asarray(loads) * sv, fudge=fudge, hardness=hard)


def test_solve_runs_with_one_blas_thread_and_restores_the_pool():
    threadpoolctl = pytest.importorskip("threadpoolctl")
    from persson_fp.solvers.sines import SineSeriesSolver

    seen = []

    class Recording(SineSeriesSolver):
        def _solve(self):
            seen.append(max(i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"))
            return super()._solve()

    def blas():
        return [i["num_threads"] for i in threadpoolctl.threadpool_info() if i["user_api"] == "blas"]

    before = blas()
    pr = _problem("YP08", None, [0.2, 0.9])
    a = pf.solve(pr, Recording).contact_area
    b = pf.solve(pr, Recording, blas_threads=None).contact_area
    assert seen[0] == 1 and seen[1] == max(before, default=1)
    assert blas() == before
    # the thread count changes only the summation order: the same areas to round-off
    np.testing.assert_allclose(a, b, rtol=1e-13)
    # and both the exact ones (sines' default: modes for 1e-13)
    np.testing.assert_allclose(a[-1], pf.exact(pr).contact_area, rtol=1e-9)


@pytest.mark.parametrize("bad", [0, -1, 1.5, "1", True])
def test_blas_threads_is_validated(bad):
    with pytest.raises(ValueError, match="blas_threads"):
        pf.solve(_problem(None, None, 0.5), "sines", blas_threads=bad)
