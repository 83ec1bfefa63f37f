"""MeasuredSurface.describe() names each rms slope and what each percentage compares; its numbers against the
height array's own differences and a quadrature of the spectrum written here."""

import re
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.special import j0

import persson_fp as pf
from persson_fp.surfaces.heightmap import ImplausibleSlopeWarning

sys.path.insert(0, str(Path(__file__).parent))
from test_surface import synthetic_surface  # noqa: E402

PSD = pf.SelfAffinePSD.from_rms_slope(0.2, 0.8, 2 * np.pi, 8 * np.pi, 256 * np.pi)


def _number(text, pattern):
    return float(re.search(pattern, text).group(1))


def _band_integral(psd, f):
    """int_{q_l}^{q_s} f(q) C(q) dq, one adaptive quadrature per interval of the table (C is smooth inside each)."""
    nodes = np.unique(np.concatenate(([psd.q_l], psd.q[(psd.q > psd.q_l) & (psd.q < psd.q_s)], [psd.q_s])))
    return sum(
        quad(lambda q: f(q) * float(psd.C(q)), a, b, epsabs=0, epsrel=1e-9, limit=200)[0]
        for a, b in zip(nodes[:-1], nodes[1:])
    )


def _plane_removed(h):
    x, y = np.meshgrid(*[np.arange(n) - (n - 1) / 2 for n in h.shape], indexing="ij")
    X = np.column_stack((np.ones(h.size), x.ravel(), y.ravel()))
    return h - (X @ np.linalg.lstsq(X, h.ravel(), rcond=None)[0]).reshape(h.shape)


def test_describe_names_each_slope_of_a_measured_map_and_its_numbers_are_the_independent_ones(rng):
    h, _, _ = synthetic_surface(PSD, 512, 1.0, rng)
    crop, L = h[:256, :256], 0.5  # a crop: not periodic, detrended and windowed
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        s = pf.psd_from_heightmap(crop, L)
    text = s.describe()
    psd = s.psd
    # the spectrum's own: integrals over its band, exact derivative
    spec_h = np.sqrt(2 * np.pi * _band_integral(psd, lambda q: q))
    spec_s = np.sqrt(2 * np.pi * _band_integral(psd, lambda q: q**3))
    line = next(ln for ln in text.splitlines() if ln.startswith("rms height"))
    assert "the spectrum's, sqrt(2 pi int q C dq) and sqrt(2 pi int q^3 C dq) (exact derivative) over q in" in line
    assert _number(line, r"rms height ([\d.e+-]+) length") == pytest.approx(spec_h, rel=1e-5)
    assert _number(line, r"rms slope ([\d.e+-]+) \(the spectrum's") == pytest.approx(spec_s, rel=1e-5)
    # the data's: numpy.gradient of the plane-removed heights
    d = L / 256
    hd = _plane_removed(crop)
    data_s = np.sqrt(sum(np.mean(np.gradient(hd, d, axis=a) ** 2) for a in (0, 1)))
    line = next(ln for ln in text.splitlines() if "rms slope" in ln and ln.startswith("height data"))
    assert "central differences of the heights (numpy.gradient)" in line
    assert _number(line, r"rms slope ([\d.e+-]+) by central differences") == pytest.approx(data_s, rel=1e-5)
    assert _number(text, r"rms height ([\d.e+-]+) length \(the detrended heights\)") == pytest.approx(
        np.sqrt(np.mean(hd**2)), rel=1e-5
    )
    # the third number: the spectrum through the same differences, sum_a sin^2(q_a d) / d^2 averaged over angle
    cd = np.sqrt(2 * np.pi * _band_integral(psd, lambda q: q * 2 * (1 - j0(2 * q * d)) / (2 * d * d)))
    assert _number(line, r"against ([\d.e+-]+), the spectrum seen through the same differences") == pytest.approx(
        cd, rel=1e-5
    )
    # the percentage compares that third number with the data's, and says so
    pct = _number(line, r"spectrum / data - 1 = ([+-][\d.]+)%")
    assert pct == pytest.approx(100 * (cd / data_s - 1), abs=0.006)
    assert spec_s > 1.03 * cd  # the two slopes differ (here by ~6 %): which is which matters


def test_describe_of_a_periodic_map_gives_the_spectral_slope_on_both_sides(rng):
    h, rms_h, rms_s = synthetic_surface(PSD, 256, 1.0, rng)  # the construction's own lattice sums
    s = pf.psd_from_heightmap(h, 1.0, periodic=True)
    text = s.describe()
    line = next(ln for ln in text.splitlines() if "rms slope" in ln and ln.startswith("height data"))
    assert "spectral derivative of the periodic heights" in line
    assert _number(line, r"rms slope ([\d.e+-]+) by the spectral") == pytest.approx(rms_s, rel=1e-5)
    spec_s = np.sqrt(2 * np.pi * _band_integral(s.psd, lambda q: q**3))
    assert _number(line, r"against the spectrum's ([\d.e+-]+)") == pytest.approx(spec_s, rel=1e-5)
    assert _number(line, r"= ([+-][\d.]+)%") == pytest.approx(100 * (spec_s / rms_s - 1), abs=0.006)


def test_describe_names_the_length_unit_and_refuses_an_empty_one():
    n, L = 64, 1e-3
    rng = np.random.default_rng(3)
    h = rng.standard_normal((n, n)) * 1e-7
    surf = pf.psd_from_heightmap(h, L, periodic=True)
    text = surf.describe("m")
    assert "rad/m" in text and f"{surf.psd.rms_height:.6g} m," in text and "length" not in text
    with pytest.raises(ValueError, match="length_unit"):
        surf.describe("  ")


@pytest.mark.parametrize("scale, word", [(1e6, "steep"), (1e-6, "flat")])
def test_heightmap_in_other_units_than_its_size_warns_naming_the_mix_up(scale, word):
    """A map whose rms slope (finite differences here, the oracle) is outside 1e-4..5 warns; the spectrum is kept."""
    n, L = 64, 1e-3
    h = 1e-7 * np.random.default_rng(5).standard_normal((n, n))  # white heights: rms slope ~ 1e-2
    gx, gy = np.gradient(h * scale, L / n)
    slope = np.sqrt(np.mean(gx**2 + gy**2))  # central differences: below the spectral slope, same order
    assert not 1e-4 <= slope <= 5
    with pytest.warns(ImplausibleSlopeWarning, match=f"too {word}.*different units"):
        surf = pf.psd_from_heightmap(h * scale, L, periodic=True)
    assert 1 < surf.rms_slope_data / slope < 3  # white noise: the spectral derivative sees the highest modes fully
    with warnings.catch_warnings():
        warnings.simplefilter("error", ImplausibleSlopeWarning)
        pf.psd_from_heightmap(h, L, periodic=True)  # slope 0.19: plausible, no warning
