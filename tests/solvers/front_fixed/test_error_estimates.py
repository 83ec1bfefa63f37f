r"""Honesty of the general engine's error estimate: random general problems against independent references.

The references are written here, not taken from the engine:

* **Brownian motion with drift, zeta-dependent diffusion** -- :math:`B_2 = \kappa V'(\zeta)(1 + a\sin(\omega\ln\zeta))`,
  :math:`B_1 = \mu B_2`.  In the clock :math:`T(\zeta) = \int_1^\zeta B_2\,d\zeta` (quadrature below) the pressure is
  a Brownian motion with drift :math:`\mu` absorbed at p = 0, whose density is the image solution with drift,
  :math:`\varphi_T(p - \bar p - \mu T) - e^{-2\mu\bar p}\varphi_T(p + \bar p - \mu T)` (Cox & Miller, The Theory of
  Stochastic Processes, 1965, Sec. 5.7).  a = mu = 0, kappa = 1 is the homogenised image solution.
* **Squared Bessel process** -- :math:`B_2 = (1 + p/(2\bar p))V'(\zeta)`: :math:`X = 8\bar p(p + 2\bar p)` obeys
  :math:`dX = 2\sqrt X\,dW_V`, a squared Bessel process of dimension 0, with the transition density
  :math:`p_V(x, y) = \frac{1}{2V}\sqrt{x/y}\,e^{-(x+y)/2V} I_1(\sqrt{xy}/V)` (Revuz & Yor, Continuous Martingales
  and Brownian Motion, Ch. XI) -- exact for the problem on p > 0 as long as the wall at p = 0 (X = 16 p_bar^2) has
  not been reached: the loads are chosen so that the free density's mass below it is < 1e-13 (checked).
* **A constant hardness** -- the same B1 = mu B2 and zeta-dependent B2 between the absorbing walls 0 and sigma_Y: the
  strip's image series in the clock T, times the Girsanov factor :math:`e^{\mu(p - \bar p) - \mu^2T/2}` of the drift
  (its cell averages from the normal CDF after completing the square, written out here).

Every result is compared by its L1 error of P0 and its contact-area error at every station with its own estimate
(``sol.error_estimate``): none may be more than 2x over it, and a ``tol=`` result none over ``tol``.  The default
run draws a small sample and the slow test 40; ``benchmarks/honesty.py`` draws 320 (the count the engine is held
to, results/honesty.md).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import i1e, ndtr

import persson_fp as pf

PSD = pf.ContactProblem.reference().psd
V_MAX = float(PSD.V(PSD.zeta_max))


def _normal_cdf_avg(edges, centre, var):
    """Cell averages x width of the normal density N(centre, var) on cells ``edges``.

    Right of the centre from the upper tail (a difference of values near 1 loses the small mass: with an image
    weight e^{mu (c - p_bar)} ~ 5e3 that measured as a 3e-10 L1 error of the reference)."""
    z = (edges - centre) / np.sqrt(var)
    return np.where(z[:-1] >= 0.0, -np.diff(ndtr(-z)), np.diff(ndtr(z)))


def _kinks(z):
    """ln zeta of the spectrum's roll-off where it lies inside (0, ln z): dV/dzeta has a kink there, which quad
    alone misjudges (a clock 6e-9 off at zeta = 40 measured)."""
    lr = float(np.log(PSD.zeta_r))
    return [lr] if 0.0 < lr < np.log(z) else None


def _drift_case(rng):
    kappa = float(rng.uniform(0.3, 3.0))
    a = float(rng.choice([0.0, rng.uniform(0.2, 0.8)]))
    omega = float(rng.uniform(1.0, 4.0))
    ratio = float(rng.uniform(0.2, 2.0))
    p_bar = ratio * np.sqrt(kappa * V_MAX)
    mu = float(rng.choice([0.0, rng.uniform(-1.5, 1.5)])) / np.sqrt(kappa * V_MAX)
    dV = PSD.dV_dzeta

    def B2(p, z):
        return np.full(np.shape(p), kappa * float(dV(z)) * (1.0 + a * np.sin(omega * np.log(z))))

    def B1(p, z):
        return mu * B2(p, z)

    def clock(z):
        f = lambda lz: kappa * float(dV(np.exp(lz))) * (1.0 + a * np.sin(omega * lz)) * np.exp(lz)  # noqa: E731
        return quad(f, 0.0, np.log(z), limit=200, epsabs=0.0, epsrel=1e-12, points=_kinks(z))[0]

    def exact(edges, z):
        T = clock(z)
        mass = _normal_cdf_avg(edges, p_bar + mu * T, T) - np.exp(-2 * mu * p_bar) * _normal_cdf_avg(
            edges, -p_bar + mu * T, T
        )
        area = ndtr((p_bar + mu * T) / np.sqrt(T)) - np.exp(-2 * mu * p_bar) * ndtr((-p_bar + mu * T) / np.sqrt(T))
        return mass, area

    kw = {"B2": B2, "B1": B1 if mu != 0.0 else None}
    label = f"drift kappa={kappa:.2f} a={a:.2f} mu*sqrt(kV)={mu * np.sqrt(kappa * V_MAX):.2f} ratio={ratio:.2f}"
    return pf.FokkerPlanckProblem(PSD, p_bar=p_bar, **kw), exact, label, None


def _besq_case(rng):
    z_end = float(rng.uniform(1.5, 8.0))
    V_end = float(PSD.V(z_end))
    p_bar = float(rng.uniform(12.0, 20.0)) * np.sqrt(V_end)
    dV = PSD.dV_dzeta

    def B2(p, z):
        return float(dV(z)) * (1.0 + p / (2.0 * p_bar))

    x0 = 8 * p_bar * (p_bar + 2 * p_bar)

    def density_X(X, V):
        s = np.sqrt(x0 * X) / V
        return (0.5 / V) * np.sqrt(x0 / X) * np.exp(-(x0 + X) / (2 * V) + s) * i1e(s)  # I1 e^{-s} for the range

    def exact(edges, z):
        V = float(PSD.V(z))
        gl_x, gl_w = np.polynomial.legendre.leggauss(8)
        lo, hi = edges[:-1], edges[1:]
        pts = 0.5 * (lo + hi)[:, None] + 0.5 * (hi - lo)[:, None] * gl_x[None, :]
        dens = density_X(8 * p_bar * (pts + 2 * p_bar), V) * 8 * p_bar  # P(p) = p_V(x0, X(p)) dX/dp
        mass = (dens * gl_w).sum(axis=1) * 0.5 * (hi - lo)
        # the wall at p = 0 must not matter yet: the free density's mass below X(0) is negligible
        below = quad(lambda X: density_X(X, V), 1e-300, 8 * p_bar * 2 * p_bar, limit=200)[0]
        assert below < 1e-13
        return mass, 1.0  # A* = 1 up to the (negligible) mass below the wall and beyond the grid

    label = f"BESQ p_bar/sqrt(V)={p_bar / np.sqrt(V_end):.1f} zeta_end={z_end:.2f}"
    return pf.FokkerPlanckProblem(PSD, p_bar=p_bar, B2=B2), exact, label, z_end


def _strip_case(rng):
    kappa = float(rng.uniform(0.5, 2.0))
    a = float(rng.choice([0.0, rng.uniform(0.2, 0.8)]))
    omega = float(rng.uniform(1.0, 4.0))
    ratio = float(rng.uniform(0.3, 1.5))
    p_bar = ratio * np.sqrt(kappa * V_MAX)
    sigma = p_bar + float(rng.uniform(0.5, 3.0)) * np.sqrt(kappa * V_MAX)
    mu = float(rng.choice([0.0, rng.uniform(-1.5, 1.5)])) / np.sqrt(kappa * V_MAX)
    dV = PSD.dV_dzeta

    def B2(p, z):
        return np.full(np.shape(p), kappa * float(dV(z)) * (1.0 + a * np.sin(omega * np.log(z))))

    def B1(p, z):
        return mu * B2(p, z)

    def exact(edges, z):
        """Strip images with drift (Girsanov): P = sum_k [e^{mu (c1 - x)} phi_T(y - c1 - mu T) - (c1 -> c2)],
        c1 = x + 2k sigma, c2 = -x + 2k sigma, x = p_bar; T the clock int B2 dzeta."""
        lz = np.log(z)
        T = quad(
            lambda u: kappa * float(dV(np.exp(u))) * (1 + a * np.sin(omega * u)) * np.exp(u),
            0.0,
            lz,
            limit=200,
            points=_kinks(z),
        )[0]
        mass = np.zeros(edges.size - 1)
        area = 0.0
        sT = np.sqrt(T)
        for k in range(-30, 31):
            for c, sgn in ((p_bar + 2 * k * sigma, 1.0), (-p_bar + 2 * k * sigma, -1.0)):
                wgt = sgn * np.exp(mu * (c - p_bar))
                m = c + mu * T
                mass += wgt * _normal_cdf_avg(edges, m, T)
                area += wgt * _ndtr_diff((sigma - m) / sT, -m / sT)
        return mass, area

    label = f"strip kappa={kappa:.2f} a={a:.2f} mu*sqrt(kV)={mu * np.sqrt(kappa * V_MAX):.2f} ratio={ratio:.2f} "
    label += f"sigma/p_bar={sigma / p_bar:.2f}"
    kw = {"B2": B2, "B1": B1 if mu != 0.0 else None}
    return pf.FokkerPlanckProblem(PSD, p_bar=p_bar, hardness=sigma, **kw), exact, label, None


def _ndtr_diff(a, b):
    """Phi(a) - Phi(b) for a >= b without the cancellation of two values near 1 (upper tails where b > 0)."""
    return ndtr(-b) - ndtr(-a) if b > 0 else ndtr(a) - ndtr(b)


FLOOR = 1e-12
"""Errors below this are round-off (sums of ~1e3 cells) and below what the references resolve (the BESQ one drops
< 1e-13 below the wall): an estimate smaller than that is compared as if it were FLOOR."""

FAMILIES = (_drift_case, _drift_case, _besq_case, _strip_case)


def stations(rng, pr, z_end):
    """1 to 3 random output stations in the last 70 % of [1, z_end] (log-uniform), the last one z_end."""
    z_hi = pr.zeta_max if z_end is None else z_end
    n_st = int(rng.integers(1, 4))
    zeta_out = np.sort(np.exp(rng.uniform(np.log(1.0 + 0.3 * (z_hi - 1.0)), np.log(z_hi), n_st)))
    zeta_out[-1] = z_hi
    return zeta_out


def draw(rng):
    """One random case: (problem, exact(edges, zeta) -> (cell masses, A*), label, zeta_out, method, options)."""
    pr, exact, label, z_end = FAMILIES[int(rng.integers(len(FAMILIES)))](rng)
    zeta_out = stations(rng, pr, z_end)
    method = str(rng.choice(["fv", "mol"]))
    if rng.uniform() < 0.3:
        opts = {"tol": float(rng.choice([1e-3, 3e-4]))}
    else:
        opts = {"n_p": int(rng.choice([100, 200, 400]))}
        if method == "fv":
            opts["n_steps"] = int(rng.choice([100, 200, 400]))
    return pr, exact, label, np.unique(zeta_out), method, opts


def check_case(rng):
    """Run one random case; (ratio of the true error to the estimate (worst over stations), tol breach, label)."""
    pr, exact, label, zeta_out, method, opts = draw(rng)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            sol = pf.solve(pr, method=method, zeta_out=zeta_out, **opts)
        except (ValueError, pf.SolverError) as err:  # refused openly: honest, counted apart
            return None, False, f"{label} {method} {opts}: refused ({str(err)[:80]})"
    est = sol.error_estimate
    worst, over_tol = 0.0, False
    for i, z in enumerate(sol.zeta):
        w = np.asarray(sol.weights)
        w = w[i] if w.ndim == 2 else w
        p = np.asarray(sol.p)
        p = p[i] if p.ndim == 2 else p
        edges = np.concatenate(([p[0] - 0.5 * w[0]], p + 0.5 * w))
        mass, area = exact(edges, float(z))
        L1 = float(np.sum(np.abs(sol.P0_all[i, 0] * w - mass)))
        dA = abs(float(sol.elastic_area_all[i, 0]) - area)  # (A_el: the references give the elastic mass)
        for err, key in ((L1, "L1"), (dA, "elastic_area" if pr.hardness is not None else "contact_area")):
            e = float(est[key][i, 0])
            worst = max(worst, err / max(e, FLOOR))
            if "tol" in opts and err > opts["tol"]:
                over_tol = True
    return worst, over_tol, f"{label} {method} {opts}"


def _sweep(n, seed):
    rng = np.random.default_rng(seed)
    results = [check_case(rng) for _ in range(n)]
    bad = [(r, lab) for r, tolbad, lab in results if r is not None and (r > 2.0 or tolbad)]
    ran = sum(r is not None for r, _, _ in results)
    return ran, bad, results


def test_estimates_are_honest_small_sample():
    ran, bad, _ = _sweep(6, seed=1)
    assert ran >= 5
    assert not bad, bad


@pytest.mark.slow
def test_estimates_are_honest_40_random_problems():
    ran, bad, results = _sweep(40, seed=2026)  # (320 in benchmarks/honesty.py: results/honesty.md)
    assert ran >= 36, [lab for r, _, lab in results if r is None]
    assert not bad, bad


# -- the parts of the estimate: start-up and far wall ----------------------------------------------------------------
REF = pf.ContactProblem.reference()
PB = float(REF.p_bar[0])


def _steep():
    """B2 = (p / p_bar)^8 dV/dzeta: a strict local martingale whose tail runs to any p (the far wall takes mass)."""
    return pf.FokkerPlanckProblem(PSD, p_bar=PB, B2=lambda p, z: PSD.dV_dzeta(z) * (p / PB) ** 8)


def test_steep_diffusion_fv_and_mol_agree_within_their_estimates():
    """Before: A* 0.9708 (fv) vs 0.9748 (mol), both with estimates ~1e-4 and the far wall's 0.029 unseen.  Now the
    far-wall loss and the start-up error are part of the estimate, and the two answers lie within it."""
    fp = _steep()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        a, b = pf.solve(fp, method="fv"), pf.solve(fp, method="mol")
    for s in (a, b):
        parts = s.info["error_estimate"]["parts"]
        assert {"discretisation", "start", "far_wall"} <= set(parts)
        assert parts["far_wall"] == pytest.approx(s.info["far_wall_mass"])
        assert s.info["domain"]["p_end"] > 5 * REF.p_max(10.0)  # sized from B2, not from dV/dzeta
    gap = abs(float(a.contact_area_all[-1, 0]) - float(b.contact_area_all[-1, 0]))
    assert gap <= float(a.error_estimate["contact_area"][-1, 0]) + float(b.error_estimate["contact_area"][-1, 0])
