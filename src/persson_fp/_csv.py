"""Named numeric columns of a CSV file with one header row (units in brackets after a name are allowed)."""

from __future__ import annotations

import numpy as np

from persson_fp._validate import as_file_path

__all__ = ["read_columns"]


def read_columns(path, names, name: str = "path") -> list[np.ndarray]:
    """The columns ``names`` of a comma-separated file whose first line names its columns.

    A header name may carry its unit after a space or in brackets (``frequency [Hz]``); other columns are ignored.

    Parameters
    ----------
    path : str or path-like
        The file.
    names : sequence of str
        The columns wanted, in order.
    name : str
        The parameter or option that gave the file (named in the errors).

    Returns
    -------
    list of numpy.ndarray
        One float array per name.

    Raises
    ------
    ValueError
        Not a file, an empty file, a missing column, a non-numeric row or a row of another length.
    """
    path = as_file_path(path, name)
    with open(path, encoding="utf-8") as fh:
        header = [h.strip().split("[")[0].strip().split(" ")[0] for h in fh.readline().split(",")]
    missing = [n for n in names if n not in header]
    if missing:
        raise ValueError(f"{name}: {path} must have a header naming {', '.join(names)}; missing {', '.join(missing)}")
    try:
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except ValueError as exc:
        raise ValueError(f"{name}: {path}: not a numeric CSV table ({exc})") from None
    if data.shape[0] == 0 or data.shape[1] != len(header):
        raise ValueError(f"{name}: {path}: expected rows of {len(header)} numbers, got shape {data.shape}")
    return [data[:, header.index(n)] for n in names]
