"""``persson-fp sweep``: a folder of CSV spectra into one table, equal to pf.exact per surface and model."""

import numpy as np
import pytest
from scipy.special import erf

import persson_fp as pf
from persson_fp.cli.app import main


def _write_surfaces(folder):
    for H in (0.3, 0.8):
        psd = pf.SelfAffinePSD.from_rms_slope(0.1, H, 1.0, 2.0, 100.0)
        q = np.geomspace(1.0, 100.0, 50)
        rows = "".join(f"{float(a)!r},{float(c)!r}\n" for a, c in zip(q, psd.C(q)))
        (folder / f"H{H}.csv").write_text("q,C\n" + rows)


def test_sweep_command_writes_the_table_pf_exact_gives(tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    _write_surfaces(tmp_path)
    out = tmp_path / "out" / "table.csv"
    rc = main(
        [
            "sweep",
            str(tmp_path),
            "--n-loads",
            "7",
            "--quantities",
            "contact_area",
            "variance",
            "--output",
            str(out),
            "--no-progress",
        ]
    )
    assert rc == 0
    assert "2 surfaces x 4 models x 7 loads" in capsys.readouterr().out
    df = pf.read_sweep_table(out)
    assert isinstance(df, pd.DataFrame) and len(df) == 2 * 4 * 2 * 7
    assert set(df["model"]) == {"none", "YP08", "WM17", "Xu24"}
    ratio = np.geomspace(1e-3, 3.0, 7)
    for name in ("H0.3", "H0.8"):
        psd = pf.TabulatedPSD.from_csv(tmp_path / f"{name}.csv")
        for model in ("none", "Xu24"):
            pr = pf.ContactProblem(psd, 1.0, ratio * np.sqrt(psd.V()), None if model == "none" else model)
            rows = df[(df["surface"] == name) & (df["model"] == model)]
            np.testing.assert_array_equal(rows[rows["quantity"] == "variance"]["value"], pf.exact(pr).variance)
    # without a fudge factor the relative loads give erf(r / sqrt 2) on every surface (eq:Area_Persson)
    a = df[(df["model"] == "none") & (df["quantity"] == "contact_area")]
    np.testing.assert_allclose(a["value"], np.tile(erf(ratio / np.sqrt(2)), 2), rtol=1e-14)
    assert df.attrs["units"]["variance"] == "pressure^2"


def test_sweep_command_absolute_loads_and_workers(tmp_path):
    _write_surfaces(tmp_path)
    out = tmp_path / "t.csv"
    rc = main(
        [
            "sweep",
            str(tmp_path / "H0.3.csv"),
            "--p-bar",
            "0.001",
            "0.01",
            "--models",
            "none",
            "--workers",
            "2",
            "--output",
            str(out),
            "--no-progress",
        ]
    )
    assert rc == 0
    lines = out.read_text().splitlines()
    assert lines[0].startswith("surface,") and len(lines) == 1 + 2  # plain CSV, the metadata in t.csv.json
    assert (tmp_path / "t.csv.json").is_file()


@pytest.mark.parametrize(
    "argv, msg",
    [
        (["--output", "x.txt"], "--output must end in .csv or .parquet"),
        (["--workers", "0"], "--workers must be >= 1"),
        (["--ratio-min", "2", "--ratio-max", "1"], "--ratio-min and --ratio-max"),
        (["--quantities", "nope"], "unknown name 'nope'"),
        (["--models", "YP09"], "invalid choice: 'YP09'"),
    ],
)
def test_sweep_command_bad_arguments_exit_2(tmp_path, capsys, argv, msg):
    _write_surfaces(tmp_path)
    try:
        rc = main(["sweep", str(tmp_path), "--no-progress", *argv])
    except SystemExit as e:  # argparse's own refusals (an unknown model name)
        rc = e.code
    assert rc == 2 and msg in capsys.readouterr().err


def test_sweep_command_missing_path(tmp_path, capsys):
    rc = main(["sweep", str(tmp_path / "nothing"), "--output", str(tmp_path / "t.csv")])
    assert rc == 2 and "no such file or folder" in capsys.readouterr().err
