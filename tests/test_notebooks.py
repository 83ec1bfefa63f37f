"""Execute every notebook in notebooks/ (examples are tests: each ends with an assert cell).

The source of each notebook is a jupytext percent script ``notebooks/NN_name.py``; the executed
``NN_name.ipynb`` beside it is generated from it (CONTRIBUTING.md, "Notebooks") and must hold the same
cells (``test_script_pairs_with_notebook``). Needs the ``notebooks`` extra (nbclient, nbformat, ipykernel,
jupytext); skipped cleanly without it. The kernel is
``python3``: jupyter_client resolves the native kernel's ``python`` to ``sys.executable``, so the notebooks
run in the interpreter that runs pytest (checked by ``test_kernel_is_this_interpreter``).
"""

import json
import sys
from pathlib import Path

import pytest

NOTEBOOK_DIR = Path(__file__).resolve().parents[1] / "notebooks"
NOTEBOOKS = sorted(NOTEBOOK_DIR.glob("*.ipynb"))
SCRIPTS = sorted(NOTEBOOK_DIR.glob("*.py"))
CELL_TIMEOUT_S = 120


def _execute(nb):
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    client = nbclient.NotebookClient(
        nb,
        timeout=CELL_TIMEOUT_S,
        kernel_name="python3",
        resources={"metadata": {"path": str(NOTEBOOK_DIR)}},
    )
    client.execute()  # a cell error raises CellExecutionError and fails the test
    return nb


def _summary(nb):
    """The numbers the notebook formats for its closing text (display metadata of the cell tagged 'summary')."""
    for cell in nb.cells:
        if "summary" in cell.metadata.get("tags", []):
            for out in cell.get("outputs", []):
                if "summary" in out.get("metadata", {}):
                    return out["metadata"]["summary"]
    return None


def test_notebooks_found():
    assert NOTEBOOKS, f"no notebooks in {NOTEBOOK_DIR}"
    # every executed notebook has its jupytext source and every source its executed notebook
    assert [p.stem for p in NOTEBOOKS] == [p.stem for p in SCRIPTS]


def _cells(nb):
    return [(c.cell_type, c.source, c.metadata.get("tags", [])) for c in nb.cells]


@pytest.mark.parametrize("script", SCRIPTS, ids=[p.name for p in SCRIPTS])
def test_script_pairs_with_notebook(script):
    """The committed .ipynb was generated from the current .py: same cells, same sources, same tags, in order."""
    nbformat = pytest.importorskip("nbformat")
    jupytext = pytest.importorskip("jupytext")
    from_script = _cells(jupytext.read(script))
    committed = _cells(nbformat.read(script.with_suffix(".ipynb"), as_version=4))
    assert len(from_script) == len(committed), f"{script.name}: cell count differs, regenerate the notebook"
    for i, (a, b) in enumerate(zip(from_script, committed)):
        assert a == b, f"{script.name}: cell {i} differs from the .ipynb, regenerate it (CONTRIBUTING.md)"
    nb = nbformat.read(script.with_suffix(".ipynb"), as_version=4)
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert all(c.get("outputs") is not None and c.get("execution_count") for c in code if c.source.strip()), (
        f"{script.with_suffix('.ipynb').name} is committed unexecuted: run the jupytext command in CONTRIBUTING.md"
    )


_FAST = {"01_pdf_evolution.ipynb"}
"""The notebook the default run executes (a smoke test of the kernel and the plotting); the others, 6-26 s each,
run in the heavy group (``-m slow``) that CI runs too."""
_HEAVY = {p.name for p in NOTEBOOKS} - _FAST


@pytest.mark.parametrize(
    "path",
    [pytest.param(p, marks=pytest.mark.slow) if p.name in _HEAVY else p for p in NOTEBOOKS],
    ids=[p.name for p in NOTEBOOKS],
)
def test_notebook_executes(path):
    nbformat = pytest.importorskip("nbformat")
    nb = _execute(nbformat.read(path, as_version=4))
    assert nb.cells[0].cell_type == "markdown", "a notebook opens with a markdown cell stating its question"
    assert nb.cells[-1].cell_type == "markdown", "a notebook closes with a markdown cell saying what it shows"
    summary = _summary(nb)
    if summary is not None:  # the closing text quotes these numbers: stale text means regenerate the notebook
        closing = nb.cells[-1].source
        stale = {k: v for k, v in summary.items() if str(v) not in closing}
        assert not stale, f"{path.name}: closing text does not quote the recomputed {stale}"


def test_kernel_is_this_interpreter():
    nbformat = pytest.importorskip("nbformat")
    nb = nbformat.v4.new_notebook()
    nb.cells = [nbformat.v4.new_code_cell("import json, sys; print(json.dumps([sys.executable, sys.prefix]))")]
    nb = _execute(nb)
    kernel_python, kernel_prefix = json.loads(nb.cells[0].outputs[0]["text"])
    # compare the environments (prefix), not resolved paths: a venv's python is a symlink to the base interpreter
    assert kernel_prefix == sys.prefix, f"kernel runs {kernel_python} (prefix {kernel_prefix}), pytest {sys.executable}"
