r"""The result of a calibration: :class:`Calibration` (fitted model, values ± uncertainty, residuals, plot).

This module imports no solver; :meth:`Calibration.plot` imports matplotlib when called.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from persson_fp.calibration.objective import predict as _predict

__all__ = ["Calibration"]

_UNITS = {"contact_area": "", "mean_separation": " [length]"}
_LABELS = {"contact_area": "A*", "mean_separation": "mean separation"}


class Calibration:
    r"""A fitted fudge-factor model and its uncertainty (returned by :func:`persson_fp.calibrate`).

    Parameters
    ----------
    objective : Objective
        The data and the residuals (:class:`persson_fp.calibration.objective.Objective`).
    theta : ndarray
        The fitted parameter values.
    cov : ndarray, shape (k, k)
        Their covariance, :math:`s^2 (J^\mathsf{T}J)^{-1}`.
    s2 : float
        Residual variance :math:`s^2` (1 with ``absolute_sigma``).
    jacobian : ndarray, shape (n, k)
        Jacobian of the weighted residuals at ``theta``.
    ls_result : scipy.optimize.OptimizeResult
        The optimiser's result.
    bootstrap : ndarray or None
        Refitted parameters of each bootstrap resample, shape ``(n_boot, k)``.
    wall_time : float, s
        Time of the whole call.
    loss : str or callable
        The ``scipy.optimize.least_squares`` loss used.

    Notes
    -----
    Attributes:

    - ``model`` (alias ``fudge``): the fitted :class:`~persson_fp.theory.fudge.FudgeFactor`, usable as
      ``fudge=`` of :class:`~persson_fp.ContactProblem` and :class:`~persson_fp.MeanSeparation`.
    - ``params``: dict name -> fitted value; ``uncertainty``: dict name -> standard error (1 sigma, from
      :math:`s^2 (J^\mathsf{T}J)^{-1}`); ``values``, ``std``, ``cov``: the same as arrays.
    - ``n_points``, ``dof`` (n - k), ``s`` (residual standard deviation, :math:`\sqrt{s^2}`), ``ssr`` (sum of
      squared residuals), ``aic`` and ``bic`` (Gaussian, :math:`n\ln(\mathrm{SSR}/n) + 2k` and
      :math:`+ k\ln n`), ``rms_rel_error`` and ``mean_abs_rel_error`` (of the fit, unweighted).
    - ``bootstrap``: the refitted parameters of each resample (shape ``(n_boot, k)``) or None;
      ``bootstrap_std``: their standard deviation.
    - ``nfev``, ``wall_time`` (s), ``success``, ``message``: the optimiser's account.
    """

    def __init__(self, objective, theta, cov, s2, jacobian, ls_result, bootstrap, wall_time, loss):
        self._obj = objective
        self.family = objective.family
        self.names = objective.family.params
        self.values = np.asarray(theta, dtype=float)
        self.cov = cov
        self.std = np.sqrt(np.diag(cov))
        self.s = float(np.sqrt(s2))
        self.jacobian = jacobian
        self.model = objective.family(self.values)
        self.fudge = self.model
        self.quantities = objective.quantities
        self.datasets = objective.datasets
        self.E_star = objective.E_star
        self.weighting = objective.weighting
        self.loss = loss
        self.bootstrap = bootstrap
        self.bootstrap_std = None if bootstrap is None else np.std(bootstrap, axis=0, ddof=1)
        self.nfev, self.success, self.message = objective.nfev, bool(ls_result.success), ls_result.message
        self.wall_time = float(wall_time)
        self.prediction = objective.model(self.values)
        self.rel_error = self.prediction / objective.y - 1.0
        r = objective.sqrt_w * (self.prediction - objective.y) / objective.scale
        self.n_points, k = objective.n, self.values.size
        self.dof = self.n_points - k
        self.ssr = float(r @ r)
        n = self.n_points
        with np.errstate(divide="ignore"):
            base = n * np.log(self.ssr / n) if self.ssr > 0 else -np.inf
        self.aic, self.bic = float(base + 2 * k), float(base + k * np.log(n))
        self.rms_rel_error = float(np.sqrt(np.mean(self.rel_error**2)))
        self.mean_abs_rel_error = float(np.mean(np.abs(self.rel_error)))

    @property
    def params(self) -> dict:
        """Fitted values, name -> float."""
        return {k: float(v) for k, v in zip(self.names, self.values)}

    @property
    def uncertainty(self) -> dict:
        """Standard errors (1 sigma), name -> float."""
        return {k: float(v) for k, v in zip(self.names, self.std)}

    def interval(self, level: float = 0.95) -> dict:
        """Confidence interval of each parameter, value ± t_{(1+level)/2, n-k} x standard error.

        Parameters
        ----------
        level : float
            Confidence level in (0, 1) (default 0.95).

        Returns
        -------
        dict of str to (float, float)
            (lower, upper) per parameter.
        """
        if not 0 < level < 1:
            raise ValueError(f"level must lie in (0, 1), got {level!r}")
        t = stats.t.ppf(0.5 + level / 2, self.dof)
        return {k: (float(v - t * s), float(v + t * s)) for k, v, s in zip(self.names, self.values, self.std)}

    def predict(self, psd, p_bar, quantity="contact_area", E_star=None, level=0.95):
        r"""The calibrated theory's prediction for a surface, with the band from the parameter uncertainty.

        The band is the delta method, :math:`\mathrm{var} f = g^\mathsf{T}\mathrm{cov}\,g` with
        :math:`g = \partial f/\partial\theta` (central differences); it covers the parameters' uncertainty, not
        the scatter of one surface about the theory (see ``s`` and ``rms_rel_error``) nor the change of
        surface class (a calibration holds for surfaces like those fitted).

        Parameters
        ----------
        psd : PSD
            The surface's spectrum.
        p_bar : float or 1-D array, pressure
            Nominal pressures, > 0.
        quantity : {"contact_area", "mean_separation"}
            What to predict.
        E_star : float, optional
            Plane-strain modulus (default the calibration's).
        level : float
            Confidence level of the band (default 0.95).

        Returns
        -------
        value, half_width : ndarray
            The prediction and the half-width of its band (t quantile x standard error), shape of ``p_bar``.
        """
        E = self.E_star if E_star is None else E_star
        p = np.atleast_1d(np.asarray(p_bar, dtype=float))
        f0 = _predict(psd, E, p, self.model, quantity, self.weighting)
        lo, hi = self.family.bounds
        g = []
        for j, v in enumerate(self.values):
            h = 1e-5 * max(abs(v), 1.0)
            up, dn = self.values.copy(), self.values.copy()
            up[j], dn[j] = min(v + h, hi[j]), max(v - h, lo[j])
            fu = _predict(psd, E, p, self.family(up), quantity, self.weighting)
            fd = _predict(psd, E, p, self.family(dn), quantity, self.weighting)
            g.append((fu - fd) / (up[j] - dn[j]))
        g = np.array(g)
        var = np.einsum("ip,ij,jp->p", g, self.cov, g)
        t = stats.t.ppf(0.5 + level / 2, self.dof)
        shape = np.shape(p_bar)
        return f0.reshape(shape), (t * np.sqrt(var)).reshape(shape)

    def residual_table(self) -> dict:
        """The data, the fit and their relative error, one row per point.

        Returns
        -------
        dict of str to ndarray
            Columns ``surface``, ``quantity``, ``p_bar``, ``data``, ``fit``, ``rel_error`` (fit/data - 1) and
            ``residual`` (the weighted residual that was minimised).  ``pandas.DataFrame(table)`` makes a frame.
        """
        o = self._obj
        return {
            "surface": o.surface.copy(),
            "quantity": o.quantity.copy(),
            "p_bar": o.p_bar.copy(),
            "data": o.y.copy(),
            "fit": self.prediction.copy(),
            "rel_error": self.rel_error.copy(),
            "residual": o.sqrt_w * (self.prediction - o.y) / o.scale,
        }

    def summary(self) -> str:
        """A few lines: the fitted values ± uncertainty, the 95 % interval, the fit's error and its scope.

        Returns
        -------
        str
            The summary (also what ``print(result)`` shows).
        """
        ci = self.interval()
        lines = [
            f"{self.family.name} calibrated on {len(self.datasets)} surface(s), {self.n_points} points "
            f"({', '.join(self.quantities)}; relative least squares, loss {self.loss!r})"
        ]
        for k, v, s in zip(self.names, self.values, self.std):
            lo, hi = ci[k]
            lines.append(f"  {k} = {v:.4g} ± {s:.2g} (1 sigma; 95 % interval [{lo:.4g}, {hi:.4g}])")
            if self.bootstrap is not None:
                j = self.names.index(k)
                lines.append(f"    bootstrap ({len(self.bootstrap)} resamples): ± {self.bootstrap_std[j]:.2g}")
        lines.append(
            f"  fit: rms relative error {self.rms_rel_error:.2%}, mean |relative error| "
            f"{self.mean_abs_rel_error:.2%}; {self.nfev} model evaluations, {self.wall_time:.3g} s"
        )
        lines.append("  valid for surfaces like those fitted: check a held-out surface before using it elsewhere")
        return "\n".join(lines)

    def __str__(self):
        return self.summary()

    def __repr__(self):
        vals = ", ".join(f"{k}={v:.4g}±{s:.2g}" for k, v, s in zip(self.names, self.values, self.std))
        return f"Calibration({self.family.name}: {vals}; n={self.n_points})"

    def plot(self, level: float = 0.95, n_curve: int = 60):
        """Data, fit and its band (``level``), one panel per quantity, relative errors below.

        Parameters
        ----------
        level : float
            Confidence level of the band (parameter uncertainty, :meth:`predict`).
        n_curve : int
            Loads on each fitted curve.

        Returns
        -------
        matplotlib.figure.Figure
        """
        import matplotlib.pyplot as plt

        nq = len(self.quantities)
        fig, axes = plt.subplots(
            2, nq, figsize=(5.2 * nq, 6), squeeze=False, sharex="col", gridspec_kw={"height_ratios": [3, 1]}
        )
        o = self._obj
        for c, q in enumerate(self.quantities):
            ax, axr = axes[0, c], axes[1, c]
            for i, ds in enumerate(self.datasets):
                if q not in ds.values:
                    continue
                color = f"C{i % 10}"
                y, err = ds.values[q], ds.errors.get(q)
                ax.errorbar(ds.p_bar, y, yerr=err, fmt="o", color=color, ms=4, label=f"{ds.name} (data)")
                p = np.geomspace(ds.p_bar.min(), ds.p_bar.max(), n_curve)
                f, hw = self.predict(ds.psd, p, q, level=level)
                ax.plot(p, f, "-", color=color, lw=1.2)
                ax.fill_between(p, f - hw, f + hw, color=color, alpha=0.25, lw=0)
                axr.fill_between(p, -100 * hw / f, 100 * hw / f, color=color, alpha=0.15, lw=0)
                m = (o.surface == ds.name) & (o.quantity == q)
                axr.plot(o.p_bar[m], 100 * self.rel_error[m], "o", color=color, ms=4)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_ylabel(_LABELS[q] + _UNITS[q])
            ax.set_title(f"{q}: {self.family.name}, " + ", ".join(f"{k} = {v:.3g}" for k, v in self.params.items()))
            axr.axhline(0.0, color="k", lw=0.6)
            axr.set_xlabel("p_bar [pressure]")
            axr.set_ylabel("fit/data - 1 [%]")
        axes[0, 0].legend(fontsize=7, title=f"lines: fit, band: {level:.0%}", title_fontsize=7)
        fig.tight_layout()
        return fig
