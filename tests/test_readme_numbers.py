"""The numbers benchmarks/README.md quotes are those of the committed results files, and the documentation's
"Performance and accuracy" page is what ``python benchmarks/performance_page.py`` builds from them.

Each claim is a regular expression on the text whose groups are numbers, and the same numbers computed from the
results file the benchmark command wrote (``benchmarks/results/``), rounded as the text rounds them.  A re-measured
results file whose numbers moved fails these tests until the text quotes them again (for the page: until the
command is run again).
"""

import csv
import importlib.util
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


_MOVING_WALL = "scene W (moving wall)"
"""The moving-wall scene's label in plasticity_auto_tol.csv (sigma_Y = 0.035 zeta^0.2, as the benchmark writes it)."""


def _auto_tol_rows(scene="scene B"):
    return [r for r in _rows("plasticity_auto_tol.csv") if r["scene"] == scene]


def _growth(method):
    return _batch(method, 10_000, "time_1_thread") / _batch(method, 1000, "time_1_thread")


def _sig(x, n):
    """``x`` to ``n`` significant digits, as a string like the text writes it."""
    return f"{float(f'{x:.{n}g}'):g}"


# (file, pattern with one group per number, the numbers from the results, significant digits)
CLAIMS = {
    "speed: the re-run's ratios (benchmarks README)": (
        "benchmarks/README.md",
        r"benchmarks/results/rerun`\) measured ([\d.]+)x and ([\d.]+)x",
        lambda: [_speed("rerun", f, "py-pde euler", 1e-3, "ratio_to_best_own") for f in ("none", "YP08")],
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
def test_benchmarks_readme_quotes_the_results_file(claim):
    doc, pattern, numbers, digits = CLAIMS[claim]
    m = re.search(pattern, _text(doc))
    assert m, f"{claim}: the sentence is no longer in {doc} (update CLAIMS with it)"
    values = numbers()
    digits = digits if isinstance(digits, list) else [digits] * len(values)
    quoted = [_sig(float(g), d) for g, d in zip(m.groups(), digits)]
    measured = [_sig(v, d) for v, d in zip(values, digits)]
    assert quoted == measured, f"{claim}: {doc} says {quoted}, the results file {measured}"


def test_mol_runs_1e4_loads_at_the_default_budget_in_the_results():
    """mol's memory model follows its traced peaks: 1000 and 1e4 loads run at the default max_memory."""
    assert _batch("mol", 1000, "time_1_thread") > 0 and _batch("mol", 10_000, "time_1_thread") > 0
    assert _batch("mol", 10_000, "peak_MB") < 300


def test_performance_page_is_what_its_command_builds_from_the_results():
    """docs/performance.md is exactly what benchmarks/performance_page.py builds from benchmarks/results/ (every number
    on the page read from a results file; the earlier-station accuracy recomputed, two fv calls)."""
    spec = importlib.util.spec_from_file_location("performance_page", ROOT / "benchmarks" / "performance_page.py")
    page = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(page)
    committed = (ROOT / "docs" / "performance.md").read_text(encoding="utf8")
    assert committed == page.build(), "docs/performance.md is stale: run python benchmarks/performance_page.py"


def test_auto_on_the_moving_wall_meets_tol_down_to_1e_7():
    """1e-3 ... 1e-7 met against the extrapolated fv reference, each estimate above its true error (the page's table;
    at 1e-8 the true error is the reference's own floor, stated on the page)."""
    rows = {float(r["tol"]): r for r in _auto_tol_rows(_MOVING_WALL)}
    assert [rows[10.0**-k]["meets_tol"] for k in range(3, 8)] == ["True"] * 5
    assert [rows[10.0**-k]["estimate_covers"] for k in range(3, 8)] == ["True"] * 5


def test_auto_meets_every_tol_on_the_constant_hardness_wall():
    """Every tol 1e-3 ... 1e-8 of scene B met, each estimate above its true error."""
    rows = _auto_tol_rows()
    assert [float(r["tol"]) for r in rows] == [10.0**-k for k in range(3, 9)]
    assert all(r["status"] == "ok" and r["meets_tol"] == "True" and r["estimate_covers"] == "True" for r in rows)


def test_earlier_station_error_is_reported_per_station():
    import persson_fp as pf

    pr = pf.ContactProblem.reference()
    sol = pf.solve(pr, "fv", zeta_out=[2.0, pr.zeta_max])
    assert sol.error_estimate["L1"].shape == (2, 1)  # (station, load)
    L1 = sol.compare().L1.ravel()
    assert L1[0] > 10 * L1[1]  # the delta start's early stations are the least accurate
