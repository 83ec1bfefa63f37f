r"""The distribution of interfacial gaps (Almqvist, Campañá, Prodanov, Persson, J. Mech. Phys. Solids 59 (2011)
2355), on the magnification-resolved contact of :mod:`persson_fp.theory.resolved`.

**Gap distribution** (Almqvist et al. 2011):

.. math::  P(u) = A(\zeta_{max})\,\delta(u) + \int_1^{\zeta_{max}} (-A'(\zeta))
           \big[G(u - u_1; h_\zeta) + G(u + u_1; h_\zeta)\big]\,d\zeta, \quad u \ge 0,

G the normal density of variance :math:`h_\zeta^2 = 2\pi\int_{\zeta q_l}^{q_s} qC\,dq` (the height variance of the
roughness finer than :math:`\zeta`).  Each bracket is a folded normal of mass 1, so P is normalised by construction.
Discretely: stations :math:`\zeta_k` (uniform in A, plus log-uniform in :math:`\zeta`), bin weights
:math:`w_k = A_k - A_{k+1}` and centres :math:`c_k = (A_k\bar u_k - A_{k+1}\bar u_{k+1})/w_k`; then
:math:`\sum w_k = 1 - A(\zeta_{max})` and :math:`\sum w_k c_k = \bar u(\bar p)` exactly.

Two properties the user must know:

- :math:`u_1(\zeta) \to \infty` as :math:`\zeta \to 1` (:math:`A' \to 0` exponentially, :math:`\bar u'` only
  algebraically): the first fraction ``weight_cut`` (default 1e-4) of the non-contact area is given the gap of
  the first resolved bin instead.  ``truncated_weight`` is that mass and ``truncation_shift`` the amount by which the
  untruncated mean would be larger; without the cut the standard deviation is dominated by tiny weights at absurd
  gaps (hundreds of rms heights).
- The mirror term :math:`G(u + u_1)` makes the mean of P exceed :math:`\bar u(\bar p)` (the folded normal's mean is
  larger than its centre): a fraction of a percent at light loads, tens of percent near
  :math:`\bar p/(E^*\bar g) \approx 0.1` and more beyond, where :math:`\bar u(\bar p)` is the better mean gap.  Both
  are reported (:attr:`persson_fp.GapDistribution.mean`, :attr:`persson_fp.GapDistribution.mean_separation`).

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from scipy.special import ndtr

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp.theory.resolved import MagnificationResolved

__all__ = ["MagnificationResolved", "GapDistribution"]

_SQ2PI = np.sqrt(2.0 * np.pi)


MAX_SAMPLES = 10**8
"""Most samples :meth:`GapDistribution.sample` draws in one call (over all loads; 0.8 GB)."""

MAX_P_BAR = 1e150
"""Largest load of :class:`GapDistribution` (pressure): its square stays a finite float."""
MAX_STATIONS = 10**6
"""Largest ``n_area`` or ``n_zeta`` of a :class:`GapDistribution`."""

MEMORY_BUDGET = 4 * 2**30
"""Bytes a :class:`GapDistribution` may take while it is built: 4 GiB, the solvers' default budget
(``persson_fp.solvers.base.MEMORY_BUDGET``; this module imports no solver, a test keeps the two equal)."""

_BYTES_PER_STATION = 48 * 8
"""Peak bytes per (load, station) while the distribution is built (tracemalloc: 18-44 float64 per station)."""


def memory_estimate(n_loads: int, n_area: int, n_zeta: int) -> int:
    """Peak memory (bytes) of building a :class:`GapDistribution`: 48 float64 per load and station, plus 1 MiB.

    Parameters
    ----------
    n_loads, n_area, n_zeta : int
        Loads, stations uniform in A and stations log-uniform in ζ.

    Returns
    -------
    int
        Bytes.
    """
    return int(_BYTES_PER_STATION * n_loads * (n_area + n_zeta) + 2**20)


def _check_rng(rng):
    """``rng``: None, an integer >= 0 or a numpy Generator (else ValueError naming ``rng``)."""
    if rng is None or isinstance(rng, np.random.Generator):
        return rng
    if isinstance(rng, (int, np.integer)) and not isinstance(rng, bool) and rng >= 0:
        return rng
    raise ValueError(f"rng must be None, an integer >= 0 or a numpy.random.Generator, got {rng!r}")


class GapDistribution:
    r"""Distribution of the interfacial gap :math:`P(u)` at each load (Almqvist et al., JMPS 59 (2011) 2355).

    An atom ``contact_fraction`` :math:`= A(\zeta_{max})` at u = 0 plus a mixture of folded normals (module
    docstring of :mod:`persson_fp.theory.gaps`).  Arrays of per-load results have shape ``(n_loads,)``.

    Parameters
    ----------
    resolved : MagnificationResolved
        Spectrum, modulus and model.
    p_bar : array_like, pressure
        Loads (> 0), 1-D.
    n_area : int
        Stations uniform in A, in [8, 1e6].
    n_zeta : int
        Extra stations log-uniform in ζ, in [8, 1e6]: they resolve :math:`h_\zeta` near :math:`\zeta_{max}`.
        Together with the loads they must fit the module's ``MEMORY_BUDGET`` (4 GiB; its ``memory_estimate``:
        about 384 bytes a load and station), else ``ValueError`` with the estimate.
    weight_cut : float
        Fraction of the non-contact area, lost first (ζ near 1), whose gap is not resolved (module docstring);
        in [1e-12, 0.01].
    zeta, area : array_like, optional
        A numerical solution's stations (n_zeta,), increasing to zeta_max (A = 1 at zeta = 1 is added if absent),
        and areas (n_zeta, n_loads) to use instead of the model's closed form (``weight_cut`` then acts on the
        given stations only: the first bins that hold the cut mass are merged).

    Notes
    -----
    After construction (arrays of shape ``(n_loads, n_bins)``): ``weights`` (mass, dimensionless), ``centres``
    (:math:`u_1`, length) and ``widths`` (:math:`h_\zeta`, length) of the folded normals, ``zeta_bins`` (geometric
    mid-magnification of each bin).  Per load (floats for a scalar load): ``contact_fraction`` (the atom at u = 0),
    ``mean_separation`` (:math:`\bar u(\bar p) = \bar u(\zeta = 1)`), ``mean``, ``std``; as arrays
    ``truncated_weight`` (mass whose gap was replaced by the first resolved bin's, ζ near 1) and
    ``truncation_shift`` (length: how much larger the mean would be without that replacement).
    """

    def __init__(self, resolved, p_bar, n_area=64, n_zeta=48, weight_cut=1e-4, zeta=None, area=None):
        self.resolved = r = resolved
        self.scalar = np.ndim(p_bar) == 0
        p = as_float_array(p_bar, "p_bar").reshape(-1)
        if p.size == 0 or not np.all(p > 0):
            raise ValueError("p_bar must hold at least one load, all > 0 (pressure)")
        if np.any(p > MAX_P_BAR):
            raise ValueError(
                f"p_bar must lie in (0, {MAX_P_BAR:.0e}] (p_bar^2 stays a float), got {float(p.max())!r}; rescale"
            )
        for name, n in (("n_area", n_area), ("n_zeta", n_zeta)):
            if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 8 <= n <= MAX_STATIONS:
                raise ValueError(f"{name} must be an integer in [8, {MAX_STATIONS:.0e}], got {n!r}")
        if area is None:
            need = memory_estimate(p.size, int(n_area), int(n_zeta))
            if need > MEMORY_BUDGET:
                big = "n_area" if n_area >= n_zeta else "n_zeta"
                raise ValueError(
                    f"{big} = {max(n_area, n_zeta)} (n_area, n_zeta each in [8, {MAX_STATIONS:.0e}]) with "
                    f"{p.size} loads would take about {need / 2**30:.3g} GiB, over the budget of "
                    f"{MEMORY_BUDGET / 2**30:.3g} GiB; use fewer stations or loads"
                )
        weight_cut = as_positive_scalar(weight_cut, "weight_cut")
        if not 1e-12 <= weight_cut <= 0.01:
            raise ValueError(f"weight_cut must lie in [1e-12, 0.01], got {weight_cut!r}")
        self.p_bar = p
        zmax = r.psd.zeta_max
        if area is None:
            A_end = r.area(p, zmax)
            A_top = 1.0 - weight_cut * (1.0 - A_end)
            frac = np.linspace(0.0, 1.0, n_area)[None, :]
            A_st = A_top[:, None] - (A_top - A_end)[:, None] * frac
            z_A = r.zeta_of_area(p[:, None], A_st[:, :-1])
            z_log = np.broadcast_to(np.geomspace(1.0, zmax, n_zeta)[1:-1], (p.size, n_zeta - 2))
            z = np.sort(np.concatenate((np.ones((p.size, 1)), z_A, z_log, np.full((p.size, 1), zmax)), axis=1))
            A = r.area(p[:, None], z)
            A[:, 0] = 1.0
            cut_at = np.argmax(z_A[:, :1] <= z, axis=1)  # station of A_top: the end of the lump
        else:
            z1 = r.psd.check_zeta(as_float_array(zeta, "zeta")).reshape(-1)
            A = np.asarray(as_float_array(area, "area"), dtype=float).reshape(z1.size, -1).T
            if A.shape != (p.size, z1.size) or np.size(area) != A.size:
                raise ValueError(f"area must have shape (n_zeta, n_loads) = {(z1.size, p.size)}, got {np.shape(area)}")
            if np.any(np.diff(z1) <= 0) or z1[-1] != zmax:
                raise ValueError("zeta must increase strictly and end at zeta_max")
            if z1[0] > 1.0:  # a solver's stations start after zeta = 1, where A = 1
                z1 = np.concatenate(([1.0], z1))
                A = np.concatenate((np.ones((p.size, 1)), A), axis=1)
            z = np.broadcast_to(z1, (p.size, z1.size))
            A = np.minimum.accumulate(np.clip(A, 0.0, 1.0), axis=1)  # contact is only lost (eq:Area)
            A[:, 0] = 1.0
            A_end = A[:, -1]
            lost = 1.0 - A
            cut_at = np.argmax(lost > weight_cut * (1.0 - A_end)[:, None], axis=1)
        u = r.separation(p[:, None], z, A)
        u[:, -1] = 0.0
        Au = A * u
        w = np.maximum(A[:, :-1] - A[:, 1:], 0.0)
        with np.errstate(invalid="ignore", divide="ignore"):
            c = np.where(w > 0, (Au[:, :-1] - Au[:, 1:]) / np.where(w > 0, w, 1.0), 0.0)
        zm = np.sqrt(z[:, :-1] * z[:, 1:])
        hb = r.h(zm)
        # the lump [1, zeta(A_top)]: one component at the gap of the first resolved bin (module docstring)
        n_b = w.shape[1]
        rows = np.arange(p.size)
        cut_at = np.clip(cut_at, 1, n_b - 1)
        in_lump = np.arange(n_b)[None, :] < cut_at[:, None]
        W0 = np.sum(np.where(in_lump, w, 0.0), axis=1)
        raw = Au[:, 0] - Au[rows, cut_at]  # = its share of the mean separation (telescoped; w = 0 bins included)
        # the first resolved bin is the first one from cut_at on that holds mass: a bin of zero width (two stations
        # at the same zeta or area, e.g. zeta(A_top) rounding onto a log station at tiny loads) has no centre (its
        # c is a placeholder 0), and the lump -- the widest gaps -- would be put at u = 0
        idx = np.arange(n_b)[None, :]
        first = np.min(np.where((w > 0) & (idx >= cut_at[:, None]), idx, n_b - 1), axis=1)
        c_first = c[rows, first]
        self.truncated_weight = W0
        self.truncation_shift = raw - W0 * c_first
        c = np.where(in_lump, c_first[:, None], c)
        hb = np.where(in_lump, hb[rows, first][:, None], hb)
        # the lump is one component: its mass on the first bin, the others emptied (fewer terms downstream)
        w = np.where(in_lump, 0.0, w)
        w[:, 0] = W0
        c[:, 0], hb[:, 0] = c_first, hb[rows, first]
        keep = w > 0
        self.weights = np.where(keep, w, 0.0)
        self.centres = np.where(keep, np.maximum(c, 0.0), 0.0)
        self.widths = np.where(keep, np.maximum(hb, 1e-300), 1.0)
        self.zeta_bins = zm
        self.atom = A_end.copy()
        self.separation = u[:, 0].copy()

    def __repr__(self):
        rows = [
            f"  p_bar={p:.4g}: contact {a:.4g}, mean gap {m:.4g} vs u_bar {u:.4g} ({m / u - 1:+.1%}: mirror term "
            f"and cut), std {sd:.4g}; truncated mass {tw:.1e} (mean +{ts:.2g} without the cut)"
            for p, a, m, u, sd, tw, ts in zip(
                self.p_bar,
                self.atom,
                self._mean(),
                self.separation,
                np.atleast_1d(self.std) if not self.scalar else [self.std],
                self.truncated_weight,
                self.truncation_shift,
            )
            if u > 0
        ] + [f"  p_bar={p:.4g}: complete contact (no gap)" for p, u in zip(self.p_bar, self.separation) if u <= 0]
        more = "" if len(rows) <= 5 else f"\n  ... {len(rows) - 5} more loads"
        return "GapDistribution (Almqvist et al. 2011)\n" + "\n".join(rows[:5]) + more

    @property
    def n_loads(self) -> int:
        """Number of loads."""
        return self.p_bar.size

    def _out(self, x):
        """Per-load results: the single entry for a scalar load."""
        return x[0] if self.scalar else x

    @property
    def contact_fraction(self):
        """The atom at u = 0, :math:`A(\\zeta_{max})` (dimensionless, per load)."""
        return self._out(self.atom)

    @property
    def mean_separation(self):
        r""":math:`\bar u(\bar p) = \bar u(\zeta = 1)`, the theory's mean separation (length, per load)."""
        return self._out(self.separation)

    @property
    def normalisation(self):
        """Total mass, atom included (1 to round-off: it telescopes)."""
        return self._out(self.atom + np.sum(self.weights, axis=1))

    def _u(self, u):
        u = as_float_array(u, "u")
        if not np.all(np.isfinite(u)):
            raise ValueError("u must be finite (gap, length)")
        return u

    def pdf(self, u) -> np.ndarray:
        r"""Density of the continuous part of P(u) (the atom at u = 0 is :attr:`contact_fraction`, not included).

        Parameters
        ----------
        u : array_like, length
            Gaps; the density is 0 for u < 0.

        Returns
        -------
        ndarray, 1/length
            Shape ``(n_loads,) + u.shape``.
        """
        u = self._u(u)
        uu = np.abs(u).reshape(-1)[None, :, None]
        c, h, w = (a[:, None, :] for a in (self.centres, self.widths, self.weights))
        with np.errstate(over="ignore"):  # far gaps: the exponent overflows to -inf, the density to 0 (exact)
            g = (np.exp(-0.5 * ((uu - c) / h) ** 2) + np.exp(-0.5 * ((uu + c) / h) ** 2)) / (_SQ2PI * h)
        out = np.sum(w * g, axis=2)
        return self._out(np.where(u.reshape(-1)[None, :] >= 0, out, 0.0).reshape((self.n_loads,) + u.shape))

    def cdf(self, u) -> np.ndarray:
        r"""Cumulative distribution :math:`\Pr(\text{gap} \le u)`, the atom at u = 0 included.

        Parameters
        ----------
        u : array_like, length
            Gaps.

        Returns
        -------
        ndarray, dimensionless
            Shape ``(n_loads,) + u.shape``; 0 for u < 0, the contact fraction at u = 0, → 1 as u → ∞.
        """
        u = self._u(u)
        uu = np.maximum(u.reshape(-1), 0.0)[None, :, None]
        c, h, w = (a[:, None, :] for a in (self.centres, self.widths, self.weights))
        with np.errstate(over="ignore"):
            out = self.atom[:, None] + np.sum(w * (ndtr((uu - c) / h) - ndtr((-uu - c) / h)), axis=2)
        return self._out(np.where(u.reshape(-1)[None, :] >= 0, out, 0.0).reshape((self.n_loads,) + u.shape))

    def _mean(self):
        c, h = self.centres, self.widths
        m = h * np.sqrt(2.0 / np.pi) * np.exp(-0.5 * (c / h) ** 2) + c * (1.0 - 2.0 * ndtr(-c / h))
        return np.sum(self.weights * m, axis=1)

    @property
    def mean(self) -> np.ndarray:
        r"""Mean gap over the whole nominal area (contact included), length.

        The folded normals' means :math:`h\sqrt{2/\pi}e^{-c^2/2h^2} + c(1 - 2\Phi(-c/h))`; compare
        :attr:`mean_separation`.
        """
        return self._out(self._mean())

    @property
    def second_moment(self) -> np.ndarray:
        r""":math:`\langle u^2\rangle = \sum w(c^2 + h^2)` (length²)."""
        return self._out(np.sum(self.weights * (self.centres**2 + self.widths**2), axis=1))

    @property
    def std(self) -> np.ndarray:
        """Standard deviation of the gap over the whole nominal area (length)."""
        m2 = np.sum(self.weights * (self.centres**2 + self.widths**2), axis=1)
        return self._out(np.sqrt(np.maximum(m2 - self._mean() ** 2, 0.0)))

    def u1(self, zeta) -> np.ndarray:
        r"""The bins' :math:`u_1` interpolated (linearly in ln ζ) at ``zeta``; shape ``(n_loads,) + zeta.shape``.

        Parameters
        ----------
        zeta : array_like, dimensionless
            Magnifications in [1, zeta_max].

        Returns
        -------
        ndarray, length
        """
        z = self.resolved.psd.check_zeta(as_float_array(zeta, "zeta"))
        out = [
            np.interp(np.log(z), np.log(zb[wb > 0]), cb[wb > 0]) if np.any(wb > 0) else np.zeros(z.shape)
            for zb, cb, wb in zip(self.zeta_bins, self.centres, self.weights)
        ]
        return self._out(np.array(out).reshape((self.n_loads,) + z.shape))

    def sample(self, n: int, rng=None) -> np.ndarray:
        """Draw gaps from P(u) (exact: a component by its weight, then the absolute value of its normal).

        Parameters
        ----------
        n : int
            Samples per load (>= 1).
        rng : None, int or numpy.random.Generator, optional
            Random source, or the integer (>= 0) that starts a new one; None: fresh entropy.

        Raises
        ------
        ValueError
            ``n`` not an integer in [1, 1e8] (over all loads), or ``rng`` none of the above.

        Returns
        -------
        ndarray, length
            Shape ``(n_loads, n)``; exactly 0 with probability :attr:`contact_fraction`.
        """
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or not 1 <= n <= MAX_SAMPLES:
            raise ValueError(f"n must be an integer in [1, {MAX_SAMPLES:.0e}] (samples per load), got {n!r}")
        if n * self.n_loads > MAX_SAMPLES:
            raise ValueError(
                f"n x loads = {n * self.n_loads:.3g} samples exceed {MAX_SAMPLES:.0e} (8 bytes each); draw in batches"
            )
        rng = np.random.default_rng(_check_rng(rng))
        out = np.zeros((self.n_loads, n))
        for j in range(self.n_loads):
            probs = np.concatenate(([self.atom[j]], self.weights[j]))
            k = rng.choice(probs.size, size=n, p=probs / probs.sum())
            cont = k > 0
            kk = k[cont] - 1
            out[j, cont] = np.abs(self.centres[j, kk] + self.widths[j, kk] * rng.standard_normal(kk.size))
        return self._out(out)
