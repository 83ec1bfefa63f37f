r"""Leak rate of a seal and contact conductance, from the magnification-resolved contact.

**Leak rate** (Lorenz & Persson, Eur. Phys. J. E 31 (2010) 159; EPL 86 (2009) 44006; Persson & Yang, J. Phys.:
Condens. Matter 20 (2008) 315011).  A fluid of viscosity :math:`\eta` flows between two rough surfaces, a seal of
length :math:`L_x` (along the flow) and width :math:`L_y`, with pressure drop :math:`\Delta p`.  Laminar flow through a
gap u carries :math:`u^3/(12\eta)` per unit width and unit pressure gradient (Reynolds).

- *Critical junction*: the non-contact channels first percolate at the magnification :math:`\zeta_c` where the
  contact area has fallen to :math:`A(\zeta_c) = A_c` (:math:`A_c \approx 0.42` for site percolation; 0.5 from 2-D
  effective-medium theory); the flow is limited by the narrowest junction of that network, whose gap is
  :math:`u_c = u_1(\zeta_c)`, and :math:`Q = (L_y/L_x)\,u_c^3\Delta p/(12\eta)`.  If the contact area never falls to
  :math:`A_c` the seal is closed: :math:`Q = 0`.
- *Effective medium* (2-D Bruggeman on the gap distribution): the effective conductivity :math:`\sigma_e` solves
  :math:`\int P(u)\,[\sigma(u) - \sigma_e]/[\sigma(u) + \sigma_e]\,du = 0`, :math:`\sigma = u^3/(12\eta)`, the contact
  atom with :math:`\sigma = 0`; :math:`Q = (L_y/L_x)\sigma_e\Delta p`.  It is 0 when the contact fraction is >= 1/2.

Both are reported also as an effective gap :math:`u_{eff} = (12\eta Q L_x/(L_y\Delta p))^{1/3}`.  Near the
percolation threshold the leak rate depends on details no mean-field theory holds (Dapp & Müser, Sci. Rep. 6 (2016)
19513): there the result is an order of magnitude at best.

**Contact conductance** (Barber, Proc. R. Soc. Lond. A 459 (2003) 53): for elastic contact the incremental normal
stiffness per nominal area :math:`K = -d\bar p/d\bar u` and the conductance are proportional,
:math:`C = 2K/(E^*(\rho_1 + \rho_2))` (electrical, resistivities :math:`\rho_i`) and
:math:`h = 2K/(E^*(1/k_1 + 1/k_2))` (thermal, conductivities :math:`k_i`).  Exact for a Hertz contact
(K = 2aE*, C = 4a/(ρ₁ + ρ₂), Holm's constriction conductance): that is the test.

What was checked (the leak-rate formulas are reconstructed from the papers' statements, not copied from them):
the critical junction on a pure power law, where :math:`A(\zeta)` and :math:`\zeta_c` are closed forms and
:math:`u_1` is rebuilt from Persson's separation of truncated spectra (tests, 2e-3); Bruggeman's two-phase limit
:math:`\sigma_e = \sigma_0(1 - 2A)` and a brute-force root of the Bruggeman integral (tests, 1e-3); and both
estimates against Reynolds flow through boundary-element gap fields (``benchmarks/interface_vs_bem.py``: effective
medium 1.0-1.4x, critical junction 1.7-2.9x for :math:`\bar p/(E^*\bar g) \le 0.1` with the corrected models, both 0
when sealed).

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from scipy.special import ndtr

from persson_fp._validate import as_float_array, as_positive_scalar

__all__ = ["A_C_DEFAULT", "critical_junction_gap", "effective_medium_gap", "flow_rate", "barber_conductance"]

A_C_DEFAULT = 0.42
"""Contact area at which the non-contact channels percolate (site percolation; Lorenz & Persson 2010)."""


def _check_A_c(A_c):
    A_c = as_positive_scalar(A_c, "A_c")
    if not 0.0 < A_c < 1.0:
        raise ValueError(f"A_c must lie in (0, 1), got {A_c!r}")
    return A_c


def critical_junction_gap(resolved, p_bar, A_c: float = A_C_DEFAULT, dA: float = 1e-3):
    r"""The gap :math:`u_c = u_1(\zeta_c)` of the critical junction, with :math:`A(\zeta_c) = A_c`.

    Parameters
    ----------
    resolved : MagnificationResolved
        Spectrum, modulus and model (:class:`persson_fp.theory.gaps.MagnificationResolved`).
    p_bar : array_like, pressure
        Loads (> 0).
    A_c : float
        Percolation threshold, in (0, 1); default 0.42.
    dA : float
        Half-width of the difference in A for :math:`u_1` (error :math:`O(dA^2)`).

    Returns
    -------
    u_c : ndarray, length
        0 where the seal is closed (:math:`A(\zeta_{max}) \ge A_c`).
    zeta_c : ndarray, dimensionless
        :math:`\zeta_c`; zeta_max where closed.
    """
    A_c = _check_A_c(A_c)
    p = as_float_array(p_bar, "p_bar")
    if np.any(p <= 0):
        raise ValueError("p_bar must be > 0 (pressure)")
    zmax = resolved.psd.zeta_max
    open_ = resolved.area(p, zmax) < A_c
    z_c = np.where(open_, resolved.zeta_of_area(p, A_c), zmax)
    u_c = np.zeros(p.shape)
    if np.any(open_):
        u_c[open_] = np.maximum(resolved.u1(p[open_], z_c[open_], dA=dA), 0.0)
    return u_c, z_c


def effective_medium_gap(gaps) -> np.ndarray:
    r"""Effective gap :math:`u_{eff} = (12\eta\sigma_e)^{1/3}` of 2-D Bruggeman theory on a gap distribution.

    Integrating by parts, with :math:`f(u) = (u^3 - u_e^3)/(u^3 + u_e^3)` and the survival function
    :math:`S(u) = 1 - \mathrm{cdf}(u)` of P (atom included), the Bruggeman condition is

    .. math::  -1 + \int_{-\infty}^{\infty} \frac{6e^{3y}}{(1 + e^{3y})^2}\, S(u_e e^{y})\,dy = 0,

    a logistic kernel in :math:`y = \ln(u/u_e)` against a smooth S (the integrand :math:`f` itself is a near-step
    in u, which Gauss-Hermite rules on the folded normals do not integrate).  S is tabulated per load on 160
    log-spaced gaps spanning 6 decades below the largest gap (S = 0 beyond) and interpolated linearly in ln u, the
    kernel integrated by the trapezoidal rule (step 0.25 on [-12, 12]: below 1e-10), the root in :math:`\ln u_e`
    found by bisection to 1e-13.  Measured: within 6e-4 relative of a 512-point, 8-decade table on the reference
    surface.

    Parameters
    ----------
    gaps : GapDistribution
        The gap distribution at each load.

    Returns
    -------
    ndarray, length
        :math:`u_{eff}` per load; exactly 0 where the contact fraction is >= 1/2 (2-D effective-medium threshold).
    """
    c, h, w, atom = gaps.centres, gaps.widths, gaps.weights, gaps.atom
    out = np.zeros(atom.size)
    live = np.flatnonzero((atom < 0.5) & (np.sum(w, axis=1) > 0))
    y = np.linspace(-12.0, 12.0, 97)
    kern = 6.0 * np.exp(3.0 * y) / (1.0 + np.exp(3.0 * y)) ** 2 * (y[1] - y[0])
    kern[[0, -1]] *= 0.5
    for i in range(0, live.size, 32):
        j = live[i : i + 32]
        used = np.any(w[j] > 0, axis=0)  # components empty in every load of the chunk are skipped
        cj, hj, wj = c[j][:, used], h[j][:, used], w[j][:, used]
        # the table ends where S = 0 to double precision (the largest gap plus ten widths, and a margin of e^0.5)
        v_hi = np.log(np.max(np.where(wj > 0, cj + 10.0 * hj, 0.0), axis=1)) + 0.5
        v = v_hi[:, None] + np.linspace(-6.0 * np.log(10.0), 0.0, 160)[None, :]
        u = np.exp(v)[:, :, None]
        cdf = atom[j][:, None] + np.sum(
            wj[:, None, :]
            * (ndtr((u - cj[:, None, :]) / hj[:, None, :]) - ndtr((-u - cj[:, None, :]) / hj[:, None, :])),
            axis=2,
        )
        S = np.clip(1.0 - cdf, 0.0, 1.0)
        dv = v[:, 1] - v[:, 0]

        def F(x, v=v, S=S, dv=dv):
            pos = (x[:, None] + y[None, :] - v[:, :1]) / dv[:, None]
            k = np.clip(pos, 0.0, S.shape[1] - 1.000001)
            i0 = k.astype(np.intp)
            fr = k - i0
            rows = np.arange(S.shape[0])[:, None]
            Sy = S[rows, i0] * (1.0 - fr) + S[rows, i0 + 1] * fr  # S is flat below the table (no mass there)
            return -1.0 + Sy @ kern

        lo, hi = v[:, 0] - 14.0, v_hi + 14.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            f = F(mid)
            lo = np.where(f > 0, mid, lo)
            hi = np.where(f > 0, hi, mid)
        out[j] = np.exp(0.5 * (lo + hi))
    return out


def flow_rate(gap, viscosity, pressure_drop, aspect=1.0) -> np.ndarray:
    r"""Volume flow rate :math:`Q = (L_y/L_x)\,u^3\Delta p/(12\eta)` through a seal of effective gap ``gap``.

    Parameters
    ----------
    gap : array_like, length
        Effective gap(s), >= 0.
    viscosity : float, pressure x time
        Dynamic viscosity :math:`\eta` (> 0), e.g. Pa s.
    pressure_drop : float, pressure
        :math:`\Delta p` across the seal (> 0).
    aspect : float, dimensionless
        :math:`L_y/L_x`, seal width over seal length along the flow (> 0).

    Returns
    -------
    ndarray, length^3 / time
        Q, of the shape of ``gap``.
    """
    eta = as_positive_scalar(viscosity, "viscosity")
    dp = as_positive_scalar(pressure_drop, "pressure_drop")
    aspect = as_positive_scalar(aspect, "aspect")
    u = as_float_array(gap, "gap")
    if np.any(u < 0):
        raise ValueError("gap must be >= 0 (length)")
    return aspect * u**3 * dp / (12.0 * eta)


def _pair(value, name):
    v = as_float_array(value, name)
    if v.shape != (2,) or not np.all(np.isfinite(v)) or np.any(v <= 0):
        raise ValueError(f"{name} must be a pair of finite values > 0 (one per body), got {value!r}")
    return v


def barber_conductance(stiffness, E_star, resistivity=None, thermal_conductivity=None):
    r"""Electrical or thermal contact conductance per nominal area from the normal stiffness (Barber 2003).

    Parameters
    ----------
    stiffness : array_like, pressure / length
        :math:`K = -d\bar p/d\bar u` per nominal area (> 0).
    E_star : float, pressure
        Plane-strain modulus of the pair (> 0).
    resistivity : pair of float, resistance x length, optional
        :math:`(\rho_1, \rho_2)` of the two bodies (> 0), e.g. Ω m: returns :math:`C = 2K/(E^*(\rho_1+\rho_2))`.
    thermal_conductivity : pair of float, power / (length x temperature), optional
        :math:`(k_1, k_2)` (> 0), e.g. W/(m K): returns :math:`h = 2K/(E^*(1/k_1+1/k_2))`.
        Exactly one of ``resistivity`` and ``thermal_conductivity`` must be given.

    Returns
    -------
    ndarray
        Conductance per nominal area, 1/(resistance x length²) (S/m²) or power/(length² x temperature) (W/(m² K)).
    """
    if (resistivity is None) == (thermal_conductivity is None):
        raise ValueError("give exactly one of resistivity=(rho1, rho2) and thermal_conductivity=(k1, k2)")
    K = as_float_array(stiffness, "stiffness")
    if np.any(~np.isfinite(K)) or np.any(K <= 0):
        raise ValueError("stiffness must be finite and > 0 (pressure / length)")
    E_star = as_positive_scalar(E_star, "E_star")
    if resistivity is not None:
        r = _pair(resistivity, "resistivity")
        return 2.0 * K / (E_star * (r[0] + r[1]))
    k = _pair(thermal_conductivity, "thermal_conductivity")
    return 2.0 * K / (E_star * (1.0 / k[0] + 1.0 / k[1]))
