"""pf.sweep: the same numbers as a hand-written loop, whichever executor runs it; failures reported."""

from __future__ import annotations

import json
import sys
import types
import warnings
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import erf

import persson_fp as pf
from persson_fp.sweeps import quantities as pq
from persson_fp.sweeps import run as psweep
from persson_fp.sweeps.run import SweepWarning

LOADS = np.array([0.01, 0.1, 0.5, 1.0, 2.5])  # p_bar / sqrt(V(zeta_max))


def _surfaces():
    q = np.geomspace(1.0, 40.0, 30)
    tab = pf.TabulatedPSD(q, 1e-4 * q ** (-2.0 * (1 + 0.5)))
    return {
        "H0.3": pf.SelfAffinePSD.from_rms_slope(0.1, 0.3, 1.0, 2.0, 64.0),
        "H0.8": pf.SelfAffinePSD.from_rms_slope(0.2, 0.8, 1.0, 3.0, 32.0),
        "tab": tab,
    }


MODELS = [None, "YP08", {"fudge": "Xu24"}]


def _hand_loop(surfaces, models, quantities, relative=True, E_star=1.0):
    out = {q: np.empty((len(surfaces), len(models), LOADS.size)) for q in quantities}
    for i, psd in enumerate(surfaces.values()):
        p_bar = LOADS * np.sqrt(psd.V(E_star=E_star)) if relative else LOADS
        for j, m in enumerate(models):
            kw = m if isinstance(m, dict) else {"fudge": m}
            pr = pf.ContactProblem(psd, E_star, p_bar, **kw)
            ex = pf.exact(pr)
            got = {"contact_area": ex.contact_area, "variance": ex.variance}
            if "elastic_energy" in quantities:
                got["elastic_energy"] = pf.elastic_energy(pr)
            for q in quantities:
                out[q][i, j] = got[q]
    return out


def test_sweep_equals_the_serial_loop_exactly():
    qs = ("contact_area", "variance", "elastic_energy")
    res = pf.sweep(_surfaces(), LOADS, models=MODELS, quantities=qs, relative_loads=True, progress=False)
    ref = _hand_loop(_surfaces(), MODELS, qs)
    assert res.shape == (3, 3, LOADS.size) and res.models == ["none", "YP08", "Xu24"]
    for q in qs:
        np.testing.assert_array_equal(res[q], ref[q])  # the same calls in the same order: bit for bit
    assert not res.failures
    # the tidy table: one row per surface x model x quantity x load, values the same numbers
    t = res.to_dict()
    assert all(len(v) == 3 * 3 * 3 * LOADS.size for v in t.values())
    rows = (t["surface"] == "H0.8") & (t["model"] == "YP08") & (t["quantity"] == "variance")
    np.testing.assert_array_equal(t["value"][rows], ref["variance"][1, 1])
    assert set(t["unit"][t["quantity"] == "variance"]) == {"pressure^2"}
    np.testing.assert_allclose(t["p_bar_over_sqrtV"][rows], LOADS, rtol=1e-15)


def test_contact_area_against_independent_quadrature():
    """Persson 2001: A* = erf(p_bar / sqrt(2 V)) with V = (pi/2) E*^2 int q^3 C dq (eq:Area_Persson,
    eq:V_equ); V by adaptive quadrature here, so the spectrum's closed-form moments are checked too.
    quad reaches ~1e-13 relative on the smooth pieces; erf's derivative is <= 1.13, so 1e-11 is safe."""
    surfaces = _surfaces()
    E_star = 2.5
    loads = np.array([1e-3, 1e-2, 0.05])
    res = pf.sweep(surfaces, loads, quantities="contact_area", E_star=E_star, progress=False)
    for i, psd in enumerate(surfaces.values()):
        brk = [getattr(psd, "q_r", psd.q_l)] if hasattr(psd, "q_r") else list(psd.q[1:-1])
        m3, _ = quad(lambda q: q**3 * psd.C(q), psd.q_l, psd.q_s, points=brk, limit=200, epsrel=1e-13)
        V = 0.5 * np.pi * E_star**2 * m3
        np.testing.assert_allclose(res["contact_area"][i, 0], erf(loads / np.sqrt(2 * V)), rtol=1e-11)


def test_relative_loads_give_the_universal_curve():
    """Without a fudge factor A* = erf(r / sqrt 2) at r = p_bar / sqrt(V), whatever the surface."""
    res = pf.sweep(_surfaces(), LOADS, relative_loads=True, progress=False)
    for i in range(3):
        np.testing.assert_allclose(res["contact_area"][i, 0], erf(LOADS / np.sqrt(2)), rtol=1e-14)
    np.testing.assert_allclose(res.p_bar, np.outer(res.sqrtV, LOADS), rtol=0)


def _same(a, b):
    assert a.quantities == b.quantities and a.surfaces == b.surfaces and a.models == b.models
    for q in a.quantities:
        np.testing.assert_array_equal(a[q], b[q])
    ta, tb = a.to_dict(), b.to_dict()
    assert list(ta) == list(tb)
    for k in ta:
        np.testing.assert_array_equal(ta[k], tb[k])


def test_process_pool_gives_the_same_table():
    kw = dict(models=MODELS, quantities=("contact_area", "variance"), relative_loads=True, progress=False)
    serial = pf.sweep(_surfaces(), LOADS, **kw)
    with ProcessPoolExecutor(max_workers=2) as ex:
        pooled = pf.sweep(_surfaces(), LOADS, executor=ex, chunksize=2, **kw)
    _same(serial, pooled)
    assert pooled.metadata["executor"] == "ProcessPoolExecutor" and pooled.metadata["chunksize"] == 2
    owned = pf.sweep(_surfaces(), LOADS, executor=2, **kw)  # an int: a pool made and shut down inside
    _same(serial, owned)


def test_dask_local_cluster_gives_the_same_table():
    distributed = pytest.importorskip("distributed")
    kw = dict(models=MODELS, quantities=("contact_area", "variance"), relative_loads=True, progress=False)
    serial = pf.sweep(_surfaces(), LOADS, **kw)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # dask's own start-up notices
        with (
            distributed.LocalCluster(
                n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
            ) as cluster,
            distributed.Client(cluster) as client,
        ):
            res = pf.sweep(_surfaces(), LOADS, executor=client.get_executor(), **kw)
    _same(serial, res)


def _fails_for_rough_H(problem, solution):
    """A user quantity that raises for H > 0.5 surfaces (module level: it pickles by name)."""
    if getattr(problem.psd, "H", 0.0) > 0.5:
        raise FloatingPointError(f"refused H = {problem.psd.H}")
    return solution.contact_area


@pytest.fixture
def failing_quantity():
    q = pf.register_quantity("test_fragile", _fails_for_rough_H, "1", "fails for H > 0.5")
    yield q
    del pq.QUANTITIES["test_fragile"]


@pytest.mark.parametrize("executor", [None, "process"])
def test_a_failing_task_is_reported_and_the_rest_kept(failing_quantity, executor):
    kw = dict(models=[None, "YP08"], quantities=("contact_area", "test_fragile"), relative_loads=True, progress=False)
    pool = ProcessPoolExecutor(2) if executor == "process" else None
    try:
        with pytest.warns(SweepWarning, match="2 of 12"):
            res = pf.sweep(_surfaces(), LOADS, executor=pool, **kw)
    finally:
        if pool is not None:
            pool.shutdown()
    assert [(f.surface, f.model, f.quantity) for f in res.failures] == [
        ("H0.8", "none", "test_fragile"),
        ("H0.8", "YP08", "test_fragile"),
    ]
    assert all(
        "FloatingPointError: refused H = 0.8" in f.error and "_fails_for_rough_H" in f.traceback for f in res.failures
    )
    assert "surface='H0.8'" in str(res.failures[0]) and "failed: surface='H0.8'" in repr(res)
    ref = pf.sweep(_surfaces(), LOADS, models=[None, "YP08"], relative_loads=True, progress=False)
    np.testing.assert_array_equal(res["contact_area"], ref["contact_area"])  # the other quantity is kept
    np.testing.assert_array_equal(res["test_fragile"][[0, 2]], ref["contact_area"][[0, 2]])  # other surfaces too
    assert np.all(np.isnan(res["test_fragile"][1]))
    t = res.to_dict()  # the failed pairs have no rows
    assert len(t["value"]) == (3 * 2 + 4) * LOADS.size
    assert res.metadata["n_failures"] == 2


def test_errors_raise_after_all_tasks_ran(failing_quantity):
    with pytest.raises(pf.SweepError, match="H0.8") as info:
        pf.sweep(_surfaces(), LOADS, quantities=("test_fragile",), relative_loads=True, progress=False, errors="raise")
    res = info.value.result
    assert res.ok["test_fragile"][:, 0].tolist() == [True, False, True]


def _as_lambda_quantity():
    return pq.Quantity("unpicklable", lambda problem, solution: solution.contact_area, "1")


def test_an_unpicklable_task_fails_per_task_not_the_sweep():
    """A lambda cannot travel to a worker process: every task says so, nothing hangs or crashes."""
    with ProcessPoolExecutor(2) as ex, pytest.warns(SweepWarning):
        res = pf.sweep(_surfaces(), LOADS, quantities=[_as_lambda_quantity()], executor=ex, progress=False)
    assert len(res.failures) == 3 and all(f.quantity is None for f in res.failures)
    assert all("pickle" in f.error.lower() for f in res.failures)
    # the same runs fine in-process and in threads (nothing to pickle)
    a = pf.sweep(_surfaces(), LOADS, quantities=[_as_lambda_quantity()], progress=False)
    with ThreadPoolExecutor(2) as ex:
        b = pf.sweep(_surfaces(), LOADS, quantities=[_as_lambda_quantity()], executor=ex, progress=False)
    _same(a, b)
    assert not a.failures


def test_a_numerical_method_through_the_sweep():
    """method="sines" gives what pf.solve gives, and agrees with the closed form to its tolerance."""
    surfaces = dict(list(_surfaces().items())[:2])
    res = pf.sweep(
        surfaces,
        LOADS[1:4],
        models=[None, "YP08"],
        method="sines",
        relative_loads=True,
        quantities=("contact_area", "variance"),
        progress=False,
    )
    ex = pf.sweep(
        surfaces,
        LOADS[1:4],
        models=[None, "YP08"],
        relative_loads=True,
        quantities=("contact_area", "variance"),
        progress=False,
    )
    psd = surfaces["H0.8"]
    sol = pf.solve(pf.ContactProblem(psd, 1.0, LOADS[1:4] * np.sqrt(psd.V()), "YP08"), "sines")
    np.testing.assert_array_equal(res["contact_area"][1, 1], sol.contact_area[-1])
    # sines truncates its mode series at tol = 1e-13 (default) and solves the tau map to rtol = 1e-14;
    # measured here 1.4e-14 in A* and 5.5e-14 relative in Var(p), so 1e-12 leaves margin for other platforms
    np.testing.assert_allclose(res["contact_area"], ex["contact_area"], atol=1e-12, rtol=0)
    np.testing.assert_allclose(res["variance"], ex["variance"], rtol=1e-12)
    assert res.metadata["method"] == "sines"


def test_a_misspelt_solver_option_is_refused_before_any_task_runs():
    with pytest.raises(TypeError, match="unknown option\\(s\\) \\['n_pp'\\]"):
        pf.sweep(_surfaces(), LOADS, method="fv", n_pp=100, progress=False)


def test_models_as_keyword_dicts_and_labels():
    res = pf.sweep(
        _surfaces(), LOADS, models={"plain": None, "yp": {"fudge": pf.fudge.YangPersson(gamma=0.45)}}, progress=False
    )
    assert res.models == ["plain", "yp"]
    assert res.model_info == [{"fudge": "none"}, {"fudge": "YP08"}]
    one = pf.sweep(_surfaces(), LOADS, models={"fudge": "WM17"}, progress=False)  # one model as keywords
    assert one.models == ["WM17"]
    assert psweep._resolve_models([{"fudge": "YP08"}])[0][0] == "YP08"


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(quantities=("contact_area", "nope")), "unknown name 'nope'"),
        (dict(quantities=()), "at least one"),
        (dict(quantities=("variance", "variance")), "twice"),
        (dict(models=[{"fudge": "YP08", "hardnes": 1.0}]), "unknown ContactProblem keyword"),
        (dict(models=[{"p_bar": 1.0}]), "unknown ContactProblem keyword"),
        (dict(models=["YP09"]), "fudge must be"),
        (dict(models=["YP08", "yp08"]), "labelled 'YP08'"),
        (dict(method="rk4"), "method must be 'exact' or one of"),
        (dict(method="exact", n_p=10), "takes no solver options"),
        (dict(executor=0), "executor must be"),
        (dict(executor="pool"), "executor must be"),
        (dict(chunksize=0), "chunksize must be"),
        (dict(errors="ignore"), "errors must be"),
        (dict(E_star=-1.0), "E_star must be > 0"),
    ],
)
def test_bad_arguments_raise_value_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        pf.sweep(_surfaces(), LOADS, progress=False, **kwargs)


@pytest.mark.parametrize("loads", [[], [1.0, -1.0], [[1.0]], [np.nan], 0.0])
def test_bad_loads(loads):
    with pytest.raises(ValueError, match="loads must"):
        pf.sweep(_surfaces(), loads, progress=False)


def test_bad_surfaces(tmp_path):
    with pytest.raises(ValueError, match="no such file"):
        pf.sweep(str(tmp_path / "missing.csv"), LOADS)
    with pytest.raises(ValueError, match="holds no files matching '\\*.csv'"):
        pf.sweep(tmp_path, LOADS)
    with pytest.raises(ValueError, match="surface_pattern must be"):
        pf.sweep(tmp_path, LOADS, surface_pattern="")
    with pytest.raises(ValueError, match="must be a SelfAffinePSD"):
        pf.sweep([1.0], LOADS)
    with pytest.raises(ValueError, match="surfaces must be"):
        pf.sweep(3, LOADS)
    with pytest.raises(ValueError, match="at least one surface"):
        pf.sweep([], LOADS)


def test_surfaces_from_a_folder_of_csv(tmp_path):
    surfaces = _surfaces()
    for name, psd in surfaces.items():
        q = np.geomspace(psd.q_l, psd.q_s, 40)
        (tmp_path / f"{name}.csv").write_text(
            "q,C\n" + "".join(f"{float(a)!r},{float(c)!r}\n" for a, c in zip(q, psd.C(q)))
        )
    (tmp_path / "README.txt").write_text("not a spectrum")  # not matched by the default "*.csv"
    res = pf.sweep(tmp_path, LOADS, relative_loads=True, progress=False)
    assert res.surfaces == sorted(surfaces)
    own = pf.sweep(tmp_path, LOADS, relative_loads=True, progress=False, surface_pattern="H*.csv")
    assert own.surfaces == ["H0.3", "H0.8"]
    assert res.surface_info[0]["source"].endswith("H0.3.csv") and res.surface_info[0]["surface_kind"] == "TabulatedPSD"
    np.testing.assert_allclose(res["contact_area"][:, 0], np.tile(erf(LOADS / np.sqrt(2)), (3, 1)), rtol=1e-14)


def test_csv_and_parquet_round_trip_keep_values_and_metadata(tmp_path):
    pytest.importorskip("pandas")
    res = pf.sweep(_surfaces(), LOADS, models=MODELS, quantities=("contact_area", "variance"), progress=False)
    res.to_csv(tmp_path / "t.csv")
    df = pf.read_sweep_table(tmp_path / "t.csv")
    ref = res.to_pandas()
    assert list(df.columns) == list(ref.columns) and len(df) == len(ref) == 3 * 3 * 2 * LOADS.size
    np.testing.assert_array_equal(df["value"].to_numpy(), ref["value"].to_numpy())  # repr() floats round-trip
    assert df.attrs["units"] == {"contact_area": "1", "variance": "pressure^2"}
    assert df.attrs["method"] == "exact" and df.attrs["version"] == pf.__version__
    import pandas as pd

    plain = pd.read_csv(tmp_path / "t.csv")  # the ecosystem's default reader: the same columns and values
    assert list(plain.columns) == list(ref.columns)
    np.testing.assert_array_equal(plain["value"].to_numpy(), ref["value"].to_numpy())
    pytest.importorskip("pyarrow")
    res.to_parquet(tmp_path / "t.parquet")
    dp = pf.read_sweep_table(tmp_path / "t.parquet")
    np.testing.assert_array_equal(dp["value"].to_numpy(), ref["value"].to_numpy())
    assert dp.attrs["units"] == df.attrs["units"]
    with pytest.raises(ValueError, match="not a persson-fp sweep table"):
        (tmp_path / "other.csv").write_text("a,b\n1,2\n")
        pf.read_sweep_table(tmp_path / "other.csv")


def test_to_xarray_labels_and_units():
    pytest.importorskip("xarray")
    res = pf.sweep(
        _surfaces(), LOADS, models=MODELS, quantities=("contact_area", "variance"), progress=False, relative_loads=True
    )
    ds = res.to_xarray()
    np.testing.assert_array_equal(ds["variance"].sel(surface="tab", model="Xu24").values, res["variance"][2, 2])
    assert ds["variance"].attrs["units"] == "pressure^2"
    np.testing.assert_array_equal(ds["p_bar"].values, res.p_bar)
    assert ds.attrs["method"] == "exact"


def test_without_pandas_the_table_is_a_dict_of_arrays(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas -> ImportError
    res = pf.sweep(_surfaces(), LOADS, progress=False)
    t = res.table
    assert isinstance(t, dict) and all(isinstance(v, np.ndarray) and v.size == 3 * LOADS.size for v in t.values())
    with pytest.raises(ImportError, match="pip install pandas"):
        res.to_pandas()
    res.to_csv(tmp_path / "t.csv")  # the CSV writer needs no pandas
    lines = (tmp_path / "t.csv").read_text().splitlines()
    assert lines[0].startswith("surface,") and len(lines) == 1 + 3 * LOADS.size  # plain CSV: a header, the rows
    assert json.loads((tmp_path / "t.csv.json").read_text())["method"] == "exact"  # the metadata next to it
    last = dict(zip(lines[0].split(","), lines[-1].split(",")))
    assert float(last["value"]) == res["contact_area"][2, 0, -1]  # repr() of a float reads back exactly


class _FakeTTY:
    def __init__(self, tty):
        self.tty = tty

    def isatty(self):
        return self.tty

    def write(self, s):
        return len(s)

    def flush(self):
        pass


def test_progress_bar_only_on_a_terminal_outside_ci(monkeypatch):
    pytest.importorskip("tqdm")
    for var in psweep._CI_VARIABLES:
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setattr(sys, "stderr", _FakeTTY(False))
    assert psweep._progress_bar(True, 10) is None
    monkeypatch.setattr(sys, "stderr", _FakeTTY(True))
    assert psweep._progress_bar(False, 10) is None
    bar = psweep._progress_bar(True, 10)
    assert bar is not None and bar.total == 10
    bar.close()
    monkeypatch.setenv("CI", "true")
    assert psweep._progress_bar(True, 10) is None
    monkeypatch.delenv("CI")
    res = pf.sweep(_surfaces(), LOADS, progress=True)  # draws on the fake terminal, same numbers
    _same(res, pf.sweep(_surfaces(), LOADS, progress=False))


def test_separation_quantities_register_when_the_module_exists():
    fake = types.SimpleNamespace(mean_separation=lambda pr: pr.p_bar * 0 + 1.0, stiffness=lambda pr: pr.p_bar * 2)
    missing = [n for n in ("mean_separation", "stiffness") if n not in pq.QUANTITIES]
    added = pq._register_separation(fake)
    try:
        assert added == missing
        if added:  # the wrappers look the module up by name
            pr = pf.ContactProblem.reference(p_bar_ratio=np.array([0.1, 0.2]))
            old = sys.modules.get("persson_fp.analysis.separation")
            sys.modules["persson_fp.analysis.separation"] = fake
            try:
                np.testing.assert_array_equal(pq.QUANTITIES["stiffness"](pr, None), 2 * pr.p_bar)
                assert pq.QUANTITIES["mean_separation"].unit == "length"
            finally:
                if old is None:
                    del sys.modules["persson_fp.analysis.separation"]
                else:
                    sys.modules["persson_fp.analysis.separation"] = old
    finally:
        for n in added:
            del pq.QUANTITIES[n]
    assert pq._register_separation(None) == []


def test_register_quantity_checks():
    with pytest.raises(ValueError, match="already registered"):
        pf.register_quantity("contact_area", lambda p, s: s.contact_area, "1")
    with pytest.raises(ValueError, match="name must be"):
        pf.register_quantity("", lambda p, s: 0, "1")
    with pytest.raises(ValueError, match="func must be callable"):
        pf.register_quantity("x", 3, "1")
    bad = pq.Quantity("bad", lambda p, s: np.zeros(7), "1")
    with pytest.raises(ValueError, match="expected \\(5,\\)"):
        bad(pf.ContactProblem.reference(p_bar_ratio=LOADS), None)


def test_compact_reprs():
    pr = pf.ContactProblem.reference(p_bar_ratio=np.geomspace(0.01, 2, 500))
    sol = pf.solve(pr, "sines")
    r = repr(sol)
    assert "\n" not in r and len(r) < 300 and r.startswith("Solution(method='sines'")
    A = sol.contact_area[-1]
    assert f"A=[{A.min():.6g}, {A.max():.6g}] (500)" in r
    assert "<table>" in sol._repr_html_() and len(sol._repr_html_()) < 2000
    ex = pf.exact(pr)
    assert repr(ex) == (
        f"ExactSolution(fudge='none', p_bar=[{pr.p_bar.min():.6g}, {pr.p_bar.max():.6g}] (500), zeta=128, "
        f"V={pr.V_max:.6g}, A=[{ex.contact_area.min():.6g}, {ex.contact_area.max():.6g}] (500))"
    )
    assert "ExactSolution" in ex._repr_html_()
    res = pf.sweep(_surfaces(), LOADS, models=MODELS, progress=False)
    assert repr(res).startswith("SweepResult(method='exact', 3 surfaces x 3 models x 5 loads; contact_area [1]")
    h = res._repr_html_()
    assert h.count("<tr>") == 1 + 3 and "median" in h


def test_docstring_example_runs():
    import doctest

    failed, attempted = doctest.testmod(psweep, verbose=False)
    assert attempted >= 3 and failed == 0
