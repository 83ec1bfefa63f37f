r"""The exact solution of a :class:`~persson_fp.ContactProblem`: :class:`ExactSolution` and :func:`exact`.

The closed forms themselves are in :mod:`persson_fp.theory.image` (the image solution of the original and the
fudge-factor theories, Xu et al. tutorial Eqs. 'eq:P0_solution', 'eq:Area_Persson', 'eq:new_B2') and
:mod:`persson_fp.theory.strip` (the strip series with a constant hardness); here they are evaluated for a whole
problem, vectorised over magnifications and loads: arrays have shape ``(n_zeta, n_loads)``, and a scalar zeta or a
scalar load drops its axis.  This module imports no solver.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from scipy.special import erf, erfc

from persson_fp._validate import as_float_array
from persson_fp.problems.contact import ContactProblem
from persson_fp.theory.image import image_pdf, variance_closed_form
from persson_fp.theory.strip import strip_areas, strip_cdf, strip_pdf, strip_quantities

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["ExactSolution", "exact"]


def _check_problem(problem):
    if not isinstance(problem, ContactProblem):
        raise ValueError(f"problem must be a ContactProblem, got {type(problem).__name__}")


class ExactSolution:
    """The exact solution of a :class:`ContactProblem` at magnification(s) ``zeta``.

    Arrays have shape ``(n_zeta, n_loads)``, with a scalar zeta's or a scalar load's axis dropped.

    Parameters
    ----------
    problem : ContactProblem
        The problem (without a moving wall or general coefficients: those have no closed form).
    zeta : float or 1-D array, optional
        Magnification(s) in [1, zeta_max]; default ``zeta_max``.

    Notes
    -----
    Properties (arrays as above):

    - ``zeta``: Magnifications (dimensionless).
    - ``V``: Complete-contact variance V(zeta) (pressure^2), shape ``(n_zeta,)``.
    - ``tau``: Effective variance (pressure^2); equals V without a fudge factor.
    - ``contact_area``: A* = erf(p_bar / sqrt(2 tau)) (Eq. 'eq:Area_Persson'); with a hardness A_el + A_pl.
    - ``atom``: 1 - A*, the probability of p = 0, computed as erfc (Eq. 'eq:PDF_piecewise_explicit').
    - ``elastic_area, plastic_area, noncontact_area``: A_el, A_pl, A_non (they sum to 1); without a hardness
      A_el = A* and A_pl = 0, with a constant hardness the strip series of :mod:`persson_fp.theory.strip`.
    - ``elastic_load, plastic_load``: F_el = int p P0 dp and F_pl = sigma_Y A_pl (pressure); F_el + F_pl = p_bar.
    - ``area_asymptote``: sqrt(2/pi) p_bar / sqrt(tau), the small-load limit (Eq. 'eq:Asymptote_1').
    - ``variance``: Var(p) (pressure^2), Eq. 'eq:variance_p_form1' (int A* dtau with a fudge factor).
    - ``second_moment``: <p^2> = Var + p_bar^2 (pressure^2).
    """

    def __init__(self, problem: ContactProblem, zeta: ArrayLike | None = None):
        if type(problem) is not ContactProblem:
            _check_problem(problem)
        problem.require_closed_form()  # (a moving yield wall or general coefficients: a ValueError naming which)
        self.problem = problem
        if zeta is None:
            # fast path (repeated questions at zeta_max): V(zeta_max) and tau(zeta_max) are cached on the
            # problem, which validated them once; nothing here depends on new input
            self._scalar_zeta = True
            self._zeta = self._V = None  # zeta_max and V_max, read from the problem
            self._tau = problem.tau_max[None, :]  # (1, n_loads), a read-only view
            self._tau_positive = problem.V_max > 0.0  # S > 0: tau > 0 exactly where V > 0
        else:
            z = as_float_array(zeta, "zeta")
            if z.ndim > 1:
                raise ValueError(f"zeta must be a scalar or a 1-D array, got shape {z.shape}")
            self._scalar_zeta = z.ndim == 0
            self._zeta = np.atleast_1d(problem.psd.check_zeta(z))
            self._V = np.atleast_1d(problem.V(self._zeta))
            self._tau = problem.tau_of_V(self._V)  # (n_zeta, n_loads)
            self._tau_positive = bool(np.all(self._V > 0.0))
        self._x = self._A = self._atom = None  # erf / erfc on first use (_areas)
        self._strip = None
        if problem.hardness is not None:  # constant hardness: the strip series (persson_fp.theory.strip)
            pb = problem.p_bar[None, :]
            sig = float(problem.hardness.sigma(1.0))
            self._sigma = sig
            tau_pos = np.where(self._tau > 0, self._tau, 1.0)
            # the absorbed masses alone (no moments); A_el and F_el by the exact balances; <p^2> on first use
            A_non, A_pl = strip_areas(np.broadcast_to(pb, self._tau.shape), sig, tau_pos)
            at1 = self._tau <= 0
            A_non[at1], A_pl[at1] = 0.0, 0.0
            q = {
                "noncontact_area": A_non,
                "plastic_area": A_pl,
                "elastic_area": 1.0 - A_non - A_pl,
                "plastic_load": sig * A_pl,
                "elastic_load": np.broadcast_to(pb, self._tau.shape) - sig * A_pl,
            }
            self._tau_pos = tau_pos
            self._strip = q
            self._A = q["elastic_area"] + q["plastic_area"]
            self._atom = q["noncontact_area"]

    def _areas(self):
        """x = p_bar / sqrt(2 tau) and A* = erf(x), computed on first use (x = inf where tau = 0)."""
        pb = self.problem.p_bar[None, :]
        if self._tau_positive:
            x = pb / np.sqrt(2.0 * self._tau)
        else:
            with np.errstate(divide="ignore"):
                x = np.divide(pb, np.sqrt(2.0 * self._tau), out=np.full(self._tau.shape, np.inf), where=self._tau > 0)
        self._x = x
        if self._strip is None:
            self._A = erf(x)

    def _shape(self, a):
        if self.problem.scalar_load:
            a = a[..., 0]
        if self._scalar_zeta:
            a = a[0]
        return a if np.ndim(a) else float(a)

    @property
    def zeta(self) -> float | np.ndarray:
        """Magnification(s) zeta = q / q_l (dimensionless): a float, or shape ``(n_zeta,)``."""
        if self._zeta is None:
            return float(self.problem.zeta_max)
        return self._zeta[0] if self._scalar_zeta else self._zeta.copy()

    @property
    def p_bar(self) -> float | np.ndarray:
        """Nominal pressure(s) p_bar (pressure): a float for a scalar load, else shape ``(n_loads,)``."""
        return self.problem.p_bar[0] if self.problem.scalar_load else self.problem.p_bar.copy()

    @property
    def V(self) -> float | np.ndarray:
        """Complete-contact variance V(zeta) (pressure^2), Eq. 'eq:Vp_closed_form': a float or ``(n_zeta,)``."""
        if self._V is None:
            return float(self.problem.V_max)
        return self._V[0] if self._scalar_zeta else self._V.copy()

    @property
    def tau(self) -> float | np.ndarray:
        """Effective variance tau = int S dV (pressure^2, Eq. 'eq:new_B2'); equals V without a fudge factor."""
        out = self._shape(self._tau)  # at zeta_max a view of the problem's cache: hand out a copy
        return out.copy() if isinstance(out, np.ndarray) else out

    @property
    def contact_area(self) -> float | np.ndarray:
        """Relative contact area A* = erf(p_bar / sqrt(2 tau)) (Eq. 'eq:Area_Persson'); A_el + A_pl with a hardness."""
        if self._A is None:
            if self._scalar_zeta and self.problem.scalar_load:  # one number: math.erf, no array round trip
                tau = float(self._tau[0, 0])
                return math.erf(float(self.problem.p_bar[0]) / math.sqrt(2.0 * tau)) if tau > 0 else 1.0
            self._areas()
        return self._shape(self._A)

    @property
    def atom(self) -> float | np.ndarray:
        """Probability 1 - A* of p = 0, the out-of-contact fraction (Eq. 'eq:PDF_piecewise_explicit'), via erfc."""
        if self._atom is None:  # erfc(x), not 1 - erf(x): full relative accuracy as A* -> 1
            if self._x is None:
                self._areas()
            self._atom = erfc(self._x)
        return self._shape(self._atom)

    # -- elastoplastic split (a hardness wall; without one: elastic = contact area, plastic = 0) --------
    @property
    def elastic_area(self):
        """A_el = int_0^sigma_Y P0 dp: the elastically loaded fraction of the nominal area."""
        return self._shape(self._area_array() if self._strip is None else self._strip["elastic_area"])

    @property
    def plastic_area(self):
        """A_pl: the fraction in plastic contact (the mass absorbed at the yield wall sigma_Y)."""
        return self._shape(np.zeros(self._tau.shape) if self._strip is None else self._strip["plastic_area"])

    @property
    def noncontact_area(self):
        """A_non = 1 - A_el - A_pl: the fraction out of contact (the atom at p = 0)."""
        return self.atom

    @property
    def elastic_load(self):
        """F_el = int p P0 dp (pressure): the load carried elastically."""
        pb = np.broadcast_to(self.problem.p_bar[None, :], self._tau.shape)
        return self._shape(pb.copy() if self._strip is None else self._strip["elastic_load"])

    @property
    def plastic_load(self):
        """F_pl = sigma_Y A_pl (pressure); F_el + F_pl = p_bar (``eq:Load_equilibrium``)."""
        return self._shape(np.zeros(self._tau.shape) if self._strip is None else self._strip["plastic_load"])

    def _area_array(self) -> np.ndarray:
        """A* with both axes kept, shape ``(n_zeta, n_loads)`` (dimensionless)."""
        if self._A is None:
            self._areas()
        return self._A

    @property
    def area_asymptote(self) -> float | np.ndarray:
        """Small-load limit of the area, sqrt(2/pi) p_bar / sqrt(tau) (Xu et al. tutorial, Eq. 'eq:Asymptote_1')."""
        if self._x is None:
            self._areas()
        with np.errstate(divide="ignore"):
            return self._shape(2.0 / np.sqrt(np.pi) * self._x)

    def _second_moment(self):
        if self._strip is None:
            return variance_closed_form(self.problem.p_bar[None, :], self._tau) + self.problem.p_bar**2
        if "elastic_second_moment" not in self._strip:
            pb = np.broadcast_to(self.problem.p_bar[None, :], self._tau.shape)
            m2 = strip_quantities(pb, self._sigma, self._tau_pos)["elastic_second_moment"]
            m2[self._tau <= 0] = pb[self._tau <= 0] ** 2
            self._strip["elastic_second_moment"] = m2
        return self._strip["elastic_second_moment"] + self._sigma**2 * self._strip["plastic_area"]

    @property
    def variance(self):
        """Var(p) over the whole interface (pressure^2): atoms at 0 and (with a hardness) at sigma_Y included."""
        return self._shape(self._second_moment() - self.problem.p_bar**2)

    @property
    def second_moment(self) -> float | np.ndarray:
        """Second moment <p^2> = Var(p) + p_bar^2 (pressure^2, Eq. 'eq:variance_p_form1'), atoms included."""
        return self._shape(self._second_moment())

    def pdf(self, p: ArrayLike) -> np.ndarray:
        """Continuous part P0(p) of the pressure distribution (Xu et al. tutorial, Eq. 'eq:P0_solution' at tau).

        The image solution (:func:`image_pdf`) at the effective variance tau; with a constant hardness the
        strip series of :mod:`persson_fp.theory.strip` on [0, sigma_Y].  The atom at p = 0 (:attr:`atom`) is not
        part of it (Eq. 'eq:PDF_piecewise_explicit').

        Parameters
        ----------
        p : float or array_like, pressure
            Contact pressure(s), finite; P0 = 0 for p <= 0.

        Returns
        -------
        ndarray, 1/pressure
            P0 of shape ``(n_zeta, n_loads) + p.shape`` with a scalar zeta's or a scalar load's axis dropped.

        Raises
        ------
        ValueError
            A non-finite or non-real ``p``; zeta = 1, where P0 is the delta function delta(p - p_bar).
        """
        p = as_float_array(p, "p")
        if np.any(self._tau <= 0):
            raise ValueError("P0 at zeta = 1 is the delta function delta(p - p_bar); ask for zeta > 1")
        pb = self.problem.p_bar[None, :]
        ext = (Ellipsis,) + (None,) * p.ndim
        if self._strip is not None:
            out = strip_pdf(p, pb[ext], self._sigma, self._tau[ext])
        else:
            out = image_pdf(p, pb[ext], self._tau[ext])
        if self.problem.scalar_load:
            out = out[:, 0]
        if self._scalar_zeta:
            out = out[0]
        return out

    def cdf_contact(self, p: ArrayLike) -> np.ndarray:
        r"""Contact area at pressures up to p, :math:`\int_0^p P_0\,dp'` (Xu et al. tutorial, Eq. 'eq:Area').

        In closed form through erf (Eq. 'eq:P0_solution'); it tends to the elastic area A_el as p grows
        (A* without a hardness).  Cell averages of P0 are differences of it.

        Parameters
        ----------
        p : float or array_like, pressure
            Upper limit(s), finite; values below 0 count as 0.

        Returns
        -------
        ndarray, dimensionless
            The integral, same shape rules as :meth:`pdf`.

        Raises
        ------
        ValueError
            A non-finite or non-real ``p``; zeta = 1, where P0 is the delta function delta(p - p_bar).
        """
        p = np.maximum(as_float_array(p, "p"), 0.0)
        if np.any(self._tau <= 0):
            raise ValueError("P0 at zeta = 1 is the delta function delta(p - p_bar); ask for zeta > 1")
        pb = self.problem.p_bar[None, :]
        ext = (Ellipsis,) + (None,) * p.ndim
        if self._strip is not None:
            out = strip_cdf(p, pb[ext], self._sigma, self._tau[ext])
            if self.problem.scalar_load:
                out = out[:, 0]
            return out[0] if self._scalar_zeta else out
        s = np.sqrt(2.0 * self._tau)[ext]
        # int_0^p [rho(p';pb) - rho(p';-pb)] dp' = [erf((p-pb)/s) + erf(pb/s)]/2 - [erf((p+pb)/s) - erf(pb/s)]/2
        out = 0.5 * (erf((p - pb[ext]) / s) - erf((p + pb[ext]) / s)) + erf(pb[ext] / s)
        if self.problem.scalar_load:
            out = out[:, 0]
        if self._scalar_zeta:
            out = out[0]
        return out

    # -- display (compact: never the arrays) -----------------------------------------------------------------
    def _summary_rows(self) -> list:
        from persson_fp._display import span

        return [
            ("fudge", "fudge", repr(self.problem.fudge.name)),
            ("p_bar", "p_bar (pressure)", span(self.problem.p_bar)),
            ("zeta", "zeta", span(np.atleast_1d(self.zeta))),
            ("V", "V (pressure^2)", span(np.atleast_1d(self.V))),
            ("A", "A*", span(np.atleast_1d(self.contact_area))),
        ]

    def __repr__(self):
        return "ExactSolution(" + ", ".join(f"{k}={v}" for k, _, v in self._summary_rows()) + ")"

    def _repr_html_(self):
        from persson_fp._display import html_table

        rows = [(label, v) for _, label, v in self._summary_rows()]
        return html_table("persson-fp ExactSolution (closed form)", rows)


FULL_CONTACT = 6.0
"""``pf.exact`` warns when every load has p_bar / sqrt(V(zeta_max)) above this (A* > 1 - 2e-9 without a fudge)."""


def exact(problem: ContactProblem, zeta: ArrayLike | None = None) -> ExactSolution:
    """The exact solution of ``problem`` at magnification(s) ``zeta``.

    Persson's closed form (Xu et al. tutorial, Eq. 'eq:P0_solution', Eq. 'eq:Area_Persson'), at the
    effective variance with a fudge factor (Eq. 'eq:new_B2') and as the strip series with a constant
    hardness.  Microseconds per (zeta, load) once the fudge factor's effective-variance map is cached.

    Parameters
    ----------
    problem : ContactProblem
        The problem; not one with a scale-dependent hardness (moving wall) or general coefficients.
    zeta : float or 1-D array, dimensionless, optional
        Magnification(s) in [1, zeta_max]; default ``zeta_max``.

    Returns
    -------
    ExactSolution
        Areas, variances and the distribution P0 (see :class:`ExactSolution`).

    Raises
    ------
    ValueError
        ``problem`` not a :class:`ContactProblem` or without a closed form; ``zeta`` not finite, of more
        than one dimension or outside [1, zeta_max].
    """
    if isinstance(problem, ContactProblem) and problem.V_max > 0:
        x = float(np.min(problem.p_bar)) / math.sqrt(problem.V_max)
        if x >= FULL_CONTACT:
            import warnings

            warnings.warn(
                f"full contact at every load: p_bar / sqrt(V) >= {x:.3g} (V = V(zeta_max) = E*^2 <|grad h|^2> / 4 = "
                f"{problem.V_max:.3g}), so A* = 1; likely p_bar and E_star in different units (p_bar / E_star = "
                f"{float(np.min(problem.p_bar)) / problem.E_star:.3g}) or a spectrum without its short wavelengths "
                f"(rms slope {math.sqrt(4 * problem.V_max) / problem.E_star:.3g})",
                UserWarning,
                stacklevel=2,
            )
    return ExactSolution(problem, zeta)
