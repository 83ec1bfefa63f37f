"""BLAS thread control for the solvers (threadpoolctl, imported on first use).

The solvers' BLAS work is narrow: products of a (loads x modes) or (steps x modes) array with a few
columns, dot products and norms inside ``solve_ivp``, SuperLU's small supernodes.  On such shapes a
multithreaded BLAS (numpy's OpenBLAS starts one thread per core) spends more time waking and
synchronising its threads than computing, and on a machine whose cores are busy it oversubscribes
them: measured in ``benchmarks/batch_scaling.py``.  :func:`persson_fp.solve` therefore runs a solve
with one BLAS thread unless told otherwise (``blas_threads=None`` keeps the library's own setting).
Without threadpoolctl installed the setting is left as it is.
"""

from __future__ import annotations

from contextlib import contextmanager, nullcontext

__all__ = ["blas_threads", "check_blas_threads"]

_CONTROLLER = []
"""The one ThreadpoolController of the process (built on first use: it inspects the loaded libraries)."""


def check_blas_threads(n):
    """``n`` as None or an int >= 1, else a ValueError naming ``blas_threads``."""
    if n is None:
        return None
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise ValueError(f"blas_threads must be None or an integer >= 1, got {n!r}")
    return n


def blas_threads(n):
    """A context manager that limits the BLAS thread pools to ``n`` threads (None: no change)."""
    if n is None:
        return nullcontext()
    if not _CONTROLLER:
        try:
            from threadpoolctl import ThreadpoolController
        except ImportError:  # optional at run time: without it the BLAS keeps its own setting
            _CONTROLLER.append(None)
        else:
            _CONTROLLER.append(ThreadpoolController().select(user_api="blas"))
    ctl = _CONTROLLER[0]
    if ctl is None:
        return nullcontext()
    libs = [(lib, lib.num_threads) for lib in ctl.lib_controllers]
    libs = [(lib, k) for lib, k in libs if k > n]
    return _limited(libs, n) if libs else nullcontext()


@contextmanager
def _limited(libs, n):
    """Set each (library, old count) to ``n`` threads, restore the old counts on exit (also on an error)."""
    for lib, _ in libs:
        lib.set_num_threads(n)
    try:
        yield
    finally:
        for lib, k in libs:
            lib.set_num_threads(k)
