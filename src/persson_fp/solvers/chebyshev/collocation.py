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
error is O(V0^2) relative (exact for constant b and c).  Used by :mod:`persson_fp.solvers.chebyshev`.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

__all__ = [
    "ChebGrid",
    "chebyshev_grid",
    "start_density",
    "propagate_with_integral",
    "with_wall_rows",
    "WallRowOperators",
    "generator",
    "wall_losses",
    "interpolate",
    "lamperti_distance",
    "roundoff_floor",
]

_GL_T, _GL_W = np.polynomial.legendre.leggauss(24)


class ChebGrid:
    """Stacked sinh-mapped Chebyshev--Lobatto grids on [0, p_max], one per load (built by :func:`chebyshev_grid`).

    Parameters
    ----------
    x : ndarray, shape (n + 1,)
        Chebyshev points in [-1, 1], ascending.
    p : ndarray, shape (n_loads, n + 1), pressure
        The nodes; ``p[:, 0] = 0`` and ``p[:, -1] = p_max``.
    D1, D2 : ndarray, shape (n_loads, n + 1, n + 1)
        First (1/pressure) and second (1/pressure^2) derivative matrices in p.
    w : ndarray, shape (n_loads, n + 1), pressure
        Clenshaw--Curtis weights in p (exact for polynomials of degree n in x).
    map_params : tuple
        (a1, h, centre, eps) of the map p = centre + eps sinh(a1 + h (x + 1)).
    """

    def __init__(self, x, p, D1, D2, w, map_params):
        self.x, self.p, self.D1, self.D2, self.w = x, p, D1, D2, w
        self._map = map_params

    @property
    def n(self) -> int:
        """The polynomial degree (n + 1 nodes)."""
        return self.x.size - 1

    def x_of_p(self, p):
        """The Chebyshev coordinate of pressures, per load (the map's exact inverse).

        Parameters
        ----------
        p : ndarray, shape (n_loads, m), pressure

        Returns
        -------
        ndarray, shape (n_loads, m)
        """
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

    Returns
    -------
    ChebGrid
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
    r"""The collocated forward operator on the interior nodes (Dirichlet walls), stacked over loads.

    Parameters
    ----------
    grid : ChebGrid
    b : ndarray, shape (n_loads, n + 1), pressure^2 per unit V
        Diffusion at the nodes.
    c : ndarray or None, shape (n_loads, n + 1), pressure per unit V
        Drift at the nodes (None: 0).

    Returns
    -------
    ndarray, shape (n_loads, n - 1, n - 1), 1 / pressure^2
        :math:`(LP)_i = \tfrac12 (bP)''(p_i) - (cP)'(p_i)`.
    """
    M = 0.5 * grid.D2 * b[:, None, :]
    if c is not None and np.any(c):
        M = M - grid.D1 * c[:, None, :]
    return M[:, 1:-1, 1:-1]


def with_wall_rows(grid: ChebGrid, L, b, c=None):
    """The operator augmented by the mass out through each wall and the drift moment: shape (n_loads, n + 2, n + 2).

    The state [P at the interior nodes, mass out at p = 0, mass out at p_max, int int c P dp dV] obeys d/dV of it
    = this matrix times it: the next two rows are the wall fluxes 1/2 d(bP)/dp at p = 0 and -1/2 d(bP)/dp at p_max
    (P = 0 on the walls, so the drift carries nothing through them; :func:`wall_losses`), the last the drift's
    moment int c P dp (Clenshaw--Curtis) of the first-moment law d/dV int p P dp = int c P dp - p_max J(p_max).

    Parameters
    ----------
    grid : ChebGrid
    L : ndarray, shape (n_loads, n - 1, n - 1)
        The operator (:func:`generator`).
    b : ndarray, shape (n_loads, n + 1)
        Diffusion per unit V at the nodes.
    c : ndarray or None, shape (n_loads, n + 1)
        Drift per unit V at the nodes (None: 0).
    """
    nl, m, _ = L.shape
    M = np.zeros((nl, m + 3, m + 3))
    M[:, :m, :m] = L
    rows = 0.5 * grid.D1[:, [0, -1], 1:-1] * b[:, None, 1:-1]
    M[:, m, :m] = rows[:, 0]
    M[:, m + 1, :m] = -rows[:, 1]
    if c is not None:
        M[:, m + 2, :m] = (grid.w * c)[:, 1:-1]
    return M


class WallRowOperators:
    """:func:`with_wall_rows` of :func:`generator` for many (b, c) at once, from matrices built once per grid.

    A march evaluates the augmented operator at several variances per step; each is one broadcast product of the
    grid's fixed matrices with b (and c) -- the same products, element by element, as the two functions above, so
    the values are identical -- without building the interior block and copying it into the augmented one.

    Parameters
    ----------
    grid : ChebGrid
    """

    def __init__(self, grid: ChebGrid):
        D1, D2 = grid.D1, grid.D2
        nl, m = D1.shape[0], D1.shape[1] - 2
        self.m = m
        K2 = np.zeros((nl, m + 3, m))  # the columns of the interior nodes, scaled by b there
        K2[:, :m] = 0.5 * D2[:, 1:-1, 1:-1]
        K2[:, m] = 0.5 * D1[:, 0, 1:-1]
        K2[:, m + 1] = -(0.5 * D1[:, -1, 1:-1])
        K1 = np.zeros((nl, m + 3, m))  # scaled by c there
        K1[:, :m] = D1[:, 1:-1, 1:-1]
        self.K2, self.K1, self.w = K2, K1, grid.w[:, 1:-1]

    def __call__(self, bc) -> np.ndarray:
        """The operators (len(bc), n_loads, m + 3, m + 3) of a sequence of (b, c or None) at the nodes (n_loads,
        n + 1) each."""
        m = self.m
        b = np.stack([pair[0] for pair in bc])[:, :, None, 1:-1]
        out = np.zeros((b.shape[0], self.K2.shape[0], m + 3, m + 3))
        np.multiply(self.K2, b, out=out[..., :m])
        for k, (_, c) in enumerate(bc):
            if c is None:
                continue
            if np.any(c):
                out[k, :, :m, :m] -= self.K1[:, :m] * c[:, None, 1:-1]
            out[k, :, m + 2, :m] = self.w * c[:, 1:-1]
        return out


def propagate_with_integral(L, P_start, dV: float):
    """P after dV and its integral over the step, for each load: one exponential of [[L dV, P0 dV], [0, 0]].

    Van Loan, IEEE Trans. Autom. Control 23 (1978) 395: expm([[A, b], [0, 0]] t) = [[e^{At},
    int_0^t e^{As} ds b], [0, 1]].  Exact in V for the discretised operator.

    Parameters
    ----------
    L : ndarray, shape (n_loads, m, m)
        The operator (:func:`generator`).
    P_start : ndarray, shape (n_loads, m), 1/pressure
        P at the interior nodes at the start.
    dV : float, pressure^2
        The increment.

    Returns
    -------
    (ndarray, ndarray), shape (n_loads, m) each
        P after dV (1/pressure) and int_0^dV P dV' (pressure; gives the mass out through the walls,
        :func:`wall_losses`).
    """
    nl, m, _ = L.shape
    M = np.zeros((nl, m + 1, m + 1))
    M[:, :m, :m] = L
    M[:, :m, m] = P_start
    E = sla.expm(M * float(dV))
    return np.einsum("lij,lj->li", E[:, :m, :m], P_start), E[:, :m, m]


def wall_losses(grid: ChebGrid, b, c, I_inner):
    """The mass that left through each wall, from the time integral of P.

    The flux is J = cP - 1/2 d(bP)/dp; with P = 0 on both walls the mass out at p = 0 is
    1/2 d(b int P dV)/dp there and at p_max -1/2 d(b int P dV)/dp (the polynomial's derivative).

    Parameters
    ----------
    grid : ChebGrid
    b, c : ndarray, shape (n_loads, n + 1)
        Diffusion and drift per unit V at the nodes (``c`` unused: P = 0 on the walls).
    I_inner : ndarray, shape (n_loads, n - 1), pressure
        int P dV at the interior nodes (:func:`propagate_with_integral`).

    Returns
    -------
    (ndarray, ndarray), shape (n_loads,) each
        Mass out at p = 0 and at p_max (dimensionless).
    """
    I = np.zeros(grid.p.shape)
    I[:, 1:-1] = I_inner
    dbI = np.einsum("lij,lj->li", grid.D1[:, [0, -1], :], b * I)
    return 0.5 * dbI[:, 0], -0.5 * dbI[:, 1]


def interpolate(grid: ChebGrid, values, p_query):
    """Barycentric interpolation (in the Chebyshev coordinate) of nodal values, per load.

    Parameters
    ----------
    grid : ChebGrid
    values : ndarray, shape (n_loads, n + 1)
    p_query : ndarray, shape (n_loads, m), pressure
        Where; points beyond [0, p_max] take the wall's value.

    Returns
    -------
    ndarray, shape (n_loads, m)
    """
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


def lamperti_distance(bfun, a, b):
    """The distance int_a^b dp / sqrt(b(p)) in the unit-diffusion (Lamperti) variable Y.

    Parameters
    ----------
    bfun : callable
        b(p) > 0 (pressure^2 per unit V), vectorised.
    a, b : ndarray, pressure
        Segment ends (broadcasting); 24-point Gauss--Legendre on each.

    Returns
    -------
    ndarray, sqrt(pressure^2 per unit V) -- i.e. in units of sqrt(V)
    """
    mid, half = 0.5 * (a + b), 0.5 * (b - a)
    q = mid[..., None] + half[..., None] * _GL_T
    return half * np.sum(_GL_W / np.sqrt(np.maximum(bfun(q), 1e-300)), axis=-1)


def start_density(coef, p, p0, V0, p_wall=None):
    r"""The PDF at V0 of the process started at p0 (small-time expansion), at the nodes ``p``.

    Parameters
    ----------
    coef : callable
        ``coef(q) -> (b, c)``: diffusion b > 0 and drift c per unit V at pressures q (any shape; one call).
    p : (n_loads, m) array, pressure
        Where the PDF is wanted.
    p0 : (n_loads,) array, pressure
        The starts (the delta's positions at V = 0).
    V0 : float, pressure^2
        The start's V.
    p_wall : float or None, pressure
        An absorbing wall above p0 (a constant hardness sigma_Y): its image is subtracted too.

    Returns
    -------
    (n_loads, m) array, 1/pressure
        :math:`\varphi_{V_0}(\Delta y) - \varphi_{V_0}(y + y_0)` times :math:`e^{\int\mu\,dy - V_0\bar\lambda}
        / \sqrt{b(p)}` (module docstring); exact for constant b and c.
    """
    h = 0.02 * np.sqrt(V0)  # the finite-difference step of b', b'', c' (4th-order stencils)
    a = np.broadcast_to(p0[:, None], p.shape)
    mid, half = 0.5 * (a + p), 0.5 * (p - a)
    q = mid[..., None] + half[..., None] * _GL_T  # (n_loads, m, 24) quadrature points of [p0, p]
    q0 = 0.5 * p0[:, None] * (1.0 + _GL_T)  # of [0, p0]
    shifts = np.array([-2.0, -1.0, 0.0, 1.0, 2.0]) * h
    qw = p0[:, None] + 0.5 * ((p0 if p_wall is None else p_wall) - p0)[:, None] * (1.0 + _GL_T)  # of [p0, wall]
    # the stencils never reach below p = 0 (B1, B2 need not exist there): within 2h of the wall they are centred at
    # 2h, the derivatives taken there (their error O(h) only where the segment passes the wall, where the density is
    # the images' difference), b and c themselves at the point
    wall = q < 2.0 * h
    centre = np.maximum(q, 2.0 * h)
    at_wall = q[wall]
    pts = np.concatenate(
        [(centre[None] + shifts[:, None, None, None]).ravel(), at_wall, q0.ravel(), p.ravel(), qw.ravel()]
    )
    b_all, c_all = coef(pts)
    k = q.size * 5
    bs = b_all[:k].reshape((5,) + q.shape)
    cs = np.zeros_like(bs) if c_all is None else c_all[:k].reshape((5,) + q.shape)
    if at_wall.size:
        bs[2][wall] = b_all[k : k + at_wall.size]
        if c_all is not None:
            cs[2][wall] = c_all[k : k + at_wall.size]
    k += at_wall.size
    b_q0 = np.maximum(b_all[k : k + q0.size].reshape(q0.shape), 1e-300)
    b_p = np.maximum(b_all[k + q0.size : k + q0.size + p.size].reshape(p.shape), 1e-300)
    b_qw = np.maximum(b_all[k + q0.size + p.size :].reshape(qw.shape), 1e-300)
    b0 = np.maximum(bs[2], 1e-300)
    b1 = (bs[0] - 8 * bs[1] + 8 * bs[3] - bs[4]) / (12 * h)
    b2 = (-bs[0] + 16 * bs[1] - 30 * bs[2] + 16 * bs[3] - bs[4]) / (12 * h * h)
    c0 = cs[2]
    c1 = (cs[0] - 8 * cs[1] + 8 * cs[3] - cs[4]) / (12 * h)
    sq = np.sqrt(b0)
    mu = (c0 - 0.25 * b1) / sq  # drift of Y = int dp / sqrt(b)
    dmu_dy = c1 - 0.5 * c0 * b1 / b0 - 0.25 * b2 + b1 * b1 / (8.0 * b0)
    lam = 0.5 * (mu * mu + dmu_dy)
    dy = half * np.sum(_GL_W / sq, axis=-1)
    drift = half * np.sum(_GL_W * mu / sq, axis=-1)
    lam_int = half * np.sum(_GL_W * lam / sq, axis=-1)
    lam_mid = lam[..., _GL_T.size // 2]  # lambda near p0 (for dy = 0)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        lam_mean = np.where(dy != 0, lam_int / np.where(dy == 0, 1.0, dy), lam_mid)
        y0 = (0.5 * p0 * np.sum(_GL_W / np.sqrt(b_q0), axis=-1))[:, None]  # the start's distance from the wall
        gauss = np.exp(-0.5 * dy * dy / V0) - np.exp(-0.5 * (2.0 * y0 + dy) ** 2 / V0)
        if p_wall is not None:  # the image across the wall at distance yw above the start
            yw = (0.5 * (p_wall - p0) * np.sum(_GL_W / np.sqrt(b_qw), axis=-1))[:, None]
            gauss = gauss - np.exp(-0.5 * (2.0 * yw - dy) ** 2 / V0)
        P = gauss * np.exp(drift - V0 * lam_mean) / np.sqrt(2 * np.pi * V0 * b_p)
    return np.where(np.isfinite(P), P, 0.0)


ROUNDOFF_N_REF = 400
"""The degree at which the round-off floor of :func:`roundoff_floor` is eps ||L span||_1 itself."""


def roundoff_floor(L, span: float, n: int):
    r"""The error floor of the dense exponential of a collocated operator: :math:`\epsilon\,\|L\,\Delta V\|_1
    (n / 400)^2`, per load (the L1 error of P, dimensionless).

    ``scipy.linalg.expm`` (scaling and squaring, Pade) has a backward error of about eps ||L dV|| in the 1-norm: a
    perturbation of that *norm* lands on every row, also on the rows of the sparse nodes (large dp, small entries)
    where it is a large relative change.  ||L|| is set by the closest nodes (the Chebyshev ends at the walls and the
    cluster at p_bar: ~n^4 / dp_min^2).  Measured (homogenised, drifted and clock problems on the engine's grids,
    n = 100 to 400, against closed forms): the true L1 error at the round-off level is 0.004 to 0.31 of
    eps ||L dV||_1 and the share grows with the degree -- as (n / 400)^2 bounds it (2.8x margin or more over the
    measured cases) -- while two evaluations that are equal in exact arithmetic (expm of L dV against the square of
    expm of L dV / 2, or of a diagonally rescaled L) agree to 1e-17: the error is the Pade approximant's, the same in
    every such variant, so it has to be modelled from the operator's size rather than measured as a difference.

    Parameters
    ----------
    L : ndarray, shape (n_loads, m, m), 1 / pressure^2
        The operator (:func:`generator`; wall rows may be included).
    span : float, pressure^2
        The increment it is exponentiated over (a clock increment on the clock path).
    n : int
        The polynomial degree.

    Returns
    -------
    ndarray, shape (n_loads,)
    """
    norm = np.max(np.sum(np.abs(L), axis=-2), axis=-1)
    return np.finfo(float).eps * norm * abs(float(span)) * (n / ROUNDOFF_N_REF) ** 2


def zero_ripple(P0):
    """(P0 with its negative ripple set to 0, how many values): values in (-1e-6 x the peak, 0) per station and load,
    the polynomial's oscillation where P is ~0 (tails, next to the walls), within the error estimate; deeper dips are
    kept for the invariant checks to judge."""
    peak = np.max(P0, axis=-1, keepdims=True)
    ripple = (P0 < 0) & (P0 > -1e-6 * peak)
    return np.where(ripple, 0.0, P0), int(np.count_nonzero(ripple))
