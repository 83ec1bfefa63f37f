"""Calibration data: loads and measured quantities of one or several surfaces, read and checked.

A data set is a table with a column ``p_bar`` (nominal pressure, > 0) and one or both of ``contact_area``
(relative contact area A*, in (0, 1]) and ``mean_separation`` (mean interfacial separation, length, > 0), each
with an optional absolute uncertainty column ``contact_area_err`` / ``mean_separation_err`` (> 0).  A column
``surface`` (text) assigns rows to surfaces when one table holds several; other columns are ignored.  Tables come
as a CSV file, a pandas DataFrame, a mapping of column name to array, or a 2-D array whose columns are
``p_bar`` followed by the quantities asked for.

Every check raises :class:`ValueError` naming the column and the row (0-based among the data rows; for a CSV
file also its line number).

This module imports no solver.
"""

from __future__ import annotations

import csv
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from persson_fp.surfaces.psd import PSD

__all__ = ["QUANTITIES", "Dataset", "read_table", "pair_surfaces"]

QUANTITIES = ("contact_area", "mean_separation")
"""Quantities a calibration can fit: relative contact area A* (dimensionless) and mean separation (length)."""

_ERR = "_err"


@dataclass
class Dataset:
    """The loads and measured values of one surface.

    Parameters
    ----------
    name : str
        Label of the surface (tables, plots, messages).
    psd : PSD
        The surface's spectrum.
    p_bar : ndarray, shape (n,), pressure
        Nominal pressures, > 0.
    values : dict of str to ndarray
        Measured values per quantity (``contact_area``, ``mean_separation``), each of shape (n,).
    errors : dict of str to ndarray
        Absolute uncertainties (1 standard deviation) per quantity where given, each of shape (n,).
    """

    name: str
    psd: PSD
    p_bar: np.ndarray
    values: dict = field(default_factory=dict)
    errors: dict = field(default_factory=dict)

    @property
    def n_points(self) -> int:
        """Number of measured values (loads x quantities present)."""
        return sum(v.size for v in self.values.values())


def _where(source, row):
    line = f" (line {row + 2} of {source})" if source else ""
    return f"row {row}{line}"


def _column(raw, name, source, numeric=True):
    """A column as a float array; a non-number or non-finite entry raises naming the column and row."""
    if not numeric:
        return np.asarray([str(v).strip() for v in raw], dtype=object)
    out = np.empty(len(raw))
    for i, v in enumerate(raw):
        if isinstance(v, (bool, np.bool_)) or np.iscomplexobj(v):
            raise ValueError(f"column {name!r}, {_where(source, i)}: not a real number: {v!r}")
        try:
            x = float(v)
        except (TypeError, ValueError):
            raise ValueError(f"column {name!r}, {_where(source, i)}: not a number: {v!r}") from None
        if not np.isfinite(x):
            raise ValueError(f"column {name!r}, {_where(source, i)}: not finite: {x!r}")
        out[i] = x
    return out


def _check_column(name, x, source):
    """Range checks of a known numeric column."""
    kind = "err" if name.endswith(_ERR) else name
    if kind == "p_bar":
        bad, what = x <= 0, "a load must be > 0 (pressure)"
    elif kind == "contact_area":
        bad, what = (x <= 0) | (x > 1), "a contact area must lie in (0, 1] (a relative error needs A* > 0)"
    elif kind == "mean_separation":
        bad, what = x <= 0, "a mean separation must be > 0 (length)"
    else:  # an uncertainty column
        bad, what = x <= 0, "an uncertainty must be > 0"
    if np.any(bad):
        i = int(np.argmax(bad))
        raise ValueError(f"column {name!r}, {_where(source, i)}: {what}, got {float(x[i])!r}")


def _read_csv(path):
    with open(path, newline="") as fh:
        reader = csv.reader(fh)
        try:
            header = [h.strip() for h in next(reader)]
        except StopIteration:
            raise ValueError(f"{path}: empty file (expected a header row with p_bar and a quantity)") from None
        rows = [r for r in reader if any(c.strip() for c in r)]
    cols = {h: [] for h in header}
    for i, r in enumerate(rows):
        if len(r) != len(header):
            raise ValueError(f"{path}: {_where(path, i)} has {len(r)} fields, the header {len(header)}")
        for h, v in zip(header, r):
            cols[h].append(v.strip())
    return cols


def _as_columns(data, quantities):
    """(columns mapping, source file or None) from any accepted table form."""
    if isinstance(data, (str, os.PathLike)):
        path = os.fspath(data)
        if os.path.isdir(path):
            raise ValueError(f"data: {path!r} is a folder; give the CSV file (columns p_bar, contact_area, ...)")
        if not os.path.isfile(path):
            raise ValueError(f"data: no such file: {path!r}")
        return _read_csv(path), path
    if hasattr(data, "columns") and hasattr(data, "to_numpy"):  # a pandas DataFrame (duck-typed: pandas optional)
        return {str(c): list(data[c].to_numpy()) for c in data.columns}, None
    if isinstance(data, Mapping):
        return {str(k): list(np.atleast_1d(np.asarray(v, dtype=object))) for k, v in data.items()}, None
    arr = np.asarray(data)
    if arr.ndim != 2 or arr.shape[1] < 2:
        raise ValueError(
            "data must be a CSV path, a DataFrame, a mapping of columns or a 2-D array with columns "
            f"(p_bar, {', '.join(quantities or QUANTITIES)}); got an array of shape {arr.shape}"
        )
    names = ["p_bar", *(quantities or QUANTITIES)]
    if arr.shape[1] > len(names):
        raise ValueError(f"a 2-D data array has columns {names}; got {arr.shape[1]} columns")
    return {n: list(arr[:, j]) for j, n in enumerate(names[: arr.shape[1]])}, None


def read_table(data, quantities=None) -> tuple[dict, str | None]:
    """Read and check one table of calibration data.

    Parameters
    ----------
    data : str, path-like, DataFrame, mapping or 2-D array
        The table (module docstring).
    quantities : sequence of str, optional
        The quantities to read; default those of ``QUANTITIES`` present in the table.

    Returns
    -------
    columns : dict of str to ndarray
        ``p_bar``, the quantities, their ``*_err`` columns where present, and ``surface`` (object array) if
        present.
    source : str or None
        The file name for a CSV input.

    Raises
    ------
    ValueError
        A missing column, an empty table, or an entry that is not a finite number or out of range (a load
        <= 0, A* outside (0, 1], a separation or an uncertainty <= 0), naming the column and the row.
    """
    cols, source = _as_columns(data, quantities)
    where = f"{source}: " if source else ""
    if "p_bar" not in cols:
        raise ValueError(f"{where}data need a column 'p_bar' (nominal pressure); got columns {sorted(cols)}")
    wanted = list(quantities) if quantities is not None else [q for q in QUANTITIES if q in cols]
    for q in wanted:
        if q not in QUANTITIES:
            raise ValueError(f"quantities must be among {list(QUANTITIES)}, got {q!r}")
        if q not in cols:
            raise ValueError(f"{where}data have no column {q!r} (asked for in quantities); columns {sorted(cols)}")
    if not wanted:
        raise ValueError(f"{where}data need a column 'contact_area' or 'mean_separation'; got {sorted(cols)}")
    n = len(cols["p_bar"])
    if n == 0:
        raise ValueError(f"{where}data hold no rows")
    out = {}
    for name in ["p_bar", *wanted, *[q + _ERR for q in wanted if q + _ERR in cols]]:
        if len(cols[name]) != n:
            raise ValueError(f"{where}column {name!r} has {len(cols[name])} rows, column 'p_bar' {n}")
        out[name] = _column(cols[name], name, source)
        _check_column(name, out[name], source)
    if "surface" in cols:
        out["surface"] = _column(cols["surface"], "surface", source, numeric=False)
    return out, source


def _surfaces(psd_or_surfaces):
    """[(name, psd)] from a PSD, a sequence of PSDs or a mapping name -> PSD."""
    if isinstance(psd_or_surfaces, PSD):
        return [("surface", psd_or_surfaces)]
    items = (
        list(psd_or_surfaces.items())
        if isinstance(psd_or_surfaces, Mapping)
        else list(enumerate(psd_or_surfaces))
        if isinstance(psd_or_surfaces, Sequence) and not isinstance(psd_or_surfaces, str)
        else None
    )
    if not items:
        raise ValueError(
            "psd_or_surfaces must be a PSD, a non-empty sequence of PSDs or a mapping name -> PSD; "
            f"got {psd_or_surfaces!r}"
        )
    for k, p in items:
        if not isinstance(p, PSD):
            raise ValueError(f"surface {k!r}: expected a persson_fp PSD, got {type(p).__name__}")
    return [(str(k), p) for k, p in items]


def _dataset(name, psd, cols, sel=None):
    take = (lambda a: a) if sel is None else (lambda a: a[sel])
    values = {q: take(cols[q]) for q in QUANTITIES if q in cols}
    errors = {q: take(cols[q + _ERR]) for q in QUANTITIES if q + _ERR in cols}
    return Dataset(name, psd, take(cols["p_bar"]), values, errors)


def pair_surfaces(psd_or_surfaces, data, quantities=None) -> list[Dataset]:
    """Pair spectra with data: one :class:`Dataset` per surface.

    Parameters
    ----------
    psd_or_surfaces : PSD, sequence of PSD or mapping of str to PSD
        One spectrum per surface.
    data : table or sequence of tables
        One table per surface (in the same order), or one table whose ``surface`` column names the surface
        of each row (the mapping's keys, or the positions 0, 1, ... of a sequence), one spectrum in a sequence or
        mapping included; with a bare PSD (unnamed) the column must hold a single label.
    quantities : sequence of str, optional
        Quantities to read (default: those present).

    Returns
    -------
    list of Dataset
        In the order of ``psd_or_surfaces``.

    Raises
    ------
    ValueError
        Bad tables (:func:`read_table`), a count of tables that does not match the surfaces, a ``surface``
        value that names no surface (the message lists the known names), or several labels for a bare PSD.
    """
    surfaces = _surfaces(psd_or_surfaces)
    single = (
        isinstance(data, (str, os.PathLike, Mapping))
        or hasattr(data, "columns")
        or (isinstance(data, np.ndarray) and data.ndim == 2)
    )
    if not single:
        try:
            tables = list(data)
        except TypeError:
            raise ValueError(
                "data must be a table (a CSV file name, a DataFrame, a mapping of columns or a 2-D array) or a "
                f"sequence of tables, one per surface; got {type(data).__name__} {data!r}"
            ) from None
        if len(tables) != len(surfaces):
            raise ValueError(f"got {len(tables)} data tables for {len(surfaces)} surfaces (one table per surface)")
        out = []
        for (name, psd), t in zip(surfaces, tables):
            cols, _ = read_table(t, quantities)
            out.append(_dataset(name, psd, cols))
        return out
    cols, source = read_table(data, quantities)
    if "surface" not in cols:
        if len(surfaces) != 1:
            raise ValueError(f"one data table for {len(surfaces)} surfaces: add a 'surface' column naming each row's")
        return [_dataset(surfaces[0][0], surfaces[0][1], cols)]
    labels = cols["surface"]
    names = [n for n, _ in surfaces]
    if isinstance(psd_or_surfaces, PSD):
        # one unnamed spectrum: the column may carry any one label, but not several (rows of other surfaces)
        found = list(dict.fromkeys(labels))
        if len(found) > 1:
            raise ValueError(
                f"column 'surface' names {len(found)} surfaces {found} but one spectrum (a bare PSD) was given; "
                "pass a mapping name -> PSD naming each"
            )
        return [_dataset(names[0], surfaces[0][1], cols)]
    for i, lab in enumerate(labels):
        if lab not in names:  # the same rule for one spectrum as for several
            raise ValueError(f"column 'surface', {_where(source, i)}: {lab!r} names no surface (have {names})")
    if len(surfaces) == 1:
        return [_dataset(names[0], surfaces[0][1], cols)]
    out = [_dataset(n, p, cols, labels == n) for n, p in surfaces if np.any(labels == n)]
    if len(out) != len(surfaces):
        missing = [n for n in names if not np.any(labels == n)]
        raise ValueError(f"data have no rows for surface(s) {missing}")
    return out
