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

This module imports no solver.
"""

from __future__ import annotations

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar

__all__ = ["A_C_DEFAULT", "critical_junction_gap", "effective_medium_gap", "flow_rate", "barber_conductance"]

A_C_DEFAULT = 0.42
"""Contact area at which the non-contact channels percolate (site percolation; Lorenz & Persson 2010)."""

_GH_X, _GH_W = np.polynomial.hermite_e.hermegauss(24)
_GH_W = _GH_W / np.sqrt(2.0 * np.pi)


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

    Each folded normal of :class:`~persson_fp.theory.gaps.GapDistribution` is integrated with 24-point
    Gauss-Hermite nodes (about 1e-3 relative in :math:`\sigma_e`); the root in :math:`\ln\sigma_e` by safeguarded
    Newton to 1e-12.

    Parameters
    ----------
    gaps : GapDistribution
        The gap distribution at each load.

    Returns
    -------
    ndarray, length
        :math:`u_{eff}` per load; exactly 0 where the contact fraction is >= 1/2.
    """
    c, h, w = gaps.centres[:, :, None], gaps.widths[:, :, None], gaps.weights[:, :, None]
    u = np.abs(c + h * _GH_X[None, None, :])
    s = (u**3).reshape(gaps.n_loads, -1)  # 12 eta sigma(u)
    W = (w * _GH_W[None, None, :]).reshape(gaps.n_loads, -1)
    atom = gaps.atom
    out = np.zeros(gaps.n_loads)
    live = np.flatnonzero((atom < 0.5) & (np.sum(W, axis=1) > 0))
    for j in live:
        keep = (W[j] > 0) & (s[j] > 0)
        sj, Wj = s[j][keep], W[j][keep]
        lo, hi = np.log(sj.min()) - 80.0, np.log(sj.max())

        def F(t, sj=sj, Wj=Wj, a=atom[j]):
            e = np.exp(t)
            return np.sum(Wj * (sj - e) / (sj + e)) - a

        t = 0.5 * (lo + hi)
        for _ in range(200):
            e = np.exp(t)
            f = F(t)
            if f > 0:
                lo = t
            else:
                hi = t
            df = -np.sum(Wj * 2.0 * sj * e / (sj + e) ** 2)
            t_new = t - f / df if df < 0 else 0.5 * (lo + hi)
            if not lo < t_new < hi:
                t_new = 0.5 * (lo + hi)
            if abs(t_new - t) < 1e-12 or hi - lo < 1e-12:
                t = t_new
                break
            t = t_new
        out[j] = np.exp(t / 3.0)
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
