"""``python -m brdfs``: the :mod:`brdfs.cli` command line."""
import sys

from brdfs.cli import main

sys.exit(main())
