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
# # 06 — Spectrum, heights, slopes, $V(\zeta)$ and elastic energy
#
# **Question.** What does the surface spectrum put into Persson's theory, and how do you bring your own measured
# spectrum? We plot the power spectral density (`E:PSD`, the tutorial's Fig. A.1), the mean-square height
# $\langle h^2\rangle(\zeta)$ (`eq:Vh_closed_form`), the rms slope $\sqrt{\langle|\nabla h|^2\rangle(\zeta)}$
# (`eq:V_gradient`), the complete-contact pressure variance $V(\zeta)=\tfrac14E^{*2}\langle|\nabla h|^2\rangle$
# (`eq:VV_relation`, `eq:Vp_closed_form`) and the elastic energy $U_{el}(\bar p)$ (`eq:Uel_original`) with its
# complete-contact limit (`eq:Uel_complete_2`) — then read a measured, tabulated PSD from a CSV file.
#
# The surfaces are those of the boundary-element reference (notebook 09, `data/bem/README.md`): $L=1$,
# $q_l=2\pi$, $q_r=4\cdot2\pi$, $q_s=64\cdot2\pi$, rms slope 0.1, $E^*=1$; plus the logarithmic limits $H=0$ and $H=1$.
#
# Equation labels such as `eq:P0_solution` or `E:PSD` and figure numbers refer to Y. Xu, X. Li, Q. Chen and
# Y. Zhou, "Persson's Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic
# Process Theory" (the Xu et al. tutorial); all works cited are listed on the documentation's references page.

# %%
# %matplotlib inline
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from IPython.display import Markdown, display
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf
import persson_fp.plotting as pfplot

plt.rcParams["figure.dpi"] = 80  # keeps the committed notebook small
DATA = Path("..") / "data" / "bem"  # the notebook runs in notebooks/
E_star = 1.0
q_l, q_r, q_s = 2 * np.pi, 4 * 2 * np.pi, 64 * 2 * np.pi
HURST = [1.0, 0.8, 0.3, 0.0]
psds = {H: pf.SelfAffinePSD.from_rms_slope(0.1, H=H, q_l=q_l, q_r=q_r, q_s=q_s) for H in HURST}
for H, psd in psds.items():
    print(
        f"H = {H}: C0 = {psd.C0:.4e}, rms height = {psd.rms_height:.4e}, rms slope = {psd.rms_slope:.4f}, "
        f"V = {float(psd.V(E_star=E_star)):.4e}"
    )

# %% [markdown]
# ## 1. The PSD (the tutorial's Fig. A.1)
#
# A plateau $C_0q_r^{-2(1+H)}$ between $q_l$ and the roll-off $q_r$, then the self-affine tail $C_0q^{-2(1+H)}$ up to
# $q_s=\zeta_{max}q_l$. All four spectra are scaled to the same rms slope 0.1, so the rougher (small-$H$)
# spectra carry more power at short wavelengths.

# %%
fig, ax = plt.subplots(figsize=(6.4, 4.4), layout="constrained")
pfplot.plot_psd({f"H = {H:g}": psd for H, psd in psds.items()}, ax=ax)
ax.set_title("self-affine PSD with roll-off, rms slope 0.1")
tail_slopes = {}
for H, psd in psds.items():  # log-log slope of the tail, must be -2(1 + H)
    qa, qb = 2 * q_r, q_s / 2
    tail_slopes[H] = float(np.log(psd.C(qb) / psd.C(qa)) / np.log(qb / qa))
print("tail slopes d ln C / d ln q:", {H: round(s, 12) for H, s in tail_slopes.items()})

# %% [markdown]
# ## 2. $\langle h^2\rangle(\zeta)$, rms slope and $V(\zeta)$
#
# All three are moments of the spectrum over $[q_l,\zeta q_l]$: $\langle h^2\rangle = 2\pi\int qC\,dq$,
# $\langle|\nabla h|^2\rangle=2\pi\int q^3C\,dq$. The height is set by the long wavelengths (for $H>0$ it saturates
# soon after the roll-off), the slope — and with it $V$ and the contact area — by the short ones (for $H<1$ it
# keeps growing up to $q_s$). The package evaluates them in closed form, with the logarithmic limits at $H=0$ (heights)
# and $H=1$ (slopes); here they are checked against direct numerical quadrature of $C(q)$.

# %%
zeta = np.geomspace(1.0, q_s / q_l, 300)
fig, axes = plt.subplots(1, 3, figsize=(13, 4), layout="constrained")
quad_dev = 0.0
h2_from_plateau, V_from_plateau, V_last_octave = {}, {}, {}
for H, psd in psds.items():
    axes[0].loglog(zeta, np.sqrt(psd.h2(zeta)), label=f"H = {H:g}")
    axes[1].semilogx(zeta, np.sqrt(psd.grad2(zeta)), label=f"H = {H:g}")
    axes[2].semilogx(zeta, psd.V(zeta, E_star), label=f"H = {H:g}")
    for k, closed in ((1, psd.h2()), (3, psd.grad2())):
        # quadrature in ln q (dq = q dt), split at the roll-off kink
        num = sum(
            quad(lambda t: 2 * np.pi * np.exp((k + 1) * t) * psd.C(np.exp(t)), np.log(a), np.log(b), epsrel=1e-13)[0]
            for a, b in ((q_l, q_r), (q_r, q_s))
        )
        quad_dev = max(quad_dev, abs(num / closed - 1.0))
    h2_from_plateau[H] = float(psd.h2(q_r / q_l) / psd.h2())
    V_from_plateau[H] = float(psd.V(q_r / q_l, E_star) / psd.V(None, E_star))
    V_last_octave[H] = float(1.0 - psd.V(psd.zeta_max / 2, E_star) / psd.V(None, E_star))
axes[0].set_ylabel(r"rms height $\sqrt{\langle h^2\rangle(\zeta)}$ [L]")
axes[1].set_ylabel(r"rms slope $\sqrt{\langle|\nabla h|^2\rangle(\zeta)}$")
axes[2].set_ylabel(r"$V(\zeta)$ [$E^{*2}$]")
for ax in axes:
    ax.set_xlabel(r"$\zeta = q/q_l$")
    ax.axvline(q_r / q_l, color="0.6", lw=0.8, ls=":")
    ax.grid(lw=0.3, which="both")
axes[0].legend(fontsize=8)
print(f"closed forms vs quadrature: max relative deviation {quad_dev:.1e}")
for H in HURST:
    print(
        f"H = {H:g}: below q_r: {h2_from_plateau[H]:.3f} of <h^2>, {V_from_plateau[H]:.3f} of V; "
        f"last octave: {V_last_octave[H]:.3f} of V"
    )

# %% [markdown]
# ## 3. Elastic energy $U_{el}(\bar p)$ (`eq:Uel_original`)
#
# $U_{el}/A_n=\frac{\pi E^*}{2}\int_{q_l}^{q_s} q^2C(q)\,A^*(\bar p,q/q_l)\,S(A^*)\,dq$ (`pf.elastic_energy`; $S=1$ for
# Persson's theory). At complete contact ($A^*=1$ at every scale) it becomes
# $\frac{\pi E^*}{2}\int q^2C\,dq$ (`eq:Uel_complete_2`, `psd.elastic_energy_complete`). Below: $H=0.8$, all fudge models,
# $U_{el}$ relative to the complete-contact value.

# %%
MODELS = {"Persson (None)": None, "YP08 (γ = 0.45)": "YP08", "WM17 (γ = 5/9)": "WM17", "Xu24 (γ = 0.45)": "Xu24"}
psd = psds[0.8]
V_max = float(psd.V(E_star=E_star))
U_c = float(psd.elastic_energy_complete(E_star=E_star))
ratio = np.geomspace(1e-3, 30.0, 40)  # p_bar / sqrt(V)
U = {}
fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
for label, f in MODELS.items():
    U[label] = pf.elastic_energy(pf.ContactProblem(psd, E_star, ratio * np.sqrt(V_max), fudge=f))
    ax0.loglog(ratio, U[label] / U_c, "-", label=label)
    ax1.semilogx(ratio, U[label] / U_c, "-", label=label)
for ax in (ax0, ax1):
    ax.axhline(1.0, color="k", ls="--", lw=1)
    ax.set_xlabel(r"$\bar p/\sqrt{V}$")
    ax.set_ylabel(r"$U_{el}\,/\,U_{el}^{complete}$")
    ax.grid(lw=0.3, which="both")
ax0.legend(fontsize=8)
ax0.set_title(f"H = 0.8; complete contact: U_el/A_n = {U_c:.3e} E*·L")
# the original theory in its own words: (pi E*/2) int q^2 C erf(p/sqrt(2V(q))) dq by plain quadrature
p_check = 0.5 * np.sqrt(V_max)


def integrand(t):  # q^2 C(q) erf(p / sqrt(2 V(q/q_l))) dq with q = e^t, dq = q dt
    q = np.exp(t)
    return q**3 * psd.C(q) * erf(p_check / np.sqrt(2.0 * psd.V(min(q / q_l, psd.zeta_max), E_star)))


manual = (
    0.5
    * np.pi
    * E_star
    * sum(quad(integrand, np.log(a), np.log(b), epsrel=1e-12)[0] for a, b in ((q_l, q_r), (q_r, q_s)))
)
U_half = float(pf.elastic_energy(pf.ContactProblem(psd, E_star, p_check)))
print(f"U_el at p/sqrt(V) = 0.5: pf.elastic_energy {U_half:.10e}, direct quadrature {manual:.10e}")
print(f"relative difference {U_half / manual - 1:.1e}")
print("U_el / U_complete at p/sqrt(V) = 30:", {k: f"{v[-1] / U_c:.6f}" for k, v in U.items()})

# %% [markdown]
# ## 4. A measured spectrum from a CSV file
#
# Users bring a table $q$, $C(q)$. Here: the realised, shell-averaged PSD of one of the boundary-element
# surfaces (`data/bem/psd_shells_H0.8_seed1.csv`). Such files often need cleaning — this one starts with the mean
# (shell $n=0$, $q=0$), and beyond $|k|=64$ it holds only round-off ($C\sim10^{-45}$). `TabulatedPSD.from_csv` refuses
# $q=0$ with a message naming the line:

# %%
path = DATA / "psd_shells_H0.8_seed1.csv"
print("".join(path.read_text().splitlines(keepends=True)[:4]))
try:
    pf.TabulatedPSD.from_csv(path, q_column="q", C_column="C_shell_avg")
except ValueError as err:
    print("ValueError:", err)

# %% [markdown]
# Two ways to clean it: (a) read the columns yourself and keep the band $1\le n\le64$, or (b) write a cleaned CSV and
# use `from_csv`. Both give the same spectrum. The table's own cumulative column `V_cum` is the *discrete* sum over
# Fourier modes; `TabulatedPSD` integrates the log-log interpolant of the shell averages, a continuum
# approximation of that sum — the small difference in $V$ printed below is that approximation, not an error of the data.

# %%
import csv
import tempfile

table = np.genfromtxt(path, delimiter=",", names=True)
keep = (table["n"] >= 1) & (table["n"] <= 64)  # drop the mean (q = 0) and the empty shells beyond q_s
measured = pf.TabulatedPSD(table["q"][keep], table["C_shell_avg"][keep])  # way (a)

with tempfile.TemporaryDirectory() as tmp:  # way (b)
    clean = Path(tmp) / "psd_clean.csv"
    with open(clean, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["q", "C"])
        w.writerows(zip(table["q"][keep], table["C_shell_avg"][keep]))
    measured_b = pf.TabulatedPSD.from_csv(clean)
same = bool(np.allclose(measured.V(), measured_b.V(), rtol=1e-15))
print(measured, "| (a) and (b) agree:", same)

V_file = float(table["V_cum"][table["n"] == 64][0])
V_tab = float(measured.V(E_star=E_star))
print(f"V: discrete sum in the file {V_file:.5e}, TabulatedPSD {V_tab:.5e} ({V_tab / V_file - 1:+.2%})")
print(f"   nominal SelfAffinePSD {V_max:.5e}")

fig, (ax0, ax1) = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
pfplot.plot_psd({"nominal H = 0.8": psd, "measured (one realisation)": measured}, ax=ax0)
ax0.set_title("realised vs nominal spectrum")
zs = table["q"][keep] / q_l
ax1.step(zs, table["V_cum"][keep], where="post", color="0.5", label="V_cum in the file (discrete sum)")
z = np.geomspace(1.0, min(measured.zeta_max, psd.zeta_max), 300)  # the CSV rounds q: zeta_max 64 + 8e-9
ax1.semilogx(z, measured.V(z, E_star), label="TabulatedPSD")
ax1.semilogx(z, psd.V(z, E_star), "--", label="nominal SelfAffinePSD")
ax1.set_xlabel(r"$\zeta$")
ax1.set_ylabel(r"$V(\zeta)$")
ax1.legend(fontsize=8)

# what it changes for the contact area: at zeta_max only through V; in between through V(zeta)
p = 0.1 * np.sqrt(V_max)
A_meas = pf.exact(pf.ContactProblem(measured, E_star, p, fudge="YP08"), zeta=z)
A_nom = pf.exact(pf.ContactProblem(psd, E_star, p, fudge="YP08"), zeta=z)
dev_A = np.abs(A_meas.contact_area / A_nom.contact_area - 1.0)
print(
    f"YP08 A* at zeta_max: measured {A_meas.contact_area[-1]:.5f}, nominal {A_nom.contact_area[-1]:.5f}; "
    f"largest relative difference along zeta {dev_A.max():.1%}"
)

# %% tags=["summary"]
SUMMARY = {
    "quad_dev": f"{quad_dev:.0e}",
    "h2_plateau_08": f"{h2_from_plateau[0.8]:.2f}",
    "h2_plateau_03": f"{h2_from_plateau[0.3]:.2f}",
    "V_plateau_08": f"{V_from_plateau[0.8]:.3f}",
    "V_plateau_03": f"{V_from_plateau[0.3]:.3f}",
    "V_oct_10": f"{V_last_octave[1.0]:.2f}",
    "V_oct_00": f"{V_last_octave[0.0]:.2f}",
    "U_c": f"{U_c:.3e}",
}
i_half = int(np.argmin(np.abs(ratio - 1.0)))
for label, s in zip(MODELS, ("none", "YP08", "WM17", "Xu24")):
    SUMMARY[f"U1_{s}"] = f"{U[label][i_half] / U_c:.3f}"
SUMMARY["r_U1"] = f"{ratio[i_half]:.2f}"
SUMMARY["U_large"] = f"{min(v[-1] for v in U.values()) / U_c:.4f}"
SUMMARY["V_tab_dev"] = f"{V_tab / V_file - 1:+.2%}"
SUMMARY["A_dev"] = f"{dev_A.max():.1%}"
display(
    Markdown("| quantity | value |\n|---|---|\n" + "\n".join(f"| `{k}` | {v} |" for k, v in SUMMARY.items())),
    metadata={"summary": SUMMARY},
)

# %%
# checks: this notebook is a test (tests/test_notebooks.py executes it)
for H, s in tail_slopes.items():
    assert abs(s + 2 * (1 + H)) < 1e-10, H  # E:PSD tail exponent
for p_ in psds.values():
    assert abs(p_.rms_slope - 0.1) < 1e-12 and abs(float(p_.V(E_star=E_star)) - 0.0025) < 1e-15
assert quad_dev < 1e-8  # eq:Vh_closed_form, eq:V_gradient
assert abs(U_half / manual - 1.0) < 1e-8  # eq:Uel_original
assert all(np.all(np.diff(v) >= 0) for v in U.values())  # U_el never falls as the load grows
assert all(abs(v[-1] / U_c - 1.0) < 1e-3 for v in U.values())  # complete-contact limit eq:Uel_complete_2
assert same and abs(V_file - 0.0025) < 1e-12 and abs(V_tab / V_file - 1.0) < 0.03
print("all checks passed")

# %% [markdown]
# ## What to take away
#
# * **PSD.** Plateau below the roll-off, power law $q^{-2(1+H)}$ beyond it (exponent checked to round-off); at
#   equal rms slope the small-$H$ spectra carry more short-wavelength power.
# * **Heights vs slopes.** The closed forms (including $H=0$ and $H=1$) agree with direct quadrature to 2e-15.
#   Heights are a long-wavelength property: the plateau $q<q_r$ (a factor 4 of the factor-64 band) holds
#   0.43 (H = 0.8) and 0.26 (H = 0.3) of $\langle h^2\rangle$ but only 0.047 and
#   0.007 of $V$. Slopes — hence $V$ and the contact area — are a short-wavelength property: the last
#   octave below $q_s$ holds 0.75 of $V$ at $H=0$ and still 0.23 at $H=1$.
# * **Elastic energy.** $U_{el}$ grows monotonically with the load towards its complete-contact value
#   $U_{el}/A_n$ = 3.135e-05 $E^*L$ (reached to better than 1e-3 by every model at $\bar p/\sqrt V$ = 30, smallest ratio
#   1.0000). At $\bar p/\sqrt V$ = 0.97, $U_{el}/U_{el}^{complete}$ = 0.929 (Persson), 0.880 (YP08),
#   0.850 (WM17), 0.868 (Xu24): the corrected models store less energy at a given load.
# * **Measured spectrum.** After dropping the $q=0$ row and the empty shells, `TabulatedPSD` reproduces the surface's
#   $V$ to -1.53% (continuum integral of shell averages vs the discrete sum). For the contact area at $\zeta_{max}$
#   only $V(\zeta_{max})$ matters; along $\zeta$ the realised spectrum changes the YP08 $A^*$ by at most 9.1% against
#   the nominal one.
