r"""Radial averaging of a 2-D power spectrum into Persson's isotropic C(q) that carries the map's own moments.

The modes :math:`q_k` of a map (power :math:`|\hat h_k|^2`, summing to :math:`\langle h^2\rangle`) are grouped
into annuli that run from the lowest mode radius (:math:`2\pi/L`) to the highest one (the corner of the
lattice, :math:`\sqrt2\,\pi N/L` for a square map): one lattice step wide at small q, log-spaced above.  In each
annulus C is a power law :math:`A_j q^{s_j}` that carries the power :math:`\sum|\hat h_k|^2` of its modes, so the
spectrum carries the map's :math:`\langle h^2\rangle` to round-off.  In the first annuli, which hold a few lattice
radii each, the exponent also carries their slope power :math:`\sum q_k^2|\hat h_k|^2`.  Above, where each annulus
holds many modes spread evenly over it, its level is the mean C of its modes (the lattice count of an annulus
differs from its area by a few % near :math:`10\cdot 2\pi/L`), times a factor and a power of q (at most
:math:`q^{\pm1}`) that keep their total power and slope power; its
exponent is the trend of these levels (a least-squares line through the annulus and its two neighbours) plus one
common tilt (at most 2) that makes their slope power sum to that of their modes: the spectrum carries the map's
:math:`\langle|\nabla h|^2\rangle` too.  Empty annuli are merged into the next; the band ends with the last annulus
that has power.  Beyond the Nyquist circle the annuli are incomplete (the corners of the lattice): their power is
spread over the whole annulus, so that the spectrum carries it, and C there is below the isotropic spectrum by the
missing fraction of the annulus.

The rms slope of non-periodic data is taken by central differences (``numpy.gradient``); the same operator
applied to an isotropic spectrum gives :math:`\langle|\nabla_{\Delta} h|^2\rangle = 2\pi\int qC(q)K(q)\,dq`,
:math:`K(q) = \sum_a (1 - J_0(2q\Delta_a))/(2\Delta_a^2)` (the angular mean of :math:`\sin^2(q_a\Delta_a)/
\Delta_a^2`), which :func:`central_difference_slope` evaluates, so both sides use one definition.
"""

from __future__ import annotations

import numpy as np

from persson_fp.surfaces.psd import powint

__all__ = ["annulus_table", "central_difference_slope"]

WIDE = 1.2
"""Annuli at least this wide (outer / inner radius: the first few, one lattice step wide) get the exponent that
carries their slope power."""


def _edges(q_lo, q_hi, step, bins_per_decade):
    r = 10.0 ** (1.0 / bins_per_decade)
    edges = [q_lo]
    while edges[-1] < q_hi:
        width = max(step, edges[-1] * (r - 1.0))
        edges.append(min(edges[-1] + width, q_hi))
        if q_hi - edges[-1] < 0.25 * width:
            edges[-1] = q_hi
    return np.array(edges)


def _populated(q_mode, power, edges, tiny):
    """Annuli holding power: (power, power-weighted mean q^2, modes, edges); empty or powerless annuli merged into the
    next (trailing ones dropped: the band ends with the last annulus that has power)."""
    n = edges.size - 1
    # the edges start on the lowest mode and step by the lattice step, so lattice radii fall on edges: a mode within
    # round-off (1e-9 relative) of an edge counts in the annulus above it, as exact arithmetic would place it, and
    # the table does not depend on the unit of length (it did, by up to a factor 2.8 in C, through round-off)
    idx = np.clip(np.searchsorted(edges, q_mode * (1.0 + 1e-9), side="right") - 1, 0, n - 1)
    P = np.bincount(idx, weights=power, minlength=n)
    Q2 = np.bincount(idx, weights=power * q_mode**2, minlength=n)
    count = np.bincount(idx, minlength=n)
    out, out_e = [], [edges[0]]
    acc = np.zeros(3)
    for j in range(n):
        acc += (P[j], Q2[j], count[j])
        if acc[0] > tiny:
            out.append(acc.copy())
            out_e.append(edges[j + 1])
            acc[:] = 0.0
    if out:  # trailing annuli without power (< tiny): the band ends with the last annulus that has power
        out[-1][:2] += acc[:2]
    P_out, Q2_out, n_out = np.array(out).T if out else (np.zeros(0),) * 3
    return P_out, Q2_out / np.where(P_out > 0, P_out, 1.0), n_out, np.array(out_e)


def _local_exponent(a, b, m2):
    """Exponent s of C ~ q^s on [a, b] whose mean q^2 (weight 2 pi q C) is ``m2`` (bisection, s in [-60, 60])."""
    lo, hi = np.full(a.shape, -60.0), np.full(a.shape, 60.0)
    r = b / a
    for _ in range(60):
        s = 0.5 * (lo + hi)
        mean = a * a * powint(1.0, r, 4.0 + s) / powint(1.0, r, 2.0 + s)
        up = mean < m2
        lo, hi = np.where(up, s, lo), np.where(up, hi, s)
    return 0.5 * (lo + hi)


def _levels(c, P, m2):
    """Powers ``c F (m2 / m2[0])^(g/2)`` of annuli whose mean-C levels are ``c``: F and g (|g| <= 1) such that they
    carry the modes' total power and slope power (sum P, sum P m2), so the lattice-count correction moves neither."""
    w_target = np.sum(P * m2) / np.sum(P)

    def weights(g):
        w = c * (m2 / m2[0]) ** (0.5 * g)
        return w * (np.sum(P) / np.sum(w))

    lo, hi = -1.0, 1.0
    if not np.sum(weights(lo) * m2) <= w_target * np.sum(P) <= np.sum(weights(hi) * m2):
        return weights(0.0)
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if np.sum(weights(mid) * m2) < w_target * np.sum(P) else (lo, mid)
    return weights(0.5 * (lo + hi))


def _trend(x, y, half=1):
    """Local log-log slope: least-squares line through the points j - half .. j + half (fewer at the ends)."""
    out = np.empty_like(x)
    for j in range(x.size):
        sl = slice(max(j - half, 0), min(j + half + 1, x.size))
        xs = x[sl] - x[sl].mean()
        out[j] = np.sum(xs * (y[sl] - y[sl].mean())) / np.sum(xs * xs)
    return out


def _slope_power(a, b, s, P):
    """Sum over annuli of P times the mean q^2 of C ~ q^s on [a, b] (weight q C)."""
    return np.sum(P * a * a * powint(1.0, b / a, 4.0 + s) / powint(1.0, b / a, 2.0 + s))


def _common_tilt(a, b, s, P, Q2):
    """The one shift of the exponents s that makes the annuli's slope power sum to that of their modes (Q2)."""
    target = np.sum(Q2)
    lo, hi = -2.0, 2.0
    if not _slope_power(a, b, s + lo, P) <= target <= _slope_power(a, b, s + hi, P):
        return 0.0
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _slope_power(a, b, s + mid, P) < target else (lo, mid)
    return 0.5 * (lo + hi)


def annulus_table(q_mode, power, step, bins_per_decade, q_full=np.inf):
    """Persson's C(q) table of modes (radius ``q_mode`` > 0 in rad/length, ``power`` summing to <h^2>, length^2)
    on a lattice of steps ``step`` (rad/length), whose annuli are complete up to ``q_full`` (the Nyquist circle).

    C is a power law :math:`A_j q^{s_j}` in each annulus :math:`[e_j, e_{j+1}]`: :math:`2\\pi\\int qC\\,dq` over
    the annulus is the power of its modes; in annuli wider than ``WIDE`` (the first few, holding a few lattice radii)
    :math:`2\\pi\\int q^3C\\,dq` is also their :math:`\\sum q_k^2|\\hat h_k|^2`, elsewhere the exponent is the trend of
    the annulus means (a few hundred modes each, spread evenly over the annulus) plus one common tilt that makes
    their total slope power that of their modes.  Each law ends a relative ``1e-7`` before the next annulus, so that
    the log-log interpolant is this piecewise law.

    Returns
    -------
    q, C : numpy.ndarray
        Table points (rad/length) from the lowest to the highest mode radius and C (length^4).
    """
    q_lo, q_hi = float(q_mode.min()), float(q_mode.max())
    edges = _edges(q_lo, q_hi, max(step), bins_per_decade)
    P_bin, m2, count, edges = _populated(q_mode, power, edges, 1e-30 * power.max())
    if P_bin.size < 2:
        raise ValueError("fewer than 2 annuli carry power: the height data are too small or constant")
    a, b = edges[:-1], edges[1:]
    area = np.pi * (b * b - a * a)
    wide = b / a >= WIDE  # few lattice radii: the exponent carries the annulus' slope power too
    # many modes: the level is their mean C (the lattice count of an annulus differs from its area / cell by a
    # few % at q ~ 10 2 pi / L), times one factor that keeps their total power
    many = ~wide & (b <= q_full * (1.0 + 1e-9))  # (an edge on the Nyquist circle is inside it, in any unit)
    P = P_bin.copy()
    mean_C = P_bin / (count * step[0] * step[1])
    if np.any(many):
        P[many] = _levels(mean_C[many] * area[many], P_bin[many], m2[many])
    s = np.clip(_trend(0.5 * np.log(a * b), np.log(P / area)), -12.0, 4.0)
    s[wide] = _local_exponent(a[wide], b[wide], np.clip(m2[wide], a[wide] ** 2, b[wide] ** 2))
    s[~wide] += _common_tilt(a[~wide], b[~wide], s[~wide], P[~wide], P_bin[~wide] * m2[~wide])
    P_bin = P
    # 2 pi int_a^b q A q^s dq = P  ->  A a^(2+s) = P / (2 pi powint(1, b/a, 2+s))
    lA = np.log(P_bin / (2.0 * np.pi * powint(1.0, b / a, 2.0 + s))) - (2.0 + s) * np.log(a)
    ends = b * (1.0 - 1e-7)
    ends[-1] = b[-1]
    q = np.column_stack((a, ends)).ravel()
    lC = np.column_stack((lA + s * np.log(a), lA + s * np.log(ends))).ravel()
    return q, np.exp(lC)


def central_difference_slope(psd, steps) -> float:
    r"""rms slope of an isotropic spectrum as central differences on a grid of spacing ``steps`` measure it.

    Parameters
    ----------
    psd : PSD
        Persson's isotropic spectrum (q in rad/length, C in length^4).
    steps : sequence of float, length
        Grid spacing along each axis.

    Returns
    -------
    float
        :math:`\sqrt{2\pi\int qC(q)K(q)\,dq}`, :math:`K(q) = \sum_a (1 - J_0(2q\Delta_a))/(2\Delta_a^2)`
        (dimensionless).
    """
    from scipy.special import j0

    x, w = np.polynomial.legendre.leggauss(16)
    nodes = np.unique(np.concatenate(([psd.q_l], np.asarray(getattr(psd, "q", []), float), [psd.q_s])))
    nodes = nodes[(nodes >= psd.q_l) & (nodes <= psd.q_s)]
    nodes = np.append(np.exp(np.linspace(np.log(nodes[:-1]), np.log(nodes[1:]), 5, axis=1)[:, :-1]).ravel(), psd.q_s)
    a, b = np.log(nodes[:-1])[:, None], np.log(nodes[1:])[:, None]
    lq = 0.5 * (a + b) + 0.5 * (b - a) * x
    q = np.exp(lq)
    K = sum((1.0 - j0(2.0 * q * d)) / (2.0 * d * d) for d in steps)
    f = 2.0 * np.pi * q * psd.C(q) * K * q  # dq = q dlnq
    return float(np.sqrt(np.sum(0.5 * (b - a) * f * w)))
