"""The Radau IIA march of method "chebyshev" (``chebyshev/radau.py``): its order, its stiff damping, its error
estimate and its forecast refusal.

References: DOP853 at 1e-13 on a small non-commuting system; the stability function of Radau IIA at infinity
(R(-inf) = 0, L-stability); for the collocated Fokker--Planck operator of a non-separable problem a march at 1/8 of
the smallest step (its own error is 8^-4 ~ 2e-4 of the coarsest's at order 4 or more); and the Gaussian of a
non-separable Ornstein--Uhlenbeck case (mean and variance from their ODEs, in ``test_error_estimates``).
"""

import re

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import persson_fp as pf
from persson_fp.solvers.chebyshev import collocation, radau
from persson_fp.solvers.chebyshev.coefficients import Coefficients

REF = pf.ContactProblem.reference()
PSD, PB = REF.psd, float(REF.p_bar[0])
DV = PSD.dV_dzeta
VMAX = float(REF.V_max)


def _small_system():
    rng = np.random.default_rng(0)
    A0, A1, A2 = (rng.normal(size=(1, 4, 4)) for _ in range(3))

    def A_of(t):
        return A0 + np.sin(t) * A1 + t * t * A2

    return A_of


def test_radau_step_is_fifth_order_on_a_non_commuting_system():
    A_of = _small_system()
    y0 = np.ones((1, 4))
    ref = solve_ivp(lambda t, y: A_of(t)[0] @ y, (0.0, 1.0), y0[0], method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
    ns = np.array([4, 8, 16, 32])
    errs = []
    for n in ns:
        y = y0
        for k in range(n):
            y = radau.radau_step(A_of, k / n, 1.0 / n, y)
        errs.append(float(np.max(np.abs(y[0] - ref))))
    slope = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert slope >= 4.8, (errs, slope)


def test_radau_step_damps_stiff_modes_and_shares_its_solves_between_right_hand_sides():
    # y' = lambda y with h lambda = -1e10: the exact factor is 0, Radau IIA's R(z) ~ 1 / z -> 0 (L-stable); a
    # Crank--Nicolson factor would be ~ -1 (the ringing of a stiff start)
    lam = np.array([-1.0, -1e3, -1e10])

    def A_of(t):
        return np.diag(lam)[None]

    y = radau.radau_step(A_of, 0.0, 1.0, np.ones((1, 3)))[0]
    assert abs(y[0] - np.exp(-1.0)) <= 1e-3  # (one step of size 1: order 5 leaves ~1e-4)
    assert abs(y[1]) <= 1e-2 and abs(y[2]) <= 1e-9
    # several right-hand sides share the operators: each as if alone
    A_small = _small_system()
    Y = np.random.default_rng(1).normal(size=(1, 3, 4))
    both = radau.radau_step(A_small, 0.2, 0.1, Y)
    for r in range(3):
        assert np.allclose(both[:, r], radau.radau_step(A_small, 0.2, 0.1, Y[:, r]), rtol=1e-12, atol=1e-14)


def _collocated_scene(n=40):
    """(A_of, y0, V_a, V_b, norm): scene B2 = V'(1 + 0.2 (p/p_bar) ln zeta) collocated at degree n, from the
    small-time start at V_a = 1e-3 V_max (with the wall and moment rows of the solver's state)."""
    pr = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: DV(z) * (1 + 0.2 * (p / PB) * np.log(z)))
    cf = Coefficients(pr)
    V_a, V_b = 1e-3 * VMAX, VMAX
    p_max = PB + 14.0 * np.sqrt(3.0 * VMAX)
    grid = collocation.chebyshev_grid(n, p_max, np.array([PB]), np.array([3.0 * np.sqrt(V_a)]))
    P = collocation.start_density(lambda q: cf.at(q, 0.5 * V_a), grid.p, np.array([PB]), V_a)
    y0 = np.concatenate([P[:, 1:-1], np.zeros((1, 3))], axis=1)

    def A_of(V):
        b, c = cf.at(grid.p, V)
        return collocation.with_wall_rows(grid, collocation.generator(grid, b, c), b, c)

    def norm(d, w=grid.w[:, 1:-1], m=n - 1):
        return np.sum(np.abs(d[:, :m]) * w, axis=-1) + np.abs(d[:, m]) + np.abs(d[:, m + 1])

    return A_of, y0, V_a, V_b, norm


def test_march_estimate_is_honest_and_near_its_tol_on_a_collocated_non_separable_operator():
    A_of, y0, V_a, V_b, norm = _collocated_scene()
    nodes = V_a * (V_b / V_a) ** np.linspace(0.0, 1.0, 161)[1:]  # (a reference march: 160 steps uniform in ln V)
    ref, _, _ = radau.radau_march(A_of, y0, V_a, V_b, 1.0, norm, 0.0, nodes=nodes)
    for tol in (1e-5, 1e-7):
        y, est, st = radau.radau_march(A_of, y0, V_a, V_b, tol, norm, 1e-15)
        true = float(norm(y - ref)[0])
        assert float(est[0]) <= tol  # (the sum of the local estimates it held to tol)
        assert true <= 2.0 * float(est[0]), (tol, true, est)  # honest: not more than 2x over it
        assert true >= 0.002 * tol, (tol, true, est)  # and not far below the tol it was asked (measured 0.005)
        assert st["solves"] == 3 * (st["steps"] + st["rejected"])


@pytest.mark.slow
def test_march_order_of_convergence_on_a_collocated_non_separable_operator():
    # fixed steps uniform in ln V (replays): the global error falls at least as h^4 (order 5, reduced by the
    # Dirichlet walls at most by one)
    A_of, y0, V_a, V_b, norm = _collocated_scene(48)
    grid = lambda k: V_a * (V_b / V_a) ** np.linspace(0.0, 1.0, k + 1)[1:]  # noqa: E731
    ref, _, _ = radau.radau_march(A_of, y0, V_a, V_b, 1.0, norm, 0.0, nodes=grid(256))
    ks = np.array([8, 16, 32])
    errs = [float(norm(radau.radau_march(A_of, y0, V_a, V_b, 1.0, norm, 0.0, nodes=grid(k))[0] - ref)[0]) for k in ks]
    slope = -np.polyfit(np.log(ks), np.log(errs), 1)[0]
    assert slope >= 4.0, (errs, slope)


def test_a_march_over_its_time_budget_is_refused_after_a_few_steps_naming_what_it_needs():
    A_of, y0, V_a, V_b, norm = _collocated_scene()
    with pytest.raises(radau.MarchTooLong) as err:
        radau.radau_march(A_of, y0, V_a, V_b, 1e-9, norm, 1e-15, time_budget=1e-6)
    m = re.search(r"forecast to need ~(\d+) Radau steps, ~(\S+) s more.*after (\d+) steps", str(err.value))
    assert m is not None, str(err.value)
    assert int(m.group(3)) == radau.PREDICT_AFTER  # refused at the first forecast, not at the end
    assert err.value.reachable > 1e-9 and err.value.needed > 1e-6
    # through the solver: a SolverError naming the tol that would fit, the time it would take, max_time and the degree
    pr = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: DV(z) * (1 + 0.2 * (p / PB) * np.log(z)))
    with pytest.raises(pf.SolverError, match=r"max_time") as err:
        pf.solve(pr, method="chebyshev", tol=1e-8, max_time=0.05)
    assert re.search(r"loosen tol to about \d|would take about \S+ s|max_time = 0.05 s exceeded", str(err.value))


def test_wall_row_operators_are_the_generator_with_its_wall_rows():
    # the march's batched assembly against the one-operator functions, element by element, with and without drift
    rng = np.random.default_rng(3)
    grid = collocation.chebyshev_grid(30, np.array([3.0, 5.0]), np.array([0.5, 1.0]), np.array([0.1, 0.3]))
    ops = collocation.WallRowOperators(grid)
    for drift in (None, "zero", "random"):
        bc = []
        for _ in range(3):
            b = rng.uniform(0.1, 2.0, (2, 31))
            c = None if drift is None else np.zeros((2, 31)) if drift == "zero" else rng.standard_normal((2, 31))
            bc.append((b, c))
        want = np.stack([collocation.with_wall_rows(grid, collocation.generator(grid, b, c), b, c) for b, c in bc])
        assert np.array_equal(ops(bc), want)


@pytest.mark.parametrize("r", [0.3, 1.0, 1.7, 2.5])
def test_first_guesses_extrapolate_a_cubic_through_the_step_exactly(r):
    # the collocation polynomial of a step is the cubic through 0 at tau = 0 and the stage increments at c_i: a cubic
    # u(tau) with u(0) = 0 is reproduced at the next step's stages 1 + r c_j, less u(1)
    u = lambda t: 0.7 * t - 1.3 * t**2 + 0.4 * t**3  # noqa: E731
    W = radau._extrapolation(r)
    assert np.allclose(W @ u(radau.C), u(1.0 + r * radau.C) - u(1.0), rtol=0, atol=1e-13)
