"""The examples of the user guide run as written, and the numbers they print are right.

Each ```python block of a page is executed in one namespace, in order (as a reader pastes them); the page's own
quantities are then checked against references written here.
"""

from __future__ import annotations

import math
import pathlib
import re

import pytest

import persson_fp as pf

DOCS = pathlib.Path(__file__).resolve().parents[1] / "docs"


def run_page(name: str) -> dict:
    text = (DOCS / name).read_text(encoding="utf8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, f"{name}: no python examples"
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, f"{name}", "exec"), namespace)
    return namespace


def test_walls_and_responses_page(capsys):
    ns = run_page("walls_and_responses.md")
    out = capsys.readouterr().out
    assert "moving yield wall with no closed form" in out and "elastic energy is not defined" in out
    pr = ns["pr"]
    # the response of the page against the same V written as a quadrature here: (pi/2) E^2 int q^3 C E_eff^2 dq
    from scipy.integrate import quad

    psd, E, a = pr.psd, 1.0, 0.5
    f = lambda q: q**3 * float(psd.C(q)) * (1 + a * psd.q_l / q) ** 2
    V = 0.5 * math.pi * E**2 * sum(quad(f, lo, hi, epsrel=1e-13, epsabs=0)[0] for lo, hi in ((1.0, 2.0), (2.0, 128.0)))
    assert pr.V_max == pytest.approx(V, rel=1e-10)
    A = math.erf(float(pr.p_bar[0]) / math.sqrt(2 * V))
    assert ns["A"] == pytest.approx(A, rel=1e-10)
    assert float(pf.exact(pr).contact_area) == pytest.approx(A, rel=1e-10)
    assert float(pf.solve(pr, "chebyshev").contact_area[-1]) == pytest.approx(A, abs=1e-7)


def test_rubber_friction_page(capsys):
    ns = run_page("rubber_friction.md")
    out = capsys.readouterr().out
    assert "mu peaks at" in out and "(3, 50)" in out
    # the page's Zener example against the quadrature written from the closed-form angular integrals
    from tests.friction.test_rubber_friction import reference_mu

    res, road = ns["res"], ns["road"]
    i = int(ns["i"])
    mu, A = reference_mu(road, 3e6, 3e9, 1e-4, 0.5, 0.2e6, float(res.velocity[i]), road.q_s)
    assert float(res.mu[i]) == pytest.approx(mu, rel=1e-6)
    assert float(res.contact_area[i]) == pytest.approx(A, rel=1e-6)
    # the conventions table is what the command it names computes
    import importlib.util

    spec = importlib.util.spec_from_file_location("fc", DOCS.parent / "benchmarks" / "friction_conventions.py")
    fc = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fc)
    text = (DOCS / "rubber_friction.md").read_text(encoding="utf8")
    for label, mu_row, A_row in fc.rows():
        assert f"| {mu_row:.4g} | {A_row:.4g} |" in text, label
