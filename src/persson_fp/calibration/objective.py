r"""The residuals, the least-squares fit and the covariance behind :func:`persson_fp.calibrate`.

The residual of a measured value :math:`y_i` (contact area or mean separation of surface s at load
:math:`\bar p_i`) and the theory's :math:`f_i(\theta)` is relative,
:math:`r_i = \sqrt{w_q}\,(f_i - y_i)/y_i`, or, where the data give an uncertainty :math:`\sigma_i`,
:math:`r_i = \sqrt{w_q}\,(f_i - y_i)/\sigma_i`.  :math:`f` is the closed form of the fudge-factor theory
(Xu et al. tutorial, ``eq:Area_Persson`` at the effective variance of ``eq:new_B2``, via :func:`persson_fp.exact`)
and Persson's mean separation (:class:`persson_fp.MeanSeparation`).  The parameters minimise
:math:`\sum r_i^2` (``scipy.optimize.least_squares``, trust-region reflective within the model's bounds),
and their covariance is the Gauss--Newton one,

.. math::  \mathrm{cov}(\theta) = s^2 (J^\mathsf{T} J)^{-1}, \qquad s^2 = \frac{\sum r_i^2}{n - k},

with J the Jacobian of the residuals at the optimum (central differences) and n points, k parameters
(with ``absolute_sigma=True`` and given uncertainties, :math:`s^2 = 1`, as in ``scipy.optimize.curve_fit``).
A bootstrap over the data points (pairs resampled with replacement, each resample refitted) is optional.

This module imports no solver.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.optimize import least_squares

from persson_fp.analysis.exact import exact
from persson_fp.problems.contact import ContactProblem
from persson_fp.theory.separation import MeanSeparation

__all__ = ["Objective", "predict", "fit", "covariance", "PENALTY"]

PENALTY = 1e3
"""Residual returned for parameter values a user model refuses (S not > 0): steers the optimiser away."""


def predict(psd, E_star, p_bar, fudge, quantity, weighting="yang-persson") -> np.ndarray:
    """The theory's value of ``quantity`` at loads ``p_bar`` (1-D) for one surface and fudge factor.

    Parameters
    ----------
    psd : PSD
        The surface's spectrum.
    E_star : float, pressure
        Plane-strain modulus.
    p_bar : 1-D array, pressure
        Nominal pressures, > 0.
    fudge : FudgeFactor
        The model S(A*).
    quantity : {"contact_area", "mean_separation"}
        A* (dimensionless, ``eq:Area_Persson`` at the effective variance) or the mean separation (length).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of the mean separation (:mod:`persson_fp.theory.separation`).

    Returns
    -------
    ndarray, shape (n,)
        The predicted values.
    """
    p = np.atleast_1d(np.asarray(p_bar, dtype=float))
    if quantity == "contact_area":
        return np.asarray(exact(ContactProblem(psd, E_star, p, fudge)).contact_area, dtype=float).reshape(p.shape)
    return np.asarray(MeanSeparation(psd, E_star, fudge, weighting).mean_separation(p), dtype=float)


class Objective:
    """The stacked data of all surfaces and the residual vector r(theta) (module docstring).

    Parameters
    ----------
    datasets : list of Dataset
        The surfaces' data.
    family : Family
        The parametric model.
    E_star : float, pressure
        Plane-strain modulus (shared by the surfaces).
    weighting : str
        Energy weighting of the mean separation.
    quantities : tuple of str
        The quantities fitted.
    weights : dict of str to float
        Weight w_q of each quantity's squared residuals.
    """

    def __init__(self, datasets, family, E_star, weighting, quantities, weights):
        self.datasets, self.family, self.E_star = datasets, family, E_star
        self.weighting, self.quantities = weighting, quantities
        surf, qty, p, y, scale, w, has_err = [], [], [], [], [], [], []
        self.blocks = []  # (dataset index, quantity, slice)
        for d, ds in enumerate(datasets):
            for q in quantities:
                if q not in ds.values:
                    continue
                n = ds.p_bar.size
                self.blocks.append((d, q, slice(len(y), len(y) + n)))
                surf += [ds.name] * n
                qty += [q] * n
                p.extend(ds.p_bar)
                y.extend(ds.values[q])
                err = ds.errors.get(q)
                scale.extend(ds.values[q] if err is None else err)
                has_err += [err is not None] * n
                w += [weights.get(q, 1.0)] * n
        self.surface = np.array(surf, dtype=object)
        self.quantity = np.array(qty, dtype=object)
        self.p_bar, self.y, self.scale = np.array(p), np.array(y), np.array(scale)
        self.sqrt_w = np.sqrt(np.array(w, dtype=float))
        self.has_err = np.array(has_err, dtype=bool)
        self.n = self.y.size
        self.nfev = 0

    def model(self, theta) -> np.ndarray:
        """The theory's value at every data point for parameters ``theta`` (raises ValueError if refused)."""
        fz = self.family(theta)
        f = np.empty(self.n)
        for d, q, sl in self.blocks:
            ds = self.datasets[d]
            f[sl] = predict(ds.psd, self.E_star, ds.p_bar, fz, q, self.weighting)
        return f

    def residuals(self, theta) -> np.ndarray:
        """Weighted residuals r(theta) at every point (a large constant where the model refuses theta)."""
        self.nfev += 1
        try:
            with np.errstate(all="ignore"):
                f = self.model(theta)
        except ValueError:
            return np.full(self.n, PENALTY)
        return self.sqrt_w * (f - self.y) / self.scale


def _jacobian(fun, theta, lo, hi, rel_step=1e-5):
    """Central-difference Jacobian of ``fun`` at ``theta`` (one-sided at a bound)."""
    theta = np.asarray(theta, dtype=float)
    cols = []
    for j in range(theta.size):
        h = rel_step * max(abs(theta[j]), 1.0)
        up, dn = theta.copy(), theta.copy()
        up[j] = min(theta[j] + h, hi[j])
        dn[j] = max(theta[j] - h, lo[j])
        cols.append((fun(up) - fun(dn)) / (up[j] - dn[j]))
    return np.column_stack(cols)


def fit(objective, p0, idx=None, loss="linear"):
    """Minimise the sum of squared residuals (at the points ``idx``, with repeats; default all).

    Returns
    -------
    (theta, scipy.optimize.OptimizeResult)
    """
    lo, hi = objective.family.bounds
    idx = np.arange(objective.n) if idx is None else np.asarray(idx)
    x0 = np.clip(np.asarray(p0, dtype=float), lo, hi)
    res = least_squares(
        lambda t: objective.residuals(t)[idx],
        x0,
        bounds=(lo, hi),
        loss=loss,
        diff_step=1e-6,
        xtol=1e-10,
        ftol=1e-12,
        gtol=1e-12,
        x_scale=np.where(np.isfinite(hi - lo), np.minimum(hi - lo, 1.0), 1.0),
    )
    return res.x, res


def covariance(objective, theta, idx=None, absolute_sigma=False):
    """(cov, s2, J) of the parameters at ``theta`` (module docstring); idx selects (and repeats) points."""
    lo, hi = objective.family.bounds
    idx = np.arange(objective.n) if idx is None else np.asarray(idx)
    r = objective.residuals(theta)[idx]
    J = _jacobian(lambda t: objective.residuals(t)[idx], theta, lo, hi)
    k = theta.size
    dof = idx.size - k
    s2 = 1.0 if absolute_sigma else float(r @ r) / dof
    JtJ = J.T @ J
    if np.linalg.matrix_rank(JtJ) < k:
        warnings.warn(
            "the data do not determine every parameter (singular J^T J): uncertainties set to inf", stacklevel=3
        )
        return np.full((k, k), np.inf), s2, J
    return s2 * np.linalg.inv(JtJ), s2, J
