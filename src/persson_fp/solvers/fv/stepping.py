"""Where ``"fv"`` puts its steps: node placement in V from the closed-form effective variance, and which steps are
damped.

"graded" (the default): uniform in s = T + g ln T with T = tau (or, with a constant hardness, tau saturating on the
strip's time scale sigma_Y^2), g = ``GRADE`` T_max (:mod:`persson_fp.solvers.schemes`): geometric while tau is small,
uniform later; "tau", "geometric" and "zeta" as in :class:`~persson_fp.solvers.fv.FiniteVolumeSolver`'s options.
Every output station is a node.
"""

from __future__ import annotations

import numpy as np

from persson_fp.solvers.schemes import GRADE, graded
from persson_fp.theory.fudge import NoFudge

__all__ = ["STEPPINGS", "step_nodes", "damped_steps", "step_kind"]

STEPPINGS = ("geometric", "zeta", "tau", "graded")


def damped_steps(opts) -> int:
    """Leading steps done as two backward-Euler half steps: Rannacher's start-up, and TR-BDF2's
    from a delta (its amplification factor is negative for dtau |lambda| > ~2.4: one-step
    2nd-order schemes cannot be positive for every step size, so rough data would ring)."""
    if opts["scheme"] == "rannacher" or (opts["scheme"] == "tr-bdf2" and opts["initial"] == "delta"):
        return opts["rannacher_steps"]
    return 0


def step_kind(opts, n: int) -> str:
    """The kind of step n: "be-halves" (damped), "tr-bdf2" or "theta"."""
    if n < damped_steps(opts):
        return "be-halves"
    return "tr-bdf2" if opts["scheme"] == "tr-bdf2" else "theta"


def step_nodes(problem, opts, zeta0: float, V0: float, zeta_out, V_out):
    """V at the step nodes, shape (n_nodes, n_loads), and the step index of each station (every station is a node).

    ``opts``: ``"fv"``'s options (``stepping``, ``n_steps``); the march starts at (zeta0, V0)."""
    o, pr = opts, problem
    V_st = np.concatenate(([V0], V_out))
    z_st = np.concatenate(([zeta0], zeta_out))
    m = pr.n_loads
    if o["stepping"] == "zeta":
        s = z_st
    elif o["stepping"] == "geometric":
        s = np.log(np.maximum(V_st, 1e-3 * V_st[1]))
    else:  # tau of the largest-tau load decides the split; nodes per load below
        s = np.max(pr.tau_of_V(V_st), axis=-1)
        if o["stepping"] == "graded":  # (the offset 1e-3 g keeps a delta start, tau = 0, finite)
            tau_st = s
            warp = _warp(pr)
            g = GRADE * float(warp(tau_st[-1]))
            s = graded(warp(tau_st), float(warp(tau_st[-1])), offset=1e-3)
    lengths = np.diff(s)
    n_seg = len(lengths)
    counts = np.maximum(1, np.round(o["n_steps"] * lengths / max(s[-1] - s[0], 1e-300)).astype(int))
    while counts.sum() > max(o["n_steps"], n_seg):
        counts[np.argmax(counts)] -= 1
    while counts.sum() < o["n_steps"]:
        counts[np.argmax(lengths / counts)] += 1
    pieces = [np.full((1, m), V_st[0])]
    for i in range(n_seg):
        t = np.linspace(0.0, 1.0, counts[i] + 1)[1:]
        Va, Vb = V_st[i], V_st[i + 1]
        if o["stepping"] == "zeta":
            V = np.atleast_1d(pr.V(z_st[i] + t * (z_st[i + 1] - z_st[i])))[:, None] * np.ones(m)
        elif o["stepping"] == "geometric":
            lo = max(Va, 1e-3 * V_st[1])
            V = np.exp(np.log(lo) + t * (np.log(Vb) - np.log(lo)))[:, None] * np.ones(m)
        elif o["stepping"] == "graded":  # uniform in s within the segment, mapped to tau fractions
            ta, tb = tau_st[i], tau_st[i + 1]
            tt = ta + np.geomspace(1e-3 * g, tb - ta + 1e-3 * g, 513) - 1e-3 * g
            ss = graded(warp(tt), float(warp(tau_st[-1])), offset=1e-3)
            tau_t = np.interp(s[i] + t * (s[i + 1] - s[i]), ss, tt)
            V = _uniform_tau_nodes(pr, Va, Vb, (tau_t - ta) / max(tb - ta, 1e-300))
        else:
            V = _uniform_tau_nodes(pr, Va, Vb, t)
        V[-1] = Vb  # land on the station exactly
        pieces.append(V)
    return np.concatenate(pieces, axis=0), np.cumsum(counts)


def _warp(problem):
    """tau as the graded stepping sees it: tau itself, or with a constant hardness
    T = c (1 - exp(-tau / c)), c = 30 sigma_Y^2: the strip forgets its start on the time scale sigma_Y^2
    (the elastic area decays like exp(-pi^2 tau / (2 sigma_Y^2))), so steps are spent before that, not
    spread uniformly over a tau far beyond it."""
    pr = problem
    if pr.hardness is None:
        return lambda t: np.asarray(t, dtype=float)
    c = 30.0 * float(pr.hardness.sigma(1.0)) ** 2
    return lambda t: -c * np.expm1(-np.asarray(t, dtype=float) / c)


def _uniform_tau_nodes(problem, Va, Vb, t):
    """V nodes at the tau fractions ``t`` between tau(Va) and tau(Vb), per load, shape (len(t), n_loads).

    The closed-form tau of each load, inverted exactly (:meth:`~persson_fp.ContactProblem.V_of_tau_each`).
    """
    pr = problem
    if Vb <= Va:
        return np.full((t.size, pr.n_loads), Vb)
    if isinstance(pr.fudge, NoFudge):
        return (Va + t * (Vb - Va))[:, None] * np.ones(pr.n_loads)
    ta, tb = pr.tau_of_V(np.array([Va, Vb]))  # (n_loads,) each
    V = pr.V_of_tau_each(ta + t[:, None] * (tb - ta))
    return np.minimum(np.maximum(V, Va), Vb)  # (round-off of the inverse table kept inside the segment)
