"""The persson-fp command, through its entry point and as a subprocess."""

import csv
import subprocess
import sys

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import main


def test_report_default_case(tmp_path, capsys):
    rc = main(["report", "--output", str(tmp_path), "--no-solvers"])
    out = capsys.readouterr().out
    assert rc == 0
    assert (tmp_path / "pdf_exact.png").stat().st_size > 1000
    # the printed A* of every fudge model equals pf.exact on the reference problem
    for name in ("none", "YP08", "WM17", "Xu24"):
        line = next(ln for ln in out.splitlines() if ln.startswith(name + " "))
        A_printed = float(line.split()[3])
        A = pf.exact(pf.ContactProblem.reference(fudge=None if name == "none" else name)).contact_area
        assert A_printed == pytest.approx(A, abs=1e-8)


def test_default_command_is_report_and_runs_as_a_program(tmp_path):
    r = subprocess.run(
        [sys.executable, "-m", "persson_fp.cli", "--output", str(tmp_path / "o"), "--no-solvers"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 0, r.stderr
    assert "Exact solution at zeta_max" in r.stdout


def test_area_command_csv_matches_exact(tmp_path):
    rc = main(["area", "--n-loads", "50", "--output", str(tmp_path), "--H", "0.3"])
    assert rc == 0
    rows = list(csv.DictReader(open(tmp_path / "contact_area.csv")))
    assert len(rows) == 50
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.3, 1.0, 2.0, 128.0)
    p_bar = np.array([float(r["p_bar [pressure]"]) for r in rows])  # the dimensionless reference: no unit
    for name in ("none", "YP08"):
        A = pf.exact(pf.ContactProblem(psd, 1.0, p_bar, None if name == "none" else name)).contact_area
        np.testing.assert_allclose(
            [float(r[f"A_{name} [-]"]) for r in rows], A, rtol=1e-10
        )  # p_bar printed to 12 digits
    assert (tmp_path / "contact_area.png").exists()


@pytest.mark.parametrize(
    "argv, word",
    [
        (["report", "--H", "1.5", "--no-solvers"], "H must lie in"),
        (["report", "--E-star", "-1", "--no-solvers"], "--E-star"),
        (["report", "--p-bar", "0", "--no-solvers"], "--p-bar must be finite pressures > 0"),
        (["report", "--psd-csv", "/nonexistent.csv", "--no-solvers"], "--psd"),
        (["area", "--ratio-min", "2", "--ratio-max", "1"], "--ratio-min"),
    ],
)
def test_bad_arguments_exit_2_with_one_line(argv, word, capsys, tmp_path):
    rc = main(argv + (["--output", str(tmp_path)] if argv[0] in ("report", "area") else []))
    err = capsys.readouterr().err
    assert rc == 2
    assert word in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_argparse_errors_exit_2(capsys):
    with pytest.raises(SystemExit) as e:
        main(["report", "--fudge", "XYZ"])
    assert e.value.code == 2


def test_psd_csv_with_bad_row_names_the_line(tmp_path, capsys):
    f = tmp_path / "psd.csv"
    f.write_text("q,C\n1,1e-4\n2,nan\n4,1e-6\n")
    rc = main(["report", "--psd-csv", str(f), "--no-solvers", "--output", str(tmp_path)])
    assert rc == 2
    assert "line 3" in capsys.readouterr().err


def test_solve_command_outputs_match_exact(tmp_path, capsys):
    out = tmp_path / "sol.csv"
    png = tmp_path / "sol.png"
    rc = main(["solve", "--method", "fv", "--p-bar-ratio", "0.2", "1.0", "--fudge", "YP08",
               "--output", str(out), "--plot", str(png)])  # fmt: skip
    assert rc == 0
    text = capsys.readouterr().out
    rows = list(csv.reader(open(out)))
    assert len(rows[0]) == 3 and len(rows) > 50
    p = np.array([float(r[0]) for r in rows[1:]])
    P = np.array([[float(v) for v in r[1:]] for r in rows[1:]])
    pr = pf.ContactProblem.reference(fudge="YP08", p_bar_ratio=np.array([0.2, 1.0]))
    ex = pf.exact(pr)
    dp = p[1] - p[0]
    # the written cell averages integrate to the exact contact area (fv default accuracy ~1e-5)
    np.testing.assert_allclose(P.sum(axis=0) * dp, ex.contact_area, atol=2e-5)
    assert png.stat().st_size > 1000
    assert "A* (exact)" in text


def test_solve_json_and_bad_method(tmp_path, capsys):
    import json

    out = tmp_path / "s.json"
    assert main(["solve", "--method", "sines", "--output", str(out)]) == 0
    data = json.load(open(out))
    A = pf.exact(pf.ContactProblem.reference()).contact_area
    assert data["contact_area"][0] == pytest.approx(A, abs=1e-10)
    capsys.readouterr()
    assert main(["solve", "--method", "fvv"]) == 2
    assert "method must be " in capsys.readouterr().err
    assert main(["solve", "--method", "fv", "--n-p", "3"]) == 2
    assert "--n-p" in capsys.readouterr().err


def test_solve_with_a_hardness(capsys):
    """persson-fp solve --hardness: the plastic area printed; a moving wall prints the solver's estimate."""
    from persson_fp.cli.app import main

    assert main(["solve", "--hardness", "0.075", "--method", "sines"]) == 0
    out = capsys.readouterr().out
    ex = pf.exact(pf.ContactProblem.reference(hardness=0.075))
    assert f"{float(ex.plastic_area):.8f}" in out
    args = ["solve", "--rms-slope", "4", "--q-r", "1", "--zeta-max", "10", "--p-bar", "0.3", "--hardness", "1"]
    assert main(args + ["--hardness-exponent", "0.2"]) == 0
    out = capsys.readouterr().out
    assert "A_pl" in out and "estimate" in out
    assert main(["solve", "--hardness-exponent", "0.2"]) == 2
    assert "--hardness-exponent needs --hardness" in capsys.readouterr().err
