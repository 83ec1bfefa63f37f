"""Random valid problems and invalid inputs shared by the property tests, and oracles written from the physics.

Valid problems (Xu, Li, Chen, Zhou tutorial notation): self-affine spectra with and without roll-off and their
log-log tabulations, H in [0.05, 1], q_s/q_l in [2, 1e6], q_l in [1e-3, 1e3], rms slope in [1e-3, 1]; moduli E* in
[1e-3, 1e3]; loads p_bar / sqrt(V) in [1e-8, 10] (the package warns below 1e-6 sqrt(V)-ish or near full contact
in some front ends: the tests that cross those ranges assert the warning); every fudge model (by name, as an
instance with a random gamma, and as a user callable); hardness laws.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
from hypothesis import strategies as st
from scipy.integrate import quad

import persson_fp as pf

FUDGE_NAMES = [None, "YP08", "WM17", "Xu24"]


def log_uniform(lo: float, hi: float) -> st.SearchStrategy[float]:
    """Floats spread evenly in log10 between ``lo`` and ``hi``."""
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda x: float(10.0**x))


@st.composite
def self_affine(draw, max_zeta: float = 1e6, rolloff: bool | None = None, tabulated: bool | None = None):
    """A self-affine spectrum (H in [0.05, 1], q_s/q_l up to ``max_zeta``), optionally as a log-log table."""
    H = draw(st.floats(0.05, 1.0))
    zeta_max = draw(log_uniform(2.0, max_zeta))
    with_roll = draw(st.booleans()) if rolloff is None else rolloff
    zeta_r = min(draw(log_uniform(1.0, 10.0)), zeta_max) if with_roll else 1.0
    q_l = draw(log_uniform(1e-3, 1e3))
    slope = draw(log_uniform(1e-3, 1.0))
    psd = pf.SelfAffinePSD.from_rms_slope(slope, H, q_l, zeta_r * q_l, zeta_max * q_l)
    if tabulated or (tabulated is None and draw(st.booleans())):
        q = np.geomspace(psd.q_l, psd.q_s, draw(st.integers(3, 40)))
        if with_roll and zeta_r > 1.0:
            q = np.unique(np.concatenate((q, [psd.q_r])))
        psd = pf.TabulatedPSD(q, psd.C(q))
    return psd


def fudges() -> st.SearchStrategy:
    """Every fudge model: a name, an instance with a random gamma, or a user callable S(A)."""
    return st.one_of(
        st.sampled_from(FUDGE_NAMES),
        st.floats(0.3, 1.0).map(pf.fudge.YangPersson),
        st.floats(0.4, 1.0).map(pf.fudge.WangMuser),
        st.floats(0.3, 1.0).map(pf.fudge.Xu24),
        st.floats(0.3, 1.0).map(lambda g: pf.fudge.CallableFudge(lambda A: g + (1.0 - g) * np.asarray(A) ** 2)),
    )


def unit_slip_expected(p_bar, E: float, V: float) -> bool:
    """The package warns (UserWarning) when a load exceeds the contact modulus deep in full contact:
    max p_bar / E* > 1 and max p_bar > 6 sqrt(V(zeta_max)), usually a unit slip between p_bar and E*."""
    return float(np.max(p_bar)) / E > 1.0 and float(np.max(p_bar)) > 6.0 * math.sqrt(V)


def make_problem(psd, E, p_bar, fudge=None, **kw):
    """ContactProblem(psd, E, p_bar, fudge), asserting that it warns exactly when :func:`unit_slip_expected`."""
    V = V_quad(psd, E)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        pr = pf.ContactProblem(psd, E, p_bar, fudge, **kw)
    slips = [w for w in caught if issubclass(w.category, UserWarning) and "p_bar / E_star" in str(w.message)]
    pm = float(np.max(p_bar))
    borderline = abs(pm / E - 1.0) < 1e-9 or abs(pm / (6.0 * math.sqrt(V)) - 1.0) < 1e-8  # V by quadrature
    assert borderline or bool(slips) == unit_slip_expected(p_bar, E, V), [str(w.message) for w in caught]
    return pr


@st.composite
def problems(draw, lo: float = 1e-8, hi: float = 10.0, n_max: int = 3, max_zeta: float = 1e6, fudge=None, per="V"):
    """A ContactProblem with 1..n_max distinct loads, p_bar/sqrt(V) (``per="V"``) or p_bar/E* (``per="E"``)
    log-uniform in [lo, hi]; the unit-slip warning asserted where expected."""
    psd = draw(self_affine(max_zeta=max_zeta))
    E = draw(log_uniform(1e-3, 1e3))
    ratios = np.unique(draw(st.lists(log_uniform(lo, hi), min_size=1, max_size=n_max)))
    model = draw(fudges()) if fudge is None else fudge
    p_bar = ratios * (math.sqrt(psd.V(E_star=E)) if per == "V" else E)
    return make_problem(psd, E, p_bar[0] if ratios.size == 1 else p_bar, model)


def V_quad(psd, E: float, zeta: float | None = None) -> float:
    """V(zeta) = pi/2 E*^2 int_{q_l}^{zeta q_l} q^3 C(q) dq (Eq. 'eq:V_equ') by adaptive quadrature in ln q,
    split at the knots of C; independent of the closed forms of the spectrum classes."""
    zeta = psd.zeta_max if zeta is None else zeta
    hi = math.log(zeta * psd.q_l)
    inner = list(psd.q) if isinstance(psd, pf.TabulatedPSD) else [psd.q_r]
    knots = np.log(np.concatenate(([psd.q_l], inner, [psd.q_s])))
    cuts = np.unique(np.clip(knots, math.log(psd.q_l), hi))
    total = sum(
        quad(lambda x: math.exp(4.0 * x) * float(psd.C(math.exp(x))), a, b, epsabs=0.0, epsrel=1e-11, limit=200)[0]
        for a, b in zip(cuts[:-1], cuts[1:])
    )
    return 0.5 * math.pi * E**2 * total


def moment_quad(psd, k: float, zeta: float | None = None) -> float:
    """2 pi int q^k q C(q) dq over [q_l, zeta q_l] (h_rms^2 for k = 0, slope^2 for k = 2) by quadrature."""
    zeta = psd.zeta_max if zeta is None else zeta
    hi = math.log(zeta * psd.q_l)
    inner = list(psd.q) if isinstance(psd, pf.TabulatedPSD) else [psd.q_r]
    knots = np.log(np.concatenate(([psd.q_l], inner, [psd.q_s])))
    cuts = np.unique(np.clip(knots, math.log(psd.q_l), hi))
    total = sum(
        quad(lambda x: math.exp((k + 2.0) * x) * float(psd.C(math.exp(x))), a, b, epsabs=0.0, epsrel=1e-11, limit=200)[
            0
        ]
        for a, b in zip(cuts[:-1], cuts[1:])
    )
    return 2.0 * math.pi * total


# Invalid inputs: each a value that no parameter of the kind named accepts.
NOT_A_NUMBER = [float("nan"), float("inf"), -float("inf"), "1.0", b"1", True, False, None, 1 + 2j, [1.0, 2.0], {}]
"""Refused by any real-number parameter."""
NOT_POSITIVE = [0.0, -1.0, -1e-300, -1e300, 0]
"""Refused by a parameter that must be > 0."""


def bad_positive() -> st.SearchStrategy:
    """Values a strictly positive real scalar parameter must refuse (with random negatives and non-numbers)."""
    return st.one_of(
        st.sampled_from(NOT_A_NUMBER + NOT_POSITIVE),
        st.floats(max_value=0.0, allow_nan=False),
        st.floats(allow_nan=True).filter(lambda x: not math.isfinite(x)),
        st.text(max_size=3),
        st.lists(st.floats(0.1, 1.0), min_size=2, max_size=3),
    )


def bad_array() -> st.SearchStrategy:
    """Arrays a real-valued array parameter must refuse: NaN/inf entries, strings, booleans, complex."""
    return st.one_of(
        st.sampled_from(
            [
                np.array([1.0, np.nan]),
                np.array([np.inf]),
                np.array(["a", "b"]),
                np.array([True, False]),
                np.array([1 + 1j]),
                "abc",
                None,
                [[1.0, 2.0], [3.0]],
            ]
        ),
    )


def slow_scale(scale: float, slow_only: bool = False):
    """Run a costly property test with ``scale`` times the slow group's example count (put above ``@given``);
    ``slow_only``: no sample in the default run."""

    def mark(test):
        test._slow_scale = scale
        test._slow_only = slow_only
        return test

    return mark
