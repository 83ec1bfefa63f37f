"""The package's layout, held by machine checks so that it cannot drift silently.

- The layering (one folder per concept, imports pointing one way) as import-linter contracts in ``pyproject.toml``
  (``[tool.importlinter]``): a broken contract fails with import-linter's report of the offending chain.
- No module imports a private name (``_x``) or a private module from another folder: a folder's helpers are its own.
- ``persson_fp/solvers`` keeps its front small: at most :data:`SOLVERS_FRONT_MAX` plain modules beside the family
  folders (the re-exports of old module paths apart).
- A soft ceiling of ~800 lines a module: above it a module most likely does two things.
"""

from __future__ import annotations

import ast
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PKG = ROOT / "src" / "persson_fp"

SOLVERS_FRONT_MAX = 8
"""Plain modules at the top of ``persson_fp/solvers`` (``__init__`` and the old-path re-exports not counted)."""
OLD_PATH_REEXPORTS = {"chapman_kolmogorov.py", "monte_carlo.py"}
"""Old module paths of moved solver classes, kept for one release (they only re-export)."""
SOFT_CEILING = 800
"""Lines a module may have."""
SOLVER_FAMILIES = {"sines", "fv", "mol", "chebyshev", "markov", "backends"}
RESULTS_OLD_PATHS = {"exact.py", "energy.py", "interface.py"}
"""Old module paths of the analytic front ends moved to ``persson_fp/analysis``, kept for one release."""


def _module_name(path: pathlib.Path, pkg: pathlib.Path) -> str:
    parts = list(path.relative_to(pkg.parent).with_suffix("").parts)
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _folder(module: str, pkg: pathlib.Path) -> str:
    """The package (folder) a module lives in: itself for a package, else its parent."""
    path = pkg.parent.joinpath(*module.split("."))
    return module if (path / "__init__.py").exists() else module.rsplit(".", 1)[0]


def _private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


def private_imports_across_folders(pkg: pathlib.Path = PKG) -> list[tuple[str, str, str]]:
    """(importing file, imported module, name) for every private name or private module imported from another
    folder of the package (the package root's own private modules, e.g. ``persson_fp._validate``, are shared by
    all folders and allowed)."""
    hits = []
    for path in sorted(pkg.rglob("*.py")):
        mine = _folder(_module_name(path, pkg), pkg)
        for node in ast.walk(ast.parse(path.read_text())):
            if not (isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("persson_fp")):
                continue
            theirs = _folder(node.module, pkg)
            if theirs == mine:
                continue
            where = str(path.relative_to(pkg.parent))
            if _private(node.module.rsplit(".", 1)[-1]) and theirs != "persson_fp":
                hits.append((where, node.module, "(private module)"))
            hits.extend((where, node.module, a.name) for a in node.names if _private(a.name))
    return hits


def test_import_contracts_kept():
    pytest.importorskip("importlinter")
    lint = pathlib.Path(sys.executable).with_name("lint-imports")
    cmd = [str(lint)] if lint.exists() else [sys.executable, "-m", "importlinter.cli"]
    r = subprocess.run([*cmd, "--no-cache"], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert " 0 broken" in r.stdout


def test_no_private_import_across_folders():
    hits = private_imports_across_folders()
    assert not hits, f"private names imported from another folder (make them public or move them): {hits}"


def test_private_import_check_sees_one(tmp_path):
    """The check itself: a private name imported across folders in a scratch package is found, one within a
    folder is not."""
    pkg = tmp_path / "persson_fp"
    for folder in ("a", "b"):
        (pkg / folder).mkdir(parents=True)
        (pkg / folder / "__init__.py").write_text("")
    (pkg / "__init__.py").write_text("")
    (pkg / "a" / "x.py").write_text("_HIDDEN = 1\nSHOWN = 2\n")
    (pkg / "a" / "y.py").write_text("from persson_fp.a.x import _HIDDEN\n")
    (pkg / "b" / "z.py").write_text("from persson_fp.a.x import SHOWN, _HIDDEN\n")
    hits = private_imports_across_folders(pkg)
    assert [(h[1], h[2]) for h in hits] == [("persson_fp.a.x", "_HIDDEN")]
    assert hits[0][0].endswith("z.py")


def test_solvers_front_is_small_and_families_have_folders():
    solvers = PKG / "solvers"
    plain = {p.name for p in solvers.glob("*.py")} - {"__init__.py"} - OLD_PATH_REEXPORTS
    assert len(plain) <= SOLVERS_FRONT_MAX, f"{len(plain)} plain modules in solvers/: {sorted(plain)}"
    folders = {p.name for p in solvers.iterdir() if (p / "__init__.py").exists()}
    assert SOLVER_FAMILIES <= folders, f"missing family folders: {SOLVER_FAMILIES - folders}"
    for name in OLD_PATH_REEXPORTS:  # re-exports only: nothing but a docstring, imports and __all__
        tree = ast.parse((solvers / name).read_text())
        kinds = {type(node).__name__ for node in tree.body}
        assert kinds <= {"Expr", "ImportFrom", "Assign"}, (name, kinds)


def test_old_paths_of_moved_modules_only_re_export():
    """The old paths kept for one release hold nothing but a docstring, imports and ``__all__``."""
    paths = [PKG / "solvers" / n for n in OLD_PATH_REEXPORTS] + [PKG / "results" / n for n in RESULTS_OLD_PATHS]
    for path in paths:
        kinds = {type(node).__name__ for node in ast.parse(path.read_text()).body}
        assert kinds <= {"Expr", "ImportFrom", "Assign"}, (path.name, kinds)


def test_modules_within_soft_ceiling():
    long = {
        str(p.relative_to(ROOT)): n for p in PKG.rglob("*.py") if (n := len(p.read_text().splitlines())) > SOFT_CEILING
    }
    assert not long, f"modules over ~{SOFT_CEILING} lines (split them where they do two things): {long}"
