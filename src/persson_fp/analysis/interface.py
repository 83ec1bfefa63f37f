r"""What happens in the gaps: the problem-taking front ends of the interface physics.

:func:`gap_distribution`, :func:`leak_rate`, :func:`contact_conductance` and :func:`adhesive_contact` take a
:class:`~persson_fp.ContactProblem` (its spectrum, E*, loads and fudge model) and call the formulas of
:mod:`persson_fp.theory.gaps`, :mod:`persson_fp.theory.leakage` and :mod:`persson_fp.theory.adhesion`, where the
physics, the references and the checks are written down.  Loads are vectorised: a problem with many p̄ gives
arrays of shape ``(n_loads,)``, a scalar load gives floats.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from persson_fp._errors import SolverError
from persson_fp.analysis.exact import exact
from persson_fp.problems.contact import ContactProblem
from persson_fp.theory import adhesion as _adh
from persson_fp.theory import leakage as _leak
from persson_fp.theory.gaps import GapDistribution
from persson_fp.theory.resolved import MagnificationResolved
from persson_fp.theory.separation import MeanSeparation

__all__ = [
    "gap_distribution",
    "leak_rate",
    "contact_conductance",
    "adhesive_contact",
    "AdhesiveContact",
    "LEAK_METHODS",
]

LEAK_METHODS = ("critical-junction", "effective-medium")
"""Leak-rate estimates (:mod:`persson_fp.theory.leakage`)."""


def _check(problem):
    if not isinstance(problem, ContactProblem):
        raise ValueError(f"problem must be a persson_fp ContactProblem, got {type(problem).__name__}")
    problem.require_elastic("the gap physics")


_RESOLVED: dict = {}


def _resolved(problem, weighting):
    # spectra and responses are immutable values: the rule built for one (spectrum, response, model, weighting)
    # serves every call
    key = (problem.psd, problem.response, problem.fudge, weighting)
    try:
        return _RESOLVED[key]
    except (KeyError, TypeError):
        r = MagnificationResolved(problem.psd, problem.E_star, problem.fudge, weighting, response=problem.response)
        if len(_RESOLVED) > 32:
            _RESOLVED.clear()
        try:
            _RESOLVED[key] = r
        except TypeError:  # an unhashable user model
            pass
        return r


def _out(problem, x):
    x = np.asarray(x, dtype=float)
    return float(x[0]) if problem.scalar_load else x


def gap_distribution(
    problem,
    solution=None,
    weighting: str = "yang-persson",
    n_area: int = 64,
    n_zeta: int = 48,
    weight_cut: float = 1e-4,
) -> GapDistribution:
    r"""The distribution P(u) of the interfacial gap at each load (Almqvist et al., JMPS 59 (2011) 2355).

    Parameters
    ----------
    problem : ContactProblem
        Spectrum, modulus, loads and fudge model (elastic).
    solution : Solution, optional
        A numerical solution of ``problem`` whose stations and areas (``contact_area_all``) replace the model's
        closed-form :math:`A(\zeta)`; its stations must end at zeta_max (``zeta_out`` of :func:`~persson_fp.solve`).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of the separation (:mod:`persson_fp.theory.separation`).
    n_area, n_zeta : int
        Stations uniform in A and log-uniform in ζ, each in [8, 1e6]; with the loads they must fit the
        memory budget of :mod:`~persson_fp.theory.gaps` (4 GiB, the solvers' default: about 384 bytes a load
        and station), else ``ValueError`` with the estimate.
    weight_cut : float
        The first fraction of the non-contact area whose gap the theory cannot resolve (:mod:`~persson_fp.theory.gaps`).

    Returns
    -------
    GapDistribution
        ``pdf(u)``, ``cdf(u)`` (atom included), ``mean``, ``std``, ``contact_fraction``, ``mean_separation``,
        ``u1(zeta)``, ``sample(n)``, ``truncated_weight``, ``truncation_shift``.  The mean differs from
        ``mean_separation`` (the mirror term of the folded normals): both are reported.

    Raises
    ------
    ValueError
        Not an elastic ContactProblem, a bad option, or a solution for another problem.

    Examples
    --------
    >>> import persson_fp as pf
    >>> psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 6.283, 25.13, 402.1)
    >>> gd = pf.gap_distribution(pf.ContactProblem(psd, 1.0, 0.001, fudge="WM17"))
    >>> round(gd.normalisation, 12)
    1.0
    """
    _check(problem)
    r = _resolved(problem, weighting)
    if solution is None:
        gd = GapDistribution(r, problem.p_bar, n_area=n_area, n_zeta=n_zeta, weight_cut=weight_cut)
    else:
        if not hasattr(solution, "contact_area_all") or not hasattr(solution, "problem"):
            raise ValueError(f"solution must be a numerical Solution of this problem, got {type(solution).__name__}")
        if getattr(solution, "problem", None) is not problem and not np.array_equal(
            solution.problem.p_bar, problem.p_bar
        ):
            raise ValueError("solution must be a numerical Solution of this problem (same loads)")
        gd = GapDistribution(
            r, problem.p_bar, weight_cut=weight_cut, zeta=solution.zeta, area=solution.contact_area_all
        )
    gd.scalar = problem.scalar_load
    return gd


def leak_rate(
    problem,
    viscosity,
    pressure_drop,
    aspect: float = 1.0,
    method: str = "critical-junction",
    A_c: float = _leak.A_C_DEFAULT,
    weighting: str = "yang-persson",
    full_output: bool = False,
):
    r"""Volume flow rate of fluid through a seal with nominal contact pressure p̄ (Lorenz & Persson 2009, 2010).

    Parameters
    ----------
    problem : ContactProblem
        The seal's surface, modulus, loads (the nominal contact pressures) and fudge model.
    viscosity : float, pressure x time
        Dynamic viscosity η (> 0), e.g. Pa s.
    pressure_drop : float, pressure
        Δp across the seal (> 0).
    aspect : float, dimensionless
        :math:`L_y/L_x`: seal width over its length along the flow (> 0).
    method : {"critical-junction", "effective-medium"}
        :mod:`persson_fp.theory.leakage`.
    A_c : float
        Percolation threshold of the critical junction, in (0, 1); default 0.42.
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of the separation.
    full_output : bool
        Return a dict with ``flow_rate``, ``effective_gap`` (length), ``sealed``, ``zeta_c`` (critical junction),
        ``effective_gap_error`` (effective medium: an upper estimate of the quadrature's relative error on the
        effective gap; the flow rate's is three times it), ``method`` and ``note`` instead of the flow rate alone.

    Returns
    -------
    float or ndarray, length^3 / time
        Q per load (0 where the seal is closed); or the dict of ``full_output``.

    Raises
    ------
    ValueError
        A bad method, unit value or threshold, or not an elastic ContactProblem.
    """
    _check(problem)
    if method not in LEAK_METHODS:
        raise ValueError(f"method must be one of {list(LEAK_METHODS)}, got {method!r}")
    r = _resolved(problem, weighting)
    zeta_c = gap_err = None
    if method == "critical-junction":
        gap, zeta_c = _leak.critical_junction_gap(r, problem.p_bar, A_c=A_c)
    else:
        if A_c != _leak.A_C_DEFAULT:  # (silently ignored before): Bruggeman's own threshold is 1/2 in 2-D
            raise ValueError(
                f"A_c = {A_c!r} applies to method='critical-junction' only; the effective medium percolates at its "
                "own threshold (2-D Bruggeman: contact fraction 1/2)"
            )
        gap, gap_err = _leak.effective_medium_gap(GapDistribution(r, problem.p_bar), return_error=True)
    Q = _leak.flow_rate(gap, viscosity, pressure_drop, aspect)
    if not full_output:
        return _out(problem, Q)
    return {
        "flow_rate": _out(problem, Q),
        "effective_gap": _out(problem, gap),
        "sealed": gap <= 0 if not problem.scalar_load else bool(gap[0] <= 0),
        "zeta_c": None if zeta_c is None else _out(problem, zeta_c),
        "effective_gap_error": None if gap_err is None else _out(problem, gap_err),
        "method": method,
        "note": "a mean-field estimate; near the percolation threshold (contact area ~0.4-0.5) only the order of "
        "magnitude is meaningful",
    }


def contact_conductance(problem, resistivity=None, thermal_conductivity=None, weighting: str = "yang-persson"):
    r"""Electrical or thermal contact conductance per nominal area (Barber, Proc. R. Soc. A 459 (2003) 53).

    :math:`C = 2K/(E^*(\rho_1+\rho_2))` or :math:`h = 2K/(E^*(1/k_1+1/k_2))` with Persson's stiffness
    :math:`K = -d\bar p/d\bar u` (:func:`~persson_fp.contact_stiffness`).

    Parameters
    ----------
    problem : ContactProblem
        Surface, modulus, loads, fudge model (elastic).
    resistivity : pair of float, resistance x length, optional
        :math:`(\rho_1, \rho_2)`, e.g. Ω m.
    thermal_conductivity : pair of float, power / (length x temperature), optional
        :math:`(k_1, k_2)`, e.g. W/(m K).  Exactly one of the two.
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of the separation.

    Returns
    -------
    float or ndarray
        S/m² (electrical) or W/(m² K) (thermal) in SI units, per load.

    Raises
    ------
    ValueError
        Not exactly one of the two pairs, a value not > 0, or a load at complete contact (unbounded conductance).
    """
    _check(problem)
    ms = MeanSeparation(problem.psd, problem.E_star, problem.fudge, weighting, response=problem.response)
    try:
        K = ms.stiffness(problem.p_bar)
    except ValueError as e:
        raise ValueError(f"{e}; the constriction conductance is unbounded there as well") from None
    E = problem.response.plane_strain_modulus("Barber's relation between stiffness and conductance")
    return _out(problem, _leak.barber_conductance(K, E, resistivity, thermal_conductivity))


@dataclass
class AdhesiveContact:
    r"""Adhesive contact in the DMT limit over the repulsive loads (:mod:`persson_fp.theory.adhesion`).

    Attributes
    ----------
    p_repulsive, p_attractive, p_applied : ndarray, pressure
        :math:`p_{rep}` (the problem's loads), :math:`p_{att}`, :math:`p = p_{rep} - p_{att}` (negative: tensile).
    contact_area : ndarray, dimensionless
        The non-adhesive :math:`A(p_{rep})` (DMT: adhesion does not change the deformation).
    mean_separation : ndarray, length
        The non-adhesive :math:`\bar u(p_{rep})`.
    pull_off : float, pressure
        :math:`-\min_{p_{rep}} p` (>= 0), found by minimisation over :math:`p_{rep}` (not only the problem's loads).
    p_rep_at_pull_off : float, pressure
        Where that minimum is.
    tabor : float
        The Tabor-like parameter; DMT needs it well below 1.
    persson_tosatti, pastewka_robbins : dict
        The stickiness criteria.
    interaction : Interaction
        The traction law.
    info : dict
        ``pull_off_at_edge`` (the minimum at the edge of the searched loads) and ``weighting``.
    """

    p_repulsive: np.ndarray
    p_attractive: np.ndarray
    p_applied: np.ndarray
    contact_area: np.ndarray
    mean_separation: np.ndarray
    pull_off: float
    p_rep_at_pull_off: float
    tabor: float
    persson_tosatti: dict
    pastewka_robbins: dict
    interaction: object
    info: dict = field(default_factory=dict)


def _p_att(r, p, interaction):
    return _adh.attractive_stress(GapDistribution(r, p), interaction)


def adhesive_contact(problem, interaction, weighting: str = "yang-persson", rho=None) -> AdhesiveContact:
    r"""Adhesive rough contact in the DMT limit: load, area and separation curves, pull-off stress.

    The problem's loads are the *repulsive* pressures :math:`p_{rep}`; the applied load is
    :math:`p_{rep} - p_{att}` with :math:`p_{att}` from the gap distribution (:mod:`persson_fp.theory.adhesion`,
    which states the DMT assumption and its validity).

    Parameters
    ----------
    problem : ContactProblem
        Surface, modulus, repulsive loads, fudge model (elastic).
    interaction : Interaction or callable
        ``pf.adhesion.Exponential(w=..., rho=...)``, ``MaugisDugdale(w=..., sigma0=...)``,
        ``LennardJones93(w=..., rho=...)``, or a callable :math:`\sigma_{att}(u) \ge 0` (then give ``rho``).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of the separation.
    rho : float, length, optional
        Range of a callable interaction.

    Returns
    -------
    AdhesiveContact
        Arrays per load (floats for a scalar load) and the pull-off stress.  The pull-off is searched on 121 loads
        log-spaced over :math:`[10^{-6}, 3]\sqrt{V(\zeta_{max})}`; where the least value is at an end, the grid grows
        past that end (20 more points on the same spacing at a time, within :math:`[10^{-30}, 30]\sqrt{V}`) until
        the minimum of :math:`p_{rep} - p_{att}` is bracketed, or (at the low end) until the attraction at the lowest
        load, which bounds what any lower load can pull, cannot beat the minimum found; then bounded Brent
        minimisation in :math:`\ln p_{rep}` refines it (relative tolerance 1e-6 in :math:`p_{rep}`).
        ``info["pull_off_at_edge"]`` says if the first grid had to grow.  The pull-off is resolved to about
        :math:`10^{-12}\sqrt{V}` absolute (below that it is zero).

    Raises
    ------
    ValueError
        Not an elastic ContactProblem, or a bad interaction.
    SolverError
        The minimum lies beyond :math:`[10^{-30}, 30]\sqrt{V}` (the message says on which side): no value from the
        edge is reported.
    """
    _check(problem)
    inter = _adh.resolve_interaction(interaction, rho)
    r = _resolved(problem, weighting)
    ms = MeanSeparation(problem.psd, problem.E_star, problem.fudge, weighting, response=problem.response)
    p = problem.p_bar
    p_att = _p_att(r, p, inter)
    area = exact(problem).contact_area
    sep = ms.mean_separation(p)
    grid = np.sqrt(r.V_max) * np.geomspace(1e-6, 3.0, 121)
    f = grid - _p_att(r, grid, inter)
    k = int(np.argmin(f))
    at_edge = k in (0, grid.size - 1)
    # the minimum at an edge: the search grows there, a decade at a time on the same spacing, until the minimum
    # has a neighbour on each side, within [1e-30, 30] sqrt(V) where the gaps and the attraction are finite
    step = grid[1] / grid[0]
    lo_end, hi_end = 1e-30 * np.sqrt(r.V_max), 30.0 * np.sqrt(r.V_max)
    while k in (0, grid.size - 1):
        down = k == 0
        # below the grid p_rep - p_att >= -p_att(grid[0]) (the attraction grows with the load: a smaller load
        # separates the surfaces further): where that bound cannot beat the minimum found, the search is done
        if down and grid[0] - f[0] <= max(-f[k], 0.0) + 1e-14 * np.sqrt(r.V_max):
            break
        if (grid[0] <= lo_end) if down else (grid[-1] >= hi_end):
            raise SolverError(
                f"the pull-off's minimum of p_rep - p_att lies {'below' if down else 'above'} p_rep = "
                f"{grid[k]:.3g} ({grid[k] / np.sqrt(r.V_max):.3g} sqrt(V)), the end of the loads where the "
                "theory's gaps are finite; the pull-off is not reported from the edge"
            )
        new = grid[0] * step ** -np.arange(20, 0, -1) if down else grid[-1] * step ** np.arange(1, 21)
        f_new = new - _p_att(r, new, inter)
        grid, f = (np.concatenate((new, grid)), np.concatenate((f_new, f))) if down else (
            np.concatenate((grid, new)), np.concatenate((f, f_new)))  # fmt: skip
        k = int(np.argmin(f))
    lo, hi = np.log(grid[max(k - 1, 0)]), np.log(grid[min(k + 1, grid.size - 1)])
    from scipy.optimize import minimize_scalar  # here, not at the top: keeps `import persson_fp` light

    res = minimize_scalar(
        lambda t: float(np.exp(t) - _p_att(r, np.array([np.exp(t)]), inter)[0]),
        bounds=(lo, hi),
        method="bounded",
        options={"xatol": 1e-6},
    )
    p_min, f_min = (float(np.exp(res.x)), float(res.fun)) if res.fun <= f[k] else (float(grid[k]), float(f[k]))
    E = problem.response.plane_strain_modulus("the Tabor parameter and the adhesion criteria")
    return AdhesiveContact(
        p_repulsive=_out(problem, p),
        p_attractive=_out(problem, p_att),
        p_applied=_out(problem, p - p_att),
        contact_area=area,
        mean_separation=_out(problem, sep),
        pull_off=max(-f_min, 0.0),
        p_rep_at_pull_off=p_min,
        tabor=_adh.tabor_parameter(problem.psd, E, inter.w, inter.rho),
        persson_tosatti=_adh.persson_tosatti(problem.psd, E, inter.w),
        pastewka_robbins=_adh.pastewka_robbins(problem.psd, E, inter.w, inter.rho),
        interaction=inter,
        info={"pull_off_at_edge": at_edge, "weighting": weighting},
    )
