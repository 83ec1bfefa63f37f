"""``import persson_fp`` loads numpy, ``scipy.special`` and the light modules only; every public name still resolves.

The heavy parts (the calibration and the sweeps with ``scipy.optimize`` and ``scipy.stats``, the solver families,
the plotting, the optional extras) load when first used.  Checked in a fresh interpreter, by the modules loaded,
never by the time taken.
"""

import importlib
import json
import subprocess
import sys

import pytest

import persson_fp as pf

# Modules that ``import persson_fp`` must not load (a package counts with its submodules).
HEAVY = (
    "scipy.optimize",
    "scipy.stats",
    "scipy.integrate",
    "scipy.sparse",
    "scipy.interpolate",
    "scipy.linalg",
    "matplotlib",
    "pandas",
    "xarray",
    "dask",
    "pde",
    "fipy",
    "SurfaceTopography",
    "persson_fp.calibration",
    "persson_fp.sweeps",
    "persson_fp.plotting",
    "persson_fp.cli",
)


def _loaded_after(statement):
    """The names in ``sys.modules`` of a fresh interpreter after running ``statement``."""
    code = f"import sys, json\n{statement}\nprint(json.dumps(sorted(sys.modules)))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def _heavy_in(loaded):
    return sorted(m for m in loaded if any(m == h or m.startswith(h + ".") for h in HEAVY))


def test_import_loads_no_heavy_module():
    loaded = _loaded_after("import persson_fp")
    assert "scipy.special" in loaded  # the light modules' one scipy part
    assert _heavy_in(loaded) == []


def test_first_problem_loads_neither_the_interface_nor_the_heightmap_import():
    """The gap physics and the height-map import load with their first name, not with the package."""
    loaded = _loaded_after("import persson_fp")
    for lazy in ("persson_fp.analysis.interface", "persson_fp.theory.adhesion", "persson_fp.surfaces.heightmap"):
        assert lazy not in loaded
    loaded = _loaded_after("import persson_fp\npersson_fp.leak_rate")
    assert "persson_fp.analysis.interface" in loaded and "persson_fp.surfaces.heightmap" not in loaded


def test_heavy_names_load_on_first_use():
    loaded = _loaded_after("from persson_fp import calibrate")
    assert "persson_fp.calibration" in loaded
    assert "persson_fp.sweeps" not in loaded  # one heavy name does not pull in the others
    loaded = _loaded_after("import persson_fp\npersson_fp.sweep")
    assert "persson_fp.sweeps" in loaded and "persson_fp.calibration" not in loaded


# Public data (no ``__module__`` of their own) and where they are defined.
DATA = {
    "__version__": "persson_fp._version",
    "METHODS": "persson_fp.solvers.registry",
    "CONVENTIONS": "persson_fp.surfaces.conventions",
    "WEIGHTINGS": "persson_fp.theory.separation",
}


def _defined(name):
    """The object that the module defining the public ``name`` holds under its own name there."""
    if name in pf._LAZY:
        module, attr = pf._LAZY[name]
        return getattr(importlib.import_module(module), attr)
    if name in DATA:
        return getattr(importlib.import_module(DATA[name]), name)
    obj = getattr(pf, name)
    if isinstance(obj, type(pf)):  # a module exported whole (fudge, hardness, adhesion)
        return sys.modules[obj.__name__]
    return getattr(importlib.import_module(obj.__module__), obj.__name__)


@pytest.mark.parametrize("name", pf.__all__)
def test_public_name_is_the_defining_modules_object(name):
    assert getattr(pf, name) is _defined(name)
    assert name in dir(pf)


def test_lazy_names_are_their_modules_objects():
    from persson_fp import calibrate, read_sweep_table
    from persson_fp.calibration.fit import calibrate as defined
    from persson_fp.sweeps.table import read_table

    assert calibrate is defined and read_sweep_table is read_table
    assert pf.calibration is importlib.import_module("persson_fp.calibration")
    assert pf.sweeps is importlib.import_module("persson_fp.sweeps")


def test_unknown_name_raises_attribute_error():
    with pytest.raises(AttributeError, match="no_such_name"):
        pf.no_such_name  # noqa: B018
    assert not hasattr(pf, "no_such_name")
