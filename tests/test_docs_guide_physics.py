"""The user-guide pages on the contact physics: their examples run, print what the pages show, and print right numbers.

Each page (measured surfaces, contact area, mean separation and stiffness, gaps and leakage, adhesion, elastoplastic
contact) is executed as a reader pastes it (``run_page`` of ``tests/test_docs_examples.py``).  Two checks per page:

- the output shown in the page (the ``text`` block after each ``python`` block) is what the examples print, word for
  word and number for number (to one unit in the last digit shown);
- the numbers are right: each is compared with a reference written here from the published formulas -- the
  self-affine spectrum and its moments in closed form, A* = erf(p/sqrt(2V)) (Xu, Li, Chen, Zhou tutorial,
  ``eq:Area_Persson``), the effective-variance ODE of the fudge models (``eq:new_B2``), Persson's mean separation
  (Phys. Rev. Lett. 99 (2007) 125502) by quadrature, the strip's images (elastoplastic contact), Barber's conductance,
  the flow through a gap, the DMT attraction by quadrature over the gap distribution.

Where a page quotes a measured table, the numbers are read from the committed results file it names.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from scipy.integrate import cumulative_simpson, quad, solve_ivp
from scipy.optimize import brentq
from scipy.special import erf, erfc, exp1, roots_legendre

import persson_fp as pf
from tests.test_docs_examples import DOCS, run_page

RESULTS = DOCS.parent / "benchmarks" / "results"
_NUMBER = re.compile(r"([-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?)")


# -- the output a page shows ------------------------------------------------------------------------------------------
def shown_output(name: str) -> str:
    """The ``text`` blocks that follow a ``python`` block of the page, concatenated: what the page says is printed."""
    text = (DOCS / name).read_text(encoding="utf8")
    blocks = list(re.finditer(r"```(\w*)\n(.*?)```", text, flags=re.S))
    shown = []
    for prev, block in zip(blocks, blocks[1:]):
        if prev.group(1) == "python" and block.group(1) == "text" and not text[prev.end() : block.start()].strip():
            shown.append(block.group(2))
    assert shown, f"{name}: no output shown"
    return "".join(shown)


def _unit(token: str) -> float:
    """One unit in the last digit of a printed number ("0.1234" -> 1e-4, "1.6e-06" -> 1e-7, "1943" -> 1)."""
    mantissa, _, exponent = token.lower().partition("e")
    decimals = len(mantissa.partition(".")[2])
    return 10.0 ** (int(exponent or 0) - decimals)


def assert_same_output(shown: str, printed: str) -> None:
    """The same words, and numbers within one unit of the last digit shown (a rounding may differ by a platform)."""
    a, b = _NUMBER.split(shown.strip()), _NUMBER.split(printed.strip())
    assert len(a) == len(b), f"page shows:\n{shown}\nexamples print:\n{printed}"
    for i, (x, y) in enumerate(zip(a, b)):
        if i % 2 == 0:
            assert x == y, f"page shows {x!r} where the examples print {y!r}"
        else:
            tol = 1.01 * max(_unit(x), _unit(y))
            assert abs(float(x) - float(y)) <= tol, f"page shows {x} where the examples print {y}"


def numbers(line: str) -> list[float]:
    return [float(t) for t in _NUMBER.findall(line)]


def line_with(out: str, start: str) -> str:
    lines = [ln for ln in out.splitlines() if ln.strip().startswith(start)]
    assert len(lines) == 1, f"no single line starting with {start!r} in:\n{out}"
    return lines[0]


def close_to_shown(shown_value: float, reference: float, token_unit: float) -> bool:
    return abs(shown_value - reference) <= 0.51 * token_unit + 1e-12 * abs(reference)


def run(name: str, capsys) -> tuple[dict, str]:
    ns = run_page(name)
    out = capsys.readouterr().out
    assert_same_output(shown_output(name), out)
    return ns, out


# -- references ------------------------------------------------------------------------------------------------------
class SelfAffine:
    """The spectrum of ``SelfAffinePSD.from_rms_slope`` written out: C = C0 below q_r, C0 (q/q_r)^(-2(1+H)) above, C0
    set by <|grad h|^2> = 2 pi int q^3 C dq = slope^2 (``eq:rms_slope_1``); moments in closed form."""

    def __init__(self, slope, H, q_l, q_r, q_s):
        self.H, self.q_l, self.q_r, self.q_s = H, q_l, q_r, q_s
        self.C0 = 1.0
        self.C0 = slope**2 / (2 * np.pi * self.moment(3, q_s))

    def C(self, q):
        q = np.asarray(q, dtype=float)
        return self.C0 * np.where(q < self.q_r, 1.0, (q / self.q_r) ** (-2 - 2 * self.H))

    def moment(self, k, q):
        """int_{q_l}^{q} q^k C dq."""
        q = np.asarray(q, dtype=float)
        lo = (np.minimum(q, self.q_r) ** (k + 1) - self.q_l ** (k + 1)) / (k + 1)
        e = k - 1 - 2 * self.H  # int q^k (q/q_r)^(-2-2H) dq = q_r^(2+2H) q^e / e
        hi = self.q_r ** (2 + 2 * self.H) * (np.maximum(q, self.q_r) ** e - self.q_r**e) / e
        return self.C0 * (lo + hi)

    def V(self, q, E_star):
        """eq:Vp_closed_form: (pi/2) E*^2 int q^3 C dq."""
        return 0.5 * np.pi * E_star**2 * self.moment(3, q)


def effective_variance(S, v_end, v_start=1e-12):
    """tau(V)/p^2 of a fudge model: d tau/dV = S(A*), A* = erf(p/sqrt(2 tau)) (eq:new_B2), in V/p^2 (scale-free)."""

    def rhs(v, t):
        return [float(S(erf(1.0 / math.sqrt(2.0 * t[0]))))]

    sol = solve_ivp(rhs, (v_start, v_end), [v_start], rtol=1e-11, atol=1e-16, method="LSODA")
    return float(sol.y[0, -1])


def area(p, V, S=None, xu_gamma=None):
    """A* at load p and complete-contact variance V: eq:Area_Persson, through the effective variance of S, or the
    global model of Xu et al. (2024) by a root find."""
    if xu_gamma is not None:
        return brentq(lambda A: A - erf(p / math.sqrt(2 * (xu_gamma + (1 - xu_gamma) * A) * V)), 0.0, 1.0, xtol=1e-15)
    if S is None:
        return erf(p / math.sqrt(2 * V))
    return erf(1.0 / math.sqrt(2.0 * effective_variance(S, V / p**2)))


def yp08(gamma=0.45):
    return lambda A: gamma + (1 - gamma) * A * A


def wm17(gamma=5 / 9):
    return lambda A: gamma - 2 / 9 * A * A + (11 / 9 - gamma) * A**4


class Separation:
    """Persson's mean separation (Phys. Rev. Lett. 99 (2007) 125502) with the Yang-Persson weight
    omega = P (gamma + (1 - gamma) P^2), P = erf(y / sqrt 2), y = p / sqrt(V(q)) (gamma = 1: the original theory):

        u = (pi/2) E* int q^2 C g(p/sigma) / sigma dq,   g(y) = int_y^inf omega'(t)/t dt,   sigma = sqrt(V(q)),

    and K = p / (dU/dp) with dU/dp = (pi/2) E* int q^2 C omega'(p/sigma) / sigma dq.  g = gamma E1(y^2/2)/sqrt(2 pi)
    + 3 (1 - gamma) sqrt(2/pi) int_y^inf exp(-t^2/2) erf(t/sqrt2)^2 / t dt, the last integral tabulated here; the q
    integral on Gauss-Legendre nodes, in s with q = q_l + (q_r - q_l) s^2 below the roll-off (1/sigma is singular at
    q_l) and in ln q above it.  ``q_from`` truncates the spectrum (sigma^2 = V(q) - V(q_from)).
    """

    def __init__(self, spec: SelfAffine, E_star, gamma=1.0):
        self.spec, self.E, self.gamma = spec, E_star, gamma
        t = np.linspace(0.0, 40.0, 100001)
        f = np.exp(-0.5 * t * t) * erf(t / math.sqrt(2)) ** 2 / np.where(t > 0, t, 1.0)
        cum = cumulative_simpson(f, x=t, initial=0.0)
        self._t, self._tail = t, cum[-1] - cum

    def g(self, y):
        y = np.asarray(y, dtype=float)
        with np.errstate(over="ignore"):
            e1 = exp1(np.minimum(0.5 * y * y, 700.0))
        rest = np.interp(y, self._t, self._tail, right=0.0)
        return self.gamma * e1 / math.sqrt(2 * np.pi) + 3 * (1 - self.gamma) * math.sqrt(2 / np.pi) * rest

    def domega(self, y):
        P = erf(y / math.sqrt(2))
        return math.sqrt(2 / np.pi) * np.exp(-0.5 * y * y) * (self.gamma + 3 * (1 - self.gamma) * P * P)

    def _nodes(self, q_from=None):
        s = self.spec
        q0 = s.q_l if q_from is None else q_from
        x, w = roots_legendre(300)  # (tridiagonal: numpy's leggauss solves a dense eigenproblem)
        nodes, weights = [], []
        if q0 < s.q_r:
            for a, b in ((0.0, 0.1), (0.1, 1.0)):  # q = q0 + (q_r - q0) u^2
                u, wu = 0.5 * (b - a) * x + 0.5 * (a + b), 0.5 * (b - a) * w
                nodes.append(q0 + (s.q_r - q0) * u * u)
                weights.append(wu * 2 * (s.q_r - q0) * u)
            lo = s.q_r
        else:
            lo = q0
        edges = np.geomspace(lo, s.q_s, 9)
        for a, b in zip(edges[:-1], edges[1:]):
            t = 0.5 * (np.log(b) - np.log(a)) * x + 0.5 * (np.log(a) + np.log(b))
            nodes.append(np.exp(t))
            weights.append(0.5 * (np.log(b) - np.log(a)) * w * np.exp(t))
        q, wq = np.concatenate(nodes), np.concatenate(weights)
        V0 = 0.0 if q_from is None else float(self.spec.V(q_from, self.E))
        sigma = np.sqrt(np.maximum(self.spec.V(q, self.E) - V0, 1e-300))
        return q, wq * 0.5 * np.pi * self.E * q * q * self.spec.C(q) / sigma, sigma

    def u(self, p, q_from=None):
        q, w, sigma = self._nodes(q_from)
        return np.array([np.sum(w * self.g(pi / sigma)) for pi in np.atleast_1d(p)])

    def K(self, p):
        q, w, sigma = self._nodes()
        return np.array([pi / np.sum(w * self.domega(pi / sigma)) for pi in np.atleast_1d(p)])

    def u0(self):
        """-du/d ln p as p -> 0: omega'(0) (pi/2) E* int q^2 C / sigma dq."""
        q, w, sigma = self._nodes()
        return float(self.domega(0.0) * np.sum(w))


def strip_areas(p, sigma_Y, tau):
    """(A_el, A_pl, A_non) of the strip 0 < p < sigma_Y: images a = +-p + 2k sigma_Y, each absorbed at 0 by the
    first-passage law (1/2) sign(a) erfc(|a| / sqrt(2 tau)); A_pl is the mirror image p -> sigma_Y - p."""

    def absorbed(p0):
        k = np.arange(-30, 31)
        a_plus, a_minus = p0 + 2 * k * sigma_Y, -p0 + 2 * k * sigma_Y
        f = lambda a: 0.5 * np.sign(a) * erfc(np.abs(a) / math.sqrt(2 * tau))  # noqa: E731
        return float(np.sum(f(a_plus) - f(a_minus)))

    A_non, A_pl = absorbed(p), absorbed(sigma_Y - p)
    return 1 - A_non - A_pl, A_pl, A_non


def test_references_match_the_spectrum_they_describe():
    """The closed-form spectrum here is the one ``from_rms_slope`` builds (else every comparison below is void)."""
    spec = SelfAffine(0.1, 0.8, 2 * np.pi / 1e-3, 4 * np.pi / 1e-3, 2 * np.pi / 1e-6)
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=spec.q_l, q_r=spec.q_r, q_s=spec.q_s)
    q = np.geomspace(spec.q_l, spec.q_s, 50)
    assert np.allclose(psd.C(q), spec.C(q), rtol=1e-12, atol=0)
    # the moment in closed form against quadrature
    m3 = quad(lambda x: x**3 * float(spec.C(x)), spec.q_l, spec.q_r, epsabs=0, epsrel=1e-12)[0]
    m3 += quad(
        lambda lx: math.exp(4 * lx) * float(spec.C(math.exp(lx))),
        math.log(spec.q_r),
        math.log(spec.q_s),
        epsabs=0,
        epsrel=1e-12,
    )[0]
    assert 2 * np.pi * m3 == pytest.approx(0.01, rel=1e-10)
    # the tabulated g of the separation reference against quadrature
    sep = Separation(spec, 1.0, gamma=0.45)
    for y in (1e-3, 0.3, 2.0):
        g = quad(lambda lt: float(sep.domega(math.exp(lt))), math.log(y), math.log(40.0), epsabs=0, epsrel=1e-12)[0]
        assert float(sep.g(y)) == pytest.approx(g, rel=1e-7)


# -- the pages -------------------------------------------------------------------------------------------------------
def test_measured_surfaces_page(capsys):
    ns, out = run("measured_surfaces.md", capsys)
    import os
    import shutil

    for written in (ns["path"], ns["csv_path"]):  # the page's example files, in folders of their own
        shutil.rmtree(os.path.dirname(written))
    h, L, n = ns["heights"], ns["L"], ns["n"]
    # the map's rms height and spectral rms slope, computed here from the heights
    hk = np.fft.fft2(h - h.mean()) / h.size
    q = 2 * np.pi * np.fft.fftfreq(n, d=L / n)
    q2 = np.add.outer(q * q, q * q)
    rms_h, rms_s = float(np.sqrt(np.mean((h - h.mean()) ** 2))), float(np.sqrt(np.sum(q2 * np.abs(hk) ** 2)))
    assert numbers(line_with(out, "rms height: data"))[:2] == pytest.approx([rms_h * 1e6] * 2, abs=1e-4)
    assert numbers(line_with(out, "rms slope:  data"))[:2] == pytest.approx([rms_s] * 2, abs=1e-4)
    # the spectrum carries them: 2 pi int q C dq and 2 pi int q^3 C dq of the imported table, by quadrature
    psd = ns["surf"].psd
    segments = list(zip(psd.q[:-1], psd.q[1:]))
    m1 = sum(quad(lambda x: x * float(psd.C(x)), a, b, epsabs=0, epsrel=1e-8)[0] for a, b in segments)
    m3 = sum(quad(lambda x: x**3 * float(psd.C(x)), a, b, epsabs=0, epsrel=1e-8)[0] for a, b in segments)
    assert math.sqrt(2 * np.pi * m1) == pytest.approx(rms_h, rel=1e-3)
    assert math.sqrt(2 * np.pi * m3) == pytest.approx(rms_s, rel=1e-3)
    band = numbers(line_with(out, "band: q from"))
    assert band[0] == pytest.approx(2 * np.pi / L, rel=1e-3)
    assert np.pi * n / L < band[1] < np.sqrt(2) * np.pi * n / L  # above the Nyquist wavenumber, below the corner
    # the unit mix-up: heights in um with the size in m make the slope 1e6 too steep; the size in um undoes it
    wrong = numbers(out.splitlines()[3])[0]
    assert wrong == pytest.approx(1e6 * rms_s, rel=1e-3)
    fixed = numbers(out.splitlines()[4])
    assert fixed[0] == pytest.approx(rms_s, abs=1e-4) and fixed[1] == pytest.approx(rms_h * 1e6, abs=1e-4)
    # the crop: central differences of the detrended heights
    crop = h[:200, :160]
    x, y = np.meshgrid(np.arange(200) - 99.5, np.arange(160) - 79.5, indexing="ij")
    X = np.stack([np.ones(crop.size), x.ravel(), y.ravel()], axis=1)
    flat = crop - (X @ np.linalg.lstsq(X, crop.ravel(), rcond=None)[0]).reshape(crop.shape)
    g2 = sum(np.mean(np.gradient(flat, L / n, axis=ax) ** 2) for ax in (0, 1))
    crop_line = line_with(out, "central differences")
    assert numbers(crop_line)[0] == pytest.approx(math.sqrt(g2), abs=1e-4)
    assert max(abs(v) for v in numbers(crop_line.split("data - 1:")[1])) < 1e-2  # the import's 1 % check holds
    # the contact.engineering export of the model: its rms slope and height in closed form
    model = SelfAffine(0.1, 0.8, 2 * np.pi / L, 4 * np.pi / L, np.pi * n / L)
    ce = numbers(line_with(out, "q/pi*2d:").split(":", 1)[1])  # slope, height [um] of the file; of the model
    assert ce[0] == pytest.approx(0.1, abs=2e-4) and ce[2] == pytest.approx(0.1, abs=1e-5)
    rms_model = math.sqrt(2 * np.pi * float(model.moment(1, model.q_s)))
    assert ce[3] * 1e-6 == pytest.approx(rms_model, rel=1e-4) and ce[1] * 1e-6 == pytest.approx(rms_model, rel=3e-3)
    # the cut-offs: A* = erf(p / sqrt(2V)), V = E*^2 <|grad h|^2> / 4 of the band kept
    for line in (ln for ln in out.splitlines() if ln.startswith("q_s =")):
        q_s, slope, A = numbers(line)[0], numbers(line)[1], numbers(line)[-1]
        segs = [(a, min(b, q_s)) for a, b in segments if a < q_s]
        band_slope = math.sqrt(
            2 * np.pi * sum(quad(lambda x: x**3 * float(psd.C(x)), a, b, epsabs=0, epsrel=1e-8)[0] for a, b in segs)
        )
        assert slope == pytest.approx(band_slope, abs=1e-4)
        assert close_to_shown(A, erf(10e6 / math.sqrt(2 * 1.15e11**2 * band_slope**2 / 4)), 1e-6)


def test_contact_area_page(capsys):
    ns, out = run("contact_area.md", capsys)
    E_star, p_bar = 10e6 / 0.75, np.array([0.1e6, 0.3e6, 1e6])
    V = E_star**2 * 0.1**2 / 4  # eq:VV_relation with the rms slope 0.1
    assert numbers(line_with(out, "sqrt(V)"))[0] == pytest.approx(math.sqrt(V) / 1e6, abs=1e-4)
    references = {
        "Persson 2001": dict(S=None),
        "YP08": dict(S=yp08()),
        "WM17": dict(S=wm17()),
        "Xu24": dict(xu_gamma=0.45),
        "YP08, gamma 0.42": dict(S=yp08(0.42)),
        "S = 0.5 + 0.5 A^2": dict(S=lambda A: 0.5 + 0.5 * A * A),
    }
    psd = ns["psd"]
    for name, kw in references.items():
        ref = [area(p, V, **kw) for p in p_bar]
        assert numbers(line_with(out, name + ":").split("A* =")[1]) == pytest.approx(ref, abs=6e-6), name
        fudge = ns["models"][name]
        A = pf.exact(pf.ContactProblem(psd, E_star=E_star, p_bar=p_bar, fudge=fudge)).contact_area
        assert A == pytest.approx(ref, rel=1e-7), name
    fv = numbers(line_with(out, "fv, YP08"))
    assert fv[1] == pytest.approx(area(p_bar[0], V, S=yp08()), abs=6e-6) and fv[-1] < 1e-5
    # the BEM table is the committed results file of the command it names
    text = (DOCS / "contact_area.md").read_text(encoding="utf8")
    assert "python benchmarks/calibration_vs_bem.py" in text
    results = (RESULTS / "calibration_vs_bem.md").read_text(encoding="utf8")

    def held_out(H, label):
        section = results.split(f"## A*, H={H}\n")[1].split("##")[0]
        return re.search(rf"\| {re.escape(label)} \| — \| ([\d.]+%) \|", section).group(1)

    for page_label, label in (
        ("Persson 2001 (`None`)", "Persson 2001"),
        ("YP08, γ = 0.45", "YP08 γ=0.45"),
        ("WM17, γ = 5/9", "WM17 γ=5/9"),
        ("Xu24, γ = 0.45", "Xu24 γ=0.45"),
    ):
        assert f"| {page_label} | {held_out('0.8', label)} | {held_out('0.3', label)} |" in text, page_label


def test_separation_stiffness_page(capsys):
    ns, out = run("separation_stiffness.md", capsys)
    E_star, p_bar = 10e6 / 0.75, ns["p_bar"]
    spec = SelfAffine(0.1, 0.8, 2 * np.pi / 1e-3, 4 * np.pi / 1e-3, 2 * np.pi / 1e-6)
    for label, gamma in (("None:", 1.0), ("YP08:", 0.45)):
        sep = Separation(spec, E_star, gamma)
        line = line_with(out, label)
        u_shown = numbers(line.split("u =")[1].split("um")[0])
        K_shown = numbers(line.split("K =")[1])
        u_ref, K_ref = sep.u(p_bar), sep.K(p_bar)
        assert u_shown == pytest.approx(u_ref * 1e6, rel=6e-4), label
        assert K_shown == pytest.approx(K_ref, rel=6e-4), label
        ms = pf.MeanSeparation(ns["psd"], E_star=E_star, fudge=None if gamma == 1.0 else "YP08")
        assert ms.mean_separation(p_bar) == pytest.approx(u_ref, rel=1e-6), label
        assert ms.stiffness(p_bar) == pytest.approx(K_ref, rel=1e-6), label
    # the small-load law of YP08: u0 = -du/d ln p as p -> 0, beta from u = u0 ln(beta E* / p) at a tiny load
    u0_ref = sep.u0()
    p_small = 1e-7 * math.sqrt(spec.V(spec.q_s, E_star))
    beta_ref = p_small / E_star * math.exp(float(sep.u(p_small)[0]) / u0_ref)
    law = numbers(line_with(out, "small loads"))
    assert close_to_shown(law[-2], u0_ref * 1e6, 1e-4) and close_to_shown(law[-1], beta_ref, 1e-4)
    assert ns["u0"] == pytest.approx(u0_ref, rel=1e-6) and ns["beta"] == pytest.approx(beta_ref, rel=1e-4)
    assert close_to_shown(
        numbers(line_with(out, "rms height"))[0], math.sqrt(2 * np.pi * spec.moment(1, spec.q_s)) * 1e6, 1e-4
    )
    # the same through a problem: K at 0.1 MPa of YP08
    assert numbers(line_with(out, "corrected-area").split("K at")[1])[1] == pytest.approx(sep.K(0.1e6)[0], rel=6e-4)
    # the BEM table is the committed results file of the command it names
    text = (DOCS / "separation_stiffness.md").read_text(encoding="utf8")
    assert "python benchmarks/separation_vs_bem.py" in text
    results = (RESULTS / "separation_vs_bem.md").read_text(encoding="utf8")

    def err(label, weighting):
        return re.search(rf"\| {re.escape(label)}{weighting} \| nominal \| ([\d.]+%) \|", results).group(1)

    for page_label, label in (
        ("YP08, γ = 0.45", "YP08 γ=0.45, "),
        ("WM17", "WM17, "),
        ("Xu24", "Xu24, "),
    ):
        assert f"| {page_label} | {err(label, 'yang-persson')} | {err(label, 'corrected-area')} |" in text, page_label
    none = re.search(r"\| Persson \(no fudge\) \| nominal \| ([\d.]+%) \|", results).group(1)
    assert f"| Persson 2001 (`None`) | {none} | {none} |" in text


def test_gaps_leakage_page(capsys):
    ns, out = run("gaps_leakage.md", capsys)
    E_star, p_bar = 10e6 / 0.75, np.array([0.05e6, 0.2e6])
    spec = SelfAffine(0.1, 0.8, 2 * np.pi / 1e-3, 4 * np.pi / 1e-3, 2 * np.pi / 1e-6)
    V = spec.V(spec.q_s, E_star)
    sep = Separation(spec, E_star, gamma=0.45)
    A_ref = np.array([area(p, V, S=yp08()) for p in p_bar])
    u_ref = sep.u(p_bar)
    first = line_with(out, "contact area")
    assert numbers(first.split("mean separation")[0]) == pytest.approx(A_ref, abs=6e-5)
    assert numbers(first.split("mean separation")[1].split("um")[0]) == pytest.approx(u_ref * 1e6, abs=6e-5)
    gd = ns["gd"]
    assert gd.contact_fraction == pytest.approx(A_ref, rel=1e-7)
    assert gd.mean_separation == pytest.approx(u_ref, rel=1e-5)
    assert np.all(gd.mean > gd.mean_separation)  # the folded normals' mirror terms
    # the cdf shown is the atom plus the density integrated here
    cdf = [
        A + quad(lambda u: float(gd.pdf(u)[i]), 0, 1e-6, limit=200, epsabs=0, epsrel=1e-8)[0]
        for i, A in enumerate(A_ref)
    ]
    assert numbers(line_with(out, "P(u < 1 um)"))[1:] == pytest.approx(cdf, abs=2e-4)
    # the flow through the effective gap: Q = (L_y / L_x) u^3 dp / (12 eta), both methods
    for method in ("critical-junction", "effective-medium"):
        line = line_with(out, method)
        Q, u_eff = numbers(line.split("Q =")[1].split("m^3")[0]), numbers(line.split("u_eff =")[1])
        flow = [(u * 1e-9) ** 3 * 1e5 / (12 * 1e-3) for u in u_eff]
        assert Q == pytest.approx(flow, rel=3e-3), method
    # the critical junction: A(zeta_c) = 0.42 on the YP08 area, its gap u_1 = d(A u)/dA of the truncated spectrum's
    # separation under p / A (Lorenz & Persson)
    leak = pf.leak_rate(ns["problem"], viscosity=1e-3, pressure_drop=1e5, method="critical-junction", full_output=True)
    for i, p in enumerate(p_bar):
        z_c = float(leak["zeta_c"][i])
        assert area(p, spec.V(z_c * spec.q_l, E_star), S=yp08()) == pytest.approx(0.42, abs=1e-6)
        dz = 1e-3 * z_c
        zs = (z_c - dz, z_c + dz)
        A = [area(p, spec.V(z * spec.q_l, E_star), S=yp08()) for z in zs]
        Au = [a * float(sep.u(p / a, q_from=z * spec.q_l)[0]) for a, z in zip(A, zs)]
        u1 = (Au[1] - Au[0]) / (A[1] - A[0])
        assert float(leak["effective_gap"][i]) == pytest.approx(u1, rel=2e-3)
    # Barber: h = 2 K / (E* (1/k1 + 1/k2)) with Persson's stiffness
    h = 2 * sep.K(p_bar) / (E_star * (1 / 0.2 + 1 / 50.0))
    assert numbers(line_with(out, "thermal contact conductance"))[:2] == pytest.approx(h, rel=6e-4)
    # the BEM table is the committed results file of the command it names (WM17, nominal spectrum)
    text = (DOCS / "gaps_leakage.md").read_text(encoding="utf8")
    results = (RESULTS / "interface_vs_bem.md").read_text(encoding="utf8")
    assert "python benchmarks/interface_vs_bem.py" in text
    for heading, row in (
        ("## Gap distribution over the non-contact area", "gap distribution (non-contact part)"),
        ("Effective medium (2-D Bruggeman on P(u)):", "leak rate, effective medium"),
        ("Critical junction (A_c = 0.42):", "leak rate, critical junction"),
    ):
        values = re.search(r"\| WM17 \|(.*?)\|\n", results.split(heading)[1]).group(1)
        page_row = next(ln for ln in text.splitlines() if ln.startswith(f"| {row}"))
        assert page_row.endswith(f"|{values}|"), row


def test_adhesion_page(capsys):
    ns, out = run("adhesion.md", capsys)
    E_star = 70e9 / (2 * (1 - 0.17**2))
    w, rho, p_rep = 0.1, 1e-9, np.array([2e6, 20e6])
    spec = SelfAffine(0.01, 0.8, 2 * np.pi / 1e-5, 4 * np.pi / 1e-5, 2 * np.pi / 1e-8)
    first = numbers(line_with(out, "rms height"))
    assert first[0] == pytest.approx(math.sqrt(2 * np.pi * spec.moment(1, spec.q_s)) * 1e9, abs=1e-4)
    assert first[-1] == pytest.approx(E_star / 1e9, abs=1e-4)
    # p_att = A sigma(0) + int P(u) sigma(u) du, by Simpson's rule over the gap distribution's density (DMT)
    from scipy.integrate import simpson

    u = np.concatenate(([0.0], np.geomspace(1e-16, 60 * rho, 2001)))  # the density is sharp near u = 0
    s = w / rho * np.exp(-u / rho)

    def attraction(p, A):
        gd = pf.gap_distribution(pf.ContactProblem(ns["psd"], E_star=E_star, p_bar=p))
        return A * w / rho + simpson(gd.pdf(u) * s, x=u, axis=-1)

    V = spec.V(spec.q_s, E_star)
    p_att = attraction(p_rep, erf(p_rep / math.sqrt(2 * V)))  # the contact atom: eq:Area_Persson
    line = line_with(out, "p_rep")
    assert numbers(line.split("p_att")[1].split("MPa")[0]) == pytest.approx(p_att / 1e6, abs=6e-3)
    assert numbers(line.split("applied")[1]) == pytest.approx((p_rep - p_att) / 1e6, abs=6e-3)
    assert ns["ad"].p_attractive == pytest.approx(p_att, rel=1e-5)
    # the pull-off: the least applied load over a fine grid of repulsive loads
    grid = ns["ad"].p_rep_at_pull_off * np.geomspace(0.8, 1.25, 31)
    f = grid - attraction(grid, erf(grid / math.sqrt(2 * V)))
    k = int(np.argmin(f))
    assert 0 < k < grid.size - 1
    assert numbers(line_with(out, "pull-off"))[0] == pytest.approx(-f[k] / 1e6, rel=2e-3)
    # the criteria: Tabor-like mu = R^(1/3) (w/E*)^(2/3) / rho with R = 1 / h''_rms, h''_rms = (1/2) sqrt(2 pi m5);
    # Pastewka-Robbins h' E* rho / (2 w) (h'^2 / (h'' rho))^(2/3); Persson-Tosatti w A_true/A0 > U_el
    h1, h2 = 0.01, 0.5 * math.sqrt(2 * np.pi * spec.moment(5, spec.q_s))
    tabor = (1 / h2) ** (1 / 3) * (w / E_star) ** (2 / 3) / rho
    pr_number = h1 * E_star * rho / (2 * w) * (h1 * h1 / (h2 * rho)) ** (2 / 3)
    U_el = 0.5 * np.pi * E_star * spec.moment(2, spec.q_s)
    criteria = line_with(out, "Tabor-like")
    assert numbers(criteria)[0] == pytest.approx(tabor, abs=6e-5)
    assert numbers(criteria)[-1] == pytest.approx(pr_number, abs=6e-5)
    assert ("sticky: True" in criteria) == (w * (1 + h1 * h1 / 2) > U_el)


def test_elastoplastic_page(capsys):
    ns, out = run("elastoplastic.md", capsys)
    E_star, p_bar, sigma_Y = 210e9 / (2 * 0.91), np.array([50e6, 200e6]), 2e9
    V = E_star**2 * 0.02**2 / 4
    assert numbers(line_with(out, "sqrt(V)"))[0] == pytest.approx(math.sqrt(V) / 1e9, abs=1e-4)
    assert numbers(line_with(out, "elastic only")) == pytest.approx(
        [erf(p / math.sqrt(2 * V)) for p in p_bar], abs=6e-6
    )
    strip = [strip_areas(p, sigma_Y, V) for p in p_bar]
    line = line_with(out, "sigma_Y 2 GPa")
    A_el = numbers(line.split("A_el =")[1].split(";")[0])
    A_pl = numbers(line.split("A_pl =")[1].split(";")[0])
    assert A_el == pytest.approx([s[0] for s in strip], abs=6e-6)
    assert A_pl == pytest.approx([s[1] for s in strip], abs=6e-6)
    ex = ns["plastic"]
    assert ex.plastic_area == pytest.approx([s[1] for s in strip], rel=1e-9)
    assert ex.noncontact_area == pytest.approx([s[2] for s in strip], rel=1e-9)
    # the zero-contact-area paradox: far beyond the cut-off A_el -> 0 and A_pl -> p / sigma_Y
    far = strip_areas(p_bar[1], sigma_Y, 30 * sigma_Y**2)
    assert far[0] < 1e-12 and far[1] == pytest.approx(p_bar[1] / sigma_Y, rel=1e-12)
    # the moving wall (no closed form): the areas add to 1, and the estimate shown is small (its honesty: the slow
    # test below, against a refined run)
    sol = ns["sol"]
    assert sol.elastic_area[-1] + sol.plastic_area[-1] + sol.noncontact_area[-1] == pytest.approx([1, 1], abs=1e-12)
    est = numbers(line_with(out, "A_el =").split("error estimate of A_pl")[1])
    assert all(0 < e < 1e-4 for e in est)


@pytest.mark.slow  # a fine moving-wall run (seconds)
def test_elastoplastic_page_moving_wall_estimate_is_honest():
    """The error estimate the page shows bounds the true error of its fv run (200 cells), against a run at 8x the
    resolution in p and zeta (second order: ~1/64 of the error, itself checked by its own estimate)."""
    ns = run_page("elastoplastic.md")
    fine = pf.solve(ns["problem"], method="fv", n_p=1600, n_steps=800)
    est_fine = fine.error_estimate["plastic_area"][-1]
    assert np.all(est_fine < 0.05 * ns["sol"].error_estimate["plastic_area"][-1])
    err = np.abs(ns["sol"].plastic_area[-1] - fine.plastic_area[-1])
    assert np.all(err <= ns["sol"].error_estimate["plastic_area"][-1] + est_fine)
