r"""Non-separable coefficients: time to an L1 accuracy, ``pf.solve(method="auto", tol=...)`` against a hand-written
Crank--Nicolson and the same with Richardson extrapolation, whole calls.

Scenes (spectrum of ``pf.ContactProblem.reference()``, p_bar = 0.5 sqrt(V(zeta_max)), B1 = 0), neither of the form
b(p) g(zeta), so ``auto`` takes method ``"chebyshev"``'s march (``info["path"]``):

- **A**: B2 = dV/dzeta (1 + 0.2 (p / p_bar) ln zeta);
- **B**: B2 = dV/dzeta (1 + p zeta / (zeta_max p_bar));
- **S**: B2 = dV/dzeta (1 + p / (2 p_bar)), which does separate (``auto`` takes the exact exponential), for scale.

Reference (written here, independent of the package's time integrators): Chebyshev collocation in p on a tan map
clustered at p_bar (not the engine's sinh map), degree 180, far wall at p_bar + 40 sqrt(V); the small-time start of
the Lamperti-transformed process (``collocation.start_density``, error O(V_s^2)) at V_s = 1e-5 V; marched in
u = ln V by 600 fixed three-stage Radau IIA steps written here (order 5; the stage system solved whole).  A second
reference (degree 140, V_s = 2e-5 V, 400 steps) gives its uncertainty (reported).

Peers, 40-line Crank--Nicolsons written here, given *more* than the engine: the reference itself at V_p = 2e-3 V
(cell averages).  Uniform cells on [0, L], P = 0 on both walls (ghost cells), the conservative form
dP/dV = 1/2 d^2(b P)/dp^2 with b = B2 / V' at the half step, m equal steps after a Rannacher start (the first step
as two backward-Euler half steps), tridiagonal solves (``scipy.linalg.solve_banded``).  "CN + Richardson":
(4 P(2n cells, 2m steps) - P(n, m)) / 3 on the coarse cells.  Each peer is the best of its settings, hand-picked
after the fact: grids double (n = 100 ... 25 600) with m = n / 8, n / 4 or n / 2 steps, on a far wall at
L = p_bar + 12 sqrt(V) (cheaper: fewer empty cells; it truncates the tail at ~4e-5 on scene A) or at the
reference's p_bar + 40 sqrt(V); a family (one m / n and one wall) stops once a call takes over ~5 s.

Times: medians of interleaved rounds of whole calls (every configuration once per round, ``--repeats`` rounds, the
first call of each not timed); calls over 2 s are timed once.  L1 = int |P0 - reference| dp at zeta_max (cells:
against the reference's cell averages, 3-point Gauss).  Output: results/general_nonseparable.{csv,md}.

    python benchmarks/general_nonseparable.py [--quick] [--repeats 3]
"""

from __future__ import annotations

import os
import statistics
import sys
import time
import warnings

import numpy as np
from scipy.linalg import solve_banded

import persson_fp as pf
from persson_fp.solvers.chebyshev import collocation

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, outdir, parser, write_csv  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "tests"))
import solvers.chebyshev.test_separable as tcheb  # noqa: E402  (the polynomial's L1, written there)

TARGETS = (1e-4, 1e-6, 1e-8)
V_PEER = 2e-3
"""The peers start from the reference at this fraction of V(zeta_max)."""
L_K = 40.0
"""The reference's far wall, p_bar + L_K sqrt(V(zeta_max))."""
PEER_WALLS = (12.0, 40.0)
"""The peers' far walls, p_bar + (each) sqrt(V(zeta_max))."""
PEER_STEPS = (8, 4, 2)
"""The peers' steps: m = n / (each)."""


def scenes():
    pr = pf.ContactProblem.reference()
    psd, pb = pr.psd, float(pr.p_bar[0])
    zm = float(psd.zeta_max)
    return {
        "A: B2 = V'(1 + 0.2 (p/p_bar) ln zeta)": pf.FokkerPlanckProblem(
            psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + 0.2 * (p / pb) * np.log(z))
        ),
        "B: B2 = V'(1 + p zeta/(zeta_max p_bar))": pf.FokkerPlanckProblem(
            psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + p * z / (zm * pb))
        ),
        "S: B2 = V'(1 + p/(2 p_bar))": pf.FokkerPlanckProblem(
            psd, p_bar=pb, B2=lambda p, z: psd.dV_dzeta(z) * (1 + p / (2 * pb))
        ),
    }


def b_of(pr, p, V):
    """b = B2 / V' at pressures p and variance V."""
    z = float(pr.psd.zeta_of_V(V, pr.E_star))
    return pr.B2_fun(p, z) / float(pr.psd.dV_dzeta(z, pr.E_star))


# -- the reference --------------------------------------------------------------------------------------------------
_S6 = np.sqrt(6.0)
_C = np.array([(4 - _S6) / 10, (4 + _S6) / 10, 1.0])
_A = np.array(
    [
        [(88 - 7 * _S6) / 360, (296 - 169 * _S6) / 1800, (-2 + 3 * _S6) / 225],
        [(296 + 169 * _S6) / 1800, (88 + 7 * _S6) / 360, (-2 - 3 * _S6) / 225],
        [(16 - _S6) / 36, (16 + _S6) / 36, 1 / 9],
    ]
)


class TanGrid:
    """Chebyshev points mapped by p = p_bar + e tan(s) onto [0, L] (clustered within ~e of p_bar)."""

    def __init__(self, n, pb, e, L):
        self.n, self.pb, self.e, self.L = n, pb, e, L
        j = np.arange(n + 1)
        self.x = -np.cos(np.pi * j / n)
        self.t0, self.t1 = np.arctan(-pb / e), np.arctan((L - pb) / e)
        s = self.t0 + (self.t1 - self.t0) * (self.x + 1) / 2
        self.p = pb + e * np.tan(s)
        self.p[0], self.p[-1] = 0.0, L
        dpdx = e * (self.t1 - self.t0) / 2 / np.cos(s) ** 2
        d2pdx2 = 2 * e * ((self.t1 - self.t0) / 2) ** 2 * np.tan(s) / np.cos(s) ** 2
        cc = np.ones(n + 1)
        cc[0] = cc[-1] = 2
        cc *= (-1.0) ** j
        D = np.outer(cc, 1 / cc) / (self.x[:, None] - self.x[None, :] + np.eye(n + 1))
        D -= np.diag(D.sum(1))
        self.D2 = (D @ D) / dpdx[:, None] ** 2 - (d2pdx2 / dpdx**3)[:, None] * D
        th = np.pi * j[1:-1] / n
        w = np.zeros(n + 1)
        v = np.ones(n - 1)
        w[0] = w[n] = 1 / (n * n - 1)
        for k in range(1, n // 2):
            v -= 2 * np.cos(2 * k * th) / (4 * k * k - 1)
        v -= np.cos(n * th) / (n * n - 1)
        w[1:-1] = 2 * v / n
        self.w = w * dpdx
        self.wb = np.ones(n + 1)
        self.wb[0] = self.wb[-1] = 0.5
        self.wb *= (-1.0) ** j

    def interp(self, values, q):
        q = np.asarray(q, dtype=float)
        xq = (np.arctan((q - self.pb) / self.e) - self.t0) / ((self.t1 - self.t0) / 2) - 1
        d = xq[:, None] - self.x[None, :]
        d[d == 0] = 1e-300
        tt = self.wb / d
        return np.where((q > 0) & (q < self.L), (tt @ values) / tt.sum(1), 0.0)


def reference(pr, n, V_s_frac, V_keep, n_steps):
    """(pdf at V_max, pdf at V_keep, A*): tan-mapped Chebyshev collocation, the map widened every 1.5 decades of V
    (the state interpolated onto the next grid), fixed Radau IIA steps in ln V written here (the stage system of
    3(n - 1) unknowns solved whole)."""
    pb, V = float(pr.p_bar[0]), float(pr.V_max)
    V_s = V_s_frac * V
    L = pb + L_K * np.sqrt(V)
    edges = np.unique(np.concatenate([V_s * 10.0 ** (1.5 * np.arange(0, 10)), [V]]))
    edges = edges[edges <= V]
    if edges[-1] < V:
        edges = np.append(edges, V)
    u_all = np.linspace(np.log(V_s), np.log(V), n_steps + 1)
    grid, P, P_keep, keep_grid = None, None, None, None
    for Va, Vb in zip(edges[:-1], edges[1:]):
        g = TanGrid(n, pb, 8.0 * np.sqrt(Va), L)
        if grid is None:
            coef = lambda q, Va=Va: (b_of(pr, q, 0.5 * Va), None)  # noqa: E731
            P = collocation.start_density(coef, g.p[None, :], np.array([pb]), Va)[0]
        else:
            P = grid.interp(P, g.p)  # (the last grid's polynomial at the new nodes)
        grid = g
        us = np.unique(np.concatenate([[np.log(Va)], u_all[(u_all > np.log(Va)) & (u_all < np.log(Vb))], [np.log(Vb)]]))
        if Va < V_keep <= Vb:
            us = np.unique(np.append(us, np.log(V_keep)))
        m = n - 1
        y = P[1:-1].copy()
        for u0, u1 in zip(us[:-1], us[1:]):
            k = u1 - u0
            K = np.eye(3 * m)
            for jj in range(3):
                Vj = np.exp(u0 + _C[jj] * k)
                Aj = Vj * (0.5 * g.D2 * b_of(pr, g.p, Vj)[None, :])[1:-1, 1:-1]
                for ii in range(3):
                    K[ii * m : (ii + 1) * m, jj * m : (jj + 1) * m] -= k * _A[ii, jj] * Aj
            y = np.linalg.solve(K, np.tile(y, 3))[2 * m :]
            if abs(u1 - np.log(V_keep)) < 1e-14:
                P_keep, keep_grid = np.concatenate([[0.0], y, [0.0]]), g
        P = np.concatenate([[0.0], y, [0.0]])
    return (lambda q: grid.interp(P, q)), (lambda q: keep_grid.interp(P_keep, q)), float(grid.w @ P)


# -- the peers ------------------------------------------------------------------------------------------------------
def cell_avg(pdf, n, L):
    dp = L / n
    c = (np.arange(n) + 0.5) * dp
    gx = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]) * dp / 2
    gw = np.array([5.0, 8.0, 5.0]) / 18.0
    return sum(wk * pdf(c + xk) for xk, wk in zip(gx, gw))


def hand_cn(pr, P_start, L, n, m):
    """Cell values at V_max: n uniform cells, m CN steps from V_p (Rannacher start), b at the half step."""
    V_p, V = V_PEER * float(pr.V_max), float(pr.V_max)
    dp = L / n
    p = (np.arange(n) + 0.5) * dp
    P = P_start.copy()

    def step(P, Va, h, theta):
        b = b_of(pr, p, Va + 0.5 * h)
        k = 0.5 / dp**2
        # A P = k (bP_{i-1} - 2 bP_i + bP_{i+1}), ghost cells: P = 0 on the walls (-3 at the ends)
        diag = -2.0 * k * b
        diag[0], diag[-1] = -3.0 * k * b[0], -3.0 * k * b[-1]
        up, lo = k * b[1:], k * b[:-1]  # (A)_{i,i+1} = k b_{i+1}, (A)_{i,i-1} = k b_{i-1}
        ab = np.zeros((3, n))
        ab[0, 1:] = -theta * h * up
        ab[1] = 1.0 - theta * h * diag
        ab[2, :-1] = -theta * h * lo
        rhs = P.copy()
        if theta < 1.0:
            AP = diag * P
            AP[:-1] += up * P[1:]
            AP[1:] += lo * P[:-1]
            rhs = P + (1.0 - theta) * h * AP
        return solve_banded((1, 1), ab, rhs)

    h = (V - V_p) / m
    P = step(P, V_p, 0.5 * h, 1.0)
    P = step(P, V_p + 0.5 * h, 0.5 * h, 1.0)
    for k in range(1, m):
        P = step(P, V_p + k * h, h, 0.5)
    return P


def hand_cn_richardson(pr, starts, L, n, m):
    coarse = hand_cn(pr, starts[n], L, n, m)
    fine = hand_cn(pr, starts[2 * n], L, 2 * n, 2 * m)
    return (4.0 * 0.5 * (fine[0::2] + fine[1::2]) - coarse) / 3.0


def log(msg):
    sys.stderr.write(msg + "\n")
    sys.stderr.flush()


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    out = outdir(args)
    rounds = args.repeats or (2 if args.quick else 3)
    rows = []
    for name, pr in scenes().items():
        pb, V = float(pr.p_bar[0]), float(pr.V_max)
        L = pb + L_K * np.sqrt(V)
        t0 = time.perf_counter()
        n_ref = (120, 100, 300, 200) if args.quick else (180, 140, 600, 400)
        pdf, pdf_start, A_ref = reference(pr, n_ref[0], 1e-5, V_PEER * V, n_ref[2])
        pdf2, _, A_ref2 = reference(pr, n_ref[1], 2e-5, V_PEER * V, n_ref[3])
        q = np.linspace(0.0, L, 40001)
        u = max(abs(A_ref - A_ref2), float(np.trapezoid(np.abs(pdf(q) - pdf2(q)), q)))
        log(f"{name}: reference in {time.perf_counter() - t0:.1f} s, uncertainty {u:.2g}")
        sizes = [100 * 2**k for k in range(0, 9)]
        walls = {lk: pb + lk * np.sqrt(V) for lk in PEER_WALLS}
        starts = {(lk, n): cell_avg(pdf_start, n, Lp) for lk, Lp in walls.items() for n in sizes + [2 * sizes[-1]]}
        refs = {(lk, n): cell_avg(pdf, n, Lp) for lk, Lp in walls.items() for n in sizes}
        configs = [
            ("persson-fp auto", f"tol={tol:g}", (lambda tol=tol: pf.solve(pr, method="auto", tol=tol)), None)
            for tol in TARGETS
        ]
        for lk, Lp in walls.items():
            st = {n: starts[(lk, n)] for n in sizes + [2 * sizes[-1]]}
            for r in PEER_STEPS:
                for n in sizes[1:] if not args.quick else sizes[1:4]:
                    configs.append(("hand CN", f"cells={n}, steps={n // r}, wall={lk:g}",
                                    (lambda n=n, r=r, st=st, Lp=Lp: hand_cn(pr, st[n], Lp, n, n // r)),
                                    ("hand CN", lk, r)))  # fmt: skip
                for n in sizes[:-1] if not args.quick else sizes[:3]:
                    configs.append(("hand CN + Richardson", f"cells={n}+{2 * n}, steps={n // r}+{2 * (n // r)}, "
                                    f"wall={lk:g}", (lambda n=n, r=r, st=st, Lp=Lp: hand_cn_richardson(pr, st, Lp, n,
                                    n // r)), ("hand CN + Richardson", lk, r)))  # fmt: skip
        times = {c[:2]: [] for c in configs}
        result, once, stopped = {}, set(), set()
        for r in range(rounds + 1):  # round 0: the first calls (untimed unless over 2 s)
            for method, setting, fn, family in configs:
                key = (method, setting)
                if key in once or (family in stopped and key not in result):
                    continue  # (timed once; or a family stopped once a call took over ~5 s: the next doubles)
                t = time.perf_counter()
                try:
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        res = fn()
                except pf.SolverError as err:
                    res = err
                dt = time.perf_counter() - t
                if r > 0 or dt > 2.0:
                    times[key].append(dt)
                if dt > 2.0:
                    once.add(key)
                if dt > 5.0 and family is not None:
                    stopped.add(family)
                result[key] = res
        for method, setting, _, family in configs:
            key = (method, setting)
            if key not in result:
                continue
            res, t = result[key], statistics.median(times[key]) if times[key] else np.nan
            row = {"scene": name, "method": method, "setting": setting, "call_time_s": t, "reference_uncertainty": u}
            if isinstance(res, Exception):
                row.update(L1=np.nan, status=f"refused: {str(res)[:160]}")
            elif method == "persson-fp auto":
                est = res.info["error_estimate"]["L1"]
                row.update(
                    L1=tcheb.chebyshev_l1(res, pdf), L1_estimate=float(np.max(est)), path=res.info.get("path"),
                    area_error=abs(float(np.ravel(res.contact_area)[-1]) - A_ref), status="ok",
                )  # fmt: skip
            else:
                n, lk = int(setting.split("=")[1].split(",")[0].split("+")[0]), family[1]
                row.update(L1=float(np.sum(np.abs(res - refs[(lk, n)])) * walls[lk] / n), status="ok")
            log(f"{name} | {method} | {setting}: {t * 1e3:.4g} ms, L1 {row['L1']:.3g}")
            rows.append(row)
    write_csv(os.path.join(out, "general_nonseparable.csv"), rows)
    table = []
    for name in scenes():
        for target in TARGETS:
            ours = [r for r in rows if r["scene"] == name and r["method"] == "persson-fp auto"
                    and r["setting"] == f"tol={target:g}"]  # fmt: skip
            cells = [name.split(":")[0], f"{target:g}"]
            o = ours[0] if ours else None
            if o is None or o["status"] != "ok":
                cells += ["refused" if o else "-", "-"]
                t_ours = np.nan
            else:
                t_ours = o["call_time_s"]
                cells += [f"{t_ours * 1e3:.3g} ms", f"{o['L1']:.2g} / {o['L1'] / target:.2g}"]
            for method in ("hand CN", "hand CN + Richardson"):
                ok = [r for r in rows if r["scene"] == name and r["method"] == method and r["L1"] <= target]
                best = min(ok, key=lambda r: r["call_time_s"]) if ok else None
                if best is None:
                    cells.append("not reached")
                else:
                    ratio = best["call_time_s"] / t_ours if np.isfinite(t_ours) else np.nan
                    cells.append(f"{best['call_time_s'] * 1e3:.3g} ms ({best['setting']}); peer/ours {ratio:.2g}")
            table.append(cells)
    md = [
        "# Non-separable coefficients: time to an L1 target (benchmarks/general_nonseparable.py)",
        "",
        f"Machine: {machine()}. Medians of {rounds} interleaved rounds of whole calls (calls over 2 s: once).",
        "Ours: `pf.solve(problem, method='auto', tol=tol)` from the delta; the peers start from the reference at "
        f"V = {V_PEER:g} V_max. Reference uncertainty (two resolutions): "
        + ", ".join(f"{r['reference_uncertainty']:.1g}" for r in rows[:1]),
        "",
        markdown_table(
            [
                "scene",
                "L1 target",
                "ours (auto)",
                "ours: true L1 / target",
                "hand CN (fastest reaching it)",
                "hand CN + Richardson (fastest reaching it)",
            ],
            table,
        ),  # fmt: skip
        "",
        "peer/ours > 1: ours is faster.  Every run in general_nonseparable.csv.",
        "",
    ]
    with open(os.path.join(out, "general_nonseparable.md"), "w") as fh:
        fh.write("\n".join(md))
    print("\n".join(md))
    return rows


if __name__ == "__main__":
    main()
