"""Text views of a :class:`~persson_fp.Solution` on every problem kind: the one-line summary and the error label
of its repr, with the true error where a closed form exists and the solver's own estimate where none does."""

from __future__ import annotations

import numpy as np

__all__ = ["summary_line", "error_label"]


def summary_line(sol) -> str:
    """The line of :meth:`Solution.summary <persson_fp.Solution.summary>` (see there)."""
    head = f"{sol.method}: n_p={np.shape(sol.p)[-1]}, steps={sol.info.get('steps')}, wall={sol.wall_time * 1e3:.2f} ms"
    plastic = ""
    if sol.plastic_area_all is not None:
        plastic = f", A_pl={float(np.max(sol.plastic_area_all[-1])):.4g}"
    if sol.problem.has_closed_form:
        cmp_ = sol.compare()
        c = cmp_.final()
        return (
            f"{head}, L1={c['L1']:.3e}, |dA*|={c['area_error']:.3e} ({c['area_error_rel']:.2e} relative), "
            f"load drift={c['load_drift']:.3e}{plastic}{_worst_station(sol, cmp_.L1, cmp_.area_error, '=')}"
        )
    law = sol.info.get("load_law")  # general coefficients: the load the first-moment law demands, not p_bar
    target = sol.problem.p_bar if law is None else np.asarray(law, dtype=float).reshape(sol.load_all.shape)[-1]
    drift = float(np.max(np.abs(sol.load_all[-1] - target) / sol.problem.p_bar))
    if law is not None:
        plastic += " (load against the first-moment law)"
    if sol.info.get("error_estimate") is None:
        return f"{head}, no closed form and no error estimate from this method, load drift={drift:.3e}{plastic}"
    e = sol.error_estimate
    dA = float(np.max(e["contact_area"][-1]))
    rel = float(np.max(e["contact_area"][-1] / np.maximum(sol.contact_area_all[-1], 1e-300)))
    return (
        f"{head}, L1~{float(np.max(e['L1'][-1])):.3e}, |dA*|~{dA:.3e} ({rel:.2e} relative) "
        f"(the solver's error estimate; no closed form), load drift={drift:.3e}{plastic}"
        f"{_worst_station(sol, e['L1'], e['contact_area'], '~')}"
    )


def _worst_station(sol, L1, dA, sign) -> str:
    """ ", worst station zeta = z: L1 .., |dA*| .." where an earlier station's L1 exceeds the last one's (the
    accuracy stated for the last station does not hold there); "" otherwise."""
    worst = np.max(np.asarray(L1), axis=-1)  # over loads, per station
    i = int(np.argmax(worst))
    if i == worst.size - 1 or not worst[i] > worst[-1]:
        return ""
    return (
        f"; worst station zeta={sol.zeta[i]:.4g}: L1{sign}{worst[i]:.3e}, "
        f"|dA*|{sign}{float(np.max(np.asarray(dA)[i])):.3e}"
    )


def error_label(sol) -> str:
    """The worst |dA*| at the last station: true ("=") or the solver's estimate ("~"); "?" without either."""
    if not sol.problem.has_closed_form and sol.info.get("error_estimate") is None:
        return "?"
    try:
        e = sol.error_estimate
    except ValueError:  # e.g. a station at zeta = 1, where the exact P0 is a delta
        return "?"
    sign = "=" if sol.problem.has_closed_form else "~"
    return f"{sign}{float(np.max(e['contact_area'][-1])):.2e}"
