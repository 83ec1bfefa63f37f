"""Every public name of the package has a property test: a function decorated with ``@given`` somewhere under
tests/ that refers to it (read from the test files themselves, see :mod:`.publicnames`), so that a new feature
cannot land unfuzzed.  Values (constants such as ``METHODS``) are exempt from that, but a test must name them (a
test of their contents)."""

from __future__ import annotations

from types import ModuleType

import persson_fp as pf

from .publicnames import coverage, is_constant, public_surface


def test_every_public_callable_has_a_property_test():
    surface = public_surface()
    given_cov, _ = coverage()
    missing = sorted(n for n, tests in given_cov.items() if not tests and not is_constant(surface[n]))
    assert not missing, f"public names without a property test (@given) that uses them: {missing}"


def test_every_public_constant_is_named_by_a_test():
    _, const_cov = coverage()
    missing = sorted(n for n, files in const_cov.items() if not files)
    assert not missing, f"public constants that no test names (a test of their contents is needed): {missing}"


def test_the_public_surface_is_what_the_package_exports():
    """The surface is computed from ``__all__`` (and the ``__all__`` of the modules listed there), so it follows the
    package; the scanner resolves a reference through ``pf.X``, ``pf.module.X`` and names imported from any module."""
    surface = public_surface()
    modules = {n for n in pf.__all__ if isinstance(getattr(pf, n), ModuleType)}
    assert {"fudge", "hardness", "adhesion", "viscoelastic"} <= modules
    assert set(pf.__all__) - modules <= set(surface)
    assert surface["fudge.YangPersson"] is pf.fudge.YangPersson
    assert all(f"{m}.{n}" in surface for m in modules for n in getattr(pf, m).__all__)
