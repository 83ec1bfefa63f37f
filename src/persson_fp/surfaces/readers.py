"""Reading measured surfaces from files and other tools: height maps (.npy / text), contact.engineering CSV exports
and SurfaceTopography objects, each imported with :mod:`persson_fp.surfaces.heightmap` (which holds the spectrum
analysis)."""

from __future__ import annotations

import numpy as np

from persson_fp._validate import as_file_path
from persson_fp.surfaces.heightmap import MeasuredSurface, as_bool, psd_from_heightmap, psd_from_profiles
from persson_fp.surfaces.tabulated import TabulatedPSD

__all__ = ["read_heightmap", "read_contact_engineering_csv", "from_surface_topography", "CE_SERIES"]


def read_heightmap(path, size, *, periodic: bool = False, **kwargs) -> MeasuredSurface:
    """Read a 2-D height map from a file and import it with :func:`psd_from_heightmap`.

    Parameters
    ----------
    path : str or path-like
        A ``.npy`` file, or text readable by ``numpy.loadtxt`` (whitespace or comma separated, ``#`` comments).
    size : float or (float, float), length
        Physical size :math:`L_x` (and :math:`L_y`) of the map, in the unit of the heights.
    periodic : bool
        True for periodic data; False (default, measurements): detrended (plane) and windowed.
    **kwargs
        Passed on to :func:`psd_from_heightmap` (``window``, ``bins_per_decade``).

    Returns
    -------
    MeasuredSurface
        As :func:`psd_from_heightmap`, with the file name in ``source``.

    Raises
    ------
    ValueError
        ``path`` not a file name (an int is not taken as a file descriptor), a missing, empty or unreadable
        file, a folder, ``periodic`` not a bool, or bad heights or size (see :func:`psd_from_heightmap`).
    """
    import os

    path = as_file_path(path)
    periodic = as_bool(periodic, "periodic")
    try:
        if path.endswith(".npy"):
            h = np.load(path, allow_pickle=False)
        else:
            with open(path) as fh:
                first = fh.readline()
            h = np.loadtxt(path, delimiter="," if "," in first else None, comments="#", ndmin=2)
    except (OSError, ValueError, EOFError, UnicodeDecodeError) as err:
        raise ValueError(f"{path}: cannot read a height map ({err or type(err).__name__})") from None
    return psd_from_heightmap(h, size, periodic=periodic, source=f"height map {os.path.basename(str(path))}", **kwargs)


CE_SERIES = {"q/π × 2D PSD": "q/pi*2d", "1D PSD along x": "1d", "1D PSD along y": "1d"}
"""The power-spectrum series of a contact.engineering CSV export and their conventions."""


def read_contact_engineering_csv(path, series: str = "q/π × 2D PSD", H: float | None = None) -> MeasuredSurface:
    r"""Read a power spectrum exported from contact.engineering (CSV, ";"-separated, SI units).

    The export has one row per point with columns "Data series", "Wavevector (m⁻¹)" (q in rad/m) and
    "PSD (m³)" (units as in the header).  ``series`` picks "q/π × 2D PSD" (default; :math:`Y = q C_{iso}/\pi`,
    converted by :math:`C = Y/(4\pi q)`), "1D PSD along x" or "1D PSD along y" (Abel-inverted, numerically or
    with the factor of ``H``).  Rows that are not finite or not > 0 (masked points) are dropped with a note.
    The conventions are those of Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5 (2017) 013001.

    Parameters
    ----------
    path : str or path-like
        The CSV file.
    series : str
        One of the keys of ``CE_SERIES``: "q/π × 2D PSD", "1D PSD along x", "1D PSD along y".
    H : float, optional
        For a 1-D series: convert with the power-law Abel factor of this Hurst exponent instead of numerically.

    Returns
    -------
    MeasuredSurface
        Persson's spectrum in metres (q in rad/m, C in m⁴), no height data (``rms_height_data`` is None).

    Raises
    ------
    ValueError
        An unknown series, a missing or empty file, a file without the expected columns, or fewer than 2
        usable points in the series.
    """
    import csv
    import os

    if series not in CE_SERIES:
        raise ValueError(f"series must be one of {list(CE_SERIES)}, got {series!r}")
    path = as_file_path(path)
    with open(path, newline="", encoding="utf-8") as fh:
        reader = csv.reader(fh, delimiter=";")
        header = next(reader, None)
        if header is None:
            raise ValueError(f"{path}: empty file")
        cols = {name.strip(): i for i, name in enumerate(header)}
        try:
            i_series = cols["Data series"]
            i_x = next(i for n, i in cols.items() if n.startswith("Wavevector"))
            i_y = next(i for n, i in cols.items() if n.startswith("PSD"))
        except (KeyError, StopIteration):
            raise ValueError(
                f"{path}: not a contact.engineering power-spectrum export (needs ';'-separated columns 'Data "
                f"series', 'Wavevector (...)', 'PSD (...)'); header: {header}"
            ) from None
        q, y, dropped, found = [], [], 0, set()
        for row in reader:
            if len(row) <= max(i_series, i_x, i_y):
                continue
            found.add(row[i_series])
            if row[i_series] != series:
                continue
            try:
                qv, yv = float(row[i_x]), float(row[i_y])
            except ValueError:
                dropped += 1
                continue
            if np.isfinite(qv) and np.isfinite(yv) and qv > 0 and yv > 0:
                q.append(qv)
                y.append(yv)
            else:
                dropped += 1
    if len(q) < 2:
        raise ValueError(f"{path}: series {series!r} has fewer than 2 usable points; series found: {sorted(found)}")
    q, y = np.array(q), np.array(y)
    order = np.argsort(q)
    q, y = q[order], y[order]
    dup = np.concatenate(([True], np.diff(q) > 0))
    notes = [f"contact.engineering series {series!r} ({CE_SERIES[series]} convention), q in rad/m, SI units"]
    if dropped:
        notes.append(f"{dropped} points that were not finite and > 0 dropped")
    if not np.all(dup):
        notes.append(f"{int(np.sum(~dup))} repeated wavevectors dropped")
    psd = TabulatedPSD(q[dup], y[dup], convention=CE_SERIES[series], H=H)
    return MeasuredSurface(psd, f"contact.engineering CSV {os.path.basename(str(path))}", notes=tuple(notes))


def from_surface_topography(topography, **kwargs) -> MeasuredSurface:
    """Import a SurfaceTopography ``Topography`` (2-D map) or ``UniformLineScan`` (profile).

    Uses the object's heights, physical sizes and periodicity with :func:`psd_from_heightmap` or
    :func:`psd_from_profiles` (so the result is in the topography's length unit).  Needs the optional
    ``SurfaceTopography`` package only for the object itself: nothing is imported here.

    Parameters
    ----------
    topography : SurfaceTopography Topography or UniformLineScan
        Any object with ``heights()``, ``physical_sizes`` and ``is_periodic``.
    **kwargs
        Passed on to :func:`psd_from_heightmap` or :func:`psd_from_profiles` (``window``,
        ``bins_per_decade``, and ``H`` for a line scan).

    Returns
    -------
    MeasuredSurface
        Persson's spectrum in the topography's length unit (q in rad/length, C in length^4).

    Raises
    ------
    ValueError
        ``topography`` lacks those attributes, or its data are rejected by the importer.
    """
    try:
        h = np.asarray(topography.heights(), dtype=float)
        sizes = topography.physical_sizes
        periodic = bool(topography.is_periodic)
    except AttributeError:
        raise ValueError(
            f"topography must be a SurfaceTopography Topography or UniformLineScan, got {type(topography).__name__}"
        ) from None
    unit = getattr(topography, "unit", None)
    src = "SurfaceTopography " + type(topography).__name__ + (f" (unit {unit})" if unit else "")
    if h.ndim == 2:
        return psd_from_heightmap(h, sizes, periodic=periodic, source=src, **kwargs)
    length = sizes[0] if np.ndim(sizes) else sizes
    return psd_from_profiles(h, length, periodic=periodic, source=src, **kwargs)
