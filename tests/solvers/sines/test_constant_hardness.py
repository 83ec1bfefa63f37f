"""The sine series with a constant hardness: on [0, sigma_Y] it is the strip's exact solution."""

import numpy as np
import pytest

import persson_fp as pf

SIGMA = 1.5 * np.sqrt(0.0025)  # 1.5 sqrt(V(zeta_max)) of the reference problem


def _problem(fudge=None):
    return pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 1.0]), hardness=SIGMA, fudge=fudge)


@pytest.mark.parametrize("fudge", [None, "YP08"])
def test_sines_constant_hardness_is_the_strip_series(fudge):
    """On [0, sigma_Y] the sine series is the strip's exact solution: round-off at tol = 1e-13."""
    sol = pf.solve(_problem(fudge), method="sines", tol=1e-13, zeta_out=[4.0, 32.0, 128.0])
    c = sol.compare()
    assert np.max(c.plastic_area_error) < 1e-13 and np.max(c.elastic_area_error) < 1e-13
    assert np.max(c.L1) < 1e-12
