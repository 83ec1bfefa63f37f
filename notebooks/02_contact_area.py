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
# # 02 — Contact area and pressure variance (exact, all fudge models)
#
# **Question.** How much of the nominal area is in contact, $A^*$, as a function of the load $\bar p$ and of the
# magnification $\zeta$; how far does the small-load asymptote carry; and how large are the pressure fluctuations
# $\mathrm{Var}(p)$ — in Persson's original theory and in the three fudge-factor theories (YP08, WM17, Xu24)?
#
# Everything here is the **exact** solution (`pf.exact`), no numerical solver:
#
# * original theory: $A^* = \mathrm{erf}\big(\bar p/\sqrt{2V(\zeta)}\big)$ (`eq:Area_Persson`), small-load limit
#   $A^*\approx\sqrt{2/\pi}\,\bar p/\sqrt{V}$ (`eq:Asymptote_1`), $\mathrm{Var}(p)=\int A^*\,dV$ (`eq:variance_p_form1`);
# * fudge-factor theories, $B_2 = S(A^*)\,dV/d\zeta$ (`eq:new_B2`): the same formulas at the effective variance
#   $\tau=\int S\,dV$ instead of $V$ (`persson_fp.theory.effective`), so $A^*=\mathrm{erf}(\bar p/\sqrt{2\tau})$ and $\mathrm{Var}(p)=\int A^*\,d\tau$.
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

plt.rcParams["figure.dpi"] = 80  # keeps the committed notebook small
MODELS = {"Persson (None)": None, "YP08 (γ = 0.45)": "YP08", "WM17 (γ = 5/9)": "WM17", "Xu24 (γ = 0.45)": "Xu24"}
# the reference surface of pf.ContactProblem.reference(): H = 0.8, q_l = 1, q_r = 2, q_s = 128 (zeta_max = 128), rms slope 0.1, E* = 1
psd = pf.SelfAffinePSD.from_rms_slope(0.1, H=0.8, q_l=1.0, q_r=2.0, q_s=128.0)
E_star = 1.0
V_max = float(psd.V(E_star=E_star))
print(psd)
print(f"V(zeta_max) = {V_max:.4e} (E* units^2), sqrt(V) = {np.sqrt(V_max):.4e}")

# %% [markdown]
# ## 1. $A^*(\bar p/\sqrt V)$ — the tutorial's Fig. 5(b)
#
# In every model $A^*$ at a given magnification depends on $\bar p/\sqrt{V(\zeta)}$ alone (for the fudge models this
# follows from the scale-free effective-variance ODE of `persson_fp.theory.effective`). Left: logarithmic load axis with the plain
# asymptote (`eq:Asymptote_1`, dotted); right: linear axis as in the tutorial's figure.

# %%
ratio = np.geomspace(1e-3, 10.0, 400)  # p_bar / sqrt(V(zeta_max))
area = {}
for label, f in MODELS.items():
    problem = pf.ContactProblem(psd, E_star, ratio * np.sqrt(V_max), fudge=f)
    area[label] = pf.exact(problem).contact_area

fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
pfplot.plot_area_curve(ratio, area, ax=ax0)
ax0.set_ylim(1e-3, 1.05)
ax0.set_yscale("log")
ax0.set_title("log-log, with the plain asymptote")
for label, A in area.items():
    ax1.plot(ratio, A, label=label)
ax1.set_xlim(0, 4)
ax1.set_xlabel(r"$\bar p/\sqrt{V}$")
ax1.set_ylabel(r"$A^*$")
ax1.set_title("linear axes (Xu et al. tutorial, Fig. 5(b))")
ax1.legend(fontsize=8)
ax1.grid(lw=0.3)

# scale-freeness: a very different surface (H = 0.3, other cut-offs, E* = 7) at the same p_bar / sqrt(V)
other = pf.SelfAffinePSD.from_rms_slope(0.3, H=0.3, q_l=3.0, q_r=30.0, q_s=3000.0)
V_other = float(other.V(E_star=7.0))
scale_free_dev = max(
    float(
        np.max(
            np.abs(
                pf.exact(pf.ContactProblem(other, 7.0, ratio * np.sqrt(V_other), fudge=f)).contact_area - area[label]
            )
        )
    )
    for label, f in MODELS.items()
)
print(f"max |A*(other surface) - A*(reference surface)| at equal p_bar/sqrt(V), all models: {scale_free_dev:.1e}")

# %% [markdown]
# ## 2. The small-load asymptote (`eq:Asymptote_1`)
#
# For $\bar p\to0$, $A^*\approx\sqrt{2/\pi}\,\bar p/\sqrt{\tau}$. With a fudge factor $\tau\to S(0)\,V$ at small loads, so the
# slope of $A^*(\bar p)$ is $1/\sqrt{S(0)}$ times the plain one. The relative error of the asymptote grows like
# $x^2/3$ with $x=\bar p/\sqrt{2\tau}$ (next term of the erf series).

# %%
fig, ax = plt.subplots(figsize=(6.4, 4.2), layout="constrained")
rows = [
    "| model | S(0) | small-load slope / plain slope | 1/√S(0) | p̄/√V where the asymptote is 1 % high |",
    "|---|---|---|---|---|",
]
slope_ratio, ratio_1pct = {}, {}
for k, (label, f) in enumerate(MODELS.items()):
    ex = pf.exact(pf.ContactProblem(psd, E_star, ratio * np.sqrt(V_max), fudge=f))
    rel = ex.area_asymptote / ex.contact_area - 1.0
    ax.loglog(ratio, rel, color=f"C{k}", label=label)
    x = ratio * np.sqrt(V_max) / np.sqrt(2.0 * ex.tau)
    ax.loglog(ratio, x**2 / 3.0, color=f"C{k}", ls=":", lw=0.8)
    S0 = float(pf.fudge.resolve(f).S(0.0))
    slope_ratio[label] = float(ex.contact_area[0] / (np.sqrt(2 / np.pi) * ratio[0]))
    ratio_1pct[label] = float(np.interp(0.01, rel, ratio))  # rel increases with the load
    rows.append(f"| {label} | {S0:.4f} | {slope_ratio[label]:.4f} | {1 / np.sqrt(S0):.4f} | {ratio_1pct[label]:.3f} |")
ax.axhline(0.01, color="0.6", lw=0.8)
ax.set_xlabel(r"$\bar p/\sqrt{V}$")
ax.set_ylabel("asymptote / A* − 1")
ax.set_title("relative error of the small-load asymptote (dotted: x²/3)")
ax.set_ylim(1e-7, 10)
ax.legend(fontsize=8)
display(Markdown("\n".join(rows)))

# %% [markdown]
# ## 3. $A^*(\zeta)$ for several loads
#
# As the magnification grows, more roughness is seen and contact is only ever lost (`eq:Area`): $A^*(\zeta)$ falls
# monotonically from 1 at $\zeta=1$. Loads are given as $\bar p/\sqrt{V(\zeta_{max})}$.

# %%
zeta = np.geomspace(1.0, psd.zeta_max, 300)
load_ratios = np.array([0.05, 0.2, 0.5, 1.0, 2.0])
fig, axes = plt.subplots(2, 2, figsize=(11, 7), layout="constrained", sharex=True, sharey=True)
monotone = True
A_zeta = {}
for ax, (label, f) in zip(axes.flat, MODELS.items()):
    ex = pf.exact(pf.ContactProblem(psd, E_star, load_ratios * np.sqrt(V_max), fudge=f), zeta=zeta)
    A_zeta[label] = ex.contact_area  # shape (n_zeta, n_loads)
    monotone &= bool(np.all(np.diff(ex.contact_area, axis=0) <= 1e-15))
    for j, r in enumerate(load_ratios):
        ax.loglog(zeta, ex.contact_area[:, j], label=rf"$\bar p/\sqrt{{V_{{max}}}}$ = {r:g}")
    ax.axvline(psd.zeta_r, color="0.6", lw=0.8, ls=":")
    ax.set_title(label)
    ax.grid(lw=0.3, which="both")
for ax in axes[1]:
    ax.set_xlabel(r"$\zeta = q/q_l$  (dotted: roll-off $q_r/q_l$)")
for ax in axes[:, 0]:
    ax.set_ylabel(r"$A^*(\zeta)$")
axes[0, 0].legend(fontsize=8)
print("A*(zeta) non-increasing for every model and load:", monotone)

# %% [markdown]
# ## 4. Pressure variance $\mathrm{Var}(p)(\zeta)$ (`eq:variance_p_form1`)
#
# $\mathrm{Var}(p)$ over the whole interface (the zeros of the non-contact area included) grows as
# $d\mathrm{Var}/d\zeta = A^*\,B_2 = A^*\,S(A^*)\,dV/d\zeta$. It is bounded by $V(\zeta)$, its value at complete contact.
# `pf.exact` evaluates the closed form in $\tau$; here it is checked against a direct quadrature of
# `eq:variance_p_form1` (with the $S$ factor for the corrected models) on a fine $\zeta$ grid.

# %%
zeta_f = np.geomspace(1.0, psd.zeta_max, 20001)
V_f = psd.V(zeta_f, E_star)
dV_f = psd.dV_dzeta(zeta_f, E_star)
load_ratio = 0.5
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
ax0.loglog(zeta_f, V_f / V_max, "k--", lw=1, label=r"$V(\zeta)$ (complete contact)")
quad_err, var_over_V = {}, {}
ratios_v = np.geomspace(0.01, 20, 60)
for k, (label, f) in enumerate(MODELS.items()):
    problem = pf.ContactProblem(psd, E_star, load_ratio * np.sqrt(V_max), fudge=f)
    ex = pf.exact(problem, zeta=zeta_f)
    ax0.loglog(zeta_f, ex.variance / V_max, color=f"C{k}", label=label)
    A = ex.contact_area
    integrand = A * problem.fudge.S(A) * dV_f  # d Var / d zeta
    cum = np.concatenate(([0.0], np.cumsum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(zeta_f))))
    quad_err[label] = float(np.max(np.abs(cum[1:] - ex.variance[1:]) / ex.variance[1:]))
    exr = pf.exact(pf.ContactProblem(psd, E_star, ratios_v * np.sqrt(V_max), fudge=f))
    ax1.semilogx(ratios_v, exr.variance / V_max, color=f"C{k}", label=label)
    var_over_V[label] = float(pf.exact(problem).variance / V_max)
ax0.set_xlabel(r"$\zeta$")
ax0.set_ylabel(r"Var$(p)/V(\zeta_{max})$")
ax0.set_title(rf"$\bar p/\sqrt{{V_{{max}}}}$ = {load_ratio}")
ax0.legend(fontsize=8)
ax1.axhline(1.0, color="k", ls="--", lw=1)
ax1.set_xlabel(r"$\bar p/\sqrt{V}$")
ax1.set_ylabel(r"Var$(p)/V$ at $\zeta_{max}$")
ax1.set_title("approach to complete contact")
ax1.legend(fontsize=8)
for label in MODELS:
    print(f"{label:18s} max rel. difference closed form vs quadrature of eq:variance_p_form1: {quad_err[label]:.1e}")

# %% tags=["summary"]
# numbers quoted in the closing text (formatted once, here)
short = {"Persson (None)": "none", "YP08 (γ = 0.45)": "YP08", "WM17 (γ = 5/9)": "WM17", "Xu24 (γ = 0.45)": "Xu24"}
SUMMARY = {"scale_free_dev": f"{scale_free_dev:.0e}", "quad_err": f"{max(quad_err.values()):.0e}"}
for label, s in short.items():
    SUMMARY[f"slope_{s}"] = f"{slope_ratio[label]:.3f}"
    SUMMARY[f"r1pct_{s}"] = f"{ratio_1pct[label]:.2f}"
    A1 = pf.exact(pf.ContactProblem(psd, E_star, 1.0 * np.sqrt(V_max), fudge=MODELS[label])).contact_area
    SUMMARY[f"A1_{s}"] = f"{A1:.3f}"
    SUMMARY[f"varV_{s}"] = f"{var_over_V[label]:.3f}"
table = "| quantity | value |\n|---|---|\n" + "\n".join(f"| `{k}` | {v} |" for k, v in SUMMARY.items())
display(Markdown(table), metadata={"summary": SUMMARY})

# %%
# checks: this notebook is a test (tests/test_notebooks.py executes it)
from scipy.special import erf

ex = pf.exact(pf.ContactProblem(psd, E_star, ratio * np.sqrt(V_max)))
assert np.allclose(ex.contact_area, erf(ratio / np.sqrt(2.0)), rtol=1e-13, atol=0)  # eq:Area_Persson
assert np.allclose(area["Persson (None)"], erf(ratio / np.sqrt(2.0)), rtol=1e-13, atol=0)
assert scale_free_dev < 1e-9  # A* = f(p_bar/sqrt(V))
for label, f in MODELS.items():  # eq:Asymptote_1 slope
    assert abs(slope_ratio[label] * np.sqrt(float(pf.fudge.resolve(f).S(0.0))) - 1.0) < 1e-3, label
assert abs(ratio_1pct["Persson (None)"] - np.sqrt(2 * 3 * 0.01)) < 0.01  # x^2/3 = 1 %
assert monotone  # eq:Area
assert max(quad_err.values()) < 1e-5  # eq:variance_p_form1
assert all(0.0 < v < 1.0 for v in var_over_V.values())
print("all checks passed")

# %% [markdown]
# ## What to take away
#
# * **Fig. 5(b).** $A^*$ rises linearly from zero and saturates at 1; the curves of all models depend on
#   $\bar p/\sqrt V$ alone (a different surface, modulus and slope give the same curves to 2e-16). At
#   $\bar p/\sqrt V = 1$ the areas are 0.683 (Persson), 0.718 (YP08), 0.738 (WM17) and 0.723 (Xu24):
#   every correction *raises* the contact area, because $S<1$ slows the diffusion towards the wall.
# * **Small-load asymptote.** The initial slope relative to Persson's is 1.000 (Persson), 1.491 (YP08),
#   1.342 (WM17), 1.490 (Xu24) — i.e. $1/\sqrt{S(0)}$. `eq:Asymptote_1` overestimates $A^*$ by 1 % at
#   $\bar p/\sqrt V$ = 0.24 (Persson), 0.18 (YP08), 0.18 (WM17), 0.18 (Xu24): it is a
#   light-load formula only.
# * **$A^*(\zeta)$.** Contact area falls monotonically with magnification for every model and load; below the
#   roll-off the plateau of the spectrum makes it fall slowly, beyond it $A^*\propto 1/\sqrt{V(\zeta)}$ at light loads.
# * **Var(p).** The closed form agrees with a direct quadrature of `eq:variance_p_form1` to 3e-08. At
#   $\bar p/\sqrt V=0.5$, Var(p)/V is 0.581 (Persson), 0.448 (YP08), 0.419 (WM17), 0.456 (Xu24),
#   and all tend to 1 (complete contact) as the load grows.
