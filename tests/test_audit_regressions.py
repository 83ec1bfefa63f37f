"""Regression tests of the fuzz audit's reproducers (issue 22): each was a traceback, a hang, a wrong number or a
silent acceptance; each is now one clear error or the right result."""

import os
import stat
import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import main

PSD = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 128.0)


def _one_line(capsys, rc, word):
    err = capsys.readouterr().err
    assert rc == 2, err
    assert "Traceback" not in err
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("note:")]
    assert len(lines) == 1 and word in lines[0], err


# -- command line -----------------------------------------------------------------------------------------
def test_surface_on_an_empty_npy_is_one_line(tmp_path, capsys):
    (tmp_path / "empty.npy").write_bytes(b"")  # was an EOFError traceback
    _one_line(capsys, main(["surface", str(tmp_path / "empty.npy"), "--size", "1"]), "cannot read a height map")


@pytest.mark.parametrize(("flag", "value", "word"), [("--tol", "5e-324", "--tol"), ("--atol", "-1", "--atol")])
def test_solve_refuses_a_tolerance_out_of_range(flag, value, word, capsys):
    # --tol 5e-324 was an OverflowError traceback; --atol -1 with fv only warned
    _one_line(capsys, main(["solve", "--method", "auto" if flag == "--tol" else "fv", flag, value]), word)


def test_surface_caps_the_number_of_loads(tmp_path, capsys):
    np.save(tmp_path / "h.npy", np.random.default_rng(0).standard_normal((16, 16)))
    # 1e7 loads ran past 120 s; "area" caps at 1e6
    _one_line(capsys, main(["surface", str(tmp_path / "h.npy"), "--size", "1", "--n-loads", "10000000"]), "--n-loads")


def _spectrum_csv(path):
    q = np.geomspace(1.0, 128.0, 40)
    np.savetxt(path, np.column_stack((q, PSD.C(q))), delimiter=",", header="q,C", comments="")


def test_sweep_does_not_overwrite_without_force_and_writes_plain_csv(tmp_path, capsys):
    pd = pytest.importorskip("pandas")
    _spectrum_csv(tmp_path / "s.csv")
    out = tmp_path / "out" / "t.csv"
    args = ["sweep", str(tmp_path / "s.csv"), "--n-loads", "3", "--models", "none", "--no-progress"]
    assert main([*args, "--output", str(out)]) == 0
    capsys.readouterr()
    _one_line(capsys, main([*args, "--output", str(out)]), "--force")  # was overwritten silently
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


# -- readers ---------------------------------------------------------------------------------------------------
def test_readers_refuse_an_int_and_keep_the_callers_file(tmp_path):
    path = tmp_path / "s.csv"
    _spectrum_csv(path)
    with open(path) as fh:
        for read in (
            lambda: pf.TabulatedPSD.from_csv(fh.fileno()),
            lambda: pf.read_contact_engineering_csv(fh.fileno()),
            lambda: pf.read_heightmap(fh.fileno(), 1.0),
        ):
            with pytest.raises(ValueError, match="path must be a file name"):
                read()
        assert fh.readline().startswith("q,C")  # the caller's file is still open


def test_readers_name_a_folder(tmp_path):
    with pytest.raises(ValueError, match="is a folder"):
        pf.TabulatedPSD.from_csv(tmp_path)  # was IsADirectoryError
    with pytest.raises(ValueError, match="is a folder"):
        pf.read_contact_engineering_csv(tmp_path)


# -- library ---------------------------------------------------------------------------------------------------
def test_mean_separation_guards():
    with pytest.raises(ValueError, match="E_star"):  # was "cannot convert float NaN to integer"
        pf.MeanSeparation(PSD, E_star=1e308)
    with pytest.raises(ValueError, match=r"n_per_unit must be an integer in \[1, 1000\]"):  # was MemoryError
        pf.MeanSeparation(PSD, n_per_unit=10**7)
    ms = pf.MeanSeparation(PSD)
    with pytest.raises(ValueError, match="full contact"):  # was inf
        ms.stiffness(1e300)
    # below the limit the stiffness is finite: K = p / (dU/dp), dU/dp > 0
    assert np.isfinite(ms.stiffness(20 * ms.sigma_max)) and ms.mean_separation(1e300) == 0.0


def test_tabulated_band_limits_must_be_numbers():
    with pytest.raises(ValueError, match="q_l must be a real number"):  # was TypeError
        pf.TabulatedPSD([1.0, 2.0, 4.0], [1.0, 0.5, 0.1], q_l=[1, 2])


@pytest.mark.parametrize("seed", [float("inf"), True, np.bool_(True), -1, 2.5, "3"])
def test_monte_carlo_refuses_odd_seeds(seed):
    pr = pf.ContactProblem.reference()
    with pytest.raises(ValueError, match="seed must be"):  # inf was OverflowError, True was accepted
        pf.solve(pr, "monte-carlo", seed=seed, n_walkers=100)


@pytest.mark.parametrize(("method", "word"), [("monte-carlo", "n_walkers"), ("chapman-kolmogorov", "n_p and")])
def test_methods_without_tolerance_control_say_so(method, word):
    with pytest.raises(ValueError, match=f"no tolerance control.*{word}"):  # was TypeError "unknown option"
        pf.solve(pf.ContactProblem.reference(), method, tol=1e-3)


# -- unit slips ----------------------------------------------------------------------------------------------------
def test_load_above_the_modulus_warns_in_terms_of_p_over_E():
    with pytest.warns(UserWarning, match=r"p_bar / E_star = 1e\+06 > 1.*same unit"):  # E* in GPa, p_bar in Pa
        pf.ContactProblem(PSD, E_star=1.0, p_bar=1e6)


def test_exact_full_contact_at_every_load_names_the_cause():
    pr = pf.ContactProblem(PSD, E_star=1.0, p_bar=[0.5, 0.9])  # sqrt(V) = 0.05: p_bar / sqrt(V) >= 10
    with pytest.warns(UserWarning, match=r"full contact at every load.*p_bar / sqrt\(V\).*different units"):
        ex = pf.exact(pr)
    np.testing.assert_allclose(ex.contact_area, 1.0, rtol=0, atol=1e-15)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # an ordinary load is quiet
        pf.exact(pf.ContactProblem.reference(p_bar_ratio=[0.5, 3.0]))


@pytest.mark.parametrize("method", ["auto", "fv", "mol"])
@pytest.mark.parametrize("tol", [5e-324, 1e-16])
def test_tol_below_round_off_is_a_value_error(method, tol):
    """pf.solve(..., tol=5e-324) raised OverflowError (a resolution of inf cells); tol is now checked against
    [1e-15, 0.1] before any resolution is derived from it."""
    with pytest.raises(ValueError, match=r"tol must lie in \[1e-15, 0.1\]"):
        pf.solve(pf.ContactProblem.reference(), method, tol=tol)


@pytest.mark.parametrize("method", ["fv", "sines"])
def test_an_ignored_knob_out_of_range_is_still_an_error(method):
    """`atol=-1` with fv (which ignores atol) only warned; a value outside a knob's range is wrong for every method."""
    with pytest.raises(ValueError, match=r"atol must lie in \[0, inf\]"):
        pf.solve(pf.ContactProblem.reference(), method, atol=-1)
    with pytest.warns(UserWarning, match="ignores the option 'atol'"):
        pf.solve(pf.ContactProblem.reference(), method, atol=1e-8)


def test_complex_heights_error_is_one_line():
    """A complex height map's error printed the whole array (hundreds of characters); now its shape and first value."""
    with pytest.raises(ValueError, match=r"heights must be real.*shape \(64, 64\), first element") as err:
        pf.psd_from_heightmap(np.ones((64, 64)) * (1 + 1j), 1.0)
    assert len(str(err.value)) < 200 and "\n" not in str(err.value)


def test_one_value_text_map_reports_its_shape(tmp_path):
    """A 1 x 1 text map was reported as "shape ()" (numpy's loadtxt drops the axes); now (1, 1)."""
    path = tmp_path / "one.txt"
    path.write_text("1.5\n")
    with pytest.raises(ValueError, match=r"at least 4 points per side, got shape \(1, 1\)"):
        pf.read_heightmap(str(path), 1.0)
