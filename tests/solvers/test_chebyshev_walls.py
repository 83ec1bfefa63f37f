"""method="chebyshev" at the wall p = 0: coefficients defined only for p >= 0, and a diffusion that vanishes there.

References written here: the image solution of Brownian motion with drift absorbed at 0, and for B2 = kappa p dV/dzeta
the squared Bessel process of dimension 0 (X = 4p / kappa in V): absorbed with probability exp(-x0 / 2V), so
A* = 1 - exp(-2 p_bar / (kappa V)) exactly.
"""

import time

import numpy as np
import pytest

import persson_fp as pf

REF = pf.ContactProblem.reference()
PSD, PB, VMAX = REF.psd, float(REF.p_bar[0]), float(REF.V_max)


def test_coefficients_undefined_below_the_wall_are_never_evaluated_there():
    """B1, B2 that are NaN for p < 0 (a natural way to write (p / p_bar)^a): the start's finite-difference stencils
    reached p < 0 and the solve was refused as "B2 must be finite" (regression); now the image solution."""
    b, c = 1.7, -0.4 * PB / VMAX

    def B2(p, z):
        return np.where(np.asarray(p) >= 0, b * float(PSD.dV_dzeta(z)), np.nan)

    def B1(p, z):
        return np.where(np.asarray(p) >= 0, c * float(PSD.dV_dzeta(z)), np.nan)

    from scipy.special import ndtr

    for tol in (1e-3, 1e-6):  # (both refused before)
        sol = pf.solve(pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=B1, B2=B2), method="chebyshev", tol=tol)
        s, m = np.sqrt(b * VMAX), PB + c * VMAX
        # A* of the image solution phi(p - m) - exp(-2 c p_bar / b) phi(p + p_bar - cV), integrated over p > 0
        A_exact = ndtr(m / s) - np.exp(-2 * c * PB / b) * ndtr((c * VMAX - PB) / s)
        est = float(np.max(sol.error_estimate["contact_area"]))
        assert abs(float(sol.contact_area[-1]) - A_exact) <= est <= tol


def test_diffusion_vanishing_linearly_at_the_wall_is_declined_at_once_and_auto_meets_the_closed_form():
    kappa = 2.0 * PB / VMAX  # A* = 1 - e^-1
    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: kappa * np.maximum(p, 0.0) * PSD.dV_dzeta(z))
    t0 = time.perf_counter()
    with pytest.raises(ValueError, match=r"vanishes at the wall p = 0 \(like p\^1"):
        pf.solve(fp, method="chebyshev", tol=1e-3)
    assert time.perf_counter() - t0 < 2.0  # (it ran to degree 400 before: 0.3 s, the message "loosen tol")
    sol = pf.solve(fp, method="auto", tol=1e-3)
    assert sol.info["auto"]["method"] == "fv"
    err = abs(float(sol.contact_area[-1]) - (1.0 - np.exp(-2.0 * PB / (kappa * VMAX))))
    assert err <= float(np.max(sol.error_estimate["contact_area"])) <= 1e-3


def test_square_root_diffusion_at_the_wall_is_still_solved():
    """B2 ~ p^(1/2) at the wall: P ~ p^(1/2) there vanishes, so the spectral wall holds (slower convergence);
    chebyshev and fv agree within the sum of their estimates."""
    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: (p / PB) ** 0.5 * PSD.dV_dzeta(z))
    a = pf.solve(fp, method="chebyshev", tol=1e-3)
    b = pf.solve(fp, method="fv", n_p=400, n_steps=200)
    gap = abs(float(a.contact_area[-1]) - float(b.contact_area[-1]))
    assert gap <= float(np.max(a.error_estimate["contact_area"])) + float(np.max(b.error_estimate["contact_area"]))
