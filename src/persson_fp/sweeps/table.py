"""The result of :func:`persson_fp.sweep`: labelled arrays, a tidy table, writers that keep the metadata.

pandas, xarray and pyarrow are optional: they are imported only by the methods that need them
(``to_pandas``, ``to_xarray``, ``to_parquet``).  Without pandas :attr:`SweepResult.table` is a plain
dict of column arrays and :meth:`SweepResult.to_csv` still works.
"""

from __future__ import annotations

import csv
import datetime
import html
import json
import os
from dataclasses import dataclass

import numpy as np

__all__ = ["SweepResult", "TaskFailure", "read_table"]

_CSV_TAG = "# persson-fp sweep table; metadata (JSON) on the next line"
"""First line of the tables written before the metadata moved to a sidecar file (still read)."""


def metadata_path(path) -> str:
    """The sidecar file of a CSV table's metadata: ``<path>.json``."""
    return str(path) + ".json"


@dataclass(frozen=True)
class TaskFailure:
    """One failed (surface, model) task, or one failed quantity of it (``quantity`` set).

    Attributes
    ----------
    surface, model : labels of the task's parameters
    quantity : the quantity that raised, or None when the problem or its solution failed
    error : "ExceptionType: message"
    traceback : the formatted traceback (from the worker process where there was one)
    surface_index, model_index : positions on the result's axes
    """

    surface: str
    model: str
    quantity: str | None
    error: str
    traceback: str = ""
    surface_index: int = -1
    model_index: int = -1

    def __str__(self):
        what = "" if self.quantity is None else f", quantity={self.quantity!r}"
        return f"surface={self.surface!r}, model={self.model!r}{what}: {self.error}"


def _version() -> str:
    from persson_fp._version import __version__

    return __version__


class SweepResult:
    """Quantities over surfaces x models x loads (built by :func:`persson_fp.sweep`).

    ``result[name]`` is an array (n_surfaces, n_models, n_loads), NaN where a task failed.

    Attributes
    ----------
    surfaces : list of str
        Surface labels (axis 0).
    models : list of str
        Model labels (axis 1).
    loads : ndarray
        The loads as given (axis 2): p_bar (pressure), or p_bar / sqrt(V) with ``relative_loads``.
    relative_loads : bool
        Whether ``loads`` are relative, p_bar / sqrt(V(zeta_max)).
    p_bar : ndarray (n_surfaces, n_loads)
        Nominal pressure of every (surface, load) (pressure).
    sqrtV : ndarray (n_surfaces,)
        sqrt(V(zeta_max)) per surface (pressure), ``eq:Vp_closed_form``.
    quantities : list of str
        The quantity names; ``units[name]`` gives each unit.
    failures : list of TaskFailure
        What failed, with the task's parameters.
    task_time : ndarray (n_surfaces, n_models)
        Seconds per task, measured where it ran.
    metadata : dict
        Method, options, E_star, executor, versions, wall time; written with every table.
    values : dict
        Quantity name -> array (n_surfaces, n_models, n_loads) (read through ``result[name]``).
    ok : ndarray of bool (n_surfaces, n_models)
        Whether each task succeeded.
    """

    def __init__(
        self,
        surfaces,
        models,
        loads,
        relative_loads,
        p_bar,
        sqrtV,
        quantities,
        values,
        ok,
        failures,
        task_time,
        metadata,
    ):
        self.surfaces = [s for s, _ in surfaces]
        self.surface_info = [d for _, d in surfaces]
        self.models = [m for m, _ in models]
        self.model_info = [c for _, c in models]
        self.loads = np.asarray(loads, dtype=float)
        self.relative_loads = relative_loads
        self.p_bar = np.asarray(p_bar, dtype=float)
        self.sqrtV = np.asarray(sqrtV, dtype=float)
        self.quantities = [q for q, _, _ in quantities]
        self.units = {q: u for q, u, _ in quantities}
        self.descriptions = {q: d for q, _, d in quantities}
        self._values = values
        self.ok = ok
        self.failures = list(failures)
        self.task_time = task_time
        self.metadata = {
            "package": "persson-fp",
            "version": _version(),
            "created": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
            **metadata,
            "relative_loads": relative_loads,
            "units": dict(self.units),
            "descriptions": dict(self.descriptions),
            "n_failures": len(self.failures),
            "failures": [str(f) for f in self.failures],
        }

    # -- arrays -----------------------------------------------------------------------------------------
    def __getitem__(self, name) -> np.ndarray:
        if name not in self._values:
            raise KeyError(f"{name!r} is not in this sweep; quantities: {self.quantities}")
        return self._values[name]

    @property
    def shape(self) -> tuple:
        """(n_surfaces, n_models, n_loads)."""
        return (len(self.surfaces), len(self.models), self.loads.size)

    def _columns(self) -> dict:
        """Column name -> 1-D array, or (codes, categories) for a label column (expanded by the callers)."""
        n_s, n_m, n_l = self.shape
        ok = np.stack([self.ok[q] for q in self.quantities], axis=-1)  # (n_s, n_m, n_q), C order = row order
        s_idx, m_idx, q_idx = np.nonzero(ok)
        vals = np.stack([self._values[q] for q in self.quantities], axis=2)[s_idx, m_idx, q_idx]  # (n_rows, n_l)
        si, mi, qi = (np.repeat(a, n_l) for a in (s_idx, m_idx, q_idx))
        li = np.tile(np.arange(n_l), s_idx.size)
        out = {"surface": (si, self.surfaces)}
        for key in self.surface_info[0]:
            col = [d[key] for d in self.surface_info]
            out[key] = (si, col) if isinstance(col[0], str) else np.asarray(col, dtype=float)[si]
        out["model"] = (mi, self.models)
        model_keys = []
        for c in self.model_info:
            model_keys += [k for k in c if k not in model_keys]
        for key in model_keys:
            col = [c.get(key, "") for c in self.model_info]
            out[key] = (mi, [str(v) for v in col]) if any(isinstance(v, str) for v in col) else np.asarray(col)[mi]
        out["method"] = (np.zeros(si.size, dtype=int), [self.metadata["method"]])
        out["E_star"] = np.full(si.size, float(self.metadata["E_star"]))
        out["load_index"] = li
        out["p_bar"] = self.p_bar[si, li]
        out["p_bar_over_sqrtV"] = self.p_bar[si, li] / self.sqrtV[si]
        out["quantity"] = (qi, self.quantities)
        out["value"] = vals.ravel()
        out["unit"] = (qi, [self.units[q] for q in self.quantities])
        return out

    def to_dict(self) -> dict:
        """The tidy table as a dict of equal-length 1-D arrays (no pandas needed).

        One row per surface x model x quantity x load of every task that succeeded, in that order.
        Columns: surface, its description (surface_kind, H, q_l, q_r, q_s, zeta_max, rms_height,
        rms_slope, source), model, fudge (and any other model keyword), method, E_star, load_index,
        p_bar, p_bar_over_sqrtV, quantity, value, unit.  Labels are object arrays of str.

        Returns
        -------
        dict of str to ndarray
            Column name -> column.
        """
        return {
            k: (np.array(v[1], dtype=object)[v[0]] if isinstance(v, tuple) else v) for k, v in self._columns().items()
        }

    def to_pandas(self):
        """The tidy table as a pandas DataFrame (label columns categorical), metadata in ``df.attrs``.

        Needs pandas.

        Returns
        -------
        pandas.DataFrame
            One row per surface x model x quantity x load.
        """
        pd = _need("pandas", "pandas")
        cols = {
            k: (pd.Categorical.from_codes(*_unique_codes(*v)) if isinstance(v, tuple) else v)
            for k, v in self._columns().items()
        }
        df = pd.DataFrame(cols)
        df.attrs = _jsonable(self.metadata)
        return df

    @property
    def table(self):
        """The tidy table: a pandas DataFrame when pandas is installed, else a dict of column arrays (built anew
        on each access; keep it in a variable)."""
        try:
            import pandas  # noqa: F401
        except ImportError:
            return self.to_dict()
        return self.to_pandas()

    def to_xarray(self):
        """An ``xarray.Dataset``: one variable per quantity on (surface, model, load), units in attrs.

        Coordinates: surface labels and descriptions, model labels, the loads as given, p_bar
        (surface, load); failed tasks are NaN.  Needs xarray.

        Returns
        -------
        xarray.Dataset
            One variable per quantity.
        """
        xr = _need("xarray", "xarray")
        coords = {"surface": self.surfaces, "model": self.models, "load": self.loads}
        for key in self.surface_info[0]:
            coords[key] = ("surface", [d[key] for d in self.surface_info])
        coords["p_bar"] = (("surface", "load"), self.p_bar)
        coords["sqrtV"] = ("surface", self.sqrtV)
        dims = ("surface", "model", "load")
        data = {
            q: (dims, self._values[q], {"units": self.units[q], "long_name": self.descriptions[q]})
            for q in self.quantities
        }
        attrs = {
            k: (v if isinstance(v, (str, int, float)) else json.dumps(_jsonable(v))) for k, v in self.metadata.items()
        }
        attrs["relative_loads"] = int(self.relative_loads)
        return xr.Dataset(data, coords=coords, attrs=attrs)

    # -- writers ------------------------------------------------------------------------------------------
    def to_csv(self, path) -> None:
        """Write the tidy table as plain CSV (a header row, then the rows: what ``pandas.read_csv`` and any CSV
        reader expect) and the metadata as JSON next to it, in ``<path>.json``
        (:func:`persson_fp.read_sweep_table` reads both back, the metadata into ``df.attrs``).  No pandas needed.

        Parameters
        ----------
        path : str or path-like
            The file to write (the metadata go to ``str(path) + ".json"``).

        Returns
        -------
        None
        """
        try:
            import pandas  # noqa: F401
        except ImportError:
            pandas = None
        with open(path, "w", newline="") as fh:
            if pandas is not None:  # ~10x faster; floats written as their shortest round-trip repr too
                self.to_pandas().to_csv(fh, index=False)
            else:
                cols = self.to_dict()
                names = list(cols)
                w = csv.writer(fh)
                w.writerow(names)
                for row in zip(*(cols[n] for n in names)):
                    w.writerow([_cell(v) for v in row])
        with open(metadata_path(path), "w") as fh:
            json.dump(_jsonable(self.metadata), fh, indent=1)

    def to_parquet(self, path) -> None:
        """Write the tidy table as Parquet with the metadata in the file (needs pandas and pyarrow).

        Parameters
        ----------
        path : str or path-like
            The file to write.

        Returns
        -------
        None
        """
        _need("pyarrow", "pyarrow")
        self.to_pandas().to_parquet(path, index=False)

    # -- display --------------------------------------------------------------------------------------------
    def _headline(self) -> str:
        n_s, n_m, n_l = self.shape
        q = ", ".join(f"{name} [{self.units[name]}]" for name in self.quantities)
        return (
            f"SweepResult(method={self.metadata['method']!r}, {n_s} surfaces x {n_m} models x {n_l} loads; "
            f"{q}; {len(self.failures)} failures; {self.metadata['wall_time_s']:.3g} s)"
        )

    def __repr__(self):
        lines = [self._headline()]
        lines += [f"  failed: {f}" for f in self.failures[:3]]
        if len(self.failures) > 3:
            lines.append(f"  ... and {len(self.failures) - 3} more (result.failures)")
        return "\n".join(lines)

    def _repr_html_(self):
        rows = []
        for q in self.quantities:
            for m, label in enumerate(self.models):
                v = self._values[q][:, m]
                v = v[np.isfinite(v)]
                stats = [f"{np.min(v):.4g}", f"{np.median(v):.4g}", f"{np.max(v):.4g}"] if v.size else ["-", "-", "-"]
                rows.append([q, self.units[q], label] + stats)
        head = "".join(f"<th>{h}</th>" for h in ("quantity", "unit", "model", "min", "median", "max"))
        body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in r) + "</tr>" for r in rows)
        fails = "".join(f"<li>{html.escape(str(f))}</li>" for f in self.failures[:5])
        more = f"<li>... {len(self.failures) - 5} more</li>" if len(self.failures) > 5 else ""
        return (
            f"<div><b>{html.escape(self._headline())}</b>"
            f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"
            + (f"<p>Failures:</p><ul>{fails}{more}</ul>" if fails else "")
            + "</div>"
        )


def read_table(path):
    """Read a table written by :meth:`SweepResult.to_csv` or :meth:`SweepResult.to_parquet`.

    Parameters
    ----------
    path : str or path-like
        A ``.csv`` or ``.parquet`` file.

    Returns
    -------
    pandas.DataFrame
        The table, with the metadata in ``df.attrs`` (needs pandas): from ``<path>.json`` for a CSV.

    Raises
    ------
    ValueError
        A CSV without its metadata file (and not an earlier table with the metadata inside).
    """
    pd = _need("pandas", "pandas")
    from persson_fp._validate import as_file_path

    path = as_file_path(path)  # a ValueError naming path: not a name, a folder, missing (was FileNotFoundError)
    if path.endswith((".parquet", ".pq")):
        return pd.read_parquet(path)
    with open(path, newline="") as fh:
        first = fh.readline()
        if first.rstrip("\r\n") == _CSV_TAG:  # a table from an earlier version: metadata in the file
            meta = json.loads(fh.readline()[2:])
            df = pd.read_csv(fh)
            df.attrs = meta
            return df
    side = metadata_path(path)
    if not os.path.isfile(side):
        raise ValueError(f"{path}: not a persson-fp sweep table (no metadata file {side!r} next to it)")
    with open(side) as fh:
        meta = json.load(fh)
    df = pd.read_csv(path)
    df.attrs = meta
    return df


def _need(module, extra):
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as err:
        raise ImportError(f"this needs the optional package {module!r}: pip install {extra}") from err


def _unique_codes(codes, labels):
    """(codes, categories) with unique categories (``Categorical.from_codes`` needs them), order kept."""
    first = {}
    remap = np.array([first.setdefault(lab, len(first)) for lab in labels], dtype=int)
    return remap[codes], list(first)


def _cell(v):
    if isinstance(v, (float, np.floating)):
        return repr(float(v))  # round-trips exactly
    return v


def _jsonable(obj):
    if isinstance(obj, dict):
        return {str(k): _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (np.floating,)):
        return float(obj)
    if isinstance(obj, (str, int, float, bool)) or obj is None:
        return obj
    return repr(obj)
