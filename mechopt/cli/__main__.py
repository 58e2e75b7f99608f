"""``python -m mechopt.cli``: the ``mechopt`` command."""
import sys

from mechopt.cli import main

sys.exit(main())
