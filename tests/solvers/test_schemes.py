"""The time-stepping schemes as data (``solvers/schemes.py``): theta, order and L-stability of each."""

from persson_fp.solvers.schemes import SCHEMES


def test_scheme_table():
    assert SCHEMES["explicit"].theta == 0.0
    assert SCHEMES["crank-nicolson"].theta == 0.5
    assert SCHEMES["implicit"].theta == 1.0
    assert SCHEMES["tr-bdf2"].l_stable and SCHEMES["tr-bdf2"].order == 2
    assert SCHEMES["implicit"].order == 1
