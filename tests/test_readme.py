"""The README is a front door that works: its examples run as written and print what it shows, and the numbers
are those of Persson's theory computed here independently of the package (closed forms and quadratures written
from the equations, not from persson_fp)."""

from __future__ import annotations

import math
import pathlib
import re

import numpy as np
import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
README = (ROOT / "README.md").read_text(encoding="utf8")
PY = re.findall(r"```python\n(.*?)```", README, flags=re.S)
TEXT = re.findall(r"```text\n(.*?)```", README, flags=re.S)


def _run(block, capsys):
    namespace: dict = {}
    exec(compile(block, "README.md", "exec"), namespace)
    return namespace, capsys.readouterr().out


# -- the SI example, and its numbers from the equations ---------------------------------------------------------------

E, P, S_RMS, H = 10e6, 0.1e6, 0.2, 0.8
QL, QR, QS = 2 * math.pi / 1e-3, 2 * math.pi / 1e-4, 2 * math.pi / 1e-6


def _spectrum():
    """Self-affine C(q) (a plateau below q_r, q^-2(1+H) above) normalised to the rms slope: <|grad h|^2> =
    2 pi int q^3 C dq = S_RMS^2 (Persson's convention, the Xu et al. tutorial's E:PSD)."""
    x = lambda q: np.where(q < QR, 1.0, (q / QR) ** (-2 * (1 + H)))
    lo = QR**4 / 4 - QL**4 / 4
    hi = QR ** (2 * (1 + H)) * (QS ** (2 - 2 * H) - QR ** (2 - 2 * H)) / (2 - 2 * H)
    C0 = S_RMS**2 / (2 * math.pi * (lo + hi))
    return lambda q: C0 * x(q)


def _V_of_q(C):
    """V(q) = (pi/2) E*^2 int_{q_l}^q q'^3 C dq' (eq:Vp_closed_form), on a fine log grid (closed form per piece)."""
    C0 = float(C(QL))

    def V(q):
        q = np.asarray(q, float)
        below = C0 * (np.minimum(q, QR) ** 4 - QL**4) / 4
        a = 2 - 2 * H
        above = C0 * QR ** (2 * (1 + H)) * (np.maximum(q, QR) ** a - QR**a) / a
        return 0.5 * math.pi * E**2 * (below + above)

    return V


def _S_wm17(A, gamma=5.0 / 9.0):
    """Wang & Müser (2017): S(A) = gamma - 2/9 A^2 + (11/9 - gamma) A^4."""
    return gamma - (2.0 / 9.0) * A**2 + (11.0 / 9.0 - gamma) * A**4


def _area_wm17(V_max):
    """A* = erf(p/sqrt(2 tau)) at the effective variance tau: d tau/dV = S(A*(tau)) (eq:new_B2), by solve_ivp."""
    from scipy.integrate import solve_ivp
    from scipy.special import erf

    v0 = 1e-12 * V_max
    f = lambda v, t: [_S_wm17(erf(P / math.sqrt(2 * t[0])))]
    sol = solve_ivp(f, (v0, V_max), [_S_wm17(1.0) * v0], rtol=1e-11, atol=0, method="DOP853")
    return float(erf(P / math.sqrt(2 * sol.y[0, -1])))


def _separation_wm17(C, V):
    """u(p) = int_p^inf U/p'^2 dp' - U(p)/p and K = p/(dU/dp) (Persson 2007), U = (pi/2) E* int q^2 C w(p/sqrt V) dq
    with Yang & Persson's weight w(y) = P S(P), P = erf(y/sqrt2); Gauss-Legendre in ln q on each smooth piece."""
    from scipy.integrate import quad
    from scipy.special import erf, roots_legendre

    x, w = roots_legendre(400)
    nodes, weights = [], []
    for a, b in ((QL, QR), (QR, QS)):
        la, lb = math.log(a), math.log(b)
        nodes.append(np.exp(0.5 * (lb - la) * x + 0.5 * (lb + la)))
        weights.append(0.5 * (lb - la) * w)
    q, wq = np.concatenate(nodes), np.concatenate(weights)
    sq = np.sqrt(V(q))
    base = 0.5 * math.pi * E * q**3 * C(q) * wq  # the q^2 C dq of U, dq = q d ln q
    omega = lambda y: erf(y / math.sqrt(2)) * _S_wm17(erf(y / math.sqrt(2)))
    U = lambda p: float(np.sum(base * omega(p / sq)))
    u = quad(lambda t: U(P / t), 0.0, 1.0, epsabs=0, epsrel=1e-11, limit=200)[0] / P - U(P) / P  # p' = P/t
    h = 1e-5
    dU = float(np.sum(base * (omega((P / sq) * (1 + h)) - omega((P / sq) * (1 - h))) / (2 * h * P)))
    return u, P / dU


def test_readme_si_example_prints_what_the_readme_shows_and_the_theory(capsys):
    ns, out = _run(PY[0], capsys)
    assert out.strip() == TEXT[0].strip(), "the README's printed output is not what its example prints"
    numbers = [float(x) for x in re.findall(r"[-+]?\d+\.\d+(?:e[-+]\d+)?", out)]
    A, u_um, K, Q, gap_um, in_contact = numbers
    C = _spectrum()
    V = _V_of_q(C)
    V_max = float(V(QS))
    assert V_max == pytest.approx(E**2 * S_RMS**2 / 4, rel=1e-12)  # V = E*^2 <|grad h|^2>/4 (eq:VV_relation)
    # A* to the 4 digits printed (the ODE oracle is good to ~1e-10)
    assert A == pytest.approx(_area_wm17(V_max), abs=0.5e-4)
    assert float(ns["A"]) == pytest.approx(_area_wm17(V_max), rel=1e-7)
    u, K_ref = _separation_wm17(C, V)
    assert u_um == pytest.approx(u * 1e6, abs=0.5e-3)
    assert float(ns["u"]) == pytest.approx(u, rel=1e-6)
    assert float(ns["K"]) == pytest.approx(K_ref, rel=1e-5)  # central difference of the weight: ~1e-10
    # the gap distribution's contact atom is the contact area; a seal that leaks, through gaps of order u
    assert in_contact == pytest.approx(A, abs=1e-4)
    assert 0 < Q and 0.5 * u_um < gap_um < 2 * u_um


def test_readme_solver_example_runs(capsys):
    import matplotlib

    matplotlib.use("Agg")
    ns, out = _run(PY[1], capsys)
    cmp = ns["sol"].compare()
    assert float(np.max(cmp.L1)) < 1e-4 and "L1" in out


def test_readme_is_a_front_door_whose_links_exist():
    lines = README.splitlines()
    assert len(lines) <= 150, f"the README has {len(lines)} lines: the user guide (docs/) is the place for more"
    links = re.findall(r"\]\(([^)#]+)\)", README)
    assert links, "no links into the user guide"
    for link in links:
        assert (ROOT / link).exists(), f"README links {link}, which does not exist"
    quick = README.split("## Quick start", 1)[1].split("##", 1)[0]
    commands = re.findall(r"```bash\n(.*?)```", quick, flags=re.S)[0].strip().splitlines()
    assert len(commands) == 2  # one installs and runs the main job, one installs and runs the tests
    ci = (ROOT / ".ci" / "run").read_text(encoding="utf8")
    assert commands[1] in ci


def test_readme_surface_command_on_a_height_map(tmp_path, monkeypatch, capsys):
    """The README's command line, run as written on a 1 mm height map in metres drawn from a self-affine spectrum of
    rms slope 0.2: A* of Persson's theory is erf(p/sqrt(2V)) with V = E*^2 s^2 / 4 (eq:VV_relation, eq:Area_Persson);
    the map's imported slope is within 3 % of the spectrum's (a finite map, detrended and windowed)."""
    import csv
    import shlex

    from persson_fp.cli.app import main

    bash = re.findall(r"```bash\n(persson-fp surface .*?)\n```", README, flags=re.S)
    assert len(bash) == 1
    argv = shlex.split(bash[0])[1:]
    n, L, s = 256, 1e-3, 0.2
    q_l, q_r, q_s = 2 * math.pi / L, 2 * math.pi / 1e-4, math.pi * n / L
    C0 = s**2 / (2 * math.pi * ((q_r**4 - q_l**4) / 4 + q_r**3.6 * (q_s**0.4 - q_r**0.4) / 0.4))  # H = 0.8
    qx = 2 * math.pi * np.fft.fftfreq(n, d=L / n)
    qm = np.hypot(*np.meshgrid(qx, qx, indexing="ij"))
    C = np.where(qm < q_r, C0, C0 * (np.maximum(qm, q_r) / q_r) ** -3.6) * ((qm >= q_l) & (qm <= q_s))
    noise = np.fft.fft2(np.random.default_rng(7).standard_normal((n, n)))
    h = np.real(np.fft.ifft2(noise / np.abs(noise) * np.sqrt(C))) * n * n * 2 * math.pi / L
    monkeypatch.chdir(tmp_path)
    np.save("heights.npy", h)
    assert main([*argv, "--output", "out"]) == 0
    with open(tmp_path / "out" / "surface.csv", newline="") as fh:
        row = next(r for r in csv.DictReader(fh) if not r["p_bar [Pa]"].startswith("#"))
    E, p = 10e6, 1e5
    assert float(row["p_bar [Pa]"]) == pytest.approx(p)
    A_ref = math.erf(p / (E * s / math.sqrt(2)))
    assert float(row["A_none [-]"]) == pytest.approx(A_ref, rel=0.03)
    for name in ("u_WM17 [m]", "K_WM17 [Pa/m]", "Q_cj_WM17 [m^3/s]", "Q_em_WM17 [m^3/s]"):
        assert float(row[name]) > 0, name
    out = capsys.readouterr().out
    assert "units: SI assumed" in out and "A* [-]" in out
