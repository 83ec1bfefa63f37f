"""Regressions from an outside review of method "chebyshev" (a zeta-dependence between the probe magnifications,
max_time).  References: the homogenised image solution in the clock tau = int g dV (B2 = g(zeta) dV/dzeta is the
homogenised theory at variance tau), by adaptive quadrature written here."""

from __future__ import annotations

import time

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf

PSD = pf.ContactProblem.reference().psd
DV = PSD.dV_dzeta
SV = float(np.sqrt(PSD.V()))


def _bump(z):  # zero at the 9 log-spaced probe magnifications of [1, 128], up to 4x between them
    return 1.0 + 3.0 * np.maximum(0.0, 1.0 - ((z - 4.75) / 1.25) ** 2) ** 2


def test_a_zeta_dependence_between_the_probes_is_not_taken_as_separable():
    pb = 0.5 * SV
    pr = pf.FokkerPlanckProblem(PSD, p_bar=pb, B2=lambda p, z: _bump(z) * DV(z) * np.ones_like(p))
    pts = [PSD.zeta_r, 3.5, 4.75, 6.0]
    tau = quad(lambda z: float(_bump(z) * DV(z)), 1.0, PSD.zeta_max, points=pts, epsabs=0.0, epsrel=1e-13, limit=500)
    exact = float(erf(pb / np.sqrt(2.0 * tau[0])))  # A* of the image solution at variance tau (eq:Area)
    assert abs(exact - 0.365) < 1e-3  # the bump matters: without it A* = 0.3829
    for method in ("chebyshev", "auto"):
        sol = pf.solve(pr, method=method, tol=1e-8)
        err = abs(float(sol.contact_area[-1]) - exact)
        assert err <= max(float(np.max(sol.error_estimate["contact_area"])), 1e-12)
        assert err < 1e-8


def test_a_nan_in_a_narrow_band_of_zeta_is_a_value_error():
    pr = pf.FokkerPlanckProblem(
        PSD, p_bar=0.5 * SV, B2=lambda p, z: np.where((z > 3.0) & (z < 3.1), np.nan, 1.0) * DV(z) * np.ones_like(p)
    )
    with pytest.raises(ValueError, match="B2"):
        pf.solve(pr, method="chebyshev")


def test_max_time_stops_the_march():
    pr = pf.FokkerPlanckProblem(PSD, p_bar=np.array([0.05, 0.5, 2.0]) * SV, B2=lambda p, z: DV(z) * np.ones_like(p))
    t0 = time.perf_counter()
    with pytest.raises(pf.SolverError, match="max_time"):
        pf.solve(pr, method="chebyshev", tol=1e-7, zeta_out=[2.0, 10.0, 128.0], march="magnus", max_time=0.05)
    assert time.perf_counter() - t0 < 2.0  # (the run without a budget takes ~3 s)


@pytest.mark.parametrize("B2", [lambda p, z: 0.0 * p, lambda p, z: ((p - 0.5 * SV) / (0.5 * SV)) ** 2 * DV(z)])
def test_a_diffusion_vanishing_at_the_load_is_named(B2):
    with pytest.raises(ValueError, match="B2 vanishes at the load"):
        pf.solve(pf.FokkerPlanckProblem(PSD, p_bar=0.5 * SV, B2=B2), method="chebyshev")
