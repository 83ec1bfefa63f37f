"""The memory estimates that refuse a run (``max_memory``) against the measured peak of the whole call.

A solve refuses, before it allocates anything, a run whose estimated peak exceeds ``max_memory`` (default 4 GiB),
with a ``ValueError`` naming it.  The estimate must not fall below the peak (the run would exhaust the machine)
nor lie far above it (a run that fits is refused): the target is estimate / peak in [1, 2].  Estimates are the
methods' own, called as the solvers call them: ``fv`` the entry of ``persson_fp.solvers.base.MEMORY_MODELS``
(through ``Solver.memory_estimate``, the figure ``check_memory`` holds against the budget), ``chebyshev``
``persson_fp.solvers.chebyshev.budget.degree_memory`` at the run's degree (checked before every pass).

Peak: ``tracemalloc``'s peak over the whole ``pf.solve`` call (validation, the solve, the ``Solution`` and its
checks).  tracemalloc sees what goes through Python's allocators, numpy's arrays included (numpy reports its data
buffers to it); memory that BLAS/LAPACK or other C code allocates for itself is not seen.  Before each case a small
call of the same method on the same scene runs untraced, so that first-use costs (imports, caches) stay outside.

Cases: ``fv`` on scene W (moving wall: ``moving_wall_auto.scene()``) and scene A (general coefficients:
``general_nonseparable.scenes()``), n_p = n_steps = 400, 1600, 6400, a few n_p != n_steps up to 12 800 cells, and
10 loads (the front-fixed engine); ``fv`` on ``ContactProblem.reference()`` (the march, which keeps a trajectory),
1 and 10 loads; ``chebyshev`` at fixed n_p on scene S (separable: the exponential path), 1 and 100 loads, on scene A
(the general march) and on scene W (the moving wall).

    python benchmarks/memory_estimates.py [--quick]  ->  results/memory_estimates.{csv,md}

``--quick`` (CI, seconds): one small case of each group.
"""

from __future__ import annotations

import gc
import os
import sys
import time
import tracemalloc
import warnings

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402
from general_nonseparable import scenes  # noqa: E402
from moving_wall_auto import scene  # noqa: E402

import persson_fp as pf  # noqa: E402
from persson_fp.solvers import get_solver  # noqa: E402
from persson_fp.solvers.chebyshev.budget import degree_memory  # noqa: E402

GROUPS = ("fv, moving wall (W)", "fv, general (A)", "fv, reference", "chebyshev")


def problems():
    """The scenes by short name: W (moving wall), A (general, non-separable), S (separable); W10, A10, S100 with 10
    or 100 loads; ref, ref10 the reference problem with 1 and 10 loads."""
    sc = {k[0]: v for k, v in scenes().items()}
    pr = pf.ContactProblem.reference()
    psd, pb = pr.psd, float(pr.p_bar[0])
    S100 = pf.FokkerPlanckProblem(
        psd, p_bar=pb * np.linspace(0.5, 2.0, 100), B2=lambda p, z: psd.dV_dzeta(z) * (1 + p / (2 * pb))
    )  # (B2 fixed by the reference load, as in scene S: the loads share their coefficients)
    W = scene()
    A10 = pf.FokkerPlanckProblem(  # (scene A's coefficients, its p_bar fixed in B2, 10 loads)
        psd, p_bar=pb * np.linspace(0.5, 2.0, 10), B2=lambda p, z: psd.dV_dzeta(z) * (1 + 0.2 * (p / pb) * np.log(z))
    )
    return {
        "W": W,
        "W10": pf.ContactProblem(W.psd, p_bar=0.03 * np.linspace(0.5, 1.1, 10), hardness=W.hardness),
        "A10": A10,
        "A": sc["A"],
        "S": sc["S"],
        "S100": S100,
        "ref": pr,
        "ref10": pf.ContactProblem.reference(p_bar_ratio=np.linspace(0.2, 2.0, 10)),
    }


def cases(quick: bool) -> list[tuple[str, str, str, str, dict]]:
    """(group, case, scene, method, options)."""
    sizes = () if quick else (400, 1600, 6400)
    out = []
    for grp, key in (("fv, moving wall (W)", "W"), ("fv, general (A)", "A")):
        out += [(grp, f"n_p = n_steps = {n}", key, "fv", {"n_p": n, "n_steps": n}) for n in sizes]
        if quick:  # (a case whose model sits mid-band: at n_p = n_steps = 400 the traced peak moved 20 % between
            # runs of the test suite)
            out += [(grp, "n_p = 3200, n_steps = 400", key, "fv", {"n_p": 3200, "n_steps": 400})]
        else:  # (12 800 cells with 400 steps: n_p = n_steps = 12 800 takes 3-6 min under tracemalloc)
            out += [
                (grp, f"n_p = {a}, n_steps = {b}", key, "fv", {"n_p": a, "n_steps": b})
                for a, b in ((400, 3200), (3200, 400), (6400, 800), (12800, 400))
            ]
            out += [
                (grp, f"n_p = {a}, n_steps = {b}, 10 loads", key + "10", "fv", {"n_p": a, "n_steps": b})
                for a, b in ((400, 400), (1600, 200), (200, 1600))
            ]
    grp = "fv, reference"
    ref = ((400, 400), (2000, 100)) if quick else ((400, 400), (2000, 100), (2000, 1000), (8000, 400), (20000, 100))
    for key, loads in (("ref", 1), ("ref10", 10)):
        out += [
            (grp, f"n_p = {a}, n_steps = {b}, {loads} load(s)", key, "fv", {"n_p": a, "n_steps": b}) for a, b in ref
        ]
    grp = "chebyshev"
    for key, loads in (("S", 1), ("S100", 100)):
        for n in (50,) if quick else (50, 100, 200, 400):
            out.append((grp, f"S (exponential), n_p = {n}, {loads} load(s)", key, "chebyshev", {"n_p": n}))
    for key, name in (("A", "A (general march)"), ("W", "W (moving wall)")):
        for n in (40,) if quick else (40, 80, 120):
            out.append((grp, f"{name}, n_p = {n}", key, "chebyshev", {"n_p": n}))
    return out


def estimate(pr, method: str, opts: dict) -> float:
    """The method's own estimate (bytes) of the run: what it holds against ``max_memory``."""
    if method == "chebyshev":  # (the degree is n_p when it is fixed; checked before each pass)
        return degree_memory(opts["n_p"], pr.n_loads, get_solver(method)(pr, **opts).path)
    return get_solver(method)(pr, **opts).memory_estimate()


def measure(pr, method: str, opts: dict) -> tuple[float, float]:
    """(tracemalloc peak in bytes, seconds) of the whole ``pf.solve`` call."""
    gc.collect()
    tracemalloc.start()
    t0 = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        pf.solve(pr, method, max_memory=np.inf, max_time=3000.0, **opts)
    secs = time.perf_counter() - t0
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return float(peak), secs


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    prs = problems()
    warm = set()
    rows = []
    for grp, name, key, method, opts in cases(args.quick):
        pr = prs[key]
        if (key, method) not in warm:  # (first-use costs outside the measure)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                pf.solve(pr, method, **({"n_p": 24} if method == "chebyshev" else {"n_p": 100, "n_steps": 50}))
            warm.add((key, method))
        est = estimate(pr, method, opts)
        peak, secs = measure(pr, method, opts)
        rows.append(
            {
                "group": grp,
                "case": name,
                "method": method,
                "loads": pr.n_loads,
                "peak_MB": peak / 1e6,
                "estimate_MB": est / 1e6,
                "ratio": est / peak,
                "seconds_traced": secs,
            }
        )
        print(f"{grp}: {name}: peak {peak / 1e6:.3f} MB, estimate {est / 1e6:.3f} MB, ratio {est / peak:.2f}")
    d = outdir(args)
    write_csv(os.path.join(d, "memory_estimates.csv"), rows)
    ratios = np.array([r["ratio"] for r in rows])
    lines = [
        "# Memory estimates against the measured peak",
        "",
        machine(),
        "",
        "Estimate: the method's own (fv: `MEMORY_MODELS['fv']`; chebyshev: `budget.degree_memory` at the degree), "
        "the figure a run is refused by (`max_memory`, default 4 GiB). Peak: tracemalloc's over the whole "
        "`pf.solve` call; it sees numpy's arrays (numpy reports its buffers to it), not memory that BLAS/LAPACK "
        "allocate for themselves. Target: 1 <= estimate / peak <= 2.",
        "",
        f"estimate / peak: {ratios.min():.2f} ... {ratios.max():.2f} over {ratios.size} cases; "
        f"{int(np.sum((ratios < 1) | (ratios > 2)))} outside [1, 2].",
        "",
    ]
    lines.append(
        markdown_table(
            ["group", "case", "peak MB", "estimate MB", "estimate / peak", "s (traced)"],
            [
                [
                    r["group"],
                    r["case"],
                    f"{r['peak_MB']:.3g}",
                    f"{r['estimate_MB']:.3g}",
                    f"{r['ratio']:.2f}",
                    f"{r['seconds_traced']:.2f}",
                ]
                for r in rows
            ],
        )
    )
    with open(os.path.join(d, "memory_estimates.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return rows


if __name__ == "__main__":
    main()
