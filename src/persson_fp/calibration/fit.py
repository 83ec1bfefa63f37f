r"""Least-squares calibration of a fudge model's free parameters: :func:`calibrate`.

The residuals, the fit and the covariance are those of :mod:`persson_fp.calibration.objective`: relative
residuals :math:`(f_i - y_i)/y_i` (or :math:`(f_i - y_i)/\sigma_i` with given uncertainties), minimised by
``scipy.optimize.least_squares``, :math:`\mathrm{cov}(\theta) = s^2 (J^\mathsf{T} J)^{-1}`.

This module imports no solver.
"""

from __future__ import annotations

import time

import numpy as np

from persson_fp._validate import as_positive_scalar
from persson_fp.calibration.data import QUANTITIES, pair_surfaces
from persson_fp.calibration.models import family as _family
from persson_fp.calibration.objective import PENALTY, Objective, covariance, fit
from persson_fp.calibration.result import Calibration
from persson_fp.calibration.select import CRITERIA, ModelSelection
from persson_fp.theory.separation import WEIGHTINGS

__all__ = ["calibrate"]


def calibrate(
    psd_or_surfaces,
    data,
    model="YP08",
    params=("gamma",),
    quantities=None,
    weights=None,
    *,
    E_star: float = 1.0,
    weighting: str = "yang-persson",
    p0=None,
    bounds=None,
    loss="linear",
    absolute_sigma: bool = False,
    bootstrap: int = 0,
    rng=None,
    criterion: str = "held-out",
):
    r"""Fit the free parameters of a fudge-factor model to measured or simulated contact data.

    Least squares on relative errors of the contact area A*(p̄) and/or the mean separation ū(p̄) of one or
    several surfaces that share the parameters; uncertainty from the Jacobian,
    :math:`\mathrm{cov} = s^2 (J^\mathsf{T}J)^{-1}` (:mod:`persson_fp.calibration.objective`), and optionally a
    bootstrap.  A calibration holds for the class of surfaces it was fitted on: check it on a held-out surface
    before using it for another class (:meth:`Calibration.predict`, and a list of models ranks them by a held-out
    error).

    Parameters
    ----------
    psd_or_surfaces : PSD, sequence of PSD or mapping of str to PSD
        One spectrum per surface (Persson's convention, :class:`~persson_fp.TabulatedPSD` for a measured one).
    data : str, path-like, DataFrame, mapping, 2-D array, or a sequence of them
        Columns ``p_bar`` (pressure, > 0), ``contact_area`` (in (0, 1]) and/or ``mean_separation`` (length, > 0),
        optional ``contact_area_err`` / ``mean_separation_err`` (absolute, 1 standard deviation) and
        ``surface`` (which surface a row belongs to); one table per surface, or one table with a ``surface``
        column (:mod:`persson_fp.calibration.data`).
    model : str, FudgeFactor class or instance, callable, or a list of them
        ``"YP08"`` (default), ``"WM17"``, ``"Xu24"``, a fudge-factor dataclass, or a callable ``S(A, *theta)``.
        A list fits each and returns a :class:`ModelSelection` ranked by ``criterion``.
    params : sequence of str
        The free parameters (default ``("gamma",)``).
    quantities : sequence of str, optional
        Among ``"contact_area"``, ``"mean_separation"``; default those present in the data.
    weights : mapping of str to float, optional
        Weight of each quantity's squared residuals (default 1 each).
    E_star : float, pressure
        Plane-strain modulus E/(1 - nu^2) of every surface (> 0).
    weighting : {"yang-persson", "corrected-area"}
        Energy weighting of the mean separation (:mod:`persson_fp.theory.separation`).
    p0 : sequence of float, optional
        Start values (default the model's; required for a callable).
    bounds : (sequence, sequence), optional
        Parameter bounds (default the range the model accepts).
    loss : str or callable
        ``scipy.optimize.least_squares`` loss (``"linear"``: least squares; ``"soft_l1"``, ``"huber"``,
        ... for outliers: the covariance is then only indicative).
    absolute_sigma : bool
        With uncertainty columns: take them as absolute (s² = 1) instead of as relative weights.
    bootstrap : int
        Number of bootstrap resamples of the data points (0: none); each is a refit.
    rng : numpy Generator or int, optional
        Random source of the bootstrap.
    criterion : {"held-out", "aic", "bic"}
        How a list of models is ranked (ignored for one model).

    Returns
    -------
    Calibration or ModelSelection
        The fit (``.model`` is the fitted fudge factor, usable as ``fudge=``; ``.params``, ``.uncertainty``,
        ``.interval()``, ``.residual_table()``, ``.plot()``), or for a list of models their ranking.

    Raises
    ------
    ValueError
        Bad data (naming the column and row: a load <= 0, A* outside (0, 1], a non-finite entry), fewer points
        than parameters + 1, an unknown model, parameter, quantity or weighting, or start values outside the
        bounds.

    References
    ----------
    .. [1] Y. Xu, X. Li, Q. Chen, Y. Zhou, Persson's theory of purely normal elastic rough surface contact: a
       tutorial based on stochastic process theory (Eqs. 'eq:Area_Persson', 'eq:new_B2').
    .. [2] C. Yang, B.N.J. Persson, J. Phys.: Condens. Matter 20 (2008) 215214.
    """
    if isinstance(model, (list, tuple)):
        if criterion not in CRITERIA:
            raise ValueError(f"criterion must be one of {list(CRITERIA)}, got {criterion!r}")
        if len(model) == 0:
            raise ValueError("model: an empty list (give at least one model)")
        fits = {}
        for m in model:
            f = calibrate(
                psd_or_surfaces,
                data,
                m,
                params,
                quantities,
                weights,
                E_star=E_star,
                weighting=weighting,
                p0=p0,
                bounds=bounds,
                loss=loss,
                absolute_sigma=absolute_sigma,
            )
            if f.family.name in fits:
                raise ValueError(f"model: {f.family.name!r} appears twice")
            fits[f.family.name] = f
        return ModelSelection(fits, criterion)
    t0 = time.perf_counter()
    E_star = as_positive_scalar(E_star, "E_star")
    if weighting not in WEIGHTINGS:
        raise ValueError(f"weighting must be one of {list(WEIGHTINGS)}, got {weighting!r}")
    if isinstance(quantities, str):
        quantities = (quantities,)
    datasets = pair_surfaces(psd_or_surfaces, data, quantities)
    qs = tuple(q for q in QUANTITIES if any(q in d.values for d in datasets))
    weights = dict(weights or {})
    for q, w in weights.items():
        if q not in QUANTITIES:
            raise ValueError(f"weights: unknown quantity {q!r} (have {list(QUANTITIES)})")
        weights[q] = as_positive_scalar(w, f"weights[{q!r}]")
    fam = _family(model, params, p0, bounds)
    obj = Objective(datasets, fam, E_star, weighting, qs, weights)
    k = len(fam.params)
    if obj.n <= k:
        raise ValueError(f"too few points: {obj.n} data value(s) for {k} parameter(s) (need at least {k + 1})")
    if not np.all(np.isfinite(obj.residuals(fam.p0))) or np.all(obj.residuals(fam.p0) == PENALTY):
        raise ValueError(f"the model {fam.name} refuses the start values p0 = {fam.p0.tolist()}")
    theta, res = fit(obj, fam.p0, loss=loss)
    cov, s2, J = covariance(obj, theta, absolute_sigma=absolute_sigma and bool(np.all(obj.has_err)))
    boot = None
    if bootstrap:
        if not isinstance(bootstrap, (int, np.integer)) or bootstrap < 2:
            raise ValueError(f"bootstrap must be 0 or an integer >= 2, got {bootstrap!r}")
        gen = np.random.default_rng(rng)
        boot = np.array([fit(obj, theta, gen.integers(0, obj.n, obj.n), loss)[0] for _ in range(bootstrap)])
    return Calibration(
        objective=obj,
        theta=theta,
        cov=cov,
        s2=s2,
        jacobian=J,
        ls_result=res,
        bootstrap=boot,
        wall_time=time.perf_counter() - t0,
        loss=loss,
    )
