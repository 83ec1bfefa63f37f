"""Sweeps: many surfaces x models x loads into one table, on one core or through any executor.

A sweep is a set of independent tasks, one per (surface, model) pair; each task builds one
:class:`~persson_fp.ContactProblem` holding every load and evaluates the requested quantities
(:mod:`persson_fp.sweeps.quantities`) vectorised over the loads.  Tasks run in this process
(``executor=None``) or through any :class:`concurrent.futures.Executor`: a
``ProcessPoolExecutor`` on one machine, a dask.distributed ``Client.get_executor()`` or a Ray
executor on a cluster.  A failing task is recorded with its parameters and the others finish.
The result is a :class:`~persson_fp.sweeps.table.SweepResult` (tidy table, labelled arrays).
"""

from __future__ import annotations

import fnmatch
import inspect
import os
import sys
import time
import traceback
import warnings
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from dataclasses import dataclass, field

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp.analysis.exact import exact
from persson_fp.problems.contact import ContactProblem
from persson_fp.surfaces.psd import PSD
from persson_fp.surfaces.tabulated import TabulatedPSD
from persson_fp.sweeps.quantities import get_quantities
from persson_fp.sweeps.table import SweepResult, TaskFailure
from persson_fp.theory import fudge as _fudge

__all__ = ["sweep", "SweepError", "SweepWarning", "describe_surface"]

_CI_VARIABLES = ("CI", "GITHUB_ACTIONS", "GITLAB_CI", "BUILDKITE", "TF_BUILD", "JENKINS_URL", "TEAMCITY_VERSION")


class SweepError(RuntimeError):
    """Some tasks of a sweep failed and ``errors="raise"`` was asked; ``.result`` holds the rest."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.result = result


class SweepWarning(RuntimeWarning):
    """Some tasks of a sweep failed (``errors="collect"``, the default); see ``result.failures``."""


# -- inputs -------------------------------------------------------------------------------------------
def describe_surface(psd: PSD) -> dict:
    """The description columns of a surface: kind, band, Hurst exponent, rms height and slope.

    ``H`` and ``q_r`` are NaN for a tabulated spectrum; lengths in the spectrum's units.
    """
    return {
        "surface_kind": type(psd).__name__,
        "H": float(getattr(psd, "H", np.nan)),
        "q_l": float(psd.q_l),
        "q_r": float(getattr(psd, "q_r", np.nan)),
        "q_s": float(psd.q_s),
        "zeta_max": float(psd.zeta_max),
        "rms_height": psd.rms_height,
        "rms_slope": psd.rms_slope,
    }


def _read_csv_surface(path) -> PSD:
    return TabulatedPSD.from_csv(path)


def _expand(surfaces, pattern="*.csv"):
    """(label, path or object) for every surface; a folder expands to its sorted files matching ``pattern``."""
    if isinstance(surfaces, (PSD, str, os.PathLike)):
        surfaces = [surfaces]
    if isinstance(surfaces, dict):
        items = [(str(k), v) for k, v in surfaces.items()]
    else:
        try:
            items = [(None, s) for s in surfaces]
        except TypeError:
            raise ValueError(
                f"surfaces must be a PSD, a path, a folder, or a list/dict of them, got {type(surfaces).__name__}"
            ) from None
    out = []
    for i, (label, s) in enumerate(items):
        if isinstance(s, (str, os.PathLike)) and os.path.isdir(s):
            files = sorted(
                f for f in os.listdir(s) if os.path.isfile(os.path.join(s, f)) and fnmatch.fnmatch(f, pattern)
            )
            if not files:
                raise ValueError(f"surfaces: folder {os.fspath(s)!r} holds no files matching {pattern!r}")
            for f in files:
                path = os.path.join(s, f)
                out.append((os.path.splitext(f)[0] if label is None else f"{label}/{os.path.splitext(f)[0]}", path))
        elif isinstance(s, (str, os.PathLike)):
            if not os.path.isfile(s):
                raise ValueError(f"surfaces: no such file or folder {os.fspath(s)!r}")
            out.append((os.path.splitext(os.path.basename(s))[0] if label is None else label, os.fspath(s)))
        else:
            out.append((f"surface{i}" if label is None else label, s))
    return out


def _resolve_surfaces(surfaces, reader, pattern):
    out = []
    for label, s in _expand(surfaces, pattern):
        source = ""
        if isinstance(s, str):
            source, s = s, reader(s)
        if not isinstance(s, PSD):
            raise ValueError(
                f"surfaces: {label!r} must be a SelfAffinePSD/TabulatedPSD or a path the reader accepts, "
                f"got {type(s).__name__}"
            )
        out.append((label, s, {**describe_surface(s), "source": source}))
    labels = [o[0] for o in out]
    if not out:
        raise ValueError("surfaces must hold at least one surface")
    if len(set(labels)) != len(labels):
        dup = next(x for x in labels if labels.count(x) > 1)
        raise ValueError(f"surfaces: the label {dup!r} appears twice (pass a dict label -> surface)")
    return out


SLIDING_KEYWORDS = frozenset({"material", "velocity", "temperature", "modulus_in_G", "strain_softening"})
"""Keywords that make a model a sliding rubber (:func:`persson_fp.sliding_contact`; ``material`` and ``velocity``
required): its problem is the sliding contact problem (``E_star`` is not used), and the quantities ``friction`` and
``sliding_area`` evaluate :func:`persson_fp.rubber_friction` at its loads."""


def _problem_keywords() -> set:
    """ContactProblem's keyword arguments a model may set (all but psd, p_bar and E_star), and a sliding rubber's."""
    return (set(inspect.signature(ContactProblem.__init__).parameters) - {"self", "psd", "p_bar", "E_star"}) | set(
        SLIDING_KEYWORDS
    )


def _value_label(v) -> str:
    if isinstance(v, _fudge.FudgeFactor):
        return v.name
    if isinstance(v, float):
        return f"{v:g}"
    return str(v)


def _resolve_model(spec):
    """(label, ContactProblem keywords, table columns) of one model spec."""
    if isinstance(spec, dict):
        allowed = _problem_keywords()
        bad = sorted(set(spec) - allowed)
        if bad:
            raise ValueError(f"models: unknown ContactProblem keyword(s) {bad}; a model may set {sorted(allowed)}")
        kwargs = dict(spec)
        sliding = set(spec) & SLIDING_KEYWORDS
        if sliding and not {"material", "velocity"} <= set(spec):
            raise ValueError(f"models: a sliding model needs material= and velocity= (got {sorted(sliding)})")
        if sliding and not set(spec) <= SLIDING_KEYWORDS | {"fudge"}:
            bad = sorted(set(spec) - SLIDING_KEYWORDS - {"fudge"})
            raise ValueError(f"models: {bad} cannot be combined with a sliding model's keywords")
    else:
        kwargs = {"fudge": spec}
    kwargs["fudge"] = _fudge.resolve(kwargs.get("fudge"))  # checks a name or a callable here, once
    extra = {k: v for k, v in kwargs.items() if k != "fudge"}
    label = kwargs["fudge"].name
    if extra:
        label = ",".join([f"fudge={label}"] + [f"{k}={_value_label(v)}" for k, v in sorted(extra.items())])
    columns = {"fudge": kwargs["fudge"].name}
    columns.update({k: (v if isinstance(v, (int, float, str)) else _value_label(v)) for k, v in extra.items()})
    return label, kwargs, columns


def _resolve_models(models):
    if models is None or isinstance(models, (str, _fudge.FudgeFactor)) or callable(models):
        models = [models]
    if isinstance(models, dict) and not (set(models) <= _problem_keywords() and models):
        items = [(str(k), v) for k, v in models.items()]
    elif isinstance(models, dict):  # one model given as a dict of keywords
        items = [(None, models)]
    else:
        try:
            items = [(None, m) for m in models]
        except TypeError:
            raise ValueError(
                "models must be a model (None, a fudge-factor name or object, a callable S(A), a dict of "
                f"ContactProblem keywords) or a list / dict (label -> model) of them; got {models!r}"
            ) from None
    out = []
    for label, spec in items:
        auto, kwargs, columns = _resolve_model(spec)
        out.append((auto if label is None else label, kwargs, columns))
    if not out:
        raise ValueError("models must hold at least one model")
    labels = [o[0] for o in out]
    if len(set(labels)) != len(labels):
        dup = next(x for x in labels if labels.count(x) > 1)
        raise ValueError(f"models: two models are labelled {dup!r} (pass a dict label -> model)")
    return out


# -- tasks --------------------------------------------------------------------------------------------
@dataclass
class _Task:
    surface: int
    model: int
    psd: PSD
    kwargs: dict
    E_star: float
    p_bar: np.ndarray
    quantities: list
    method: str
    options: dict


@dataclass
class _TaskResult:
    surface: int
    model: int
    values: dict = field(default_factory=dict)
    errors: list = field(default_factory=list)  # (quantity name or None, "Type: message", traceback text)
    wall_time: float = 0.0


def _error(err) -> str:
    return f"{type(err).__name__}: {err}"


def _run_task(task: _Task) -> _TaskResult:
    """One (surface, model): build the problem, solve it once, evaluate every quantity."""
    res = _TaskResult(task.surface, task.model)
    t0 = time.perf_counter()
    try:
        if "material" in task.kwargs:
            from persson_fp.problems.sliding import sliding_contact

            problem = sliding_contact(task.psd, sigma0=task.p_bar, **task.kwargs)
        else:
            problem = ContactProblem(task.psd, task.E_star, task.p_bar, **task.kwargs)
        if task.method == "exact":
            solution = exact(problem)
        else:
            from persson_fp.solvers import solve

            with warnings.catch_warnings():
                warnings.simplefilter("ignore")  # the Solution records its own warnings in info
                solution = solve(problem, task.method, **task.options)
    except Exception as err:  # noqa: BLE001 - reported with the task's parameters, the sweep goes on
        res.errors.append((None, _error(err), traceback.format_exc()))
        res.wall_time = time.perf_counter() - t0
        return res
    for q in task.quantities:
        try:
            res.values[q.name] = q(problem, solution)
        except Exception as err:  # noqa: BLE001
            res.errors.append((q.name, _error(err), traceback.format_exc()))
    res.wall_time = time.perf_counter() - t0
    return res


def _run_chunk(tasks: list) -> list:
    """Several tasks in one submission (fewer round trips to the executor)."""
    return [_run_task(t) for t in tasks]


def _progress_bar(progress, total):
    """A tqdm bar on stderr when asked, stderr is a terminal, not in CI and tqdm is installed; else None."""
    if not progress:
        return None
    if not getattr(sys.stderr, "isatty", lambda: False)() or any(os.environ.get(v) for v in _CI_VARIABLES):
        return None
    try:
        from tqdm.auto import tqdm
    except ImportError:
        return None
    return tqdm(total=total, unit="task", desc="persson-fp sweep", file=sys.stderr)


def _default_chunksize(n_tasks, executor) -> int:
    if executor is None:
        return 1
    workers = getattr(executor, "_max_workers", None) or os.cpu_count() or 1
    return max(1, n_tasks // (4 * workers))


def _execute(chunks, executor, bar):
    """Yield (chunk, list of _TaskResult) as chunks complete; a chunk that raises marks its tasks failed."""
    if executor is None:
        for chunk in chunks:
            yield chunk, _run_chunk(chunk)
            if bar is not None:
                bar.update(len(chunk))
        return
    futures = {}
    try:
        for chunk in chunks:
            futures[executor.submit(_run_chunk, chunk)] = chunk
        for fut in as_completed(futures):
            chunk = futures[fut]
            try:
                out = fut.result()
            except Exception as err:  # noqa: BLE001 - pickling, a dead worker, a lost cluster node
                tb = traceback.format_exc()
                out = [_TaskResult(t.surface, t.model, errors=[(None, _error(err), tb)]) for t in chunk]
            yield chunk, out
            if bar is not None:
                bar.update(len(chunk))
    finally:
        for fut in futures:
            fut.cancel()


# -- front --------------------------------------------------------------------------------------------
def sweep(
    surfaces,
    loads,
    models=None,
    quantities=("contact_area",),
    method: str = "exact",
    *,
    E_star: float = 1.0,
    relative_loads: bool = False,
    executor=None,
    chunksize: int | None = None,
    progress: bool = True,
    errors: str = "collect",
    surface_reader=None,
    surface_pattern: str = "*.csv",
    **options,
) -> SweepResult:
    """Evaluate quantities of Persson's theory over surfaces x models x loads.

    One task per (surface, model): a :class:`~persson_fp.ContactProblem` with all loads, solved
    once (``method``), every quantity evaluated vectorised over the loads.  Results are identical
    whichever executor runs the tasks.

    Parameters
    ----------
    surfaces : PSD, path, folder, or a list / dict (label -> surface) of them
        Spectra (:class:`~persson_fp.SelfAffinePSD`, :class:`~persson_fp.TabulatedPSD`), CSV files
        with columns ``q,C`` (Persson's isotropic C, length^4) or folders of such files.  Labels:
        the dict keys, file names, else ``surface0``, ``surface1``, ...
    loads : float or 1-D array
        Nominal pressures p_bar (pressure), > 0; with ``relative_loads`` the ratios
        p_bar / sqrt(V(zeta_max)) of each surface (dimensionless, ``eq:Vp_closed_form``).
    models : model or list / dict (label -> model) of models, default ``[None]``
        A model is ``None`` (Persson 2001), a fudge-factor name ("YP08", "WM17", "Xu24"), a
        :class:`~persson_fp.theory.fudge.FudgeFactor`, a callable S(A*) (``eq:new_B2``), or a dict of
        :class:`~persson_fp.ContactProblem` keyword arguments such as ``{"fudge": "YP08"}`` (any
        keyword but psd, p_bar and E_star; new ones of ContactProblem are accepted as they appear), or a sliding
        rubber ``{"material": ..., "velocity": ..., "temperature": ..., "fudge": ...}`` (``SLIDING_KEYWORDS``,
        :func:`persson_fp.sliding_contact`; with the quantities ``friction`` and ``sliding_area``).
        ``models`` itself as a dict is one model when all its keys are such keywords, else labels.
    quantities : str or sequence of str
        Names from ``persson_fp.QUANTITIES`` ("contact_area", "variance",
        "elastic_energy", and more once registered).
    method : str
        ``"exact"`` (closed form, :func:`persson_fp.exact`) or a :func:`persson_fp.solve` method;
        ``**options`` go to that solver.
    E_star : float, pressure
        Plane-strain modulus of every problem, > 0.
    relative_loads : bool
        Read ``loads`` as p_bar / sqrt(V(zeta_max)) per surface.
    executor : None, int or concurrent.futures.Executor
        ``None`` or 1: serial, in this process.  An int n >= 2: a ``ProcessPoolExecutor(n)`` made and
        shut down here.  An executor: tasks are submitted to it (it is left running).
    chunksize : int, optional
        Tasks per submission; default 1 serially, else n_tasks // (4 workers) (at least 1).
    progress : bool
        A tqdm bar over completed tasks; shown only on a terminal, outside CI, with tqdm installed.
    errors : {"collect", "raise"}
        A failed task is recorded in ``result.failures`` (with its surface and model) and the others
        finish; "collect" then warns (``SweepWarning``), "raise" raises :class:`~persson_fp.SweepError`
        carrying the result.
    surface_reader : callable, optional
        ``reader(path) -> PSD`` for file surfaces; default :meth:`TabulatedPSD.from_csv`.
    surface_pattern : str
        Which files of a folder are surfaces (a glob, default ``"*.csv"``).

    Returns
    -------
    SweepResult
        ``result["contact_area"]`` has shape (n_surfaces, n_models, n_loads); ``result.table`` is the
        tidy table (pandas DataFrame, or a dict of column arrays without pandas); ``to_xarray()``,
        ``to_csv()``, ``to_parquet()`` keep units and metadata.

    Raises
    ------
    ValueError
        Bad surfaces, loads, models, quantities, method, ``chunksize``, ``errors`` or
        ``surface_pattern``.
    TypeError
        An option the solver of ``method`` does not take.
    ImportError
        ``method`` needs an optional package that is missing (names the pip extra).
    SweepError
        With ``errors="raise"``, after every task has run, when any failed.

    Notes
    -----
    A cluster's workers need persson-fp installed (tasks travel as pickles naming its functions).
    With ``method="exact"`` A* and Var(p) are the closed forms of Xu, Li, Chen, Zhou, "Persson's
    Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic Process
    Theory" (``eq:Area_Persson``, ``eq:variance_p_form1``) at the effective variance of the model.

    Examples
    --------
    >>> import numpy as np, persson_fp as pf
    >>> psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
    >>> res = pf.sweep([psd], np.array([0.5, 1.0]), models=[None, "YP08"], relative_loads=True, progress=False)
    >>> res.shape
    (1, 2, 2)
    >>> round(float(res["contact_area"][0, 0, 1]), 6)  # erf(1 / sqrt 2)
    0.682689
    """
    t_start = time.perf_counter()
    if errors not in ("collect", "raise"):
        raise ValueError(f"errors must be 'collect' or 'raise', got {errors!r}")
    E_star = as_positive_scalar(E_star, "E_star")
    loads = np.atleast_1d(as_float_array(loads, "loads"))
    if loads.ndim != 1 or loads.size == 0 or np.any(loads <= 0):
        raise ValueError("loads must be a non-empty scalar or 1-D array of values > 0")
    qs = get_quantities(quantities)
    if not isinstance(method, str):
        raise ValueError(f"method must be 'exact' or a solver name, got {method!r}")
    if method != "exact":
        from persson_fp.solvers import METHODS, SHARED_KNOBS, get_solver

        if method not in METHODS:
            raise ValueError(f"method must be 'exact' or one of {sorted(METHODS)}, got {method!r}")
        known = set(get_solver(method).OPTIONS) | set(SHARED_KNOBS)  # (ImportError here for a missing extra)
        bad = sorted(set(options) - known)
        if bad:  # a misspelt option: once, here, rather than once per task
            raise TypeError(f"method {method!r} got unknown option(s) {bad}; it takes {sorted(known)}")
    elif options:
        raise ValueError(f"method='exact' takes no solver options, got {sorted(options)}")
    if not isinstance(surface_pattern, str) or not surface_pattern:
        raise ValueError(f"surface_pattern must be a non-empty glob pattern such as '*.csv', got {surface_pattern!r}")
    surf = _resolve_surfaces(surfaces, surface_reader or _read_csv_surface, surface_pattern)
    mods = _resolve_models(models)

    sqrtV = np.array([float(np.sqrt(psd.V(E_star=E_star))) for _, psd, _ in surf])
    p_bar = np.outer(sqrtV, loads) if relative_loads else np.tile(loads, (len(surf), 1))
    tasks = [  # models inner: a chunk mixes cheap and costly models (the Xu24 / ODE ones cost more)
        _Task(i, j, psd, kwargs, E_star, p_bar[i], qs, method, options)
        for i, (_, psd, _) in enumerate(surf)
        for j, (_, kwargs, _) in enumerate(mods)
    ]

    own = None
    if isinstance(executor, (int, np.integer)) and not isinstance(executor, bool):
        if executor < 1:
            raise ValueError(f"executor must be None, an int >= 1 or an Executor, got {executor!r}")
        executor = None if executor == 1 else ProcessPoolExecutor(max_workers=int(executor))
        own = executor
    elif executor is not None and not isinstance(executor, Executor) and not hasattr(executor, "submit"):
        raise ValueError(f"executor must be None, an int >= 1 or a concurrent.futures.Executor, got {executor!r}")
    if chunksize is None:
        chunksize = _default_chunksize(len(tasks), executor)
    elif not isinstance(chunksize, (int, np.integer)) or chunksize < 1:
        raise ValueError(f"chunksize must be an int >= 1, got {chunksize!r}")
    chunks = [tasks[k : k + chunksize] for k in range(0, len(tasks), chunksize)]

    n_s, n_m, n_l = len(surf), len(mods), loads.size
    values = {q.name: np.full((n_s, n_m, n_l), np.nan) for q in qs}
    ok = {q.name: np.zeros((n_s, n_m), dtype=bool) for q in qs}
    task_time = np.full((n_s, n_m), np.nan)
    failures = []
    bar = _progress_bar(progress, len(tasks))
    try:
        for _chunk, results in _execute(chunks, executor, bar):
            for r in results:
                task_time[r.surface, r.model] = r.wall_time
                for name, arr in r.values.items():
                    values[name][r.surface, r.model] = arr
                    ok[name][r.surface, r.model] = True
                for qname, err, tb in r.errors:
                    failures.append(
                        TaskFailure(
                            surface=surf[r.surface][0],
                            model=mods[r.model][0],
                            quantity=qname,
                            error=err,
                            traceback=tb,
                            surface_index=r.surface,
                            model_index=r.model,
                        )
                    )
    finally:
        if bar is not None:
            bar.close()
        if own is not None:
            own.shutdown(wait=True, cancel_futures=True)
    failures.sort(key=lambda f: (f.surface_index, f.model_index, f.quantity or ""))

    result = SweepResult(
        surfaces=[(label, desc) for label, _, desc in surf],
        models=[(label, columns) for label, _, columns in mods],
        loads=loads,
        relative_loads=bool(relative_loads),
        p_bar=p_bar,
        sqrtV=sqrtV,
        quantities=[(q.name, q.unit, q.description) for q in qs],
        values=values,
        ok=ok,
        failures=failures,
        task_time=task_time,
        metadata={
            "method": method,
            "options": {k: repr(v) for k, v in options.items()},
            "E_star": E_star,
            "executor": "serial" if executor is None else type(executor).__name__,
            "chunksize": int(chunksize),
            "wall_time_s": time.perf_counter() - t_start,
        },
    )
    if failures:
        msg = (
            f"{len(failures)} of {len(tasks) * len(qs)} (task, quantity) evaluations failed; first: "
            f"{failures[0]}; see result.failures"
        )
        if errors == "raise":
            raise SweepError(msg, result)
        warnings.warn(msg, SweepWarning, stacklevel=2)
    return result
