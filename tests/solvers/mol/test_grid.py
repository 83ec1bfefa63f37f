"""The grid of the method-of-lines solver (``mol/grid.py``): its Laplacians, quadrature weights and Jacobian against
readable forms, exact polynomials and finite differences."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.solvers.mol import MethodOfLinesSolver, laplacian, laplacian_readable, quadrature_weights


def _fit_order(n_p, errs):
    return -np.polyfit(np.log(np.asarray(n_p) - 1.0), np.log(errs), 1)[0]


def test_laplacian_fast_equals_readable_and_is_exact_for_odd_polynomials(rng):
    for order in (2, 4):
        m, h = 17, 0.3
        P = rng.standard_normal((3, m))
        np.testing.assert_allclose(
            (laplacian(m, h, order) @ P.T).T, laplacian_readable(P, h, order), rtol=1e-13, atol=1e-10
        )
    # odd quintic about p = 0: the 4th-order stencil with odd ghosts is exact next to the wall
    h = 0.1
    p = h * np.arange(1, 9)
    f = p**5 - 3 * p**3 + p
    d2 = laplacian_readable(f[None, :], h, 4)[0]
    np.testing.assert_allclose(d2[:4], 20 * p[:4] ** 3 - 18 * p[:4], atol=1e-9)


def test_gregory_weights_fourth_order():
    errs = []
    n_p = [21, 41, 81]
    for n in n_p:
        p = np.linspace(0.0, 2.0, n)
        errs.append(abs(quadrature_weights(n, p[1], 4) @ np.sin(p) - (1 - np.cos(2.0))))
    assert _fit_order(n_p, errs) > 3.7


@pytest.mark.parametrize(("variable", "fudge"), [("tau", "YP08"), ("zeta", "YP08"), ("zeta", None), ("tau", None)])
def test_jacobian_equals_finite_differences(variable, fudge):
    pr = pf.ContactProblem.reference(fudge=fudge, p_bar_ratio=[0.3, 1.0])
    sysm = MethodOfLinesSolver(pr, n_p=24, variable=variable).system()
    t = sysm.t0 * 1.3
    y = sysm.y0 * (1.0 + 0.1 * np.sin(np.arange(sysm.y0.size)))
    f0 = sysm.fun_readable(t, y)
    np.testing.assert_allclose(sysm.fun(t, y), f0, rtol=1e-12, atol=1e-12 * np.max(np.abs(f0)))
    J = sysm.jac(t, y) if callable(sysm.jac) else sysm.jac
    J = J.toarray()
    Jfd = np.empty_like(J)
    for k in range(y.size):
        e = np.zeros_like(y)
        e[k] = 1e-6 * np.max(np.abs(y))
        Jfd[:, k] = (sysm.fun_readable(t, y + e) - sysm.fun_readable(t, y - e)) / (2 * e[k])
    np.testing.assert_allclose(J, Jfd, rtol=1e-6, atol=1e-7 * np.max(np.abs(J)))
    if fudge is not None:  # the nonlocal coupling is really there
        n = sysm.n_loads * sysm.m
        block = (
            J[n:, :n] if variable == "tau" else J[: sysm.m, : sysm.m] - np.triu(np.tril(J[: sysm.m, : sysm.m], 2), -2)
        )
        assert np.max(np.abs(block)) > 0
