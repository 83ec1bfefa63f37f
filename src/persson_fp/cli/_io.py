"""What every subcommand of ``persson-fp`` shares: atomic file output, the ``--force`` rule, units in headers and
labels, case-insensitive names and one-line warnings.

A file is written under a temporary name in its folder and renamed when complete, so that an
interrupted or failed run leaves no partial file; problems with paths are :class:`CLIError` (one
line, exit code 2).  An output that exists is refused (one line, exit code 2) unless ``--force``.
Warnings, the library's and the command's own, are printed once each as one line on stderr at the end of a run,
``persson-fp: warning: ...`` (:func:`one_line_warnings`, used by :func:`persson_fp.cli.app.main`).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import tempfile
import warnings

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


def _check_new_files(folder, names, force: bool, option: str = "--output"):
    """Refuse to replace any of ``names`` in ``folder`` unless ``--force`` (before any work is done)."""
    old = [n for n in names if os.path.isfile(os.path.join(folder, n))]
    if old and not force:
        them = "it" if len(old) == 1 else "them"
        raise CLIError(f"{option}: {', '.join(old)} exist{'s' if len(old) == 1 else ''} in {folder}; pass --force "
                       f"to replace {them}")  # fmt: skip


# -- units ---------------------------------------------------------------------------------------------

UNIT_SYSTEMS = ("SI", "none")
"""``--units``: SI (lengths in m, pressures in Pa, times in s) or none (any consistent set, dimensions named)."""

_UNITS = {
    "SI": {
        "-": "-", "length": "m", "pressure": "Pa", "stiffness": "Pa/m", "wavenumber": "rad/m", "psd": "m^4",
        "1/length": "1/m", "1/pressure": "1/Pa", "flow": "m^3/s", "flow/(dp/eta)": "m^3", "viscosity": "Pa s",
        "ms": "ms",
    },
    "none": {
        "-": "-", "length": "length", "pressure": "pressure", "stiffness": "pressure/length",
        "wavenumber": "rad/length", "psd": "length^4", "1/length": "1/length", "1/pressure": "1/pressure",
        "flow": "length^3/time", "flow/(dp/eta)": "length^3", "viscosity": "pressure time", "ms": "ms",
    },
}  # fmt: skip


def unit(kind: str, units: str) -> str:
    """The unit of a quantity of dimension ``kind`` ("length", "pressure", ...) in the system ``units``."""
    return _UNITS[units][kind]


def col(name: str, kind: str, units: str) -> str:
    """A CSV column header with its unit in brackets: ``col("p_bar", "pressure", "SI") == "p_bar [Pa]"``."""
    return f"{name} [{unit(kind, units)}]"


def add_units_arg(p):
    """``--units SI|none`` (case-insensitive; default: SI, said once on stdout)."""
    p.add_argument(
        "--units",
        type=choice(UNIT_SYSTEMS),
        default=None,
        help="SI (default: lengths in m, pressures in Pa; said once) or none (dimensionless input: headers and "
        "labels name the dimension, [length], [pressure])",
    )


_PHYSICAL_INPUTS = ("q_l", "q_r", "rms_height", "C0", "psd_csv", "p_bar", "file")
"""Options that carry a length or a pressure: without any of them (and with E* = 1) the run is the dimensionless
reference problem."""


def resolve_units(args) -> str:
    """The unit system of the run; when ``--units`` was not given, SI is assumed and said once on stdout -- except
    for the dimensionless reference problem (no option with a length or a pressure, E* = 1), which says so."""
    if getattr(args, "units", None) is None:
        reference = all(getattr(args, name, None) is None for name in _PHYSICAL_INPUTS)
        if reference and getattr(args, "E_star", 1.0) == 1.0:
            args.units = "none"
            print("units: none (the dimensionless reference problem, E* = 1; --units SI with values in m and Pa)")
        else:
            args.units = "SI"
            print("units: SI assumed (lengths in m, pressures in Pa; --units none for dimensionless input)")
    return args.units


# -- names ---------------------------------------------------------------------------------------------


def choice(names, what: str = "choose from"):
    """An argparse ``type`` accepting any of ``names`` in any letter case, returned in their canonical spelling
    (``--fudge yp08`` is ``YP08``); anything else is refused with the list."""
    table = {n.lower(): n for n in names}

    def convert(text: str) -> str:
        try:
            return table[text.lower()]
        except KeyError:
            raise argparse.ArgumentTypeError(f"invalid choice: {text!r} ({what} {', '.join(names)})") from None

    convert.__name__ = "name"
    return convert


# -- warnings ------------------------------------------------------------------------------------------

WARNING_PREFIX = "persson-fp: warning: "


class CLIWarning(UserWarning):
    """A plausibility warning of the command itself (printed like the library's)."""


_SUPERSEDED = {"load-vs-modulus": ("p_bar / E_star",)}
"""Library warnings that say again what a command's own warning (the key) already said: not printed after it."""


@contextlib.contextmanager
def one_line_warnings(stream=None):
    """Collect every warning raised inside and, when the block completes, print each message once as one line
    ``persson-fp: warning: MESSAGE`` on stderr (no file names, no source lines).  A block that raises prints none:
    the error line is then the whole of stderr."""
    lines: list[str] = []
    said: set[str] = set()

    def show(message, category, filename, lineno, file=None, line=None):
        text = " ".join(str(message).split())
        key = getattr(message, "key", None)
        if key:
            said.add(key)
        if text in lines or any(s in text for k in said for s in _SUPERSEDED.get(k, ())):
            return
        lines.append(text)

    with warnings.catch_warnings():
        warnings.simplefilter("always")
        warnings.showwarning = show
        yield
    for text in lines:
        print(WARNING_PREFIX + text, file=stream or sys.stderr)


def warn(message: str, key: str | None = None) -> None:
    """A warning of the command (one line on stderr through :func:`one_line_warnings`); ``key`` names its topic,
    after which the library's warnings on the same topic are not repeated."""
    w = CLIWarning(message)
    w.key = key
    warnings.warn(w, stacklevel=2)


def check_load_vs_modulus(p_bar, E_star, units: str = "SI") -> None:
    """Warn (one line) when a load reaches the contact modulus: small-slope contact has p_bar << E*."""
    pmax = float(np.max(p_bar))
    if np.isfinite(pmax) and np.isfinite(E_star) and E_star > 0 and pmax >= E_star:
        u = unit("pressure", units)
        warn(
            f"--p-bar {pmax:g} {u} >= --E-star {E_star:g} {u}: the nominal pressure reaches the contact modulus "
            "(small-slope contact needs p_bar << E*); are they in the same unit (E* in MPa or GPa with p_bar in Pa?)",
            key="load-vs-modulus",
        )


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
