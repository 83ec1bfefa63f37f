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
# # 03 — Fudge factors: S(A*), the PDE with the numerical A* in the loop, and how much the area moves
#
# **Question.** The corrected theories replace $B_2=dV/d\zeta$ by $B_2=S(A^*)\,dV/d\zeta$ (`eq:new_B2`), with $A^*$ the
# *current* contact area — a nonlinear, nonlocal PDE. What do the models' $S(A^*)$ look like (Yang–Persson with
# $\gamma$ from 0.42 to 0.48, Wang–Müser, Xu24, and a user-defined callable); do the numerical solvers, which take
# $A^*=\int P_0\,dp$ from their own solution at every step, reproduce the exact effective-variance solution
# ($P_0$ = image solution at $\tau=\int S\,dV$, `persson_fp.theory.effective`); and how far does each model move $A^*$ away from
# Persson 2001?
#
# Equation labels such as `eq:P0_solution` or `E:PSD` and figure numbers refer to Y. Xu, X. Li, Q. Chen and
# Y. Zhou, "Persson's Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic
# Process Theory" (the Xu et al. tutorial); all works cited are listed on the documentation's references page.

# %%
# %matplotlib inline
import matplotlib.pyplot as plt
import numpy as np
from IPython.display import Markdown, display

import persson_fp as pf
import persson_fp.plotting as pfplot

plt.rcParams["figure.dpi"] = 80


def user_S(A):  # a user-defined fudge factor: any callable S(A*) > 0 on [0, 1]
    return 0.5 + 0.5 * A**3


MODELS = {
    "Persson 2001": None,
    "YP08 γ=0.42": pf.fudge.YangPersson(gamma=0.42),
    "YP08 γ=0.45": "YP08",
    "YP08 γ=0.48": pf.fudge.YangPersson(gamma=0.48),
    "WM17": "WM17",
    "Xu24": "Xu24",
    "user: 0.5+0.5A³": user_S,
}
base = pf.ContactProblem.reference(p_bar_ratio=0.5)
psd, V_max = base.psd, float(base.V())
A_grid = np.linspace(0, 1, 201)
fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
for k, (label, f) in enumerate(MODELS.items()):
    ax.plot(A_grid, pf.fudge.resolve(f).S(A_grid), color=f"C{k}", label=label)
ax.fill_between(
    A_grid,
    pf.fudge.YangPersson(gamma=0.42).S(A_grid),
    pf.fudge.YangPersson(gamma=0.48).S(A_grid),
    color="C2",
    alpha=0.15,
    label="YP08 documented γ range",
)
ax.set_xlabel("$A^*$")
ax.set_ylabel("$S(A^*)$")
ax.set_title("fudge factors S(A*); S(1) = 1: complete contact is Persson's")
ax.legend(fontsize=8)
for label, f in MODELS.items():
    S = pf.fudge.resolve(f).S(np.array([0.0, 0.5, 1.0]))
    print(f"{label:16s} S(0) = {S[0]:.4f}  S(0.5) = {S[1]:.4f}  S(1) = {S[2]:.4f}")

# %% [markdown]
# ## 1. The PDE with the numerical $A^*$ in the loop
#
# `fv` (TR-BDF2 with the predictor coupling), `mol` (the area as part of the ODE system, exact Jacobian) and `sines`
# (series area in a scalar ODE for $\tau$) at their defaults, stations $\zeta$ = 4, 16, 128; the reference is
# `pf.exact`, i.e. the image solution at the exact effective variance. None of the solvers uses the exact $\tau$.

# %%
ZS = [4.0, 16.0, 128.0]
rows = ["| model | method | L1 at ζ = 4 / 16 / 128 | $|\\Delta A^*|$ at ζ_max | wall [ms] |", "|---|---|---|---|---|"]
errs = {}
sols = {}
for label, f in MODELS.items():
    if label == "Persson 2001":
        continue
    pr = pf.ContactProblem(psd, 1.0, base.p_bar[0], fudge=f)
    for m in ["fv", "mol", "sines"]:
        sol = pf.solve(pr, method=m, zeta_out=ZS)
        c = sol.compare()
        errs[(label, m)] = (float(c.L1[-1, 0]), float(c.area_error[-1, 0]))
        sols[(label, m)] = sol
        rows.append(
            f"| {label} | {m} | "
            + " / ".join(f"{v:.1e}" for v in c.L1[:, 0])
            + f" | {c.area_error[-1, 0]:.1e} | {sol.wall_time * 1e3:.1f} |"
        )
display(Markdown("\n".join(rows)))
fig, axes = plt.subplots(1, 2, figsize=(12, 4), layout="constrained")
s = np.sqrt(V_max)
for k, label in enumerate(["YP08 γ=0.45", "WM17", "Xu24", "user: 0.5+0.5A³"]):
    sol = sols[(label, "fv")]
    axes[0].plot(sol.p / s, sol.exact_on_grid()[-1, 0] * s, color=f"C{k}", lw=1, label=f"{label} exact")
    axes[0].plot(sol.p[::6] / s, sol.P0[-1, ::6] * s, "o", ms=3, mfc="none", color=f"C{k}")
ex0 = pf.exact(base)
axes[0].plot(sol.p / s, ex0.pdf(sol.p) * s, "k--", lw=1, label="Persson 2001")
axes[0].set_xlim(0, 4)
axes[0].set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
axes[0].set_ylabel(r"$P_0\sqrt{V}$ at $\zeta_{max}$ (markers: fv)")
axes[0].legend(fontsize=8)
zeta = np.geomspace(1.2, 128, 60)
for k, label in enumerate(["YP08 γ=0.45", "WM17", "Xu24", "user: 0.5+0.5A³"]):
    pr = pf.ContactProblem(psd, 1.0, base.p_bar[0], fudge=MODELS[label])
    sol = pf.solve(pr, method="mol", zeta_out=zeta)
    axes[1].semilogx(zeta, sol.contact_area, "o", ms=2, color=f"C{k}")
    axes[1].semilogx(zeta, pf.exact(pr, zeta).contact_area, color=f"C{k}", lw=1, label=label)
axes[1].semilogx(zeta, pf.exact(base, zeta).contact_area, "k--", lw=1, label="Persson 2001")
axes[1].set_xlabel(r"$\zeta$")
axes[1].set_ylabel(r"$A^*(\zeta)$ (dots: mol, lines: exact)")
axes[1].legend(fontsize=8)
worst = max(errs.items(), key=lambda kv: kv[1][1])
print(f"largest |dA*| at zeta_max: {worst[1][1]:.1e} ({worst[0][0]}, {worst[0][1]})")

# %% [markdown]
# ## 2. How much the area moves
#
# $A^*$ depends on $\bar p/\sqrt V$ alone in every model (exact, `pf.exact`). Left: $A^*$; right: the relative change
# against Persson 2001. Every model has $S<1$, slows the diffusion towards the wall and *raises* $A^*$; the change is
# largest at light loads, where $A^*\to\sqrt{2/\pi}\,\bar p/\sqrt{S(0)V}$.

# %%
ratio = np.geomspace(0.01, 5, 300)
area = {
    label: pf.exact(pf.ContactProblem(psd, 1.0, ratio * np.sqrt(V_max), fudge=f)).contact_area
    for label, f in MODELS.items()
}
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(12, 4), layout="constrained")
pfplot.plot_area_curve(ratio, area, ax=ax0)
for k, (label, A) in enumerate(area.items()):
    ax1.semilogx(ratio, 100 * (A / area["Persson 2001"] - 1), color=f"C{k}", label=label)
ax1.set_xlabel(r"$\bar p/\sqrt{V}$")
ax1.set_ylabel("A* / A*(Persson 2001) − 1  [%]")
ax1.legend(fontsize=8)
ax1.grid(lw=0.3)
probe = [0.1, 0.5, 1.0, 2.0]
rows = ["| model | " + " | ".join(f"p̄/√V = {r:g}" for r in probe) + " |", "|---|" + "---|" * len(probe)]
shift = {}
for label, f in MODELS.items():
    A = pf.exact(pf.ContactProblem(psd, 1.0, np.array(probe) * np.sqrt(V_max), fudge=f)).contact_area
    A0 = pf.exact(pf.ContactProblem(psd, 1.0, np.array(probe) * np.sqrt(V_max))).contact_area
    shift[label] = 100 * (A / A0 - 1)
    rows.append(f"| {label} | " + " | ".join(f"{a:.4f} ({d:+.1f} %)" for a, d in zip(A, shift[label])) + " |")
display(Markdown("\n".join(rows)))

# %% tags=["summary"]
# numbers quoted in the closing text (formatted once, here)
SUMMARY = {
    "worst_dA": f"{worst[1][1]:.0e}",
    # the sine series is exact to round-off, whose last digit changes from run to run: quote a bound
    "sines_L1": "1e-12" if max(v[0] for (lab, m), v in errs.items() if m == "sines") < 1e-12 else "above 1e-12",
    "fv_L1": f"{max(v[0] for (lab, m), v in errs.items() if m == 'fv'):.0e}",
    "mol_L1": f"{max(v[0] for (lab, m), v in errs.items() if m == 'mol'):.0e}",
    "yp42_01": f"{shift['YP08 γ=0.42'][0]:+.0f}",
    "yp48_01": f"{shift['YP08 γ=0.48'][0]:+.0f}",
    "wm_01": f"{shift['WM17'][0]:+.0f}",
    "xu_01": f"{shift['Xu24'][0]:+.0f}",
    "user_01": f"{shift['user: 0.5+0.5A³'][0]:+.0f}",
    "yp45_1": f"{shift['YP08 γ=0.45'][2]:+.1f}",
    "wm_1": f"{shift['WM17'][2]:+.1f}",
    "xu_1": f"{shift['Xu24'][2]:+.1f}",
    "yp45_2": f"{shift['YP08 γ=0.45'][3]:+.1f}",
}
table = "| quantity | value |\n|---|---|\n" + "\n".join(f"| `{k}` | {v} |" for k, v in SUMMARY.items())
display(Markdown(table), metadata={"summary": SUMMARY})

# %%
# checks: this notebook is a test (tests/test_notebooks.py executes it)
from scipy.special import erf

tol = {"fv": 1e-4, "mol": 1e-4, "sines": 1e-10}
for (label, m), (L1, dA) in errs.items():
    assert L1 < tol[m] and dA < tol[m], (label, m, L1, dA)
for label, f in MODELS.items():
    assert np.all(pf.fudge.resolve(f).S(A_grid) > 0)
    assert abs(float(pf.fudge.resolve(f).S(1.0)) - 1.0) < 1e-12, label  # S(1) = 1 in every model here
    assert np.all(area[label] >= area["Persson 2001"] - 1e-15), label  # S <= 1 raises A*
assert np.allclose(area["Persson 2001"], erf(ratio / np.sqrt(2)), rtol=1e-13, atol=0)  # eq:Area_Persson
for label, f in MODELS.items():  # light-load limit 1/sqrt(S(0))
    S0 = float(pf.fudge.resolve(f).S(0.0))
    tol_lim = 2e-2 if label == "Xu24" else 2e-3  # Xu24: S has a term linear in A*, slower approach
    assert abs(area[label][0] / area["Persson 2001"][0] - 1 / np.sqrt(S0)) < tol_lim, label
print("all checks passed")

# %% [markdown]
# ## What to take away
#
# * **S(A*).** All models start below one at vanishing contact (Yang–Persson at $S(0)=\gamma$) and reach $S(1)=1$; the
#   documented $\gamma$ range 0.42–0.48 is a narrow band around the default 0.45.
# * **Numerical $A^*$ in the loop.** With the area taken from their own solution at every step, the solvers
#   reproduce the exact effective-variance solution for every model, the user's callable included: worst $L_1$ of
#   $P_0$ at $\zeta_{max}$ 6e-06 (`fv`), 3e-06 (`mol`), below 1e-12, i.e. round-off (`sines`); worst $|\Delta A^*|$ over all runs 2e-06.
# * **How much the area moves.** At $\bar p/\sqrt V=0.1$ the models raise $A^*$ over Persson 2001 by +48 % (YP08
#   γ=0.42) to +40 % (γ=0.48), +34 % (WM17), +40 % (Xu24) and +40 % (the user model) — close to
#   $1/\sqrt{S(0)}-1$; at $\bar p/\sqrt V=1$ by +5.2 % (YP08 0.45), +8.2 % (WM17), +5.9 % (Xu24); at 2 only
#   +0.1 % (YP08): near complete contact all theories agree.
