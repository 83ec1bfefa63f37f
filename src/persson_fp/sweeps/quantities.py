"""The quantities a sweep tabulates: a plain registry, name -> :class:`Quantity`.

Each quantity is a function ``func(problem, solution) -> array (n_loads,)`` evaluated once per
(surface, model) task, vectorised over the loads of ``problem``.  ``solution`` is what the sweep's
method produced at zeta_max: an :class:`~persson_fp.ExactSolution` for ``method="exact"``, else a
numerical :class:`~persson_fp.Solution`.

Built in (Xu, Li, Chen, Zhou, "Persson's Theory of Purely Normal Elastic Rough Surface Contact: A
Tutorial Based on Stochastic Process Theory"):

- ``"contact_area"``: relative contact area A* (``eq:Area_Persson``; the method's own A* = int P0 dp
  for a numerical method, ``eq:Area``);
- ``"variance"``: Var(p) of the interface pressure, atom at p = 0 included (``eq:variance_p_form1``);
- ``"elastic_energy"``: U_el / A_n (``eq:Uel_original``), always by the closed-form quadrature of
  :func:`persson_fp.elastic_energy` (the method does not enter).

When :mod:`persson_fp.analysis.separation` is installed (mean interfacial separation, Persson, PRL 99 (2007)
125502; Yang & Persson, J. Phys.: Condens. Matter 20 (2008) 215214), ``"mean_separation"`` and
``"stiffness"`` are registered too.  What happens in the gaps (:mod:`persson_fp.analysis.interface`):
``"gap_mean"`` (mean of P(u)), ``"leak_rate"`` (critical junction, Q eta/dp = u_c^3/12 for a square seal),
``"conductance"`` (Barber's C (rho1 + rho2) = 2K/E*) and ``"pull_off"`` (DMT, an exponential law with
w = 0.1 U_el of full contact and rho = h_rms; register your own law with ``functools.partial`` of
:func:`persson_fp.adhesive_contact`).  Add your own with :func:`register_quantity`; a function used
with a process pool or a cluster must be importable by name (a module-level ``def``, not a lambda).
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from persson_fp.analysis.energy import elastic_energy

__all__ = ["Quantity", "QUANTITIES", "register_quantity", "get_quantities"]


@dataclass(frozen=True)
class Quantity:
    """One column family of a sweep table.

    Attributes
    ----------
    name : str
        Registry key and the ``quantity`` column of the tidy table.
    func : callable
        ``func(problem, solution) -> array of shape (n_loads,)``.
    unit : str
        Unit in words ("1", "pressure^2", "pressure*length", ...): persson-fp works in any consistent
        unit system, so the unit names the dimension of the value.
    description : str
        One line, with the equation it evaluates.
    """

    name: str
    func: Callable
    unit: str
    description: str = ""

    def __call__(self, problem, solution) -> np.ndarray:
        out = np.asarray(self.func(problem, solution), dtype=float)
        n = problem.n_loads
        if out.size % n or out.size == 0:
            raise ValueError(f"quantity {self.name!r} returned shape {out.shape}, expected ({n},) (one per load)")
        return out.reshape(-1, n)[-1].copy()  # the last station (zeta_max) of a numerical Solution


def _contact_area(problem, solution):
    return solution.contact_area


def _variance(problem, solution):
    return solution.variance


def _elastic_energy(problem, solution):
    return elastic_energy(problem)


QUANTITIES: dict[str, Quantity] = {}
"""Quantity name -> :class:`Quantity` (filled at import, extended by :func:`register_quantity`)."""


def register_quantity(name: str, func: Callable, unit: str, description: str = "", overwrite: bool = False) -> Quantity:
    """Make ``name`` available to :func:`persson_fp.sweep`.

    Parameters
    ----------
    name : str
        Registry key (non-empty).
    func : callable
        ``func(problem, solution) -> (n_loads,) array`` (see the module docstring).  For process
        pools and clusters it must pickle by reference: a module-level function.
    unit : str
        The value's unit (dimension) as text.
    description : str
        One line for the table's metadata.
    overwrite : bool
        Replace an existing entry (else a ``ValueError``).

    Returns
    -------
    Quantity
    """
    if not isinstance(name, str) or not name:
        raise ValueError(f"name must be a non-empty string, got {name!r}")
    if not callable(func):
        raise ValueError(f"func must be callable (problem, solution) -> array, got {func!r}")
    if not isinstance(unit, str):
        raise ValueError(f"unit must be a string, got {unit!r}")
    if name in QUANTITIES and not overwrite:
        raise ValueError(f"quantity {name!r} is already registered (pass overwrite=True to replace it)")
    q = Quantity(name, func, unit, description)
    QUANTITIES[name] = q
    return q


def get_quantities(names) -> list[Quantity]:
    """Resolve names (or :class:`Quantity` objects) to a list, refusing unknown names and duplicates."""
    if isinstance(names, (str, Quantity)):
        names = [names]
    out = []
    for n in names:
        if isinstance(n, Quantity):
            q = n
        elif n in QUANTITIES:
            q = QUANTITIES[n]
        else:
            raise ValueError(f"quantities: unknown name {n!r}; registered: {sorted(QUANTITIES)}")
        if any(q.name == o.name for o in out):
            raise ValueError(f"quantities: {q.name!r} is asked for twice")
        out.append(q)
    if not out:
        raise ValueError("quantities must name at least one quantity")
    return out


register_quantity("contact_area", _contact_area, "1", "relative contact area A* at zeta_max (eq:Area_Persson)")
register_quantity(
    "variance", _variance, "pressure^2", "Var(p) at zeta_max, atom at p = 0 included (eq:variance_p_form1)"
)
register_quantity(
    "elastic_energy", _elastic_energy, "pressure*length", "U_el/A_n, closed-form quadrature (eq:Uel_original)"
)


# -- mean separation and stiffness, once persson_fp.analysis.separation exists -------------------------------
def _separation_module():
    return importlib.import_module("persson_fp.analysis.separation")


def _mean_separation(problem, solution):
    return _separation_module().mean_separation(problem)


def _stiffness(problem, solution):
    return _separation_module().contact_stiffness(problem)


def _register_separation(module) -> list:
    """Register "mean_separation" / "stiffness" when ``module`` provides them; the names added."""
    added = []
    if module is not None and hasattr(module, "mean_separation") and "mean_separation" not in QUANTITIES:
        register_quantity(
            "mean_separation",
            _mean_separation,
            "length",
            "mean interfacial separation u(p_bar) (Persson, PRL 99 (2007) 125502)",
        )
        added.append("mean_separation")
    if module is not None and hasattr(module, "contact_stiffness") and "stiffness" not in QUANTITIES:
        register_quantity(
            "stiffness",
            _stiffness,
            "pressure/length",
            "normal contact stiffness per area K = -dp_bar/du (Persson 2007)",
        )
        added.append("stiffness")
    return added


try:  # guarded: the module may not be there yet (any other import error inside it is not hidden)
    _register_separation(_separation_module())
except ModuleNotFoundError as _err:  # pragma: no cover - depends on the installed version
    if _err.name != "persson_fp.analysis.separation":
        raise


# -- what happens in the gaps (persson_fp.analysis.interface) --------------------------------------------------
def _interface():
    return importlib.import_module("persson_fp.analysis.interface")


def _gap_mean(problem, solution):
    return _interface().gap_distribution(problem).mean


def _leak_rate(problem, solution):
    return _interface().leak_rate(problem, viscosity=1.0, pressure_drop=1.0)


def _conductance(problem, solution):
    return _interface().contact_conductance(problem, resistivity=(0.5, 0.5))


def _pull_off(problem, solution):
    from persson_fp.theory.adhesion import Exponential

    w = 0.1 * float(problem.psd.elastic_energy_complete(E_star=problem.E_star))
    ad = _interface().adhesive_contact(problem, Exponential(w=w, rho=problem.psd.rms_height))
    return np.full(problem.n_loads, ad.pull_off)


register_quantity(
    "gap_mean", _gap_mean, "length", "mean of the gap distribution P(u) (Almqvist et al., JMPS 59 (2011) 2355)"
)
register_quantity(
    "leak_rate",
    _leak_rate,
    "length^3/time per (pressure drop/viscosity)",
    "critical-junction leak rate Q eta/dp = u_c^3/12, aspect 1 (Lorenz & Persson, EPJE 31 (2010) 159)",
)
register_quantity(
    "conductance",
    _conductance,
    "1/length per resistivity",
    "electrical conductance per area C (rho1 + rho2) = 2K/E* (Barber, Proc. R. Soc. A 459 (2003) 53)",
)
register_quantity(
    "pull_off",
    _pull_off,
    "pressure",
    "DMT pull-off stress, exponential law w = 0.1 U_el(full contact), rho = h_rms (same for every load)",
)


# -- rubber friction (persson_fp.analysis.friction) ---------------------------------------------------------------
def _friction_of(problem, what: str) -> np.ndarray:
    """``what`` of :func:`persson_fp.rubber_friction` at each load of a sliding problem (the model's fudge factor
    as the weight S(P) of the friction integrand)."""
    from persson_fp.analysis.friction import rubber_friction
    from persson_fp.theory.sliding import SlidingViscoelastic

    resp = problem.response
    if not isinstance(resp, SlidingViscoelastic):
        raise ValueError(
            f"{what} needs a sliding model: a model dict with material= and velocity= (and temperature= for a "
            "material with a shift law)"
        )
    out = [
        getattr(
            rubber_friction(problem.psd, resp.material, float(p), resp.velocity, resp.temperature,
                            fudge=problem.fudge, modulus_in_G=resp.modulus_in_G,
                            strain_softening=resp.strain_softening),
            what,
        )
        for p in np.atleast_1d(problem.p_bar)
    ]  # fmt: skip
    return np.array(out, dtype=float)


def _friction(problem, solution):
    return _friction_of(problem, "mu")


def _sliding_area(problem, solution):
    return _friction_of(problem, "contact_area")


register_quantity(
    "friction",
    _friction,
    "1",
    "viscoelastic friction coefficient mu of a sliding model (Persson, J. Chem. Phys. 115 (2001) 3840; isothermal, "
    "hysteretic part only)",
)
register_quantity(
    "sliding_area",
    _sliding_area,
    "1",
    "sliding contact area A/A0 = P(q1) of a sliding model (Persson 2001; independent of the fudge factor)",
)
