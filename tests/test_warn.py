"""A warning raised deep in a solve points at the user's line, not at the package's internals."""

from __future__ import annotations

import warnings

import numpy as np

import persson_fp as pf
from persson_fp._warn import warn_user


def test_warn_user_points_at_the_first_frame_outside_the_package():
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        warn_user("here", RuntimeWarning)
    assert w[0].filename == __file__ and w[0].category is RuntimeWarning


def test_coarse_general_solve_warns_at_the_call():
    ref = pf.ContactProblem.reference()
    p_bar = 0.5 * float(np.sqrt(ref.V_max))

    def B2(p, z):
        return (1.0 + p / (2.0 * p_bar)) * ref.psd.dV_dzeta(z, ref.E_star)

    pr = pf.FokkerPlanckProblem(ref.psd, E_star=ref.E_star, p_bar=p_bar, B2=B2)
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        pf.solve(pr, "fv", n_p=20, n_steps=10)  # an estimate above 1e-2: "a coarse answer"
    coarse = [x for x in w if "coarse answer" in str(x.message)]
    assert coarse and all(x.filename == __file__ for x in coarse), [(x.filename, x.lineno) for x in w]
