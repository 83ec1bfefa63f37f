"""The ``persson-fp`` command line: :func:`main` parses the arguments and runs one subcommand.

``app.py`` holds the parser and the report/solve/area subcommands, ``surface.py`` and ``sweep.py`` their own
subcommands, ``_io.py`` the shared file handling.
"""

from persson_fp.cli.app import main

__all__ = ["main"]
