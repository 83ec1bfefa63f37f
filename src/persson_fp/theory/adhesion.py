r"""Adhesion between rough surfaces in the DMT limit, through the gap distribution.

In the Derjaguin-Muller-Toporov (DMT) limit the attraction does not change the deformation: the interface is the
non-adhesive one at the repulsive nominal pressure :math:`p_{rep}`, and the attraction adds the nominal stress

.. math::  p_{att} = A\,\sigma_{att}(0) + \int_{u>0} P(u)\,\sigma_{att}(u)\,du ,

so that the applied load is :math:`p = p_{rep} - p_{att}` (Persson & Scaraggi, J. Chem. Phys. 141 (2014) 124701,
for the use of the gap distribution; Almqvist et al., J. Mech. Phys. Solids 59 (2011) 2355, for P(u)).
:math:`\sigma_{att}(u) \ge 0` is the attractive traction at gap u, with :math:`\int_0^\infty \sigma_{att}\,du = w`,
the work of adhesion per area.  The pull-off stress is :math:`-\min_{p_{rep}} p`.

**Validity.**  DMT holds when the range :math:`\rho` of the interaction is long compared with the elastic
deformation it causes: a Tabor-like parameter :math:`\mu = R^{1/3}(w/E^*)^{2/3}/\rho \ll 1` with R the typical
asperity radius, here :math:`1/h''_{rms}` (the generalised Tabor parameter quoted by ContactEngineering after
Müser).  For :math:`\mu \gtrsim 1` the contact grows by the attraction (JKR-like) and this module underestimates
area and pull-off.  Two stickiness estimates from the spectrum are offered: Persson & Tosatti (J. Chem. Phys. 115
(2001) 5597) compare w, times the true-area ratio, with the elastic energy of full contact; Pastewka & Robbins
(PNAS 111 (2014) 3298, their Eq. 10 with :math:`\kappa_{rep} = 2`) give the number
:math:`\frac{h'_{rms}E^*\rho}{2w}\left(\frac{h'^2_{rms}}{h''_{rms}\rho}\right)^{2/3}`, sticky below 1.  Here
:math:`h''_{rms}` is the rms mean curvature :math:`\tfrac12\langle(\nabla^2 h)^2\rangle^{1/2}`.  Checked against
ContactEngineering: its Adhesion package's rough-contact example (``examples/adhesive_simulation_rough.py``, "P&R
equation 10, with kappa_rep = 2") evaluates exactly this number with SurfaceTopography's ``rms_gradient`` and
``rms_curvature_from_area``, and the latter is documented there as half the rms Laplacian; the Tabor-like parameter
below is the same example's "generalized Tabor parameter following Martin Müser" (tests: the number from a height
map's own rms gradient and half rms Laplacian, 1e-2).

What was checked: :math:`p_{att}` against adaptive quadrature of :math:`\int P\sigma\,du` for every law (tests,
1e-6), the closed-form folded-normal means, the pull-off against brute-force minimisation, the limit
:math:`w \to 0` (the non-adhesive area and separation exactly), and the boundary-element runs of
``benchmarks/interface_vs_bem.py`` (exponential law: :math:`p_{att}` within ~2 % for :math:`p_{rep}/(E^*\bar g) \ge
0.005`, pull-off 10-25 % low with the corrected models, 45-61 % low with the plain theory, whose mean gap grows
without bound at small loads).  The Tabor-like parameter here is one number for the whole spectrum (the radius
:math:`1/h''_{rms}` of the finest scale), not the per-scale parameter a full analysis would use.

This module imports no solver.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.special import erfcx, log_ndtr, ndtr

from persson_fp._validate import as_positive_scalar
from persson_fp.theory.response import ElasticHalfSpace

__all__ = [
    "Interaction",
    "Exponential",
    "MaugisDugdale",
    "LennardJones93",
    "CallableInteraction",
    "resolve_interaction",
    "attractive_stress",
    "persson_tosatti",
    "pastewka_robbins",
    "tabor_parameter",
]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(64)


def _check_scale(w, rho, rho_name="rho"):
    """The peak traction ~ w/rho must be a finite number (else the law is outside the floating-point range)."""
    with np.errstate(over="ignore"):
        peak = w / rho
    if not np.isfinite(peak):
        raise ValueError(
            f"w / {rho_name} = {w!r} / {rho!r} (the peak attraction, pressure) leaves the floating-point range; "
            "rescale the units"
        )


class Interaction:
    r"""An attractive traction law :math:`\sigma_{att}(u) \ge 0` (pressure) at gap u >= 0 (length).

    Subclasses set ``w`` (work of adhesion, pressure x length), ``rho`` (its range, length) and ``name`` and
    implement :meth:`sigma`; :meth:`folded_mean` defaults to quadrature.
    """

    w: float
    rho: float
    name: str = "interaction"

    def _set_range(self, w: float, rho: float):
        """``w`` and ``rho``, each a finite number > 0, whose ratio w / rho stays in floating-point range."""
        self.w = as_positive_scalar(w, "w")
        self.rho = as_positive_scalar(rho, "rho")
        _check_scale(self.w, self.rho)

    def sigma(self, u) -> np.ndarray:  # pragma: no cover - abstract
        """Attractive traction at gap(s) ``u`` >= 0 (pressure)."""
        raise NotImplementedError

    def __call__(self, u):
        return self.sigma(u)

    def folded_mean(self, c, h) -> np.ndarray:
        r""":math:`E[\sigma(|X|)]`, X normal with mean c and std h (broadcast arrays).

        Quadrature: 64 Gauss-Legendre nodes in :math:`\ln(1 + u/\rho)` on :math:`[0, c + 9h]` where
        :math:`c < 9h`, else linear nodes on :math:`[c - 9h, c + 9h]` (outside, the normal is below
        :math:`e^{-40}`).  Tests check it against adaptive quadrature to 1e-7 relative.
        """
        c, h = np.broadcast_arrays(np.asarray(c, float), np.asarray(h, float))
        shape = c.shape
        c, h = c.ravel()[:, None], h.ravel()[:, None]
        lo = np.maximum(c - 9.0 * h, 0.0)
        hi = c + 9.0 * h
        near = lo <= 0.0
        x = 0.5 * (_GL_X + 1.0)[None, :]
        with np.errstate(over="ignore"):
            L = np.log1p(hi / self.rho)
        if not np.all(np.isfinite(L)):
            raise ValueError(f"rho = {self.rho!r} is too small against the gaps (gap / rho overflows); rescale units")
        u_log = self.rho * np.expm1(L * x)
        du_log = L * (u_log + self.rho)
        u_lin = lo + (hi - lo) * x
        u = np.where(near, u_log, u_lin)
        du = np.where(near, du_log, hi - lo)
        dens = (np.exp(-0.5 * ((u - c) / h) ** 2) + np.exp(-0.5 * ((u + c) / h) ** 2)) / (np.sqrt(2 * np.pi) * h)
        out = np.sum(0.5 * _GL_W[None, :] * du * dens * self.sigma(u), axis=1)
        return out.reshape(shape)

    def __repr__(self):
        return f"{type(self).__name__}(w={self.w!r}, rho={self.rho!r})"


class Exponential(Interaction):
    r""":math:`\sigma_{att} = (w/\rho)\,e^{-u/\rho}`.

    Parameters
    ----------
    w : float, pressure x length
        Work of adhesion per area (> 0; e.g. J/m²).
    rho : float, length
        Decay length (> 0).
    """

    name = "exponential"

    def __init__(self, w: float, rho: float):
        self._set_range(w, rho)

    def sigma(self, u):
        return self.w / self.rho * np.exp(-np.asarray(u, float) / self.rho)

    def folded_mean(self, c, h):
        r"""Closed form: :math:`\frac{w}{\rho}\sum_\pm e^{\mp c/\rho + h^2/2\rho^2}\Phi(\pm c/h - h/\rho)`.

        Where :math:`h/\rho > c/h` each term is written :math:`\tfrac12 e^{-c^2/2h^2}\mathrm{erfcx}((h/\rho \mp
        c/h)/\sqrt2)` (the same number; no overflow of :math:`e^{h^2/2\rho^2}` when the range is short against the
        widths, where the limit is :math:`w\,P(0)`).
        """
        c, h = np.broadcast_arrays(np.asarray(c, float), np.asarray(h, float))
        a = h / self.rho
        r = c / h
        with np.errstate(over="ignore", under="ignore", invalid="ignore"):
            plus = np.exp(-c / self.rho + 0.5 * a * a + log_ndtr(r - a))
            minus = np.exp(c / self.rho + 0.5 * a * a + log_ndtr(-r - a))
            g = np.exp(-0.5 * r * r)
            # erfcx form where its argument is >= 0, for each term on its own (one condition for both gave
            # 0 * inf = NaN for a mean gap below -rho with a narrow width, where the minus term's argument is < 0)
            plus = np.where(a > r, 0.5 * g * erfcx((a - r) / np.sqrt(2.0)), plus)
            minus = np.where(a > -r, 0.5 * g * erfcx((a + r) / np.sqrt(2.0)), minus)
        return self.w / self.rho * (plus + minus)


class MaugisDugdale(Interaction):
    r"""Maugis-Dugdale step: :math:`\sigma_{att} = \sigma_0` for :math:`u < \delta = w/\sigma_0`, else 0.

    Parameters
    ----------
    w : float, pressure x length
        Work of adhesion per area (> 0).
    sigma0 : float, pressure
        Cohesive stress (> 0); the range is :math:`\rho = w/\sigma_0`.
    """

    name = "maugis-dugdale"

    def __init__(self, w: float, sigma0: float):
        self.w = as_positive_scalar(w, "w")
        self.sigma0 = as_positive_scalar(sigma0, "sigma0")
        with np.errstate(over="ignore"):
            self.rho = self.w / self.sigma0
        if not np.isfinite(self.rho):
            raise ValueError(f"w / sigma0 = {w!r} / {sigma0!r} (the range, length) leaves the floating-point range")

    def sigma(self, u):
        u = np.asarray(u, float)
        return np.where(u < self.rho, self.sigma0, 0.0)

    def folded_mean(self, c, h):
        r"""Closed form: :math:`\sigma_0\Pr(|X| < \delta) = \sigma_0[\Phi((\delta - c)/h) - \Phi((-\delta - c)/h)]`."""
        c, h = np.asarray(c, float), np.asarray(h, float)
        return self.sigma0 * (ndtr((self.rho - c) / h) - ndtr((-self.rho - c) / h))


class LennardJones93(Interaction):
    r"""9-3 Lennard-Jones traction from its zero: :math:`\sigma_{att} = \frac{8w}{3\rho}[(\frac{\rho}{u+\rho})^3 -
    (\frac{\rho}{u+\rho})^9]`.

    :math:`\sigma_{att}(0) = 0` (the equilibrium distance :math:`\rho` is the contact), :math:`\int_0^\infty
    \sigma_{att}\,du = w`, maximum :math:`\approx 1.026\,w/\rho` at :math:`u = (3^{1/6} - 1)\rho`.

    Parameters
    ----------
    w : float, pressure x length
        Work of adhesion per area (> 0).
    rho : float, length
        Equilibrium distance (> 0).
    """

    name = "lennard-jones-9-3"

    def __init__(self, w: float, rho: float):
        self._set_range(w, rho)

    def sigma(self, u):
        x = self.rho / (np.asarray(u, float) + self.rho)
        return 8.0 * self.w / (3.0 * self.rho) * (x**3 - x**9)


class CallableInteraction(Interaction):
    """A user traction law ``fn(u) -> sigma_att >= 0`` (vectorised), with its range ``rho`` and work ``w``.

    Parameters
    ----------
    fn : callable
        Attractive traction (pressure) at gaps u >= 0 (length); must be finite and >= 0.
    rho : float, length
        Its range (> 0): the scale the quadrature resolves near u = 0.
    w : float, optional, pressure x length
        Work of adhesion; default the integral of ``fn`` (adaptive quadrature split at 1, 10, 100 and 1e4
        ``rho``: 1e-10 relative for a smooth law of that range).
    """

    name = "user"

    def __init__(self, fn: Callable, rho: float, w: float | None = None):
        if not callable(fn):
            raise ValueError(f"interaction must be an Interaction or a callable sigma(u); got {fn!r}")
        self.fn = fn
        self.rho = as_positive_scalar(rho, "rho")
        try:
            probe = np.asarray(fn(self.rho * np.geomspace(1e-6, 1e3, 64)), dtype=float)
        except Exception as e:  # the user's function: any failure is a bad input
            raise ValueError(f"the interaction callable failed on an array of gaps: {type(e).__name__}: {e}") from e
        if probe.shape != (64,) or not np.all(np.isfinite(probe)) or np.any(probe < 0):
            raise ValueError("the interaction callable must return finite values >= 0 for an array of gaps u >= 0")
        if w is None:
            from scipy.integrate import quad

            # split at multiples of the range: one quad over [0, inf) misses a law of short range (rho = 1e-9 gave
            # w = 6e-91 instead of 1, or 0 and a refusal)
            def f(u):
                return float(fn(np.array([u]))[0])

            cuts = self.rho * np.array([0.0, 1.0, 10.0, 100.0, 1e4])
            w = sum(quad(f, a, b, epsabs=0.0, epsrel=1e-10, limit=200)[0] for a, b in zip(cuts[:-1], cuts[1:]))
            w += quad(f, cuts[-1], np.inf, limit=200)[0]
        self.w = as_positive_scalar(w, "w")
        _check_scale(self.w, self.rho)
        self.name = getattr(fn, "__name__", "user")

    def sigma(self, u):
        return np.asarray(self.fn(np.asarray(u, float)), dtype=float)


def resolve_interaction(interaction, rho=None) -> Interaction:
    """An :class:`Interaction` as is, or a callable wrapped as :class:`CallableInteraction` (``rho`` needed)."""
    if isinstance(interaction, Interaction):
        return interaction
    if callable(interaction):
        if rho is None:
            raise ValueError("a callable interaction needs its range rho (length) for the quadrature")
        return CallableInteraction(interaction, rho)
    raise ValueError(
        f"interaction must be Exponential, MaugisDugdale, LennardJones93 or a callable; got {interaction!r}"
    )


def attractive_stress(gaps, interaction: Interaction) -> np.ndarray:
    r"""Nominal attractive stress :math:`p_{att} = A\sigma(0) + \sum_k w_k E[\sigma(|X_k|)]` per load.

    Parameters
    ----------
    gaps : GapDistribution
        The non-adhesive gap distribution at each repulsive load.
    interaction : Interaction
        The traction law.

    Returns
    -------
    ndarray, pressure
        :math:`p_{att} \ge 0`, shape ``(n_loads,)``.
    """
    from persson_fp.theory.gaps import GapDistribution

    if not isinstance(gaps, GapDistribution):
        raise ValueError(f"gaps must be a GapDistribution (persson_fp.gap_distribution), got {type(gaps).__name__}")
    if not isinstance(interaction, Interaction):
        raise ValueError(f"interaction must be an Interaction (persson_fp.adhesion), got {type(interaction).__name__}")
    s0 = float(np.asarray(interaction.sigma(np.array([0.0])))[0])
    cont = np.sum(gaps.weights * interaction.folded_mean(gaps.centres, gaps.widths), axis=1)
    return gaps.atom * s0 + cont


def _moments(psd):
    from persson_fp.surfaces.psd import PSD

    if not isinstance(psd, PSD):
        raise ValueError(f"psd must be a persson_fp spectrum (PSD), got {type(psd).__name__} {psd!r}")
    h1 = float(psd.rms_slope)
    h2 = 0.5 * float(np.sqrt(2.0 * np.pi * psd.moment(5)))  # rms mean curvature 1/2 <(lap h)^2>^(1/2)
    return h1, h2


def persson_tosatti(psd, E_star, w) -> dict:
    r"""Persson-Tosatti stickiness: effective interfacial energy at full contact.

    :math:`w_{eff} = w\,A_{true}/A_0 - U_{el}`, :math:`U_{el} = \frac{\pi}{2}E^*\int q^2C\,dq` (elastic energy per
    area of full contact, Xu et al. tutorial ``eq:Uel_complete_2``), :math:`A_{true}/A_0 = E\sqrt{1 + |\nabla h|^2}`
    for a Gaussian isotropic surface, :math:`= 1 + \tfrac12\sqrt{\pi/\lambda}\,\mathrm{erfcx}(\sqrt\lambda)` with
    :math:`\lambda = 1/\langle|\nabla h|^2\rangle` (exact for that surface; small slopes give
    :math:`1 + \langle|\nabla h|^2\rangle/2`).  Sticky when :math:`w_{eff} > 0`.

    Parameters
    ----------
    psd : PSD
        The spectrum.
    E_star : float, pressure
        Plane-strain modulus (> 0).
    w : float, pressure x length
        Work of adhesion (> 0).

    Returns
    -------
    dict
        ``w_eff`` (pressure x length), ``U_el`` (pressure x length), ``area_ratio``, ``sticky`` (bool).
    """
    E_star = as_positive_scalar(E_star, "E_star")
    w = as_positive_scalar(w, "w")
    U = float(ElasticHalfSpace(E_star).elastic_energy_complete(psd, needed_for="the Persson-Tosatti stickiness"))
    lam = 1.0 / float(psd.grad2())
    ratio = 1.0 + 0.5 * np.sqrt(np.pi / lam) * erfcx(np.sqrt(lam))
    w_eff = w * ratio - U
    return {"w_eff": w_eff, "U_el": U, "area_ratio": ratio, "sticky": bool(w_eff > 0)}


def pastewka_robbins(psd, E_star, w, rho) -> dict:
    r"""Pastewka-Robbins stickiness number (PNAS 111 (2014) 3298, Eq. 10, :math:`\kappa_{rep} = 2`).

    :math:`\Pi = \frac{h'_{rms}E^*\rho}{2w}\left(\frac{h'^2_{rms}}{h''_{rms}\rho}\right)^{2/3}`: sticky for
    :math:`\Pi < 1`, with :math:`h'_{rms} = \langle|\nabla h|^2\rangle^{1/2}` and :math:`h''_{rms} =
    \tfrac12\langle(\nabla^2 h)^2\rangle^{1/2}` (as ContactEngineering evaluates it; module docstring).  Valid for
    short-range adhesion: ``range_ratio`` :math:`= \rho/g_0`, :math:`g_0 = \tfrac{16}{3}h'^2_{rms}/h''_{rms}`
    (Monti, Sanner & Pastewka, Tribol. Lett. (2021), doi:10.1007/s11249-021-01454-6), should be well below 1
    (ContactEngineering's example asks for 0.1).

    Parameters
    ----------
    psd : PSD
        The spectrum; :math:`h'_{rms}` its rms slope, :math:`h''_{rms}` its rms mean curvature.
    E_star : float, pressure
        Plane-strain modulus (> 0).
    w : float, pressure x length
        Work of adhesion (> 0).
    rho : float, length
        Interaction range (> 0).

    Returns
    -------
    dict
        ``number`` (dimensionless), ``sticky`` (bool), ``rms_slope``, ``rms_curvature`` (1/length) and
        ``range_ratio`` (:math:`\rho/g_0`, dimensionless).
    """
    E_star = as_positive_scalar(E_star, "E_star")
    w = as_positive_scalar(w, "w")
    rho = as_positive_scalar(rho, "rho")
    h1, h2 = _moments(psd)
    # rho^(1/3) taken apart: rho * rho^(-2/3) overflows to inf * 0 = NaN for rho near the float limit
    with np.errstate(over="ignore", under="ignore"):
        number = float(h1 * E_star / (2.0 * w) * np.cbrt(rho) * (h1 * h1 / h2) ** (2.0 / 3.0))
        g0 = 16.0 / 3.0 * h1 * h1 / h2
        ratio = rho / g0
    if not (np.isfinite(number) and number > 0.0 and np.isfinite(ratio) and ratio > 0.0):
        raise ValueError(
            f"E_star = {E_star!r}, w = {w!r} and rho = {rho!r} (with the spectrum's g0 = {g0:.3g}) put the adhesion "
            "number or rho / g0 outside floating-point range; rescale the units"
        )
    return {
        "number": number,
        "sticky": bool(number < 1.0),
        "rms_slope": h1,
        "rms_curvature": h2,
        "range_ratio": ratio,
    }


def tabor_parameter(psd, E_star, w, rho) -> float:
    r"""Tabor-like parameter :math:`\mu = R^{1/3}(w/E^*)^{2/3}/\rho`, :math:`R = 1/h''_{rms}`; DMT needs
    :math:`\mu \ll 1`.

    Parameters
    ----------
    psd : PSD
        The spectrum.
    E_star : float, pressure
        Plane-strain modulus (> 0).
    w : float, pressure x length
        Work of adhesion (> 0).
    rho : float, length
        Interaction range (> 0).

    Returns
    -------
    float, dimensionless
    """
    E_star = as_positive_scalar(E_star, "E_star")
    w = as_positive_scalar(w, "w")
    rho = as_positive_scalar(rho, "rho")
    _, h2 = _moments(psd)
    return float((1.0 / h2) ** (1.0 / 3.0) * (w / E_star) ** (2.0 / 3.0) / rho)
