"""The command line as a tribologist meets it: loads in Pa, units in every header and axis, plausibility warnings
on one line each, leak rates only for a stated fluid, outputs never replaced silently, names in any letter case.

Oracles written here: Persson's contact area of the fudge-free theory, A* = erf(p_bar / sqrt(2 V)) with
V = E*^2 <|grad h|^2> / 4 (Xu et al. tutorial, eq:Area_Persson), from the rms slope the spectrum was built with.
"""

from __future__ import annotations

import csv
import math
import re

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import build_parser, main

SLOPE, E_STAR = 0.2, 2.1e11


def _ce_csv(path, slope=SLOPE):
    """A contact.engineering export of a self-affine spectrum in SI (q in rad/m), rms slope ``slope``."""
    psd = pf.SelfAffinePSD.from_rms_slope(slope, 0.7, 1e5, 4e5, 1e8)
    q = np.geomspace(psd.q_l, psd.q_s, 200)
    Y = q * (2 * np.pi) ** 2 * psd.C(q) / np.pi
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("Subject type;Subject name;Function name;Data series;Wavevector (m⁻¹);PSD (m³)\n")
        for a, b in zip(q, Y):
            fh.write(f"measurement;x;Power spectrum;q/π × 2D PSD;{float(a)!r};{float(b)!r}\n")
    return path


@pytest.fixture()
def no_figure(monkeypatch):
    """The surface figure replaced by an empty one where a test reads only the tables and messages (the figure costs
    about half of a run; test_surface_figure_axes_say_m_and_pa looks at it)."""
    import matplotlib.pyplot as plt

    import persson_fp.cli.surface as surface

    monkeypatch.setattr(surface, "_figure", lambda *a, **k: plt.figure(figsize=(1, 1)))


def _table(path):
    rows = list(csv.reader(open(path)))
    return rows[0], np.array(rows[1:], dtype=float)


def _rc(argv):
    try:
        return main(argv)
    except SystemExit as e:  # argparse's own refusals
        return e.code


def _errors(err):
    return [ln for ln in err.strip().splitlines() if ln]


def test_surface_p_bar_in_pascal_units_in_headers_and_the_closed_form(tmp_path, capsys, no_figure):
    """--p-bar in Pa: A*_none = erf(p_bar / sqrt(2V)), V = (E* s / 2)^2; every header carries its SI unit, SI is said
    once; without --viscosity / --pressure-drop there are no leak-rate columns."""
    src = _ce_csv(tmp_path / "psd.csv")
    loads = [1e5, 1e7, 3e9]
    assert main(["surface", str(src), "--E-star", f"{E_STAR:g}", "--p-bar", *map(str, loads), "--output",
                 str(tmp_path / "o")]) == 0  # fmt: skip
    out = capsys.readouterr().out
    assert sum("SI assumed" in ln for ln in out.splitlines()) == 1
    header, data = _table(tmp_path / "o" / "surface.csv")
    units = dict(h.rsplit(" [", 1) for h in header)
    assert units["p_bar"] == "Pa]" and units["A_YP08"] == "-]" and units["u_YP08"] == "m]"
    assert units["K_YP08"] == "Pa/m]" and units["gap_mean_WM17"] == "m]" and units["C_rho_none"] == "1/m]"
    assert not any(h.startswith("Q_") for h in header)
    np.testing.assert_allclose(data[:, 0], loads, rtol=1e-12)
    V = (E_STAR * SLOPE / 2) ** 2
    A = [math.erf(p / math.sqrt(2 * V)) for p in loads]
    # the tabulated spectrum's rms slope is 0.2 to ~2e-5 (the roll-off kink between table points): A* to ~1e-4
    np.testing.assert_allclose(data[:, header.index("A_none [-]")], A, rtol=2e-4)
    # the printed table carries the same numbers (6 digits)
    line = next(ln for ln in out.splitlines()[out.splitlines().index("p_bar = 100000 Pa (p_bar/sqrt(V) = 4.762e-06):"):]
                if ln.startswith("none "))  # fmt: skip
    assert float(line.split()[1]) == pytest.approx(A[0], rel=2e-4)


def test_surface_units_none_and_ranges(tmp_path, capsys, no_figure):
    """--units none names the dimensions; --p-bar-min/--p-bar-max is a log-spaced range of --n-loads pressures;
    an explicit --units says nothing about units on stdout."""
    src = _ce_csv(tmp_path / "psd.csv")
    argv = ["surface", str(src), "--units", "NONE", "--E-star", "1e9", "--p-bar-min", "1e4", "--p-bar-max", "1e6"]
    assert main(argv + ["--n-loads", "3", "--output", str(tmp_path / "o")]) == 0
    assert "SI assumed" not in capsys.readouterr().out
    header, data = _table(tmp_path / "o" / "surface.csv")
    assert header[:2] == ["p_bar [pressure]", "p_bar_over_sqrtV [-]"]
    assert "u_WM17 [length]" in header and "K_Xu24 [pressure/length]" in header
    np.testing.assert_allclose(data[:, 0], [1e4, 1e5, 1e6], rtol=1e-12)


def test_surface_figure_axes_say_m_and_pa(tmp_path):
    """Every axis of the surface figure names its SI unit; the leak panel without a fluid is Q eta / dp in m^3."""
    from persson_fp.cli.surface import _figure

    model = pf.SelfAffinePSD.from_rms_slope(SLOPE, 0.7, 1e5, 4e5, 1e8)
    q = np.geomspace(1e5, 1e8, 60)
    psd = pf.TabulatedPSD(q, model.C(q))
    sV = E_STAR * SLOPE / 2
    p = sV * np.geomspace(1e-3, 3, 12)
    pr = pf.ContactProblem(psd, E_STAR, p, "WM17")
    ms = pf.MeanSeparation(psd, E_STAR, "WM17")
    models = ("none", "YP08", "WM17", "Xu24")
    A = {n: pf.exact(pr).contact_area for n in models}
    u, K = {n: ms.mean_separation(p) for n in models}, {n: ms.stiffness(p) for n in models}
    Q = pf.leak_rate(pr, 1.0, 1.0)
    fig = _figure(psd, sV, (p, A, u, K, pf.gap_distribution(pr), Q, Q), np.array([3, 6]), "t", "SI", None)
    labels = [t for ax in fig.axes for t in (ax.get_xlabel(), ax.get_ylabel())]
    assert not any("[length]" in t or "[pressure]" in t for t in labels)
    assert all("[" in t for t in labels), labels
    assert sum("[Pa]" in t for t in labels) == 3 and sum("[m]" in t for t in labels) == 2  # p_bar axes; u, gap u
    leak = fig.axes[5]
    assert "eta" in leak.get_ylabel() and "m$^3$" in leak.get_ylabel() and "per unit" in leak.get_title()
    legend = [t.get_text() for t in fig.axes[2].get_legend().get_texts()]
    assert legend and all(re.match(r"p̄ = [\d.e+-]+ Pa: contact atom A = [\d.]+$", t) for t in legend), legend
    import matplotlib.pyplot as plt

    plt.close(fig)


def test_leak_columns_need_both_viscosity_and_pressure_drop(tmp_path, capsys, no_figure):
    """Both given: Q columns in m^3/s equal to pf.leak_rate with that fluid; one of them alone: one-line error."""
    src = _ce_csv(tmp_path / "psd.csv")
    base = ["surface", str(src), "--E-star", "1e9", "--p-bar", "1e6", "3e6"]
    assert main(base + ["--viscosity", "2e-3", "--pressure-drop", "3e5", "--output", str(tmp_path / "o")]) == 0
    header, data = _table(tmp_path / "o" / "surface.csv")
    psd = pf.read_contact_engineering_csv(str(src)).psd
    pr = pf.ContactProblem(psd, 1e9, data[:, 0], "YP08")
    Q = pf.leak_rate(pr, viscosity=2e-3, pressure_drop=3e5, method="effective-medium")
    assert Q.min() > 0
    np.testing.assert_allclose(data[:, header.index("Q_em_YP08 [m^3/s]")], Q, rtol=1e-10)
    capsys.readouterr()
    assert main(base + ["--viscosity", "1e-3", "--output", str(tmp_path / "p")]) == 2
    err = _errors(capsys.readouterr().err)
    assert len(err) == 1 and "--pressure-drop" in err[0] and not (tmp_path / "p" / "surface.csv").exists()


@pytest.mark.parametrize("command", ["surface", "report", "area"])
def test_folder_writers_refuse_existing_outputs_without_force(tmp_path, capsys, no_figure, command):
    """An output that exists: exit 2, one line naming --force, the file untouched; --force replaces it."""
    first = {"surface": "surface.csv", "report": "pdf_exact.png", "area": "contact_area.csv"}[command]
    argv = {
        "surface": ["surface", str(_ce_csv(tmp_path / "psd.csv")), "--E-star", "1e9", "--p-bar", "1e6"],
        "report": ["report", "--no-solvers"],
        "area": ["area", "--n-loads", "3"],
    }[command] + ["--output", str(tmp_path / "o")]
    (tmp_path / "o").mkdir()
    (tmp_path / "o" / first).write_bytes(b"keep me")
    assert main(argv) == 2
    err = _errors(capsys.readouterr().err)
    assert len(err) == 1 and "--force" in err[0] and first in err[0]
    assert (tmp_path / "o" / first).read_bytes() == b"keep me"
    assert main(argv + ["--force"]) == 0
    assert (tmp_path / "o" / first).read_bytes() != b"keep me"


@pytest.mark.parametrize(
    "argv, flag",
    [
        (["surface", "{ce}", "--viscosity", "-1e-3", "--pressure-drop", "1e5"], "--viscosity"),
        (["surface", "{ce}", "--p-bar", "-2e5"], "--p-bar"),
        (["solve", "--p-bar", "-2e5"], "--p-bar"),
        (["report", "--no-solvers", "--E-star", "-1e-3"], "--E-star"),
        (["area", "--ratio-min", "-1e-3"], "--ratio-min"),
        (["friction", "--zener", "3e6", "3e9", "1e-4", "--psd", "{psd}", "--p-bar", "-2e5"], "--p-bar"),
        (["sweep", "{psd}", "--p-bar", "-1e5", "--output", "{t}/s.csv"], "--p-bar"),
        (["sweep", "{psd}", "--E-star", "-1e9", "--output", "{t}/s.csv"], "--E-star"),
    ],
)
def test_negative_numbers_are_values_refused_with_their_range(tmp_path, capsys, argv, flag):
    """'-1e-3' is a value (not an unknown option): the refusal names the option and its range (> 0)."""
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1e3, 2e3, 1e6)
    q = np.geomspace(1e3, 1e6, 40)
    np.savetxt(tmp_path / "p.csv", np.c_[q, psd.C(q)], delimiter=",", header="q,C", comments="")
    subs = {"{ce}": str(_ce_csv(tmp_path / "ce.csv")), "{psd}": str(tmp_path / "p.csv"), "{t}": str(tmp_path)}
    argv = [subs.get(a, a.replace("{t}", str(tmp_path))) for a in argv]
    if argv[0] in ("surface", "report", "area", "friction"):
        argv += ["--output", str(tmp_path / "o")]
    rc = _rc(argv)
    err = _errors(capsys.readouterr().err)
    assert rc == 2 and len(err) == 1, err
    assert flag in err[0] and "expected one argument" not in err[0], err[0]
    assert "> 0" in err[0] or "0 < min" in err[0], err[0]  # the allowed range


def test_warnings_print_once_as_one_line(capsys):
    """The unit slip p_bar >= E*: one line 'persson-fp: warning: ...' naming both options (no file, no source line,
    not repeated by the solver, the comparison and the exact solution that all meet it)."""
    assert main(["solve", "--E-star", "1e7", "--p-bar", "2e7", "--method", "sines"]) == 0
    err = _errors(capsys.readouterr().err)
    assert len(err) == 1, err
    assert err[0].startswith("persson-fp: warning: --p-bar 2e+07 Pa >= --E-star 1e+07 Pa")
    assert ".py" not in err[0] and "UserWarning" not in err[0]


@pytest.mark.parametrize("p_bar, warned", [("1e5", True), ("9.9e4", False)])
def test_load_at_the_modulus_is_warned(capsys, p_bar, warned):
    """p_bar >= E* (equality included) warns; just below, nothing (the reference surface, rms slope 0.1, is in full
    contact at either load: only the unit slip is worth a line)."""
    assert main(["solve", "--E-star", "1e5", "--p-bar", p_bar, "--method", "sines"]) == 0
    err = _errors(capsys.readouterr().err)
    assert any(">= --E-star" in ln for ln in err) == warned
    assert all(ln.startswith("persson-fp: warning: ") for ln in err) and len(err) <= 1


@pytest.mark.parametrize("target, warned", [(7.0, "larger"), (3e-5, "smaller"), (0.3, None)])
def test_rms_slope_outside_the_usual_band_is_one_warning(tmp_path, capsys, no_figure, target, warned):
    """A height map accepted (rms slope within 1e-6..10) but unusual (above 5 or below 1e-4): the run goes on with
    one warning naming the likely unit mix-up; a usual slope says nothing.  The slope is computed here from the
    heights' finite differences."""
    rng = np.random.default_rng(3)
    h = np.cumsum(np.cumsum(rng.standard_normal((32, 32)), axis=0), axis=1)
    L = 1e-3
    slope = np.sqrt(np.mean(np.gradient(h, L / 32, axis=0) ** 2 + np.gradient(h, L / 32, axis=1) ** 2))
    np.save(tmp_path / "h.npy", h * target / slope)
    rc = main(["surface", str(tmp_path / "h.npy"), "--size", str(L), "--E-star", "1e9", "--p-bar-ratio", "0.1",
               "--output", str(tmp_path / "o")])  # fmt: skip
    err = [ln for ln in _errors(capsys.readouterr().err) if "rms slope of" in ln]
    assert rc == 0
    if warned is None:
        assert err == []
    else:
        assert len(err) == 1 and err[0].startswith("persson-fp: warning: ") and warned in err[0] and "units" in err[0]


@pytest.mark.parametrize(
    "argv, attr, value",
    [
        (["solve", "--fudge", "yp08", "--method", "FV"], ("fudge", "method"), ("YP08", "fv")),
        (["report", "--fudge", "wm17", "--units", "si"], ("fudge", "units"), ("WM17", "SI")),
        (["calibrate", "d.csv", "--psd", "p.csv", "--model", "xu24", "wm17"], ("model",), (["Xu24", "WM17"],)),
        (["calibrate", "d.csv", "--psd", "p.csv", "--fudge", "YP08"], ("model",), (["YP08"],)),
        (["sweep", "s", "--models", "NONE", "xu24"], ("models",), (["none", "Xu24"],)),
        (["sweep", "s", "--fudge", "wm17", "--p-bar-ratio", "0.5"], ("models", "p_bar_ratio"), (["WM17"], [0.5])),
        (["friction", "--zener", "1", "2", "3", "--p-bar", "1", "--fudge", "xu24"], ("fudge",), ("Xu24",)),
        (["surface", "f", "--weighting", "Corrected-Area", "--ratio-min", "0.01"], ("weighting", "ratio_min"),
         ("corrected-area", 0.01)),
        (["solve", "--psd", "x.csv"], ("psd_csv",), ("x.csv",)),
    ],
)  # fmt: skip
def test_names_in_any_case_and_the_shared_option_names(argv, attr, value):
    """Model and method names in any letter case, read as their canonical spelling; the shared option names
    (--psd, --fudge, --p-bar-ratio) beside the old spellings (--psd-csv, --model(s), --ratio-min)."""
    args = build_parser().parse_args(argv)
    assert tuple(getattr(args, a) for a in attr) == value


def test_unknown_model_name_lists_the_choices(capsys):
    assert _rc(["solve", "--fudge", "yp09"]) == 2
    err = _errors(capsys.readouterr().err)
    assert len(err) == 1 and "YP08" in err[0] and "'yp09'" in err[0]


def test_report_times_are_warm_medians_with_the_first_call_apart(tmp_path, capsys, monkeypatch):
    """solvers.csv: the time unit in the header and the screen's unit (ms, the same numbers); the first call apart."""
    import persson_fp.solvers as solvers

    monkeypatch.setattr(solvers, "available_methods", lambda: ["sines"])
    assert main(["report", "--output", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    header, data = None, None
    rows = list(csv.reader(open(tmp_path / "solvers.csv")))
    header, data = rows[0], rows[1]
    assert header[:4] == ["method", "wall [ms]", "first call [ms]", "warm calls"]
    assert data[0] == "sines" and 1 <= int(data[3]) <= 5
    line = next(ln for ln in out.splitlines() if ln.startswith("sines "))
    wall_screen, first_screen = float(line.split()[3]), float(line.split()[4])
    assert wall_screen == pytest.approx(float(data[1]), rel=5e-3)  # 3 significant digits on the screen
    assert first_screen == pytest.approx(float(data[2]), rel=5e-3)
    assert "median of" in out and "warm calls" in out


def test_the_dimensionless_reference_problem_is_not_labelled_si(tmp_path, capsys):
    """Without a length or a pressure among the options (and E* = 1) the run is the reference problem: no SI units on
    it; one physical value makes it SI, said once."""
    assert main(["area", "--n-loads", "5", "--output", str(tmp_path / "a")]) == 0
    out = capsys.readouterr().out
    assert out.count("units: none (the dimensionless reference problem") == 1 and "[Pa]" not in out
    header = (tmp_path / "a" / "contact_area.csv").read_text(encoding="utf8").splitlines()
    assert any(line.startswith("p_bar [pressure]") for line in header)
    assert main(["area", "--n-loads", "5", "--E-star", "2e11", "--output", str(tmp_path / "b")]) == 0
    out = capsys.readouterr().out
    assert out.count("units: SI assumed") == 1


def test_a_negative_poisson_ratio_is_refused_by_its_flag_with_its_range(capsys):
    rc = main(["friction", "--zener", "3e6", "3e9", "1e-4", "--nu", "-0.5", "--psd", "x.csv", "--p-bar", "2e5"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "--nu" in err[0] and "[0, 0.5]" in err[0] and "-0.5" in err[0]
