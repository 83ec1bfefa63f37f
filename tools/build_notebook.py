"""Build an executed notebook from its jupytext percent script: ``python tools/build_notebook.py notebooks/NN_x.py``.

Reads the script (the source of truth), executes it in a fresh ``python3`` kernel with the notebook folder as
the working directory, and writes ``notebooks/NN_x.ipynb`` next to it with its outputs (needs the
``notebooks`` extra and jupytext).
"""

import sys
from pathlib import Path

import jupytext
import nbformat
from nbclient import NotebookClient

KERNELSPEC = {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"}


def build(script: str) -> Path:
    src = Path(script).resolve()
    nb = jupytext.read(src)
    nb.metadata["kernelspec"] = KERNELSPEC
    NotebookClient(nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(src.parent)}}).execute()
    out = src.with_suffix(".ipynb")
    nbformat.write(nb, out)
    return out


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        print(build(arg))
