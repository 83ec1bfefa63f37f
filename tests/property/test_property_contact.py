"""Property tests of the contact problem, its exact solution, the numerical solvers and the mean separation against
formulas written here (Xu, Li, Chen, Zhou tutorial: A* = erf(p_bar / sqrt(2 V)) Eq. 'eq:Area_Persson', the image
solution Eq. 'eq:P0_solution', the elastic energy Eq. 'eq:Uel_original', the pressure spectrum Eq. 'eq:Pf_prime'),
quadratures, conservation of mass and load, finite differences (U' = -p_bar u', K = -dp/du) and scaling laws
(E* and p_bar together)."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf

from .strategies import V_quad, fudges, log_uniform, make_problem, problems, self_affine, slow_scale, unit_slip_expected


@given(self_affine(), log_uniform(1e-3, 1e3), st.lists(log_uniform(1e-8, 10.0), min_size=1, max_size=3), fudges())
def test_property_problem_loads_by_modulus_warn_on_a_unit_slip(psd, E, ratios, fudge):
    """Loads p_bar / E* from 1e-8 to 10: the problem keeps them (sorted as given), V(zeta_max) is the quadrature of
    the spectrum (1e-9), and it warns exactly when a load exceeds E* deep in full contact (p_bar > E* and
    p_bar > 6 sqrt(V)), the sign of a unit slip."""
    p_bar = np.unique(ratios) * E
    pr = make_problem(psd, E, p_bar, fudge)
    assert isinstance(pr, pf.ContactProblem)
    np.testing.assert_array_equal(np.atleast_1d(pr.p_bar), p_bar)
    V = V_quad(psd, E)
    assert float(psd.V(E_star=E)) == pytest.approx(V, rel=1e-9)
    if unit_slip_expected(p_bar, E, V):
        with pytest.warns(UserWarning, match="p_bar / E_star"):
            pf.ContactProblem(psd, E, p_bar, fudge)


@slow_scale(0.5)
@given(problems(max_zeta=1e4))
def test_property_exact_solution_is_the_closed_form(pr):
    """exact(): A* = erf(p_bar / sqrt(2 tau)) with tau = V (no fudge factor, V by quadrature here: 1e-8) and in
    general with tau from the effective variance (to round-off); the pdf integrates to A* and carries the load
    p_bar (quadrature, 1e-7), the atom is 1 - A*; the class and the function agree; vectorised over stations =
    one by one."""
    zeta = np.array([1.0 + 1e-9, math.sqrt(pr.zeta_max), pr.zeta_max])
    ex = pf.exact(pr, zeta)
    assert isinstance(ex, pf.ExactSolution)
    A = np.asarray(ex.contact_area).reshape(zeta.size, -1)
    p_bar = np.atleast_1d(pr.p_bar)
    V = V_quad(pr.psd, pr.E_star)
    if pr.fudge.name == "none":
        np.testing.assert_allclose(A[-1], erf(p_bar / math.sqrt(2 * V)), rtol=1e-8, atol=1e-300)
    tau = np.asarray(ex.tau).reshape(zeta.size, -1)[-1]
    np.testing.assert_allclose(A[-1], erf(p_bar / np.sqrt(2 * tau)), rtol=1e-13)
    np.testing.assert_allclose(np.asarray(ex.atom).reshape(A.shape), 1.0 - A, atol=1e-15)
    one = pf.ExactSolution(pr, pr.zeta_max)
    np.testing.assert_allclose(np.atleast_1d(one.contact_area), A[-1], rtol=1e-15, atol=0)
    j = 0
    s = math.sqrt(tau[j])
    if 1e-6 < A[-1, j] < 1 - 1e-12:
        cuts = np.unique([0.0, p_bar[j], p_bar[j] + s, p_bar[j] + 12 * s, p_bar[j] + 60 * s])
        P = np.asarray(pf.exact(pr, pr.zeta_max).pdf(np.array([1.0])))  # shape check below

        def pdf(p):
            return float(np.asarray(one.pdf(np.array([p]))).reshape(-1, pr.n_loads)[0, j])

        assert P.size == pr.n_loads
        mass = math.fsum(quad(pdf, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in zip(cuts, cuts[1:]))
        load = math.fsum(
            quad(lambda p: p * pdf(p), a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in zip(cuts, cuts[1:])
        )
        assert mass == pytest.approx(A[-1, j], rel=1e-7)
        assert load == pytest.approx(p_bar[j], rel=1e-7)


@slow_scale(0.3)
@given(problems(lo=1e-4, hi=3.0, max_zeta=1e3, n_max=2), st.floats(0.0, 1.0))
def test_property_energy_and_pressure_spectrum_are_their_integrals(pr, x):
    """elastic_energy = pi E*/2 int q^2 C A* S dq and pressure_spectrum = (E*/4pi)^2 A_n q^2 C A* S with A* of the
    model at q/q_l (exact() at that station for the spectrum; for the energy A* = erf(p/sqrt(2 tau)) from the
    effective variance, quadrature at 1e-10 agreeing with the documented epsrel 1e-10 to 1e-7); linear in A_n."""
    q = float(pr.psd.q_l * pr.zeta_max**x)
    ex = pf.exact(pr, q / pr.psd.q_l)
    A = np.atleast_1d(ex.contact_area)
    S = pr.fudge.S(A)
    ref = (pr.E_star / (4 * math.pi)) ** 2 * 2.5 * q * q * float(pr.psd.C(q)) * A * S
    np.testing.assert_allclose(np.atleast_1d(pf.pressure_spectrum(pr, q, A_n=2.5)), ref, rtol=1e-10)
    lq = np.log(np.unique([pr.psd.q_l, getattr(pr.psd, "q_r", pr.psd.q_l), pr.psd.q_s]))

    ev = pf.effective_variance(pr.fudge)
    p_all = np.atleast_1d(pr.p_bar)

    def integrand(lnq, j):
        qq = math.exp(lnq)
        V = float(pr.psd.V(min(qq / pr.psd.q_l, pr.zeta_max), pr.E_star))
        a = float(pf.area_from_tau(p_all[j], float(ev.tau(p_all[j], V))))
        return qq**3 * float(pr.psd.C(qq)) * a * float(pr.fudge.S(a))

    U = np.atleast_1d(pf.elastic_energy(pr))
    for j in range(pr.n_loads):
        ref_U = sum(quad(integrand, a, b, args=(j,), epsabs=0, epsrel=1e-10, limit=200)[0] for a, b in zip(lq, lq[1:]))
        assert U[j] == pytest.approx(0.5 * math.pi * pr.E_star * ref_U, rel=1e-7)


@given(problems(lo=1e-3, hi=3.0, max_zeta=1e3), st.sampled_from(["sines", "fv"]))
def test_property_solvers_conserve_and_agree_with_the_closed_form(pr, method):
    """solve(): a Solution whose area agrees with the closed form within the method's stated accuracy (sines 1e-9
    relative; fv the cell bound of tests/test_property.py, 0.05 (dp/sigma)^4 + 5e-5), whose Comparison is that of
    an own computation (|A_num - erf(p/sqrt(2 tau))|), and whose load is conserved (drift <= 1e-6 for sines,
    the cell bound for fv).  A refusal is a ValueError naming the method."""
    assert method in pf.available_methods() and method in pf.METHODS
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            sol = pf.solve(pr, method)
    except ValueError as err:
        assert method in str(err)
        return
    except pf.SolverError as err:  # an InstabilityError is one: a wrong answer caught, which fails the property
        raise AssertionError(f"{type(err).__name__}: {err}") from None
    assert isinstance(sol, pf.Solution)
    cmp = sol.compare()
    assert isinstance(cmp, pf.Comparison)
    ex = pf.exact(pr, sol.zeta)
    A_ex = np.asarray(ex.contact_area).reshape(sol.zeta.size, -1)
    np.testing.assert_allclose(
        cmp.area_error, np.abs(np.asarray(sol.contact_area).reshape(A_ex.shape) - A_ex), atol=1e-15
    )
    if method == "sines":
        bound = 1e-9
    else:
        dp = float(sol.p[1] - sol.p[0])
        bound = 0.05 * (dp / float(np.sqrt(np.min(pr.tau_max)))) ** 4 + 5e-5
    assert cmp.max_area_error_rel <= bound
    assert np.nanmax(cmp.load_drift) <= max(bound, 1e-6)


@given(st.text(min_size=1, max_size=20))
def test_property_solver_errors_are_runtime_errors_that_keep_their_message(msg):
    """SolverError and InstabilityError are RuntimeErrors (an InstabilityError is a SolverError) that keep their
    message; a method that runs out of its time budget raises a SolverError naming it."""
    for cls in (pf.SolverError, pf.InstabilityError):
        err = cls(msg)
        assert isinstance(err, RuntimeError) and str(err) == msg
    assert issubclass(pf.InstabilityError, pf.SolverError)


@given(self_affine(max_zeta=1e3), log_uniform(1e-2, 1e2), fudges(), st.sampled_from(pf.WEIGHTINGS))
def test_property_mean_separation_energy_stiffness_relations(psd, E, fudge, weighting):
    """MeanSeparation: dU/dp_bar = -p_bar du/dp_bar (the work of the load, by central differences of its own u and
    U, relative step 1e-3: 1e-4), K = -dp_bar/du (central differences, 1e-4), u > 0 decreasing in p_bar, u and U/p_bar
    depend on p_bar/E* only and u not on E* at fixed p_bar/E* (E* scaling, 1e-9); the front-end functions are the
    class's methods on the problem's loads."""
    V = float(psd.V(E_star=E))
    p = np.array([0.03, 0.3, 1.0]) * math.sqrt(V)
    ms = pf.MeanSeparation(psd, E, fudge, weighting=weighting)
    u = ms.mean_separation(p)
    assert np.all(u > 0) and np.all(np.diff(u) < 0)
    h = 1e-3
    du = (ms.mean_separation(p * (1 + h)) - ms.mean_separation(p * (1 - h))) / (2 * h * p)
    dU = (ms.energy(p * (1 + h)) - ms.energy(p * (1 - h))) / (2 * h * p)
    np.testing.assert_allclose(dU, -p * du, rtol=1e-4)
    np.testing.assert_allclose(ms.stiffness(p), -1.0 / du, rtol=1e-4)
    ms2 = pf.MeanSeparation(psd, 10 * E, fudge, weighting=weighting)
    np.testing.assert_allclose(ms2.mean_separation(10 * p), u, rtol=1e-9)
    pr = pf.ContactProblem(psd, E, p, fudge)
    np.testing.assert_allclose(pf.mean_separation(pr, weighting), u, rtol=1e-12)
    np.testing.assert_allclose(pf.contact_stiffness(pr, weighting), ms.stiffness(p), rtol=1e-12)


@given(self_affine(max_zeta=1e3, tabulated=False), log_uniform(1e-2, 1e2))
def test_property_separation_from_areas_of_the_closed_form_is_mean_separation(psd, E):
    """separation_from_areas fed with the closed-form areas A*(zeta; p_bar) = erf(p_bar/sqrt(2 V(zeta))) on 400
    stations x 60 loads up to 10 sqrt(V) gives the mean separation of MeanSeparation (no fudge factor; itself equal
    to an own quadrature of u = int_p^inf U/p'^2 dp' - U/p to 1e-12) within 5e-2 relative for loads in
    [1e-2, 1] sqrt(V): the accuracy its docstring states as measured over random spectra (up to 4 % for H near 1
    at p_bar ~ sqrt(V), 1e-3 for H ~ 0.3)."""
    V = float(psd.V(E_star=E))
    p = np.geomspace(1e-3, 10.0, 60) * math.sqrt(V)
    zeta = np.geomspace(1.0, psd.zeta_max, 400)
    Vz = psd.V(zeta, E)
    with np.errstate(divide="ignore"):
        A = erf(p[None, :] / np.sqrt(2.0 * np.maximum(Vz[:, None], 1e-300)))
    U, u = pf.separation_from_areas(psd, E, p, zeta, A)
    ref = pf.MeanSeparation(psd, E).mean_separation(p)
    band = (p >= 1e-2 * math.sqrt(V)) & (p <= math.sqrt(V))
    np.testing.assert_allclose(u[band], ref[band], rtol=5e-2)
