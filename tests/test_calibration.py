"""pf.calibrate: recovery of known parameters, an independent least-squares reference, coverage of the stated
uncertainty, model selection, data checks and the result object.

References are computed here by other routes than the package's: the Xu24 closed form A = erf(p / sqrt(2 g(A) V))
solved by brentq, the YP08 effective variance by integrating d tau / dV = S(erf(p / sqrt(2 tau))) with solve_ivp,
and the least-squares minimum by scipy.optimize.minimize_scalar.
"""

from __future__ import annotations

import csv
import os

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq, minimize_scalar
from scipy.special import erf

import persson_fp as pf

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEM = os.path.join(ROOT, "data", "bem")
Q_L = 2 * np.pi
PSD = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, Q_L, 4 * Q_L, 64 * Q_L)  # the BEM surfaces' nominal spectrum
V = 0.0025  # = E*^2 g^2 / 4 with E* = 1 and rms slope g = 0.1 (eq:VV_relation): checked below
LOADS = np.array([0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]) * 0.1


def bem_area(H=0.8, seed=1):
    with open(os.path.join(BEM, "runs.csv"), newline="") as fh:
        rows = [r for r in csv.DictReader(fh) if r["tag"] == "main" and float(r["H"]) == H and int(r["seed"]) == seed]
    rows.sort(key=lambda r: float(r["pbar"]))
    return np.array([float(r["pbar"]) for r in rows]), np.array([float(r["Astar"]) for r in rows])


def xu24_area(p, gamma):
    """A* of the Xu24 global model by brentq on A - erf(p / sqrt(2 (gamma + (1 - gamma) A) V))."""
    return np.array([brentq(lambda A: A - erf(x / np.sqrt(2 * (gamma + (1 - gamma) * A) * V)), 0, 1, xtol=1e-15)
                     for x in p])  # fmt: skip


def yp08_area(p, gamma):
    """A* of YP08: d tau / dV = gamma + (1 - gamma) A^2, A = erf(p / sqrt(2 tau)), integrated over V in [V0, V]."""
    V0 = 1e-3 * p.min() ** 2  # there A = 1 to double precision, so tau = V
    rhs = lambda v, tau: gamma + (1 - gamma) * erf(p / np.sqrt(2 * tau)) ** 2  # noqa: E731
    sol = solve_ivp(rhs, (V0, V), np.full(p.size, V0), method="DOP853", rtol=1e-12, atol=1e-18)
    return erf(p / np.sqrt(2 * sol.y[:, -1]))


def test_nominal_variance():
    assert float(PSD.V(E_star=1.0)) == pytest.approx(V, rel=1e-12)


@pytest.mark.parametrize("model, area", [("Xu24", xu24_area), ("YP08", yp08_area)])
def test_matches_independent_least_squares(model, area):
    # real data (BEM A*, H = 0.8, surface 1): the minimiser of sum (A(gamma)/A_data - 1)^2 by minimize_scalar
    p, A = bem_area()

    def ssr(g):
        return float(np.sum((area(p, g) / A - 1) ** 2))

    ref = minimize_scalar(ssr, bounds=(0.2, 0.9), method="bounded", options={"xatol": 1e-10})
    cal = pf.calibrate(PSD, {"p_bar": p, "contact_area": A}, model=model)
    # both minimise the same function; the package's tau table agrees with the ODE to ~1e-11, the optimisers stop
    # at xtol 1e-10: 1e-6 leaves room for the flatness of the minimum (gamma enters A* at first order)
    assert cal.params["gamma"] == pytest.approx(ref.x, abs=1e-6)
    # standard error s^2 / sum (dr/dgamma)^2 with s^2 = SSR / (n - 1), derivative by central differences here
    h = 1e-5
    dr = (area(p, ref.x + h) - area(p, ref.x - h)) / (2 * h) / A
    se = np.sqrt(ssr(ref.x) / (p.size - 1) / np.sum(dr**2))
    assert cal.uncertainty["gamma"] == pytest.approx(se, rel=1e-4)  # O(h^2) differences, 1e-11 tables
    assert cal.ssr == pytest.approx(ref.fun, rel=1e-6)


def _noisy(rng, gamma, rel_noise):
    A = xu24_area(LOADS, gamma)
    return {"p_bar": LOADS, "contact_area": A * (1 + rel_noise * rng.standard_normal(A.size))}


def test_coverage_of_stated_uncertainty(rng):
    # 50 noisy data sets (3 % relative Gaussian noise) generated from Xu24 with gamma = 0.45: the 95 % interval
    # must hold the true gamma in >= 90 % of the draws (binomial: P(< 45 of 50 | p = 0.95) ~ 4 %; seeded), and
    # the 1-sigma interval about 68 % of the time (not inflated: < 85 %; not too narrow: > 50 %)
    hits95 = hits68 = 0
    for _ in range(50):
        cal = pf.calibrate(PSD, _noisy(rng, 0.45, 0.03), model="Xu24")
        lo, hi = cal.interval(0.95)["gamma"]
        hits95 += lo <= 0.45 <= hi
        hits68 += abs(cal.params["gamma"] - 0.45) <= cal.uncertainty["gamma"]
    assert hits95 >= 45
    assert 25 <= hits68 <= 42


@pytest.mark.slow
def test_coverage_yp08(rng):
    # the same with YP08 (an ODE per gamma: ~0.2 s a fit), noise on A* and mean separation of 2 surfaces
    other = pf.SelfAffinePSD.from_rms_slope(0.1, 0.3, Q_L, 4 * Q_L, 64 * Q_L)
    truth = pf.fudge.YangPersson(0.45)
    clean = []
    for psd in (PSD, other):
        A = np.asarray(pf.exact(pf.ContactProblem(psd, 1.0, LOADS, truth)).contact_area)
        u = pf.MeanSeparation(psd, 1.0, truth).mean_separation(LOADS)
        clean.append((A, u))
    hits = 0
    for _ in range(50):
        data = [
            {"p_bar": LOADS, "contact_area": A * (1 + 0.03 * rng.standard_normal(7)),
             "mean_separation": u * (1 + 0.03 * rng.standard_normal(7))}
            for A, u in clean
        ]  # fmt: skip
        lo, hi = pf.calibrate([PSD, other], data).interval(0.95)["gamma"]
        hits += lo <= 0.45 <= hi
    assert hits >= 45


def test_recovers_gamma_from_separation_and_is_usable_as_fudge():
    truth = pf.fudge.YangPersson(0.42)
    ms = pf.MeanSeparation(PSD, 1.0, truth, "corrected-area")
    data = {"p_bar": LOADS, "mean_separation": ms.mean_separation(LOADS)}
    cal = pf.calibrate(PSD, data, weighting="corrected-area")
    assert cal.params["gamma"] == pytest.approx(0.42, abs=1e-7)  # noise-free: to the tables' accuracy
    assert cal.quantities == ("mean_separation",)
    # the fitted model plugs in as fudge=
    A = pf.exact(pf.ContactProblem(PSD, 1.0, LOADS, fudge=cal.model)).contact_area
    assert np.allclose(A, yp08_area(LOADS, cal.params["gamma"]), rtol=1e-8)


def test_user_callable_matches_named_model():
    p, A = bem_area(0.3, 2)

    def S(A, g):
        return g + (1 - g) * A**2

    named = pf.calibrate(PSD, {"p_bar": p, "contact_area": A})
    user = pf.calibrate(PSD, {"p_bar": p, "contact_area": A}, model=S, params=("g",), p0=(0.5,), bounds=(0.01, 1))
    assert user.params["g"] == pytest.approx(named.params["gamma"], abs=1e-7)
    assert user.uncertainty["g"] == pytest.approx(named.uncertainty["gamma"], rel=1e-4)
    with pytest.raises(ValueError, match="p0"):
        pf.calibrate(PSD, {"p_bar": p, "contact_area": A}, model=S, params=("g",))
    # a fudge instance: its value starts the fit, the same minimum is found
    by_name = pf.calibrate(PSD, {"p_bar": p, "contact_area": A}, model="Xu24")
    by_instance = pf.calibrate(PSD, {"p_bar": p, "contact_area": A}, model=pf.fudge.Xu24(0.3))
    assert by_instance.params["gamma"] == pytest.approx(by_name.params["gamma"], abs=1e-7)
    assert isinstance(by_instance.model, pf.fudge.Xu24)


def test_input_forms_agree(tmp_path):
    pd = pytest.importorskip("pandas")
    tables = [dict(zip(("p_bar", "contact_area"), bem_area(0.8, s))) for s in (1, 2, 3)]
    by_list = pf.calibrate([PSD] * 3, tables, model="Xu24")
    frame = pd.concat([pd.DataFrame(t).assign(surface=name) for t, name in zip(tables, "abc")])
    by_frame = pf.calibrate(dict(zip("abc", [PSD] * 3)), frame, model="Xu24")
    path = tmp_path / "data.csv"
    frame.to_csv(path, index=False)
    by_csv = pf.calibrate(dict(zip("abc", [PSD] * 3)), path, model="Xu24")
    arr = np.column_stack([np.concatenate([t["p_bar"] for t in tables]),
                           np.concatenate([t["contact_area"] for t in tables])])  # fmt: skip
    by_array = pf.calibrate(PSD, arr, model="Xu24")
    for other in (by_frame, by_csv, by_array):
        assert other.params["gamma"] == pytest.approx(by_list.params["gamma"], rel=1e-9)
        assert other.n_points == 21
    table = by_frame.residual_table()
    assert list(dict.fromkeys(table["surface"])) == ["a", "b", "c"]
    assert np.allclose(table["rel_error"], table["fit"] / table["data"] - 1)


def test_uncertainty_columns_absolute_sigma():
    rng = np.random.default_rng(7)
    A = xu24_area(LOADS, 0.5)
    err = 0.01 * A
    data = {"p_bar": LOADS, "contact_area": A + err * rng.standard_normal(7), "contact_area_err": err}
    rel = pf.calibrate(PSD, data, model="Xu24")
    ab = pf.calibrate(PSD, data, model="Xu24", absolute_sigma=True)
    assert ab.params == rel.params
    # absolute: cov = (J^T J)^-1, i.e. the relative one divided by s^2
    assert ab.uncertainty["gamma"] == pytest.approx(rel.uncertainty["gamma"] / rel.s, rel=1e-6)


def test_model_selection_ranks_the_true_model_first(rng):
    data = [_noisy(rng, 0.45, 0.005) for _ in range(2)]
    first = pf.calibrate([PSD] * 2, data, model=["YP08", "WM17", "Xu24"])
    for criterion in ("held-out", "aic", "bic"):
        sel = pf.ModelSelection(first.fits, criterion, held_out=(first.held_out, first.held_out_scheme))
        assert sel.ranking[0] == "Xu24" and sel.best.family.name == "Xu24"
        assert sel.held_out_scheme == "leave one surface out"
        assert criterion.upper() in str(sel).upper()
    one = pf.calibrate(PSD, data[0], model=["Xu24"], criterion="aic")
    assert one.held_out_scheme == "leave one load out"


def test_bootstrap_and_band(rng):
    cal = pf.calibrate(PSD, _noisy(rng, 0.45, 0.03), model="Xu24", bootstrap=40, rng=1)
    assert cal.bootstrap.shape == (40, 1)
    assert 0.3 < cal.bootstrap_std[0] / cal.std[0] < 3  # two estimates of one spread (7 points: loose)
    # the band of predict() is t * |df/dgamma| * sigma: check df/dgamma by the closed form
    f, hw = cal.predict(PSD, LOADS, level=0.6827)
    g, s = cal.params["gamma"], cal.std[0]
    slope = (xu24_area(LOADS, g + 1e-5) - xu24_area(LOADS, g - 1e-5)) / 2e-5
    from scipy.stats import t

    assert np.allclose(f, xu24_area(LOADS, g), rtol=1e-10)
    assert np.allclose(hw, t.ppf(0.5 + 0.6827 / 2, cal.dof) * np.abs(slope) * s, rtol=1e-4)
    fig = cal.plot()
    assert len(fig.axes) == 2
    assert "gamma = " in str(cal) and "held-out" in str(cal)


@pytest.mark.parametrize(
    "table, match",
    [
        ({"p_bar": [1e-3, -1e-3, 2e-3], "contact_area": [0.1, 0.1, 0.2]}, r"column 'p_bar', row 1: a load must be > 0"),
        ({"p_bar": [1e-3, 2e-3, 3e-3], "contact_area": [0.1, 1.2, 0.2]}, r"column 'contact_area', row 1: .*\(0, 1\]"),
        (
            {"p_bar": [1e-3, 2e-3, 3e-3], "contact_area": [0.1, 0.2, np.nan]},
            r"column 'contact_area', row 2: not finite",
        ),
        ({"p_bar": [1e-3, 2e-3, np.inf], "contact_area": [0.1, 0.2, 0.3]}, r"column 'p_bar', row 2: not finite"),
        ({"p_bar": [1e-3, 2e-3], "mean_separation": [0.1, -0.2]}, r"column 'mean_separation', row 1"),
        ({"p_bar": [1e-3], "contact_area": [0.1]}, r"too few points: 1 .* for 1 parameter"),
        ({"p_bar": [1e-3, 2e-3], "contact_area": [0.1, 0.2], "contact_area_err": [0.01, 0]}, "contact_area_err"),
        ({"load": [1e-3, 2e-3], "contact_area": [0.1, 0.2]}, "column 'p_bar'"),
        ({"p_bar": [1e-3, 2e-3], "area": [0.1, 0.2]}, "contact_area"),
    ],
)
def test_bad_data_names_column_and_row(table, match):
    with pytest.raises(ValueError, match=match):
        pf.calibrate(PSD, table)


def test_bad_csv_names_line(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("p_bar,contact_area\n0.001,0.1\n0.002,abc\n")
    with pytest.raises(ValueError, match=r"column 'contact_area', row 1 \(line 3 of .*bad.csv\): not a number"):
        pf.calibrate(PSD, path)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        ({"model": "YP09"}, "model must be one of"),
        ({"params": ("beta",)}, "no parameter 'beta'"),
        ({"quantities": ("stiffness",)}, "quantities must be among"),
        ({"weighting": "energy"}, "weighting must be one of"),
        ({"model": ["YP08", "yp08"]}, "appears twice"),
        ({"model": ["YP08"], "criterion": "r2"}, "criterion must be one of"),
        ({"p0": (2.0,)}, "outside the bounds"),
    ],
)
def test_bad_options(kwargs, match):
    p, A = bem_area()
    with pytest.raises(ValueError, match=match):
        pf.calibrate(PSD, {"p_bar": p, "contact_area": A}, **kwargs)


def test_surfaces_and_tables_must_pair():
    p, A = bem_area()
    with pytest.raises(ValueError, match="2 data tables for 3 surfaces"):
        pf.calibrate([PSD] * 3, [{"p_bar": p, "contact_area": A}] * 2)
    with pytest.raises(ValueError, match="'surface' column"):
        pf.calibrate([PSD] * 2, {"p_bar": p, "contact_area": A})
    with pytest.raises(ValueError, match=r"column 'surface', row 0: 'x' names no surface"):
        pf.calibrate({"a": PSD, "b": PSD}, {"p_bar": p, "contact_area": A, "surface": ["x"] * 7})


def test_surface_column_must_name_a_single_spectrum_too():
    # one spectrum in a sequence or mapping is named like several ("0", or the key): a 'surface' column naming
    # another surface is refused the same way, not fitted against the only spectrum
    p, A = bem_area()
    with pytest.raises(ValueError, match=r"column 'surface', row 0: 'x' names no surface \(have \['0'\]\)"):
        pf.calibrate([PSD], {"p_bar": p, "contact_area": A, "surface": ["x"] * 7})
    with pytest.raises(ValueError, match=r"'b' names no surface \(have \['a'\]\)"):
        pf.calibrate({"a": PSD}, {"p_bar": p, "contact_area": A, "surface": ["a"] * 6 + ["b"]})
    # a bare PSD is unnamed: any one label, but not rows of two surfaces
    with pytest.raises(ValueError, match=r"column 'surface' names 2 surfaces"):
        pf.calibrate(PSD, {"p_bar": p, "contact_area": A, "surface": ["a"] * 6 + ["b"]})
    good = pf.calibrate({"a": PSD}, {"p_bar": p, "contact_area": A, "surface": ["a"] * 7})
    bare = pf.calibrate(PSD, {"p_bar": p, "contact_area": A})
    assert good.params == pytest.approx(bare.params, rel=1e-12)


def test_weights_scale_the_quantities(rng):
    # A* from gamma = 0.45 and a separation from gamma = 0.6 (inconsistent on purpose): a tiny weight on the
    # separation leaves the A*-only fit, a huge one gives the separation-only fit
    A = xu24_area(LOADS, 0.45)
    u = pf.MeanSeparation(PSD, 1.0, pf.fudge.Xu24(0.6)).mean_separation(LOADS)
    both = {"p_bar": LOADS, "contact_area": A, "mean_separation": u}
    g_area = pf.calibrate(PSD, both, model="Xu24", weights={"mean_separation": 1e-12}).params["gamma"]
    g_sep = pf.calibrate(PSD, both, model="Xu24", weights={"contact_area": 1e-12}).params["gamma"]
    g_mid = pf.calibrate(PSD, both, model="Xu24").params["gamma"]
    assert g_area == pytest.approx(0.45, abs=1e-5) and g_sep == pytest.approx(0.6, abs=1e-5)
    assert 0.45 < g_mid < 0.6
    with pytest.raises(ValueError, match="weights"):
        pf.calibrate(PSD, both, model="Xu24", weights={"contact_area": 0.0})
