"""The command never prints a traceback: every error is one line and exit code 2, Ctrl-C is
"interrupted" and 130, an interrupted write leaves no file, an existing output needs --force, written files get the
umask's default mode, options that would be ignored are refused."""

import csv
import os
import stat
import subprocess
import sys

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import main


def _one_line_error(capsys, rc, word):
    err = capsys.readouterr().err
    assert rc == 2, err
    assert "Traceback" not in err
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("note:")]
    assert len(lines) == 1, err
    assert word in lines[0], err
    return lines[0]


@pytest.fixture
def a_file(tmp_path):
    f = tmp_path / "regular.txt"
    f.write_text("x")
    return f


CASES = {
    # file system
    "output is a folder": (lambda t, f: ["solve", "--method", "sines", "--output", str(t)], "is a directory"),
    "output under a file": (lambda t, f: ["solve", "--method", "sines", "--output", str(f / "x.csv")], "not a folder"),
    "plot under a file": (lambda t, f: ["solve", "--method", "sines", "--plot", str(f / "x.png")], "not a folder"),
    "report into a file": (lambda t, f: ["report", "--no-solvers", "--output", str(f)], "not a folder"),
    "area into a file": (lambda t, f: ["area", "--n-loads", "5", "--output", str(f)], "not a folder"),
    "psd-csv folder": (lambda t, f: ["solve", "--psd-csv", str(t)], "--psd: is a directory"),
    "psd-csv missing": (lambda t, f: ["solve", "--psd-csv", str(t / "none.csv")], "no such file"),
    # numbers out of range
    "q-l 1e-300": (lambda t, f: ["solve", "--method", "sines", "--q-l", "1e-300"], "floating-point range"),
    "E-star 1e308": (lambda t, f: ["solve", "--method", "sines", "--E-star", "1e308"], "--E-star"),
    "n-p negative": (lambda t, f: ["solve", "--n-p", "-3"], "--n-p must be an integer"),
    "mol 1e6": (lambda t, f: ["solve", "--method", "mol", "--p-bar-ratio", "1e6"], "pf.exact"),
    "ck 1e-100": (lambda t, f: ["solve", "--method", "chapman-kolmogorov", "--p-bar-ratio", "1e-100"], "'sines'"),
    "n-p huge": (lambda t, f: ["solve", "--n-p", "1e8"], "GiB of memory"),
    "n-loads huge": (lambda t, f: ["area", "--n-loads", "100000000", "--output", str(t)], "--n-loads"),
    "bad gamma": (lambda t, f: ["solve", "--fudge", "YP08", "--gamma", "2"], "gamma"),
    # options that would be ignored
    "H with psd-csv": (lambda t, f: ["solve", "--psd-csv", str(f), "--H", "0.3"], "--H: not used with --psd"),
    "slope with psd-csv": (lambda t, f: ["solve", "--psd-csv", str(f), "--rms-slope", "0.2"], "--rms-slope"),
    "gamma without fudge": (lambda t, f: ["solve", "--gamma", "0.4"], "--gamma: not used with --fudge none"),
    "p-bar with area": (lambda t, f: ["area", "--p-bar", "1", "--output", str(t)], "--p-bar: not used by 'area'"),
    "fudge with area": (lambda t, f: ["area", "--fudge", "YP08", "--output", str(t)], "--fudge: not used"),
    "seed without MC": (lambda t, f: ["solve", "--seed", "3"], "--seed: only used with --method monte-carlo"),
}


@pytest.mark.parametrize("case", list(CASES))
def test_error_is_one_line_and_exit_2(case, tmp_path, a_file, capsys):
    make, word = CASES[case]
    rc = main(make(tmp_path, a_file))
    _one_line_error(capsys, rc, word)


@pytest.mark.parametrize(
    "argv", [["solve", "--n-p", "1e6.5"], ["report", "--fudge", "XYZ"], ["area", "--n-loads"], ["solve", "--bogus"]]
)
def test_argparse_errors_are_one_line_too(argv, capsys):
    with pytest.raises(SystemExit) as e:
        main(argv)
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "error:" in err and "--help" in err


def test_dev_full_is_a_one_line_error(capsys):
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full here")
    rc = main(["solve", "--method", "sines", "--output", "/dev/full"])
    _one_line_error(capsys, rc, "/dev/full")


def test_as_a_program_no_traceback(tmp_path, a_file):
    r = subprocess.run(
        [sys.executable, "-m", "persson_fp.cli", "solve", "--method", "sines", "--output", str(a_file / "x.csv")],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_existing_output_needs_force(tmp_path, capsys):
    out = tmp_path / "sol.csv"
    out.write_text("keep me")
    rc = main(["solve", "--method", "sines", "--output", str(out)])
    _one_line_error(capsys, rc, "--force")
    assert out.read_text() == "keep me"
    assert main(["solve", "--method", "sines", "--output", str(out), "--force"]) == 0
    rows = list(csv.reader(open(out)))
    p = np.array([float(r[0]) for r in rows[1:]])
    P = np.array([float(r[1]) for r in rows[1:]])
    ex = pf.exact(pf.ContactProblem.reference())
    np.testing.assert_allclose(P, ex.pdf(p), rtol=0, atol=1e-8 * P.max())  # sines: point values to ~1e-12


def test_folder_outputs_are_refused_without_force(tmp_path, capsys):
    """A second run into the same folder is refused (one line, exit 2, the file untouched); --force replaces."""
    assert main(["area", "--n-loads", "5", "--output", str(tmp_path)]) == 0
    capsys.readouterr()
    before = (tmp_path / "contact_area.csv").read_text()
    _one_line_error(capsys, main(["area", "--n-loads", "6", "--output", str(tmp_path)]), "--force")
    assert (tmp_path / "contact_area.csv").read_text() == before
    assert main(["area", "--n-loads", "6", "--output", str(tmp_path), "--force"]) == 0
    assert len((tmp_path / "contact_area.csv").read_text().splitlines()) == 7


def test_ctrl_c_is_interrupted_130_and_leaves_no_partial_file(tmp_path, monkeypatch, capsys):
    out = tmp_path / "sol.csv"
    calls = {"n": 0}
    real_writer = csv.writer

    class Interrupting:
        def __init__(self, fh):
            self.w = real_writer(fh)

        def writerow(self, row):
            calls["n"] += 1
            if calls["n"] == 20:  # part of the table is written when the user presses Ctrl-C
                raise KeyboardInterrupt
            self.w.writerow(row)

    monkeypatch.setattr(csv, "writer", Interrupting)
    rc = main(["solve", "--method", "sines", "--output", str(out)])
    err = capsys.readouterr().err
    assert rc == 130 and "interrupted" in err and "Traceback" not in err
    assert calls["n"] == 20
    assert list(tmp_path.iterdir()) == []  # neither sol.csv nor a temporary file


def test_seed_makes_monte_carlo_reproducible(tmp_path):
    """--seed reaches the random walks: the same seed writes the same histogram, another seed another one."""
    runs = {}
    for name, seed in (("a", "5"), ("b", "5"), ("c", "6")):
        out = tmp_path / f"{name}.csv"
        assert main(["solve", "--method", "monte-carlo", "--seed", seed, "--output", str(out)]) == 0
        runs[name] = out.read_text()
    assert runs["a"] == runs["b"] != runs["c"]


def _spectrum_csv(path):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 128.0)
    q = np.geomspace(1.0, 128.0, 40)
    np.savetxt(path, np.column_stack((q, psd.C(q))), delimiter=",", header="q,C", comments="")


def test_surface_on_an_empty_npy_is_one_line(tmp_path, capsys):
    (tmp_path / "empty.npy").write_bytes(b"")  # was an EOFError traceback
    _one_line_error(capsys, main(["surface", str(tmp_path / "empty.npy"), "--size", "1"]), "cannot read a height map")


@pytest.mark.parametrize(("flag", "value", "word"), [("--tol", "5e-324", "--tol"), ("--atol", "-1", "--atol")])
def test_solve_refuses_a_tolerance_out_of_range(flag, value, word, capsys):
    # --tol 5e-324 was an OverflowError traceback; --atol -1 with fv only warned
    _one_line_error(capsys, main(["solve", "--method", "auto" if flag == "--tol" else "fv", flag, value]), word)


def test_surface_caps_the_number_of_loads(tmp_path, capsys):
    np.save(tmp_path / "h.npy", np.random.default_rng(0).standard_normal((16, 16)))
    # 1e7 loads ran past 120 s; "area" caps at 1e6
    _one_line_error(
        capsys, main(["surface", str(tmp_path / "h.npy"), "--size", "1", "--n-loads", "10000000"]), "--n-loads"
    )


def test_sweep_does_not_overwrite_without_force_and_writes_plain_csv(tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    _spectrum_csv(tmp_path / "s.csv")
    out = tmp_path / "out" / "t.csv"
    args = ["sweep", str(tmp_path / "s.csv"), "--n-loads", "3", "--models", "none", "--no-progress"]
    assert main([*args, "--output", str(out)]) == 0
    capsys.readouterr()
    _one_line_error(capsys, main([*args, "--output", str(out)]), "--force")  # was overwritten silently
    assert main([*args, "--output", str(out), "--force"]) == 0
    df = pd.read_csv(out)  # plain pandas: was one column because of the "#" metadata lines
    assert {"surface", "model", "quantity", "value"} <= set(df.columns) and len(df) == 3
    assert pf.read_sweep_table(out).attrs["method"] == "exact"
    assert sorted(os.listdir(out.parent)) == ["t.csv", "t.csv.json"]  # no temporary file left behind


def test_an_interrupted_sweep_leaves_no_partial_table(tmp_path, monkeypatch, capsys):
    from persson_fp.sweeps.table import SweepResult

    _spectrum_csv(tmp_path / "s.csv")
    out = tmp_path / "t.csv"
    out.write_text("old")

    def interrupted(self, path):
        with open(path, "w") as fh:
            fh.write("partial")
        raise KeyboardInterrupt

    monkeypatch.setattr(SweepResult, "to_csv", interrupted)
    argv = ["sweep", str(tmp_path / "s.csv"), "--n-loads", "3", "--models", "none", "--no-progress", "--force"]
    assert main([*argv, "--output", str(out)]) == 130
    assert out.read_text() == "old" and sorted(os.listdir(tmp_path)) == ["s.csv", "t.csv"]


def test_written_files_get_the_umask_default_mode(tmp_path, capsys):
    mask = os.umask(0o022)
    try:
        out = tmp_path / "p.csv"
        assert main(["solve", "--method", "sines", "--output", str(out)]) == 0  # was 0600 (mkstemp)
        assert stat.S_IMODE(os.stat(out).st_mode) == 0o644
        assert main(["area", "--n-loads", "20", "--output", str(tmp_path / "a")]) == 0
        for name in os.listdir(tmp_path / "a"):
            assert stat.S_IMODE(os.stat(tmp_path / "a" / name).st_mode) == 0o644, name
    finally:
        os.umask(mask)
