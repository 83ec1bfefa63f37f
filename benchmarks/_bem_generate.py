"""Regenerate the BEM gap fields, Reynolds leak rates and exponential-adhesion runs of ``data/bem`` and compare them.

Needs the optional ``bem`` extra (``pip install .[bem]``: Tamaas 2.9.0 and reynoldsflow).  The recipe is the one
``data/bem/README.md`` states for the shipped files: the H = 0.8 surfaces rebuilt from their Fourier modes
(``data/bem/surfaces``), L = 1, E* = 1, rms slope 0.1, loads p̄/(E* ḡ) in {0.005, ..., 0.5}; gap histograms over the
non-contact area (``_bem_stats``), Reynolds flow with conductance g^3/(12 eta), eta = 1, unit pressure drop along
x (axis 0) and along y (axis 1), periodic across, solved by ``reynoldsflow`` (direct) and by ``_reynolds.flow``; and
the exponential adhesion (rho = 8e-3, w = 1e-5 and 3e-6, seed 1) at the shipped rows' repulsive pressures
(``_bem_tamaas.Contact.adhesive``).  Written to ``<out>/bem_generated/*.csv`` in the shipped files' columns.
"""

from __future__ import annotations

import csv
import os
import time

import numpy as np
from _bem_stats import gap_statistics, ks_histograms
from _bem_tamaas import Contact, surface_from_modes
from _common import write_csv
from _reynolds import flow, flow_reynoldsflow

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "bem")
LOADS = (0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5)
G_BAR, E_STAR, HURST = 0.1, 1.0, 0.8
FILES = ("gap_histograms_H0.8.csv", "leakage_H0.8.csv", "adhesion_exponential_H0.8_seed1.csv")


def read(folder, name):
    with open(os.path.join(folder, name), newline="") as fh:
        return list(csv.DictReader(fh))


def _versions():
    from importlib.metadata import version

    return f"tamaas {version('tamaas')}, reynoldsflow {version('reynoldsflow')}"


def _leak(gap):
    out = {}
    for axis, name in ((0, "x"), (1, "y")):
        fv = flow(gap, axis=axis)
        rf = flow_reynoldsflow(gap, axis=axis)
        out[f"K_{name}"] = rf["Q"]
        out[f"K_{name}_fv"] = fv["Q"]
        out[f"percolates_{name}"] = fv["percolates"]
        if fv["percolates"] != rf["percolates"]:
            raise RuntimeError("the finite-volume solver and reynoldsflow disagree on percolation")
        out[f"fv_conservation_{name}"] = abs(fv["inflow"] - fv["outflow"]) / fv["Q"] if fv["Q"] > 0 else 0.0
        out[f"fv_vs_rf_{name}"] = abs(fv["Q"] / rf["Q"] - 1) if rf["Q"] > 0 else float(fv["Q"] != 0)
    out["K_mean"] = 0.5 * (out["K_x"] + out["K_y"])
    out["K_mean_fv"] = 0.5 * (out["K_x_fv"] + out["K_y_fv"])
    return out


def contact_runs(n, seeds, log):
    """Gap histogram rows and leak-rate rows for each seed and load; (hist_rows, leak_rows, seconds)."""
    hist_rows, leak_rows, t_contact, t_flow = [], [], 0.0, 0.0
    for seed in seeds:
        h = surface_from_modes(os.path.join(DATA, "surfaces", f"surface_H0.8_seed{seed}_modes.npz"), n)
        hrms = float(h.std())
        bem = Contact(h)
        for pn in LOADS:  # increasing loads: Tamaas starts from the previous pressure
            pbar = pn * E_STAR * G_BAR
            t0 = time.perf_counter()
            p, u, gap = bem.solve(pbar)
            t1 = time.perf_counter()
            if abs(p.mean() / pbar - 1) > 1e-8:
                raise RuntimeError(f"mean pressure {p.mean():.6g} is not {pbar:.6g}")
            if bem.check_compliance(p, u) > 1e-8:
                raise RuntimeError("Tamaas's displacement is not the half-space compliance 2 p_q / (E* |q|)")
            st = gap_statistics(gap, hrms)
            base = dict(H=HURST, seed=seed, N=n, pbar_norm=pn, pbar=pbar)
            stats = dict(contact_fraction=st["contact_fraction"], mean_gap=st["mean_gap"], gap_std=st["gap_std"])
            for lo, hi, d in zip(st["edges"][:-1], st["edges"][1:], st["density"]):
                hist_rows.append(dict(base, **stats, hrms=hrms, bin_lo=lo, bin_hi=hi, density=d))
            leak = _leak(gap)
            t2 = time.perf_counter()
            t_contact, t_flow = t_contact + t1 - t0, t_flow + t2 - t1
            leak_rows.append(
                dict(base, hrms=hrms, contact_fraction=st["contact_fraction"], mean_gap=st["mean_gap"], **leak)
            )
            log(
                f"seed {seed} p/(E*g) {pn:g}: A {st['contact_fraction']:.5f}, K {leak['K_mean']:.4g} "
                f"(fv {leak['K_mean_fv']:.4g}), BEM {t1 - t0:.1f} s, flow {t2 - t1:.1f} s"
            )
    return hist_rows, leak_rows, t_contact, t_flow


def adhesion_runs(n, quick, log):
    """Seed 1 with exponential adhesion at the repulsive pressures of the shipped rows (w > 0)."""
    shipped = [r for r in read(DATA, FILES[2]) if float(r["w"]) > 0]
    h = surface_from_modes(os.path.join(DATA, "surfaces", "surface_H0.8_seed1_modes.npz"), n)
    bem = Contact(h)
    rows = []
    for w in sorted({float(r["w"]) for r in shipped}, reverse=True):
        sel = sorted((r for r in shipped if float(r["w"]) == w), key=lambda r: -float(r["mean_p_rep"]))
        p_reps = sorted({float(r["mean_p_rep"]) for r in sel}, reverse=True)
        if quick:
            p_reps = p_reps[::3]
        rho = float(sel[0]["rho"])
        for p_rep in p_reps:
            r = bem.adhesive(p_rep, w, rho)
            rows.append(
                dict(
                    H=HURST,
                    seed=1,
                    N=n,
                    w=w,
                    rho=rho,
                    hrms=float(h.std()),
                    control="prescribed mean repulsive pressure",
                    mean_p=r["mean_p"],
                    pbar_norm=r["mean_p"] / (E_STAR * G_BAR),
                    mean_p_rep=r["mean_p_rep"],
                    p_rep_target=p_rep,
                    mean_p_att=r["mean_p_att"],
                    A_rep=r["A_rep"],
                    mean_gap=r["mean_gap"],
                    loops=r["loops"],
                    converged=r["converged"],
                )
            )
            log(f"adhesion w {w:g} p_rep {p_rep:.4g}: mean p {r['mean_p']:.5g} ({r['loops']} loops)")
    return rows


def generate(out, n=512, quick=False, log=print):
    """Write ``out``/bem_generated/{gap_histograms,leakage,adhesion...}.csv and generation.csv; return that folder."""
    folder = os.path.join(out, "bem_generated")
    os.makedirs(folder, exist_ok=True)
    seeds = (1,) if quick else (1, 2, 3)
    t0 = time.perf_counter()
    hist, leak, t_contact, t_flow = contact_runs(n, seeds, log)
    t1 = time.perf_counter()
    adh = adhesion_runs(n, quick, log)
    t2 = time.perf_counter()
    write_csv(os.path.join(folder, FILES[0]), hist)
    write_csv(os.path.join(folder, FILES[1]), leak)
    write_csv(os.path.join(folder, FILES[2]), adh)
    meta = dict(
        N=n,
        seeds=" ".join(map(str, seeds)),
        packages=_versions(),
        tamaas_contact_s=round(t_contact, 2),
        reynolds_flow_s=round(t_flow, 2),
        contact_and_flow_s=round(t1 - t0, 2),
        adhesion_s=round(t2 - t1, 2),
        adhesion_solves=sum(r["loops"] for r in adh),
    )
    write_csv(os.path.join(folder, "generation.csv"), [meta])
    return folder


def _hist(rows):
    out = {}
    for r in rows:
        h = out.setdefault((int(r["seed"]), float(r["pbar_norm"])), dict(r=r, edges=[float(r["bin_lo"])], d=[]))
        h["edges"].append(float(r["bin_hi"]))
        h["d"].append(float(r["density"]))
    return out


def _span(values, fmt):
    values = [v for v in values if np.isfinite(v)]
    return "—" if not values else f"{fmt.format(min(values))} to {fmt.format(max(values))}"


def compare(folder, shipped=DATA):
    """Generated against shipped data: a list of (quantity, agreement, worst value) rows and a dict of the worsts."""
    gh, sh = _hist(read(folder, FILES[0])), _hist(read(shipped, FILES[0]))
    keys = sorted(set(gh) & set(sh))
    dA = [abs(float(gh[k]["r"]["contact_fraction"]) / float(sh[k]["r"]["contact_fraction"]) - 1) for k in keys]
    dg = [abs(float(gh[k]["r"]["mean_gap"]) / float(sh[k]["r"]["mean_gap"]) - 1) for k in keys]
    ks = [ks_histograms(np.array(gh[k]["edges"]), gh[k]["d"], sh[k]["d"]) for k in keys]
    gl = {(int(r["seed"]), float(r["pbar_norm"])): r for r in read(folder, FILES[1])}
    sl = {(int(r["seed"]), float(r["pbar_norm"])): r for r in read(shipped, FILES[1])}
    lk = sorted(set(gl) & set(sl))
    ratio = [float(gl[k]["K_mean"]) / float(sl[k]["K_mean"]) for k in lk if float(sl[k]["K_mean"]) > 0]
    sealed = all((float(gl[k]["K_mean"]) == 0) == (float(sl[k]["K_mean"]) == 0) for k in lk)
    fv = [float(gl[k][f"fv_vs_rf_{a}"]) for k in gl for a in "xy"]
    cons = [float(gl[k][f"fv_conservation_{a}"]) for k in gl for a in "xy"]
    ga = read(folder, FILES[2])
    sa = [r for r in read(shipped, FILES[2]) if float(r["w"]) > 0]
    dp, pull = [], []
    for w in sorted({float(r["w"]) for r in ga}):
        g_w = [r for r in ga if float(r["w"]) == w]
        s_w = [r for r in sa if float(r["w"]) == w]
        by_p = {float(r["mean_p_rep"]): float(r["mean_p"]) for r in s_w}
        dp += [abs(float(r["mean_p"]) - by_p[float(r["p_rep_target"])]) / (w / float(r["rho"])) for r in g_w]
        pull.append((w, -min(float(r["mean_p"]) for r in g_w), -min(float(r["mean_p"]) for r in s_w)))
    worst = dict(
        contact_fraction=max(dA),
        mean_gap=max(dg),
        ks=max(ks),
        leak=max(abs(r - 1) for r in ratio),
        sealed_same=sealed,
        fv_vs_reynoldsflow=max(fv),
        fv_conservation=max(cons),
        mean_p_adhesion=max(dp),
        pull_off=max(abs(g / s - 1) for _, g, s in pull),
    )
    rows = [
        ("contact fraction: max relative difference", f"{len(keys)} fields", f"{worst['contact_fraction']:.1e}"),
        ("mean gap: max relative difference", f"{len(keys)} fields", f"{worst['mean_gap']:.1e}"),
        ("gap histogram: max Kolmogorov-Smirnov distance", f"{len(keys)} fields", f"{worst['ks']:.1e}"),
        (
            "leak rate K_mean: generated/shipped (worst: max relative difference)",
            _span(ratio, "{:.6f}") + ("; sealed alike" if sealed else ""),
            "",
        ),
        (
            "own finite volumes (_reynolds.py) vs reynoldsflow: max relative difference of K",
            f"{len(fv)} flows",
            f"{worst['fv_vs_reynoldsflow']:.1e}",
        ),
        ("own finite volumes: max (inflow − outflow)/Q", f"{len(cons)} flows", f"{worst['fv_conservation']:.1e}"),
        (
            "adhesion, same p_rep: max difference of the applied mean traction / (w/ρ)",
            f"{len(dp)} rows",
            f"{worst['mean_p_adhesion']:.1e}",
        ),
    ]
    for w, g, s in pull:
        rows.append((f"pull-off w = {w:g}: generated / shipped", f"{g:.6g} / {s:.6g}", f"{g / s - 1:+.1e}"))
    rows[3] = (rows[3][0], rows[3][1], f"{worst['leak']:.1e}")
    return rows, worst
