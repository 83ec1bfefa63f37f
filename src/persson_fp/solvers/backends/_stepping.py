"""Step placement shared by the fixed-step cell solvers of the generic backends (py-pde, FiPy).

Steps are placed in V (the complete-contact variance) so that every output station is a node;
``step_nodes`` spreads them uniformly in V or in the effective variance tau, ``r_per_step`` gives the
diffusion number of each step, ``_pchip_map`` a smooth pseudo-time map through the stations.
"""

from __future__ import annotations

import numpy as np

from persson_fp.theory.fudge import NoFudge


def _distribute(n_total, L):
    """Integer steps per segment (each >= 1) proportional to the segment lengths ``L``."""
    raw = n_total * L / L.sum()
    n = np.maximum(1, np.floor(raw)).astype(int)
    rest = n_total - n.sum()
    if rest > 0:
        order = np.argsort(-(raw - np.floor(raw)))
        n[order[:rest]] += 1
    return n


def _pchip_map(knots, V_st):
    """(knots, coefficients (3, n_seg) of V'(s) per segment, max V'(s)) of the PCHIP V(s)."""
    from scipy.interpolate import PchipInterpolator

    knots = np.asarray(knots, float)
    if knots.size == 2:
        slope = (V_st[1] - V_st[0]) / (knots[1] - knots[0])
        coef = np.array([[0.0], [0.0], [slope]])
        return knots, coef, float(slope)
    d = PchipInterpolator(knots, V_st).derivative()
    coef = np.ascontiguousarray(d.c.astype(float))
    s = np.linspace(knots[0], knots[-1], 20 * knots.size + 1)
    s = np.concatenate((s, knots))
    return knots, coef, float(np.max(d(s)))


def r_per_step(problem, V_nodes, dp):
    """S(A*_exact) dV / dp^2 per step (rows) and load (columns), with A* at the step start."""
    from scipy.special import erf

    tau = problem.tau_of_V(V_nodes[:-1])
    with np.errstate(divide="ignore"):
        A = erf(problem.p_bar / np.sqrt(2.0 * np.maximum(tau, 1e-300)))
    return problem.fudge.S(A) * (np.diff(V_nodes)[:, None] / dp**2)


def step_nodes(problem, V_st, dp, n_steps, cfl, stepping):
    """V at the step nodes of a fixed-step run, shape (n_steps + 1,), and the station indices.

    ``stepping="V"``: uniform in V within each station segment; ``"tau"``: uniform in the exact
    effective variance tau(V) of the load with the largest tau (so S dV is about constant and
    r = S dV / (2 dp^2) stays at ``cfl``/2: with cfl = 1/3 the leading time error of explicit
    Euler cancels the leading space error, the classical r = 1/6).  Steps per segment are
    proportional to the segment's length in the chosen variable; ``n_steps=None`` takes
    n_steps = ceil(range / (cfl dp^2)) in tau (or max S times the range in V).
    """
    pr = problem
    if stepping == "tau" and not isinstance(pr.fudge, NoFudge):
        j = int(np.argmax(pr.tau_of_V(V_st[-1])))
        Vf = np.unique(np.concatenate((np.linspace(V_st[0], V_st[-1], 4001), V_st)))
        tf = pr.tau_of_V(Vf)[:, j]
        x_st = pr.tau_of_V(V_st)[:, j]
        scale = 1.0
    else:
        Vf = tf = None
        x_st = V_st
        tau_run = pr.tau_of_V(np.linspace(V_st[0], V_st[-1], 401))
        from scipy.special import erf

        with np.errstate(divide="ignore"):
            A = erf(pr.p_bar / np.sqrt(2.0 * np.maximum(tau_run, 1e-300)))
        scale = float(np.max(pr.fudge.S(A)))
    L = np.diff(x_st)
    n_total = n_steps
    if n_total is None:
        n_total = int(np.ceil(scale * (x_st[-1] - x_st[0]) / (cfl * dp**2)))
    n_total = max(n_total, L.size)
    n_k = _distribute(n_total, L)
    parts = [np.array([V_st[0]])]
    for k, n in enumerate(n_k):
        x = np.linspace(x_st[k], x_st[k + 1], n + 1)[1:]
        if Vf is not None:
            V = np.interp(x, tf, Vf)
            V[-1] = V_st[k + 1]
        else:
            V = x
        parts.append(V)
    V_nodes = np.concatenate(parts)
    idx = np.concatenate(([0], np.cumsum(n_k)))
    V_nodes[idx] = V_st
    return V_nodes, idx
