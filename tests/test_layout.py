"""The package's layering (one folder per concept, imports pointing one way) as import-linter contracts.

The contracts live in ``pyproject.toml`` (``[tool.importlinter]``); a broken contract fails this test with
import-linter's report of the offending import chain.  Also: no module in ``src/`` over 500 lines.
"""

import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


def test_import_contracts_kept():
    pytest.importorskip("importlinter")
    lint = pathlib.Path(sys.executable).with_name("lint-imports")
    cmd = [str(lint)] if lint.exists() else [sys.executable, "-m", "importlinter.cli"]
    r = subprocess.run([*cmd, "--no-cache"], cwd=ROOT, capture_output=True, text=True)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "0 broken" in r.stdout


def test_no_module_over_500_lines():
    long = {
        str(p.relative_to(ROOT)): n
        for p in (ROOT / "src" / "persson_fp").rglob("*.py")
        if (n := len(p.read_text().splitlines())) > 500
    }
    assert not long, f"modules over ~500 lines (split them where they do two things): {long}"
