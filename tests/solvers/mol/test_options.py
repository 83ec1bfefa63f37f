"""mol's options: a bad value or a misspelt name is an error naming it, an ignored shared knob a warning."""

import pytest

import persson_fp as pf


def test_options_validated():
    pr = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match="order"):
        pf.solve(pr, "mol", order=3)
    with pytest.raises(ValueError, match="integrator"):
        pf.solve(pr, "mol", integrator="Euler")
    with pytest.raises(ValueError, match="variable"):
        pf.solve(pr, "mol", variable="V")
    with pytest.raises(TypeError, match="integrator"):
        pf.solve(pr, "mol", integrater="BDF")
    with pytest.warns(UserWarning, match="n_steps"):
        pf.solve(pr, "mol", n_steps=10, n_p=41)
