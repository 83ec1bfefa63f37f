r"""Time-stepping schemes as data: the θ-schemes, TR-BDF2's coefficients and the grading of step nodes.

One table for every marching method of the package (``"fv"``'s cell march and its DST-II path, the front-fixed
engine's steps): a scheme is numbers, not code (cf. scipy's ``RungeKutta`` tableaux).

TR-BDF2 (Bank et al. 1985; Hosea & Shampine 1996): a trapezoidal stage to :math:`t + \gamma\,\Delta t`, then BDF2
through :math:`t`, :math:`t + \gamma\Delta t`, :math:`t + \Delta t`,

.. math:: y_{n+1} = A\,y_\gamma - B\,y_n + W\,\Delta t\,f(y_{n+1}),\qquad
          A = \frac{1}{\gamma(2-\gamma)},\ B = \frac{(1-\gamma)^2}{\gamma(2-\gamma)},\ W = \frac{1-\gamma}{2-\gamma};

with :math:`\gamma = 2 - \sqrt2` both stages share the matrix :math:`1 - \tfrac{\gamma}{2}\Delta t\,L` (W = γ/2),
and the scheme is L-stable and second order.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Scheme", "SCHEMES", "TRBDF2_GAMMA", "TRBDF2_A", "TRBDF2_B", "TRBDF2_W", "GRADE", "graded"]


@dataclass(frozen=True)
class Scheme:
    """A θ-scheme (or TR-BDF2) as data."""

    theta: float
    """Implicitness θ of the θ-step (TR-BDF2: θ of its first stage)."""
    order: int
    """Order in time."""
    l_stable: bool
    """L-stable (stiff components damped to 0 in one step)."""
    coupling: str
    """Default coupling of the fudge factor in ``"fv"`` (lagged or predictor, see :mod:`persson_fp.solvers.fv`)."""


SCHEMES = {
    "explicit": Scheme(theta=0.0, order=1, l_stable=False, coupling="lagged"),
    "implicit": Scheme(theta=1.0, order=1, l_stable=True, coupling="lagged"),
    "crank-nicolson": Scheme(theta=0.5, order=2, l_stable=False, coupling="predictor"),
    "rannacher": Scheme(theta=0.5, order=2, l_stable=False, coupling="predictor"),
    "tr-bdf2": Scheme(theta=0.5, order=2, l_stable=True, coupling="predictor"),
}
"""Scheme name -> θ, order, L-stability and default coupling."""

TRBDF2_GAMMA = 2.0 - np.sqrt(2.0)
"""TR-BDF2 stage fraction γ: makes the trapezoidal and the BDF2 matrices equal."""
TRBDF2_A = 1.0 / (TRBDF2_GAMMA * (2.0 - TRBDF2_GAMMA))
"""TR-BDF2: weight of the intermediate stage in the BDF2 step."""
TRBDF2_B = (1.0 - TRBDF2_GAMMA) ** 2 / (TRBDF2_GAMMA * (2.0 - TRBDF2_GAMMA))
"""TR-BDF2: weight of the old value in the BDF2 step."""
TRBDF2_W = (1.0 - TRBDF2_GAMMA) / (2.0 - TRBDF2_GAMMA)
"""TR-BDF2: weight of the implicit term of the BDF2 step (= γ / 2)."""

GRADE = 0.05
r"""Graded step nodes are uniform in :math:`s = x + g \ln x` with :math:`g = ` ``GRADE`` :math:`\times x_{end}`:
geometric while x is small against g, uniform beyond (:func:`graded`)."""


def graded(x, x_end: float, offset: float = 0.0):
    r"""The graded coordinate :math:`s = x + g \ln(x + \text{offset}\,g)`, :math:`g = ` ``GRADE`` :math:`x_{end}`.

    Parameters
    ----------
    x : array_like
        The time-like variable (tau or V, pressure^2), > 0 (or >= 0 with ``offset`` > 0).
    x_end : float
        Its end value (sets the scale g where the grading turns from geometric to uniform).
    offset : float
        Added to x in the logarithm, in units of g (keeps x = 0 finite).

    Returns
    -------
    ndarray
        s(x), increasing in x.
    """
    g = GRADE * x_end
    x = np.asarray(x, dtype=float)
    return x + g * np.log(x + offset * g)
