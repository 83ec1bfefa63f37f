"""Speed and accuracy of ``pf.rubber_friction``: mu(v) and A(v) at 300 speeds, and friction maps mu(v, T).

Whole user calls, end to end: ``pf.rubber_friction(psd, material, sigma0, velocity, temperature=...)``, each the
median of ``--repeats`` warm calls after one untimed warm-up; the first call of each case in this process (which
builds the angular tables and imports scipy's interpolation for a master curve) is reported apart.

Materials: a Zener rubber (E_r = 3 MPa, E_g = 3 GPa, tau = 1e-4 s, nu = 0.5) and a tabulated master curve made
here from a 12-element Prony model (10 points per decade, 1e-6 to 1e13 Hz), each with the WLF shift
(C1 = 8.86, C2 = 101.6 K, T_ref = 20 degC) for the maps.  Road: self-affine, rms slope 1, H = 0.8, q from 1e3 to
1e8 1/m (roll-off at 1e4); sigma0 = 0.2 MPa.

Accuracy: the largest relative error estimate (``mu_error / mu``, ``contact_area_error / contact_area``) over the
speeds, and the largest true relative error against the same integrals with every rule refined fourfold.

Output: friction_speed.csv and friction_speed.md.

    python benchmarks/friction_speed.py [--quick] [--repeats 7]
"""

from __future__ import annotations

import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import machine, markdown_table, median_time, outdir, parser, write_csv  # noqa: E402

import persson_fp as pf  # noqa: E402
from persson_fp.analysis import friction as _friction  # noqa: E402
from persson_fp.theory import fudge as _fudge  # noqa: E402


def prony_compound(**kw):
    """A generalised Maxwell rubber defined for this benchmark (12 elements, 1e-9..1e2 s)."""
    tau = np.logspace(-9, 2, 12)
    E_i = 4e7 * np.exp(-0.5 * ((np.log10(tau) + 4.0) / 2.5) ** 2)
    return pf.viscoelastic.Prony(2e6, E_i, tau, **kw)


def materials(shift: bool):
    wlf = dict(T_ref=20.0, shift=pf.viscoelastic.WLF(8.86, 101.6)) if shift else {}
    zener = pf.viscoelastic.Zener(3e6, 3e9, 1e-4, **wlf)
    f = np.logspace(-6, 13, 191)
    E = prony_compound().modulus(2 * np.pi * f)
    curve = pf.viscoelastic.MasterCurve(f, E.real, E.imag, frequency_unit="Hz", **wlf)
    return {"Zener": zener, "master curve": curve}


def true_error(psd, material, sigma0, v, res, aT=None):
    """Largest relative error of mu and A against every rule refined fourfold."""
    vb = np.ravel(np.broadcast_to(v, res.mu.shape))
    aT = np.ones(vb.size) if aT is None else np.ravel(aT)
    mu, A, *_ = _friction._pass(psd, material, sigma0, vb, aT, np.ones(vb.size), psd.q_s, _fudge.resolve("YP08"),
                                True, None, 4)  # fmt: skip
    return float(np.max(np.abs(res.mu.ravel() - mu) / mu)), float(np.max(np.abs(res.contact_area.ravel() - A) / A))


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    repeats = args.repeats or (2 if args.quick else 7)
    n_v, n_map_v, n_map_T = (30, 10, 4) if args.quick else (300, 50, 20)
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, H=0.8, q_l=1e3, q_r=1e4, q_s=1e8)
    sigma0 = 2e5
    rows = []
    for name, mat in materials(shift=False).items():
        v = np.logspace(-8, 1, n_v)
        t0 = time.perf_counter()
        pf.rubber_friction(psd, mat, sigma0, v)
        first = time.perf_counter() - t0
        t, res = median_time(lambda: pf.rubber_friction(psd, mat, sigma0, v), repeats)
        e_mu, e_A = true_error(psd, mat, sigma0, v, res)
        rows.append(dict(case=f"mu(v), A(v): {n_v} speeds", material=name, calls=n_v, first_call_s=first,
                         median_s=t, max_est_rel_mu=float(np.max(res.mu_error / res.mu)),
                         max_est_rel_A=float(np.max(res.contact_area_error / res.contact_area)),
                         max_true_rel_mu=e_mu, max_true_rel_A=e_A))  # fmt: skip
    for name, mat in materials(shift=True).items():
        v = np.logspace(-8, 1, n_map_v)
        T = np.linspace(-20.0, 100.0, n_map_T)[:, None]
        t0 = time.perf_counter()
        pf.rubber_friction(psd, mat, sigma0, v, temperature=T)
        first = time.perf_counter() - t0
        t, res = median_time(lambda: pf.rubber_friction(psd, mat, sigma0, v, temperature=T), repeats)
        aT = np.broadcast_to(10.0 ** mat.log10_aT(T), res.mu.shape)
        e_mu, e_A = true_error(psd, mat, sigma0, np.broadcast_to(v, res.mu.shape), res, aT)
        rows.append(dict(case=f"map mu(v, T): {n_map_v} x {n_map_T}", material=name, calls=n_map_v * n_map_T,
                         first_call_s=first, median_s=t, max_est_rel_mu=float(np.max(res.mu_error / res.mu)),
                         max_est_rel_A=float(np.max(res.contact_area_error / res.contact_area)),
                         max_true_rel_mu=e_mu, max_true_rel_A=e_A))  # fmt: skip
    out = outdir(args)
    write_csv(os.path.join(out, "friction_speed.csv"), rows)
    header = ["case", "material", "first call [s]", "warm median [s]", "max est. rel. err mu / A",
              "max true rel. err mu / A"]  # fmt: skip
    cells = [
        [r["case"], r["material"], f"{r['first_call_s']:.3f}", f"{r['median_s']:.3f}",
         f"{r['max_est_rel_mu']:.1e} / {r['max_est_rel_A']:.1e}",
         f"{r['max_true_rel_mu']:.1e} / {r['max_true_rel_A']:.1e}"]
        for r in rows
    ]  # fmt: skip
    table = markdown_table(header, cells)
    text = (
        "# Rubber friction: speed and accuracy\n\n"
        f"`python benchmarks/friction_speed.py{' --quick' if args.quick else ''}` ({machine()}; medians of "
        f"{repeats} warm calls, the first call apart). True errors: against every quadrature refined fourfold.\n\n"
        + table
        + "\n"
    )
    with open(os.path.join(out, "friction_speed.md"), "w") as fh:
        fh.write(text)
    print(text)
    return rows


if __name__ == "__main__":
    main()
