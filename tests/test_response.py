"""The solid's elastic response (:mod:`persson_fp.theory.response`).

- A ratchet: the theory and result modules ask a response for V, its derivative, its inverse and the elastic
  energy; no call hands them a scalar E* (a frequency- or wavevector-dependent modulus could not plug in).
- :class:`ElasticHalfSpace` against the physics written here: V(zeta) = (pi/2) E*^2 int_{q_l}^{zeta q_l} q^3 C dq by
  adaptive quadrature, dV/dzeta by a central difference, the inverse, the scaling V ~ E*^2, the compliance
  2/(E* q) and the complete-contact energy (pi/2) E* int q^2 C dq.
- Bad E* raises ValueError naming ``E_star``; a response without stored elastic energy raises ValueError naming
  the quantity asked.
"""

from __future__ import annotations

import ast
import math
import pathlib
import pickle

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import persson_fp as pf
from persson_fp.theory.response import ElasticHalfSpace, ElasticResponse

ROOT = pathlib.Path(__file__).resolve().parents[1]
PKG = ROOT / "src" / "persson_fp"
RATCHET_FILES = {
    "theory": ("separation", "resolved", "gaps", "leakage", "adhesion"),
    "results": ("energy", "interface"),
}
"""Modules (and their folder today) that must ask a response; they are looked for in ``analysis/`` too."""
SPECTRUM_CALLS = {"V", "dV_dzeta", "zeta_of_V", "zeta_of_V_unchecked", "dV_dzeta_unchecked", "elastic_energy_complete"}
"""Attribute calls that take the elastic modulus when called on a spectrum."""


def _ratchet_paths() -> list[pathlib.Path]:
    paths = []
    for folder, names in RATCHET_FILES.items():
        for name in names:
            paths.extend(p for f in (folder, "analysis") for p in (PKG / f).glob(f"**/{name}.py"))
    return sorted(set(paths))


def scalar_modulus_calls(source: str) -> list[tuple[int, str]]:
    """(line, call text) of every call ``x.V(...)`` (and kin) with an argument whose text mentions ``E_star``."""
    hits = []
    for node in ast.walk(ast.parse(source)):
        if not (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)):
            continue
        if node.func.attr not in SPECTRUM_CALLS:
            continue
        args = [*node.args, *(k.value for k in node.keywords)]
        if any("E_star" in (ast.get_source_segment(source, a) or "") for a in args) or any(
            k.arg == "E_star" for k in node.keywords
        ):
            hits.append((node.lineno, ast.get_source_segment(source, node)))
    return hits


def test_ratchet_finds_the_modules():
    names = {p.stem for p in _ratchet_paths()}
    assert names == {n for group in RATCHET_FILES.values() for n in group}, names


ENGINE_FOLDERS = ("solvers", "problems", "analysis")
"""Folders where nothing hands E* to the spectrum either: the methods, the problem and its walls, the analytic front
ends ask the problem's response (``problem.response``, ``problem.V_kernels``)."""


def test_nothing_in_the_methods_hands_a_scalar_modulus_to_the_spectrum():
    paths = [p for f in ENGINE_FOLDERS for p in sorted((PKG / f).rglob("*.py"))]
    hits = {str(p.relative_to(ROOT)): scalar_modulus_calls(p.read_text()) for p in paths}
    hits = {k: v for k, v in hits.items() if v}
    assert sum(len(v) for v in hits.values()) == 0, f"calls handing E_star to V and kin (ask a response): {hits}"


def test_no_scalar_modulus_handed_to_the_spectrum():
    hits = {str(p.relative_to(ROOT)): scalar_modulus_calls(p.read_text()) for p in _ratchet_paths()}
    hits = {k: v for k, v in hits.items() if v}
    assert sum(len(v) for v in hits.values()) == 0, f"calls handing E_star to V and kin (ask a response): {hits}"


def test_ratchet_sees_one():
    src = "a = psd.V(z, self.E_star)\nb = psd.elastic_energy_complete(E_star=E)\nc = r.V(psd, z)\nd = psd.h2(E_star)\n"
    assert [h[0] for h in scalar_modulus_calls(src)] == [1, 2]


# -- the half-space against the physics ------------------------------------------------------------------------
spectra = st.builds(
    lambda H, q_l, r, s, slope: pf.SelfAffinePSD.from_rms_slope(slope, H, q_l, q_l * r, q_l * r * s),
    H=st.floats(0.1, 0.95),
    q_l=st.floats(1e-2, 1e2),
    r=st.floats(1.0, 8.0),
    s=st.floats(4.0, 1e3),
    slope=st.floats(0.05, 2.0),
)
moduli = st.floats(1e-3, 1e4)


def V_oracle(psd, zeta, E):
    """(pi/2) E*^2 int_{q_l}^{zeta q_l} q^3 C(q) dq, adaptive quadrature in ln q split at the roll-off."""
    lo, hi = math.log(psd.q_l), math.log(zeta * psd.q_l)
    pts = [math.log(psd.q_r)] if lo < math.log(psd.q_r) < hi else None
    val, _ = quad(lambda t: math.exp(4 * t) * float(psd.C(math.exp(t))), lo, hi, points=pts, epsrel=1e-12, limit=200)
    return 0.5 * math.pi * E * E * val


@settings(max_examples=25, deadline=None)
@given(psd=spectra, E=moduli, x=st.floats(0.0, 1.0))
def test_V_is_the_integral_of_the_spectrum(psd, E, x):
    r = ElasticHalfSpace(E)
    zeta = psd.zeta_max**x
    V = float(r.V(psd, zeta))
    assert V == float(psd.V(zeta, E))  # bit for bit the spectrum's closed form
    # the upper limit zeta q_l is rounded (relative eps) by both sides: V is known to dV/dzeta zeta eps at best
    # (what dominates near zeta = 1, where V itself vanishes)
    limit = 8.0 * np.finfo(float).eps * zeta * float(r.dV_dzeta(psd, zeta))
    assert V == pytest.approx(V_oracle(psd, zeta, E), rel=1e-8, abs=limit)
    assert float(r.V(psd)) == pytest.approx(V_oracle(psd, psd.zeta_max, E), rel=1e-8)
    # V ~ E*^2
    assert float(ElasticHalfSpace(3.0 * E).V(psd, zeta)) == pytest.approx(9.0 * V, rel=1e-12, abs=0.0)
    # the inverse
    if 0.0 < x < 1.0:
        assert float(r.zeta_of_V(psd, V)) == pytest.approx(zeta, rel=1e-9)
        assert float(r.zeta_of_V_unchecked(psd, np.array(V))) == pytest.approx(zeta, rel=1e-9)


@settings(max_examples=25, deadline=None)
@given(psd=spectra, E=moduli, x=st.floats(0.05, 0.95))
def test_dV_dzeta_is_the_slope_of_V(psd, E, x):
    r = ElasticHalfSpace(E)
    zeta = psd.zeta_max**x
    if abs(zeta * psd.q_l / psd.q_r - 1.0) < 1e-3:  # the roll-off's kink: no central difference across it
        return
    h = 1e-5 * zeta
    fd = (float(r.V(psd, zeta + h)) - float(r.V(psd, zeta - h))) / (2.0 * h)
    d = float(r.dV_dzeta(psd, zeta))
    assert d == float(psd.dV_dzeta(zeta, E)) == float(r.dV_dzeta(psd, np.array([zeta]))[0])  # bit for bit
    assert d == pytest.approx(fd, rel=1e-6)
    assert float(r.dV_dzeta_unchecked(psd, zeta)) == pytest.approx(d, rel=1e-14)


@settings(max_examples=15, deadline=None)
@given(psd=spectra, E=moduli)
def test_energy_side_of_the_half_space(psd, E):
    r = ElasticHalfSpace(E)
    q = np.geomspace(psd.q_l, psd.q_s, 5)
    assert np.allclose(r.compliance(q), 2.0 / (E * q), rtol=1e-15, atol=0.0)
    assert r.effective_modulus(q) == E
    lo, hi = math.log(psd.q_l), math.log(psd.q_s)
    val, _ = quad(lambda t: math.exp(3 * t) * float(psd.C(math.exp(t))), lo, hi, points=[math.log(psd.q_r)])
    assert float(r.elastic_energy_complete(psd)) == pytest.approx(0.5 * math.pi * E * val, rel=1e-8)


def test_the_base_inverse_bisects_V():
    """A response that defines only V and dV/dzeta gets an inverse by bisection (here: the half-space's V)."""

    class OnlyV(ElasticResponse):
        def V(self, psd, zeta=None):
            return ElasticHalfSpace(2.0).V(psd, zeta)

        def dV_dzeta(self, psd, zeta=None):
            return ElasticHalfSpace(2.0).dV_dzeta(psd, zeta)

    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1.0, 4.0, 400.0)
    z = np.array([1.0, 1.5, 4.0, 37.0, 400.0])
    V = np.asarray(OnlyV().V(psd, z))
    assert np.allclose(OnlyV().zeta_of_V(psd, V), z, rtol=1e-12, atol=0.0)
    assert OnlyV().zeta_of_V(psd, np.array([-1.0, 2.0 * V[-1]])).tolist() == [1.0, 400.0]


# -- values, refusals ------------------------------------------------------------------------------------------
def test_value_semantics():
    r = ElasticHalfSpace(2.5)
    assert r.E_star == 2.5 and repr(r) == "ElasticHalfSpace(E_star=2.5)"
    assert r == ElasticHalfSpace(np.float64(2.5)) and hash(r) == hash(ElasticHalfSpace(2.5))
    assert r != ElasticHalfSpace(2.0) and r != 2.5
    assert pickle.loads(pickle.dumps(r)) == r
    with pytest.raises(AttributeError):
        r.E_star = 1.0


def test_problem_owns_a_half_space():
    problem = pf.ContactProblem.reference()
    assert problem.response == ElasticHalfSpace(problem.E_star)
    assert problem.with_loads(0.1).response == problem.response
    assert float(problem.V()) == float(problem.response.V(problem.psd))


bad_moduli = st.one_of(
    st.sampled_from([math.nan, math.inf, -math.inf, 0.0, -0.0, True, False, None, "1.0", "E", [1.0], 1j]),
    st.floats(max_value=0.0, allow_nan=False),
    st.integers(max_value=0),
)


@settings(max_examples=30, deadline=None)
@given(E=bad_moduli)
def test_bad_modulus_is_refused(E):
    with pytest.raises(ValueError, match="E_star"):
        ElasticHalfSpace(E)


def test_a_response_without_energy_names_the_quantity():
    """A response that defines only V and dV/dzeta (sliding on a viscoelastic solid) has no elastic energy: asking
    for it, as the mean separation does, raises ValueError naming what needed it."""

    class Sliding(ElasticResponse):
        def V(self, psd, zeta=None):
            return ElasticHalfSpace(1.0).V(psd, zeta)

        def dV_dzeta(self, psd, zeta=None):
            return ElasticHalfSpace(1.0).dV_dzeta(psd, zeta)

    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1.0, 4.0, 400.0)
    r = Sliding()
    assert float(r.V(psd)) > 0
    with pytest.raises(ValueError, match=r"elastic energy is not defined.*needed for the mean separation"):
        r.effective_modulus(np.array([1.0, 2.0]), needed_for="the mean separation")
    with pytest.raises(ValueError, match=r"elastic energy is not defined.*needed for the elastic energy"):
        r.compliance(2.0)
    with pytest.raises(ValueError, match=r"elastic energy is not defined.*Persson-Tosatti"):
        r.elastic_energy_complete(psd, needed_for="the Persson-Tosatti stickiness")
