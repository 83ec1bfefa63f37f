"""Compact text and HTML summaries for results (``__repr__`` / ``_repr_html_`` in notebooks)."""

from __future__ import annotations

import html

import numpy as np

__all__ = ["span", "html_table"]


def span(values, fmt: str = ".6g") -> str:
    """One value as ``x``, several as ``[min, max] (n)``: never the whole array."""
    a = np.asarray(values, dtype=float).ravel()
    if a.size == 0:
        return "[]"
    if a.size == 1:
        return format(float(a[0]), fmt)
    return f"[{format(float(np.nanmin(a)), fmt)}, {format(float(np.nanmax(a)), fmt)}] ({a.size})"


def html_table(title: str, rows: list) -> str:
    """A two-column HTML table (name, value) under a bold title, everything escaped."""
    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(str(k))}</th><td style='text-align:left'>"
        f"{html.escape(str(v))}</td></tr>"
        for k, v in rows
    )
    return f"<div><b>{html.escape(title)}</b><table>{body}</table></div>"
