"""``tools/fingerprint.py``, the table that must not change under an internal change: it runs, it is deterministic,
and its comparison flags a change of 1e-11 relative (above its 1e-12 threshold) and passes round-off below it."""

from __future__ import annotations

import csv
import importlib.util
import pathlib

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def fingerprint():
    spec = importlib.util.spec_from_file_location("fingerprint", ROOT / "tools" / "fingerprint.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _scale_first_area(src, dst, factor):
    with open(src, newline="") as fh:
        rows = list(csv.DictReader(fh))
    rows[0]["A"] = repr(float(rows[0]["A"]) * factor)
    with open(dst, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)


@pytest.mark.slow
def test_deterministic_and_sensitive(fingerprint, tmp_path, capsys):
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    assert fingerprint.main(["--only", "batch-sines", "--output", str(a)]) == 0
    assert fingerprint.main(["--only", "batch-sines", "--output", str(b)]) == 0
    assert fingerprint.main(["--compare", str(a), str(b)]) == 0  # the same run twice: the same numbers
    assert " 0 above" in capsys.readouterr().out
    _scale_first_area(a, b, 1.0 + 1e-11)
    assert fingerprint.main(["--compare", str(a), str(b)]) == 1
    _scale_first_area(a, b, 1.0 + 1e-14)
    assert fingerprint.main(["--compare", str(a), str(b)]) == 0
