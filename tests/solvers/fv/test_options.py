"""Method "fv"'s options: a value out of range or a misspelt name is an error naming the option."""

from __future__ import annotations

import pytest

from persson_fp.solvers.fv import FiniteVolumeSolver


@pytest.mark.parametrize(
    "bad",
    [
        {"scheme": "leapfrog"},
        {"stepping": "random"},
        {"coupling": "magic"},
        {"initial": "gauss"},
        {"n_p": 2},
        {"n_steps": 0},
        {"k_domain": -1.0},
        {"space": "fv6"},
        {"linalg": "lu"},
    ],
)
def test_bad_options_raise(problems, bad):
    with pytest.raises(ValueError, match=next(iter(bad))):
        FiniteVolumeSolver(problems[None], **bad)


def test_misspelt_option(problems):
    with pytest.raises(TypeError, match="scheme"):
        FiniteVolumeSolver(problems[None], schem="implicit")
