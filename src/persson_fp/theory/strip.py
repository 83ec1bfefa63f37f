r"""Closed forms of the elastoplastic strip: absorbing walls at p = 0 and at a constant hardness sigma_Y.

With a constant yield stress :math:`\sigma_Y` (Persson, Phys. Rev. Lett. 87 (2001) 116101; Surf. Sci.
Rep. 61 (2006) 201, Sec. 3) the pressure PDF obeys the heat equation
:math:`\partial_\tau P = \tfrac12\partial_p^2 P` on :math:`0 < p < \sigma_Y` with
:math:`P(0) = P(\sigma_Y) = 0` and :math:`P(p, 0) = \delta(p - \bar p)`.  Two exact series solve it:

*Images* (fast for :math:`\tau \le \sigma_Y^2`): with :math:`\rho(p; a, \tau)` the Gaussian of the Xu et al.
tutorial's Eq. 'eq:P0_solution',

.. math::  P = \sum_{k\in\mathbb Z}\big[\rho(p;\bar p + 2k\sigma_Y,\tau) - \rho(p;-\bar p + 2k\sigma_Y,\tau)\big].

*Sines* (fast for :math:`\tau > \sigma_Y^2`), :math:`\lambda_n = n^2\pi^2/(2\sigma_Y^2)`,
:math:`s_n = \sin(n\pi\bar p/\sigma_Y)`:

.. math::  P = \frac{2}{\sigma_Y}\sum_{n\ge1} s_n \sin\frac{n\pi p}{\sigma_Y} e^{-\lambda_n\tau}.

The areas (fractions of the nominal area) and loads follow in closed form from either:
elastic :math:`A_{el} = \int_0^{\sigma_Y} P\,dp`; non-contact :math:`A_{non}` = the mass absorbed at p = 0,
:math:`\tfrac12\int_0^\tau\partial_pP(0)\,d\tau'`, which per image of centre a is
:math:`\tfrac12\,\mathrm{sign}(a)\,\mathrm{erfc}(|a|/\sqrt{2\tau})` (the first-passage law), and in sines
:math:`1 - \bar p/\sigma_Y - \sum 2 s_n e^{-\lambda_n\tau}/(n\pi)`; plastic :math:`A_{pl}` = the mass absorbed at
:math:`\sigma_Y` (the mirror image :math:`\bar p \to \sigma_Y - \bar p` of :math:`A_{non}`); elastic load
:math:`F_{el} = \int p P\,dp` and plastic load :math:`F_{pl} = \sigma_Y A_{pl}` with
:math:`F_{el} + F_{pl} = \bar p` (load balance, the tutorial's Eq. 'eq:Load_equilibrium') and
:math:`A_{el} + A_{pl} + A_{non} = 1`.  As :math:`\tau\to\infty`: :math:`A_{el} \to 0` but
:math:`A_{pl} \to \bar p/\sigma_Y` -- the zero-contact-area paradox of the tutorial resolved.

Both series are truncated where the next term is below exp(-60) of the first (``_K_IMAGES`` image pairs each
side, ``_N_SINES`` modes), so every quantity is exact to round-off.

*Fudge factors* (the tutorial's Eq. 'eq:new_B2'): :math:`B_2 = S(A)\,dV/d\zeta` with A the *total* contact
area :math:`A_{el} + A_{pl} = 1 - A_{non}` (plastically deformed asperities are in contact; this is the
choice made here and the one that reduces to the elastic theory as sigma_Y -> infinity).  In the effective
variance :math:`d\tau = S\,dV` the strip is still the heat equation, and :math:`\tau(V)` obeys
:math:`d\tau/dV = S(1 - A_{non}(\tau))` -- one ODE per load, because :math:`A_{non}` depends on
:math:`\bar p/\sqrt\tau` and :math:`\sigma_Y/\sqrt\tau` (:class:`StripEffectiveVariance`).

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf, erfc

__all__ = ["strip_pdf", "strip_cdf", "strip_quantities", "strip_areas", "StripEffectiveVariance"]

_K_IMAGES = 5
"""Image pairs k = -K..K; the first one dropped is below exp(-(2K-1)^2/2) = e^-40.5 (2.6e-18) for tau <= sigma^2."""
_N_SINES = 12
"""Sine modes; the first one dropped is below exp(-13^2 pi^2/2) for tau > sigma^2."""
_SQRT2PI = np.sqrt(2.0 * np.pi)


def _prep(p_bar, sigma, tau):
    p_bar, sigma, tau = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (p_bar, sigma, tau)))
    if np.any(tau <= 0):
        raise ValueError("tau must be > 0 (at zeta = 1 the PDF is the delta function delta(p - p_bar))")
    return p_bar, sigma, tau, tau <= sigma**2


def _images(p_bar, sigma):
    """Image centres (..., 2K+1) for the + and - families."""
    k = np.arange(-_K_IMAGES, _K_IMAGES + 1)
    return p_bar[..., None] + 2.0 * k * sigma[..., None], -p_bar[..., None] + 2.0 * k * sigma[..., None]


def _first_passage(a, tau):
    """Mass absorbed at p = 0 by time tau from an image at a: sign(a) erfc(|a|/sqrt(2 tau)) / 2."""
    return 0.5 * np.sign(a) * erfc(np.abs(a) / np.sqrt(2.0 * tau))


def _moments_images(p_bar, sigma, tau):
    """int_0^sigma p^k P dp (k = 0, 1, 2) by images: sum over centres of the Gaussian's partial moments."""
    ap, am = _images(p_bar, sigma)
    s = np.sqrt(tau)[..., None]
    out = []
    for a, sign in ((ap, 1.0), (am, -1.0)):
        z0, z1 = -a / s, (sigma[..., None] - a) / s
        with np.errstate(under="ignore"):
            f0, f1 = np.exp(-0.5 * z0**2) / _SQRT2PI, np.exp(-0.5 * z1**2) / _SQRT2PI
        dPhi = 0.5 * (erf(z1 / np.sqrt(2.0)) - erf(z0 / np.sqrt(2.0)))
        m0 = dPhi
        m1 = a * dPhi + s * (f0 - f1)
        m2 = a**2 * dPhi + 2.0 * a * s * (f0 - f1) + s**2 * (dPhi + z0 * f0 - z1 * f1)
        out.append([sign * m for m in (m0, m1, m2)])
    return [np.sum(out[0][i] + out[1][i], axis=-1) for i in range(3)]


def _sine_terms(p_bar, sigma, tau):
    n = np.arange(1, _N_SINES + 1)
    sig = sigma[..., None]
    with np.errstate(under="ignore"):
        e = np.exp(-(n**2) * np.pi**2 * tau[..., None] / (2.0 * sig**2))
    s_n = np.sin(n * np.pi * p_bar[..., None] / sig)
    sgn = np.where(n % 2 == 1, 1.0, -1.0)  # (-1)^(n+1)
    return n, sig, s_n * e, sgn


def strip_quantities(p_bar, sigma, tau) -> dict:
    r"""Areas, loads and the second moment of the strip at effective variance ``tau``.

    Parameters
    ----------
    p_bar : array, pressure
        Nominal pressure(s), 0 < p_bar < sigma.
    sigma : array, pressure
        Constant hardness sigma_Y.
    tau : array, pressure^2
        Effective variance (= V without a fudge factor), > 0.  The three broadcast.

    Returns
    -------
    dict of arrays
        ``elastic_area`` :math:`A_{el}`, ``plastic_area`` :math:`A_{pl}`, ``noncontact_area`` :math:`A_{non}`
        (dimensionless), ``elastic_load`` :math:`F_{el}`, ``plastic_load`` :math:`\sigma_Y A_{pl}` (pressure) and
        ``elastic_second_moment`` :math:`\int_0^{\sigma_Y} p^2 P\,dp` (pressure^2); see the module docstring.
    """
    A_non, A_pl = strip_areas(p_bar, sigma, tau)  # the absorbed masses (first passage / sines)
    p_bar, sigma, tau, use_images = _prep(p_bar, sigma, tau)
    out = {"A_non": A_non, "A_pl": A_pl, **{k: np.empty(p_bar.shape) for k in ("A_el", "F_el", "M2")}}
    if np.any(use_images):  # the moments of the PDF, independently of the absorbed masses
        pb, sg, tt = p_bar[use_images], sigma[use_images], tau[use_images]
        m0, m1, m2 = _moments_images(pb, sg, tt)
        for key, val in zip(("A_el", "F_el", "M2"), (m0, m1, m2)):
            out[key][use_images] = val
    far = ~use_images
    if np.any(far):
        pb, sg, tt = p_bar[far], sigma[far], tau[far]
        n, sig, se, sgn = _sine_terms(pb, sg, tt)
        npi = n * np.pi
        out["A_el"][far] = np.sum(2.0 / npi * (1.0 + sgn) * se, axis=-1)
        out["F_el"][far] = np.sum(2.0 * sig * sgn / npi * se, axis=-1)
        out["M2"][far] = np.sum(2.0 * sig**2 * (sgn / npi - 2.0 * (1.0 + sgn) / npi**3) * se, axis=-1)
    return {
        "elastic_area": out["A_el"],
        "plastic_area": out["A_pl"],
        "noncontact_area": out["A_non"],
        "elastic_load": out["F_el"],
        "plastic_load": sigma * out["A_pl"],
        "elastic_second_moment": out["M2"],
    }


def strip_areas(p_bar, sigma, tau):
    r"""Only the absorbed masses :math:`(A_{non}, A_{pl})` of :func:`strip_quantities` (cheaper: no moments).

    The rest follows exactly: :math:`A_{el} = 1 - A_{non} - A_{pl}` and :math:`F_{el} = \bar p - \sigma_Y A_{pl}`.
    Arguments as for :func:`strip_quantities`; returns two arrays (dimensionless).
    """
    p_bar, sigma, tau, use_images = _prep(p_bar, sigma, tau)
    A_non, A_pl = np.empty(p_bar.shape), np.empty(p_bar.shape)
    if np.any(use_images):
        pb, sg, tt = p_bar[use_images], sigma[use_images], tau[use_images][..., None]
        ap, am = _images(pb, sg)
        A_non[use_images] = np.sum(_first_passage(ap, tt) - _first_passage(am, tt), axis=-1)
        bp, bm = _images(sg - pb, sg)
        A_pl[use_images] = np.sum(_first_passage(bp, tt) - _first_passage(bm, tt), axis=-1)
    far = ~use_images
    if np.any(far):
        pb, sg, tt = p_bar[far], sigma[far], tau[far]
        n, sig, se, sgn = _sine_terms(pb, sg, tt)
        A_non[far] = (1.0 - pb / sg) - np.sum(2.0 / (n * np.pi) * se, axis=-1)
        A_pl[far] = pb / sg - np.sum(2.0 / (n * np.pi) * sgn * se, axis=-1)
    return A_non, A_pl


def strip_pdf(p, p_bar, sigma, tau) -> np.ndarray:
    """P(p) (1/pressure) of the strip, 0 outside (0, sigma); all arguments broadcast."""
    p = np.asarray(p, dtype=float)
    p, p_bar, sigma, tau = np.broadcast_arrays(p, *(np.asarray(x, dtype=float) for x in (p_bar, sigma, tau)))
    p_bar, sigma, tau, use_images = _prep(p_bar, sigma, tau)
    inside = (p > 0) & (p < sigma)
    out = np.zeros(p.shape)
    if np.any(use_images):
        sel = use_images & inside
        ap, am = _images(p_bar[sel], sigma[sel])
        pp, tt = p[sel][..., None], tau[sel][..., None]
        with np.errstate(under="ignore"):
            g = lambda a: np.exp(-((pp - a) ** 2) / (2.0 * tt)) / (_SQRT2PI * np.sqrt(tt))  # noqa: E731
            out[sel] = np.sum(g(ap) - g(am), axis=-1)
    sel = ~use_images & inside
    if np.any(sel):
        n, sig, se, _ = _sine_terms(p_bar[sel], sigma[sel], tau[sel])
        out[sel] = np.sum(2.0 / sig * se * np.sin(n * np.pi * p[sel][..., None] / sig), axis=-1)
    return out


def strip_cdf(p, p_bar, sigma, tau) -> np.ndarray:
    r""":math:`\int_0^{\min(p,\sigma)} P\,dp'` (dimensionless) of the strip; all arguments broadcast."""
    p = np.asarray(p, dtype=float)
    p, p_bar, sigma, tau = np.broadcast_arrays(p, *(np.asarray(x, dtype=float) for x in (p_bar, sigma, tau)))
    p_bar, sigma, tau, use_images = _prep(p_bar, sigma, tau)
    pc = np.clip(p, 0.0, sigma)
    out = np.zeros(p.shape)
    if np.any(use_images):
        sel = use_images
        ap, am = _images(p_bar[sel], sigma[sel])
        pp, st = pc[sel][..., None], np.sqrt(2.0 * tau[sel])[..., None]
        part = lambda a: 0.5 * (erf((pp - a) / st) + erf(a / st))  # noqa: E731
        out[sel] = np.sum(part(ap) - part(am), axis=-1)
    sel = ~use_images
    if np.any(sel):
        n, sig, se, _ = _sine_terms(p_bar[sel], sigma[sel], tau[sel])
        out[sel] = np.sum(2.0 / (n * np.pi) * se * (1.0 - np.cos(n * np.pi * pc[sel][..., None] / sig)), axis=-1)
    return out


class StripEffectiveVariance:
    r"""tau(V) of a fudge factor on the strip: :math:`d\tau/dV = S(1 - A_{non}(\tau))`, one ODE per load.

    Solved once (DOP853, rtol 1e-12, in the log variables ln V -> ln tau, all loads in one system, dense
    output) from :math:`V_0` where no contact has been lost yet (:math:`\tau = S(1)V` exactly there) to
    ``V_max``.  Evaluation: the dense output (~1e-11 relative).  The inverse map V(tau) interpolates a table of
    the same solution (PCHIP in the log variables, ~1e-8 relative: used only to place nodes).

    Parameters
    ----------
    S : callable
        The fudge factor S(A) > 0 on [0, 1].
    p_bar : array (n_loads,), pressure
    sigma : float, pressure
        Constant hardness.
    V_max : float, pressure^2
        Largest complete-contact variance asked for.
    """

    def __init__(self, S, p_bar, sigma: float, V_max: float):
        self.S = S
        self.p_bar = np.asarray(p_bar, dtype=float)
        self.sigma = float(sigma)
        S1 = float(S(np.array(1.0)))
        self.S1 = S1
        dist = np.minimum(self.p_bar, self.sigma - self.p_bar)
        self.V0 = float(1e-4 * np.min(dist) ** 2 / max(S1, 1.0))  # erfc(1/sqrt(2e-4)) ~ 1e-1000: no loss yet
        self.V_max = float(max(V_max, self.V0 * 10))
        sig = np.full(self.p_bar.shape, self.sigma)

        def rhs(s, w):
            tau = np.exp(w)
            A_non = strip_quantities(self.p_bar, sig, tau)["noncontact_area"]
            return np.exp(s - w) * S(np.clip(1.0 - A_non, 0.0, 1.0))

        s0, s1 = np.log(self.V0), np.log(self.V_max)
        w0 = np.log(S1 * self.V0) * np.ones(self.p_bar.shape)
        from scipy.integrate import solve_ivp  # here, not at the top: keeps `import persson_fp` light

        sol = solve_ivp(rhs, (s0, s1), w0, method="DOP853", rtol=1e-12, atol=1e-13, dense_output=True)
        if not sol.success:  # pragma: no cover - DOP853 on a smooth bounded rhs
            raise RuntimeError(f"effective variance of the strip: {sol.message}")
        self._sol = sol
        ss = np.linspace(s0, s1, 2049)
        self._s_grid = ss
        self._w_grid = sol.sol(ss)  # (n_loads, 2049)

    def tau(self, V) -> np.ndarray:
        """tau at one V per load: ``V`` of shape (..., n_loads), pressure^2, 0 <= V <= V_max."""
        V = np.asarray(V, dtype=float)
        flat = V.reshape(-1, self.p_bar.size)
        res = np.empty(flat.shape)
        for j in range(self.p_bar.size):
            v = flat[:, j]
            big = v > self.V0
            res[~big, j] = self.S1 * v[~big]
            if np.any(big):
                res[big, j] = np.exp(self._sol.sol(np.log(np.minimum(v[big], self.V_max)))[j])
        out = res.reshape(V.shape)
        return out

    def V_of_tau(self, tau) -> np.ndarray:
        """The inverse map at one tau per load (``tau`` of shape (..., n_loads)), ~1e-8 relative."""
        from scipy.interpolate import PchipInterpolator  # here, not at the top: keeps `import persson_fp` light

        tau = np.asarray(tau, dtype=float)
        flat = tau.reshape(-1, self.p_bar.size)
        res = np.empty(flat.shape)
        for j in range(self.p_bar.size):
            t = flat[:, j]
            small = t <= self.S1 * self.V0
            res[small, j] = t[small] / self.S1
            if np.any(~small):
                inv = PchipInterpolator(self._w_grid[j], self._s_grid, extrapolate=True)
                res[~small, j] = np.exp(inv(np.log(t[~small])))
        return res.reshape(tau.shape)
