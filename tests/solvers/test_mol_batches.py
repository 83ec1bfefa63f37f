"""mol on batches of loads: chunked large batches agree with the exact solution and with the one-piece solve."""

from __future__ import annotations

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.mol import solver as mol


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
