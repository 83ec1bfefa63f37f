r"""General coefficients: time to reach an L1 accuracy, persson-fp's engines against a hand-written
Crank--Nicolson, py-pde and FiPy, whole calls.

Two scenes on the reference problem (``pf.ContactProblem.reference()``, p_bar = 0.5 sqrt(V(zeta_max))), both as
``pf.FokkerPlanckProblem``:

- ``B2 = dV/dzeta`` -- the homogenised theory; the reference is the closed form ``pf.exact`` (image solution);
- ``B2 = (1 + p/(2 p_bar)) dV/dzeta`` -- X = 8 p_bar (p + 2 p_bar) is then a squared Bessel process of dimension 0
  in V, with free transition density (1/2V) sqrt(x/y) exp(-(x+y)/2V) I_1(sqrt(xy)/V); the reference starts from it
  at V_s = 2e-3 V (where the wall at p = 0 has not yet been felt: p_bar = 9 widths away) and is propagated by a
  Chebyshev collocation with a tan map and one dense matrix exponential, written here (two resolutions: their
  spread, ~1e-10, is the reference's own uncertainty and is reported).

Methods: ``"chebyshev"`` (``tol`` = 1e-4 ... 1e-10; starts from the delta), the old general path ``"fv"``
(``n_p = n_steps``), a Crank--Nicolson written here (uniform cells, a sparse LU factorised once per call) and
py-pde (``pde.PDE`` expression, numba backend, adaptive explicit Runge--Kutta; the compiled stepper is built once
and reused, its compile time is not counted) and FiPy (``Grid1D`` of uniform cells on the same [0, L],
``constrain(0)`` on both faces, ``TransientTerm() == DiffusionTerm(B2/2 at the faces) +
CentralDifferenceConvectionTerm(b'/2)`` -- the conservative form of dP/dV = 1/2 d^2(b P)/dp^2 -- with the
``LinearLUSolver``; Crank--Nicolson from FiPy's implicit terms alone: a backward-Euler half step
(I - h/2 A) Y = P^n, then P^{n+1} = 2 Y - P^n, which is exactly (I - h/2 A)^{-1} (I + h/2 A) P^n; FiPy's
explicit terms are not used, they ignore the constrained faces).  The hand CN, py-pde and FiPy are given *more* start
information than persson-fp: the exact solution at V_s, and the same far wall at L.  Each FiPy call builds its mesh,
variable and equation (as a user's script would) and is timed whole.

Every time is the median of ``--repeats`` whole calls (a call that takes over a second: at most 3; the first call
is not timed).  L1 = int |P0 - reference| dp at zeta_max (the polynomial or the cell values against the reference
on 20 001 points, trapezoid).  Output: general_engine.csv (every run) and general_engine.md (the fastest run of each
method that reaches each target).

    python benchmarks/general_engine.py [--quick] [--repeats 5]
"""

from __future__ import annotations

import os
import statistics
import sys
import time
import warnings

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.special import ive

import persson_fp as pf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests"))
import solvers.chebyshev.test_separable as tcheb  # noqa: E402  (the squared-Bessel reference and the polynomial's L1, written there)

TARGETS = (1e-4, 1e-6, 1e-8, 1e-10)
V_START = 2e-3
"""Start of the hand CN, py-pde and the squared-Bessel reference, as a fraction of V(zeta_max)."""


# -- the scenes and their references --------------------------------------------------------------------------------
def scenes():
    pr = pf.ContactProblem.reference()
    psd, pb = pr.psd, float(pr.p_bar[0])
    return {
        "B2 = dV/dzeta": (pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) + 0.0 * p), 0.0),
        "B2 = (1 + p/(2 p_bar)) dV/dzeta": (
            pf.FokkerPlanckProblem(psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + p / (2 * pb))),
            1.0 / (2 * pb),
        ),
    }


def start_density(p, pb, V, slope):
    """The exact PDF at a small V from the delta at pb: image solution (slope 0) or the free BESQ(0) density."""
    if slope == 0.0:
        g = lambda u: np.exp(-0.5 * u * u / V) / np.sqrt(2 * np.pi * V)  # noqa: E731
        return g(p - pb) - g(p + pb)
    X0, X = 8 * pb * 3 * pb, 8 * pb * (np.maximum(p, 0) + 2 * pb)
    z = np.sqrt(X0 * X) / V
    return 8 * pb / (2 * V) * np.sqrt(X0 / X) * np.exp(-((np.sqrt(X) - np.sqrt(X0)) ** 2) / (2 * V)) * ive(1, z)


def reference(name, pr, slope):
    """(pdf callable, A*, uncertainty of the reference in L1)."""
    pb, V = float(pr.p_bar[0]), float(pr.V_max)
    if slope == 0.0:
        ex = pf.exact(pf.ContactProblem.reference())
        return (lambda q: np.asarray(ex.pdf(q)).ravel()), float(np.ravel(ex.contact_area)[0]), 0.0
    L = pb + 45.0 * np.sqrt(V)
    pdf, A, _ = tcheb.besq_reference(pb, V, n=160, V_start_frac=3e-3, e_k=50.0, L_k=45.0)
    pdf2, A2, _ = tcheb.besq_reference(pb, V, n=200, V_start_frac=1e-3, e_k=8.0, L_k=45.0)
    q = np.linspace(0.0, L, 20001)
    u = max(abs(A - A2), float(np.trapezoid(np.abs(pdf(q) - pdf2(q)), q)))
    return pdf, A, u


# -- the competitors ------------------------------------------------------------------------------------------------
def cell_l1(p_centres, P, dp, pdf):
    """L1 of cell values against the reference's cell averages (3-point Gauss per cell)."""
    gx = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]) * dp / 2
    gw = np.array([5.0, 8.0, 5.0]) / 18.0
    avg = sum(wk * pdf(p_centres + xk) for xk, wk in zip(gx, gw))
    return float(np.sum(np.abs(P - avg)) * dp)


def hand_cn(pb, V, slope, L, n, m):
    """Crank--Nicolson on n uniform cells of [0, L] (P = 0 at both walls), m equal steps from V_s to V."""
    V_s = V_START * V
    dp = L / n
    p = (np.arange(n) + 0.5) * dp
    b = 1 + slope * p
    lap = sp.diags([np.ones(n - 1), -2 * np.ones(n), np.ones(n - 1)], [-1, 0, 1]) / dp**2
    lap = lap.tolil()
    lap[0, 0] = lap[-1, -1] = -3 / dp**2  # ghost cells: P = 0 on the walls
    A = 0.5 * (lap.tocsr() @ sp.diags(b))
    h = (V - V_s) / m
    I = sp.identity(n, format="csc")  # noqa: E741
    lu = spla.splu((I - 0.5 * h * A).tocsc())
    B = (I + 0.5 * h * A).tocsr()
    P = start_density(p, pb, V_s, slope)
    for _ in range(m):
        P = lu.solve(B @ P)
    return p, P, dp


def pypde_stepper(pb, V, slope, L, n, rtol):
    import pde

    V_s = V_START * V
    grid = pde.CartesianGrid([[0.0, L]], n)
    expr = "0.5 * laplace(P)" if slope == 0 else f"0.5 * (1 + {slope!r} * x) * laplace(P) + {slope!r} * d_dx(P)"
    eq = pde.PDE({"P": expr}, bc={"value": 0.0})
    p = grid.axes_coords[0]
    state = pde.ScalarField(grid, start_density(p, pb, V_s, slope))
    solver = pde.ExplicitSolver(eq, scheme="runge-kutta", adaptive=True, tolerance=rtol, backend="numba")
    stepper = solver.make_stepper(state, dt=1e-3 * (L / n) ** 2)
    start = state.data.copy()

    def run():
        state.data[:] = start
        stepper(state, V_s, V)
        return state.data.copy()

    return p, run, L / n


def fipy_cn(pb, V, slope, L, n, m):
    """FiPy on n uniform cells of [0, L] (P = 0 on both faces), m Crank--Nicolson steps from V_s to V, each one
    backward-Euler half step and an extrapolation (module docstring)."""
    import fipy

    V_s = V_START * V
    dp = L / n
    mesh = fipy.Grid1D(nx=n, dx=dp)
    p = np.asarray(mesh.cellCenters.value[0])
    phi = fipy.CellVariable(mesh=mesh, value=start_density(p, pb, V_s, slope))
    phi.constrain(0.0, mesh.facesLeft)
    phi.constrain(0.0, mesh.facesRight)
    # 1/2 d^2(b P)/dp^2 = d/dp (b/2 dP/dp) + d/dp (b'/2 P), b = 1 + slope p
    rhs = fipy.DiffusionTerm(coeff=0.5 * (1.0 + slope * mesh.faceCenters[0]))
    if slope:
        rhs = rhs + fipy.CentralDifferenceConvectionTerm(coeff=(0.5 * slope,))
    eq = fipy.TransientTerm() == rhs
    lin = fipy.LinearLUSolver()
    h = (V - V_s) / m
    for _ in range(m):
        P_n = np.array(phi.value)
        eq.solve(var=phi, dt=0.5 * h, solver=lin)
        phi.setValue(2.0 * np.asarray(phi.value) - P_n)
    return p, np.array(phi.value), dp


def log(msg):
    sys.stderr.write(msg + "\n")
    sys.stderr.flush()


def timed(fn, repeats, slow=1.0):
    fn()  # the first call (not timed)
    t0 = time.perf_counter()
    out = fn()
    times = [time.perf_counter() - t0]
    n = repeats - 1 if times[0] <= slow else min(repeats, 3) - 1
    for _ in range(max(n, 0)):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def main(argv=None):
    args = parser(__doc__).parse_args(argv)
    out = outdir(args)
    repeats = args.repeats or (2 if args.quick else 5)
    rows = []
    for name, (fp, slope) in scenes().items():
        pb, V = float(fp.p_bar[0]), float(fp.V_max)
        pdf, A_ref, u = reference(name, fp, slope)
        L = pb + (10.0 if slope == 0 else 40.0) * np.sqrt(V)

        def add(method, setting, t, l1, est=np.nan, status="ok"):
            log(f"{name} | {method} | {setting}: {t * 1e3:.4g} ms, L1 {l1:.3g}")
            rows.append(
                {
                    "scene": name,
                    "method": method,
                    "setting": setting,
                    "call_time_s": t,
                    "L1": l1,
                    "L1_estimate": est,
                    "reference_uncertainty": u,
                    "status": status,
                }  # fmt: skip
            )

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            for tol in TARGETS[:2] if args.quick else TARGETS:
                try:
                    t, sol = timed(lambda tol=tol: pf.solve(fp, method="chebyshev", tol=tol), max(repeats, 3 * repeats))
                    add("chebyshev", f"tol={tol:g}", t, tcheb.chebyshev_l1(sol, pdf),
                        float(np.max(sol.info["error_estimate"]["L1"])))  # fmt: skip
                except pf.SolverError as err:
                    add("chebyshev", f"tol={tol:g}", np.nan, np.nan, status=f"SolverError: {err}")
            for n in (100,) if args.quick else (200, 400, 800, 1600, 3200):
                t, sol = timed(lambda n=n: pf.solve(fp, method="fv", n_p=n, n_steps=n), repeats)
                pc, dp = np.atleast_2d(sol.p)[-1], float(np.atleast_2d(sol.weights)[-1, 0])
                add("fv (old general path)", f"n_p=n_steps={n}", t, cell_l1(pc, sol.P0_all[-1, 0], dp, pdf),
                    float(np.max(sol.info["error_estimate"]["L1"])))  # fmt: skip
            for n in (200,) if args.quick else (400, 800, 1600, 3200, 6400, 12800, 25600):
                m = max(20, n // 4)
                t, (p, P, dp) = timed(lambda n=n, m=m: hand_cn(pb, V, slope, L, n, m), repeats)
                add("hand Crank-Nicolson", f"cells={n}, steps={m}", t, cell_l1(p, P, dp, pdf))
                if t > 10.0:
                    break
            try:  # (not in --quick: the numba compilation takes ~10 s)
                import pde  # noqa: F401

                have_pde = not args.quick
            except ImportError:
                have_pde = False
            for n in (400, 800, 1600, 3200, 6400) if have_pde else ():
                p, run, dp = pypde_stepper(pb, V, slope, L, n, 1e-9)
                t, P = timed(run, repeats)
                add("py-pde (numba, adaptive RK)", f"cells={n}", t, cell_l1(p, P, dp, pdf))
                if t > 10.0:  # (explicit steps grow as n^2: the next size would take minutes)
                    break
            try:
                import fipy  # noqa: F401

                have_fipy = True
            except ImportError:
                have_fipy = False
            # FiPy costs ~10 ms of Python per step whatever the grid: the steps set its time, so it is also given
            # fewer steps per cell than the hand CN (its best trade of space against time error is among these)
            fipy_runs = [(200, 50)] if args.quick else [(400, 50), (800, 100), (1600, 100), (1600, 200), (3200, 400)]
            for n, m in fipy_runs if have_fipy else ():
                t, (p, P, dp) = timed(lambda n=n, m=m: fipy_cn(pb, V, slope, L, n, m), repeats)
                add("FiPy (Crank-Nicolson, LU)", f"cells={n}, steps={m}", t, cell_l1(p, P, dp, pdf))
                if t > 10.0:
                    break
        rows[-1]["A_ref"] = A_ref
    write_csv(os.path.join(out, "general_engine.csv"), rows)
    table = []
    for name in scenes():
        for method in dict.fromkeys(r["method"] for r in rows):
            cells = [name, method]
            for target in TARGETS:
                ok = [r for r in rows if r["scene"] == name and r["method"] == method and r["L1"] <= target]
                best = min(ok, key=lambda r: r["call_time_s"]) if ok else None
                cells.append(f"{best['call_time_s'] * 1e3:.3g} ms ({best['setting']})" if best else "not reached")
            table.append(cells)
    md = [
        "# General coefficients: time to an L1 target (benchmarks/general_engine.py)",
        "",
        f"Machine: {machine()}. Medians of whole calls; the fastest run of each method that reaches each L1.",
        "The squared-Bessel reference is itself uncertain by the `reference_uncertainty` column of the CSV.",
        "",
        markdown_table(["scene", "method"] + [f"L1 <= {t:g}" for t in TARGETS], table),
        "",
        "`chebyshev` per asked tol (median of 3x the repeats): whole call, true L1, its own estimate",
        "",
        markdown_table(
            ["scene", "tol", "time", "true L1", "estimate"],
            [
                [
                    r["scene"],
                    r["setting"],
                    f"{r['call_time_s'] * 1e3:.3g} ms",
                    f"{r['L1']:.2g}",
                    f"{r['L1_estimate']:.2g}",
                ]
                for r in rows
                if r["method"] == "chebyshev"
            ],
        ),
        "",
    ]
    with open(os.path.join(out, "general_engine.md"), "w") as fh:
        fh.write("\n".join(md))
    return rows


if __name__ == "__main__":
    main()
