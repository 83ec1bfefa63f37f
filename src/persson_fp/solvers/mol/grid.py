"""The grid of the ``"mol"`` solver: finite-difference Laplacians (2nd and 4th order), their readable form, the
quadrature weights of area and load, the semi-discrete system (:class:`MOLSystem`), and the start from the
exact solution (:func:`start_V`, :func:`start_pdf`).

The driver that integrates the system in V with ``scipy.integrate.solve_ivp`` is :mod:`persson_fp.solvers.mol`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.optimize import brentq

from persson_fp.theory.fudge import NoFudge
from persson_fp.theory.image import image_pdf
from persson_fp.theory.strip import strip_pdf


def laplacian(m: int, h: float, order: int = 2) -> sp.csr_matrix:
    """d^2/dp^2 on the ``m`` interior nodes with P = 0 at both walls (1/pressure^2).

    ``order=4`` closes the five-point stencil with the odd extension about
    each wall (ghost P_{-1} = -P_1), see the module docstring.
    """
    if order == 2:
        L = sp.diags([np.ones(m - 1), -2.0 * np.ones(m), np.ones(m - 1)], [-1, 0, 1], shape=(m, m))
        return (L / h**2).tocsr()
    d0 = -30.0 * np.ones(m)
    d0[0] += 1.0  # ghost -P_1 enters with weight -1: -(-P_1)
    d0[-1] += 1.0
    L = sp.diags(
        [-np.ones(m - 2), 16.0 * np.ones(m - 1), d0, 16.0 * np.ones(m - 1), -np.ones(m - 2)],
        [-2, -1, 0, 1, 2],
        shape=(m, m),
    )
    return (L / (12.0 * h**2)).tocsr()


def laplacian_readable(P: np.ndarray, h: float, order: int = 2) -> np.ndarray:
    """The same operator as :func:`laplacian`, written with ghost values on the last axis of ``P``."""
    z = np.zeros(P.shape[:-1] + (1,))
    if order == 2:
        Q = np.concatenate([z, P, z], axis=-1)  # walls
        return (Q[..., :-2] - 2.0 * Q[..., 1:-1] + Q[..., 2:]) / h**2
    Q = np.concatenate([-P[..., :1], z, P, z, -P[..., -1:]], axis=-1)  # odd ghosts, walls
    return (-Q[..., :-4] + 16.0 * Q[..., 1:-3] - 30.0 * Q[..., 2:-2] + 16.0 * Q[..., 3:-1] - Q[..., 4:]) / (12.0 * h**2)


def quadrature_weights(n_p: int, h: float, order: int = 2) -> np.ndarray:
    """Weights on all ``n_p`` nodes (pressure): trapezoid (order 2) or Gregory's 4th-order rule (order 4)."""
    w = np.full(n_p, h)
    if order == 2:
        w[[0, -1]] = 0.5 * h
    else:
        end = h * np.array([3.0 / 8.0, 7.0 / 6.0, 23.0 / 24.0])
        w[:3] = end
        w[-3:] = end[::-1]
    return w


@dataclass
class MOLSystem:
    """The semi-discrete system handed to ``solve_ivp`` (exposed for tests and studies).

    ``fun`` is the fast (sparse) right-hand side, ``fun_readable`` the plain
    numpy one, ``jac`` the exact Jacobian (sparse) or None.
    """

    fun: object
    fun_readable: object
    jac: object
    y0: np.ndarray
    t0: float
    t1: float
    n_loads: int
    m: int
    augmented: bool


def start_V(pr, tau0: float) -> np.ndarray:
    """Complete-contact variance (pressure^2) at which each load of problem ``pr`` reaches the effective variance
    ``tau0`` (the start of the march from the exact solution)."""
    if isinstance(pr.fudge, NoFudge):
        return np.full(pr.n_loads, tau0)
    if pr.hardness is None:  # the inverse of the same effective-variance table, all loads at once (~1e-13)
        return pr.V_of_tau_each(np.full(pr.n_loads, float(tau0)))
    S1 = float(pr.fudge.S(np.array(1.0)))
    out = np.empty(pr.n_loads)
    V_max = float(pr.V(pr.zeta_max))
    for j, pb in enumerate(pr.p_bar):
        if pb / np.sqrt(2.0 * tau0) >= 6.0:  # A* = 1 to round-off until tau0: tau = S(1) V exactly
            out[j] = tau0 / S1
            continue
        sub = pr.with_loads(pb)
        out[j] = brentq(lambda v, s=sub: float(s.tau_of_V(v)[0]) - tau0, 0.0, 2 * V_max, xtol=1e-300, rtol=1e-15)
    return out


def start_pdf(pr, p, p_bar, tau):
    """The exact PDF at the start: the image solution, or the strip's with a constant hardness."""
    hard = pr.hardness
    if hard is None:
        return image_pdf(p, p_bar, tau)
    return strip_pdf(p, p_bar, float(hard.sigma(1.0)), tau)
