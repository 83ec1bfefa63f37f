"""The analytic front ends stay importable from the module paths they had before they got their own folder
(``persson_fp.results.exact``, ``.energy`` and ``.interface``, for one release): the old paths re-export the very
same objects, and the top-level names are the ones of :mod:`persson_fp.analysis`."""

from __future__ import annotations

import importlib

import pytest

import persson_fp as pf

MOVED = {
    "persson_fp.results.exact": "persson_fp.analysis.exact",
    "persson_fp.results.energy": "persson_fp.analysis.energy",
    "persson_fp.results.interface": "persson_fp.analysis.interface",
}


@pytest.mark.parametrize("old", sorted(MOVED))
def test_old_path_re_exports_the_same_objects(old):
    before, now = importlib.import_module(old), importlib.import_module(MOVED[old])
    assert set(now.__all__) <= set(before.__all__), set(now.__all__) - set(before.__all__)
    for name in before.__all__:
        assert getattr(before, name) is getattr(now, name), name


def test_top_level_names_come_from_analysis():
    sep = importlib.import_module("persson_fp.analysis.separation")
    assert pf.mean_separation is sep.mean_separation and pf.contact_stiffness is sep.contact_stiffness
    for old, new in MOVED.items():
        module = importlib.import_module(new)
        for name in module.__all__:
            if name in pf.__all__:
                assert getattr(pf, name) is getattr(module, name), (old, name)


def test_theory_keeps_the_spectrum_taking_separation():
    """theory.separation keeps what takes a spectrum (MeanSeparation, separation_from_areas); the problem-taking
    front ends live in analysis only (theory imports no problem or analysis module)."""
    theory = importlib.import_module("persson_fp.theory.separation")
    assert set(theory.__all__) == {"WEIGHTINGS", "MeanSeparation", "separation_from_areas"}
    assert pf.MeanSeparation is theory.MeanSeparation and pf.separation_from_areas is theory.separation_from_areas
