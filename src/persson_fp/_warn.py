"""Warnings that point at the user's line: the first frame outside persson_fp, however deep the warning is raised."""

from __future__ import annotations

import os
import sys
import warnings

__all__ = ["warn_user"]

_PACKAGE = os.path.dirname(os.path.abspath(__file__))


def warn_user(message: str, category: type[Warning] = UserWarning) -> None:
    """``warnings.warn(message, category)`` attributed to the first caller outside persson_fp (its file and line are
    what the user sees), wherever in the package the warning is raised."""
    level, frame = 1, sys._getframe(0)  # level 1: this function
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE + os.sep):
        frame, level = frame.f_back, level + 1
    warnings.warn(message, category, stacklevel=level)
