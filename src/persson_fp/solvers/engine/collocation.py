r"""Mapped Chebyshev collocation in p with exact propagation in the variance-like variable V.

For coefficients of the form :math:`B_1 = c(p)\,dV/d\zeta`, :math:`B_2 = b(p)\,dV/d\zeta` (the homogenised
theory, every fudge-free pressure-dependent diffusion ``b(p) dV/dzeta`` and a drift of the same form) the
Fokker--Planck equation of the Xu et al. tutorial (Eq. 'E:Fokker_Planck_Forward') becomes autonomous in V:

.. math::  \partial_V P = \mathcal L P = \tfrac12\,\partial_p^2(bP) - \partial_p(cP),
           \qquad P(0, V) = P(p_{max}, V) = 0,

so that :math:`P(V_k) = e^{(V_k - V_{k-1})\mathcal L} P(V_{k-1})` is exact in V.  The operator is discretised by
Chebyshev collocation on a sinh-mapped grid (Tee & Trefethen, SIAM J. Sci. Comput. 28 (2006) 1798) that clusters
nodes around the start p_bar, where the PDF is narrow, and at both walls; the matrix exponential is dense
(``scipy.linalg.expm``, scaling and squaring), stacked over loads.

The start: the delta at p_bar at V = 0 is replaced by the small-time expansion at V0 of the Lamperti-transformed
process (Y = int dp / sqrt(b), unit diffusion, drift mu(Y); Ait-Sahalia, Econometrica 70 (2002) 223):
:math:`p_Y \approx \varphi_{V_0}(y - y_0) e^{\int_{y_0}^{y}\mu}\,e^{-V_0\bar\lambda}`, with
:math:`\lambda = (\mu^2 + \mu')/2` averaged over [y0, y], and the image across the absorbing wall at p = 0.  Its
error is O(V0^2) relative (exact for b = const, c = 0).  No solver imports this module's callers.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

__all__ = ["ChebGrid", "chebyshev_grid", "start_density", "propagate", "interpolate", "lamperti_distance"]

_GL_T, _GL_W = np.polynomial.legendre.leggauss(24)


class ChebGrid:
    """Stacked sinh-mapped Chebyshev--Lobatto grids on [0, p_max], one per load.

    Attributes
    ----------
    x : (n + 1,) Chebyshev points in [-1, 1].
    p : (n_loads, n + 1) nodes (pressure); p[:, 0] = 0, p[:, -1] = p_max.
    D1, D2 : (n_loads, n + 1, n + 1) first and second derivative matrices in p.
    w : (n_loads, n + 1) Clenshaw--Curtis weights in p (exact for polynomials of degree n in x).
    """

    def __init__(self, x, p, D1, D2, w, map_params):
        self.x, self.p, self.D1, self.D2, self.w = x, p, D1, D2, w
        self._map = map_params

    @property
    def n(self) -> int:
        return self.x.size - 1

    def x_of_p(self, p):
        """The Chebyshev coordinate of pressures ``p`` ((n_loads, m) or broadcasting), per load."""
        a1, h, c, eps = self._map
        return (np.arcsinh((p - c[:, None]) / eps[:, None]) - a1[:, None]) / h[:, None] - 1.0


def _cheb_basic(n: int):
    """Chebyshev--Lobatto points (ascending), the differentiation matrix and the Clenshaw--Curtis weights."""
    j = np.arange(n + 1)
    x = -np.cos(np.pi * j / n)
    c = np.ones(n + 1)
    c[0] = c[-1] = 2.0
    c *= (-1.0) ** j
    X = x[:, None] - x[None, :]
    D = np.outer(c, 1.0 / c) / (X + np.eye(n + 1))
    D -= np.diag(D.sum(axis=1))
    theta = np.pi * j[1:-1] / n
    w = np.zeros(n + 1)
    v = np.ones(n - 1)
    if n % 2 == 0:
        w[0] = w[n] = 1.0 / (n * n - 1.0)
        for k in range(1, n // 2):
            v -= 2.0 * np.cos(2 * k * theta) / (4.0 * k * k - 1.0)
        v -= np.cos(n * theta) / (n * n - 1.0)
    else:
        w[0] = w[n] = 1.0 / (n * n)
        for k in range(1, (n - 1) // 2 + 1):
            v -= 2.0 * np.cos(2 * k * theta) / (4.0 * k * k - 1.0)
    w[1:-1] = 2.0 * v / n
    return x, D, w


_BASIC_CACHE: dict = {}


def chebyshev_grid(n: int, p_max: float, centre, eps) -> ChebGrid:
    """Grids x -> p = centre + eps sinh(a1 + h (x + 1)) mapping [-1, 1] onto [0, p_max], one per centre.

    Parameters
    ----------
    n : int
        Polynomial degree (n + 1 nodes), >= 4.
    p_max : float, pressure
        The far wall.
    centre, eps : (n_loads,) arrays, pressure
        Where the nodes cluster (p_bar) and the width of the cluster (a few start widths); a large ``eps``
        gives the plain Chebyshev grid.
    """
    if n not in _BASIC_CACHE:
        _BASIC_CACHE[n] = _cheb_basic(n)
    x, D, w = _BASIC_CACHE[n]
    c = np.asarray(centre, dtype=float)
    eps = np.asarray(eps, dtype=float)
    a1 = np.arcsinh(-c / eps)
    h = 0.5 * (np.arcsinh((p_max - c) / eps) - a1)
    s = a1[:, None] + h[:, None] * (x[None, :] + 1.0)
    p = c[:, None] + eps[:, None] * np.sinh(s)
    p[:, 0], p[:, -1] = 0.0, p_max
    dp = eps[:, None] * np.cosh(s) * h[:, None]  # dp/dx
    d2p = eps[:, None] * np.sinh(s) * (h * h)[:, None]
    D1 = D[None, :, :] / dp[:, :, None]
    D2 = (D @ D)[None, :, :] / (dp * dp)[:, :, None] - (d2p / dp**3)[:, :, None] * D[None, :, :]
    return ChebGrid(x, p, D1, D2, w[None, :] * dp, (a1, h, c, eps))


def generator(grid: ChebGrid, b, c):
    """The collocated forward operator on the interior nodes (Dirichlet walls), stacked over loads.

    ``b``, ``c``: (n_loads, n + 1) diffusion and drift per unit V at the nodes.
    Returns (n_loads, n - 1, n - 1): (L P)_i = 1/2 (b P)''(p_i) - (c P)'(p_i).
    """
    M = 0.5 * grid.D2 * b[:, None, :]
    if c is not None and np.any(c):
        M = M - grid.D1 * c[:, None, :]
    return M[:, 1:-1, 1:-1]


def propagate(L, P_start, dV):
    """P after the V increments ``dV`` (a sequence): the states after each, stacked (n_steps, n_loads, n - 1).

    Exact in V for the discretised operator ``L`` (n_loads, m, m): one matrix exponential per increment.
    """
    out = np.empty((len(dV),) + P_start.shape)
    P = P_start
    for k, d in enumerate(dV):
        E = sla.expm(L * float(d))
        P = np.einsum("lij,lj->li", E, P)
        out[k] = P
    return out


def interpolate(grid: ChebGrid, values, p_query):
    """Barycentric interpolation of nodal ``values`` (n_loads, n + 1) to ``p_query`` (n_loads, m)."""
    n = grid.n
    wb = np.ones(n + 1)
    wb[0] = wb[-1] = 0.5
    wb *= (-1.0) ** np.arange(n + 1)
    xq = np.clip(grid.x_of_p(p_query), -1.0, 1.0)
    d = xq[:, :, None] - grid.x[None, None, :]
    exact = d == 0.0
    d[exact] = 1.0
    t = wb / d
    out = np.einsum("lmk,lk->lm", t, values) / t.sum(axis=-1)
    hit = exact.any(axis=-1)
    if np.any(hit):
        li, mi = np.nonzero(hit)
        out[li, mi] = values[li, np.argmax(exact[li, mi], axis=-1)]
    return out


def _segment_integral(f, a, b):
    """int_a^b f(p) dp for arrays of endpoints (broadcast), by 24-point Gauss--Legendre; f vectorised."""
    mid, half = 0.5 * (a + b), 0.5 * (b - a)
    q = mid[..., None] + half[..., None] * _GL_T
    return half * np.sum(f(q) * _GL_W, axis=-1)


def lamperti_distance(bfun, a, b):
    """int_a^b dp / sqrt(b(p)) (pressure^(0) per sqrt(V)): the distance in the unit-diffusion variable."""
    return _segment_integral(lambda q: 1.0 / np.sqrt(np.maximum(bfun(q), 1e-300)), a, b)


def start_density(bfun, cfun, p, p0, V0, scale):
    r"""The PDF at V0 of the process started at p0 (small-time expansion), at the nodes ``p``.

    Parameters
    ----------
    bfun, cfun : callables
        Diffusion b(p) > 0 and drift c(p) per unit V (``cfun`` may be None).
    p : (n_loads, m) pressures; p0 : (n_loads,) starts; V0 : float, pressure^2; scale : float, pressure
        (the finite-difference step for b', b'' is 1e-3 * scale * sqrt(V0) / scale ... in units of sqrt(V0)).

    Returns
    -------
    (n_loads, m) array, 1/pressure.
    """
    h = 0.02 * np.sqrt(V0)

    def coeffs(q):
        bs = [bfun(q + k * h) for k in (-2, -1, 0, 1, 2)]
        b0 = bs[2]
        b1 = (bs[0] - 8 * bs[1] + 8 * bs[3] - bs[4]) / (12 * h)
        b2 = (-bs[0] + 16 * bs[1] - 30 * b0 + 16 * bs[3] - bs[4]) / (12 * h * h)
        if cfun is None:
            c0 = c1 = 0.0
        else:
            cs = [cfun(q + k * h) for k in (-2, -1, 1, 2)]
            c0 = cfun(q)
            c1 = (cs[0] - 8 * cs[1] + 8 * cs[2] - cs[3]) / (12 * h)
        return np.maximum(b0, 1e-300), b1, b2, c0, c1

    def drift_integrand(q):  # mu_Y dy = (c / b - b' / (4 b)) dp
        b0, b1, _, c0, _ = coeffs(q)
        return c0 / b0 - 0.25 * b1 / b0

    def lam_integrand(q):  # lambda dy = lambda / sqrt(b) dp
        b0, b1, b2, c0, c1 = coeffs(q)
        mu = (c0 - 0.25 * b1) / np.sqrt(b0)
        dmu_dy = c1 - 0.5 * c0 * b1 / b0 - 0.25 * b2 + b1 * b1 / (8.0 * b0)
        return 0.5 * (mu * mu + dmu_dy) / np.sqrt(b0)

    a = np.broadcast_to(p0[:, None], p.shape)
    dy = lamperti_distance(bfun, a, p)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        drift = _segment_integral(drift_integrand, a, p)
        lam = _segment_integral(lam_integrand, a, p)
        lam_mean = np.where(
            np.abs(dy) > 0,
            lam / np.where(dy == 0, 1.0, dy),
            0.5 * (lam_integrand(a)) * np.sqrt(np.maximum(bfun(a), 1e-300)),
        )
        y0 = lamperti_distance(bfun, np.zeros_like(p0), p0)[:, None]  # start's distance from the wall
        yy = y0 + dy
        gauss = np.exp(-0.5 * dy * dy / V0) - np.exp(-0.5 * (yy + y0) ** 2 / V0)
        P = gauss * np.exp(drift - V0 * lam_mean) / np.sqrt(2 * np.pi * V0 * np.maximum(bfun(p), 1e-300))
    return np.where(np.isfinite(P), P, 0.0)
