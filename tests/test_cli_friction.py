"""``persson-fp friction``: the table it writes is the library's mu(v, T), with units; bad input is one line."""

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.cli.app import main


@pytest.fixture()
def files(tmp_path):
    tau = np.logspace(-9, 2, 12)
    E_i = 4e7 * np.exp(-0.5 * ((np.log10(tau) + 4.0) / 2.5) ** 2)
    prony = pf.viscoelastic.Prony(2e6, E_i, tau)
    f = np.logspace(-6, 13, 96)
    E = prony.modulus(2 * np.pi * f)
    mc = tmp_path / "mc.csv"
    np.savetxt(mc, np.c_[f, E.real, E.imag], delimiter=",", header="frequency [Hz],E_storage [Pa],E_loss [Pa]",
               comments="")  # fmt: skip
    psd = pf.SelfAffinePSD.from_rms_slope(1.0, 0.8, 1e3, 1e4, 1e7)
    q = np.geomspace(1e3, 1e7, 120)
    road = tmp_path / "road.csv"
    np.savetxt(road, np.c_[q, psd.C(q)], delimiter=",", header="q,C", comments="")
    return tmp_path, mc, road


def _table(path):
    lines = [ln for ln in path.read_text().splitlines() if not ln.startswith("#")]
    header = lines[0].split(",")
    return header, np.loadtxt(lines[1:], delimiter=",", ndmin=2)


def test_friction_table_is_the_librarys(files, capsys):
    tmp, mc, road = files
    out = tmp / "out"
    rc = main(["friction", "--master-curve", str(mc), "--wlf", "8.86", "101.6", "--T-ref", "20", "--psd", str(road),
               "--p-bar", "2e5", "--temperature", "0", "40", "--velocity", "1e-4", "1", "--n-velocities", "5",
               "--output", str(out)])  # fmt: skip
    assert rc == 0
    text = capsys.readouterr().out
    assert "flash temperature" in text and "wrote" in text
    header, data = _table(out / "friction.csv")
    assert header == ["temperature [degC]", "velocity [m/s]", "mu [-]", "mu_error [-]", "contact_area [-]",
                      "contact_area_error [-]"]  # fmt: skip
    assert (out / "friction.png").stat().st_size > 1000
    f, E1, E2 = np.loadtxt(mc, delimiter=",", skiprows=1, unpack=True)
    mat = pf.viscoelastic.MasterCurve(f, E1, E2, T_ref=20.0, shift=pf.viscoelastic.WLF(8.86, 101.6))
    res = pf.rubber_friction(pf.TabulatedPSD.from_csv(road), mat, 2e5, np.geomspace(1e-4, 1, 5),
                             temperature=np.array([[0.0], [40.0]]))  # fmt: skip
    np.testing.assert_allclose(data[:, 2], res.mu.ravel(), rtol=1e-9)
    np.testing.assert_allclose(data[:, 4], res.contact_area.ravel(), rtol=1e-9)
    # a second run into the same folder is refused without --force
    assert main(["friction", "--zener", "3e6", "3e9", "1e-4", "--psd", str(road), "--p-bar", "2e5", "--output",
                 str(out)]) == 2  # fmt: skip
    assert "--force" in capsys.readouterr().err


@pytest.mark.parametrize(
    "extra, message",
    [
        (["--p-bar", "-2e5"], "--p-bar"),
        (["--p-bar", "2e5", "--velocity", "1", "-2", "3"], "velocity"),
        (["--p-bar", "2e5", "--nu", "0.7"], "nu"),
        (["--p-bar", "2e5", "--q1", "1e9"], "q1"),
        (["--p-bar", "2e5", "--wlf", "8.86", "101.6"], "--T-ref"),
    ],
)
def test_friction_bad_input_is_one_line(files, capsys, extra, message):
    tmp, mc, road = files
    rc = main(["friction", "--zener", "3e6", "3e9", "1e-4", "--psd", str(road), "--output", str(tmp / "o"), *extra])
    err = capsys.readouterr().err
    assert rc == 2 and message in err and len(err.strip().splitlines()) == 1
