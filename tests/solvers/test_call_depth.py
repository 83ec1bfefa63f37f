"""Calls point one way and stay shallow: front -> method -> engine -> result.

Measured with ``sys.setprofile``: the number of persson_fp frames on the stack at the deepest point of three whole
``pf.solve`` calls (the validating public API is not called from inner loops, engines do not call back into their
solvers), and the depth at which the numerical kernels (the step, the right-hand side, the propagator) run.  The
limit holds for these three solves, on warm caches (a first call's one-off set-up apart); other paths go deeper
today (fv on general coefficients 16, chebyshev's moving wall 15: the front-fixed step's damped start and the
moving wall's clock), which the walls-as-objects step is to flatten.
"""

from __future__ import annotations

import os
import sys

import pytest

import persson_fp as pf

PKG = os.path.dirname(pf.__file__)
MAX_DEPTH = 12
"""persson_fp frames on the stack, at most, anywhere in the three solves below."""
MAX_KERNEL_DEPTH = 10
"""The depth at which a numerical kernel (a step, a right-hand side, a propagator) is entered, at most."""
KERNELS = {
    ("fv/spectral.py", "march"),
    ("fv/spectral.py", "_dst_closed"),
    ("fv/solver.py", "theta_step"),
    ("fv/dst.py", "_amplification"),
    ("mol/lines.py", "fun"),
    ("mol/lines.py", "jac"),
    ("front_fixed/fluxes.py", "assemble"),
    ("front_fixed/fluxes.py", "apply"),
    ("chebyshev/collocation.py", "propagate_with_integral"),
    ("chebyshev/magnus.py", "cf4_step"),
    ("chebyshev/shared.py", "density"),
}
"""(module under solvers/, function) of the numerical kernels."""


def measure(call):
    """(deepest persson_fp stack, its frames, deepest kernel entry, kernels seen) during ``call()``."""
    stack: list[str] = []
    out = {"max": 0, "chain": [], "kernel": 0, "seen": set()}

    def profile(frame, event, arg):
        code = frame.f_code
        if not code.co_filename.startswith(PKG):
            return
        if event == "call":
            where = os.path.relpath(code.co_filename, PKG).replace(os.sep, "/")
            stack.append(f"{where}:{code.co_name}")
            if len(stack) > out["max"]:
                out["max"], out["chain"] = len(stack), list(stack)
            key = (where.removeprefix("solvers/"), code.co_name)
            if key in KERNELS:
                out["seen"].add(key)
                out["kernel"] = max(out["kernel"], len(stack))
        elif event == "return" and stack:
            stack.pop()

    sys.setprofile(profile)
    try:
        call()
    finally:
        sys.setprofile(None)
    return out


def _readme_moving_wall():
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    return pf.ContactProblem(psd, E_star=1.0, p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2))


SCENES = {
    "fv to tol 1e-4, reference problem": lambda: pf.solve(pf.ContactProblem.reference(), "fv", tol=1e-4),
    "mol, moving yield wall": lambda: pf.solve(_readme_moving_wall(), "mol"),
    "chebyshev, reference problem": lambda: pf.solve(pf.ContactProblem.reference(), "chebyshev"),
}


@pytest.mark.parametrize("scene", list(SCENES))
def test_call_depth(scene):
    call = SCENES[scene]
    call()  # (caches warm: the first call's one-off set-up is not what is measured)
    got = measure(call)
    chain = "\n  ".join(got["chain"])
    assert got["max"] <= MAX_DEPTH, f"{got['max']} persson_fp frames deep:\n  {chain}"
    assert got["seen"], "no numerical kernel ran: the list of kernels is out of date"
    assert got["kernel"] <= MAX_KERNEL_DEPTH, (got["kernel"], sorted(got["seen"]))


MAX_RANGE_CHECKS = 20
"""Calls of the range check behind the spectrum's validating methods (``check_in_range``) in one whole solve, at most:
the call's own validation, never one per step (a moving-wall mol solve made 451 through ``check_zeta``)."""


@pytest.mark.parametrize("scene", list(SCENES))
def test_inner_loops_do_not_validate(scene):
    from persson_fp import _validate

    call = SCENES[scene]
    call()
    code, n = _validate.check_in_range.__code__, [0]

    def profile(frame, event, arg):
        if event == "call" and frame.f_code is code:
            n[0] += 1

    sys.setprofile(profile)
    try:
        call()
    finally:
        sys.setprofile(None)
    assert 0 < n[0] <= MAX_RANGE_CHECKS, n[0]


def test_measure_counts_frames():
    """The measurement itself: a chain of three package calls inside a lambda reads as their number."""
    from persson_fp._validate import check_in_range

    got = measure(lambda: check_in_range([1.0, 2.0], "x", 0.0, 3.0))  # check_in_range -> as_float_array -> refuse
    assert got["max"] == 3, got["chain"]
