r"""Parametric fudge-factor families S(A*; theta) for calibration.

A :class:`Family` turns parameter values theta into a checked
:class:`~persson_fp.theory.fudge.FudgeFactor` (Xu et al. tutorial, ``eq:new_B2``: :math:`B_2 = S(A^*)\,dV/d\zeta`).
It is built from a model name (``"YP08"``, ``"WM17"``, ``"Xu24"``), a fudge-factor class or instance (its
dataclass fields are the parameters), or a user callable ``S(A, *theta)``.

This module imports no solver.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from persson_fp.theory import fudge as _fudge

__all__ = ["Family", "family"]

_X = np.linspace(0.0, 1.0, 20001)[1:-1]
_WM17_GAMMA_MIN = float(np.max((2.0 / 9.0 * _X - 11.0 / 9.0 * _X**2) / (1.0 - _X**2)))
"""Smallest WM17 gamma with S > 0 on [0, 1]: S = gamma (1 - x^2) - 2/9 x + 11/9 x^2, x = A*^2 (about 0.0101)."""

_BOUNDS = {
    ("YP08", "gamma"): (1e-3, 1.0),
    ("Xu24", "gamma"): (1e-3, 1.0),
    ("WM17", "gamma"): (_WM17_GAMMA_MIN * 1.01, 11.0 / 9.0),
}
"""Parameter ranges of the named models (the ranges their constructors accept, open ends moved inside)."""


class Family:
    """A fudge-factor model with free parameters: theta -> FudgeFactor.

    Parameters
    ----------
    name : str
        Label of the model (tables, plots).
    params : tuple of str
        Names of the free parameters, in the order of theta.
    build : callable
        ``build(theta) -> FudgeFactor`` (raises ``ValueError`` for values the model refuses).
    p0 : ndarray
        Start values.
    bounds : (ndarray, ndarray)
        Lower and upper bounds of each parameter (``-inf``/``inf`` where free).
    """

    def __init__(self, name: str, params: tuple, build: Callable, p0, bounds):
        self.name = name
        self.params = tuple(params)
        self._build = build
        self.p0 = np.asarray(p0, dtype=float).reshape(len(self.params))
        lo, hi = (np.broadcast_to(np.asarray(b, dtype=float), self.p0.shape).copy() for b in bounds)
        if np.any(lo >= hi):
            raise ValueError(f"bounds of {name}: each lower bound must be below its upper bound, got {lo}, {hi}")
        self.bounds = (lo, hi)
        if np.any(self.p0 < lo) or np.any(self.p0 > hi):
            raise ValueError(f"start values p0 = {self.p0.tolist()} of {name} lie outside the bounds {lo}, {hi}")

    def __call__(self, theta) -> _fudge.FudgeFactor:
        """The fudge factor at parameter values ``theta`` (a sequence of ``len(params)`` floats)."""
        return self._build(np.asarray(theta, dtype=float))

    def __repr__(self):
        return f"Family({self.name!r}, params={self.params})"


def _dataclass_family(cls, instance, params, p0, bounds):
    fields = {f.name: f for f in dataclasses.fields(cls) if f.name != "name"}
    params = tuple(params)
    for p in params:
        if p not in fields:
            raise ValueError(f"{cls.__name__} has no parameter {p!r}; its parameters: {sorted(fields)}")
    base = instance if instance is not None else cls()
    label = getattr(base, "name", cls.__name__)
    start = [float(getattr(base, p)) for p in params] if p0 is None else p0
    if bounds is None:
        pairs = [_BOUNDS.get((label, p), (-np.inf, np.inf)) for p in params]
        bounds = ([a for a, _ in pairs], [b for _, b in pairs])

    def build(theta):
        fz = dataclasses.replace(base, **{p: float(v) for p, v in zip(params, theta)})
        fz.check()
        return fz

    return Family(label, params, build, start, bounds)


def family(model, params=("gamma",), p0=None, bounds=None) -> Family:
    """The parametric family of a model name, fudge class or instance, or a user callable.

    Parameters
    ----------
    model : str, FudgeFactor class, FudgeFactor instance or callable
        ``"YP08"``, ``"WM17"``, ``"Xu24"`` (case-insensitive); a dataclass subclass of
        :class:`~persson_fp.theory.fudge.FudgeFactor` (or an instance of one: its values start the fit and its
        other fields stay fixed); or a callable ``S(A, *theta)`` returning S > 0 for A* in [0, 1].
    params : sequence of str
        Names of the free parameters (for a callable: the names of its arguments after ``A``).
    p0 : sequence of float, optional
        Start values (required for a callable; default the model's own values).
    bounds : (sequence, sequence), optional
        Lower and upper bounds; default the range the model accepts (``gamma`` of YP08 and Xu24 in
        [1e-3, 1], of WM17 where S > 0 on [0, 1]), else unbounded.

    Returns
    -------
    Family
        theta -> checked fudge factor.

    Raises
    ------
    ValueError
        An unknown model name, a parameter the model does not have, a callable without ``p0``, or start values
        outside the bounds.
    """
    if isinstance(params, str):
        params = (params,)
    params = tuple(params)
    if not params:
        raise ValueError("params must name at least one free parameter")
    if isinstance(model, str):
        key = {k.lower(): k for k in _fudge.MODELS if k != "none"}.get(model.lower())
        if key is None:
            names = [k for k in _fudge.MODELS if k != "none"]
            raise ValueError(
                f"model must be one of {names}, a FudgeFactor class or instance, or a callable; got {model!r}"
            )
        return _dataclass_family(_fudge.MODELS[key], None, params, p0, bounds)
    if isinstance(model, type) and issubclass(model, _fudge.FudgeFactor) and dataclasses.is_dataclass(model):
        return _dataclass_family(model, None, params, p0, bounds)
    if isinstance(model, _fudge.FudgeFactor) and dataclasses.is_dataclass(model):
        return _dataclass_family(type(model), model, params, p0, bounds)
    if callable(model) and not isinstance(model, _fudge.FudgeFactor):
        if p0 is None:
            raise ValueError(f"a callable model S(A, {', '.join(params)}) needs start values p0")
        label = getattr(model, "__name__", "user")

        def build(theta):
            values = tuple(float(v) for v in theta)
            return _fudge.CallableFudge(lambda A: model(A, *values), name=label)

        return Family(label, params, build, p0, bounds if bounds is not None else (-np.inf, np.inf))
    raise ValueError(
        f"model must be a model name, a FudgeFactor dataclass (class or instance) or a callable; got {model!r}"
    )
