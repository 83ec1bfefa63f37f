"""The adaptive fourth-order march of method "chebyshev" (``chebyshev/magnus.py``): its order, the ``march`` option,
the budgets it keeps (max_time, its step limit and the forecast of it) and its default tol.

References: DOP853 at 1e-13 on a small non-commuting system, the matrix exponential of a constant operator, and the
homogenised image solution A* = erf(p_bar / sqrt(2V)).
"""

import re

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.integrate import solve_ivp
from scipy.special import erf

import persson_fp as pf
from persson_fp.solvers.chebyshev import magnus

REF = pf.ContactProblem.reference()
PSD = REF.psd
DV = PSD.dV_dzeta
SV = float(np.sqrt(PSD.V()))


def test_commutator_free_step_is_fourth_order():
    # a small non-commuting system y' = A(t) y against DOP853 at 1e-13: the error of the fixed-step march falls
    # as h^4 (log-log fit)
    rng = np.random.default_rng(0)
    A0, A1, A2 = (rng.normal(size=(1, 4, 4)) for _ in range(3))

    def A_of(t):
        return A0 + np.sin(t) * A1 + t * t * A2

    y0 = np.ones((1, 4))
    ref = solve_ivp(lambda t, y: A_of(t)[0] @ y, (0.0, 1.0), y0[0], method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
    ns = np.array([8, 16, 32, 64])
    errs = []
    for n in ns:
        y = y0
        for k in range(n):
            y = magnus.cf4_step(A_of, k / n, 1.0 / n, y)
        errs.append(float(np.max(np.abs(y[0] - ref))))
    slope = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert slope >= 3.9, (errs, slope)
    # and exact for a constant operator (the separable case), to round-off
    y = magnus.cf4_step(lambda t: A0, 0.0, 0.7, y0)
    assert np.allclose(y, y0 @ sla.expm(0.7 * A0[0]).T, rtol=1e-12, atol=1e-13)


def test_march_option_and_refusals():
    with pytest.raises(ValueError, match="march"):
        pf.solve(REF, method="chebyshev", march="rk4")
    sol = pf.solve(REF, method="chebyshev", tol=1e-6, march="magnus")  # constant operator: one step suffices
    assert sol.info["path"] == "magnus" and float(np.max(sol.compare().L1)) <= 1e-6


def test_max_time_stops_the_march():
    pr = pf.FokkerPlanckProblem(PSD, p_bar=np.array([0.05, 0.5, 2.0]) * SV, B2=lambda p, z: DV(z) * np.ones_like(p))
    with pytest.raises(pf.SolverError, match="max_time") as err:
        pf.solve(pr, method="chebyshev", tol=1e-7, zeta_out=[2.0, 10.0, 128.0], march="magnus", max_time=0.05)
    # the deadline is checked inside the march, which stops short of its end (not after a whole run)
    m = re.search(r"the march stopped at V = (\S+) of (\S+) after (\d+) steps", str(err.value))
    assert m is not None, str(err.value)
    assert float(m.group(1)) < float(m.group(2))


def test_a_march_over_its_step_limit_is_forecast_and_refused_fast():
    # B2 = (1 + p zeta) dV/dzeta: drift-free but its operators at different V do not commute; at tol 1e-7 the march
    # needs > MAX_STEPS = 600 steps; it used to run all of them before refusing, now the forecast refuses it early
    pr = pf.FokkerPlanckProblem(PSD, p_bar=0.5 * SV, B2=lambda p, z: DV(z) * (1.0 + p * z))
    with pytest.raises(pf.SolverError, match=r"forecast to need .* loosen tol to about \d\.\de-0[67]") as err:
        pf.solve(pr, method="chebyshev", tol=1e-7, march="magnus", max_time=600)
    taken = int(re.search(r"after (\d+) steps", str(err.value)).group(1))
    assert taken < magnus.MAX_STEPS, str(err.value)


@pytest.mark.slow
def test_the_tol_a_refused_march_names_fits():
    # the tol the refusal above names fits in the march's steps (~7 s: the march at ~450 steps)
    pr = pf.FokkerPlanckProblem(PSD, p_bar=0.5 * SV, B2=lambda p, z: DV(z) * (1.0 + p * z))
    with pytest.raises(pf.SolverError, match=r"loosen tol to about") as err:
        pf.solve(pr, method="chebyshev", tol=1e-7, march="magnus", max_time=600)
    reach = float(re.search(r"loosen tol to about ([0-9.]+e[-+]?\d+)", str(err.value)).group(1))
    sol = pf.solve(pr, method="chebyshev", tol=reach, march="magnus", max_time=600)
    assert sol.info["march"]["steps"] <= 600 and float(np.max(sol.info["error_estimate"]["L1"])) <= reach


def test_the_default_tol_is_1e_6_on_the_march_and_1e_8_where_the_exponential_is_exact():
    # a march costs far more than the exponential path (tens of steps, each a few LUs): its default is 1e-6
    # (MARCH_DEFAULT_TOL), the exponential path's 1e-8
    pb = 1.83 * SV
    march = pf.FokkerPlanckProblem(PSD, p_bar=pb, B2=lambda p, z: DV(z) * (1 + 0.2 * (p / pb) * np.log(z)))
    sol = pf.solve(march, method="chebyshev", max_time=600)  # (not the default budget: a loaded machine is slow)
    assert sol.info["path"] == "radau" and sol.info["options"]["tol"] == 1e-6
    assert float(np.max(sol.error_estimate["contact_area"])) <= 1e-6
    exact_path = pf.FokkerPlanckProblem(PSD, p_bar=pb, B2=lambda p, z: DV(z) * np.ones_like(p))
    sol = pf.solve(exact_path, method="chebyshev")
    assert sol.info["path"] == "exponential" and sol.info["options"]["tol"] == 1e-8
    assert abs(float(sol.contact_area[-1]) - float(erf(pb / np.sqrt(2.0 * PSD.V())))) <= 1e-8
