"""``python -m persson_fp.cli``: the ``persson-fp`` command."""

from persson_fp.cli.app import main

raise SystemExit(main())
