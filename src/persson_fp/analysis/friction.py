r"""Rubber friction: the viscoelastic (hysteretic) friction coefficient and the sliding contact area.

Persson, J. Chem. Phys. 115 (2001) 3840 and J. Phys.: Condens. Matter 18 (2006) 7789; the strain softening of
Lorenz, Persson, Dieluweit, Tada, Eur. Phys. J. E 34 (2011) 129.  A rigid rough surface of spectrum :math:`C(q)`
(a road) slides at speed :math:`v` over a rubber of complex modulus :math:`E(\omega, T)` under the nominal pressure
:math:`\sigma_0`:

.. math::
   \mu(v) = \frac12\int_{q_0}^{q_1} dq\,q^3 C(q)\,P(q)\,S(q)\int_0^{2\pi} d\phi\,\cos\phi\,
            \frac{\mathrm{Im}\,E(qv\cos\phi)}{(1-\nu^2)\,\sigma_0},\qquad
   P(q) = \mathrm{erf}\left(\frac{1}{2\sqrt{G(q)}}\right),

.. math::
   G(q) = \frac18\int_{q_0}^{q} dq'\,q'^3 C(q')\int_0^{2\pi} d\phi\,
          \left|\frac{E(q'v\cos\phi)}{(1-\nu^2)\,\sigma_0}\right|^2,

:math:`S(q)` the fudge factor's weight at :math:`P(q)` (Yang & Persson 2008: :math:`S = \gamma + (1-\gamma)P^2`),
and the sliding contact area :math:`A/A_0 = P(q_1)`.  :math:`G = V(\zeta; v)/(2\sigma_0^2)` with the sliding
response's :math:`V` (:mod:`persson_fp.theory.sliding`), so :math:`P(q)` is the diffusion equation's contact area
:math:`A^*(\zeta)` at :math:`\zeta = q/q_0` (:func:`persson_fp.sliding_contact`).

Scope: the isothermal viscoelastic (hysteretic) part of rubber friction only — no flash temperature, no shear
stress in the area of real contact (adhesive friction).
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp._warn import warn_user
from persson_fp.theory import fudge as _fudge
from persson_fp.theory.sliding import (
    LnQRule,
    angular_integrals,
    check_material,
    check_modulus_in_G,
    check_spectrum,
    check_strain_softening,
    local_strain,
)
from persson_fp.theory.viscoelastic import check_temperature

__all__ = ["rubber_friction", "FrictionResult", "SCOPE"]

SCOPE = (
    "mu is the isothermal viscoelastic (hysteretic) part of rubber friction only: no flash temperature, no shear "
    "stress in the area of real contact (adhesive friction). On real compounds flash heating lowers mu by ~15 % near "
    "1 m/s and by a factor 2 or more at high speed, and the viscoelastic part can be a third of a measured mu."
)
"""What :func:`rubber_friction` computes and what it leaves out (printed by the result's ``repr`` and the CLI)."""


class FrictionResult:
    r"""The friction coefficient and sliding contact area of :func:`rubber_friction`.

    Built by :func:`rubber_friction`; each parameter is kept as the attribute of its name.

    Parameters
    ----------
    mu : numpy.ndarray, dimensionless
        Viscoelastic friction coefficient, shape ``np.broadcast_shapes(np.shape(temperature),
        np.shape(velocity))`` (0-d for scalars).
    mu_error : numpy.ndarray
        Error estimate of ``mu``: the change when every quadrature (the angle, its table in frequency, the
        wavenumber panels) is refined twofold.
    contact_area : numpy.ndarray, dimensionless
        Sliding contact area :math:`A/A_0 = P(q_1)` (independent of the fudge factor), the shape of ``mu``.
    contact_area_error : numpy.ndarray
        Its error estimate (as ``mu_error``).
    q : numpy.ndarray, 1/length
        Wavenumbers from :math:`q_0` to :math:`q_1` (the quadrature nodes with both ends).
    G, P : numpy.ndarray
        :math:`G(q)` and :math:`P(q)` (dimensionless) with a trailing q axis: shape ``mu.shape + q.shape``.
    velocity, temperature : numpy.ndarray
        The inputs broadcast to the shape of ``mu`` (``temperature`` None without one), length/s and degrees C.
    sigma0 : float, pressure
    q0, q1 : float, 1/length
    conventions : dict
        Every convention used (modulus in G, frequency unit, shift, PSD convention, q0, q1, fudge factor, ...).
    material : ViscoelasticMaterial
    psd : PSD
    """

    def __init__(
        self, mu, mu_error, contact_area, contact_area_error, q, G, P, velocity, temperature, sigma0, q0, q1,
        conventions, material, psd,
    ):  # fmt: skip
        self.mu, self.mu_error = mu, mu_error
        self.contact_area, self.contact_area_error = contact_area, contact_area_error
        self.q, self.G, self.P = q, G, P
        self.velocity, self.temperature, self.sigma0, self.q0, self.q1 = velocity, temperature, sigma0, q0, q1
        self.conventions, self.material, self.psd = conventions, material, psd

    def __repr__(self):
        c = self.conventions
        shape = self.mu.shape
        if self.mu.ndim == 0:
            mu = f"{float(self.mu):.6g}"
        else:
            mu = f"{shape} values in [{self.mu.min():.4g}, {self.mu.max():.4g}]"
        A = (
            f"{float(self.contact_area):.6g}"
            if self.mu.ndim == 0
            else f"[{self.contact_area.min():.4g}, {self.contact_area.max():.4g}]"
        )
        conv = ", ".join(f"{k}={v}" for k, v in c.items())
        return (
            f"FrictionResult(mu={mu} (error <= {float(np.max(self.mu_error)):.2g}), contact_area={A}, "
            f"sigma0={self.sigma0:.6g}, {conv})\n  {SCOPE}"
        )

    @property
    def table(self):
        """One row per (velocity, temperature): a pandas DataFrame when pandas is installed, else a dict of columns.

        Columns carry their units: ``velocity [length/s]``, ``temperature [degC]``, ``mu [-]``, ``mu_error [-]``,
        ``contact_area [-]``, ``contact_area_error [-]``.
        """
        cols = {"velocity [length/s]": self.velocity.ravel()}
        if self.temperature is not None:
            cols["temperature [degC]"] = self.temperature.ravel()
        cols.update(
            {
                "mu [-]": self.mu.ravel(),
                "mu_error [-]": self.mu_error.ravel(),
                "contact_area [-]": self.contact_area.ravel(),
                "contact_area_error [-]": self.contact_area_error.ravel(),
            }
        )
        try:
            import pandas as pd
        except ImportError:
            return cols
        return pd.DataFrame(cols)

    def plot(self, axes=None):
        """mu(v) and A(v)/A0 against the sliding speed on log axes, one curve per temperature.

        Parameters
        ----------
        axes : sequence of two matplotlib Axes, optional
            Where to draw mu and the contact area; default a new figure with two panels side by side.

        Returns
        -------
        matplotlib.figure.Figure
        """
        import matplotlib.pyplot as plt

        if axes is None:
            fig, axes = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
        else:
            fig = axes[0].figure
        v = np.atleast_1d(self.velocity)
        mu, A = np.atleast_1d(self.mu), np.atleast_1d(self.contact_area)
        mu_e = np.atleast_1d(self.mu_error)
        if mu.ndim == 1:
            v, mu, A, mu_e = v[None, :], mu[None, :], A[None, :], mu_e[None, :]
            labels = [None if self.temperature is None else f"T = {float(np.ravel(self.temperature)[0]):g} degC"]
        else:  # (temperature, velocity): one curve per row
            v = v.reshape(-1, v.shape[-1])
            mu, A, mu_e = (x.reshape(-1, x.shape[-1]) for x in (mu, A, mu_e))
            T = np.broadcast_to(self.temperature, self.mu.shape).reshape(-1, self.mu.shape[-1])
            labels = [f"T = {t:g} degC" for t in T[:, 0]]
        for vi, mi, ai, lab in zip(v, mu, A, labels):
            axes[0].plot(vi, mi, marker="." if vi.size < 30 else None, label=lab)
            axes[1].plot(vi, ai, marker="." if vi.size < 30 else None, label=lab)
        for ax in axes:
            ax.set_xscale("log")
            ax.set_xlabel("sliding speed v [length/s]")
        axes[0].set_ylabel("viscoelastic friction coefficient mu [-]")
        axes[1].set_yscale("log")
        axes[1].set_ylabel("sliding contact area A/A0 [-]")
        c = self.conventions
        axes[0].set_title(
            f"sigma0 = {self.sigma0:.4g} [pressure], q1 = {self.q1:.3g} [1/length], fudge {c['fudge']}"
            f"\n(max error estimate {float(np.max(mu_e)):.1g})",
            fontsize=9,
        )
        axes[1].set_title("A/A0 = P(q1), independent of the fudge factor", fontsize=9)
        if any(lab is not None for lab in labels):
            axes[0].legend(fontsize=8)
        return fig


_ZT, _ZW = np.polynomial.legendre.leggauss(40)


def _first_panel_factor(a: np.ndarray, S) -> np.ndarray:
    r"""The mean of :math:`P\,S(P)` over the innermost panel :math:`[x_0, x_0 + \delta]`, where G is linear.

    With :math:`G = g_0 s` (:math:`s = \ln q - \ln q_0 \le \delta`, :math:`a = g_0\delta`) and
    :math:`P = \mathrm{erf}(1/(2\sqrt{G}))`: :math:`J(a) = \int_0^1 P S(P)\,d\sigma
    = rac{1}{2a}\int_0^{2\sqrt a} \mathrm{erf}(1/z)\,S(\mathrm{erf}(1/z))\,z\,dz` (:math:`z = 2\sqrt{a\sigma}`),
    Gauss–Legendre on :math:`z \le 8` and in :math:`\ln z` beyond: exact however steeply P falls near
    :math:`q_0` (a Gauss rule in :math:`s` is not, where P falls within the panel like :math:`1/\sqrt{g_0 s}`).
    """
    a = np.asarray(a, dtype=float)
    Z = 2.0 * np.sqrt(a)
    zA = np.minimum(Z, 8.0)[:, None] * 0.5 * (_ZT + 1.0)
    with np.errstate(divide="ignore"):
        PA = erf(1.0 / zA)
    part = (PA * S(PA) * zA) @ _ZW * (0.5 * np.minimum(Z, 8.0))
    far = Z > 8.0
    if np.any(far):
        lo, hi = np.log(8.0), np.log(Z[far])
        u = lo + (hi - lo)[:, None] * 0.5 * (_ZT + 1.0)
        zB = np.exp(u)
        PB = erf(1.0 / zB)
        part[far] += (PB * S(PB) * zB * zB) @ _ZW * (0.5 * (hi - lo))
    with np.errstate(divide="ignore", invalid="ignore"):
        J = part / (2.0 * a)
    return np.where(a > 0, J, S(np.ones(1))[0])


def _pass(psd, material, sigma0, v, aT, bT, q1, S, red_G, soft, refine):
    """One evaluation of mu, P(q1) and G, P at the nodes, for flattened speeds ``v`` with shifts ``aT``, ``bT``."""
    rule = LnQRule(psd, q1, refine=refine)
    q = np.concatenate([[psd.q_l], rule.q])  # q0 itself first: the slope of G and the integrand there
    q4C = q**4 * psd.C(q)
    ang = angular_integrals(material, refine)
    w0 = (v * aT)[:, None] * q[None, :]
    if soft is not None:
        P1, P2, Psi = ang(w0)
        f, g = soft.factors(local_strain(psd, q))
        Phi, Psi = f * f * P1 + g * g * P2, g * Psi
    else:
        Phi, Psi = ang.phi_psi(w0)
    nu2 = 1.0 - material.nu**2
    gG = q4C * (bT * bT)[:, None] * Phi / (8.0 * sigma0 * sigma0 * (nu2 * nu2 if red_G else 1.0))
    G, G1 = rule.cumulative(gG[:, 1:])
    if not (np.all(np.isfinite(G1)) and np.all(np.isfinite(gG))):
        raise FloatingPointError("G(q) out of floating-point range")  # (named as sigma0's by rubber_friction)
    G = np.maximum(G, 0.0)  # a running integral of a positive function: round-off never makes it negative
    with np.errstate(divide="ignore"):
        P = erf(0.5 / np.sqrt(G))
        A = erf(0.5 / np.sqrt(G1))
    F = 0.5 * q4C * Psi * bT[:, None] / (nu2 * sigma0)  # the friction integrand without P S(P)
    integrand = F[:, 1:] * P * S(P)
    m, delta = rule.m, rule.right[0] - rule.left[0]
    inner = F[:, 0] * delta * _first_panel_factor(gG[:, 0] * delta, S)
    mu = integrand[:, m:] @ rule.weights[m:] + inner
    return mu, A, rule.q, G, G1, P


def _coverage(material, q0, q1, omega_needed):
    rng = material.frequency_range
    if rng is None:
        return
    lo, hi = float(np.min(omega_needed[0])), float(np.max(omega_needed[1]))
    if lo >= rng[0] * (1 - 1e-9) and hi <= rng[1] * (1 + 1e-9):
        return
    msg = (
        f"the master curve does not cover the frequencies the friction integrals need: q v a_T spans "
        f"[{lo:.3g}, {hi:.3g}] rad/s (q from q0 = {q0:.4g} to q1 = {q1:.4g}), the curve gives "
        f"[{rng[0]:.3g}, {rng[1]:.3g}] rad/s"
    )
    if getattr(material, "extrapolation", None) == "raise":
        raise ValueError(msg + " (extrapolation='raise'): widen the curve or narrow velocity, temperature or q1")
    warn_user(msg + f"; outside it the modulus is extrapolated ({material.extrapolation!r})")


def rubber_friction(
    psd,
    material,
    sigma0,
    velocity,
    temperature=None,
    q1=None,
    fudge="YP08",
    modulus_in_G: str = "reduced",
    strain_softening=None,
) -> FrictionResult:
    r"""Viscoelastic friction coefficient :math:`\mu(v, T)` and sliding contact area of a rubber on a rough surface.

    Persson's theory (Persson, J. Chem. Phys. 115 (2001) 3840, Eqs. for :math:`\mu`, :math:`P(q)` and
    :math:`G(q)`; J. Phys.: Condens. Matter 18 (2006) 7789; the module docstring writes them out).  **Scope**:
    the isothermal hysteretic part only (``SCOPE``).

    Conventions (each in the result's ``conventions`` and ``repr``):

    * ``modulus_in_G``: "reduced" (default) puts :math:`E/(1-\nu^2)` in :math:`G` as Persson writes it; "plain"
      puts :math:`E` (some programs do: it multiplies :math:`G` by :math:`(1-\nu^2)^2`, 0.5625 at
      :math:`\nu = 0.5`).  :math:`\mu` always has :math:`\mathrm{Im}\,E/(1-\nu^2)`.
    * The fudge factor enters :math:`\mu` only as the weight :math:`S(P(q))`; :math:`P(q)` is the plain
      :math:`\mathrm{erf}(1/(2\sqrt{G}))` and ``contact_area`` = :math:`P(q_1)` does not depend on it, as in Persson's
      papers.  (:func:`persson_fp.sliding_contact` with ``fudge=`` is a different quantity: the fudge factor in the
      diffusion equation's loop.)
    * :math:`q_0` is the spectrum's :math:`q_l`; ``q1`` (default the spectrum's :math:`q_s`) is the short-wavelength
      cut-off; :math:`\mu` depends on it.  The spectrum's own convention is used as given (its ``C(q)``).
    * Frequencies: :math:`\omega = q v \cos\phi` rad/s, shifted as :math:`E(\omega, T) = b_T E_{ref}(\omega a_T)`
      (:mod:`persson_fp.theory.viscoelastic`).

    Accuracy: the angular integrals use Gauss–Legendre in :math:`\phi` near :math:`\phi = 0` and in
    :math:`-\ln\cos\phi` near :math:`\pi/2` (resolving the sharp feature there at high speed), tabulated at 32
    points per decade of :math:`q v a_T` (four-point interpolation); :math:`q` in Gauss–Legendre panels of
    :math:`\ln q` (5 per decade, 6 nodes; panel ends at the spectrum's kinks).  The whole evaluation is repeated with
    every rule refined twofold; the refined values are returned and their difference is ``mu_error`` and
    ``contact_area_error`` (measured below 1e-5 relative on Zener, Prony and tabulated materials at the defaults).
    ``G`` at the nodes inside a panel comes from the panel's interpolating polynomial (about 1e-7 relative); at
    ``q1`` (a panel's end) from its full Gauss rule.

    Parameters
    ----------
    psd : PSD
        The rough surface's spectrum (the road), lengths in the unit of ``velocity``.
    material : ViscoelasticMaterial
        The rubber: :class:`~persson_fp.theory.viscoelastic.Zener`, :class:`~persson_fp.theory.viscoelastic.Prony` or
        :class:`~persson_fp.theory.viscoelastic.MasterCurve`.
    sigma0 : float, pressure
        Nominal contact pressure (the unit of the material's moduli), finite and > 0.
    velocity : float or array_like, length/s
        Sliding speed(s), finite and > 0, in the spectrum's length unit per second (m/s for a spectrum in metres).
    temperature : float or array_like, optional, degrees C
        Required when the material has a time–temperature shift; broadcast against ``velocity``.
    q1 : float, optional, 1/length
        Upper cut-off in (q_l, q_s]; default the spectrum's q_s.
    fudge : None, str, FudgeFactor or callable
        The weight S(P) in the friction integrand (default "YP08"; None: S = 1).
    modulus_in_G : {"reduced", "plain"}
        The modulus in G (above).
    strain_softening : StrainSoftening, optional
        The Payne effect: :math:`E' f(\epsilon)`, :math:`E'' g(\epsilon)` at the local strain
        :math:`\epsilon(q)` (:func:`persson_fp.theory.sliding.local_strain`), in G and in :math:`\mu`.

    Returns
    -------
    FrictionResult
        ``mu``, ``contact_area`` (shape ``np.broadcast_shapes(np.shape(temperature), np.shape(velocity))``), their
        error estimates, ``q``, ``G``, ``P`` (trailing q axis), the conventions, ``plot()`` and ``table``.

    Raises
    ------
    ValueError
        A parameter out of range (named); a temperature below the WLF law's pole; a master curve that does not
        cover the frequencies needed with ``extrapolation="raise"`` (otherwise a warning names both ranges).
    """
    check_spectrum(psd)
    material = check_material(material)
    sigma0 = as_positive_scalar(sigma0, "sigma0")
    v = as_float_array(velocity, "velocity")
    if np.any(v <= 0):
        raise ValueError(f"velocity must be > 0 (length/s), got {float(np.min(v))!r}")
    if temperature is None:
        if material.needs_temperature:
            raise ValueError(
                f"temperature (degrees C) is required: the material has a time-temperature shift ({material.shift!r})"
            )
        T = None
        shape = v.shape
    else:
        T = check_temperature(temperature, "temperature")
        try:
            shape = np.broadcast_shapes(T.shape, v.shape)
        except ValueError:
            raise ValueError(
                f"temperature (shape {T.shape}) and velocity (shape {v.shape}) do not broadcast together"
            ) from None
    if q1 is None:
        q1 = float(psd.q_s)
    else:
        q1 = as_positive_scalar(q1, "q1")
        if not psd.q_l * (1 + 1e-9) < q1 <= psd.q_s * (1 + 1e-12):  # (a band narrower than 1e-9 has no panel)
            raise ValueError(
                f"q1 must lie in the spectrum's band: above its lower cut-off {psd.q_l!r} and at most its upper "
                f"cut-off {psd.q_s!r} (1/length); got {q1!r}"
            )
        q1 = min(q1, float(psd.q_s))
    S = _fudge.resolve(fudge)
    modulus_in_G = check_modulus_in_G(modulus_in_G)
    soft = check_strain_softening(strain_softening)

    vb = np.broadcast_to(v, shape).ravel()
    if T is None:
        aT, bT, Tb = np.ones(vb.size), np.ones(vb.size), None
    else:
        Tb = np.broadcast_to(T, shape).ravel()
        aT = 10.0 ** np.broadcast_to(material.log10_aT(Tb), vb.shape)
        bT = np.broadcast_to(material.b_T(Tb), vb.shape).astype(float)
    if not np.all(np.isfinite(vb * aT * q1)) or np.any(vb * aT * psd.q_l <= 0):
        raise ValueError("velocity x a_T(temperature) x q leaves floating-point range; check the units and the shift")
    _coverage(material, psd.q_l, q1, (psd.q_l * vb * aT, q1 * vb * aT))

    try:
        with np.errstate(over="ignore", divide="ignore", invalid="ignore", under="ignore"):  # judged just below
            coarse = _pass(psd, material, sigma0, vb, aT, bT, q1, S, modulus_in_G == "reduced", soft, 1)
            fine = _pass(psd, material, sigma0, vb, aT, bT, q1, S, modulus_in_G == "reduced", soft, 2)
    except FloatingPointError:
        coarse = fine = (np.full(vb.size, np.nan),) * 6
    mu, A, qn, G, G1, P = fine
    if not (np.all(np.isfinite(mu)) and np.all(np.isfinite(coarse[0])) and np.all(np.isfinite(G1))):
        raise ValueError(
            f"sigma0 = {sigma0!r} against the rubber's moduli leaves floating-point range in the friction integrals; "
            "use one pressure unit for sigma0 and the moduli"
        )
    n = qn.size + 2
    q_out = np.concatenate([[psd.q_l], qn, [q1]])
    G_out = np.concatenate([np.zeros((vb.size, 1)), G, G1[:, None]], axis=1)
    P_out = np.concatenate([np.ones((vb.size, 1)), P, A[:, None]], axis=1)
    shift = material.shift
    conventions = {
        "modulus_in_G": modulus_in_G,
        "nu": material.nu,
        "frequency": "omega = q v cos(phi) in rad/s"
        + (f" (master curve given in {material.frequency_unit})" if hasattr(material, "frequency_unit") else ""),
        "shift": "none" if shift is None else f"{shift!r}, T_ref={material.T_ref!r} degC",
        "vertical": "none" if material.vertical is None else repr(material.vertical),
        "psd_convention": f"Persson's isotropic C(q) (the spectrum given as {getattr(psd, 'convention', 'persson')!r})",
        "q0": float(psd.q_l),
        "q1": q1,
        "fudge": S.name,
        "strain_softening": "none" if soft is None else repr(soft),
    }
    return FrictionResult(
        mu=mu.reshape(shape),
        mu_error=np.abs(mu - coarse[0]).reshape(shape),
        contact_area=A.reshape(shape),
        contact_area_error=np.abs(A - coarse[1]).reshape(shape),
        q=q_out,
        G=G_out.reshape((*shape, n)),
        P=P_out.reshape((*shape, n)),
        velocity=np.broadcast_to(v, shape).copy(),
        temperature=None if Tb is None else Tb.reshape(shape),
        sigma0=sigma0,
        q0=float(psd.q_l),
        q1=q1,
        material=material,
        psd=psd,
        conventions=conventions,
    )
