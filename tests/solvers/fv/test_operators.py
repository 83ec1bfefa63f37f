"""The finite-volume operators of method "fv" (``fv/operators.py``, ``fv/dst.py``): the banded matrix against the
readable right-hand side, conservation up to the wall fluxes, the compact mass matrix, and the DST-II basis that
diagonalises both."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import fft

from persson_fp.solvers.fv import apply_mass, apply_operator, banded_operator, dst_eigenvalues, rhs
from persson_fp.solvers.fv.operators import SPACES


def test_banded_matrix_equals_readable_rhs():
    rng = np.random.default_rng(1)
    n, dp = 17, 0.3
    P = rng.standard_normal((3, n))
    ab = banded_operator(n, dp)
    dense = np.diag(ab[1]) + np.diag(ab[0, 1:], 1) + np.diag(ab[2, :-1], -1)
    np.testing.assert_allclose(P @ dense.T, rhs(P, dp), rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(apply_operator(P, 0.5 / dp**2), rhs(P, dp), rtol=1e-13, atol=1e-12)


def test_flux_form_conserves_up_to_wall_fluxes():
    rng = np.random.default_rng(2)
    P = rng.random((2, 30))
    dp = 0.1
    # sum of flux differences = minus the outflow at both walls (P_0 + P_-1) / dp
    np.testing.assert_allclose(rhs(P, dp).sum(axis=-1) * dp, -(P[:, 0] + P[:, -1]) / dp, rtol=1e-12)


def test_compact_mass_matrix_rows():
    P = np.eye(6)
    M = apply_mass(P, "compact4")  # rows of M^T = columns of M (M symmetric)
    np.testing.assert_allclose(M, M.T)
    np.testing.assert_allclose(M[2, 1:4], [1 / 12, 10 / 12, 1 / 12])
    np.testing.assert_allclose(M[0, :2], [9 / 12, 1 / 12])
    np.testing.assert_array_equal(apply_mass(P, "fv2"), P)
    assert set(SPACES) == {"fv2", "compact4"}


@pytest.mark.parametrize("space", ["fv2", "compact4"])
@pytest.mark.parametrize("n", [4, 7, 64])
def test_dst_diagonalises_L_and_M_exactly(space, n):
    dp = 0.37
    ab = banded_operator(n, dp)
    L = np.diag(ab[1]) + np.diag(ab[0, 1:], 1) + np.diag(ab[2, :-1], -1)
    M = apply_mass(np.eye(n), space)
    S = fft.dst(np.eye(n), type=2, norm="ortho", axis=0)  # S @ x == dst(x)
    np.testing.assert_allclose(S @ S.T, np.eye(n), atol=1e-14)
    mu, m = dst_eigenvalues(n, dp, space)
    j = np.arange(1, n + 1)
    np.testing.assert_allclose(mu, -(2.0 / dp**2) * np.sin(np.pi * j / (2 * n)) ** 2, rtol=1e-14)
    np.testing.assert_allclose(S @ L @ S.T, np.diag(mu), atol=1e-14 * np.max(np.abs(mu)))
    np.testing.assert_allclose(S @ M @ S.T, np.diag(m), atol=1e-14)
