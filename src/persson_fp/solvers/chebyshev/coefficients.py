r"""The Fokker--Planck coefficients per unit V for method ``"chebyshev"``: separable or V-dependent.

In the variance-like variable V (dV = V'(zeta) dzeta) the Fokker--Planck equation of the Xu et al. tutorial
(Eq. 'E:Fokker_Planck_Forward') reads :math:`\partial_V P = \tfrac12\partial_p^2(bP) - \partial_p(cP)` with

.. math::  b(p, V) = B_2(p, \zeta(V)) / V'(\zeta(V)), \qquad c(p, V) = B_1(p, \zeta(V)) / V'(\zeta(V)).

Where b and c do not depend on V (B2 = b(p) dV/dzeta, B1 = c(p) dV/dzeta: the homogenised theory, any
pressure-dependent diffusion of that form) the collocated operator is constant and one exponential propagates it
exactly; otherwise (a zeta-dependent b(p, zeta), a drift c(p, zeta)) the solver marches it with adaptive Radau IIA
steps (:mod:`persson_fp.solvers.chebyshev.radau`). The form is found in one pass of sampling b and c on 33
pressures (relative tolerance 1e-9): at 257 log-spaced magnifications in one call of each coefficient where it
broadcasts over an array of zeta (its rows checked against calls with a scalar zeta), else at 33 magnifications, one
call each; the clock form is confirmed at 129 magnifications. A third form is exact too: b
= s(V) b(p, V_max), c = s(V) c(p, V_max) (a zeta-dependent factor common to both, e.g. B2 = b(p) g(zeta) with any
g): in the clock tau = int s dV it is the separable form, and one exponential over the clock's increment
(``Coefficients.tau``) propagates it.
"""

from __future__ import annotations

import numpy as np

from persson_fp.solvers.base import zeta_of

__all__ = ["Coefficients"]


class Coefficients:
    """b(p, V), c(p, V) of a problem (module docstring), its detected form and an envelope for the domain.

    Parameters
    ----------
    problem : ContactProblem or FokkerPlanckProblem
        Its spectrum (V and its inverse), coefficients B1, B2 and hardness.

    Attributes
    ----------
    separable : bool
        True where b and c do not depend on V.
    clock : bool
        True where they depend on V through a common factor s(V) only (and are not separable).
    drift : bool
        True where c is not identically 0 on the probe grid.
    """

    def __init__(self, problem):
        pr = self.problem = problem
        z_ref = float(pr.zeta_max)
        if not float(pr.dV_dzeta(z_ref)) > 0:
            raise ValueError("method 'chebyshev' needs dV/dzeta > 0 at zeta_max")
        hi = pr.upper_wall.probe_end(1.0, lambda: pr.p_max(8.0))
        self._probe = np.linspace(0.0, hi, 33)
        self.z_ref = z_ref
        self._tau_cache: dict = {}
        # one pass (where an adaptive quadrature of B2, ~250 calls, confirmed the separable form before): 33
        # pressures at 257 magnifications in one call of each coefficient where it broadcasts over zeta as well (its
        # rows at the envelope's 9 magnifications checked against calls with a scalar zeta), else at 33
        # magnifications, one call each -- dense enough in ln zeta that a zeta-dependence between the envelope's
        # magnifications (a bump) is seen, and with 257 a bad value in a band of 2 % of zeta (ln(zeta_max) / 256)
        self._classify(33)
        if self.clock:
            self._classify(129)  # the clock form confirmed on a dense set (its clock is a quadrature of B2 itself)
        self._check_wall()

    def _check_wall(self):
        """Refuse a diffusion that vanishes at the wall p = 0 like p^a with a >= 0.9: there b P -> 0 does not make
        P vanish (for b = kappa p the density at the wall is finite: the squared Bessel process of dimension 0),
        while the collocated wall sets P(0) = 0 -- the degree would grow without bound.  Smaller exponents
        (P ~ p^(1 - a) at the wall) are solved, their slower convergence measured by the estimate."""
        pb = float(np.min(self.problem.p_bar))
        b = self.envelope(pb * np.array([0.0, 1e-7, 2e-7, 1.0]))[0]
        if not (b[3] > 0 and b[0] <= 1e-12 * b[3]):  # (B2 = 0 at the load: refused by the domain, naming it)
            return
        a = float(np.log2(b[2] / b[1])) if b[1] > 0 and b[2] > 0 else np.inf
        if a >= 0.9 - 1e-9:  # (p^0.9 itself measures 0.9 to round-off, at times just below it)
            how = f"like p^{a:.2g} there" if np.isfinite(a) else "and next to it"
            raise ValueError(
                f"method 'chebyshev': B2 vanishes at the wall p = 0 ({how}), so the contact-pressure "
                "density need not vanish at the wall as the spectral method's absorbing wall P(0) = 0 assumes (for "
                "B2 proportional to p it is finite there); use method='fv' or 'mol', whose wall flux holds for it"
            )

    def _classify(self, n_z: int):
        """Sample b, c at 33 pressures and ``n_z`` magnifications (and the spectrum's roll-off); set ``drift``,
        ``separable``, ``clock``.  Each magnification is one call of B1 and B2 (vectorised in p); the values are
        checked together, the checked ``problem.coefficients`` naming a bad one and where."""
        pr, probe, z_ref = self.problem, self._probe, self.z_ref
        zs = np.geomspace(1.0 + 1e-9, z_ref, n_z)
        if n_z == 33:  # the envelope's magnifications (the domain's): every 4th
            self._probe_z = zs[::4][pr.V_kernels.dV_dzeta(zs[::4]) > 0]
        dense = None
        if n_z == 33:
            zd = np.geomspace(1.0 + 1e-9, z_ref, 257)
            dense = self._sample_broadcast(probe, zd)
            if dense is not None:
                zs = zd
        zr = getattr(pr.psd, "zeta_r", None)
        if dense is None and zr is not None and 1.0 < zr < z_ref:
            zs = np.sort(np.append(zs, zr))
        g = np.asarray(pr.V_kernels.dV_dzeta(zs), dtype=float)
        keep = g > 0
        zs, g = zs[keep], g[keep]
        B1s, B2s = self._sample(probe, zs) if dense is None else (None if v is None else v[keep] for v in dense)
        bs = B2s / g[:, None]
        cs = np.zeros_like(bs) if B1s is None else B1s / g[:, None]
        scale_b = max(float(np.max(np.abs(bs))), 1e-300)
        scale_c = max(float(np.max(np.abs(cs))), scale_b / max(probe[-1], 1e-300), 1e-300)
        self.drift = bool(np.any(cs != 0.0))
        self.separable = bool(
            np.max(np.abs(bs - bs[-1])) <= 1e-9 * scale_b and np.max(np.abs(cs - cs[-1])) <= 1e-9 * scale_c
        )
        # a clock: b = s(V) b(p, V_max), c = s(V) c(p, V_max) -- the separable form in tau = int s dV
        j = int(np.argmax(np.abs(bs[-1])))
        s = bs[:, j] / bs[-1, j] if bs[-1, j] != 0 else np.ones(len(zs))
        self.clock = (not self.separable) and bool(
            np.all(s > 0)
            and np.max(np.abs(bs - s[:, None] * bs[-1])) <= 1e-9 * scale_b
            and np.max(np.abs(cs - s[:, None] * cs[-1])) <= 1e-9 * scale_c
        )
        self._p_star = float(probe[j])

    def _callables(self):
        """(B1, B2) as the user gave them (None: the default, 0 and dV/dzeta; a ContactProblem has neither)."""
        return getattr(self.problem, "B1_fun", None), getattr(self.problem, "B2_fun", None)

    def _sample_broadcast(self, p, zs):
        """(B1 or None, B2), each (len(zs), p.size), from one call of each coefficient with p (1, m) and zeta
        (len(zs), 1) -- None where a coefficient does not broadcast so (raises, another shape, other values than
        its calls with a scalar zeta at 9 of the magnifications, which are the checked ``problem.coefficients``
        and name a bad value).  A bad value (non-finite; B2 < 0) is named by the checked call at its zeta."""
        pr = self.problem
        out = []
        for k, f in enumerate(self._callables()):
            if f is None:
                out.append(None if k == 0 else np.asarray(pr.V_kernels.dV_dzeta(zs), float)[:, None] * np.ones(p.size))
                continue
            try:
                with np.errstate(all="ignore"):
                    v = np.asarray(f(p[None, :], zs[:, None]))
            except Exception:
                return None
            if v.dtype.kind not in "fiu" or v.shape != (zs.size, p.size):
                return None
            v = v.astype(float)
            step = (zs.size - 1) // 8
            ref = np.array([pr.coefficients(p, float(z))[k] for z in zs[::step]])  # (raises, naming a bad value)
            with np.errstate(invalid="ignore"):
                if not np.all(np.abs(v[::step] - ref) <= 1e-12 * np.abs(ref)):
                    return None
            bad = ~np.isfinite(v) if k == 0 else ~(v >= 0) | ~np.isfinite(v)
            if np.any(bad):
                pr.coefficients(p, float(zs[int(np.argmax(np.any(bad, axis=1)))]))  # (raises, naming where)
                return None  # (a scalar call does not give the bad value: sample one magnification at a time)
            out.append(v)
        return out[0], out[1]

    def _sample(self, p, zs):
        """(B1 or None, B2), each (len(zs), p.size): the user's callables called directly where they return
        float64 arrays of p's shape, checked all at once (finite; B2 >= 0); the checked ``problem.coefficients``
        for a magnification where not (it broadcasts a scalar or a list, or raises naming the bad value)."""
        pr = self.problem
        out = []
        for name, f in zip(("B1", "B2"), self._callables()):
            if f is None:
                out.append(
                    None if name == "B1" else np.asarray(pr.V_kernels.dV_dzeta(zs), float)[:, None] * np.ones(p.size)
                )
                continue
            rows = []
            for z in zs:
                try:
                    v = f(p, float(z))
                except Exception:
                    v = None
                if not (type(v) is np.ndarray and v.dtype == np.float64 and v.shape == p.shape):
                    v = pr.coefficients(p, float(z))[0 if name == "B1" else 1]  # (broadcasts, or raises)
                rows.append(v)
            vals = np.array(rows)
            bad = ~np.isfinite(vals) if name == "B1" else ~(vals >= 0) | ~np.isfinite(vals)
            if np.any(bad):
                pr.coefficients(p, float(zs[int(np.argmax(np.any(bad, axis=1)))]))  # (raises, naming where)
            out.append(vals)
        return out[0], out[1]

    def _per_V(self, p, z):
        """(c or None, b) per unit V at pressures ``p`` and magnification ``z``."""
        pr = self.problem
        g = float(pr.V_kernels.dV_dzeta(z))  # (z from the spectrum's inverse: in range)
        if pr.general:
            B1, B2 = pr.coefficients(p, z)
            return (B1 / g if self.problem.B1_fun is not None else None), B2 / g
        return None, np.ones(np.shape(p))

    def tau(self, V_a: float, V_b: float) -> float:
        """The clock int_{V_a}^{V_b} s dV (pressure^2) of the clock form, s = b(p, V) / b(p, V_max).

        tau(0, V_b) - tau(0, V_a), each by adaptive Gauss--Kronrod quadrature in zeta (``scipy.integrate.quad``,
        relative 1e-13; cached per V) of B2(p*, zeta) / b(p*, V_max) at the pressure p* of the largest b, split at
        the spectrum's roll-off (a kink of dV/dzeta that quad alone misjudges: 6e-9 relative measured)."""
        return self._tau0(V_b) - self._tau0(V_a)

    def _tau0(self, V: float) -> float:
        from scipy.integrate import quad

        V = float(V)
        if V <= 0.0:
            return 0.0
        if V not in self._tau_cache:
            pr = self.problem
            p_star = np.array([self._p_star])
            b_ref = float(self._per_V(p_star, self.z_ref)[1][0])
            zb = self.zeta_of(V)
            zr = getattr(pr.psd, "zeta_r", None)
            pts = [zr] if zr is not None and 1.0 < zr < zb else None
            b2 = self._b2_at(p_star)
            self._tau_cache[V] = float(
                quad(
                    lambda z: b2(z) / b_ref,
                    1.0,
                    zb,
                    epsabs=0.0,
                    epsrel=1e-13,
                    limit=500,
                    points=pts,
                )[0]
            )
        return self._tau_cache[V]

    def _b2_at(self, p_star: np.ndarray):
        """B2(p*, zeta) as a float function of zeta for the quadratures: the user's callable called directly where
        it returns a finite, non-negative float array of the shape of ``p*`` (~5 us, a quadrature makes ~250 calls),
        the checked ``problem.coefficients`` otherwise (which names a bad value and where, or broadcasts)."""
        pr = self.problem
        f = pr.B2_fun
        if f is None:
            return lambda z: float(pr.V_kernels.dV_dzeta(z))  # (quadrature nodes inside [1, zeta_max])

        def b2(z):
            try:
                v = f(p_star, z)
            except Exception:
                v = None
            if type(v) is np.ndarray and v.dtype == np.float64 and v.shape == p_star.shape:
                x = float(v[0])
                if 0.0 <= x < np.inf:
                    return x
            return float(pr.coefficients(p_star, z)[1][0])  # (raises naming B2 and where, or broadcasts)

        return b2

    def zeta_of(self, V: float) -> float:
        """The magnification where the variance is V."""
        return float(zeta_of(self.problem, V)[0])

    def at(self, p, V=None):
        """(b, c or None) per unit V at pressures ``p`` (any shape) and variance ``V`` (ignored if separable).

        Raises
        ------
        ValueError
            dV/dzeta vanishes at zeta(V) (V is no clock there: use method 'fv' or 'mol').
        """
        z = self.z_ref if (self.separable or V is None) else self.zeta_of(V)
        pr = self.problem
        if not float(pr.V_kernels.dV_dzeta(z)) > 0:  # (z: zeta_max or the clipped inverse)
            raise ValueError(
                f"method 'chebyshev' marches in V and needs dV/dzeta > 0, which vanishes at zeta = {z:.6g}; "
                "use method='fv' or 'mol'"
            )
        c, b = self._per_V(p, z)
        return b, (c if self.drift else None)

    def at_many(self, p, Vs):
        """[(b, c or None)] per unit V at pressures ``p`` for each variance of ``Vs`` (one inversion zeta(V) for
        all of them; :meth:`at` for one)."""
        if self.separable:
            return [self.at(p)] * len(Vs)
        pr, out = self.problem, []
        zs = np.asarray(zeta_of(pr, Vs), dtype=float)
        gs = np.asarray(pr.V_kernels.dV_dzeta(zs), dtype=float)  # (one evaluation for all of them)
        if not np.all(gs > 0):
            return [self.at(p, float(V)) for V in Vs]  # (raises naming zeta)
        for z, g in zip(zs.tolist(), gs.tolist()):
            c, b = self._fast_per_V(p, z, g)
            out.append((b, c if self.drift else None))
        return out

    def _fast_per_V(self, p, z, g=None):
        """:meth:`_per_V` for the march's inner loop: the user's callables called directly where both return finite
        float arrays of the shape of ``p`` (B2 >= 0), the checked ``problem.coefficients`` otherwise (which names a
        bad value and where); ``g``: dV/dzeta at z where the caller has it."""
        pr = self.problem
        f1, f2 = getattr(pr, "B1_fun", None), getattr(pr, "B2_fun", None)
        if f2 is None:  # (no callable B2: the homogenised problem, or B2 = dV/dzeta)
            return self._per_V(p, z)
        try:
            B2 = f2(p, z)
            B1 = None if f1 is None else f1(p, z)
        except Exception:
            return self._per_V(p, z)
        for v in (B2,) if B1 is None else (B2, B1):
            if not (type(v) is np.ndarray and v.dtype == np.float64 and v.shape == p.shape):
                return self._per_V(p, z)
        if not (np.isfinite(B2.sum()) and B2.min() >= 0.0 and (B1 is None or np.isfinite(B1.sum()))):
            return self._per_V(p, z)
        g = float(pr.V_kernels.dV_dzeta(z)) if g is None else g
        return (None if B1 is None else B1 / g), B2 / g

    def envelope(self, p):
        """(b_max, c_max): the largest b and outward drift c / sqrt(b) over the probe magnifications, at ``p``."""
        if self.separable:
            b, c = self.at(p)
            return b, (np.zeros_like(b) if c is None else c)
        out_b, out_c = None, None
        for z in self._probe_z:
            c, b = self._per_V(p, z)
            c = np.zeros_like(b) if c is None else c
            out_b = b if out_b is None else np.maximum(out_b, b)
            out_c = c if out_c is None else np.maximum(out_c, c)
        return out_b, out_c
