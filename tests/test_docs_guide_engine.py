"""The guide pages on general coefficients and ``method="auto"``, calibration and sweeps: their examples run as
written, print what the page shows, and their numbers agree with references written here.

References, computed by other routes than the package's: the complete-contact variance V = (pi/2) E*^2 int q^3 C dq
by scipy quad from the spectrum (the tutorial by Xu, Li, Chen and Zhou, ``eq:Vp_closed_form``); A* = erf(p / sqrt(2V))
(``eq:Area_Persson``); the Xu24 global model A = erf(p / sqrt(2 (gamma + (1 - gamma) A) V)) by brentq; Brownian
motion with drift absorbed at p = 0 by the method of images, integrated by quad; the least-squares minimum by
minimize_scalar; the sliding contact area's scaling A/A0 = erf(c sigma0) (G proportional to 1/sigma0^2).
"""

from __future__ import annotations

import math
import pathlib
import re

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq, minimize_scalar
from scipy.special import erf, erfinv

import persson_fp as pf
from tests.test_docs_examples import run_page

DOCS = pathlib.Path(__file__).resolve().parents[1] / "docs"


def page_blocks(name: str) -> tuple[list[str], list[str]]:
    """The page's ```python blocks and, for each, the ```text block right after it ("" where there is none)."""
    text = (DOCS / name).read_text(encoding="utf8")
    pairs = re.findall(r"```python\n(.*?)```(?:\n\n```text\n(.*?)```)?", text, flags=re.S)
    return [code for code, _ in pairs], [shown for _, shown in pairs]


def run_blocks(name: str, n: int) -> dict:
    """The first ``n`` python blocks of a page in one namespace (``run_page`` runs them all)."""
    namespace: dict = {}
    for block in page_blocks(name)[0][:n]:
        exec(compile(block, name, "exec"), namespace)
    return namespace


def shown_output(name: str, n: int | None = None) -> str:
    """What the page says its first ``n`` blocks print."""
    return "".join(page_blocks(name)[1][:n])


def variance(psd, E_star=1.0):
    """V(zeta_max) = (pi/2) E*^2 int_{q_l}^{q_s} q^3 C(q) dq, by quad in ln q with the roll-off as a break."""
    f = lambda lq: math.exp(4 * lq) * float(psd.C(math.exp(lq)))  # noqa: E731
    ends = [math.log(psd.q_l), math.log(psd.q_r), math.log(psd.q_s)]
    total = sum(quad(f, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in zip(ends[:-1], ends[1:]) if b > a)
    return 0.5 * math.pi * E_star**2 * total


def xu24_area(p, gamma, V):
    return np.array([brentq(lambda A: A - erf(x / math.sqrt(2 * (gamma + (1 - gamma) * A) * V)), 0, 1, xtol=1e-15)
                     for x in np.atleast_1d(p)])  # fmt: skip


# -- general coefficients and auto ---------------------------------------------------------------------------------
def drift_survival(p_bar, m, V):
    """A* of Brownian motion with drift m per unit V, started at p_bar, absorbed at 0: the image density
    phi_V(p - p_bar - mV) - exp(-2 m p_bar) phi_V(p + p_bar - mV) integrated over p > 0 by quad."""
    s = math.sqrt(V)
    phi = lambda x: math.exp(-0.5 * (x / s) ** 2) / (s * math.sqrt(2 * math.pi))  # noqa: E731
    dens = lambda p: phi(p - p_bar - m * V) - math.exp(-2 * m * p_bar) * phi(p + p_bar - m * V)  # noqa: E731
    c = p_bar + m * V
    return sum(quad(dens, a, b, epsabs=1e-15, epsrel=1e-13, limit=200)[0] for a, b in ((0, c), (c, c + 40 * s)))


def test_general_coefficients_page(capsys):
    ns = run_page("general_coefficients.md")
    out = capsys.readouterr().out
    assert out == shown_output("general_coefficients.md")  # the page shows what its examples print
    base = ns["base"]
    V = variance(base.psd)
    assert ns["V"] == pytest.approx(V, rel=1e-10)
    p_bar = float(base.p_bar[0])
    assert p_bar == pytest.approx(0.5 * math.sqrt(V), rel=1e-10)
    # the drift example: asked tol 1e-8, met against the image solution with drift; its estimate bounds its error
    ref = drift_survival(p_bar, -p_bar / (2 * V), V)
    err = abs(float(ns["sol"].contact_area[0]) - ref)
    assert err <= 1e-8
    assert err <= float(ns["sol"].error_estimate["contact_area"][0, 0])
    # the non-separable diffusion: its estimate meets the asked tol (its accuracy: the slow test below)
    assert float(ns["sol2"].error_estimate["contact_area"][0, 0]) <= 1e-5
    # the moving wall: the areas partition the nominal area and the loads add up to p_bar (eq:Load_equilibrium)
    s3 = ns["sol3"]
    assert float(s3.elastic_area[0] + s3.plastic_area[0] + s3.noncontact_area[0]) == pytest.approx(1.0, abs=1e-12)
    assert float(s3.error_estimate["plastic_area"][0, 0]) <= 1e-4


def test_general_coefficients_homogenised_limit():
    # the page's engine with B1 = 0, B2 = dV/dzeta given as callables is Persson's problem: erf(p / sqrt(2V))
    base = pf.ContactProblem.reference(p_bar_ratio=0.5)
    dV = base.dV_dzeta
    pr = pf.FokkerPlanckProblem(base.psd, p_bar=float(base.p_bar[0]), B2=lambda p, z: dV(z) * np.ones_like(p))
    sol = pf.solve(pr, method="auto", tol=1e-8)
    V = variance(base.psd)
    assert float(sol.contact_area[0]) == pytest.approx(math.erf(float(base.p_bar[0]) / math.sqrt(2 * V)), abs=1e-8)


def richardson(problem, what, n=800):
    """fv (second order in p and zeta at n cells and n steps) extrapolated from n and 2n: (4 A_2n - A_n) / 3."""
    a, b = (float(getattr(pf.solve(problem, "fv", n_p=m, n_steps=m), what)[0]) for m in (n, 2 * n))
    return b + (b - a) / 3


@pytest.mark.slow  # four fine finite-volume runs (~30 s)
def test_general_coefficients_page_against_extrapolated_fv():
    ns = run_page("general_coefficients.md")
    # the non-separable diffusion: chebyshev's Radau march against fv, another method, Richardson-extrapolated
    sol2 = ns["sol2"]
    ref = richardson(ns["bent"], "contact_area")
    assert abs(float(sol2.contact_area[0]) - ref) <= float(sol2.error_estimate["contact_area"][0, 0])
    # the moving wall: the page's auto run against fv at 800 and 1600 cells, extrapolated
    s3 = ns["sol3"]
    for what in ("plastic_area", "elastic_area"):
        ref = richardson(ns["wall"], what)
        assert abs(float(getattr(s3, what)[0]) - ref) <= float(s3.error_estimate[what][0, 0]), what


# -- calibration ---------------------------------------------------------------------------------------------------
def check_calibration_fit(ns):
    surfaces, data = ns["surfaces"], ns["data"]
    p = ns["p_bar"]
    Vs = [variance(psd) for psd in surfaces.values()]
    # the synthetic data: the Xu24 closed form at gamma = 0.6 (brentq here) with the page's 2 % noise
    rng = np.random.default_rng(7)
    for V, d in zip(Vs, data):
        assert d["contact_area"] == pytest.approx(xu24_area(p, 0.6, V) * (1 + 0.02 * rng.standard_normal(p.size)),
                                                  rel=1e-9)  # fmt: skip
    cal = ns["cal"]
    g, s = cal.params["gamma"], cal.uncertainty["gamma"]
    # the known gamma is recovered within the reported uncertainty (3 sigma), and the uncertainty is not vacuous
    assert abs(g - 0.6) <= 3 * s and s < 0.02
    lo, hi = cal.interval(0.95)["gamma"]
    assert lo < 0.6 < hi

    # the same least-squares problem by another route: the relative residuals of brentq's A*, minimize_scalar
    def ssr(gamma):
        return sum(float(np.sum((xu24_area(p, gamma, V) / d["contact_area"] - 1) ** 2)) for V, d in zip(Vs, data))

    ref = minimize_scalar(ssr, bounds=(0.3, 0.9), method="bounded", options={"xatol": 1e-10})
    assert g == pytest.approx(ref.x, abs=1e-6)
    # s^2 / sum (dr/dgamma)^2 with s^2 = SSR / (n - 1), derivatives by central differences here
    h = 1e-5
    dr2 = sum(float(np.sum(((xu24_area(p, ref.x + h, V) - xu24_area(p, ref.x - h, V)) / (2 * h) / d["contact_area"])
                           ** 2)) for V, d in zip(Vs, data))  # fmt: skip
    assert s == pytest.approx(math.sqrt(ssr(ref.x) / (2 * p.size - 1) / dr2), rel=1e-4)
    # the prediction of the page: the fitted Xu24 on the H = 0.3 surface at p_bar = 0.01
    assert float(ns["A"]) == pytest.approx(xu24_area(1e-2, g, Vs[1])[0], rel=1e-9)


def test_calibration_page_fit(capsys):
    ns = run_blocks("calibration.md", 2)  # the model ranking (seconds of table building) runs in the slow test
    assert capsys.readouterr().out == shown_output("calibration.md", 2)
    check_calibration_fit(ns)


@pytest.mark.slow  # the ranking fits WM17 with its tables (~5 s)
def test_calibration_page_ranking(capsys):
    ns = run_page("calibration.md")
    assert capsys.readouterr().out == shown_output("calibration.md")
    check_calibration_fit(ns)
    rows = ns["sel"].table()
    assert rows[0]["model"] == "Xu24"  # the data were made with Xu24: it predicts a held-out surface best
    assert rows[0]["held_out_mean_abs_rel_error"] < 0.03  # 2 % noise
    assert rows[1]["held_out_mean_abs_rel_error"] > rows[0]["held_out_mean_abs_rel_error"]


# -- sweeps --------------------------------------------------------------------------------------------------------
def test_sweeps_page(capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the page writes sweep.csv and sweep.parquet
    ns = run_page("sweeps.md")
    assert capsys.readouterr().out == shown_output("sweeps.md")
    res, loads = ns["res"], np.array([1e6, 3e6, 1e7])
    for i, psd in enumerate(ns["surfaces"].values()):
        V = variance(psd, E_star=1e9)
        assert res["contact_area"][i, 0] == pytest.approx(erf(loads / math.sqrt(2 * V)), rel=1e-9)
        assert res["contact_area"][i, 1] == pytest.approx(xu24_area(loads, 0.45, V), rel=1e-9)
    assert (tmp_path / "sweep.csv").is_file() and (tmp_path / "sweep.csv.json").is_file()
    assert len(ns["table"]) == 2 * 2 * 2 * 3  # surfaces x models x quantities x loads
    # the sliding contact area: G ~ 1/sigma0^2, so A/A0 = erf(c sigma0) and A(0.4 MPa) = erf(4 erfinv(A(0.1 MPa)))
    area = ns["fr"]["sliding_area"][0]
    assert area[:, 1] == pytest.approx(erf(4 * erfinv(area[:, 0])), rel=1e-9)


@pytest.mark.slow  # nested quadratures for mu (~10 s)
def test_sweeps_page_friction_against_quadrature(tmp_path, monkeypatch):
    from tests.friction.test_rubber_friction import reference_mu

    monkeypatch.chdir(tmp_path)
    ns = run_page("sweeps.md")
    fr, road = ns["fr"], ns["road"]
    for j, v in enumerate(ns["speeds"]):
        for k, s0 in enumerate((0.1e6, 0.4e6)):
            mu, A = reference_mu(road, 3e6, 3e9, 1e-4, 0.5, s0, v, road.q_s, gamma=0.45)
            assert fr["friction"][0, j, k] == pytest.approx(mu, rel=1e-6)
            assert fr["sliding_area"][0, j, k] == pytest.approx(A, rel=1e-6)


@pytest.mark.slow  # a local dask cluster
def test_sweeps_page_dask_call():
    distributed = pytest.importorskip("dask.distributed")
    text = (DOCS / "sweeps.md").read_text(encoding="utf8")
    assert "executor=client.get_executor()" in text
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    ratios = np.geomspace(1e-3, 3, 50)
    with distributed.Client(processes=False, n_workers=1, threads_per_worker=2) as client:
        res = pf.sweep([psd, psd], ratios, relative_loads=True, models=[None, "Xu24"], progress=False,
                       executor=client.get_executor())  # fmt: skip
    assert res["contact_area"][0, 0] == pytest.approx(erf(ratios / math.sqrt(2)), rel=1e-12)
    serial = pf.sweep([psd, psd], ratios, relative_loads=True, models=[None, "Xu24"], progress=False)
    assert np.array_equal(res["contact_area"], serial["contact_area"])


# -- the site's index and the method guide -------------------------------------------------------------------------
def test_index_lists_the_guide_pages_and_counts_the_methods():
    index = (DOCS / "index.md").read_text(encoding="utf8")
    toctree = index.split("User guide", 1)[1].split("```", 1)[0]
    for page in ("general_coefficients", "calibration", "sweeps", "choosing_a_method"):
        assert page in toctree.split(), page
    words = {6: "six", 7: "seven", 8: "eight", 9: "nine", 10: "ten"}
    assert f"{words[len(pf.METHODS)]} numerical methods" in index
    guide = (DOCS / "choosing_a_method.md").read_text(encoding="utf8")
    for method in pf.METHODS:
        assert f'`"{method}"`' in guide, method
