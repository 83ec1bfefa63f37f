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
# # 01 — Evolution of the pressure PDF $P_0(p,\zeta)$: every own solver against the image solution
#
# **Question.** How does the contact-pressure PDF broaden from $\delta(p-\bar p)$ at $\zeta=1$ as more roughness is
# seen (Fig. 2(b) of the Xu et al. tutorial); why does the image solution $P_0=\rho(p;\bar p,V)-\rho(p;-\bar p,V)$ (`eq:P0_solution`)
# satisfy the absorbing wall (Fig. 5(a)); and how close do the package's own solvers — finite volumes (`fv`),
# method of lines (`mol`), the sine series (`sines`) and the compounded Chapman–Kolmogorov iteration
# (`chapman-kolmogorov`, `E:Compounded_CK`) — come to it at several magnifications?
#
# The PDF is $P(p,\zeta)=[1-A^*]\,\delta(p)+\theta(p)\,P_0(p,\zeta)$ (`eq:PDF_piecewise_explicit`): the contact part
# $P_0$ is a function, the non-contact part is an **atom** of weight $1-A^*$ at $p=0$. Atoms are drawn as arrows
# whose length is proportional to their weight (the weight is written next to them).
# Problem: the reference surface of `pf.ContactProblem.reference()` (H = 0.8, $q_l=1$, $q_r=2$, $\zeta_{max}=128$, rms slope 0.1, $E^*=1$) at
# $\bar p/\sqrt{V(\zeta_{max})}=0.5$, Persson's original theory (no fudge factor).
#
# Equation labels such as `eq:P0_solution` or `E:PSD` and figure numbers refer to Y. Xu, X. Li, Q. Chen and
# Y. Zhou, "Persson's Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic
# Process Theory" (the Xu et al. tutorial); all works cited are listed on the documentation's references page.

# %%
# %matplotlib inline
import time

import matplotlib.pyplot as plt
import numpy as np
from IPython.display import Markdown, display

import persson_fp as pf
import persson_fp.plotting as pfplot

plt.rcParams["figure.dpi"] = 80  # keeps the committed notebook small
problem = pf.ContactProblem.reference(p_bar_ratio=0.5)
p_bar = float(problem.p_bar[0])
V_max = float(problem.V())
s = np.sqrt(V_max)  # pressure unit of the plots
ZETAS = [1.5, 4.0, 16.0, 128.0]  # output stations
print(problem)
print(f"p_bar = {p_bar:.4g}, V(zeta_max) = {V_max:.4g}, p_bar/sqrt(V) = {p_bar / s:.3g}")
ex = pf.exact(problem, ZETAS)
for z, V, A in zip(ZETAS, ex.V, ex.contact_area):
    print(f"zeta = {z:6.1f}: V = {V:.4e}, A* = {A:.5f}, atom 1 - A* = {1 - A:.5f}")

# %% [markdown]
# ## 1. The image construction — the tutorial's Fig. 5(a)
#
# A Gaussian of variance $V(\zeta)$ centred at $\bar p$ (`eq:Gauss_Distribution`) and its mirror image centred at
# $-\bar p$: their difference vanishes at $p=0$ for every $\zeta$ (absorbing wall, `eq:DiffEqu_BCS`) and obeys the
# diffusion equation, so it *is* $P_0$. The area lost to the mirror image is the atom $1-A^*$; here at $\zeta_{max}$,
# where $\bar p/\sqrt V=0.5$ and the two Gaussians overlap strongly.

# %%
from scipy.integrate import quad


def rho(p, mean, var):  # eq:Gauss_Distribution
    return np.exp(-((p - mean) ** 2) / (2 * var)) / np.sqrt(2 * np.pi * var)


p = np.linspace(-p_bar - 4 * s, p_bar + 4 * s, 801)
g_plus, g_minus = rho(p, p_bar, V_max), rho(p, -p_bar, V_max)
P0_img = pf.image_pdf(p, p_bar, V_max)  # the package's image solution (0 for p <= 0)
ex_max = pf.exact(problem)
fig, ax = plt.subplots(figsize=(7.5, 4.2), layout="constrained")
ax.plot(p / s, g_plus * s, "C0", label=r"$\rho(p;\bar p,V)$")
ax.plot(p / s, g_minus * s, "C1", label=r"$\rho(p;-\bar p,V)$ (mirror image)")
ax.plot(p / s, (g_plus - g_minus) * s, "k:", lw=1, label="difference (all p)")
ax.fill_between(
    p / s, P0_img * s, color="C2", alpha=0.35, label=rf"$P_0$ (p > 0): area $A^*$ = {ex_max.contact_area:.4f}"
)
pfplot.plot_atom(ax, ex_max.atom, ex_max.atom * float(np.max(P0_img * s)), color="C3", label="atom $1-A^*$ at p = 0")
ax.axvline(0, color="0.5", lw=0.8)
ax.axhline(0, color="0.5", lw=0.8)
ax.set_xlabel(r"$p/\sqrt{V}$")
ax.set_ylabel(r"$P\,\sqrt{V}$")
ax.set_title(r"Gaussian, its mirror image and their difference $P_0$ (image solution), $\zeta=\zeta_{max}$")
ax.legend(fontsize=8, loc="upper left")
pos = p > 0
image_dev = float(np.max(np.abs((g_plus - g_minus)[pos] - ex_max.pdf(p[pos]))))
wall_value = float(rho(0.0, p_bar, V_max) - rho(0.0, -p_bar, V_max))
mass_img = quad(lambda x: float(pf.image_pdf(x, p_bar, V_max)), 0.0, np.inf, epsabs=1e-13, epsrel=1e-12)[0]
print(f"max |(rho+ - rho-) - pf.exact(...).pdf| for p > 0: {image_dev:.1e};  rho+ - rho- at p = 0: {wall_value:.1e}")
print(f"quadrature of P0 over p > 0: {mass_img:.12f}, erf(p_bar/sqrt(2V)) = {ex_max.contact_area:.12f}")

# %% [markdown]
# ## 2. PDF broadening with $\zeta$ — the tutorial's Fig. 2(b)
#
# The exact $P_0(p,\zeta)$ on a logarithmic $\zeta$ axis. At $\zeta=1$ the PDF is the unit pulse at $\bar p$; as
# $\zeta$ grows it spreads (variance $V(\zeta)$) and leaks into the atom at $p=0$ (blue stems, length = weight).

# %%
zeta_w = np.concatenate(([1.0], np.geomspace(3.0, problem.zeta_max, 12)))
fig = pfplot.plot_pdf_waterfall(problem, zeta_w)
fig.axes[0].view_init(elev=24, azim=-60)
ex_w = pf.exact(problem, zeta_w[1:])
print("zeta  :", " ".join(f"{z:6.2f}" for z in zeta_w[1:]))
print("1 - A*:", " ".join(f"{a:6.3f}" for a in ex_w.atom))

# %% [markdown]
# ## 3. The four own solvers against the image solution
#
# Each method at its defaults, output stations $\zeta$ = 1.5, 4, 16, 128 (`pf.solve(..., zeta_out=ZETAS)`).
# Lines: exact $P_0$ (cell averages for `fv`/`chapman-kolmogorov`, point values for `mol`/`sines`); markers:
# numerical; arrows at $p=0$: the numerical atom $1-A^*_{num}$ (length = weight × the peak of $P_0$ at
# $\zeta_{max}$). `fv` and `mol` start from the exact solution at a small $\zeta_0>1$ (reported), `sines` and
# `chapman-kolmogorov` from the $\delta$ itself (both represent the first step exactly).

# %%
METHODS = {"fv": {}, "mol": {}, "sines": {}, "chapman-kolmogorov": {}}
sols, rows = (
    {},
    [
        "| method | grid | $\\zeta_0$ | wall [ms] | L1 at ζ = "
        + " / ".join(f"{z:g}" for z in ZETAS)
        + " | $A^*_{num}$ at ζ_max | atom $1-A^*_{num}$ |",
        "|---|---|---|---|---|---|---|",
    ],
)
for m, kw in METHODS.items():
    sol = pf.solve(problem, method=m, zeta_out=ZETAS, **kw)
    sols[m] = sol
    c = sol.compare()
    z0 = np.atleast_1d(sol.info.get("zeta0", 1.0))[0]
    rows.append(
        f"| {m} | {sol.p.size} {sol.kind}s | {z0:.3f} | {sol.wall_time * 1e3:.1f} | "
        + " / ".join(f"{v:.1e}" for v in c.L1[:, 0])
        + f" | {sol.contact_area[-1]:.6f} | {1 - sol.contact_area[-1]:.6f} |"
    )
display(Markdown("\n".join(rows)))

peak = float(np.max(ex_max.pdf(np.linspace(0, p_bar + 5 * s, 2001)))) * s
fig, axes = plt.subplots(2, 2, figsize=(11, 7.5), layout="constrained", sharex=True, sharey=True)
for ax, (m, sol) in zip(axes.flat, sols.items()):
    ref = sol.exact_on_grid()[:, 0]
    step = max(1, sol.p.size // 45)
    for i, z in enumerate(sol.zeta):
        (ln,) = ax.plot(sol.p / s, ref[i] * s, lw=1.0, color=f"C{i}", label=f"ζ = {z:g}")
        ax.plot(sol.p[::step] / s, sol.P0[i, ::step] * s, "o", ms=3, mfc="none", color=f"C{i}")
        w = 1.0 - sol.contact_area[i]
        pfplot.plot_atom(ax, w, w * peak, x=-0.08 * i, color=f"C{i}", fontsize=7, text=w > 1e-3)
    ax.set_title(f"{m}: L1(ζ_max) = {sol.compare().L1[-1, 0]:.1e}", fontsize=10)
    ax.set_xlim(-0.4, (p_bar + 4.5 * s) / s)
    ax.set_ylim(0, 1.1 * float(np.max(ref[2])) * s)
for ax in axes[1]:
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$  (atoms at p = 0, offset left for legibility)")
for ax in axes[:, 0]:
    ax.set_ylabel(r"$P_0\,\sqrt{V(\zeta_{max})}$")
axes[0, 0].legend(fontsize=8)

# %% [markdown]
# ## 4. The errors: $P_0-P_0^{exact}$ against $p$, and $L_1$ against $\zeta$
#
# Top: the signed pointwise error at every station (each panel its own scale: the methods differ by ten orders of
# magnitude; `sines` shows round-off).
# Bottom: $L_1=\int|P_0-P_0^{exact}|\,dp$ at 24 stations per method, from one run each (`sol.compare().L1`).

# %%
fig, axes = plt.subplots(1, 4, figsize=(13, 3.6), layout="constrained")
for ax, (m, sol) in zip(axes, sols.items()):
    d = sol.P0 - sol.exact_on_grid()[:, 0]
    for i, z in enumerate(sol.zeta):
        ax.plot(sol.p / s, d[i] * s, color=f"C{i}", lw=1.0, label=f"ζ = {z:g}")
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-2, 2))
    ax.set_title(m, fontsize=10)
    ax.set_xlabel(r"$p/\sqrt{V(\zeta_{max})}$")
    ax.grid(lw=0.3)
axes[0].set_ylabel(r"$(P_0-P_0^{exact})\sqrt{V(\zeta_{max})}$")
axes[0].legend(fontsize=7)

zeta_many = np.geomspace(1.25, problem.zeta_max, 24)
L1_curves, t_many = {}, {}
for m, kw in METHODS.items():
    t0 = time.perf_counter()
    sol = pf.solve(problem, method=m, zeta_out=zeta_many, **kw)
    t_many[m] = time.perf_counter() - t0
    L1_curves[m] = sol.compare().L1[:, 0]
fig, ax = plt.subplots(figsize=(7, 4.2), layout="constrained")
for k, (m, L1) in enumerate(L1_curves.items()):
    ax.loglog(zeta_many, np.maximum(L1, 1e-17), "o-", ms=3, color=f"C{k}", label=f"{m} ({t_many[m] * 1e3:.0f} ms)")
ax.set_xlabel(r"$\zeta$")
ax.set_ylabel(r"$L_1$ error of $P_0$")
ax.set_title("error against magnification, defaults of each method, 24 stations")
ax.grid(lw=0.3, which="both")
ax.legend(fontsize=8)
for m, L1 in L1_curves.items():
    z_worst = zeta_many[np.argmax(L1)]
    print(f"{m:20s} L1 over the 24 stations: min {L1.min():.1e}, max {L1.max():.1e} (at zeta = {z_worst:.3g})")

# %% tags=["summary"]
# numbers quoted in the closing text (formatted once, here)
A_ex = np.asarray(ex.contact_area)
SUMMARY = {
    "A_max": f"{A_ex[-1]:.4f}",
    "atom_max": f"{1 - A_ex[-1]:.4f}",
    "atom_1p5": f"{1 - A_ex[0]:.2e}",
    "image_dev": f"{image_dev:.0e}",
}
for m, sol in sols.items():
    key = m.split("-")[0]
    SUMMARY[f"L1_{key}"] = f"{sol.compare().L1[-1, 0]:.1e}"
    SUMMARY[f"dA_{key}"] = f"{sol.compare().area_error[-1, 0]:.1e}"
    SUMMARY[f"L1max_{key}"] = f"{L1_curves[m].max():.1e}"
table = "| quantity | value |\n|---|---|\n" + "\n".join(f"| `{k}` | {v} |" for k, v in SUMMARY.items())
display(Markdown(table), metadata={"summary": SUMMARY})

# %%
# checks: this notebook is a test (tests/test_notebooks.py executes it)
from scipy.special import erf, erfc

assert image_dev < 1e-12 and abs(wall_value) < 1e-12  # eq:P0_solution, wall
assert abs(mass_img - erf(p_bar / np.sqrt(2 * V_max))) < 1e-10  # eq:Area_Persson
assert np.allclose(ex_w.atom, erfc(p_bar / np.sqrt(2 * problem.V(zeta_w[1:]))), rtol=1e-12, atol=0)
tol_L1 = {"fv": 1e-3, "mol": 1e-4, "sines": 1e-11, "chapman-kolmogorov": 1e-5}
for m, sol in sols.items():
    c = sol.compare()
    assert np.all(c.L1[-1] < tol_L1[m]), (m, c.L1[-1])
    assert np.all(np.abs(sol.contact_area - pf.exact(problem, ZETAS).contact_area) < 10 * tol_L1[m]), m
    assert np.all(np.diff(sol.contact_area) <= 1e-12), m  # contact only lost
    assert sol.info["checks"]["min_P0"] > -1e-10, m  # P0 >= 0
    assert np.all(c.load_drift < 1e-4), m  # eq:Load_equilibrium
assert np.all(L1_curves["sines"] < 1e-11) and np.all(L1_curves["chapman-kolmogorov"] < 1e-4)
print("all checks passed")

# %% [markdown]
# ## What to take away
#
# * **Fig. 5(a).** The Gaussian minus its mirror image is zero at $p=0$ and equals `pf.exact(...).pdf` to 2e-15
#   for $p>0$. At $\zeta_{max}$ ($\bar p/\sqrt V=0.5$) the contact part keeps $A^*$ = 0.3829; the mirror image has
#   taken the rest, the atom $1-A^*$ = 0.6171 at $p=0$.
# * **Fig. 2(b).** The unit pulse at $\bar p$ broadens with $\zeta$ into a bell that is pinned to zero at the wall,
#   while the atom at $p=0$ grows from 5.35e-11 at $\zeta=1.5$ to 0.6171 at $\zeta_{max}$.
# * **Solvers at their defaults** (L1 of $P_0$ at $\zeta_{max}$ / $|\Delta A^*|$): `fv` 8.2e-06 / 2.8e-06,
#   `mol` 1.8e-06 / 4.6e-07, `sines` 3.1e-16 / 0.0e+00 (round-off: exact start, spectral in $p$, exact in $\zeta$),
#   `chapman-kolmogorov` 3.9e-08 / 1.6e-08 (the first step from the $\delta$ is exact, later steps carry
#   the 4th-order cell error). The numerical atoms agree with the exact ones to the same accuracy.
# * **Error vs $\zeta$.** The worst $L_1$ over 24 stations is 1.0e-02 (`fv`, largest just after its start
#   $\zeta_0$, where few steps have been taken — its default steps are uniform in $\tau$ and favour $\zeta_{max}$),
#   5.2e-06 (`mol`), 5.2e-14 (`sines`) and 2.3e-05 (`chapman-kolmogorov`). The grid methods' errors
#   fall as the PDF widens and the grid resolves it better. `sines` is slower with 24 stations down to $\zeta=1.25$ (legend)
#   than with 4: it sizes its mode count for the narrowest PDF asked for.
