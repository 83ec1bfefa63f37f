"""Regenerate executed notebooks from their jupytext sources: ``python tools/notebook.py notebooks/NN_name.py ...``.

Each ``notebooks/NN_name.py`` (jupytext percent format) is the source; this writes ``notebooks/NN_name.ipynb``
with the same cells, executed top to bottom in a fresh ``python3`` kernel whose working directory is
``notebooks/``. It does what ``jupytext --to ipynb --update`` followed by ``jupyter execute --inplace`` does,
but numbers the cell ids ``NN-00, NN-01, ...`` and records no execution timestamps, so that a regenerated
notebook differs from the committed one only where its sources or outputs changed. Needs the ``notebooks``
extra (jupytext, nbclient, nbformat, ipykernel).
"""

import argparse
import sys
import time
from pathlib import Path

import jupytext
import nbformat
from nbclient import NotebookClient

KERNELSPEC = {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"}


def regenerate(script: Path, timeout: int = 600) -> Path:
    """Build ``script.with_suffix('.ipynb')`` from the percent script ``script``, executed; return its path."""
    nb = jupytext.read(script)
    nb.metadata = {
        "kernelspec": KERNELSPEC,
        "language_info": {"name": "python"},
        "jupytext": {"formats": "ipynb,py:percent"},  # lets Jupyter + jupytext keep the pair in sync
    }
    prefix = script.stem.split("_")[0]
    for i, cell in enumerate(nb.cells):
        cell["id"] = f"{prefix}-{i:02d}"
    client = NotebookClient(
        nb,
        timeout=timeout,
        kernel_name="python3",
        record_timing=False,
        resources={"metadata": {"path": str(script.resolve().parent)}},
    )
    client.execute()
    out = script.with_suffix(".ipynb")
    nbformat.write(nb, out)
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scripts", nargs="+", type=Path, help="percent scripts, e.g. notebooks/02_contact_area.py")
    parser.add_argument("--timeout", type=int, default=600, help="seconds allowed per cell (default 600)")
    args = parser.parse_args(argv)
    for script in args.scripts:
        if script.suffix != ".py" or not script.is_file():
            parser.error(f"scripts: {script} is not an existing .py file")
        t = time.perf_counter()
        out = regenerate(script, args.timeout)
        print(f"{out}: executed in {time.perf_counter() - t:.1f} s, {out.stat().st_size / 1e3:.0f} kB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
