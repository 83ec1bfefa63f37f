"""mol on batches of loads: each load of a batch as if solved alone, and chunked large batches agree with the exact
solution and with the one-piece solve."""

from __future__ import annotations

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.mol import solver as mol


def _single_like_batch(pr_batch, j, sol_batch, **opts):
    """Single-load run on the batch's grid and with the batch's start-up tau0."""
    pb = pr_batch.p_bar[j]
    single = pr_batch.with_loads(pb)
    tau_max = float(single.tau(single.zeta_max)[0])
    k = (sol_batch.p[-1] - pb) / np.sqrt(tau_max)
    tau0 = sol_batch.info["t_span"][0]
    return pf.solve(single, "mol", k_domain=k, tau0_fraction=tau0 / tau_max, **opts)


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_batched_loads_equal_single_loads(fudge):
    ratios = np.geomspace(0.01, 3.0, 4)
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=ratios)
    opts = {"n_p": 81, "rtol": 1e-10, "zeta_out": [20.0, 128.0]}
    batch = pf.solve(pr, "mol", **opts)
    for j in range(pr.n_loads):
        single = _single_like_batch(pr, j, batch, **opts)
        np.testing.assert_allclose(single.p, batch.p, rtol=1e-13)
        np.testing.assert_allclose(batch.P0[:, j], single.P0, rtol=0, atol=1e-7 * single.P0.max())
        np.testing.assert_allclose(batch.contact_area[:, j], single.contact_area, atol=1e-8)


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_chunked_batch_matches_exact_and_unchunked(monkeypatch, fudge):
    base = pf.ContactProblem.reference()
    sv = np.sqrt(base.V_max)
    pr = pf.ContactProblem(base.psd, 1.0, np.array([0.02, 0.3, 0.9, 2.0, 0.5]) * sv, fudge=fudge)
    opts = dict(zeta_out=[8.0, 128.0], n_p=120, rtol=1e-7)
    whole = pf.solve(pr, "mol", **opts)
    monkeypatch.setattr(mol, "_LOADS_PER_CHUNK", 2)
    chunked = pf.solve(pr, "mol", **opts)
    assert chunked.info["chunks"] == 3 and "chunks" not in whole.info
    assert chunked.P0.shape == whole.P0.shape and np.array_equal(chunked.p, whole.p)
    # against the closed form: 120 nodes over p_max = 2 sqrt(V) + 10 sqrt(tau) leave the space error of the
    # smallest load's narrow peak, L1 ~ 2e-4 (measured on the one-piece run, which is the yardstick: a factor
    # 3 for the chunks' own step sequences); 1e-3 bounds both
    err_c, err_w = chunked.compare(), whole.compare()
    assert err_c.max_L1 <= 3 * err_w.max_L1 + 1e-9 and err_c.max_L1 < 1e-3
    assert chunked.info["zeta0"].shape == (5,)
    np.testing.assert_allclose(chunked.contact_area, whole.contact_area, rtol=1e-5)
