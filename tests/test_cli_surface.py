"""``persson-fp surface``: a height map and a contact.engineering export in, CSV with units and PNG out."""

import json
import os

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import main

DATA = os.path.join(os.path.dirname(__file__), "..", "data", "bem")


def _bem_map(N=128):
    d = np.load(os.path.join(DATA, "surfaces", "surface_H0.8_seed1_modes.npz"))
    A = np.zeros((N, N), complex)
    A[np.ix_(d["k"] % N, d["k"] % N)] = d["hq"]
    return np.real(np.fft.ifft2(A) * N * N)


def _read_csv(path):
    """The plain CSV (no comment lines: any CSV reader takes it) and its metadata from the JSON beside it."""
    lines = open(path).read().splitlines()
    assert not any(ln.startswith("#") for ln in lines)
    rows = [ln.split(",") for ln in lines]
    meta = json.load(open(os.path.join(os.path.dirname(path), "surface.json")))
    header = [*meta["surface"], "units: " + meta["units"], meta["columns"]]
    return header, rows[0], np.array(rows[1:], dtype=float)


def test_surface_command_height_map(tmp_path, capsys):
    h = _bem_map()
    np.save(tmp_path / "h.npy", h)
    rc = main(
        [
            "surface",
            str(tmp_path / "h.npy"),
            "--size",
            "1",
            "--periodic",
            "--n-loads",
            "8",
            "--output",
            str(tmp_path / "o"),
        ]
    )
    out = capsys.readouterr().out
    assert rc == 0
    assert "convention 'persson'" in out and "rms slope" in out
    header, cols, data = _read_csv(tmp_path / "o" / "surface.csv")
    assert any("units:" in ln for ln in header) and any("source: height map" in ln for ln in header)
    # the CSV's numbers are the library's on the imported spectrum (12 printed digits)
    psd = pf.psd_from_heightmap(h, 1.0, periodic=True).psd
    p = data[:, cols.index("p_bar [Pa]")]
    ms = pf.MeanSeparation(psd, 1.0, "YP08")
    np.testing.assert_allclose(data[:, cols.index("u_YP08 [m]")], ms.mean_separation(p), rtol=1e-10)
    np.testing.assert_allclose(data[:, cols.index("K_none [Pa/m]")], pf.MeanSeparation(psd).stiffness(p), rtol=1e-10)
    A = pf.exact(pf.ContactProblem(psd, 1.0, p, "WM17")).contact_area
    np.testing.assert_allclose(data[:, cols.index("A_WM17 [-]")], A, rtol=1e-10)
    assert (tmp_path / "o" / "surface.png").stat().st_size > 1000


def test_surface_command_contact_engineering_csv(tmp_path, capsys):
    psd = pf.SelfAffinePSD.from_rms_slope(0.2, 0.7, 1e5, 4e5, 1e8)  # SI: q in rad/m
    q = np.geomspace(psd.q_l, psd.q_s, 80)
    Y = q * (2 * np.pi) ** 2 * psd.C(q) / np.pi
    path = tmp_path / "psd.csv"
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("Subject type;Subject name;Function name;Data series;Wavevector (m⁻¹);PSD (m³)\n")
        for a, b in zip(q, Y):
            fh.write(f"measurement;x;Power spectrum;q/π × 2D PSD;{float(a)!r};{float(b)!r}\n")
    rc = main(["surface", str(path), "--E-star", "1e9", "--n-loads", "5", "--output", str(tmp_path / "o")])
    out = capsys.readouterr().out
    assert rc == 0
    line = next(ln for ln in out.splitlines() if ln.startswith("rms height"))
    # 6 printed digits; the roll-off kink falls between table points (measured -1.5e-5)
    assert float(line.split("rms slope ")[1].split()[0]) == pytest.approx(0.2, rel=1e-4)


@pytest.mark.parametrize(
    "argv, message",
    [
        (["surface", "missing.npy", "--size", "1"], "no such file"),
        (["surface", "{h}"], "--size"),
        (["surface", "{h}", "--size", "1", "--ratio-min", "2", "--ratio-max", "1"], "ratio"),
        (["surface", "{h}", "--size", "-1"], "size"),
        (["surface", "{h}", "--size", "1", "--n-loads", "1"], "n-loads"),
    ],
)
def test_surface_command_bad_arguments_one_line_exit_2(tmp_path, capsys, argv, message):
    np.save(tmp_path / "h.npy", _bem_map(32))
    argv = [a.replace("{h}", str(tmp_path / "h.npy")) for a in argv] + ["--output", str(tmp_path / "o")]
    rc = main(argv)
    err = capsys.readouterr().err.strip()
    assert rc == 2
    assert len(err.splitlines()) == 1 and message in err and "Traceback" not in err


def test_surface_csv_is_read_by_plain_pandas(tmp_path):
    """The table has no comment lines (its metadata is in surface.json): pandas' default reader gets every column."""
    pd = pytest.importorskip("pandas")
    np.save(tmp_path / "h.npy", _bem_map())
    assert main(["surface", str(tmp_path / "h.npy"), "--size", "1", "--periodic", "--n-loads", "5",
                 "--output", str(tmp_path / "o")]) == 0  # fmt: skip
    df = pd.read_csv(tmp_path / "o" / "surface.csv")
    assert len(df) == 5 and {"p_bar [Pa]", "A_WM17 [-]", "u_YP08 [m]", "K_none [Pa/m]"} <= set(df.columns)
    assert json.load(open(tmp_path / "o" / "surface.json"))["E_star"] > 0


def test_surface_png_has_the_gap_panels(tmp_path):
    """The figure: spectrum, area, load-separation, stiffness, and the gap panels (P(u) with the contact atom as
    arrows carrying its weight, the leak rate against the load with sealed loads ticked); the CLI with --viscosity
    and --pressure-drop writes it."""
    from persson_fp.cli.surface import GAP_MODEL, _figure

    psd = pf.psd_from_heightmap(_bem_map(64), 1.0, periodic=True).psd
    sV = float(np.sqrt(psd.V()))
    ratio = np.geomspace(1e-3, 3.0, 12)
    p = ratio * sV
    problem = pf.ContactProblem(psd, 1.0, p, fudge=GAP_MODEL)
    gd = pf.gap_distribution(problem)
    Q_cj, Q_em = pf.leak_rate(problem, 1.0, 1.0), pf.leak_rate(problem, 1.0, 1.0, method="effective-medium")
    assert Q_cj[-1] == 0 and Q_cj[0] > 0  # both open and sealed loads are drawn
    ms = pf.MeanSeparation(psd, 1.0, GAP_MODEL)
    A = {n: pf.exact(pf.ContactProblem(psd, 1.0, p)).contact_area for n in ("none", "YP08", "WM17", "Xu24")}
    u = {n: ms.mean_separation(p) for n in A}
    K = {n: ms.stiffness(p) for n in A}
    fig = _figure(psd, sV, (p, A, u, K, gd, Q_cj, Q_em), slice(None), "test", "SI", (1.0, (1.0, 1.0)))
    axes = fig.get_axes()
    assert len(axes) == 6
    gap_ax = next(a for a in axes if a.get_title().startswith("gap distribution P(u)"))
    leak_ax = next(a for a in axes if a.get_title().startswith("leak rate"))
    assert "gap u" in gap_ax.get_xlabel() and "P(u)" in gap_ax.get_ylabel()
    assert len(gap_ax.get_lines()) >= 4
    # the atom arrows carry the contact fractions (3 significant digits)
    texts = {t.get_text() for t in gap_ax.texts}
    shown = [k for k in range(gd.n_loads) if f"{gd.contact_fraction[k]:.3g}" in texts]
    assert len(shown) >= 3
    labels = [ln.get_label() for ln in leak_ax.get_lines()]
    assert "critical junction" in labels and "effective medium" in labels
    assert "Q" in leak_ax.get_ylabel() and leak_ax.get_xscale() == leak_ax.get_yscale() == "log"
    np.save(tmp_path / "h.npy", _bem_map(64))
    args = ["surface", str(tmp_path / "h.npy"), "--size", "1", "--periodic", "--n-loads", "6"]
    assert main(args + ["--viscosity", "1e-3", "--pressure-drop", "1e5", "--output", str(tmp_path / "o")]) == 0
    assert (tmp_path / "o" / "surface.png").stat().st_size > 1000


@pytest.mark.parametrize(
    "content, extra, message",
    [
        (b"", [], "2-D array"),
        (b"\x93NUMPYgarbage", [], "cannot read a height map"),
        (bytes(range(256)) * 4, [], "cannot read a height map"),
        (b"1 2 3\n4 5\n", [], "cannot read a height map"),
        (b"1 2\nnan 4\n", [], "finite"),
        (b"Subject type;Subject name;Function name;Data series;Wavevector;PSD\n", [], "usable points"),
        (None, ["--size", "1e300"], "--size 1e+300"),
        (None, ["--size", "1e-300"], "--size 1e-300"),
        (None, ["--E-star", "1e308"], "--E-star"),
        (None, ["--E-star", "1e-308"], "--E-star"),
        (None, ["--ratio-max", "1e6"], "--p-bar-ratio-max 1e+06"),
        (None, ["--viscosity", "nan", "--pressure-drop", "1"], "--viscosity"),
        (None, ["--pressure-drop", "-1", "--viscosity", "1"], "--pressure-drop"),
        (None, ["--viscosity", "1e-308", "--pressure-drop", "1", "--size", "1e-3"], "rescale the units"),
    ],
)
def test_surface_command_fuzzed_files_and_options_are_one_line_errors(tmp_path, capsys, content, extra, message):
    """Found by fuzzing the command: bad files and options give one line on stderr and exit status 2 (no
    traceback, no multi-line warnings, no silently infinite flow rate); huge sizes and moduli name the option."""
    path = tmp_path / ("h.npy" if content is None else "bad.txt")
    if content is None:
        np.save(path, np.random.default_rng(0).standard_normal((32, 32)))
    else:
        path.write_bytes(content)
    # white noise on a unit square has an rms slope of ~34: --trust-units lets the other options' checks speak
    argv = ["surface", str(path), "--n-loads", "4", "--trust-units", "--output", str(tmp_path / "o")]
    argv += extra if "--size" in extra else ["--size", "1", *extra]
    rc = main(argv)
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and message in err and "Traceback" not in err, err
    assert all(ln.startswith(("warning: ", "note: ")) or "Warning" not in ln for ln in captured.out.splitlines())


@pytest.mark.parametrize("size, expect", [("1e-3", "too steep"), ("1e9", "too flat")])
def test_surface_heights_and_size_in_different_units_are_refused(tmp_path, capsys, size, expect):
    """Heights of rms 1 (micrometres) with a size in metres give an rms slope of ~1e4: refused as a unit slip, with
    the slope computed here from the heights' finite differences as the reference of 'too steep'."""
    rng = np.random.default_rng(3)
    h = np.cumsum(np.cumsum(rng.standard_normal((32, 32)), axis=0), axis=1)
    h = (h - h.mean()) / h.std()
    path = tmp_path / "um.npy"
    np.save(path, h)
    L = float(size)
    slope = np.sqrt(np.mean(np.gradient(h, L / 32, axis=0) ** 2 + np.gradient(h, L / 32, axis=1) ** 2))
    assert (slope > 10) == (expect == "too steep") and (slope < 1e-6) == (expect == "too flat")
    rc = main(["surface", str(path), "--size", size, "--output", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 2 and expect in err and "--trust-units" in err and len(err.strip().splitlines()) == 1
    rc = main(
        ["surface", str(path), "--size", size, "--trust-units", "--n-loads", "3", "--output", str(tmp_path / "o")]
    )
    assert rc == 0
