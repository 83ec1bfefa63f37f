"""method="chebyshev" on the separable form B2 = b(p) dV/dzeta (the exponential path): accuracy against independent
references, spectral order, an estimate above the error, and which problems are taken as separable.

References written here, none of them the engine:
- the image solution of Brownian motion with constant drift c and diffusion b, absorbed at p = 0
  (density phi(p - p_bar - cV) - exp(-2 c p_bar / b) phi(p + p_bar - cV), variance bV) -- the homogenised
  closed form for b = 1, c = 0;
- B2 = (1 + p / (2 p_bar)) dV/dzeta: X = 8 p_bar (p + 2 p_bar) is a squared Bessel process of dimension 0 in V,
  whose free transition density starts a Chebyshev solution on a finer, wider grid with exact stepping in V
  (written below, a different map, start and domain from the engine's);
- B2 = g(zeta) dV/dzeta is the homogenised theory at variance tau = int g dV: its image solution, with tau by
  adaptive quadrature written here.
"""

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.integrate import quad
from scipy.special import erf, ive

import persson_fp as pf

REF = pf.ContactProblem.reference()
PSD, PB, VMAX = REF.psd, float(REF.p_bar[0]), float(REF.V_max)
DV = PSD.dV_dzeta
SV = float(np.sqrt(PSD.V()))


def _problem(b=1.0, c=0.0, p_bar=PB):
    dV = PSD.dV_dzeta
    B1 = None if c == 0 else (lambda p, z: np.full(np.shape(p), c * float(dV(z))))
    return pf.FokkerPlanckProblem(PSD, p_bar=p_bar, B1=B1, B2=lambda p, z: np.full(np.shape(p), b * float(dV(z))))


def _image(p, p_bar, V, b=1.0, c=0.0):
    s2 = b * V
    phi = lambda u: np.exp(-0.5 * u * u / s2) / np.sqrt(2 * np.pi * s2)  # noqa: E731
    return phi(p - p_bar - c * V) - np.exp(-2 * c * p_bar / b) * phi(p + p_bar - c * V)


def chebyshev_l1(sol, ref_pdf):
    """(Also used by benchmarks/general_engine.py.)

    int |P0 - ref| dp at the last station, first load: the polynomial (barycentric form in the Chebyshev
    coordinate of the solution's map) on 20 001 points, trapezoid (its error << the tested levels)."""
    p, P, g = np.atleast_2d(sol.p)[-1], sol.P0_all[-1, 0], sol.info["grid"]
    n = p.size - 1
    c, e = float(g["centre"][0]), float(g["eps"][0])
    a1 = np.arcsinh(-c / e)
    h = 0.5 * (np.arcsinh((p[-1] - c) / e) - a1)
    x = -np.cos(np.pi * np.arange(n + 1) / n)
    q = np.linspace(0.0, p[-1], 20001)[1:-1]
    d = ((np.arcsinh((q - c) / e) - a1) / h - 1.0)[:, None] - x[None, :]
    d[d == 0] = 1e-300
    wb = np.ones(n + 1)
    wb[0] = wb[-1] = 0.5
    wb *= (-1.0) ** np.arange(n + 1)
    t = wb / d
    Pq = (t @ P) / t.sum(axis=1)
    return float(np.trapezoid(np.abs(Pq - ref_pdf(q)), q))


def test_homogenised_matches_the_closed_form_and_the_estimate_covers_it():
    for tol in (1e-6, 1e-9):
        sol = pf.solve(REF, method="chebyshev", tol=tol)
        c = sol.compare()
        est = sol.info["error_estimate"]
        assert float(np.max(c.L1)) <= tol and float(np.max(c.area_error)) <= tol
        assert np.all(est["L1"] >= c.L1) and np.all(est["noncontact_area"] >= c.area_error)
        assert abs(float(sol.load[0]) - PB) / PB <= tol
        assert sol.info["mass_balance_residual"] <= tol  # what left the domain crossed a wall


@pytest.mark.filterwarnings("ignore:chebyshev. P0 has negative values")  # coarse degrees ripple, as expected
def test_observed_order_is_at_least_four():
    # fixed degrees, an exact start (b = 1: the expansion is the image solution): the error is the grid's alone
    ns = np.array([16, 20, 24, 28, 32])
    errs = []
    for n in ns:
        sol = pf.solve(REF, method="chebyshev", n_p=int(n), V0_fraction=1e-2)
        errs.append(float(sol.compare().L1[0, 0]))
    slope = -np.polyfit(np.log(ns), np.log(errs), 1)[0]
    assert errs[-1] < 1e-5 and slope >= 4.0, (errs, slope)


@pytest.mark.parametrize("seed", range(6))
def test_estimate_above_the_true_error_with_drift(seed):
    rng = np.random.default_rng(seed)
    b = float(rng.uniform(0.3, 3.0))
    c = float(rng.uniform(-1.0, 1.0)) * PB / VMAX
    pb = PB * float(rng.uniform(0.5, 3.0))
    tol = float(10.0 ** rng.uniform(-9, -5))
    sol = pf.solve(_problem(b, c, pb), method="chebyshev", tol=tol)
    ex = lambda q: _image(q, pb, VMAX, b, c)  # noqa: E731
    true = chebyshev_l1(sol, ex)
    est = float(sol.info["error_estimate"]["L1"][-1, 0])
    A_true = abs(float(sol.contact_area[-1]) - float(np.sum(sol.weights * ex(sol.p))))
    assert est <= tol
    assert est >= true or true < 1e-11, (true, est)
    assert float(sol.info["error_estimate"]["elastic_area"][-1, 0]) >= A_true or A_true < 1e-11


def besq_reference(p_bar, V_end, n=360, V_start_frac=2e-3, e_k=8.0, L_k=60.0, r=1.0):
    """(Also used by benchmarks/general_engine.py.)

    P(p, V_end) for B2 = (1 + r p / (2 p_bar)) dV/dzeta: exact free start at a small V, then exp(L dV).

    X = (8 p_bar / r)(p + 2 p_bar / r) has quadratic variation 4X dV: a squared Bessel process of dimension 0."""
    V_s = V_start_frac * V_end
    L = p_bar + L_k * np.sqrt(V_end)
    # Chebyshev points clustered about p_bar by p = p_bar + e tan(...) (a map unlike the engine's)
    j = np.arange(n + 1)
    x = -np.cos(np.pi * j / n)
    e = e_k * np.sqrt(V_s)
    t0, t1 = np.arctan(-p_bar / e), np.arctan((L - p_bar) / e)
    s = t0 + (t1 - t0) * (x + 1) / 2
    p = p_bar + e * np.tan(s)
    dpdx = e * (t1 - t0) / 2 / np.cos(s) ** 2
    d2pdx2 = 2 * e * ((t1 - t0) / 2) ** 2 * np.tan(s) / np.cos(s) ** 2
    cc = np.ones(n + 1)
    cc[0] = cc[-1] = 2
    cc *= (-1.0) ** j
    D = np.outer(cc, 1 / cc) / (x[:, None] - x[None, :] + np.eye(n + 1))
    D -= np.diag(D.sum(1))
    D2 = (D @ D) / dpdx[:, None] ** 2 - (d2pdx2 / dpdx**3)[:, None] * D
    b = 1 + r * p / (2 * p_bar)
    Lop = (0.5 * D2 * b[None, :])[1:-1, 1:-1]
    kappa = 8 * p_bar / r
    X0, X = kappa * (p_bar + 2 * p_bar / r), kappa * (p + 2 * p_bar / r)
    z = np.sqrt(X0 * X) / V_s
    P0 = kappa / (2 * V_s) * np.sqrt(X0 / X) * np.exp(-((np.sqrt(X) - np.sqrt(X0)) ** 2) / (2 * V_s)) * ive(1, z)
    P = np.zeros(n + 1)
    P[1:-1] = sla.expm(Lop * (V_end - V_s)) @ P0[1:-1]
    # Clenshaw--Curtis weights (x) times dp/dx
    th = np.pi * j[1:-1] / n
    w = np.zeros(n + 1)
    v = np.ones(n - 1)
    w[0] = w[n] = 1 / (n * n - 1)
    for k in range(1, n // 2):
        v -= 2 * np.cos(2 * k * th) / (4 * k * k - 1)
    v -= np.cos(n * th) / (n * n - 1)
    w[1:-1] = 2 * v / n
    w = w * dpdx

    def pdf(q):
        xq = t_inv(q)
        d = xq[:, None] - x[None, :]
        d[d == 0] = 1e-300
        wb = np.ones(n + 1)
        wb[0] = wb[-1] = 0.5
        wb *= (-1.0) ** j
        tt = wb / d
        return np.where(q < L, (tt @ P) / tt.sum(1), 0.0)

    def t_inv(q):
        return (np.arctan((q - p_bar) / e) - t0) / ((t1 - t0) / 2) - 1

    return pdf, float(w @ P), float(w @ (p * P))


@pytest.mark.slow
def test_squared_bessel_reference():
    # two reference resolutions (map width, start, degree): their spread u bounds the reference's own error
    # (round-off in the exponential of the strongly clustered grid limits it to ~1e-10)
    pdf, A_ref, F_ref = besq_reference(PB, VMAX, n=160, V_start_frac=3e-3, e_k=50.0, L_k=45.0)
    pdf2, A_ref2, _ = besq_reference(PB, VMAX, n=200, V_start_frac=1e-3, e_k=8.0, L_k=45.0)
    q = np.linspace(0.0, 45.0 * np.sqrt(VMAX), 20001)[1:-1]
    u = max(abs(A_ref - A_ref2), float(np.trapezoid(np.abs(pdf(q) - pdf2(q)), q)), 1e-11)
    assert u < 5e-10 and abs(F_ref - PB) / PB < 5e-10
    fp = pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: PSD.dV_dzeta(z) * (1 + p / (2 * PB)))
    for tol in (1e-6, 1e-8):
        sol = pf.solve(fp, method="chebyshev", tol=tol)
        true_A = abs(float(sol.contact_area[-1]) - A_ref)
        true_L1 = chebyshev_l1(sol, pdf)
        est = sol.info["error_estimate"]
        assert true_L1 <= tol + u and true_A <= tol + u, (tol, true_L1, true_A)
        assert float(est["L1"][-1, 0]) >= true_L1 - u
        assert float(est["elastic_area"][-1, 0]) >= true_A - u


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4))
def test_estimate_above_the_true_error_random_squared_bessel(seed):
    # random slope r of B2 = (1 + r p / (2 p_bar)) dV/dzeta, load and tol; reference: the squared Bessel start
    rng = np.random.default_rng(100 + seed)
    r, pb, tol = float(rng.uniform(0.2, 3.0)), PB * float(rng.uniform(0.7, 2.0)), float(10.0 ** rng.uniform(-8, -5))
    pdf, A_ref, F_ref = besq_reference(pb, VMAX, n=160, V_start_frac=3e-3, e_k=50.0, L_k=45.0, r=r)
    _, A_ref2, _ = besq_reference(pb, VMAX, n=200, V_start_frac=1e-3, e_k=8.0, L_k=45.0, r=r)
    u = max(abs(A_ref - A_ref2), 1e-11)
    fp = pf.FokkerPlanckProblem(PSD, p_bar=pb, B2=lambda p, z: PSD.dV_dzeta(z) * (1 + r * p / (2 * pb)))
    sol = pf.solve(fp, method="chebyshev", tol=tol)
    true_A, true_L1 = abs(float(sol.contact_area[-1]) - A_ref), chebyshev_l1(sol, pdf)
    est = sol.info["error_estimate"]
    assert true_L1 <= tol + u and true_A <= tol + u
    assert float(est["L1"][-1, 0]) >= true_L1 - u and float(est["elastic_area"][-1, 0]) >= true_A - u


def test_loads_advance_together():
    pr = pf.ContactProblem.reference(p_bar_ratio=np.array([0.3, 0.5, 2.0]))
    sol = pf.solve(pr, method="chebyshev", tol=1e-8, zeta_out=[2.0, pr.zeta_max])
    c = sol.compare()
    assert float(np.max(c.area_error)) <= 1e-8
    assert np.all(sol.info["error_estimate"]["noncontact_area"] >= c.area_error)


def test_linear_drift_obeys_the_moment_law():
    # B1 = -a p dV/dzeta: d/dV int p P dp = int B1/(dV/dzeta) P dp = -a int p P dp (walls: P = 0, the far wall's
    # flux negligible), so the load is p_bar exp(-a V) exactly -- an independent check of drift and start
    a = 2.0 / VMAX
    dV = PSD.dV_dzeta
    fp = pf.FokkerPlanckProblem(
        PSD, p_bar=PB, B1=lambda p, z: -a * p * dV(z), B2=lambda p, z: (1 + p / (2 * PB)) * dV(z)
    )
    sol = pf.solve(fp, method="chebyshev", tol=1e-9)
    exact_load = PB * np.exp(-a * VMAX)
    err = abs(float(sol.load[-1]) - exact_load) / PB
    assert err <= 1e-8 and err <= float(sol.info["error_estimate"]["load"][-1, 0])


def _bump(z):  # zero at the 9 log-spaced probe magnifications of [1, 128], up to 4x between them
    return 1.0 + 3.0 * np.maximum(0.0, 1.0 - ((z - 4.75) / 1.25) ** 2) ** 2


def test_a_zeta_dependence_between_the_probes_is_not_taken_as_separable():
    pb = 0.5 * SV
    pr = pf.FokkerPlanckProblem(PSD, p_bar=pb, B2=lambda p, z: _bump(z) * DV(z) * np.ones_like(p))
    pts = [PSD.zeta_r, 3.5, 4.75, 6.0]
    tau = quad(lambda z: float(_bump(z) * DV(z)), 1.0, PSD.zeta_max, points=pts, epsabs=0.0, epsrel=1e-13, limit=500)
    exact = float(erf(pb / np.sqrt(2.0 * tau[0])))  # A* of the image solution at variance tau (eq:Area)
    assert abs(exact - 0.365) < 1e-3  # the bump matters: without it A* = 0.3829
    for method in ("chebyshev", "auto"):
        sol = pf.solve(pr, method=method, tol=1e-8)
        err = abs(float(sol.contact_area[-1]) - exact)
        assert err <= max(float(np.max(sol.error_estimate["contact_area"])), 1e-12)
        assert err < 1e-8


@pytest.mark.parametrize(
    "B2",
    [
        lambda p, z: DV(z),  # a scalar (broadcast over p)
        lambda p, z: [DV(z)] * np.size(p),  # a list
        lambda p, z: np.array(DV(z) * np.ones_like(p), order="F"),  # a copy, not a view
    ],
)
def test_the_separable_confirmation_accepts_every_coefficient_form_the_checked_path_does(B2):
    # the quadrature confirming B2 = b(p) dV/dzeta calls B2 directly where it returns a float64 array of p's shape
    # and goes through the checked path otherwise: every form gives the image solution A* = erf(p_bar / sqrt(2V))
    pb = 0.5 * SV
    sol = pf.solve(pf.FokkerPlanckProblem(PSD, p_bar=pb, B2=B2), method="chebyshev", tol=1e-8)
    exact = float(erf(pb / np.sqrt(2.0 * PSD.V())))
    assert sol.info["path"] == "exponential"
    assert abs(float(sol.contact_area[-1]) - exact) < 1e-8
