"""The budgets of a chebyshev run: memory of the dense operators of a degree, and the time limit of its loops."""

from __future__ import annotations

from persson_fp.results.invariants import SolverError

__all__ = ["check_degree_memory", "out_of_time"]


def check_degree_memory(n: int, n_loads: int, max_memory: float) -> None:
    """A ``ValueError`` if a run at degree ``n`` would exceed ``max_memory`` (bytes): 160 (n + 1)^2 bytes a load
    + 1 MB (tracemalloc peaks: 12-24 x 8 (n + 1)^2 a load, exponential path, n = 100-300; 9-14 x on the march)."""
    need = 160.0 * (n + 1) ** 2 * n_loads + 1e6
    if need > max_memory:
        raise ValueError(
            f"chebyshev: a run at degree {n} with {n_loads} load(s) would need about "
            f"{need / 2**20:.3g} MiB of memory (estimate), more than max_memory = {max_memory / 2**20:.3g} "
            "MiB; use fewer loads per call, a smaller n_p or a looser tol, or pass a larger max_memory (bytes)"
        )


def out_of_time(max_time: float, where: str):
    """Raise the :class:`~persson_fp.SolverError` of a run past ``max_time`` (seconds), saying ``where``."""
    raise SolverError(
        f"chebyshev: max_time = {max_time:.3g} s exceeded ({where}); loosen tol, or pass a larger max_time (seconds)"
    ) from None
