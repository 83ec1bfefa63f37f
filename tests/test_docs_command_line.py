"""The command-line page of the user guide runs as written, and the numbers it prints are Persson's.

Oracle written here, from the spectrum file the page writes (not from persson_fp): C(q) = Y / (4 pi q) of the
contact.engineering series "q/pi x 2D PSD", V = (pi/2) E*^2 int q^3 C(q) dq integrated segment by segment as the
power law through each pair of table points (exact for a log-log linear table), and the fudge-free contact area
A* = erf(p_bar / sqrt(2 V)) (Xu et al. tutorial, eq:Area_Persson).
"""

from __future__ import annotations

import csv
import math
import os
import re

import numpy as np
import pytest

from tests.test_docs_examples import run_page


def _V_from_file(path, E_star):
    rows = [ln.split(";") for ln in open(path, encoding="utf-8").read().splitlines()[1:]]
    q = np.array([float(r[4]) for r in rows])
    C = np.array([float(r[5]) for r in rows]) / (4 * np.pi * q)
    f = q**3 * C  # integrand, a power law q^k between table points
    k = np.log(f[1:] / f[:-1]) / np.log(q[1:] / q[:-1])
    seg = np.where(
        np.abs(k + 1) < 1e-12,
        f[:-1] * q[:-1] * np.log(q[1:] / q[:-1]),
        f[:-1] * q[:-1] * ((q[1:] / q[:-1]) ** (k + 1) - 1) / (k + 1),
    )
    return 0.5 * np.pi * E_star**2 * float(seg.sum())


def test_command_line_page(capsys, monkeypatch):
    import matplotlib.pyplot as plt

    import persson_fp.cli.surface as surface

    # the figure is not this test's subject (tests/test_cli_units.py looks at its axes): an empty one saves ~1 s
    monkeypatch.setattr(surface, "_figure", lambda *a, **k: plt.figure(figsize=(1, 1)))
    ns = run_page("command_line.md")
    out = capsys.readouterr().out
    assert ns["rc"] == 0 and out.count("units: SI assumed") == 1
    E, p = 2.31e11, 1e5
    V = _V_from_file(ns["spectrum"], E)
    assert V == pytest.approx((E * 0.2 / 2) ** 2, rel=1e-4)  # the model's rms slope 0.2 (the roll-off kink: ~2e-5)
    A = math.erf(p / math.sqrt(2 * V))
    printed = re.search(r"A\* = (\S+) \(Persson\), (\S+) \(YP08\)", out)
    assert float(printed.group(1)) == pytest.approx(A, rel=1e-5)  # 6 printed digits
    with open(os.path.join(ns["out"], "surface.csv"), newline="") as fh:
        row = next(csv.DictReader(fh))
    assert float(row["A_none [-]"]) == pytest.approx(A, rel=1e-9)
    assert float(row["p_bar_over_sqrtV [-]"]) == pytest.approx(p / math.sqrt(V), rel=1e-9)
    # YP08's fudge factor raises the area (S > 1 at small A*): Yang & Persson 2008, by more than 40 % here
    assert float(printed.group(2)) > 1.4 * float(printed.group(1))
    # the page's quoted output is what the example prints
    text = open(os.path.join(os.path.dirname(__file__), "..", "docs", "command_line.md"), encoding="utf8").read()
    quoted = text.split("It prints")[1].split("```text\n")[1].split("```")[0]
    assert quoted.strip() in out
