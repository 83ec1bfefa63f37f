"""Build the documentation site with warnings as errors (``docs/``, Sphinx + numpydoc + MyST-NB).

Skipped when the ``docs`` extra is not installed. The build is nitpicky (``-n``): a broken cross-reference,
malformed reStructuredText in a docstring, an uncited reference or a missing page fails it. The notebooks are
rendered from their committed outputs, not executed (``tests/test_notebooks.py`` executes them), so the build
takes about 10-15 s from scratch on a 2-core machine.
"""

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"


@pytest.mark.slow  # a full Sphinx build (~30 s): the heavy group
def test_docs_build_without_warnings(tmp_path):
    for mod in ("sphinx", "numpydoc", "myst_nb", "furo", "sphinx-mathjax-offline"):
        pytest.importorskip(mod)
    out = tmp_path / "html"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), os.environ.get("PYTHONPATH", "")])}
    cmd = [sys.executable, "-m", "sphinx", "-W", "-n", "--keep-going", "-q", "-b", "html", str(DOCS), str(out)]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=env, cwd=ROOT, timeout=600)
    assert proc.returncode == 0, f"docs build failed:\n{proc.stderr[-6000:]}"
    # the pages the site promises, the API reference rendered from the docstrings, every notebook rendered
    for page in ("index", "getting_started", "physics", "choosing_a_method", "api", "references", "notebooks"):
        assert (out / f"{page}.html").is_file(), page
    api = (out / "api.html").read_text(encoding="utf8")
    for name in ("persson_fp.solve", "persson_fp.exact", "persson_fp.ContactProblem", "persson_fp.Solution"):
        assert f'id="{name}"' in api, f"{name} missing from the API reference"
    # MathJax is served with the site (formulas render offline), not loaded from a CDN
    physics = (out / "physics.html").read_text(encoding="utf8")
    assert "_static/mathjax/tex-chtml.js" in physics and "cdn.jsdelivr" not in physics
    assert (out / "_static" / "mathjax" / "tex-chtml.js").is_file()
    notebooks = sorted(p.stem for p in (ROOT / "notebooks").glob("*.ipynb"))
    rendered = sorted(p.stem for p in (out / "notebooks").glob("*.html"))
    assert rendered == notebooks
