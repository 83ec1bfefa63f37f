r"""Model selection: fit several fudge models to the same data and rank them (:class:`ModelSelection`).

Criteria (stated in every table):

``"held-out"`` (default)
    Mean absolute relative error of predictions for data not used in the fit: leave one surface out (fit on the
    others, predict it) when there are two or more surfaces, else leave one load out.  It measures what a user
    wants -- how well the calibrated model predicts a new surface of the same class.
``"aic"``, ``"bic"``
    Gaussian information criteria of the fit to all data, :math:`n\ln(\mathrm{SSR}/n) + 2k` and
    :math:`n\ln(\mathrm{SSR}/n) + k\ln n` (lower is better).

This module imports no solver.
"""

from __future__ import annotations

import numpy as np

from persson_fp.calibration.objective import fit

__all__ = ["CRITERIA", "ModelSelection"]

CRITERIA = ("held-out", "aic", "bic")
"""Ranking criteria of :func:`persson_fp.calibrate` for a list of models."""


class ModelSelection:
    """Several calibrations of the same data, ranked.

    Notes
    -----
    Attributes: ``fits`` (dict model name -> :class:`~persson_fp.calibration.result.Calibration`), ``held_out``
    (dict name -> mean absolute relative error of the held-out predictions), ``held_out_scheme`` ("leave one surface
    out" or "leave one load out"), ``criterion``, ``ranking`` (names, best first), ``best`` (the best
    :class:`Calibration`).

    Parameters
    ----------
    fits : dict of str to Calibration
        One calibration per model, all of the same data.
    criterion : {"held-out", "aic", "bic"}
        The ranking criterion (module docstring).
    held_out : (dict, str), optional
        Held-out errors and scheme already computed for these fits (e.g. another selection's
        ``(held_out, held_out_scheme)``); default: computed here (a refit per surface or load and model).
    """

    def __init__(self, fits, criterion="held-out", held_out=None):
        if criterion not in CRITERIA:
            raise ValueError(f"criterion must be one of {list(CRITERIA)}, got {criterion!r}")
        self.fits, self.criterion = dict(fits), criterion
        if held_out is None:
            self.held_out = {}
            for name, f in self.fits.items():
                self.held_out[name], self.held_out_scheme = _held_out(f._obj, f.values, f.loss)
        else:
            self.held_out, self.held_out_scheme = dict(held_out[0]), held_out[1]

        def score(name):
            f = self.fits[name]
            v = {"held-out": self.held_out[name], "aic": f.aic, "bic": f.bic}[criterion]
            return v if np.isfinite(v) else np.inf  # (NaN: too few points to hold any out)

        self.ranking = sorted(fits, key=score)
        self.best = fits[self.ranking[0]]

    def table(self) -> list[dict]:
        """One row per model, best first: values ± uncertainty, fit error, held-out error, AIC, BIC.

        Returns
        -------
        list of dict
            Keys ``rank``, ``model``, ``params`` (text), ``fit_mean_abs_rel_error``,
            ``held_out_mean_abs_rel_error``, ``aic``, ``bic``.
        """
        rows = []
        for rank, name in enumerate(self.ranking, 1):
            f = self.fits[name]
            rows.append(
                {
                    "rank": rank,
                    "model": name,
                    "params": ", ".join(f"{k} = {v:.4g} ± {s:.2g}" for k, v, s in zip(f.names, f.values, f.std)),
                    "fit_mean_abs_rel_error": f.mean_abs_rel_error,
                    "held_out_mean_abs_rel_error": self.held_out[name],
                    "aic": f.aic,
                    "bic": f.bic,
                }
            )
        return rows

    def summary(self) -> str:
        """The ranking as text, with the criterion stated.

        Returns
        -------
        str
            A table, best model first (also what ``print(selection)`` shows).
        """
        how = {
            "held-out": f"held-out mean |relative error| ({self.held_out_scheme})",
            "aic": "AIC (Gaussian, lower is better)",
            "bic": "BIC (Gaussian, lower is better)",
        }
        lines = [
            f"models ranked by {how[self.criterion]}:",
            f"{'rank':>4} {'model':<8} {'parameters':<30} {'fit err':>8} {'held-out':>9} {'AIC':>9} {'BIC':>9}",
        ]
        for r in self.table():
            lines.append(
                f"{r['rank']:>4} {r['model']:<8} {r['params']:<30} {r['fit_mean_abs_rel_error']:8.2%} "
                f"{r['held_out_mean_abs_rel_error']:9.2%} {r['aic']:9.2f} {r['bic']:9.2f}"
            )
        return "\n".join(lines)

    def __str__(self):
        return self.summary()

    def __repr__(self):
        return f"ModelSelection(ranking={self.ranking}, criterion={self.criterion!r})"


def _held_out(obj, fam_p0, loss):
    """Mean |relative error| of leave-one-surface-out (or leave-one-load-out) predictions, and the scheme."""
    names = list(dict.fromkeys(obj.surface))
    if len(names) >= 2:
        groups, scheme = [obj.surface == n for n in names], "leave one surface out"
    else:
        groups, scheme = [np.arange(obj.n) == i for i in range(obj.n)], "leave one load out"
    errs = []
    k = fam_p0.size
    for out in groups:
        keep = np.flatnonzero(~out)
        if keep.size <= k:
            return np.nan, scheme
        theta, _ = fit(obj, fam_p0, keep, loss)
        f = obj.model(theta)
        errs.extend(np.abs(f[out] / obj.y[out] - 1.0))
    return float(np.mean(errs)), scheme
