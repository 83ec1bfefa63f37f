"""Walls and elastic responses are objects the problem carries and every method asks.

- A response that is not the elastic half-space -- here a solid whose effective modulus grows at long wavelengths,
  E_eff(q) = E (1 + a q_l / q), written in the test with V by adaptive quadrature -- plugs into
  ``ContactProblem.with_response`` and every method solves it unchanged: the contact area matches the image solution
  A* = erf(p_bar / sqrt(2 V)) (Xu et al. tutorial, Eq. 'eq:Area_Persson') with V from the spectrum's closed-form
  moments, V = (pi/2) E^2 (m3 + 2 a q_l m2 + a^2 q_l^2 m1) -- an oracle independent of the response's quadrature.
  What needs the stored elastic energy refuses it, naming the quantity.
- The walls (:mod:`persson_fp.problems.walls`): the far end of a power-law yield wall and its rate in V against a
  finite difference, the strip's load balance, the fudge factor's area two ways, what each wall makes of the mass it
  absorbs; the problem's refusals (``require_closed_form``, ``require_elastic``) name what leaves the closed forms.
- The hints of a method that does not solve a problem are generated from the registry: they name exactly the
  methods whose ``SUPPORTS`` hold the feature.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import persson_fp as pf
from persson_fp.problems import walls
from persson_fp.solvers.registry import EXTRAS, METHODS, get_solver, supporting
from persson_fp.theory.response import ElasticHalfSpace, ElasticResponse

_GL_X, _GL_W = np.polynomial.legendre.leggauss(64)


class LongWaveStiffened(ElasticResponse):
    """E_eff(q) = E (1 + a q_l / q): V and dV/dzeta from (pi/2) q^3 C(q) E_eff^2 by quadrature (no elastic energy);
    the inverse of V is the base class's bisection."""

    def __init__(self, E: float, a: float):
        self.E, self.a = E, a

    def _integrand(self, psd, q):
        return q**3 * np.asarray(psd.C(q)) * (1.0 + self.a * psd.q_l / q) ** 2

    def V(self, psd, zeta=None):
        """Gauss-Legendre in ln q (64 nodes a piece, split at the roll-off q_r): ~1e-15 relative on these spectra."""
        z = np.asarray(psd.zeta_max if zeta is None else zeta, dtype=float)
        hi = np.log(np.atleast_1d(z).ravel() * psd.q_l)
        lo = np.full_like(hi, np.log(psd.q_l))
        mid = np.clip(np.log(getattr(psd, "q_r", psd.q_l)), lo, hi)
        total = np.zeros_like(hi)
        for a, b in ((lo, mid), (mid, hi)):
            t = 0.5 * (b - a)[:, None] * _GL_X + 0.5 * (a + b)[:, None]
            q = np.exp(t)
            total += 0.5 * (b - a) * np.sum(_GL_W * q * self._integrand(psd, q), axis=1)
        return (0.5 * np.pi * self.E**2 * total).reshape(z.shape)

    def dV_dzeta(self, psd, zeta=None):
        q = np.asarray(psd.zeta_max if zeta is None else zeta, dtype=float) * psd.q_l
        return 0.5 * np.pi * self.E**2 * psd.q_l * q**3 * np.asarray(psd.C(q)) * (1.0 + self.a * psd.q_l / q) ** 2

    def dV_dzeta_unchecked(self, psd, z):
        return self.dV_dzeta(psd, z)


def last(x) -> float:
    """The value at the last station (and only load) of a result's array."""
    return float(np.ravel(x)[-1])


def V_oracle(psd, E, a, zeta=None):
    """(pi/2) E^2 int q^3 C (1 + a q_l/q)^2 dq from the spectrum's closed-form moments."""
    m = {k: float(psd.moment(k, zeta)) for k in (1.0, 2.0, 3.0)}
    return 0.5 * np.pi * E**2 * (m[3.0] + 2.0 * a * psd.q_l * m[2.0] + (a * psd.q_l) ** 2 * m[1.0])


problems = st.builds(
    lambda H, ratio: pf.ContactProblem.reference(H=H, p_bar_ratio=ratio),
    st.floats(0.2, 1.0),
    st.floats(0.05, 3.0),
)


@settings(max_examples=15, deadline=None)
@given(problems, st.floats(0.1, 10.0), st.floats(0.0, 2.0))
def test_a_new_response_plugs_into_the_closed_form_and_the_methods(pr, E, a):
    plugged = pr.with_response(LongWaveStiffened(E, a))
    V = V_oracle(pr.psd, E, a)
    assert plugged.V_max == pytest.approx(V, rel=1e-10)
    A_ref = math.erf(float(pr.p_bar[0]) / math.sqrt(2.0 * V))
    assert last(pf.exact(plugged).contact_area) == pytest.approx(A_ref, rel=1e-9, abs=1e-14)
    # sines sums the same image series (exact to its tol); chebyshev meets its tol (1e-8) on the area
    assert last(pf.solve(plugged, "sines").contact_area) == pytest.approx(A_ref, rel=1e-9, abs=1e-14)
    assert last(pf.solve(plugged, "chebyshev").contact_area) == pytest.approx(A_ref, abs=1e-7)


@pytest.mark.parametrize("method", ["fv", pytest.param("mol", marks=pytest.mark.slow)])
def test_a_new_response_reaches_the_front_fixed_engine(method):
    """fv and mol on a moving yield wall with the new response, against the same wall on a half-space with the same
    V(zeta) everywhere (a = 0: E_eff = E, the half-space of E*): the engines ask the problem, not E*."""
    h = pf.hardness.PowerLaw(sigma_1=0.04, n=0.2)
    base = pf.ContactProblem.reference(p_bar_ratio=0.5, hardness=h)
    plugged = base.with_response(LongWaveStiffened(1.0, 0.0))
    a = pf.solve(plugged, method)
    b = pf.solve(base, method)
    assert last(a.contact_area) == pytest.approx(last(b.contact_area), rel=1e-8)
    assert last(a.plastic_area) == pytest.approx(last(b.plastic_area), rel=1e-7)


@pytest.mark.parametrize(
    "front_end",
    [pf.mean_separation, pf.contact_stiffness, pf.gap_distribution, lambda pr: pf.contact_conductance(pr, 1.0)],
    ids=["mean_separation", "contact_stiffness", "gap_distribution", "contact_conductance"],
)
def test_a_response_without_elastic_energy_is_refused_by_name(front_end):
    pr = pf.ContactProblem.reference().with_response(LongWaveStiffened(1.0, 0.5))
    with pytest.raises(ValueError, match="elastic energy|half-space"):
        front_end(pr)


@pytest.mark.parametrize("bad", [None, "x", 1.0, ElasticHalfSpace, object()])
def test_with_response_refuses_what_is_not_a_response(bad):
    with pytest.raises(ValueError, match="response"):
        pf.ContactProblem.reference().with_response(bad)


def test_with_response_refuses_a_response_without_a_finite_V():
    class Broken(LongWaveStiffened):
        def V(self, psd, zeta=None):
            return np.full(np.shape(psd.zeta_max if zeta is None else zeta), np.nan)

    with pytest.raises(ValueError, match="V\\(zeta_max\\)"):
        pf.ContactProblem.reference().with_response(Broken(1.0, 0.0))


def test_the_half_space_response_changes_nothing():
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=[0.3, 1.0])
    same = pr.with_response(ElasticHalfSpace(pr.E_star))
    assert same.V_max == pr.V_max and np.array_equal(same.tau_max, pr.tau_max)
    assert repr(same) == repr(pr)
    assert np.array_equal(pf.solve(same, "fv").contact_area, pf.solve(pr, "fv").contact_area)


# -- walls ----------------------------------------------------------------------------------------------------------
hardness = st.one_of(
    st.none(),
    st.floats(0.06, 1.0),
    st.builds(lambda s1, n: pf.hardness.PowerLaw(sigma_1=s1, n=n), st.floats(0.06, 1.0), st.floats(0.01, 0.5)),
)


@settings(max_examples=30, deadline=None)
@given(hardness)
def test_the_problem_carries_its_walls(h):
    pr = pf.ContactProblem.reference(hardness=h)
    low, up = pr.walls
    assert isinstance(low, walls.AbsorbingWall) and float(low.sigma(3.0)) == 0.0
    assert up is pr.upper_wall
    assert np.array_equal(pr.conserved_load, pr.p_bar)  # the load balance (eq:Load_equilibrium) with any wall
    zeta = np.geomspace(1.0, pr.zeta_max, 7)
    sigma = np.inf if h is None else (h if isinstance(h, float) else h.sigma_1 * zeta**h.n)
    assert np.allclose(pr.sigma_Y(zeta), sigma, rtol=1e-14)
    moving = isinstance(h, pf.hardness.PowerLaw)
    assert pr.moving_wall == moving and pr.has_closed_form == (not moving)
    assert pr.features == ({"moving_wall"} if moving else {"hardness"} if h is not None else set())
    absorbed = np.array([0.1, 0.2])
    if h is None:  # an open end: what reaches the cut is a loss, not an area
        assert up.plastic_area(absorbed) is None and np.array_equal(up.lost_mass(absorbed), absorbed)
    else:  # a yield wall: what it absorbs is the plastic area, nothing is lost
        assert np.array_equal(up.plastic_area(absorbed), absorbed) and not np.any(up.lost_mass(absorbed))
    if moving:
        with pytest.raises(ValueError, match="scale-dependent hardness"):
            pr.require_closed_form()
    else:
        pr.require_closed_form()  # the image or the strip solution
    if h is not None:
        with pytest.raises(ValueError, match="gap physics is the elastic theory's: a problem with a hardness"):
            pr.require_elastic("the gap physics")


@settings(max_examples=20, deadline=None)
@given(st.floats(0.06, 1.0), st.floats(0.01, 0.5), st.floats(0.05, 0.95))
def test_a_moving_wall_in_the_clock_V(s1, n, frac):
    """s(V) = sigma_1 zeta(V)^n and ds/dV against a central difference of s along the spectrum's V."""
    pr = pf.ContactProblem.reference(hardness=pf.hardness.PowerLaw(sigma_1=s1, n=n))
    zeta = pr.zeta_max**frac
    V = float(pr.V(zeta))
    s, sV = pr.upper_wall.front(pr, np.array([V]))
    assert float(s[0]) == pytest.approx(s1 * zeta**n, rel=1e-10)
    dz = 1e-5 * zeta
    fd = s1 * ((zeta + dz) ** n - (zeta - dz) ** n) / float(pr.V(zeta + dz) - pr.V(zeta - dz))
    assert float(sV[0]) == pytest.approx(fd, rel=1e-6)


@settings(max_examples=30, deadline=None)
@given(st.floats(0.1, 2.0), st.integers(3, 12), st.integers(0, 2**31 - 1))
def test_the_strip_areas_asked_of_a_yield_wall(sigma, n, seed):
    """A_pl from the load balance F_el + sigma A_pl = p_bar, and the area S sees, written two ways."""
    rng = np.random.default_rng(seed)
    wall = walls.upper_wall(sigma)
    p = np.sort(rng.uniform(0.0, sigma, n))
    w = rng.uniform(0.0, 1.0 / n, n)
    P = rng.uniform(0.0, 1.0, (2, n))
    p_bar = rng.uniform(0.0, 0.9 * sigma, 2)
    F_el = P @ (w * p)
    assert np.allclose(wall.plastic_from_load(p_bar, F_el), np.maximum((p_bar - F_el) / sigma, 0.0), rtol=1e-14)
    wA, a0 = wall.fudge_area_weights(w, p, p_bar)
    both = np.array([wall.contact_for_fudge(P[j], w, p, p_bar[j]) for j in range(2)])
    assert np.allclose(P @ wA + a0, both, rtol=1e-12, atol=1e-15)
    open_end = walls.upper_wall(None)
    assert open_end.plastic_from_load(p_bar, F_el) is None
    assert np.allclose(open_end.contact_for_fudge(P, w, p, p_bar), P @ w)


@pytest.mark.parametrize("bad", [0.0, -1.0, np.nan, np.inf, "x", True])
def test_a_bad_hardness_is_refused_by_the_wall(bad):
    with pytest.raises(ValueError, match="hardness"):
        pf.ContactProblem.reference(hardness=bad)


def test_a_general_problem_is_refused_by_name():
    ref = pf.ContactProblem.reference()
    pr = pf.FokkerPlanckProblem(ref.psd, p_bar=ref.p_bar[0], B1=lambda p, z: 0.0 * p)
    assert pr.features == {"general"}
    assert pr.conserved_load is None  # a drift moves the load: the solver's first-moment law is the reference
    with pytest.raises(ValueError, match="general Fokker-Planck coefficients"):
        pr.require_closed_form()
    with pytest.raises(ValueError, match="general coefficients.*use a ContactProblem"):
        pr.require_elastic("the gap physics")


# -- hints from the registry ----------------------------------------------------------------------------------------
@pytest.mark.parametrize("feature", ["hardness", "moving_wall", "general"])
def test_hints_name_exactly_the_methods_that_support_a_feature(feature):
    expected = [name for name in METHODS if name not in EXTRAS and feature in get_solver(name).SUPPORTS]
    got = supporting(feature)
    assert [g.split("'")[1] for g in got] == expected


@settings(max_examples=15, deadline=None)
@given(hardness, st.sampled_from([None, "YP08", "WM17", "Xu24"]), st.floats(0.1, 0.55))
def test_the_elastic_counterpart_drops_the_wall_and_keeps_the_rest(h, fudge, ratio):
    """The purely elastic problem of the same surface, response, loads and fudge: its tau(V) is the open map of the
    fudge factor (Xu et al. tutorial, Eq. 'eq:new_B2'), the same as a problem built without a hardness."""
    pr = pf.ContactProblem.reference(p_bar_ratio=[ratio, 2 * ratio], fudge=fudge, hardness=h)
    el = pr.elastic_counterpart()
    plain = pf.ContactProblem.reference(p_bar_ratio=[ratio, 2 * ratio], fudge=fudge)
    assert isinstance(el.upper_wall, walls.OpenEnd) and el.features == frozenset()
    assert el.response == pr.response and np.array_equal(el.p_bar, pr.p_bar) and el.fudge.name == pr.fudge.name
    V = np.geomspace(1e-6, 1.0, 5) * plain.V_max
    np.testing.assert_array_equal(el.tau_of_V(V), plain.tau_of_V(V))
    stiff = pr.with_response(LongWaveStiffened(1.0, 0.3)).elastic_counterpart()
    assert isinstance(stiff.response, LongWaveStiffened) and stiff.V_max == pytest.approx(V_oracle(pr.psd, 1.0, 0.3))
