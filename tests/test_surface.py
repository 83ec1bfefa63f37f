"""Spectrum conventions and surface import against known spectra and the BEM surfaces' parameters."""

import os
import warnings

import numpy as np
import pytest

import persson_fp as pf
from persson_fp.surfaces.conventions import abel_factor, abel_forward, abel_inverse

DATA = os.path.join(os.path.dirname(__file__), "..", "data", "bem")
REF = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 2 * np.pi, 8 * np.pi, 128 * np.pi)


def synthetic_surface(psd, N, L, rng):
    """A periodic height map whose modes have amplitude exactly sqrt(C(q) dq^2) and random phases, so its
    rms height and slope are the lattice sums of the spectrum (an exact reference, no sampling noise)."""
    k = np.fft.fftfreq(N, d=1.0 / N)
    KX, KY = np.meshgrid(k, k, indexing="ij")
    q = 2 * np.pi / L * np.hypot(KX, KY)
    dq2 = (2 * np.pi / L) ** 2
    amp = np.sqrt(psd.C(q) * dq2)
    theta = 2 * np.pi * rng.random((N, N))
    neg = (-np.arange(N)) % N
    theta = theta - theta[np.ix_(neg, neg)]  # odd phases: h_{-k} = conj(h_k), so h is real with this exact power
    h = np.real(np.fft.ifft2(amp * np.exp(1j * theta)) * N * N)
    return h, float(np.sqrt(np.sum(amp**2))), float(np.sqrt(np.sum(q**2 * amp**2)))


# -- conventions ---------------------------------------------------------------------------------------
def test_abel_factor_closed_values():
    # 2 sqrt(pi) Gamma(H+1)/Gamma(H+1/2): pi at H = 1/2, 2 at H = 0, 4 at H = 1
    np.testing.assert_allclose(abel_factor([0.0, 0.5, 1.0]), [2.0, np.pi, 4.0], rtol=1e-14)


@pytest.mark.parametrize("H", [0.2, 0.5, 0.8, 1.0])
def test_numerical_abel_inversion_of_a_power_law_is_the_factor(H):
    q = np.geomspace(1.0, 1e3, 30)
    C1 = 2.0 * q ** (-1 - 2 * H)
    # exact for a power law (the inversion integrates upward from q and the tail is continued): GL to ~1e-12
    np.testing.assert_allclose(abel_inverse(q, C1), abel_factor(H) * C1 / (4 * np.pi**2 * q), rtol=1e-9)


def test_one_d_round_trip_through_the_forward_abel_transform():
    """C -> C1D (forward Abel, what line scans of an isotropic surface give) -> C by numerical inversion."""
    q = np.geomspace(REF.q_l, REF.q_s, 200)[:-1]
    t = pf.TabulatedPSD(q, abel_forward(REF, q), convention="1d")
    inner = (q > 1.2 * REF.q_l) & (q < 0.8 * REF.q_s)
    # pointwise: the log-log interpolant of C1D rounds the roll-off kink (measured 1.3 % next to it)
    np.testing.assert_allclose(t.C(q[inner]), REF.C(q[inner]), rtol=0.02)
    assert t.rms_slope == pytest.approx(REF.rms_slope, rel=0.01)  # measured -0.8 % (table ends at 0.98 q_s)
    assert t.rms_height == pytest.approx(REF.rms_height, rel=0.01)
    assert t.convention == "1d"


def test_conventions_and_units_convert_to_the_same_spectrum():
    q = np.geomspace(2 * np.pi, 128 * np.pi, 60)
    C = REF.C(q)
    base = pf.TabulatedPSD(q, C)
    same = [
        pf.TabulatedPSD(q, (2 * np.pi) ** 2 * C, convention="iso2d"),  # SurfaceTopography / 2-D FFT
        pf.TabulatedPSD(q, q * (2 * np.pi) ** 2 * C / np.pi, convention="q/pi*2d"),  # contact.engineering
        pf.TabulatedPSD(q / (2 * np.pi), (2 * np.pi) ** 2 * C, q_unit="1/length"),  # per (1/wavelength)^2
    ]
    for t in same:
        np.testing.assert_allclose(t.q, base.q, rtol=1e-14)
        np.testing.assert_allclose(t.values, base.values, rtol=1e-13)
        assert t.rms_slope == pytest.approx(base.rms_slope, rel=1e-13)
    r = repr(same[0])
    assert "convention='iso2d'" in r and "rms_height=" in r and "rms_slope=" in r


def test_convention_errors():
    q, C = [1.0, 2.0, 4.0], [1.0, 0.5, 0.1]
    with pytest.raises(ValueError, match="convention must be one of"):
        pf.TabulatedPSD(q, C, convention="fft")
    with pytest.raises(ValueError, match="q_unit"):
        pf.TabulatedPSD(q, C, q_unit="1/m")
    with pytest.raises(ValueError, match="H is used only"):
        pf.TabulatedPSD(q, C, convention="iso2d", H=0.8)
    with pytest.raises(ValueError, match="rises"):  # a rising 1-D PSD has no non-negative 2-D spectrum
        pf.TabulatedPSD([1.0, 2.0, 4.0, 8.0], [1.0, 0.1, 1.0, 0.01], convention="1d")
    with pytest.raises(ValueError, match="H must be > -0.5"):
        abel_factor(-0.6)


# -- height maps -----------------------------------------------------------------------------------------
@pytest.mark.parametrize("H", [0.3, 0.8])
def test_synthetic_height_map_recovers_rms_and_hurst(H, rng):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, H, 2 * np.pi, 8 * np.pi, 64 * np.pi)  # q_s = 32 dq
    h, rms_h, rms_s = synthetic_surface(psd, 256, 1.0, rng)
    s = pf.psd_from_heightmap(h, 1.0, periodic=True)
    assert s.rms_height_data == pytest.approx(rms_h, rel=1e-10)  # the map is what it was built to be
    assert s.rms_slope_data == pytest.approx(rms_s, rel=1e-10)
    # annulus means vs lattice sums: measured -0.4 / -0.85 % (height, H = 0.3 / 0.8), slope within 0.05 %
    assert s.psd.rms_height == pytest.approx(rms_h, rel=0.01)
    assert s.psd.rms_slope == pytest.approx(rms_s, rel=0.01)
    # the continuum spectrum it came from (lattice sums vs integrals differ by < 1 % at 32 modes per side)
    assert s.psd.rms_slope == pytest.approx(psd.rms_slope, rel=0.01)
    # H from a fit of the recovered tail (deterministic amplitudes: no sampling scatter), above the first annuli
    # (one lattice step wide, up to 6 dq), whose exponents carry their few lattice radii's slope power instead
    qq = np.geomspace(14 * np.pi, 50 * np.pi, 20)
    slope = np.polyfit(np.log(qq), np.log(s.psd.C(qq)), 1)[0]
    assert -slope / 2 - 1 == pytest.approx(H, abs=0.02)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_bem_surface_import_matches_psd_params(seed):
    """The BEM surfaces (data/bem/surfaces: Fourier modes) rebuilt on N = 256 and imported: rms height and slope
    against the height data (<= 1 %) and against psd_params.csv (h_rms; rms slope 0.1 exactly)."""
    d = np.load(os.path.join(DATA, "surfaces", f"surface_H0.8_seed{seed}_modes.npz"))
    N = 256
    A = np.zeros((N, N), complex)
    A[np.ix_(d["k"] % N, d["k"] % N)] = d["hq"]
    h = np.real(np.fft.ifft2(A) * N * N)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the import's own <= 1 % check must not fire
        s = pf.psd_from_heightmap(h, 1.0, periodic=True)
    params = np.genfromtxt(os.path.join(DATA, "psd_params.csv"), delimiter=",", names=True)
    row = params[(params["H_nominal"] == 0.8) & (params["seed"] == seed)][0]
    eh, es = s.rms_errors
    assert abs(eh) < 0.01 and abs(es) < 0.01
    assert s.psd.rms_height == pytest.approx(row["hrms"], rel=0.01)
    assert s.psd.rms_slope == pytest.approx(row["rms_slope"], rel=0.01)
    # full-contact pressure variance of the BEM runs: V = E*^2/4 <|grad h|^2> = 0.0025 (E* = 1)
    assert float(s.psd.V()) == pytest.approx(0.0025, rel=0.02)


def test_non_periodic_map_is_windowed_and_carries_the_crops_moments(rng):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 2 * np.pi, 8 * np.pi, 64 * np.pi)
    h, _, _ = synthetic_surface(psd, 128, 1.0, rng)
    x = np.linspace(0, 1, 128)
    tilted = h + 0.05 * x[:, None]  # a tilt that detrending must remove
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the import's own 1 % check must not fire
        s = pf.psd_from_heightmap(tilted[:100, :100], 100 / 128, periodic=False)
    assert any("tukey" in n for n in s.notes) and any("plane" in n for n in s.notes)
    assert any("scaled by" in n for n in s.notes)  # the window's levels, set by the crop's two moments
    # the crop's own moments, computed here: detrended rms height, central-difference rms slope
    crop = tilted[:100, :100]
    X = np.stack([np.ones(10000), *[g.ravel() for g in np.meshgrid(np.arange(100), np.arange(100), indexing="ij")]], 1)
    d = crop.ravel() - X @ np.linalg.lstsq(X, crop.ravel(), rcond=None)[0]
    gx, gy = np.gradient(d.reshape(100, 100), 1 / 128)
    assert s.psd.rms_height == pytest.approx(np.sqrt(np.mean(d * d)), rel=1e-6)
    assert s.slope_definition == "central differences"
    # the spectrum under the same differences (J0 kernel vs the modes' own sin^2: measured 0.1 %)
    assert s.rms_slope_spectrum == pytest.approx(np.sqrt(np.mean(gx**2 + gy**2)), rel=0.01)
    assert "central differences on both sides" in s.describe()


def test_height_map_errors():
    with pytest.raises(ValueError, match="2-D array"):
        pf.psd_from_heightmap(np.zeros(10), 1.0)
    with pytest.raises(ValueError, match="flat"):
        pf.psd_from_heightmap(np.ones((16, 16)), 1.0)
    with pytest.raises(ValueError, match="size"):
        pf.psd_from_heightmap(np.random.default_rng(0).random((16, 16)), -1.0)
    with pytest.raises(ValueError, match="bins_per_decade"):
        pf.psd_from_heightmap(np.random.default_rng(0).random((16, 16)), 1.0, bins_per_decade=2)
    with pytest.raises(ValueError, match="window"):
        pf.psd_from_heightmap(np.random.default_rng(0).random((16, 16)), 1.0, window="kaiser")
    with pytest.raises(ValueError, match="periodic must be True or False"):  # "False" is not taken as true
        pf.psd_from_heightmap(np.random.default_rng(0).random((16, 16)), 1.0, periodic="False")
    with pytest.raises(ValueError, match="periodic must be True or False"):
        pf.psd_from_profiles(np.random.default_rng(0).random(64), 1.0, periodic="yes")


def test_read_heightmap_text_and_npy(tmp_path, rng):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 2 * np.pi, 8 * np.pi, 32 * np.pi)  # inside N = 64's Nyquist
    h, _, _ = synthetic_surface(psd, 64, 1.0, rng)
    np.save(tmp_path / "h.npy", h)
    np.savetxt(tmp_path / "h.txt", h)
    a = pf.read_heightmap(tmp_path / "h.npy", 1.0, periodic=True)
    b = pf.read_heightmap(str(tmp_path / "h.txt"), 1.0, periodic=True)
    np.testing.assert_allclose(a.psd.values, b.psd.values, rtol=1e-10)  # text keeps 18 digits
    with pytest.raises(ValueError, match="no such file"):
        pf.read_heightmap(tmp_path / "missing.npy", 1.0)


# -- line scans and contact.engineering ----------------------------------------------------------------
def test_profiles_of_a_bem_surface():
    """Rows and columns of BEM surface 1 as 1024 periodic line scans, 1-D PSD Abel-inverted numerically."""
    d = np.load(os.path.join(DATA, "surfaces", "surface_H0.8_seed1_modes.npz"))
    N = 256
    A = np.zeros((N, N), complex)
    A[np.ix_(d["k"] % N, d["k"] % N)] = d["hq"]
    h = np.real(np.fft.ifft2(A) * N * N)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = pf.psd_from_profiles(np.concatenate([h, h.T]), 1.0, periodic=True)
    # the full-gradient slope from scans (sqrt 2 rms dh/dx) is the surface's 0.1 to its anisotropy (~1 %)
    assert s.rms_slope_data == pytest.approx(0.1, rel=0.02)
    # one realisation: the 1-D PSD scatters and its inversion amplifies that; measured -0.8 % slope, +5 % height
    assert s.psd.rms_slope == pytest.approx(0.1, rel=0.03)
    assert s.psd.rms_height == pytest.approx(s.rms_height_data, rel=0.08)


def _write_ce_csv(path, series):
    header = [
        "Subject type",
        "Subject name",
        "Creator",
        "Instrument name",
        "Instrument type",
        "Instrument parameters",
        "Function name",
        "Data series",
        "Wavevector (m⁻¹)",
        "PSD (m³)",
        "standard error of PSD (m³)",
        "comment",
    ]
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(";".join(header) + "\n")
        for name, q, y in series:
            for qi, yi in zip(q, y):
                fh.write(f"measurement;s1;me;;;{{}};Power spectrum;{name};{float(qi)!r};{float(yi)!r};;\n")


def test_contact_engineering_csv_round_trip(tmp_path):
    """Persson's C -> the export's 'q/π × 2D PSD' (Y = q C_iso/pi) and '1D PSD along x' series -> back."""
    q = np.geomspace(REF.q_l, REF.q_s, 120)[:-1]
    C = REF.C(q)
    Y = q * (2 * np.pi) ** 2 * C / np.pi
    C1 = abel_forward(REF, q)
    path = tmp_path / "power-spectrum.csv"
    _write_ce_csv(path, [("q/π × 2D PSD", q, Y), ("1D PSD along x", q, C1), ("q/π × 2D PSD", [q[0]], ["nan"])])
    s = pf.read_contact_engineering_csv(path)
    np.testing.assert_allclose(s.psd.values, C, rtol=1e-13)  # repr() of floats round-trips exactly
    assert any("dropped" in n for n in s.notes)
    s1 = pf.read_contact_engineering_csv(path, series="1D PSD along x")
    # the table stops at 0.97 q_s (the top 3 % of the band carry ~1 % of <|grad h|^2>): measured -1.3 %
    assert s1.psd.rms_slope == pytest.approx(REF.rms_slope, rel=0.02)
    with pytest.raises(ValueError, match="series must be one of"):
        pf.read_contact_engineering_csv(path, series="2D PSD")
    bad = tmp_path / "bad.csv"
    bad.write_text("q,C\n1,2\n")
    with pytest.raises(ValueError, match="not a contact.engineering"):
        pf.read_contact_engineering_csv(bad)


def test_surface_topography_objects(rng):
    st = pytest.importorskip("SurfaceTopography")
    h, rms_h, rms_s = synthetic_surface(REF, 128, 1.0, rng)
    topo = st.Topography(h, (1.0, 1.0), periodic=True)
    s = pf.from_surface_topography(topo)
    assert s.psd.rms_height == pytest.approx(rms_h, rel=0.01)
    assert s.psd.rms_slope == pytest.approx(rms_s, rel=0.01)
    # the trap: SurfaceTopography's power_spectrum_from_area is C_iso = (2 pi)^2 C
    q, C_iso = topo.power_spectrum_from_area()
    m = np.isfinite(C_iso) & (C_iso > 0) & (q > 0)
    wrong = pf.TabulatedPSD(q[m], C_iso[m])
    right = pf.TabulatedPSD(q[m], C_iso[m], convention="iso2d")
    assert wrong.rms_slope / right.rms_slope == pytest.approx(2 * np.pi, rel=1e-12)
    assert right.rms_slope == pytest.approx(rms_s, rel=0.03)  # its own binning, not ours
    line = st.UniformLineScan(h[0], 1.0, periodic=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s1 = pf.from_surface_topography(line)
    assert s1.source.startswith("SurfaceTopography UniformLineScan")
    with pytest.raises(ValueError, match="topography must be"):
        pf.from_surface_topography(object())


def _spectrum_csv(path):
    psd = pf.SelfAffinePSD.from_rms_slope(0.1, 0.8, 1.0, 2.0, 128.0)
    q = np.geomspace(1.0, 128.0, 40)
    np.savetxt(path, np.column_stack((q, psd.C(q))), delimiter=",", header="q,C", comments="")


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
