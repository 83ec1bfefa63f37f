r"""Measured surfaces in: height maps, line scans, contact.engineering exports, SurfaceTopography objects.

Every importer returns a :class:`~persson_fp.MeasuredSurface`: Persson's isotropic spectrum as a
:class:`~persson_fp.TabulatedPSD` (convention ``"persson"``, :math:`\langle h^2\rangle =
2\pi\int qC\,dq`, Xu et al. tutorial ``eq:variance_h_continuous``), the rms height and slope of the height data
themselves, and notes on what was dropped.  The import compares the spectrum's rms height and slope with the
height data's and warns when they differ by more than 1 %.  Conventions of the spectra read are those of
Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5 (2017) 013001 (:mod:`persson_fp.surfaces.conventions`).

Spectrum of a height map (periodic square or rectangle :math:`L_x\times L_y`, :math:`N_x\times N_y` points):
:math:`\hat h_k = N^{-1}\sum h\,e^{-i q_k\cdot x}`, :math:`C(q_k) = \frac{L_xL_y}{(2\pi)^2}|\hat h_k|^2`, so
that :math:`\langle h^2\rangle = \sum_k C(q_k)\,\Delta^2q` exactly.  Radial averaging
(:func:`persson_fp.surfaces.annuli.annulus_table`): the band is the data's, from the lowest mode radius
:math:`2\pi/L` to the highest that carries power (at most the lattice's corner); the table has one point per
annulus of modes, their mean C at their mean radius, sorted in q; a lift of the lowest radii (fading out by
``4 * 2 pi / L``: the cells of the lowest modes reach below :math:`2\pi/L`) and a small tilt make the spectrum
carry the map's :math:`\langle h^2\rangle` and :math:`\langle|\nabla h|^2\rangle` (to round-off on periodic
self-affine maps with and without roll-off, H in [0.2, 0.9]; tests); the notes give the lift and the tilt.
Beyond the Nyquist circle the annuli are incomplete; the notes
give the share of the moments they carry.  A narrower band is a :class:`~persson_fp.TabulatedPSD` of the same
table with ``q_l``/``q_s`` inside it.

rms slope, the same definition on both sides: for periodic data the exact (spectral) derivative,
:math:`\sqrt{\sum_k q_k^2|\hat h_k|^2}` against :math:`\sqrt{2\pi\int q^3C\,dq}`; for non-periodic data, which
have no periodic continuation, central differences (``numpy.gradient``) against the same differences applied
to the spectrum (:func:`persson_fp.surfaces.annuli.central_difference_slope`).  Non-periodic data are detrended
(plane) and windowed (Tukey by default, normalised to keep the power).  The window weights the map's centre, so
its estimate of the longest wavelengths varies by 10-40 % from crop to crop of one self-affine surface: the power
below :math:`4\cdot 2\pi/L` is scaled so that the spectrum carries the data's :math:`\langle h^2\rangle` (the
notes give the factor); the rms slope is carried within 3 % (tests).

This module imports no solver and never imports SurfaceTopography
(:func:`~persson_fp.from_surface_topography` only reads the object it is given).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from persson_fp._validate import as_float_array, as_positive_scalar
from persson_fp.surfaces.annuli import LOW, annulus_table, central_difference_slope
from persson_fp.surfaces.tabulated import TabulatedPSD

__all__ = [
    "MeasuredSurface",
    "psd_from_heightmap",
    "psd_from_profiles",
]

RMS_TOLERANCE = 0.01
"""Relative difference of rms height or slope (spectrum vs height data) above which the import warns."""

PLAUSIBLE_SLOPE = (1e-4, 5.0)
"""rms slopes of measured surfaces (polished to rough: 1e-4 to ~3).  Outside, the import warns
(:class:`ImplausibleSlopeWarning`): heights and size are probably in different units -- heights in micrometres with
the size in metres make the slope 1e6 too steep, the reverse 1e6 too flat."""


class ImplausibleSlopeWarning(UserWarning):
    """A height map whose rms slope is outside :data:`PLAUSIBLE_SLOPE`: probably heights and size in different
    units (the spectrum is still returned)."""


TUKEY_ALPHA = 0.5
"""Tapered share of the Tukey window of non-periodic maps (a cosine taper over a quarter of each side)."""

LONG_WAVES = 4
"""Windowed maps: the power below ``LONG_WAVES`` times 2 pi / L is scaled to carry the data's <h^2>."""

LONG_SHARE = 0.5
"""... or below the q that holds this share of the windowed power, where that is higher."""


@dataclass(frozen=True)
class MeasuredSurface:
    """A surface imported from data.

    Attributes
    ----------
    psd : TabulatedPSD
        Persson's isotropic spectrum (q in rad/length, C in length^4).
    source : str
        What was read (``"height map"``, ``"line scans"``, ``"contact.engineering CSV"`` ...).
    rms_height_data, rms_slope_data : float or None
        rms height (length) and rms slope (dimensionless, full gradient :math:`\\sqrt{\\langle|\\nabla h|^2\\rangle}`)
        of the height data after detrending, None where there are no heights (a PSD file).
    notes : tuple of str
        What the import dropped or assumed, one line each.
    grid_step : tuple of float or None, length
        Grid spacing of central-difference slopes (non-periodic data); None: the slopes are spectral.
    """

    psd: TabulatedPSD
    source: str
    rms_height_data: float | None = None
    rms_slope_data: float | None = None
    notes: tuple = field(default_factory=tuple)
    grid_step: tuple | None = None

    @property
    def slope_definition(self) -> str:
        """How both rms slopes are taken: ``"spectral derivative"`` or ``"central differences"``."""
        return "spectral derivative" if self.grid_step is None else "central differences"

    @property
    def rms_slope_spectrum(self) -> float:
        """rms slope of the spectrum by :attr:`slope_definition` (dimensionless): the value ``rms_slope_data``
        is compared with (``psd.rms_slope`` is always the spectral one)."""
        if self.grid_step is None:
            return float(self.psd.rms_slope)
        return central_difference_slope(self.psd, self.grid_step)

    @property
    def rms_errors(self) -> tuple[float, float] | None:
        """(rms height, rms slope) of the spectrum relative to the height data, minus 1; None without heights."""
        if self.rms_height_data is None:
            return None
        return self.psd.rms_height / self.rms_height_data - 1.0, self.rms_slope_spectrum / self.rms_slope_data - 1.0

    def describe(self, length_unit: str = "length") -> str:
        r"""A few lines for a report or a CSV header: source, convention, each rms value named with how it is taken.

        The spectrum's rms height and slope are its integrals over the band :math:`[q_l, q_s]`,
        :math:`\sqrt{2\pi\int qC\,dq}` and :math:`\sqrt{2\pi\int q^3C\,dq}` (exact derivative).  The height data's
        rms slope is the spectral derivative of periodic data, or central differences (``numpy.gradient``) of
        non-periodic data; it is then compared with the spectrum seen through the same differences
        (:func:`~persson_fp.surfaces.annuli.central_difference_slope`), a third number, which the percentage
        compares, so each percentage is "spectrum / data - 1" of one definition.

        Parameters
        ----------
        length_unit : str
            The name of the heights' and the size's unit ("m", "um", ...): lengths are written in it and wavenumbers
            in rad per it.  Default "length" (any consistent unit).

        Returns
        -------
        str
            Lines separated by newlines: the source, the spectrum's input convention and band (rad/length), its rms
            height (length) and slope, the height data's with the definition of each and their relative differences,
            the notes.
        """
        if not isinstance(length_unit, str) or not length_unit.strip():
            raise ValueError(f"length_unit must be a non-empty string (the name of a unit), got {length_unit!r}")
        p, L = self.psd, length_unit.strip()
        band = f"over q in [{p.q_l:.6g}, {p.q_s:.6g}] rad/{L}"
        lines = [
            f"source: {self.source}",
            f"spectrum: Persson's isotropic C(q) (<h^2> = 2 pi int q C dq), input convention {p.convention!r}, "
            f"{p.q.size} points, q in [{p.q_l:.6g}, {p.q_s:.6g}] rad/{L}",
            f"rms height {p.rms_height:.6g} {L}, rms slope {p.rms_slope:.6g} (the spectrum's, "
            f"sqrt(2 pi int q C dq) and sqrt(2 pi int q^3 C dq) (exact derivative) {band})",
        ]
        if self.rms_height_data is not None:
            eh, es = self.rms_errors
            lines.append(
                f"height data: rms height {self.rms_height_data:.6g} {L} (the detrended heights); "
                f"spectrum / data - 1 = {eh:+.2%}"
            )
            if self.grid_step is None:
                lines.append(
                    f"height data: rms slope {self.rms_slope_data:.6g} by the spectral derivative of the periodic "
                    f"heights (sqrt(sum q^2 |h_q|^2)), against the spectrum's {self.rms_slope_spectrum:.6g}: "
                    f"spectrum / data - 1 = {es:+.2%}"
                )
            else:
                lines.append(
                    f"height data: rms slope {self.rms_slope_data:.6g} by central differences of the heights "
                    f"(numpy.gradient), against {self.rms_slope_spectrum:.6g}, the spectrum seen through the same "
                    f"differences (sqrt(2 pi int q C K dq), K(q) = sum_a (1 - J0(2 q d_a)) / (2 d_a^2)): "
                    f"spectrum / data - 1 = {es:+.2%}; central differences on both sides, so this slope is below the "
                    "exact-derivative one"
                )
        lines.extend(f"note: {n}" for n in self.notes)
        return "\n".join(lines)


def _check_rms(surface: MeasuredSurface) -> MeasuredSurface:
    slope = surface.rms_slope_data
    lo, hi = PLAUSIBLE_SLOPE
    if slope is not None and not lo <= slope <= hi:
        way = "steep" if slope > hi else "flat"
        likely = (
            "heights in a larger unit than the size (um heights with a size in m: 1e6 too steep)"
            if slope > hi
            else "heights in a smaller unit than the size (m heights with a size in um: 1e6 too flat)"
        )
        warnings.warn(
            f"the height map's rms slope is {slope:.3g}, too {way} for a measured surface ({lo:g} to ~3): the "
            f"heights and the size are probably in different units, {likely}; give both in one unit",
            ImplausibleSlopeWarning,
            stacklevel=3,
        )
    errs = surface.rms_errors
    if errs is not None and max(abs(errs[0]), abs(errs[1])) > RMS_TOLERANCE:
        warnings.warn(
            f"the imported spectrum's rms height / slope differ from the height data's by {errs[0]:+.2%} / "
            f"{errs[1]:+.2%} (more than {RMS_TOLERANCE:.0%}): the notes of the MeasuredSurface say what was dropped",
            UserWarning,
            stacklevel=3,
        )
    return surface


def _calibrate(power, q_axes, steps, h2, g2, notes):
    """Scale the windowed power (in place) so that the modes carry the data's <h^2> and central-difference
    <|grad h|^2>: one factor for the long waves, one for the rest (the window keeps the shape of each part).

    The window weights the map's centre, so its estimate of the longest wavelengths depends on where they sit.
    The long waves are those below ``LONG_WAVES`` 2 pi / L, or below the q holding ``LONG_SHARE`` of the power
    where that is higher.  Where the two factors are not both positive, only the long waves are scaled (<h^2>)."""
    qm = np.hypot(*q_axes)
    nz = qm > 0
    order = np.argsort(qm[nz])
    share = np.cumsum(power[nz][order]) / power.sum()
    q_cut = max(
        LONG_WAVES * max(np.min(np.abs(q[q != 0])) for q in q_axes),
        float(qm[nz][order][np.searchsorted(share, LONG_SHARE)]),
    )
    low = nz & (qm <= q_cut)
    high = nz & ~low
    k_fd = sum(np.sin(q * d) ** 2 / d**2 for q, d in zip(q_axes, steps))  # what np.gradient sees of each mode
    A = np.array([[power[low].sum(), power[high].sum()], [(k_fd * power)[low].sum(), (k_fd * power)[high].sum()]])
    f = np.linalg.solve(A, [h2, g2]) if abs(np.linalg.det(A)) > 0 else np.zeros(2)
    if np.all(f > 0):
        power[low] *= f[0]
        power[high] *= f[1]
        what = f"scaled by {f[0]:.3g} for the long waves q <= {q_cut:.6g} and {f[1]:.3g} above"
    else:
        f0 = (h2 - A[0, 1]) / A[0, 0]
        power[low] *= max(f0, 0.0) or 1.0
        what = f"of the long waves q <= {q_cut:.6g} scaled by {f0:.3g} (<h^2> only)"
    notes.append(
        f"window's power {what}, so that the spectrum carries the data's <h^2> and rms slope (the window weights "
        "the map's centre; the level of the longest waves is the uncertain part)"
    )


def _size(size, ndim):
    s = np.atleast_1d(as_float_array(size, "size"))  # (a bool, complex or string size is refused by name)
    if s.size == 1:
        s = np.repeat(s, ndim)
    if s.size != ndim:
        raise ValueError(f"size must be one length or {ndim} lengths (physical size of the data), got {size!r}")
    return tuple(as_positive_scalar(v, "size") for v in s)


def _window(n, kind):
    if kind is None or kind == "none":
        return np.ones(n)
    if kind == "hann":
        return np.hanning(n + 1)[:-1] if n > 1 else np.ones(1)  # periodic Hann: no zero at both ends
    if kind == "tukey":
        from scipy.signal.windows import tukey

        return tukey(n, TUKEY_ALPHA, sym=False)
    raise ValueError(f"window must be 'auto', 'tukey', 'hann' or None, got {kind!r}")


def _detrend(h, periodic):
    h = h - h.mean()
    if periodic:
        return h
    grids = np.meshgrid(*[np.arange(n) - (n - 1) / 2.0 for n in h.shape], indexing="ij")
    X = np.stack([g.ravel() for g in grids], axis=1)
    coef, *_ = np.linalg.lstsq(X, h.ravel(), rcond=None)
    return h - (X @ coef).reshape(h.shape)


def as_bool(value, name: str) -> bool:
    """``value`` as a bool; a ValueError for anything but True / False (a string "False" is not false)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise ValueError(f"{name} must be True or False, got {value!r}")


def _rms_slope_data(h, size, periodic):
    """rms of the full gradient: spectral for periodic data, central differences otherwise."""
    if periodic:
        hk = np.fft.fftn(h) / h.size
        q2 = sum(g**2 for g in _qgrid(h.shape, size))
        return float(np.sqrt(np.sum(q2 * np.abs(hk) ** 2)))
    g2 = 0.0
    for axis, (n, L) in enumerate(zip(h.shape, size)):
        g2 = g2 + np.mean(np.gradient(h, L / n, axis=axis) ** 2)
    return float(np.sqrt(g2))


def _qgrid(shape, size):
    return np.meshgrid(*[2.0 * np.pi * np.fft.fftfreq(n, d=L / n) for n, L in zip(shape, size)], indexing="ij")


def _radial_bins(q_mode, power, dq, q_max, bins_per_decade):
    """Annuli one lattice step dq wide at small q, log-spaced above.

    Returns (mean radius, power, edges) of the populated annuli (empty ones merged into the next)."""
    r = 10.0 ** (1.0 / bins_per_decade)
    edges = [0.5 * dq]
    while edges[-1] < q_max:
        step = max(dq, edges[-1] * (r - 1.0))
        edges.append(min(edges[-1] + step, q_max))
        if q_max - edges[-1] < 0.25 * step:
            edges[-1] = q_max
    edges = np.array(edges)
    idx = np.searchsorted(edges, q_mode, side="right") - 1
    # the top edge is the Nyquist wavenumber, where a mode lies: within round-off (1e-9) it is in the last annulus
    # (it fell in or out by the round-off of q_max, so that the table depended on the unit of length)
    idx = np.where((idx == edges.size - 1) & (q_mode <= edges[-1] * (1.0 + 1e-9)), edges.size - 2, idx)
    ok = (idx >= 0) & (idx < edges.size - 1)
    n = edges.size - 1
    P = np.bincount(idx[ok], weights=power[ok], minlength=n)
    count = np.bincount(idx[ok], minlength=n)
    qsum = np.bincount(idx[ok], weights=q_mode[ok], minlength=n)
    # merge empty annuli into the next populated one (their area goes with it)
    keep_edges = [edges[0]]
    q_out, P_out, n_out = [], [], []
    acc_P = acc_n = acc_q = 0.0
    for j in range(n):
        acc_P += P[j]
        acc_n += count[j]
        acc_q += qsum[j]
        if acc_n > 0 and (count[j] > 0):
            b = edges[j + 1]
            q_out.append(acc_q / acc_n)
            P_out.append(acc_P)
            n_out.append(acc_n)
            keep_edges.append(b)
            acc_P = acc_n = acc_q = 0.0
    return np.array(q_out), np.array(P_out), np.array(keep_edges), np.array(n_out)


def psd_from_heightmap(
    heights,
    size,
    *,
    periodic: bool = False,
    window: str | None = "auto",
    bins_per_decade: int = 20,
    source: str = "height map",
) -> MeasuredSurface:
    r"""Persson's isotropic spectrum of a 2-D height map (see the module docstring).

    Parameters
    ----------
    heights : array_like, shape (Nx, Ny), length
        Heights on a uniform grid (finite; no missing points: fill or crop them first).
    size : float or (float, float), length
        Physical size :math:`L_x` (and :math:`L_y`) of the map.
    periodic : bool
        True for periodic data (simulated surfaces); False (default, measurements): detrended (plane) and
        windowed.
    window : {"auto", "tukey", "hann", None}
        Window for non-periodic data ("auto": Tukey with a cosine taper over a quarter of each side when not
        periodic, none when periodic), normalised by its mean square so that the power is kept.
    bins_per_decade : int
        Log-spaced annuli per decade of q above the region where they are one lattice step wide (>= 4).
    source : str
        Description stored in :attr:`MeasuredSurface.source <persson_fp.MeasuredSurface>`.

    Returns
    -------
    MeasuredSurface
        Persson's spectrum (q in rad/length of the unit of ``size``, C in length^4), the rms height and slope
        of the data and notes on what was dropped; a ``UserWarning`` when the spectrum's rms height or slope
        differs from the data's by more than 1 %.

    Raises
    ------
    ValueError
        ``heights`` not 2-D with >= 4 points per side or flat, ``size`` not > 0, ``bins_per_decade`` < 4, an
        unknown ``window``, ``periodic`` not a bool.
    """
    h = as_float_array(heights, "heights")
    periodic = as_bool(periodic, "periodic")
    if h.ndim != 2 or min(h.shape) < 4:
        raise ValueError(f"heights must be a 2-D array with at least 4 points per side, got shape {h.shape}")
    if not isinstance(bins_per_decade, (int, np.integer)) or bins_per_decade < 4:
        raise ValueError(f"bins_per_decade must be an integer >= 4, got {bins_per_decade!r}")
    Lx, Ly = _size(size, 2)
    h = _detrend(h, periodic)
    if np.all(h == 0):
        raise ValueError("heights are flat (after removing the mean / plane): no roughness to import")
    rms_h = float(np.sqrt(np.mean(h * h)))
    rms_s = _rms_slope_data(h, (Lx, Ly), periodic)
    if window == "auto":
        window = None if periodic else "tukey"
    w = np.outer(_window(h.shape[0], window), _window(h.shape[1], window))
    hw = h * w / np.sqrt(np.mean(w * w))
    hk = np.fft.fft2(hw) / h.size
    QX, QY = _qgrid(h.shape, (Lx, Ly))
    qm = np.hypot(QX, QY).ravel()
    power = (np.abs(hk) ** 2).ravel()  # sum = <h^2> of the windowed data
    q_nyq = min(np.pi * h.shape[0] / Lx, np.pi * h.shape[1] / Ly)
    outside = qm > q_nyq
    out_h2 = power[outside].sum() / power.sum()
    out_g2 = np.sum((qm * qm * power)[outside]) / np.sum(qm * qm * power)
    notes = ["mean height (q = 0) removed" + ("" if periodic else ", plane detrended")]
    if window:
        notes.append(f"{window} window applied (normalised to keep the mean-square height)")
    if out_h2 > 1e-12:
        notes.append(
            f"modes beyond the Nyquist circle q > {q_nyq:.6g} (incomplete annuli, the lattice's corners) carry "
            f"{out_h2:.2%} of <h^2> and {out_g2:.2%} of <|grad h|^2>: C there is their power spread over the whole "
            "annulus, below the isotropic spectrum"
        )
    if window and not periodic:
        _calibrate(power, (QX.ravel(), QY.ravel()), (Lx / h.shape[0], Ly / h.shape[1]), rms_h**2, rms_s**2, notes)
    nz = qm > 0
    q, C, (f0, g, F) = annulus_table(qm[nz], power[nz], (2.0 * np.pi / Lx, 2.0 * np.pi / Ly), bins_per_decade, q_nyq)
    notes.append(
        f"spectrum: one point per annulus of modes (their mean C at their mean radius), times a lift {f0:.3g} at "
        f"q = {q[0]:.6g} fading out by {LOW:g} times that q and a tilt (q/q_l)^{g:+.3g}"
        + ("" if abs(F - 1.0) < 1e-9 else f" and a factor {F:.3g}")
        + ", so that it carries the data's <h^2> and <|grad h|^2> (the lowest modes' cells reach below q_l)"
    )
    psd = TabulatedPSD(q, C)
    step = None if periodic else (Lx / h.shape[0], Ly / h.shape[1])
    return _check_rms(MeasuredSurface(psd, source, rms_h, rms_s, tuple(notes), step))


def _decreasing_blocks(q, C, weight):
    """Least-squares non-increasing fit of ln C (weights = bin widths, pool-adjacent-violators); one point per
    block at the weighted mean ln q.  Returns (q, C, number of bins merged away)."""
    blocks = []  # [sum w ln C, sum w, sum w ln q]
    for lq, lc, w in zip(np.log(q), np.log(C), weight):
        blocks.append([w * lc, w, w * lq])
        while len(blocks) > 1 and blocks[-1][0] / blocks[-1][1] >= blocks[-2][0] / blocks[-2][1]:
            a = blocks.pop()
            for i in range(3):
                blocks[-1][i] += a[i]
    b = np.array(blocks)
    return np.exp(b[:, 2] / b[:, 1]), np.exp(b[:, 0] / b[:, 1]), q.size - b.shape[0]


def psd_from_profiles(
    profiles,
    length,
    *,
    periodic: bool = False,
    window: str | None = "auto",
    bins_per_decade: int = 20,
    H: float | None = None,
    source: str = "line scans",
) -> MeasuredSurface:
    r"""Persson's isotropic spectrum from line scans of an isotropic surface (1-D PSD, Abel-inverted).

    The 1-D PSD (convention ``"1d"``, :math:`\langle h^2\rangle = \frac1\pi\int_0^\infty C^{1D}dq`) is
    averaged over the scans and over power-conserving bins (one step :math:`2\pi/L` wide at small q,
    log-spaced above), then converted by :func:`persson_fp.surfaces.conventions.to_persson`: numerically, or with
    the Abel factor of ``H`` when given.  The rms slope of the data is reported as the full gradient
    :math:`\sqrt2\,\mathrm{rms}(dh/dx)` (isotropy).

    Parameters
    ----------
    profiles : array_like, shape (n,) or (n_scans, n), length
        One profile or several parallel scans of equal length, uniformly sampled.
    length : float, length
        Physical length of each scan.
    periodic, window, bins_per_decade
        As in :func:`psd_from_heightmap` (default: not periodic, so each scan is detrended and Hann-windowed).
    H : float, optional
        Convert with the power-law Abel factor of this Hurst exponent instead of numerically
        (:func:`persson_fp.surfaces.conventions.abel_factor`).
    source : str
        Description stored in :attr:`MeasuredSurface.source <persson_fp.MeasuredSurface>`.

    Returns
    -------
    MeasuredSurface
        Persson's isotropic spectrum (q in rad/length of the unit of ``length``, C in length^4), the rms height
        and slope of the data and notes; a ``UserWarning`` when their rms values differ by more than 1 %.

    Raises
    ------
    ValueError
        ``profiles`` not 1-D or 2-D with >= 8 points, flat or too short to carry power in 3 bins, ``length``
        not > 0, ``bins_per_decade`` < 4, an unknown ``window``.
    """
    z = as_float_array(profiles, "profiles")
    periodic = as_bool(periodic, "periodic")
    if z.ndim == 1:
        z = z[None, :]
    if z.ndim != 2 or z.shape[1] < 8:
        raise ValueError(f"profiles must be 1-D or (n_scans, n) with n >= 8 points, got shape {z.shape}")
    if not isinstance(bins_per_decade, (int, np.integer)) or bins_per_decade < 4:
        raise ValueError(f"bins_per_decade must be an integer >= 4, got {bins_per_decade!r}")
    L = as_positive_scalar(length, "length")
    n = z.shape[1]
    x = np.arange(n) - (n - 1) / 2.0
    z = z - z.mean(axis=1, keepdims=True)
    if not periodic:
        z = z - np.outer(z @ x / (x @ x), x)
    if np.all(z == 0):
        raise ValueError("profiles are flat (after removing the mean / tilt): no roughness to import")
    rms_h = float(np.sqrt(np.mean(z * z)))
    if periodic:
        qk = 2.0 * np.pi * np.fft.fftfreq(n, d=L / n)
        zk = np.fft.fft(z, axis=1) / n
        rms_dx = float(np.sqrt(np.mean(np.sum(qk**2 * np.abs(zk) ** 2, axis=1))))
    else:
        rms_dx = float(np.sqrt(np.mean(np.gradient(z, L / n, axis=1) ** 2)))
    if window == "auto":
        window = None if periodic else "hann"
    w = _window(n, window)
    zk = np.fft.fft(z * w / np.sqrt(np.mean(w * w)), axis=1) / n
    power = np.mean(np.abs(zk) ** 2, axis=0)  # sum over k = <h^2>
    qk = 2.0 * np.abs(np.pi * np.fft.fftfreq(n, d=L / n))
    notes = ["mean height removed from each scan" + ("" if periodic else ", tilt detrended")]
    if window:
        notes.append(f"{window} window applied (normalised to keep the mean-square height)")
    notes.append(
        "1-D PSD converted to Persson's isotropic C by "
        + ("numerical Abel inversion" if H is None else f"the power-law Abel factor at H = {H}")
        + " (assumes an isotropic surface)"
    )
    dq = 2.0 * np.pi / L
    pos = qk > 0
    q_bin, P_bin, edges, _ = _radial_bins(qk[pos], power[pos], dq, np.pi * n / L, bins_per_decade)
    tiny = P_bin <= 1e-30 * P_bin.max()
    if np.sum(~tiny) < 3:
        raise ValueError("fewer than 3 bins carry power: the profiles are too short or constant")
    width = np.diff(edges)
    q1, C1 = q_bin[~tiny], (np.pi * P_bin / width)[~tiny]  # (1/pi) int_bin C1D dq = bin power
    if H is None:
        q1, C1, n_merged = _decreasing_blocks(q1, C1, width[~tiny])
        if n_merged:
            notes.append(
                f"{n_merged} bins of the 1-D PSD merged (pool-adjacent-violators) so that it decreases, which the "
                "numerical Abel inversion needs for C >= 0"
            )
    psd = TabulatedPSD(q1, C1, convention="1d", H=H)
    step = None if periodic else (L / n, L / n)  # isotropy: the y differences are those along x
    return _check_rms(MeasuredSurface(psd, source, rms_h, np.sqrt(2.0) * rms_dx, tuple(notes), step))
