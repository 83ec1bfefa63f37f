"""The physics seams hold: the code asks the problem's walls, coefficients and elastic response, it does not branch
on what kind of problem it has.

A condition (``if``/``elif``/``while``/``assert``, a conditional expression or a comprehension filter) that reads a
problem-kind flag -- ``.general``, ``.moving_wall``, ``.has_closed_form``, ``.features``, a wall's ``.moves``, a
hardness's ``.is_constant``, ``.hardness`` compared with None, an ``isinstance`` test against a problem or wall class,
or ``kind == ...`` -- is counted over the package.  New physics is a new wall, coefficient model or response object,
so the count may only fall: a new branch on a problem kind fails this test (lower ``MAX_KIND_BRANCHES`` when you
remove some).
"""

from __future__ import annotations

import ast
import pathlib

import persson_fp

SRC = pathlib.Path(persson_fp.__file__).parent
FLAGS = {"general", "moving_wall", "has_closed_form", "features", "moves", "is_constant"}
KIND_CLASSES = {  # (not ContactProblem, the base of every problem: testing it is checking a type)
    "FokkerPlanckProblem",
    "Wall",
    "AbsorbingWall",
    "OpenEnd",
    "YieldWall",
    "MovingYieldWall",
    "ConstantHardness",
}
MAX_KIND_BRANCHES = 19
"""Branches on the problem kind left (each listed by ``kind_branches``): the choice of a method family's path (fv,
mol, chebyshev on the front-fixed engine or not), the one place each dispatch is made (the upper wall of a hardness,
the engine's coefficient model), chebyshev's coefficient forms, the strip's own tau map of sines and fv's step grading
and mol's start, and the text of the summaries, plots and CLI tables (a true error or an estimate)."""


def _is_problem(node) -> bool:
    """``pr``, ``problem`` or ``<anything>.problem``."""
    return getattr(node, "id", None) in ("pr", "problem") or getattr(node, "attr", None) == "problem"


def _reads_kind(node) -> bool:
    for n in ast.walk(node):
        if isinstance(n, ast.Attribute) and n.attr in FLAGS:
            return True
        if isinstance(n, ast.Compare):
            parts = [n.left, *n.comparators]
            named = [p for p in parts if isinstance(p, ast.Attribute) and p.attr == "hardness"]
            if named and any(isinstance(p, ast.Constant) and p.value is None for p in parts):
                return True
            if any(isinstance(p, ast.Attribute) and p.attr == "kind" and _is_problem(p.value) for p in parts):
                return True
        if isinstance(n, ast.Call) and getattr(n.func, "id", None) == "getattr" and len(n.args) >= 2:
            name = n.args[1]
            if isinstance(name, ast.Constant) and name.value in FLAGS | {"hardness"}:
                return True
        if isinstance(n, ast.Call) and getattr(n.func, "id", None) == "isinstance" and len(n.args) == 2:
            classes = n.args[1].elts if isinstance(n.args[1], ast.Tuple) else [n.args[1]]
            names = {getattr(c, "id", getattr(c, "attr", None)) for c in classes}
            if names & KIND_CLASSES:
                return True
    return False


def kind_branches() -> list[str]:
    """``file:line`` of every condition of the package that reads a problem-kind flag."""
    out = []
    for path in sorted(SRC.rglob("*.py")):
        tree = ast.parse(path.read_text())
        for node in ast.walk(tree):
            tests = []
            if isinstance(node, (ast.If, ast.While, ast.IfExp, ast.Assert)):
                tests = [node.test]
            elif isinstance(node, ast.comprehension):
                tests = list(node.ifs)
            out += [f"{path.relative_to(SRC)}:{t.lineno}" for t in tests if _reads_kind(t)]
    return out


def stored_kind_flags() -> list[str]:
    """``file:line`` of every assignment that stores a problem-kind flag in a variable (``hard = pr.hardness is not
    None``): a branch on that variable is a branch on the kind that :func:`kind_branches` cannot see."""
    out = []
    for path in sorted(SRC.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, (ast.Assign, ast.AnnAssign)) and node.value is not None and _reads_kind(node.value):
                if not isinstance(node.value, ast.IfExp):  # (a conditional expression is counted as a branch)
                    out.append(f"{path.relative_to(SRC)}:{node.lineno}")
    return out


MAX_STORED_FLAGS = 4
"""Kind flags kept in a variable: fv's "a yield wall" (its DST and banded marches), the plot's "a closed form"."""


def test_stored_kind_flags_only_fall():
    got = stored_kind_flags()
    assert len(got) <= MAX_STORED_FLAGS, "kind flags stored in variables:\n  " + "\n  ".join(got)


def test_kind_branches_only_fall():
    got = kind_branches()
    assert len(got) <= MAX_KIND_BRANCHES, "branches on the problem kind:\n  " + "\n  ".join(got)


def test_the_counter_sees_a_branch(tmp_path):
    """The counter is not blind: each form of a kind branch counts once."""
    src = (
        "if pr.general: pass\n"
        "x = 1 if pr.hardness is None else 2\n"
        "while not problem.moving_wall: pass\n"
        "assert isinstance(pr, FokkerPlanckProblem)\n"
        "y = [a for a in b if a.upper_wall.moves]\n"
        "if pr.kind == 'strip': pass\n"
        "if getattr(pr, 'general', False): pass\n"
        "if grid.kind == 'cell': pass\n"  # not a problem kind
        "if pr.fudge is None: pass\n"  # not a problem kind
    )
    tree = ast.parse(src)
    n = 0
    for node in ast.walk(tree):
        tests = [node.test] if isinstance(node, (ast.If, ast.While, ast.IfExp, ast.Assert)) else []
        tests += list(node.ifs) if isinstance(node, ast.comprehension) else []
        n += sum(_reads_kind(t) for t in tests)
    assert n == 7
