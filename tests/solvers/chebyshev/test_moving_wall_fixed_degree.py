"""method="chebyshev" on a moving yield wall with a fixed degree and an explicit tol: the estimate decides, as on the
fixed walls -- a result whose own estimate exceeds the asked tol is refused, never returned silently."""

import numpy as np
import pytest

import persson_fp as pf


def _moving_wall():
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, E_star=1.0, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


def test_a_fixed_degree_over_an_explicit_tol_is_refused_on_a_moving_wall():
    pr = _moving_wall()
    loose = pf.solve(pr, method="chebyshev", n_p=16, tol=1e-1)  # the estimate at this degree: ~1e-2
    worst = max(float(np.max(loose.info["error_estimate"][q])) for q in ("L1", "elastic_area", "plastic_area"))
    assert 1e-3 < worst <= 1e-1
    with pytest.raises(pf.SolverError, match="n_p = 16 cannot meet tol"):
        pf.solve(pr, method="chebyshev", n_p=16, tol=1e-3)
