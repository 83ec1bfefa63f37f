"""The numbers the README and benchmarks/README quote are those of the committed results files.

Each claim is a regular expression on the README text whose groups are numbers, and the same numbers computed from
the results file the benchmark command wrote (``benchmarks/results/``), rounded as the README rounds them.  A
re-measured results file whose numbers moved fails this test until the README quotes them again.
"""

import csv
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"


def _text(name):
    return " ".join((ROOT / name).read_text(encoding="utf8").split())  # line breaks as spaces


def _rows(name):
    with open(RESULTS / name, newline="") as fh:
        return list(csv.DictReader(fh))


def _speed(run, fudge, label, threshold, key="time"):
    """A row of a speed_accuracy_table.csv (``run``: "" for the committed run, "rerun" for the re-run)."""
    rows = _rows(f"{run}/speed_accuracy_table.csv" if run else "speed_accuracy_table.csv")
    row = next(r for r in rows if r["fudge"] == fudge and r["label"] == label and float(r["threshold"]) == threshold)
    return float(row[key])


def _batch(method, n, key):
    row = next(r for r in _rows("batch_scaling.csv") if r["method"] == method and int(r["n_loads"]) == n)
    return float(row[key]) if row[key] else None


def _overhead(row, fudge, key):
    value = next(r for r in _rows("overhead.csv") if r["row"] == row and r["fudge"] == fudge)[key]
    return value if key == "note" else float(value)


_WHOLE = "pf.solve(problem, 'sines'): whole call"


def _pypde(fudge, n_p, key):
    """A row of overhead_pypde.csv: py-pde's explicit Euler on ``n_p`` cells against the whole sines call."""
    return float(
        next(r for r in _rows("overhead_pypde.csv") if r["fudge"] == fudge and int(r["pypde_n_p"]) == n_p)[key]
    )


def _whole_call_ratio(fudge):
    note = _overhead("pf.solve(problem, 'sines'): whole call", fudge, "note")
    return float(re.search(r"whole call / solver ([\d.]+)x", note).group(1))


def _general(scene, method, setting=None, target=None, key="call_time_s", csv_name="general_engine.csv"):
    """A row of general_engine.csv: the named ``setting``, or the fastest run of ``method`` with L1 <= ``target``."""
    rows = [r for r in _rows(csv_name) if r["scene"] == scene and r["method"] == method]
    if setting is not None:
        return float(next(r for r in rows if r["setting"] == setting)[key])
    return float(min((r for r in rows if float(r["L1"]) <= target), key=lambda r: float(r["call_time_s"]))[key])


_BESQ = "B2 = (1 + p/(2 p_bar)) dV/dzeta"
_RERUN = "rerun/general_engine.csv"


_PR2 = "the README's example"


def _auto_tol_rows(scene="scene B"):
    return [r for r in _rows("plasticity_auto_tol.csv") if r["scene"] == scene]


def _auto_tol(tol, scene="scene B", key="time_s"):
    return float(next(r for r in _auto_tol_rows(scene) if float(r["tol"]) == tol)[key])


def _auto_tol_all_met():
    """Every tol 1e-3 ... 1e-8 of scene B in plasticity_auto_tol.csv met, each estimate above its true error."""
    rows = _auto_tol_rows()
    return [float(r["tol"]) for r in rows] == [10.0**-k for k in range(3, 9)] and all(
        r["status"] == "ok" and r["meets_tol"] == "True" and r["estimate_covers"] == "True" for r in rows
    )


def _growth(method):
    return _batch(method, 10_000, "time_1_thread") / _batch(method, 1000, "time_1_thread")


def _sig(x, n):
    """``x`` to ``n`` significant digits, as a string like the README writes it."""
    return f"{float(f'{x:.{n}g}'):g}"


# (README file, pattern with one group per number, the numbers from the results, significant digits)
CLAIMS = {
    "overhead: pf.exact and with_loads (README)": (
        "README.md",
        r"for one load ([\d.]+) us, ([\d.]+)x a bare .*? A new load through `problem.with_loads\(p\)` ([\d.]+) us "
        r"\(([\d.]+) us with YP08",
        lambda: [
            _overhead("pf.exact(problem).contact_area, one scalar load", "none", "seconds_per_call") * 1e6,
            _overhead("pf.exact(problem).contact_area, one scalar load", "none", "ratio_to_erf"),
            _overhead("pf.exact(problem.with_loads(p)).contact_area", "none", "seconds_per_call") * 1e6,
            _overhead("pf.exact(problem.with_loads(p)).contact_area", "YP08", "seconds_per_call") * 1e6,
        ],
        3,
    ),
    "overhead: the whole sines call (README)": (
        "README.md",
        r"call costs ([\d.]+) us, ([\d.]+)x the solver's own time \(`sol.wall_time`, ([\d.]+) us: .*?; ([\d.]+)x with "
        r"YP08; .*?: the ([\d.]+) us above it",
        lambda: [
            _overhead(_WHOLE, "none", "seconds_per_call") * 1e6,
            _whole_call_ratio("none"),
            _overhead(_WHOLE, "none", "core_seconds") * 1e6,
            _whole_call_ratio("YP08"),
            _overhead(_WHOLE, "none", "overhead_seconds") * 1e6,
        ],
        3,
    ),
    "overhead: the whole sines call against py-pde's compiled stepper (README)": (
        "README.md",
        r"for L1 ≤ 1e-3 ([\d.]+) ms on 25 cells against ([\d.]+) ms \(sines ([\d.]+)x the stepper; YP08 ([\d.]+) ms on "
        r"50 cells against ([\d.]+) ms, ([\d.]+)x\), for L1 ≤ 1e-5 ([\d.]+) ms on 100 cells against ([\d.]+) ms "
        r"\(([\d.]+)x;",
        lambda: [
            _pypde("none", 25, "pypde_stepper_s") * 1e3,
            _pypde("none", 25, "sines_whole_call_s") * 1e3,
            _pypde("none", 25, "sines_over_stepper"),
            _pypde("YP08", 50, "pypde_stepper_s") * 1e3,
            _pypde("YP08", 50, "sines_whole_call_s") * 1e3,
            _pypde("YP08", 50, "sines_over_stepper"),
            _pypde("none", 100, "pypde_stepper_s") * 1e3,
            _pypde("none", 100, "sines_whole_call_s") * 1e3,
            _pypde("none", 100, "sines_over_stepper"),
        ],
        [2, 2, 3, 2, 2, 3, 3, 2, 2],
    ),
    "general engine: chebyshev against the peers (README)": (
        "README.md",
        r"L1 ≤ 1e-6 in ([\d.]+) ms, ≤ 1e-8 in ([\d.]+) ms, ≤ 1e-10 in ([\d.]+) ms \(asked tol .*? a hand-written "
        r"Crank–Nicolson ([\d.]+) ms for 1e-4 and ([\d.]+) s for 1e-6, FiPy .*? ([\d.]+) s for 1e-4 and does not reach "
        r"1e-6 \(([\d.e-]+) in ([\d.]+) s, 3200 cells\), py-pde .*? ([\d.]+) s for 1e-4",
        lambda: [
            _general(_BESQ, "chebyshev", "tol=1e-06") * 1e3,
            _general(_BESQ, "chebyshev", "tol=1e-08") * 1e3,
            _general(_BESQ, "chebyshev", "tol=1e-10") * 1e3,
            _general(_BESQ, "hand Crank-Nicolson", target=1e-4) * 1e3,
            _general(_BESQ, "hand Crank-Nicolson", target=1e-6),
            _general(_BESQ, "FiPy (Crank-Nicolson, LU)", target=1e-4),
            _general(_BESQ, "FiPy (Crank-Nicolson, LU)", "cells=3200, steps=400", key="L1"),
            _general(_BESQ, "FiPy (Crank-Nicolson, LU)", "cells=3200, steps=400"),
            _general(_BESQ, "py-pde (numba, adaptive RK)", target=1e-4),
        ],
        [2, 2, 2, 2, 3, 2, 2, 3, 3],
    ),
    "general engine: the re-run of the current code (README)": (
        "README.md",
        r"\(the hand Crank–Nicolson ([\d.]+) ms for 1e-4, ([\d.]+) s for 1e-6\): chebyshev reached L1 ≤ 1e-6 in "
        r"([\d.]+) ms \(its tol=1e-4 run, true L1 ([\d.e-]+)\) and ≤ 1e-8 in ([\d.]+) ms; "
        r".*?\(([\d.]+) ms against ([\d.]+) ms:",
        lambda: [
            _general(_BESQ, "hand Crank-Nicolson", target=1e-4, csv_name=_RERUN) * 1e3,
            _general(_BESQ, "hand Crank-Nicolson", target=1e-6, csv_name=_RERUN),
            _general(_BESQ, "chebyshev", target=1e-6, csv_name=_RERUN) * 1e3,
            _general(_BESQ, "chebyshev", "tol=0.0001", key="L1", csv_name=_RERUN),
            _general(_BESQ, "chebyshev", target=1e-8, csv_name=_RERUN) * 1e3,
            _general("B2 = dV/dzeta", "hand Crank-Nicolson", target=1e-4, csv_name=_RERUN) * 1e3,
            _general("B2 = dV/dzeta", "chebyshev", target=1e-4, csv_name=_RERUN) * 1e3,
        ],
        [2, 3, 3, 2, 2, 2, 2],
    ),
    "plasticity: auto on the moving wall at every tol (README)": (
        "README.md",
        r"`method=\"auto\"` meets every tol from 1e-3 to 1e-8, .*? ([\d.]+) ms for 1e-5, ([\d.]+) ms for 1e-6, "
        r"([\d.]+) s for 1e-7, ([\d.]+) s for 1e-8",
        lambda: [
            _auto_tol(1e-5) * 1e3,
            _auto_tol(1e-6) * 1e3,
            _auto_tol(1e-7),
            _auto_tol(1e-8),
        ],
        3,
    ),
    "plasticity: auto on the README's moving-wall example (README)": (
        "README.md",
        r"it meets 1e-3 to 1e-6 \(([\d.]+) s for 1e-6\) and refuses 1e-7 and 1e-8 .*? its best run there reached "
        r"([\d.e-]+)\)",
        lambda: [_auto_tol(1e-6, _PR2), _best_refused_L1()],
        [3, 2],
    ),
    "batch: exact at 1e4 loads (README, closed form)": (
        "README.md",
        r"1e4 loads in ([\d.]+) ms \(`batch_scaling.py`\)",
        lambda: [_batch("exact", 10_000, "time_1_thread") * 1e3],
        3,
    ),
    "speed: sines vs py-pde at 1e-3 (README)": (
        "README.md",
        r"`sines` ([\d.]+) ms \(YP08 ([\d.]+) ms\) against py-pde's explicit Euler through `pf.solve` ([\d.]+) ms "
        r"\(YP08 ([\d.]+) ms\): ([\d.]+)x and ([\d.]+)x in the committed run, ([\d.]+)x and ([\d.]+)x in a re-run",
        lambda: [
            _speed("", "none", "sines", 1e-3) * 1e3,
            _speed("", "YP08", "sines", 1e-3) * 1e3,
            _speed("", "none", "py-pde euler", 1e-3) * 1e3,
            _speed("", "YP08", "py-pde euler", 1e-3) * 1e3,
            _speed("", "none", "py-pde euler", 1e-3, "ratio_to_best_own"),
            _speed("", "YP08", "py-pde euler", 1e-3, "ratio_to_best_own"),
            _speed("rerun", "none", "py-pde euler", 1e-3, "ratio_to_best_own"),
            _speed("rerun", "YP08", "py-pde euler", 1e-3, "ratio_to_best_own"),
        ],
        [2, 2, 2, 2, 3, 3, 3, 3],
    ),
    "speed: the re-run's ratios (benchmarks README)": (
        "benchmarks/README.md",
        r"benchmarks/results/rerun`\) measured ([\d.]+)x and ([\d.]+)x",
        lambda: [_speed("rerun", f, "py-pde euler", 1e-3, "ratio_to_best_own") for f in ("none", "YP08")],
        3,
    ),
    "speed: the re-run's times (README)": (
        "README.md",
        r"sines ([\d.]+) / ([\d.]+) ms, py-pde ([\d.]+) / ([\d.]+) ms\)",
        lambda: [_speed("rerun", f, m, 1e-3) * 1e3 for m in ("sines", "py-pde euler") for f in ("none", "YP08")],
        3,
    ),
    "batch: BLAS threads (README)": (
        "README.md",
        r"which was ([\d.]+)x faster than numpy's two threads for mol \(100 loads\) and ([\d.]+)x for sines \(1000",
        lambda: [_batch("mol", 100, "default_over_1_thread"), _batch("sines", 1000, "default_over_1_thread")],
        2,
    ),
    "batch: 1e4 loads (README)": (
        "README.md",
        r"1e4 loads: `pf.exact` ([\d.]+) ms, `sines` ([\d.]+) ms, `fv` ([\d.]+) s \(([\d.]+) MB\), `mol` ([\d.]+) s "
        r"\(([\d.]+) MB\)",
        lambda: [
            _batch("exact", 10_000, "time_1_thread") * 1e3,
            _batch("sines", 10_000, "time_1_thread") * 1e3,
            _batch("fv", 10_000, "time_1_thread"),
            _batch("fv", 10_000, "peak_MB"),
            _batch("mol", 10_000, "time_1_thread"),
            _batch("mol", 10_000, "peak_MB"),
        ],
        3,
    ),
    "batch: growth (README)": (
        "README.md",
        r"the time grew ([\d.]+)x \(exact\), ([\d.]+)x \(fv\) and ([\d.]+)x \(sines\)",
        lambda: [_growth("exact"), _growth("fv"), _growth("sines")],
        3,
    ),
    "batch: growth (benchmarks README)": (
        "benchmarks/README.md",
        r"From 1000 to 1e4 loads: exact ([\d.]+)x the time, fv ([\d.]+)x, sines ([\d.]+)x, mol ([\d.]+)x",
        lambda: [_growth("exact"), _growth("fv"), _growth("sines"), _growth("mol")],
        3,
    ),
    "batch: BLAS threads (benchmarks README)": (
        "benchmarks/README.md",
        r"([\d.]+)x faster for mol with 100 loads and ([\d.]+)x for sines with 1000",
        lambda: [_batch("mol", 100, "default_over_1_thread"), _batch("sines", 1000, "default_over_1_thread")],
        3,
    ),
    "batch: memory (benchmarks README)": (
        "benchmarks/README.md",
        r"\(fv ([\d.]+) MB, sines ([\d.]+) MB, exact ([\d.]+) MB, mol ([\d.]+) MB\)",
        lambda: [
            max(float(r["peak_MB"]) for r in _rows("batch_scaling.csv") if r["method"] == m and r["peak_MB"])
            for m in ("fv", "sines", "exact", "mol")
        ],
        3,
    ),
}


@pytest.mark.parametrize("claim", list(CLAIMS))
def test_readme_quotes_the_results_file(claim):
    doc, pattern, numbers, digits = CLAIMS[claim]
    m = re.search(pattern, _text(doc))
    assert m, f"{claim}: the sentence is no longer in {doc} (update CLAIMS with the README)"
    values = numbers()
    digits = digits if isinstance(digits, list) else [digits] * len(values)
    quoted = [_sig(float(g), d) for g, d in zip(m.groups(), digits)]
    measured = [_sig(v, d) for v, d in zip(values, digits)]
    assert quoted == measured, f"{claim}: {doc} says {quoted}, the results file {measured}"


def test_mol_runs_1e4_loads_at_the_default_budget_in_the_results():
    """mol's memory model follows its traced peaks: 1000 and 1e4 loads run at the default max_memory."""
    assert _batch("mol", 1000, "time_1_thread") > 0 and _batch("mol", 10_000, "time_1_thread") > 0
    assert _batch("mol", 10_000, "peak_MB") < 300


def test_readme_states_the_accuracy_of_an_earlier_station():
    """The README's figures for an earlier output station are what fv's defaults give (recomputed here: 2 ms)."""
    import persson_fp as pf

    m = re.search(r"L1 ([\d.e-]+) at ζ = 2 against ([\d.e-]+) at ζ_max", _text("README.md"))
    assert m, "the sentence on earlier stations is no longer in README.md"
    pr = pf.ContactProblem.reference()
    L1 = pf.solve(pr, "fv", zeta_out=[2.0, pr.zeta_max]).compare().L1.ravel()
    assert [_sig(float(g), 2) for g in m.groups()] == [_sig(x, 2) for x in L1]
    assert pf.solve(pr, "fv", zeta_out=[2.0, pr.zeta_max]).error_estimate["L1"].shape == (2, 1)  # (station, load)


def _best_refused_L1():
    """The smallest L1 estimate that the refusals of the README's example name ("best so far: L1 ...")."""
    rows = [r for r in _auto_tol_rows(_PR2) if r["status"] != "ok"]
    return min(float(re.search(r"best so far: L1 ([\d.e-]+)", r["status"]).group(1)) for r in rows)


def test_readme_auto_on_the_readmes_moving_wall_example():
    """As the README says: 1e-3 ... 1e-6 met, 1e-7 and 1e-8 refused by a SolverError (not a wrong answer)."""
    rows = {float(r["tol"]): r for r in _auto_tol_rows(_PR2)}
    assert [rows[10.0**-k]["meets_tol"] for k in range(3, 7)] == ["True"] * 4
    assert all(rows[t]["status"].startswith("SolverError: fv: tol") for t in (1e-7, 1e-8))


def test_readme_auto_meets_every_tol_on_the_moving_wall():
    """The README says auto meets every tol 1e-3 ... 1e-8 on the moving wall with each estimate above its true error:
    so does the results file."""
    assert "meets every tol from 1e-3 to 1e-8" in _text("README.md")
    assert _auto_tol_all_met()
