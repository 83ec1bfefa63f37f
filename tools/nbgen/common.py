"""Shared machinery of the notebook generators: build, execute twice, fill the closing text, save."""

import json
import string
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient

NB_DIR = Path(__file__).resolve().parents[2] / "notebooks"
KERNELSPEC = {"name": "python3", "display_name": "Python 3 (ipykernel)", "language": "python"}


def _cell(kind, src, tags=()):
    src = src.strip("\n")
    c = nbformat.v4.new_markdown_cell(src) if kind == "md" else nbformat.v4.new_code_cell(src)
    if tags:
        c.metadata["tags"] = list(tags)
    return c


def _execute(nb):
    t = time.perf_counter()
    client = NotebookClient(
        nb, timeout=120, kernel_name="python3", record_timing=False, resources={"metadata": {"path": str(NB_DIR)}}
    )
    client.execute()
    return time.perf_counter() - t


def _summary(nb):
    for c in nb.cells:
        if "summary" in c.metadata.get("tags", []):
            for o in c.outputs:
                if o.get("output_type") == "display_data" and "summary" in o.get("metadata", {}):
                    return o["metadata"]["summary"]
    raise RuntimeError("no summary output found")


def build(name, cells, closing_template):
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = KERNELSPEC
    nb.metadata["language_info"] = {"name": "python"}
    nb.cells = [_cell(*c) for c in cells]
    t1 = _execute(nb)
    summary = _summary(nb)
    keys = {f for _, f, _, _ in string.Formatter().parse(closing_template) if f}
    missing = set(summary) - keys
    extra = keys - set(summary)
    assert not missing and not extra, (missing, extra)
    closing = closing_template.format(**summary)
    # rebuild with the closing text and execute again from a clean kernel (outputs must be from one run)
    nb2 = nbformat.v4.new_notebook()
    nb2.metadata["kernelspec"] = KERNELSPEC
    nb2.metadata["language_info"] = {"name": "python"}
    nb2.cells = [_cell(*c) for c in cells] + [_cell("md", closing)]
    t2 = _execute(nb2)
    s2 = _summary(nb2)
    assert s2 == summary, (s2, summary)
    for i, c in enumerate(nb2.cells):
        c["id"] = f"{name.split('_')[0]}-{i:02d}"
    path = NB_DIR / f"{name}.ipynb"
    nbformat.write(nb2, path)
    # lint/format the sources in place (import sorting, line wrapping: semantics unchanged, outputs stay valid)
    import shutil
    import subprocess
    import sys

    # ruff of the interpreter's environment (else the one on PATH), with the repository's configuration
    ruff = str(Path(sys.executable).parent / "ruff")
    ruff = ruff if Path(ruff).exists() else shutil.which("ruff")
    repo = NB_DIR.parent
    subprocess.run([ruff, "check", "--fix", "-q", str(path)], cwd=repo, check=False)
    subprocess.run([ruff, "format", "-q", str(path)], cwd=repo, check=True)
    subprocess.run([ruff, "check", "-q", str(path)], cwd=repo, check=False)
    print(f"{path}: executed in {t1:.1f} s and {t2:.1f} s; {path.stat().st_size / 1e3:.0f} kB")
    print(json.dumps(summary, indent=1, ensure_ascii=False))
