"""A measured spectrum: :class:`TabulatedPSD`, C(q) given as a table and interpolated in log-log.

The base class and the self-affine model are in :mod:`persson_fp.surfaces.psd`; height maps and profiles are turned
into a table by :mod:`persson_fp.surfaces.heightmap`.
"""

from __future__ import annotations

import os

import numpy as np
from numpy.typing import ArrayLike

from persson_fp._validate import as_float_array, as_positive_scalar, check_in_range
from persson_fp.surfaces.psd import PSD, powint, powint_inverse

__all__ = ["TabulatedPSD"]


class TabulatedPSD(PSD):
    r"""A measured isotropic spectrum given at points ``(q_i, C_i)``.

    Between the points ``C`` is interpolated linearly in log-log (a power law
    per interval), and every moment is the exact integral of that interpolant,
    so a spectrum that *is* piecewise power law (like :class:`SelfAffinePSD`)
    is reproduced to round-off.

    Parameters
    ----------
    q : array_like, 1/length
        Strictly increasing wavenumbers > 0 (at least two).
    C : array_like, length^4
        Spectrum values > 0 at ``q`` (same convention as ``E:PSD``).
    q_l, q_s : float, optional
        Band limits inside ``[q[0], q[-1]]`` (after conversion to rad/length); default the table's ends.
    convention : str, optional
        What ``C`` is (:mod:`persson_fp.surfaces.conventions`): ``"persson"`` (default, as above), ``"iso2d"``
        (2-D FFT / SurfaceTopography ``power_spectrum_from_area``, :math:`C_{iso} = (2\pi)^2 C`),
        ``"1d"`` (1-D PSD of line scans, Abel-inverted) or ``"q/pi*2d"`` (contact.engineering's
        "q/π × 2D PSD" series; Jacobs, Junge & Pastewka, Surf. Topogr.: Metrol. Prop. 5 (2017) 013001).
        The table is converted once; the attribute ``convention`` records the input's.
    q_unit : str, optional
        ``"rad/length"`` (default, q = 2 pi / wavelength) or ``"1/length"`` (1 / wavelength, densities
        per unit 1/wavelength).
    H : float, optional
        ``convention="1d"`` only: convert with the Abel factor of this Hurst exponent instead of the
        numerical inversion.
    """

    def __init__(
        self,
        q: ArrayLike,
        C: ArrayLike,
        q_l: float | None = None,
        q_s: float | None = None,
        *,
        convention: str = "persson",
        q_unit: str = "rad/length",
        H: float | None = None,
    ):
        from persson_fp.surfaces.conventions import check_convention, to_persson

        convention, q_unit = check_convention(convention, q_unit)
        q = as_float_array(q, "q")
        C = as_float_array(C, "C")
        if q.ndim != 1 or C.ndim != 1:
            raise ValueError(f"q and C must be 1-D arrays, got shapes {q.shape} and {C.shape}")
        if q.size < 2:
            raise ValueError(f"q must hold at least 2 points, got {q.size}")
        if C.shape != q.shape:
            raise ValueError(f"C must have the same length as q ({q.size}), got {C.size}")
        if np.any(q <= 0):
            raise ValueError(f"q must be > 0 everywhere, got {float(q[q <= 0][0])!r}")
        if np.any(np.diff(q) <= 0):
            i = int(np.argmax(np.diff(q) <= 0))
            raise ValueError(
                f"q must be strictly increasing; q[{i + 1}] = {float(q[i + 1])!r} <= q[{i}] = {float(q[i])!r}"
            )
        if np.any(C <= 0):
            i = int(np.argmax(C <= 0))
            raise ValueError(f"C must be > 0 everywhere (log-log interpolation); C[{i}] = {float(C[i])!r}")
        if convention != "persson" or q_unit != "rad/length":
            q, C = to_persson(q, C, convention, q_unit, H)
            if np.any(C <= 0):  # only the numerical Abel inversion of a rising 1-D PSD can do this
                i = int(np.argmax(C <= 0))
                raise ValueError(
                    f"the Abel inversion of the 1-D PSD gives C <= 0 at q = {q[i]!r} (the 1-D PSD rises there); "
                    "smooth it or pass H= to convert with the power-law factor"
                )
        elif H is not None:
            raise ValueError("H is used only with convention='1d' (Abel factor)")
        if q_l is not None:
            q_l = float(check_in_range(as_positive_scalar(q_l, "q_l"), "q_l", q[0], q[-1], rtol=0.0))
        if q_s is not None:
            q_s = float(check_in_range(as_positive_scalar(q_s, "q_s"), "q_s", q[0], q[-1], rtol=0.0))
        q_l = float(q[0]) if q_l is None else q_l
        q_s = float(q[-1]) if q_s is None else q_s
        if not q_s > q_l:
            raise ValueError(f"q_s must be > q_l = {q_l!r}, got {q_s!r}")
        self.q = q.copy()
        self.values = C.copy()
        self.q_l = q_l
        self.q_s = q_s
        self.convention = convention if q_unit == "rad/length" else f"{convention}, q in {q_unit}"
        self._freeze()

    def __repr__(self):
        return (
            f"TabulatedPSD(<{self.q.size} points>, q_l={self.q_l!r}, q_s={self.q_s!r}, "
            f"convention={self.convention!r}, rms_height={self.rms_height:.6g}, rms_slope={self.rms_slope:.6g})"
        )

    @classmethod
    def from_csv(cls, path: str | os.PathLike, q_column: str = "q", C_column: str = "C", **kwargs) -> TabulatedPSD:
        """Read a spectrum from a CSV file with a header row naming ``q_column`` and ``C_column``.

        Parameters
        ----------
        path : str or path-like
            The CSV file.
        q_column, C_column : str
            Header names of the wavenumber (1/length) and spectrum (length^4) columns.
        **kwargs
            Passed on to :class:`TabulatedPSD` (``q_l``, ``q_s``, ``convention``, ``q_unit``, ``H``).

        Returns
        -------
        TabulatedPSD
            The tabulated spectrum.

        Raises
        ------
        ValueError
            ``path`` not the name of an existing file (an int is not taken as a file descriptor; a folder), a
            missing column, or a row with a non-numeric, non-finite, zero or negative value (the message names
            the line).
        """
        import csv

        from persson_fp._validate import as_file_path

        path = as_file_path(path)
        qs, Cs = [], []
        with open(path, newline="") as fh:
            reader = csv.DictReader(fh)
            if reader.fieldnames is None or q_column not in reader.fieldnames or C_column not in reader.fieldnames:
                raise ValueError(
                    f"{path}: header must name columns {q_column!r} and {C_column!r}, got {reader.fieldnames}"
                )
            for row in reader:
                line = reader.line_num
                try:
                    qv, Cv = float(row[q_column]), float(row[C_column])
                except (TypeError, ValueError):
                    raise ValueError(f"{path}, line {line}: q and C must be numbers, got {row!r}") from None
                if not (np.isfinite(qv) and np.isfinite(Cv) and qv > 0 and Cv > 0):
                    raise ValueError(f"{path}, line {line}: q and C must be finite and > 0, got q={qv}, C={Cv}")
                qs.append(qv)
                Cs.append(Cv)
        return cls(np.array(qs), np.array(Cs), **kwargs)

    def _slopes(self):
        return np.diff(np.log(self.values)) / np.diff(np.log(self.q))

    def C(self, q: ArrayLike) -> np.ndarray:
        q = as_float_array(q, "q")
        inside = (q >= self.q_l) & (q <= self.q_s)
        qc = np.clip(q, self.q[0], self.q[-1])
        logC = np.interp(np.log(qc), np.log(self.q), np.log(self.values))
        return np.where(inside, np.exp(logC), 0.0)

    def _segment_moment(self, k, i, q_lo, q_hi):
        """Exact integral of q^k C over [q_lo, q_hi] inside table interval i."""
        s = self._slopes()[i]
        Ci = self.values[i] * (q_lo / self.q[i]) ** s
        return Ci * q_lo ** (k + 1.0) * powint(1.0, q_hi / q_lo, k + 1.0 + s)

    def _band(self, k):
        """Nodes of the band, table interval of each piece, and the cumulative moment at the nodes."""
        inner = self.q[(self.q > self.q_l) & (self.q < self.q_s)]
        nodes = np.concatenate(([self.q_l], inner, [self.q_s]))
        seg = np.clip(np.searchsorted(self.q, nodes[:-1], side="right") - 1, 0, self.q.size - 2)
        full = self._segment_moment(k, seg, nodes[:-1], nodes[1:])
        return nodes, seg, np.concatenate(([0.0], np.cumsum(full)))

    def moment_inverse(self, k: float, M: ArrayLike) -> np.ndarray:
        M = np.asarray(M, dtype=float)
        nodes, seg, cum = self._band(k)
        j = np.clip(np.searchsorted(cum, M, side="right") - 1, 0, nodes.size - 2)
        s = self._slopes()[seg[j]]
        q0 = nodes[j]
        C_lo = self.values[seg[j]] * (q0 / self.q[seg[j]]) ** s
        # int_{q0}^{q} x^k C_lo (x/q0)^s dx = C_lo q0^(k+1) powint(1, q/q0, k+1+s)
        r = powint_inverse(1.0, (M - cum[j]) / (C_lo * q0 ** (k + 1.0)), k + 1.0 + s)
        return np.minimum(q0 * r, nodes[j + 1])

    def moment(self, k: float, zeta: ArrayLike | None = None) -> np.ndarray:
        r"""Spectral moment :math:`\int_{q_l}^{\zeta q_l} q^k C(q)\,dq`, exact for the log-log interpolant.

        Parameters
        ----------
        k : float
            Power of q.
        zeta : array_like, optional, dimensionless
            Upper magnification(s) in ``[1, zeta_max]``; default ``zeta_max``.

        Returns
        -------
        numpy.ndarray, length^(3-k)
            The moment at each ``zeta``.
        """
        return self.moment_unchecked(k, self._zeta(zeta))

    def moment_unchecked(self, k: float, z) -> np.ndarray:
        # (documented on PSD.moment_unchecked: z finite in [1, zeta_max], nothing validated)
        z = np.asarray(z, dtype=float)
        q_hi = z * self.q_l
        nodes, seg, cum = self._band(k)  # q_l, the table points strictly inside, q_s
        j = np.clip(np.searchsorted(nodes, q_hi, side="right") - 1, 0, nodes.size - 2)
        partial = self._segment_moment(k, seg[j], nodes[j], np.maximum(q_hi, nodes[j]))
        return cum[j] + partial
