"""The ``persson-fp`` command: the parser and the dispatch to one module per subcommand (``report``, ``solve``,
``area``, ``surface``, ``sweep``, ``calibrate``, ``friction``; what they share is in ``_problem.py`` and ``_io.py``).

It only wires the package together.  Every warning prints once as one line ``persson-fp: warning: ...`` on
stderr (``_io.one_line_warnings``).  Every error -- a bad argument, an unreadable or unwritable
file, a solver that refuses a problem or breaks an invariant -- prints one line on stderr and exits
with code 2; Ctrl-C prints "interrupted" and exits with 130.  Files are written under a temporary
name and renamed when complete, so an interrupted run leaves no half-written file.
"""

from __future__ import annotations

import argparse
import re
import sys

from persson_fp._version import __version__
from persson_fp.cli import area, report, solve
from persson_fp.cli import calibrate as cli_calibrate
from persson_fp.cli import friction as cli_friction
from persson_fp.cli import surface as cli_surface
from persson_fp.cli import sweep as cli_sweep
from persson_fp.cli._io import CLIError, one_line_warnings
from persson_fp.cli._problem import _check_combination
from persson_fp.results.solution import SolverError

DESCRIPTION = """\
persson-fp: Persson's theory of elastic rough-surface contact as a diffusion (Fokker-Planck) problem.

The contact-pressure PDF P0(p, zeta) obeys dP0/dzeta = 1/2 B2 d2P0/dp2 with an absorbing wall at p = 0;
B2 = S(A*) dV/dzeta, S = 1 in Persson's original theory.  The default surface is the reference problem:
self-affine, H = 0.8, q_l = 1, q_r = 2, q_s = 128 (zeta_max = 128), rms slope 0.1, E* = 1,
p_bar = 0.5 sqrt(V(zeta_max)).  Units: SI unless --units none (lengths in m, pressures in Pa; said once on
stdout); every CSV header carries its unit in brackets, e.g. "p_bar [Pa]", "u_YP08 [m]".  Existing outputs are
refused unless --force; warnings print once each, one line "persson-fp: warning: ...", on stderr.

commands:
  report   (default) table of V, A*, Var(p), elastic energy for every fudge model, persson-fp's own
           solvers checked against the exact solution (--all-methods adds py-pde and FiPy), PNG figures
  solve    solve one problem (your surface and loads) with a chosen method; CSV/JSON/PNG output
  area     the contact-area curve A*(p_bar) for a range of loads, every fudge model (CSV + PNG)
  surface  a measured surface (height map or contact.engineering CSV) -> spectrum, A*, mean separation,
           stiffness for a range of loads, every fudge model (CSV + PNG)
  sweep    a folder of surfaces (CSV spectra) x fudge models x loads into one table (CSV or Parquet)
  calibrate  fit a fudge model's gamma to your A*(p_bar) / mean-separation data, with uncertainty;
           several models ranked by held-out error
  friction rubber friction mu(v, T) and sliding contact area from a DMA master curve (or a Zener model),
           a time-temperature shift and the road's spectrum: the isothermal viscoelastic part only (CSV + PNG)

examples:
  persson-fp
  persson-fp report --H 0.3 --zeta-max 1000 --output results/
  persson-fp solve --method fv --p-bar-ratio 0.1 0.5 2 --fudge YP08 --output sol.csv
  persson-fp solve --psd my_psd.csv --E-star 2.1e11 --p-bar 1e6 --method sines
  persson-fp area --n-loads 200 --output area/
  persson-fp surface heights.npy --size 1e-3 --E-star 2.1e11 --p-bar 1e5 --viscosity 1e-3 --pressure-drop 1e5
  persson-fp calibrate data.csv --psd psd.csv --model YP08 WM17 Xu24
  persson-fp friction --master-curve mc.csv --wlf 8.86 101.6 --T-ref 20 --psd road.csv --p-bar 2e5

Equation labels such as eq:Area_Persson or E:PSD are those of Y. Xu, X. Li, Q. Chen, Y. Zhou, "Persson's
Theory of Purely Normal Elastic Rough Surface Contact: A Tutorial Based on Stochastic Process Theory".
Fudge factors: Yang & Persson 2008 (YP08), Wang & Muser 2017 (WM17), Xu et al. 2024 (Xu24).
"""


class _Parser(argparse.ArgumentParser):
    """argparse with its errors on one line (no usage block): "persson-fp solve: error: ... (see --help)".

    A negative number in any notation (``-2e5``, ``-1e-3``) is a value, not an option, so that a bad value such as
    ``--p-bar -2e5`` reaches the check that names what is wrong with it (argparse alone knows only ``-2``, ``-0.5``).
    """

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|nan)$", re.I)

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {' '.join(message.split())} (see {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="persson-fp", description=DESCRIPTION, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--version", action="version", version=f"persson-fp {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="{report,solve,area,surface,sweep,calibrate,friction}")

    for command in (report, solve, area, cli_surface, cli_sweep, cli_calibrate, cli_friction):
        command.add_parser(sub)
    return parser


def main(argv=None) -> int:
    import matplotlib

    matplotlib.use("Agg")
    parser = build_parser()
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0].startswith("-") and argv[0] not in ("-h", "--help", "--version"):
        argv = ["report", *argv]
    try:
        args = parser.parse_args(argv)
        if args.command is None:
            args = parser.parse_args(["report"])
        with one_line_warnings():  # every warning once, as one line "persson-fp: warning: ..."
            _check_combination(args)
            return args.func(args)
    except KeyboardInterrupt:
        print("persson-fp: interrupted", file=sys.stderr)
        return 130
    except _USER_ERRORS as err:
        print(f"persson-fp {argv[0] if argv else 'report'}: error: {_one_line(err)}", file=sys.stderr)
        return 2


_USER_ERRORS = (
    CLIError,
    ValueError,
    TypeError,
    ImportError,
    NotImplementedError,
    SolverError,
    OSError,
    MemoryError,
    EOFError,
    OverflowError,
)
"""Errors reported as one line (a solver's refusal, a breached invariant, a file that cannot be read or written)."""


def _one_line(err) -> str:
    """The error as one line (an ``OSError`` as "reason: file")."""
    if isinstance(err, OSError) and err.strerror:
        text = f"{err.strerror}: {err.filename}" if err.filename else err.strerror
    elif isinstance(err, MemoryError):
        text = "out of memory (use a coarser grid or fewer loads)"
    else:
        text = str(err) or type(err).__name__
        for name, flag in _FLAGS.items():  # the solvers' option names, as the command spells them
            text = re.sub(rf"(?<![-\w]){name}(?!\w)", flag, text)
        if any(re.search(rf"(?<![-\w]){name}(?!\w)", text) for name in _API_ONLY):
            text += " (k_domain, zeta_out and n_walkers are options of the Python API, persson_fp.solve)"
    return " ".join(text.split())


_FLAGS = {
    "n_p": "--n-p",
    "n_steps": "--n-steps",
    "E_star": "--E-star",
    "q_l": "--q-l",
    "q_r": "--q-r",
    "nu": "--nu",
    "bootstrap": "--bootstrap",
}
"""Option names in library messages -> the command-line flag that sets them."""

_API_ONLY = ("k_domain", "zeta_out", "n_walkers")
"""Options named in library messages that the command line does not offer."""


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
