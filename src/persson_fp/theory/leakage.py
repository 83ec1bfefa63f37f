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
    if not 1e-12 <= A_c <= 1.0 - 1e-12:
        raise ValueError(f"A_c must lie in (0, 1) (at least 1e-12 from either end), got {A_c!r}")
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
        u_raw = np.asarray(resolved.u1(p[open_], z_c[open_], dA=dA), dtype=float)
        bad = ~(np.isfinite(u_raw) & (u_raw > 0.0))
        if np.any(bad):  # zeta_c within round-off of 1, where u1 = d(A u)/dA diverges: no junction gap to give
            pb = float(p[open_][bad][0])
            raise ValueError(
                f"critical junction undefined at p_bar = {pb:.3g}: the contact area falls to A_c = {A_c:g} at zeta_c "
                f"= {float(z_c[open_][bad][0]):.9g}, within round-off of zeta = 1, where u1 diverges (the load is too "
                "small for this estimate); use method='effective-medium'"
            )
        u_c[open_] = u_raw
    return u_c, z_c


def effective_medium_gap(gaps, return_error: bool = False):
    r"""Effective gap :math:`u_{eff} = (12\eta\sigma_e)^{1/3}` of 2-D Bruggeman theory on a gap distribution.

    With :math:`\sigma \propto u^3`, :math:`(\sigma - \sigma_e)/(\sigma + \sigma_e) = \tanh(\tfrac32(v - x))` in
    :math:`v = \ln u`, :math:`x = \ln u_e`, so the Bruggeman condition (contact atom A, :math:`\sigma = 0`) is

    .. math::  F(x) = -A + \int_{-\infty}^{\infty} \rho(v)\,\tanh\big(\tfrac32(v - x)\big)\,dv = 0,
               \qquad \rho(v) = u\,P(u)\big|_{u = e^v},

    the density of the continuous part in ln u against a smooth sigmoid (in u the integrand is a near-step, which
    Gauss-Hermite rules on the folded normals do not integrate).  :math:`\rho` is evaluated once per load on nodes
    uniform in v spanning 6 decades below the largest gap (9 where the contact fraction exceeds 0.3, deeper if the
    root comes within 8 of the bottom; :math:`\rho = 0` above to double precision), the mass below the lowest node,
    where the sigmoid is -1 to 2e-24, taken from the CDF, and the integral is the trapezoidal rule on those fixed
    nodes for every x, with the Euler-Maclaurin correction at the bottom (:math:`\rho \propto e^v` there).  The rule
    converges like :math:`e^{-c(\sigma/\Delta v)^2}` for a feature of width :math:`\sigma` in v; a folded normal
    of centre c and width h is one of width ~h/c, so the step is chosen per load from the narrowest component
    holding more than 1e-6 of the mass (``_spacing``), at most 0.2, and halved until three times the rule's error
    on the known mass, divided by :math:`|dF/dx|`, is below 1e-6 relative.  F decreases in x; it is tabulated on
    every few nodes (one matrix product) to bracket the root, which bracketed Newton steps find to
    :math:`|F| < 10^{-13}`.  The error returned is an upper estimate: the larger of that and the shift of the root
    under the same rule on every other node (step :math:`2\Delta v`).  Measured against scipy ``quad`` +
    ``brentq`` on the Bruggeman integral in u (tests): within 4e-7 relative, on the theory's distributions and on
    random mixtures with components down to h/c = 0.03, and never above the returned estimate.  A load's answer
    does not depend on the other loads of the call: steps lie on the ladder 0.2 / 2^k, loads share a vectorised
    chunk only with the same step and depth, and each stops its own Newton iteration (a converged load iterated on
    with its chunk drifted along a flat F by up to 1e-5 relative, within its estimate).  The earlier
    linear-interpolation table (6e-4) took 2.5x as long (1 000 loads, medians).

    Parameters
    ----------
    gaps : GapDistribution
        The gap distribution at each load.
    return_error : bool
        Also return the estimated relative error of :math:`u_{eff}` per load.

    Returns
    -------
    ndarray, length
        :math:`u_{eff}` per load; exactly 0 where the contact fraction is >= 1/2 (2-D effective-medium threshold).
    ndarray, dimensionless
        With ``return_error``: the trapezoidal rule's error on the (known) mass divided by :math:`|dF/dx|`, an
        estimate of the relative error of :math:`u_{eff}` (0 where sealed).
    """
    c, h, w, atom = gaps.centres, gaps.widths, gaps.weights, gaps.atom
    out, err, coarse = np.zeros(atom.size), np.zeros(atom.size), np.zeros(atom.size)
    todo = np.flatnonzero((atom < 0.5) & (np.sum(w, axis=1) > 0))
    dv_all = _spacing(c, h, w)
    depth = np.where(atom > 0.3, _DEPTH + 3.0 * np.log(10.0), _DEPTH)  # near the threshold u_e is small
    while todo.size:
        # loads of the same spacing and table depth share a chunk (a load's answer never depends on the others')
        todo = todo[np.lexsort((depth[todo], dv_all[todo]))]
        key = np.stack([dv_all[todo], depth[todo]])
        cuts = np.flatnonzero(np.any(key[:, 1:] != key[:, :-1], axis=0)) + 1
        for group in np.split(todo, cuts):
            for i in range(0, group.size, _CHUNK):
                j = group[i : i + _CHUNK]
                used = np.any(w[j] > 0, axis=0)  # components empty in every load of the chunk are skipped
                out[j], err[j], coarse[j], x = _bruggeman_chunk(
                    c[j][:, used], h[j][:, used], w[j][:, used], atom[j], float(dv_all[j[0]]), float(depth[j[0]])
                )
                # a root within 8 of the table's bottom (u_e < ~1e-3 of the largest gap x 1e-3): deepen the table
                shallow = (x > -depth[j] + 8.0) | (depth[j] >= _DEPTH_MAX)
                depth[j] = np.where(shallow, depth[j], np.minimum(np.ceil(-x + 9.0), _DEPTH_MAX))
                err[j] = np.where(shallow, err[j], np.inf)
        # halve the spacing where the estimate (x 3: it is within a factor 2 when resolved) exceeds the target
        deeper = ~np.isfinite(err[todo])
        redo = (_SAFETY * err[todo] > _TOL) & (dv_all[todo] > _DV_MIN) & ~deeper
        dv_all[todo[redo]] *= 0.5
        todo = todo[redo | deeper]
    if not return_error:
        return out
    return out, np.where(out > 0, np.maximum(_SAFETY * err, np.nan_to_num(coarse, nan=np.inf)) + _FLOOR, 0.0)


_CHUNK = 64
_DV_MIN, _DV_MAX = 0.005, 0.2
_DEPTH = 6.0 * np.log(10.0)  # the table spans 6 decades below the largest gap unless the root is deeper
_DEPTH_MAX = 60.0 * np.log(10.0)  # a root deeper than 60 decades (contact fraction within ~1e-16 of 1/2) is left
_TOL = 1e-6  # target relative error of u_e
_SAFETY = 3.0
_FLOOR = 1e-10  # the root (|F| < 1e-13) and the sigmoid's tails (2e-24) below the estimate's reach
_SQ2PI = np.sqrt(2.0 * np.pi)


def _spacing(c, h, w):
    """Node spacing in ln u per load: the trapezoidal error of a component of mass w and relative width s = h/c
    was measured as ~1e-2 w exp(-7.2 (s/dv)^2) (random mixtures against adaptive quadrature); each is kept
    below 1e-8."""
    felt = (w > 1e-6) & (h < c)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(felt, h / np.where(felt, c, 1.0) * np.sqrt(7.2 / np.log(1e6 * np.where(felt, w, 1.0))), np.inf)
    dv = np.clip(np.min(s, axis=1), _DV_MIN, _DV_MAX)
    return _DV_MAX * 2.0 ** -np.ceil(np.log2(_DV_MAX / dv))  # on the ladder _DV_MAX / 2^k (never coarser)


def _bruggeman_chunk(c, h, w, atom, dv, depth):
    """Roots u_e of the Bruggeman condition for a chunk of loads sharing the node spacing dv (in ln u) and the
    table depth (in ln u); also the error estimate and the root relative to the top of the table."""
    # the table ends where rho = 0 to double precision (the largest gap plus ten widths, and a margin of e^0.5)
    v_hi = np.log(np.max(np.where(w > 0, c + 10.0 * h, 0.0), axis=1)) + 0.5
    n = int(np.ceil(depth / dv)) + 1
    off = dv * np.arange(-(n - 1), 1)  # nodes relative to v_hi
    u = np.exp(v_hi[:, None] + off[None, :])
    cc, hh = c[:, None, :], h[:, None, :]
    # the pair G(u - c) + G(u + c), in place (the array is loads x nodes x components); exponents clipped at -600
    # (denormals are slow, and those terms negligible)
    uu = u[:, :, None]
    g = uu * (1.0 / hh) - cc / hh
    g *= g
    g *= -0.5
    np.maximum(g, -600.0, out=g)
    np.exp(g, out=g)
    mirror = uu * (-2.0 * cc / hh**2)
    np.maximum(mirror, -600.0, out=mirror)
    np.exp(mirror, out=mirror)
    mirror += 1.0
    g *= mirror
    rho = u * np.matmul(g, (w / (_SQ2PI * h))[:, :, None])[:, :, 0]
    rb = rho[:, 0].copy()
    rho[:, 0] *= 0.5  # trapezoidal end weight; rho vanishes at the top
    # the bottom end: rho ~ P(0) e^v there (P is even in u), so the Euler-Maclaurin correction of the trapezoidal
    # rule is (dv^2/12) g'(v_0) with g' = rho (s + 1.5 (1 - s^2)), s the sigmoid at v_0; below v_0 the sigmoid is
    # -1 to 2e^-24 (the root is >= 8 above it) against the mass there, from the CDF
    u0 = u[:, :1, None]
    below = np.sum(w[:, None, :] * (ndtr((u0 - cc) / hh) - ndtr((-u0 - cc) / hh)), axis=2)[:, 0]
    base = -atom - below
    em = dv * dv / 12.0 * rb

    def F(x):  # x relative to v_hi, shape (loads,)
        sb = np.tanh(1.5 * (off[0] - x))
        return (
            base
            + em * (sb + 1.5 * (1.0 - sb * sb))
            + dv * np.sum(rho * np.tanh(1.5 * (off[None, :] - x[:, None])), axis=1)
        )

    def dF(x):
        t = np.tanh(1.5 * (off[None, :] - x[:, None]))
        sb = t[:, 0]
        return -1.5 * dv * np.sum(rho * (1.0 - t * t), axis=1) - 1.5 * (1.0 - sb * sb) * (1.0 - 3.0 * sb) * em

    # F on every few nodes (spacing ~0.4): one matrix product brackets the root in a cell
    k = max(1, int(round(0.4 / dv)))
    xs = off[::k]
    sb = np.tanh(1.5 * (off[0] - xs))[None, :]
    Fg = base[:, None] + em[:, None] * (sb + 1.5 * (1.0 - sb * sb)) + rho @ (dv * np.tanh(1.5 * (off[:, None] - xs)))
    rows = np.arange(rho.shape[0])
    pos = Fg > 0
    m = np.clip(np.where(pos[:, 0], np.argmin(pos, axis=1) - 1, 0), 0, xs.size - 2)  # last with F > 0
    lo, hi = xs[m], xs[m + 1]
    f_lo, f_hi = Fg[rows, m], Fg[rows, m + 1]
    with np.errstate(invalid="ignore", divide="ignore"):
        x = np.where(f_lo > f_hi, lo + (hi - lo) * f_lo / (f_lo - f_hi), lo)
    active = np.ones(x.shape, dtype=bool)  # a load stops when its own |F| is round-off (others' do not move it)
    for _ in range(12):
        f = F(x)
        active &= np.abs(f) >= 1e-13
        if not active.any():
            break
        lo = np.where(active & (f > 0), x, lo)
        hi = np.where(active & (f <= 0), x, hi)
        with np.errstate(divide="ignore", invalid="ignore"):  # dF = 0 (rho underflowed): bisect instead
            x_new = x - f / dF(x)
        x_new = np.where((x_new > lo) & (x_new < hi) & np.isfinite(x_new), x_new, 0.5 * (lo + hi))
        x = np.where(active, x_new, x)
    # the trapezoidal rule's error on the mass (known: 1) measures its error on F; in x it is divided by dF/dx
    d = np.abs(dF(x))
    mass_err = np.abs(dv * np.sum(rho, axis=1) + em - base - 1.0)
    # the same rule on every other node (step 2 dv): its root differs from x by more than x's own error
    x2, r2, t2 = x.copy(), rho[:, ::2], np.tanh(1.5 * (off[0] - x))
    for _ in range(4):
        t = np.tanh(1.5 * (off[::2][None, :] - x2[:, None]))
        t2 = t[:, 0]
        f2 = base + 4.0 * em * (t2 + 1.5 * (1.0 - t2 * t2)) + 2.0 * dv * np.sum(r2 * t, axis=1)
        with np.errstate(divide="ignore", invalid="ignore"):  # a coarse rule with no slope: its shift is inf
            x2 = x2 + f2 / (3.0 * dv * np.sum(r2 * (1.0 - t * t), axis=1))
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        return np.exp(v_hi + x), np.minimum(mass_err / d, np.inf), np.abs(np.expm1(x2 - x)), x


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

    Raises
    ------
    ValueError
        A value out of range, or a Q that overflows or, for an open gap, underflows the floating-point range
        (it would read as a sealed seal).
    """
    eta = as_positive_scalar(viscosity, "viscosity")
    dp = as_positive_scalar(pressure_drop, "pressure_drop")
    aspect = as_positive_scalar(aspect, "aspect")
    u = as_float_array(gap, "gap")
    if np.any(u < 0):
        raise ValueError("gap must be >= 0 (length)")
    with np.errstate(over="ignore", under="ignore"):
        Q = aspect * u**3 * dp / (12.0 * eta)
    bad = ~np.isfinite(Q) | ((u > 0) & (Q < np.finfo(float).tiny))
    if np.any(bad):
        raise ValueError(
            f"the flow rate u^3 dp/(12 eta) leaves the floating-point range (gap {float(u[bad].flat[0]):.3g}, "
            f"viscosity {eta!r}, pressure_drop {dp!r}, aspect {aspect!r}): rescale the units (e.g. mm, MPa, Pa s)"
        )
    return Q


def _pair(value, name):
    try:
        v = as_float_array(value, name)
    except ValueError as e:
        if name in str(e):
            raise
        raise ValueError(f"{name} must be a pair of finite values > 0 (one per body), got {value!r}") from None
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
