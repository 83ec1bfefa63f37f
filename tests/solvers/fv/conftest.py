"""The reference problems of the fv tests, one per fudge factor (built once per module)."""

import pytest

import persson_fp as pf

FUDGES = [None, "YP08", "WM17"]


@pytest.fixture(scope="module")
def problems():
    return {f: pf.ContactProblem.reference(fudge=f) for f in FUDGES}
