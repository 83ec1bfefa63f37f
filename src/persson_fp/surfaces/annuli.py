r"""Radial averaging of a 2-D power spectrum into Persson's isotropic C(q) that carries the map's own moments.

The modes :math:`q_k` of a map (power :math:`|\hat h_k|^2`, summing to :math:`\langle h^2\rangle`) are grouped
into annuli that run from the lowest mode radius (:math:`2\pi/L`) to the highest one (the corner of the
lattice, :math:`\sqrt2\,\pi N/L` for a square map): one lattice step wide at small q, log-spaced above; empty
annuli are merged into the next and the band ends with the last annulus that has power.  Each annulus gives one
point of the table: the mean C of its modes, :math:`\sum|\hat h_k|^2/(n\,\Delta q_x\Delta q_y)` (an unbiased
estimate of C there), at the geometric mean of their radii, so that the points are sorted in q and the
spectrum has no jumps.  The first point sits at the lowest mode radius and the last at the highest, so that the
band is the data's.  Beyond the Nyquist circle the annuli are incomplete (the corners of the lattice): their power
is spread over the whole annulus, so C there is below the isotropic spectrum by the missing fraction.

The log-log interpolant of these points is then multiplied by one factor and one power of q,
:math:`F\,(q/q_1)^g` with :math:`|g| \le 1`, that make it carry the modes' total power and slope power: the
spectrum carries the map's :math:`\langle h^2\rangle` and :math:`\langle|\nabla h|^2\rangle` (to round-off
where :math:`|g| \le 1` suffices; measured :math:`|g| < 0.05` on self-affine maps).

The rms slope of non-periodic data is taken by central differences (``numpy.gradient``); the same operator
applied to an isotropic spectrum gives :math:`\langle|\nabla_{\Delta} h|^2\rangle = 2\pi\int qC(q)K(q)\,dq`,
:math:`K(q) = \sum_a (1 - J_0(2q\Delta_a))/(2\Delta_a^2)` (the angular mean of :math:`\sin^2(q_a\Delta_a)/
\Delta_a^2`), which :func:`central_difference_slope` evaluates, so both sides use one definition.
"""

from __future__ import annotations

import numpy as np

from persson_fp.surfaces.psd import powint

__all__ = ["annulus_table", "central_difference_slope"]


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
    """Annuli holding power: (power, power-weighted mean q^2, modes, edges, mean ln q of the modes); empty or powerless
    annuli merged into the next (trailing ones dropped: the band ends with the last annulus that has power)."""
    n = edges.size - 1
    # the edges start on the lowest mode and step by the lattice step, so lattice radii fall on edges: a mode within
    # round-off (1e-9 relative) of an edge counts in the annulus above it, as exact arithmetic would place it, and
    # the table does not depend on the unit of length (it did, by up to a factor 2.8 in C, through round-off)
    idx = np.clip(np.searchsorted(edges, q_mode * (1.0 + 1e-9), side="right") - 1, 0, n - 1)
    P = np.bincount(idx, weights=power, minlength=n)
    Q2 = np.bincount(idx, weights=power * q_mode**2, minlength=n)
    count = np.bincount(idx, minlength=n)
    LQ = np.bincount(idx, weights=np.log(q_mode), minlength=n)
    out, out_e = [], [edges[0]]
    acc = np.zeros(4)
    for j in range(n):
        acc += (P[j], Q2[j], count[j], LQ[j])
        if acc[0] > tiny:
            out.append(acc.copy())
            out_e.append(edges[j + 1])
            acc[:] = 0.0
    if out:  # trailing annuli without power (< tiny): the band ends with the last annulus that has power
        out[-1][:2] += acc[:2]
    P_out, Q2_out, n_out, LQ_out = np.array(out).T if out else (np.zeros(0),) * 4
    return P_out, Q2_out / np.where(P_out > 0, P_out, 1.0), n_out, np.array(out_e), LQ_out / np.maximum(n_out, 1)


def _moments(q, C):
    """(int q C dq, int q^3 C dq) of the log-log interpolant of the table (q, C), per interval."""
    r = q[1:] / q[:-1]
    s = np.log(C[1:] / C[:-1]) / np.log(r)  # C = C_i (q/q_i)^s_i on [q_i, q_i+1]
    return C[:-1] * q[:-1] ** 2 * powint(1.0, r, 2.0 + s), C[:-1] * q[:-1] ** 4 * powint(1.0, r, 4.0 + s)


TINY = 1e-20
"""Annuli whose power is below ``TINY`` times the largest mode's carry none (round-off of modes without power, e.g.
beyond a synthetic map's cut-off): merged into the next, and the band ends with the last annulus that has power."""

LOW = 4.0
"""The lift that carries the lowest lattice modes' power fades out by ``LOW`` times the lowest mode radius."""


def _carry(q, C, h2, g2):
    """The table made to carry <h^2> = h2 and <|grad h|^2> = g2 (module docstring): C times
    :math:`f_0^{w(q)}(q/q_0)^g`, :math:`w = \\max(0, 1 - \\ln(q/q_0)/\\ln 4)`, with ln f_0 in [-3, 3] and |g| <= 1
    (Newton in both; then, where they cannot, one factor F on all carries h2).

    Returns (C, f_0, g, F)."""
    lq = np.log(q / q[0])
    w = np.clip(1.0 - lq / np.log(LOW), 0.0, 1.0)
    lo, hi = np.array([-3.0, -1.0]), np.array([3.0, 1.0])

    def table(x):
        return C * np.exp(x[0] * w + x[1] * lq)

    def residual(x):
        m0, m2 = (float(np.sum(m)) for m in _moments(q, table(x)))
        return np.array([np.log(2.0 * np.pi * m0 / h2), np.log(2.0 * np.pi * m2 / g2)])

    x = np.zeros(2)
    r = residual(x)
    for _ in range(30):
        if np.max(np.abs(r)) < 1e-13:
            break
        J = np.column_stack([(residual(x + d) - r) / 1e-7 for d in np.eye(2) * 1e-7])
        try:
            step = np.linalg.solve(J, -r)
        except np.linalg.LinAlgError:
            break
        x_new = np.clip(x + step, lo, hi)
        r_new = residual(x_new)
        if np.max(np.abs(r_new)) >= np.max(np.abs(r)) and np.allclose(x_new, x):
            break
        x, r = x_new, r_new
    out = table(x)
    F = h2 / (2.0 * np.pi * float(np.sum(_moments(q, out)[0])))
    return out * F, float(np.exp(x[0])), float(x[1]), F


def annulus_table(q_mode, power, step, bins_per_decade, q_full=np.inf):
    """Persson's C(q) table of modes (radius ``q_mode`` > 0 in rad/length, ``power`` summing to <h^2>, length^2)
    on a lattice of steps ``step`` (rad/length), whose annuli are complete up to ``q_full`` (the Nyquist circle).

    One point per annulus (module docstring): the mean C of its modes at the geometric mean of their radii (the
    first point at the lowest mode radius, the last at the highest); in the incomplete annuli beyond ``q_full``
    their power over the annulus' area.  The log-log interpolant, times the lift :math:`f_0^{w(q)}` of the
    lowest radii and a tilt :math:`(q/q_0)^g`, carries the modes' :math:`\\sum|\\hat h_k|^2` and
    :math:`\\sum q_k^2|\\hat h_k|^2`.

    Returns
    -------
    q, C : numpy.ndarray
        Table points (rad/length), strictly increasing from the lowest to the highest mode radius, and C
        (length^4).
    lift : tuple of float
        (f_0, g, F): the lift at the lowest mode radius, the tilt and the factor on all (1 where the lift and the
        tilt suffice).
    """
    q_lo = float(q_mode.min())
    edges = _edges(q_lo, float(q_mode.max()), max(step), bins_per_decade)
    P_bin, m2, count, edges, mean_lq = _populated(q_mode, power, edges, TINY * power.max())
    if P_bin.size < 2:
        raise ValueError("fewer than 2 annuli carry power: the height data are too small or constant")
    a, b = edges[:-1], edges[1:]
    inside = b <= q_full * (1.0 + 1e-9)  # (an edge on the Nyquist circle is inside it, in any unit)
    # the mean C of the modes inside the Nyquist circle; beyond it their power spread over the whole annulus
    C = np.where(inside, P_bin / (count * step[0] * step[1]), P_bin / (np.pi * (b * b - a * a)))
    q = np.exp(mean_lq)
    q[0], q[-1] = q_lo, edges[-1]  # the band is the data's: the end annuli's points on its ends
    C, f0, g, F = _carry(q, C, float(np.sum(P_bin)), float(np.sum(P_bin * m2)))
    return q, C, (f0, g, F)


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
