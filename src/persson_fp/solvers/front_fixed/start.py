r"""The start-up of a run of the front-fixed engine and its refusals (``"fv"``, ``"mol"``).

``general_start`` checks the stations' resolution and asks the coefficient model
(``persson_fp.solvers.front_fixed.models``) for a start-up Gaussian cleared of the walls (``clear_start_V``) and
the drift's cell Peclet number at a wall (``check_wall_peclet``); the model's ``singular_step_error`` names a drift
too strong for the implicit step.  (General coefficients only: the homogenised start is exact.)
"""

from __future__ import annotations

import numpy as np

from persson_fp.solvers.base import zeta_of
from persson_fp.solvers.front_fixed.models import N_P_LIMIT, PECLET_MAX, START_CLEARANCE, model_of
from persson_fp.solvers.front_fixed.moving_wall import MovingWall, check_resolved

__all__ = ["general_start", "START_CLEARANCE", "PECLET_MAX", "N_P_LIMIT"]


def general_start(problem, stations, n: int, zeta0, k_domain: float, tau0_fraction: float, name: str):
    """The start-up zeta0 of a general-coefficient run of the engine on ``n`` cells, checked (``"fv"``, ``"mol"``).

    The resolution of the stations (:func:`~persson_fp.solvers.front_fixed.moving_wall.check_resolved`), the
    engine's own
    start-up (``MovingWall.choose_V0``) lowered by :func:`clear_start_V`, and the drift at the walls
    (:func:`check_wall_peclet`), each asked of the coefficient model (:mod:`~persson_fp.solvers.front_fixed.models`:
    nothing to clear or check for the homogenised coefficients).  Returns ``zeta0`` unchanged where it is given; else
    the cleared start-up (None where it is the engine's own choice).  ``stations``: (zeta, V) of
    the output stations; ``name``: the method's, for the messages."""
    pr = problem
    model = model_of(pr)
    p_end = pr.upper_wall.grid_cut(lambda: model.domain_end(pr, k_domain))[0]
    zeta_st, V_st = stations
    V_st = np.asarray(V_st, dtype=float)
    check_resolved(pr, V_st, n, zeta_st, k_domain, p_end)
    mw = MovingWall(pr, n, k_domain, p_end)
    if zeta0 is not None:
        V0 = float(pr.V(zeta0))
        out = zeta0
    else:
        V_own = mw.choose_V0(float(V_st[0]), tau0_fraction)
        V0 = model.clear_start_V(mw, V_own)
        out = None if V0 == V_own else float(zeta_of(pr, V0)[0])
    if V0 > 0.0:
        model.check_wall_peclet(mw, V0, name)
    return out
