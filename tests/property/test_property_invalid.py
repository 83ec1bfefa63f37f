"""Invalid inputs, drawn at random per parameter (NaN, inf, negative, zero, huge, wrong type, wrong shape, bools,
strings, file descriptors, empty files), give exactly one ValueError whose message names the parameter -- never
a TypeError, an AttributeError, a NaN or a silent number.  Each entry is (public callable, parameter, a call
with the bad value in that parameter's place, the name the message must carry, the values that parameter
refuses); the contents of the public constants are checked at the end."""

from __future__ import annotations

import os
import re
import tempfile

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import persson_fp as pf

from .strategies import NOT_A_NUMBER, NOT_POSITIVE, slow_scale

PSD = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 1e3)
PR = pf.ContactProblem(PSD, 1.0, 0.05)
HUGE = [1e308, 1e200]
NUMBER = NOT_A_NUMBER + NOT_POSITIVE
ELEMENTS = [x for x in NOT_A_NUMBER if not isinstance(x, list)] + [[1.0, float("nan")], [1.0, "x"]]
"""Refused by an array parameter (a list of numbers is an array)."""
ARRAY = ELEMENTS + NOT_POSITIVE
NOT_AN_OBJECT = [1.0, float("nan"), "x", True, None, [1.0, 2.0], {}]
PATHS = [3, True, None, 1.5, "/nonexistent/file.txt", "/"]

CASES = [
    # (name, call, message must name, bad values)
    ("image_pdf p_bar", lambda b: pf.image_pdf(1.0, b, 1.0), "p_bar", ARRAY + HUGE),
    ("image_pdf tau", lambda b: pf.image_pdf(1.0, 1.0, b), "tau", ARRAY + [1e308]),
    ("image_pdf p", lambda b: pf.image_pdf(b, 1.0, 1.0), "p", ELEMENTS + HUGE),
    ("area_from_tau p_bar", lambda b: pf.area_from_tau(b, 1.0), "p_bar", ARRAY + HUGE),
    ("area_from_tau tau", lambda b: pf.area_from_tau(1.0, b), "tau", ELEMENTS + [-1.0, 1e308]),
    ("variance_closed_form p_bar", lambda b: pf.variance_closed_form(b, 1.0), "p_bar", ARRAY + HUGE),
    ("variance_closed_form tau", lambda b: pf.variance_closed_form(1.0, b), "tau", ELEMENTS + [-1.0, 1e308]),
    ("EffectiveVariance fudge", lambda b: pf.EffectiveVariance(b), "fudge", NOT_AN_OBJECT),
    ("effective_variance fudge", lambda b: pf.effective_variance(b), "fudge", NOT_AN_OBJECT),
    ("fudge.YangPersson gamma", lambda b: pf.fudge.YangPersson(b), "gamma", NUMBER + HUGE),
    ("fudge.WangMuser gamma", lambda b: pf.fudge.WangMuser(b), "gamma", NUMBER + HUGE),
    ("fudge.Xu24 gamma", lambda b: pf.fudge.Xu24(b), "gamma", NUMBER + HUGE),
    ("fudge.FudgeFactor.S A", lambda b: pf.fudge.YangPersson().S(b), "A", ELEMENTS),
    ("fudge.Xu24.area V", lambda b: pf.fudge.Xu24().area(0.1, b), "V", ELEMENTS + [-1.0]),
    (
        "EffectiveVariance.tau p_bar",
        lambda b: pf.EffectiveVariance(pf.fudge.YangPersson()).tau(b, 1.0),
        "p_bar",
        ARRAY,
    ),
    ("fudge.resolve fudge", lambda b: pf.fudge.resolve(b), "fudge", ["x", "YP09", 1.0, True, [1.0]]),
    ("fudge.CallableFudge fn", lambda b: pf.fudge.CallableFudge(b), "fudge", NOT_AN_OBJECT),
    (
        "fudge.NoFudge check",
        lambda b: pf.fudge.CallableFudge(lambda A: b + 0 * np.asarray(A)),
        "fudge",
        [-1.0, 0.0, float("nan"), 1e300],
    ),
    ("hardness.ConstantHardness sigma", lambda b: pf.hardness.ConstantHardness(b), "hardness", NUMBER),
    ("hardness.PowerLaw sigma_1", lambda b: pf.hardness.PowerLaw(b, 0.5), "sigma_1", NUMBER),
    ("hardness.PowerLaw n", lambda b: pf.hardness.PowerLaw(1.0, b), "n", NOT_A_NUMBER + [-1.0, 3.0] + HUGE),
    ("hardness.CallableHardness fun", lambda b: pf.hardness.CallableHardness(b), "hardness", NOT_AN_OBJECT),
    (
        "hardness.CallableHardness derivative",
        lambda b: pf.hardness.CallableHardness(np.sqrt, b),
        "derivative",
        [1.0, "x", True, [1.0]],
    ),
    (
        "hardness.resolve hardness",
        lambda b: pf.hardness.resolve(b),
        "hardness",
        [float("nan"), -1.0, 0.0, "x", True, [1.0, 2.0]],
    ),
    ("hardness.Hardness check", lambda b: pf.hardness.ConstantHardness(1.0).check(10.0, b), "p_bar", [1.0, 2.0, 1e300]),
    ("abel_factor H", lambda b: pf.abel_factor(b), "H", ELEMENTS + [-0.5, -1.0] + HUGE),
    ("abel_forward psd", lambda b: pf.abel_forward(b, [1.0]), "psd", NOT_AN_OBJECT),
    ("abel_forward q", lambda b: pf.abel_forward(PSD, b), "q", ELEMENTS + NOT_POSITIVE),
    (
        "abel_inverse n_nodes",
        lambda b: pf.abel_inverse([1.0, 2.0, 3.0], [1.0, 0.5, 0.2], n_nodes=b),
        "n_nodes",
        NOT_A_NUMBER + [10, 49, 10**9, 1e308],
    ),
    ("abel_inverse C1D", lambda b: pf.abel_inverse([1.0, 2.0, 3.0], b), "C1D", NOT_A_NUMBER + [[1.0, -1.0, 0.5]]),
    ("SelfAffinePSD C0", lambda b: pf.SelfAffinePSD(b, 0.8, 1.0, 2.0, 10.0), "C0", NUMBER),
    ("SelfAffinePSD.C q", lambda b: PSD.C(b), "q", ELEMENTS + [-1.0, -1e-300]),
    ("TabulatedPSD C", lambda b: pf.TabulatedPSD([1.0, 2.0], b), "C", ELEMENTS + [[1.0, -1.0], [1.0]]),
    ("ContactProblem E_star", lambda b: pf.ContactProblem(PSD, b, 0.05), "E_star", NUMBER + HUGE),
    ("ContactProblem p_bar", lambda b: pf.ContactProblem(PSD, 1.0, b), "p_bar", ARRAY + HUGE),
    ("FokkerPlanckProblem p_bar", lambda b: pf.FokkerPlanckProblem(PSD, 1.0, b), "p_bar", ARRAY + HUGE),
    ("exact problem", lambda b: pf.exact(b), "problem", NOT_AN_OBJECT),
    (
        "ExactSolution zeta",
        lambda b: pf.ExactSolution(PR, b),
        "zeta",
        [x for x in ELEMENTS if x is not None] + [0.5, -1.0, 1e9],
    ),
    ("pressure_spectrum A_n", lambda b: pf.pressure_spectrum(PR, 2.0, b), "A_n", NUMBER),
    ("elastic_energy epsrel", lambda b: pf.elastic_energy(PR, None, b), "epsrel", NUMBER + [1.0]),
    ("solve method", lambda b: pf.solve(PR, b), "method", ["x", 1.0, True, None]),
    ("solve tol", lambda b: pf.solve(PR, "sines", tol=b), "tol", [x for x in NUMBER if x is not None]),
    ("MeanSeparation E_star", lambda b: pf.MeanSeparation(PSD, b), "E_star", NUMBER),
    ("MeanSeparation weighting", lambda b: pf.MeanSeparation(PSD, 1.0, weighting=b), "weighting", ["x", 1.0, None]),
    ("mean_separation weighting", lambda b: pf.mean_separation(PR, b), "weighting", ["x", 1.0, None]),
    ("contact_stiffness weighting", lambda b: pf.contact_stiffness(PR, b), "weighting", ["x", 1.0, None]),
    (
        "separation_from_areas A",
        lambda b: pf.separation_from_areas(PSD, 1.0, [0.1, 0.2, 0.3], [1.0, 2.0], b),
        "A",
        NOT_A_NUMBER + [np.ones((3, 2)), 2 * np.ones((2, 3))],
    ),
    ("MagnificationResolved E_star", lambda b: pf.MagnificationResolved(PSD, b), "E_star", NUMBER),
    ("gap_distribution n_area", lambda b: pf.gap_distribution(PR, n_area=b), "n_area", NOT_A_NUMBER + [0, -1, 10**9]),
    ("GapDistribution p_bar", lambda b: pf.GapDistribution(pf.MagnificationResolved(PSD), b), "p_bar", ARRAY),
    ("leak_rate viscosity", lambda b: pf.leak_rate(PR, b, 1.0), "viscosity", NUMBER),
    ("leak_rate pressure_drop", lambda b: pf.leak_rate(PR, 1.0, b), "pressure_drop", NUMBER),
    (
        "contact_conductance resistivity",
        lambda b: pf.contact_conductance(PR, resistivity=b),
        "resistivity",
        [float("nan"), -1.0, "x", True, [1.0, -1.0]],
    ),
    ("adhesion.Exponential w", lambda b: pf.adhesion.Exponential(b, 1e-3), "w", NUMBER),
    ("adhesion.MaugisDugdale sigma0", lambda b: pf.adhesion.MaugisDugdale(1e-3, b), "sigma0", NUMBER),
    ("adhesion.LennardJones93 rho", lambda b: pf.adhesion.LennardJones93(1e-3, b), "rho", NUMBER),
    (
        "adhesion.CallableInteraction rho",
        lambda b: pf.adhesion.CallableInteraction(lambda u: np.exp(-u), b),
        "rho",
        NUMBER,
    ),
    (
        "adhesion.resolve_interaction interaction",
        lambda b: pf.adhesion.resolve_interaction(b),
        "interaction",
        NOT_AN_OBJECT,
    ),
    (
        "adhesion.attractive_stress gaps",
        lambda b: pf.adhesion.attractive_stress(b, pf.adhesion.Exponential(1e-3, 1e-3)),
        "gaps",
        NOT_AN_OBJECT,
    ),
    ("adhesion.persson_tosatti w", lambda b: pf.adhesion.persson_tosatti(PSD, 1.0, b), "w", NUMBER),
    ("adhesion.pastewka_robbins E_star", lambda b: pf.adhesion.pastewka_robbins(PSD, b, 1e-3, 1e-3), "E_star", NUMBER),
    ("adhesion.tabor_parameter psd", lambda b: pf.adhesion.tabor_parameter(b, 1.0, 1e-3, 1e-3), "psd", NOT_AN_OBJECT),
    ("adhesive_contact interaction", lambda b: pf.adhesive_contact(PR, b), "interaction", NOT_AN_OBJECT),
    (
        "psd_from_heightmap bins_per_decade",
        lambda b: pf.psd_from_heightmap(np.random.default_rng(0).normal(size=(16, 16)), 1.0, bins_per_decade=b),
        "bins_per_decade",
        NOT_A_NUMBER + [0, 3],
    ),
    (
        "psd_from_profiles length",
        lambda b: pf.psd_from_profiles(np.random.default_rng(0).normal(size=(4, 64)), b),
        "length",
        NUMBER,
    ),
    ("read_heightmap path", lambda b: pf.read_heightmap(b, 1.0), "path", PATHS),
    ("read_contact_engineering_csv path", lambda b: pf.read_contact_engineering_csv(b), "path", PATHS),
    ("read_sweep_table path", lambda b: pf.read_sweep_table(b), "path", PATHS),
    ("from_surface_topography topography", lambda b: pf.from_surface_topography(b), "topography", NOT_AN_OBJECT),
    ("register_quantity func", lambda b: pf.register_quantity("bad_prop", b, "1"), "func", NOT_AN_OBJECT),
    ("sweep E_star", lambda b: pf.sweep([PSD], [0.1], E_star=b, progress=False), "E_star", NUMBER),
    (
        "calibrate E_star",
        lambda b: pf.calibrate(PSD, {"p_bar": [0.01, 0.02], "contact_area": [0.3, 0.5]}, E_star=b),
        "E_star",
        NUMBER,
    ),
]
CASE = st.sampled_from(CASES).flatmap(lambda c: st.tuples(st.just(c), st.sampled_from(c[3])))


@slow_scale(5.0)
@given(CASE)
def test_property_bad_input_is_a_value_error_naming_the_parameter(case_and_value):
    """One ValueError naming the parameter, for every drawn (callable, parameter, bad value)."""
    (label, call, name, _), bad = case_and_value
    with pytest.raises(ValueError, match=re.escape(name)):
        call(bad)


@given(st.sampled_from(["empty", "folder", "binary"]))
def test_property_unreadable_files_are_value_errors_naming_the_file(kind):
    """Empty files, folders and binary junk given as a height map, a contact.engineering export or a sweep table."""
    with tempfile.TemporaryDirectory() as d:
        path = d if kind == "folder" else os.path.join(d, "f.csv")
        if kind != "folder":
            with open(path, "wb") as fh:
                fh.write(b"" if kind == "empty" else bytes(range(256)))
        for reader in (lambda p: pf.read_heightmap(p, 1.0), pf.read_contact_engineering_csv, pf.read_sweep_table):
            with pytest.raises(ValueError):
                reader(path)


def test_public_constants_hold_what_the_docs_say():
    """METHODS, CONVENTIONS, WEIGHTINGS, QUANTITIES, the fudge-factor defaults and models, and the version."""
    assert pf.fudge.GAMMA_YP08 == 0.45 and pf.fudge.GAMMA_WM17 == 5.0 / 9.0 and pf.fudge.GAMMA_XU24 == 0.45
    assert set(pf.fudge.MODELS) == {"none", "YP08", "WM17", "Xu24"}
    assert all(issubclass(c, pf.fudge.FudgeFactor) for c in pf.fudge.MODELS.values())
    assert {"fv", "mol", "sines", "chapman-kolmogorov", "monte-carlo", "chebyshev"} <= set(pf.METHODS)
    assert set(pf.available_methods()) <= set(pf.METHODS)
    assert set(pf.CONVENTIONS) == {"persson", "iso2d", "1d", "q/pi*2d"}
    assert pf.WEIGHTINGS == ("yang-persson", "corrected-area")
    assert {"contact_area", "mean_separation"} <= set(pf.QUANTITIES)
    assert re.fullmatch(r"\d+\.\d+(\.\d+)?([.-]?\w+)*", pf.__version__)


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda: pf.EffectiveVariance(1.0), "fudge"),  # was AttributeError
        (lambda: pf.effective_variance([1.0]), "fudge"),  # was TypeError (unhashable)
        (lambda: pf.adhesion.attractive_stress(1.0, pf.adhesion.Exponential(1e-3, 1e-3)), "gaps"),  # AttributeError
        (lambda: pf.adhesion.tabor_parameter(1.0, 1.0, 1e-3, 1e-3), "psd"),  # AttributeError
        (lambda: pf.abel_forward(1.0, [1.0]), "psd"),  # AttributeError
        (lambda: pf.abel_forward(PSD, 0.0), "q"),  # FloatingPointError / inf
        (lambda: pf.abel_factor(1e308), "H"),  # NaN
        (lambda: pf.abel_inverse([1.0, 2.0, 3.0], [1.0, 0.5, 0.2], n_nodes=float("inf")), "n_nodes"),  # OverflowError
        (lambda: pf.hardness.PowerLaw(1.0, [1.0, 2.0]), "n"),  # TypeError
        (lambda: pf.hardness.CallableHardness(np.sqrt, 1.0), "derivative"),  # accepted, failed later
        (lambda: pf.read_sweep_table("/nonexistent/table.csv"), "path"),  # FileNotFoundError
        (lambda: pf.image_pdf(1.0, float("nan"), 1.0), "p_bar"),  # NaN
        (lambda: pf.area_from_tau(-1.0, 1.0), "p_bar"),  # a negative area
        (lambda: pf.variance_closed_form(1.0, float("nan")), "tau"),  # 0.0
    ],
)
def test_regression_bad_inputs_found_by_the_property(call, name):
    with pytest.raises(ValueError, match=name):
        call()
