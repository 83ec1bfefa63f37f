"""A small conservative finite-volume Reynolds solver for the flow through a gap field (and a `reynoldsflow` wrapper).

Steady incompressible Reynolds flow in the gap g(x, y) between two surfaces (Lorenz & Persson, EPJE 31 (2010) 159;
the reference against which the theory's leak rate is compared, see ``benchmarks/interface_vs_bem.py``):

    div( c(x, y) grad p ) = 0,        c = g^3 / (12 eta)        (local Poiseuille conductance, m^3/(Pa s))

on the periodic square [0, L)^2 sampled on an N x N grid of cells.  The flow runs along ``axis`` (0 by default):
reservoirs at pressure ``pressure_drop`` (inlet, the face before the first cell) and 0 (outlet, the face after the
last cell), periodic across.  Cells with g <= 0 (in contact) are blocked.

Discretisation (cell-centred finite volumes, 5-point stencil): the conductance of the face between two open cells is
the harmonic mean 2 c_a c_b / (c_a + c_b) of the cell conductances (exact for two resistors in series), zero when
either cell is blocked; a reservoir face sits half a cell from the cell centre, so its conductance is 2 c.  Only the
open clusters that touch both reservoirs carry a net flow (any other cluster is at the pressure of the reservoir it
touches, or carries nothing); they are found with a graph search first, so the linear system is non-singular, and it
is solved directly (SuperLU): the flux leaving the inlet equals the flux entering the outlet to round-off (1e-12 of Q
on the BEM gap fields up to p̄/(E*ḡ) = 0.1; ~1e-8 near percolation, where Q is ~1e-7 of the open-channel flow and the
reservoir-face pressure differences it comes from are that small a fraction of the pressure drop).

Returned Q is the volume flow rate through the whole cross-section (m^3/s for a length L); for a square of side L the
flow per unit width per unit pressure gradient is K = Q / pressure_drop (what ``data/bem/leakage_H0.8.csv`` calls K).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import spsolve


def _check(gap, viscosity, pressure_drop, axis):
    g = np.asarray(gap, dtype=float)
    if g.ndim != 2 or min(g.shape) < 2:
        raise ValueError(f"gap must be a 2-D array with at least 2 x 2 cells, got shape {g.shape}")
    if not np.all(np.isfinite(g)):
        raise ValueError("gap must be finite everywhere (use 0 for contact cells)")
    if not (np.isfinite(viscosity) and viscosity > 0):
        raise ValueError(f"viscosity must be finite and > 0, got {viscosity!r}")
    if not np.isfinite(pressure_drop):
        raise ValueError(f"pressure_drop must be finite, got {pressure_drop!r}")
    if axis not in (0, 1):
        raise ValueError(f"axis must be 0 or 1, got {axis!r}")
    return g if axis == 0 else g.T


def _links(open_):
    """Index pairs of neighbouring open cells: along the flow (not periodic) and across it (periodic)."""
    n0, n1 = open_.shape
    idx = np.arange(n0 * n1).reshape(n0, n1)
    a_x, b_x = idx[:-1, :].ravel(), idx[1:, :].ravel()
    a_y, b_y = idx.ravel(), np.roll(idx, -1, axis=1).ravel()
    if n1 == 2:  # both periodic neighbours are the same cell: one link, not two
        a_y, b_y = idx[:, 0], idx[:, 1]
    flat = open_.ravel()
    keep_x = flat[a_x] & flat[b_x]
    keep_y = flat[a_y] & flat[b_y]
    return (a_x[keep_x], b_x[keep_x]), (a_y[keep_y], b_y[keep_y])


def percolating_cells(gap, axis=0):
    """Boolean mask of the open cells (g > 0) in clusters that touch both reservoirs of the flow along ``axis``."""
    g = _check(gap, 1.0, 1.0, axis)
    open_ = g > 0
    n = open_.size
    (ax, bx), (ay, by) = _links(open_)
    a, b = np.concatenate((ax, ay)), np.concatenate((bx, by))
    graph = sp.coo_matrix((np.ones(a.size), (a, b)), shape=(n, n))
    _, labels = connected_components(graph, directed=False)
    labels = labels.reshape(open_.shape)
    inlet = set(labels[0][open_[0]].tolist())
    outlet = set(labels[-1][open_[-1]].tolist())
    both = np.array(sorted(inlet & outlet), dtype=int)
    mask = open_ & np.isin(labels, both)
    return mask if axis == 0 else mask.T


def flow(gap, viscosity=1.0, pressure_drop=1.0, axis=0, length=1.0):
    """Reynolds flow through ``gap`` (N0 x N1 cells of a periodic L x L square; length L in the units of g).

    Returns a dict: ``Q`` (flow rate through the cross-section, the mean of inflow and outflow), ``inflow``,
    ``outflow``, ``percolates`` (a cluster of open cells joins the two reservoirs), ``pressure`` (N0 x N1, NaN on
    blocked and non-percolating cells; in the input orientation).
    """
    g = _check(gap, viscosity, pressure_drop, axis)
    if not (np.isfinite(length) and length > 0):
        raise ValueError(f"length must be finite and > 0, got {length!r}")
    n0, n1 = g.shape
    dx, dy = length / n0, length / n1
    live = percolating_cells(g, axis=0)
    pressure = np.full(g.shape, np.nan)
    out = dict(Q=0.0, inflow=0.0, outflow=0.0, percolates=bool(live.any()))
    if not live.any():
        out["pressure"] = pressure if axis == 0 else pressure.T
        return out
    c = np.where(live, g, 0.0) ** 3 / (12.0 * viscosity)
    dof = -np.ones(g.shape, dtype=np.int64)
    dof[live] = np.arange(int(live.sum()))
    m = int(live.sum())
    (ax, bx), (ay, by) = _links(live)
    cf = c.ravel()
    kx = 2 * cf[ax] * cf[bx] / (cf[ax] + cf[bx]) * (dy / dx)  # face conductance x face area / distance
    ky = 2 * cf[ay] * cf[by] / (cf[ay] + cf[by]) * (dx / dy)
    d = dof.ravel()
    a = np.concatenate((d[ax], d[ay]))
    b = np.concatenate((d[bx], d[by]))
    k = np.concatenate((kx, ky))
    diag = np.bincount(a, k, m) + np.bincount(b, k, m)
    rhs = np.zeros(m)
    k_in = 2 * c[0] * dy / dx  # reservoir faces: half a cell from the centre
    k_out = 2 * c[-1] * dy / dx
    j_in, j_out = np.flatnonzero(live[0]), np.flatnonzero(live[-1])
    diag += np.bincount(dof[0, j_in], k_in[j_in], m) + np.bincount(dof[-1, j_out], k_out[j_out], m)
    rhs += np.bincount(dof[0, j_in], k_in[j_in] * pressure_drop, m)
    rows = np.concatenate((a, b, np.arange(m)))
    cols = np.concatenate((b, a, np.arange(m)))
    vals = np.concatenate((-k, -k, diag))
    matrix = sp.csc_matrix((vals, (rows, cols)), shape=(m, m))
    p = np.atleast_1d(spsolve(matrix, rhs))
    pressure[live] = p
    inflow = float(np.sum(k_in[j_in] * (pressure_drop - pressure[0, j_in])))
    outflow = float(np.sum(k_out[j_out] * pressure[-1, j_out]))
    out.update(Q=0.5 * (inflow + outflow), inflow=inflow, outflow=outflow)
    out["pressure"] = pressure if axis == 0 else pressure.T
    return out


def flow_reynoldsflow(gap, viscosity=1.0, pressure_drop=1.0, axis=0):
    """The same flow (L = 1) with the ``reynoldsflow`` package's direct solver (optional ``bem`` extra).

    ``reynoldsflow.transport.solve_fluid_problem`` solves div(g^3 grad p) = 0 with reservoirs 0 and 1 along axis 0,
    periodic across, harmonic-mean faces; its total flux is scaled here by pressure_drop / (12 eta).
    """
    from reynoldsflow import transport

    g = _check(gap, viscosity, pressure_drop, axis)
    if g.shape[0] != g.shape[1]:
        raise ValueError(f"reynoldsflow needs a square gap field, got shape {g.shape}")
    if not np.any(g > 0):
        return dict(Q=0.0, percolates=False)
    filtered, _, flux = transport.solve_fluid_problem(np.ascontiguousarray(g), solver="scipy-spsolve")
    if filtered is None:
        return dict(Q=0.0, percolates=False)
    q, _ = transport.compute_total_flux(filtered, flux, g.shape[0])
    return dict(Q=float(q) * pressure_drop / (12.0 * viscosity), percolates=True)
