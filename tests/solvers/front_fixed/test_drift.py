"""A drift B1 on the front-fixed engine ("fv", "mol"): what the cells cannot resolve is refused before the march,
naming the remedy; what they can is solved within a closed-form bound.

- A strong constant drift toward the wall p = 0 (B1 = -1) puts the start-up Gaussian beyond the wall and makes a
  layer at the wall far below a cell, where the centred fluxes ring (mol crawled, fv's areas did not sum to 1): a
  refusal naming n_p, before any numerical kernel runs.  Weaker drifts are solved, within a closed-form bound and
  without the ringing that made mol's march crawl.
- A drift away from the load carries the PDF out of reach of the grid: refused the same way, and by auto before any
  attempt.
- A drift of 1e20 makes the implicit step singular: a ValueError naming B1 and the singular step (not the raw
  "Factor is exactly singular" or "LAPACK info 201").
"""

import numpy as np
import pytest
from scipy.special import ndtr

import persson_fp as pf
from persson_fp.solvers.front_fixed.start import PECLET_MAX

from ..test_call_depth import measure

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, 0.025


def _constant_drift(b1, **kw):
    return pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=lambda p, z: np.full(np.shape(p), b1), **kw)


def _refused_before_any_kernel(call, error, match):
    """Run ``call``, which must raise ``error`` matching ``match``, and return the numerical kernels it entered
    (``test_call_depth.KERNELS``: the step, the right-hand side, the propagator; that test checks the list is
    current): a refusal made before the march enters none."""

    def attempt():
        with pytest.raises(error, match=match):
            call()

    return measure(attempt)["seen"]


@pytest.mark.parametrize("b1", [-1.0, -10.0])
@pytest.mark.parametrize("method", ["mol", "fv"])
def test_strong_drift_toward_the_wall_is_refused_at_once_naming_the_remedy(method, b1):
    match = r"drift B1 is not resolved where the PDF meets the wall.*raise n_p to >= \d+"
    assert not _refused_before_any_kernel(lambda: pf.solve(_constant_drift(b1), method=method), ValueError, match)


@pytest.mark.parametrize("b1", [1.0, 5.0])
@pytest.mark.parametrize("method", ["mol", "fv"])
def test_strong_drift_away_from_the_wall_is_refused_at_once(method, b1):
    call = lambda: pf.solve(_constant_drift(b1), method=method)  # noqa: E731
    assert not _refused_before_any_kernel(call, ValueError, "raise n_p to >=")


def test_strong_drift_is_refused_fast():
    """B1 = 5 per unit zeta carries the PDF 635 pressure units away: the domain follows it and the resolution
    check refuses the run before its march (it once ran mol for minutes and into gigabytes, and gave fv an area
    residual of 2)."""
    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=lambda p, z: np.full(np.shape(p), 5.0))
    for method in ("fv", "mol"):
        assert not _refused_before_any_kernel(lambda: pf.solve(fp, method=method), ValueError, "raise n_p to >=")
    with pytest.raises(pf.SolverError, match="would need more than") as err:
        pf.solve(fp, method="auto", tol=1e-3)
    assert "no attempt yet" in str(err.value)  # auto refuses from the resolution it would need, before any attempt


@pytest.mark.parametrize("b1", [-0.01, -0.1])
@pytest.mark.parametrize("method", ["mol", "fv"])
def test_moderate_drift_toward_the_wall_within_the_closed_form_bound(method, b1):
    """Without the wall the pressure at zeta_max is N(p_bar + B1 (zeta - 1), V); the absorbed process's contact area
    is at most its mass above 0, Phi((p_bar + B1 (zeta_max - 1)) / sqrt(V)) (1e-137 and 0 here).  Once: mol's march
    crawled through a ring of cell masses at the tolerance (B1 = -0.1), and fv said 'the areas do not sum to 1' for
    B1 <= -0.1."""
    sol = pf.solve(_constant_drift(b1), method=method)
    A = float(sol.contact_area_all[-1, 0])
    est = float(sol.error_estimate["contact_area"][-1, 0])
    bound = float(ndtr((PB + b1 * (REF.zeta_max - 1.0)) / np.sqrt(REF.V_max)))
    assert -est <= A <= bound + est
    assert est < 1e-10
    # no ringing to crawl through: fv's cells resolve the drift's layer at the wall, mol's march takes a few hundred
    # right-hand sides (measured 470 and 561)
    if method == "fv":
        assert sol.info["max_cell_peclet"] <= PECLET_MAX
    else:
        assert sol.info["nfev"] < 2000


@pytest.mark.parametrize("method", ["mol", "fv", "auto"])
def test_huge_constant_drift_names_B1_and_the_singular_step(method):
    with pytest.raises(ValueError, match=r"drift B1 is too large for the implicit step.*singular"):
        pf.solve(_constant_drift(-1e20), method=method)


@pytest.mark.parametrize("method", ["mol", "fv"])
def test_huge_drift_away_from_the_pdf_names_B1_and_the_singular_step(method):
    """B1 = -1e20 only at p > 0.3, beyond the band the wall check follows: the solve itself meets the singular
    matrix (before: RuntimeError 'Factor is exactly singular', LinAlgError 'LAPACK info 201')."""
    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B1=lambda p, z: np.where(p > 0.3, -1e20, 0.0))
    with pytest.raises(ValueError, match=r"drift B1 is too large for the implicit step.*\|B1\| = 1e\+20.*singular"):
        pf.solve(fp, method=method)
