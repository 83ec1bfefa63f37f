"""Old path of :func:`~persson_fp.elastic_energy` and :func:`~persson_fp.pressure_spectrum` (moved to
:mod:`persson_fp.analysis.energy`).

Kept for one release so that existing imports keep working; import from :mod:`persson_fp.analysis.energy` (or
``persson_fp``).
"""

from persson_fp.analysis.energy import elastic_energy, pressure_spectrum

__all__ = ["pressure_spectrum", "elastic_energy"]
