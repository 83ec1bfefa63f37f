# ---
# jupyter:
#   jupytext:
#     formats: ipynb,py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3 (ipykernel)
#     language: python
#     name: python3
# ---

# %% [markdown]
# # The zero-contact-area paradox and elastoplastic contact
#
# In Persson's purely elastic theory the relative contact area at full magnification is
# $A^* = \mathrm{erf}(\bar p/\sqrt{2V(\zeta)})$ (Xu et al. tutorial, Eq. 'eq:Area_Persson'). For a fractal
# surface $V(\zeta)$ grows without bound, so $A^* \to 0$ as $\zeta \to \infty$: two solids pressed together
# would touch nowhere. The tutorial's section "Zero contact area paradox" points to the resolution
# (Persson, Phys. Rev. Lett. 87 (2001) 116101): real asperities cannot carry more than the penetration
# hardness $\sigma_Y$. The pressure PDF then lives on $0 < p < \sigma_Y$; what reaches the yield wall
# becomes **plastic** contact area $A_{pl}$, with the load balance $F_{el} + \sigma_Y A_{pl} = \bar p$.
#
# This notebook shows, for magnifications up to $\zeta = 10^{16}$:
# 1. a constant hardness (the strip problem, exact in closed form, checked against `fv`);
# 2. a size-dependent hardness $\sigma_Y = \sigma_1\zeta^{0.2}$ (a moving yield wall, no closed form:
#    `fv` with its own error estimate);
# 3. the pressure PDF with its yield cap.

# %%
import matplotlib.pyplot as plt
import numpy as np

import persson_fp as pf

# a rough self-affine surface: H = 0.8, rms slope 3 over 16 decades of wavenumber, E* = 1
psd = pf.SelfAffinePSD.from_rms_slope(3.0, H=0.8, q_l=1.0, q_r=1.0, q_s=1e16)
p_bar, sigma_1 = 3e-4, 1e-3  # nominal pressure and hardness at the macroscale, in units of E*
zeta = np.geomspace(1.0 + 1e-6, 1e16, 400)

elastic = pf.ContactProblem(psd, p_bar=p_bar)
constant = pf.ContactProblem(psd, p_bar=p_bar, hardness=sigma_1)
moving = pf.ContactProblem(psd, p_bar=p_bar, hardness=pf.hardness.PowerLaw(sigma_1, 0.2))
print(constant)
print(moving)

# %% [markdown]
# ## 1. Constant hardness: the exact strip series
# With a constant $\sigma_Y$ the PDF obeys the heat equation between two absorbing walls; its image and sine
# series give $A_{el}$, $A_{pl}$ and the non-contact area $A_{non}$ in closed form (`pf.exact`).
# `fv` solves the same problem numerically (its spectral fast path, the yield wall as the far wall).

# %%
ex_el = pf.exact(elastic, zeta)
ex = pf.exact(constant, zeta)
stations = np.geomspace(10.0, 1e16, 16)
sol_c = pf.solve(constant, method="fv", n_p=200, n_steps=1000, zeta_out=stations)
err_c = sol_c.compare()
print(
    f"fv vs exact strip: max |dA_pl| = {np.max(err_c.plastic_area_error):.2e}, "
    f"max |dA_el| = {np.max(err_c.elastic_area_error):.2e}"
)
print(f"A_pl(1e16) = {ex.plastic_area[-1]:.12f}   p_bar / sigma_Y = {p_bar / sigma_1:.12f}")

# %% [markdown]
# ## 2. A size-dependent hardness: the moving yield wall
# Indentation hardness grows at small scales; with $\sigma_Y = \sigma_1\zeta^{n}$ the wall moves outwards as
# the magnification grows. The PDF no longer vanishes at the wall: the load balance requires
# $P(\sigma_Y) = 2\,\dot\sigma_Y A_{pl}$ ($\dot\sigma_Y = d\sigma_Y/d\tau$), and plastic area is handed back to
# the elastic domain as the wall recedes. `fv` front-fixes the wall ($x = p/\sigma_Y$, second order) and
# pairs every run with one at half the resolution: the difference is its error estimate.

# %%
sol_m = pf.solve(moving, method="fv", n_p=200, n_steps=1600, zeta_out=stations)
est = sol_m.info["error_estimate"]
print(f"area balance residual {sol_m.info['area_residual']:.1e}, load residual {sol_m.info['load_residual']:.1e}")
print(f"A_pl(1e16) = {float(sol_m.plastic_area[-1]):.6e} +- {float(est['plastic_area'][-1, 0]):.1e}")

# %%
fig, ax = plt.subplots(figsize=(8, 4.8))
ax.semilogx(zeta, ex_el.contact_area, "k-", label="purely elastic $A^*$ (tends to 0)")
ax.semilogx(zeta, ex.contact_area, "C0-", label=r"constant $\sigma_Y$: $A_{el} + A_{pl}$ (exact)")
ax.semilogx(zeta, ex.elastic_area, "C0:", label=r"constant $\sigma_Y$: elastic part $A_{el}$")
ax.semilogx(zeta, ex.plastic_area, "C0--", label=r"constant $\sigma_Y$: plastic part $A_{pl}$")
ax.semilogx(stations, sol_c.plastic_area, "C0o", ms=4, label="finite volumes (fv), constant $\\sigma_Y$")
ax.errorbar(
    stations,
    sol_m.contact_area,
    yerr=est["plastic_area"][:, 0] + est["elastic_area"][:, 0],
    fmt="C3s-",
    ms=4,
    label=r"$\sigma_Y = \sigma_1\zeta^{0.2}$: $A_{el} + A_{pl}$ (fv, with error bars)",
)
ax.semilogx(stations, sol_m.plastic_area, "C3^--", ms=4, label=r"$\sigma_Y = \sigma_1\zeta^{0.2}$: $A_{pl}$")
ax.axhline(p_bar / sigma_1, color="0.5", lw=0.8)
ax.text(1e12, p_bar / sigma_1 * 1.04, r"$\bar p/\sigma_Y$", color="0.4")
ax.set_xlabel(r"magnification $\zeta = q/q_l$")
ax.set_ylabel("fraction of the nominal area")
ax.set_ylim(0, 1.02)
ax.legend(fontsize=8, loc="upper right")
ax.set_title("Contact area with and without a hardness")
plt.show()

# %% [markdown]
# ## 3. The pressure PDF with its yield cap
# Below: $P(p)$ at three magnifications each (for the constant hardness early ones: the strip empties on the
# time scale $V \sim \sigma_Y^2$). The plastic area is an atom at $p = \sigma_Y$ (drawn as a bar whose
# height is its mass); the non-contact area an atom at $p = 0$ (not drawn). With the moving wall the PDF ends
# at a non-zero value, $2\dot\sigma_Y A_{pl}$.

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4))
# constant hardness: the strip empties on the time scale sigma_Y^2, so look where V = 0.05, 0.3, 1.5 sigma_Y^2
z_const = psd.zeta_of_V(np.array([0.05, 0.3, 1.5]) * sigma_1**2)
p = np.linspace(0, sigma_1, 400)
for i, (z, c) in enumerate(zip(z_const, ("C0", "C1", "C2"))):
    exz = pf.exact(constant, z)
    axes[0].plot(p / sigma_1, exz.pdf(p) * sigma_1, c, label=f"zeta = {z:.3g}")
    axes[0].bar(1.0 + 0.025 * i, float(exz.plastic_area), width=0.02, color=c, alpha=0.6)
for i, (k, c) in enumerate(zip((0, 1, 5), ("C0", "C1", "C2"))):
    axes[1].plot(sol_m.p[k] / sol_m.sigma_Y[k], sol_m.P0[k] * sol_m.sigma_Y[k], c, label=f"zeta = {stations[k]:.3g}")
    axes[1].bar(1.0 + 0.025 * i, float(sol_m.plastic_area[k]), width=0.02, color=c, alpha=0.6)
axes[0].set_title(r"constant $\sigma_Y$ (exact strip series)")
axes[1].set_title(r"$\sigma_Y = \sigma_1\zeta^{0.2}$ (fv, front-fixed)")
for ax in axes:
    ax.set_xlabel(r"$p/\sigma_Y(\zeta)$")
    ax.set_ylabel(r"$\sigma_Y P(p)$;  bars: plastic area $A_{pl}$")
    ax.legend(fontsize=8)
plt.tight_layout()
plt.show()

# %% [markdown]
# ## Checks (this notebook is a test: it fails if a number drifts)

# %%
# the paradox resolved: all elastic contact is gone, the plastic area carries the load at the hardness
assert float(ex_el.contact_area[-1]) < 1e-3
assert abs(float(ex.plastic_area[-1]) - p_bar / sigma_1) < 1e-12
assert float(ex.elastic_area[-1]) < 1e-12
# fv against the exact strip series, and the moving wall's own bookkeeping
assert np.max(err_c.plastic_area_error) < 1e-6
assert sol_m.info["area_residual"] < 1e-12 and sol_m.info["load_residual"] < 1e-3
# the estimate (|run - half-resolution run|, conservative) stays below 0.2 % of A_pl at every station
assert np.all(est["plastic_area"][:, 0] <= 2e-3 * sol_m.plastic_area)
# self-similarity: sigma_Y and sqrt(V) both grow like zeta^0.2 on this surface, so at large zeta the
# dimensionless problem stops changing and A_pl ~ p_bar / sigma_Y ~ zeta^-0.2 (fitted over the last 6 decades)
slope = np.polyfit(np.log(stations[-7:]), np.log(sol_m.plastic_area[-7:]), 1)[0]
print(f"d ln A_pl / d ln zeta = {slope:.4f} (self-similar value -0.2)")
assert abs(slope + 0.2) < 2e-3

# %% [markdown]
# ## What to take away
# - Without a hardness the contact area vanishes as the magnification grows (the tutorial's paradox); with a
#   constant hardness the elastic area still vanishes, but the **plastic area tends to $\bar p/\sigma_Y$**, so the
#   total contact area stays finite: the load is carried at the yield stress.
# - A hardness that grows at small scales (here $\sigma_1\zeta^{0.2}$, which grows like $\sqrt{V}$ on this surface)
#   keeps shrinking the contact area, but only like $\zeta^{-0.2}$ (the problem becomes self-similar, and
#   $A_{pl} \propto \bar p/\sigma_Y$), with the plastic part the larger one.
# - The constant case is exact in closed form (`pf.exact`), and `fv` reproduces it to better than 1e-6; the moving
#   wall has no closed form: `fv` reports the area balance (round-off), the load balance and an error estimate
#   from a half-resolution partner run with every result.
