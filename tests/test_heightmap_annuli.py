"""The spectrum of a height map is one point per annulus of modes, sorted in q, each within the sampling scatter of
the spectrum the map was drawn from (a random periodic map with Gaussian mode amplitudes); it used to be a
piecewise law with two points per annulus whose first annuli jumped by 2-3 decades."""

import numpy as np
import pytest
from scipy.stats import gamma

import persson_fp as pf
from persson_fp.surfaces.annuli import LOW, _edges

N, L = 256, 1e-3  # a 1 mm periodic map, 256 points a side
DQ = 2 * np.pi / L
INPUT = pf.SelfAffinePSD.from_rms_slope(0.15, 0.8, DQ, 8 * DQ, np.pi * N / L)  # roll-off, power law to Nyquist


def random_map(seed):
    """White noise filtered to E|h_k|^2 = C(|q_k|) dq^2 (complex Gaussian modes, h_-k = conj(h_k))."""
    rng = np.random.default_rng(seed)
    k = np.fft.fftfreq(N, d=1.0 / N)
    q = DQ * np.hypot(*np.meshgrid(k, k, indexing="ij"))
    C = np.where((q > 0) & (q <= INPUT.q_s), INPUT.C(np.clip(q, INPUT.q_l, INPUT.q_s)), 0.0)
    return np.real(np.fft.ifft2(np.fft.fft2(rng.standard_normal((N, N))) * np.sqrt(C) * N * DQ)), q


@pytest.mark.parametrize("seed", [1, 2])
def test_annulus_points_are_sorted_and_within_the_sampling_scatter_of_the_input(seed):
    h, q_modes = random_map(seed)
    psd = pf.psd_from_heightmap(h, L, periodic=True).psd
    q, C = psd.q, psd.values
    assert np.all(np.diff(q) / q[1:] > 1e-3)  # strictly increasing, no repeated q (the sawtooth had q, q(1 - 1e-7))
    # one point per annulus of modes: the annuli the import groups the modes into, counted here
    radii = q_modes[q_modes > 0]
    edges = _edges(radii.min(), radii.max(), DQ, 20)  # the import's annuli (from the lowest to the highest radius)
    carried = radii[radii <= INPUT.q_s * (1 + 1e-12)]  # the modes drawn with power (none beyond Nyquist here)
    counts = np.histogram(carried, bins=np.append(edges[:-1], edges[-1] * (1 + 1e-9)))[0]
    assert q.size == np.count_nonzero(counts)
    at = np.clip(np.searchsorted(edges, q * (1 + 1e-9), side="right") - 1, 0, counts.size - 1)
    n = np.maximum(counts[at], 1).astype(float)  # the modes behind each point (the band's end: its last annulus)
    # the annulus mean of |h_k|^2 / (C dq^2) is a mean of n/2 independent Exp(1) (the pairs h_k, h_-k): its
    # 1e-6 and 1 - 1e-6 quantiles, widened by 3 % for C's curvature across an annulus and the import's tilt
    # (|g| < 0.02 here) and the lift of the lowest radii (q < LOW q_l, left out), bound ln(C / C_input)
    k = n / 2
    lo, hi = np.log(gamma.ppf(1e-6, k, scale=1 / k)) - 0.03, np.log(gamma.ppf(1 - 1e-6, k, scale=1 / k)) + 0.03
    test = (q >= LOW * q[0]) & (q < INPUT.q_s * 0.95)  # the last point: the band's end, a part-empty annulus
    r = np.log(C / INPUT.C(np.minimum(q, INPUT.q_s)))
    assert test.sum() >= 20
    assert np.all(((r >= lo) & (r <= hi))[test]), (q[test], r[test], lo[test], hi[test])
    # no jump between neighbours beyond their joint scatter (5 sigma of ln, sigma^2 = 1/k each, plus 3 %)
    pair = test[:-1] & test[1:]
    jump = np.abs(np.diff(r))
    assert np.all(jump[pair] <= (5 * np.sqrt(1 / k[:-1] + 1 / k[1:]) + 0.03)[pair])
    # and the two-decade sawtooth is gone everywhere, the lowest radii included
    assert np.max(np.abs(np.diff(np.log10(C[q < 0.95 * INPUT.q_s])))) < 1.0
