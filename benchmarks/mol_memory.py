"""mol's peak memory (tracemalloc) against its estimate ``persson_fp.solvers.base.MEMORY_MODELS['mol']``.

The estimate refuses a run before it starts (``max_memory``, default 4 GiB): it must be neither far below the
peak (a run that exhausts the machine) nor far above it (a refused run that would fit).  Target: within 2x.

    python benchmarks/mol_memory.py [--quick]  ->  results/mol_memory.{csv,md}
"""

from __future__ import annotations

import gc
import os
import time
import tracemalloc
import warnings

import numpy as np
from _common import machine, outdir, parser, write_csv

import persson_fp as pf
from persson_fp.solvers import get_solver
from persson_fp.solvers.base import MEMORY_MODELS


def cases(quick):
    ref = pf.ContactProblem.reference
    out = [
        ("reference, automatic grid", ref(), {}),
        ("reference, n_p = 4000, YP08", ref(fudge="YP08"), {"n_p": 4000}),
        ("constant hardness, n_p = 4000", ref(hardness=0.05), {"n_p": 4000}),
        ("20 loads, n_p = 1000", ref(p_bar_ratio=np.linspace(0.1, 2, 20)), {"n_p": 1000}),
    ]
    if not quick:
        out += [
            ("reference, n_p = 2e4", ref(), {"n_p": 20000}),
            ("50 loads, n_p = 2000", ref(p_bar_ratio=np.linspace(0.1, 2, 50)), {"n_p": 2000}),
            ("50 loads, n_p = 2000, YP08", ref(p_bar_ratio=np.linspace(0.1, 2, 50), fudge="YP08"), {"n_p": 2000}),
            ("1000 loads, automatic grid", ref(p_bar_ratio=np.linspace(0.2, 2, 1000)), {}),
            ("1000 loads, automatic grid, YP08", ref(p_bar_ratio=np.linspace(0.2, 2, 1000), fudge="YP08"), {}),
        ]
    return out


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    rows = []
    for name, pr, opts in cases(args.quick):
        gc.collect()
        solver = get_solver("mol")(pr, max_memory=1e15, **opts)
        tracemalloc.start()
        t0 = time.perf_counter()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            sol = solver.run()
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        o = dict(solver.opts, n_p=int(sol.info["grid"].size))
        est = MEMORY_MODELS["mol"](o, pr.n_loads, 1, pr.fudge.name != "none")
        rows.append(
            {
                "case": name,
                "n_p": o["n_p"],
                "loads": pr.n_loads,
                "peak_MB": peak / 1e6,
                "estimate_MB": est / 1e6,
                "ratio": est / peak,
                "seconds_traced": time.perf_counter() - t0,
            }
        )
    d = outdir(args)
    write_csv(os.path.join(d, "mol_memory.csv"), rows)
    lines = [
        "# mol: memory estimate vs tracemalloc peak",
        "",
        machine(),
        "",
        "| case | n_p | loads | peak MB | estimate MB | estimate / peak |",
        "|---|---|---|---|---|---|",
    ]
    lines += [
        f"| {r['case']} | {r['n_p']} | {r['loads']} | {r['peak_MB']:.2f} | {r['estimate_MB']:.2f} | {r['ratio']:.2f} |"
        for r in rows
    ]
    with open(os.path.join(d, "mol_memory.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return rows


if __name__ == "__main__":
    main()
