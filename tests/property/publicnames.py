"""The package's public surface and the public names each hypothesis test exercises, read from the tests.

The public surface is computed from ``persson_fp.__all__`` at test time: every name there, and for the modules it
lists (``pf.fudge``, ``pf.hardness``, ``pf.adhesion``, ...) every name of their own ``__all__`` as
``"module.name"``.  A name counts as property-tested when a function decorated with ``@given`` refers to it in its
body, or in a helper of the same module that the body calls (transitively): as ``pf.X`` / ``persson_fp.X`` /
``pf.module.X``, through a name imported from any ``persson_fp`` module, or through an alias of a public module.
References are resolved by importing them and matching the objects, so ``from persson_fp.theory.gaps import
GapDistribution`` counts for ``pf.GapDistribution``.
"""

from __future__ import annotations

import ast
import functools
import importlib
import pathlib
from types import ModuleType

import persson_fp as pf

TESTS = pathlib.Path(__file__).resolve().parents[1]


def public_surface() -> dict[str, object]:
    """Public name -> object: ``persson_fp.__all__`` and the ``__all__`` of the modules listed there."""
    out: dict[str, object] = {}
    for name in pf.__all__:
        obj = getattr(pf, name)
        if isinstance(obj, ModuleType):
            inner = getattr(obj, "__all__", None) or [n for n in vars(obj) if not n.startswith("_")]
            for sub in inner:
                out[f"{name}.{sub}"] = getattr(obj, sub)
        else:
            out[name] = obj
    return out


def is_constant(obj: object) -> bool:
    """A value, not something to call: exempt from a property test, covered by a test of its contents."""
    return not callable(obj)


def _module_aliases(tree: ast.Module) -> tuple[dict[str, ModuleType], dict[str, object]]:
    """Names bound at module level by imports from persson_fp: alias -> module, and alias -> object."""
    modules: dict[str, ModuleType] = {}
    objects: dict[str, object] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name == "persson_fp" or a.name.startswith("persson_fp."):
                    if a.asname:
                        modules[a.asname] = importlib.import_module(a.name)
                    else:
                        modules["persson_fp"] = importlib.import_module("persson_fp")
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            if node.module != "persson_fp" and not node.module.startswith("persson_fp."):
                continue
            try:
                mod = importlib.import_module(node.module)
            except ImportError:
                continue
            for a in node.names:
                try:
                    obj = getattr(mod, a.name)
                except AttributeError:
                    try:
                        obj = importlib.import_module(f"{node.module}.{a.name}")
                    except ImportError:
                        continue
                key = a.asname or a.name
                if isinstance(obj, ModuleType):
                    modules[key] = obj
                else:
                    objects[key] = obj
    return modules, objects


def _is_given(dec: ast.expr) -> bool:
    target = dec.func if isinstance(dec, ast.Call) else dec
    return (isinstance(target, ast.Name) and target.id == "given") or (
        isinstance(target, ast.Attribute) and target.attr == "given"
    )


def _referenced(node: ast.AST, modules: dict, objects: dict) -> list[object]:
    """The persson_fp objects a function body refers to (attribute chains resolved by import)."""
    found: list[object] = []
    for sub in ast.walk(node):
        if isinstance(sub, ast.Attribute):
            chain = []
            cur: ast.AST = sub
            while isinstance(cur, ast.Attribute):
                chain.append(cur.attr)
                cur = cur.value
            if isinstance(cur, ast.Name) and cur.id in modules:
                obj: object = modules[cur.id]
                for attr in reversed(chain):
                    try:
                        obj = getattr(obj, attr)
                    except AttributeError:
                        break
                    found.append(obj)
        elif isinstance(sub, ast.Name) and sub.id in objects:
            found.append(objects[sub.id])
    return found


def _called_helpers(node: ast.AST, helpers: dict[str, ast.FunctionDef]) -> set[str]:
    return {
        sub.func.id
        for sub in ast.walk(node)
        if isinstance(sub, ast.Call) and isinstance(sub.func, ast.Name) and sub.func.id in helpers
    }


def scan(path: pathlib.Path) -> tuple[dict[str, list[object]], list[object]]:
    """One test file: ``{given test name: objects it exercises}`` and the objects named in any test function."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    modules, objects = _module_aliases(tree)
    functions = {n.name: n for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)}
    helpers = {k: v for k, v in functions.items() if not any(_is_given(d) for d in v.decorator_list)}
    given_tests: dict[str, list[object]] = {}
    anywhere: list[object] = []
    for name, fn in functions.items():
        if name.startswith("test"):
            anywhere += _referenced(fn, modules, objects)
        if not any(_is_given(d) for d in fn.decorator_list):
            continue
        seen, todo, refs = set(), [fn], []
        while todo:
            cur = todo.pop()
            refs += _referenced(cur, modules, objects)
            for h in _called_helpers(cur, helpers) - seen:
                seen.add(h)
                todo.append(helpers[h])
        given_tests[f"{path.relative_to(TESTS)}::{name}"] = refs
    return given_tests, anywhere


@functools.lru_cache(maxsize=1)
def coverage() -> tuple[dict[str, list[str]], dict[str, list[str]]]:
    """Public name -> the @given tests that exercise it, and public constant -> the tests that name it."""
    surface = public_surface()
    by_id: dict[int, list[str]] = {}
    for name, obj in surface.items():
        by_id.setdefault(id(obj), []).append(name)
    given_cov: dict[str, list[str]] = {n: [] for n in surface}
    const_cov: dict[str, list[str]] = {n: [] for n in surface if is_constant(surface[n])}
    for path in sorted(TESTS.rglob("test_*.py")):
        tests, anywhere = scan(path)
        for test, refs in tests.items():
            for obj in refs:
                for name in by_id.get(id(obj), []):
                    if test not in given_cov[name]:
                        given_cov[name].append(test)
        for obj in anywhere:
            for name in by_id.get(id(obj), []):
                rel = str(path.relative_to(TESTS))
                if name in const_cov and rel not in const_cov[name]:
                    const_cov[name].append(rel)
    return given_cov, const_cov
