"""method="chebyshev" with many loads on one grid (the separable paths): one set of modes for every load.

The batched call must give what one call per load gives (the per-load path, grids clustered at each load, a
different start and estimate) within the two estimates; and independent references: the closed form of the
homogenised theory (pf.exact) and the image solution of a constant drift and diffusion absorbed at p = 0.
Memory: what a batch holds per load, measured by tracemalloc (bytes, deterministic), is no more than the
arrays its Solution keeps for that load.
"""

import tracemalloc

import numpy as np
import pytest
from scipy.special import ndtr

import persson_fp as pf
from persson_fp.solvers.chebyshev.shared import CHUNK, N_SHARED_MAX, shared_memory

REF = pf.ContactProblem.reference()
PSD, E, PB, VMAX = REF.psd, REF.E_star, float(REF.p_bar[0]), float(REF.V_max)
SV = float(np.sqrt(VMAX))
LOADS = np.array([1e-3, 0.1, 0.5, 1.2, 2.0]) * SV


def _besq(p_bar=LOADS, g=lambda z: 1.0):
    """B2 = (1 + p / (2 PB)) g(zeta) dV/dzeta: the same coefficients for every load (PB fixed)."""
    return pf.FokkerPlanckProblem(PSD, E, p_bar, B2=lambda p, z: (1 + p / (2 * PB)) * g(z) * PSD.dV_dzeta(z, E))


def _poly(sol, i):
    """The solution's polynomial for load i at the last station, as a function of p (barycentric, its own map)."""
    p, P, g = np.atleast_2d(sol.p)[-1], sol.P0_all[-1, i], sol.info["grid"]
    n = p.size - 1
    c, e = float(g["centre"][0]), float(g["eps"][0])
    a1 = np.arcsinh(-c / e)
    h = 0.5 * (np.arcsinh((p[-1] - c) / e) - a1)
    x = -np.cos(np.pi * np.arange(n + 1) / n)
    wb = np.ones(n + 1)
    wb[0] = wb[-1] = 0.5
    wb *= (-1.0) ** np.arange(n + 1)

    def f(q):
        with np.errstate(all="ignore"):
            return _eval(q)

    def _eval(q):
        d = ((np.arcsinh((q - c) / e) - a1) / h - 1.0)[:, None] - x[None, :]
        d[d == 0] = 1e-300
        t = wb / d
        return np.where(q <= p[-1], (t @ P) / t.sum(axis=1), 0.0)

    return f


def _last(values, n_loads, i):
    """The value at the last station for load i (any of the Solution's shapes)."""
    return float(np.reshape(values, (-1, n_loads))[-1, i])


def _elastic(sol):
    """A_el (stations, loads): the contact area less the plastic area."""
    A = np.reshape(sol.contact_area, (-1, sol.problem.n_loads))
    return A if sol.plastic_area is None else A - np.reshape(sol.plastic_area, A.shape)


def _l1(f1, f2, p_hi):
    q = np.linspace(0.0, p_hi, 20001)
    return float(np.trapezoid(np.abs(f1(q) - f2(q)), q))


def test_batch_equals_one_by_one_and_shares_its_modes():
    tol = 1e-7
    pr = _besq()
    sol = pf.solve(pr, method="chebyshev", tol=tol)
    assert sol.info["loads"].startswith("shared")
    est = sol.info["error_estimate"]
    for i, pb in enumerate(LOADS):
        single = pf.solve(pr.with_loads(pb), method="chebyshev", tol=tol)  # (one load: the same kind of grid)
        dA = abs(_last(sol.contact_area, LOADS.size, i) - _last(single.contact_area, 1, 0))
        assert dA <= est["elastic_area"][-1, i] + single.info["error_estimate"]["elastic_area"][-1, 0]
        # the per-load path (a grid clustered at the load, the start at V0 = 1e-4 V): independent of the modes
        one = pf.solve(pr.with_loads(pb), method="chebyshev", tol=tol, V0_fraction=1e-4)
        assert "loads" not in one.info
        e1 = one.info["error_estimate"]
        dA = abs(_last(sol.contact_area, LOADS.size, i) - _last(one.contact_area, 1, 0))
        assert dA <= est["elastic_area"][-1, i] + e1["elastic_area"][-1, 0] and dA <= 2 * tol, (pb, dA)
        dF = abs(_last(sol.load, LOADS.size, i) - _last(one.load, 1, 0)) / pb
        assert dF <= est["load"][-1, i] + e1["load"][-1, 0], (pb, dF)
        L1 = _l1(_poly(sol, i), _poly(one, 0), float(np.max(one.p)))
        assert L1 <= est["L1"][-1, i] + e1["L1"][-1, 0] and L1 <= 2 * tol, (pb, L1)
    # the work is shared: ten times the loads (same range) take the same degree and the same runs
    many = pf.solve(_besq(np.geomspace(LOADS[0], LOADS[-1], 50)), method="chebyshev", tol=tol)
    assert (many.info["grid"]["n_p"], many.info["runs"]) == (sol.info["grid"]["n_p"], sol.info["runs"])


@pytest.mark.parametrize("tol", [1e-5, 1e-9])
def test_homogenised_batch_against_the_closed_form(tol):
    pr = pf.ContactProblem(PSD, E, np.geomspace(1e-4, 3.0, 40) * SV)
    sol = pf.solve(pr, method="chebyshev", tol=tol)
    assert sol.info["loads"].startswith("shared")
    c = sol.compare()
    est = sol.info["error_estimate"]
    assert np.all(c.area_error <= est["elastic_area"]) and float(np.max(c.area_error)) <= tol
    assert np.all(c.L1 <= est["L1"]) and float(np.max(c.L1)) <= tol
    assert np.max(np.abs(sol.load - pr.p_bar) / pr.p_bar) <= tol


def test_drift_batch_against_the_image_solution():
    # b = 1.7, constant drift c: phi(p - p_bar - cV) - exp(-2 c p_bar / b) phi(p + p_bar - cV), variance b V
    b, c = 1.7, -0.6 * PB / VMAX
    pr = pf.FokkerPlanckProblem(
        PSD,
        E,
        LOADS,
        B1=lambda p, z: np.full(np.shape(p), c * PSD.dV_dzeta(z, E)),
        B2=lambda p, z: np.full(np.shape(p), b * PSD.dV_dzeta(z, E)),
    )
    tol = 1e-7
    sol = pf.solve(pr, method="chebyshev", tol=tol)
    assert sol.info["loads"].startswith("shared")
    for i, pb in enumerate(LOADS):

        def ex(q, pb=pb):
            phi = lambda u: np.exp(-0.5 * u * u / (b * VMAX)) / np.sqrt(2 * np.pi * b * VMAX)  # noqa: E731
            return phi(q - pb - c * VMAX) - np.exp(-2 * c * pb / b) * phi(q + pb - c * VMAX)

        true = _l1(_poly(sol, i), ex, float(np.max(sol.p)))
        assert true <= sol.info["error_estimate"]["L1"][-1, i] <= tol, (pb, true)


def test_hardness_batch_against_the_images_between_two_walls():
    # b = 1, walls at 0 and sigma_Y: P = sum_k phi(p - p_bar - 2 k sigma) - phi(p + p_bar - 2 k sigma); A_el its mass
    sig = 2.5 * SV
    pr = pf.ContactProblem(PSD, E, LOADS[1:], hardness=sig)
    tol = 1e-8
    sol = pf.solve(pr, method="chebyshev", tol=tol)
    assert sol.info["loads"].startswith("shared")
    s = np.sqrt(VMAX)
    k = np.arange(-30, 31)[:, None] * 2 * sig
    pb = pr.p_bar[None, :]
    mass = lambda a: ndtr((sig - a - k) / s) - ndtr((-a - k) / s)  # noqa: E731
    A_el = np.sum(mass(pb) - mass(-pb), axis=0)
    err = np.abs(_elastic(sol)[-1] - A_el)
    assert np.all(err <= sol.info["error_estimate"]["elastic_area"][-1]) and np.max(err) <= tol, err
    # A_pl from the martingale p (b = 1, no drift): p_bar = int p P dp + sigma A_pl, int p P dp of the images
    phi = lambda u: np.exp(-0.5 * u * u) / np.sqrt(2 * np.pi)  # noqa: E731

    def moment(mu):
        a, b = -mu / s, (sig - mu) / s
        return mu * (ndtr(b) - ndtr(a)) + s * (phi(a) - phi(b))

    A_pl = (pr.p_bar - np.sum(moment(pb + k) - moment(-pb + k), axis=0)) / sig
    err = np.abs(np.ravel(sol.plastic_area) - A_pl)
    assert np.all(err <= sol.info["error_estimate"]["plastic_area"][-1] + 1e-14) and np.max(err) <= tol, err


def test_hardness_stations_and_clock_batch_equal_one_by_one():
    kw = {"zeta_out": [REF.zeta_max**0.5, REF.zeta_max**0.8, REF.zeta_max]}
    cases = [
        (pf.ContactProblem(PSD, E, LOADS[1:], hardness=2.5 * SV), {}),
        (_besq(LOADS[1:]), kw),
        (_besq(LOADS[1:], g=lambda z: z**0.3), {}),  # the clock path: B2 = b(p) g(zeta)
    ]
    tol = 1e-6
    for pr, opts in cases:
        sol = pf.solve(pr, method="chebyshev", tol=tol, **opts)
        assert sol.info["loads"].startswith("shared")
        est = sol.info["error_estimate"]
        for i, pb in enumerate(pr.p_bar):
            one = pf.solve(pr.with_loads(pb), method="chebyshev", tol=tol, **opts)
            e1 = one.info["error_estimate"]
            dA = np.abs(_elastic(sol)[:, i] - _elastic(one)[:, 0])
            assert np.all(dA <= est["elastic_area"][:, i] + e1["elastic_area"][:, 0]), (pr, pb, dA)
            if pr.hardness is not None:
                dP = abs(_last(sol.plastic_area, pr.n_loads, i) - _last(one.plastic_area, 1, 0))
                assert dP <= est["plastic_area"][-1, i] + e1["plastic_area"][-1, 0], (pb, dP)


def test_a_grid_out_of_reach_runs_per_load():
    # a first station at zeta = 1.05 makes the kernel narrow against the loads' spread: past N_SHARED_MAX
    pr = _besq(LOADS[1:3])
    sol = pf.solve(pr, method="chebyshev", tol=1e-6, zeta_out=[1.05, REF.zeta_max])
    assert "loads" not in sol.info and sol.info["grid"]["n_p"] <= N_SHARED_MAX


def _bytes(obj, seen=None) -> int:
    """The bytes of every numpy array a Solution keeps (fields and info, recursively)."""
    seen = set() if seen is None else seen
    if id(obj) in seen:
        return 0
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        return obj.nbytes
    if isinstance(obj, dict):
        return sum(_bytes(v, seen) for v in obj.values())
    if isinstance(obj, (list, tuple)):
        return sum(_bytes(v, seen) for v in obj)
    if hasattr(obj, "__dict__"):
        return sum(_bytes(v, seen) for k, v in vars(obj).items() if k != "problem")
    return 0


def test_memory_per_load_within_the_solution_size_and_the_estimate():
    def peak(n_loads):
        pr = _besq(np.geomspace(LOADS[0], LOADS[-1], n_loads))
        pf.solve(pr, method="chebyshev", tol=1e-6)  # (first-call caches outside the measure)
        tracemalloc.start()
        sol = pf.solve(pr, method="chebyshev", tol=1e-6)
        out = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        return out, sol

    (m1, s1), (m2, s2) = peak(2 * CHUNK), peak(4 * CHUNK)
    assert s1.info["grid"]["n_p"] == s2.info["grid"]["n_p"]
    per_load = (m2 - m1) / (2 * CHUNK)
    sol_per_load = (_bytes(s2) - _bytes(s1)) / (2 * CHUNK)
    assert per_load <= sol_per_load, (per_load, sol_per_load)
    est = shared_memory(s2.info["grid"]["n_p"], 4 * CHUNK, 1)
    assert m2 <= est <= 2 * m2, (m2, est)
