"""fv step placement: L1 at zeta_max and worst over the stations, for "graded", "tau" and "geometric".

Reproduces the numbers quoted in the ``stepping`` option of ``persson_fp.solvers.fv`` (reference
problem, default 100 steps; one station, 3 stations 4/32/128, 24 stations geometric from zeta = 1.5).

    python benchmarks/fv_stepping.py [--quick]
"""

from __future__ import annotations

import sys
import warnings

import numpy as np

import persson_fp as pf

sys.path.insert(0, __import__("os").path.dirname(__file__))
from _common import outdir, parser, write_csv  # noqa: E402


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    stations = {"1": None, "3": [4.0, 32.0, 128.0], "24": list(np.geomspace(1.5, 128.0, 24))}
    fudges = [None] if args.quick else [None, "YP08"]
    rows = []
    for f in fudges:
        pr = pf.ContactProblem.reference(fudge=f)
        for label, zo in stations.items():
            for st in ("graded", "tau", "geometric"):
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    sol = pf.solve(pr, "fv", zeta_out=zo, stepping=st)
                L1 = sol.compare().L1[:, 0]
                rows.append(
                    {"fudge": f or "none", "stations": label, "stepping": st, "L1_final": L1[-1], "L1_worst": L1.max()}
                )
                print(f"{f or 'none':5s} {label:>3s} stations {st:9s} final {L1[-1]:.2e}  worst {L1.max():.2e}")
    write_csv(f"{out}/fv_stepping.csv", rows)
    print(f"wrote {out}/fv_stepping.csv")
    return rows


if __name__ == "__main__":
    main()
