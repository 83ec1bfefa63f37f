r"""Sliding on a viscoelastic solid: the angular integrals of the modulus, the wavenumber quadrature, the response.

Persson's theory of rubber friction (Persson, J. Chem. Phys. 115 (2001) 3840; J. Phys.: Condens. Matter 18 (2006)
7789): a rigid rough surface with spectrum :math:`C(q)` slides at speed :math:`v` over a rubber of complex modulus
:math:`E(\omega)` (:mod:`persson_fp.theory.viscoelastic`) and Poisson ratio :math:`\nu`.  A roughness component of
wavevector :math:`\mathbf q` at angle :math:`\phi` to the sliding direction excites the frequency
:math:`\omega = q v \cos\phi`, so the rubber answers with :math:`E(q v\cos\phi)` and the complete-contact pressure
variance becomes

.. math::  V(\zeta; v) = \frac14 \int_{q_0}^{\zeta q_0} dq\, q^3 C(q)
           \int_0^{2\pi} d\phi\, \left|\frac{E(q v \cos\phi)}{1-\nu^2}\right|^2

(Xu, Li, Chen, Zhou tutorial ``eq:Vp_closed_form`` with :math:`E_{eff} = E(qv\cos\phi)/(1-\nu^2)`; for an elastic
solid it is the half-space's :math:`V = \frac{\pi}{2}E^{*2}\int q^3 C\,dq`).  The angular integrals depend on
:math:`q`, :math:`v` and the temperature only through :math:`\omega_0 = q v a_T`:

.. math::  \Phi(\omega_0) = \int_0^{2\pi}|E(\omega_0\cos\phi)|^2 d\phi = 4\int_0^{\pi/2}|E(\omega_0\cos\phi)|^2 d\phi,
           \qquad \Psi(\omega_0) = \int_0^{2\pi}\cos\phi\,\mathrm{Im}\,E(\omega_0\cos\phi)\,d\phi
           = 4\int_0^{\pi/2}\cos\phi\,E''(\omega_0\cos\phi)\,d\phi

(:math:`|E(-\omega)| = |E(\omega)|` and :math:`E''` is odd in :math:`\omega`).  :class:`AngularIntegrals` computes
them once per material on a grid in :math:`\ln\omega_0` and interpolates.  Near :math:`\phi = \pi/2` the frequency
:math:`\omega_0\cos\phi` sweeps down through every relaxation frequency of the rubber, a sharp feature in
:math:`\phi` at high speed; the rule here resolves it by integrating that part in :math:`s = -\ln\cos\phi`, where
the feature has its natural width (a decade of frequency), with Gauss–Legendre panels.

:class:`SlidingViscoelastic` is the response (:class:`persson_fp.theory.response.ElasticResponse`) of a rubber at
one speed and temperature: it gives :math:`V(\zeta; v)` and :math:`dV/d\zeta`, so the diffusion equation and every
solver give the sliding contact area :math:`A^*(\zeta; v) = P(q)`; it stores no elastic energy (the rubber
dissipates), so the mean separation and the gaps refuse it.

This module imports numpy and scipy.special only.
"""

from __future__ import annotations

import math

import numpy as np

from persson_fp._validate import as_positive_scalar, check_in_range
from persson_fp.theory.response import ElasticResponse
from persson_fp.theory.viscoelastic import StrainSoftening, ViscoelasticMaterial, check_temperature

__all__ = [
    "AngularIntegrals",
    "angular_integrals",
    "LnQRule",
    "SlidingViscoelastic",
    "MODULI_IN_G",
    "check_material",
    "check_spectrum",
    "check_modulus_in_G",
    "check_strain_softening",
    "breakpoints",
    "local_strain",
]

MODULI_IN_G = ("reduced", "plain")
"""The modulus in the contact-area variance: ``"reduced"`` E/(1-nu^2) (Persson's papers), ``"plain"`` E."""


def check_material(material) -> ViscoelasticMaterial:
    """``material`` if it is a :class:`~persson_fp.theory.viscoelastic.ViscoelasticMaterial`, else a ValueError."""
    if not isinstance(material, ViscoelasticMaterial):
        raise ValueError(
            "material must be a viscoelastic material (pf.viscoelastic.Zener, Prony or MasterCurve), got "
            f"{type(material).__name__}"
        )
    return material


def check_spectrum(psd):
    """``psd`` if it is a spectrum (:class:`persson_fp.PSD`), else a ValueError naming ``psd``."""
    from persson_fp.surfaces.psd import PSD

    if not isinstance(psd, PSD):
        raise ValueError(f"psd must be a spectrum (pf.SelfAffinePSD, pf.TabulatedPSD, a PSD), got {type(psd).__name__}")
    return psd


def check_modulus_in_G(modulus_in_G) -> str:
    """``modulus_in_G`` if it is "reduced" or "plain", else a ValueError."""
    if not isinstance(modulus_in_G, str) or modulus_in_G not in MODULI_IN_G:
        raise ValueError(f"modulus_in_G must be one of {MODULI_IN_G}, got {modulus_in_G!r}")
    return modulus_in_G


def check_strain_softening(strain_softening) -> StrainSoftening | None:
    """``strain_softening`` if None or a :class:`~persson_fp.theory.viscoelastic.StrainSoftening`."""
    if strain_softening is None or isinstance(strain_softening, StrainSoftening):
        return strain_softening
    raise ValueError(
        f"strain_softening must be None or pf.viscoelastic.StrainSoftening(strain, f, g), got {strain_softening!r}"
    )


# -- the angular rule and integrals -----------------------------------------------------------------------------
def _gauss(n: int):
    t, w = np.polynomial.legendre.leggauss(n)
    return t, w


def phi_rule(refine: int = 1) -> tuple[np.ndarray, np.ndarray]:
    r"""Nodes :math:`x_k = \cos\phi_k` and weights of :math:`\int_0^{\pi/2} F(\cos\phi)\,d\phi \approx \sum w_k F(x_k)`.

    :math:`\phi \in [0, \pi/3]` (:math:`\cos\phi \ge 1/2`): Gauss–Legendre in :math:`\phi` (24 nodes);
    :math:`\phi \in [\pi/3, \pi/2]`: :math:`s = -\ln\cos\phi \in [\ln 2, \ln 2 + 40]` in Gauss–Legendre panels of
    width 1 (1/8 to 1/4 near :math:`\ln 2`; 8 nodes each), weight :math:`d\phi/ds = e^{-s}/\sqrt{1 - e^{-2s}}`
    (the part beyond is below
    :math:`e^{-40}` of the integrand's bound).  ``refine`` = 2 doubles every node count (the error estimate).
    """
    t, w = _gauss(24 * refine)
    phi = (t + 1.0) * (math.pi / 6.0)
    x1, w1 = np.cos(phi), w * (math.pi / 6.0)
    t, w = _gauss(8 * refine)
    bounds = math.log(2.0) + np.concatenate([[0.0, 0.125, 0.25, 0.5, 0.75], np.arange(1.0, 40.5, 1.0)])
    a, width = bounds[:-1], np.diff(bounds)
    s = (a[:, None] + 0.5 * width[:, None] * (t[None, :] + 1.0)).ravel()
    ws = (0.5 * width[:, None] * w[None, :]).ravel()
    x2 = np.exp(-s)
    w2 = ws * x2 / np.sqrt(-np.expm1(-2.0 * s))
    return np.concatenate([x1, x2]), np.concatenate([w1, w2])


def _lagrange4(u0: float, h: float, table: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Four-point Lagrange interpolation of ``table`` (rows: points u0 + i h; columns: quantities) at ``u``.

    Returns shape ``u.shape + (table.shape[1],)``; ``u`` is clipped to the grid."""
    n = table.shape[0]
    r = (np.asarray(u, dtype=float).ravel() - u0) / h
    i = np.clip(np.floor(r).astype(np.intp) - 1, 0, n - 4)
    t = np.clip(r - i, 0.0, n - 1.0 - i)  # offset from point i, in [0, 3] inside
    t1, t2, t3 = t - 1.0, t - 2.0, t - 3.0
    c0 = (-t1 * t2 * t3 / 6.0)[:, None]
    c1 = (t * t2 * t3 / 2.0)[:, None]
    c2 = (-t * t1 * t3 / 2.0)[:, None]
    c3 = (t * t1 * t2 / 6.0)[:, None]
    out = c0 * table[i] + c1 * table[i + 1] + c2 * table[i + 2] + c3 * table[i + 3]
    return out.reshape((*np.shape(u), table.shape[1]))


class AngularIntegrals:
    r"""The angular integrals of a material's modulus at the reference temperature, tabulated in :math:`\ln\omega_0`.

    :math:`\Phi'(\omega_0) = 4\int_0^{\pi/2} E'(\omega_0\cos\phi)^2 d\phi`,
    :math:`\Phi''(\omega_0) = 4\int_0^{\pi/2} E''(\omega_0\cos\phi)^2 d\phi` (so :math:`\Phi = \Phi' + \Phi''`;
    strain softening weights them by :math:`f^2` and :math:`g^2`) and
    :math:`\Psi(\omega_0) = 4\int_0^{\pi/2}\cos\phi\,E''(\omega_0\cos\phi)\,d\phi`, each with the rule of
    ``phi_rule``.

    Parameters
    ----------
    material : ViscoelasticMaterial
        The rubber.
    refine : int
        1 (default rule) or 2 (doubled nodes and table density: the error estimate).
    per_decade : int
        Table points per decade of :math:`\omega_0` (default 32; four-point Lagrange interpolation of the
        logarithm, error :math:`O(h^4)`).
    """

    def __init__(self, material: ViscoelasticMaterial, refine: int = 1, per_decade: int = 32):
        self.material = material
        self.refine = refine
        self.x, self.w = phi_rule(refine)
        self.h = math.log(10.0) / (per_decade * refine)
        self._table = None  # (u0, n, values (3, n), logs (3,) bool)

    def _modulus(self, omega):
        m = self.material
        f = getattr(m, "modulus_for_integrals", None)
        return f(omega) if f is not None else m.modulus_ref(omega)

    def direct(self, omega0) -> np.ndarray:
        """(Phi', Phi'', Psi) at ``omega0`` (rad/s, > 0) by the rule itself: shape ``(3, *omega0.shape)``, pressure^2,
        pressure^2, pressure."""
        w0 = np.asarray(omega0, dtype=float).ravel()
        out = np.empty((3, w0.size))
        chunk = max(1, 200_000 // self.x.size)
        for a in range(0, w0.size, chunk):
            E = self._modulus(w0[a : a + chunk, None] * self.x[None, :])
            out[0, a : a + chunk] = 4.0 * ((E.real**2) @ self.w)
            out[1, a : a + chunk] = 4.0 * ((E.imag**2) @ self.w)
            out[2, a : a + chunk] = 4.0 * (E.imag @ (self.w * self.x))
        return out.reshape((3, *np.shape(omega0)))

    def _ensure(self, lo: float, hi: float):
        u_lo, u_hi = math.log(lo) - 2 * self.h, math.log(hi) + 2 * self.h
        t = self._table
        if t is not None and t[0] <= u_lo and t[0] + (t[1] - 1) * self.h >= u_hi:
            return t
        if t is not None:  # grow the grid to cover both the old and the new range (points on the same lattice)
            u_lo = min(u_lo, t[0])
            u_hi = max(u_hi, t[0] + (t[1] - 1) * self.h)
        k0 = math.floor(u_lo / self.h)
        n = max(math.ceil(u_hi / self.h) - k0 + 1, 4)
        u = (k0 + np.arange(n)) * self.h
        P1, P2, Psi = self.direct(np.exp(u))
        vals = np.stack([P1 + P2, Psi, P1, P2], axis=1)  # columns: Phi, Psi, Phi', Phi''
        logs = np.all(vals > 0, axis=0)
        store = np.ascontiguousarray(np.where(logs, np.log(np.where(vals > 0, vals, 1.0)), vals))
        self._table = (k0 * self.h, n, store, logs)
        return self._table

    def _interpolate(self, omega0, columns: slice) -> np.ndarray:
        w0 = np.asarray(omega0, dtype=float)
        k = len(range(4)[columns])
        if w0.size == 0:
            return np.zeros((k, *w0.shape))
        u0, _n, store, logs = self._ensure(float(w0.min()), float(w0.max()))
        vals = _lagrange4(u0, self.h, store[:, columns], np.log(w0))
        vals = np.where(logs[columns], np.exp(vals), vals)
        return np.moveaxis(vals, -1, 0)

    def __call__(self, omega0) -> np.ndarray:
        """(Phi', Phi'', Psi) at ``omega0`` (rad/s, > 0), interpolated: shape ``(3, *omega0.shape)``."""
        Phi, Psi, P1, P2 = self._interpolate(omega0, slice(0, 4))
        return np.stack([P1, P2, Psi])

    def phi_psi(self, omega0) -> np.ndarray:
        """(Phi = Phi' + Phi'', Psi) at ``omega0`` (rad/s, > 0), interpolated: shape ``(2, *omega0.shape)``."""
        return self._interpolate(omega0, slice(0, 2))


_ANGULAR_CACHE: dict = {}
_ANGULAR_CACHE_SIZE = 16


def angular_integrals(material: ViscoelasticMaterial, refine: int = 1) -> AngularIntegrals:
    """The :class:`AngularIntegrals` of ``material`` at ``refine``, kept for later calls (the last 16 materials):
    a material's tables are built once, on its first use."""
    key = (material, refine)
    hit = _ANGULAR_CACHE.pop(key, None)
    if hit is None:
        hit = AngularIntegrals(material, refine)
        if len(_ANGULAR_CACHE) >= _ANGULAR_CACHE_SIZE:
            _ANGULAR_CACHE.pop(next(iter(_ANGULAR_CACHE)))
    _ANGULAR_CACHE[key] = hit  # most recent last
    return hit


# -- the wavenumber rule ------------------------------------------------------------------------------------------
BREAK_GAP = 1e-6
"""Kinks closer than this (relative) to an end or to each other are not panel ends: a panel that narrow carries
no weight and its nodes would coincide in floating point."""


def breakpoints(psd, q_hi: float) -> np.ndarray:
    """The spectrum's kinks inside (q_l, q_hi): the roll-off of a self-affine spectrum, the points of a table."""
    pts = []
    q_r = getattr(psd, "q_r", None)
    if q_r is not None:
        pts.append(float(q_r))
    table = getattr(psd, "q", None)
    if isinstance(table, np.ndarray) and table.ndim == 1 and table.size <= 2000:
        pts.extend(table.tolist())
    pts = np.unique(np.asarray(pts, dtype=float))
    pts = pts[(pts > psd.q_l * (1 + BREAK_GAP)) & (pts < q_hi * (1 - BREAK_GAP))]
    if pts.size > 1:  # kinks closer than BREAK_GAP to the previous one are one kink for the rule
        keep = np.concatenate([[True], np.diff(np.log(pts)) > BREAK_GAP])
        pts = pts[keep]
    return pts


GRADING_LEVELS = 14
"""Geometrically shrinking panels towards q0 in :class:`LnQRule` (doubled when refined, at the square root of
:data:`GRADING_RATIO`: the same smallest panel)."""

GRADING_RATIO = 0.25
"""Width ratio of successive graded panels towards q0: the smallest is 0.25^14 ~ 4e-9 of a regular panel."""


class LnQRule:
    r"""Gauss–Legendre panels in :math:`x = \ln q` over :math:`[q_0, q_1]`, with the running integral at every node.

    Panels end at the spectrum's kinks (:func:`breakpoints`) and are at most ``1/panels_per_decade`` decade wide,
    ``m`` nodes each; the first regular panel is split geometrically towards :math:`q_0` (``GRADING_LEVELS``
    panels shrinking by ``GRADING_RATIO``), where the contact area can fall like
    :math:`1/\sqrt{\ln(q/q_0)}`.  :meth:`cumulative` returns :math:`\int_{x_0}^{x_k} g\,dx` at every node
    :math:`x_k` (the integration matrix of the panel's interpolating polynomial, exact for degree :math:`m-1`) and
    the total.

    Parameters
    ----------
    psd : PSD
        The spectrum (its kinks).
    q1 : float, 1/length
        Upper end, in (q_l, q_s].
    refine : int
        1 or 2 (doubled panels).
    panels_per_decade, m : int
        Panel density (default 5 per decade) and Gauss nodes per panel (default 6).
    graded : bool
        Grade the panels towards q0 (default True; the variance V, whose integrand is smooth there, does without).
    """

    def __init__(self, psd, q1: float, refine: int = 1, panels_per_decade: int = 5, m: int = 6, graded: bool = True):
        x0, x1 = math.log(psd.q_l), math.log(q1)
        edges = np.concatenate([[x0], np.log(breakpoints(psd, q1)), [x1]])
        hmax = math.log(10.0) / (panels_per_decade * refine)
        panels = []
        for a, b in zip(edges[:-1], edges[1:]):
            k = max(1, math.ceil((b - a) / hmax - 1e-9))
            panels.append(a + (b - a) * np.arange(k + 1)[:-1] / k)
        # geometric grading towards q0, whatever kinks lie there: G(q) grows from 0 at q0, so P = erf(1/(2 sqrt G))
        # behaves like 1/sqrt(ln q - ln q0) where G grows fast; panels shrinking by GRADING_RATIO resolve it (hp
        # refinement).  Refined: twice the levels at the square root of the ratio (the same smallest panel).
        first = min(hmax * refine, x1 - x0)  # the regular width of the unrefined rule
        levels = GRADING_LEVELS * refine if graded else 0
        grading = x0 + first * (GRADING_RATIO ** (1.0 / refine)) ** np.arange(levels, 0, -1)
        left = np.unique(np.concatenate(panels + [grading[grading < x1]]))
        tiny = 1e-10 * max(1.0, abs(x0), abs(x1))  # never a panel below what floating point resolves
        left = left[np.concatenate([[True], np.diff(left) > tiny])]
        left = left[x1 - left > tiny]
        right = np.append(left[1:], x1)
        t, w = _gauss(m)
        half = 0.5 * (right - left)
        self.x = (left[:, None] + half[:, None] * (t[None, :] + 1.0)).ravel()
        self.weights = (half[:, None] * w[None, :]).ravel()
        self.left, self.right, self.half, self.m = left, right, half, m
        V = np.polynomial.legendre.legvander(t, m - 1)
        integ = np.empty((m, m))
        for j in range(m):
            e = np.zeros(m)
            e[j] = 1.0
            integ[:, j] = np.polynomial.legendre.legval(t, np.polynomial.legendre.legint(e, lbnd=-1.0))
        self._W = integ @ np.linalg.inv(V)  # partial integrals over [-1, t_k] of the interpolant
        self._t, self._w = t, w

    @property
    def q(self) -> np.ndarray:
        """The nodes as wavenumbers, 1/length."""
        return np.exp(self.x)

    def cumulative(self, g: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Running integrals of ``g`` (last axis: the nodes) in x: (at each node, total)."""
        n_p, m = self.left.size, self.m
        gp = g.reshape((*g.shape[:-1], n_p, m))
        part = (gp @ self._W.T) * self.half[:, None]
        totals = gp @ self._w * self.half
        start = np.cumsum(totals, axis=-1) - totals
        return (part + start[..., None]).reshape(g.shape), totals.sum(-1)

    def integral(self, g: np.ndarray) -> np.ndarray:
        """The integral of ``g`` (last axis: the nodes) over [x0, x1]."""
        return g @ self.weights


def local_strain(psd, q) -> np.ndarray:
    r"""Local strain :math:`\epsilon(q) = \xi(q)/2`, :math:`\xi^2 = 2\pi\int_{q_l}^{q} q'^3C\,dq'` (Lorenz et al. 2011).

    Parameters
    ----------
    psd : PSD
        The spectrum.
    q : array_like, 1/length
        Wavenumbers in [q_l, q_s].

    Returns
    -------
    numpy.ndarray, dimensionless
        Half the rms slope of the roughness with wavenumbers up to ``q``.
    """
    z = np.clip(np.asarray(q, dtype=float) / psd.q_l, 1.0, psd.zeta_max)
    return 0.5 * np.sqrt(2.0 * np.pi * np.maximum(psd.moment_unchecked(3, z), 0.0))


# -- the sliding response -----------------------------------------------------------------------------------------
class SlidingViscoelastic(ElasticResponse):
    r"""A rubber sliding at speed :math:`v`: :math:`E_{eff} = E(qv\cos\phi)/(1-\nu^2)` (module docstring).

    .. math::  V(\zeta; v) = \frac14\int_{q_l}^{\zeta q_l} dq\,q^3C(q)\,\frac{b_T^2\,[f^2\Phi'(qva_T)
               + g^2\Phi''(qva_T)]}{(1-\nu^2)^2},\qquad
               \frac{dV}{d\zeta} = q_l\,\frac{q^3 C(q)\,b_T^2[f^2\Phi' + g^2\Phi'']}{4(1-\nu^2)^2}\Big|_{q=\zeta q_l}

    with :math:`f, g = 1` without strain softening; ``modulus_in_G="plain"`` drops the :math:`(1-\nu^2)^2` (the
    plain modulus E, as some programs use).  A :class:`~persson_fp.ContactProblem` on this response gives the
    sliding contact area :math:`A^*(\zeta; v)`, Persson's :math:`P(q) = \mathrm{erf}(1/(2\sqrt{G}))` with
    :math:`G = V/(2\sigma_0^2)`, and its PDF; with a fudge factor the problem solves the PDE with
    :math:`B_2 = S(A^*)\,dV/d\zeta` (the fudge factor in the loop), which is *not* what
    :func:`persson_fp.rubber_friction` does (there the fudge factor only weights the friction integrand, and the
    contact area is the plain :math:`P(q_1)`).

    Parameters
    ----------
    material : ViscoelasticMaterial
        The rubber (:mod:`persson_fp.theory.viscoelastic`).
    velocity : float, length/s
        Sliding speed in the spectrum's length unit per second (m/s for a spectrum in metres), finite and > 0.
    temperature : float, optional, degrees C
        Required when the material has a shift law.
    modulus_in_G : {"reduced", "plain"}
        The modulus in V (default "reduced", E/(1-nu^2)).
    strain_softening : StrainSoftening, optional
        The Payne effect at the local strain :func:`local_strain`.
    """

    def __init__(self, material, velocity, temperature=None, modulus_in_G="reduced", strain_softening=None):
        self.material = check_material(material)
        self.velocity = as_positive_scalar(velocity, "velocity")
        if temperature is not None:
            T = check_temperature(temperature, "temperature")
            if T.ndim != 0:
                raise ValueError(f"temperature must be one number (degrees C) for one sliding response, got {T!r}")
            temperature = float(T)
        elif material.needs_temperature:
            raise ValueError("temperature (degrees C) is required: the material has a time-temperature shift")
        self.temperature = temperature
        self.modulus_in_G = check_modulus_in_G(modulus_in_G)
        self.strain_softening = check_strain_softening(strain_softening)
        self.aT = float(10.0 ** material.log10_aT(temperature)) if material.needs_temperature else 1.0
        self.bT = float(material.b_T(temperature)) if material.needs_temperature else 1.0
        self._angular = angular_integrals(material)
        self._cache = None

    def __repr__(self):
        T = "" if self.temperature is None else f", temperature={self.temperature!r} degrees C"
        soft = "" if self.strain_softening is None else f", strain_softening={self.strain_softening!r}"
        return (
            f"SlidingViscoelastic({self.material!r}, velocity={self.velocity!r}{T}, "
            f"modulus_in_G={self.modulus_in_G!r}{soft})"
        )

    def _key(self):
        return (self.material, self.velocity, self.temperature, self.modulus_in_G, self.strain_softening)

    def __eq__(self, other):
        if type(other) is not SlidingViscoelastic:
            return NotImplemented
        return self._key() == other._key()

    def __hash__(self):
        return hash((SlidingViscoelastic, self._key()))

    def __getstate__(self):
        return dict(self.__dict__, _cache=None)

    @property
    def nu(self) -> float:
        """The rubber's Poisson ratio."""
        return self.material.nu

    def _denominator(self) -> float:
        return (1.0 - self.nu**2) ** 2 if self.modulus_in_G == "reduced" else 1.0

    def integrand(self, psd, q) -> np.ndarray:
        """dV/d(ln q) at wavenumbers ``q`` (in [q_l, q_s]), pressure^2."""
        q = np.asarray(q, dtype=float)
        if self.strain_softening is not None:
            P1, P2, _ = self._angular(q * (self.velocity * self.aT))
            f, g = self.strain_softening.factors(local_strain(psd, q))
            Phi = f * f * P1 + g * g * P2
        else:
            Phi = self._angular.phi_psi(q * (self.velocity * self.aT))[0]
        return 0.25 * q**4 * psd.C(q) * (self.bT**2) * Phi / self._denominator()

    def _setup(self, psd):
        c = self._cache
        if c is not None and c[0] is psd:
            return c[1]
        check_spectrum(psd)
        if not np.isfinite(psd.q_s * self.velocity * self.aT):
            raise ValueError(
                f"velocity {self.velocity!r} x a_T {self.aT!r} x q_s {psd.q_s!r} leaves floating-point range; check "
                "the units of the speed and of the spectrum"
            )
        rule = LnQRule(psd, psd.q_s, graded=False)
        g = self.integrand(psd, rule.q)
        n_p = rule.left.size
        totals = g.reshape(n_p, rule.m) @ rule._w * rule.half
        start = np.concatenate([[0.0], np.cumsum(totals)])
        self._cache = (psd, (rule, start))
        return rule, start

    def V(self, psd, zeta=None) -> np.ndarray:
        """V(zeta; v), pressure^2 (Gauss–Legendre in ln q on the panels of :class:`LnQRule`)."""
        z = np.float64(psd.zeta_max) if zeta is None else check_in_range(zeta, "zeta", 1.0, psd.zeta_max)
        rule, start = self._setup(psd)
        q = np.asarray(z, dtype=float) * psd.q_l
        x = np.log(q)
        k = np.clip(np.searchsorted(rule.left, x, side="right") - 1, 0, rule.left.size - 1)
        a = rule.left[k]
        left_q = np.exp(a)
        left_q = np.where(k == 0, psd.q_l, left_q)  # the first panel starts at q_l exactly
        half = 0.5 * np.log(q / left_q)  # not x - a: no cancellation just above a panel's start
        nodes = a[..., None] + half[..., None] * (rule._t + 1.0)
        part = (self.integrand(psd, np.exp(nodes)) @ rule._w) * half
        return start[k] + part

    def dV_dzeta(self, psd, zeta=None) -> np.ndarray:
        """dV/dzeta = (dV/d ln q) / zeta at q = zeta q_l, pressure^2."""
        z = np.float64(psd.zeta_max) if zeta is None else check_in_range(zeta, "zeta", 1.0, psd.zeta_max)
        return self.integrand(psd, np.asarray(z, dtype=float) * psd.q_l) / np.asarray(z, dtype=float)

    def dV_dzeta_unchecked(self, psd, z) -> np.ndarray:
        """:meth:`dV_dzeta` without the range check."""
        z = np.asarray(z, dtype=float)
        return self.integrand(psd, z * psd.q_l) / z
