r"""The walls of the pressure domain: objects a problem carries and every method asks.

Persson's diffusion equation (Xu et al. tutorial, Eq. 'E:diffusion_equ') lives on a pressure interval whose ends
absorb probability mass.  What an end absorbs is an area: the absorbing wall at p = 0 (Eq. 'E:BC_p0') takes the
non-contact area; a yield wall at the hardness sigma_Y(zeta) takes the plastic contact area (Persson, Phys. Rev.
Lett. 87 (2001) 116101); without a hardness the far end is open (the PDF decays like the image solution,
Eq. 'eq:P0_solution') and a numerical method cuts its grid where the mass left is below double precision, so
whatever reaches that cut is a loss the method reports.

A solver never asks which wall it has.  It asks the wall where it stands (:meth:`Wall.sigma`), where a grid must
end (:meth:`Wall.p_max`, :meth:`Wall.probe_end`), how what the wall absorbed splits into a plastic area and a loss
(:meth:`Wall.plastic_area`, :meth:`Wall.lost_mass`), the strip's load balance (:meth:`Wall.plastic_from_load`),
the effective-variance map of a fudge factor (:meth:`Wall.tau_map`) and what a method must support to solve it
(``Wall.feature``, matched against each method's ``SUPPORTS``).  A new kind of wall -- an adhesive wall at a
negative pressure -sigma_a(zeta) (Persson, Phys. Rev. Lett. 89 (2002) 245502) -- is one more class here.

This module imports no solver.
"""

from __future__ import annotations

import numpy as np
from scipy.special import erf

from persson_fp.theory import fudge as _fudge
from persson_fp.theory import hardness as _hardness
from persson_fp.theory.effective import effective_variance
from persson_fp.theory.strip import StripEffectiveVariance

__all__ = ["Wall", "AbsorbingWall", "OpenEnd", "YieldWall", "MovingYieldWall", "upper_wall"]


class Wall:
    """A boundary of the pressure domain (see the module docstring).

    Attributes
    ----------
    feature : str or None
        What a method must list in its ``SUPPORTS`` to solve a problem with this wall (None: every method does).
    moves : bool
        Whether the wall's position depends on zeta (no closed form then).
    hardness : Hardness or None
        The yield stress model behind a yield wall.
    """

    feature: str | None = None
    moves: bool = False
    mass_back: float = 0.0
    """The fraction of its absorbed mass the wall hands back into the domain as it moves (1 for a moving yield wall,
    whose plastic area sits at the wall and re-enters as sigma_Y grows; 0 for a fixed one)."""
    hardness = None
    description: str = "a wall"

    def check(self, zeta_max: float, p_bar_max: float) -> None:
        """Raise ``ValueError`` if the wall cannot hold the loads (a yield stress at or below a load)."""

    def sigma(self, zeta) -> np.ndarray:
        """The wall's pressure at magnification(s) ``zeta`` (inf for an open end)."""
        return np.full(np.shape(zeta), np.inf)

    def p_max(self, problem, k: float) -> float:
        """The far end of a pressure grid for the whole run: max(p_bar + k sqrt(tau(zeta_max))), where the image
        solution (Xu et al. tutorial, Eq. 'eq:P0_solution') is below exp(-k^2/2) of its peak; a fixed wall is the
        end itself."""
        return float(np.max(problem.p_bar + k * np.sqrt(problem.tau_max)))

    def tau_scale(self, problem) -> float:
        """The width^2 of the PDF at zeta_max a load is measured against: tau(zeta_max) per load (V(zeta_max) for a
        moving wall, where tau has no closed form with a fudge factor)."""
        return problem.tau_max

    def probe_end(self, zeta: float, open_end) -> float:
        """Where the pressure range at magnification ``zeta`` ends: the wall, or ``open_end()`` for an open end."""
        return float(open_end())

    def grid_cut(self, make):
        """``(p_end, info)`` of a numerical grid's far cut: ``make()`` for an open end; ``(None, None)`` at a yield
        wall (the wall is the end, it moves with zeta)."""
        return make()

    def front(self, problem, V, p_end: float):
        """The grid's far end s and ds/dV (pressure, 1/pressure) at complete-contact variances ``V`` (an array):
        the cut ``p_end`` for an open end, sigma_Y(zeta(V)) for a yield wall."""
        V = np.atleast_1d(np.asarray(V, dtype=float))
        return np.full(V.shape, p_end), np.zeros(V.shape)

    def loss(self, absorbed):
        """What reached the grid's far cut, a numerical loss (None at a physical wall, which absorbs area)."""
        return absorbed

    def plastic_area(self, absorbed):
        """The plastic contact area of what the wall absorbed (None: the wall makes none)."""
        return None

    def lost_mass(self, absorbed):
        """The part of what the far end absorbed that is a numerical loss (zeros at a physical wall)."""
        return absorbed

    def solution_areas(self, zeta, elastic_area, plastic_area):
        """``(sigma_Y, A_pl, A*)`` of a solution with the elastic area ``elastic_area`` (n_zeta, n_loads) at the
        stations ``zeta`` and the absorbed ``plastic_area`` (or None): no wall, no plastic area, A* = A_el."""
        return None, None, elastic_area

    def strip_sigma(self):
        """The constant yield stress that bounds the strip (pressure), None without a yield wall."""
        return None

    def plastic_from_load(self, p_bar, elastic_load):
        """The strip's load balance F_el + sigma_Y A_pl = p_bar solved for A_pl (None without a yield wall)."""
        return None

    def contact_for_fudge(self, P, w, p, p_bar):
        """The contact area that the fudge factor S sees for a PDF ``P`` (..., n) on nodes ``p`` with weights
        ``w`` and the load ``p_bar``: the elastic area, plus the plastic one at a constant hardness (from the load
        balance F_el + sigma_Y A_pl = p_bar)."""
        return P @ w

    def fudge_area_weights(self, w, p, p_bar):
        """(wA, a0) with :meth:`contact_for_fudge` = P . wA + a0 for every load at once (``p_bar`` (m,))."""
        return w, np.zeros(np.shape(p_bar))

    def tau_map(self, problem):
        """The effective-variance map tau(V) = int S(A*) dV of a fudge factor (Xu et al. tutorial,
        Eq. 'eq:new_B2') for ``problem`` with this wall: an object with ``tau(V)`` and ``V_of_tau(tau)``."""
        return _OpenMap(problem)

    def repr_part(self) -> str:
        """What ``ContactProblem.__repr__`` adds for this wall."""
        return ""

    def require_closed_form(self, remedy: str) -> None:
        """Raise ``ValueError`` (ending in ``remedy``) where this wall leaves no closed form (a moving wall)."""

    def require_elastic(self, what: str, remedy: str = "") -> None:
        """Raise ``ValueError`` where ``what`` (a theory of the purely elastic contact) does not cover this wall;
        ``remedy``: what to do instead (appended)."""


class AbsorbingWall(Wall):
    """Persson's wall at p = 0 (Xu et al. tutorial, Eq. 'E:BC_p0', P(0, zeta) = 0): what it absorbs is the
    non-contact area."""

    description = "the absorbing wall at p = 0"

    def sigma(self, zeta) -> np.ndarray:
        return np.zeros(np.shape(zeta))


class OpenEnd(Wall):
    """No wall: the PDF decays towards large pressures (purely elastic contact).  A numerical grid ends at
    max(p_bar + k sqrt(tau(zeta_max))) and what reaches that end is a loss the method reports."""

    description = "no yield wall (purely elastic)"


class YieldWall(Wall):
    """A constant yield stress sigma_Y: the strip problem, exact in closed form (:mod:`persson_fp.theory.strip`);
    what the wall absorbs is the plastic contact area."""

    feature = "hardness"
    description = "a hardness wall"

    def __init__(self, hardness: _hardness.Hardness):
        self.hardness = hardness
        self._sigma1 = None

    def check(self, zeta_max: float, p_bar_max: float) -> None:
        self.hardness.check(zeta_max, p_bar_max)

    def sigma(self, zeta) -> np.ndarray:
        return self.hardness.sigma(zeta)

    def p_max(self, problem, k: float) -> float:
        return float(self.hardness.sigma(1.0))  # the strip: the yield wall is the domain's end

    def plastic_area(self, absorbed):
        return absorbed

    def lost_mass(self, absorbed):
        return np.zeros(np.shape(absorbed))

    def loss(self, absorbed):
        return None

    def probe_end(self, zeta: float, open_end) -> float:
        return float(self.hardness.sigma(zeta))

    def grid_cut(self, make):
        return None, None

    def front(self, problem, V, p_end=None):
        V = np.atleast_1d(np.asarray(V, dtype=float))
        kernels = problem.V_kernels
        z = np.atleast_1d(kernels.zeta_of_V(V))
        s = self.hardness.sigma(z)
        dV = kernels.dV_dzeta(z)
        sV = np.where(dV > 0, self.hardness.dsigma_dzeta(z) / np.where(dV > 0, dV, 1.0), 0.0)
        return s, sV

    def strip_sigma(self):
        return float(self.hardness.sigma(1.0))

    def solution_areas(self, zeta, elastic_area, plastic_area):
        sigma_Y = np.atleast_1d(self.hardness.sigma(zeta)).astype(float)
        if plastic_area is None:
            plastic_area = np.zeros_like(elastic_area)
        plastic_area = np.asarray(plastic_area, dtype=float).reshape(elastic_area.shape)
        return sigma_Y, plastic_area, elastic_area + plastic_area

    def plastic_from_load(self, p_bar, elastic_load):
        # (clipped at 0: the quadrature error of F_el may push a vanishing A_pl a little below)
        return np.maximum((p_bar - elastic_load) / self.sigma_1, 0.0)

    def contact_for_fudge(self, P, w, p, p_bar):
        return P @ w + (p_bar - P @ (w * p)) / self.sigma_1

    def fudge_area_weights(self, w, p, p_bar):
        return w - w * p / self.sigma_1, p_bar / self.sigma_1

    @property
    def sigma_1(self) -> float:
        """sigma_Y(1) (pressure): the whole wall of a constant hardness."""
        if self._sigma1 is None:
            self._sigma1 = float(self.hardness.sigma(1.0))
        return self._sigma1

    def tau_map(self, problem):
        return StripEffectiveVariance(problem.fudge.S, problem.p_bar, float(self.hardness.sigma(1.0)), problem.V_max)

    def repr_part(self) -> str:
        return f", hardness={self.hardness!r}"

    def require_elastic(self, what: str, remedy: str = "") -> None:
        raise ValueError(f"{what} is the elastic theory's: a problem with a hardness is not covered{remedy}")


class MovingYieldWall(YieldWall):
    """A scale-dependent yield stress sigma_Y(zeta): a moving wall, no closed form (the PDE solvers solve it)."""

    feature = "moving_wall"
    moves = True
    mass_back = 1.0
    description = "a scale-dependent hardness (moving yield wall)"

    def p_max(self, problem, k: float) -> float:
        return Wall.p_max(self, problem, k)

    def tau_scale(self, problem) -> float:
        return problem.V_max

    def require_closed_form(self, remedy: str) -> None:
        raise ValueError(
            f"a scale-dependent hardness ({self.hardness!r}) is a moving yield wall with no closed form; {remedy}"
        )

    def tau_map(self, problem):
        raise ValueError(
            "a scale-dependent hardness with a fudge factor has no closed-form effective variance: the "
            "area that S depends on comes from the numerical solution (pf.solve(problem, method='fv'))"
        )


def upper_wall(hardness) -> Wall:
    """The wall at the high-pressure end for a user's ``hardness=`` argument
    (:func:`persson_fp.theory.hardness.resolve`)."""
    h = _hardness.resolve(hardness)
    if h is None:
        return OpenEnd()
    return YieldWall(h) if h.is_constant else MovingYieldWall(h)


class _OpenMap:
    """tau(V) of a fudge factor without a yield wall: Xu24 in closed form, the others by the cached ODE table of
    :mod:`persson_fp.theory.effective`."""

    def __init__(self, problem):
        self.problem = problem

    def tau(self, V):
        pr = self.problem
        if isinstance(pr.fudge, _fudge.Xu24):
            return pr.fudge.g(pr.fudge.area(pr.p_bar, V)) * V
        return effective_variance(pr.fudge).tau(pr.p_bar, V)

    def V_of_tau(self, tau):
        pr = self.problem
        if isinstance(pr.fudge, _fudge.Xu24):
            with np.errstate(divide="ignore"):
                A = erf(np.divide(pr.p_bar, np.sqrt(2.0 * tau), out=np.full(tau.shape, np.inf), where=tau > 0))
            return tau / pr.fudge.g(A)
        return effective_variance(pr.fudge).V_of_tau(pr.p_bar, tau)
