r"""The pressure domain of the general engine, sized from the actual coefficients B1 and B2.

Without a hardness the engine's far wall at :math:`p_{end}` absorbs what reaches it (reported as
``info["far_wall_mass"]`` and added to the error estimate).  The homogenised rule :math:`\bar p + k\sqrt{V}` fits
:math:`B_2 = dV/d\zeta` only: a diffusion that grows with p spreads faster, a drift carries the PDF away.  Here the
domain follows the coefficients sampled on a probe grid in p and zeta:

* **diffusion** -- the total variance a walker would collect while sitting at p,
  :math:`T(p) = \int_1^{\zeta_{max}} B_2(p, \zeta)\,d\zeta`, defines the Lamperti-like distance
  :math:`y(p) = \int_{\bar p}^{p} dp'/\sqrt{T(p')}` (for :math:`B_2 = dV/d\zeta`: :math:`(p - \bar p)/\sqrt V`);
  the far end of the diffusion is where :math:`y = 0.7k` (``k_domain``; ``Y_FRACTION``), but never closer than
  :math:`\bar p + k\sqrt{T(\bar p)}` (the homogenised rule when B2 = dV/dzeta);
* **drift** -- plus the distance the largest outward drift can carry the PDF,
  :math:`R = \int \max_p \max(B_1, 0)\,d\zeta`.

A diffusion that grows so fast with p that y stays below k (e.g. :math:`B_2 \propto p^8`: the process is a strict
local martingale whose tail reaches any p) is capped at ``CAP`` times the homogenised width; what then leaves
through the far wall is measured and counted in the error estimate, never hidden.
"""

from __future__ import annotations

import numpy as np

__all__ = ["coefficient_domain", "CAP"]

Y_FRACTION = 0.7
"""The diffusion's far end is where y = Y_FRACTION x k_domain, but never closer than k_domain sqrt(T(p_bar)) (the
Gaussian tail of the diffusion at p_bar): a diffusion that grows with p has an exponential, not a Gaussian, tail in
y (measured: the squared Bessel case needs y ~ 0.6 k for 1e-14), and what a short domain loses is measured anyway."""
CAP = 8.0
"""The diffusive part of the domain is at most CAP x the homogenised width k sqrt(V(zeta_max))."""


def coefficient_domain(problem, k: float) -> tuple[float, dict]:
    """Far end p_end (pressure) of the general engine's domain and how it was found (a dict for ``info``).

    Parameters
    ----------
    problem : FokkerPlanckProblem
        Without a hardness (a hardness wall ends the domain itself).
    k : float
        ``k_domain``: distance in units of the local diffusive width.
    """
    pbm = float(np.max(problem.p_bar))
    s = float(np.sqrt(problem.V_max))
    hom = pbm + k * s
    cap = pbm + CAP * k * s
    z = np.geomspace(1.0, float(problem.zeta_max), 65)
    p = np.linspace(0.0, cap, 513)
    B1 = np.empty((z.size, p.size))
    B2 = np.empty((z.size, p.size))
    limited = None
    try:
        for i, zi in enumerate(z):
            B1[i], B2[i] = problem.coefficients(p, float(zi))
    except ValueError as err:  # coefficients defined only on a smaller range: probe (and cap) the homogenised one
        limited = str(err)
        cap = hom
        p = np.linspace(0.0, cap, 513)
        for i, zi in enumerate(z):
            B1[i], B2[i] = problem.coefficients(p, float(zi))
    T = np.trapezoid(B2, z, axis=0)  # (p,): variance collected at fixed p over the whole range
    # y(p) from p_bar outwards (midpoint rule per probe cell; T = 0 blocks the way: y jumps to infinity)
    Tm = 0.5 * (T[1:] + T[:-1])
    with np.errstate(divide="ignore"):
        dy = np.where(Tm > 0, np.diff(p) / np.sqrt(np.maximum(Tm, 0.0)), np.inf)
    start = int(np.searchsorted(p, pbm))
    y = np.concatenate(([0.0], np.cumsum(dy[start:])))
    target = Y_FRACTION * k
    reach = np.flatnonzero(y >= target)
    capped = reach.size == 0
    if capped:
        p_diff = cap
    else:
        j = int(reach[0])  # y crosses k inside probe cell start + j - 1: interpolate
        lo = p[start + j - 1]
        frac = 0.0 if not np.isfinite(dy[start + j - 1]) else (target - y[j - 1]) / max(y[j] - y[j - 1], 1e-300)
        p_diff = float(lo + np.clip(frac, 0.0, 1.0) * (p[1] - p[0]))
    # the Gaussian tail of the diffusion at p_bar itself (the homogenised rule with the local clock): a floor
    p_diff = max(p_diff, pbm + k * float(np.sqrt(max(np.interp(pbm, p, T), 0.0))))
    drift = 0.0
    for _ in range(3):  # the drift seen on the domain it makes (fixed point; B1 > 0 at larger p widens it)
        inside = p <= p_diff + drift
        up = np.max(np.maximum(B1[:, inside], 0.0), axis=1) if np.any(inside) else np.zeros(z.size)
        new = float(np.trapezoid(up, z))
        if new <= drift * (1 + 1e-3):
            drift = max(drift, new)
            break
        drift = new
    p_end = p_diff + drift
    info = {
        "p_end": p_end,
        "homogenised": hom,
        "diffusion_reach": p_diff - pbm,
        "drift_reach": drift,
        "capped": bool(capped),
        **({"probe_limited": limited} if limited else {}),
        "rule": "y(p) = int dp / sqrt(int B2 dzeta) = 0.7 k_domain (>= k_domain sqrt(T(p_bar))) + int max(B1, 0) dzeta",
    }
    return float(p_end), info
