# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#       jupytext_version: 1.19.6
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # 05 — Where the methods fail: the stability atlas in pictures
#
# **Question.** Where does each numerical method for `E:diffusion_equ` break down, what does the failure look like,
# and does persson-fp say so? Five scenes, each computed live on the reference problem `pf.ContactProblem.reference()`
# ($\bar p/\sqrt{V(\zeta_{max})}=0.5$, $\zeta_{max}=128$):
#
# 1. explicit finite volumes past the stability limit $r=\Delta\tau/(2\Delta p^2)\le r_{lim}$;
# 2. Crank–Nicolson from a single-cell $\delta$ start (`initial="delta"`) — ringing, negative $P_0$ —
#    and the cures (L-stable TR-BDF2, Rannacher start-up);
# 3. backward Euler's first-order smearing at coarse steps;
# 4. method of lines: explicit RK45 against stiff BDF, cost (right-hand-side calls) against grid size;
# 5. the fudge-factor coupling (`eq:new_B2`): lagged $S(A^*_n)$ against the predictor, error against steps.
#
# Equation labels such as `eq:P0_solution` or `E:PSD` and figure numbers refer to Y. Xu, X. Li, Q. Chen and
# Y. Zhou, "Persson's Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic
# Process Theory" (the Xu et al. tutorial); all works cited are listed on the documentation's references page.

# %%
# %matplotlib inline
import time
import warnings

import matplotlib.pyplot as plt
import numpy as np
from IPython.display import Markdown, display

import persson_fp as pf


def solve_inspect(*args, **kw):
    """pf.solve with check=False: this notebook looks at failing runs, so an invariant breach of a finished run
    warns instead of raising (instabilities during a run still raise InstabilityError)."""
    return pf.solve(*args, check=False, **kw)


plt.rcParams["figure.dpi"] = 80
problem = pf.ContactProblem.reference(p_bar_ratio=0.5)
s = float(np.sqrt(problem.V()))  # pressure unit of the plots
print(problem)

# %% [markdown]
# ## 1. Explicit finite volumes past their limit
#
# With the default compact 4th-order space discretisation the explicit scheme is stable for $r\le 1/3$ (1/2 for
# `space="fv2"`). persson-fp checks $r$ *before* stepping and refuses with a message that says what to change:

# %%
try:
    solve_inspect(problem, method="fv", stepping="tau", scheme="explicit", n_steps=100)
except ValueError as err:
    refusal = str(err)
    print("ValueError:", refusal)
n_min = int(refusal.split("n_steps to >= ")[1].split(",")[0])
ok = solve_inspect(problem, method="fv", stepping="tau", scheme="explicit", n_steps=n_min)
print(f"with n_steps = {n_min}: r = {ok.info['r_max']:.4f}, L1 = {ok.compare().final()['L1']:.2e}")

# %% [markdown]
# With `allow_unstable=True` the run goes ahead. Left: for $r$ above the limit, persson-fp's run-time checks
# (every `check_every` steps: NaN, growing or negative mass, $\max|P_0|$ growing) stop it with an
# `InstabilityError` that names the $\zeta$ where it happened; the larger $r$, the earlier. Right: to *see* the growth,
# the checks are deferred (`check_every` larger than the run) and the run is stopped at successively larger $\zeta$
# — the error $\max|P_0-P_0^{exact}|$ grows geometrically from round-off, and the last profile that persson-fp
# still returns is the saw-tooth of the highest grid mode.

# %%
n_steps_list = [300, 400, 500, 600, 700, 760, 785, 800, 1000]
atlas = []
for n in n_steps_list:
    try:
        sol = solve_inspect(problem, method="fv", stepping="tau", scheme="explicit", n_steps=n, allow_unstable=True)
        atlas.append((n, ok.info["r_max"] * n_min / n, "ok", sol.compare().final()["L1"], np.nan))
    except pf.SolverError as err:  # InstabilityError, or an invariant breach of the finished run
        msg = str(err)
        z_fail = float(msg.split("zeta = ")[1].split()[0].rstrip(";"))
        r = ok.info["r_max"] * n_min / n  # r ~ 1/n_steps (uniform steps in tau)
        atlas.append((n, r, msg, np.nan, z_fail))
rows = ["| n_steps | r | outcome |", "|---|---|---|"]
for n, r, msg, L1, _z in atlas:
    rows.append(
        f"| {n} | {r:.3f} | " + (f"stable, L1 = {L1:.1e}" if msg == "ok" else f"`InstabilityError`: {msg}") + " |"
    )
display(Markdown("\n".join(rows)))

# growth made visible: r = 0.40 per step in tau, stopped at increasing zeta
tau = lambda z: float(problem.tau(z)[0])
tau0 = 0.05 * tau(problem.zeta_max)  # fv's default start (tau0_fraction)
n_full = 660  # r ~ 0.40 over the full range
zeta_stop = np.geomspace(4.5, 14.0, 30)  # tau >= 2 tau0: fv keeps its default start
growth = []
last = None
for z in zeta_stop:
    n = max(1, round(n_full * (tau(z) - tau0) / (tau(problem.zeta_max) - tau0)))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            sol = solve_inspect(
                problem,
                method="fv",
                stepping="tau",
                scheme="explicit",
                n_steps=n,
                allow_unstable=True,
                check_every=10**9,
                zeta_out=z,
            )
    except pf.InstabilityError:
        break
    growth.append((z, n, sol.info["r_max"], float(np.max(np.abs(sol.P0[-1] - sol.exact_on_grid()[-1, 0])))))
    last = sol
fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(14, 3.8), layout="constrained")
rs = [a[1] for a in atlas]
ax0.semilogx(
    [a[1] for a in atlas if a[2] != "ok"],
    [a[4] for a in atlas if a[2] != "ok"],
    "rx",
    ms=8,
    label="InstabilityError at this ζ",
)
ax0.semilogx(
    [a[1] for a in atlas if a[2] == "ok"],
    [problem.zeta_max] * sum(a[2] == "ok" for a in atlas),
    "go",
    label="reached ζ_max",
)
ax0.axvline(1 / 3, color="k", ls=":", label="limit r = 1/3")
ax0.set_xlabel("r = Δτ/(2Δp²)")
ax0.set_ylabel("ζ reached")
ax0.set_yscale("log")
ax0.legend(fontsize=8)
ax0.set_title("explicit FV: where the checks stop it")
g = np.array(growth)
ax1.semilogy(g[:, 1], g[:, 3], "o-", ms=3)
ax1.set_xlabel("steps taken")
ax1.set_ylabel(r"max $|P_0-P_0^{exact}|$")
grow = g[:, 3] > 5 * g[0, 3]  # past the ordinary truncation error: the unstable mode dominates
growth_factor = float(np.exp(np.polyfit(g[grow, 1], np.log(g[grow, 3]), 1)[0]))
ax1.set_title(f"growth at r = {g[-1, 2]:.3f}: ×{growth_factor:.2f} per step (fit)")
ax1.grid(lw=0.3, which="both")
ax2.plot(last.p / s, last.P0[-1] * s, lw=0.8, label=f"explicit, r = {last.info['r_max']:.3f}")
ax2.plot(last.p / s, last.exact_on_grid()[-1, 0] * s, "k--", lw=1, label="exact")
ax2.set_xlim(0, 3)
ax2.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
ax2.set_ylabel(r"$P_0\sqrt{V(\zeta_{max})}$")
ax2.set_title(f"last profile returned, ζ = {g[-1, 0]:.2f}")
ax2.legend(fontsize=8)
r_growth = float(g[-1, 2])
print(
    f"max error grew from {g[0, 3]:.1e} to {g[-1, 3]:.1e} in {int(g[-1, 1] - g[0, 1])} steps; fitted factor "
    f"{growth_factor:.3f}/step; von Neumann factor of the top mode |1 - 6r| = {abs(1 - 6 * r_growth):.3f}"
)

# %% [markdown]
# ## 2. Crank–Nicolson from a $\delta$ start: ringing, and its cures
#
# `initial="delta"` puts all the mass in the cell that holds $\bar p$ at $\zeta=1$; with the stations below the first
# segment ($\zeta$ 1 → 2) is a single large step. Crank–Nicolson is A-stable but not
# L-stable: its amplification factor tends to $-1$ for the stiff modes that the one-cell pulse excites, so they
# flip sign every step instead of decaying — $P_0$ goes negative (persson-fp warns, `info["checks"]`). Rannacher's
# start-up (the first steps as backward-Euler half steps) damps them; so does TR-BDF2, which from a $\delta$ starts
# the same way: L-stability alone is not enough, its amplification factor is negative for $\Delta\tau|\lambda| > 2.41$
# (no second-order one-step scheme is positive at every step size).
# The remaining $L_1$ error of all three is the one-cell start itself (no grid resolves $\delta$).

# %%
ZS = [2.0, 8.0, 32.0, 128.0]  # the 100 steps are shared out by tau: the first segment is ONE step
ring = {}
for scheme in ["crank-nicolson", "rannacher", "tr-bdf2"]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sol = solve_inspect(
            problem, method="fv", stepping="tau", scheme=scheme, initial="delta", n_steps=100, zeta_out=ZS
        )
    ring[scheme] = sol
    print(
        f"{scheme:15s} min P0 = {sol.info['checks']['min_P0']:+.3e}, L1 at the stations = "
        + ", ".join(f"{v:.1e}" for v in sol.compare().L1[:, 0])
    )
    for w in caught:
        print("   warning:", w.message)
dp = ring["crank-nicolson"].info["grid"]["dp"]
r_first = float(problem.V(ZS[0])) / (2 * dp**2)
print(f"first step: zeta 1 -> {ZS[0]:g} in one step, r = dtau/(2 dp^2) = {r_first:.0f}")
fig, axes = plt.subplots(1, 3, figsize=(14, 3.8), layout="constrained", sharey=True)
for ax, (scheme, sol) in zip(axes, ring.items()):
    for i, z in enumerate(ZS[:2]):
        ax.plot(sol.p / s, sol.P0[i] * s, lw=0.9, color=f"C{i}", label=f"ζ = {z:g}")
        ax.plot(sol.p / s, sol.exact_on_grid()[i, 0] * s, "k:", lw=0.8)
    ax.axhline(0, color="0.5", lw=0.6)
    ax.set_xlim(0, 1.2)
    ax.set_title(f"{scheme}: min P0·√V = {sol.info['checks']['min_P0'] * s:+.2f}")
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
axes[0].set_ylabel(r"$P_0\sqrt{V(\zeta_{max})}$ (dotted: exact)")
axes[0].legend(fontsize=8)
cn_min = ring["crank-nicolson"].info["checks"]["min_P0"] * s

# %% [markdown]
# ## 3. Backward Euler: first order, smeared
#
# At equal steps (exact start at $\zeta_0$) backward Euler's error is first order in $\Delta\tau$, Crank–Nicolson's and
# TR-BDF2's second order. Left: $L_1$ at $\zeta_{max}$ against steps; right: the coarse-step profiles at
# $\zeta=2$ (5 steps in all). Backward Euler damps each Fourier mode by $1/(1+x)$ instead of $e^{-x}$
# ($x=k^2\Delta\tau/2$), i.e. *less* than the exact evolution: its first-order error is a lag in $\tau$ — the bell is
# too narrow and too high — a smooth, non-oscillating error unlike Crank–Nicolson's.

# %%
steps = [5, 10, 20, 40, 80, 160]
conv = {}
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    for scheme in ["implicit", "crank-nicolson", "tr-bdf2"]:
        conv[scheme] = [
            solve_inspect(problem, method="fv", stepping="tau", scheme=scheme, n_steps=n, n_p=800)
            .compare()
            .final()["L1"]
            for n in steps
        ]
for w in caught:  # coarse Crank-Nicolson steps ring even from the exact start
    print("warning:", w.message)
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 3.8), layout="constrained")
for k, (scheme, L1) in enumerate(conv.items()):
    slope = -np.polyfit(np.log(steps[2:]), np.log(L1[2:]), 1)[0]
    ax0.loglog(steps, L1, "o-", color=f"C{k}", label=f"{scheme} (order {slope:.2f})")
ax0.set_xlabel("n_steps")
ax0.set_ylabel(r"$L_1$ at $\zeta_{max}$")
ax0.grid(lw=0.3, which="both")
ax0.legend(fontsize=8)
coarse = {}
warnings.simplefilter("ignore", RuntimeWarning)  # the coarse CN warning was shown above
for k, scheme in enumerate(["implicit", "crank-nicolson", "tr-bdf2"]):
    sol = solve_inspect(problem, method="fv", stepping="tau", scheme=scheme, n_steps=5, n_p=800, zeta_out=[2.0, 128.0])
    coarse[scheme] = sol
    ax1.plot(sol.p / s, (sol.P0[0] - sol.exact_on_grid()[0, 0]) * s, color=f"C{k}", label=scheme)
ax1.set_xlim(0, 2)
ax1.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
ax1.set_ylabel(r"$(P_0-P_0^{exact})\sqrt{V(\zeta_{max})}$ at ζ = 2")
ax1.legend(fontsize=8)
be = coarse["implicit"]
be_peak = float(np.max(be.P0[0]) / np.max(be.exact_on_grid()[0, 0]) - 1)
print(f"backward Euler, 5 steps: peak of P0 at zeta = 2 is {100 * be_peak:.1f} % above the exact peak")
slopes = {k: float(-np.polyfit(np.log(steps[2:]), np.log(v[2:]), 1)[0]) for k, v in conv.items()}
print("observed orders:", {k: round(v, 2) for k, v in slopes.items()})

# %% [markdown]
# ## 4. Method of lines: explicit RK45 against BDF
#
# The semi-discrete system is stiff: its largest eigenvalue grows like $1/h^2$, so an explicit integrator must take
# steps $\propto h^2$ whatever the tolerance — its cost grows like $n_p^2$ (`n_p` points, here `order=4`,
# `rtol=1e-5`) while BDF's grows slowly (number of right-hand-side calls, `info["nfev"]`).

# %%
n_ps = [50, 100, 200, 400, 800]
cost = {"BDF": [], "RK45": []}
warnings.simplefilter("always", RuntimeWarning)
for integ in cost:
    for n_p in n_ps:
        t0 = time.perf_counter()
        with warnings.catch_warnings(record=True) as caught:
            sol = solve_inspect(problem, method="mol", integrator=integ, n_p=n_p)
        for w in caught:
            print(f"{integ}, n_p = {n_p}: warning: {w.message}")
        cost[integ].append((sol.info["nfev"], time.perf_counter() - t0, sol.compare().final()["L1"]))
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 3.8), layout="constrained")
for k, (integ, c) in enumerate(cost.items()):
    c = np.array(c)
    ax0.loglog(n_ps, c[:, 0], "o-", color=f"C{k}", label=integ)
    ax1.loglog(c[:, 1], c[:, 2], "o-", color=f"C{k}", label=integ)
ax0.loglog(n_ps, cost["RK45"][-1][0] * (np.array(n_ps) / n_ps[-1]) ** 2, "k:", lw=0.8, label=r"$\propto n_p^2$")
ax0.set_xlabel("n_p")
ax0.set_ylabel("nfev")
ax0.legend(fontsize=8)
ax0.grid(lw=0.3, which="both")
ax1.set_xlabel("wall time [s]")
ax1.set_ylabel(r"$L_1$ at $\zeta_{max}$")
ax1.legend(fontsize=8)
ax1.grid(lw=0.3, which="both")
rows = ["| n_p | nfev BDF | nfev RK45 | L1 BDF | L1 RK45 |", "|---|---|---|---|---|"]
for i, n_p in enumerate(n_ps):
    rows.append(
        f"| {n_p} | {cost['BDF'][i][0]} | {cost['RK45'][i][0]} | {cost['BDF'][i][2]:.1e} | {cost['RK45'][i][2]:.1e} |"
    )
display(Markdown("\n".join(rows)))

# %% [markdown]
# ## 5. Coupling of the fudge factor: lagged against predictor
#
# With a fudge factor (`YP08`) the step $\Delta\tau=S(A^*)\Delta V$ needs $A^*$ *during* the step. `coupling="lagged"`
# takes $S(A^*_n)$ from the start of the step (first order, whatever the scheme); `"predictor"` (Heun, one solve per
# step) and `"picard"` (trapezoidal rule iterated) are second order. TR-BDF2, `n_p=400` so that space error is
# negligible; $|\Delta A^*|$ at $\zeta_{max}$ against the exact effective-variance solution.

# %%
problem_yp = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=0.5)
steps_c = [5, 10, 20, 40, 80, 160, 320]
coupling = {}
for c in ["lagged", "predictor", "picard"]:
    out = []
    for n in steps_c:
        sol = solve_inspect(problem_yp, method="fv", stepping="tau", coupling=c, n_steps=n, n_p=400, linalg="banded")
        out.append((sol.compare().final()["area_error"], sol.wall_time, sol.info["tridiagonal_solves"]))
    coupling[c] = np.array(out)
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 3.8), layout="constrained")
order_c = {}
for k, (c, out) in enumerate(coupling.items()):
    order_c[c] = float(-np.polyfit(np.log(steps_c[2:]), np.log(out[2:, 0]), 1)[0])
    ax0.loglog(steps_c, out[:, 0], "o-", color=f"C{k}", label=f"{c} (order {order_c[c]:.2f})")
    ax1.loglog(out[:, 2], out[:, 0], "o-", color=f"C{k}", label=c)
ax0.set_xlabel("n_steps")
ax0.set_ylabel(r"$|\Delta A^*|$ at $\zeta_{max}$ (YP08)")
ax1.set_xlabel("tridiagonal solves (banded path; the default DST path needs none)")
ax1.set_ylabel(r"$|\Delta A^*|$")
for ax in (ax0, ax1):
    ax.grid(lw=0.3, which="both")
    ax.legend(fontsize=8)

# %% [markdown]
# ## 6. The committed stability atlas (`benchmarks/stability.py`)
#
# The scenes above are single runs. `benchmarks/stability.py` maps the same failures systematically; its committed
# results (`benchmarks/results/stability_*.csv`, read here, nothing re-run) are drawn below, with this notebook's live
# numbers on top where they are the same experiment.
#
# * **Explicit onset map** (`stability_explicit.csv`, `stability_onsets.csv`): every explicit run, fv with both space
#   discretisations, from the exact smooth start and from a one-cell $\delta$, on three grids, plus py-pde's and FiPy's
#   explicit steppers. Outcome *stable*, *oscillating* (damped sign-alternating modes: the most negative eigenvalue of the
#   step matrix is below 0) or *blown up* (`InstabilityError`); the theoretical limit of each row is marked. Right: the
#   spectral radius of the step matrix against $r$.
# * **Crank–Nicolson ringing** (`stability_ringing.csv`): $-\min P_0/\max P_0^{exact}$ at $\zeta=4$ from the one-cell
#   $\delta$, against the first step's $r$, for four schemes.
# * **MOL cost** (`stability_mol.csv`, rtol = 1e-6) and **fudge coupling** (`stability_coupling.csv`, TR-BDF2,
#   $n_p=400$ as in section 5).

# %%
import csv
import re
from pathlib import Path

RESULTS = Path("../benchmarks/results")


def read(name):
    with open(RESULTS / name, newline="") as fh:
        return list(csv.DictReader(fh))


def f(v):
    return float(v) if v not in ("", None) else np.nan


st_machine = re.search(r"^Machine: (.*)$", (RESULTS / "stability.md").read_text(), re.M).group(1)
expl, onsets = read("stability_explicit.csv"), read("stability_onsets.csv")
ringing, mol_c, coup_c = read("stability_ringing.csv"), read("stability_mol.csv"), read("stability_coupling.csv")
print(
    f"committed atlas ({st_machine}): {len(expl)} explicit runs, {len(onsets)} onset rows,",
    f"{len(ringing)} ringing rows, {len(mol_c)} MOL runs, {len(coup_c)} coupling runs",
)

# explicit onset map: one row per (method, space, start, n_p)
keys = list(dict.fromkeys((o["method"], o["space"], o["initial"], o["n_p"]) for o in onsets))
STYLE = {"stable": ("o", "tab:green"), "oscillating": ("^", "tab:orange"), "blown-up": ("x", "tab:red")}
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(14, 5.2), layout="constrained", gridspec_kw={"width_ratios": [1.6, 1]})
for y, key in enumerate(keys):
    runs = [e for e in expl if (e["method"], e["space"], e["initial"], e["n_p"]) == key]
    for outcome, (mk, col) in STYLE.items():
        rr = [f(e["r"]) for e in runs if e["outcome"] == outcome]
        ax0.plot(rr, [y] * len(rr), mk, color=col, ms=6, label=outcome if y == 0 else None)
    o = onsets[y]
    ax0.plot([f(o["theory"])] * 2, [y - 0.4, y + 0.4], "k-", lw=2, label="theoretical limit" if y == 0 else None)
ax0.set_xscale("log")
ax0.set_yticks(range(len(keys)), [f"{m} {sp}, {ini} start, n_p={n}" for m, sp, ini, n in keys], fontsize=8)
ax0.invert_yaxis()
ax0.set_xlabel("r = Δτ/(2Δp²)")
ax0.set_title("committed explicit runs: outcome against r")
ax0.legend(fontsize=8, loc="lower left")
ax0.grid(True, axis="x", which="both", lw=0.3)
for space, col in (("fv2", "C0"), ("compact4", "C1")):
    sel = sorted(
        (
            e
            for e in expl
            if e["method"] == "fv" and e["space"] == space and e["n_p"] == "200" and e["initial"] == "exact"
        ),
        key=lambda e: f(e["r"]),
    )
    ax1.loglog(
        [f(e["r"]) for e in sel],
        [f(e["spectral_radius"]) for e in sel],
        "o-",
        color=col,
        ms=4,
        label=f"fv {space} (n_p = 200)",
    )
ax1.axhline(1, color="k", lw=0.8, ls=":")
ax1.axvline(1 / 2, color="C0", lw=0.8, ls="--")
ax1.axvline(1 / 3, color="C1", lw=0.8, ls="--")
ax1.set_xlabel("r")
ax1.set_ylabel("spectral radius of one explicit step")
ax1.set_title("growth factor of the worst mode (dashed: theory)")
ax1.legend(fontsize=8)
ax1.grid(lw=0.3, which="both")
fig.suptitle(f"stability atlas, machine: {st_machine}", fontsize=9)
plt.show()
onset = {
    (o["space"], o["initial"], o["n_p"]): (f(o["stable_up_to"]), f(o["blown_up_from"]))
    for o in onsets
    if o["method"] == "fv"
}
rows = ["| space | start | n_p | stable up to r | blown up from r | theory |", "|---|---|---|---|---|---|"]
for o in onsets:
    rows.append(
        f"| {o['method']} {o['space']} | {o['initial']} | {o['n_p']} | {f(o['stable_up_to']):.3f} | "
        f"{f(o['blown_up_from']):.3f} | {f(o['theory']):.3f} |"
    )
display(Markdown("\n".join(rows)))

# %%
fig, (ax0, ax1, ax2) = plt.subplots(1, 3, figsize=(15, 4.2), layout="constrained")
ring_c = {}
for k, scheme in enumerate(["crank-nicolson", "tr-bdf2", "rannacher", "implicit"]):
    sel = sorted((x for x in ringing if x["scheme"] == scheme and f(x["zeta"]) == 4.0), key=lambda x: f(x["r"]))
    ring_c[scheme] = np.array([(f(x["r"]), f(x["neg_P0_rel"])) for x in sel])
    ax0.plot(
        ring_c[scheme][:, 0],
        ring_c[scheme][:, 1],
        "o-",
        color=f"C{k}",
        ms=4 + 2 * (k == 3),
        mfc="none" if k == 3 else None,
        label=scheme,
        lw=2.5 if k == 0 else 1.2,
        zorder=5 - k,
    )
ax0.set_xscale("log")
ax0.set_yscale("symlog", linthresh=1e-2)
ax0.set_ylim(bottom=0)
ax0.set_xlabel("r of the first step (Δτ/(2Δp²))")
ax0.set_ylabel(r"$-\min P_0/\max P_0^{exact}$ at ζ = 4")
ax0.set_title("ringing from a one-cell δ (n_p = 200)")
ax0.legend(fontsize=8)
ax0.grid(lw=0.3, which="both")
for k, integ in enumerate(["BDF", "RK45"]):
    sel = [m for m in mol_c if m["integrator"] == integ]
    ax1.loglog(
        [f(m["n_p"]) for m in sel],
        [f(m["nfev"]) for m in sel],
        "o-",
        color=f"C{k}",
        alpha=0.5,
        label=f"{integ}, committed (rtol 1e-6)",
    )
    ax1.loglog(
        n_ps, [c[0] for c in cost[integ]], "D--", color=f"C{k}", ms=6, mec="k", label=f"{integ}, live (section 4)"
    )
ax1.set_xlabel("n_p")
ax1.xaxis.set_minor_formatter(plt.NullFormatter())
ax1.set_ylabel("right-hand-side calls")
ax1.set_title("MOL order 4: explicit pays for stiffness")
ax1.legend(fontsize=7)
ax1.grid(lw=0.3, which="both")
coup_committed = {}
for k, c in enumerate(["lagged", "predictor", "picard"]):
    sel = [x for x in coup_c if x["coupling"] == c]
    coup_committed[c] = {int(x["n_steps"]): f(x["area_error"]) for x in sel}
    ax2.loglog(
        list(coup_committed[c]),
        list(coup_committed[c].values()),
        "o-",
        color=f"C{k}",
        alpha=0.5,
        label=f"{c}, committed",
    )
    ax2.loglog(steps_c, coupling[c][:, 0], "D", color=f"C{k}", ms=6, mec="k", label=f"{c}, live (section 5)")
ax2.set_xlabel("n_steps")
ax2.set_ylabel(r"$|\Delta A^*|$ at $\zeta_{max}$ (YP08)")
ax2.set_title("fudge coupling: committed and live")
ax2.legend(fontsize=7, ncol=2)
ax2.grid(lw=0.3, which="both")
plt.show()
cn_c = ring_c["crank-nicolson"]
cn_ring_max, cn_r_max = float(cn_c[:, 1].max()), float(cn_c[cn_c[:, 1].argmax(), 0])  # smallest r at the maximum
cn_r_clean = float(cn_c[cn_c[:, 1] <= 1e-12, 0].max())  # largest r without a negative P0 (beyond round-off)
tr_c = ring_c["tr-bdf2"]
tr_ring_max, tr_r_clean = float(tr_c[:, 1].max()), float(tr_c[tr_c[:, 1] <= 1e-12, 0].max())
tr_damped = tr_ring_max <= 1e-12  # TR-BDF2 from a delta starts with backward-Euler half steps (fv.py)
coup_match = max(
    abs(coupling[c][i, 0] / coup_committed[c][n] - 1)
    for c in coupling
    for i, n in enumerate(steps_c)
    if n in coup_committed[c]
)
print(
    f"CN: -min P0/max P0_exact up to {cn_ring_max:.1f} (from r = {cn_r_max:.0f} on); none at r <= {cn_r_clean:.2f}. "
    f"TR-BDF2: up to {tr_ring_max:.2f}, none at r <= {tr_r_clean:.1f}. Rannacher, implicit: max "
    f"{max(ring_c['rannacher'][:, 1].max(), ring_c['implicit'][:, 1].max()):.0f}"
)
print(f"coupling: live |dA*| vs committed at the same steps, largest relative difference {coup_match:.1e}")


# %% tags=["summary"]
# numbers quoted in the closing text (formatted once, here)
def tiny(v):  # round-off-level values differ between machines and linear-algebra paths: say so instead
    return "0 to round-off" if abs(v) < 1e-12 else f"{v:.1e}"


SUMMARY = {
    "n_min": str(n_min),
    "r_growth": f"{r_growth:.3f}",
    "growth_factor": f"{growth_factor:.1f}",  # grows from round-off: 2 digits are reproducible, 4 are not
    "top_mode": f"{abs(1 - 6 * r_growth):.3f}",
    "cn_min": f"{cn_min:.1f}",
    "rb_min": tiny(ring["rannacher"].info["checks"]["min_P0"] * s),
    "tr_min": tiny(ring["tr-bdf2"].info["checks"]["min_P0"] * s),
    "L1_delta": f"{ring['tr-bdf2'].compare().final()['L1']:.1e}",
    "order_be": f"{slopes['implicit']:.2f}",
    "be_peak": f"{100 * be_peak:.0f}",
    "order_cn": f"{slopes['crank-nicolson']:.2f}",
    "order_tr": f"{slopes['tr-bdf2']:.2f}",
    "nfev_rk": str(cost["RK45"][-1][0]),
    "nfev_bdf": str(cost["BDF"][-1][0]),
    "nfev_rk50": str(cost["RK45"][0][0]),
    "nfev_bdf50": str(cost["BDF"][0][0]),
    "ord_lag": f"{order_c['lagged']:.2f}",
    "ord_pred": f"{order_c['predictor']:.2f}",
    "ord_pic": f"{order_c['picard']:.2f}",
    "dA_lag": f"{coupling['lagged'][4, 0]:.1e}",
    "dA_pred": f"{coupling['predictor'][4, 0]:.1e}",
    "st_machine": st_machine,
    "fv2_ok": f"{onset['fv2', 'delta', '200'][0]:.3f}",
    "fv2_blown": f"{onset['fv2', 'delta', '200'][1]:.3f}",
    "c4_ok": f"{onset['compact4', 'delta', '200'][0]:.3f}",
    "c4_blown": f"{onset['compact4', 'delta', '200'][1]:.3f}",
    "cn_ring": f"{cn_ring_max:.1f}",
    "cn_r": f"{cn_r_max:.0f}",
    "cn_clean": f"{cn_r_clean:.1f}",
    "tr_ring": f"{tr_ring_max:.0e}",
    "tr_clean": f"{tr_r_clean:.0f}",
}
table = "| quantity | value |\n|---|---|\n" + "\n".join(f"| `{k}` | {v} |" for k, v in SUMMARY.items())
display(Markdown(table), metadata={"summary": SUMMARY})

# %%
# checks: this notebook is a test (tests/test_notebooks.py executes it)
ex_max = pf.exact(problem)
assert "stability limit" in refusal and ok.compare().final()["L1"] < 1e-3
assert abs(ok.contact_area[-1] - ex_max.contact_area) < 1e-3  # stable explicit run is right
assert any(a[2] != "ok" for a in atlas) and all(a[2] == "ok" for a in atlas if a[1] < 1 / 3)
assert growth_factor > 1.0
assert cn_min < -1.0  # CN rings from the delta
for scheme in ["rannacher", "tr-bdf2"]:  # the cures
    assert ring[scheme].info["checks"]["min_P0"] > -1e-10
    assert abs(ring[scheme].contact_area[-1] - ex_max.contact_area) < 1e-2
assert 0.8 < slopes["implicit"] < 1.2 and slopes["tr-bdf2"] > 1.7 and be_peak > 0
assert cost["RK45"][-1][0] > 10 * cost["BDF"][-1][0]
assert all(c[2] < 1e-3 for c in cost["BDF"][1:])
assert 0.8 < order_c["lagged"] < 1.2 and order_c["predictor"] > 1.8 and order_c["picard"] > 1.8
assert coupling["predictor"][-1, 0] < 1e-6  # vs pf.exact (eq:new_B2)
# the committed atlas parses and says what the text says
assert len(expl) > 100 and {e["outcome"] for e in expl} == {"stable", "oscillating", "blown-up"}
for (space, ini, n_p), (ok_r, blown_r) in onset.items():
    lim = 0.5 if space == "fv2" else 1 / 3
    assert ok_r < blown_r and blown_r > lim * 0.99 and (ini == "exact" or ok_r <= lim + 1e-3), (space, ini, n_p)
assert all(e["outcome"] == "blown-up" for e in expl if f(e["r"]) > 1.4)  # r = 1.5 and 2 blow up everywhere
assert cn_ring_max > 10 and tr_damped  # CN rings, TR-BDF2 (damped start) not
assert ring_c["rannacher"][:, 1].max() <= 1e-12 and ring_c["implicit"][:, 1].max() <= 1e-12  # round-off of the DST path
assert coup_match < 1e-3  # live section 5 = committed atlas
print("all checks passed")

# %% [markdown]
# ## What to take away
#
# * **Explicit FV.** persson-fp refuses an explicit run past $r=1/3$ with a `ValueError` that names the fix
#   (here: at least 789 steps). Forced on (`allow_unstable=True`), every run with $r>1/3$ that the table lists
#   either ends in an `InstabilityError` naming the $\zeta$ where it was caught — earlier for larger $r$ — or, just
#   past the limit, grows too slowly to matter. At $r$ = 0.399 the error, once above the ordinary truncation
#   error, grows by ×1.3 per step (fit; bounded by the von Neumann factor $|1-6r|$ = 1.392 of the
#   highest grid mode) into the saw-tooth of the last profile.
# * **Crank–Nicolson from a one-cell $\delta$** rings: $\min P_0\sqrt V$ = -1.6 (persson-fp warns). Rannacher's start
#   (0 to round-off) and TR-BDF2 (0 to round-off) stay non-negative; what remains ($L_1$ = 7.9e-03 at $\zeta_{max}$ for TR-BDF2) is the
#   one-cell start itself, which is why `fv` starts from the exact solution at $\zeta_0$ by default.
# * **Backward Euler** converges at order 1.00 (Crank–Nicolson 2.00, TR-BDF2 2.01); at coarse steps it lags
#   behind the diffusion — with 5 steps its peak at $\zeta=2$ is 7 % too high — a smooth error, no ringing.
# * **MOL.** At $n_p=800$ RK45 needs 32660 right-hand-side calls against BDF's 340 (at $n_p=50$: 128
#   vs 116): the explicit integrator pays $\propto n_p^2$ for stability, not accuracy.
# * **Fudge coupling (YP08).** The lagged $S(A^*_n)$ caps the scheme at order 1.01; the predictor restores
#   order 2.29 (Picard 2.00) — at 80 steps $|\Delta A^*|$ = 5.2e-04 lagged against 3.8e-07 predictor.
# * **The committed atlas** (machine: vm: x86_64, 2 cores, Python 3.11.7, numpy 2.4.6, scipy 1.17.1) agrees and adds the map: from a one-cell $\delta$ on $n_p=200$ the
#   fv2 scheme is stable up to $r$ = 0.500 and blown up from 0.519 (theory 1/2), compact4 up to 0.333 and
#   from 0.360 (theory 1/3). Crank–Nicolson's ringing reaches $-\min P_0/\max P_0^{exact}$ = 13.5 for
#   first steps with $r\ge$ 36 and is gone only for $r\le$ 2.2; TR-BDF2 with its backward-Euler start
#   (largest dip 5e-15, i.e. round-off, up to $r$ = 251), Rannacher's start-up and backward Euler never go
#   negative. (Without that start TR-BDF2 dipped to 0.41 of the peak for $r \ge 36$: `rannacher_steps=0`.)
