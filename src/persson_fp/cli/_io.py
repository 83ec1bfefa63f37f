"""File output of the ``persson-fp`` command: atomic writes, folders, replacement notes.

A file is written under a temporary name in its folder and renamed when complete, so that an
interrupted or failed run leaves no partial file; problems with paths are :class:`CLIError` (one
line, exit code 2).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import tempfile

import numpy as np

__all__ = ["CLIError"]


class CLIError(Exception):
    """A user error: printed as one line, exit code 2."""


@contextlib.contextmanager
def _atomic_open(path, mode="w", newline=None):
    """Open ``path`` for writing through a temporary file in the same folder, renamed on success.

    An interrupted or failed write leaves no partial file (and an existing file untouched).  A path
    that exists but is not a regular file (``/dev/null``, ``/dev/full``) is written directly.
    """
    path = os.fspath(path)
    if os.path.isdir(path):
        raise CLIError(f"{path}: is a directory, expected a file name")
    if os.path.exists(path) and not os.path.isfile(path):
        try:
            with open(path, mode, newline=newline) as fh:
                yield fh
        except OSError as err:
            raise CLIError(f"{path}: {err.strerror or err}") from None
        return
    with _atomic_path(path) as tmp, open(tmp, mode, newline=newline) as fh:
        yield fh


def _default_mode() -> int:
    """The mode a new file gets from ``open``: 0o666 less the umask (mkstemp's files are 0o600)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


@contextlib.contextmanager
def _atomic_path(path):
    """A temporary name in the folder of ``path`` (same suffix) to write to; renamed to ``path`` on success with the
    umask's default mode, removed on failure or interruption (so no partial file is left)."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(dir=folder, prefix=".persson-fp-", suffix=".part" + os.path.splitext(path)[1])
    os.close(fd)
    try:
        yield tmp
        os.chmod(tmp, _default_mode())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _save_figure(fig, path, dpi):
    """``fig.savefig`` through :func:`_atomic_open`; the figure is closed afterwards."""
    import matplotlib.pyplot as plt

    fmt = os.path.splitext(os.fspath(path))[1].lstrip(".").lower() or "png"
    try:
        with _atomic_open(path, "wb") as fh:
            fig.savefig(fh, format=fmt, dpi=dpi)
    finally:
        plt.close(fig)


def _make_parent(path, option: str):
    """Create the folder of ``path``; a regular file where a folder is needed is a one-line error."""
    parent = os.path.dirname(os.path.abspath(path))
    probe = parent
    while not os.path.exists(probe):
        probe = os.path.dirname(probe)
    if not os.path.isdir(probe):
        raise CLIError(f"{option}: {probe} is not a folder (in {path})")
    os.makedirs(parent, exist_ok=True)


def _check_new_file(path, force: bool, option: str):
    """Refuse to replace an existing regular file unless ``--force``."""
    if path and os.path.isfile(path) and not force:
        raise CLIError(f"{option}: {path} exists; pass --force to replace it")


def _note_replaced(folder, names):
    """Say which of ``names`` in ``folder`` already exist (they are replaced)."""
    old = [n for n in names if os.path.isfile(os.path.join(folder, n))]
    if old:
        print(f"note: replacing existing {', '.join(old)} in {folder}", file=sys.stderr)


def _count(text: str) -> int:
    """An integer argument; "1e6" is read as 1000000 (an integral number in any float notation)."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        x = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}") from None
    if not (np.isfinite(x) and x == np.floor(x) and abs(x) < 2**63):
        raise argparse.ArgumentTypeError(f"not an integer: {text!r}")
    return int(x)
