"""Boundary-element contact with Tamaas (optional ``bem`` extra): the gap fields behind ``interface_vs_bem.py``.

Frictionless normal contact of a linear-elastic half-space (E* = 1) with a periodic rigid rough surface h on the
unit square, solved by Tamaas 2.9.0's ``PolonskyKeerRey`` (Polonsky & Keer, Wear 231 (1999) 206: constrained
conjugate gradient at prescribed mean pressure), tolerance 1e-10, as the shipped data in ``data/bem`` were made.

The gap is g = u - h - c with c its (constant, to ~1e-13) value on the contact points p > 0, so g = 0 in contact.

Exponential adhesion sigma(g) = (w/rho) exp(-g/rho) (an attraction, Pa) on the whole area: the elastic displacement
of the attraction is -K[sigma] with K the half-space compliance, u_q = 2 p_q / (E* |q|) (Johnson, Contact Mechanics,
the periodic form used by the BEM), so the contact at a prescribed mean *repulsive* pressure p_rep is a non-adhesive
one with the surface h + K[sigma]; a fixed-point loop on sigma around Tamaas's non-adhesive solver converges because
the attraction's compliance is small (max |d sigma| / (w/rho) < 1e-9 in ~10 loops here).  The applied mean traction
is p_rep - <sigma>, and the pull-off stress is -min of it over a path of p_rep.
"""

from __future__ import annotations

import contextlib
import os
import sys

import numpy as np

E_STAR = 1.0


def have_tamaas() -> bool:
    try:
        import tamaas  # noqa: F401
    except ImportError:
        return False
    return True


@contextlib.contextmanager
def quiet():
    """Send the C++ library's std::cout / std::cerr to /dev/null for the duration."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    null = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(null, 1)
        os.dup2(null, 2)
        yield
    finally:
        sys.stdout.flush()
        sys.stderr.flush()
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, null):
            os.close(fd)


def compliance(p, length=1.0, e_star=E_STAR):
    """K[p]: the half-space displacement (zero mean) of a periodic traction field p, u_q = 2 p_q / (E* |q|)."""
    n0, n1 = p.shape
    qx = 2 * np.pi * np.fft.fftfreq(n0, d=length / n0)
    qy = 2 * np.pi * np.fft.rfftfreq(n1, d=length / n1)
    q = np.hypot(qx[:, None], qy[None, :])
    q[0, 0] = np.inf
    return np.fft.irfft2(np.fft.rfft2(p) * 2.0 / (e_star * q), s=p.shape)


class Contact:
    """One Tamaas model and solver for a surface h (N x N on the unit square)."""

    def __init__(self, h, tol=1e-10):
        import tamaas as tm

        tm.set_log_level(tm.LogLevel.error)
        self.h = np.ascontiguousarray(h, dtype=float)
        n = self.h.shape[0]
        self.surface = self.h.copy()  # the solver keeps this buffer: adhesion rewrites it in place
        with quiet():
            self.model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
            self.model.E, self.model.nu = E_STAR, 0.0  # E* = E/(1 - nu^2) = 1
            self.solver = tm.PolonskyKeerRey(self.model, self.surface, tol)
        self.solver.max_iter = 200000
        self.solver.dump_freq = 10**9

    def solve(self, pbar):
        """Solve at mean pressure ``pbar``; return (p, gap) with the gap zero in contact."""
        with quiet():
            err = self.solver.solve(float(pbar))
        p = np.array(self.model.traction, dtype=float, copy=True)
        u = np.array(self.model.displacement, dtype=float, copy=True)
        if not err < 1e-6:
            raise RuntimeError(f"Tamaas did not converge at pbar={pbar:g} (error {err:.3g})")
        contact = p > 0
        gap = u - self.surface
        gap -= gap[contact].mean()
        spread = np.ptp(gap[contact]) if contact.any() else 0.0
        if spread > 1e-8 * self.h.std() or gap[~contact].min(initial=0.0) < -1e-8 * self.h.std():
            raise RuntimeError(f"gap not constant in contact / negative outside (spread {spread:.3g})")
        gap[contact] = 0.0
        np.maximum(gap, 0.0, out=gap)
        return p, u, gap

    def check_compliance(self, p, u):
        """Relative difference of Tamaas's displacement and K[p] (up to the mean): the Green's function used."""
        d = u - compliance(p)
        return float(np.ptp(d) / np.ptp(u))

    def adhesive(self, p_rep, w, rho, tol=1e-9, max_loops=200):
        """Exponential adhesion at prescribed mean repulsive pressure ``p_rep``: a dict of the averages."""
        s0 = w / rho
        sigma = None
        loop = 0
        while loop < max_loops:
            loop += 1
            self.surface[...] = self.h if sigma is None else self.h + compliance(sigma)
            p, _, gap = self.solve(p_rep)
            new = s0 * np.exp(-gap / rho)
            change = np.inf if sigma is None else float(np.max(np.abs(new - sigma)) / s0)
            sigma = new
            if change < tol:
                break
        if change >= tol:
            raise RuntimeError(f"adhesion loop did not converge at p_rep={p_rep:g}, w={w:g} ({change:.3g})")
        self.surface[...] = self.h
        mean_att = -float(sigma.mean())
        return dict(
            mean_p=float(p.mean()) + mean_att,
            mean_p_rep=float(p.mean()),
            mean_p_att=mean_att,
            A_rep=float(np.mean(p > 0)),
            mean_gap=float(gap.mean()),
            loops=loop,
            converged=True,
        )


def surface_from_modes(path, n):
    """The shipped surface on an n x n grid: its Fourier modes k = -64..64 put at index k % n, real(ifft2 * n^2)."""
    d = np.load(path)
    k = np.asarray(d["k"], dtype=int)
    if n < 2 * int(np.abs(k).max()) + 1:
        raise ValueError(f"N must be >= {2 * int(np.abs(k).max()) + 1} to hold the surface's modes, got {n}")
    hq = np.zeros((n, n), dtype=complex)
    hq[np.ix_(k % n, k % n)] = d["hq"]
    return np.ascontiguousarray(np.real(np.fft.ifft2(hq) * n * n))
