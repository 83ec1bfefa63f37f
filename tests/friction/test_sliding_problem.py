"""The sliding contact problem: its V against the half-space's, its closed form against pf.rubber_friction's P(q),
the numerical methods against the closed form."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf
from persson_fp.theory.sliding import SlidingViscoelastic

ve = pf.viscoelastic


def test_elastic_sliding_V_is_the_half_space_V(road):
    E, nu = 3e6, 0.3
    resp = SlidingViscoelastic(ve.Zener(E, E, 1e-3, nu=nu), velocity=2.0)
    z = np.array([1.001, 1.7, 10.0, 123.4, 1e4, road.zeta_max])
    E_star = E / (1 - nu**2)
    np.testing.assert_allclose(resp.V(road, z), road.V(z, E_star), rtol=1e-12)
    np.testing.assert_allclose(resp.dV_dzeta(road, z), road.dV_dzeta(z, E_star), rtol=1e-12)
    pr = pf.sliding_contact(road, ve.Zener(E, E, 1e-3, nu=nu), [1e5, 3e5], 2.0)
    ref = pf.ContactProblem(road, E_star, [1e5, 3e5])
    np.testing.assert_allclose(pf.exact(pr).contact_area, pf.exact(ref).contact_area, rtol=1e-12)
    assert pr.E_star == pytest.approx(E_star, rel=1e-12)


def test_sliding_V_against_quadrature(road, zener):
    v = 0.01
    resp = SlidingViscoelastic(zener, v)

    def phi(w):
        x = w * 1e-4
        return 2 * np.pi * (3e9**2 - (3e9**2 - 3e6**2) / np.sqrt(1 + x * x))

    for z in (5.0, 40.0, 3e3):
        ref = quad(lambda q: 0.25 * q**3 * road.C(q) * phi(q * v) / 0.75**2, road.q_l, z * road.q_l,
                   points=[road.q_r] if z * road.q_l > road.q_r else None, limit=400, epsrel=1e-11)[0]  # fmt: skip
        assert float(resp.V(road, z)) == pytest.approx(ref, rel=2e-6)  # the angular table's interpolation (2e-6)


def test_exact_contact_area_is_rubber_frictions_P(road, zener):
    v = 0.03
    res = pf.rubber_friction(road, zener, 2e5, v, fudge=None)
    pr = pf.sliding_contact(road, zener, 2e5, v)
    # the sliding problem's closed form A*(zeta) = erf(sigma0 / sqrt(2 V(zeta; v))) at the friction result's q
    zeta = res.q[1:] / road.q_l
    A = erf(2e5 / np.sqrt(2 * pr.V(np.clip(zeta, 1.0, road.zeta_max))))
    np.testing.assert_allclose(res.P[1:], A, rtol=1e-6)
    assert float(res.contact_area) == pytest.approx(float(np.ravel(pf.exact(pr).contact_area)[-1]), rel=1e-6)


@pytest.mark.parametrize("method", ["sines", "fv", "mol"])
def test_numerical_methods_on_the_sliding_problem(road, zener, method):
    pr = pf.sliding_contact(road, zener, [1e5, 3e5], 1e-7)  # near the rubbery plateau: areas of a few per cent
    sol = pf.solve(pr, method=method, tol=1e-6)
    ex = pf.exact(pr)
    A_num = np.ravel(sol.contact_area)
    A_ex = np.ravel(ex.contact_area)
    assert np.all(A_ex > 0.01)
    # each method meets the requested L1 accuracy against the closed form, and reports that error
    L1 = np.ravel(sol.error_estimate["L1"])
    assert sol.error_estimate["kind"].startswith("true error") and np.all(L1 <= 1e-6)
    assert np.all(np.abs(A_num - A_ex) <= 1e-6)


def test_fudge_in_the_loop_is_another_quantity(road, zener):
    plain = pf.exact(pf.sliding_contact(road, zener, 2e5, 0.01))
    looped = pf.solve(pf.sliding_contact(road, zener, 2e5, 0.01, fudge="YP08"), method="fv")
    res = pf.rubber_friction(road, zener, 2e5, 0.01, fudge="YP08")
    # S < 1 slows the diffusion: a larger area than Persson's plain P(q1), which rubber_friction returns
    assert np.ravel(looped.contact_area)[-1] > 1.05 * float(res.contact_area)
    assert float(np.ravel(plain.contact_area)[-1]) == pytest.approx(float(res.contact_area), rel=1e-6)


def test_energy_side_refuses_by_name(road, zener):
    pr = pf.sliding_contact(road, zener, 2e5, 0.01)
    with pytest.raises(ValueError, match="elastic energy"):
        pf.mean_separation(pr)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(velocity=-1.0), "velocity"),
        (dict(sigma0=-1.0), "p_bar"),
        (dict(material="rubber"), "material"),
        (dict(modulus_in_G="x"), "modulus_in_G"),
        (dict(temperature=[1.0, 2.0]), "temperature"),
    ],
)
def test_sliding_contact_refuses_bad_input(road, zener, kwargs, name):
    args = dict(psd=road, material=zener, sigma0=2e5, velocity=0.01)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        pf.sliding_contact(**args)
