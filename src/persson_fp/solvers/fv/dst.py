r"""The DST-II basis of the ``"fv"`` solver's spectral fast path: the eigenvalues of its operators, the transform,
and the amplification factors of the θ-schemes and TR-BDF2 in that basis.

The march that uses them is :mod:`persson_fp.solvers.fv.spectral`; the operators they diagonalise are in
:mod:`persson_fp.solvers.fv.operators`.
"""

from __future__ import annotations

import numpy as np
from scipy import fft as _fft

from persson_fp.solvers.fv.operators import SPACES
from persson_fp.solvers.schemes import TRBDF2_A, TRBDF2_B, TRBDF2_GAMMA, TRBDF2_W


# -- the spectral fast path: L and M are diagonal in the DST-II basis ------------------------------
def dst_eigenvalues(n_p: int, dp: float, space: str = "fv2"):
    r"""Eigenvalues of L (:func:`banded_operator`) and of M (``apply_mass``) in the DST-II basis.

    Both are diagonalised *exactly* by the orthonormal cell-centred sines
    :math:`\phi_j(i) \propto \sin(\pi j (i+\tfrac12)/n_p)`, j = 1..n_p (odd about both walls, so the
    odd ghost cells hold for every j):
    :math:`\mu_j = -\frac{2}{\Delta p^2}\sin^2\frac{\pi j}{2 n_p}` and
    :math:`m_j = m_d + 2 m_o \cos\frac{\pi j}{n_p}` (compact4: :math:`(10 + 2\cos(\pi j/n_p))/12`).

    Returns
    -------
    mu : ndarray (n_p,), 1/pressure^2
    m : ndarray (n_p,)
    """
    j = np.arange(1, n_p + 1)
    s2 = np.sin(0.5 * np.pi * j / n_p) ** 2
    md, mo = SPACES[space]
    return -(2.0 / dp**2) * s2, md + 2.0 * mo * (1.0 - 2.0 * s2)


class _Spectral:
    """The DST-II pair of the fast path and the linear functionals it needs in coefficient space."""

    def __init__(self, n_p: int, dp: float, space: str):
        mu, m_eig = dst_eigenvalues(n_p, dp, space)
        self.lam = mu / m_eig  # eigenvalues of M^-1 L
        self.transforms = 0
        unit = np.zeros((3, n_p))
        unit[0] = 1.0  # sum_i P_i
        unit[1, 0] = 1.0  # P_0 (wall p = 0)
        unit[2, -1] = 1.0  # P_{n-1} (wall p = p_max)
        E = self.forward(unit)  # <v, P> = <S v, S P> (S orthogonal)
        # a 4th (zero) column: with 3, numpy's matmul of (1000, 250) @ (250, 3) is ~20x slower than with 4
        self.functionals = np.ascontiguousarray(np.stack([E[0] * dp, E[1] / dp, E[2] / dp, 0.0 * E[0]], axis=1))
        """(n_p, 4): coefficients -> (sum P dp, wall flux at 0, wall flux at p_max, 0)."""
        self.transforms = 0  # count the run's transforms only

    def forward(self, P):
        self.transforms += 1
        return _fft.dst(P, type=2, norm="ortho", axis=-1)

    def inverse(self, C):
        self.transforms += 1
        return _fft.idst(C, type=2, norm="ortho", axis=-1)


def _amplification(kind: str, theta: float, x, work=None):
    r"""Per-mode amplification R and wall-flux weight F of one step, with x = dtau lambda_j.

    One step maps the DST coefficient :math:`c_j` to :math:`R_j c_j`; the outflow through a wall
    over the step is :math:`\Delta\tau\sum_j F_j c_j \phi_j(\text{wall})/\Delta p`, F being the
    scheme's stage weights applied to the wall flux (exactly what the banded path accumulates).
    ``kind``: "theta" (θ-step), "be-halves" (two backward-Euler half steps, the Rannacher start)
    or "tr-bdf2".  ``work``: optional three arrays of x's shape (R, F, scratch) written in place
    (no temporaries: for 1000 loads allocating them costs more than the arithmetic).
    """
    R, F, T = work if work is not None else (np.empty_like(x), np.empty_like(x), np.empty_like(x))
    if kind == "tr-bdf2":
        # both stages share 1 - h, h = gamma x / 2 = W x: the trapezoidal stage is Rs = (1 + h)/(1 - h),
        # then R = (A Rs - B)/(1 - h) = (1 + (A + B) h)/(1 - h)^2 (A - B = 1) and the wall-flux weight
        # F = (A gamma / 2)(Rs + 1) + W R = A gamma/(1 - h) + W R
        np.multiply(x, -TRBDF2_W, out=T)
        T += 1.0
        np.divide(1.0, T, out=T)  # 1/(1 - h)
        np.multiply(x, (TRBDF2_A + TRBDF2_B) * TRBDF2_W, out=R)
        R += 1.0
        R *= T
        R *= T
        np.multiply(R, TRBDF2_W, out=F)
        T *= TRBDF2_A * TRBDF2_GAMMA
        F += T
    elif kind == "be-halves":
        np.multiply(x, -0.5, out=T)
        T += 1.0
        np.divide(1.0, T, out=T)  # Rh
        np.multiply(T, T, out=R)
        np.add(T, R, out=F)
        F *= 0.5
    else:
        np.multiply(x, -theta, out=T)
        T += 1.0  # 1 - theta x
        np.multiply(x, 1.0 - theta, out=R)
        R += 1.0
        R /= T
        np.multiply(R, theta, out=F)
        F += 1.0 - theta
    return R, F


def _growth(kind: str, theta: float, x):
    """The amplification factor R of ``_amplification`` alone (no wall-flux weight): the trajectory
    sweeps of the fudge coupling need only R."""
    if kind == "tr-bdf2":
        T = 1.0 / (1.0 - TRBDF2_W * x)
        return (1.0 + ((TRBDF2_A + TRBDF2_B) * TRBDF2_W) * x) * (T * T)
    if kind == "be-halves":
        T = 1.0 / (1.0 - 0.5 * x)
        return T * T
    return (1.0 + (1.0 - theta) * x) / (1.0 - theta * x)
