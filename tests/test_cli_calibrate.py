"""``persson-fp calibrate``: the command gives the numbers pf.calibrate gives, writes its files, names bad data."""

import csv
import json

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import main

LOADS = np.array([0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5]) * 0.1


def _write(folder, gammas=(0.5, 0.5)):
    """Two spectra (H = 0.8, 0.3) and one data table with a 'surface' column: Xu24 areas with 1 % noise."""
    rng = np.random.default_rng(3)
    rows = ["surface,p_bar,contact_area"]
    psds = {}
    for H, g in zip((0.8, 0.3), gammas):
        psd = pf.SelfAffinePSD.from_rms_slope(0.1, H, 2 * np.pi, 8 * np.pi, 128 * np.pi)
        q = np.geomspace(2 * np.pi, 128 * np.pi, 80)
        name = f"H{H}"
        (folder / f"{name}.csv").write_text(
            "q,C\n" + "".join(f"{a!r},{c!r}\n" for a, c in zip(map(float, q), map(float, psd.C(q))))
        )
        psds[name] = pf.TabulatedPSD(q, psd.C(q))
        A = pf.exact(pf.ContactProblem(psds[name], 1.0, LOADS, pf.fudge.Xu24(g))).contact_area
        A = A * (1 + 0.01 * rng.standard_normal(A.size))
        rows += [f"{name},{float(p)!r},{float(a)!r}" for p, a in zip(LOADS, A)]
    (folder / "data.csv").write_text("\n".join(rows) + "\n")
    return psds


def test_calibrate_command_matches_api(tmp_path, capsys):
    psds = _write(tmp_path)
    out, js, png = tmp_path / "r.csv", tmp_path / "f.json", tmp_path / "f.png"
    argv = ["calibrate", str(tmp_path / "data.csv"), "--psd", str(tmp_path / "H0.8.csv"), str(tmp_path / "H0.3.csv"),
            "--model", "Xu24", "--output", str(out), "--json", str(js), "--plot", str(png)]  # fmt: skip
    assert main(argv) == 0
    text = capsys.readouterr().out
    ref = pf.calibrate(psds, tmp_path / "data.csv", model="Xu24")
    record = json.loads(js.read_text())
    assert record["params"]["gamma"] == pytest.approx(ref.params["gamma"], rel=1e-9)
    assert record["std"]["gamma"] == pytest.approx(ref.uncertainty["gamma"], rel=1e-6)
    assert f"gamma = {ref.params['gamma']:.4g}" in text
    with open(out, newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == 14 and {r["surface"] for r in rows} == {"H0.8", "H0.3"}
    assert png.stat().st_size > 1000
    assert main(argv) == 2  # files exist: --force needed
    assert "--force" in capsys.readouterr().err


def test_calibrate_command_ranks_models(tmp_path, capsys):
    _write(tmp_path)
    argv = ["calibrate", str(tmp_path / "data.csv"), "--psd", str(tmp_path / "H0.8.csv"), str(tmp_path / "H0.3.csv"),
            "--model", "YP08", "Xu24", "--criterion", "bic"]  # fmt: skip
    assert main(argv) == 0
    text = capsys.readouterr().out
    assert "ranked by BIC" in text and "best: Xu24" in text


def test_calibrate_command_bad_data(tmp_path, capsys):
    _write(tmp_path)
    bad = tmp_path / "bad.csv"
    bad.write_text("p_bar,contact_area\n0.001,0.02\n-0.002,0.04\n0.003,0.05\n")
    assert main(["calibrate", str(bad), "--psd", str(tmp_path / "H0.8.csv")]) == 2
    err = capsys.readouterr().err
    assert "column 'p_bar', row 1 (line 3 of" in err and len(err.strip().splitlines()) == 1
    assert main(["calibrate", str(tmp_path / "nope.csv"), "--psd", str(tmp_path / "H0.8.csv")]) == 2
    assert "no such file" in capsys.readouterr().err
