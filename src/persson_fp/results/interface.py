"""Old path of the interface front ends -- :func:`~persson_fp.gap_distribution`, :func:`~persson_fp.leak_rate`,
:func:`~persson_fp.contact_conductance`, :func:`~persson_fp.adhesive_contact` (moved to
:mod:`persson_fp.analysis.interface`).

Kept for one release so that existing imports keep working; import from :mod:`persson_fp.analysis.interface` (or
``persson_fp``).
"""

from persson_fp.analysis.interface import (
    LEAK_METHODS,
    AdhesiveContact,
    adhesive_contact,
    contact_conductance,
    gap_distribution,
    leak_rate,
)

__all__ = [
    "gap_distribution",
    "leak_rate",
    "contact_conductance",
    "adhesive_contact",
    "AdhesiveContact",
    "LEAK_METHODS",
]
