"""The budgets of a chebyshev run: memory of the dense operators of a degree, and the time limit of its loops."""

from __future__ import annotations

from persson_fp.results.invariants import SolverError

__all__ = ["DEGREE_MEMORY", "check_degree_memory", "degree_memory", "out_of_time"]


DEGREE_MEMORY = {
    # path -> (bytes shared by the loads, bytes a load), each a (n + 1)^2 + b: fitted to tracemalloc's peaks of whole
    # pf.solve calls at a fixed n_p (benchmarks/memory_estimates.py), the model 1.1-1.6x those.
    # exponential (separable B2, scene S): 0.58 / 0.68 / 1.47 / 5.7 / 22.8 MB at n = 25 / 50 / 100 / 200 / 400, one
    # load (the dense operators, ~142 (n + 1)^2 + 0.5 MB); each further load 0.60 / 0.94 / 3.05 MB at n = 50 / 100 /
    # 200 (10 and 100 loads: ~75 (n + 1)^2 + a few 0.1 MB of the load's own stations)
    "exponential": ((100.0, 1e5), (80.0, 5e5)),
    # the general march (Radau; scene A): 0.57 / 0.64 / 1.66 / 3.62 / 9.86 MB at n = 20 / 40 / 80 / 120 / 200, one
    # load; 5.8 / 15.8 MB with 10 loads at n = 40 / 80 (~240 (n + 1)^2 + 0.17 MB a load)
    "march": ((0.0, 3e5), (300.0, 2e5)),
    # the moving wall (scene W): 0.18 / 0.50 / 1.80 / 3.94 MB at n = 20 / 40 / 80 / 120, one load; 4.5 / 17.1 MB with
    # 10 loads at n = 40 / 80 (~265 (n + 1)^2 a load)
    "moving-wall": ((0.0, 1e5), (330.0, 0.0)),
}
"""Peak-memory model of a chebyshev run at one degree, by path (:func:`degree_memory`); was 160 (n + 1)^2 bytes a load
+ 1 MB on every path: 0.7x the peak of 100 loads at n = 50, 2.6x that of the moving wall at n = 40."""


def degree_memory(n: int, n_loads: int, path: str = "exponential") -> float:
    """The estimated peak memory (bytes) of a run at degree ``n`` with ``n_loads`` loads on ``path`` ("exponential",
    a march -- "radau" or "clock" -- or "moving-wall"): :data:`DEGREE_MEMORY`'s shared part + ``n_loads`` x its part
    a load."""
    (a0, b0), (a1, b1) = DEGREE_MEMORY[path if path in DEGREE_MEMORY else "march"]
    m = (n + 1.0) ** 2
    return a0 * m + b0 + n_loads * (a1 * m + b1)


def check_degree_memory(n: int, n_loads: int, max_memory: float, path: str = "exponential") -> None:
    """A ``ValueError`` if a run at degree ``n`` on ``path`` would exceed ``max_memory`` (bytes):
    :func:`degree_memory`."""
    need = degree_memory(n, n_loads, path)
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
