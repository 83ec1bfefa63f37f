"""Property test of height-map import: the spectrum carries the map's own rms height and slope.

60 random self-affine maps made here by FFT filtering of white noise (H in [0.2, 0.9], with and without a roll-off,
with and without a short-wavelength cut-off, square and rectangular, 32-256 points a side), imported as periodic
maps (30) and as non-periodic crops (30, detrended and windowed).  The references are the maps' own moments,
computed here from the heights: the mean square of the (detrended) heights, and the rms gradient by the exact
spectral derivative (periodic) or by central differences (``numpy.gradient``, non-periodic).
"""

import warnings

import numpy as np
import pytest

import persson_fp as pf


def fft_map(rng, shape, size, H, q_r, q_s):
    """White noise filtered by sqrt(C), C = q^(-2(1+H)) above q_r (flat below), zero above q_s (rad/length)."""
    axes = [2 * np.pi * np.fft.fftfreq(n, d=L / n) for n, L in zip(shape, size)]
    q = np.hypot(*np.meshgrid(*axes, indexing="ij"))
    C = np.where(q > 0, np.maximum(q, max(q_r, q[q > 0].min())) ** (-2 * (1 + H)), 0.0)
    C[q > q_s] = 0.0
    return np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal(shape)) * np.sqrt(C)))


def spectral_slope(h, size):
    axes = [2 * np.pi * np.fft.fftfreq(n, d=L / n) for n, L in zip(h.shape, size)]
    q2 = sum(g**2 for g in np.meshgrid(*axes, indexing="ij"))
    return np.sqrt(np.sum(q2 * np.abs(np.fft.fft2(h) / h.size) ** 2))


def detrended(h):
    grids = np.meshgrid(*[np.arange(n) for n in h.shape], indexing="ij")
    X = np.stack([np.ones(h.size)] + [g.ravel() for g in grids], axis=1)
    return (h.ravel() - X @ np.linalg.lstsq(X, h.ravel(), rcond=None)[0]).reshape(h.shape)


def cases(n):
    rng = np.random.default_rng(20261124)
    for i in range(n):
        N = int(rng.choice([64, 128, 256]))
        shape = (N, N) if i % 5 else (N, N // 2)  # every fifth map rectangular
        size = (1.0, shape[1] / N)
        H = float(rng.uniform(0.2, 0.9))
        q_r = 2 * np.pi * [1, 1, 4, 16][i % 4]  # no roll-off in half of them
        q_s = np.inf if i % 3 else np.pi * N / 2  # a short-wavelength cut-off in a third
        yield i, rng, shape, size, H, q_r, q_s


@pytest.mark.parametrize("case", list(cases(30)), ids=lambda c: f"map{c[0]}")
def test_periodic_map_carries_its_rms_height_and_slope(case):
    _, rng, shape, size, H, q_r, q_s = case
    h = fft_map(rng, shape, size, H, q_r, q_s)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the import's own 1 % check must not fire
        s = pf.psd_from_heightmap(h, size, periodic=True)
    d = h - h.mean()
    # <h^2>: each annulus' power is carried exactly (round-off and the 1e-7 joins between annuli)
    assert s.psd.rms_height == pytest.approx(np.sqrt(np.mean(d * d)), rel=1e-6)
    # <|grad h|^2>: exact in the first annuli, the trend of the annulus means above (measured max 0.5 %)
    assert s.psd.rms_slope == pytest.approx(spectral_slope(d, size), rel=0.01)
    assert s.slope_definition == "spectral derivative"
    # the band is the data's: from the lowest mode 2 pi / L_max to the lattice's corner
    assert s.psd.q_l == pytest.approx(2 * np.pi / max(size), rel=1e-12)
    corner = np.hypot(np.pi * shape[0] / size[0], np.pi * shape[1] / size[1])
    assert s.psd.q_s <= corner * (1 + 1e-12)


@pytest.mark.parametrize("case", list(cases(30)), ids=lambda c: f"crop{c[0]}")
def test_windowed_crop_carries_its_rms_height_and_slope(case):
    i, rng, shape, size, H, q_r, q_s = case
    big = fft_map(rng, (2 * shape[0], 2 * shape[1]), (2 * size[0], 2 * size[1]), H, q_r, q_s)
    crop = big[: shape[0] * 3 // 4, : shape[1] * 3 // 4]  # a non-periodic piece
    L = (size[0] * 3 / 4, size[1] * 3 / 4)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        s = pf.psd_from_heightmap(crop, L)  # default: not periodic (detrended, Tukey window)
    d = detrended(crop)
    assert s.psd.rms_height == pytest.approx(np.sqrt(np.mean(d * d)), rel=1e-6)  # set by the calibration
    g = np.gradient(d, L[0] / crop.shape[0], L[1] / crop.shape[1])
    err = s.rms_slope_spectrum / np.sqrt(np.mean(g[0] ** 2 + g[1] ** 2)) - 1
    assert s.slope_definition == "central differences"
    if H > 0.7 and q_r == 2 * np.pi:
        # what is lost: no roll-off inside the map and a steep spectrum, so the longest waves carry the height and
        # much of the slope, and the window adds h grad(w) to the slope (measured up to +44 %): the import warns
        assert abs(err) <= 0.01 or any("differ from the height data" in str(w.message) for w in caught)
    else:
        # the same central differences on the spectrum: J0 kernel vs the modes' own sin^2 (measured max 1.3 %)
        assert abs(err) < 0.03


def test_map_without_roll_off_keeps_its_rms_height(rng):
    """512^2, H = 0.7, rms slope 0.2, L = 1 mm, no roll-off: the spectrum used to extend to pi / L (+56 %)."""
    h = fft_map(rng, (512, 512), (1e-3, 1e-3), 0.7, 0.0, np.inf)
    h *= 0.2 / spectral_slope(h, (1e-3, 1e-3))
    s = pf.psd_from_heightmap(h, 1e-3, periodic=True)
    assert s.psd.rms_height == pytest.approx(np.std(h), rel=1e-6)
    assert s.psd.rms_slope == pytest.approx(0.2, rel=0.01)
    assert s.psd.q_l == pytest.approx(2 * np.pi / 1e-3, rel=1e-12)
