"""General Fokker-Planck coefficients on the front-fixed engine ("fv", "mol") against closed forms written here: the
homogenised special case given as callables (the image solution), and the first-moment law with a drift."""

import numpy as np
import pytest
from scipy.special import ndtr

import persson_fp as pf

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, float(REF.p_bar[0])


@pytest.mark.parametrize("method", ["fv", "mol"])
def test_homogenised_special_case_reproduces_the_image_solution(method):
    """B1 = 0, B2 = dV/dzeta given as callables: the general path against pf.exact (second order; measured
    |dA*| 2.1e-4 at 400 cells for fv), and inside its own error estimate."""
    ref = pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 1.0]))
    fp = pf.FokkerPlanckProblem(ref.psd, p_bar=ref.p_bar, B2=lambda p, z: np.full(p.shape, float(ref.psd.dV_dzeta(z))))
    opts = {"n_p": 400, "n_steps": 400} if method == "fv" else {"n_p": 400, "rtol": 1e-8}
    sol = pf.solve(fp, method=method, zeta_out=[4.0, 128.0], **opts)
    err = np.abs(sol.contact_area - pf.exact(ref, zeta=np.array([4.0, 128.0])).contact_area)
    assert np.max(err) < 5e-4
    est = sol.info["error_estimate"]
    assert np.all(err <= est["elastic_area"] + 1e-12)
    with pytest.raises(ValueError, match="no exact"):
        sol.compare()


def test_first_moment_law_with_drift_against_the_closed_form():
    """B2 = dV/dzeta, B1 = mu B2: Brownian motion with drift mu in V, absorbed at 0.  The engine's first-moment law
    (info["load_law"], checked by the invariants) and its load both match the closed-form first moment
    int p [phi(p - p_bar - mu V) - e^{-2 mu p_bar} phi(p + p_bar - mu V)] dp, written here."""
    mu = -0.8 / np.sqrt(REF.V_max)
    fp = pf.FokkerPlanckProblem(
        PSD, p_bar=PB, B1=lambda p, z: mu * PSD.dV_dzeta(z) + 0 * p, B2=lambda p, z: PSD.dV_dzeta(z) + 0 * p
    )
    z = np.array([8.0, 128.0])
    sol = pf.solve(fp, method="fv", zeta_out=z, n_p=400, n_steps=400)
    V = np.asarray(PSD.V(z))
    s = np.sqrt(V)

    def first_moment(c):  # int_0^inf p phi((p - c)/s)/s dp
        return c * ndtr(c / s) + s * np.exp(-0.5 * (c / s) ** 2) / np.sqrt(2 * np.pi)

    F = first_moment(PB + mu * V) - np.exp(-2 * mu * PB) * first_moment(-PB + mu * V)
    law = sol.info["load_law"][:, 0]
    assert np.max(np.abs(sol.load - F)) / PB < 5e-4
    assert np.max(np.abs(law - F)) / PB < 5e-4
    assert np.all(np.abs(F - PB) / PB > 0.1)  # the drift moved the load: a p_bar check would have failed
