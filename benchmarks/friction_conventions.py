"""What each convention of rubber-friction programs does to mu and A/A0, on one example.

The example (made here, no outside data): a 12-element Prony rubber (E_r = 2 MPa, relaxation times 1e-9..1e2 s),
tabulated as a master curve in Hz at 20 degC with the WLF shift (C1 = 8.86, C2 = 101.6 K), nu = 0.5, on a
self-affine road (rms slope 1, H = 0.8, q from 1e3 to 1e8 1/m, roll-off at 1e4), sigma0 = 0.2 MPa, v = 1 cm/s,
T = 20 degC, fudge YP08.  Each row changes one convention from this baseline and reports mu and A/A0 and their
change in per cent.

Output: friction_conventions.csv and friction_conventions.md.

    python benchmarks/friction_conventions.py
"""

from __future__ import annotations

import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from _common import markdown_table, outdir, parser, write_csv  # noqa: E402

import persson_fp as pf  # noqa: E402

SIGMA0, VELOCITY, TEMPERATURE = 2e5, 1e-2, 20.0


def compound():
    """The example rubber: a Prony model (the same as notebook 14's)."""
    tau = np.logspace(-9, 2, 12)
    E_i = 4e7 * np.exp(-0.5 * ((np.log10(tau) + 4.0) / 2.5) ** 2)
    return pf.viscoelastic.Prony(2e6, E_i, tau)


def master_curve(frequency_unit="Hz", **kw):
    """The example rubber tabulated at 10 points per decade, 1e-6 to 1e13 Hz (as a DMA master curve)."""
    f = np.logspace(-6, 13, 191)
    E = compound().modulus(2 * np.pi * f)
    kw.setdefault("T_ref", 20.0)
    kw.setdefault("shift", pf.viscoelastic.WLF(8.86, 101.6))
    return pf.viscoelastic.MasterCurve(f, E.real, E.imag, frequency_unit=frequency_unit, **kw)


def road():
    return pf.SelfAffinePSD.from_rms_slope(1.0, H=0.8, q_l=1e3, q_r=1e4, q_s=1e8)


def rows():
    """(label, mu, A) for the baseline and each change of convention."""
    psd = road()
    mc = master_curve()
    soft = pf.viscoelastic.StrainSoftening([1e-3, 1e-2, 0.1, 1.0], [1.0, 0.8, 0.5, 0.35], [1.0, 0.9, 0.7, 0.6])
    q = np.geomspace(psd.q_l, psd.q_s, 400)
    iso = pf.TabulatedPSD(q, psd.C(q) * (2 * np.pi) ** 2)  # an iso2d table read as if it were Persson's C

    def run(label, psd=psd, material=mc, T=TEMPERATURE, **kw):
        r = pf.rubber_friction(psd, material, SIGMA0, VELOCITY, temperature=T, **kw)
        return label, float(r.mu), float(r.contact_area)

    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the Hz curve read as rad/s misses the highest frequencies: the point
        out = [
            run("baseline: reduced E/(1-nu^2) in G, Hz, WLF, q1 = q_s, YP08"),
            run('modulus_in_G="plain" (E in G)', modulus_in_G="plain"),
            run("the Hz curve read as rad/s", material=master_curve("rad/s")),
            run("T = 40 degC (WLF shift)", T=40.0),
            run('T = 40 degC with vertical="kelvin"', material=master_curve(vertical="kelvin"), T=40.0),
            run("an iso2d spectrum read as Persson's C", psd=iso),
            run("q1 = q_s / 10", q1=psd.q_s / 10),
            run("q1 = q_s / 100", q1=psd.q_s / 100),
            run("fudge=None (S = 1)", fudge=None),
            run("strain softening (Payne effect)", strain_softening=soft),
        ]
    return out


def main(argv=None):
    args = parser(__doc__.splitlines()[0]).parse_args(argv)
    data = rows()
    mu0, A0 = data[0][1], data[0][2]
    table = [
        dict(convention=lab, mu=mu, contact_area=A, mu_change_pct=100 * (mu / mu0 - 1),
             area_change_pct=100 * (A / A0 - 1))
        for lab, mu, A in data
    ]  # fmt: skip
    out = outdir(args)
    write_csv(os.path.join(out, "friction_conventions.csv"), table)
    md = markdown_table(
        ["convention", "mu", "A/A0", "mu change", "A/A0 change"],
        [[r["convention"], f"{r['mu']:.4g}", f"{r['contact_area']:.4g}", f"{r['mu_change_pct']:+.1f} %",
          f"{r['area_change_pct']:+.1f} %"] for r in table],
    )  # fmt: skip
    text = "# Rubber friction: what each convention does\n\n`python benchmarks/friction_conventions.py`\n\n" + md + "\n"
    with open(os.path.join(out, "friction_conventions.md"), "w") as fh:
        fh.write(text)
    print(text)
    return table


if __name__ == "__main__":
    main()
