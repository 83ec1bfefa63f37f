"""Fingerprint table of persson-fp's numerical behaviour, for checking that an internal change altered no number.

Run it before and after an internal change (a reorganisation of ``persson_fp.solvers``, a refactor of a
method's internals): the two tables must agree to 1e-12 relative.  It solves a fixed list of about sixty
deterministic scenes -- every method of ``pf.METHODS`` (py-pde and FiPy when importable, on small grids), the
closed form with batches of loads and several output stations, the fudge factors YP08 / WM17 / Xu24, a constant
hardness and a moving yield wall, general Fokker-Planck coefficients, ``tol=`` runs and ``method="auto"`` --
through the public API only (``pf.solve``, ``pf.exact``, ``Solution.compare()``, ``.error_estimate``,
``.info``), so that the same file runs unchanged on both sides of the change.

For every scene, load and station it records the contact area A* (full precision), the L1 error of P0 (the
true one against the closed form where one exists, otherwise the solver's own estimate), the
``Solution.error_estimate`` L1 and a note of ``key=value`` items (area error, plastic area, Monte Carlo
standard error, the method ``auto`` chose, chebyshev's path, steps, warning categories).  A scene that raises
records the exception type and the first line of its message instead.  Every random number generator is
fixed, and BLAS runs on one thread.

Usage::

    python tools/fingerprint.py                          # print the table
    python tools/fingerprint.py --output before.csv      # ... and write it as CSV
    python tools/fingerprint.py --only ref-              # only the scenes whose name contains "ref-"
    python tools/fingerprint.py --compare before.csv after.csv

``--compare`` prints, for every row, the largest relative difference of A, L1 and estimate (and of the
numbers in the note); a row above 1e-12 relative, a changed text (exception, path, method) or a row present
in one table only is flagged, and the exit status is 1 if any row is.
"""

from __future__ import annotations

import os

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")  # one BLAS thread everywhere: the same sums in the same order

import argparse  # noqa: E402
import csv  # noqa: E402
import importlib.util  # noqa: E402
import math  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402

import numpy as np  # noqa: E402

import persson_fp as pf  # noqa: E402

COLUMNS = ["scene", "method", "load_index", "zeta", "A", "L1", "estimate", "note"]
RTOL = 1e-12
"""Largest relative difference two tables may show."""
FLOOR = 1e-300
"""Absolute floor of the relative difference's denominator."""
MISSING = "-"
MC_ENTROPY = 20240611
"""The Monte Carlo generator's fixed entropy (its option of that name in ``OPTIONS``)."""


# -- the problems -------------------------------------------------------------------------------------------------
def _readme_psd():
    """The README's spectrum: rms slope 0.1, H = 0.8, q_l = 1, q_r = 2, q_s = 128."""
    return pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)


def _small_psd():
    """A shorter spectrum (zeta_max = 32) for the slower general-coefficient runs."""
    return pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=32.0)


def _tabulated_psd():
    """The README's spectrum as a table of 41 points (log-log interpolation reproduces it)."""
    psd = _readme_psd()
    q = np.geomspace(1.0, 128.0, 41)
    return pf.TabulatedPSD(q, psd.C(q))


LOADS = np.array([0.01, 0.025, 0.1])
"""The README's batch of loads (pressure, E* = 1)."""


def _batch(fudge=None, psd=None):
    return pf.ContactProblem(_readme_psd() if psd is None else psd, E_star=1.0, p_bar=LOADS, fudge=fudge)


def _hard_const():
    """A constant yield stress just above the load: the strip, exact."""
    return pf.ContactProblem(_readme_psd(), E_star=1.0, p_bar=0.03, hardness=0.08)


def _hard_moving():
    """sigma_Y = 0.035 zeta^0.2: a moving yield wall, no closed form."""
    hardness = pf.hardness.PowerLaw(sigma_1=0.035, n=0.2)
    return pf.ContactProblem(_readme_psd(), E_star=1.0, p_bar=0.03, hardness=hardness)


def _fp_bessel(psd=None, p_bar=None):
    """B2 = (1 + p / (2 p_bar)) dV/dzeta: separable, a squared-Bessel process."""
    psd = _readme_psd() if psd is None else psd
    ref = pf.ContactProblem(psd, p_bar=1.0)
    pb = 0.5 * math.sqrt(float(ref.V_max)) if p_bar is None else p_bar

    def B2(p, z):
        return (1.0 + p / (2.0 * pb)) * float(psd.dV_dzeta(z))

    return pf.FokkerPlanckProblem(psd, E_star=1.0, p_bar=pb, B2=B2)


def _fp_clock():
    """B2 = kappa V'(zeta)(1 + a V / V_max), B1 = mu B2: a clock other than V, with drift."""
    psd = _readme_psd()
    v_max = float(pf.ContactProblem(psd, p_bar=1.0).V_max)
    kappa, a = 1.3, 0.7
    mu = 0.4 / math.sqrt(kappa * v_max)
    pb = 0.8 * math.sqrt(kappa * v_max)

    def B2(p, z):
        return np.full(np.shape(p), kappa * float(psd.dV_dzeta(z)) * (1.0 + a * float(psd.V(z)) / v_max))

    def B1(p, z):
        return mu * B2(p, z)

    return pf.FokkerPlanckProblem(psd, E_star=1.0, p_bar=pb, B1=B1, B2=B2)


def _fp_nonseparable():
    """B2 = V'(1 + 0.2 (p / p_bar) ln zeta): not separable, chebyshev's adaptive march."""
    psd = _small_psd()
    pb = 0.5 * math.sqrt(float(pf.ContactProblem(psd, p_bar=1.0).V_max))

    def B2(p, z):
        return float(psd.dV_dzeta(z)) * (1.0 + 0.2 * (p / pb) * math.log(z))

    return pf.FokkerPlanckProblem(psd, E_star=1.0, p_bar=pb, B2=B2)


def _fp_const_hardness():
    """The homogenised coefficients (B2 = None) with a constant hardness, as a FokkerPlanckProblem."""
    return pf.FokkerPlanckProblem(_readme_psd(), E_star=1.0, p_bar=0.03, hardness=0.08)


def _ref(fudge=None, **kw):
    return lambda: pf.ContactProblem.reference(fudge=fudge, **kw)


STATIONS = [2.0, 8.0, 32.0, 128.0]
STATIONS_SHORT = [4.0, 32.0]
MC = {"n_walkers": 20_000, "seed": MC_ENTROPY}

# (name, problem factory, method, keyword arguments of pf.solve, needs an optional package)
SCENES = [
    # the closed form: the reference problem through every method
    ("ref-sines", _ref(), "sines", {}, None),
    ("ref-fv", _ref(), "fv", {}, None),
    ("ref-mol", _ref(), "mol", {}, None),
    ("ref-chebyshev", _ref(), "chebyshev", {}, None),
    ("ref-ck", _ref(), "chapman-kolmogorov", {}, None),
    ("ref-mc", _ref(), "monte-carlo", MC, None),
    ("ref-pypde", _ref(), "py-pde", {"n_p": 40}, "pde"),
    ("ref-fipy", _ref(), "fipy", {"n_p": 60, "n_steps": 40}, "fipy"),
    # the methods' options, on the reference problem
    ("opt-fv-explicit", _ref(), "fv", {"scheme": "explicit", "space": "fv2", "n_p": 50, "n_steps": 400}, None),
    ("opt-fv-implicit-geometric", _ref("YP08"), "fv", {"scheme": "implicit", "stepping": "geometric"}, None),
    (
        "opt-fv-rannacher-banded",
        _ref("YP08"),
        "fv",
        {"scheme": "rannacher", "linalg": "banded", "coupling": "picard", "stepping": "zeta"},
        None,
    ),
    ("opt-fv-delta", _ref(), "fv", {"initial": "delta", "n_p": 100, "n_steps": 200, "stepping": "tau"}, None),
    ("opt-mol-radau-zeta", _ref("YP08"), "mol", {"integrator": "Radau", "variable": "zeta", "n_p": 80}, None),
    ("opt-mol-rk45", _ref(), "mol", {"integrator": "RK45", "order": 2, "n_p": 40}, None),
    ("opt-ck-exact-start", _ref("WM17"), "chapman-kolmogorov", {"initial": "exact", "n_p": 200, "n_steps": 20}, None),
    ("opt-mc-nobridge", _ref("WM17"), "monte-carlo", {**MC, "bridge": False, "n_steps": 16, "check": False}, None),
    ("opt-sines-tol", _ref(p_bar_ratio=[0.1, 2.0]), "sines", {"tol": 1e-6}, None),
    ("opt-chebyshev-magnus", _fp_bessel, "chebyshev", {"march": "magnus", "tol": 1e-5}, None),
    (
        "opt-fipy-implicit",
        _ref("YP08"),
        "fipy",
        {"scheme": "implicit", "stepping": "V", "n_p": 40, "n_steps": 30},
        "fipy",
    ),
    # a batch of loads at several stations
    ("batch-sines", _batch, "sines", {"zeta_out": STATIONS}, None),
    ("batch-fv", _batch, "fv", {"zeta_out": STATIONS}, None),
    ("batch-fv-cn", _batch, "fv", {"zeta_out": STATIONS, "scheme": "crank-nicolson", "n_p": 120}, None),
    ("batch-mol", _batch, "mol", {"zeta_out": STATIONS_SHORT}, None),
    ("batch-mol-o2", _batch, "mol", {"order": 2, "n_p": 150}, None),
    ("batch-chebyshev", _batch, "chebyshev", {"zeta_out": STATIONS}, None),
    ("batch-ck", _batch, "chapman-kolmogorov", {"zeta_out": STATIONS_SHORT}, None),
    ("batch-tabulated-sines", lambda: _batch(psd=_tabulated_psd()), "sines", {"zeta_out": STATIONS_SHORT}, None),
    # fudge factors
    ("yp08-sines", _ref("YP08", p_bar_ratio=[0.2, 0.5, 1.5]), "sines", {}, None),
    ("yp08-fv", _ref("YP08", p_bar_ratio=[0.2, 0.5, 1.5]), "fv", {}, None),
    ("yp08-mc", _ref("YP08"), "monte-carlo", MC, None),
    ("yp08-pypde-numpy", _ref("YP08"), "py-pde", {"n_p": 30, "backend": "numpy"}, "pde"),
    ("wm17-fv", lambda: _batch("WM17"), "fv", {"zeta_out": STATIONS_SHORT}, None),
    ("wm17-mol", _ref("WM17"), "mol", {}, None),
    ("wm17-fipy", _ref("WM17"), "fipy", {"n_p": 60, "n_steps": 40}, "fipy"),
    ("xu24-sines", lambda: _batch("Xu24"), "sines", {"zeta_out": STATIONS}, None),
    ("xu24-ck", _ref("Xu24"), "chapman-kolmogorov", {}, None),
    ("xu24-fv", _ref("Xu24"), "fv", {"n_p": 100, "n_steps": 50}, None),
    # hardness: a constant yield stress (closed form) and a moving yield wall (estimates)
    ("hard-const-sines", _hard_const, "sines", {}, None),
    ("hard-const-fv", _hard_const, "fv", {"zeta_out": STATIONS_SHORT}, None),
    ("hard-const-mol", _hard_const, "mol", {}, None),
    ("hard-const-chebyshev", _hard_const, "chebyshev", {}, None),
    (
        "hard-const-yp08-fv",
        lambda: pf.ContactProblem(_readme_psd(), p_bar=0.03, hardness=0.08, fudge="YP08"),
        "fv",
        {},
        None,
    ),
    (
        "hard-const-yp08-sines",
        lambda: pf.ContactProblem(_readme_psd(), p_bar=[0.02, 0.03], hardness=0.08, fudge="YP08"),
        "sines",
        {},
        None,
    ),
    ("hard-moving-fv", _hard_moving, "fv", {"zeta_out": STATIONS_SHORT + [128.0]}, None),
    ("hard-moving-mol", _hard_moving, "mol", {"n_p": 100}, None),
    ("hard-moving-chebyshev", _hard_moving, "chebyshev", {"tol": 1e-4}, None),
    ("hard-moving-auto", _hard_moving, "auto", {"tol": 1e-4}, None),
    # general Fokker-Planck coefficients
    ("fp-bessel-chebyshev", _fp_bessel, "chebyshev", {"tol": 1e-8}, None),
    ("fp-bessel-fv", _fp_bessel, "fv", {"zeta_out": STATIONS_SHORT + [128.0]}, None),
    ("fp-bessel-mol", lambda: _fp_bessel(_small_psd()), "mol", {"n_p": 100}, None),
    ("fp-clock-chebyshev", _fp_clock, "chebyshev", {"tol": 1e-8, "zeta_out": STATIONS}, None),
    ("fp-nonsep-chebyshev", _fp_nonseparable, "chebyshev", {"tol": 1e-4}, None),
    ("fp-nonsep-fv", _fp_nonseparable, "fv", {"n_p": 100, "n_steps": 100}, None),
    ("fp-hard-chebyshev", _fp_const_hardness, "chebyshev", {"tol": 1e-8}, None),
    ("fp-auto", lambda: _fp_bessel(_small_psd()), "auto", {"tol": 1e-5}, None),
    # tol= runs and method="auto" on the closed form
    ("tol-fv", _ref(), "fv", {"tol": 1e-6}, None),
    ("tol-mol-yp08", _ref("YP08"), "mol", {"tol": 1e-5}, None),
    ("auto-default", lambda: _batch(), "auto", {}, None),
    ("auto-wm17-stations", lambda: _batch("WM17"), "auto", {"tol": 1e-7, "zeta_out": STATIONS_SHORT}, None),
    # refusals: the exception is the fingerprint
    ("refuse-ck-tol", _ref(), "chapman-kolmogorov", {"tol": 1e-6}, None),
    ("refuse-chebyshev-fudge", _ref("WM17"), "chebyshev", {}, None),
    ("refuse-sines-general", _fp_bessel, "sines", {}, None),
    (
        "refuse-chebyshev-moving-yp08",
        lambda: pf.ContactProblem(
            _readme_psd(), p_bar=0.03, hardness=pf.hardness.PowerLaw(sigma_1=0.035, n=0.2), fudge="YP08"
        ),
        "chebyshev",
        {},
        None,
    ),
]


# -- one scene ----------------------------------------------------------------------------------------------------
def _fmt(x) -> str:
    if x is None:
        return MISSING
    return f"{float(x):.17g}"


def _first_line(err: BaseException) -> str:
    text = str(err).strip().splitlines()
    return f"raises {type(err).__name__}: {text[0] if text else ''}"


def _at(a, iz, il):
    return None if a is None else float(np.asarray(a, dtype=float).reshape(-1, np.shape(a)[-1])[iz, il])


def _rows_of(name, method, sol, caught) -> list[list[str]]:
    """The table rows of one solved scene: one per (load, station)."""
    problem = sol.problem
    est = sol.error_estimate
    closed = problem.has_closed_form
    cmp = sol.compare() if closed else None
    L1 = cmp.L1 if closed else est["L1"]
    dA = cmp.area_error if closed else est["contact_area"]
    common = ["est=" + ("true" if est["kind"].startswith("true") else "own")]
    auto = sol.info.get("auto")
    if method == "auto" and isinstance(auto, dict):
        common.append(f"via={auto.get('method')}")
    path = sol.info.get("path")
    if isinstance(path, str):
        common.append(f"path={path}")
    if isinstance(sol.steps, (int, np.integer)):
        common.append(f"steps={int(sol.steps)}")
    if caught:
        common.append("warn=" + "/".join(sorted(caught)))
    rows = []
    for il in range(problem.n_loads):
        for iz, z in enumerate(sol.zeta):
            note = [f"dA={_fmt(_at(dA, iz, il))}"]
            if sol.plastic_area_all is not None:
                note.append(f"A_pl={_fmt(_at(sol.plastic_area_all, iz, il))}")
            if sol.stderr_area_all is not None:
                note.append(f"stderr_A={_fmt(_at(sol.stderr_area_all, iz, il))}")
            rows.append(
                [
                    name,
                    method,
                    str(il),
                    _fmt(z),
                    _fmt(_at(sol.contact_area_all, iz, il)),
                    _fmt(_at(L1, iz, il)),
                    _fmt(_at(est["L1"], iz, il)),
                    ";".join(note + common),
                ]
            )
    return rows


_NOT_COUNTED = (DeprecationWarning, PendingDeprecationWarning, FutureWarning, ImportWarning, ResourceWarning)


def _counts(category) -> bool:
    """A warning of the package's (Python's own categories or its own classes), not an import-time notice of a
    third-party library, which appears only in the scene that happens to import it first."""
    own = category.__module__ == "builtins" or category.__module__.startswith("persson_fp")
    return own and not issubclass(category, _NOT_COUNTED)


def run_scene(name, factory, method, kwargs) -> list[list[str]]:
    """Solve one scene; its rows, or one row naming the exception it raised."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            problem = factory()
            sol = pf.solve(problem, method=method, **kwargs)
            return _rows_of(name, method, sol, {w.category.__name__ for w in caught if _counts(w.category)})
        except Exception as err:  # a refusal is a fingerprint too
            return [[name, method, MISSING, MISSING, MISSING, MISSING, MISSING, _first_line(err)]]


def _print_scene(rows) -> None:
    name, method = rows[0][0], rows[0][1]
    if rows[0][2] == MISSING:
        cells = [rows[0][7]]
    else:
        cells = [f"l{r[2]} z={float(r[3]):g}: A={r[4]} L1={r[5]} est={r[6]}" for r in rows]
    print(f"{name:<30} {method:<19} " + " | ".join(cells), flush=True)


def make_table(only: str | None = None) -> list[list[str]]:
    table = []
    t_all = time.perf_counter()
    for name, factory, method, kwargs, package in SCENES:
        if only and only not in name:
            continue
        if package is not None and importlib.util.find_spec(package) is None:
            rows = [[name, method, MISSING, MISSING, MISSING, MISSING, MISSING, f"skipped: {package} not importable"]]
        else:
            t0 = time.perf_counter()
            rows = run_scene(name, factory, method, dict(kwargs))
            print(f"  [{name}: {time.perf_counter() - t0:.2f} s]", file=sys.stderr, flush=True)
        _print_scene(rows)
        table.extend(rows)
    print(f"  [{len(table)} rows, {time.perf_counter() - t_all:.1f} s in all]", file=sys.stderr, flush=True)
    return table


def write_csv(path: str, table) -> None:
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(COLUMNS)
        w.writerows(table)


# -- comparing two tables -----------------------------------------------------------------------------------------
def _number(s: str):
    try:
        return float(s)
    except ValueError:
        return None


def _rel(a: str, b: str):
    """Relative difference of two cells: a float, or None where the texts differ and are not both numbers."""
    x, y = _number(a), _number(b)
    if x is None or y is None:
        return 0.0 if a == b else None
    if math.isnan(x) or math.isnan(y):
        return 0.0 if math.isnan(x) and math.isnan(y) else None
    if x == y:  # both zero, or equal infinities
        return 0.0
    if math.isinf(x) or math.isinf(y):
        return math.inf
    return abs(x - y) / max(abs(x), abs(y), FLOOR)


_TEXT_NOTES = ("raises ", "skipped: ")
"""Notes compared as text, exactly."""


def _note_items(note: str) -> dict:
    out = {}
    for i, item in enumerate(note.split(";")):
        key, sep, value = item.partition("=")
        out[key if sep else f"#{i}"] = value if sep else item
    return out


def _compare_rows(old, new):
    """(largest relative difference of A / L1 / estimate / note numbers, list of text mismatches)."""
    worst, texts = 0.0, []
    for col in ("A", "L1", "estimate"):
        r = _rel(old[col], new[col])
        if r is None:
            texts.append(f"{col}: {old[col]!r} -> {new[col]!r}")
        else:
            worst = max(worst, r)
    if old["note"].startswith(_TEXT_NOTES) or new["note"].startswith(_TEXT_NOTES):
        if old["note"] != new["note"]:
            texts.append(f"note: {old['note']!r} -> {new['note']!r}")
        return worst, texts
    a, b = _note_items(old["note"]), _note_items(new["note"])
    for key in sorted(set(a) | set(b)):
        r = _rel(a.get(key, "<none>"), b.get(key, "<none>"))
        if r is None:
            texts.append(f"{key}: {a.get(key, '<none>')!r} -> {b.get(key, '<none>')!r}")
        else:
            worst = max(worst, r)
    return worst, texts


def _read(path: str):
    with open(path, newline="") as fh:
        rows = list(csv.DictReader(fh))
    keyed = {}
    for r in rows:
        head = (r["scene"], r["method"], r["load_index"], r["zeta"])
        k = 0
        while (*head, k) in keyed:  # (the same station twice: told apart by the order written)
            k += 1
        keyed[(*head, k)] = r
    return keyed


def compare(old_path: str, new_path: str) -> int:
    old, new = _read(old_path), _read(new_path)
    keys = list(old) + [k for k in new if k not in old]
    flagged = 0
    print(f"{'scene':<30} {'method':<19} {'load':>4} {'zeta':>8} {'max rel diff':>13}  flag")
    for key in keys:
        o, n = old.get(key), new.get(key)
        if o is None or n is None:
            flagged += 1
            zeta = key[3] if key[3] == MISSING else f"{float(key[3]):g}"
            where = "NEW" if o is None else "OLD"
            print(f"{key[0]:<30} {key[1]:<19} {key[2]:>4} {zeta:>8} {'':>13}  ONLY IN {where}")
            continue
        worst, texts = _compare_rows(o, n)
        bad = worst > RTOL or bool(texts)
        flagged += bad
        zeta = o["zeta"] if o["zeta"] == MISSING else f"{float(o['zeta']):g}"
        flag = ("DIFF " + "; ".join(texts)) if texts else ("DIFF" if bad else "")
        print(f"{key[0]:<30} {key[1]:<19} {o['load_index']:>4} {zeta:>8} {worst:13.3e}  {flag}")
    print(f"{len(keys)} rows compared, {flagged} above {RTOL:g} relative or changed")
    return 1 if flagged else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--output", metavar="FILE", help="also write the table as CSV")
    ap.add_argument("--only", metavar="TEXT", help="run only the scenes whose name contains TEXT")
    ap.add_argument("--compare", nargs=2, metavar=("OLD", "NEW"), help="compare two CSV tables and exit")
    args = ap.parse_args(argv)
    if args.compare:
        return compare(*args.compare)
    print(f"persson_fp {pf.__version__} from {os.path.dirname(pf.__file__)}", file=sys.stderr)
    table = make_table(args.only)
    if args.output:
        write_csv(args.output, table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
