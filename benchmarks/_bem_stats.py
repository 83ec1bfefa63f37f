"""Gap-field statistics in the format of ``data/bem/gap_histograms_H0.8.csv``, and Kolmogorov-Smirnov distances.

The gap histogram counts the NON-contact cells only: 60 bins on [0, 8 h_rms], density = count / (N^2 dg), so that
sum(density dg) = 1 - contact_fraction - (the fraction of cells with a gap above 8 h_rms).  Distributions over the
non-contact area are compared through their CDFs at the bin edges, each normalised to 1 at the last edge (the
Kolmogorov-Smirnov distance sup |F_a - F_b| evaluated on the edges).
"""

from __future__ import annotations

import numpy as np

BINS, UPPER = 60, 8.0  # 60 bins on [0, 8 h_rms]


def gap_histogram(gap, hrms, bins=BINS, upper=UPPER):
    """(edges, density) of the gaps g > 0 of a field (g = 0 in contact), density per unit gap over the whole area."""
    g = np.asarray(gap, dtype=float)
    if not np.all(np.isfinite(g)) or g.min(initial=0.0) < 0:
        raise ValueError("gap must be finite and >= 0 (0 in contact)")
    if not (np.isfinite(hrms) and hrms > 0):
        raise ValueError(f"hrms must be finite and > 0, got {hrms!r}")
    if int(bins) != bins or bins < 1:
        raise ValueError(f"bins must be a positive integer, got {bins!r}")
    edges = np.linspace(0.0, upper * hrms, int(bins) + 1)
    counts, _ = np.histogram(g[g > 0], bins=edges)
    return edges, counts / (g.size * np.diff(edges))


def gap_statistics(gap, hrms):
    """Contact fraction, mean gap and gap std over the whole area, and the histogram of the non-contact gaps."""
    g = np.asarray(gap, dtype=float)
    edges, density = gap_histogram(g, hrms)
    return dict(
        contact_fraction=float(np.mean(g == 0)),
        mean_gap=float(g.mean()),
        gap_std=float(g.std()),
        hrms=float(hrms),
        edges=edges,
        density=density,
    )


def histogram_cdf(edges, density):
    """The CDF of a histogram at its edges, normalised to 1 at the last edge (0 at the first)."""
    edges, density = np.asarray(edges, dtype=float), np.asarray(density, dtype=float)
    if edges.ndim != 1 or density.shape != (edges.size - 1,):
        raise ValueError(f"need len(edges) = len(density) + 1, got {edges.shape} and {density.shape}")
    if np.any(np.diff(edges) <= 0) or np.any(density < 0):
        raise ValueError("edges must increase and density must be >= 0")
    mass = np.concatenate(([0.0], np.cumsum(density * np.diff(edges))))
    if mass[-1] <= 0:
        raise ValueError("the histogram holds no mass")
    return mass / mass[-1]


def ks_histograms(edges, density_a, density_b):
    """Kolmogorov-Smirnov distance between two histograms on the same edges (their normalised CDFs at the edges)."""
    return float(np.max(np.abs(histogram_cdf(edges, density_a) - histogram_cdf(edges, density_b))))
