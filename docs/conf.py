"""Sphinx configuration of the persson-fp documentation site.

Build (what ``tests/test_docs.py`` runs, warnings are errors, references are checked)::

    python -m sphinx -W -n --keep-going -b html docs docs/_build/html

The notebooks are rendered from their committed, executed ``.ipynb`` (copied from ``../notebooks`` at
build time); they are not re-executed here -- ``tests/test_notebooks.py`` executes them.
"""

import shutil
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT / "src"))  # document this checkout, not an installed copy

import persson_fp  # noqa: E402

project = "persson-fp"
author = "The persson-fp developers"
copyright = "2026, the persson-fp developers"
release = version = persson_fp.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",  # MathJax served from _static/mathjax: formulas render offline, no CDN
    "numpydoc",
    "myst_nb",
]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "**.ipynb_checkpoints"]
nitpicky = True

# -- notebooks: render the committed outputs, never execute ---------------------------------------------------------
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3
suppress_warnings = ["mystnb.unknown_mime_type"]

_NB_SRC, _NB_DST = ROOT / "notebooks", DOCS / "notebooks"
_NB_DST.mkdir(exist_ok=True)
for _nb in sorted(_NB_SRC.glob("*.ipynb")):
    _dst = _NB_DST / _nb.name
    if not _dst.exists() or _dst.read_bytes() != _nb.read_bytes():
        shutil.copyfile(_nb, _dst)
for _stale in _NB_DST.glob("*.ipynb"):
    if not (_NB_SRC / _stale.name).exists():
        _stale.unlink()

# -- API reference: numpydoc docstrings --------------------------------------------------------------------------------
# The types shown are the docstrings' (with units, as numpydoc writes them); the code's type hints serve type checkers
# and IDEs (py.typed). Sphinx 9 renders numpy's ArrayLike alias in signatures as a page-long Union.
autodoc_member_order = "bysource"
autodoc_typehints = "none"
autodoc_default_options = {"members": True}
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# -- HTML -------------------------------------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"persson-fp {release}"


# -- docstring defects awaiting their fix ---------------------------------------------------------------------------
# These modules are being reshaped on another branch (the elastoplastic engine), so their docstrings are fixed there;
# until then each entry below hides exactly one known message, matched by where it comes from and its text. Delete an
# entry with its fix: a defect that is not listed, or one that appears anywhere else, still fails the build.
def _numpydoc_citation(name: str) -> str:
    import hashlib

    from numpydoc.numpydoc import HASH_LEN

    return "Citation [R" + hashlib.sha256(name.encode("utf8")).hexdigest()[:HASH_LEN] + "-"


PENDING_DOCSTRING_FIXES = [
]


class _PendingFixes:
    """A logging filter that drops the messages of ``PENDING_DOCSTRING_FIXES`` (and counts them)."""

    def __init__(self):
        self.hidden = []

    def filter(self, record) -> bool:
        from sphinx.util.logging import get_node_location

        where = getattr(record, "location", None)
        if isinstance(where, tuple):  # (docname, line)
            where = f"{where[0]}:{where[1]}"
        elif hasattr(where, "source") or hasattr(where, "line"):  # a docutils node
            where = get_node_location(where)
        where, text = str(where), record.getMessage()
        for origin, message in PENDING_DOCSTRING_FIXES:
            if origin in where and message in text:
                self.hidden.append((origin, message))
                return False
        return True


def setup(app):
    import logging

    from sphinx.util.logging import NAMESPACE, WarningStreamHandler

    for handler in logging.getLogger(NAMESPACE).handlers:
        if isinstance(handler, WarningStreamHandler):
            handler.filters.insert(0, _PendingFixes())  # before Sphinx counts the warning
