"""The cost of ``import persson_fp`` against ``import numpy, scipy.special`` (its own light dependencies).

Each run is a fresh interpreter (``sys.executable -c ...``, no ``-X importtime``) that times its import statement
with ``time.perf_counter`` around it and reports the seconds and the number of modules it loaded; the parent also
times the whole process (interpreter start-up included).  The runs come in interleaved pairs -- the baseline
``import numpy, scipy.special`` and ``import persson_fp`` back to back, their order alternating from pair to pair
-- so machine load affects both sides alike.  Reported: the medians over the ``--repeats`` pairs (default 15) and
the median of the per-pair ratios.  With ``--baseline-src DIR`` a third statement, ``import persson_fp`` from the
source tree ``DIR`` (say an export of an older commit, named by ``--baseline-label``), joins every round.

The ``persson_fp`` measured is the one this interpreter imports (its folder is put first on the children's
``PYTHONPATH``).

Output: import_time.csv (one row per run) and import_time.md.

    python benchmarks/import_time.py [--quick] [--repeats 15] [--baseline-src DIR]
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402

BASELINE = "import numpy, scipy.special"
TARGET = "import persson_fp"
HEAVY = ("scipy.optimize", "scipy.stats", "scipy.integrate", "scipy.sparse", "scipy.interpolate", "scipy.linalg")

_CHILD = (
    "import sys, time, json\n"
    "n0 = len(sys.modules)\n"
    "t0 = time.perf_counter()\n"
    "{statement}\n"
    "t1 = time.perf_counter()\n"
    "heavy = sorted(h for h in {heavy!r} if h in sys.modules)\n"
    "print(json.dumps({{'seconds': t1 - t0, 'modules': len(sys.modules) - n0, 'heavy': heavy}}))\n"
)


def _src_of_this_package() -> str:
    import persson_fp

    return os.path.dirname(os.path.dirname(os.path.abspath(persson_fp.__file__)))


def run_once(statement: str, src: str) -> dict:
    """One fresh interpreter running ``statement`` with ``src`` first on its path: its timings and module count."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (src, env.get("PYTHONPATH", "")) if p)
    code = _CHILD.format(statement=statement, heavy=HEAVY)
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True, env=env)
    wall = time.perf_counter() - t0
    res = json.loads(out.stdout.strip().splitlines()[-1])
    res["process_seconds"] = wall
    return res


def main(argv=None):
    p = parser(__doc__)
    p.add_argument("--baseline-src", default=None, help="also time `import persson_fp` from this source tree")
    p.add_argument("--baseline-label", default="an older tree", help="what --baseline-src holds (for the table)")
    args = p.parse_args(argv)
    out = outdir(args)
    repeats = args.repeats or (3 if args.quick else 15)
    src = _src_of_this_package()
    cases = [("baseline", BASELINE, src), ("persson_fp", TARGET, src)]
    if args.baseline_src:
        cases.append((f"persson_fp ({args.baseline_label})", TARGET, os.path.abspath(args.baseline_src)))
    print(machine())
    for _, statement, s in cases:  # untimed: warm the file caches once
        run_once(statement, s)

    rows = []
    for i in range(repeats):
        order = cases if i % 2 == 0 else cases[::-1]
        for label, statement, s in order:
            r = run_once(statement, s)
            rows.append(
                {
                    "pair": i,
                    "case": label,
                    "statement": statement,
                    "import_seconds": r["seconds"],
                    "process_seconds": r["process_seconds"],
                    "modules_loaded": r["modules"],
                    "heavy_scipy_loaded": " ".join(r["heavy"]),
                }
            )
        sys.stderr.write(f"\rpairs: {i + 1}/{repeats}")
    sys.stderr.write("\n")
    write_csv(os.path.join(out, "import_time.csv"), rows)

    def of(label, key):
        return [r[key] for r in rows if r["case"] == label]

    base_imp, base_proc = of("baseline", "import_seconds"), of("baseline", "process_seconds")
    table = []
    summary = {}
    for label, statement, s in cases:
        imp, proc = of(label, "import_seconds"), of(label, "process_seconds")
        ratio = statistics.median(a / b for a, b in zip(imp, base_imp, strict=True))
        ratio_proc = statistics.median(a / b for a, b in zip(proc, base_proc, strict=True))
        summary[label] = ratio
        heavy = sorted({h for r in rows if r["case"] == label for h in r["heavy_scipy_loaded"].split()})
        table.append(
            [
                f"`{statement}`" + ("" if s == src else f" ({args.baseline_label})"),
                f"{1e3 * statistics.median(imp):.0f} ms",
                f"{ratio:.2f}x",
                f"{1e3 * statistics.median(proc):.0f} ms",
                f"{ratio_proc:.2f}x",
                str(int(statistics.median(of(label, "modules_loaded")))),
                ", ".join(heavy) or "none",
            ]
        )
        print(f"{label:26s} import {1e3 * statistics.median(imp):7.1f} ms  ratio {ratio:.2f}x")
    print(f"import persson_fp / import numpy, scipy.special: {summary['persson_fp']:.2f}x (median of paired ratios)")

    cmd = "python benchmarks/import_time.py" + (" --quick" if args.quick else "")
    if args.repeats:
        cmd += f" --repeats {args.repeats}"
    if args.baseline_src:
        cmd += f' --baseline-src DIR --baseline-label "{args.baseline_label}"'
    md = [
        "# Import time",
        "",
        f"Machine: {machine()}",
        f"Command: `{cmd}`; medians of {repeats} interleaved rounds, each statement in a fresh interpreter "
        "(order alternating per round); ratios are the medians of the per-round ratios to the baseline",
        "",
        markdown_table(
            [
                "statement",
                "import (in process)",
                "ratio to baseline",
                "whole process",
                "ratio (whole process)",
                "modules loaded",
                "heavy scipy parts loaded",
            ],
            table,
        ),
        "",
        "The import is timed inside the fresh interpreter (`time.perf_counter` around the statement); the whole "
        "process adds the interpreter's start-up, the same for every row. Heavy scipy parts: "
        + ", ".join(f"`{h}`" for h in HEAVY)
        + ".",
    ]
    with open(os.path.join(out, "import_time.md"), "w") as fh:
        fh.write("\n".join(md) + "\n")
    return rows, summary


if __name__ == "__main__":
    main()
